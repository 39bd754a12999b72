//! Simulated clock cycles per second of the normalizer: the hand-stepped rust-hdl harness
//! (`rtl::core::sim::Stepper`) versus the exported Verilog under Verilator and Icarus
//! (compiled once, outside the timed loop; each timed run is the whole testbench process:
//! reading the stimulus file and writing one output line per clock, like the differential
//! test). Run with `cargo bench --bench rtl_sim`; criterion reports "elements/s" = clocks/s.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use flow::tools::{self, Tool};
use flow::verilog::{compare_rows, compile, Simulator, VerilogRun};
use rtl::core::export;
use rtl::core::sim::{simulate_rows, Dut, Stepper};
use rtl::units::normalizer::{Normalizer, NormalizerCoeffs};
use testbenches::registry::Bench;

const CYCLES: usize = 20_000;

fn stimulus(c: &NormalizerCoeffs) -> Vec<Vec<u64>> {
    let seed = golden::seed::seed_for("bench_rtl_sim");
    Normalizer::stimulus(c, CYCLES, seed).rows
}

fn hand_stepped(cr: &mut Criterion) {
    let c = NormalizerCoeffs::published();
    let rows = stimulus(&c);
    let mut g = cr.benchmark_group("normalizer_clocks");
    g.throughput(Throughput::Elements(rows.len() as u64));
    g.bench_function(BenchmarkId::new("rust-hdl hand-stepped", rows.len()), |b| {
        b.iter(|| {
            let mut s = Stepper::new(Normalizer::new(&c)).unwrap();
            let mut out = vec![0; 4];
            for r in &rows {
                s.step(r, &mut out).unwrap();
            }
            out
        })
    });
    g.finish();
}

fn verilog(cr: &mut Criterion) {
    let c = NormalizerCoeffs::published();
    let rows = stimulus(&c);
    let v = export::verilog::<Normalizer>(&c).unwrap();
    let dut = Normalizer::new(&c);
    let (inputs, outputs) = (dut.inputs(), dut.outputs());
    let reference = simulate_rows(Normalizer::new(&c), &rows).unwrap();
    let mut g = cr.benchmark_group("normalizer_clocks");
    g.throughput(Throughput::Elements(rows.len() as u64));
    for (sim, tool) in [
        (Simulator::Verilator, Tool::Verilator),
        (Simulator::Icarus, Tool::Iverilog),
    ] {
        if !tools::available(tool) {
            eprintln!(
                "SKIPPED {sim:?} benchmark: {} not installed",
                tool.program()
            );
            continue;
        }
        let compiled = compile(
            sim,
            &v,
            "normalizer",
            &inputs,
            &outputs,
            &format!("bench-{sim:?}"),
        )
        .unwrap();
        eprintln!(
            "{sim:?}: compiled in {:.1?} (not timed)",
            compiled.compile_time
        );
        compiled.write_stimulus(&rows).unwrap();
        // Sanity: the simulator agrees with rust-hdl bit for bit before it is timed.
        compiled.execute().unwrap();
        let run = VerilogRun {
            rows: compiled.read_outputs().unwrap(),
            dir: compiled.dir.clone(),
            sim_time: Duration::ZERO,
        };
        compare_rows(&outputs, &reference, &run).unwrap_or_else(|m| panic!("{sim:?}: {m}"));
        g.bench_function(
            BenchmarkId::new(format!("{sim:?} (exported Verilog)"), rows.len()),
            |b| b.iter(|| compiled.execute().unwrap()),
        );
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().without_plots().sample_size(10).measurement_time(Duration::from_secs(8)).warm_up_time(Duration::from_secs(1));
    targets = hand_stepped, verilog
}
criterion_main!(benches);
