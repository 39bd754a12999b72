//! Throughput of the textured pixel pipeline (`rtl::pipelines::textured_pipeline`, issue 39's
//! figures):
//!
//! - printed once (clock counts of the simulated hardware under Verilator, not timings):
//!   fragments per clock of `texture=additive` for k = 1, 2 and 4 and of the per-line builds
//!   (`texture=quadratic`, `texture=bezier`, their line records pushed whenever `line_ready` is
//!   high), on the default scene (the textured sphere) and on `plane`, whose nearest and
//!   farthest (minified) fifths of triangles by mean w are run apart; and the clocks from the
//!   first load to the first fragment. The texture is loaded first (one texel per clock) and
//!   not counted. The triangles go in the engine's balanced order, back to back.
//! - measured by criterion: simulated clocks per second of the k = 4 build over a tenth of the
//!   default scene, a fresh Verilator model per iteration, its construction and the texture's
//!   load included (throughput in elements = clocks: the load's 65 536 and the triangles').
//!
//! The same runs are checked (a larger k never costs clocks, the k = 4 build takes the clocks
//! of the pipeline's twin) by the full-tier test `tests/rtl_texture.rs`.

mod common;

use common::texture::{jobs_of, run, scene};
use criterion::{Criterion, Throughput};
use pipeline::textured::TexJob;
use rtl::pipelines::textured_pipeline::TexCoord;

fn figures(name: &str) {
    let s = scene(name);
    let all = jobs_of(&s, TexCoord::Additive);
    let mut by_w = all.clone();
    by_w.sort_by(|a, b| a.1.total_cmp(&b.1));
    let fifth = by_w.len() / 5;
    let jobs = |v: &[(TexJob, f64)]| v.iter().map(|(j, _)| j.clone()).collect::<Vec<_>>();
    let mut sets = vec![("all", jobs(&all))];
    if name == "plane" {
        sets.push(("nearest fifth by mean w", jobs(&by_w[..fifth])));
        sets.push((
            "farthest fifth by mean w",
            jobs(&by_w[by_w.len() - fifth..]),
        ));
    }
    for (label, jobs) in &sets {
        let mut line = format!(
            "textured-pipeline, {name} ({label}, {} triangles):",
            jobs.len()
        );
        for k in ["1", "2", "4"] {
            let (p, c, first, _) = run(&s, jobs, k);
            line += &format!(
                " k = {k}: {p} fragments in {c} clocks, {:.3} per clock, first fragment in clock \
                 {first};",
                p as f64 / c as f64
            );
        }
        println!("{line}");
    }
    for coord in [TexCoord::Quadratic, TexCoord::Bezier] {
        let lined: Vec<TexJob> = jobs_of(&s, coord).into_iter().map(|(j, _)| j).collect();
        let (p, c, first, _) = run(&s, &lined, coord.name());
        println!(
            "textured-pipeline texture={}, {name} (all, {} line records): {p} fragments in {c} \
             clocks, {:.3} per clock, first fragment in clock {first}",
            coord.name(),
            lined.iter().map(|j| j.lines.len()).sum::<usize>(),
            p as f64 / c as f64
        );
    }
}

fn bench(c: &mut Criterion) {
    // The default scene (the textured sphere), then the ground plane.
    figures("sphere");
    figures("plane");
    let s = scene("sphere");
    let all: Vec<TexJob> = jobs_of(&s, TexCoord::Additive)
        .into_iter()
        .map(|(j, _)| j)
        .collect();
    let slice = &all[..all.len() / 10];
    let (_, clocks, _, loaded) = run(&s, slice, "4");
    let mut g = c.benchmark_group("rtl_texture");
    g.sample_size(10);
    g.throughput(Throughput::Elements(loaded + clocks));
    g.bench_function("textured_pipeline_clocks", |b| {
        b.iter(|| run(&s, slice, "4"))
    });
    g.finish();
}

criterion_without_plots!(bench);
