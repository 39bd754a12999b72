//! Cycle-by-cycle tests of the normalizer (rtl::normalizer) against golden::normalizer.

use golden::testing::{runner, seed_for};
use rtl::normalizer::{Normalizer, NormalizerCoeffs};
use testbenches::normalizer::*;

#[test]
fn normalizer_domain_back_to_back() {
    let name = "normalizer_domain";
    let mut r = runner(name, 1);
    let seed = seed_for(name);
    let vectors = domain_vectors(&mut r, 100_000);
    let coeffs = NormalizerCoeffs::published();
    let b = domain_budget(&coeffs);
    let slots: Vec<Slot> = vectors.iter().map(|v| Slot::Vector(quantize(*v))).collect();
    let t = std::time::Instant::now();
    let report =
        check_normalizer(name, seed, &slots, &coeffs, &b).unwrap_or_else(|f| panic!("{f}"));
    println!("{report}took {:?}", t.elapsed());
    println!("budget {b:?}");
    let e = end_to_end(&report, &vectors, Normalizer::LATENCY);
    println!("{e:?}");
}
