//! Rounding errors of a quarter LSB in the lit pipeline's blocks are caught by the bit-exact
//! twins: each block's exported Verilog, with one rounding constant moved by a quarter of its
//! output LSB, runs under Icarus on the block's test rows and must differ from the twin's
//! outputs somewhere (and the unmodified Verilog must equal them everywhere). The twins are
//! written from the headers, not from the RTL, so this is the check that a wrong rounding in
//! the hardware would fail the generic twin test.
//!
//! Skips with a notice without Icarus (fails when `CI` is set).

use golden::testing::seed_for;
use rtl::registry::Options;
use testbenches::registry::{find, test_rows};
use testbenches::tools;
use testbenches::verilog::{differential_rows, DiffError, Mutant, Simulator};

fn check(block: &str, o: Options, mutants: &[Mutant]) {
    let b = find(block).unwrap();
    let name = format!("quarter-lsb-{block}");
    let seed = seed_for(&name);
    let rows = test_rows(b, &o, 400, seed).unwrap();
    let twin = b.twin_rows(&o, &rows).unwrap();
    let v = b.verilog(&o).unwrap();
    let run = |text: &str, tag: &str| {
        differential_rows(
            text,
            &b.module_name(),
            b.ports(),
            &rows,
            &twin,
            Simulator::Icarus,
            tag,
        )
    };
    run(&v, &format!("{name}-control")).unwrap_or_else(|e| panic!("{block} control: {e}"));
    for m in mutants {
        match run(&m.apply(&v), &name) {
            Err(DiffError::Mismatch(d)) => println!("{block}: caught [{}]: {d}", m.what),
            Err(DiffError::Tool(e)) => panic!("{block} [{}] did not run: {e}", m.what),
            Ok(_) => panic!(
                "{block} [{}] was NOT caught by the twin (seed {seed})",
                m.what
            ),
        }
    }
}

#[test]
fn quarter_lsb_rounding_errors_are_caught_by_the_twins() {
    if !tools::require(
        Simulator::Icarus.tools(),
        "quarter_lsb_rounding_errors_are_caught_by_the_twins",
    ) {
        return;
    }
    #[rustfmt::skip]
    check("lighting-unit", Options::new().with("coeffs", "fit"), &[
        Mutant { what: "cosine rounding + ¼ LSB", module: "lighting_unit", from: "localparam  half_lsb = 34'h1000;", to: "localparam  half_lsb = 34'h1800;" },
    ]);
    #[rustfmt::skip]
    check("colour-combine", Options::new(), &[
        Mutant { what: "colour rounding + ¼ LSB", module: "colour_combine", from: "localparam  half_lsb = 34'h400000;", to: "localparam  half_lsb = 34'h600000;" },
    ]);
    #[rustfmt::skip]
    check("power-unit", Options::new().with("power", "exact"), &[
        Mutant { what: "square-and-multiply rounding (E5) − ¼ LSB", module: "power_unit$e_rnd_prod$5", from: "localparam  half_lsb = 32'h4000;", to: "localparam  half_lsb = 32'h2000;" },
    ]);
    #[rustfmt::skip]
    check("power-unit", Options::new().with("power", "w16"), &[
        Mutant { what: "W bracket rounding + ¼ LSB", module: "power_unit", from: "localparam  w_half = 32'h80;", to: "localparam  w_half = 32'hc0;" },
    ]);
    #[rustfmt::skip]
    check("brzssk", Options::new(), &[
        Mutant { what: "perturbed cosine rounding + ¼ LSB", module: "brzssk", from: "localparam  half_lsb = 32'h4000;", to: "localparam  half_lsb = 32'h6000;" },
        Mutant { what: "sin γ interpolation rounding + ¼ LSB", module: "brzssk", from: "d_rnd = d_prod + 32'h8;", to: "d_rnd = d_prod + 32'hc;" },
    ]);
}
