//! Address block: RTL vs cycle-accurate golden model every clock, and the emitted pixels vs
//! the golden walk and the edge-function rasterizer (same set, no duplicates, same order and
//! step types), over named edge cases and seeded random triangles.

use golden::raster::{edge_function_pixels, walk};
use golden::testing::runner;
use golden::testing::seed_for;
use golden::types::ScreenTriangle;
use golden::units::address_block::{stream_pixels, AddressOutputs, AddressSetup};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use rtl::units::address_block::AddressBlock;
use std::collections::HashSet;
use testbenches::units::address_block::{check as check_rtl, triangle_strategy};

type Tri = [(i32, i32); 3];

fn tri(p: Tri) -> ScreenTriangle {
    ScreenTriangle::from_points(p)
}

/// Check one stream of triangles: RTL vs model every clock (harness), then the pixels.
/// Returns the clock count.
fn check(name: &str, seed: u64, tris: &[Tri]) -> Result<usize, String> {
    let ts: Vec<ScreenTriangle> = tris.iter().map(|&p| tri(p)).collect();
    let setups: Vec<AddressSetup> = ts.iter().map(AddressSetup::new).collect();
    let (_, out) =
        check_rtl(name, seed, &setups).map_err(|f| format!("{f}\n  triangles {tris:?}"))?;
    check_pixels(&ts, &out).map_err(|e| format!("{name}: {e} (seed {seed}) {tris:?}"))?;
    Ok(out.len())
}

/// The RTL's pixel stream against the walks and the edge-function reference.
fn check_pixels(ts: &[ScreenTriangle], out: &[AddressOutputs]) -> Result<(), String> {
    // Split the stream at `done` markers: one segment per triangle.
    let mut segs: Vec<&[AddressOutputs]> = Vec::new();
    let mut start = 0;
    for (i, o) in out.iter().enumerate() {
        if o.done {
            segs.push(&out[start..=i]);
            start = i + 1;
        }
    }
    if segs.len() != ts.len() {
        return Err(format!(
            "{} done markers for {} triangles",
            segs.len(),
            ts.len()
        ));
    }
    for (t, seg) in ts.iter().zip(segs) {
        let got = stream_pixels(seg);
        let w = walk(t);
        if got != w.pixels() {
            return Err(format!("pixel stream differs from the walk of {t:?}"));
        }
        let set: HashSet<(i32, i32)> = got.iter().map(|p| (p.x, p.y)).collect();
        if set.len() != got.len() {
            return Err("duplicate address".into());
        }
        let reference: HashSet<(i32, i32)> = edge_function_pixels(t).into_iter().collect();
        if set != reference {
            return Err("pixel set differs from the edge-function rasterizer".into());
        }
        let rows = seg.iter().filter(|o| o.row_start).count();
        if rows != w.rows.len() {
            return Err(format!("{rows} row starts for {} rows", w.rows.len()));
        }
    }
    Ok(())
}

/// Every named triangle of `golden/src/named_triangles.txt` but the address-limit corners (each case walked back to back).
#[test]
fn named_edge_cases() {
    // The `corner_` cases span the whole 4096² address range (millions of pixels each): the
    // golden walk checks them (golden/tests/raster.rs); the clock-by-clock RTL run skips them.
    let cases = golden::testing::named_triangles().into_iter();
    for case in cases.filter(|c| !c.name.starts_with("corner_")) {
        let name = case.name;
        let clocks = check(name, seed_for(name), &case.tris).unwrap_or_else(|e| panic!("{e}"));
        println!("{name}: {clocks} clocks");
    }
}

#[test]
fn random_triangles_match_model_and_walk() {
    let name = "address_block_random";
    let mut r = runner(name, 300);
    let seed = golden::testing::seed_for(name);
    let clocks = std::cell::Cell::new(0usize);
    r.run(&prop::collection::vec(triangle_strategy(), 1..4), |tris| {
        clocks.set(clocks.get() + check(name, seed, &tris).map_err(TestCaseError::fail)?);
        Ok(())
    })
    .unwrap();
    println!("[{name}] {} clocks simulated", clocks.get());
}

// ---------------------------------------------------------------------------------------------
// Exported Verilog: Yosys, Icarus/Verilator differential (bit-exact every clock), mutants.

use flow::tools;
use flow::verilog::{Mutant, Simulator};
use proptest::strategy::ValueTree;
use testbenches::registry::assert_mutants_caught;
use testbenches::units::address_block::stimulus;

fn block(name: &str) -> &'static dyn testbenches::registry::Entry {
    testbenches::registry::find(name).unwrap()
}

/// The differential stimulus: the named cases and `n` seeded random triangle streams, walked
/// back to back in one run (so triangle overlap and every handshake path are exercised).
fn differential_setups(n: usize) -> Vec<AddressSetup> {
    let name = "address_block_differential";
    let mut r = runner(name, 1);
    let s = prop::collection::vec(triangle_strategy(), 1..4);
    let mut tris: Vec<Tri> = vec![
        [(0, 0), (10, 0), (0, 10)],
        [(2, 3), (30, 3), (17, 20)],
        [(17, 3), (2, 20), (30, 20)],
        [(40, 1), (3, 7), (11, 30)],
        [(0, 0), (1, 1), (2, 2)],
        [(0, 0), (1, 0), (0, 1)],
        [(0, 0), (1, 3), (1, 4)],
        [(0, 0), (4095, 1), (0, 2)],
        [(4095, 0), (0, 3), (3000, 7)],
        [(0, 0), (4095, 4095), (4095, 4094)],
    ];
    for _ in 0..n {
        tris.extend(s.new_tree(&mut r).unwrap().current());
    }
    tris.iter().map(|&p| AddressSetup::new(&tri(p))).collect()
}

fn differential_run(sim: Simulator, n: usize, tag: &str) {
    if !tools::require(sim.tools(), tag) {
        return;
    }
    let rows = stimulus(&differential_setups(n)).rows;
    let rep = flow::blocks::differential(
        block("address-block"),
        &rtl::core::registry::Options::new(),
        &rows,
        sim,
        tag,
    )
    .unwrap_or_else(|e| panic!("{e} (seed {})", seed_for("address_block_differential")));
    println!(
        "{sim:?}: bit-exact over {} clocks × {} ports; ran {:?}",
        rep.cycles, rep.ports, rep.verilog_sim_time
    );
    assert_eq!(rep.cycles, rows.len());
}

#[test]
fn address_block_differential_icarus() {
    differential_run(Simulator::Icarus, 10, "diff-address-block-icarus");
}

/// The same differential check under Verilator (the shared testbench reads `$fscanf` into
/// temporaries, which Verilator 5.006 needs to re-evaluate the design's inputs).
#[test]
fn address_block_differential_verilator() {
    differential_run(Simulator::Verilator, 40, "diff-address-block-verilator");
}

#[test]
fn broken_address_block_export_is_caught() {
    if !Simulator::Icarus.require("broken_address_block_export_is_caught") {
        return;
    }
    let rows = stimulus(&differential_setups(5)).rows;
    #[rustfmt::skip]
    let mutants = [
        Mutant { what: "CTx step: +1 → +2", module: "", from: "p_x$d = p_x$q + 12'h1", to: "p_x$d = p_x$q + 12'h2" },
        Mutant { what: "row length: B_o − B_w → B_w − B_o", module: "", from: "rec_len = other$bound - working$bound", to: "rec_len = working$bound - other$bound" },
        Mutant { what: "third-edge switch: == → !=", module: "", from: "e_at_switch$d = e_y_next2 == e_y_switch$q", to: "e_at_switch$d = e_y_next2 != e_y_switch$q" },
        Mutant { what: "ready: & → |", module: "", from: "ready_now = ~e_busy$q & ~wait_first$q", to: "ready_now = ~e_busy$q | ~wait_first$q" },
    ];
    assert_mutants_caught(block("address-block"), &rows, &mutants);
}

/// `hold` (the stall the fragment stream's back-pressure uses): the RTL equals the cycle model
/// every clock under a seeded stall pattern (a quarter of the clocks, and long stretches), and
/// the events with the held clocks removed are exactly the events of the run without stalls.
#[test]
fn held_address_block_emits_the_same_events_with_gaps() {
    use testbenches::harness::{run_rows, CheckSpec, Compare, Expected};
    use testbenches::stall::StallPattern;
    use testbenches::units::address_block::{address_run, address_run_held, triangle_jobs};
    let seed = seed_for("held_address_block_emits_the_same_events_with_gaps");
    let (jobs, _) = triangle_jobs(seed, 40);
    let (rows0, exp0, _) = address_run(&jobs);
    let mut stalls = StallPattern::new(seed, 0.3);
    let (rows, exp, _) = address_run_held(&jobs, &mut stalls);
    let spec = CheckSpec {
        name: "address-block-held".into(),
        seed,
        compare: vec![Compare::Exact; 9],
    };
    let report =
        run_rows(AddressBlock::default, &spec, &rows, &exp).unwrap_or_else(|f| panic!("{f}"));
    // Events: clocks with valid, row_start or done (x, y, step, line_start, carry, done).
    let events = |out: &[Vec<u64>]| -> Vec<Vec<u64>> {
        out.iter()
            .filter(|r| r[1] != 0 || r[6] != 0 || r[8] != 0)
            .map(|r| r[1..].to_vec())
            .collect()
    };
    let word = |e: &Vec<Expected>| -> Vec<u64> {
        e.iter()
            .map(|x| match x {
                Expected::Word(w) => *w,
                _ => unreachable!("address block expectations are exact words"),
            })
            .collect()
    };
    let plain: Vec<Vec<u64>> = exp0.iter().map(word).collect();
    assert_eq!(events(&report.outputs), events(&plain));
    assert!(
        stalls.stalled > rows0.len() / 4,
        "stalls happened: {} of {}",
        stalls.stalled,
        rows.len()
    );
    println!(
        "seed {seed}: {} events; {} clocks without stalls, {} with {} stalled",
        events(&plain).len(),
        rows0.len(),
        rows.len(),
        stalls.stalled
    );
}

// ---------------------------------------------------------------------------------------------
// Sub-pixel vertices (`address-block-subpixel`).

/// The sub-pixel block on seeded triangles with 4 fraction bits (and the named cases of
/// `subpixel_triangles`): every port every clock against the model, the pixel stream against
/// the sub-pixel walk, and each pixel set against the edge-function reference; and the events
/// per clock of the same triangles' integer walk (vertices rounded to whole pixels) through
/// `address-block`, for the fragments-per-clock comparison.
#[test]
fn subpixel_triangles_match_model_walk_and_reference() {
    use golden::raster::{edge_function_pixels_of, walk_subpixel};
    use golden::SUBPIXEL_BITS;
    use testbenches::units::address_block::{check_subpixel, subpixel_triangles};
    let name = "address_block_subpixel";
    let seed = seed_for(name);
    let tris = subpixel_triangles(seed, 300);
    let setups: Vec<AddressSetup> = tris.iter().map(AddressSetup::subpixel).collect();
    let (_, out) = check_subpixel(name, seed, &setups).unwrap_or_else(|f| panic!("{f}"));
    let mut segs = out.split_inclusive(|o| o.done);
    let mut pixels = 0;
    for t in &tris {
        let seg = segs.next().unwrap_or_else(|| panic!("no `done` for {t:?}"));
        let got = stream_pixels(seg);
        assert_eq!(
            got,
            walk_subpixel(t).pixels(),
            "{t:?}: stream against the walk"
        );
        let set: HashSet<(i32, i32)> = got.iter().map(|p| (p.x, p.y)).collect();
        let reference: HashSet<(i32, i32)> = edge_function_pixels_of(t).into_iter().collect();
        assert_eq!(set.len(), got.len(), "{t:?}: an address twice");
        assert_eq!(set, reference, "{t:?}: against the edge-function reference");
        pixels += got.len();
    }
    assert!(segs.next().is_none(), "more `done` events than triangles");
    // The integer block on the same triangles with vertices rounded to whole pixels.
    let half = 1 << (SUBPIXEL_BITS - 1);
    let rounded: Vec<AddressSetup> = tris
        .iter()
        .map(|t| {
            AddressSetup::new(&tri(t
                .v
                .map(|(x, y)| ((x + half) >> SUBPIXEL_BITS, (y + half) >> SUBPIXEL_BITS))))
        })
        .collect();
    let (_, int_out) = check_rtl(name, seed, &rounded).unwrap_or_else(|f| panic!("{f}"));
    let int_pixels = int_out.iter().filter(|o| o.valid).count();
    // An event is a pixel or an empty row's one clock: the walk's work, one per clock at most.
    let events = |o: &[AddressOutputs]| o.iter().filter(|o| o.valid || o.row_start).count();
    let (ev, int_ev) = (events(&out), events(&int_out));
    assert!(ev <= out.len() && int_ev <= int_out.len());
    println!(
        "[{name}] sub-pixel: {pixels} pixels, {ev} events in {} clocks ({:.3} events per clock); \
         integer (vertices rounded): {int_pixels} pixels, {int_ev} events in {} clocks ({:.3})",
        out.len(),
        ev as f64 / out.len() as f64,
        int_out.len(),
        int_ev as f64 / int_out.len() as f64
    );
}
