//! The textured pipeline's runs shared by `benches/rtl_texture.rs` and `tests/rtl_texture.rs`
//! (the test includes this file by path): a built-in scene, its jobs in the engine's order, and
//! one run through a build under Verilator.

use pipeline::lit::ShadingRegs;
use pipeline::textured::{TexJob, TexRegs, TexturedPipe};
use rtl::pipelines::textured_pipeline::TexCoord;
use shadecore::setup::{build, SceneArgs, Setup};

/// The built-in scene `name` with the default arguments.
pub fn scene(name: &str) -> Setup {
    build(&SceneArgs {
        scene: name.into(),
        ..SceneArgs::default()
    })
    .unwrap()
}

/// The jobs of `s` for the build `coord`, in the engine's balanced order, with their mean w.
pub fn jobs_of(s: &Setup, coord: TexCoord) -> Vec<(TexJob, f64)> {
    let v: Vec<(TexJob, f64)> = s
        .tris
        .iter()
        .filter(|t| t.depth_plane().is_some())
        .filter_map(|t| {
            TexJob::of(t, &s.texture, coord)
                .unwrap()
                .map(|j| (j, t.v.iter().map(|v| v.w).sum::<f64>() / 3.0))
        })
        .collect();
    let order = pipeline::lit::balanced_order(&v.iter().map(|(j, _)| j.lit).collect::<Vec<_>>());
    order.iter().map(|&i| v[i].clone()).collect()
}

/// Fragments, clocks, and the clock of the first fragment (the first load in clock 0), for
/// `jobs` through the build `build` (`1`, `2`, `4`: the additive build's k; `quadratic`,
/// `bezier`); then the clocks of the texture's load before them.
pub fn run(s: &Setup, jobs: &[TexJob], build: &str) -> (u64, u64, u64, u64) {
    let regs = ShadingRegs::of(&s.ctx).unwrap();
    let t = TexRegs::of(&s.ctx, &s.texture).unwrap();
    let mut pipe = TexturedPipe::on(build, flow::engine::Sim::fastest(), false).unwrap();
    let loaded = pipe.load_texture(&s.texture, &regs, &t).unwrap();
    let mut first = None;
    let st = pipe
        .run(
            jobs,
            &regs,
            &t,
            u64::MAX,
            |f| {
                first.get_or_insert(f.clock);
            },
            |_| {},
        )
        .unwrap();
    (st.pixels, st.clocks, first.unwrap_or(0), loaded)
}
