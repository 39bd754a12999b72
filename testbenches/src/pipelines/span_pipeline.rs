//! Benches of the span pipelines (`rtl::pipelines::span_pipeline`: `angular-pipeline`, `fast-pipeline`):
//! their bit-exact twin (the span units' twins, the base registers and depth runs, the power and
//! colour twins per lane, wired as the tops wire them) and the golden method of the same build
//! (`golden::shading::angular::shade`, `golden::shading::fast::shade` with the build's 1/√(M+1) set), every clock.
//!
//! Stimulus: seeded random triangles (`crate::pipelines::pixel_pipeline::lit_triangles`: unit vertex
//! normals facing the viewer, depths in [−2, 2]) under the default context (Blinn, n = 50),
//! through the span front end (`pipeline::span::span_jobs`), each span loaded in the clock
//! `ready` rises. Triangle tips give the short spans (m = 0, 1, 2), odd and even m throughout.
//! Expectations: `ready`, the valid flags, `x`, `y`, `done` exact from the schedule (clock k of a
//! span shows pixel k in lane A and pixel m − k in lane B when m − k > k); colours within 2 LSB
//! of the golden method (the bound), RMS 0.5 LSB; `z` within 2048·2⁻¹⁷ + 2⁻¹⁶ of the
//! f64 depth plane (the depth run's bound).

use golden::raster::walk;
use golden::shade::ShadeContext;
use golden::types::ScreenTriangle;
use golden::units::colour_combine::twin::ColourTwin;
use golden::units::cos_v_accumulator::{twin::CosVTwin, SpanWords};
use golden::units::fast_unit::{twin::FastTwin, FastWords};
use golden::units::normalizer::Coeffs;
use golden::units::power_unit::twin::PowerTwin;
use golden::units::power_unit::PowerMode;
use pipeline::lit::ShadingRegs;
use pipeline::span::{span_jobs, span_row, SpanJob, SpanKind, UnitWords};
use proptest::strategy::{Strategy, ValueTree};
use rtl::core::fixed::{INTENSITY, LEVEL};
use rtl::core::registry::NoParams;
use rtl::pipelines::span_pipeline::{
    AngularPipeline, FastPipeline, FastPipelineParams, SHADE_LATENCY,
};
use rtl::units::cos_v_accumulator::CosVAccumulator;
use rtl::units::fast_unit::FastUnit;
use rtl::units::power_unit::PowerUnit;

use crate::harness::{Compare, Expected, Tolerance};
use crate::pipelines::pixel_pipeline::{lit_triangles, DelayLine};
use crate::registry::{Bench, Stimulus, Twin};
use golden::testing::seeded_runner;

const NOT_CUBIC: &str =
    "the cubic and quadric tops have their own benches (crate::pipelines::cubic_pipeline, crate::units::quadric_unit)";

/// One span unit's twin.
enum UnitTwin {
    Angular(CosVTwin),
    Fast(FastTwin),
}

impl UnitTwin {
    /// ready, valid_a, index_a, cos_a, valid_b, index_b, cos_b, last.
    fn outputs(&self, hold: bool) -> Vec<u64> {
        match self {
            UnitTwin::Angular(t) => t.outputs_held(hold),
            UnitTwin::Fast(t) => t.outputs_held(hold),
        }
    }
    fn clock(&mut self, load: Option<&UnitWords>, hold: bool) {
        match (self, load) {
            (UnitTwin::Angular(t), Some(UnitWords::Angular(w))) => t.clock_held(Some(w), hold),
            (UnitTwin::Angular(t), _) => t.clock_held(None, hold),
            (UnitTwin::Fast(t), Some(UnitWords::Fast(w))) => t.clock_held(Some(w), hold),
            (UnitTwin::Fast(t), _) => t.clock_held(None, hold),
        }
    }
}

/// Twin of a span pipeline top.
pub struct SpanPipelineTwin {
    kind: SpanKind,
    unit_l: UnitTwin,
    unit_h: UnitTwin,
    // base registers: x0, y, dir, dz, za, zb
    base: [u64; 6],
    base_d: Vec<DelayLine>,
    power: [PowerTwin; 2],
    cd: [DelayLine; 2],
    colour: [ColourTwin; 2],
    // x_a, x_b, z_a, z_b, y, last
    out_d: Vec<DelayLine>,
}

impl SpanPipelineTwin {
    pub fn new(kind: SpanKind) -> Self {
        let unit = || match kind {
            SpanKind::Angular => UnitTwin::Angular(CosVTwin::default()),
            SpanKind::Fast(_) => UnitTwin::Fast(FastTwin::new(coeffs(kind))),
            SpanKind::Cubic { .. } | SpanKind::Quadric => unreachable!("{NOT_CUBIC}"),
        };
        let u1 = match kind {
            SpanKind::Angular => CosVAccumulator::LATENCY - 1,
            SpanKind::Fast(_) => FastUnit::LATENCY - 1,
            SpanKind::Cubic { .. } | SpanKind::Quadric => unreachable!("{NOT_CUBIC}"),
        };
        let (unit_l, unit_h) = (unit(), unit());
        SpanPipelineTwin {
            kind,
            unit_l,
            unit_h,
            base: [0; 6],
            base_d: (0..5).map(|_| DelayLine::new(u1)).collect(),
            power: [0, 1].map(|_| PowerTwin::new(PowerMode::Exact)),
            cd: [0, 1].map(|_| DelayLine::new(PowerUnit::LATENCY)),
            colour: Default::default(),
            out_d: (0..6).map(|_| DelayLine::new(SHADE_LATENCY)).collect(),
        }
    }
}

fn coeffs(kind: SpanKind) -> Coeffs {
    kind.fast_params().0.coeffs
}

/// The span a row loads (if `load`): its base and unit words, n, the weights and `hold`, from
/// the row layout of `pipeline::span::span_row`.
#[allow(clippy::type_complexity)]
fn row_span(
    kind: SpanKind,
    r: &[u64],
) -> (bool, [u64; 6], UnitWords, UnitWords, u64, [u64; 9], bool) {
    let sx = |x: u64, bits: u32| ((x << (64 - bits)) as i64) >> (64 - bits);
    let m = r[4] as u32;
    let (l, h, at) = match kind {
        SpanKind::Angular => {
            let w = |k: usize| {
                UnitWords::Angular(SpanWords {
                    p: sx(r[k], 32),
                    q: sx(r[k + 1], 32),
                    d: sx(r[k + 2], 32),
                    cos_beta: r[k + 3],
                    m,
                })
            };
            (w(5), w(9), 13)
        }
        SpanKind::Fast(_) => {
            let w = |k: usize| {
                UnitWords::Fast(FastWords {
                    b: sx(r[k], 32),
                    h: sx(r[k + 1], 32),
                    g: sx(r[k + 2], 32),
                    d0: sx(r[k + 3], 48),
                    dd: sx(r[k + 4], 48),
                    m,
                })
            };
            (w(5), w(10), 15)
        }
        SpanKind::Cubic { .. } | SpanKind::Quadric => unreachable!("{NOT_CUBIC}"),
    };
    // base: x0, y, dir, dz, z0, zm
    let base = [r[2], r[1], r[3], r[at + 2], r[at], r[at + 1]];
    let weights = std::array::from_fn(|i| r[at + 4 + i]);
    (r[0] != 0, base, l, h, r[at + 3], weights, r[at + 13] != 0)
}

impl Twin for SpanPipelineTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (load, base, l, h, n, w, hold) = row_span(self.kind, r);
        let ul = self.unit_l.outputs(hold);
        let uh = self.unit_h.outputs(hold);
        let lane = |k: usize, this: &Self| {
            let (v, rgb) = this.colour[k].outputs();
            vec![
                v as u64,
                this.out_d[k].out(),
                this.out_d[2 + k].out(),
                rgb[0],
                rgb[1],
                rgb[2],
            ]
        };
        let mut o = vec![ul[0]];
        o.extend(lane(0, self));
        o.extend(lane(1, self));
        o.push(self.out_d[4].out());
        o.push(self.out_d[5].out());

        let take = load && ul[0] != 0;
        for k in 0..2 {
            let (pv, spec) = self.power[k].outputs();
            self.colour[k].clock(pv, self.cd[k].out(), spec, &w);
            // lanes: (valid, index, cos) at 1.. and 4..
            self.power[k].clock(ul[1 + 3 * k] != 0, uh[3 + 3 * k], n);
            self.cd[k].clock(ul[3 + 3 * k]);
        }
        let (x0, y, dir) = (
            self.base_d[0].out(),
            self.base_d[1].out(),
            self.base_d[2].out(),
        );
        let x = |t: u64| {
            if dir != 0 {
                x0.wrapping_sub(t) & 0xfff
            } else {
                (x0 + t) & 0xfff
            }
        };
        let outs = [
            x(ul[2]),
            x(ul[5]),
            self.base_d[3].out(),
            self.base_d[4].out(),
            y,
            ul[7],
        ];
        for (d, v) in self.out_d.iter_mut().zip(outs) {
            d.clock(v);
        }
        let [bx, by, bdir, bdz, za, zb] = self.base;
        for (d, v) in self.base_d.iter_mut().zip([bx, by, bdir, za, zb]) {
            d.clock(v);
        }
        self.base = if take {
            let [x0, y, dir, dz, z0, zm] = base;
            [x0, y, dir, dz, z0, zm]
        } else if hold {
            self.base
        } else {
            [
                bx,
                by,
                bdir,
                bdz,
                (za + bdz) & 0xffff_ffff,
                zb.wrapping_sub(bdz) & 0xffff_ffff,
            ]
        };
        let (wl, wh) = (load.then_some(&l), load.then_some(&h));
        self.unit_l.clock(wl, hold);
        self.unit_h.clock(wh, hold);
        o
    }
}

/// The golden colour of every pixel of `t` under `kind`, in walk order.
pub(crate) fn golden_colours(
    t: &ScreenTriangle,
    ctx: &ShadeContext,
    kind: SpanKind,
) -> Vec<[u8; 3]> {
    let w = walk(t);
    let mut out = Vec::with_capacity(w.pixel_count());
    let mut emit = |_: i32, _: i32, rgb: [u8; 3]| out.push(rgb);
    match kind {
        SpanKind::Angular => golden::shading::angular::shade(t, &w, ctx, &mut emit),
        SpanKind::Fast(_) => golden::shading::fast::shade(t, &w, ctx, coeffs(kind), &mut emit),
        SpanKind::Cubic { .. } => golden::shading::cubic::shade(t, &w, ctx, &mut emit),
        SpanKind::Quadric => golden::shading::quadric::shade(t, &w, ctx, &mut emit),
    }
    out
}

/// The golden side of a span-top bench: the spans of `tris` (default context, through the span
/// front end), the golden colour and the f64 depth of every pixel in walk order, and where each
/// span's pixels start in them.
pub(crate) struct GoldenSpans {
    pub spans: Vec<SpanJob>,
    pub regs: ShadingRegs,
    colours: Vec<[u8; 3]>,
    depths: Vec<f64>,
    first: Vec<usize>,
}

impl GoldenSpans {
    pub fn new(kind: SpanKind, tris: &[ScreenTriangle]) -> GoldenSpans {
        let ctx = ShadeContext::default();
        let regs = ShadingRegs::of(&ctx).expect("default context fits the registers");
        let mut spans: Vec<SpanJob> = Vec::new();
        let mut colours = Vec::new();
        let mut depths = Vec::new();
        for (i, t) in tris.iter().enumerate() {
            spans.extend(span_jobs(t, i, kind, &ctx).expect("in range"));
            colours.extend(golden_colours(t, &ctx, kind));
            let d = t.depth_plane().expect("non-degenerate");
            depths.extend(
                walk(t)
                    .pixels()
                    .into_iter()
                    .map(|px| d.at_pixel(px.x, px.y)),
            );
        }
        // Pixel p of span i is colours[first[i] + p] (walk order = span order, t order).
        let mut first = Vec::with_capacity(spans.len());
        let mut at = 0;
        for s in &spans {
            first.push(at);
            at += s.m as usize + 1;
        }
        assert_eq!(at, colours.len(), "spans and golden pixels disagree");
        GoldenSpans {
            spans,
            regs,
            colours,
            depths,
            first,
        }
    }

    /// Pixel t of span i as a lane: valid, x, z (f64 plane), r, g, b (golden).
    pub fn lane(&self, i: usize, t: u64) -> Vec<Expected> {
        let s = &self.spans[i];
        let x = if s.leftward {
            s.x0 as u64 - t
        } else {
            s.x0 as u64 + t
        };
        let p = self.first[i] + t as usize;
        let mut v = vec![
            Expected::Word(1),
            Expected::Word(x),
            Expected::Real(self.depths[p]),
        ];
        v.extend(self.colours[p].map(|c| Expected::Real(c as f64)));
        v
    }
}

/// What a span top shows in one clock: the span, lane A's pixel, lane B's pixel if any (`None`
/// inside the outer option for a one-lane top), and whether it is the span's last clock.
pub(crate) struct Shown {
    pub span: usize,
    pub a: u64,
    pub b: Option<Option<u64>>,
    pub last: bool,
}

/// The expected output row of a span top: ready, lane A, lane B (two-lane tops), y, last.
pub(crate) fn expect_row(
    g: &GoldenSpans,
    ready: bool,
    two_lanes: bool,
    shown: Option<Shown>,
) -> Vec<Expected> {
    let mut e = vec![Expected::Word(ready as u64)];
    match shown {
        Some(sh) => {
            e.extend(g.lane(sh.span, sh.a));
            if two_lanes {
                e.extend(match sh.b.flatten() {
                    Some(t) => g.lane(sh.span, t),
                    None => idle_lane(),
                });
            }
            e.push(Expected::Word(g.spans[sh.span].y as u64));
            e.push(Expected::Word(sh.last as u64));
        }
        None => {
            e.extend(idle_lane());
            if two_lanes {
                e.extend(idle_lane());
            }
            e.push(Expected::DontCare);
            e.push(Expected::Word(0));
        }
    }
    e
}

/// A lane showing nothing: valid low, the rest unchecked.
pub(crate) fn idle_lane() -> Vec<Expected> {
    let mut v = vec![Expected::Word(0)];
    v.extend([Expected::DontCare; 5]);
    v
}

/// A lane's comparisons: valid and x exact, z within `steps`·2⁻¹⁷ + 2⁻¹⁶ (the depth run's
/// rounded step over at most `steps` additions), colours within 2 LSB of golden, RMS 0.5.
pub(crate) fn lane_compare(steps: f64) -> [Compare; 6] {
    let level = Compare::Fixed {
        format: LEVEL,
        tol: Tolerance {
            max_abs: 2.0,
            rms: 0.5,
        },
    };
    let zb = steps * (-17f64).exp2() + (-16f64).exp2();
    let depth = Compare::Fixed {
        format: INTENSITY,
        tol: Tolerance {
            max_abs: zb,
            rms: zb,
        },
    };
    [Compare::Exact, Compare::Exact, depth, level, level, level]
}

/// Rows and expectations for `tris` through the span pipeline of `kind`.
fn span_stimulus(kind: SpanKind, tris: &[ScreenTriangle], latency: usize) -> Stimulus {
    let g = GoldenSpans::new(kind, tris);
    let (spans, regs) = (&g.spans, &g.regs);
    // Schedule: the first span loads in clock 0; span i occupies clocks(i) clocks; the next
    // loads in its last clock.
    let mut rows = vec![span_row(kind, spans.first(), regs)];
    let mut state: Vec<Option<(usize, u64)>> = vec![None];
    for (i, s) in spans.iter().enumerate() {
        for k in 0..s.clocks() {
            state.push(Some((i, k)));
            let next = (k + 1 == s.clocks()).then(|| spans.get(i + 1)).flatten();
            rows.push(span_row(kind, next, regs));
        }
    }
    for _ in 0..=latency {
        rows.push(span_row(kind, None, regs));
        state.push(None);
    }
    let expected = (0..rows.len())
        .map(|c| {
            let ready = state[c].is_none_or(|(i, k)| k + 1 == spans[i].clocks());
            let shown = c.checked_sub(latency - 1).and_then(|s| state[s]);
            expect_row(
                &g,
                ready,
                true,
                shown.map(|(i, k)| {
                    let m = spans[i].m as u64;
                    Shown {
                        span: i,
                        a: k,
                        b: Some((m - k > k).then_some(m - k)),
                        last: k + 1 == spans[i].clocks(),
                    }
                }),
            )
        })
        .collect();
    let lane = lane_compare(2048.0);
    let mut compare = vec![Compare::Exact];
    compare.extend(lane);
    compare.extend(lane);
    compare.extend([Compare::Exact, Compare::Exact]);
    Stimulus {
        rows,
        expected,
        compare,
    }
}

/// Loads in random clocks (ignored while `ready` is low) with the spans of a few triangles.
fn span_edge_rows(kind: SpanKind, seed: u64) -> Vec<Vec<u64>> {
    let ctx = ShadeContext::default();
    let regs = ShadingRegs::of(&ctx).expect("default context fits the registers");
    let spans: Vec<SpanJob> = lit_triangles(seed ^ 0x5a5, 4)
        .iter()
        .enumerate()
        .flat_map(|(i, t)| span_jobs(t, i, kind, &ctx).expect("depths in range"))
        .collect();
    let mut r = seeded_runner(seed ^ 0x5a6);
    let mut next = 0;
    (0..600)
        .map(|_| {
            let load = (0u8..4).new_tree(&mut r).expect("no rejection").current() == 0;
            let s = (load && next < spans.len()).then(|| &spans[next]);
            next += s.is_some() as usize;
            span_row(kind, s, &regs)
        })
        .collect()
}

impl Bench for AngularPipeline {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 12;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        span_stimulus(SpanKind::Angular, &lit_triangles(seed, n), Self::LATENCY)
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(SpanPipelineTwin::new(SpanKind::Angular))
    }
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        span_edge_rows(SpanKind::Angular, seed)
    }
}

fn fast_kind(p: &FastPipelineParams) -> SpanKind {
    SpanKind::Fast(p.0.name)
}

impl Bench for FastPipeline {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 12;
    fn stimulus(p: &FastPipelineParams, n: usize, seed: u64) -> Stimulus {
        span_stimulus(fast_kind(p), &lit_triangles(seed, n), Self::LATENCY)
    }
    fn twin(p: &FastPipelineParams) -> Box<dyn Twin> {
        Box::new(SpanPipelineTwin::new(fast_kind(p)))
    }
    fn edge_rows(p: &FastPipelineParams, seed: u64) -> Vec<Vec<u64>> {
        span_edge_rows(fast_kind(p), seed)
    }
}
