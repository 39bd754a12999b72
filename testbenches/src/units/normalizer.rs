//! Bench of the normalizer blocks (`rtl::units::normalizer`) against the golden model
//! (`golden::units::normalizer`): stimulus over the formula's domain, named edge cases, the
//! documented saturation behaviour, per-clock expectations and the end-to-end error against
//! exact normalization.

pub use golden::testing::seeded_runner;
use golden::units::normalizer::{twin, Scale};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use rtl::core::fixed::{HORNER_T1, INTERPOLATED, K_NARROW, NORMALIZED, NORM_SCALE};
use rtl::units::normalizer::{
    error_budget, ErrorBudget, Normalizer, NormalizerCoeffs, NormalizerK,
};

use crate::harness::{self, CheckSpec, Compare, Expected, Failure, Report, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};

/// K range of quantized domain vectors: interpolating unit vectors ≤ 90° apart gives
/// K ∈ [0.5, 1]; rounding each component to Q2.17 moves |N| by ≤ √3·2⁻¹⁸ (the bounds
/// below were set for Q2.14, √3·2⁻¹⁵, and still hold).
pub const DOMAIN_K: (f64, f64) = (0.499, 1.0 + 1.0 / 4096.0);
/// Largest |component| of a quantized domain vector (Q2.17: one LSB above 1).
pub const DOMAIN_X_MAX: f64 = 1.0 + 1.0 / 131072.0;

fn unit(z: f64, phi: f64) -> [f64; 3] {
    let r = (1.0 - z * z).max(0.0).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

/// A vector of the formula's domain: (1−t)·A + t·B for unit A, B with A·B ≥ 0 (≤ 90° apart),
/// A and B uniform on the sphere (B mirrored into A's hemisphere), t uniform in [0, 1].
pub fn domain_vector() -> impl Strategy<Value = [f64; 3]> {
    use std::f64::consts::TAU;
    (
        -1.0..=1.0f64,
        0.0..TAU,
        -1.0..=1.0f64,
        0.0..TAU,
        0.0..=1.0f64,
    )
        .prop_map(|(z1, p1, z2, p2, t)| {
            let a = unit(z1, p1);
            let mut b = unit(z2, p2);
            if a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0 {
                b = [-b[0], -b[1], -b[2]];
            }
            [0, 1, 2].map(|i| (1.0 - t) * a[i] + t * b[i])
        })
}

/// Name (hence seed) of the 100 000-vector domain run shared by the cycle-by-cycle test and
/// the differential Verilog test, so both see the same vectors.
pub const DOMAIN_RUN: &str = "normalizer_domain";
/// Vectors in the domain run.
pub const DOMAIN_VECTORS: usize = 100_000;

/// The domain run's seed and vectors (prints the seed; `SHADECORE_SEED` overrides it).
pub fn domain_run_vectors() -> (u64, Vec<[f64; 3]>) {
    let mut r = golden::testing::runner(DOMAIN_RUN, 1);
    (
        golden::testing::seed_for(DOMAIN_RUN),
        domain_vectors(&mut r, DOMAIN_VECTORS),
    )
}

/// `n` domain vectors drawn with `runner`.
pub fn domain_vectors(runner: &mut TestRunner, n: usize) -> Vec<[f64; 3]> {
    let s = domain_vector();
    (0..n)
        .map(|_| {
            s.new_tree(runner)
                .expect("strategy never rejects")
                .current()
        })
        .collect()
}

/// Named vectors of the domain (quantized before use).
pub fn edge_cases() -> Vec<(&'static str, [f64; 3])> {
    let s3 = 1.0 / 3f64.sqrt();
    let h = 0.5;
    vec![
        ("K=1 +x axis", [1.0, 0.0, 0.0]),
        ("K=1 -x axis", [-1.0, 0.0, 0.0]),
        ("K=1 +y axis", [0.0, 1.0, 0.0]),
        ("K=1 -y axis", [0.0, -1.0, 0.0]),
        ("K=1 +z axis", [0.0, 0.0, 1.0]),
        ("K=1 -z axis", [0.0, 0.0, -1.0]),
        ("K=1 diagonal", [s3, s3, s3]),
        ("K=1 all negative", [-s3, -s3, -s3]),
        ("K=1 mixed signs", [-0.6, 0.48, -0.64]),
        ("K=0.5 midpoint x,y", [h, h, 0.0]),
        ("K=0.5 midpoint -x,z", [-h, 0.0, h]),
        ("K=0.5 midpoint -y,-z", [0.0, -h, -h]),
        ("K=0.5 all negative", [-h, -h, 0.0]),
        (
            "K=0.5 midpoint of diagonals",
            [
                0.5 * (s3 + 0.0),
                0.5 * (s3 - 1.0 / 2f64.sqrt()),
                0.5 * (s3 + 1.0 / 2f64.sqrt()),
            ],
        ),
        ("K~0.75 t=1/4", [0.75, 0.25, 0.0]),
        (
            "one LSB off +x axis",
            [1.0, 1.0 / 131072.0, -1.0 / 131072.0],
        ),
        (
            "one Q2.14 LSB off +x axis",
            [1.0, 1.0 / 16384.0, -1.0 / 16384.0],
        ),
        // Either side of the piecewise set's segment boundaries (K = 0.625, 0.75, 0.875, 1):
        // K = x² one Q1.15 LSB of K (2⁻¹⁵) below and above.
        (
            "K just below 0.625",
            [(0.625f64 - 1.0 / 32768.0).sqrt(), 0.0, 0.0],
        ),
        (
            "K just above 0.625",
            [(0.625f64 + 1.0 / 32768.0).sqrt(), 0.0, 0.0],
        ),
        (
            "K just below 0.75",
            [0.0, (0.75f64 - 1.0 / 32768.0).sqrt(), 0.0],
        ),
        (
            "K just above 0.75",
            [0.0, (0.75f64 + 1.0 / 32768.0).sqrt(), 0.0],
        ),
        (
            "K just below 0.875",
            [0.0, 0.0, -(0.875f64 - 1.0 / 32768.0).sqrt()],
        ),
        (
            "K just above 0.875",
            [0.0, 0.0, -(0.875f64 + 1.0 / 32768.0).sqrt()],
        ),
        (
            "K just below 1",
            [(1.0f64 - 1.0 / 32768.0).sqrt(), 0.0, 0.0],
        ),
    ]
}

/// Named raw inputs (signed Q2.17 words) outside the domain, checked against the documented
/// saturation behaviour ([`saturating_model`]).
pub fn extreme_cases() -> Vec<(&'static str, [u64; 3])> {
    vec![
        ("zero vector (K=0, f saturates at 2)", [0, 0, 0]),
        (
            "most negative components -2,-2,-2 (K=12)",
            [0x4_0000, 0x4_0000, 0x4_0000],
        ),
        (
            "most positive components (K≈12)",
            [0x3_FFFF, 0x3_FFFF, 0x3_FFFF],
        ),
        ("-2 on x only (K=4)", [0x4_0000, 0, 0]),
        ("max on y only (K≈4)", [0, 0x3_FFFF, 0]),
        ("one LSB (K=2^-34, floored to 0)", [1, 0, 0]),
        ("minus one LSB", [0, 0, 0x7_FFFF]),
        ("one LSB on each (K floored to 0)", [1, 0x7_FFFF, 1]),
        ("eight LSBs (K=2^-28)", [8, 0, 0]),
        ("low bits all ones, x = 1 - 2^-17", [0x1_FFFF, 0, 0]),
        ("K just below 2 - 2^-16 (no K saturation)", [0x2_D413, 0, 0]),
        ("K just above 2 - 2^-16 (K saturates)", [0x2_D414, 0, 0]),
        ("K=0.25 (f = 1.77, below the domain)", [0x1_0000, 0, 0]),
        ("K=0.0625 (f saturates at 2)", [0x8000, 0, 0]),
        ("K=1.5", [0x2_0000, 0x1_6A08, 0]),
        // K saturates but the outputs do not: the only way to see the K saturation alone.
        (
            "K=2.5 (K saturates, outputs in range)",
            [0x2_0000, 0x2_0000, 0x1_6A08],
        ),
        ("mixed extremes", [0x4_0000, 0x3_FFFF, 0x0_0001]),
    ]
}

/// Raw Q2.17 words of an interpolated normal (round to nearest, saturate).
pub fn quantize(v: [f64; 3]) -> [u64; 3] {
    v.map(|c| INTERPOLATED.quantize(c))
}

/// Real values of raw Q2.17 words (the inputs).
pub fn dequantize(raw: [u64; 3]) -> [f64; 3] {
    raw.map(|r| INTERPOLATED.to_f64(r))
}

/// Real values of raw Q2.17 words (the outputs, N').
pub fn dequantize_out(raw: [u64; 3]) -> [f64; 3] {
    raw.map(|r| NORMALIZED.to_f64(r))
}

/// The golden formula with the block's documented saturation rules applied in f64 (K clamped
/// to the Q1.15 range, t1 to Q2.17, f to Q1.18, outputs to Q2.17). Inside the domain none of
/// the clamps acts and this is exactly `golden::units::normalizer::normalize`.
pub fn saturating_model(raw: [u64; 3], c: impl Into<Scale>) -> [f64; 3] {
    let n = dequantize(raw);
    let k = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).min(K_NARROW.max());
    let g = c.into().0[Scale::segment(k)];
    let t1 = (g.c[0] * k + g.c[1]).clamp(HORNER_T1.min(), HORNER_T1.max());
    let f = (t1 * (k - g.base).max(0.0) + g.c[2]).clamp(NORM_SCALE.min(), NORM_SCALE.max());
    n.map(|x| (x * f).clamp(NORMALIZED.min(), NORMALIZED.max()))
}

/// Tolerance of an output component for domain inputs, from [`error_budget`].
pub fn domain_budget(c: &NormalizerCoeffs) -> ErrorBudget {
    error_budget(c, DOMAIN_K.0, DOMAIN_K.1, DOMAIN_X_MAX)
}

/// Tolerance of an output component for any input (K up to the Q1.15 saturation, |x| ≤ 2).
pub fn general_budget(c: &NormalizerCoeffs) -> ErrorBudget {
    error_budget(c, 0.0, K_NARROW.max(), 2.0)
}

fn tolerance(b: &ErrorBudget) -> Tolerance {
    Tolerance {
        max_abs: b.component_max,
        rms: b.component_rms,
    }
}

/// How the normalizer's outputs are compared: `valid_out` exactly, components through Q2.17.
pub fn check_spec(name: &str, seed: u64, b: &ErrorBudget) -> CheckSpec {
    let fixed = Compare::Fixed {
        format: NORMALIZED,
        tol: tolerance(b),
    };
    CheckSpec {
        name: name.into(),
        seed,
        compare: vec![Compare::Exact, fixed, fixed, fixed],
    }
}

/// One clock of normalizer input: `Some(raw vector)` or an idle clock with `filler` data.
#[derive(Clone, Copy, Debug)]
pub enum Slot {
    Vector([u64; 3]),
    Idle([u64; 3]),
}

/// Stimulus rows (valid_in, x, y, z) for `slots`, padded with idle clocks to flush the pipeline.
pub fn stimulus_rows(slots: &[Slot], latency: usize) -> Vec<Vec<u64>> {
    let mut rows: Vec<Vec<u64>> = slots
        .iter()
        .map(|s| match s {
            Slot::Vector(v) => vec![1, v[0], v[1], v[2]],
            Slot::Idle(v) => vec![0, v[0], v[1], v[2]],
        })
        .collect();
    harness::pad_rows(&mut rows, &[0, 0, 0, 0], latency);
    rows
}

/// Per-clock expectations for `rows` (from [`stimulus_rows`]) through a pipeline of `latency`.
pub fn expectations(rows: &[Vec<u64>], latency: usize, c: Scale) -> Vec<Vec<Expected>> {
    let per_input: Vec<Vec<Expected>> = rows
        .iter()
        .map(|r| {
            if r[0] == 1 {
                let e = saturating_model([r[1], r[2], r[3]], c);
                vec![
                    Expected::Word(1),
                    Expected::Real(e[0]),
                    Expected::Real(e[1]),
                    Expected::Real(e[2]),
                ]
            } else {
                vec![
                    Expected::Word(0),
                    Expected::DontCare,
                    Expected::DontCare,
                    Expected::DontCare,
                ]
            }
        })
        .collect();
    let idle = [
        Expected::Word(0),
        Expected::DontCare,
        Expected::DontCare,
        Expected::DontCare,
    ];
    harness::delay_expectations(&per_input, latency, &idle)
}

/// Run `slots` through a [`Normalizer`] built with `coeffs`, checking every clock against the
/// golden model within budget `b`.
#[allow(clippy::result_large_err)] // harness::Failure, returned once per run
pub fn check_normalizer(
    name: &str,
    seed: u64,
    slots: &[Slot],
    coeffs: &NormalizerCoeffs,
    b: &ErrorBudget,
) -> Result<Report, Failure> {
    let rows = stimulus_rows(slots, Normalizer::LATENCY);
    let exp = expectations(&rows, Normalizer::LATENCY, coeffs.requested);
    harness::run_rows(
        || Normalizer::new(coeffs),
        &check_spec(name, seed, b),
        &rows,
        &exp,
    )
}

/// End-to-end error of a run's valid outputs (Euclidean norm of N'_hw − unit vector).
#[derive(Clone, Copy, Debug, Default)]
pub struct EndToEnd {
    /// Vectors measured.
    pub count: usize,
    /// Max ‖N'_hw − N_q/|N_q|‖ (N_q: the quantized vector the hardware saw).
    pub max_vs_quantized: f64,
    /// RMS of the same.
    pub rms_vs_quantized: f64,
    /// Max ‖N'_hw − N/|N|‖ (N: the f64 vector before quantization).
    pub max_vs_float: f64,
}

/// Compare each valid output of `report` (a run of [`stimulus_rows`] of `vectors`, one vector
/// per slot in order, with `latency`) with exact normalization.
pub fn end_to_end(report: &Report, vectors: &[[f64; 3]], latency: usize) -> EndToEnd {
    let mut e = EndToEnd::default();
    let mut sum_sq = 0.0;
    let mut next = 0;
    for (c, out) in report.outputs.iter().enumerate() {
        if out[0] != 1 || c < latency {
            continue;
        }
        let inp = &report.inputs[c - latency];
        let nq = dequantize([inp[1], inp[2], inp[3]]);
        let hw = dequantize_out([out[1], out[2], out[3]]);
        let dist = |a: [f64; 3]| {
            let len = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            ((hw[0] - a[0] / len).powi(2)
                + (hw[1] - a[1] / len).powi(2)
                + (hw[2] - a[2] / len).powi(2))
            .sqrt()
        };
        let dq = dist(nq);
        e.max_vs_quantized = e.max_vs_quantized.max(dq);
        sum_sq += dq * dq;
        if let Some(v) = vectors.get(next) {
            e.max_vs_float = e.max_vs_float.max(dist(*v));
        }
        next += 1;
        e.count += 1;
    }
    e.rms_vs_quantized = (sum_sq / e.count.max(1) as f64).sqrt();
    e
}

/// Max |f(K)·√K − 1| of the formula itself over K ∈ [lo, hi] (the sources' "relative error").
pub fn formula_max_error(c: impl Into<Scale>, lo: f64, hi: f64) -> f64 {
    let c = c.into();
    (0..=100_000)
        .map(|i| lo + (hi - lo) * i as f64 / 100_000.0)
        .map(|k| (c.at(k) * k.sqrt() - 1.0).abs())
        .fold(0.0, f64::max)
}

/// Extra error bound vs the f64 (unquantized) vector: rounding N to Q2.17 moves N/|N| by at
/// most ‖δ‖/|N| ≤ √3·2⁻¹⁸/√K_min.
pub fn input_quantization_bound() -> f64 {
    3f64.sqrt() * INTERPOLATED.lsb() / 2.0 / DOMAIN_K.0.sqrt()
}

/// The normalizer's input word of a signed Q2.17 component, as the twin takes it.
fn signed19(w: u64) -> i64 {
    INTERPOLATED.to_int(w)
}

/// K of a vector of raw Q2.17 words as `NormalizerK` takes it: x² + y² + z² (units 2⁻³⁴)
/// floored to Q4.28, as the full normalizer's squarers form it.
fn k_word(raw: [u64; 3]) -> u64 {
    let v = raw.map(signed19);
    ((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) >> 6) as u64
}

fn vector_out(valid: bool, n: [i64; 3]) -> Vec<u64> {
    let mut o = vec![valid as u64];
    o.extend(n.map(|x| NORMALIZED.from_int(x)));
    o
}

/// Row adapter of [`twin::NormalizerTwin`] (inputs valid_in, x, y, z).
struct NormalizerRows(twin::NormalizerTwin);

impl Twin for NormalizerRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (v, n) = self.0.outputs();
        self.0.clock(r[0] != 0, [r[1], r[2], r[3]].map(signed19));
        vector_out(v, n)
    }
}

/// Row adapter of [`twin::NormalizerKTwin`] (inputs valid_in, x, y, z, k).
struct NormalizerKRows(twin::NormalizerKTwin);

impl Twin for NormalizerKRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (v, n) = self.0.outputs();
        self.0
            .clock(r[0] != 0, [r[1], r[2], r[3]].map(signed19), r[4] as i64);
        vector_out(v, n)
    }
}

/// `n` seeded domain vectors as normalizer rows with golden expectations (plus, for
/// [`NormalizerK`], K as a fifth input: the sum of squares of the quantized vector, floored to
/// Q4.28).
fn vector_stimulus(
    c: &NormalizerCoeffs,
    n: usize,
    seed: u64,
    latency: usize,
    with_k: bool,
) -> Stimulus {
    let mut r = seeded_runner(seed);
    let slots: Vec<Slot> = domain_vectors(&mut r, n)
        .iter()
        .map(|v| Slot::Vector(quantize(*v)))
        .collect();
    let mut rows = stimulus_rows(&slots, latency);
    let expected = expectations(&rows, latency, c.requested);
    if with_k {
        for row in &mut rows {
            let k = k_word([row[1], row[2], row[3]]);
            row.push(k);
        }
    }
    Stimulus {
        rows,
        expected,
        compare: check_spec("", 0, &domain_budget(c)).compare,
    }
}

/// Rows outside the domain for the twin: the named extreme cases, then `n` clocks of random
/// raw words (K up to 12, every saturation path), valid toggling at random.
pub fn raw_rows(seed: u64, n: usize, with_k: bool) -> Vec<Vec<u64>> {
    let mut r = seeded_runner(seed ^ 0x5a5a_5a5a);
    let words = prop::array::uniform4(any::<u32>());
    let mut rows: Vec<Vec<u64>> = extreme_cases()
        .iter()
        .map(|(_, v)| vec![1, v[0], v[1], v[2]])
        .collect();
    for _ in 0..n {
        let w = words.new_tree(&mut r).expect("no rejection").current();
        rows.push(vec![
            (w[3] & 3 != 0) as u64,
            (w[0] & 0x7_FFFF) as u64,
            (w[1] & 0x7_FFFF) as u64,
            (w[2] & 0x7_FFFF) as u64,
        ]);
    }
    if with_k {
        for (i, row) in rows.iter_mut().enumerate() {
            let k = k_word([row[1], row[2], row[3]]);
            // Every fourth clock a random 32-bit K instead of the exact one (K saturation).
            let k = if i % 4 == 3 {
                (k.wrapping_mul(0x9E37_79B9) ^ (k >> 7)) & 0xFFFF_FFFF
            } else {
                k
            };
            row.push(k);
        }
    }
    rows
}

/// The two normalizer tops share their bench: seeded domain vectors (with their exact K as a
/// fifth input for the back end), the raw extreme rows, and their twin.
macro_rules! normalizer_bench {
    ($block:ty, $rows:ident, $twin:ident, $with_k:expr) => {
        impl Bench for $block {
            const ITEMS: &'static str = "vectors";
            const DEFAULT_ITEMS: usize = 1000;
            fn stimulus(c: &NormalizerCoeffs, n: usize, seed: u64) -> Stimulus {
                vector_stimulus(c, n, seed, <$block>::LATENCY, $with_k)
            }
            fn twin(c: &NormalizerCoeffs) -> Box<dyn Twin> {
                Box::new($rows(twin::$twin::new(c.requested)))
            }
            fn edge_rows(_: &NormalizerCoeffs, seed: u64) -> Vec<Vec<u64>> {
                raw_rows(seed, 4000, $with_k)
            }
        }
    };
}

normalizer_bench!(Normalizer, NormalizerRows, NormalizerTwin, false);
normalizer_bench!(NormalizerK, NormalizerKRows, NormalizerKTwin, true);
