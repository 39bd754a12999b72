//! Throughput of the lit pixel pipeline (`rtl::pipelines::pixel_pipeline`):
//!
//! - printed once (clock counts of the simulated hardware, not timings): fragments per clock
//!   over the default scene (sphere rez 50, 400×400, light 90°) for each build, the latency
//!   from load to the first fragment of one triangle, the wall time of each default-scene
//!   RTL render and its simulated clocks per second, beside the Gouraud raster pipe's in the
//!   same run (a ratio);
//! - measured by criterion: simulated clocks per second of the whole pipeline over a slice
//!   of the scene (throughput in elements = clocks);
//! - the AXI4-Stream top `pixel-stream` on the default scene with `tready` high: fragments per
//!   clock beside `pixel-pipeline`'s, in mesh order and in the driver's balanced order
//!   (`SHADECORE_BENCH_ONLY=stream` prints only this).

mod common;
use common::default_scene;
use std::time::Instant;

use criterion::{Criterion, Throughput};
use golden::methods::Method;
use golden::types::ScreenTriangle;
use pipeline::gouraud::{clock_budget, Pipe, TriangleJob};
use pipeline::lit::{lit_clock_budget, LitJob, LitPipe, ShadingRegs, LIT_METHODS};

fn lit_jobs(tris: &[ScreenTriangle]) -> Vec<LitJob> {
    tris.iter()
        .filter_map(|t| LitJob::new(t).unwrap())
        .collect()
}

fn run(method: Method, jobs: &[LitJob], regs: &ShadingRegs) -> pipeline::axis::PipeStats {
    LitPipe::new(method)
        .unwrap()
        .run(jobs, regs, lit_clock_budget(jobs), |_| {}, |_| {})
        .unwrap()
}

fn figures() {
    let (tris, ctx) = default_scene();
    let jobs = lit_jobs(&tris);
    let regs = ShadingRegs::of(&ctx).unwrap();
    // Latency: one triangle, clocks from the load to the first fragment.
    let mut pipe = LitPipe::new(Method::NormalizerFit).unwrap();
    let mut first = None;
    let one = &jobs[jobs.len() / 2..jobs.len() / 2 + 1];
    pipe.run(
        one,
        &regs,
        lit_clock_budget(one),
        |f| {
            first.get_or_insert(f.clock);
        },
        |_| {},
    )
    .unwrap();
    println!(
        "pixel pipeline latency: load in clock 0, first fragment shown in clock {} (registry: {})",
        first.unwrap(),
        rtl::pipelines::pixel_pipeline::PixelPipeline::LATENCY
    );
    let g_jobs: Vec<TriangleJob> = tris
        .iter()
        .filter_map(|t| TriangleJob::gouraud(t, &ctx))
        .collect();
    let t0 = Instant::now();
    let g = Pipe::new()
        .unwrap()
        .run(&g_jobs, clock_budget(&g_jobs), |_, _, _, _| {}, |_| {})
        .unwrap();
    let g_rate = g.clocks as f64 / t0.elapsed().as_secs_f64();
    println!(
        "gouraud raster pipe, default scene: {} fragments in {} clocks ({:.4}/clock), {:.0} clocks/s",
        g.pixels,
        g.clocks,
        g.pixels_per_clock(),
        g_rate
    );
    for m in LIT_METHODS {
        let t0 = Instant::now();
        let s = run(m, &jobs, &regs);
        let secs = t0.elapsed().as_secs_f64();
        let rate = s.clocks as f64 / secs;
        println!(
            "pixel pipeline {m}, default scene: {} fragments in {} clocks ({:.4} fragments/clock); \
             {secs:.1} s wall, {rate:.0} clocks/s ({:.3}× the Gouraud pipe's rate)",
            s.pixels,
            s.clocks,
            s.pixels_per_clock(),
            rate / g_rate
        );
    }
}

/// The AXI4-Stream top on the default scene with `m_axis_tready` always high: fragments per
/// clock beside `pixel-pipeline`'s in the same run, with the triangles in mesh order and in the
/// driver's balanced order (`pipeline::lit::balanced_order`, the default of `render`), from
/// the rust-hdl simulation (checked clock for clock against the twin that paces the producer).
fn stream_figures() {
    use rtl::core::registry::BlockParams;
    let (tris, ctx) = default_scene();
    let mesh = lit_jobs(&tris);
    let regs = ShadingRegs::of(&ctx).unwrap();
    let o = pipeline::lit::method_options(Method::NormalizerFit).unwrap();
    let p = rtl::pipelines::pixel_pipeline::PipelineParams::from_options(&o).unwrap();
    let balanced: Vec<LitJob> = pipeline::lit::balanced_order(&mesh)
        .iter()
        .map(|&i| mesh[i])
        .collect();
    for (label, jobs) in [("mesh order", &mesh), ("balanced order", &balanced)] {
        let words = pipeline::lit::scene_words(jobs, &regs);
        let run = testbenches::stream::pixel_stream::drive(
            &p,
            &words,
            1,
            0.0,
            &mut testbenches::stall::StallPattern::never(),
            1,
        );
        let t0 = Instant::now();
        let out = testbenches::registry::find("pixel-stream")
            .unwrap()
            .simulate(&o, &run.rows)
            .unwrap();
        let secs = t0.elapsed().as_secs_f64();
        assert!(out == run.outputs, "rust-hdl and the twin agree");
        let fragments = run.beats.iter().filter(|b| b.pixel).count();
        // From the first word to the last beat.
        let last = out.iter().rposition(|r| r[1] != 0).unwrap() + 1;
        let plain = run_plain(jobs, &regs);
        println!(
            "pixel-stream normalizer-fit, default scene, {label}, tready high: {fragments} fragments in {last} clocks \
             ({:.4} fragments/clock; pixel-pipeline in the same order {:.4} in {} clocks, ratio {:.3}); {} set-up words \
             for {} triangles; address block held {} clocks; {:.0} clocks/s",
            fragments as f64 / last as f64,
            plain.pixels_per_clock(),
            plain.clocks,
            (fragments as f64 / last as f64) / plain.pixels_per_clock(),
            words.len(),
            jobs.len(),
            run.held,
            out.len() as f64 / secs
        );
    }
}

fn run_plain(jobs: &[LitJob], regs: &ShadingRegs) -> pipeline::axis::PipeStats {
    run(Method::NormalizerFit, jobs, regs)
}

fn bench(c: &mut Criterion) {
    // `SHADECORE_BENCH_ONLY=stream` prints only the stream top's figure.
    if std::env::var("SHADECORE_BENCH_ONLY").as_deref() == Ok("stream") {
        stream_figures();
        return;
    }
    figures();
    stream_figures();
    let (tris, ctx) = default_scene();
    let jobs = lit_jobs(&tris);
    let slice = &jobs[..jobs.len() / 10];
    let regs = ShadingRegs::of(&ctx).unwrap();
    let clocks = run(Method::NormalizerFit, slice, &regs).clocks;
    let mut g = c.benchmark_group("rtl_lit");
    g.sample_size(10);
    g.throughput(Throughput::Elements(clocks));
    g.bench_function("pixel_pipeline_clocks", |b| {
        b.iter(|| run(Method::NormalizerFit, slice, &regs))
    });
    g.finish();
}

criterion_without_plots!(bench);
