//! The RTL render engine: Gouraud images produced by the simulated hardware.
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
use golden::render::Frame;
use golden::shade::ShadeContext;
use golden::types::{ScreenTriangle, MAX_ADDRESS};
use indicatif::ProgressBar;
use pipeline::gouraud::{clock_budget, Pipe, PipeStats, TriangleJob};

/// An RTL render: the frame and the hardware's clock counts.
#[derive(Clone, Debug)]
pub struct RtlRender {
    pub frame: Frame,
    pub stats: PipeStats,
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
    Ok(RtlRender { frame, stats })
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
