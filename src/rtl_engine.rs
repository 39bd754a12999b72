//! `--engine rtl`: the CLI's one call into the hardware, [`pipeline::render::render`] (every
//! method family behind one trait there), with its progress on an indicatif bar and its errors
//! as one line.

use anyhow::{anyhow, Result};
use golden::methods::Method;
use golden::shade::ShadeContext;
use golden::types::ScreenTriangle;
use indicatif::ProgressBar;

pub use pipeline::render::{
    max_channel_diff, Address, LitTop, Options as RtlBuild, Rendered as RtlRender, SetupOrder,
};

/// The methods the RTL engine renders ([`pipeline::render::methods`]).
pub fn rtl_methods() -> Vec<Method> {
    pipeline::render::methods()
}

/// An error naming the methods the RTL engine has, unless it has `m`.
pub fn check_rtl_method(m: Method) -> Result<()> {
    pipeline::render::check_method(m).map_err(|e| anyhow!(e))
}

/// Check the canvas and the vertex addresses against the hardware's 12 bits.
pub(crate) fn check_addresses(tris: &[ScreenTriangle], width: u32, height: u32) -> Result<()> {
    pipeline::render::check_addresses(tris, width, height).map_err(|e| anyhow!(e))
}

/// The Verilator designs rendering `methods` with `build` steps (to compile them before the
/// run, in parallel).
pub fn designs(methods: &[Method], build: RtlBuild) -> Result<Vec<verilated::Design>> {
    pipeline::render::designs(methods, &build).map_err(|e| anyhow!(e))
}

/// Render `tris` with `method` through the simulated hardware, with the default [`RtlBuild`]
/// (the textured methods read the built-in texture).
pub fn render_rtl(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
) -> Result<RtlRender> {
    let scene = pipeline::render::Scene {
        tris,
        ctx,
        width,
        height,
        texture: None,
    };
    render_scene(&scene, method, &RtlBuild::default(), progress)
}

/// Render `setup`'s triangles (its canvas, shading and texture) with `method` and the build
/// choices `build`: `progress` gets the number of set-up records (triangles, parents or lines)
/// and advances as the hardware finishes each.
pub fn render_rtl_with(
    setup: &crate::setup::Setup,
    method: Method,
    build: RtlBuild,
    progress: &ProgressBar,
) -> Result<RtlRender> {
    render_scene(&setup.scene(), method, &build, progress)
}

fn render_scene(
    scene: &pipeline::render::Scene,
    method: Method,
    build: &RtlBuild,
    progress: &ProgressBar,
) -> Result<RtlRender> {
    pipeline::render::render(scene, method, build, &mut |t| match t {
        pipeline::render::Tick::Total(n) => {
            progress.set_length(n);
            progress.set_position(0);
        }
        pipeline::render::Tick::Done(d) => progress.set_position(d),
    })
    .map_err(|e| anyhow!(e))
}
