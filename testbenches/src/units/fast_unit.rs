//! Bench of the fast two-point unit (`rtl::units::fast_unit`) against `golden::units::fast_unit` (the f64
//! recurrences on the same words and 1/√(M+1) by the build's quadratic) and its bit-exact twin.
//!
//! Stimulus: named spans — m = 0, 1, 2, odd and even m, N_a = N_b, N_a ⟂ N_b (M reaches −0.5
//! at the middle), X opposite the normals (clamped at 0) — then seeded random spans (unit end
//! normals ≤ 90° apart, a unit X, m up to 60), loaded back to back as `ready` allows.
//! Expectations: `ready`, valid flags, indices and `done` exact from the schedule (step k of a
//! span shows pixel k and its mirror m − k); cos within `golden::units::fast_unit::error_bound`.

use glam::DVec3;
use golden::shading::fast::span_setup;
use golden::units::fast_unit::{error_bound, twin::FastTwin, FastWords};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::SCALE;
use rtl::units::fast_unit::{FastParams, FastUnit};

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::span::{random_span_vectors, span_run};
use golden::testing::seeded_runner;

const M32: i64 = (1 << 32) - 1;
const M48: i64 = (1 << 48) - 1;

/// Named spans.
pub fn named_spans() -> Vec<(&'static str, FastWords)> {
    let a = DVec3::new(0.0, 0.0, 1.0);
    let b = DVec3::new(0.6, 0.0, 0.8);
    let x = DVec3::new(0.3, 0.2, 0.93).normalize();
    let w = |na: DVec3, nb: DVec3, x: DVec3, m: u32| FastWords::new(&span_setup(na, nb, x, m));
    vec![
        ("m = 0", w(a, b, x, 0)),
        ("m = 1", w(a, b, x, 1)),
        ("m = 2", w(a, b, x, 2)),
        ("m = 7 (odd)", w(a, b, x, 7)),
        ("m = 8 (even)", w(a, b, x, 8)),
        ("N_a = N_b", w(a, a, x, 9)),
        ("N_a ⟂ N_b: M = −0.5 at the middle", w(a, DVec3::X, x, 40)),
        ("X opposite: clamped at 0", w(a, b, -x, 10)),
        ("long span", w(a, b, x, 301)),
    ]
}

fn random_spans(seed: u64, n: usize) -> Vec<FastWords> {
    random_span_vectors(seed, n)
        .into_iter()
        .map(|(na, nb, x, m)| FastWords::new(&span_setup(na, nb, x, m)))
        .collect()
}

fn load_row(w: Option<&FastWords>) -> Vec<u64> {
    match w {
        Some(w) => vec![
            1,
            (w.b & M32) as u64,
            (w.h & M32) as u64,
            (w.g & M32) as u64,
            (w.d0 & M48) as u64,
            (w.dd & M48) as u64,
            w.m as u64,
            0,
        ],
        None => vec![0; 8],
    }
}

struct FastRows(FastTwin);

impl Twin for FastRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[7] != 0;
        let o = self.0.outputs_held(hold);
        let sx = |v: u64, bits: u32| ((v as i64) << (64 - bits)) >> (64 - bits);
        let w = FastWords {
            b: sx(r[1], 32),
            h: sx(r[2], 32),
            g: sx(r[3], 32),
            d0: sx(r[4], 48),
            dd: sx(r[5], 48),
            m: r[6] as u32,
        };
        self.0.clock_held((r[0] != 0).then_some(&w), hold);
        o
    }
}

/// Rows for `spans` back to back and every clock's expectations: step k of a span shows
/// pixel k and (unless it is the same pixel) its mirror m − k, `FastUnit::LATENCY` − 1 clocks
/// after its state (the load takes the other clock).
fn run(spans: &[FastWords], p: &FastParams) -> (Vec<Vec<u64>>, Vec<Vec<Expected>>) {
    let values: Vec<Vec<f64>> = spans.iter().map(|w| w.values(p.coeffs)).collect();
    span_run(
        spans.len(),
        |i| spans[i].clocks(),
        |i| load_row(i.map(|i| &spans[i])),
        FastUnit::LATENCY - 1,
        |i, k| {
            let m = spans[i].m as usize;
            let right = (2 * k != m).then(|| ((m - k) as u64, values[i][m - k]));
            [Some((k as u64, values[i][k])), right]
        },
    )
}

impl Bench for FastUnit {
    const ITEMS: &'static str = "spans";
    const DEFAULT_ITEMS: usize = 200;
    fn stimulus(p: &FastParams, n: usize, seed: u64) -> Stimulus {
        let mut spans: Vec<FastWords> = named_spans().into_iter().map(|(_, w)| w).collect();
        spans.extend(random_spans(seed, n));
        let (rows, expected) = run(&spans, p);
        let b = error_bound(p.coeffs);
        let cos = Compare::Fixed {
            format: SCALE,
            tol: Tolerance { max_abs: b, rms: b },
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
    fn twin(p: &FastParams) -> Box<dyn Twin> {
        Box::new(FastRows(FastTwin::new(p.coeffs)))
    }
    /// Raw words anywhere (every saturation), loads at random, `hold` in a quarter of the clocks.
    fn edge_rows(_: &FastParams, seed: u64) -> Vec<Vec<u64>> {
        let mut r = seeded_runner(seed ^ 0xfa57);
        let st = (
            any::<u32>(),
            any::<u32>(),
            any::<u32>(),
            any::<u64>(),
            any::<u64>(),
            0u64..40,
            any::<u8>(),
        );
        (0..1500)
            .map(|_| {
                let (b, h, g, d0, dd, m, v) = st.new_tree(&mut r).expect("no rejection").current();
                vec![
                    (v & 7 == 0) as u64,
                    b as u64,
                    h as u64,
                    g as u64,
                    d0 & 0xFFFF_FFFF_FFFF,
                    dd & 0xFFFF_FFFF_FFFF,
                    m,
                    (v >> 4 & 3 == 0) as u64,
                ]
            })
            .collect()
    }
}
