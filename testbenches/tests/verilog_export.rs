//! Exported Verilog of the SPEC §1 blocks beyond the generic registry tests
//! (`tests/registry.rs`: Yosys, Icarus and Verilator for every block and parameter set): the
//! normalizer over the whole 100 000-vector domain run and the K recurrence on long spans
//! under both simulators, and a deliberately broken export that the differential check must
//! catch; the Yosys check itself rejects a latch. (The address block, BVI and raster pipe have their own in
//! `tests/address_block.rs` and `tests/intensity_interpolator.rs`.)
//!
//! Tests needing a tool skip with a notice when it is missing, and fail when `CI` is set.

use flow::blocks::differential;
use flow::synth::{check_and_map_ice40, check_and_map_ice40_dsp, check_and_synth};
use flow::tools::{self, Tool};
use flow::verilog::{self as verilog, DiffError, Mutant, Simulator};
use golden::testing::seed_for;
use rtl::core::export;
use rtl::core::registry::Options;
use rtl::units::normalizer::{Normalizer, NormalizerCoeffs};
use testbenches::registry::{self, assert_mutants_caught};
use testbenches::units::k_recurrence::{krec_rows, span_rows, spans_and_schedule};
use testbenches::units::normalizer::*;

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
    // The same checks without the generic synth, and with the iCE40 map stopped after its
    // multiplier packing (the registry test's path).
    for (map, tag) in [
        (check_and_map_ice40 as Map, "map"),
        (check_and_map_ice40_dsp, "dsp"),
    ] {
        let e =
            map(v, "latchy", &format!("yosys-latch-{tag}")).expect_err("a latch must be rejected");
        println!("{e}");
        let e = map(undriven, "undriven", &format!("yosys-undriven-{tag}"))
            .expect_err("an undriven wire must be rejected");
        println!("{e}");
    }
}

type Map = fn(&str, &str, &str) -> Result<flow::synth::SynthReport, String>;

/// The stopped iCE40 map has packed the products: a registered 16×16 product is one SB_MAC16
/// there, as in the whole map, and a 20×16 one is two.
#[test]
fn yosys_packs_products_before_the_lut_map() {
    if !tools::require(&[Tool::Yosys], "yosys_packs_products_before_the_lut_map") {
        return;
    }
    for (a, want) in [(16, 1), (20, 2)] {
        let v = format!(
            "module mul(input clock, input [{}:0] a, input [15:0] b, output reg [{}:0] p);\n\
             reg [{}:0] ar; reg [15:0] br;\n\
             always @(posedge clock) begin ar <= a; br <= b; p <= ar * br; end\nendmodule\n",
            a - 1,
            a + 15,
            a - 1
        );
        let stopped = check_and_map_ice40_dsp(&v, "mul", &format!("yosys-mul{a}-dsp")).unwrap();
        let whole = check_and_map_ice40(&v, "mul", &format!("yosys-mul{a}-map")).unwrap();
        println!("{stopped}{whole}");
        assert!(stopped.ice40_coarse && stopped.luts() == 0, "{stopped}");
        assert_eq!(stopped.mac16(), want, "{a}×16 stopped");
        assert_eq!(whole.mac16(), want, "{a}×16 whole");
    }
}

/// `rows` through the registered block `name` (published coefficients) and its exported
/// Verilog under both simulators, bit-exact every clock: Verilator in process on every row,
/// Icarus (an interpreter, through files) on the first [`ICARUS_ROWS`].
fn bit_exact_both(test: &str, name: &str, rows: &[Vec<u64>]) {
    let b = registry::find(name).unwrap();
    for sim in [Simulator::Icarus, Simulator::Verilator] {
        if !tools::require(sim.tools(), test) {
            continue;
        }
        let rows = match sim {
            Simulator::Icarus => &rows[..rows.len().min(ICARUS_ROWS)],
            Simulator::Verilator => rows,
        };
        let rep = differential(b, &Options::new(), rows, sim, &format!("{test}-{name}"))
            .unwrap_or_else(|e| {
                panic!("{name} under {sim:?}: {e} (seed {})", seed_for(DOMAIN_RUN))
            });
        println!(
            "{name}: bit-exact under {sim:?} over {} clocks × {} ports ({:?})",
            rep.cycles, rep.ports, rep.verilog_sim_time
        );
    }
}

/// Rows of a long run that Icarus takes (the whole run goes through Verilator).
const ICARUS_ROWS: usize = 10_000;

/// The whole 100 000-vector domain run, the named and extreme cases and junk in idle clocks.
/// (Verilator 5.006 once disagreed here: it ignored inputs written by `$fscanf` output
/// arguments; the generated testbench now reads through temporaries.)
#[test]
fn normalizer_differential_100k() {
    let rows = normalizer_rows();
    assert!(rows.len() > 100_000);
    bit_exact_both("normalizer_differential_100k", "normalizer", &rows);
}

/// Long spans: the exact-K spans of tests/k_recurrence.rs and 1500 span-normalizer spans.
#[test]
fn k_recurrence_and_span_normalizer_differential() {
    let test = "k_recurrence_and_span_normalizer_differential";
    let (spans, sched) = spans_and_schedule("k_recurrence_exact", 3000);
    bit_exact_both(test, "k-recurrence", &krec_rows(&spans, &sched).0);
    let (spans, sched) = spans_and_schedule("span_normalizer", 1500);
    let c = NormalizerCoeffs::published();
    bit_exact_both(
        test,
        "span-normalizer",
        &span_rows(&spans, &sched, c.requested).0,
    );
}

#[test]
fn broken_export_is_caught() {
    if !icarus("broken_export_is_caught") {
        return;
    }
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
    // One flipped operator each (inside a shared primitive: the instance named).
    #[rustfmt::skip]
    let mutants = [
        Mutant { what: "K sum: + → -", module: "", from: "k_xy = sq_x$sq + sq_y$sq", to: "k_xy = sq_x$sq - sq_y$sq" },
        Mutant { what: "K's cross terms: + → -", module: "", from: "xterm_sum = sq_x$xterm + sq_y$xterm", to: "xterm_sum = sq_x$xterm - sq_y$xterm" },
        Mutant { what: "sign correction of Mul6 (x·f): - → +", module: "normalizer__scale__lane_x__mul", from: "p_q$d = raw$q - corr_w", to: "p_q$d = raw$q + corr_w" },
        Mutant { what: "K rounding: + → -", module: "normalizer__scale__k_round", from: "rounded = wide + half_lsb", to: "rounded = wide - half_lsb" },
        Mutant { what: "K saturation test: | → &", module: "normalizer__scale__k_round", from: "|wide[(29)+:(3)] | &wide[", to: "|wide[(29)+:(3)] & &wide[" },
        Mutant { what: "halving c2·K: >> → <<", module: "", from: "c2k_half = c2k$q >> 32'h1", to: "c2k_half = c2k$q << 32'h1" },
        Mutant { what: "Horner add: + → -", module: "", from: "f_wide = c0_low$q + t1k_half", to: "f_wide = c0_low$q - t1k_half" },
    ];
    assert_mutants_caught(registry::find("normalizer").unwrap(), &rows, &mutants);
}

/// A rounding bias of a quarter LSB in the normalizer's output stage (the half-LSB constant
/// 2¹¹ of every output lane made 2¹¹ + 2¹⁰) — the kind of bug the rust-hdl simulation shares
/// with its own Verilog, so only an independent model can see it — is caught by the
/// bit-exact twin on the first vectors; the unmodified export equals the twin every clock.
#[test]
fn twin_catches_a_quarter_lsb_output_bias() {
    use rtl::core::registry::RtlBlock;
    use rtl::core::sim::Dut;
    use testbenches::registry::Bench;
    if !icarus("twin_catches_a_quarter_lsb_output_bias") {
        return;
    }
    let c = NormalizerCoeffs::published();
    let seed = seed_for("quarter_lsb_bias");
    println!("[quarter_lsb_bias] seed {seed}");
    let rows = Normalizer::stimulus(&c, 2000, seed).rows;
    let mut twin = Normalizer::twin(&c);
    let expected: Vec<Vec<u64>> = rows.iter().map(|r| twin.step(r)).collect();
    let good = export::verilog::<Normalizer>(&c).unwrap();
    let ports = Normalizer::build(&c);
    let ports = (ports.inputs(), ports.outputs());
    let run = |v: &str, tag: &str| {
        verilog::differential_rows(
            v,
            "normalizer",
            ports.clone(),
            &rows,
            &expected,
            Simulator::Icarus,
            tag,
        )
    };
    run(&good, "quarter-lsb-control").unwrap_or_else(|e| panic!("control: {e}"));
    let mut bad = good.clone();
    for lane in ["x", "y", "z"] {
        let module = format!("normalizer__scale__lane_{lane}");
        let (from, to) = ("half_lsb = 32'h800", "half_lsb = 32'hc00");
        bad = Mutant {
            what: "¼-LSB bias",
            module: &module,
            from,
            to,
        }
        .apply(&bad);
    }
    match run(&bad, "quarter-lsb-mutant") {
        Err(DiffError::Mismatch(m)) => {
            println!("caught the ¼-LSB bias (the rust-hdl column is the twin here): {m}")
        }
        Err(DiffError::Tool(e)) => panic!("mutant did not run: {e}"),
        Ok(_) => panic!("a ¼-LSB output bias was NOT caught by the twin"),
    }
}
