//! Bench of the K recurrence (`rtl::units::k_recurrence`): spans of linearly interpolated normals,
//! pixels with random gaps, K compared exactly with K computed directly from the same
//! quantized vectors (and with `golden::units::normalizer::k_recurrence`), and the span normalizer
//! compared with the golden model and bit-for-bit with the squaring normalizer.

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use rtl::core::fixed::{INTERPOLATED, K_FULL, NORMAL, NORMALIZED};
use rtl::units::k_recurrence::{span_setup, KRecurrence, SpanNormalizer};
use rtl::units::normalizer::Normalizer;

use crate::harness::{self, Expected};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::normalizer::{check_spec, seeded_runner};
use crate::units::normalizer::{domain_vector, saturating_model};
use golden::units::normalizer::twin;
use rtl::core::registry::NoParams;
use rtl::units::normalizer::{error_budget, ErrorBudget, NormalizerCoeffs};

/// A raster-line span: N_i = n0 + i·delta for i < len, integers in Q2.14 LSB units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    pub n0: [i64; 3],
    pub delta: [i64; 3],
    pub len: usize,
}

impl Span {
    /// The span from `a` to (about) `b` in `m` steps: n0 = a quantized, Δ = (b − a)/m rounded
    /// to LSB units (as per-triangle set-up software would), `m + 1` pixels.
    pub fn between(a: [f64; 3], b: [f64; 3], m: usize) -> Self {
        let n0 = a.map(|c| NORMAL.quantize_int(c));
        let nb = b.map(|c| NORMAL.quantize_int(c));
        let delta = [0, 1, 2].map(|i| ((nb[i] - n0[i]) as f64 / m as f64).round() as i64);
        Span {
            n0,
            delta,
            len: m + 1,
        }
    }
    /// Pixel i's vector (raw Q2.14 integers).
    pub fn vector(&self, i: usize) -> [i64; 3] {
        [0, 1, 2].map(|k| self.n0[k] + i as i64 * self.delta[k])
    }
    /// K_i computed directly: the exact sum of squares of pixel i's quantized vector (Q4.28).
    pub fn k_direct(&self, i: usize) -> u64 {
        let v = self.vector(i);
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) as u64
    }
}

/// A span between two unit normals ≤ 90° apart (endpoints from the normalizer's domain
/// strategy with t = 0 and 1), 1..=max_len steps.
pub fn span_strategy(max_len: usize) -> impl Strategy<Value = Span> {
    (domain_vector(), domain_vector(), 1..=max_len).prop_map(|(a, b, m)| {
        let unit = |v: [f64; 3]| {
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            v.map(|c| c / l)
        };
        let (a, mut b) = (unit(a), unit(b));
        if a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0 {
            b = b.map(|c| -c);
        }
        Span::between(a, b, m)
    })
}

/// The normalizer's error budget for the vectors of `spans` (K range and largest component
/// of the stimulus: rounding Δ to an LSB lets a span drift slightly off the unit sphere).
pub fn span_budget(spans: &[Span], c: &NormalizerCoeffs) -> ErrorBudget {
    let (mut lo, mut hi, mut xmax) = (f64::MAX, 0.0f64, 0.0f64);
    for s in spans {
        for i in 0..s.len {
            let k = s.k_direct(i) as f64 * K_FULL.lsb();
            lo = lo.min(k);
            hi = hi.max(k);
            xmax = s
                .vector(i)
                .iter()
                .fold(xmax, |m, v| m.max(v.unsigned_abs() as f64 * NORMAL.lsb()));
        }
    }
    error_budget(c, lo, hi, xmax)
}

/// Named spans: the extremes of the recurrence.
pub fn edge_spans() -> Vec<(&'static str, Span)> {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    vec![
        (
            "single pixel",
            Span::between([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1),
        ),
        (
            "constant vector (Δ = 0)",
            Span {
                n0: [0, 16384, 0],
                delta: [0, 0, 0],
                len: 17,
            },
        ),
        (
            "90° x→y, 64 steps (K dips to 0.5)",
            Span::between([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 64),
        ),
        (
            "90° -x→-z, 63 steps (negative components)",
            Span::between([-1.0, 0.0, 0.0], [0.0, 0.0, -1.0], 63),
        ),
        (
            "90° across the diagonal, 3310 steps of Δy = 7 LSB",
            Span::between([s, -s, 0.0], [s, s, 0.0], 3310),
        ),
        (
            "90° x→y, 4096 pixels (12-bit line)",
            Span {
                n0: [16384, 0, 0],
                delta: [-4, 4, 0],
                len: 4096,
            },
        ),
        (
            "two pixels 90° apart",
            Span::between([0.0, 0.0, 1.0], [0.0, -1.0, 0.0], 1),
        ),
        (
            "tiny Δ (1 LSB per pixel), 200 pixels",
            Span {
                n0: [16384, 0, 0],
                delta: [-1, 1, 0],
                len: 200,
            },
        ),
    ]
}

/// One clock of a span schedule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// Pixel `i` of span `s` (i = 0 loads the span).
    Pixel {
        s: usize,
        i: usize,
    },
    Idle,
}

/// Pixels of `spans` in order, with an idle clock before a pixel when `gaps` says so
/// (`gaps[p]` idle clocks before the p-th pixel overall; missing entries mean none).
pub fn schedule(spans: &[Span], gaps: &[u8]) -> Vec<Clock> {
    let mut out = Vec::new();
    let mut p = 0;
    for (s, span) in spans.iter().enumerate() {
        for i in 0..span.len {
            for _ in 0..gaps.get(p).copied().unwrap_or(0) {
                out.push(Clock::Idle);
            }
            out.push(Clock::Pixel { s, i });
            p += 1;
        }
    }
    out
}

/// Random gap counts: 0 with probability 7/8, else 1..=3 idle clocks.
pub fn random_gaps(runner: &mut TestRunner, n: usize) -> Vec<u8> {
    let st = (0u8..8, 1u8..=3).prop_map(|(a, g)| if a == 0 { g } else { 0 });
    (0..n)
        .map(|_| st.new_tree(runner).expect("no rejection").current())
        .collect()
}

/// Garbage driven on the data inputs of idle clocks (and `load` = 1: it must be ignored
/// without `valid_in`).
const JUNK32: u64 = 0xDEAD_BEEF;
const JUNK16: u64 = 0xA5C3;

/// Stimulus and exact expectations for [`KRecurrence`]: on each pixel, K must equal
/// [`Span::k_direct`]; while `valid_out` is low, `k` holds its last value.
pub fn krec_rows(spans: &[Span], sched: &[Clock]) -> (Vec<Vec<u64>>, Vec<Vec<Expected>>) {
    let mut rows = Vec::new();
    let mut per_input = Vec::new();
    let mut last_k = 0;
    for c in sched {
        match *c {
            Clock::Pixel { s, i } => {
                let su = span_setup(spans[s].n0, spans[s].delta);
                if i == 0 {
                    rows.push(vec![1, 1, su.k0, su.alpha, su.beta]);
                } else {
                    // Set-up ports carry junk between loads: they must be ignored.
                    rows.push(vec![1, 0, JUNK32, JUNK32, JUNK32]);
                }
                last_k = spans[s].k_direct(i);
                per_input.push(vec![Expected::Word(1), Expected::Word(last_k)]);
            }
            Clock::Idle => {
                rows.push(vec![0, 1, JUNK32, JUNK32, JUNK32]);
                per_input.push(vec![Expected::Word(0), Expected::Word(last_k)]);
            }
        }
    }
    let lat = KRecurrence::LATENCY;
    harness::pad_rows(&mut rows, &[0, 0, 0, 0, 0], lat);
    per_input.extend(std::iter::repeat_n(
        vec![Expected::Word(0), Expected::Word(last_k)],
        lat,
    ));
    let idle = [Expected::Word(0), Expected::Word(0)];
    (
        rows.clone(),
        harness::delay_expectations(&per_input, lat, &idle),
    )
}

/// Stimulus for [`SpanNormalizer`] and per-clock expectations from the golden model
/// (`saturating_model` on each pixel's quantized vector).
pub fn span_rows(
    spans: &[Span],
    sched: &[Clock],
    coeffs: golden::units::normalizer::Scale,
) -> (Vec<Vec<u64>>, Vec<Vec<Expected>>) {
    let raw16 = |v: i64| NORMAL.from_int(v);
    let mut rows = Vec::new();
    let mut per_input = Vec::new();
    for c in sched {
        match *c {
            Clock::Pixel { s, i } => {
                let sp = &spans[s];
                if i == 0 {
                    let su = span_setup(sp.n0, sp.delta);
                    let mut r = vec![1, 1];
                    r.extend(sp.n0.map(raw16));
                    r.extend(sp.delta.map(raw16));
                    r.extend([su.k0, su.alpha, su.beta]);
                    rows.push(r);
                } else {
                    rows.push(vec![
                        1, 0, JUNK16, JUNK16, JUNK16, JUNK16, JUNK16, JUNK16, JUNK32, JUNK32,
                        JUNK32,
                    ]);
                }
                // The normalizer's model takes Q2.17 words: the Q2.14 vector times 8.
                let e =
                    saturating_model(sp.vector(i).map(|x| INTERPOLATED.from_int(x * 8)), coeffs);
                per_input.push(vec![
                    Expected::Word(1),
                    Expected::Real(e[0]),
                    Expected::Real(e[1]),
                    Expected::Real(e[2]),
                ]);
            }
            Clock::Idle => {
                rows.push(vec![
                    0, 1, JUNK16, JUNK16, JUNK16, JUNK16, JUNK16, JUNK16, JUNK32, JUNK32, JUNK32,
                ]);
                per_input.push(vec![
                    Expected::Word(0),
                    Expected::DontCare,
                    Expected::DontCare,
                    Expected::DontCare,
                ]);
            }
        }
    }
    let lat = SpanNormalizer::LATENCY;
    harness::pad_rows(&mut rows, &[0; 11], lat);
    let idle = vec![
        Expected::Word(0),
        Expected::DontCare,
        Expected::DontCare,
        Expected::DontCare,
    ];
    per_input.extend(std::iter::repeat_n(idle.clone(), lat));
    (rows, harness::delay_expectations(&per_input, lat, &idle))
}

/// The same pixel sequence as normalizer rows (valid_in, x, y, z: the Q2.14 vectors as the
/// normalizer's signed Q2.17 input, three zero LSBs), for the bit-exact comparison of
/// SpanNormalizer with Normalizer.
pub fn normalizer_rows(spans: &[Span], sched: &[Clock]) -> Vec<Vec<u64>> {
    let mut rows: Vec<Vec<u64>> = sched
        .iter()
        .map(|c| match *c {
            Clock::Pixel { s, i } => {
                let v = spans[s].vector(i).map(|x| INTERPOLATED.from_int(x * 8));
                vec![1, v[0], v[1], v[2]]
            }
            Clock::Idle => vec![0, JUNK16, JUNK16, JUNK16],
        })
        .collect();
    harness::pad_rows(&mut rows, &[0, 0, 0, 0], Normalizer::LATENCY);
    rows
}

/// K_i of `span` from the golden f64 recurrence, in Q4.28 units (exact in f64: every term is
/// a multiple of 2⁻²⁸ below 2²⁵).
pub fn golden_k(span: &Span) -> Vec<f64> {
    let f = |v: [i64; 3]| glam::DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64) * NORMAL.lsb();
    golden::units::normalizer::k_recurrence(f(span.n0), f(span.delta), span.len)
        .into_iter()
        .map(|k| k / K_FULL.lsb())
        .collect()
}

/// Random spans (≤ 64 steps, `n_spans` of them) after the named edge spans, and a schedule
/// with random gaps, drawn with the runner named `name` (seed printed).
pub fn spans_and_schedule(name: &str, n_spans: usize) -> (Vec<Span>, Vec<Clock>) {
    let mut r = golden::testing::runner(name, 1);
    let st = span_strategy(64);
    let mut spans: Vec<Span> = edge_spans().into_iter().map(|(_, s)| s).collect();
    spans.extend((0..n_spans).map(|_| st.new_tree(&mut r).expect("no rejection").current()));
    let pixels: usize = spans.iter().map(|s| s.len).sum();
    let gaps = random_gaps(&mut r, pixels);
    let sched = schedule(&spans, &gaps);
    (spans, sched)
}

/// Seeded random spans totalling `pixels` pixels, and a schedule with random gaps.
pub fn spans_for(runner: &mut TestRunner, pixels: usize) -> (Vec<Span>, Vec<Clock>) {
    let st = span_strategy(64);
    let mut spans = Vec::new();
    let mut total = 0;
    while total < pixels {
        let mut s = st.new_tree(runner).expect("no rejection").current();
        s.len = s.len.min(pixels - total);
        total += s.len;
        spans.push(s);
    }
    let gaps = random_gaps(runner, total);
    let sched = schedule(&spans, &gaps);
    (spans, sched)
}

/// Row adapter of [`twin::KRecurrenceTwin`] (inputs valid_in, load, k0, alpha, beta).
struct KRecurrenceRows(twin::KRecurrenceTwin);

impl Twin for KRecurrenceRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (v, k) = self.0.outputs();
        let w = |i: usize| r[i] as u32;
        self.0.clock(r[0] != 0, r[1] != 0, w(2), w(3), w(4));
        vec![v as u64, k as u64]
    }
}

/// Row adapter of [`twin::SpanNormalizerTwin`] (inputs valid_in, load, x0, y0, z0, dx, dy,
/// dz, k0, alpha, beta).
struct SpanNormalizerRows(twin::SpanNormalizerTwin);

impl Twin for SpanNormalizerRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (v, n) = self.0.outputs();
        let s = |i: usize| NORMAL.to_int(r[i]);
        let w = |i: usize| r[i] as u32;
        self.0.clock(
            r[0] != 0,
            r[1] != 0,
            [s(2), s(3), s(4)],
            [s(5), s(6), s(7)],
            w(8),
            w(9),
            w(10),
        );
        let mut o = vec![v as u64];
        o.extend(n.map(|x| NORMALIZED.from_int(x)));
        o
    }
}

impl Bench for KRecurrence {
    const ITEMS: &'static str = "pixels";
    const DEFAULT_ITEMS: usize = 1000;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let (spans, sched) = spans_for(&mut seeded_runner(seed), n);
        let (rows, expected) = krec_rows(&spans, &sched);
        Stimulus {
            rows,
            expected,
            compare: vec![harness::Compare::Exact; 2],
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(KRecurrenceRows(twin::KRecurrenceTwin::new()))
    }
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        // The named edge spans, then loads with random 32-bit K_0, α, β (wrap-around sums).
        let spans: Vec<Span> = edge_spans().into_iter().map(|(_, s)| s).collect();
        let mut r = seeded_runner(seed ^ 0x6b72);
        let gaps = random_gaps(&mut r, spans.iter().map(|s| s.len).sum());
        let (mut rows, _) = krec_rows(&spans, &schedule(&spans, &gaps));
        let words = prop::array::uniform4(any::<u32>());
        for _ in 0..2000 {
            let w = words.new_tree(&mut r).expect("no rejection").current();
            rows.push(vec![
                (w[3] & 3 != 0) as u64,
                (w[3] & 12 == 0) as u64,
                w[0] as u64,
                w[1] as u64,
                w[2] as u64,
            ]);
        }
        rows
    }
}

impl Bench for SpanNormalizer {
    const ITEMS: &'static str = "pixels";
    const DEFAULT_ITEMS: usize = 1000;
    fn stimulus(c: &NormalizerCoeffs, n: usize, seed: u64) -> Stimulus {
        let (spans, sched) = spans_for(&mut seeded_runner(seed), n);
        let (rows, expected) = span_rows(&spans, &sched, c.requested);
        Stimulus {
            rows,
            expected,
            compare: check_spec("", 0, &span_budget(&spans, c)).compare,
        }
    }
    fn twin(c: &NormalizerCoeffs) -> Box<dyn Twin> {
        Box::new(SpanNormalizerRows(twin::SpanNormalizerTwin::new(
            c.requested,
        )))
    }
    fn edge_rows(c: &NormalizerCoeffs, seed: u64) -> Vec<Vec<u64>> {
        let spans: Vec<Span> = edge_spans().into_iter().map(|(_, s)| s).collect();
        let gaps = random_gaps(
            &mut seeded_runner(seed ^ 0x736e),
            spans.iter().map(|s| s.len).sum(),
        );
        span_rows(&spans, &schedule(&spans, &gaps), c.requested).0
    }
}
