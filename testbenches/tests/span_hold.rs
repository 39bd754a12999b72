//! `hold` on the span tops (the two-lane `quadric-unit`, `angular-pipeline`, `fast-pipeline`;
//! `cubic-pipeline` in both Horner variants): the back-pressure a stream top gives them. Under random and long holds the RTL shows exactly
//! the pixels of the unheld run, in the same order; the exported Verilog (Verilator in
//! process) equals the block's bit-exact twin every port every clock of the run, and the
//! rust-hdl simulation equals it over the run's first 1 500 clocks (both long holds), so the
//! Verilog is bit-exact with rust-hdl under the holds. The
//! quadric unit shows no pixel two clocks after a held one (its stages after the generator
//! are the output register and the colours' rounding from the high halves, a clock behind); the span pipelines' shading stages (and the Horner
//! units' pixels already issued) run on through a hold, so pixels already in them keep coming
//! out. (The generic tests — golden every clock,
//! twin, Icarus, Verilator, lint — are the registry's; the span units' edge rows hold in a
//! quarter of their clocks.)

use golden::testing::seed_for;
use pipeline::span::SpanKind;
use rtl::core::registry::Options;
use testbenches::pipelines::span_held::{held_run, HeldRun};
use testbenches::registry::find;
use testbenches::stall::StallPattern;
use testbenches::units::quadric_unit::triangles;

/// A pixel shown: (line number, x, y, z, r, g, b).
type Pixel = (usize, u64, u64, u64, [u64; 3]);

/// The block and build of a span kind.
fn block(kind: SpanKind) -> (&'static str, Options) {
    match kind {
        SpanKind::Quadric => ("quadric-unit", Options::new()),
        SpanKind::Angular => ("angular-pipeline", Options::new()),
        SpanKind::Fast(c) => ("fast-pipeline", Options::new().with("inv-sqrt", c)),
        SpanKind::Cubic { pipelined } => (
            "cubic-pipeline",
            Options::new().with("horner", if pipelined { "pipelined" } else { "serial" }),
        ),
    }
}

/// The output rows of the run's exported Verilog under Verilator in process (rust-hdl without
/// Verilator, a failure under `CI`).
fn verilog_outputs(kind: SpanKind, run: &HeldRun) -> Vec<Vec<u64>> {
    let (name, o) = block(kind);
    find(name)
        .unwrap()
        .simulate_on(&o, &run.rows, flow::engine::fast_sim("span_hold"))
        .unwrap()
}

/// The pixels `out` (a run's output rows) shows, in order (lane A before lane B in a clock),
/// each with the number of `done` flags before it (its line).
fn rtl_pixels(kind: SpanKind, run: &HeldRun, out: &[Vec<u64>]) -> Vec<Pixel> {
    let (name, _) = block(kind);
    let mut px = Vec::new();
    let mut line = 0;
    let (lanes, y, last) = pipeline::span::output_columns(kind);
    for (c, o) in out.iter().enumerate() {
        if kind == SpanKind::Quadric && c > 1 && *run.rows[c - 2].last().unwrap() != 0 {
            assert!(
                o[1] == 0 && o[7] == 0 && o[14] == 0,
                "clock {c}: a pixel shown two clocks after a held clock"
            );
        }
        for &lane in lanes {
            if o[lane] != 0 {
                let rgb = [o[lane + 3], o[lane + 4], o[lane + 5]];
                px.push((line, o[lane + 1], o[y], o[lane + 2], rgb));
            }
        }
        line += o[last] as usize;
    }
    assert_eq!(line, run.lines, "{name}: lines ended");
    px
}

/// The clocks of a held run rust-hdl simulates (the exported Verilog runs them all): past the
/// second long hold (clocks 300 to 900).
const RUST_HDL_CLOCKS: usize = 1500;

/// Random holds (probability 0.3, in stretches) and two long ones — over the first lines'
/// loads and hand-overs, and mid-walk: the RTL equals the twin every clock and shows the
/// unheld run's pixels in order.
fn hold_keeps_every_pixel(kind: SpanKind, test: &str, n: usize) {
    let seed = seed_for(test);
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let tris = triangles(n, seed);
    let free = held_run(kind, &tris, &mut StallPattern::never());
    let reference = rtl_pixels(kind, &free, &verilog_outputs(kind, &free));
    assert_eq!(
        reference.len(),
        free.pixels,
        "the unheld run shows every pixel once"
    );
    let mut random = StallPattern::new(seed, 0.3);
    let mut stalls = StallPattern::from_fn(move |c| {
        let r = random.next_stalled();
        (2..40).contains(&c) || (300..900).contains(&c) || r
    });
    let run = held_run(kind, &tris, &mut stalls);
    assert!(run.held > 800, "held {} clocks", run.held);
    let (name, o) = block(kind);
    let b = find(name).unwrap();
    // rust-hdl equals the twin every port every clock over the first RUST_HDL_CLOCKS (both
    // long holds and the random ones among them), and so does the exported Verilog over the
    // whole run: the Verilog is bit-exact with rust-hdl under the holds.
    let head = &run.rows[..run.rows.len().min(RUST_HDL_CLOCKS)];
    b.run_twin(&o, head, &format!("{name}-hold"), seed)
        .unwrap_or_else(|f| panic!("{f}"));
    let out = verilog_outputs(kind, &run);
    b.check_twin(&o, &run.rows, &out, &format!("{name}-hold-verilog"), seed)
        .unwrap_or_else(|f| panic!("the Verilog under holds: {f}"));
    let pixels = rtl_pixels(kind, &run, &out);
    assert!(
        pixels == reference,
        "{name}: the held run's pixels differ from the unheld run's"
    );
    println!(
        "{name}: {} lines, {} pixels: {} clocks unheld, {} with {} held clocks",
        run.lines,
        run.pixels,
        free.rows.len(),
        run.rows.len(),
        run.held
    );
    assert!(run.rows.len() > free.rows.len() + 600);
}

#[test]
fn quadric_hold_loses_no_pixel_and_matches_the_twin() {
    hold_keeps_every_pixel(
        SpanKind::Quadric,
        "quadric_hold_loses_no_pixel_and_matches_the_twin",
        8,
    );
}

#[test]
fn angular_hold_loses_no_pixel_and_matches_the_twin() {
    hold_keeps_every_pixel(
        SpanKind::Angular,
        "angular_hold_loses_no_pixel_and_matches_the_twin",
        3,
    );
}

#[test]
fn cubic_hold_loses_no_pixel_and_matches_the_twin() {
    for pipelined in [false, true] {
        hold_keeps_every_pixel(
            SpanKind::Cubic { pipelined },
            "cubic_hold_loses_no_pixel_and_matches_the_twin",
            2,
        );
    }
}

#[test]
fn fast_hold_loses_no_pixel_and_matches_the_twin() {
    for c in ["fit", "chebyshev"] {
        hold_keeps_every_pixel(
            SpanKind::Fast(c),
            "fast_hold_loses_no_pixel_and_matches_the_twin",
            3,
        );
    }
}
