//! Bench of the Horner unit (`rtl::units::horner_unit`, both variants) against
//! `golden::units::horner_unit` (the f64 cubic of the same sample words at p = t/m) and its bit-exact
//! twin.
//!
//! Stimulus: named spans first — one pixel (m = 0, p = 0), two pixels (p = 0 and 1), constant
//! intensity, saturating above 255 and below 0, a highlight inside the span, a long span, the
//! extreme sample words — then seeded random spans, half smooth (a quadratic in p sampled at
//! 0, 1, ½, ¼), half with independent samples in [−40, 420]; m up to 80; each span loaded in the
//! clock `ready` rises, back to back.
//! Expectations: `ready`, `valid`, `t`, `done` exact from the schedule (serial: pixel t after
//! the span's clock 3t + 2, one clock later; pipelined: after its clock t, three clocks later);
//! `value` within each span's own `HornerWords::error_bound` of the clamped f64 value
//! (`Expected::Within`; the port's tolerance is the largest bound of the run).

use golden::units::horner_unit::{twin::HornerTwin, HornerWords};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::LEVEL;
use rtl::units::horner_unit::{HornerParams, HornerUnit};

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use golden::testing::seeded_runner;

/// Named spans: (name, words).
pub fn named_spans() -> Vec<(&'static str, HornerWords)> {
    let w = HornerWords::new;
    vec![
        ("one pixel (m = 0, p = 0)", w([120.0, 30.0, 60.0, 90.0], 0)),
        ("two pixels (p = 0 and 1)", w([20.0, 200.0, 90.0, 50.0], 1)),
        ("constant intensity", w([77.5; 4], 10)),
        ("saturating above 255", w([300.0, 420.0, 380.0, 340.0], 6)),
        ("saturating below 0", w([-20.0, -35.0, -10.0, 5.0], 5)),
        (
            "highlight inside the span",
            w([40.0, 40.0, 255.0, 120.0], 31),
        ),
        ("long span", w([60.0, 180.0, 140.0, 95.0], 300)),
        (
            "extreme sample words",
            HornerWords {
                i: [-32768, 32767, -32768, 32767],
                step: golden::units::horner_unit::step_word(7),
                m: 7,
            },
        ),
    ]
}

fn random_spans(seed: u64, n: usize) -> Vec<HornerWords> {
    let mut r = seeded_runner(seed);
    let smooth =
        (0.0..300.0f64, -100.0..100.0f64, -100.0..100.0f64, 0u32..=80).prop_map(|(a, b, c, m)| {
            let f = |p: f64| a + b * p + c * p * p;
            HornerWords::new([f(0.0), f(1.0), f(0.5), f(0.25)], m)
        });
    let wild = (prop::array::uniform4(-40.0..420.0f64), 0u32..=80)
        .prop_map(|(s, m)| HornerWords::new(s, m));
    let st = prop_oneof![smooth, wild];
    (0..n)
        .map(|_| st.new_tree(&mut r).expect("no rejection").current())
        .collect()
}

fn load_row(w: Option<&HornerWords>) -> Vec<u64> {
    match w {
        Some(w) => {
            let mut r = vec![1];
            r.extend(w.i.map(|v| (v as u64) & 0xFFFF));
            r.extend([w.step, w.m as u64, 0]);
            r
        }
        None => vec![0; 8],
    }
}

struct HornerRows(HornerTwin);

impl Twin for HornerRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        // Row: load i1..i4 step m hold.
        let hold = r[7] != 0;
        let o = self.0.outputs_held(hold);
        let w = HornerWords {
            i: std::array::from_fn(|k| r[1 + k] as u16 as i16 as i64),
            step: r[5],
            m: r[6] as u32,
        };
        self.0.clock_held((r[0] != 0).then_some(&w), hold);
        o
    }
}

/// Rows and every clock's expectations for `spans` back to back.
fn run(p: &HornerParams, spans: &[HornerWords]) -> (Vec<Vec<u64>>, Vec<Vec<Expected>>, f64) {
    // A pixel's last clock to its output: the latency less the load clock (pipelined), or
    // less the load clock and a pixel's first two clocks (serial).
    let per_pixel = if p.pipelined { 1 } else { 3 };
    let delay = if p.pipelined {
        HornerUnit::LATENCY - 1
    } else {
        HornerUnit::LATENCY - 3
    };
    let clocks = |i: usize| (spans[i].m as usize + 1) * per_pixel;
    let mut rows = vec![load_row(spans.first())];
    let mut state: Vec<Option<(usize, usize)>> = vec![None];
    for i in 0..spans.len() {
        for k in 0..clocks(i) {
            state.push(Some((i, k)));
            let next = (k + 1 == clocks(i)).then(|| spans.get(i + 1)).flatten();
            rows.push(load_row(next));
        }
    }
    // Serial: idle to a multiple of three clocks, so a batch that follows in the same
    // simulation (`shadecore-sim` streams) starts in the first clock of a slot.
    let end = rows.len() + delay + 2;
    while rows.len() < end || (!p.pipelined && rows.len() % 3 != 0) {
        rows.push(load_row(None));
        state.push(None);
    }
    let mut worst: f64 = 0.5;
    let bounds: Vec<f64> = spans.iter().map(HornerWords::error_bound).collect();
    let w = Expected::Word;
    let expected = (0..rows.len())
        .map(|c| {
            // Serial: a span is taken only in the last clock of a three-clock slot (the phase
            // runs free from reset), so when idle, every third clock.
            let ready = match state[c] {
                None => p.pipelined || c % 3 == 0,
                Some((i, k)) => k + 1 == clocks(i),
            };
            let shown = c
                .checked_sub(delay)
                .and_then(|s| state[s])
                .filter(|&(_, k)| k % per_pixel == per_pixel - 1)
                .map(|(i, k)| (i, (k / per_pixel) as u32));
            match shown {
                Some((i, t)) => {
                    let s = &spans[i];
                    worst = worst.max(bounds[i]);
                    vec![
                        w(ready as u64),
                        w(1),
                        w(t as u64),
                        Expected::Within(s.value(t).clamp(0.0, 255.0), bounds[i]),
                        w((t == s.m) as u64),
                    ]
                }
                None => vec![
                    w(ready as u64),
                    w(0),
                    Expected::DontCare,
                    Expected::DontCare,
                    w(0),
                ],
            }
        })
        .collect();
    (rows, expected, worst)
}

impl Bench for HornerUnit {
    const ITEMS: &'static str = "spans";
    const DEFAULT_ITEMS: usize = 200;
    fn stimulus(p: &HornerParams, n: usize, seed: u64) -> Stimulus {
        let mut spans: Vec<HornerWords> = named_spans().into_iter().map(|(_, w)| w).collect();
        spans.extend(random_spans(seed, n));
        let (rows, expected, worst) = run(p, &spans);
        let value = Compare::Fixed {
            format: LEVEL,
            tol: Tolerance {
                max_abs: worst,
                rms: worst,
            },
        };
        Stimulus {
            rows,
            expected,
            compare: vec![
                Compare::Exact,
                Compare::Exact,
                Compare::Exact,
                value,
                Compare::Exact,
            ],
        }
    }
    fn twin(p: &HornerParams) -> Box<dyn Twin> {
        Box::new(HornerRows(HornerTwin::new(p.pipelined)))
    }
    /// Loads in clocks where `ready` is low (ignored), idle gaps, raw words (any samples, any
    /// step: the p accumulator wraps and p clamps), `hold` in a quarter of the clocks.
    fn edge_rows(_: &HornerParams, seed: u64) -> Vec<Vec<u64>> {
        let mut r = seeded_runner(seed ^ 0x4042);
        let st = (
            prop::array::uniform4(any::<u16>()),
            0u64..(1 << 28),
            0u64..12,
            any::<u8>(),
        );
        (0..1500)
            .map(|_| {
                let (i, step, m, v) = st.new_tree(&mut r).expect("no rejection").current();
                let mut row = vec![(v & 3 == 0) as u64];
                row.extend(i.map(u64::from));
                row.extend([step, m, ((v >> 2) & 3 == 0) as u64]);
                row
            })
            .collect()
    }
}
