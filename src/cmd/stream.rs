//! `shadecore stream`: a scene as a stream top's AXI4-Stream set-up words (`pixel-stream` for
//! the lit methods, `gouraud-stream` for `gouraud`, `cubic-stream` for `cubic`,
//! `textured-stream` for `texture`, `texture-quadratic` and `texture-bezier`, the texture's
//! texel records included, and the per-line builds' line records after each triangle), with the
//! fragment beats the simulation of that top delivers for them and its Verilog — what an
//! external testbench (the cocotb test in `testbenches/cocotb/`) drives and checks. The top is
//! driven as the renderer drives it (`pipeline::axis`: a word every clock the top takes one,
//! the consumer never stalls); the tests hold its beats to the bit-exact twin's.

use std::path::PathBuf;

use anyhow::{anyhow, bail, Context, Result};
use pipeline::axis::{drive_beats, Beat, StreamTop, Word};
use pipeline::lit::scene_words;
use pipeline::lit::{method_options, LitJob, ShadingRegs};

use crate::setup::SceneArgs;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The method: a lit one runs its `pixel-stream` build (normalizer, normalizer-fit,
    /// normalizer-pw, brdf-k4, brdf-k8, brdf-k16, bump); gouraud runs `gouraud-stream`; cubic runs
    /// `cubic-stream` (one record per raster line, in walk order); texture, texture-quadratic
    /// and texture-bezier run `textured-stream` built additive, quadratic or bezier (the
    /// texture first, a record per texel, then the triangles, each followed by its line
    /// records in the per-line builds).
    #[arg(long, default_value = "normalizer-fit")]
    pub method: String,
    /// The order the triangles are sent in: balanced (large and small walks alternately, as
    /// `render` sends them) or mesh.
    #[arg(long, value_enum, default_value = "balanced")]
    pub setup_order: crate::rtl_engine::SetupOrder,
    /// With `--method cubic`: the Horner units of `cubic-stream` — serial (fig. 2.6, 3 clocks
    /// per pixel) or pipelined (one pixel per clock).
    #[arg(long, value_enum, default_value = "serial")]
    pub horner: crate::cmd::render::Horner,
    /// The simulator whose beats are written: verilator (the exported Verilog in process) or
    /// rust-hdl. Default: verilator when it is installed.
    #[arg(long, value_enum)]
    pub sim: Option<crate::sim::SimArg>,
    /// Output directory: setup.txt, beats.txt, and the top's Verilog (pixel_stream.v,
    /// gouraud_stream.v, cubic_stream.v or textured_stream.v).
    #[arg(long, default_value = "target/stream")]
    pub out: PathBuf,
}

pub fn run(a: Args) -> Result<()> {
    let method = crate::cmd::render::parse_methods(std::slice::from_ref(&a.method))?[0];
    if method == golden::methods::Method::Gouraud {
        return run_gouraud(&a);
    }
    if method == golden::methods::Method::Cubic {
        return run_cubic(&a);
    }
    if pipeline::textured::TEXTURED_RTL_METHODS.contains(&method) {
        return run_textured(&a, method);
    }
    let Some(o) = method_options(method) else {
        bail!(
            "`stream` writes no streams for method {} (it writes pixel-stream's for normalizer, normalizer-fit, normalizer-pw, brdf-k4, brdf-k8, brdf-k16, bump; gouraud-stream's for gouraud; cubic-stream's for cubic; textured-stream's for texture, texture-quadratic, texture-bezier; angular, fast, fast-fit, quadric and subdivision have stream tops with a fragment stream per lane, angular-stream, fast-stream, quadric-stream and subdivision-stream, that it does not write yet)",
            a.method
        );
    };
    let s = crate::setup::build(&a.scene)?;
    s.ensure_drawn()?;
    let regs = ShadingRegs::of(&s.ctx).map_err(|e| anyhow!(e))?;
    let jobs = triangle_jobs(&s, LitJob::new)?;
    let jobs: Vec<LitJob> = a.setup_order.of(&jobs).iter().map(|&i| jobs[i]).collect();
    stream_triangles::<rtl::stream::pixel_stream::PixelStream>(
        &a,
        &o,
        &scene_words(&jobs, &regs),
        jobs.len(),
        &format!("pixel-stream ({})", a.method),
    )
}

/// The set-up `job` gives each triangle of `s` (none where the method draws nothing); an
/// error names the triangle.
fn triangle_jobs<J>(
    s: &crate::setup::Setup,
    job: impl Fn(&golden::types::ScreenTriangle) -> Result<Option<J>, String>,
) -> Result<Vec<J>> {
    let mut jobs = Vec::new();
    for (i, t) in s.tris.iter().enumerate() {
        jobs.extend(job(t).map_err(|e| anyhow!("triangle {i}: {e}"))?);
    }
    Ok(jobs)
}

/// [`simulate_and_write`] for a top whose records are triangles, then the one line `stream`
/// prints (`label`: the top and its build).
fn stream_triangles<T: StreamTop + rtl::core::registry::RtlBlock>(
    a: &Args,
    o: &rtl::core::registry::Options,
    words: &[Word],
    triangles: usize,
    label: &str,
) -> Result<()> {
    let order = format!("{:?}", a.setup_order).to_lowercase();
    let (beats, clocks) = simulate_and_write::<T>(
        &a.out,
        o,
        words,
        triangles as u64,
        &order,
        crate::sim::resolve(a.sim)?,
    )?;
    crate::outln!(
        "{label}: {triangles} triangles, {} set-up words, {} beats ({} fragments) in {clocks} clocks -> {}",
        words.len(),
        beats.len(),
        beats.iter().filter(|b| b.pixel).count(),
        a.out.display()
    )?;
    Ok(())
}

/// `stream --method cubic`: the scene's raster lines through `cubic-stream` (the cubic set-up
/// per line, `pipeline::span::span_jobs`, in walk order).
fn run_cubic(a: &Args) -> Result<()> {
    use pipeline::span::{span_jobs, SpanKind};
    let pipelined = a.horner == crate::cmd::render::Horner::Pipelined;
    let s = crate::setup::build(&a.scene)?;
    s.ensure_drawn()?;
    crate::rtl_engine::check_addresses(&s.tris, s.width, s.height)?;
    let kind = SpanKind::Cubic { pipelined };
    let mut spans = Vec::new();
    for (i, t) in s.tris.iter().enumerate() {
        spans.extend(span_jobs(t, i, kind, &s.ctx).map_err(|e| anyhow!("triangle {i}: {e}"))?);
    }
    let words = pipeline::span::cubic_words(&spans);
    let o = rtl::core::registry::Options::new()
        .with("horner", if pipelined { "pipelined" } else { "serial" });
    let (beats, clocks) = simulate_and_write::<rtl::stream::cubic_stream::CubicStream>(
        &a.out,
        &o,
        &words,
        spans.len() as u64,
        "walk",
        crate::sim::resolve(a.sim)?,
    )?;
    crate::outln!(
        "cubic-stream ({}): {} lines, {} set-up words, {} beats in {} clocks -> {}",
        if pipelined { "pipelined" } else { "serial" },
        spans.len(),
        words.len(),
        beats.len(),
        clocks,
        a.out.display()
    )?;
    Ok(())
}

/// `stream --method texture|texture-quadratic|texture-bezier`: the scene through
/// `textured-stream` built for the method — the register record, the texture (a texel record
/// per texel), then the triangles (the method's set-up, `pipeline::textured::TexJob`), each
/// followed by its line records in the per-line builds.
fn run_textured(a: &Args, method: golden::methods::Method) -> Result<()> {
    use pipeline::textured::{coord_of, textured_scene_words, TexJob, TexRegs};
    let coord = coord_of(method);
    let s = crate::setup::build(&a.scene)?;
    s.check_textured(&[method], &a.scene.scene)?;
    s.ensure_drawn()?;
    crate::rtl_engine::check_addresses(&s.tris, s.width, s.height)?;
    let regs = ShadingRegs::of(&s.ctx).map_err(|e| anyhow!(e))?;
    let tregs = TexRegs::of(&s.ctx, &s.texture).map_err(|e| anyhow!(e))?;
    let jobs = triangle_jobs(&s, |t| TexJob::of(t, &s.texture, coord))?;
    let order = a
        .setup_order
        .of_addrs(&jobs.iter().map(|j| j.lit.addr).collect::<Vec<_>>());
    let jobs: Vec<TexJob> = order.iter().map(|&i| jobs[i].clone()).collect();
    let words = textured_scene_words(&jobs, &regs, &tregs, &s.texture).map_err(|e| anyhow!(e))?;
    // The default k (4, the render engine's ENGINE_K); the per-line builds by `texture`.
    let mut o = rtl::core::registry::Options::new();
    if coord != rtl::pipelines::textured_pipeline::TexCoord::Additive {
        o = o.with("texture", coord.name());
    }
    stream_triangles::<rtl::stream::textured_stream::TexturedStream>(
        a,
        &o,
        &words,
        jobs.len(),
        &format!(
            "textured-stream ({}, {}x{} texels)",
            method.name(),
            s.texture.width(),
            s.texture.height()
        ),
    )
}

/// What every `stream --method` writes: the simulation on `sim` of stream top `T` built with
/// `o`, fed `words` until `records` records have ended, then `setup.txt` (the words, sent in
/// `order`), `beats.txt` (the beats the simulation delivers; z = 0 for a top without
/// `m_axis_tuser`) and the top's Verilog. Returns the beats and the clocks to the last one.
fn simulate_and_write<T: StreamTop + rtl::core::registry::RtlBlock>(
    dir: &std::path::Path,
    o: &rtl::core::registry::Options,
    words: &[Word],
    records: u64,
    order: &str,
    sim: crate::sim::Sim,
) -> Result<(Vec<Beat>, u64)> {
    let block = T::NAME;
    let top = rtl::stream::layout::TOPS
        .iter()
        .find(|t| t.block == block)
        .ok_or_else(|| anyhow!("{block} is not a stream top"))?;
    let b = flow::blocks::find(block).map_err(|e| anyhow!(e))?;
    let design = b.design(o).map_err(|e| anyhow!(e))?;
    crate::sim::prepare(sim, vec![design], &indicatif::MultiProgress::new())?;
    let mut model = b.model(o, sim).map_err(|e| anyhow!(e))?;
    let mut beats = Vec::new();
    // A record's walk is at most 4096 × 4096 addresses; every word takes at least a clock.
    let max_clocks = 64 + words.len() as u64 * 64 + records.max(1) * (1 << 24);
    let stats = drive_beats::<T>(
        model.as_mut(),
        block,
        "records",
        words,
        records,
        max_clocks,
        &mut |bt, _| beats.push(bt),
    )
    .map_err(|e| anyhow!(e))?;
    let tuser = top.tuser.is_some();
    let mut setup = format!("# {block} set-up words ({order} order): hex word, tlast\n");
    for (w, last) in words {
        setup.push_str(&format!("{w:08x} {}\n", *last as u8));
    }
    let mut text = format!(
        "# {block} fragment beats: x y pixel red green blue z tlast (tlast: {}{})\n",
        top.tlast,
        if tuser { "" } else { "; z: 0, no tuser" }
    );
    for bt in &beats {
        text.push_str(&format!(
            "{} {} {} {} {} {} {} {}\n",
            bt.x, bt.y, bt.pixel as u8, bt.rgb[0], bt.rgb[1], bt.rgb[2], bt.z, bt.last as u8
        ));
    }
    let verilog = b.verilog(o).map_err(|e| anyhow!(e))?;
    write_files(
        dir,
        &[
            ("setup.txt", setup.as_str()),
            ("beats.txt", text.as_str()),
            (&format!("{}.v", b.module_name()), verilog.as_str()),
        ],
    )?;
    Ok((beats, stats.clocks))
}

fn write_files(dir: &std::path::Path, files: &[(&str, &str)]) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    for (name, body) in files {
        crate::output::write_whole(&dir.join(name), body.as_bytes())?;
    }
    Ok(())
}

/// `stream --method gouraud`: the scene through `gouraud-stream` (beats.txt's `z` column is 0:
/// the top has no `tuser`).
fn run_gouraud(a: &Args) -> Result<()> {
    use pipeline::gouraud::TriangleJob;
    let s = crate::setup::build(&a.scene)?;
    s.ensure_drawn()?;
    let jobs: Vec<TriangleJob> = s
        .tris
        .iter()
        .filter_map(|t| TriangleJob::gouraud(t, &s.ctx))
        .collect();
    let order = a
        .setup_order
        .of_addrs(&jobs.iter().map(|j| j.addr).collect::<Vec<_>>());
    let jobs: Vec<TriangleJob> = order.iter().map(|&i| jobs[i]).collect();
    stream_triangles::<rtl::stream::gouraud_stream::GouraudStream>(
        a,
        &rtl::core::registry::Options::new(),
        &pipeline::gouraud::gouraud_words(&jobs),
        jobs.len(),
        "gouraud-stream",
    )
}
