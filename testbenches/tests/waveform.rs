//! `shadecore-sim … --vcd FILE`: the VCD it writes (through `testbenches::registry::sim_to_vcd`,
//! the function the command calls) read back with an independent parser: the ports are
//! declared and the sampled values equal the simulation's, clock by clock.

use flow::vcd_check::{sample, variables};
use golden::testing::seed_for;
use rtl::core::registry::Options;
use testbenches::harness::{target_dir, CLOCK_PERIOD_PS};
use testbenches::registry::{find, sim_to_vcd};

fn check_vcd_of(block: &str, n: usize) {
    let block = find(block).unwrap();
    let name = format!("waveform_{}", block.module_name());
    let seed = seed_for(&name);
    println!("[{name}] seed {seed}");
    let o = Options::new();
    let path = target_dir().join("sims").join(format!("test-{name}.vcd"));
    let out = sim_to_vcd(block, &o, n, seed, &path).unwrap_or_else(|e| panic!("{e}"));
    let (inputs, outputs) = block.ports();

    // Every port is declared, with its width, in the `uut` scope.
    let vars = variables(&path).unwrap();
    for p in std::iter::once(("clock", 1))
        .chain(inputs.iter().chain(&outputs).map(|p| (p.name, p.width)))
    {
        let full = format!("uut.{}", p.0);
        assert!(
            vars.iter().any(|(n, w)| *n == full && *w as usize == p.1),
            "{full} ({} bits) missing",
            p.1
        );
    }

    // At t = 10c (clock low, inputs applied, settled) the VCD holds the row the harness drove
    // and the outputs it sampled; at t = 10c + 5 the clock is high.
    let cycles = out.report.inputs.len();
    let names: Vec<Vec<&str>> = std::iter::once("clock")
        .chain(inputs.iter().map(|p| p.name))
        .chain(outputs.iter().map(|p| p.name))
        .map(|n| vec!["uut", n])
        .collect();
    let low: Vec<u64> = (0..cycles as u64).map(|c| c * CLOCK_PERIOD_PS).collect();
    let high: Vec<u64> = low.iter().map(|t| t + CLOCK_PERIOD_PS / 2).collect();
    let at_low = sample(&path, &names, &low).unwrap();
    let at_high = sample(&path, &names, &high).unwrap();
    for c in 0..cycles {
        assert_eq!(at_low[c][0], 0, "clock low at cycle {c}");
        assert_eq!(at_high[c][0], 1, "clock high at cycle {c}");
        let (vi, vo) = at_low[c][1..].split_at(inputs.len());
        assert_eq!(vi, &out.report.inputs[c][..], "inputs at cycle {c}");
        assert_eq!(vo, &out.report.outputs[c][..], "outputs at cycle {c}");
    }
    let valid = out.report.outputs.iter().filter(|o| o[0] == 1).count();
    println!(
        "[{name}] {cycles} clocks compared with {} ({valid} valid outputs)",
        path.display()
    );
    assert!(valid >= n.min(1));
}

#[test]
fn normalizer_vcd_matches_simulation() {
    check_vcd_of("normalizer", 300);
}

#[test]
fn k_recurrence_vcd_matches_simulation() {
    check_vcd_of("k-recurrence", 300);
}
