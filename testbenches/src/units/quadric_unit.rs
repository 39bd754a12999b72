//! Bench of the quadric forward-difference unit (`rtl::units::quadric_unit`) against the golden
//! `quadric` method (`golden::shading::quadric::shade`, f64) and its bit-exact twin
//! (`golden::units::quadric_unit::twin`).
//!
//! Stimulus: named triangles first — equal vertex normals (constant intensity), normals at the
//! half vector (the highlight saturates at 255), a one-pixel-high sliver (one-pixel lines), a
//! large triangle (long lines; every triangle ends with its last line) — then seeded random
//! triangles (`crate::pipelines::pixel_pipeline::lit_triangles`), under the default context, through the
//! span front end (`pipeline::span::span_jobs`, the quadric set-up), each line loaded in the clock
//! `ready` is high. Expectations: `ready`, valid flags, `x`, `y`, `done` exact from the timing
//! model `pipeline::span::quadric_timing` (written apart from the twin: a line is taken at its
//! predecessor's hand-over, the tracker moves 1 + ⌈|Δx0|/2⌉ clocks, the generator shows pixels
//! 2j and 2j + 1 three clocks after hand-over + j: the colours are rounded a clock after the
//! generator's clock, from the words' high halves); colours within
//! 2 LSB of the golden method, RMS 0.5; `z` within 4096·2⁻¹⁷ + 2⁻¹⁶ of the f64 depth plane.

use glam::DVec3;
use golden::shade::ShadeContext;
use golden::types::ScreenTriangle;
use golden::units::quadric_unit::twin::{QuadricLine, QuadricTwin};
use golden::units::quadric_unit::QuadricWords;
use pipeline::span::{quadric_timing, span_jobs, span_row, SpanKind};
use rtl::core::registry::NoParams;
use rtl::units::quadric_unit::QuadricUnit;

use crate::harness::Compare;
use crate::pipelines::pixel_pipeline::lit_triangles;
use crate::pipelines::span_pipeline::{expect_row, lane_compare, GoldenSpans, Shown};
use crate::registry::{Bench, Stimulus, Twin};

/// Named triangles: (name, triangle).
pub fn named_triangles() -> Vec<(&'static str, ScreenTriangle)> {
    let ctx = ShadeContext::default();
    let with = |p: [(i32, i32); 3], n: [DVec3; 3]| {
        let mut t = ScreenTriangle::from_points(p);
        for (v, n) in t.v.iter_mut().zip(n) {
            v.normal = n.normalize();
        }
        t
    };
    let h = ctx.half();
    vec![
        (
            "constant intensity (equal normals)",
            with([(5, 3), (40, 9), (12, 30)], [DVec3::new(0.2, 0.3, 0.9); 3]),
        ),
        (
            "highlight: normals near H, saturating",
            with(
                [(50, 5), (90, 12), (60, 40)],
                [
                    h,
                    (h + DVec3::new(0.05, 0.0, 0.0)),
                    (h + DVec3::new(0.0, 0.05, 0.0)),
                ],
            ),
        ),
        (
            "one-pixel-high sliver: one-pixel lines",
            with(
                [(10, 60), (30, 61), (11, 61)],
                [DVec3::Z, DVec3::X + DVec3::Z, DVec3::Y + DVec3::Z],
            ),
        ),
        (
            "large triangle: long lines",
            with(
                [(0, 70), (300, 90), (40, 160)],
                [
                    DVec3::new(-0.5, -0.3, 0.8),
                    DVec3::new(0.6, -0.2, 0.7),
                    DVec3::new(0.1, 0.7, 0.7),
                ],
            ),
        ),
    ]
}

/// Twin on the top's rows: load y x0 dir m first (i dx dy a2 b2 c per channel) z0 dz hold.
pub struct QuadricRows(pub QuadricTwin);

impl Twin for QuadricRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[26] != 0;
        let o = self.0.outputs_held(hold);
        let w = |k: usize| r[k] as i64;
        let line = QuadricLine {
            y: r[1],
            x0: r[2],
            leftward: r[3] != 0,
            m: r[4] as u32,
            first: r[5] != 0,
            ch: std::array::from_fn(|c| {
                let at = 6 + 6 * c;
                QuadricWords {
                    i0: w(at),
                    dx: w(at + 1),
                    dy: w(at + 2),
                    a2: w(at + 3),
                    b2: w(at + 4),
                    c: w(at + 5),
                }
            }),
            z0: r[24],
            dz: r[25],
        };
        self.0.clock_held((r[0] != 0).then_some(&line), hold);
        o
    }
}

fn stimulus(tris: &[ScreenTriangle]) -> Stimulus {
    let kind = SpanKind::Quadric;
    let g = GoldenSpans::new(kind, tris);
    let (spans, regs) = (&g.spans, &g.regs);
    // Schedule: `quadric_timing` gives each line's load and hand-over clocks; clock j of its
    // generator (hand-over + 1 + j) shows pixels 2j and 2j + 1 two clocks later (the output
    // register, and the colours' rounding from the high halves a clock behind).
    let timing = quadric_timing(spans);
    let last_hand = timing.last().map_or(0, |&(_, h)| h) as usize;
    let end = last_hand + spans.last().map_or(0, |s| s.clocks()) as usize + 4;
    let mut rows = vec![span_row(kind, None, regs); end];
    let mut shown: Vec<Option<(usize, u64)>> = vec![None; end];
    let mut ready = vec![false; end];
    ready[0] = true;
    for (i, &(take, hand)) in timing.iter().enumerate() {
        rows[take as usize] = span_row(kind, Some(&spans[i]), regs);
        ready[hand as usize] = true;
        for j in 0..spans[i].clocks() {
            shown[(hand + 3 + j) as usize] = Some((i, j));
        }
    }
    for r in ready.iter_mut().skip(last_hand + 1) {
        *r = true;
    }
    let expected = (0..rows.len())
        .map(|c| {
            expect_row(
                &g,
                ready[c],
                true,
                shown[c].map(|(i, k)| Shown {
                    span: i,
                    a: 2 * k,
                    b: Some((2 * k < spans[i].m as u64).then_some(2 * k + 1)),
                    last: k + 1 == spans[i].clocks(),
                }),
            )
        })
        .collect();
    let lane = lane_compare(4096.0);
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

/// The triangles of the bench: the named ones, then `n` seeded random ones whose quadric stays
/// in the unit's range.
pub fn triangles(n: usize, seed: u64) -> Vec<ScreenTriangle> {
    let mut tris: Vec<ScreenTriangle> = named_triangles().into_iter().map(|(_, t)| t).collect();
    let ctx = ShadeContext::default();
    tris.extend(
        lit_triangles(seed, 4 * n + 8)
            .into_iter()
            .filter(|t| span_jobs(t, 0, SpanKind::Quadric, &ctx).is_ok())
            .take(n),
    );
    tris
}

impl Bench for QuadricUnit {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 12;
    /// Random triangles whose quadric leaves the unit's range on some line (slivers; the
    /// front end rejects them with a one-line error) are replaced by the next ones.
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        stimulus(&triangles(n, seed))
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(QuadricRows(QuadricTwin::new()))
    }
}
