//! Throughput of the Gouraud raster pipe (address block + BVI, `rtl::pipelines::gouraud_raster`):
//!
//! - printed once (clock counts of the simulated hardware, not timings): pixels per clock over
//!   the default scene (sphere rez 50, 400×400, light 90°) and over large triangles
//!   (≥ 1000 pixels), and the clocks each raster line costs beyond its pixels;
//! - the same figures through the four-triangle block (`rtl::pipelines::subdivision_raster`: four
//!   address lanes and a BVI each, SPEC §7), side by side with the single address block in
//!   one run: addresses per clock on the default scene and on triangles of ≥ 1000 pixels;
//! - measured by criterion: simulated clocks per second of the hand-stepped rust-hdl model of
//!   the two blocks together, and of the four-triangle pipe (throughput in elements = clocks).

mod common;
use common::default_scene;
use criterion::{Criterion, Throughput};
use golden::raster::walk;
use golden::shade::ShadeContext;
use golden::types::{ScreenTriangle, ScreenVertex};
use pipeline::axis::PipeStats;
use pipeline::gouraud::{clock_budget, Pipe, TriangleJob};
use pipeline::subdivision::{clock_budget as sub_budget, SubJob, SubPipe};

/// Seeded random triangles with at least 1000 pixels, extents up to 400.
fn large_triangles(n: usize) -> Vec<ScreenTriangle> {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut rnd = |m: i32| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % m as u64) as i32
    };
    let mut out = Vec::new();
    while out.len() < n {
        let v = [0; 3].map(|_| ScreenVertex {
            x: 100 + rnd(400),
            y: 100 + rnd(400),
            z: 0.0,
            normal: glam::DVec3::new(rnd(100) as f64 - 50.0, rnd(100) as f64 - 50.0, 100.0)
                .normalize(),
            uv: glam::DVec2::ZERO,
            w: 1.0,
        });
        let t = ScreenTriangle { v, frac: 0 };
        if walk(&t).pixel_count() >= 1000 {
            out.push(t);
        }
    }
    out
}

fn jobs(tris: &[ScreenTriangle], ctx: &ShadeContext) -> Vec<TriangleJob> {
    tris.iter()
        .filter_map(|t| TriangleJob::gouraud(t, ctx))
        .collect()
}

fn run(jobs: &[TriangleJob]) -> PipeStats {
    Pipe::new()
        .unwrap()
        .run(jobs, clock_budget(jobs), |_, _, _, _| {}, |_| {})
        .unwrap()
}

fn sub_jobs(tris: &[ScreenTriangle], ctx: &ShadeContext) -> Vec<SubJob> {
    tris.iter()
        .filter_map(|t| SubJob::gouraud(t, ctx))
        .collect()
}

fn sub_run(jobs: &[SubJob]) -> PipeStats {
    SubPipe::new()
        .unwrap()
        .run(jobs, sub_budget(jobs), |_, _, _, _| {}, |_| {})
        .unwrap()
}

/// Single address block vs four-triangle block, on the same triangles, in one run.
fn four_triangle_figures() {
    let (tris, ctx) = default_scene();
    let large = large_triangles(40);
    let lctx = ShadeContext::default();
    println!("addresses per clock, single address block vs four-triangle block (Gouraud pipes):");
    for (label, t, c) in [
        ("default scene", &tris, &ctx),
        ("large triangles (≥ 1000 px) back to back", &large, &lctx),
    ] {
        let a = run(&jobs(t, c));
        let b = sub_run(&sub_jobs(t, c));
        assert_eq!(
            a.pixels, b.pixels,
            "{label}: the two blocks cover different pixels"
        );
        println!(
            "  {label}: {} pixels; single {} clocks ({:.3}/clock), four-triangle {} clocks \
             ({:.3}/clock), ratio {:.2}×",
            a.pixels,
            a.clocks,
            a.pixels_per_clock(),
            b.clocks,
            b.pixels_per_clock(),
            a.clocks as f64 / b.clocks as f64
        );
    }
    let (mut worst, mut px, mut clk) = (f64::INFINITY, 0, 0);
    for t in &large {
        let s = sub_run(&sub_jobs(std::slice::from_ref(t), &lctx));
        worst = worst.min(s.pixels_per_clock());
        px += s.pixels;
        clk += s.clocks;
    }
    println!(
        "  large triangles one at a time (with the 4-clock latency each): {:.3} addresses/clock, \
         worst triangle {worst:.3}",
        px as f64 / clk as f64
    );
}

fn rows(tris: &[ScreenTriangle]) -> u64 {
    tris.iter().map(|t| walk(t).rows.len() as u64).sum()
}

fn figures() {
    let (tris, ctx) = default_scene();
    let scene_jobs = jobs(&tris, &ctx);
    let s = run(&scene_jobs);
    let r = rows(&tris);
    println!(
        "default scene: {} triangles, {} rows, {} pixels in {} clocks: {:.3} pixels/clock; \
         {:.3} clocks per raster line beyond its pixels (latency, empty lines, gaps)",
        s.triangles,
        r,
        s.pixels,
        s.clocks,
        s.pixels_per_clock(),
        (s.clocks - s.pixels) as f64 / r as f64
    );
    let large = large_triangles(40);
    let lj = jobs(&large, &ShadeContext::default());
    let (mut px, mut clk, mut lat, mut min_ppc) = (0, 0, 0, f64::INFINITY);
    let mut empty_rows = 0;
    for (t, j) in large.iter().zip(&lj) {
        let s = run(std::slice::from_ref(j));
        px += s.pixels;
        clk += s.clocks;
        lat += 4; // load → first pixel of the pipe
        min_ppc = min_ppc.min(s.pixels_per_clock());
        empty_rows += walk(t).rows.iter().filter(|r| r.len == 0).count() as u64;
    }
    let lr = rows(&large);
    println!(
        "large triangles (≥ 1000 px), one at a time: {px} pixels in {clk} clocks: {:.4} pixels/clock \
         (worst triangle {min_ppc:.4})",
        px as f64 / clk as f64,
    );
    println!(
        "line-start cost: {:.4} extra clocks per line with pixels; {empty_rows} of {lr} lines are \
         empty and cost 1 clock each; plus the 4-clock load latency per triangle",
        (clk - px - lat - empty_rows) as f64 / (lr - empty_rows) as f64,
    );
    let s = run(&lj);
    println!(
        "large triangles back to back: {} pixels in {} clocks: {:.4} pixels/clock",
        s.pixels,
        s.clocks,
        s.pixels_per_clock()
    );
}

fn bench(c: &mut Criterion) {
    figures();
    four_triangle_figures();
    let (tris, ctx) = default_scene();
    let scene_jobs = jobs(&tris, &ctx);
    let clocks = run(&scene_jobs).clocks;
    let mut g = c.benchmark_group("rtl_raster");
    g.sample_size(10);
    g.throughput(Throughput::Elements(clocks));
    g.bench_function("default_scene_clocks", |b| b.iter(|| run(&scene_jobs)));
    let sj = sub_jobs(&tris, &ctx);
    g.throughput(Throughput::Elements(sub_run(&sj).clocks));
    g.bench_function("four_triangle_default_scene_clocks", |b| {
        b.iter(|| sub_run(&sj))
    });
    g.finish();
}

criterion_without_plots!(bench);
