//! The ECP5 multiplier mapping (`rtl::targets::ecp5_dsp`: registered 16×16 products rewritten as
//! MULT18X18D instances holding their operand and product registers, what `synth --target
//! ecp5` places) computes what the exported Verilog computes: for every block with such
//! products, the mapped Verilog with the behavioural MULT18X18D model runs under Verilator (in
//! process) bit-exact with the rust-hdl simulation, every port, every clock; and, under Icarus,
//! a mapping a clock off either way (the product register left out, or the operands taken a
//! register late) fails.
//!
//! Skips with a notice without Verilator or Icarus (fails when `CI` is set). `SHADECORE_SEED`
//! varies the seeds.

use flow::tools::{self, two_at_a_time, Tool};
use flow::verilog::{differential_rows, DiffError, Simulator};
use golden::testing::seed_for;
use rtl::core::registry::Options;
use testbenches::registry::{self, test_rows, Entry, BLOCKS};

/// Stimulus items per block (fewer than the registry's generic tests: this checks the
/// mapping's wiring, which every product exercises every clock).
fn items(b: &dyn Entry) -> usize {
    match b.items() {
        "triangles" => 3,
        "spans" => 40,
        _ => 600,
    }
}

/// The mapped Verilog of `b` with the model appended, and the number of products mapped.
fn mapped(b: &dyn Entry, o: &Options) -> (String, usize) {
    let v = b.verilog(o).unwrap();
    let m = rtl::targets::ecp5_dsp::map_multipliers(&v);
    (
        format!("{}\n{}", m.verilog, rtl::targets::ecp5_dsp::sim_model()),
        m.products,
    )
}

fn run(
    b: &dyn Entry,
    o: &Options,
    verilog: &str,
    tag: &str,
) -> Result<flow::verilog::DiffReport, DiffError> {
    let seed = seed_for(tag);
    let rows = test_rows(b, o, items(b), seed).unwrap();
    let expected = b.simulate(o, &rows).unwrap();
    differential_rows(
        verilog,
        &b.module_name(),
        b.ports(),
        &rows,
        &expected,
        Simulator::Icarus,
        tag,
    )
}

/// The mapped Verilog of `b` built with `o` (`verilog`), verilated and stepped in process on
/// the test rows seeded by `tag`, against the rust-hdl simulation; the clocks compared.
fn run_verilated(b: &dyn Entry, o: &Options, verilog: &str, tag: &str) -> Result<usize, String> {
    let seed = seed_for(tag);
    let rows = test_rows(b, o, items(b), seed)?;
    let expected = b.simulate(o, &rows)?;
    let (inputs, outputs) = b.ports();
    // Keyed like a registered block's build (`block:…|…|fingerprint`), so that a build from
    // older RTL sources is evicted rather than kept beside it.
    // Verilator (5.006 without `--timing`) takes no delays: the model's check of its mode pins,
    // a time step after the start under Icarus, runs at the start, where the pins tied off
    // by the mapping already hold their constants.
    let delay = "        #1;\n";
    assert_eq!(verilog.matches(delay).count(), 1, "the model's one delay");
    let mut design = verilated::Design::from_verilog(
        &format!("{} (ECP5 multipliers mapped)", b.name()),
        &b.module_name(),
        verilog.replacen(delay, "", 1),
        inputs,
        outputs.clone(),
    );
    design.key = format!(
        "block:{}+ecp5-dsp|{o:?}|{}",
        b.name(),
        rtl::SOURCE_FINGERPRINT
    );
    let mut model = verilated::VModel::new(verilated::build(&design)?)?;
    let got = rtl::core::sim::run_model(&mut model, &rows)?;
    flow::verilog::compare_outputs(&outputs, &expected, &got)?;
    Ok(rows.len())
}

#[test]
#[ignore = "full tier: the ECP5 multiplier mapping of every block, each verilated"]
fn mapped_multipliers_are_bit_exact_with_the_simulation() {
    if !tools::require(&[Tool::Verilator], "ecp5_dsp") {
        return;
    }
    // Every build with products, in registry order (its index names it and seeds it); two
    // at a time. Every product the registry counts as a
    // multiplier is in the mapping's reach: a 16×16 one between registers (the Horner unit's
    // composed 32×16 products are not).
    // A pipeline top is mapped and run inside its stream top where the stream builds the same
    // option set (`registry::INSIDE_STREAM`): the stream's mapped Verilog holds the pipeline's.
    let builds: Vec<(&dyn Entry, Options, String, usize)> = BLOCKS
        .iter()
        .flat_map(|b| b.test_sets().into_iter().map(move |o| (*b, o)))
        .filter(|(b, o)| registry::wrapped_by_tested_stream(b.name(), o).is_none())
        .filter_map(|(b, o)| {
            let (v, products) = mapped(b, &o);
            (products > 0).then_some((b, o, v, products))
        })
        .collect();
    let checked = builds.len();
    two_at_a_time(
        builds.into_iter().enumerate(),
        |(i, (b, o, v, products))| {
            let label = format!("ecp5-dsp-{}-{}", b.name(), i);
            let seed = seed_for(&label);
            let clocks = run_verilated(b, &o, &v, &label)
                .unwrap_or_else(|e| panic!("{}: {e} (seed {seed})", b.name()));
            println!(
                    "[{label}] {} ({:?}, seed {seed}): {products} products on MULT18X18D, bit-exact over {clocks} clocks under Verilator",
                    b.name(),
                    o,
                );
        },
    );
    // The lit path's blocks all have such products; a mapping that found none would pass
    // vacuously.
    assert!(
        checked >= 13,
        "only {checked} block builds had products to map"
    );
}

#[test]
#[ignore = "full tier: the ECP5 multiplier mapping under Icarus"]
fn the_power_unit_maps_every_product_and_a_clock_off_is_caught() {
    if !tools::require(&[Tool::Iverilog, Tool::Vvp], "ecp5_dsp") {
        return;
    }
    let b = registry::find("power-unit").unwrap();
    let o = Options::new();
    let (v, products) = mapped(b, &o);
    // 9 squares and 9 products in the exponent chain, the W product and its 4 partial products.
    assert!(
        products >= b.multipliers_with(&o).unwrap(),
        "{products} products mapped"
    );
    let first = v.find("MULT18X18D #(").expect("a DSP instance");
    let end = first + v[first..].find(");\n").unwrap();
    let inst = &v[first..end];
    // The product one clock early: no output register.
    let early = format!(
        "{}{}{}",
        &v[..first],
        inst.replacen(".REG_OUTPUT_CLK(\"CLK0\")", ".REG_OUTPUT_CLK(\"NONE\")", 1),
        &v[end..]
    );
    // The operands a clock late: the fabric registers' outputs into the input registers.
    let late = format!("{}{}{}", &v[..first], inst.replace("$d[", "$q["), &v[end..]);
    assert_ne!(early, v);
    assert_ne!(late, v);
    run(b, &o, &v, "ecp5-dsp-power").unwrap_or_else(|e| panic!("unmutated: {e}"));
    for (what, text) in [("output register left out", early), ("operands late", late)] {
        match run(b, &o, &text, "ecp5-dsp-power-mutant") {
            Err(DiffError::Mismatch(m)) => println!("{what}: caught: {m}"),
            Err(e) => panic!("{what}: the run failed to complete: {e}"),
            Ok(_) => panic!("{what}: the mutant passed"),
        }
    }
}
