//! Rounding errors of a quarter LSB in the lit pipeline's blocks, the span units, the Horner unit
//! and the quadric unit are caught by the bit-exact
//! twins: each block's exported Verilog, with one rounding constant moved by a quarter of its
//! output LSB, runs under Icarus on the block's test rows and must differ from the twin's
//! outputs somewhere (and the unmodified Verilog must equal them everywhere). The twins are
//! written from the headers, not from the RTL, so this is the check that a wrong rounding in
//! the hardware would fail the generic twin test.
//!
//! Skips with a notice without Icarus (fails when `CI` is set).

use flow::tools;
use flow::verilog::{Mutant, Simulator};
use rtl::core::registry::Options;
use testbenches::registry::assert_mutants_caught_by_twin as check;

fn check400(block: &str, o: Options, mutants: &[Mutant]) {
    check(block, &o, 400, mutants);
}

#[test]
#[ignore = "full tier: the quarter-LSB Verilog mutants under Icarus"]
fn quarter_lsb_rounding_errors_are_caught_by_the_twins() {
    if !tools::require(
        Simulator::Icarus.tools(),
        "quarter_lsb_rounding_errors_are_caught_by_the_twins",
    ) {
        return;
    }
    // Two Icarus runs at a time (one core each).
    std::thread::scope(|s| {
        s.spawn(lit_units);
        span_units();
    });
}

/// The lit path's units.
fn lit_units() {
    #[rustfmt::skip]
    check400("lighting-unit", Options::new().with("coeffs", "fit"), &[
        Mutant { what: "cosine rounding + ¼ LSB", module: "lighting_unit", from: "localparam  half_lsb = 32'h1000;", to: "localparam  half_lsb = 32'h1800;" },
    ]);
    // The vector interpolator's output rounding (x component), since N is Q2.17.
    #[rustfmt::skip]
    check("vector-interpolator", &Options::new(), 8, &[
        Mutant { what: "N output rounding + ¼ LSB", module: "vector_interpolator__round__0", from: "localparam  half_lsb = 32'h800;", to: "localparam  half_lsb = 32'hc00;" },
    ]);
    #[rustfmt::skip]
    check400("colour-combine", Options::new(), &[
        Mutant { what: "colour rounding + ¼ LSB", module: "colour_combine", from: "localparam  half_lsb = 32'h400000;", to: "localparam  half_lsb = 32'h600000;" },
    ]);
    #[rustfmt::skip]
    check400("power-unit", Options::new().with("power", "exact"), &[
        Mutant { what: "square-and-multiply rounding (E5) − ¼ LSB", module: "power_unit__e_rnd_prod__5", from: "localparam  half_lsb = 32'h4000;", to: "localparam  half_lsb = 32'h2000;" },
    ]);
    #[rustfmt::skip]
    check400("power-unit", Options::new().with("power", "w16"), &[
        Mutant { what: "W bracket rounding + ¼ LSB", module: "power_unit", from: "localparam  w_half = 32'h80;", to: "localparam  w_half = 32'hc0;" },
    ]);
    #[rustfmt::skip]
    check400("brzssk", Options::new(), &[
        Mutant { what: "perturbed cosine rounding + ¼ LSB", module: "brzssk", from: "localparam  half_lsb = 32'h4000;", to: "localparam  half_lsb = 32'h6000;" },
        Mutant { what: "sin γ interpolation rounding + ¼ LSB", module: "brzssk", from: "d_rnd = d_prod + 16'h8;", to: "d_rnd = d_prod + 16'hc;" },
    ]);
}

/// The span units, the Horner unit and the quadric unit.
fn span_units() {
    // The span units (issue 10).
    #[rustfmt::skip]
    check("cos-v-accumulator", &Options::new(), 60, &[
        Mutant { what: "PROM address rounding + ¼ step", module: "cos_v_accumulator", from: "localparam  half_step = 32'h40000;", to: "localparam  half_step = 32'h60000;" },
    ]);
    #[rustfmt::skip]
    check("fast-unit", &Options::new(), 60, &[
        Mutant { what: "t1 rounding + ¼ LSB", module: "fast_unit", from: "localparam  half_t1 = 32'h8000;", to: "localparam  half_t1 = 32'hc000;" },
        Mutant { what: "M rounding + ¼ LSB", module: "fast_unit", from: "localparam  half31 = 49'h40000000;", to: "localparam  half31 = 49'h60000000;" },
    ]);
    // The Horner unit and the quadric unit (issue 11).
    #[rustfmt::skip]
    check("horner-unit", &Options::new().with("horner", "serial"), 60, &[
        Mutant { what: "MUL product rounding (the loop's kk term) + ¼ LSB", module: "horner_unit", from: "localparam  half48 = 48'h4000;", to: "localparam  half48 = 48'h6000;" },
        Mutant { what: "output rounding + ¼ LSB", module: "horner_unit__out_s", from: "localparam  half = 32'h800;", to: "localparam  half = 32'hc00;" },
        Mutant { what: "p rounding + ¼ LSB", module: "horner_unit", from: "localparam  p_half = 29'h800;", to: "localparam  p_half = 29'hc00;" },
    ]);
    #[rustfmt::skip]
    check("horner-unit", &Options::new().with("horner", "pipelined"), 60, &[
        Mutant { what: "second step's product rounding + ¼ LSB", module: "horner_unit__step2", from: "localparam  half48 = 48'h4000;", to: "localparam  half48 = 48'h6000;" },
        Mutant { what: "output rounding + ¼ LSB", module: "horner_unit__out_p", from: "localparam  half = 32'h800;", to: "localparam  half = 32'hc00;" },
    ]);
    #[rustfmt::skip]
    check("quadric-unit", &Options::new(), 12, &[
        Mutant { what: "lane B red rounding + ¼ LSB", module: "quadric_unit__rlo_b__0", from: "localparam  half = 5'b10;", to: "localparam  half = 5'b11;" },
        // The carry-save adds, the halves' carries and the flags from the distance register
        // (not roundings: one operator each, which the twin must catch as well).
        // (A subtraction's +1 in the carry word is 2⁻³⁰ LSB: below what the 8-bit outputs
        // resolve, so it is not among them.)
        // (In the high half this one would go unseen: there −2·Dx and −Dx differ only for
        // |Dx| ≥ 2³¹ in Q34.30, 2 LSB per pixel, where the high half is more than sign.)
        Mutant { what: "−2 x-step of I: −Dx in place of −2·Dx (red, low half)", module: "quadric_unit__half_lo", from: "xt1$0 = n_sdx$0;", to: "xt1$0 = n_dx$0;" },
        Mutant { what: "generator difference e' = e + 2A instead of e + 2·2A (green, low half)", module: "quadric_unit__half_lo", from: "cs_ge$1 = ge$1$q + s_ga2$1 +", to: "cs_ge$1 = ge$1$q + ga2$1$q +" },
        Mutant { what: "leftward hand-over e = 2A + Dx + 1 instead of 2A − Dx (green, low half)", module: "quadric_unit__half_lo", from: "cs_hge$1 = ta2$1$q + n_dx$1 +", to: "cs_hge$1 = ta2$1$q + tdx$1$q +" },
        Mutant { what: "the y-step's carry from I's low half into its high half dropped (red)", module: "quadric_unit__half_hi", from: "cs_yi$0 = ti$0$q + tdy$0$q + {31'h0, cin$0[(16)+:(1)]};", to: "cs_yi$0 = ti$0$q + tdy$0$q;" },
        Mutant { what: "a +2 x-step from d = 3 taken as reaching the line start (d = 2)", module: "quadric_unit", from: "n_zero = tdist$q == 13'b10;", to: "n_zero = tdist$q == 13'b11;" },
    ]);
}
