//! The quadric unit's `hold` (the back-pressure a stream top gives it): under random and long
//! holds the RTL equals its bit-exact twin every clock, shows exactly the pixels of the unheld
//! run in the same order, none in a clock after a held one, and its exported Verilog is
//! bit-exact with the rust-hdl simulation under the same pattern. (The generic tests — golden
//! every clock, twin, Icarus, Verilator, lint — are the registry's, with `hold` low.)

use golden::testing::seed_for;
use rtl::registry::Options;
use testbenches::quadric_unit::{held_run, triangles, HeldRun, HOLD};
use testbenches::registry::{differential, find};
use testbenches::stall::StallPattern;
use testbenches::verilog::Simulator;

/// A pixel shown: (line number, x, y, z, r, g, b).
type Pixel = (usize, u64, u64, u64, [u64; 3]);

/// The pixels the RTL (rust-hdl) shows for the run, in order (lane A before lane B in a
/// clock), with the number of `last` flags before each (its line).
fn rtl_pixels(run: &HeldRun) -> Vec<Pixel> {
    let b = find("quadric-unit").unwrap();
    let out = b.simulate(&Options::new(), &run.rows).unwrap();
    let mut px = Vec::new();
    let mut line = 0;
    for (c, o) in out.iter().enumerate() {
        if c > 0 && run.rows[c - 1][HOLD] != 0 {
            assert!(
                o[1] == 0 && o[7] == 0 && o[14] == 0,
                "clock {c}: a pixel shown after a held clock"
            );
        }
        for lane in [1, 7] {
            if o[lane] != 0 {
                px.push((
                    line,
                    o[lane + 1],
                    o[13],
                    o[lane + 2],
                    [o[lane + 3], o[lane + 4], o[lane + 5]],
                ));
            }
        }
        line += o[14] as usize;
    }
    assert_eq!(line, run.lines, "lines ended");
    px
}

#[test]
fn hold_loses_no_pixel_and_matches_the_twin() {
    let seed = seed_for("hold_loses_no_pixel_and_matches_the_twin");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let tris = triangles(8, seed);
    let free = held_run(&tris, &mut StallPattern::never());
    let reference = rtl_pixels(&free);
    assert_eq!(
        reference.len(),
        free.pixels,
        "the unheld run shows every pixel once"
    );
    let mut random = StallPattern::new(seed, 0.3);
    // Random holds, and two long ones: over the first triangle's hand-overs, and mid-walk.
    let mut stalls = StallPattern::from_fn(move |c| {
        let r = random.next_stalled();
        (2..40).contains(&c) || (300..900).contains(&c) || r
    });
    let run = held_run(&tris, &mut stalls);
    assert!(run.held > 800, "held {} clocks", run.held);
    let b = find("quadric-unit").unwrap();
    b.run_twin(&Options::new(), &run.rows, "quadric-hold", seed)
        .unwrap_or_else(|f| panic!("{f}"));
    let pixels = rtl_pixels(&run);
    assert!(
        pixels == reference,
        "the held run's pixels differ from the unheld run's"
    );
    println!(
        "{} lines, {} pixels: {} clocks unheld, {} with {} held clocks",
        run.lines,
        run.pixels,
        free.rows.len(),
        run.rows.len(),
        run.held
    );
    assert!(run.rows.len() > free.rows.len() + 600);
}

#[test]
fn held_verilog_is_bit_exact() {
    let seed = seed_for("held_verilog_is_bit_exact");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let tris = triangles(3, seed);
    let run = held_run(&tris, &mut StallPattern::new(seed, 0.4));
    for sim in [Simulator::Verilator, Simulator::Icarus] {
        if !sim.require("held_verilog_is_bit_exact") {
            continue;
        }
        let rep = differential(
            find("quadric-unit").unwrap(),
            &Options::new(),
            &run.rows,
            sim,
            &format!("quadric-hold-{sim:?}"),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        println!(
            "{sim:?} bit-exact: {} clocks × {} ports, {} held",
            rep.cycles, rep.ports, run.held
        );
    }
}
