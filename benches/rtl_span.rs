//! Throughput of the span units (issue 10) — the cos v accumulator
//! (`rtl::cos_v_accumulator`) and the fast two-point unit (`rtl::fast_unit`), fed the default
//! scene's spans (sphere rez 50, 400×400, light
//! 90°): per-span set-up by `golden::angular::span_setup` for H (the specular vector) and L,
//! spans loaded whenever `ready` is high.
//!
//! Printed once (clock counts of the simulated hardware, not timings): pixels per clock over
//! all spans and over spans of at least 16 pixels (the runs split each span at its midpoint),
//! and how often the symmetry point E lies inside a span (the thesis' split point: splitting
//! there would give two pixels per clock only for those) — then criterion measures simulated
//! clocks per second.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{DQuat, DVec3};
use golden::angular::span_setup;
use golden::cos_v_accumulator::SpanWords;
use golden::fast_unit::FastWords;
use golden::methods::span_end_normals;
use rtl::cos_v_accumulator::CosVAccumulator;
use rtl::fast_unit::{FastParams, FastUnit};
use rtl::registry::{BlockParams, Options};
use rtl::sim::Stepper;

/// The default scene's end normals per span, with its context.
fn span_normals() -> (Vec<(DVec3, DVec3, u32)>, golden::shade::ShadeContext) {
    let mesh = golden::scene::uv_sphere(50).unwrap();
    let cam = golden::scene::Camera::fit(&mesh, 400, 400, DQuat::IDENTITY);
    let tris = golden::scene::project(&mesh, &cam, 400, 400).unwrap();
    let ctx = golden::shade::ShadeContext {
        light: golden::scene::light_direction(90.0).unwrap(),
        ..Default::default()
    };
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

fn fast_figures() {
    let (n, ctx) = span_normals();
    let words: Vec<FastWords> = n
        .iter()
        .map(|&(na, nb, m)| FastWords::new(&golden::fast::span_setup(na, nb, ctx.half(), m)))
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
            ]
        } else {
            vec![0; 6]
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

fn bench(c: &mut Criterion) {
    figures();
    fast_figures();
    let s = spans(|c| c.half());
    let slice = &s[..s.len() / 4];
    let clocks = run(slice).0;
    let mut g = c.benchmark_group("rtl_span");
    g.sample_size(10);
    g.throughput(Throughput::Elements(clocks));
    g.bench_function("cos_v_accumulator_clocks", |b| b.iter(|| run(slice)));
    g.finish();
}

criterion_group! {
    name = benches;
    // No plots: the plotters backend needs fonts the CI image may lack.
    config = Criterion::default().without_plots();
    targets = bench
}
criterion_main!(benches);
