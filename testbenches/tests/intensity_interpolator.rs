//! Intensity interpolator BVI: RTL vs the golden f64 BVI every clock (valid exactly; the running
//! word within the format's bound, max and RMS; the 8-bit output exactly the saturated word and
//! within 1 LSB of the rounded golden value), then the whole raster pipe (address block + BVI)
//! on a tiled region and a back-face-culled sphere: every pixel written exactly once, colours
//! within 1 LSB of golden Gouraud.

use glam::{DQuat, DVec3};
use golden::raster::{edge_function_pixels, walk};
use golden::shade::ShadeContext;
use golden::testing::{runner, seed_for};
use golden::types::{Plane, ScreenTriangle, ScreenVertex};
use golden::units::intensity_interpolator::{additions, interpolate};
use pipeline::gouraud::{clock_budget, Pipe, TriangleJob};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use std::collections::HashMap;
use testbenches::units::address_block::{channel_planes, triangle_strategy, GoldenPixel};
use testbenches::units::intensity_interpolator::{check_bvi as run_bvi, check_words};

type Tri = [(i32, i32); 3];

fn tri(p: Tri) -> ScreenTriangle {
    ScreenTriangle::from_points(p)
}

/// Error statistics of the running words against the golden value (LSB units).
#[derive(Default)]
struct Stats {
    n: usize,
    sum_sq: f64,
    max_err: f64,
    /// Largest err / bound seen.
    max_ratio: f64,
}

/// Run the BVI on `tris` with per-vertex channel intensities `vals[t][vertex][channel]`
/// (harness: every clock; then every pixel against its own bound).
fn check_bvi(
    name: &str,
    seed: u64,
    tris: &[Tri],
    vals: &[[[f64; 3]; 3]],
    st: &mut Stats,
) -> Result<(), String> {
    let ts: Vec<ScreenTriangle> = tris.iter().map(|&p| tri(p)).collect();
    // Zero-area triangles have no plane; the hardware still walks them (no pixel): flat zero.
    let planes: Vec<[Plane; 3]> = ts
        .iter()
        .zip(vals)
        .map(|(t, v)| {
            std::array::from_fn(|c| {
                t.scalar_plane([v[0][c], v[1][c], v[2][c]])
                    .unwrap_or(Plane {
                        a: 0.0,
                        b: 0.0,
                        c: 0.0,
                    })
            })
        })
        .collect();
    let jobs: Vec<TriangleJob> = ts
        .iter()
        .zip(&planes)
        .map(|(t, p)| TriangleJob::new(t, p))
        .collect();
    let mut golden: Vec<GoldenPixel> = Vec::new();
    for (t, p) in ts.iter().zip(&planes) {
        let w = walk(t);
        let per: Vec<Vec<f64>> = p.iter().map(|pl| interpolate(&w, pl)).collect();
        for (k, adds) in additions(&w).into_iter().enumerate() {
            golden.push(([per[0][k], per[1][k], per[2][k]], adds));
        }
    }
    let context = || format!("triangles {tris:?} values {vals:?}");
    let report =
        run_bvi(name, seed, &jobs, &golden).map_err(|f| format!("{f}\n  {}", context()))?;
    let (max, rms, ratio) =
        check_words(&report, &golden).map_err(|e| format!("{e}; {}", context()))?;
    let n = golden.len() * 3;
    st.sum_sq += rms * rms * n as f64;
    st.n += n;
    st.max_err = st.max_err.max(max);
    st.max_ratio = st.max_ratio.max(ratio);
    Ok(())
}

fn report(name: &str, st: &Stats) {
    let rms = (st.sum_sq / st.n.max(1) as f64).sqrt();
    println!(
        "[{name}] {} channel samples: max |err| {:.3e} LSB, RMS {:.3e} LSB, max err/bound {:.3}",
        st.n, st.max_err, rms, st.max_ratio
    );
    assert!(st.max_ratio <= 1.0 && rms <= st.max_err);
}

/// Every named triangle of `golden/src/named_triangles.txt` but the address-limit corners with its intensities (flat colour,
/// both saturation ends, back-to-back runs), or a ramp reaching 0 and 255 where it gives none.
#[test]
fn named_edge_cases() {
    let mut st = Stats::default();
    let ramp = [[0.0; 3], [255.0; 3], [100.0, 50.0, 200.0]];
    // The `corner_` cases span the whole 4096² address range (millions of pixels each): the
    // golden walk checks them (golden/tests/raster.rs); the clock-by-clock RTL run skips them.
    let cases = golden::testing::named_triangles().into_iter();
    for case in cases.filter(|c| !c.name.starts_with("corner_")) {
        let vals = case.values.unwrap_or_else(|| vec![ramp; case.tris.len()]);
        check_bvi(case.name, seed_for(case.name), &case.tris, &vals, &mut st)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    report("bvi_named", &st);
}

#[test]
fn random_triangles_within_format_bound() {
    let name = "bvi_random";
    let seed = golden::testing::seed_for(name);
    let mut r = runner(name, 300);
    let st = std::cell::RefCell::new(Stats::default());
    let vals = prop::array::uniform3(prop::array::uniform3(-40.0..320.0f64));
    r.run(
        &prop::collection::vec((triangle_strategy(), vals), 1..4),
        |case| {
            let (tris, vals): (Vec<Tri>, Vec<[[f64; 3]; 3]>) = case.into_iter().unzip();
            check_bvi(name, seed, &tris, &vals, &mut st.borrow_mut()).map_err(TestCaseError::fail)
        },
    )
    .unwrap();
    report(name, &st.borrow());
}

/// Pixels written by the pipe for `tris` under `ctx`: (x, y) → list of colours.
fn pipe_render(tris: &[ScreenTriangle], ctx: &ShadeContext) -> HashMap<(u32, u32), Vec<[u8; 3]>> {
    let jobs: Vec<TriangleJob> = tris
        .iter()
        .filter_map(|t| TriangleJob::gouraud(t, ctx))
        .collect();
    let mut px: HashMap<(u32, u32), Vec<[u8; 3]>> = HashMap::new();
    Pipe::new()
        .unwrap()
        .run(
            &jobs,
            clock_budget(&jobs),
            |_, x, y, rgb| px.entry((x, y)).or_default().push(rgb),
            |_| {},
        )
        .expect("pipe finished within its clock budget");
    px
}

/// Every written colour within 1 LSB of golden Gouraud of the triangle that wrote it (the
/// pipe writes the triangles in order, so a pixel's k-th colour belongs to its k-th owner).
fn check_colours(
    tris: &[ScreenTriangle],
    ctx: &ShadeContext,
    px: &HashMap<(u32, u32), Vec<[u8; 3]>>,
) -> usize {
    let mut max_diff = 0;
    let mut seen: HashMap<(u32, u32), usize> = HashMap::new();
    for t in tris {
        let Some(g) = golden::shading::gouraud::setup(t, ctx) else {
            continue;
        };
        for (x, y) in edge_function_pixels(t) {
            let key = (x as u32, y as u32);
            let k = seen.entry(key).or_default();
            let got = px[&key][*k];
            *k += 1;
            let want = golden::shading::gouraud::pixel(&g, x, y);
            for c in 0..3 {
                let d = (got[c] as i32 - want[c] as i32).unsigned_abs() as usize;
                assert!(
                    d <= 1,
                    "pixel ({x}, {y}) channel {c}: rtl {} golden {}",
                    got[c],
                    want[c]
                );
                max_diff = max_diff.max(d);
            }
        }
    }
    max_diff
}

#[test]
fn tiled_region_written_exactly_once() {
    // A jittered grid of triangles over the rectangle [16, 16 + 8·17] × [9, 9 + 6·13]: every
    // pixel whose centre is inside the rectangle belongs to exactly one triangle.
    let (x0, y0, nx, ny, s) = (16, 9, 8, 6, (17, 13));
    let mut r = runner("tiled_region", 4);
    r.run(
        &proptest::collection::vec((-5..=5i32, -4..=4i32, any::<bool>()), (nx + 1) * (ny + 1)),
        |jit| {
            let p = |i: usize, j: usize| {
                let (jx, jy, _) = jit[j * (nx + 1) + i];
                let x = x0 + i as i32 * s.0 + if i == 0 || i == nx { 0 } else { jx };
                let y = y0 + j as i32 * s.1 + if j == 0 || j == ny { 0 } else { jy };
                (x, y)
            };
            let mut tris = Vec::new();
            for j in 0..ny {
                for i in 0..nx {
                    let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
                    let t = if jit[j * (nx + 1) + i].2 {
                        [[a, b, c], [a, c, d]]
                    } else {
                        [[a, b, d], [b, c, d]]
                    };
                    for q in t {
                        let v = q.map(|(x, y)| ScreenVertex {
                            x,
                            y,
                            z: 0.0,
                            normal: DVec3::new(x as f64, y as f64, 100.0).normalize(),
                            uv: glam::DVec2::ZERO,
                            w: 1.0,
                        });
                        tris.push(ScreenTriangle { v, frac: 0 });
                    }
                }
            }
            let ctx = ShadeContext::default();
            let px = pipe_render(&tris, &ctx);
            let (x1, y1) = (x0 + nx as i32 * s.0, y0 + ny as i32 * s.1);
            for y in y0..y1 {
                for x in x0..x1 {
                    let n = px.get(&(x as u32, y as u32)).map_or(0, |v| v.len());
                    prop_assert_eq!(n, 1, "pixel ({}, {}) written {} times", x, y, n);
                }
            }
            prop_assert_eq!(
                px.len(),
                ((x1 - x0) * (y1 - y0)) as usize,
                "pixels outside the region"
            );
            check_colours(&tris, &ctx, &px);
            Ok(())
        },
    )
    .unwrap();
}

/// Sphere through the pipe: the per-pixel write counts equal the edge-function reference's,
/// and the colours are within 1 LSB of golden Gouraud. Returns (pixels, pixels written more
/// than once).
fn sphere(rez: u32, (w, h): (u32, u32), rotation: DQuat) -> (usize, usize) {
    let mesh = golden::scene::uv_sphere(rez).unwrap();
    let cam = golden::scene::Camera::fit(&mesh, w, h, rotation);
    let tris = golden::scene::project(&mesh, &cam, w, h).unwrap();
    let ctx = ShadeContext {
        light: golden::scene::light_direction(60.0).unwrap(),
        ..ShadeContext::default()
    };
    let px = pipe_render(&tris, &ctx);
    let mut reference: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &tris {
        for (x, y) in edge_function_pixels(t) {
            *reference.entry((x as u32, y as u32)).or_default() += 1;
        }
    }
    let counts: HashMap<(u32, u32), usize> = px.iter().map(|(&k, v)| (k, v.len())).collect();
    assert_eq!(
        counts, reference,
        "write counts differ from the edge-function rasterizer"
    );
    let max_diff = check_colours(&tris, &ctx, &px);
    let multi = counts.values().filter(|&&n| n > 1).count();
    println!(
        "sphere rez {rez} {w}x{h}: {} triangles, {} pixels, {multi} written more than once, \
         max |rtl − golden| {max_diff} LSB",
        tris.len(),
        px.len()
    );
    (px.len(), multi)
}

/// The default scene's sphere (rez 50, 400×400, seen from the front): back-face culled, every
/// covered pixel written exactly once.
#[test]
fn culled_sphere_written_exactly_once_within_one_lsb() {
    let (n, multi) = sphere(50, (400, 400), DQuat::IDENTITY);
    assert!(n > 100_000);
    assert_eq!(multi, 0, "pixels written more than once");
}

/// A tilted sphere: rounding vertex addresses can fold a front face over its neighbour at the
/// silhouette, so a few pixels legitimately receive two fragments; the RTL must write exactly
/// the reference's counts (checked inside `sphere`), no more, no fewer.
#[test]
fn tilted_sphere_write_counts_match_reference() {
    let (n, multi) = sphere(24, (160, 120), DQuat::from_rotation_x(0.4));
    assert!(n > 9_000 && multi < 20, "{n} pixels, {multi} folds");
}

// ---------------------------------------------------------------------------------------------
// Exported Verilog of the BVI and of the whole pipe: Yosys, Icarus differential, mutants.

use flow::synth::check_and_synth;
use flow::tools::{self, Tool};
use flow::verilog::{Mutant, Simulator};
use proptest::strategy::ValueTree;
use testbenches::registry::assert_mutants_caught;
use testbenches::units::intensity_interpolator::{bvi_rows, pipe_rows};

fn block(name: &str) -> &'static dyn testbenches::registry::Entry {
    testbenches::registry::find(name).unwrap()
}

/// Seeded random triangles with random vertex intensities (−40..320, so both saturation ends
/// are reached), plus a few named ones.
fn differential_jobs(n: usize) -> Vec<TriangleJob> {
    let name = "bvi_differential";
    let mut r = runner(name, 1);
    let s = (
        triangle_strategy(),
        prop::array::uniform3(prop::array::uniform3(-40.0..320.0f64)),
    );
    let ramp = [[0.0; 3], [255.0; 3], [100.0, 50.0, 200.0]];
    let mut cases: Vec<(Tri, [[f64; 3]; 3])> = vec![
        ([(3, 1), (40, 7), (11, 30)], ramp),
        (
            [(0, 0), (100, 0), (0, 100)],
            [
                [-100.0, 400.0, 128.0],
                [400.0, -100.0, 128.0],
                [128.0, 128.0, 600.0],
            ],
        ),
        ([(0, 0), (4095, 4094), (4094, 4093)], ramp),
        ([(0, 0), (1, 1), (2, 2)], ramp),
    ];
    for _ in 0..n {
        cases.push(s.new_tree(&mut r).unwrap().current());
    }
    cases
        .iter()
        .map(|(p, v)| {
            let t = tri(*p);
            TriangleJob::new(&t, &channel_planes(&t, v))
        })
        .collect()
}

/// Beyond the registry's generic Yosys check (clean, no SB_MAC16 in the BVI or the pipe):
/// the BVI keeps its nine 32-bit registers per channel (RG1–RG5, SH1–SH3, SH5).
#[test]
fn yosys_keeps_the_bvi_registers() {
    if !tools::require(&[Tool::Yosys], "yosys_keeps_the_bvi_registers") {
        return;
    }
    let v = block("intensity-interpolator")
        .verilog(&rtl::core::registry::Options::new())
        .unwrap();
    let rep = check_and_synth(&v, "intensity_interpolator", "yosys-bvi")
        .unwrap_or_else(|e| panic!("{e}"));
    print!("{rep}");
    assert!(rep.ffs() >= 3 * 9 * 32, "nine 32-bit registers per channel");
}

/// The BVI (20 seeded triangles' streams) and the raster pipe (10) against their exported
/// Verilog under Icarus, bit-exact every clock.
#[test]
fn bvi_and_pipe_differential_icarus() {
    if !Simulator::Icarus.require("bvi_and_pipe_differential_icarus") {
        return;
    }
    let runs = [
        ("intensity-interpolator", bvi_rows(&differential_jobs(20)).0),
        ("gouraud-raster", pipe_rows(&differential_jobs(10))),
    ];
    for (name, rows) in runs {
        let rep = flow::blocks::differential(
            block(name),
            &rtl::core::registry::Options::new(),
            &rows,
            Simulator::Icarus,
            &format!("diff-{name}"),
        )
        .unwrap_or_else(|e| panic!("{name}: {e} (seed {})", seed_for("bvi_differential")));
        println!(
            "{name} bit-exact over {} clocks × {} ports; Icarus ran {:?}",
            rep.cycles, rep.ports, rep.verilog_sim_time
        );
    }
}

#[test]
fn broken_bvi_export_is_caught() {
    if !Simulator::Icarus.require("broken_bvi_export_is_caught") {
        return;
    }
    let (rows, _) = bvi_rows(&differential_jobs(10));
    // Each site occurs once per channel module; the red channel's is mutated.
    #[rustfmt::skip]
    let mutants = [
        Mutant { what: "adder: + → -", module: "intensity_interpolator__chan__0", from: "s_line = rg4$q + rg3$q", to: "s_line = rg4$q - rg3$q" },
        Mutant { what: "carry selects RG1", module: "intensity_interpolator__chan__0", from: "sum = s_long", to: "sum = s_short" },
        Mutant { what: "saturation high: bits 30..24 → 30..25", module: "intensity_interpolator__chan__0", from: "|rg4$q[(24)+:(7)]", to: "|rg4$q[(25)+:(6)]" },
    ];
    assert_mutants_caught(block("intensity-interpolator"), &rows, &mutants);
}
