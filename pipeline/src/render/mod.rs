//! One way through the pipeline: [`render`] takes a scene and a method and gives the frame the
//! simulated hardware draws.
//!
//! Each method family implements [`Family`] once — its set-up records, the top it steps
//! (`crate::gouraud::Pipe`, `crate::subdivision::SubPipe`, `crate::lit::LitPipe`,
//! `crate::span::SpanPipe`, each on either simulator and through its ports or its AXI4-Stream
//! top) and its fragment-to-frame step; [`family`] picks the family of a method and
//! [`Options`]. The textured family (`crate::textured::TexturedPipe`) renders `texture`
//! through `textured-pipeline` (or, when asked, `textured-stream`), `texture-quadratic` and
//! `texture-bezier` through `textured-pipeline` built `texture=quadratic`, `texture=bezier`
//! (its ports only).
//!
//! Every triangle the golden renderer would draw (the same list, in the same order; zero-area
//! triangles skipped as `golden::render::render` skips them) gets its set-up in software and is
//! fed to the hardware. **Depth**: the Gouraud and subdivision families resolve it as the golden
//! renderer does (the triangle's f64 depth plane at the pixel centre, nearer wins, at equal depth
//! the lower mesh index); the lit and span families test the hardware's own z words
//! ([`frame::FrameWriter`]) and count the pixels where that picks another triangle than the f64
//! planes would.

mod families;
pub mod frame;

use golden::methods::Method;
use golden::render::Frame;
use golden::shade::ShadeContext;
use golden::types::{ScreenTriangle, MAX_ADDRESS};

use crate::axis::PipeStats;
use crate::lit::LIT_METHODS;
use crate::span::SPAN_METHODS;
use crate::textured::TEXTURED_RTL_METHODS;
use flow::engine::Sim;

/// What is drawn: the screen triangles (mesh order), the shading context, the canvas.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    pub tris: &'a [ScreenTriangle],
    pub ctx: &'a ShadeContext,
    pub width: u32,
    pub height: u32,
    /// The texture the textured methods read (`None`: the built-in one,
    /// `golden::texture::Texture::builtin`, as `golden::render::render` reads).
    pub texture: Option<&'a golden::texture::Texture>,
}

/// A render through the hardware: the frame and the hardware's clock counts.
#[derive(Clone, Debug)]
pub struct Rendered {
    pub frame: Frame,
    pub stats: PipeStats,
    /// Lit and span families only: pixels whose visible triangle under the hardware's depth
    /// words differs from the one the f64 depth planes pick (surfaces closer than the z format
    /// resolves); 0 where the depth test uses the f64 planes.
    pub visibility_mismatches: usize,
    /// Over those pixels, the largest difference of the two surfaces' f64 depths (pixels; 0
    /// when there are none): how close two surfaces are where the depth words decide
    /// otherwise than the f64 planes.
    pub visibility_depth_gap: f64,
}

/// Progress of a render: how many set-up records (triangles, parents, lines) there are, then
/// how many the hardware has finished.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tick {
    Total(u64),
    Done(u64),
}

/// The order in which the driver sends the triangles (`--setup-order`). The images do not
/// depend on it (the frame writers' tie rule); the clock counts do.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum SetupOrder {
    /// Large and small walks alternately (`crate::lit::balanced_order`), so the 26-word
    /// set-up records of small triangles stream in while large ones are walked.
    #[default]
    Balanced,
    /// The mesh's order.
    Mesh,
}

impl SetupOrder {
    /// The indices of `jobs` in sending order.
    pub fn of(self, jobs: &[crate::lit::LitJob]) -> Vec<usize> {
        self.of_addrs(&jobs.iter().map(|j| j.addr).collect::<Vec<_>>())
    }

    /// The order of triangles given by their address set-ups.
    pub fn of_addrs(self, addrs: &[golden::units::address_block::AddressSetup]) -> Vec<usize> {
        match self {
            SetupOrder::Balanced => crate::axis::balanced_order_of(addrs),
            SetupOrder::Mesh => (0..addrs.len()).collect(),
        }
    }
}

/// The top the lit methods' and `gouraud`'s frames go through (`--lit-top`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum LitTop {
    /// `stream` for the lit methods and `gouraud` (single address block), `pipeline` for the
    /// span methods and `subdivision`.
    #[default]
    Default,
    /// `pixel-stream` / `gouraud-stream` / `cubic-stream` / `angular-stream` / `fast-stream` /
    /// `quadric-stream` / `textured-stream`: set-up records on a 32-bit AXI4-Stream, fragment
    /// beats out (the span methods only when asked: their per-line records make short lines
    /// set-up bound; `texture` only when asked: its texture's records would dominate the clocks).
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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
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

/// Build choices of a render beyond the method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
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

impl Default for Options {
    /// Every choice at its default; the simulator the fastest installed ([`Sim::fastest`]).
    fn default() -> Self {
        Options {
            horner_pipelined: false,
            sim: Sim::fastest(),
            address: Address::default(),
            lit_top: LitTop::default(),
            setup_order: SetupOrder::default(),
        }
    }
}

/// A method family: how its methods go through the hardware.
pub trait Family {
    /// The Verilator design its render steps (to compile several before a run, in parallel).
    fn design(&self, o: &Options) -> Result<verilated::Design, String>;
    /// The scene's set-up records through its top, its fragments into a frame (the scene
    /// passed [`check_scene`]).
    fn render(&self, scene: &Scene, o: &Options, progress: Progress) -> Result<Rendered, String>;
}

/// Where a render reports its progress.
pub type Progress<'a> = &'a mut dyn FnMut(Tick);

/// The methods the hardware renders, in order: Gouraud, subdivision, the lit pipeline's, the
/// span pipelines', the textured pipeline's.
pub fn methods() -> Vec<Method> {
    [Method::Gouraud, Method::Subdivision]
        .into_iter()
        .chain(LIT_METHODS)
        .chain(SPAN_METHODS)
        .chain(TEXTURED_RTL_METHODS)
        .collect()
}

/// [`methods`], comma-separated.
pub fn method_names() -> String {
    methods()
        .iter()
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// An error naming the methods the hardware has, unless it has `m`.
pub fn check_method(m: Method) -> Result<(), String> {
    if methods().contains(&m) {
        Ok(())
    } else {
        Err(format!(
            "the rtl engine has no hardware for method {m} (it has: {})",
            method_names()
        ))
    }
}

/// The checks of `scene` that `render` makes for `method` before its first clock, without
/// rendering anything: the canvas and vertex addresses, and for a span method the per-line
/// set-up's memory budget. `shadecore render` runs them before the reference image, so a
/// scene the hardware refuses fails at once rather than after the golden pass.
pub fn check_scene(scene: &Scene, method: Method) -> Result<(), String> {
    check_method(method)?;
    check_addresses(scene.tris, scene.width, scene.height)?;
    if crate::span::SPAN_METHODS.contains(&method) {
        crate::span::check_span_budget(scene.tris)?;
    }
    Ok(())
}

/// The family that renders `method` with `o` (an error for a method without hardware, or an
/// address block the method cannot go through).
pub fn family(method: Method, o: &Options) -> Result<Box<dyn Family>, String> {
    check_method(method)?;
    Ok(match (method, o.address) {
        (Method::Gouraud | Method::Subdivision, Address::FourTriangle)
        | (Method::Subdivision, Address::Default) => Box::new(families::Subdivision(method)),
        (Method::Subdivision, Address::Single) => {
            return Err(
                "method subdivision walks its four sub-triangles with the four-triangle \
                        block: use --address four-triangle (or leave --address out)"
                    .into(),
            )
        }
        (m, Address::FourTriangle) => {
            return Err(format!(
                "--address four-triangle feeds a BVI per lane: it renders gouraud and \
                 subdivision, not {m}"
            ))
        }
        (Method::Gouraud, _) => Box::new(families::Gouraud),
        (m, _) if SPAN_METHODS.contains(&m) => Box::new(families::Span(m)),
        (m, _) if TEXTURED_RTL_METHODS.contains(&m) => Box::new(families::Textured(m)),
        (m, _) => Box::new(families::Lit(m)),
    })
}

/// `scene` drawn with `method` by the simulated hardware built as `o` says.
pub fn render(
    scene: &Scene,
    method: Method,
    o: &Options,
    progress: &mut dyn FnMut(Tick),
) -> Result<Rendered, String> {
    let family = family(method, o)?;
    check_scene(scene, method)?;
    family.render(scene, o, progress)
}

/// The Verilator designs rendering `methods` with `o` steps, each once (`flat` has none).
pub fn designs(methods: &[Method], o: &Options) -> Result<Vec<verilated::Design>, String> {
    let mut out: Vec<verilated::Design> = Vec::new();
    for &m in methods {
        if m == Method::Flat {
            continue;
        }
        let d = family(m, o)?.design(o)?;
        if !out.iter().any(|x| x.key == d.key) {
            out.push(d);
        }
    }
    Ok(out)
}

/// An error unless the canvas and every vertex address fit the hardware's 12 bits.
pub fn check_addresses(tris: &[ScreenTriangle], width: u32, height: u32) -> Result<(), String> {
    let limit = MAX_ADDRESS as u32 + 1;
    if width == 0 || height == 0 || width > limit || height > limit {
        return Err(format!(
            "canvas {width}x{height}: each side must be 1..={limit} (12-bit addresses)"
        ));
    }
    if let Some((i, t, v)) = tris.iter().enumerate().find_map(|(i, t)| {
        let max = MAX_ADDRESS << t.frac;
        t.v.iter()
            .find(|v| !(0..=max).contains(&v.x) || !(0..=max).contains(&v.y))
            .map(|v| (i, t, v))
    }) {
        let u = t.unit();
        return Err(format!(
            "triangle {i}: vertex ({}, {}) is outside the 12-bit address range 0..={MAX_ADDRESS}",
            v.x as f64 * u,
            v.y as f64 * u
        ));
    }
    Ok(())
}

/// Largest per-channel difference between two frames' colours, and how many pixels differ at
/// all (for the "within 1 LSB of golden" checks).
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

    #[test]
    fn bad_inputs_are_one_line_errors() {
        let v = golden::types::ScreenVertex {
            x: 4096,
            y: 0,
            z: 0.0,
            normal: glam::DVec3::Z,
            uv: glam::DVec2::ZERO,
            w: 1.0,
        };
        let t = ScreenTriangle {
            v: [v, v, v],
            frac: 0,
        };
        let ctx = ShadeContext::default();
        let o = Options {
            sim: Sim::RustHdl,
            ..Options::default()
        };
        let one = [t];
        let scene = |tris, width| Scene {
            tris,
            ctx: &ctx,
            width,
            height: 10,
            texture: None,
        };
        let run = |s: Scene, m, o: &Options| render(&s, m, o, &mut |_| {}).unwrap_err();
        // The pre-flight alone gives the same refusals, rendering nothing.
        let check = |s: Scene, m| check_scene(&s, m).unwrap_err();
        let e = run(scene(&one, 10), Method::Gouraud, &o);
        assert!(e.contains("outside the 12-bit"), "{e}");
        assert!(check(scene(&one, 10), Method::Angular).contains("outside the 12-bit"));
        let e = run(scene(&[], 5000), Method::Gouraud, &o);
        assert!(e.contains("canvas"), "{e}");
        assert!(check(scene(&[], 5000), Method::Gouraud).contains("canvas"));
        let e = run(scene(&[], 10), Method::Flat, &o);
        assert!(e.contains("no hardware for method flat"), "{e}");
        assert!(check(scene(&[], 10), Method::Flat).contains("no hardware"));
        let four = Options {
            address: Address::FourTriangle,
            ..o
        };
        let e = run(scene(&[], 10), Method::Angular, &four);
        assert!(e.contains("four-triangle"), "{e}");
    }
}
