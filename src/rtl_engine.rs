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

/// Render `tris` with `method` through the simulated hardware, with the default [`RtlBuild`].
pub fn render_rtl(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
) -> Result<RtlRender> {
    render_rtl_with(
        tris,
        method,
        ctx,
        width,
        height,
        progress,
        RtlBuild::default(),
    )
}

/// [`render_rtl`] with the build choices `build`: `progress` gets the number of set-up records
/// (triangles, parents or lines) and advances as the hardware finishes each. The textured
/// methods read the built-in texture.
pub fn render_rtl_with(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
    build: RtlBuild,
) -> Result<RtlRender> {
    render_rtl_textured(
        tris,
        method,
        ctx,
        golden::texture::Texture::builtin(),
        width,
        height,
        progress,
        build,
    )
}

/// [`render_rtl_with`] with the texture the textured methods read.
#[allow(clippy::too_many_arguments)]
pub fn render_rtl_textured(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    texture: &golden::texture::Texture,
    width: u32,
    height: u32,
    progress: &ProgressBar,
    build: RtlBuild,
) -> Result<RtlRender> {
    let scene = pipeline::render::Scene {
        tris,
        ctx,
        width,
        height,
        texture: Some(texture),
    };
    pipeline::render::render(&scene, method, &build, &mut |t| match t {
        pipeline::render::Tick::Total(n) => {
            progress.set_length(n);
            progress.set_position(0);
        }
        pipeline::render::Tick::Done(d) => progress.set_position(d),
    })
    .map_err(|e| anyhow!(e))
}
