//! Bench of the cubic span pipeline (`rtl::pipelines::cubic_pipeline`, both Horner variants): its
//! bit-exact twin (three Horner twins, the base registers and their delay, the output register
//! with the depth run) and the golden `cubic` method (`golden::shading::cubic::shade`), every clock.
//!
//! Stimulus: seeded random triangles (`crate::pipelines::pixel_pipeline::lit_triangles`) under the default
//! context, through the span front end (`pipeline::span::span_jobs`, the cubic set-up per line),
//! each line loaded in the clock `ready` rises; triangle tips give one-pixel lines, every
//! triangle ends with its last line. Expectations: `ready`, `valid`, `x`, `y`, `done` exact from
//! the schedule (serial: pixel t after the line's clock 3t + 2, two clocks later; pipelined:
//! after its clock t, four clocks later); colours within 2 LSB of the golden method, RMS 0.5;
//! `z` within 4096·2⁻¹⁷ + 2⁻¹⁶ of the f64 depth plane.

use golden::types::ScreenTriangle;
use golden::units::horner_unit::{twin::HornerTwin, HornerWords};
use pipeline::span::{span_row, SpanKind};
use rtl::core::registry::RtlBlock;
use rtl::pipelines::cubic_pipeline::{CubicParams, CubicPipeline};
use rtl::units::horner_unit::HornerUnit;

use crate::harness::Compare;
use crate::pipelines::pixel_pipeline::{lit_triangles, DelayLine};
use crate::pipelines::span_pipeline::{expect_row, lane_compare, GoldenSpans, Shown};
use crate::registry::{Bench, Stimulus, Twin};

/// Twin of the cubic pipeline.
pub struct CubicPipelineTwin {
    units: [HornerTwin; 3],
    // x0, y, dir, z0, dz
    base: [u64; 5],
    base_d: Vec<DelayLine>,
    // valid, x, z, r, g, b, y, last
    out: [u64; 8],
}

impl CubicPipelineTwin {
    pub fn new(p: &CubicParams) -> Self {
        CubicPipelineTwin {
            units: [0, 1, 2].map(|_| HornerTwin::new(p.0.pipelined)),
            base: [0; 5],
            base_d: (0..5)
                .map(|_| DelayLine::new(<HornerUnit as RtlBlock>::LATENCY - 1))
                .collect(),
            out: [0; 8],
        }
    }
}

impl Twin for CubicPipelineTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        // Row: load y x0 dir m step r1..r4 g1..g4 b1..b4 z0 dz hold.
        let hold = r[20] != 0;
        let u: Vec<Vec<u64>> = self.units.iter().map(|t| t.outputs_held(hold)).collect();
        let mut o = vec![u[0][0]];
        o.extend(self.out);
        let load = r[0] != 0;
        let take = load && u[0][0] != 0;
        let [x0, y, dir, z0, dz] = std::array::from_fn(|k| self.base_d[k].out());
        let (valid, t) = (u[0][1] != 0, u[0][2]);
        let x = if dir != 0 {
            x0.wrapping_sub(t) & 0xfff
        } else {
            (x0 + t) & 0xfff
        };
        let z = if !valid {
            self.out[2]
        } else if t == 0 {
            z0
        } else {
            (self.out[2] + dz) & 0xffff_ffff
        };
        self.out = [valid as u64, x, z, u[0][3], u[1][3], u[2][3], y, u[0][4]];
        for (d, v) in self.base_d.iter_mut().zip(self.base) {
            d.clock(v);
        }
        if take {
            self.base = [r[2], r[1], r[3], r[18], r[19]];
        }
        for (c, unit) in self.units.iter_mut().enumerate() {
            let w = HornerWords {
                i: std::array::from_fn(|k| r[6 + 4 * c + k] as u16 as i16 as i64),
                step: r[5],
                m: r[4] as u32,
            };
            unit.clock_held(load.then_some(&w), hold);
        }
        o
    }
}

fn stimulus(p: &CubicParams, tris: &[ScreenTriangle]) -> Stimulus {
    let kind = SpanKind::Cubic {
        pipelined: p.0.pipelined,
    };
    let g = GoldenSpans::new(kind, tris);
    let (spans, regs) = (&g.spans, &g.regs);
    // A pixel's last clock to its fragment: the units' latency less their first clock
    // (pipelined) or less a pixel's three clocks (serial), plus the output register.
    let lat = <rtl::units::horner_unit::HornerUnit as rtl::core::registry::RtlBlock>::LATENCY;
    let (per_pixel, delay) = if p.0.pipelined {
        (1, lat)
    } else {
        (3, lat - 2)
    };
    let mut rows = vec![span_row(kind, spans.first(), regs)];
    let mut state: Vec<Option<(usize, u64)>> = vec![None];
    for (i, s) in spans.iter().enumerate() {
        for k in 0..s.clocks() {
            state.push(Some((i, k)));
            let next = (k + 1 == s.clocks()).then(|| spans.get(i + 1)).flatten();
            rows.push(span_row(kind, next, regs));
        }
    }
    // Serial: idle to a multiple of three clocks, so a batch that follows in the same
    // simulation (`shadecore-sim` streams) starts in the first clock of a slot.
    let end = rows.len() + delay + 2;
    while rows.len() < end || (!p.0.pipelined && rows.len() % 3 != 0) {
        rows.push(span_row(kind, None, regs));
        state.push(None);
    }
    let expected = (0..rows.len())
        .map(|c| {
            // Serial units take a line only in the last clock of a three-clock slot (their
            // phase runs free from reset): idle, every third clock.
            let ready = match state[c] {
                None => p.0.pipelined || c % 3 == 0,
                Some((i, k)) => k + 1 == spans[i].clocks(),
            };
            let shown = c
                .checked_sub(delay)
                .and_then(|s| state[s])
                .filter(|&(_, k)| k % per_pixel == per_pixel - 1)
                .map(|(i, k)| (i, k / per_pixel));
            expect_row(
                &g,
                ready,
                false,
                shown.map(|(i, t)| Shown {
                    span: i,
                    a: t,
                    b: None,
                    last: t == spans[i].m as u64,
                }),
            )
        })
        .collect();
    let mut compare = vec![Compare::Exact];
    compare.extend(lane_compare(4096.0));
    compare.extend([Compare::Exact, Compare::Exact]);
    Stimulus {
        rows,
        expected,
        compare,
    }
}

impl Bench for CubicPipeline {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 4;
    fn stimulus(p: &CubicParams, n: usize, seed: u64) -> Stimulus {
        stimulus(p, &lit_triangles(seed, n))
    }
    fn twin(p: &CubicParams) -> Box<dyn Twin> {
        Box::new(CubicPipelineTwin::new(p))
    }
}
