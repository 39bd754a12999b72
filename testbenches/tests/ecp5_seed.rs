//! `synth --target ecp5 --seed N`: nextpnr-ecp5's placer seed reaches the placer. The same
//! netlist placed twice with seed 1 gives the same placement (nextpnr's checksum after
//! placement), another seed a different one, and the report names a seed other than 1.
//!
//! Skips with a notice without Yosys or nextpnr-ecp5 (fails when `CI` is set).

use flow::synth::{ecp5_with, require_ecp5, MultRegs};
use rtl::core::registry::Options;
use testbenches::registry;

/// The last "Checksum: 0x…" nextpnr printed (after placement and routing).
fn last_checksum(log_dir: &std::path::Path) -> String {
    let log = std::fs::read_to_string(log_dir.join("nextpnr-ecp5.log")).expect("nextpnr log");
    log.lines()
        .rev()
        .find_map(|l| l.split("Checksum: ").nth(1))
        .unwrap_or_else(|| panic!("no checksum in {}", log_dir.display()))
        .trim()
        .to_string()
}

#[test]
#[ignore = "full tier: nextpnr-ecp5"]
fn the_placer_seed_reaches_nextpnr() {
    if !require_ecp5("the_placer_seed_reaches_nextpnr") {
        return;
    }
    let b = registry::find("k-recurrence").unwrap();
    let v = b.verilog(&Options::new()).unwrap();
    let run = |seed: u64, tag: &str| {
        ecp5_with(
            &v,
            &b.module_name(),
            &b.ports(),
            None,
            tag,
            seed,
            MultRegs::Dsp,
            true,
        )
        .unwrap_or_else(|e| panic!("seed {seed}: {e}"))
    };
    let a = run(1, "seed-test-a");
    let again = run(1, "seed-test-b");
    let other = run(7, "seed-test-c");
    for r in [&a, &again, &other] {
        assert!(r.fmax.is_some(), "not placed: {r}");
    }
    let (ca, cb, cc) = (
        last_checksum(&a.dir),
        last_checksum(&again.dir),
        last_checksum(&other.dir),
    );
    println!("seed 1: {ca}, seed 1 again: {cb}, seed 7: {cc}");
    assert_eq!(ca, cb, "seed 1 twice placed differently");
    assert_ne!(
        ca, cc,
        "seed 7 placed as seed 1 did: the seed did not reach nextpnr"
    );
    assert_eq!(other.seed, 7);
    let text = other.to_string();
    assert!(text.contains("placer seed 7"), "{text}");
    assert!(!a.to_string().contains("placer seed"), "{a}");
}
