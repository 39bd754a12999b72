//! The span pipelines (`rtl::pipelines::span_pipeline`) as a render driver: the span front end — per
//! raster line of the triangle walk, the software set-up of the golden method (end normals,
//! then `golden::shading::angular::span_setup` or `golden::shading::fast::span_setup` for L and H, quantized to
//! the span unit's words) and the line's depth words — then the spans fed back to back, two
//! fragments per clock out.
//!
//! Row layout (the top's input ports in order): `load`, `y`, `x0`, `dir`, `m`, the L words, the
//! H words (angular: p q d cos β; fast: b h g d0 dd), `z0`, `zm`, `dz`, then the material
//! registers (n, amb r g b, dif r g b, spc r g b). Outputs: ready, lane A (valid x z r g b),
//! lane B (valid x z r g b), y, last.

use std::collections::VecDeque;
use std::io::Write;

use golden::methods::{row_end, span_end_normals, Method};
use golden::raster::walk;
use golden::shade::ShadeContext;
use golden::types::ScreenTriangle;
use golden::units::cos_v_accumulator::SpanWords;
use golden::units::fast_unit::FastWords;
use golden::units::horner_unit::HornerWords;
use golden::units::intensity_interpolator::quantize;
use golden::units::quadric_unit::{check_line, triangle_words, QuadricWords};
use rtl::core::registry::{BlockParams, Options, RtlBlock};
use rtl::core::sim::Model;
use rtl::pipelines::cubic_pipeline::{CubicParams, CubicPipeline};
use rtl::stream::angular_stream::AngularStream;
use rtl::stream::cubic_stream::CubicStream;
use rtl::stream::fast_stream::FastStream;
use rtl::stream::quadric_stream::QuadricStream;
use rtl::units::horner_unit::HornerParams;
use rtl::units::quadric_unit::QuadricUnit;

use flow::engine::Sim;
use rtl::pipelines::span_pipeline::{AngularPipeline, FastPipeline, FastPipelineParams};

use crate::axis::PipeStats;
use crate::axis::{with_last, Word};
use crate::lit::{check_depths, ShadingRegs};
use rtl::stream::layout::{
    pack, ANGULAR_LINE, CUBIC_LINE, FAST_LINE, QUADRIC_LINE, QUADRIC_TRIANGLE, SPAN_REGISTERS,
};

/// The methods the span pipelines render.
pub const SPAN_METHODS: [Method; 5] = [
    Method::Angular,
    Method::Fast,
    Method::FastFit,
    Method::Quadric,
    Method::Cubic,
];

/// Outputs per clock of the two-lane tops: ready, 2 × (valid x z r g b), y, last; the cubic
/// top has one lane: ready, valid x z r g b, y, last.
pub const OUTPUTS: usize = 15;

/// Where a span top's outputs are: the lanes' `valid` columns (x, z, r, g, b follow each), then
/// the line's `y` and `done` columns. One lane for the cubic pipeline, two for the others.
pub fn output_columns(kind: SpanKind) -> (&'static [usize], usize, usize) {
    match kind {
        SpanKind::Cubic { .. } => (&[1], 7, 8),
        _ => (&[1, 7], 13, 14),
    }
}

/// Which span unit a method uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpanKind {
    Angular,
    /// The fast unit with this `inv-sqrt` set (`chebyshev`, `shift-add`, `fit`).
    Fast(&'static str),
    /// Three Horner units, serial (fig. 2.6) or pipelined.
    Cubic {
        pipelined: bool,
    },
    /// The quadric forward-difference unit.
    Quadric,
}

impl SpanKind {
    /// The span pipeline that computes `method`; `None` if none does.
    /// (`cubic` through the serial Horner unit; [`SpanKind::with_horner`] picks the variant.)
    pub fn of(method: Method) -> Option<SpanKind> {
        match method {
            Method::Angular => Some(SpanKind::Angular),
            Method::Fast => Some(SpanKind::Fast("chebyshev")),
            Method::FastFit => Some(SpanKind::Fast("fit")),
            Method::Cubic => Some(SpanKind::Cubic { pipelined: false }),
            Method::Quadric => Some(SpanKind::Quadric),
            _ => None,
        }
    }
    /// The cubic kind with the Horner variant `pipelined`; other kinds unchanged.
    pub fn with_horner(self, pipelined: bool) -> SpanKind {
        match self {
            SpanKind::Cubic { .. } => SpanKind::Cubic { pipelined },
            k => k,
        }
    }
    /// The fast unit's build parameters (the chebyshev set for the other kinds, unused).
    pub fn fast_params(self) -> FastPipelineParams {
        let name = match self {
            SpanKind::Fast(n) => n,
            _ => "chebyshev",
        };
        FastPipelineParams::from_options(&Options::new().with("inv-sqrt", name))
            .expect("the span kinds name known sets")
    }
}

/// One vector's span-unit words.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UnitWords {
    Angular(SpanWords),
    Fast(FastWords),
}

const MASK32: i64 = (1 << 32) - 1;
const MASK48: i64 = (1 << 48) - 1;

impl UnitWords {
    /// The unit's set-up of `x` on a line with end normals `na`, `nb` (`None`: the end normals
    /// vanish, zero words: the pixel gets the ambient colour).
    pub fn new(
        kind: SpanKind,
        ends: Option<(glam::DVec3, glam::DVec3)>,
        x: glam::DVec3,
        m: u32,
    ) -> UnitWords {
        match (kind, ends) {
            (SpanKind::Angular, Some((a, b))) => UnitWords::Angular(SpanWords::new(
                &golden::shading::angular::span_setup(a, b, x, m),
            )),
            (SpanKind::Angular, None) => UnitWords::Angular(SpanWords {
                m,
                ..SpanWords::default()
            }),
            (SpanKind::Fast(_), Some((a, b))) => UnitWords::Fast(FastWords::new(
                &golden::shading::fast::span_setup(a, b, x, m),
            )),
            (SpanKind::Fast(_), None) | (SpanKind::Cubic { .. } | SpanKind::Quadric, _) => {
                UnitWords::Fast(FastWords {
                    m,
                    ..FastWords::default()
                })
            }
        }
    }
    /// The words in port order.
    pub fn row(&self) -> Vec<u64> {
        match self {
            UnitWords::Angular(w) => vec![
                (w.p & MASK32) as u64,
                (w.q & MASK32) as u64,
                (w.d & MASK32) as u64,
                w.cos_beta,
            ],
            UnitWords::Fast(w) => vec![
                (w.b & MASK32) as u64,
                (w.h & MASK32) as u64,
                (w.g & MASK32) as u64,
                (w.d0 & MASK48) as u64,
                (w.dd & MASK48) as u64,
            ],
        }
    }
    fn zero(kind: SpanKind) -> UnitWords {
        UnitWords::new(kind, None, glam::DVec3::ZERO, 0)
    }
}

/// Memory a span render's set-up may hold (`golden::scene::MEMORY_BUDGET_BYTES`, 2 GiB): the
/// span families build every raster line's [`SpanJob`] before the run.
pub const SPAN_BUDGET_BYTES: u64 = golden::scene::MEMORY_BUDGET_BYTES;
/// Peak memory per raster line of the span set-up, measured: `render --engine both --method
/// cubic` (or `angular`) of 50 000 identical faces at 64×48, about 1.65 M lines, peaks at
/// 326 MB (about 193 bytes a line, the vector's growth included); rounded up.
pub const BYTES_PER_SPAN_LINE: u64 = 256;

/// An error naming the budget when the raster lines of `tris` (each triangle's rows, an upper
/// bound of its span jobs) would not fit [`SPAN_BUDGET_BYTES`].
pub fn check_span_budget(tris: &[ScreenTriangle]) -> Result<(), String> {
    let lines: u64 = tris
        .iter()
        .map(|t| {
            let ys = t.v.map(|v| (v.y >> t.frac) as i64);
            (ys.iter().max().unwrap() - ys.iter().min().unwrap() + 1) as u64
        })
        .sum();
    let max = SPAN_BUDGET_BYTES / BYTES_PER_SPAN_LINE;
    if lines > max {
        return Err(format!(
            "the triangles span {lines} raster lines, above the {max} whose per-line set-up ({BYTES_PER_SPAN_LINE} bytes each) fits the {} MiB memory budget: use fewer or smaller triangles, a smaller canvas, or a method that is not a span method",
            SPAN_BUDGET_BYTES >> 20
        ));
    }
    Ok(())
}

/// One raster line's set-up for a span pipeline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpanJob {
    /// Index of the triangle (jobs keep their order).
    pub triangle: usize,
    pub y: u32,
    /// x of pixel 0.
    pub x0: u32,
    /// Pixel t is at x0 − t (else x0 + t).
    pub leftward: bool,
    /// Pixels − 1.
    pub m: u32,
    pub words: JobWords,
    /// Depth at pixel 0, at pixel m, and per pixel step (signed Q16.16 words).
    pub z0: u32,
    pub zm: u32,
    pub dz: u32,
}

/// A line's words for the span units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JobWords {
    /// Angular or fast: the unit words for L and for H.
    Pair { light: UnitWords, half: UnitWords },
    /// Cubic: each channel's samples; `pipelined`: the Horner variant (clocks per pixel).
    Cubic {
        channels: [HornerWords; 3],
        pipelined: bool,
    },
    /// Quadric: `first` line of its triangle, with each channel's tracker words (zero on the
    /// other lines: the tracker walks there).
    Quadric { first: bool, ch: [QuadricWords; 3] },
}

impl SpanJob {
    /// Clocks the span occupies in the span units: ⌊m/2⌋ + 1 (two pixels per clock), or
    /// m + 1 (pipelined Horner), 3(m + 1) (serial Horner).
    pub fn clocks(&self) -> u64 {
        match self.words {
            JobWords::Pair { .. } | JobWords::Quadric { .. } => self.m as u64 / 2 + 1,
            JobWords::Cubic {
                pipelined: true, ..
            } => self.m as u64 + 1,
            JobWords::Cubic {
                pipelined: false, ..
            } => 3 * (self.m as u64 + 1),
        }
    }
}

/// The span front end: the spans of triangle `tri` (index `triangle`) for `kind` under `ctx`,
/// in walk order; none for a zero-area triangle. Error: a vertex depth beyond ±[`DEPTH_LIMIT`](crate::lit::DEPTH_LIMIT).
pub fn span_jobs(
    tri: &ScreenTriangle,
    triangle: usize,
    kind: SpanKind,
    ctx: &ShadeContext,
) -> Result<Vec<SpanJob>, String> {
    check_depths(tri)?;
    let (Some(plane), Some(depth)) = (tri.normal_plane(), tri.depth_plane()) else {
        return Ok(Vec::new());
    };
    let spec = ctx.specular_vector();
    let quadric = match kind {
        SpanKind::Quadric => match golden::shading::quadric::setup(tri, ctx) {
            Some(q) => Some(q),
            None => return Ok(Vec::new()), // the golden method draws nothing either
        },
        _ => None,
    };
    walk(tri)
        .rows
        .iter()
        .filter(|r| r.len > 0)
        .enumerate()
        .map(|(line, row)| {
            let m = row.len - 1;
            let ends = span_end_normals(&plane, row);
            let end = row_end(row);
            let words = match kind {
                SpanKind::Quadric => {
                    let q = quadric.as_ref().expect("set up above");
                    let mut ch = [QuadricWords::default(); 3];
                    for (c, w) in ch.iter_mut().enumerate() {
                        check_line(q, c, row)?;
                        if line == 0 {
                            *w = triangle_words(q, c, row);
                        }
                    }
                    JobWords::Quadric {
                        first: line == 0,
                        ch,
                    }
                }
                SpanKind::Cubic { pipelined } => JobWords::Cubic {
                    channels: golden::shading::cubic::span_samples(&plane, row, ctx)
                        .map(|s| HornerWords::new(s, m)),
                    pipelined,
                },
                _ => JobWords::Pair {
                    light: UnitWords::new(kind, ends, ctx.light, m),
                    half: spec.map_or(UnitWords::new(kind, None, glam::DVec3::ZERO, m), |h| {
                        UnitWords::new(kind, ends, h, m)
                    }),
                },
            };
            Ok(SpanJob {
                triangle,
                y: row.y as u32,
                x0: row.x_start as u32,
                leftward: row.dir < 0,
                m,
                words,
                z0: quantize(depth.at_pixel(row.x_start, row.y)),
                zm: quantize(depth.at_pixel(end, row.y)),
                dz: quantize(depth.a * row.dir as f64),
            })
        })
        .collect()
}

/// The top's input row: `load` with a span (or idle), then (angular, fast) the material
/// registers, then `hold` low (every span top).
pub fn span_row(kind: SpanKind, job: Option<&SpanJob>, regs: &ShadingRegs) -> Vec<u64> {
    let mut row = match job {
        Some(j) => vec![1, j.y as u64, j.x0 as u64, j.leftward as u64, j.m as u64],
        None => vec![0; 5],
    };
    if kind == SpanKind::Quadric {
        match job.map(|j| j.words) {
            Some(JobWords::Quadric { first, ch }) => {
                row.push(first as u64);
                for w in ch {
                    row.extend([w.i0, w.dx, w.dy, w.a2, w.b2, w.c].map(|v| v as u64));
                }
            }
            _ => row.extend([0; 19]),
        }
        row.extend(job.map_or([0; 2], |j| [j.z0, j.dz]).map(u64::from));
        row.push(0); // hold: a stream top's back-pressure; never here
        return row;
    }
    if let SpanKind::Cubic { .. } = kind {
        match job.map(|j| j.words) {
            Some(JobWords::Cubic { channels, .. }) => {
                row.push(channels[0].step);
                for c in channels {
                    row.extend(c.i.map(|v| (v as u64) & 0xFFFF));
                }
            }
            _ => row.extend([0; 13]),
        }
        row.extend(job.map_or([0; 2], |j| [j.z0, j.dz]).map(u64::from));
        row.push(0); // hold: a stream top's back-pressure; never here
        return row;
    }
    let z = UnitWords::zero(kind);
    let (l, h) = match job.map(|j| j.words) {
        Some(JobWords::Pair { light, half }) => (light, half),
        _ => (z, z),
    };
    row.extend(l.row());
    row.extend(h.row());
    row.extend(job.map_or([0; 3], |j| [j.z0, j.zm, j.dz]).map(u64::from));
    row.push(regs.n);
    row.extend(regs.weights);
    row.push(0); // hold: a stream top's back-pressure; never here
    row
}

/// One fragment out of a span pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpanFragment {
    pub triangle: usize,
    pub x: u32,
    pub y: u32,
    /// Depth word, signed Q16.16.
    pub z: i32,
    pub rgb: [u8; 3],
    /// The clock (0 = the run's first) whose outputs show it.
    pub clock: u64,
    /// Lane B (the mirror run).
    pub lane_b: bool,
}

impl SpanFragment {
    /// The fragment a stream top's beat carries for line `span`, shown at `clock`.
    fn of(span: &SpanJob, b: &crate::axis::Beat, clock: u64, lane_b: bool) -> Self {
        SpanFragment {
            triangle: span.triangle,
            x: b.x,
            y: b.y,
            z: b.z,
            rgb: b.rgb,
            clock,
            lane_b,
        }
    }
}

/// How a span top is driven.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    /// A pipeline's ports (`angular-pipeline`, `fast-pipeline`, `cubic-pipeline`,
    /// `quadric-unit`): a line loaded whenever `ready`.
    Ports,
    /// `cubic-stream`: line records in, one fragment stream out.
    CubicStream,
    /// A two-lane stream top: `angular-stream`, `fast-stream`, `quadric-stream`.
    AngularStream,
    FastStream,
    QuadricStream,
}

/// A span pipeline or its stream top, on either simulator ([`Sim`]).
pub struct SpanPipe {
    kind: SpanKind,
    model: Box<dyn Model>,
    shape: Shape,
    latency: usize,
}

fn span_kind(method: Method, pipelined: bool) -> Result<SpanKind, String> {
    SpanKind::of(method)
        .map(|k| k.with_horner(pipelined))
        .ok_or_else(|| {
            format!(
                "the RTL span pipelines do not compute {method} (they have: {})",
                SPAN_METHODS.map(|m| m.name()).join(", ")
            )
        })
}

/// A span top made by [`top_of`]: the simulated model (or, asked for no simulator, its Verilator
/// design) and its latency.
type Made = (Option<Box<dyn Model>>, Option<verilated::Design>, usize);

/// A top for `kind` in `shape`, on `sim` (`None`: its Verilator design instead).
fn top_of(kind: SpanKind, shape: Shape, sim: Option<Sim>) -> Result<Made, String> {
    use flow::engine::{design, model};
    fn one<B: RtlBlock + 'static>(p: &B::Params, sim: Option<Sim>) -> Result<Made, String> {
        Ok(match sim {
            Some(sim) => (Some(model::<B>(p, sim)?), None, B::LATENCY),
            None => (None, Some(design::<B>(p)), B::LATENCY),
        })
    }
    let cubic = |pipelined| CubicParams(HornerParams { pipelined });
    match (shape, kind) {
        (Shape::Ports, SpanKind::Angular) => one::<AngularPipeline>(&Default::default(), sim),
        (Shape::Ports, SpanKind::Fast(_)) => one::<FastPipeline>(&kind.fast_params(), sim),
        (Shape::Ports, SpanKind::Cubic { pipelined }) => {
            one::<CubicPipeline>(&cubic(pipelined), sim)
        }
        (Shape::Ports, SpanKind::Quadric) => one::<QuadricUnit>(&Default::default(), sim),
        (Shape::CubicStream, SpanKind::Cubic { pipelined }) => {
            one::<CubicStream>(&cubic(pipelined), sim)
        }
        (Shape::AngularStream, _) => one::<AngularStream>(&Default::default(), sim),
        (Shape::FastStream, _) => one::<FastStream>(&kind.fast_params(), sim),
        (Shape::QuadricStream, _) => one::<QuadricStream>(&Default::default(), sim),
        _ => Err(format!("no {shape:?} top for {kind:?}")),
    }
}

/// The two-lane stream top of `kind`, if it has one.
fn lane_shape(kind: SpanKind) -> Option<Shape> {
    match kind {
        SpanKind::Angular => Some(Shape::AngularStream),
        SpanKind::Fast(_) => Some(Shape::FastStream),
        SpanKind::Quadric => Some(Shape::QuadricStream),
        SpanKind::Cubic { .. } => None,
    }
}

impl SpanPipe {
    /// The span pipeline for `method` (one of [`SPAN_METHODS`]; `cubic` with the serial Horner
    /// unit), on rust-hdl.
    pub fn new(method: Method) -> Result<SpanPipe, String> {
        SpanPipe::with_horner(method, false)
    }

    /// As [`SpanPipe::new`], `cubic` through the pipelined Horner units if `pipelined`.
    pub fn with_horner(method: Method, pipelined: bool) -> Result<SpanPipe, String> {
        SpanPipe::on(method, pipelined, Sim::RustHdl, false)
    }

    /// The span top for `method` on `sim`: its pipeline's ports, or with `stream` its AXI4-Stream
    /// top (`cubic-stream`, or the two-lane `angular-stream`, `fast-stream`, `quadric-stream`).
    /// `pipelined` picks the Horner units of `cubic`.
    pub fn on(method: Method, pipelined: bool, sim: Sim, stream: bool) -> Result<SpanPipe, String> {
        let kind = span_kind(method, pipelined)?;
        let shape = SpanPipe::shape(kind, stream)?;
        let (model, _, latency) = top_of(kind, shape, Some(sim))?;
        Ok(SpanPipe {
            kind,
            model: model.expect("built on a simulator"),
            shape,
            latency,
        })
    }

    fn shape(kind: SpanKind, stream: bool) -> Result<Shape, String> {
        Ok(match (stream, kind) {
            (false, _) => Shape::Ports,
            (true, SpanKind::Cubic { .. }) => Shape::CubicStream,
            (true, k) => lane_shape(k).ok_or_else(|| format!("{k:?} has no stream top"))?,
        })
    }

    /// The design [`SpanPipe::on`] builds under Verilator.
    pub fn design(
        method: Method,
        pipelined: bool,
        stream: bool,
    ) -> Result<verilated::Design, String> {
        let kind = span_kind(method, pipelined)?;
        let (_, d, _) = top_of(kind, SpanPipe::shape(kind, stream)?, None)?;
        Ok(d.expect("a design"))
    }

    /// `cubic` through its AXI4-Stream top `cubic-stream` (pipelined Horner units if
    /// `pipelined`), on rust-hdl: [`SpanPipe::run`] sends every line's record on the set-up
    /// stream (one word per clock while `s_axis_tready`) and takes every fragment beat
    /// (`m_axis_tready` high).
    pub fn cubic_stream(pipelined: bool) -> Result<SpanPipe, String> {
        SpanPipe::on(Method::Cubic, pipelined, Sim::RustHdl, true)
    }

    /// `angular`, `fast`, `fast-fit` or `quadric` through its AXI4-Stream top
    /// (`angular-stream`, `fast-stream`, `quadric-stream`), on rust-hdl: [`SpanPipe::run`] sends
    /// the register record (not to the quadric's) and every line's record on the set-up stream
    /// (one word per clock while `s_axis_tready`) and takes every beat of both lanes (both
    /// `m_axis_*_tready` high).
    pub fn span_stream(method: Method) -> Result<SpanPipe, String> {
        match SpanKind::of(method).and_then(lane_shape) {
            Some(_) => SpanPipe::on(method, false, Sim::RustHdl, true),
            None => Err(format!(
                "{method} has no two-lane stream top (angular, fast, fast-fit and quadric have)"
            )),
        }
    }

    pub fn kind(&self) -> SpanKind {
        self.kind
    }

    /// Load → first fragments.
    pub fn latency(&self) -> usize {
        self.latency
    }

    /// Trace every following clock into `w` (rust-hdl only: an error on Verilator).
    pub fn start_vcd(&mut self, w: Box<dyn Write>) -> Result<(), String> {
        self.model.start_vcd(w)
    }

    /// Run `spans` (from [`span_jobs`], in order) with registers `regs`, each loaded in the clock
    /// `ready` is high; `fragment` for every valid lane, `progress(spans_done)` every 256 spans.
    /// [`PipeStats::triangles`] counts spans here. Stops after the last span's `done`, or with
    /// an error after `max_clocks`.
    pub fn run(
        &mut self,
        spans: &[SpanJob],
        regs: &ShadingRegs,
        max_clocks: u64,
        mut fragment: impl FnMut(SpanFragment),
        mut progress: impl FnMut(u64),
    ) -> Result<PipeStats, String> {
        let (kind, f, p) = (self.kind, &mut fragment, &mut progress);
        let s = self.model.as_mut();
        match self.shape {
            Shape::CubicStream => return run_cubic_stream(s, spans, max_clocks, f, p),
            Shape::AngularStream => {
                return run_lanes::<AngularStream>(s, kind, spans, regs, max_clocks, f, p)
            }
            Shape::FastStream => {
                return run_lanes::<FastStream>(s, kind, spans, regs, max_clocks, f, p)
            }
            Shape::QuadricStream => {
                return run_lanes::<QuadricStream>(s, kind, spans, regs, max_clocks, f, p)
            }
            Shape::Ports => {}
        }
        crate::axis::first_output_is(self.model.as_ref(), "ready")?;
        let mut st = PipeStats::default();
        let mut out = vec![0u64; OUTPUTS];
        let idle = span_row(self.kind, None, regs);
        let mut in_flight: VecDeque<usize> = VecDeque::new();
        let mut next = 0;
        while st.triangles < spans.len() as u64 {
            if st.clocks >= max_clocks {
                return Err(format!(
                    "span pipeline: {} of {} spans done after {max_clocks} clocks",
                    st.triangles,
                    spans.len()
                ));
            }
            let load = (self.model.peek(0) != 0 && next < spans.len()).then(|| &spans[next]);
            match load {
                Some(j) => {
                    in_flight.push_back(j.triangle);
                    next += 1;
                    let row = span_row(self.kind, Some(j), regs);
                    self.model.step(&row, &mut out)?;
                }
                None => self.model.step(&idle, &mut out)?,
            }
            st.clocks += 1;
            let triangle = in_flight.front().copied().unwrap_or(usize::MAX);
            // Lane A: valid x z r g b from port 1; lane B (two-lane tops) from port 7.
            let (lanes, y_at, last_at) = output_columns(self.kind);
            for (lane, &at) in lanes.iter().enumerate() {
                if out[at] != 0 {
                    st.pixels += 1;
                    fragment(SpanFragment {
                        triangle,
                        x: out[at + 1] as u32,
                        y: out[y_at] as u32,
                        z: out[at + 2] as u32 as i32,
                        rgb: [out[at + 3] as u8, out[at + 4] as u8, out[at + 5] as u8],
                        clock: st.clocks - 1,
                        lane_b: lane == 1,
                    });
                }
            }
            if out[last_at] != 0 {
                in_flight.pop_front();
                st.triangles += 1;
                if st.triangles % 256 == 0 || st.triangles == spans.len() as u64 {
                    progress(st.triangles);
                }
            }
        }
        self.model.stop_vcd()?;
        Ok(st)
    }
}

/// [`SpanPipe::run`] through `cubic-stream`: the lines' records on the set-up stream, every
/// beat taken; a line ends with its `tlast`.
fn run_cubic_stream(
    s: &mut dyn Model,
    spans: &[SpanJob],
    max_clocks: u64,
    fragment: &mut dyn FnMut(SpanFragment),
    progress: &mut dyn FnMut(u64),
) -> Result<PipeStats, String> {
    let n = spans.len() as u64;
    crate::axis::drive::<CubicStream>(
        s,
        "cubic-stream",
        "lines",
        &crate::span::cubic_words(spans),
        n,
        max_clocks,
        &mut |line, b, clock| fragment(SpanFragment::of(&spans[line], &b, clock, false)),
        &mut |done| {
            if done % 256 == 0 || done == n {
                progress(done);
            }
        },
    )
}

/// [`SpanPipe::run`] through a two-lane stream top (`angular-stream`, `fast-stream`): the
/// register record and the lines' records on the set-up stream, every beat of both lanes
/// taken; a line ends with both lanes' `tlast`.
#[allow(clippy::too_many_arguments)]
fn run_lanes<T: crate::axis::LaneTop>(
    s: &mut dyn Model,
    kind: SpanKind,
    spans: &[SpanJob],
    regs: &ShadingRegs,
    max_clocks: u64,
    fragment: &mut dyn FnMut(SpanFragment),
    progress: &mut dyn FnMut(u64),
) -> Result<PipeStats, String> {
    let n = spans.len() as u64;
    crate::axis::drive_lanes::<T>(
        s,
        &crate::span::span_stream_words(kind, spans, regs),
        n,
        max_clocks,
        &mut |line, b, clock, lane| fragment(SpanFragment::of(&spans[line], &b, clock, lane == 1)),
        &mut |done| {
            if done % 256 == 0 || done == n {
                progress(done);
            }
        },
    )
}

/// A clock budget for `spans`: their clocks plus the pipeline's latency and margin (and for
/// the quadric unit every line start's move).
pub fn span_clock_budget(spans: &[SpanJob]) -> u64 {
    // A line through a stream top takes at least its record's words (one per clock; the fast
    // line's, the longer of the two span records); the span stream tops' register record
    // comes first.
    let words = 1 + rtl::stream::layout::payload_words(&rtl::stream::layout::CUBIC_LINE) as u64;
    let pair_words = 1 + rtl::stream::layout::payload_words(&rtl::stream::layout::FAST_LINE) as u64;
    spans
        .iter()
        .map(|s| match s.words {
            JobWords::Quadric { .. } => s.clocks() + 2 + 4096 / 2,
            JobWords::Cubic { .. } => s.clocks().max(words) + 2,
            JobWords::Pair { .. } => s.clocks().max(pair_words) + 2,
        })
        .sum::<u64>()
        + 64
        + 1
        + rtl::stream::layout::payload_words(&rtl::stream::layout::SPAN_REGISTERS) as u64
}

/// The quadric unit's timing (the header of `rtl::units::quadric_unit`), written apart from its twin:
/// for each line (loaded whenever `ready` is high) the clock its load is taken and the clock the
/// tracker hands it to the generator. A line is taken in its predecessor's hand-over clock; the
/// tracker reaches its start 1 + (Δy − 1) + ⌈|Δx0|/2⌉ clocks after the load (the first line of a
/// triangle: 1); the hand-over waits for the generator's last clock of the previous line
/// (⌊m/2⌋ + 1 clocks after its hand-over). The line's pixels show from hand-over + 2.
pub fn quadric_timing(spans: &[SpanJob]) -> Vec<(u64, u64)> {
    let mut out = Vec::with_capacity(spans.len());
    let mut take = 0u64;
    let mut gen_free_at = 0u64;
    for (i, s) in spans.iter().enumerate() {
        let first = matches!(s.words, JobWords::Quadric { first: true, .. });
        let moves = if first {
            1
        } else {
            let prev = &spans[i - 1];
            let dy = (s.y - prev.y) as u64;
            let dx = (s.x0 as i64 - prev.x0 as i64).unsigned_abs();
            1 + (dy - 1) + dx.div_ceil(2)
        };
        let hand = (take + moves).max(gen_free_at);
        out.push((take, hand));
        gen_free_at = hand + s.clocks();
        take = hand;
    }
    out
}

/// Clocks the spans take at two pixels per clock with no gap, and their pixels.
pub fn span_schedule(spans: &[SpanJob]) -> (u64, u64) {
    (
        spans.iter().map(SpanJob::clocks).sum(),
        spans.iter().map(|s| s.m as u64 + 1).sum(),
    )
}

/// The `cubic-stream` record of a cubic line (`span` from `crate::span::span_jobs` with a
/// cubic kind): the same field values `cubic-pipeline`'s load row carries.
pub fn cubic_record(span: &SpanJob) -> Vec<Word> {
    let kind = match span.words {
        JobWords::Cubic { pipelined, .. } => SpanKind::Cubic { pipelined },
        _ => panic!("cubic_record: not a cubic line"),
    };
    let row = span_row(kind, Some(span), &ShadingRegs::default());
    let fields = CUBIC_LINE.fields.len();
    debug_assert_eq!(row.len(), fields + 2, "load, the fields, hold");
    with_last(pack(&CUBIC_LINE, &row[1..=fields]))
}

/// A cubic scene's set-up stream: every line, in walk order.
pub fn cubic_words(spans: &[SpanJob]) -> Vec<Word> {
    spans.iter().flat_map(cubic_record).collect()
}

/// The line record of the two-lane span stream top of `kind` (`angular-stream` for
/// [`SpanKind::Angular`], `fast-stream` for [`SpanKind::Fast`]) for `span` (from
/// `crate::span::span_jobs` with that kind): the same field values the span pipeline's load row
/// carries.
pub fn span_line_record(kind: SpanKind, span: &SpanJob) -> Vec<Word> {
    let row = span_row(kind, Some(span), &ShadingRegs::default());
    if kind == SpanKind::Quadric {
        // Row: load, y, x0, dir, m, first, 18 coefficient words, z0, dz, hold. A triangle's
        // first line carries its coefficients (type 2), a later line only its base (type 1).
        let base = [row[1], row[2], row[3], row[4], row[24], row[25]];
        return with_last(if row[5] != 0 {
            let mut v = base.to_vec();
            v.extend(&row[6..24]);
            pack(&QUADRIC_TRIANGLE, &v)
        } else {
            pack(&QUADRIC_LINE, &base)
        });
    }
    let line = span_line_layout(kind);
    with_last(pack(&line, &row[1..=line.fields.len()]))
}

/// The line layout of the span stream top of `kind`.
pub fn span_line_layout(kind: SpanKind) -> rtl::stream::layout::Record {
    match kind {
        SpanKind::Angular => ANGULAR_LINE,
        SpanKind::Fast(_) => FAST_LINE,
        SpanKind::Quadric => QUADRIC_LINE,
        _ => panic!("{kind:?} has no two-lane stream top"),
    }
}

/// The span stream tops' register record of `regs` (n and the nine colour weights; L and H
/// are in each line's words).
pub fn span_register_record(regs: &ShadingRegs) -> Vec<Word> {
    let mut values = vec![regs.n];
    values.extend(regs.weights);
    with_last(pack(&SPAN_REGISTERS, &values))
}

/// A span scene's set-up stream for the stream top of `kind`: the registers (not for the
/// quadric, lit in the set-up), then every line in walk order.
pub fn span_stream_words(kind: SpanKind, spans: &[SpanJob], regs: &ShadingRegs) -> Vec<Word> {
    let mut w = if kind == SpanKind::Quadric {
        Vec::new()
    } else {
        span_register_record(regs)
    };
    for s in spans {
        w.extend(span_line_record(kind, s));
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn span_rows_have_the_ports_width() {
        let t = ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let ctx = ShadeContext::default();
        let regs = ShadingRegs::of(&ctx).unwrap();
        for (kind, words) in [(SpanKind::Angular, 4), (SpanKind::Fast("fit"), 5)] {
            let jobs = span_jobs(&t, 0, kind, &ctx).unwrap();
            assert_eq!(
                jobs.iter().map(|j| j.m as usize + 1).sum::<usize>(),
                walk(&t).pixel_count()
            );
            let row = span_row(kind, Some(&jobs[0]), &regs);
            assert_eq!(row.len(), 5 + 2 * words + 3 + 10 + 1);
            assert_eq!(span_row(kind, None, &regs).len(), row.len());
        }
        // Cubic: base, step, 12 samples, z0, dz, hold.
        for pipelined in [false, true] {
            let kind = SpanKind::Cubic { pipelined };
            let jobs = span_jobs(&t, 0, kind, &ctx).unwrap();
            assert_eq!(span_row(kind, Some(&jobs[0]), &regs).len(), 21);
            assert_eq!(span_row(kind, None, &regs).len(), 21);
            let per = if pipelined { 1 } else { 3 };
            assert!(jobs.iter().all(|j| j.clocks() == per * (j.m as u64 + 1)));
        }
        // Quadric: base, first, 18 words, z0, dz, hold; the first line carries the words.
        let jobs = span_jobs(&t, 0, SpanKind::Quadric, &ctx).unwrap();
        assert_eq!(span_row(SpanKind::Quadric, Some(&jobs[0]), &regs).len(), 27);
        assert_eq!(span_row(SpanKind::Quadric, None, &regs).len(), 27);
        assert_eq!(span_row(SpanKind::Quadric, Some(&jobs[0]), &regs)[5], 1);
        assert_eq!(span_row(SpanKind::Quadric, Some(&jobs[1]), &regs)[5], 0);
        let mut far = t;
        far.v[0].z = 1e6;
        assert!(span_jobs(&far, 0, SpanKind::Angular, &ctx)
            .unwrap_err()
            .contains("depth"));
        assert!(SpanKind::of(Method::Gouraud).is_none());
    }
}

#[cfg(test)]
mod record_tests {
    use super::*;
    use rtl::stream::layout::unpack;

    #[test]
    fn cubic_records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let ctx = golden::shade::ShadeContext::default();
        let kind = SpanKind::Cubic { pipelined: true };
        let spans = crate::span::span_jobs(&t, 0, kind, &ctx).unwrap();
        let rec = cubic_record(&spans[3]);
        assert_eq!(rec.len(), 12);
        assert_eq!(rec[0], (1, false));
        assert!(rec[..11].iter().all(|w| !w.1) && rec[11].1);
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = span_row(kind, Some(&spans[3]), &ShadingRegs::default());
        assert_eq!(
            unpack(&CUBIC_LINE, &payload),
            row[1..row.len() - 1].to_vec()
        );
        assert_eq!(cubic_words(&spans).len(), 12 * spans.len());
    }

    #[test]
    fn span_records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let ctx = golden::shade::ShadeContext::default();
        let regs = ShadingRegs::of(&ctx).unwrap();
        for (kind, words) in [(SpanKind::Angular, 14), (SpanKind::Fast("fit"), 20)] {
            let spans = crate::span::span_jobs(&t, 0, kind, &ctx).unwrap();
            let rec = span_line_record(kind, &spans[3]);
            assert_eq!(rec.len(), words, "{kind:?}");
            assert_eq!(rec[0], (1, false));
            assert!(rec[..words - 1].iter().all(|w| !w.1) && rec[words - 1].1);
            let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
            let row = span_row(kind, Some(&spans[3]), &regs);
            let line = span_line_layout(kind);
            let fields = line.fields.len();
            assert_eq!(unpack(&line, &payload), row[1..=fields].to_vec());
            // The register record carries the row's material registers (before `hold`).
            let r = span_register_record(&regs);
            assert_eq!(r.len(), 6);
            assert_eq!(r[0], (2, false));
            let payload: Vec<u32> = r[1..].iter().map(|w| w.0).collect();
            assert_eq!(
                unpack(&SPAN_REGISTERS, &payload),
                row[fields + 1..row.len() - 1].to_vec()
            );
            assert_eq!(
                span_stream_words(kind, &spans, &regs).len(),
                6 + words * spans.len()
            );
        }
    }
}
