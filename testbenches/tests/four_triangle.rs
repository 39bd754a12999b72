//! Four-triangle address block: RTL vs its cycle model every clock (every port exact), and the
//! lanes' pixels vs the golden sub-triangle walks and the parent's edge-function pixel set
//! (no address twice, none lost), over named cases, seeded random parents of every family, a
//! tiled region and a back-face-culled sphere; a broken export must be caught.

use golden::raster::edge_function_pixels;
use golden::testing::{runner, seed_for};
use golden::types::{ScreenTriangle, SubpixelTriangle};
use golden::units::address_block::AddressOutputs;
use golden::units::four_triangle::{self as g4, FourOutputs, FourTriangleSetup, LANES};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestCaseError;
use std::collections::{HashMap, HashSet};
use testbenches::units::address_block::{subpixel_triangles, triangle_strategy};
use testbenches::units::four_triangle::{
    check as check_rtl, check_subpixel, run_reactive, stimulus,
};

type Tri = [(i32, i32); 3];

/// Each lane's stream cut at its `done` markers: `segments[lane][parent]`.
fn lane_segments(
    out: &[FourOutputs],
    parents: usize,
) -> Result<Vec<Vec<Vec<AddressOutputs>>>, String> {
    let mut segs = vec![Vec::new(); LANES];
    for (k, seg) in segs.iter_mut().enumerate() {
        let mut cur = Vec::new();
        for o in out {
            cur.push(o.lanes[k]);
            if o.lanes[k].done {
                seg.push(std::mem::take(&mut cur));
            }
        }
        if seg.len() != parents {
            return Err(format!(
                "lane {k}: {} done markers for {parents} parents",
                seg.len()
            ));
        }
    }
    Ok(segs)
}

/// Every lane's pixels against the golden sub-triangle walk, and each parent's union against
/// its edge-function pixel set, with no address twice.
fn check_pixels(ts: &[ScreenTriangle], out: &[FourOutputs]) -> Result<(), String> {
    let segs = lane_segments(out, ts.len())?;
    for (i, t) in ts.iter().enumerate() {
        let subs = g4::subdivide_subpixel(&SubpixelTriangle::of(t));
        let mut seen = HashSet::new();
        for k in 0..LANES {
            let got = golden::units::address_block::stream_pixels(&segs[k][i]);
            let expect = subs
                .map(|s| golden::raster::walk_subpixel(&s[k]).pixels())
                .unwrap_or_default();
            if got != expect {
                return Err(format!(
                    "parent {i} lane {k}: stream differs from the sub-triangle walk"
                ));
            }
            for p in &got {
                if !seen.insert((p.x, p.y)) {
                    return Err(format!(
                        "parent {i}: address {:?} emitted twice",
                        (p.x, p.y)
                    ));
                }
            }
        }
        let reference: HashSet<(i32, i32)> = edge_function_pixels(t).into_iter().collect();
        if seen != reference {
            return Err(format!(
                "parent {i}: the lanes cover {} pixels, the parent has {} ({} lost, {} extra)",
                seen.len(),
                reference.len(),
                reference.difference(&seen).count(),
                seen.difference(&reference).count()
            ));
        }
    }
    Ok(())
}

fn check(name: &str, seed: u64, tris: &[Tri]) -> Result<usize, String> {
    let ts: Vec<ScreenTriangle> = tris
        .iter()
        .map(|&p| ScreenTriangle::from_points(p))
        .collect();
    let setups: Vec<FourTriangleSetup> = ts.iter().map(FourTriangleSetup::new).collect();
    let (_, out) =
        check_rtl(name, seed, &setups).map_err(|f| format!("{f}\n  parents {tris:?}"))?;
    check_pixels(&ts, &out).map_err(|e| format!("{name}: {e} (seed {seed}) {tris:?}"))?;
    Ok(out.len())
}

#[test]
fn named_edge_cases() {
    let cases = golden::testing::named_triangles().into_iter();
    for case in cases.filter(|c| !c.name.starts_with("corner_")) {
        let name = case.name;
        let clocks = check(name, seed_for(name), &case.tris).unwrap_or_else(|e| panic!("{e}"));
        println!("{name}: {clocks} clocks");
    }
    // Odd and even extents, both orientations, flat tops and bottoms, one-pixel parents.
    let extra: Vec<Tri> = vec![
        [(0, 0), (11, 0), (0, 11)],
        [(0, 0), (10, 0), (0, 10)],
        [(0, 0), (11, 0), (11, 11)],
        [(5, 0), (0, 11), (11, 11)],
        [(3, 1), (40, 7), (11, 30)],
        [(40, 1), (3, 7), (11, 30)],
        [(1, 1), (2, 4), (5, 2)],
        [(0, 0), (1, 0), (0, 1)],
        [(0, 0), (1, 1), (2, 2)],
        [(0, 0), (4095, 1), (0, 2)],
        [(4095, 0), (0, 3), (3000, 7)],
        [(0, 0), (4095, 4095), (4095, 4094)],
    ];
    check("four_triangle_named", 0, &extra).unwrap_or_else(|e| panic!("{e}"));
}

/// `four-triangle-subpixel` (21-bit lanes): sub-pixel parents (the address block's sub-pixel
/// families, 150 seeded after the named edge cases) every port exact against the sub-pixel
/// model every clock, each lane's pixels the sub-triangle's walk at 5 fraction bits, the four
/// tiling the parent's edge-function pixel set at 4; and integer parents walk through it
/// exactly as through the integer block.
#[test]
fn subpixel_parents_through_the_subpixel_block() {
    use golden::raster::{edge_function_pixels_of, walk_subpixel};
    let name = "four_triangle_subpixel";
    let seed = seed_for(name);
    let parents = subpixel_triangles(seed, 150);
    let setups: Vec<FourTriangleSetup> = parents.iter().map(FourTriangleSetup::subpixel).collect();
    let (_, out) = check_subpixel(name, seed, &setups).unwrap_or_else(|f| panic!("{f}"));
    let segs = lane_segments(&out, parents.len()).unwrap_or_else(|e| panic!("{e}"));
    let mut pixels = 0;
    for (i, t) in parents.iter().enumerate() {
        let subs = g4::subdivide_subpixel(t);
        let mut seen = HashSet::new();
        for k in 0..LANES {
            let got = golden::units::address_block::stream_pixels(&segs[k][i]);
            let want = subs
                .map(|s| walk_subpixel(&s[k]).pixels())
                .unwrap_or_default();
            assert_eq!(got, want, "parent {i} {t:?} lane {k}: against the walk");
            for p in &got {
                assert!(seen.insert((p.x, p.y)), "parent {i}: {p:?} twice");
            }
        }
        let parent: HashSet<(i32, i32)> = edge_function_pixels_of(t).into_iter().collect();
        assert_eq!(
            seen, parent,
            "parent {i} {t:?}: the lanes against the parent"
        );
        pixels += seen.len();
    }
    assert!(pixels > 5_000, "{pixels} pixels");
    // Integer parents: the same outputs from both blocks, clock for clock.
    let ints: Vec<FourTriangleSetup> = parents
        .iter()
        .take(60)
        .map(|t| {
            FourTriangleSetup::new(&ScreenTriangle::from_points(
                t.v.map(|(x, y)| (x >> 4, y >> 4)),
            ))
        })
        .collect();
    let (_, a) = check_rtl("four_triangle_integer", seed, &ints).unwrap_or_else(|f| panic!("{f}"));
    let (_, b) = check_subpixel("four_triangle_integer_on_subpixel", seed, &ints)
        .unwrap_or_else(|f| panic!("{f}"));
    assert_eq!(
        a, b,
        "integer parents: the sub-pixel block differs from the integer one"
    );
}

#[test]
fn random_parents_match_model_walks_and_parent_set() {
    let name = "four_triangle_random";
    let mut r = runner(name, 200);
    let seed = seed_for(name);
    let clocks = std::cell::Cell::new(0usize);
    r.run(&prop::collection::vec(triangle_strategy(), 1..4), |tris| {
        clocks.set(clocks.get() + check(name, seed, &tris).map_err(TestCaseError::fail)?);
        Ok(())
    })
    .unwrap();
    println!("[{name}] {} clocks simulated", clocks.get());
}

/// Pixel write counts of a list of parents through the RTL (its own `ready` pacing).
fn rtl_counts(tris: &[ScreenTriangle]) -> (HashMap<(u32, u32), usize>, usize) {
    let setups: Vec<FourTriangleSetup> = tris.iter().map(FourTriangleSetup::new).collect();
    let out = run_reactive(&setups, 10_000_000, None).unwrap();
    let mut counts: HashMap<(u32, u32), usize> = HashMap::new();
    for o in &out {
        for l in o.lanes.iter().filter(|l| l.valid) {
            *counts.entry((l.x, l.y)).or_default() += 1;
        }
    }
    (counts, out.len())
}

/// A jittered grid of triangles tiling a 96×64 rectangle: through the block every pixel of the
/// rectangle is written exactly once.
#[test]
fn tiled_region_every_pixel_exactly_once() {
    let name = "four_triangle_tiled";
    let seed = seed_for(name);
    println!("[{name}] seed {seed} (replay with SHADECORE_SEED={seed})");
    let mut r = golden::testing::seeded_runner(seed);
    let (nx, ny, cell) = (8, 6, 12);
    let jitter = (-4..=4i32, -4..=4i32);
    let mut grid = vec![vec![(0, 0); nx + 1]; ny + 1];
    for (j, row) in grid.iter_mut().enumerate() {
        for (i, p) in row.iter_mut().enumerate() {
            let (dx, dy) = jitter.new_tree(&mut r).unwrap().current();
            let inner = |k: usize, n: usize| k > 0 && k < n;
            *p = (
                (i * cell) as i32 + if inner(i, nx) { dx } else { 0 },
                (j * cell) as i32 + if inner(j, ny) { dy } else { 0 },
            );
        }
    }
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (
                grid[j][i],
                grid[j][i + 1],
                grid[j + 1][i],
                grid[j + 1][i + 1],
            );
            tris.push(ScreenTriangle::from_points([a, b, d]));
            tris.push(ScreenTriangle::from_points([a, d, c]));
        }
    }
    let (counts, clocks) = rtl_counts(&tris);
    let area = nx * cell * ny * cell;
    assert_eq!(counts.len(), area, "pixels covered");
    assert!(counts.values().all(|&n| n == 1), "a pixel written twice");
    assert!(counts
        .keys()
        .all(|&(x, y)| (x as usize) < nx * cell && (y as usize) < ny * cell));
    println!(
        "[{name}] {} parents, {area} pixels each written once, {clocks} clocks ({:.2} addresses/clock)",
        tris.len(),
        area as f64 / clocks as f64
    );
}

/// The default scene's sphere at 200×200 (back-face culled): the write counts equal the
/// single address block's (the edge-function rasterizer's), every covered pixel once.
#[test]
fn culled_sphere_every_pixel_exactly_once() {
    let mesh = golden::scene::uv_sphere(24).unwrap();
    let cam = golden::scene::Camera::fit(&mesh, 200, 200, glam::DQuat::IDENTITY);
    let tris = golden::scene::project(&mesh, &cam, 200, 200).unwrap();
    let (counts, clocks) = rtl_counts(&tris);
    let mut reference: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &tris {
        for (x, y) in edge_function_pixels(t) {
            *reference.entry((x as u32, y as u32)).or_default() += 1;
        }
    }
    assert_eq!(
        counts, reference,
        "write counts differ from the single address block's"
    );
    assert!(counts.values().all(|&n| n == 1), "a pixel written twice");
    println!(
        "sphere rez 24 200x200: {} triangles, {} pixels each once, {clocks} clocks",
        tris.len(),
        counts.len()
    );
}

// ---------------------------------------------------------------------------------------------
// Exported Verilog: a broken export must be caught (the bit-exact runs themselves are the
// registry's generic tests).

use flow::verilog::{Mutant, Simulator};
use testbenches::registry::assert_mutants_caught;

#[test]
fn broken_four_triangle_export_is_caught() {
    if !Simulator::Icarus.require("broken_four_triangle_export_is_caught") {
        return;
    }
    let tris: Vec<FourTriangleSetup> = [
        [(3, 1), (40, 7), (11, 30)],
        [(40, 1), (3, 7), (11, 30)],
        [(0, 0), (11, 0), (0, 11)],
        [(5, 0), (0, 11), (11, 11)],
    ]
    .iter()
    .map(|&p| FourTriangleSetup::new(&ScreenTriangle::from_points(p)))
    .collect();
    let rows = stimulus(&tris).0;
    let b = testbenches::registry::find("four-triangle").unwrap();
    let v = b.verilog(&rtl::core::registry::Options::new()).unwrap();
    for m in ["lane3$a_f = t_f", "all_ready = "] {
        assert!(v.contains(m), "mutant anchor {m:?} not in the export");
    }
    #[rustfmt::skip]
    let mutants = [
        Mutant { what: "middle lane's other edge: third triple → adjacent", module: "", from: "lane3$a_f = t_f", to: "lane3$a_f = a_f" },
        Mutant { what: "load taken when any lane is ready", module: "", from: "all_ready = lane0$ready & lane1$ready", to: "all_ready = lane0$ready | lane1$ready" },
    ];
    assert_mutants_caught(b, &rows, &mutants);
}
