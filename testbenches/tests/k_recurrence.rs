//! The K recurrence (`rtl::units::k_recurrence`): exact K along spans, and the span normalizer.

use golden::testing::seed_for;
use rtl::units::k_recurrence::{KRecurrence, SpanNormalizer};
use rtl::units::normalizer::{Normalizer, NormalizerCoeffs};
use testbenches::harness::{self, simulate_rows, CheckSpec, Compare};
use testbenches::units::k_recurrence::*;
use testbenches::units::normalizer::check_spec;

#[test]
fn span_vectors_stay_in_the_formula_domain() {
    // The stimulus is meaningful: every pixel of every random span has K in the domain (with
    // the rounding of Δ), and the edge spans reach K = 0.5.
    let (spans, _) = spans_and_schedule("k_recurrence_domain", 2000);
    let (mut lo, mut hi) = (f64::MAX, 0.0f64);
    for s in &spans {
        for i in 0..s.len {
            let k = s.k_direct(i) as f64 * rtl::core::fixed::K_FULL.lsb();
            lo = lo.min(k);
            hi = hi.max(k);
        }
    }
    println!("K over all span pixels: [{lo:.5}, {hi:.5}]");
    // Δ rounded to an LSB drifts ≤ 32 LSB over 64 steps: K stays within 1 % of the domain.
    assert!(lo > 0.49 && lo < 0.5001 && hi <= 1.01, "[{lo}, {hi}]");
}

#[test]
fn golden_recurrence_equals_direct_k() {
    // In Q4.28 integers the f64 recurrence of the golden model is exact, so it must equal the
    // direct sum of squares on every pixel; the hardware is then held to the same integers.
    let (spans, _) = spans_and_schedule("k_recurrence_golden", 2000);
    for s in &spans {
        let g = golden_k(s);
        for (i, k) in g.iter().enumerate() {
            assert_eq!(*k, s.k_direct(i) as f64, "span {s:?} pixel {i}");
        }
    }
}

#[test]
fn k_recurrence_is_exact() {
    let name = "k_recurrence_exact";
    let (spans, sched) = spans_and_schedule(name, 3000);
    let (rows, exp) = krec_rows(&spans, &sched);
    let spec = CheckSpec {
        name: name.into(),
        seed: seed_for(name),
        compare: vec![Compare::Exact, Compare::Exact],
    };
    let report =
        harness::run_rows(KRecurrence::new, &spec, &rows, &exp).unwrap_or_else(|f| panic!("{f}"));
    println!("{report}");
    let pixels: usize = spans.iter().map(|s| s.len).sum();
    println!(
        "{} spans, {pixels} pixels, {} clocks",
        spans.len(),
        sched.len()
    );
    assert!(pixels > 90_000, "enough pixels ({pixels})");
}

#[test]
fn span_normalizer_matches_golden_and_the_squaring_normalizer() {
    let name = "span_normalizer";
    let (spans, sched) = spans_and_schedule(name, 1500);
    let c = NormalizerCoeffs::published();
    let (rows, exp) = span_rows(&spans, &sched, c.requested);
    let b = span_budget(&spans, &c);
    println!("budget for this stimulus: {b:?}");
    let spec = check_spec(name, seed_for(name), &b);
    let report = harness::run_rows(|| SpanNormalizer::new(&c), &spec, &rows, &exp)
        .unwrap_or_else(|f| panic!("{f}"));
    println!("{report}");
    // Bit-for-bit: the recurrence's K equals the squarers' K, so the outputs are identical,
    // the squaring normalizer's later by the difference of the latencies (its squarers take
    // 3 clocks, the recurrence 2).
    let squaring = simulate_rows(Normalizer::new(&c), &normalizer_rows(&spans, &sched)).unwrap();
    let lag = Normalizer::LATENCY - SpanNormalizer::LATENCY;
    assert_eq!(squaring.len(), report.outputs.len() + lag);
    for (cyc, (a, b)) in report.outputs.iter().zip(&squaring[lag..]).enumerate() {
        if b[0] == 1 || a[0] == 1 {
            assert_eq!(
                a, b,
                "cycle {cyc}: span normalizer {a:x?} vs normalizer {b:x?}"
            );
        }
    }
}
