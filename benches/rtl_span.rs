//! Throughput of the span units (issue 10) — the cos v accumulator
//! (`rtl::units::cos_v_accumulator`) and the fast two-point unit (`rtl::units::fast_unit`), fed the default
//! scene's spans (sphere rez 50, 400×400, light
//! 90°): per-span set-up by `golden::shading::angular::span_setup` for H (the specular vector) and L,
//! spans loaded whenever `ready` is high.
//!
//! Printed once (clock counts of the simulated hardware, not timings):
//! - per unit: pixels per clock over all spans and over spans of at least 16 pixels (the runs
//!   split each span at its midpoint), and how often the symmetry point E lies inside a span
//!   (the thesis' split point: splitting there would give two pixels per clock only for those);
//! - per span pipeline top (`angular-pipeline`, `fast-pipeline` with the fit set,
//!   `quadric-unit`), the whole default scene through the span front end: fragments per clock,
//!   the clocks beyond Σ(⌊m/2⌋ + 1) per line (the per-line overhead), and the rate on the
//!   lines of ≥ 16 pixels inside that stream (each line's clocks counted from the previous
//!   line's last fragment, so whatever the hardware spends between lines is included);
//! - the cubic pipeline's clocks per pixel with each Horner variant, through its ports and
//!   through its stream top `cubic-stream` (`tready` high: the same fragments, the clocks of a
//!   12-word record per line), in one run;
//! - the thesis' average triangle (SPEC §11; both the 78-pixel triangle the deltas give and the
//!   100-pixel scaled one): clocks from its load to its last fragment and its steady-state
//!   clocks, through each span top and through the one-pixel-per-clock lit pipeline and the
//!   Gouraud pipe, beside the sources' Pentium M cycle counts (the README's table).
//!
//! Then criterion measures simulated clocks per second.

mod common;
use common::default_scene;
use criterion::{Criterion, Throughput};
use glam::DVec3;
use golden::methods::span_end_normals;
use golden::methods::Method;
use golden::shade::ShadeContext;
use golden::shading::angular::span_setup;
use golden::types::ScreenTriangle;
use golden::units::cos_v_accumulator::SpanWords;
use golden::units::fast_unit::FastWords;
use pipeline::gouraud::{clock_budget, Pipe, TriangleJob};
use pipeline::lit::{lit_clock_budget, LitJob, LitPipe, ShadingRegs};
use pipeline::span::{span_clock_budget, span_jobs, span_schedule, SpanJob, SpanPipe};
use rtl::core::registry::{BlockParams, Options};
use rtl::core::sim::Stepper;
use rtl::units::cos_v_accumulator::CosVAccumulator;
use rtl::units::fast_unit::{FastParams, FastUnit};

/// The default scene's end normals per span, with its context.
fn span_normals() -> (Vec<(DVec3, DVec3, u32)>, golden::shade::ShadeContext) {
    let (tris, ctx) = default_scene();
    let mut out = Vec::new();
    for t in &tris {
        let Some(plane) = t.normal_plane() else {
            continue;
        };
        let w = golden::raster::walk(t);
        for row in w.rows.iter().filter(|r| r.len > 0) {
            if let Some((na, nb)) = span_end_normals(&plane, row) {
                out.push((na, nb, row.len - 1));
            }
        }
    }
    (out, ctx)
}

/// The default scene's spans for the unit vector `x` (cos v accumulator words).
fn spans(x_of: impl Fn(&golden::shade::ShadeContext) -> DVec3) -> Vec<SpanWords> {
    let (n, ctx) = span_normals();
    let x = x_of(&ctx);
    n.iter()
        .map(|&(na, nb, m)| SpanWords::new(&span_setup(na, nb, x, m)))
        .collect()
}

/// Run `spans` through the fast unit back to back; (clocks, pixels).
fn run_fast(spans: &[FastWords]) -> (u64, u64) {
    let p = FastParams::from_options(&Options::new()).unwrap();
    let mut st = Stepper::new(FastUnit::new(&p)).unwrap();
    let mut out = vec![0u64; 8];
    let (mut clocks, mut pixels, mut next, mut lasts) = (0u64, 0u64, 0usize, 0usize);
    let m48 = (1u64 << 48) - 1;
    while lasts < spans.len() {
        let row = if st.dut().ready.val() && next < spans.len() {
            let w = &spans[next];
            next += 1;
            vec![
                1,
                w.b as u64 & 0xFFFF_FFFF,
                w.h as u64 & 0xFFFF_FFFF,
                w.g as u64 & 0xFFFF_FFFF,
                w.d0 as u64 & m48,
                w.dd as u64 & m48,
                w.m as u64,
                0, // hold: never here
            ]
        } else {
            vec![0; 8]
        };
        st.step(&row, &mut out).unwrap();
        clocks += 1;
        pixels += out[1] + out[4];
        lasts += out[7] as usize;
    }
    (clocks, pixels)
}

fn fast_figures() {
    let (n, ctx) = span_normals();
    let words: Vec<FastWords> = n
        .iter()
        .map(|&(na, nb, m)| {
            FastWords::new(&golden::shading::fast::span_setup(na, nb, ctx.half(), m))
        })
        .collect();
    let long: Vec<FastWords> = words.iter().copied().filter(|w| w.m >= 15).collect();
    let (c, p) = run_fast(&words);
    let (cl, pl) = run_fast(&long);
    println!(
        "fast unit, default scene, X = H: {} spans, {p} pixels in {c} clocks ({:.3} pixels/clock); \
         spans ≥ 16 pixels: {pl} pixels in {cl} clocks ({:.3} pixels/clock)",
        words.len(),
        p as f64 / c as f64,
        pl as f64 / cl as f64
    );
}

/// Run `spans` back to back; (clocks, pixels).
fn run(spans: &[SpanWords]) -> (u64, u64) {
    let mut st = Stepper::new(CosVAccumulator::default()).unwrap();
    let mut out = vec![0u64; 8];
    let (mut clocks, mut pixels, mut next, mut lasts) = (0u64, 0u64, 0usize, 0usize);
    while lasts < spans.len() {
        let row = if st.dut().ready.val() && next < spans.len() {
            let w = &spans[next];
            next += 1;
            vec![
                1,
                (w.p as u64) & 0xFFFF_FFFF,
                (w.q as u64) & 0xFFFF_FFFF,
                w.d as u64,
                w.cos_beta,
                w.m as u64,
                0, // hold: never here
            ]
        } else {
            vec![0; 7]
        };
        st.step(&row, &mut out).unwrap();
        clocks += 1;
        pixels += out[1] + out[4];
        lasts += out[7] as usize;
    }
    (clocks, pixels)
}

fn figures() {
    for (name, x_of) in [
        (
            "H",
            (|c: &golden::shade::ShadeContext| c.half())
                as fn(&golden::shade::ShadeContext) -> DVec3,
        ),
        ("L", |c: &golden::shade::ShadeContext| c.light),
    ] {
        let all = spans(x_of);
        let long: Vec<SpanWords> = all.iter().copied().filter(|w| w.m >= 15).collect();
        // The symmetry point E (argument 0) lies inside the span when ψ ≥ 0 and φ − ψ > 0.
        let inside = |v: &[SpanWords]| v.iter().filter(|w| w.p >= 0 && w.q > 0).count();
        let (c, p) = run(&all);
        let (cl, pl) = run(&long);
        println!(
            "cos v accumulator, default scene, X = {name}: {} spans, {p} pixels in {c} clocks \
             ({:.3} pixels/clock; E inside {} spans); spans ≥ 16 pixels: {} spans, {pl} pixels in \
             {cl} clocks ({:.3} pixels/clock; E inside {})",
            all.len(),
            p as f64 / c as f64,
            inside(&all),
            long.len(),
            pl as f64 / cl as f64,
            inside(&long),
        );
    }
}

/// (clocks, pixels, spans, Σ(⌊m/2⌋ + 1), latency) of `tris` through the span top for `method`.
fn run_top(
    method: Method,
    tris: &[ScreenTriangle],
    ctx: &ShadeContext,
    keep: impl Fn(&SpanJob) -> bool,
) -> (u64, u64, usize, u64, usize) {
    run_top_with(method, false, tris, ctx, keep)
}

/// [`run_top`] with the cubic's Horner variant.
fn run_top_with(
    method: Method,
    pipelined: bool,
    tris: &[ScreenTriangle],
    ctx: &ShadeContext,
    keep: impl Fn(&SpanJob) -> bool,
) -> (u64, u64, usize, u64, usize) {
    let mut pipe = SpanPipe::with_horner(method, pipelined).unwrap();
    let spans: Vec<SpanJob> = tris
        .iter()
        .filter(|t| t.depth_plane().is_some())
        .enumerate()
        .flat_map(|(i, t)| span_jobs(t, i, pipe.kind(), ctx).unwrap())
        .filter(|s| keep(s))
        .collect();
    let regs = ShadingRegs::of(ctx).unwrap();
    let st = pipe
        .run(&spans, &regs, span_clock_budget(&spans), |_| {}, |_| {})
        .unwrap();
    let (span_clocks, pixels) = span_schedule(&spans);
    assert_eq!(st.pixels, pixels);
    (
        st.clocks,
        st.pixels,
        spans.len(),
        span_clocks,
        pipe.latency(),
    )
}

/// Per line of a whole-scene run through the top for `method`, from the fragments' clock
/// stamps: (pixels, clocks since the previous line's last fragment). Lines of ≥ 16 pixels
/// measured this way include whatever the hardware spends between lines (the quadric tracker's
/// moves).
fn line_clocks(method: Method, tris: &[ScreenTriangle], ctx: &ShadeContext) -> Vec<(u64, u64)> {
    let mut pipe = SpanPipe::new(method).unwrap();
    let spans: Vec<SpanJob> = tris
        .iter()
        .filter(|t| t.depth_plane().is_some())
        .enumerate()
        .flat_map(|(i, t)| span_jobs(t, i, pipe.kind(), ctx).unwrap())
        .collect();
    let regs = ShadingRegs::of(ctx).unwrap();
    // Lines come out in order; a line ends with the fragment of its last pixel.
    let mut lines: Vec<(u64, u64)> = Vec::new(); // (pixels, last clock)
    let mut key = None;
    pipe.run(
        &spans,
        &regs,
        span_clock_budget(&spans),
        |f| {
            let k = (f.triangle, f.y);
            if key != Some(k) {
                key = Some(k);
                lines.push((0, 0));
            }
            let l = lines.last_mut().unwrap();
            l.0 += 1;
            l.1 = f.clock;
        },
        |_| {},
    )
    .unwrap();
    let mut prev = 0;
    lines
        .into_iter()
        .map(|(p, last)| {
            let c = last - prev;
            prev = last;
            (p, c)
        })
        .collect()
}

fn pipeline_figures() {
    let (tris, ctx) = default_scene();
    for m in [Method::Angular, Method::FastFit, Method::Quadric] {
        let (c, p, n, sc, lat) = run_top(m, &tris, &ctx, |_| true);
        let lines = line_clocks(m, &tris, &ctx);
        let long: Vec<_> = lines.iter().filter(|l| l.0 >= 16).collect();
        let (lp, lc) = long.iter().fold((0, 0), |(p, c), l| (p + l.0, c + l.1));
        println!(
            "span pipeline {m}, default scene: {p} fragments in {c} clocks ({:.3}/clock); {n} \
             lines, {sc} line clocks + latency {lat}: {:.3} clocks per line beyond its own; lines \
             ≥ 16 pixels in the stream: {} lines, {lp} fragments in {lc} clocks ({:.3}/clock)",
            p as f64 / c as f64,
            (c - sc - lat as u64) as f64 / n as f64,
            long.len(),
            lp as f64 / lc as f64,
        );
    }
}

/// The thesis' average triangle (SPEC §11) with normals from a sphere-like cap, n = 256.
fn average_triangle(points: [(i32, i32); 3]) -> ScreenTriangle {
    let mut t = ScreenTriangle::from_points(points);
    let normals = [
        DVec3::new(-0.2, -0.3, 0.93),
        DVec3::new(-0.4, 0.1, 0.91),
        DVec3::new(0.3, 0.35, 0.89),
    ];
    for (v, n) in t.v.iter_mut().zip(normals) {
        v.normal = n.normalize();
    }
    t
}

fn average_triangle_table() {
    let ctx = ShadeContext {
        material: golden::shade::Material {
            shininess: 256,
            ..Default::default()
        },
        ..ShadeContext::default()
    };
    let regs = ShadingRegs::of(&ctx).unwrap();
    println!("| triangle | pixels | method | hardware | clocks, load → last fragment | clocks per triangle, streamed |");
    println!("|---|---|---|---|---|---|");
    for (label, pts) in [
        (
            "A (17,10) B (10,18) C (26,22)",
            [(17, 10), (10, 18), (26, 22)],
        ),
        (
            "scaled (20,10) (12,19) (30,24)",
            [(20, 10), (12, 19), (30, 24)],
        ),
    ] {
        let t = average_triangle(pts);
        let px = golden::raster::walk(&t).pixel_count();
        let tris = [t];
        // Gouraud pipe and the lit pipeline: one triangle, then the steady state (10 copies).
        let g = |k: usize| {
            let jobs: Vec<TriangleJob> = (0..k)
                .map(|_| TriangleJob::gouraud(&t, &ctx).unwrap())
                .collect();
            Pipe::new()
                .unwrap()
                .run(&jobs, clock_budget(&jobs), |_, _, _, _| {}, |_| {})
                .unwrap()
                .clocks
        };
        let l = |k: usize| {
            let jobs: Vec<LitJob> = (0..k).map(|_| LitJob::new(&t).unwrap().unwrap()).collect();
            LitPipe::new(Method::NormalizerFit)
                .unwrap()
                .run(&jobs, &regs, lit_clock_budget(&jobs), |_| {}, |_| {})
                .unwrap()
                .clocks
        };
        let (g1, g10) = (g(1), g(10));
        println!(
            "| {label} | {px} | gouraud | raster pipe (address block + BVI) | {g1} | {:.1} |",
            (g10 - g1) as f64 / 9.0
        );
        let (l1, l10) = (l(1), l(10));
        println!("| {label} | {px} | normalizer-fit, brdf-k*, bump | lit pixel pipeline | {l1} | {:.1} |", (l10 - l1) as f64 / 9.0);
        for (m, pipelined, hw) in [
            (Method::Angular, false, "angular-pipeline"),
            (Method::FastFit, false, "fast-pipeline"),
            (Method::Quadric, false, "quadric-unit"),
            (
                Method::Cubic,
                false,
                "cubic-pipeline, serial Horner (fig. 2.6)",
            ),
            (Method::Cubic, true, "cubic-pipeline, pipelined Horner"),
        ] {
            let (c1, ..) = run_top_with(m, pipelined, &tris, &ctx, |_| true);
            let ten: Vec<ScreenTriangle> = std::iter::repeat_n(t, 10).collect();
            let (c10, ..) = run_top_with(m, pipelined, &ten, &ctx, |_| true);
            println!(
                "| {label} | {px} | {m} | {hw} | {c1} | {:.1} |",
                (c10 - c1) as f64 / 9.0
            );
        }
    }
}

/// The Horner unit's clocks per pixel (fig. 2.6 serial, pipelined) over the default scene,
/// through `cubic-pipeline`'s ports and through `cubic-stream`.
fn horner_figures() {
    let (tris, ctx) = default_scene();
    for pipelined in [false, true] {
        let (c, p, n, sc, _) = run_top_with(Method::Cubic, pipelined, &tris, &ctx, |_| true);
        let mut stream = SpanPipe::cubic_stream(pipelined).unwrap();
        let spans: Vec<SpanJob> = tris
            .iter()
            .filter(|t| t.depth_plane().is_some())
            .enumerate()
            .flat_map(|(i, t)| span_jobs(t, i, stream.kind(), &ctx).unwrap())
            .collect();
        let st = stream
            .run(
                &spans,
                &ShadingRegs::default(),
                span_clock_budget(&spans),
                |_| {},
                |_| {},
            )
            .unwrap();
        assert_eq!(st.pixels, p);
        let short = spans
            .iter()
            .filter(|s| {
                s.clocks()
                    < 1 + rtl::stream::layout::payload_words(&rtl::stream::layout::CUBIC_LINE)
                        as u64
            })
            .count();
        println!(
            "cubic-stream ({} Horner), default scene, tready high: {} fragments in {} clocks ({:.3} fragments/clock; the ports {:.3}; ratio {:.3}); {short} of {} lines take fewer clocks than their 12-word record",
            if pipelined { "pipelined" } else { "serial" },
            st.pixels,
            st.clocks,
            st.pixels as f64 / st.clocks as f64,
            p as f64 / c as f64,
            c as f64 / st.clocks as f64,
            spans.len()
        );
        println!(
            "cubic pipeline ({} Horner), default scene: {p} fragments in {c} clocks ({:.3} clocks \
             per pixel; {n} lines, {sc} line clocks + {} tail)",
            if pipelined {
                "pipelined"
            } else {
                "serial, fig. 2.6"
            },
            c as f64 / p as f64,
            c - sc,
        );
    }
}

fn bench(c: &mut Criterion) {
    figures();
    fast_figures();
    pipeline_figures();
    horner_figures();
    average_triangle_table();
    let s = spans(|c| c.half());
    let slice = &s[..s.len() / 4];
    let clocks = run(slice).0;
    let mut g = c.benchmark_group("rtl_span");
    g.sample_size(10);
    g.throughput(Throughput::Elements(clocks));
    g.bench_function("cos_v_accumulator_clocks", |b| b.iter(|| run(slice)));
    g.finish();
}

criterion_without_plots!(bench);
