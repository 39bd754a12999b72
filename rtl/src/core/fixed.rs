//! Fixed-point conventions shared by every shadecore RTL block.
//!
//! Not a block: formats, rounding/saturation rules and f64 ↔ word conversions only, so it has
//! no ports, no latency (0 clocks) and no throughput of its own; every block's header states
//! its own latency using the formats named here.
//!
//! # Notation
//! `Qm.n` is a word of `m + n` bits with `n` fractional bits. For a **signed** format `m`
//! counts the sign bit: signed Q2.14 is a 16-bit two's-complement word covering
//! [−2, 2 − 2⁻¹⁴]; unsigned Q1.15 covers [0, 2 − 2⁻¹⁵]. A raw word `r` of format `Qm.n` means
//! the real number `r · 2⁻ⁿ` (two's complement when signed).
//!
//! Words live in rust-hdl `Bits<N>` (two's complement for signed values, never `Signed<N>`,
//! which simulates through BigInt and is an order of magnitude slower). Every datapath word is
//! at most 32 bits wide, so rust-hdl keeps it in its fast `u32` representation.
//!
//! # Formats of the normal-vector datapath
//! | name (const)   | format           | bits | meaning                                        |
//! |----------------|------------------|------|------------------------------------------------|
//! | [`NORMAL`]     | signed Q2.14     | 16   | N, L and H (the normalizer's input, not its output) |
//! | [`K_FULL`]     | unsigned Q4.28   | 32   | K = x²+y²+z², exact (3·2³⁰ < 2³²)               |
//! | [`K_ALPHA`]    | signed Q4.28     | 32   | α = N₀·Δ of the K recurrence, exact             |
//! | [`K_NARROW`]   | unsigned Q1.15   | 16   | K rounded to a multiplier operand              |
//! | [`COEF_C2`]    | unsigned Q1.15   | 16   | \|c2\| (its sign is a separate constant bit)    |
//! | [`COEF_C1`]    | signed Q3.29     | 32   | c1 (added, never multiplied: full precision)   |
//! | [`COEF_C0`]    | signed Q4.28     | 32   | c0 (added, never multiplied: full precision)   |
//! | [`HORNER_T1`]  | signed Q2.17     | 19   | t1 = c2·K + c1, multiplier operand (split 16 + 3) |
//! | [`NORM_SCALE`] | unsigned Q1.18   | 19   | f(K), multiplier operand (split 16 + 3)        |
//! | [`NORMALIZED`] | signed Q2.17     | 19   | N' = N·f(K), the normalizer's output           |
//! | [`SCALE`]      | unsigned Q1.15   | 16   | cosines and other unsigned multiplier operands |
//! | [`PRODUCT`]    | signed Q3.29     | 32   | Q2.14 × Q1.15 products                         |
//!
//! # Formats of the Gouraud intensity datapath (BVI, `crate::units::intensity_interpolator`)
//! | name (const)   | format           | bits | meaning                                        |
//! |----------------|------------------|------|------------------------------------------------|
//! | [`INTENSITY`]  | signed Q16.16    | 32   | set-up words and running intensities, in 8-bit LSB units (0..255 scale); wrapping adds |
//! | [`LEVEL`]      | unsigned Q8.0    | 8    | `red`, `green`, `blue`: the intensity's integer part, saturated to 0..=255 |
//!
//! # Arithmetic rules
//! - **Multiplies** are rust-hdl's 16×16→32 unsigned multiply (one FPGA DSP slice). A signed
//!   operand `a` (two's complement) times an unsigned `b` is formed from the unsigned product
//!   with the standard correction `a·b = ua·ub − [a<0]·(ub ≪ 16)  (mod 2³²)`; a signed square
//!   is `a² = ua² − [a<0]·(ua ≪ 17)  (mod 2³²)`. Both are exact: the true product fits 32 bits.
//!   A 19-bit operand (N, t1, f and N' of the normalizer) is split into its top 16 bits,
//!   which go through the multiplier (exact), and its three low bits, multiplied by shift and
//!   add ([`MulLow3Pipe`](crate::core::primitives::MulLow3Pipe), exact) and floored to the LSB of the
//!   32-bit sum they join (an error below one LSB of that sum, stated in each block's budget).
//! - **Rounding**: whenever LSBs are dropped the result is rounded to nearest, ties toward +∞
//!   (add half an output LSB, then shift right arithmetically). The half-LSB is folded into a
//!   constant where one is being added anyway. [`QFormat::quantize`] rounds the same way.
//! - **Saturation**: a narrowing that can overflow clamps to the format's min/max instead of
//!   wrapping (a wrapped normal would flip a pixel's shading). Additions that provably cannot
//!   overflow (stated at each one) are plain modular adds.
//! - **Modular exactness**: the K recurrence runs in 32-bit wrap-around arithmetic; since every
//!   true K_i is in [0, 2³²), the wrapped sums equal the exact integers. The BVI's [`INTENSITY`]
//!   sums wrap the same way: only the pixel values need to be in range, not the increments.
//!
//! The multiplies and narrowings above are built once, in [`crate::core::primitives`]
//! ([`MulSignedUnsigned`](crate::core::primitives::MulSignedUnsigned),
//! [`MulSignedPipe`](crate::core::primitives::MulSignedPipe),
//! [`RoundToQ2_17`](crate::core::primitives::RoundToQ2_17), [`SatToQ2_17`](crate::core::primitives::SatToQ2_17),
//! [`SatToUQ1_18`](crate::core::primitives::SatToUQ1_18), [`RoundToUQ1_15`](crate::core::primitives::RoundToUQ1_15),
//! [`MulLow3Pipe`](crate::core::primitives::MulLow3Pipe)), and the blocks use those.
//!
//! Every block header restates the formats of its ports and width-changing intermediates.

/// A fixed-point format: `int_bits` integer bits (including the sign bit when `signed`) and
/// `frac_bits` fractional bits, stored in `int_bits + frac_bits` bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QFormat {
    pub int_bits: u32,
    pub frac_bits: u32,
    pub signed: bool,
}

/// Unit-vector components: L and H, and the span normalizer's N₀ and Δ.
pub const NORMAL: QFormat = QFormat::signed(2, 14);
/// The interpolated normal N: the vector interpolator's output, the normalizer's input. Three
/// bits finer than [`NORMAL`], split 16 + 3 at the normalizer's multipliers like t1 and f
/// (`docs/bump-precision.md`: its rounding was the largest error left in `bump`'s cos γ).
pub const INTERPOLATED: QFormat = QFormat::signed(2, 17);
/// K = x² + y² + z² of the normalizer's input in Q4.28: exact for Q2.14 components (the K
/// recurrence), floored for Q2.17 ones (the squarers drop what lies below 2⁻²⁸).
pub const K_FULL: QFormat = QFormat::unsigned(4, 28);
/// α = N₀·Δ of the K recurrence (and the increments 2α + β_i), exact.
pub const K_ALPHA: QFormat = QFormat::signed(4, 28);
/// K rounded to a 16-bit multiplier operand.
pub const K_NARROW: QFormat = QFormat::unsigned(1, 15);
/// |c2|, the coefficient that goes through a multiplier.
pub const COEF_C2: QFormat = QFormat::unsigned(1, 15);
/// c1, added to the 32-bit product c2·K.
pub const COEF_C1: QFormat = QFormat::signed(3, 29);
/// c0, added to the 32-bit product t1·K (halved to Q4.28 so the sum cannot overflow).
pub const COEF_C0: QFormat = QFormat::signed(4, 28);
/// t1 = c2·K + c1, the Horner intermediate fed to the second multiplier: its top 16 bits go
/// through the multiplier, its three low bits through a shift-add
/// ([`MulLow3Pipe`](crate::core::primitives::MulLow3Pipe)).
pub const HORNER_T1: QFormat = QFormat::signed(2, 17);
/// f(K) = (c2·K + c1)·K + c0, the normalizer's scale factor (split 16 + 3 like t1).
pub const NORM_SCALE: QFormat = QFormat::unsigned(1, 18);
/// N' = N·f(K), the normalizer's output components. Three bits finer than [`NORMAL`]: the
/// lit methods' 2-LSB bound needs them (`docs/bump-precision.md`).
pub const NORMALIZED: QFormat = QFormat::signed(2, 17);
/// Unsigned Q1.15: the cosines and the other unsigned 16-bit multiplier operands.
pub const SCALE: QFormat = QFormat::unsigned(1, 15);
/// Product of a Q2.14 and a Q1.15 word.
pub const PRODUCT: QFormat = QFormat::signed(3, 29);
/// The BVI's words (`crate::units::intensity_interpolator`): set-up words `r_start` … `b_line` and the
/// running intensities RG1–RG5 (`red_word` … `blue_word`), in units of the 8-bit output's LSB
/// (value 0..255 is the colour scale). Sums wrap modulo 2³² on purpose.
pub const INTENSITY: QFormat = QFormat::signed(16, 16);
/// The BVI's 8-bit outputs `red`, `green`, `blue`, read as integers 0..=255: the integer part
/// of an [`INTENSITY`] word, saturated (negative → 0, ≥ 256 → 255).
pub const LEVEL: QFormat = QFormat::unsigned(8, 0);

impl QFormat {
    pub const fn signed(int_bits: u32, frac_bits: u32) -> Self {
        Self {
            int_bits,
            frac_bits,
            signed: true,
        }
    }
    pub const fn unsigned(int_bits: u32, frac_bits: u32) -> Self {
        Self {
            int_bits,
            frac_bits,
            signed: false,
        }
    }
    /// Word width in bits.
    pub const fn width(&self) -> u32 {
        self.int_bits + self.frac_bits
    }
    /// Value of one LSB.
    pub fn lsb(&self) -> f64 {
        (-(self.frac_bits as f64)).exp2()
    }
    /// Smallest representable raw integer (as a signed integer).
    pub const fn min_int(&self) -> i64 {
        if self.signed {
            -(1i64 << (self.width() - 1))
        } else {
            0
        }
    }
    /// Largest representable raw integer.
    pub const fn max_int(&self) -> i64 {
        if self.signed {
            (1i64 << (self.width() - 1)) - 1
        } else {
            (1i64 << self.width()) - 1
        }
    }
    /// Smallest representable value.
    pub fn min(&self) -> f64 {
        self.min_int() as f64 * self.lsb()
    }
    /// Largest representable value.
    pub fn max(&self) -> f64 {
        self.max_int() as f64 * self.lsb()
    }
    /// Mask of the word's bits.
    pub const fn mask(&self) -> u64 {
        (1u64 << self.width()) - 1
    }
    /// The integer nearest `v / lsb` (ties toward +∞), clamped to the format's range.
    /// NaN maps to 0.
    pub fn quantize_int(&self, v: f64) -> i64 {
        if v.is_nan() {
            return 0;
        }
        let scaled = (v * (self.frac_bits as f64).exp2() + 0.5).floor();
        scaled.clamp(self.min_int() as f64, self.max_int() as f64) as i64
    }
    /// `v` rounded to nearest (ties toward +∞) and saturated, as a raw word.
    pub fn quantize(&self, v: f64) -> u64 {
        self.from_int(self.quantize_int(v))
    }
    /// Raw word of a (signed) integer, wrapped to the word width.
    pub fn from_int(&self, i: i64) -> u64 {
        (i as u64) & self.mask()
    }
    /// Integer value of a raw word (sign-extended when signed).
    pub fn to_int(&self, raw: u64) -> i64 {
        let raw = raw & self.mask();
        if self.signed && raw >> (self.width() - 1) != 0 {
            raw as i64 - (1i64 << self.width())
        } else {
            raw as i64
        }
    }
    /// Real value of a raw word.
    pub fn to_f64(&self, raw: u64) -> f64 {
        self.to_int(raw) as f64 * self.lsb()
    }
    /// Whether the real value `v` is representable without saturation.
    pub fn contains(&self, v: f64) -> bool {
        v >= self.min() && v <= self.max()
    }
}

impl std::fmt::Display for QFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = if self.signed { "signed" } else { "unsigned" };
        write!(f, "{s} Q{}.{}", self.int_bits, self.frac_bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q2_14_range_and_rounding() {
        assert_eq!(NORMAL.width(), 16);
        assert_eq!(NORMAL.min(), -2.0);
        assert_eq!(NORMAL.max(), 2.0 - 2f64.powi(-14));
        assert_eq!(NORMAL.quantize(1.0), 0x4000);
        assert_eq!(NORMAL.quantize(-1.0), 0xC000);
        assert_eq!(NORMAL.quantize(-2.0), 0x8000);
        assert_eq!(NORMAL.quantize(5.0), 0x7FFF, "saturates high");
        assert_eq!(NORMAL.quantize(-5.0), 0x8000, "saturates low");
        // Ties go toward +infinity: +0.5 LSB -> 1, -0.5 LSB -> 0.
        let half = NORMAL.lsb() / 2.0;
        assert_eq!(NORMAL.quantize(half), 1);
        assert_eq!(NORMAL.quantize(-half), 0);
        assert_eq!(NORMAL.quantize(-3.0 * half), NORMAL.from_int(-1));
        assert_eq!(NORMAL.to_f64(0xC000), -1.0);
        assert_eq!(NORMAL.to_f64(0x8000), -2.0);
    }

    #[test]
    fn intensity_formats() {
        assert_eq!(INTENSITY.width(), 32);
        assert_eq!(INTENSITY.to_f64(0x0001_8000), 1.5);
        assert_eq!(INTENSITY.to_f64(0xFFFF_0000), -1.0);
        assert_eq!(LEVEL.width(), 8);
        assert_eq!(LEVEL.quantize(300.0), 255);
        assert_eq!(LEVEL.quantize(-3.0), 0);
    }

    #[test]
    fn unsigned_formats() {
        assert_eq!(K_FULL.max_int(), u32::MAX as i64);
        assert_eq!(K_NARROW.quantize(-0.1), 0);
        assert_eq!(K_NARROW.quantize(2.5), 0xFFFF);
        assert_eq!(K_NARROW.to_f64(0x8000), 1.0);
        assert_eq!(
            COEF_C1.to_int(COEF_C1.quantize(-2.046)),
            (-2.046f64 * 2f64.powi(29)).round() as i64
        );
    }
}
