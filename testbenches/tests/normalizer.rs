//! Cycle-by-cycle tests of the normalizer (`rtl::units::normalizer`) against `golden::units::normalizer`.

use golden::testing::{runner, seed_for};
use golden::units::normalizer::{FIT, K_DOMAIN, PIECEWISE, PUBLISHED};
use proptest::strategy::{Strategy, ValueTree};
use rtl::core::fixed::{INTERPOLATED, K_FULL};
use rtl::units::normalizer::{CoeffError, ErrorBudget, Normalizer, NormalizerCoeffs, NormalizerK};
use testbenches::harness::{self, Expected};
use testbenches::units::normalizer::*;

/// Runs the 100k domain vectors through the normalizer; returns (measured end-to-end max vs
/// the quantized vector, vs the f64 vector, datapath bound).
fn domain_run(coeffs: &NormalizerCoeffs, name: &str) -> (f64, f64, f64) {
    // The same vectors as the differential Verilog test (tests/verilog_export.rs).
    let (seed, vectors) = domain_run_vectors();
    let b = domain_budget(coeffs);
    let slots: Vec<Slot> = vectors.iter().map(|v| Slot::Vector(quantize(*v))).collect();
    let report = check_normalizer(name, seed, &slots, coeffs, &b).unwrap_or_else(|f| panic!("{f}"));
    println!("{report}");
    println!(
        "[{name}] tolerance from the formats: component max {:.3e}, rms {:.3e}",
        b.component_max, b.component_rms
    );

    // One vector per clock after the latency: valid_out is high on exactly the clocks
    // LATENCY .. LATENCY + N (the check above compared every clock's valid_out exactly).
    let valid: Vec<usize> = report
        .outputs
        .iter()
        .enumerate()
        .filter(|(_, o)| o[0] == 1)
        .map(|(c, _)| c)
        .collect();
    assert_eq!(valid.len(), DOMAIN_VECTORS);
    assert_eq!(valid[0], Normalizer::LATENCY);
    assert_eq!(
        *valid.last().unwrap(),
        Normalizer::LATENCY + DOMAIN_VECTORS - 1,
        "a bubble in the output stream"
    );

    // End-to-end error against exact normalization.
    let e = end_to_end(&report, &vectors, Normalizer::LATENCY);
    let formula = formula_max_error(coeffs.requested, K_DOMAIN.0, K_DOMAIN.1);
    println!(
        "[{name}] end-to-end ‖N'_hw − N_q/|N_q|‖: max {:.4} % (rms {:.4} %), vs the f64 vector: max {:.4} %",
        100.0 * e.max_vs_quantized,
        100.0 * e.rms_vs_quantized,
        100.0 * e.max_vs_float
    );
    println!(
        "[{name}] formula alone: max {:.4} %; datapath bound {:.4} % [+ {:.4} % for rounding the input to Q2.17]",
        100.0 * formula,
        100.0 * b.vector_max,
        100.0 * input_quantization_bound()
    );
    assert_eq!(e.count, DOMAIN_VECTORS);
    // Whatever the set, the hardware adds at most the datapath bound to the formula's error.
    let (bq, bf) = (
        formula + b.vector_max,
        formula + b.vector_max + input_quantization_bound(),
    );
    assert!(
        e.max_vs_quantized <= bq,
        "end-to-end {:.5} > formula + datapath {:.5}",
        e.max_vs_quantized,
        bq
    );
    assert!(
        e.max_vs_float <= bf,
        "end-to-end (f64 input) {:.5} > {:.5}",
        e.max_vs_float,
        bf
    );
    (e.max_vs_quantized, e.max_vs_float, b.vector_max)
}

#[test]
fn normalizer_domain_100k_published() {
    let c = NormalizerCoeffs::published();
    let (max_q, max_f, datapath) = domain_run(&c, "normalizer_domain_published");
    // The bar: ≤ 0.36 % (the sources' claim) + the documented quantization bound.
    assert!(max_q <= 0.0036 + datapath, "{max_q} > 0.36 % + {datapath}");
    assert!(
        max_f <= 0.0036 + datapath + input_quantization_bound(),
        "{max_f}"
    );
}

#[test]
fn normalizer_domain_100k_fit() {
    let c = NormalizerCoeffs::new(FIT).expect("FIT fits the formats");
    // FIT's coefficients are multiples of 2^-14: the hardware holds them exactly.
    assert_eq!(c.quantized(), FIT.into());
    // FIT trades the worst case at K = 0.499 for exactness near K = 1 (see golden), so its
    // bar is its own formula error (printed) plus the same datapath bound.
    domain_run(&c, "normalizer_domain_fit");
}

#[test]
fn normalizer_domain_100k_piecewise() {
    let c = NormalizerCoeffs::new(PIECEWISE).expect("PIECEWISE fits the formats");
    // Its words are multiples of 2^-28 (c2 of 2^-15) and its bases of 1/8: held exactly.
    assert_eq!(c.quantized(), PIECEWISE);
    let (max_q, _, datapath) = domain_run(&c, "normalizer_domain_piecewise");
    // Its formula is within 1.13e-4 of 1/√K (golden::accuracy); 0.82 % for FIT.
    assert!(
        max_q <= 1.13e-4 + datapath,
        "{max_q} > 1.13e-4 + {datapath}"
    );
}

/// One named raw vector through the normalizer within budget `b`; prints input and output.
fn check_named(kind: &str, label: &str, raw: [u64; 3], b: &ErrorBudget) {
    check_named_with(&NormalizerCoeffs::published(), kind, label, raw, b);
}

/// [`check_named`] with coefficient set `c`.
fn check_named_with(c: &NormalizerCoeffs, kind: &str, label: &str, raw: [u64; 3], b: &ErrorBudget) {
    let name = format!("normalizer_{kind} {label}");
    let report =
        check_normalizer(&name, 0, &[Slot::Vector(raw)], c, b).unwrap_or_else(|f| panic!("{f}"));
    let out = &report.outputs[Normalizer::LATENCY];
    let (i, o) = (dequantize(raw), dequantize_out([out[1], out[2], out[3]]));
    println!("{label:<44} in {i:?} -> out {o:?}");
}

#[test]
fn normalizer_named_domain_cases() {
    let b = domain_budget(&NormalizerCoeffs::published());
    for (label, v) in edge_cases() {
        check_named("edge", label, quantize(v), &b);
    }
    // The piecewise set at the same cases, its boundaries among them.
    let pw = NormalizerCoeffs::new(PIECEWISE).unwrap();
    let b = domain_budget(&pw);
    for (label, v) in edge_cases() {
        check_named_with(&pw, "edge-pw", label, quantize(v), &b);
    }
    // The K = 0.5 and K = 1 cases really have those K after quantization.
    let k = |v: [f64; 3]| {
        let q = quantize(v).map(|r| INTERPOLATED.to_int(r));
        (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) as f64 * INTERPOLATED.lsb().powi(2)
    };
    assert_eq!(k([0.5, 0.5, 0.0]), 0.5);
    assert_eq!(k([-1.0, 0.0, 0.0]), 1.0);
}

#[test]
fn normalizer_extreme_inputs_saturate_as_documented() {
    let c = NormalizerCoeffs::published();
    let b = general_budget(&c);
    for (label, raw) in extreme_cases() {
        check_named("extreme", label, raw, &b);
    }
    // Spot checks of the rules themselves (not of the hardware): -2 on x gives K = 4 → K
    // saturates, f(2 − 2⁻¹⁵) ≈ 1.42 → x·f = −2.85 saturates to −2.
    let e = saturating_model([0x4_0000, 0, 0], PUBLISHED);
    assert_eq!(e[0], -2.0);
    let zero = saturating_model([0, 0, 0], PUBLISHED);
    assert_eq!(zero, [0.0, 0.0, 0.0]);
}

#[test]
fn normalizer_valid_gaps_and_junk() {
    // valid_in low on about a quarter of the clocks, with random data on those clocks: the
    // outputs must follow valid_in exactly and ignore the junk.
    let name = "normalizer_gaps";
    let mut r = runner(name, 1);
    let c = NormalizerCoeffs::published();
    let b = domain_budget(&c);
    let vectors = domain_vectors(&mut r, 20_000);
    let junk = (0u64..0x8_0000, 0u64..0x8_0000, 0u64..0x8_0000, 0u8..4);
    let mut slots = Vec::new();
    for v in &vectors {
        let (a, b2, c2, gap) = junk.new_tree(&mut r).unwrap().current();
        if gap == 0 {
            slots.push(Slot::Idle([a, b2, c2]));
        }
        slots.push(Slot::Vector(quantize(*v)));
    }
    let report =
        check_normalizer(name, seed_for(name), &slots, &c, &b).unwrap_or_else(|f| panic!("{f}"));
    println!("{report}");
    assert_eq!(report.port("nx").unwrap().checked, vectors.len() as u64);
}

#[test]
fn normalizer_k_takes_exact_k() {
    // The back end alone (its registry bench): 10 000 domain vectors, each with K = x² + y² + z²
    // of the quantized (Q2.17) vector, floored to Q4.28, as the fifth input, checked every clock
    // against the golden model.
    use rtl::core::registry::RtlBlock;
    use testbenches::registry::Bench;
    let name = "normalizer_k";
    let seed = seed_for(name);
    let c = NormalizerCoeffs::published();
    let stim = NormalizerK::stimulus(&c, 10_000, seed);
    for r in stim.rows.iter().filter(|r| r[0] == 1) {
        let i = [r[1], r[2], r[3]].map(|w| INTERPOLATED.to_int(w));
        let k = (i[0] * i[0] + i[1] * i[1] + i[2] * i[2]) as f64 * INTERPOLATED.lsb().powi(2);
        assert_eq!(r[4], (k / K_FULL.lsb()).floor() as u64, "K column");
    }
    let spec = harness::CheckSpec {
        name: name.into(),
        seed,
        compare: stim.compare.clone(),
    };
    let report = harness::run_rows(|| NormalizerK::build(&c), &spec, &stim.rows, &stim.expected)
        .unwrap_or_else(|f| panic!("{f}"));
    println!("{report}");
    assert_eq!(report.port("nx").unwrap().checked, 10_000);
}

#[test]
fn harness_catches_a_wrong_model_and_writes_a_vcd() {
    // The hardware uses the published c0; the "golden" here uses c0 + 0.001, which moves every
    // output by ~0.001 ≫ the 1.1e-4 tolerance: the harness must fail at the first valid output
    // and leave a VCD.
    let c = NormalizerCoeffs::published();
    let b = domain_budget(&c);
    let name = "harness_self_test_wrong_model";
    let slots: Vec<Slot> = edge_cases()
        .iter()
        .map(|(_, v)| Slot::Vector(quantize(*v)))
        .collect();
    let rows = stimulus_rows(&slots, Normalizer::LATENCY);
    let wrong = [PUBLISHED[0], PUBLISHED[1], PUBLISHED[2] + 0.001];
    let exp = expectations(&rows, Normalizer::LATENCY, wrong.into());
    let vcd = harness::vcd_path(name);
    let _ = std::fs::remove_file(&vcd);
    let f = harness::run_rows(
        || Normalizer::new(&c),
        &check_spec(name, 7, &b),
        &rows,
        &exp,
    )
    .expect_err("a wrong model must be caught");
    println!("{f}");
    assert_eq!(f.cycle, Normalizer::LATENCY as u64);
    assert_eq!(f.signal, "nx");
    assert_eq!(f.seed, 7);
    assert_eq!(f.vcd.as_deref(), Some(vcd.as_path()));
    let text = std::fs::read_to_string(&vcd).expect("VCD written");
    assert!(
        text.contains("$var") && text.contains("nx"),
        "VCD has the ports"
    );
    assert!(
        f.to_string()
            .contains(&format!("cycle {}", Normalizer::LATENCY))
            && f.to_string().contains(&vcd.display().to_string())
    );
}

#[test]
fn coefficient_sets_are_validated() {
    assert!(NormalizerCoeffs::new(PUBLISHED).is_ok());
    assert!(NormalizerCoeffs::new(FIT).is_ok());
    assert!(matches!(
        NormalizerCoeffs::new([2.5, -2.0, 2.0]),
        Err(CoeffError::OutOfRange { name: "c2", .. })
    ));
    assert!(matches!(
        NormalizerCoeffs::new([0.8, -9.0, 2.0]),
        Err(CoeffError::OutOfRange { name: "c1", .. })
    ));
    // f(K) = 3 everywhere does not fit the Q1.15 scale on the domain.
    assert!(matches!(
        NormalizerCoeffs::new([0.0, 0.0, 3.0]),
        Err(CoeffError::SaturatesInDomain { .. })
    ));
    // The message is one line.
    let e = NormalizerCoeffs::new([2.5, -2.0, 2.0])
        .unwrap_err()
        .to_string();
    assert!(!e.contains('\n'), "{e}");
}

#[test]
fn error_budget_is_small_against_the_formula() {
    // The datapath's own error must be well below the formula's 0.35 % so the end-to-end
    // figure is the formula's.
    for c in [PUBLISHED, FIT] {
        let b = domain_budget(&NormalizerCoeffs::new(c).unwrap());
        println!("{c:?}: {b:?}");
        assert!(b.vector_max < 2e-4, "{b:?}");
        assert!(b.component_rms < b.component_max);
    }
}

#[test]
fn domain_strategy_stays_in_the_domain() {
    let mut r = runner("domain_strategy", 1);
    let s = domain_vector();
    let (mut lo, mut hi) = (f64::MAX, 0.0f64);
    for _ in 0..20_000 {
        let v = s.new_tree(&mut r).unwrap().current();
        let k = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        lo = lo.min(k);
        hi = hi.max(k);
    }
    println!("K over 20000 draws: [{lo:.5}, {hi:.5}]");
    assert!(lo >= 0.5 - 1e-12 && hi <= 1.0 + 1e-12);
    assert!(
        lo < 0.52 && hi > 0.999,
        "the strategy reaches both ends of the domain"
    );
}

/// A quantization bug in the coefficients the hardware is built with — one LSB on c2, c1 or
/// c0, either set — is caught against the twin, which quantizes the requested coefficients
/// itself: the coefficient words must equal the twin's, and a run with c2 one LSB off fails
/// the every-clock comparison. (One LSB of c1 or c0 is 2⁻²⁹ or 2⁻²⁸: it moves an output only
/// when a rounding lands within that of a half-LSB boundary, about once per 2¹⁴ vectors, so
/// only the word comparison catches it reliably; the f64 bound never could.)
#[test]
fn twin_catches_a_one_lsb_coefficient_error() {
    use golden::units::normalizer::twin::NormalizerKTwin;
    use rtl::core::registry::RtlBlock;
    use testbenches::registry::Bench;
    let words = |c: &NormalizerCoeffs| {
        c.words
            .map(|w| (w.c2_mag as i64, w.c2_neg, w.c1, w.c0, w.base as i64))
    };
    let seed = seed_for("twin_one_lsb_coefficient");
    println!("[twin_one_lsb_coefficient] seed {seed}");
    let rows = Normalizer::stimulus(&NormalizerCoeffs::published(), 3000, seed).rows;
    for requested in [PUBLISHED.into(), FIT.into(), PIECEWISE] {
        let good = NormalizerCoeffs::new(requested).unwrap();
        let twin_words = NormalizerKTwin::new(requested)
            .segment_words()
            .map(|w| (w.c2_mag, w.c2_neg, w.c1, w.c0, w.base));
        assert_eq!(words(&good), twin_words, "{requested:?}: coefficient words");
        // Every segment's word one LSB off.
        let off = |f: fn(&mut rtl::units::normalizer::SegmentWords)| {
            let mut c = good.clone();
            c.words.iter_mut().for_each(f);
            c
        };
        let bad = [
            ("c2 + 1 LSB", off(|w| w.c2_mag += 1)),
            ("c1 + 1 LSB", off(|w| w.c1 += 1)),
            ("c0 + 1 LSB", off(|w| w.c0 += 1)),
        ];
        for (what, c) in &bad {
            assert_ne!(words(c), twin_words, "{what}");
        }
        let run = |c: &NormalizerCoeffs, name: &str| {
            let mut twin = Normalizer::twin(&good);
            let spec = harness::CheckSpec {
                name: name.into(),
                seed,
                compare: vec![harness::Compare::Exact; 4],
            };
            harness::run(
                || Normalizer::build(c),
                &spec,
                |k, _| rows.get(k as usize).cloned(),
                |_, row| twin.step(row).into_iter().map(Expected::Word).collect(),
            )
            .map_err(Box::new)
        };
        run(&good, "twin-coeff-control").unwrap_or_else(|f| panic!("control: {f}"));
        let f = run(&bad[0].1, "twin-coeff-mutant").expect_err("c2 + 1 LSB must be caught");
        println!(
            "{requested:?} c2 + 1 LSB: caught at cycle {} on {}",
            f.cycle, f.signal
        );
    }
}
