//! The RTL render engine: images produced by the simulated hardware — Gouraud through the
//! raster pipe, and the lit methods (`pipeline::lit::LIT_METHODS`) through the lit pixel
//! pipeline ([`render_lit_rtl`], which also resolves depth with the hardware's z).
//!
//! Every triangle the golden renderer would draw (the same list, in the same order; zero-area
//! triangles skipped as `golden::render::render` skips them) gets its set-up in software —
//! `golden::address_block::AddressSetup` for the address block, `golden::gouraud::setup` planes
//! quantized by `golden::intensity_interpolator` for the BVI — and is fed to the rust-hdl
//! raster pipe (`rtl::gouraud_raster`: address block + BVI), stepped clock by clock. Each pixel
//! the pipe emits goes into a `golden::render::Frame`.
//!
//! **Depth** is resolved in this driver exactly as in the golden renderer: the triangle's
//! screen-space depth plane (`ScreenTriangle::depth_plane`) is evaluated in f64 at the pixel
//! centre and offered to `Frame::put` (nearer wins, ties keep the first writer). So both
//! engines see identical visibility, and the colours are the only difference: the RTL's are
//! within 1 LSB per channel of the golden Gouraud image (the BVI's error budget).

use anyhow::{bail, Result};
use golden::methods::Method;
use golden::render::Frame;
use golden::shade::ShadeContext;
use golden::types::{ScreenTriangle, MAX_ADDRESS};
use indicatif::ProgressBar;
use pipeline::gouraud::{clock_budget, Pipe, PipeStats, TriangleJob};
use pipeline::lit::{lit_clock_budget, LitJob, LitPipe, ShadingRegs, LIT_METHODS};

/// An RTL render: the frame and the hardware's clock counts.
#[derive(Clone, Debug)]
pub struct RtlRender {
    pub frame: Frame,
    pub stats: PipeStats,
    /// Lit pipeline only: pixels whose visible triangle under the hardware's depth words
    /// differs from the one the f64 depth planes pick (surfaces closer than the z format
    /// resolves); 0 for Gouraud, whose depth test uses the f64 planes.
    pub visibility_mismatches: usize,
}

/// The methods the RTL engine renders, comma-separated.
pub fn rtl_method_names() -> String {
    std::iter::once(Method::Gouraud)
        .chain(LIT_METHODS)
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Check a method name for the RTL engine (one-line error naming the ones it has).
pub fn check_rtl_method(m: Method) -> Result<()> {
    if m == Method::Gouraud || LIT_METHODS.contains(&m) {
        Ok(())
    } else {
        bail!(
            "the rtl engine has no hardware for method {m} (it has: {})",
            rtl_method_names()
        )
    }
}

/// Check the canvas and the vertex addresses against the hardware's 12 bits.
fn check_addresses(tris: &[ScreenTriangle], width: u32, height: u32) -> Result<()> {
    let limit = MAX_ADDRESS as u32 + 1;
    if width == 0 || height == 0 || width > limit || height > limit {
        bail!("canvas {width}x{height}: each side must be 1..={limit} (12-bit addresses)");
    }
    if let Some((i, v)) = tris.iter().enumerate().find_map(|(i, t)| {
        t.v.iter()
            .find(|v| !(0..=MAX_ADDRESS).contains(&v.x) || !(0..=MAX_ADDRESS).contains(&v.y))
            .map(|v| (i, v))
    }) {
        bail!(
            "triangle {i}: vertex ({}, {}) is outside the 12-bit address range 0..={MAX_ADDRESS}",
            v.x,
            v.y
        );
    }
    Ok(())
}

/// Render `tris` with `method` (Gouraud or one of [`LIT_METHODS`]) through the simulated
/// hardware.
pub fn render_rtl(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
) -> Result<RtlRender> {
    check_rtl_method(method)?;
    if method == Method::Gouraud {
        render_gouraud_rtl(tris, ctx, width, height, progress)
    } else {
        render_lit_rtl(tris, method, ctx, width, height, progress)
    }
}

/// Render `tris` with a lit method through the pixel pipeline (`rtl::pixel_pipeline`) built
/// for it. Depth is the hardware's: each fragment's z word is tested against a z-buffer here
/// (the frame writer, memory outside the pipeline; nearer wins, ties keep the first writer).
/// Beside it the f64 depth planes pick a visible triangle per pixel as the golden renderer
/// does; pixels where the two disagree are counted in
/// [`RtlRender::visibility_mismatches`].
///
/// Errors (one line): as [`render_gouraud_rtl`], plus a lighting model or material the
/// registers cannot hold (Phong lighting, a colour weight ≥ 256, a vertex depth beyond the
/// depth words' range).
pub fn render_lit_rtl(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
) -> Result<RtlRender> {
    check_addresses(tris, width, height)?;
    let regs = ShadingRegs::of(ctx).map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?;
    let mut jobs = Vec::with_capacity(tris.len());
    let mut depth = Vec::with_capacity(tris.len());
    for (i, t) in tris.iter().enumerate() {
        let job = LitJob::new(t).map_err(|e| anyhow::anyhow!("triangle {i}: {e}"))?;
        let (Some(d), Some(job)) = (t.depth_plane(), job) else {
            continue;
        };
        jobs.push(job);
        depth.push(d);
    }
    progress.set_length(jobs.len() as u64);
    progress.set_position(0);
    let mut frame = Frame::new(width, height);
    let n = width as usize * height as usize;
    let mut golden_z = vec![f64::INFINITY; n];
    let mut golden_winner = vec![usize::MAX; n];
    let mut hw_winner = vec![usize::MAX; n];
    let mut pipe = LitPipe::new(method).map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?;
    let stats = pipe
        .run(
            &jobs,
            &regs,
            lit_clock_budget(&jobs),
            |f| {
                let (x, y) = (f.x as i32, f.y as i32);
                if frame.put(x, y, f.z as f64, f.rgb) {
                    hw_winner[y as usize * width as usize + x as usize] = f.job;
                }
                if (x as u32) < width && (y as u32) < height {
                    let i = y as usize * width as usize + x as usize;
                    let z = depth[f.job].at_pixel(x, y);
                    if z < golden_z[i] {
                        golden_z[i] = z;
                        golden_winner[i] = f.job;
                    }
                }
            },
            |done| progress.set_position(done),
        )
        .map_err(|e| anyhow::anyhow!("RTL simulation: {e}"))?;
    let visibility_mismatches = hw_winner
        .iter()
        .zip(&golden_winner)
        .filter(|(a, b)| a != b)
        .count();
    Ok(RtlRender {
        frame,
        stats,
        visibility_mismatches,
    })
}

/// Render `tris` with Gouraud shading through the simulated address block and intensity
/// interpolator into a `width`×`height` frame. `progress` gets its length set to the number
/// of triangles sent to the hardware and advances as each one's `done` comes out.
///
/// Errors (one line): a canvas wider or taller than 4096, a vertex outside 0..=4095, or the
/// hardware not finishing within its clock budget.
pub fn render_gouraud_rtl(
    tris: &[ScreenTriangle],
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
) -> Result<RtlRender> {
    check_addresses(tris, width, height)?;
    // Same triangles as the golden renderer: those with a depth plane (non-zero area).
    let mut jobs = Vec::with_capacity(tris.len());
    let mut depth = Vec::with_capacity(tris.len());
    for t in tris {
        let (Some(d), Some(job)) = (t.depth_plane(), TriangleJob::gouraud(t, ctx)) else {
            continue;
        };
        jobs.push(job);
        depth.push(d);
    }
    progress.set_length(jobs.len() as u64);
    let mut frame = Frame::new(width, height);
    let mut pipe = Pipe::new().map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?;
    let stats = pipe
        .run(
            &jobs,
            clock_budget(&jobs),
            |k, x, y, rgb| {
                let (x, y) = (x as i32, y as i32);
                frame.put(x, y, depth[k].at_pixel(x, y), rgb);
            },
            |done| progress.set_position(done),
        )
        .map_err(|e| anyhow::anyhow!("RTL simulation: {e}"))?;
    Ok(RtlRender {
        frame,
        stats,
        visibility_mismatches: 0,
    })
}

/// Largest per-channel difference between two frames' colours, and how many pixels differ at
/// all (for the "within 1 LSB of golden" check).
pub fn max_channel_diff(a: &Frame, b: &Frame) -> (u8, usize) {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "frames of different sizes"
    );
    let mut max = 0u8;
    let mut n = 0;
    for (p, q) in a.rgb.iter().zip(&b.rgb) {
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        max = max.max(d);
        n += (d > 0) as usize;
    }
    (max, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use golden::methods::Method;

    /// The default scene (sphere rez 50, 400×400, light 90°) through the RTL: same coverage and
    /// fragment counts as the golden Gouraud render, every colour within 1 LSB.
    #[test]
    fn default_scene_within_one_lsb_of_golden() {
        let s = crate::setup::build(&crate::setup::SceneArgs::default()).unwrap();
        let rtl =
            render_gouraud_rtl(&s.tris, &s.ctx, s.width, s.height, &ProgressBar::hidden()).unwrap();
        let gold = golden::render::render(&s.tris, Method::Gouraud, &s.ctx, s.width, s.height);
        assert_eq!(rtl.frame.fragments, gold.fragments, "coverage differs");
        let (max, n) = max_channel_diff(&rtl.frame, &gold);
        println!(
            "default scene: {} pixels in {} clocks ({:.3} px/clock); {n} pixels differ, by at most {max} LSB",
            rtl.stats.pixels,
            rtl.stats.clocks,
            rtl.stats.pixels_per_clock()
        );
        assert!(max <= 1, "RTL differs from golden Gouraud by {max} LSB");
    }

    #[test]
    fn bad_inputs_are_one_line_errors() {
        let v = golden::types::ScreenVertex {
            x: 4096,
            y: 0,
            z: 0.0,
            normal: glam::DVec3::Z,
        };
        let t = ScreenTriangle { v: [v, v, v] };
        let ctx = ShadeContext::default();
        let e = render_gouraud_rtl(&[t], &ctx, 10, 10, &ProgressBar::hidden()).unwrap_err();
        assert!(format!("{e:#}").contains("outside the 12-bit"));
        let e = render_gouraud_rtl(&[], &ctx, 5000, 10, &ProgressBar::hidden()).unwrap_err();
        assert!(format!("{e:#}").contains("canvas"));
    }
}
