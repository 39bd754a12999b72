//! Exported Verilog of the blocks in the registry (`rtl::export::BlockKind`): Yosys synthesizes
//! every one cleanly and Icarus compiles it; the normalizer blocks behave bit-for-bit like the
//! rust-hdl simulation every clock (differential test), which a deliberately broken export
//! fails. (The differential tests of the address block, BVI and raster pipe are in
//! `tests/address_block.rs` and `tests/intensity_interpolator.rs`.)
//!
//! Tests needing a tool skip with a notice when it is missing, and fail when `CI` is set.

use golden::normalizer::FIT;
use golden::testing::seed_for;
use rtl::export::{self, BlockKind};
use rtl::k_recurrence::{KRecurrence, SpanNormalizer};
use rtl::normalizer::{Normalizer, NormalizerCoeffs, NormalizerK};
use testbenches::blocks::ports;
use testbenches::k_recurrence::{krec_rows, span_rows, spans_and_schedule};
use testbenches::normalizer::*;
use testbenches::synth::check_and_synth;
use testbenches::tools::{self, Tool};
use testbenches::verilog::{compile, differential, DiffError, Simulator};

fn icarus(test: &str) -> bool {
    tools::require(Simulator::Icarus.tools(), test)
}

/// The normalizer stimulus: the 100 000 domain vectors of the cycle-by-cycle test, the named
/// domain and extreme cases, and a stretch with idle clocks carrying junk.
fn normalizer_rows() -> Vec<Vec<u64>> {
    let (_, vectors) = domain_run_vectors();
    let mut slots: Vec<Slot> = vectors.iter().map(|v| Slot::Vector(quantize(*v))).collect();
    slots.extend(edge_cases().iter().map(|(_, v)| Slot::Vector(quantize(*v))));
    slots.extend(extreme_cases().iter().map(|(_, r)| Slot::Vector(*r)));
    for (i, v) in vectors.iter().take(2000).enumerate() {
        if i % 3 == 0 {
            slots.push(Slot::Idle([0xA5C3, 0x8000, i as u64]));
        }
        slots.push(Slot::Vector(quantize(*v)));
    }
    stimulus_rows(&slots, Normalizer::LATENCY)
}

#[test]
fn yosys_synthesizes_every_block_cleanly() {
    if !tools::require(&[Tool::Yosys], "yosys_synthesizes_every_block_cleanly") {
        return;
    }
    let c = NormalizerCoeffs::published();
    for b in BlockKind::ALL {
        // SB_MAC16 expected: one per multiplier of the block's header.
        let macs = match b {
            BlockKind::Normalizer => 8,
            BlockKind::NormalizerK | BlockKind::SpanNormalizer => 5,
            BlockKind::KRecurrence
            | BlockKind::AddressBlock
            | BlockKind::IntensityInterpolator
            | BlockKind::GouraudRaster => 0,
        };
        let v = export::verilog(b, &c).unwrap();
        let rep = check_and_synth(&v, &b.module_name(), &format!("yosys-{b}"))
            .unwrap_or_else(|e| panic!("{b}: {e}"));
        print!("{rep}");
        assert_eq!(rep.mac16(), macs, "{b}: multipliers mapped to SB_MAC16");
        assert!(rep.luts() > 0 && rep.ffs() > 0, "{b}: empty netlist?");
    }
    // The fitted set builds too.
    let fit = NormalizerCoeffs::new(FIT).unwrap();
    let v = export::verilog(BlockKind::Normalizer, &fit).unwrap();
    let rep = check_and_synth(&v, "normalizer", "yosys-normalizer-fit")
        .unwrap_or_else(|e| panic!("FIT: {e}"));
    assert_eq!(rep.mac16(), 8);
}

#[test]
fn yosys_check_rejects_a_latch() {
    // The check can fail: a combinational always block that does not assign its output on
    // every path infers a latch.
    if !tools::require(&[Tool::Yosys], "yosys_check_rejects_a_latch") {
        return;
    }
    let v = "module latchy(input clock, input en, input [3:0] d, output reg [3:0] q);\n\
             always @(*) begin if (en) q = d; end\nendmodule\n";
    let e = check_and_synth(v, "latchy", "yosys-latch").expect_err("a latch must be rejected");
    println!("{e}");
    let undriven = "module undriven(input clock, output [3:0] q);\n  wire [3:0] w;\n  assign q = w;\nendmodule\n";
    let e = check_and_synth(undriven, "undriven", "yosys-undriven")
        .expect_err("an undriven wire must be rejected");
    println!("{e}");
}

#[test]
fn icarus_compiles_every_block() {
    if !icarus("icarus_compiles_every_block") {
        return;
    }
    let c = NormalizerCoeffs::published();
    for b in BlockKind::ALL {
        let v = export::verilog(b, &c).unwrap();
        // The generated testbench instantiates the module with the harness's port list, so
        // a port missing from (or misnamed in) the export fails to elaborate.
        let (i, o) = ports(b, &c);
        compile(
            Simulator::Icarus,
            &v,
            &b.module_name(),
            &i,
            &o,
            &format!("icarus-{b}"),
        )
        .unwrap_or_else(|e| panic!("{b}: {e}"));
    }
}

#[test]
fn normalizer_differential_100k() {
    if !icarus("normalizer_differential_100k") {
        return;
    }
    let c = NormalizerCoeffs::published();
    let rows = normalizer_rows();
    let v = export::verilog(BlockKind::Normalizer, &c).unwrap();
    let rep = differential(
        || Normalizer::new(&c),
        &v,
        "normalizer",
        &rows,
        Simulator::Icarus,
        "diff-normalizer",
    )
    .unwrap_or_else(|e| panic!("{e} (seed {})", seed_for(DOMAIN_RUN)));
    println!(
        "bit-exact over {} clocks × {} ports; Icarus ran {:?}",
        rep.cycles, rep.ports, rep.verilog_sim_time
    );
    assert!(rep.cycles > 100_000);
}

#[test]
fn normalizer_fit_and_back_end_differential() {
    if !icarus("normalizer_fit_and_back_end_differential") {
        return;
    }
    let mut rows = normalizer_rows();
    rows.truncate(20_000);
    let fit = NormalizerCoeffs::new(FIT).unwrap();
    let v = export::verilog(BlockKind::Normalizer, &fit).unwrap();
    differential(
        || Normalizer::new(&fit),
        &v,
        "normalizer",
        &rows,
        Simulator::Icarus,
        "diff-normalizer-fit",
    )
    .unwrap_or_else(|e| panic!("FIT: {e}"));
    // NormalizerK: the same vectors with their exact K appended.
    let c = NormalizerCoeffs::published();
    let krows: Vec<Vec<u64>> = rows
        .iter()
        .map(|r| {
            let i = [r[1], r[2], r[3]].map(|w| rtl::fixed::NORMAL.to_int(w));
            let mut r = r.clone();
            r.push((i[0] * i[0] + i[1] * i[1] + i[2] * i[2]) as u64);
            r
        })
        .collect();
    let v = export::verilog(BlockKind::NormalizerK, &c).unwrap();
    differential(
        || NormalizerK::new(&c),
        &v,
        "normalizer_k",
        &krows,
        Simulator::Icarus,
        "diff-normalizer-k",
    )
    .unwrap_or_else(|e| panic!("normalizer-k: {e}"));
}

#[test]
fn k_recurrence_and_span_normalizer_differential() {
    if !icarus("k_recurrence_and_span_normalizer_differential") {
        return;
    }
    let c = NormalizerCoeffs::published();
    // The same spans as the exact-K test (tests/k_recurrence.rs).
    let (spans, sched) = spans_and_schedule("k_recurrence_exact", 3000);
    let (rows, _) = krec_rows(&spans, &sched);
    let v = export::verilog(BlockKind::KRecurrence, &c).unwrap();
    let rep = differential(
        KRecurrence::new,
        &v,
        "k_recurrence",
        &rows,
        Simulator::Icarus,
        "diff-k-recurrence",
    )
    .unwrap_or_else(|e| panic!("k-recurrence: {e}"));
    println!("k-recurrence bit-exact over {} clocks", rep.cycles);
    let (spans, sched) = spans_and_schedule("span_normalizer", 1500);
    let (rows, _) = span_rows(&spans, &sched, c.requested);
    let v = export::verilog(BlockKind::SpanNormalizer, &c).unwrap();
    let rep = differential(
        || SpanNormalizer::new(&c),
        &v,
        "span_normalizer",
        &rows,
        Simulator::Icarus,
        "diff-span",
    )
    .unwrap_or_else(|e| panic!("span-normalizer: {e}"));
    println!("span-normalizer bit-exact over {} clocks", rep.cycles);
}

/// Replace the single occurrence of `from` in `v` by `to` (panics if not exactly one).
fn mutate(v: &str, from: &str, to: &str) -> String {
    assert_eq!(
        v.matches(from).count(),
        1,
        "mutation site {from:?} must occur once"
    );
    v.replacen(from, to, 1)
}

#[test]
fn broken_export_is_caught() {
    if !icarus("broken_export_is_caught") {
        return;
    }
    let c = NormalizerCoeffs::published();
    // 3000 domain vectors, then the named and extreme cases (saturation logic is only
    // exercised by the latter).
    let (_, vectors) = domain_run_vectors();
    let mut slots: Vec<Slot> = vectors[..3000]
        .iter()
        .map(|v| Slot::Vector(quantize(*v)))
        .collect();
    slots.extend(edge_cases().iter().map(|(_, v)| Slot::Vector(quantize(*v))));
    slots.extend(extreme_cases().iter().map(|(_, r)| Slot::Vector(*r)));
    let rows = stimulus_rows(&slots, Normalizer::LATENCY);
    let good = export::verilog(BlockKind::Normalizer, &c).unwrap();
    // Control: the unmodified export passes on this stimulus.
    differential(
        || Normalizer::new(&c),
        &good,
        "normalizer",
        &rows,
        Simulator::Icarus,
        "mutant-control",
    )
    .unwrap_or_else(|e| panic!("control: {e}"));
    // One flipped operator each; every mutant must be caught.
    let mutants = [
        (
            "K sum: + → -",
            "k_full$d = sq_x$q + sq_y$q",
            "k_full$d = sq_x$q - sq_y$q",
        ),
        (
            "sign correction: - → +",
            "xf$d = xf_raw - xf_corr",
            "xf$d = xf_raw + xf_corr",
        ),
        (
            "K rounding: + → -",
            "k_rnd = k + k_half_lsb",
            "k_rnd = k - k_half_lsb",
        ),
        (
            "K saturation test: | → &",
            "|k[(32'h1d)+:(3)] | &k[",
            "|k[(32'h1d)+:(3)] & &k[",
        ),
        (
            "halving c2·K: >> → <<",
            "c2k_half = c2k$q >> 32'h1",
            "c2k_half = c2k$q << 32'h1",
        ),
        (
            "Horner add: + → -",
            "f_wide = c0_rnd + t1k_half",
            "f_wide = c0_rnd - t1k_half",
        ),
    ];
    for (what, from, to) in mutants {
        let bad = mutate(&good, from, to);
        match differential(
            || Normalizer::new(&c),
            &bad,
            "normalizer",
            &rows,
            Simulator::Icarus,
            "mutant",
        ) {
            Err(DiffError::Mismatch(m)) => println!("caught mutant [{what}]: {m}"),
            Err(DiffError::Tool(e)) => panic!("mutant [{what}] did not run: {e}"),
            Ok(_) => panic!("mutant [{what}] was NOT caught by the differential test"),
        }
    }
}

#[test]
fn normalizer_and_span_differential_verilator() {
    // The same mechanism under Verilator (it once disagreed: Verilator 5.006 ignored inputs
    // written by `$fscanf` output arguments; the generated testbench now avoids that).
    if !tools::require(
        Simulator::Verilator.tools(),
        "normalizer_and_span_differential_verilator",
    ) {
        return;
    }
    let c = NormalizerCoeffs::published();
    let rows = normalizer_rows();
    let v = export::verilog(BlockKind::Normalizer, &c).unwrap();
    let rep = differential(
        || Normalizer::new(&c),
        &v,
        "normalizer",
        &rows,
        Simulator::Verilator,
        "vl-normalizer",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    println!(
        "Verilator: normalizer bit-exact over {} clocks in {:?}",
        rep.cycles, rep.verilog_sim_time
    );
    let (spans, sched) = spans_and_schedule("span_normalizer", 1500);
    let (rows, _) = span_rows(&spans, &sched, c.requested);
    let v = export::verilog(BlockKind::SpanNormalizer, &c).unwrap();
    let rep = differential(
        || SpanNormalizer::new(&c),
        &v,
        "span_normalizer",
        &rows,
        Simulator::Verilator,
        "vl-span",
    )
    .unwrap_or_else(|e| panic!("span-normalizer: {e}"));
    println!(
        "Verilator: span-normalizer bit-exact over {} clocks",
        rep.cycles
    );
}
