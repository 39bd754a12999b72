//! Bench of the cos v accumulator (`rtl::units::cos_v_accumulator`) against
//! `golden::units::cos_v_accumulator` (the runs' index sets and cos β·cos(arg) in f64) and its
//! bit-exact twin.
//!
//! Stimulus: named spans first — m = 0, 1, 2, odd and even m, N_a = N_b (Δφ = 0), E before the
//! span (the borrow on run A's first clock), E beyond it (run B stops at once), cos β near 0 —
//! then seeded random spans: unit end normals ≤ 90° apart, a unit X, m up to 60; each span
//! loaded in the clock `ready` rises, back to back.
//! Expectations: `ready`, valid flags, indices and `done` exact from the runs' index sets
//! (`SpanWords::run_a`, `run_b`: clock k of a span shows run A's k-th and run B's k-th pixel);
//! cos within `golden::units::cos_v_accumulator::ERROR_BOUND` of the f64 value.

use glam::DVec3;
use golden::shading::angular::span_setup;
use golden::units::cos_v_accumulator::{cos_v, twin::CosVTwin, SpanWords, ERROR_BOUND};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::SCALE;
use rtl::core::registry::NoParams;
use rtl::units::cos_v_accumulator::CosVAccumulator;

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::span::{random_span_vectors, span_run};
use golden::testing::seeded_runner;

const MASK: i64 = (1 << 32) - 1;

/// Named spans: (name, words).
pub fn named_spans() -> Vec<(&'static str, SpanWords)> {
    let a = DVec3::new(0.0, 0.0, 1.0);
    let b = DVec3::new(0.6, 0.0, 0.8);
    let mid = (a + b).normalize();
    let w = |na: DVec3, nb: DVec3, x: DVec3, m: u32| SpanWords::new(&span_setup(na, nb, x, m));
    vec![
        ("m = 0", w(a, b, mid, 0)),
        ("m = 1", w(a, b, mid, 1)),
        ("m = 2", w(a, b, mid, 2)),
        ("m = 7 (odd), E mid-span", w(a, b, mid, 7)),
        ("m = 8 (even), E mid-span", w(a, b, mid, 8)),
        ("N_a = N_b", w(a, a, mid, 9)),
        (
            "E before the span: borrow on the first clock",
            w(a, b, DVec3::new(-0.3, 0.0, 0.95).normalize(), 10),
        ),
        (
            "E beyond the span: run B stops at once",
            w(a, b, DVec3::new(0.9, 0.0, 0.43).normalize(), 10),
        ),
        (
            "cos β near 0",
            w(a, b, DVec3::new(0.02, 0.9998, 0.0).normalize(), 12),
        ),
        // End normals 158° apart (a scan's vertex whose normal points away): the argument
        // passes −3π/2, where cos is positive again (the dragon at 1920×1080, row 371).
        (
            "end normals 158° apart, argument past a half turn",
            w(
                DVec3::new(0.0, -0.447_213_6, -0.894_427_2),
                DVec3::new(0.286_253, 0.190_367, 0.939_052).normalize(),
                DVec3::new(-0.6, 0.1, 0.79).normalize(),
                5,
            ),
        ),
    ]
}

fn random_spans(seed: u64, n: usize) -> Vec<SpanWords> {
    random_span_vectors(seed, n)
        .into_iter()
        .map(|(na, nb, x, m)| SpanWords::new(&span_setup(na, nb, x, m)))
        .collect()
}

fn load_row(w: Option<&SpanWords>) -> Vec<u64> {
    match w {
        Some(w) => vec![
            1,
            (w.p & MASK) as u64,
            (w.q & MASK) as u64,
            (w.d & MASK) as u64,
            w.cos_beta,
            w.m as u64,
            0,
        ],
        None => vec![0; 7],
    }
}

struct CosVRows(CosVTwin);

impl Twin for CosVRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[6] != 0;
        let o = self.0.outputs_held(hold);
        let signed = |x: u64| ((x as i64) << 32) >> 32;
        let w = SpanWords {
            p: signed(r[1]),
            q: signed(r[2]),
            d: signed(r[3]),
            cos_beta: r[4],
            m: r[5] as u32,
        };
        self.0.clock_held((r[0] != 0).then_some(&w), hold);
        o
    }
}

/// Rows for `spans` back to back and every clock's expectations: clock k of a span shows run
/// A's k-th and run B's k-th pixel, `CosVAccumulator::LATENCY` − 1 clocks after its state.
fn run(spans: &[SpanWords]) -> (Vec<Vec<u64>>, Vec<Vec<Expected>>) {
    let runs: Vec<(Vec<u32>, Vec<u32>)> = spans.iter().map(|w| (w.run_a(), w.run_b())).collect();
    span_run(
        spans.len(),
        |i| spans[i].clocks(),
        |i| load_row(i.map(|i| &spans[i])),
        CosVAccumulator::LATENCY - 1,
        |i, k| {
            let lane = |r: &Vec<u32>| r.get(k).map(|&t| (t as u64, cos_v(&spans[i], t)));
            [lane(&runs[i].0), lane(&runs[i].1)]
        },
    )
}

impl Bench for CosVAccumulator {
    const ITEMS: &'static str = "spans";
    const DEFAULT_ITEMS: usize = 200;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let mut spans: Vec<SpanWords> = named_spans().into_iter().map(|(_, w)| w).collect();
        spans.extend(random_spans(seed, n));
        let (rows, expected) = run(&spans);
        let cos = Compare::Fixed {
            format: SCALE,
            tol: Tolerance {
                max_abs: ERROR_BOUND,
                rms: ERROR_BOUND,
            },
        };
        Stimulus {
            rows,
            expected,
            compare: vec![
                Compare::Exact,
                Compare::Exact,
                Compare::Exact,
                cos,
                Compare::Exact,
                Compare::Exact,
                cos,
                Compare::Exact,
            ],
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(CosVRows(CosVTwin::default()))
    }
    /// Loads in clocks where `ready` is low (ignored), idle gaps, raw words, `hold` in a quarter
    /// of the clocks.
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let mut r = seeded_runner(seed ^ 0xc05);
        let st = (
            any::<u32>(),
            any::<u32>(),
            0u32..(1 << 20),
            any::<u16>(),
            0u64..40,
            any::<u8>(),
        );
        (0..1500)
            .map(|_| {
                let (p, q, d, cb, m, v) = st.new_tree(&mut r).expect("no rejection").current();
                vec![
                    (v & 7 == 0) as u64,
                    p as u64,
                    q as u64,
                    d as u64,
                    cb as u64,
                    m,
                    (v >> 4 & 3 == 0) as u64,
                ]
            })
            .collect()
    }
}
