//! Normalizer without division or square root (SPEC §1, Ukrainian patent 63343).
//!
//! ```text
//! N' = N · f(K),   f(K) = (c2·K + c1)·K + c0,   K = x² + y² + z²
//! published: c2 = 0.822, c1 = −2.046, c0 = 2.227;  valid for K ∈ [0.499, 1]
//! piecewise (coeffs=piecewise): per segment s of K, f(K) = (c2ₛ·K + c1ₛ)·(K − baseₛ) + c0ₛ
//! ```
//! The coefficients are four sets, one per segment of K (K's leading bits in unsigned Q1.15:
//! bit 15 → 3, bit 14 clear → 0, else bits 13..12; `golden::units::normalizer::Scale`),
//! each with a base; one quadratic is the same set four times with base 0, and the selection
//! then costs nothing after synthesis.
//! Two tops share one back end:
//! - [`Normalizer`]: N in, N' out. Three squarers (Mul1–Mul3) and the three-operand adder Sm1
//!   form K, then [`NormalizerK`] does the rest. **Latency 15 clocks.**
//! - [`NormalizerK`]: N and K in (K from the K recurrence, `crate::units::k_recurrence`), N' out.
//!   Horner f = (c2·K + c1)·K + c0 on Mul4, Sm2, Mul5, Sm3; output scaling on Mul6–Mul8.
//!   **Latency 11 clocks.**
//!
//! 8 multipliers, 3 datapath adders (Sm1 three-operand), as in the patent's device; the only
//! other adders are the fixed-point bookkeeping of `crate::core::fixed` (sign corrections of the
//! unsigned multiplies, rounding, saturation) and the shift-adds of the 19-bit operands' low
//! parts (N, t1 and f are 19 bits: their top 16 bits go through Mul1–3, Mul5 and Mul6–8, their
//! three low bits through `MulLow3Pipe`, no multiplier).
//!
//! # Ports (formats from [`crate::core::fixed`])
//! | port                   | dir | format                    |
//! |------------------------|-----|---------------------------|
//! | `clock`                | in  | clock, rising edge        |
//! | `valid_in`             | in  | 1 = x, y, z (and k) hold a vector this clock |
//! | `x`, `y`, `z`          | in  | signed Q2.17, 19 bits     |
//! | `k` (NormalizerK only) | in  | unsigned Q4.28, x²+y²+z² (exact, or floored to Q4.28) |
//! | `valid_out`            | out | `valid_in` delayed by the latency |
//! | `nx`, `ny`, `nz`       | out | signed Q2.17, 19 bits (registered) |
//!
//! Throughput: one vector per clock, no stalls; `valid` travels with the data, data words move
//! every clock whatever `valid_in` says (outputs are meaningful only with `valid_out`).
//!
//! # Pipeline (registers named after the quantity; `_pk` = delayed k clocks)
//! The multipliers, narrowings and delay lines are the shared blocks of `crate::core::primitives`
//! (named in brackets); B6–B7 form one `ScaleLane` per component (`lane_x`, `lane_y`,
//! `lane_z`), which also delays its component by 7 clocks (`x_to_f`) to meet f.
//! ```text
//! Normalizer only:
//!  S1  x = 8·xh + xl            per component [Square19]: xh² (Mul1-3), Q2.14² → Q4.28,
//!                                exact, in three clocks [MulSignedPipe, both operands xh];
//!                                beside it the cross term xl·(16·xh + xl) (units 2⁻³⁴,
//!                                exact) by shift-add in two [MulLow3Pipe]; in the third,
//!                                xterm_q = ⌊Σ cross terms / 64⌋ (Q4.28)
//!  S2  k_full = Σ xh² + xterm_q  Sm1, Q4.28 unsigned: ⌊x² + y² + z²⌋ exactly (x²/64 =
//!                                xh² + xl·(16·xh + xl)/64; < 12, cannot overflow);
//!                                valid_p4, x_p4 … carry the vector alongside [Delay]
//! NormalizerK (its stage 1 follows Normalizer's S2):
//!  B1  k_narrow = K              Q4.28 → Q1.15 unsigned: round (drop 13 LSBs), saturate at
//!                                2 − 2⁻¹⁵ when K ≥ 2 − 2⁻¹⁶ [RoundToUQ1_15]; beside it its
//!                                segment `seg`, which travels with the vector (`seg_p1`,
//!                                `seg_c0`) to select each stage's constants
//!  B2  c2k = |c2|·k_narrow       Mul4, Q1.15 × Q1.15 → Q2.30 unsigned, exact; beside it
//!                                K' = k_narrow − base (0 below the base; K' = K for base 0)
//!  B3  t1 = c1 ± c2k             Sm2 in Q3.29 (c2k halved: drops 1 LSB = 2⁻³⁰; cannot
//!                                overflow, checked by NormalizerCoeffs::new), then
//!                                Q3.29 → Q2.17 (19 bits): round (drop 12 LSBs; the half LSB
//!                                is in the constant c1_rnd), saturate to [−2, 2) [SatToQ2_17]
//!  B4  t1k = t1·K'               t1 = 8·t1h + t1l: Mul5, t1h (bits 18..3, signed Q2.14) ×
//!                                unsigned Q1.15 → signed Q3.29, exact, three clocks
//!                                [MulSignedUnsignedPipe]; beside it t1l·k (units 2⁻³², < 2¹⁹)
//!                                by shift-add in two clocks [MulLow3Pipe], then in the third
//!                                c0_low = c0_rnd + ⌊t1l·k / 16⌋ (Q4.28)
//!  B5  f = c0 + t1k              Sm3: c0_low + ⌊t1h·k / 2⌋ in Q4.28 (range [−8, 8), cannot
//!                                overflow), then Q4.28 → Q1.18 (19 bits): round (drop 10
//!                                LSBs; half LSB in c0_rnd), saturate to [0, 2 − 2⁻¹⁸]
//!                                [SatToUQ1_18]
//!  B6  xf = x_to_f·f (Mul6-8)    x = 8·xh + xl, f = 8·fh + fl: xh·fh, signed Q2.14 × unsigned
//!                                Q1.15 → signed Q3.29, exact, three clocks
//!                                [MulSignedUnsignedPipe]; beside it x·fl (units 2⁻³⁵) and
//!                                xl·fh (units 2⁻³²) by shift-add [MulLow3Pipe ×2], then
//!                                corr = ⌊(x·fl + 8·xl·fh) / 64⌋ + 2¹¹ (Q3.29, the half output
//!                                LSB): xh·fh + corr − 2¹¹ = ⌊x·f⌋ in Q3.29, exactly
//!  B7  nx = xf + corr            Q3.29 → Q2.17: drop 12 LSBs, saturate to [−2, 2)
//!                                [SatToQ2_17] (|x·fh| ≤ 2³¹ − 2¹⁵, |corr| < 2¹⁵: no wrap);
//!                                valid_p7 carries valid_in [Delay]
//! ```
//! ```text
//! clock      : 0    1    2    3    4    5    6    7    8    9    10   11   12   13   14   15
//! valid_in   : v0   v1   v2 ...
//! Normalizer : S1a  S1b  S1c  S2   B1   B2   B3   B4a  B4b  B4c  B5   B6a  B6b  B6c  B7
//! valid_out  :                                                                          v0 (edge 15)
//! ```
//! S1, B4 and B6 took one clock each (latency 9, `NormalizerK` 7) until ECP5 timing: in the
//! pixel pipeline a multiplier and its sign correction in one clock ran at 92–98 MHz, and a
//! multiplier fed from registers placed by other logic, 94 MHz (see `crate::core::primitives`).
//!
//! t1, f and the outputs were 16 bits (Q2.14, Q1.15, Q2.14) until the lit methods' 2-LSB bound
//! (issue 9): the lighting unit's cos γ was up to 3.1–3.9 LSB of Q1.15 off the golden f64 front
//! end, and `bump` up to 6 LSB of 8 bits off its golden image. These three words were the
//! cheapest to widen (`docs/bump-precision.md`: no port of the lighting unit changes, no extra
//! multiplier). The input N followed (Q2.14 → Q2.17, the vector interpolator's output): its
//! rounding was then the largest error left in cos γ, and `bump` on an OBJ mesh was still
//! 3 LSB off at one pixel. Again no multiplier was added: three shift-adds in the squarers,
//! three more in the lanes.
//!
//! # Overflow
//! Nothing wraps. K cannot overflow; K ≥ 2 saturates k_narrow (out of the formula's domain);
//! t1 and f saturate; outputs saturate to the Q2.17 range. In the domain K ∈ [0.499, 1] with
//! the published or fitted coefficients no saturation happens (checked by
//! [`NormalizerCoeffs::new`], which rejects coefficient sets that would saturate t1 or f there
//! or overflow an adder anywhere).
//!
//! # Error budget (vs the f64 golden N·f(K) on the same quantized N, requested coefficients)
//! [`error_budget`] derives it from the formats above: per output component
//! `|err| ≤ |x|max·Δf + 2⁻¹⁸ + 2⁻²⁹` (the output rounding and the floor of x·f) with
//! `Δf = max|f'(K)|·(2⁻¹⁶ + 2⁻²⁸) (K's floor and rounding) + Δc2·K² (c2 quantization, ≤ 2⁻¹⁶·K²)
//!      + 2⁻¹⁸·K (t1 rounding) + 2⁻¹⁹ (f rounding) + ~2⁻²⁷ (c0, c1, halvings, low-part floors)`.
//! Published coefficients on the domain (K ∈ [0.499, 1 + 2⁻¹²], |x| ≤ 1 + 2⁻¹⁷): Δf ≤ 3.35·10⁻⁵,
//! component error ≤ 3.73·10⁻⁵ (4.9 LSB of Q2.17, 1.2 of Q2.14), RMS bound 2.03·10⁻⁵
//! (measured over 100 000 vectors: 2.21·10⁻⁵ and 5.4·10⁻⁶; 2.22·10⁻⁵ with N at Q2.14). FIT
//! (exact in these formats): 2.65·10⁻⁵, RMS 1.04·10⁻⁵ (measured 1.66·10⁻⁵, 4.1·10⁻⁶). With
//! 16-bit t1, f and outputs (before) the published set's bound was 1.04·10⁻⁴ (measured
//! 8.3·10⁻⁵): K's rounding to Q1.15 is now the largest term.
//! End-to-end against exact normalization N/|N| of the same quantized N:
//! max|f(K)·√K − 1| (0.351 % for the published set) + √K·Δf + √3·(2⁻¹⁸ + 2⁻²⁹) = 0.351 % +
//! 0.0040 % (measured: 0.3523 %). Rounding N to Q2.17 in the vector interpolator moves N/|N| by
//! at most 0.0009 % more (0.0075 % at Q2.14).
//! Piecewise: the same terms per segment (with K' for the second product), the largest
//! segment's, plus the largest difference of two neighbouring segments' polynomials within
//! K's rounding of their boundary (the hardware picks the segment from the rounded K): 2.3·10⁻⁴
//! for `golden::units::normalizer::PIECEWISE`, whose formula error is 0.0112 % (measured end to
//! end over 100 000 vectors: 0.0128 %).

use golden::units::normalizer::{Scale, K_DOMAIN, SEGMENTS};
use rust_hdl::prelude::*;

use crate::core::fixed::{
    QFormat, COEF_C0, COEF_C1, COEF_C2, HORNER_T1, K_FULL, K_NARROW, NORMALIZED, NORM_SCALE,
    PRODUCT,
};
use crate::core::primitives::{
    Delay, MulLow3Pipe, MulSignedPipe, MulSignedUnsignedPipe, RoundToUQ1_15, SatToQ2_17,
    SatToUQ1_18, SIGNED_MUL_LATENCY,
};
use crate::core::registry::{BlockParams, Options};

/// Why a coefficient set cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum CoeffError {
    #[error("coefficient {name} = {value} is outside {format} (range [{min}, {max}])")]
    OutOfRange {
        name: &'static str,
        value: f64,
        format: QFormat,
        min: f64,
        max: f64,
    },
    #[error("{what} would overflow the 32-bit adder for these coefficients")]
    AdderOverflow { what: &'static str },
    #[error("{what} leaves its format at K = {k} inside the domain (value {value})")]
    SaturatesInDomain {
        what: &'static str,
        k: f64,
        value: f64,
    },
}

/// One segment's words as the hardware holds them (see the module header for formats).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentWords {
    /// |c2| in unsigned Q1.15.
    pub c2_mag: u64,
    /// Sign of c2.
    pub c2_neg: bool,
    /// c1 as a signed Q3.29 integer.
    pub c1: i64,
    /// c0 as a signed Q4.28 integer.
    pub c0: i64,
    /// The segment's base in unsigned Q1.15 (0 for one quadratic).
    pub base: u64,
}

/// The coefficients as the hardware holds them: four segments of K, each (c2, c1, c0, base)
/// (`golden::units::normalizer::Scale`; one quadratic is the same in all four, base 0).
#[derive(Clone, Debug, PartialEq)]
pub struct NormalizerCoeffs {
    /// The coefficients asked for.
    pub requested: Scale,
    /// Their words, per segment.
    pub words: [SegmentWords; SEGMENTS],
}

/// Extra margin on the K domain for the saturation check: quantizing a vector of the domain
/// to Q2.17 (or Q2.14, the span normalizer's) moves K by less than 2·√3·2⁻¹⁵ ≈ 1.1·10⁻⁴.
const DOMAIN_MARGIN: f64 = 0.01;
/// Margin around a boundary between segments: K's rounding to Q1.15 (2⁻¹⁶) and its
/// quantization (above) can put a K of one segment into its neighbour.
const SEGMENT_MARGIN: f64 = 0.001;

/// Where segment `s`'s words are used, for the checks and the error budget: its part of
/// [k_lo, k_hi] (the golden `Scale::segment_range`, open at the outer ends) widened by
/// [`SEGMENT_MARGIN`] at inner boundaries; `None` when it has none.
fn segment_span(s: usize, k_lo: f64, k_hi: f64) -> Option<(f64, f64)> {
    let (lo, hi) = Scale::segment_range(s);
    let lo = if s == 0 {
        f64::NEG_INFINITY
    } else {
        lo - SEGMENT_MARGIN
    };
    let hi = if s == SEGMENTS - 1 {
        f64::INFINITY
    } else {
        hi + SEGMENT_MARGIN
    };
    let (a, b) = (lo.max(k_lo), hi.min(k_hi));
    (a <= b).then_some((a, b))
}

impl NormalizerCoeffs {
    /// Quantize `c` (one quadratic or a [`Scale`]) and check that the datapath cannot
    /// overflow with it.
    pub fn new(c: impl Into<Scale>) -> Result<Self, CoeffError> {
        let c: Scale = c.into();
        let check = |name, value: f64, fmt: QFormat| {
            if fmt.contains(value) {
                Ok(())
            } else {
                Err(CoeffError::OutOfRange {
                    name,
                    value,
                    format: fmt,
                    min: fmt.min(),
                    max: fmt.max(),
                })
            }
        };
        for g in c.0 {
            check("c2", g.c[0].abs(), COEF_C2)?;
            check("c1", g.c[1], COEF_C1)?;
            check("c0", g.c[2], COEF_C0)?;
            check("base", g.base, K_NARROW)?;
        }
        let coeffs = Self {
            requested: c,
            words: c.0.map(|g| SegmentWords {
                c2_mag: COEF_C2.quantize(g.c[0].abs()),
                c2_neg: g.c[0] < 0.0,
                c1: COEF_C1.quantize_int(g.c[1]),
                c0: COEF_C0.quantize_int(g.c[2]),
                base: K_NARROW.quantize(g.base),
            }),
        };
        for w in coeffs.words {
            // Sm2: c1 + 2^11 ± (c2k >> 1) over every k_narrow in [0, 0xFFFF].
            let c2k_half_max = ((w.c2_mag * 0xFFFF) >> 1) as i64;
            let base = w.c1 + (1 << 11);
            let (lo, hi) = if w.c2_neg {
                (base - c2k_half_max, base)
            } else {
                (base, base + c2k_half_max)
            };
            if lo < i32::MIN as i64 || hi > i32::MAX as i64 {
                return Err(CoeffError::AdderOverflow {
                    what: "Sm2 (c1 + c2·K)",
                });
            }
            // Sm3: c0 + 2^9 + (t1l·K' >> 4) + (t1k >> 1), t1k = t1h·K' in
            // [-2^15·0xFFFF, 0x7FFF·0xFFFF], t1l·K' in [0, 7·0xFFFF] (K' = K − base ≤ K).
            let base = w.c0 + (1 << 9);
            let (lo, hi) = (
                base + ((-(1i64 << 15) * 0xFFFF) >> 1),
                base + ((7 * 0xFFFF) >> 4) + ((0x7FFFi64 * 0xFFFF) >> 1),
            );
            if lo < i32::MIN as i64 || hi > i32::MAX as i64 {
                return Err(CoeffError::AdderOverflow {
                    what: "Sm3 (t1·K + c0)",
                });
            }
        }
        // No saturation of t1 or f on the domain (with margin), each segment on its part.
        let q = coeffs.quantized();
        let (k_lo, k_hi) = (K_DOMAIN.0 - DOMAIN_MARGIN, K_DOMAIN.1 + DOMAIN_MARGIN);
        for (s, g) in q.0.iter().enumerate() {
            let Some((a, b)) = segment_span(s, k_lo, k_hi) else {
                continue;
            };
            for i in 0..=1000 {
                let k = a + (b - a) * i as f64 / 1000.0;
                let t1 = g.c[0] * k + g.c[1];
                if !HORNER_T1.contains(t1) {
                    return Err(CoeffError::SaturatesInDomain {
                        what: "t1 = c2·K + c1",
                        k,
                        value: t1,
                    });
                }
                let f = g.at(k);
                if !NORM_SCALE.contains(f) {
                    return Err(CoeffError::SaturatesInDomain {
                        what: "f(K)",
                        k,
                        value: f,
                    });
                }
            }
        }
        Ok(coeffs)
    }

    /// The published set (0.822, −2.046, 2.227).
    pub fn published() -> Self {
        Self::new(golden::units::normalizer::PUBLISHED)
            .expect("published coefficients fit the formats")
    }

    /// The coefficients the hardware actually multiplies and adds, as f64.
    pub fn quantized(&self) -> Scale {
        let mut out = self.requested;
        for (g, w) in out.0.iter_mut().zip(self.words) {
            let c2 = COEF_C2.to_f64(w.c2_mag);
            g.c = [
                if w.c2_neg { -c2 } else { c2 },
                w.c1 as f64 * COEF_C1.lsb(),
                w.c0 as f64 * COEF_C0.lsb(),
            ];
            g.base = K_NARROW.to_f64(w.base);
        }
        out
    }
}

impl BlockParams for NormalizerCoeffs {
    const KEYS: &'static [&'static str] = &["coeffs"];
    /// `coeffs=published` (default, SPEC §1: 0.822, −2.046, 2.227), `coeffs=fit` (exact in
    /// value and slope at K = 1, `golden::units::normalizer::FIT`) or `coeffs=piecewise` (four
    /// segments of K, `golden::units::normalizer::PIECEWISE`).
    fn from_options(o: &Options) -> Result<Self, String> {
        let c: Scale = match o.get("coeffs").unwrap_or("published") {
            "published" => golden::units::normalizer::PUBLISHED.into(),
            "fit" => golden::units::normalizer::FIT.into(),
            "piecewise" => golden::units::normalizer::PIECEWISE,
            other => {
                return Err(format!(
                    "unknown coefficient set {other:?} (expected published, fit or piecewise)"
                ))
            }
        };
        NormalizerCoeffs::new(c).map_err(|e| e.to_string())
    }
    fn test_sets() -> Vec<Options> {
        ["published", "fit", "piecewise"]
            .map(|c| Options::new().with("coeffs", c))
            .to_vec()
    }
    fn describe(&self) -> Option<String> {
        let c = self.requested;
        Some(if c.is_piecewise() {
            let segs: Vec<String> =
                c.0.iter()
                    .map(|g| format!("base {}: ({}, {}, {})", g.base, g.c[0], g.c[1], g.c[2]))
                    .collect();
            format!(
                "Piecewise, f = (c2·K + c1)·(K − base) + c0 per segment: {}",
                segs.join("; ")
            )
        } else {
            let g = c.0[0].c;
            format!(
                "Coefficients (c2, c1, c0) = ({}, {}, {}); as quantized: {:?}",
                g[0],
                g[1],
                g[2],
                self.quantized().0[0].c
            )
        })
    }
}

/// Error budget of the normalizer datapath, derived from the formats (see the module header).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorBudget {
    /// Bound on |f_hw − f(K)| (f with the requested coefficients, K exact).
    pub scale_max: f64,
    /// Bound on the absolute error of one output component vs x·f(K).
    pub component_max: f64,
    /// Bound on the RMS error of the output components: quantization noise (σ² = step²/12 for
    /// each rounding, times its largest sensitivity) plus the deterministic bias terms.
    pub component_rms: f64,
    /// Bound on the extra Euclidean error of N' vs N·f(K) from the datapath, for |N| ≤ √k_hi:
    /// √k_hi·Δf + √3·2⁻¹⁵. Add the formula's own error to get the end-to-end bound.
    pub vector_max: f64,
}

/// The error budget of [`Normalizer`]/[`NormalizerK`] for inputs with K ∈ [k_lo, k_hi] and
/// |component| ≤ x_max (K and x as quantized, i.e. as the hardware sees them). Per segment
/// (on its part of [k_lo, k_hi], [`segment_span`]) the terms of the module header, with
/// K' = K − base for the second product; the largest segment's; plus, for a piecewise set, the
/// largest jump |f_s(K) − f_s+1(K)| near a boundary (where K's rounding to Q1.15 picks the
/// neighbouring segment).
pub fn error_budget(c: &NormalizerCoeffs, k_lo: f64, k_hi: f64, x_max: f64) -> ErrorBudget {
    let q = c.quantized();
    let dk = K_NARROW.lsb() / 2.0 + K_FULL.lsb();
    let t1_round = HORNER_T1.lsb() / 2.0;
    let f_round = NORM_SCALE.lsb() / 2.0;
    // The output rounding, and the floor of x·f (units 2⁻³⁵ → Q3.29) before it.
    let out_round = NORMALIZED.lsb() / 2.0 + PRODUCT.lsb();
    let var = |step: f64| step * step / 12.0;
    let (mut scale_max, mut noise_f, mut bias_f) = (0f64, 0f64, 0f64);
    // One quadratic: one span, the whole of [k_lo, k_hi].
    let spans: Vec<(usize, (f64, f64))> = if c.requested.is_piecewise() {
        (0..SEGMENTS)
            .filter_map(|s| segment_span(s, k_lo, k_hi).map(|span| (s, span)))
            .collect()
    } else {
        vec![(0, (k_lo, k_hi))]
    };
    for (s, (a, b)) in spans {
        let (rg, qg) = (c.requested.0[s], q.0[s]);
        let r = rg.plain();
        // K after rounding to Q1.15 may exceed b by half an LSB; before it, the squarers floor
        // K to Q4.28 (for Q2.17 components). K' = K − base ≤ k_n − base.
        let k_n = (b + K_NARROW.lsb() / 2.0).min(K_NARROW.max());
        let k_l = (k_n - rg.base).max(0.0);
        // f'(K) = 2·c2·K + c1 (plain form) is linear: its extremes are at the span's ends.
        let fprime = |k: f64| (2.0 * r[0] * k + r[1]).abs();
        let fprime_max = fprime(a - dk).max(fprime(k_n));
        let dc2 = (qg.c[0] - rg.c[0]).abs();
        let dc1 = (qg.c[1] - rg.c[1]).abs() + COEF_C1.lsb(); // + halving of c2k (Q2.30 → Q3.29)
                                                             // c0's quantization, the halving of t1h·K' (Q3.29 → Q4.28) and the floor of t1l·K'
                                                             // (units 2⁻³² → Q4.28).
        let dc0 = (qg.c[2] - rg.c[2]).abs() + 2.0 * COEF_C0.lsb();
        let seg_max = fprime_max * dk
            + r[0].abs() * dk * dk
            + dc2 * k_n * k_l
            + dc1 * k_l
            + t1_round * k_l
            + dc0
            + f_round;
        scale_max = scale_max.max(seg_max);
        noise_f = noise_f.max(
            var(NORM_SCALE.lsb())
                + k_l * k_l * var(HORNER_T1.lsb())
                + fprime_max.powi(2) * var(K_NARROW.lsb()),
        );
        bias_f = bias_f.max(dc2 * k_n * k_l + dc1 * k_l + dc0);
    }
    // A K within its rounding (dk) of a boundary may take the neighbouring segment's
    // polynomial: the largest difference of the two there. Only that window's share of K
    // (3 boundaries, 2·dk each, over [k_lo, k_hi]) carries it into the RMS bound.
    let mut jump = 0f64;
    for s in 0..SEGMENTS - 1 {
        let (g0, g1) = (c.requested.0[s], c.requested.0[s + 1]);
        let edge = Scale::segment_range(s).1;
        for i in 0..=20 {
            let k = edge - dk + 2.0 * dk * i as f64 / 20.0;
            if (k_lo..=k_hi).contains(&k) {
                jump = jump.max((g0.at(k) - g1.at(k)).abs());
            }
        }
    }
    let window = (6.0 * dk / (k_hi - k_lo).max(6.0 * dk)).sqrt();
    let scale_max = scale_max + jump;
    let component_max = x_max * scale_max + out_round;
    let noise = var(NORMALIZED.lsb()) + x_max * x_max * noise_f;
    ErrorBudget {
        scale_max,
        component_max,
        component_rms: noise.sqrt() + x_max * (bias_f + jump * window),
        vector_max: k_hi.sqrt() * scale_max + 3f64.sqrt() * out_round,
    }
}

/// A 32-bit constant from a signed integer (two's complement).
fn b32(v: i64) -> Constant<Bits<32>> {
    Constant::new(((v as u64) & 0xFFFF_FFFF).into())
}

crate::hw_block! {
    /// Back end of the normalizer: K in, N·f(K) out. Latency [`NormalizerK::LATENCY`].
    pub struct NormalizerK(clock) as "normalizer-k" {
        summary: "N and K in, N·f(K) out: the normalizer without its squarers (SPEC §1)",
        latency: F_LATENCY + ScaleLane::LATENCY_FROM_F
            => "valid_in to valid_out, one input per clock",
        multipliers: 5,
        in { valid_in: Bit, x: Bits<19>, y: Bits<19>, z: Bits<19>, k: Bits<32> }
        out { valid_out: Bit, nx: Bits<19>, ny: Bits<19>, nz: Bits<19> }
        // Coefficients per segment, with half an output LSB folded into the constants that
        // are added anyway: t1 drops 12 LSBs, f drops 10. One quadratic: four equal sets.
        c2_mag: [Constant<Bits<16>>; SEGMENTS] = c.words.map(|w| Constant::new(w.c2_mag.into())),
        c2_neg: [Constant<Bit>; SEGMENTS] = c.words.map(|w| Constant::new(w.c2_neg)),
        c1_rnd: [Constant<Bits<32>>; SEGMENTS] = c.words.map(|w| b32(w.c1 + (1 << 11))),
        c0_rnd: [Constant<Bits<32>>; SEGMENTS] = c.words.map(|w| b32(w.c0 + (1 << 9))),
        base: [Constant<Bits<16>>; SEGMENTS] = c.words.map(|w| Constant::new(w.base.into())),
        sign32: Constant<Bits<32>> = b32(1 << 31),
        // B1, and the segment of K (bit 15 → 3, bit 14 clear → 0, else bits 13..12), which
        // travels with it to select each stage's constant.
        k_round: RoundToUQ1_15, k_narrow: DFF<Bits<16>>,
        seg_b1: Signal<Local, Bits<2>>, seg: DFF<Bits<2>>, seg_p1: DFF<Bits<2>>,
        seg_c0: Delay<Bits<2>, 4>,
        c2_sel: Signal<Local, Bits<16>>, base_sel: Signal<Local, Bits<16>>,
        c2_neg_sel: Signal<Local, Bit>, c1_sel: Signal<Local, Bits<32>>,
        c0_sel: Signal<Local, Bits<32>>, k_local: Signal<Local, Bits<16>>,
        // B2 (Mul4 is the plain unsigned multiply: both operands are unsigned); beside it
        // K' = K − base (clamped at 0) for Mul5.
        c2k: DFF<Bits<32>>, k_local_p2: Delay<Bits<16>, 2>,
        // B3
        t1_sat: SatToQ2_17, t1: DFF<Bits<19>>,
        // B4: t1's top 16 bits on Mul5, its 3 low bits by shift-add, then c0 + the low part.
        mul5: MulSignedUnsignedPipe, low5: MulLow3Pipe, c0_low: DFF<Bits<32>>,
        // B5
        f_sat: SatToUQ1_18, f: DFF<Bits<19>>,
        // B6, B7: one lane per component.
        lane_x: ScaleLane, lane_y: ScaleLane, lane_z: ScaleLane,
        valid_p7: Delay<Bit, { NormalizerK::LATENCY }>,
        // Combinational intermediates, each exactly sized (rust-hdl wraps per op, Verilog per
        // context).
        c2k_half: Signal<Local, Bits<32>>, t1_wide: Signal<Local, Bits<32>>,
        k_ext: Signal<Local, Bits<24>>, low5_shift: Signal<Local, Bits<32>>,
        t1k_half: Signal<Local, Bits<32>>, f_wide: Signal<Local, Bits<32>>,
    }
    new(c: &NormalizerCoeffs);
}

impl Logic for NormalizerK {
    #[hdl_gen]
    fn update(&mut self) {
        // B1..B5 registers, then the lanes (B6, B7) and the valid line.
        clock!(
            self, clock, k_narrow, seg, seg_p1, seg_c0, c2k, k_local_p2, t1, mul5, low5, c0_low, f
        );
        clock!(self, clock, lane_x, lane_y, lane_z, valid_p7);
        // B1: K (Q4.28) → Q1.15, round to nearest, saturate.
        self.k_round.wide.next = self.k.val();
        self.k_narrow.d.next = self.k_round.narrow.val();
        self.seg_b1.next = self.k_round.narrow.val().get_bits::<2>(12);
        if !self.k_round.narrow.val().get_bit(14) {
            self.seg_b1.next = 0.into();
        }
        if self.k_round.narrow.val().get_bit(15) {
            self.seg_b1.next = 3.into();
        }
        self.seg.d.next = self.seg_b1.val();
        self.seg_p1.d.next = self.seg.q.val();
        self.seg_c0.d.next = self.seg.q.val();
        // Each stage's constants, selected by its vector's segment.
        self.c2_sel.next = self.c2_mag[0].val();
        self.base_sel.next = self.base[0].val();
        if self.seg.q.val() == 1 {
            self.c2_sel.next = self.c2_mag[1].val();
            self.base_sel.next = self.base[1].val();
        }
        if self.seg.q.val() == 2 {
            self.c2_sel.next = self.c2_mag[2].val();
            self.base_sel.next = self.base[2].val();
        }
        if self.seg.q.val() == 3 {
            self.c2_sel.next = self.c2_mag[3].val();
            self.base_sel.next = self.base[3].val();
        }
        self.c2_neg_sel.next = self.c2_neg[0].val();
        self.c1_sel.next = self.c1_rnd[0].val();
        if self.seg_p1.q.val() == 1 {
            self.c2_neg_sel.next = self.c2_neg[1].val();
            self.c1_sel.next = self.c1_rnd[1].val();
        }
        if self.seg_p1.q.val() == 2 {
            self.c2_neg_sel.next = self.c2_neg[2].val();
            self.c1_sel.next = self.c1_rnd[2].val();
        }
        if self.seg_p1.q.val() == 3 {
            self.c2_neg_sel.next = self.c2_neg[3].val();
            self.c1_sel.next = self.c1_rnd[3].val();
        }
        self.c0_sel.next = self.c0_rnd[0].val();
        if self.seg_c0.q.val() == 1 {
            self.c0_sel.next = self.c0_rnd[1].val();
        }
        if self.seg_c0.q.val() == 2 {
            self.c0_sel.next = self.c0_rnd[2].val();
        }
        if self.seg_c0.q.val() == 3 {
            self.c0_sel.next = self.c0_rnd[3].val();
        }

        // B2 (Mul4): |c2|·K, Q1.15 × Q1.15 → Q2.30; K' = K − base, 0 below the base.
        self.c2k.d.next = self.c2_sel.val() * self.k_narrow.q.val();
        self.k_local.next = self.k_narrow.q.val() - self.base_sel.val();
        if self.k_narrow.q.val() < self.base_sel.val() {
            self.k_local.next = 0.into();
        }
        self.k_local_p2.d.next = self.k_local.val();

        // B3 (Sm2): t1 = c1 ± c2·K in Q3.29 (+ half LSB of Q2.17), then round/saturate to Q2.17.
        self.c2k_half.next = self.c2k.q.val() >> 1;
        if self.c2_neg_sel.val() {
            self.t1_wide.next = self.c1_sel.val() - self.c2k_half.val();
        } else {
            self.t1_wide.next = self.c1_sel.val() + self.c2k_half.val();
        }
        self.t1_sat.wide.next = self.t1_wide.val();
        self.t1.d.next = self.t1_sat.narrow.val();

        // B4 (Mul5): t1h·K, t1h = t1 bits 18..3 (signed Q2.14), × unsigned Q1.15 → signed
        // Q3.29; beside it t1l·K (t1l = bits 2..0, units 2⁻³², < 2¹⁹) by shift-add, floored
        // to Q4.28 and added to c0 (+ half LSB of Q1.18) in the clock Mul5's product arrives.
        self.mul5.a.next = self.t1.q.val().get_bits::<16>(3);
        self.mul5.b.next = self.k_local_p2.q.val();
        self.k_ext.next = bit_cast::<24, 16>(self.k_local_p2.q.val());
        self.low5.v.next = self.k_ext.val();
        self.low5.m.next = self.t1.q.val().get_bits::<3>(0);
        self.low5_shift.next = self.low5.p.val() >> 4;
        self.c0_low.d.next = self.c0_sel.val() + self.low5_shift.val();

        // B5 (Sm3): f = c0 + t1·K in Q4.28 (+ half LSB of Q1.18), then round/saturate to Q1.18.
        self.t1k_half.next = self.mul5.p.val() >> 1;
        if self.mul5.p.val().get_bit(31) {
            self.t1k_half.next = self.t1k_half.val() | self.sign32.val();
        }
        self.f_wide.next = self.c0_low.q.val() + self.t1k_half.val();
        self.f_sat.wide.next = self.f_wide.val();
        self.f.d.next = self.f_sat.narrow.val();

        // B6, B7 (Mul6-8): each component, delayed to meet f, times f, rounded to Q2.17.
        self.lane_x.x.next = self.x.val();
        self.lane_y.x.next = self.y.val();
        self.lane_z.x.next = self.z.val();
        self.lane_x.f.next = self.f.q.val();
        self.lane_y.f.next = self.f.q.val();
        self.lane_z.f.next = self.f.q.val();
        self.nx.next = self.lane_x.n.val();
        self.ny.next = self.lane_y.n.val();
        self.nz.next = self.lane_z.n.val();

        self.valid_p7.d.next = self.valid_in.val();
        self.valid_out.next = self.valid_p7.q.val();
    }
}

/// Clocks from K (B1's input) to f (B5's register): the delay a component needs to meet f.
const F_LATENCY: usize = 4 + SIGNED_MUL_LATENCY;

crate::hw_block! {
    /// One output component of [`NormalizerK`], stages B6 and B7: `n = x·f` (Mul6, Mul7 or
    /// Mul8), signed Q2.17 × unsigned Q1.18, rounded and saturated to Q2.17. Both words are
    /// split, x = 8·xh + xl and f = 8·fh + fl: the top 16 bits go through the multiplier
    /// (xh·fh, signed Q3.29, exact), the low parts through two shift-adds (x·fl and xl·fh,
    /// exact; units 2⁻³⁵ and 2⁻³²), whose sum T = x·fl + 8·xl·fh is floored to Q3.29, so that
    /// xh·fh + ⌊T/64⌋ = ⌊x·f⌋ in Q3.29 exactly; then the half output LSB. `x` enters with the
    /// vector's `valid_in` and waits [`F_LATENCY`] clocks for `f`; `n` is registered,
    /// [`ScaleLane::LATENCY_FROM_F`] clocks after `f`.
    struct ScaleLane(clock) {
        in { x: Bits<19>, f: Bits<19> }
        out { n: Bits<19> }
        x_to_f: Delay<Bits<19>, F_LATENCY>, mul: MulSignedUnsignedPipe,
        low: MulLow3Pipe, low_f: MulLow3Pipe, corr: DFF<Bits<32>>,
        half_lsb: Constant<Bits<32>> = Constant::new((1u64 << 11).into()),
        sign6: Constant<Bits<32>> = Constant::new(0xFC00_0000u64.into()),
        sign5: Constant<Bits<24>> = Constant::new(0xF8_0000u64.into()),
        x_ext: Signal<Local, Bits<24>>, fh_ext: Signal<Local, Bits<24>>,
        low_f_sh: Signal<Local, Bits<32>>, low_sum: Signal<Local, Bits<32>>,
        low_shift: Signal<Local, Bits<32>>,
        sum: Signal<Local, Bits<32>>,
        sat: SatToQ2_17, n_q: DFF<Bits<19>>,
    }
}

impl ScaleLane {
    /// Clocks from `f` to `n`: the product's registers (B6) and the output register (B7).
    const LATENCY_FROM_F: usize = SIGNED_MUL_LATENCY + 1;
}

impl Logic for ScaleLane {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, x_to_f, mul, low, low_f, corr, n_q);
        self.x_to_f.d.next = self.x.val();
        // B6: xh·fh, signed Q2.14 × unsigned Q1.15 → signed Q3.29 (three clocks).
        self.mul.a.next = self.x_to_f.q.val().get_bits::<16>(3);
        self.mul.b.next = self.f.val().get_bits::<16>(3);
        // Beside it, in two clocks: x·fl (x sign-extended to 24 bits; |x·fl| < 2²¹) and
        // xl·fh (fh zero-extended; < 2¹⁹); in the third, T = x·fl + 8·xl·fh (< 2²³ in
        // magnitude) and corr = ⌊T / 64⌋ + 2¹¹ (Q3.29, with the half output LSB).
        if self.x_to_f.q.val().get_bit(18) {
            self.x_ext.next = bit_cast::<24, 19>(self.x_to_f.q.val()) | self.sign5.val();
        } else {
            self.x_ext.next = bit_cast::<24, 19>(self.x_to_f.q.val());
        }
        self.low.v.next = self.x_ext.val();
        self.low.m.next = self.f.val().get_bits::<3>(0);
        self.fh_ext.next = bit_cast::<24, 16>(self.f.val().get_bits::<16>(3));
        self.low_f.v.next = self.fh_ext.val();
        self.low_f.m.next = self.x_to_f.q.val().get_bits::<3>(0);
        self.low_f_sh.next = self.low_f.p.val() << 3;
        self.low_sum.next = self.low.p.val() + self.low_f_sh.val();
        if self.low_sum.val().get_bit(31) {
            self.low_shift.next = (self.low_sum.val() >> 6) | self.sign6.val();
        } else {
            self.low_shift.next = self.low_sum.val() >> 6;
        }
        self.corr.d.next = self.low_shift.val() + self.half_lsb.val();
        // B7: Q3.29 → Q2.17, saturate (|xh·fh| ≤ 2³¹ − 2¹⁵ and −2¹⁵ < corr < 2¹⁷, with
        // xh·fh + corr ≤ 2³¹ − 2¹⁶ − 2¹⁵ + 88 064: the sum cannot wrap).
        self.sum.next = self.mul.p.val() + self.corr.q.val();
        self.sat.wide.next = self.sum.val();
        self.n_q.d.next = self.sat.narrow.val();
        self.n.next = self.n_q.q.val();
    }
}

crate::hw_block! {
    /// One squarer of [`Normalizer`]'s S1 for a signed Q2.17 component x = 8·xh + xl (xh its
    /// top 16 bits, signed Q2.14; xl its three low bits): x²/64 = xh² + xl·(16·xh + xl)/64.
    /// `sq` = xh² (Mul1, Mul2 or Mul3: signed Q4.28, exact), [`SIGNED_MUL_LATENCY`] clocks
    /// after `x`; `xterm` = xl·(16·xh + xl) (units 2⁻³⁴, exact, |xterm| < 2²²) by shift-add,
    /// [`MUL_LOW_LATENCY`](crate::core::primitives::MUL_LOW_LATENCY) clocks after `x` — 16·xh + xl
    /// is x's bits with a zero inserted above xl (wiring).
    struct Square19(clock) {
        in { x: Bits<19> }
        out { sq: Bits<32>, xterm: Bits<32> }
        mul: MulSignedPipe, low: MulLow3Pipe,
        lo_mask: Constant<Bits<24>> = Constant::new(0x7u64.into()),
        hi_mask: Constant<Bits<24>> = Constant::new(0xFF_FFF8u64.into()),
        sign5: Constant<Bits<24>> = Constant::new(0xF8_0000u64.into()),
        x_wide: Signal<Local, Bits<24>>, x_hi: Signal<Local, Bits<24>>,
        x_hi_sh: Signal<Local, Bits<24>>, x_lo: Signal<Local, Bits<24>>,
    }
}

impl Logic for Square19 {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, mul, low);
        self.mul.a.next = self.x.val().get_bits::<16>(3);
        self.mul.b.next = self.x.val().get_bits::<16>(3);
        self.sq.next = self.mul.p.val();
        // v = 16·xh + xl = {x[18:3], 0, x[2:0]} sign-extended to 24 bits, m = xl: x
        // sign-extended, its top part shifted up one bit over the inserted zero.
        if self.x.val().get_bit(18) {
            self.x_wide.next = bit_cast::<24, 19>(self.x.val()) | self.sign5.val();
        } else {
            self.x_wide.next = bit_cast::<24, 19>(self.x.val());
        }
        self.x_hi.next = self.x_wide.val() & self.hi_mask.val();
        self.x_hi_sh.next = self.x_hi.val() << 1;
        self.x_lo.next = self.x_wide.val() & self.lo_mask.val();
        self.low.v.next = self.x_hi_sh.val() | self.x_lo.val();
        self.low.m.next = self.x.val().get_bits::<3>(0);
        self.xterm.next = self.low.p.val();
    }
}

crate::hw_block! {
    /// The full normalizer: N in, N' = N·f(|N|²) out. Latency [`Normalizer::LATENCY`].
    pub struct Normalizer(clock) as "normalizer" {
        summary: "N in, N·f(|N|²) out: squarers, Horner f(K), scaling; no division or root (SPEC §1)",
        latency: SIGNED_MUL_LATENCY + 1 + NormalizerK::LATENCY => "valid_in to valid_out, one input per clock",
        multipliers: 8,
        in { valid_in: Bit, x: Bits<19>, y: Bits<19>, z: Bits<19> }
        out { valid_out: Bit, nx: Bits<19>, ny: Bits<19>, nz: Bits<19> }
        // S1: one squarer per component (xh² on the multiplier, the cross term by shift-add),
        // the cross terms' sum floored to Q4.28 and registered.
        sq_x: Square19, sq_y: Square19, sq_z: Square19,
        xterm_sum: Signal<Local, Bits<32>>, xterm_shift: Signal<Local, Bits<32>>,
        xterm_q: DFF<Bits<32>>,
        k_xy: Signal<Local, Bits<32>>, k_zc: Signal<Local, Bits<32>>,
        sign6: Constant<Bits<32>> = Constant::new(0xFC00_0000u64.into()),
        // S2
        k_full: DFF<Bits<32>>,
        // The vector and its valid wait for K (S1, S2).
        valid_p4: Delay<Bit, { SIGNED_MUL_LATENCY + 1 }>,
        x_p4: Delay<Bits<19>, { SIGNED_MUL_LATENCY + 1 }>,
        y_p4: Delay<Bits<19>, { SIGNED_MUL_LATENCY + 1 }>,
        z_p4: Delay<Bits<19>, { SIGNED_MUL_LATENCY + 1 }>,
        // B1..B7
        scale: NormalizerK = NormalizerK::new(c),
    }
    new(c: &NormalizerCoeffs);
}

impl Logic for Normalizer {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, sq_x, sq_y, sq_z, xterm_q, k_full, valid_p4, x_p4, y_p4, z_p4, scale);
        // S1 (Mul1-3): xh², Q2.14² → Q4.28, exact, in three clocks; the cross terms
        // xl·(16·xh + xl) (units 2⁻³⁴) in two, their sum floored to Q4.28 in the third.
        self.sq_x.x.next = self.x.val();
        self.sq_y.x.next = self.y.val();
        self.sq_z.x.next = self.z.val();
        self.xterm_sum.next = self.sq_x.xterm.val() + self.sq_y.xterm.val() + self.sq_z.xterm.val();
        if self.xterm_sum.val().get_bit(31) {
            self.xterm_shift.next = (self.xterm_sum.val() >> 6) | self.sign6.val();
        } else {
            self.xterm_shift.next = self.xterm_sum.val() >> 6;
        }
        self.xterm_q.d.next = self.xterm_shift.val();
        // S2 (Sm1): K = ⌊x² + y² + z²⌋ in Q4.28 (< 12, cannot overflow), as
        // xh² + yh² + zh² + ⌊Σ xl·(16·xh + xl) / 64⌋.
        // Two adds side by side, then their sum: two carry chains deep, as the three-operand
        // Sm1 was.
        self.k_xy.next = self.sq_x.sq.val() + self.sq_y.sq.val();
        self.k_zc.next = self.sq_z.sq.val() + self.xterm_q.q.val();
        self.k_full.d.next = self.k_xy.val() + self.k_zc.val();
        self.valid_p4.d.next = self.valid_in.val();
        self.x_p4.d.next = self.x.val();
        self.y_p4.d.next = self.y.val();
        self.z_p4.d.next = self.z.val();
        // B1..B7
        self.scale.valid_in.next = self.valid_p4.q.val();
        self.scale.x.next = self.x_p4.q.val();
        self.scale.y.next = self.y_p4.q.val();
        self.scale.z.next = self.z_p4.q.val();
        self.scale.k.next = self.k_full.q.val();
        self.valid_out.next = self.scale.valid_out.val();
        self.nx.next = self.scale.nx.val();
        self.ny.next = self.scale.ny.val();
        self.nz.next = self.scale.nz.val();
    }
}
