//! `shadecore render`: the reference and every method on one scene; PNGs, diffs, a contact
//! sheet, `report.json`, and the NMSE table.

use std::collections::BTreeMap;
use std::path::PathBuf;

use anyhow::{Context, Result};
use golden::methods::Method;
use golden::nmse::{self, Band};
use golden::render::Frame;
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use pipeline::textured::TEXTURED_RTL_METHODS;
use rayon::prelude::*;
use serde::Serialize;

use crate::output::{save_png, sheet};
use crate::setup::{build, SceneArgs, Setup};

/// Which model computes the pixels.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Engine {
    /// Both: every method through the golden model, and every method the hardware has through
    /// the simulated RTL as well (the default: the main job).
    Both,
    /// The f64 golden model.
    Golden,
    /// The rust-hdl RTL simulated clock by clock (methods: gouraud through the raster pipe
    /// (or the four-triangle block with --address four-triangle); subdivision through the
    /// four-triangle block and four BVIs;
    /// normalizer, normalizer-fit, normalizer-pw, brdf-k4, brdf-k8, brdf-k16, bump through the
    /// lit pixel pipeline; angular, fast, fast-fit through the span pipelines, two pixels per clock;
    /// cubic through the Horner units (--horner); texture, texture-quadratic and
    /// texture-bezier through the textured pixel pipeline, built additive (SPEC §14),
    /// quadratic (§15) and bezier (§16); without --method, all of them).
    Rtl,
}

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Methods to render, comma-separated (default: all, the textured ones where the scene has
    /// texture coordinates; with `--engine rtl`, all the hardware has). Names: flat, gouraud,
    /// subdivision, normalizer, normalizer-fit, normalizer-pw, fast, fast-fit, angular,
    /// quadric, cubic, brdf-k4, brdf-k8, brdf-k16, bump; the textured methods texture,
    /// texture-quadratic, texture-bezier, texture-affine (judged against texture-reference,
    /// rendered with them).
    #[arg(long, value_delimiter = ',')]
    pub method: Vec<String>,
    /// Output directory.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Engine computing the method images (the reference is always golden). `both` (the
    /// default) renders every method through the golden model and every method the hardware has
    /// through the simulated RTL, methods in parallel, one pipeline instance each.
    #[arg(long, value_enum, default_value = "both")]
    pub engine: Engine,
    /// With the RTL engine (`rtl`, `both`): the Horner units `cubic` goes through — serial (fig. 2.6, one
    /// multiplier, 3 clocks per pixel; the default) or pipelined (three multipliers, one pixel
    /// per clock). The images are identical; the clock counts differ.
    #[arg(long, value_enum)]
    pub horner: Option<Horner>,
    /// With the RTL engine (`rtl`, `both`): the simulator — verilator (the exported Verilog,
    /// verilated once per block into a library cached under target/verilated and stepped in
    /// process) or rust-hdl (stepped by hand, about 400 times slower). Default: verilator when
    /// it is installed. The frames are bit-identical.
    #[arg(long, value_enum)]
    pub sim: Option<crate::sim::SimArg>,
    /// With the RTL engine (`rtl`, `both`): the address block — single (SPEC §5, one address per clock) or
    /// four-triangle (SPEC §7, four lanes with a BVI each: gouraud and subdivision only).
    /// Default: single, four-triangle for subdivision.
    #[arg(long, value_enum)]
    pub address: Option<crate::rtl_engine::Address>,
    /// With the RTL engine: the top the lit methods (normalizer, normalizer-fit, normalizer-pw,
    /// brdf-k*, bump), gouraud, the span methods (cubic, angular, fast, fast-fit, quadric) and
    /// subdivision go through — stream (`pixel-stream`, `gouraud-stream`, `cubic-stream`,
    /// `angular-stream`, `fast-stream`, `quadric-stream`, `subdivision-stream`: AXI4-Stream
    /// set-up records and fragment beats) or pipeline (`pixel-pipeline`, `gouraud-raster`, the
    /// span pipelines, `subdivision-raster`: set-up on load ports). Default: stream for
    /// the lit methods and gouraud (the span methods and subdivision: pipeline, as
    /// their per-line and per-parent records make the stream set-up bound on short lines and
    /// small triangles; texture, texture-quadratic and texture-bezier: pipeline, as the
    /// texture's records, four clocks a texel, would dominate their clocks). The images are
    /// identical; the clock counts differ (the set-up stream carries 27 words per lit
    /// triangle, 23 per Gouraud one, 12 per cubic line, 72 per subdivision parent, 51 per
    /// textured triangle and 17 per textured line record).
    #[arg(long, value_enum)]
    pub lit_top: Option<crate::rtl_engine::LitTop>,
    /// With the RTL engine: the order the lit methods' and gouraud's triangles are sent in — balanced (large
    /// and small walks alternately, so small triangles' set-up words stream in while large
    /// ones are walked; the default) or mesh. The images are identical (at equal depth the
    /// lower triangle index wins); the clock counts differ.
    #[arg(long, value_enum)]
    pub setup_order: Option<crate::rtl_engine::SetupOrder>,
}

/// The Horner unit variant of the cubic pipeline.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Horner {
    Serial,
    Pipelined,
}

/// Per-method result in `report.json`.
#[derive(Serialize, Debug, Clone)]
pub struct MethodReport {
    /// Against the reference (Phong shading, exact normalization; for a textured method
    /// `texture-reference`): the golden image's, or with `--engine rtl` the RTL image's.
    pub nmse: f64,
    pub band: Band,
    pub max_abs_diff: u8,
    /// With `--engine rtl`: the RTL image against the golden image of the same method.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rtl_vs_golden: Option<RtlComparison>,
    /// With `--engine both`, for a method the hardware has: the RTL image against the
    /// reference, and against the golden image of the same method.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rtl: Option<RtlReport>,
}

/// The RTL image of a method (`--engine both`).
#[derive(Serialize, Debug, Clone)]
pub struct RtlReport {
    /// Against the reference.
    pub nmse: f64,
    pub band: Band,
    pub max_abs_diff: u8,
    /// Against the golden image of the same method, with the hardware's counters.
    pub vs_golden: RtlComparison,
}

/// The RTL image of a method against its golden image.
#[derive(Serialize, Debug, Clone)]
pub struct RtlComparison {
    pub nmse: f64,
    pub max_abs_diff: u8,
    pub pixels_differing: usize,
    pub clocks: u64,
    pub pixels: u64,
    pub pixels_per_clock: f64,
    /// Pixels whose visible surface under the hardware's depth words differs from the f64
    /// depth planes' choice (0 where the engine tests depth in f64).
    pub visibility_mismatches: usize,
    /// Over those pixels, the largest f64 depth difference of the two surfaces (pixels).
    pub visibility_depth_gap: f64,
    /// Wall time of the simulation, seconds.
    pub seconds: f64,
}

#[derive(Serialize, Debug)]
struct Report<'a> {
    scene: &'a SceneArgs,
    engine: Engine,
    triangles: usize,
    methods: BTreeMap<String, MethodReport>,
    /// Every other output file of the folder, with its size and hash: `report.json` is
    /// written last, so a folder with a report holds exactly these files.
    files: BTreeMap<String, crate::output::FileEntry>,
}

/// Parse `--method` names (empty = every method).
pub fn parse_methods(names: &[String]) -> Result<Vec<Method>> {
    if names.is_empty() {
        let mut all = Method::ALL_NON_REFERENCE.to_vec();
        all.extend(Method::TEXTURED);
        return Ok(all);
    }
    let mut out: Vec<Method> = Vec::with_capacity(names.len());
    for n in names {
        let m = n
            .trim()
            .parse::<Method>()
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        // A method named twice is rendered and reported once.
        if !out.contains(&m) {
            out.push(m);
        }
    }
    Ok(out)
}

/// The reference images `methods` are judged against ([`Method::reference_of`]): `reference`,
/// and `texture-reference` when a textured method is among them; golden, from the undivided
/// mesh.
pub fn render_references(setup: &Setup, methods: &[Method]) -> References {
    let textured = methods
        .iter()
        .any(|m| m.reference_of() == Method::TextureReference)
        .then(|| render_setup(setup, &setup.base, Method::TextureReference));
    References {
        plain: render_setup(setup, &setup.base, Method::Reference),
        textured,
    }
}

/// The reference images of a render.
pub struct References {
    pub plain: Frame,
    /// `texture-reference`, when a textured method is rendered.
    pub textured: Option<Frame>,
}

impl References {
    /// The image `m` is judged against.
    pub fn of(&self, m: Method) -> &Frame {
        match m.reference_of() {
            Method::TextureReference => self.textured.as_ref().expect("rendered with its methods"),
            _ => &self.plain,
        }
    }
}

/// `m` on `tris` of the set-up, golden, with the set-up's texture.
fn render_setup(setup: &Setup, tris: &[golden::ScreenTriangle], m: Method) -> Frame {
    golden::render::render_textured(
        tris,
        m,
        &setup.ctx,
        &setup.texture,
        setup.width,
        setup.height,
    )
}

/// Render the references and `methods` with the golden engine, in parallel.
pub fn render_golden(
    setup: &Setup,
    methods: &[Method],
    bar: &ProgressBar,
) -> (References, Vec<Frame>) {
    let reference = render_references(setup, methods);
    bar.inc(1);
    let frames = methods
        .par_iter()
        .map(|&m| {
            let f = colours_only(render_setup(setup, &setup.tris, m));
            bar.inc(1);
            f
        })
        .collect();
    (reference, frames)
}

/// `f` with its colours only: the depth and fragment counts (12 of a frame's 15 bytes a
/// pixel) are not used once it is rendered, and a render holds a frame per method and
/// engine until its images are written.
fn colours_only(mut f: Frame) -> Frame {
    f.depth = Vec::new();
    f.fragments = Vec::new();
    f
}

/// Compare a method's frame with the reference.
pub fn compare(reference: &Frame, frame: &Frame) -> MethodReport {
    let nmse = nmse::nmse(&reference.rgb, &frame.rgb);
    MethodReport {
        nmse,
        band: Band::of(nmse),
        max_abs_diff: nmse::max_abs_diff(&reference.rgb, &frame.rgb),
        rtl_vs_golden: None,
        rtl: None,
    }
}

/// The progress bar of a render: one step per method plus the reference.
fn progress_bar(methods: usize, engine: Engine) -> ProgressBar {
    let bar = ProgressBar::new(methods as u64 + 1).with_style(
        ProgressStyle::with_template("{msg:>10} [{bar:40}] {pos}/{len} {elapsed}")
            .expect("static template")
            .progress_chars("=> "),
    );
    bar.set_message(format!("{engine:?}").to_lowercase());
    bar
}

/// The frames of one render: the reference, and per method the golden frame and/or the RTL
/// frame with the hardware's counters.
struct Frames {
    reference: References,
    golden: Vec<Option<Frame>>,
    rtl: Vec<Option<(Frame, RtlStats)>>,
}

/// The hardware's counters of one RTL method render.
struct RtlStats {
    pipe: pipeline::axis::PipeStats,
    visibility_mismatches: usize,
    visibility_depth_gap: f64,
    seconds: f64,
}

/// One method's RTL render: its frame and counters, or the error that stopped it.
type RtlResult = Result<(Frame, RtlStats)>;

/// Rough simulation cost of a method on the rust-hdl engine (clocks × the pipeline's size),
/// to start the longest first.
fn rtl_cost(m: Method) -> u32 {
    match m {
        Method::Cubic => 30,
        m if pipeline::lit::LIT_METHODS.contains(&m) => 16,
        m if pipeline::textured::TEXTURED_RTL_METHODS.contains(&m) => 18,
        m if pipeline::span::SPAN_METHODS.contains(&m) => 6,
        _ => 2,
    }
}

/// Render `methods` through the simulated hardware, in parallel: one worker per core, each
/// taking the next method (the costliest first) with its own pipeline instance. Each frame is
/// the one a sequential run gives (a method's triangles go through one pipeline in order).
fn render_rtl_parallel(
    setup: &Setup,
    methods: &[Method],
    build: crate::rtl_engine::RtlBuild,
    multi: &MultiProgress,
    ticker: &crate::output::LogTicker,
) -> Result<Vec<(Frame, RtlStats)>> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;
    let mut order: Vec<usize> = (0..methods.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(rtl_cost(methods[i])));
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<RtlResult>>> =
        Mutex::new((0..methods.len()).map(|_| None).collect());
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(methods.len().max(1));
    let overall = multi.add(ProgressBar::new(methods.len() as u64));
    ticker.watch("rtl methods done", &overall);
    overall.set_style(
        ProgressStyle::with_template("rtl methods [{bar:40}] {pos}/{len} done {elapsed}")
            .expect("static template")
            .progress_chars("=> "),
    );
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&i) = order.get(k) else { break };
                let m = methods[i];
                let bar = multi.insert_before(&overall, ProgressBar::new(0));
                bar.set_style(
                    ProgressStyle::with_template(&format!(
                        "  rtl {:<15} [{{bar:30}}] {{pos}}/{{len}} {} {{elapsed}} (eta {{eta}})",
                        m.name(),
                        if pipeline::span::SPAN_METHODS.contains(&m) {
                            "lines"
                        } else {
                            "triangles"
                        }
                    ))
                    .expect("static template")
                    .progress_chars("=> "),
                );
                ticker.watch(&format!("rtl {m}"), &bar);
                let t0 = std::time::Instant::now();
                let r = crate::rtl_engine::render_rtl_with(&setup, m, build, &bar)
                    .with_context(|| format!("method {m}"))
                    .map(|rtl| {
                        (
                            colours_only(rtl.frame),
                            RtlStats {
                                pipe: rtl.stats,
                                visibility_mismatches: rtl.visibility_mismatches,
                                visibility_depth_gap: rtl.visibility_depth_gap,
                                seconds: t0.elapsed().as_secs_f64(),
                            },
                        )
                    });
                bar.finish_and_clear();
                overall.inc(1);
                let failed = r.is_err();
                results.lock().expect("no worker panicked")[i] = Some(r);
                if failed {
                    // Stop handing out work: the first error ends the run.
                    next.store(order.len(), Ordering::Relaxed);
                }
            });
        }
    });
    overall.finish_and_clear();
    // The error that stopped the run names its method and cause, whichever method's slot
    // comes first (methods after it in the list may not have started).
    let results = results.into_inner().expect("no worker panicked");
    if let Some(e) = results.iter().flatten().find_map(|r| r.as_ref().err()) {
        return Err(anyhow::anyhow!("{e:#}"));
    }
    Ok(results.into_iter().flatten().flatten().collect())
}

/// Render the reference (always golden) and `methods` with `engine`.
fn render_frames(
    setup: &Setup,
    methods: &[Method],
    engine: Engine,
    build: crate::rtl_engine::RtlBuild,
) -> Result<Frames> {
    let n = methods.len();
    // The methods the hardware renders: with `rtl` all (each must have hardware); with `both`
    // those it has, the textured ones only with a texture the texture memory holds (`run`
    // notes it).
    let idx: Vec<usize> = if engine == Engine::Golden {
        Vec::new()
    } else {
        if engine == Engine::Rtl {
            for &m in methods {
                crate::rtl_engine::check_rtl_method(m)?;
            }
        }
        let hw = crate::rtl_engine::rtl_methods();
        let fits = texture_fits(setup).is_ok();
        (0..n)
            .filter(|&i| hw.contains(&methods[i]))
            .filter(|&i| {
                engine == Engine::Rtl || fits || !TEXTURED_RTL_METHODS.contains(&methods[i])
            })
            .collect()
    };
    // A scene the hardware refuses (addresses, the span set-up's memory) fails before the
    // golden pass, not after it.
    let scene = setup.scene();
    for &i in &idx {
        pipeline::render::check_scene(&scene, methods[i])
            .map_err(|e| anyhow::anyhow!(e))
            .with_context(|| format!("method {}", methods[i]))?;
    }
    let multi = MultiProgress::new();
    let ticker = crate::output::LogTicker::start("render");
    let (reference, golden) = if engine == Engine::Rtl {
        (render_references(setup, methods), vec![None; n])
    } else {
        let bar = multi.add(progress_bar(n, Engine::Golden));
        ticker.watch("golden images", &bar);
        let (r, f) = render_golden(setup, methods, &bar);
        bar.finish_and_clear();
        (r, f.into_iter().map(Some).collect())
    };
    let mut rtl: Vec<Option<(Frame, RtlStats)>> = (0..n).map(|_| None).collect();
    if engine != Engine::Golden {
        let ms: Vec<Method> = idx.iter().map(|&i| methods[i]).collect();
        crate::sim::prepare(build.sim, crate::rtl_engine::designs(&ms, build)?, &multi)?;
        for (i, f) in idx
            .into_iter()
            .zip(render_rtl_parallel(setup, &ms, build, &multi, &ticker)?)
        {
            rtl[i] = Some(f);
        }
    }
    Ok(Frames {
        reference,
        golden,
        rtl,
    })
}

/// For an RTL frame of method `m`: write the golden image of the same method and the
/// RTL-vs-golden heat map, and measure how far the hardware is from the golden model.
fn compare_with_golden(
    setup: &Setup,
    m: Method,
    frame: &Frame,
    rtl: &RtlStats,
    golden: Option<&Frame>,
    out: &std::path::Path,
) -> Result<RtlComparison> {
    let stats = &rtl.pipe;
    let (w, h) = (setup.width, setup.height);
    let rendered;
    let golden = match golden {
        Some(g) => g,
        None => {
            rendered = render_setup(setup, &setup.tris, m);
            save_png(
                &out.join(format!("{}-golden.png", m.name())),
                w,
                h,
                &rendered.rgb,
            )?;
            &rendered
        }
    };
    let heat = nmse::diff_heatmap(&golden.rgb, &frame.rgb, 4);
    save_png(
        &out.join(format!("{}-rtl-vs-golden-diff.png", m.name())),
        w,
        h,
        &heat,
    )?;
    Ok(RtlComparison {
        nmse: nmse::nmse(&golden.rgb, &frame.rgb),
        max_abs_diff: nmse::max_abs_diff(&golden.rgb, &frame.rgb),
        pixels_differing: golden
            .rgb
            .iter()
            .zip(&frame.rgb)
            .filter(|(a, b)| a != b)
            .count(),
        clocks: stats.clocks,
        pixels: stats.pixels,
        pixels_per_clock: stats.pixels_per_clock(),
        visibility_mismatches: rtl.visibility_mismatches,
        visibility_depth_gap: rtl.visibility_depth_gap,
        seconds: rtl.seconds,
    })
}

/// A sheet column: the golden tile (label, image) and the RTL tile under it, if any.
type SheetColumn<'a> = (
    String,
    Option<&'a [[u8; 3]]>,
    Option<(String, &'a [[u8; 3]])>,
);

/// Write every image (reference, each method with its diff against the reference, the RTL
/// comparisons, the sheet) and return the per-method reports.
///
/// Files: `<method>.png` and `<method>-diff.png` (against the reference) for the engine's
/// image — the golden one, or the RTL one with `--engine rtl` (beside `<method>-golden.png`);
/// with `--engine both` also `<method>-rtl.png` and `<method>-rtl-diff.png`; with either RTL
/// engine `<method>-rtl-vs-golden-diff.png`. The sheet has the golden row and, under each
/// method the hardware has, its RTL image.
fn write_images(
    setup: &Setup,
    methods: &[Method],
    frames: &Frames,
    out: &std::path::Path,
) -> Result<BTreeMap<String, MethodReport>> {
    let (w, h) = (setup.width, setup.height);
    let cols = 5;
    save_png(
        &out.join("reference.png"),
        w,
        h,
        &frames.reference.plain.rgb,
    )?;
    let mut reports = BTreeMap::new();
    let mut tiles: Vec<SheetColumn> = vec![(
        "reference".into(),
        Some(&frames.reference.plain.rgb[..]),
        None,
    )];
    // The textured methods start a row of the sheet, after their reference.
    let mut order: Vec<usize> = (0..methods.len()).collect();
    order.sort_by_key(|&i| methods[i].is_textured());
    let mut textured_row = false;
    for i in order {
        let m = methods[i];
        if m.is_textured() && !textured_row {
            textured_row = true;
            let t = frames
                .reference
                .textured
                .as_ref()
                .expect("rendered with its methods");
            save_png(&out.join("texture-reference.png"), w, h, &t.rgb)?;
            while !tiles.len().is_multiple_of(cols) {
                tiles.push((String::new(), None, None));
            }
            tiles.push(("texture-reference".into(), Some(&t.rgb[..]), None));
        }
        let reference = frames.reference.of(m);
        let golden = frames.golden[i].as_ref();
        let rtl = frames.rtl[i].as_ref();
        // The engine's image for `<method>.png`: golden, or the RTL one under `--engine rtl`.
        let main = golden.or(rtl.map(|r| &r.0)).expect("a frame per method");
        let mut r = compare(reference, main);
        save_png(&out.join(format!("{}.png", m.name())), w, h, &main.rgb)?;
        let heat = nmse::diff_heatmap(&reference.rgb, &main.rgb, 32);
        save_png(&out.join(format!("{}-diff.png", m.name())), w, h, &heat)?;
        let mut rtl_tile = None;
        if let Some((f, stats)) = rtl {
            let vs = compare_with_golden(setup, m, f, stats, golden, out)?;
            if golden.is_some() {
                save_png(&out.join(format!("{}-rtl.png", m.name())), w, h, &f.rgb)?;
                let heat = nmse::diff_heatmap(&reference.rgb, &f.rgb, 32);
                save_png(&out.join(format!("{}-rtl-diff.png", m.name())), w, h, &heat)?;
                let c = compare(reference, f);
                rtl_tile = Some((
                    format!("rtl {:.2e} {}lsb", c.nmse, vs.max_abs_diff),
                    &f.rgb[..],
                ));
                r.rtl = Some(RtlReport {
                    nmse: c.nmse,
                    band: c.band,
                    max_abs_diff: c.max_abs_diff,
                    vs_golden: vs,
                });
            } else {
                r.rtl_vs_golden = Some(vs);
            }
        }
        tiles.push((
            format!("{} {:.2e}", m.name(), r.nmse),
            Some(&main.rgb[..]),
            rtl_tile,
        ));
        reports.insert(m.name().to_string(), r);
    }
    let grid: Vec<(String, Option<&[[u8; 3]]>)> =
        if frames.rtl.iter().any(Option::is_some) && frames.golden.iter().any(Option::is_some) {
            // Bands of two rows: golden images, then the RTL image under each (blank where the
            // hardware has no such method; no second row where none of the band has).
            let mut g = Vec::new();
            for band in tiles.chunks(cols) {
                g.extend(band.iter().map(|(l, img, _)| (l.clone(), *img)));
                g.extend(std::iter::repeat_n(
                    (String::new(), None),
                    cols - band.len(),
                ));
                if band.iter().all(|(_, _, r)| r.is_none()) {
                    continue; // no method of the band has hardware (the textured row)
                }
                g.extend(band.iter().map(|(_, _, r)| match r {
                    Some((l, img)) => (l.clone(), Some(*img)),
                    None => (String::new(), None),
                }));
            }
            g
        } else {
            tiles.iter().map(|(l, img, _)| (l.clone(), *img)).collect()
        };
    let s = sheet(&grid, w, h, cols as u32);
    save_png(&out.join("sheet.png"), s.width, s.height, &s.rgb)?;
    Ok(reports)
}

/// Print the NMSE table (and the RTL comparisons) of `report`.
fn print_table(args: &Args, setup: &Setup, methods: &[Method], report: &Report) -> Result<()> {
    crate::outln!(
        "{} n {} light {}° {}x{} {:?} lighting, {} front-facing triangles{}, engine {:?}",
        args.scene.describe(),
        args.scene.shininess,
        args.scene.light_deg,
        setup.width,
        setup.height,
        args.scene.lighting,
        setup.tris.len(),
        if setup.tris.len() != setup.base.len() {
            format!(" ({} before subdivision)", setup.base.len())
        } else {
            String::new()
        },
        args.engine
    )?;
    if args.engine == Engine::Both {
        crate::outln!(
            "{:<18} {:>10} {:>10}  {:<22} {:>13} {:>9} {:>9} {:>7}",
            "method",
            "golden",
            "rtl",
            "band (golden)",
            "rtl vs golden",
            "other vis",
            "px/clock",
            "rtl s"
        )?;
        for m in methods {
            let r = &report.methods[m.name()];
            match &r.rtl {
                Some(t) => crate::outln!(
                    "{:<18} {:>10.3e} {:>10.3e}  {:<22} {:>9} LSB {:>9} {:>9.3} {:>7.1}",
                    m.name(),
                    r.nmse,
                    t.nmse,
                    r.band.label(),
                    t.vs_golden.max_abs_diff,
                    t.vs_golden.visibility_mismatches,
                    t.vs_golden.pixels_per_clock,
                    t.vs_golden.seconds
                )?,
                None => crate::outln!(
                    "{:<18} {:>10.3e} {:>10}  {:<22} {:>13}",
                    m.name(),
                    r.nmse,
                    "-",
                    r.band.label(),
                    "no hardware"
                )?,
            }
        }
        crate::outln!("NMSE against the reference (the textured methods: against texture-reference); \"rtl vs golden\": largest channel difference between the RTL and golden images of the same method; \"other vis\": pixels where the hardware's depth words show another surface than the f64 depth planes")?;
        return Ok(());
    }
    crate::outln!("{:<18} {:>12} {:>6}  band", "method", "NMSE", "max Δ")?;
    for m in methods {
        let r = &report.methods[m.name()];
        crate::outln!(
            "{:<18} {:>12.3e} {:>6}  {}",
            m.name(),
            r.nmse,
            r.max_abs_diff,
            r.band.label()
        )?;
        if let Some(c) = &r.rtl_vs_golden {
            crate::outln!(
                "  rtl vs golden {}: NMSE {:.3e}, max {} LSB, {} pixels differ; {} pixels in {} clocks ({:.3} pixels/clock, {:.1} s, {:.0} clocks/s); {} pixels with other visibility{}",
                m.name(), c.nmse, c.max_abs_diff, c.pixels_differing, c.pixels, c.clocks, c.pixels_per_clock,
                c.seconds, c.clocks as f64 / c.seconds.max(1e-9), c.visibility_mismatches,
                if c.visibility_mismatches > 0 {
                    format!(" (their two surfaces at most {:.2e} pixels apart in depth)", c.visibility_depth_gap)
                } else {
                    String::new()
                }
            )?;
        }
    }
    Ok(())
}

/// An error naming the flag when an RTL engine flag is given that has no effect: with `--engine
/// golden`, or when no method it concerns goes through the hardware.
fn check_rtl_flags(args: &Args, methods: &[Method]) -> Result<()> {
    use pipeline::{lit::LIT_METHODS, span::SPAN_METHODS};
    let hw: Vec<Method> = if args.engine == Engine::Golden {
        Vec::new()
    } else {
        let has = crate::rtl_engine::rtl_methods();
        methods
            .iter()
            .copied()
            .filter(|m| has.contains(m))
            .collect()
    };
    let any = |f: &dyn Fn(Method) -> bool| hw.iter().any(|&m| f(m));
    for (given, flag, concerns, applies) in [
        (
            args.sim.is_some(),
            "--sim",
            "any hardware method",
            any(&|_| true),
        ),
        (
            args.horner.is_some(),
            "--horner",
            "cubic",
            any(&|m| m == Method::Cubic),
        ),
        (
            args.address.is_some(),
            "--address",
            "gouraud or subdivision",
            any(&|m| matches!(m, Method::Gouraud | Method::Subdivision)),
        ),
        (
            args.lit_top.is_some(),
            "--lit-top",
            "the lit methods, gouraud, the span methods, subdivision or the textured ones",
            any(&|m| {
                LIT_METHODS.contains(&m)
                    || SPAN_METHODS.contains(&m)
                    || pipeline::textured::TEXTURED_RTL_METHODS.contains(&m)
                    || matches!(m, Method::Gouraud | Method::Subdivision)
            }),
        ),
        (
            args.setup_order.is_some(),
            "--setup-order",
            "the lit methods or gouraud",
            any(&|m| LIT_METHODS.contains(&m) || m == Method::Gouraud),
        ),
    ] {
        if given && !applies {
            if args.engine == Engine::Golden {
                anyhow::bail!(
                    "{flag} has no effect with --engine golden (it chooses how the RTL engine renders: use --engine rtl or both)"
                );
            }
            anyhow::bail!(
                "{flag} has no effect here: it concerns {concerns}, and no such method is rendered through the hardware"
            );
        }
    }
    Ok(())
}

/// Whether the texture memory of `textured-pipeline` holds the set-up's texture (2^16 texels);
/// the one-line reason if not.
fn texture_fits(setup: &Setup) -> std::result::Result<(), String> {
    let (w, h) = (setup.texture.width(), setup.texture.height());
    if (w as u64) * (h as u64) > 1 << golden::units::texture_memory::ADDRESS_BITS {
        Err(format!(
            "a {w}x{h} texture does not fit the texture memory (2^16 texels)"
        ))
    } else {
        Ok(())
    }
}

pub fn run(args: Args) -> Result<()> {
    let mut methods = if args.engine == Engine::Rtl && args.method.is_empty() {
        // The RTL engine's default: every method the hardware has.
        crate::rtl_engine::rtl_methods()
    } else {
        parse_methods(&args.method)?
    };
    check_rtl_flags(&args, &methods)?;
    let setup = build(&args.scene)?;
    setup.ensure_drawn()?;
    if args.method.is_empty() {
        // The default list: the textured methods only where the scene can be textured (a mesh
        // with texture coordinates, within the texture-coordinate block's range).
        if let Err(e) = setup.check_textured(&methods, &args.scene.scene) {
            methods.retain(|m| !m.is_textured());
            eprintln!("note: the textured methods are left out: {e:#}");
        }
    } else {
        setup.check_textured(&methods, &args.scene.scene)?;
    }
    let hw_textured: Vec<Method> = methods
        .iter()
        .copied()
        .filter(|m| TEXTURED_RTL_METHODS.contains(m))
        .collect();
    if args.engine != Engine::Golden && !hw_textured.is_empty() {
        if let Err(e) = texture_fits(&setup) {
            let names = hw_textured
                .iter()
                .map(|m| m.name())
                .collect::<Vec<_>>()
                .join(", ");
            let is = if hw_textured.len() == 1 { "is" } else { "are" };
            match (args.engine, args.method.is_empty()) {
                (Engine::Rtl, false) => {
                    anyhow::bail!("method {} through the hardware: {e}", hw_textured[0])
                }
                (Engine::Rtl, true) => {
                    methods.retain(|m| !TEXTURED_RTL_METHODS.contains(m));
                    eprintln!("note: {names} {is} left out: {e}");
                }
                _ => eprintln!("note: {names} {is} rendered golden only: {e}"),
            }
        }
    }
    let dir = crate::output::RenderDir::open(&args.out)?;
    let sim = if args.engine == Engine::Golden {
        crate::sim::Sim::RustHdl
    } else {
        crate::sim::resolve(args.sim)?
    };
    let build = crate::rtl_engine::RtlBuild {
        horner_pipelined: args.horner == Some(Horner::Pipelined),
        sim,
        address: args.address.unwrap_or_default(),
        lit_top: args.lit_top.unwrap_or_default(),
        setup_order: args.setup_order.unwrap_or_default(),
    };
    let t0 = std::time::Instant::now();
    let frames = render_frames(&setup, &methods, args.engine, build)?;
    let seconds = t0.elapsed().as_secs_f64();
    let reports = write_images(&setup, &methods, &frames, &args.out)?;
    let report = Report {
        scene: &args.scene,
        engine: args.engine,
        triangles: setup.tris.len(),
        methods: reports,
        files: dir.files()?,
    };
    let json = serde_json::to_string_pretty(&report).expect("report serializes");
    dir.finish(&(json + "\n"))?;
    print_table(&args, &setup, &methods, &report)?;
    crate::outln!("wrote {} ({seconds:.1} s)", args.out.display())?;
    Ok(())
}
