//! Vector interpolator (SPEC §1, "constant increments"; the hardware adds them the way the BVI
//! of SPEC §6 does): the interpolated normal N along the address block's walk, the golden of
//! `rtl/src/units/vector_interpolator.rs`.
//!
//! Each component of N is a screen-space plane through the three vertex normals' component
//! (`ScreenTriangle::scalar_plane`), so it is walked exactly like a BVI intensity channel: the
//! value at the first line start, then per event one increment — the whole working-edge move
//! into a line (`short` = f·a + b or `long` = (f + 1)·a + b, the grouped ΔN_H/ΔN_V/ΔN_D of
//! SPEC §1) or one pixel along the line (`line` = dir·a). The hardware words are signed Q3.29
//! (wrapping, like the BVI's: only the pixel values must be in range, and |N| ≤ 1 for
//! interpolated unit normals); the output is rounded to signed Q2.17 (it was Q2.14 until
//! `bump`'s 2-LSB bound: that rounding was the largest error left in cos γ,
//! `docs/bump-precision.md`).

use crate::types::Plane;
use crate::units::address_block::{AddressOutputs, AddressSetup};
use crate::units::intensity_interpolator::{BviTwin, ChannelSetup, ChannelWords};

/// Fraction bits of the accumulator words (signed Q3.29).
pub const WORD_FRAC_BITS: u32 = 29;
/// Fraction bits of the output components (signed Q2.17).
pub const OUT_FRAC_BITS: u32 = 17;

/// `v` rounded to the nearest signed Q3.29 word (ties toward +∞), modulo 2³².
pub fn quantize(v: f64) -> u32 {
    let scaled = (v * (WORD_FRAC_BITS as f64).exp2() + 0.5).floor();
    (scaled as i128).rem_euclid(1i128 << 32) as u32
}

/// The twelve set-up words (start, short, long, line for x, y, z) of the component planes
/// `planes` for the walk `addr` describes. No rounding bias: the output stage rounds.
pub fn setup(planes: &[Plane; 3], addr: &AddressSetup) -> [ChannelWords; 3] {
    planes.map(|p| {
        let s = ChannelSetup::new(&p, addr);
        ChannelWords {
            start: quantize(s.start),
            short: quantize(s.short),
            long: quantize(s.long),
            line: quantize(s.line),
        }
    })
}

/// The bound on |output − N_k| for a pixel reached by `adds` additions: each of the `adds`
/// quantized terms is off by ≤ 2⁻³⁰, and the output rounding by ≤ 2⁻¹⁸.
pub fn error_bound(adds: u32) -> f64 {
    adds as f64 * (-(WORD_FRAC_BITS as f64 + 1.0)).exp2() + (-(OUT_FRAC_BITS as f64 + 1.0)).exp2()
}

/// The output stage: a Q3.29 word to Q2.17 — add half an output LSB (2¹¹) in the 32-bit
/// adder (wrapping), drop 12 bits, saturate to [−2, 2 − 2⁻¹⁷] when the sum leaves [−2, 2).
pub fn round_word(word: u32) -> i64 {
    let sum = word.wrapping_add(1 << 11) as i32 as i64;
    if (-(1 << 30)..(1 << 30)).contains(&sum) {
        sum >> 12
    } else if sum < 0 {
        -(1 << 18)
    } else {
        (1 << 18) - 1
    }
}

/// Bit-exact twin of the vector interpolator: the BVI's three accumulators ([`BviTwin`], the
/// same register transfers on Q3.29 words) and the rounding output stage.
#[derive(Clone, Copy, Debug, Default)]
pub struct VectorTwin(BviTwin);

impl VectorTwin {
    /// (valid_out, [nx, ny, nz] as signed Q2.17 integers) shown this clock.
    pub fn outputs(&self) -> (bool, [i64; 3]) {
        let (valid, _, words) = self.0.outputs();
        (valid, words.map(round_word))
    }
    /// One rising edge with the address block's event `ev` and, with `load`, the next words.
    pub fn clock(&mut self, load: Option<&[ChannelWords; 3]>, ev: &AddressOutputs) {
        self.0.clock(load, ev);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantize_and_round() {
        assert_eq!(quantize(1.0), 1 << 29);
        assert_eq!(quantize(-1.0), (-(1i64 << 29)) as u32);
        assert_eq!(round_word(1 << 29), 1 << 17);
        // Half an output LSB rounds up; just below it rounds down.
        assert_eq!(round_word(1 << 11), 1);
        assert_eq!(round_word((1 << 11) - 1), 0);
        assert_eq!(round_word((-(1i64 << 11)) as u32), 0);
        assert_eq!(round_word((-(1i64 << 11) - 1) as u32), -1);
        // Beyond ±2: saturation, not wrap.
        assert_eq!(round_word(3 << 29), (1 << 18) - 1);
        assert_eq!(round_word((-(3i64 << 29)) as u32), -(1 << 18));
        assert!(error_bound(8189) < 1.51 * (-17f64).exp2());
    }
}
