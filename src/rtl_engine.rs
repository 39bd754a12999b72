//! The RTL render engine: images produced by the simulated hardware — Gouraud through the
//! raster pipe, the lit methods (`pipeline::lit::LIT_METHODS`) through the lit pixel
//! pipeline ([`render_lit_rtl`], which also resolves depth with the hardware's z), and the
//! span methods (`pipeline::span::SPAN_METHODS`: angular, fast, fast-fit) through the span
//! pipelines, two fragments per clock ([`render_span_rtl`]).
//!
//! Every triangle the golden renderer would draw (the same list, in the same order; zero-area
//! triangles skipped as `golden::render::render` skips them) gets its set-up in software —
//! `golden::units::address_block::AddressSetup` for the address block, `golden::shading::gouraud::setup` planes
//! quantized by `golden::units::intensity_interpolator` for the BVI — and is fed to the rust-hdl
//! raster pipe (`rtl::pipelines::gouraud_raster`: address block + BVI), stepped clock by clock: by default
//! through its AXI4-Stream top `rtl::stream::gouraud_stream` (set-up records in, fragment beats out),
//! with `--lit-top pipeline` through its ports. Each pixel the pipe emits goes into a
//! `golden::render::Frame`.
//!
//! **Depth** is resolved in this driver exactly as in the golden renderer: the triangle's
//! screen-space depth plane (`ScreenTriangle::depth_plane`) is evaluated in f64 at the pixel
//! centre and offered to `Frame::put` (nearer wins; at equal depth the lower mesh index, the
//! golden renderer's first writer, whatever order the set-up order sent the triangles in). So
//! both engines see identical visibility, and the colours are the only difference: the RTL's
//! are within 1 LSB per channel of the golden Gouraud image (the BVI's error budget).

use anyhow::{bail, Result};
use golden::methods::Method;
use golden::render::Frame;
use golden::shade::ShadeContext;
use golden::types::{Plane, ScreenTriangle, MAX_ADDRESS};
use indicatif::ProgressBar;

use flow::engine::Sim;
use pipeline::axis::PipeStats;
use pipeline::gouraud::{clock_budget, Pipe, TriangleJob};
use pipeline::lit::{lit_clock_budget, LitJob, LitPipe, ShadingRegs, LIT_METHODS};
use pipeline::span::{span_clock_budget, span_jobs, SpanPipe, SPAN_METHODS};

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

/// The methods the RTL engine renders, in order: Gouraud, the lit pipeline's, the span
/// pipelines'.
pub fn rtl_methods() -> Vec<Method> {
    [Method::Gouraud, Method::Subdivision]
        .into_iter()
        .chain(LIT_METHODS)
        .chain(SPAN_METHODS)
        .collect()
}

/// The methods the RTL engine renders, comma-separated.
pub fn rtl_method_names() -> String {
    rtl_methods()
        .iter()
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Check a method name for the RTL engine (one-line error naming the ones it has).
pub fn check_rtl_method(m: Method) -> Result<()> {
    if rtl_methods().contains(&m) {
        Ok(())
    } else {
        bail!(
            "the rtl engine has no hardware for method {m} (it has: {})",
            rtl_method_names()
        )
    }
}

/// Check the canvas and the vertex addresses against the hardware's 12 bits.
pub(crate) fn check_addresses(tris: &[ScreenTriangle], width: u32, height: u32) -> Result<()> {
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

/// Build choices of the RTL engine beyond the method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RtlBuild {
    /// `cubic` through the pipelined Horner units (one pixel per clock) instead of the serial
    /// fig. 2.6 unit (three clocks per pixel).
    pub horner_pipelined: bool,
    /// The simulator: the exported Verilog under Verilator in process, or rust-hdl.
    pub sim: Sim,
    /// The address block `gouraud` goes through: the single block (one address per clock,
    /// default) or the four-triangle block (four lanes, a BVI each). `subdivision` always
    /// takes the four-triangle block; the other methods only the single one.
    pub address: Address,
    /// The top the lit methods, `gouraud` (single address block) and `cubic` go through
    /// (`--lit-top`; `cubic` takes its stream top only when `Stream` is asked for).
    pub lit_top: LitTop,
    /// The order the lit methods' triangles are sent in (`--setup-order`).
    pub setup_order: SetupOrder,
}

impl Default for RtlBuild {
    /// Every choice at its default; the simulator the fastest installed ([`Sim::fastest`]).
    fn default() -> Self {
        RtlBuild {
            horner_pipelined: false,
            sim: Sim::fastest(),
            address: Address::default(),
            lit_top: LitTop::default(),
            setup_order: SetupOrder::default(),
        }
    }
}

/// The Verilator designs rendering `methods` with `build` steps (to compile them before the
/// run, in parallel).
pub fn designs(methods: &[Method], build: RtlBuild) -> Result<Vec<verilated::Design>> {
    let mut out: Vec<verilated::Design> = Vec::new();
    for &m in methods {
        if m == Method::Flat {
            continue;
        }
        let four = matches!(
            (m, build.address),
            (Method::Gouraud, Address::FourTriangle) | (Method::Subdivision, _)
        );
        let d = if four {
            pipeline::subdivision::SubPipe::design(build.lit_top == LitTop::Stream)
        } else if m == Method::Gouraud {
            Pipe::design(build.lit_top.resolve() == LitTop::Stream)
        } else if SPAN_METHODS.contains(&m) {
            SpanPipe::design(m, build.horner_pipelined, build.lit_top == LitTop::Stream)
                .map_err(|e| anyhow::anyhow!(e))?
        } else {
            LitPipe::design(m, build.lit_top.resolve() == LitTop::Stream)
                .map_err(|e| anyhow::anyhow!(e))?
        };
        if !out.iter().any(|o| o.key == d.key) {
            out.push(d);
        }
    }
    Ok(out)
}

/// The order in which the driver sends the lit methods' triangles (`--setup-order`). The
/// images do not depend on it (the frame writer's tie rule, [`render_lit_rtl`]); the clock
/// counts do.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SetupOrder {
    /// Large and small walks alternately (`pipeline::lit::balanced_order`), so the 26-word
    /// set-up records of small triangles stream in while large ones are walked.
    #[default]
    Balanced,
    /// The mesh's order.
    Mesh,
}

impl SetupOrder {
    /// The indices of `jobs` in sending order.
    pub fn of(self, jobs: &[LitJob]) -> Vec<usize> {
        self.of_addrs(&jobs.iter().map(|j| j.addr).collect::<Vec<_>>())
    }

    /// The order of triangles given by their address set-ups.
    pub fn of_addrs(self, addrs: &[golden::units::address_block::AddressSetup]) -> Vec<usize> {
        match self {
            SetupOrder::Balanced => pipeline::axis::balanced_order_of(addrs),
            SetupOrder::Mesh => (0..addrs.len()).collect(),
        }
    }
}

/// The top the lit methods' and `gouraud`'s frames go through (`--lit-top`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LitTop {
    /// `stream` for the lit methods and `gouraud` (single address block), `pipeline` for the
    /// span methods and `subdivision`.
    #[default]
    Default,
    /// `pixel-stream` / `gouraud-stream` / `cubic-stream` / `angular-stream` / `fast-stream` /
    /// `quadric-stream`: set-up records on a 32-bit AXI4-Stream, fragment beats out (the span methods only when
    /// asked: their per-line records make short lines set-up bound).
    Stream,
    /// `pixel-pipeline` / `gouraud-raster` / `cubic-pipeline`: the set-up on load ports, one
    /// triangle (cubic: one line) per load.
    Pipeline,
}

impl LitTop {
    /// The top of the lit methods and `gouraud` (single address block).
    pub fn resolve(self) -> LitTop {
        match self {
            LitTop::Default => LitTop::Stream,
            t => t,
        }
    }
}

/// Which address block walks the triangles (`--address`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Address {
    /// The method's default: the single address block (SPEC §5), the four-triangle block for
    /// `subdivision`.
    #[default]
    Default,
    /// The single address block (SPEC §5), one address per clock.
    Single,
    /// The four-triangle block (SPEC §7), up to four addresses per clock.
    FourTriangle,
}

/// Render `tris` with `method` (Gouraud, one of [`LIT_METHODS`] or of [`SPAN_METHODS`])
/// through the simulated hardware, with the default [`RtlBuild`].
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

/// [`render_rtl`] with the build choices `build`.
pub fn render_rtl_with(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
    build: RtlBuild,
) -> Result<RtlRender> {
    check_rtl_method(method)?;
    match (method, build.address) {
        (Method::Gouraud | Method::Subdivision, Address::FourTriangle)
        | (Method::Subdivision, Address::Default) => {
            return render_subdivision_rtl(tris, method, ctx, width, height, progress, build)
        }
        (Method::Subdivision, Address::Single) => bail!(
            "method subdivision walks its four sub-triangles with the four-triangle block: \
             use --address four-triangle (or leave --address out)"
        ),
        (m, Address::FourTriangle) => bail!(
            "--address four-triangle feeds a BVI per lane: it renders gouraud and subdivision, \
             not {m}"
        ),
        _ => {}
    }
    if method == Method::Gouraud {
        render_gouraud_rtl_with(tris, ctx, width, height, progress, build)
    } else if SPAN_METHODS.contains(&method) {
        render_span_rtl(tris, method, ctx, width, height, progress, build)
    } else {
        render_lit_rtl_with(tris, method, ctx, width, height, progress, build)
    }
}

/// Render `tris` with a lit method through the pixel pipeline (`rtl::pipelines::pixel_pipeline`) built
/// for it. The triangles are sent in the build's [`SetupOrder`] (balanced by default). Depth
/// is the hardware's: each fragment's z word is tested against a z-buffer here (the frame
/// writer, memory outside the pipeline; nearer wins, and at equal depth the lower triangle
/// index, i.e. the mesh-order first writer, so the image does not depend on the order sent).
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
    render_lit_rtl_with(
        tris,
        method,
        ctx,
        width,
        height,
        progress,
        RtlBuild::default(),
    )
}

/// [`render_lit_rtl`] with the build choices `build` (the simulator).
pub fn render_lit_rtl_with(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
    build: RtlBuild,
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
    let order = build.setup_order.of(&jobs);
    let sent: Vec<LitJob> = order.iter().map(|&i| jobs[i]).collect();
    let mut writer = FrameWriter::new(width, height);
    let stream = build.lit_top.resolve() == LitTop::Stream;
    let mut pipe =
        LitPipe::on(method, build.sim, stream).map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?;
    let stats = pipe
        .run(
            &sent,
            &regs,
            lit_clock_budget(&sent),
            |f| {
                let k = order[f.job];
                writer.put(k, f.x, f.y, f.z, f.rgb, &depth[k])
            },
            |done| progress.set_position(done),
        )
        .map_err(|e| anyhow::anyhow!("RTL simulation: {e}"))?;
    Ok(writer.finish(stats))
}

/// Render `tris` with a span method through the span pipeline built for it — `angular`,
/// `fast`, `fast-fit` through `rtl::pipelines::span_pipeline` (two fragments per clock), `cubic` through
/// `rtl::pipelines::cubic_pipeline` (Horner variant from `build`): the span front end
/// (`pipeline::span::span_jobs`, the golden method's per-line set-up in software) loads one
/// raster line at a time and the frame writer takes every fragment (z-buffer as in
/// [`render_lit_rtl`]). `progress` counts spans.
pub fn render_span_rtl(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
    build: RtlBuild,
) -> Result<RtlRender> {
    check_addresses(tris, width, height)?;
    // The cubic's samples and the quadric's coefficients are lit in software (any lighting
    // model); the other span tops light in hardware and need the registers.
    let regs = if matches!(method, Method::Cubic | Method::Quadric) {
        ShadingRegs {
            light: [0; 3],
            half: [0; 3],
            n: 0,
            weights: [0; 9],
        }
    } else {
        ShadingRegs::of(ctx).map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?
    };
    // `cubic` goes through its stream top `cubic-stream` (and `angular`, `fast`, `fast-fit`,
    // `quadric` through `angular-stream`, `fast-stream`, `quadric-stream`) only when asked
    // (`--lit-top stream`): a line's record is 12 set-up words, so on meshes whose triangles
    // give lines of a few pixels the stream is set-up bound (the default scene: see the
    // README) and the main job keeps `cubic-pipeline`'s ports.
    // `angular-stream`, `fast-stream` and `quadric-stream` likewise: a line's record is 14,
    // 20 or 5 words (a quadric triangle's first line 41) and a line of m + 1 pixels takes
    // ⌊m/2⌋ + 1 clocks, so lines under 27, 39 or 9 pixels are set-up bound.
    let stream = build.lit_top == LitTop::Stream;
    let mut pipe = SpanPipe::on(method, build.horner_pipelined, build.sim, stream)
        .map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?;
    let mut spans = Vec::new();
    let mut depth = Vec::with_capacity(tris.len());
    for (i, t) in tris.iter().enumerate() {
        let Some(d) = t.depth_plane() else { continue };
        let k = depth.len();
        spans.extend(
            span_jobs(t, k, pipe.kind(), ctx).map_err(|e| anyhow::anyhow!("triangle {i}: {e}"))?,
        );
        depth.push(d);
    }
    progress.set_length(spans.len() as u64);
    progress.set_position(0);
    let mut writer = FrameWriter::new(width, height);
    let stats = pipe
        .run(
            &spans,
            &regs,
            span_clock_budget(&spans),
            |f| writer.put(f.triangle, f.x, f.y, f.z, f.rgb, &depth[f.triangle]),
            |done| progress.set_position(done),
        )
        .map_err(|e| anyhow::anyhow!("RTL simulation: {e}"))?;
    Ok(writer.finish(stats))
}

/// The frame writer of the lit and span pipelines: a z-buffer on the hardware's depth words
/// (nearer wins, ties keep the first writer), and beside it the f64 depth planes picking a
/// visible triangle per pixel as the golden renderer does, to count the pixels where the two
/// disagree.
struct FrameWriter {
    frame: Frame,
    golden_z: Vec<f64>,
    golden_winner: Vec<usize>,
    hw_winner: Vec<usize>,
}

impl FrameWriter {
    fn new(width: u32, height: u32) -> FrameWriter {
        let n = width as usize * height as usize;
        FrameWriter {
            frame: Frame::new(width, height),
            golden_z: vec![f64::INFINITY; n],
            golden_winner: vec![usize::MAX; n],
            hw_winner: vec![usize::MAX; n],
        }
    }

    /// A fragment of triangle `k` (whose f64 depth plane is `plane`) with depth word `z`.
    /// Nearer wins; at equal depth the lower `k` (the first writer in mesh order), whatever
    /// order the fragments arrive in.
    fn put(&mut self, k: usize, x: u32, y: u32, z: i32, rgb: [u8; 3], plane: &Plane) {
        let (w, h) = (self.frame.width, self.frame.height);
        let (xi, yi) = (x as i32, y as i32);
        let at = (x < w && y < h).then(|| y as usize * w as usize + x as usize);
        let tie_won = at.is_some_and(|i| z as f64 == self.frame.depth[i] && k < self.hw_winner[i]);
        if self.frame.put(xi, yi, z as f64, rgb) {
            self.hw_winner[y as usize * w as usize + x as usize] = k;
        } else if let (true, Some(i)) = (tie_won, at) {
            self.frame.rgb[i] = rgb;
            self.hw_winner[i] = k;
        }
        if let Some(i) = at {
            let zf = plane.at_pixel(xi, yi);
            if zf < self.golden_z[i] || (zf == self.golden_z[i] && k < self.golden_winner[i]) {
                self.golden_z[i] = zf;
                self.golden_winner[i] = k;
            }
        }
    }

    fn finish(self, stats: PipeStats) -> RtlRender {
        let visibility_mismatches = self
            .hw_winner
            .iter()
            .zip(&self.golden_winner)
            .filter(|(a, b)| a != b)
            .count();
        RtlRender {
            frame: self.frame,
            stats,
            visibility_mismatches,
        }
    }
}

/// The jobs of the triangles the golden renderer draws (those with a depth plane, i.e. non-zero
/// area, and a set-up from `job`), in order, with each one's f64 depth plane.
fn jobs_with_depth<J>(
    tris: &[ScreenTriangle],
    mut job: impl FnMut(&ScreenTriangle) -> Result<Option<J>>,
) -> Result<(Vec<J>, Vec<Plane>)> {
    let mut jobs = Vec::with_capacity(tris.len());
    let mut depth = Vec::with_capacity(tris.len());
    for t in tris {
        let Some(d) = t.depth_plane() else { continue };
        if let Some(j) = job(t)? {
            jobs.push(j);
            depth.push(d);
        }
    }
    Ok((jobs, depth))
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
    render_gouraud_rtl_with(tris, ctx, width, height, progress, RtlBuild::default())
}

/// [`render_gouraud_rtl`] with the build choices `build` (the simulator).
pub fn render_gouraud_rtl_with(
    tris: &[ScreenTriangle],
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
    build: RtlBuild,
) -> Result<RtlRender> {
    check_addresses(tris, width, height)?;
    // Same triangles as the golden renderer: those with a depth plane (non-zero area).
    let (jobs, depth) = jobs_with_depth(tris, |t| Ok(TriangleJob::gouraud(t, ctx)))?;
    progress.set_length(jobs.len() as u64);
    let mut frame = Frame::new(width, height);
    // The triangles are sent in the set-up order (balanced by default: a 22-word record per
    // triangle streams in while a larger one is walked); the frame keeps, at equal depth, the
    // lower mesh index, so the image does not depend on the order.
    let order = build
        .setup_order
        .of_addrs(&jobs.iter().map(|j| j.addr).collect::<Vec<_>>());
    let sent: Vec<TriangleJob> = order.iter().map(|&i| jobs[i]).collect();
    let stream = build.lit_top.resolve() == LitTop::Stream;
    let mut pipe = Pipe::on(build.sim, stream).map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?;
    let mut winner = vec![usize::MAX; width as usize * height as usize];
    let stats = pipe
        .run(
            &sent,
            clock_budget(&sent),
            |k, x, y, rgb| {
                let k = order[k];
                let at =
                    (x < width && y < height).then(|| y as usize * width as usize + x as usize);
                let (x, y) = (x as i32, y as i32);
                let z = depth[k].at_pixel(x, y);
                let tie_won = at.is_some_and(|i| z == frame.depth[i] && k < winner[i]);
                if frame.put(x, y, z, rgb) {
                    if let Some(i) = at {
                        winner[i] = k;
                    }
                } else if let (true, Some(i)) = (tie_won, at) {
                    frame.rgb[i] = rgb;
                    winner[i] = k;
                }
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

/// Render `tris` through the subdivision raster pipe (`rtl::pipelines::subdivision_raster`: the
/// four-triangle address block and a BVI per lane): `gouraud` (every lane interpolates the
/// parent's planes) or `subdivision` (each lane its sub-triangle's). Depth as in
/// [`render_gouraud_rtl`] (the parent's f64 depth plane at the pixel centre). `progress`
/// counts parents every lane has finished. With `--lit-top stream` through the
/// stream top `subdivision-stream` (a 72-word record per parent, a fragment stream per lane);
/// by default through the pipe's ports, as the records make small parents set-up bound.
pub fn render_subdivision_rtl(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
    progress: &ProgressBar,
    build: RtlBuild,
) -> Result<RtlRender> {
    use pipeline::subdivision::{clock_budget, SubJob, SubPipe};
    check_addresses(tris, width, height)?;
    let (jobs, depth) = jobs_with_depth(tris, |t| match method {
        Method::Gouraud => Ok(SubJob::gouraud(t, ctx)),
        Method::Subdivision => Ok(SubJob::subdivision(t, ctx)),
        m => bail!("the subdivision pipe has no set-up for method {m}"),
    })?;
    progress.set_length(jobs.len() as u64);
    progress.set_position(0);
    let mut frame = Frame::new(width, height);
    let mut pipe = SubPipe::on(build.sim, build.lit_top == LitTop::Stream)
        .map_err(|e| anyhow::anyhow!("RTL set-up: {e}"))?;
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

    /// The frame writer's tie rule: at equal depth the lower triangle index wins, in whichever
    /// order the fragments arrive (so the set-up order cannot change an image); nearer still
    /// wins over a lower index.
    #[test]
    fn frame_writer_ties_go_to_the_lower_triangle() {
        let flat = Plane {
            a: 0.0,
            b: 0.0,
            c: 1.0,
        };
        let near = Plane { c: 0.5, ..flat };
        let stats = PipeStats::default();
        for order in [[0usize, 1, 2], [2, 1, 0], [1, 2, 0]] {
            let mut w = FrameWriter::new(4, 4);
            for &k in &order {
                let (z, plane) = if k == 2 { (100, &near) } else { (200, &flat) };
                // Pixel (1, 1): triangles 0 and 1 tie (z = 200). Pixel (2, 1): all three, and
                // triangle 2 is nearer.
                w.put(k, 1, 1, 200, [k as u8 + 1; 3], &flat);
                w.put(k, 2, 1, z, [k as u8 + 1; 3], plane);
            }
            let r = w.finish(stats);
            assert_eq!(r.frame.rgb[4 + 1], [1; 3], "tie, arrival order {order:?}");
            assert_eq!(
                r.frame.rgb[4 + 2],
                [3; 3],
                "nearer, arrival order {order:?}"
            );
            assert_eq!(r.visibility_mismatches, 0, "arrival order {order:?}");
        }
    }

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

    /// The span methods through their two-lane stream tops (`angular-stream`, `fast-stream`,
    /// `quadric-stream`: line and register records, a fragment stream per lane) and through the span pipelines'
    /// ports give the same frame, bit for bit: the torus at 80×80 (`angular`, `fast`) and the
    /// default sphere at 72×72 (`quadric`, `fast-fit`); the clocks of both are printed (lines
    /// shorter than 27, 39 or 9 pixels are set-up bound: a line's record is 14, 20 or 5 words).
    #[test]
    fn span_streams_and_ports_render_the_same_frame() {
        for (scene, size, methods) in [
            ("torus", 80, [Method::Angular, Method::Fast]),
            ("sphere", 72, [Method::Quadric, Method::FastFit]),
        ] {
            let s = crate::setup::build(&crate::setup::SceneArgs {
                scene: scene.into(),
                size: (size, size),
                ..crate::setup::SceneArgs::default()
            })
            .unwrap();
            for method in methods {
                let run = |top| {
                    let build = RtlBuild {
                        lit_top: top,
                        ..RtlBuild::default()
                    };
                    render_span_rtl(
                        &s.tris,
                        method,
                        &s.ctx,
                        s.width,
                        s.height,
                        &ProgressBar::hidden(),
                        build,
                    )
                    .unwrap()
                };
                let stream = run(LitTop::Stream);
                let ports = run(LitTop::Pipeline);
                assert!(
                    stream.stats.pixels > 1000,
                    "{scene}: a scene worth rendering"
                );
                assert_eq!(stream.stats.pixels, ports.stats.pixels, "{scene} {method}");
                assert_eq!(stream.stats.triangles, ports.stats.triangles);
                assert!(
                    stream.frame.rgb == ports.frame.rgb,
                    "{scene} {method}: frames differ"
                );
                // The stream top ran (its set-up words cost clocks the ports do not).
                assert!(stream.stats.clocks > ports.stats.clocks, "{scene} {method}");
                println!(
                    "{method}, {scene} {size}×{size}: stream top {} clocks ({:.3} px/clock), pipeline ports {} ({:.3}), ratio {:.3}",
                    stream.stats.clocks,
                    stream.stats.pixels_per_clock(),
                    ports.stats.clocks,
                    ports.stats.pixels_per_clock(),
                    ports.stats.clocks as f64 / stream.stats.clocks as f64
                );
            }
        }
    }

    /// Cubic through `cubic-stream` (line records, fragment beats) and through
    /// `cubic-pipeline`'s ports gives the same frame, bit for bit, on the torus at 200×200 (both Horner
    /// variants); the clocks of both are printed (lines shorter than a 12-word record are
    /// set-up bound).
    #[test]
    fn cubic_stream_and_ports_render_the_same_frame() {
        let s = crate::setup::build(&crate::setup::SceneArgs {
            scene: "torus".into(),
            size: (200, 200),
            ..crate::setup::SceneArgs::default()
        })
        .unwrap();
        for pipelined in [false, true] {
            let run = |top| {
                let build = RtlBuild {
                    lit_top: top,
                    horner_pipelined: pipelined,
                    ..RtlBuild::default()
                };
                render_span_rtl(
                    &s.tris,
                    Method::Cubic,
                    &s.ctx,
                    s.width,
                    s.height,
                    &ProgressBar::hidden(),
                    build,
                )
                .unwrap()
            };
            let stream = run(LitTop::Stream);
            let ports = run(LitTop::Pipeline);
            assert_eq!(
                stream.stats.pixels, ports.stats.pixels,
                "pipelined {pipelined}"
            );
            assert_eq!(stream.stats.triangles, ports.stats.triangles);
            assert!(
                stream.frame.rgb == ports.frame.rgb,
                "pipelined {pipelined}: frames differ"
            );
            println!(
                "cubic (pipelined {pipelined}): cubic-stream {} clocks ({:.3} px/clock), cubic-pipeline {} ({:.3}), ratio {:.3}",
                stream.stats.clocks,
                stream.stats.pixels_per_clock(),
                ports.stats.clocks,
                ports.stats.pixels_per_clock(),
                ports.stats.clocks as f64 / stream.stats.clocks as f64
            );
        }
    }

    /// Subdivision (and Gouraud through the four-triangle block) through `subdivision-stream`
    /// (parent records, a fragment stream per lane) and through `subdivision-raster`'s ports
    /// give the same frame, bit for bit, on the default scene and the torus; the clocks of
    /// both are printed (parents whose longest lane walk is shorter than a 72-word record are
    /// set-up bound).
    #[test]
    fn subdivision_stream_and_ports_render_the_same_frame() {
        for scene in ["sphere", "torus"] {
            let s = crate::setup::build(&crate::setup::SceneArgs {
                scene: scene.into(),
                ..crate::setup::SceneArgs::default()
            })
            .unwrap();
            for method in [Method::Subdivision, Method::Gouraud] {
                let run = |top| {
                    let build = RtlBuild {
                        lit_top: top,
                        address: Address::FourTriangle,
                        ..RtlBuild::default()
                    };
                    render_subdivision_rtl(
                        &s.tris,
                        method,
                        &s.ctx,
                        s.width,
                        s.height,
                        &ProgressBar::hidden(),
                        build,
                    )
                    .unwrap()
                };
                let stream = run(LitTop::Stream);
                let ports = run(LitTop::Pipeline);
                assert!(stream.stats.pixels > 1000, "{scene} {method}");
                assert_eq!(stream.stats.pixels, ports.stats.pixels, "{scene} {method}");
                assert_eq!(stream.stats.triangles, ports.stats.triangles);
                assert!(
                    stream.frame.rgb == ports.frame.rgb,
                    "{scene} {method}: frames differ"
                );
                // The stream top ran (its set-up words cost clocks the ports do not).
                assert!(stream.stats.clocks > ports.stats.clocks, "{scene} {method}");
                println!(
                    "{method}, {scene}: subdivision-stream {} clocks ({:.3} px/clock), subdivision-raster ports {} ({:.3}), ratio {:.3}",
                    stream.stats.clocks,
                    stream.stats.pixels_per_clock(),
                    ports.stats.clocks,
                    ports.stats.pixels_per_clock(),
                    ports.stats.clocks as f64 / stream.stats.clocks as f64
                );
            }
        }
    }

    /// Gouraud through `gouraud-stream` (set-up records, fragment beats) and through
    /// `gouraud-raster`'s ports gives the same frame, bit for bit, on the default scene, in
    /// either set-up order.
    #[test]
    fn gouraud_stream_and_ports_render_the_same_frame() {
        let s = crate::setup::build(&crate::setup::SceneArgs::default()).unwrap();
        let run = |top, setup_order| {
            let build = RtlBuild {
                lit_top: top,
                setup_order,
                ..RtlBuild::default()
            };
            render_gouraud_rtl_with(
                &s.tris,
                &s.ctx,
                s.width,
                s.height,
                &ProgressBar::hidden(),
                build,
            )
            .unwrap()
        };
        let stream = run(LitTop::Stream, SetupOrder::Balanced);
        let mesh = run(LitTop::Stream, SetupOrder::Mesh);
        let ports = run(LitTop::Pipeline, SetupOrder::Mesh);
        for (label, r) in [("balanced", &stream), ("mesh order", &mesh)] {
            assert_eq!(r.stats.pixels, ports.stats.pixels, "{label}");
            assert_eq!(r.stats.triangles, ports.stats.triangles, "{label}");
            assert!(r.frame.rgb == ports.frame.rgb, "{label}: frames differ");
        }
        println!(
            "gouraud-stream {} clocks ({:.3} px/clock; mesh order {}, {:.3}), gouraud-raster {} ({:.3}), ratio {:.3}",
            stream.stats.clocks,
            stream.stats.pixels_per_clock(),
            mesh.stats.clocks,
            mesh.stats.pixels_per_clock(),
            ports.stats.clocks,
            ports.stats.pixels_per_clock(),
            ports.stats.clocks as f64 / stream.stats.clocks as f64
        );
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
