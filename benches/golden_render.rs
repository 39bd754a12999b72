//! Golden render of the default scene (sphere, rez 50, n 50, light 90°, 400×400): pixels per
//! second for the reference and each method. Run with `cargo bench --bench golden_render`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use golden::methods::Method;
use golden::render::render;
use shadecore::setup::{build, SceneArgs};

fn bench(c: &mut Criterion) {
    let setup = build(&SceneArgs::default()).expect("default scene");
    let (w, h) = (setup.width, setup.height);
    let fragments: u64 = render(&setup.tris, Method::Reference, &setup.ctx, w, h)
        .fragments
        .iter()
        .map(|&f| f as u64)
        .sum();
    let mut g = c.benchmark_group("golden_render_default_scene");
    g.throughput(Throughput::Elements(fragments));
    g.sample_size(20);
    for m in std::iter::once(Method::Reference).chain(Method::ALL_NON_REFERENCE.iter().copied()) {
        g.bench_function(m.name(), |b| {
            b.iter(|| render(&setup.tris, m, &setup.ctx, w, h))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
