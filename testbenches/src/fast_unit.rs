//! Bench of the fast two-point unit (`rtl::fast_unit`) against `golden::fast_unit` (the f64
//! recurrences on the same words and 1/√(M+1) by the build's quadratic) and its bit-exact twin.
//!
//! Stimulus: named spans — m = 0, 1, 2, odd and even m, N_a = N_b, N_a ⟂ N_b (M reaches −0.5
//! at the middle), X opposite the normals (clamped at 0) — then seeded random spans (unit end
//! normals ≤ 90° apart, a unit X, m up to 60), loaded back to back as `ready` allows.
//! Expectations: `ready`, valid flags, indices and `last` exact from the schedule (step k of a
//! span shows pixel k and its mirror m − k); cos within `golden::fast_unit::error_bound`.

use glam::DVec3;
use golden::fast::span_setup;
use golden::fast_unit::{error_bound, twin::FastTwin, FastWords};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::fast_unit::{FastParams, FastUnit};
use rtl::fixed::SCALE;

use crate::harness::{Compare, Expected, Tolerance};
use crate::normalizer::seeded_runner;
use crate::registry::{Bench, Stimulus, Twin};

const M32: i64 = (1 << 32) - 1;
const M48: i64 = (1 << 48) - 1;

fn unit(z: f64, phi: f64) -> DVec3 {
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

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
    let mut r = seeded_runner(seed);
    let st = (
        (0.0..=1.0f64, 0.0..std::f64::consts::TAU),
        (0.0..=1.0f64, 0.0..std::f64::consts::TAU),
        (-1.0..=1.0f64, 0.0..std::f64::consts::TAU),
        0u32..=60,
    );
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let ((z1, p1), (z2, p2), (z3, p3), m) =
            st.new_tree(&mut r).expect("no rejection").current();
        let (na, nb, x) = (unit(z1, p1), unit(z2, p2), unit(z3, p3));
        if na.dot(nb) < 0.0 {
            continue;
        }
        out.push(FastWords::new(&span_setup(na, nb, x, m)));
    }
    out
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
        ],
        None => vec![0; 7],
    }
}

struct FastRows(FastTwin);

impl Twin for FastRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let o = self.0.outputs();
        let sx = |v: u64, bits: u32| ((v as i64) << (64 - bits)) >> (64 - bits);
        let w = FastWords {
            b: sx(r[1], 32),
            h: sx(r[2], 32),
            g: sx(r[3], 32),
            d0: sx(r[4], 48),
            dd: sx(r[5], 48),
            m: r[6] as u32,
        };
        self.0.clock((r[0] != 0).then_some(&w));
        o
    }
}

/// Rows for `spans` back to back and every clock's expectations.
fn run(spans: &[FastWords], p: &FastParams) -> (Vec<Vec<u64>>, Vec<Vec<Expected>>) {
    let mut rows = vec![load_row(spans.first())];
    let mut state: Vec<Option<(usize, usize)>> = vec![None];
    for (i, w) in spans.iter().enumerate() {
        let len = w.clocks();
        for k in 0..len {
            state.push(Some((i, k)));
            let load = (k == len - 1).then(|| spans.get(i + 1)).flatten();
            rows.push(load_row(load));
        }
    }
    for _ in 0..8 {
        rows.push(load_row(None));
        state.push(None);
    }
    let values: Vec<Vec<f64>> = spans.iter().map(|w| w.values(p.coeffs)).collect();
    let expected = (0..rows.len())
        .map(|c| {
            let ready = match state[c] {
                Some((i, k)) => k + 1 == spans[i].clocks(),
                None => true,
            };
            let mut e = vec![Expected::Word(ready as u64)];
            match c.checked_sub(7).and_then(|s| state[s]) {
                Some((i, k)) => {
                    let m = spans[i].m as usize;
                    let v = &values[i];
                    e.extend([
                        Expected::Word(1),
                        Expected::Word(k as u64),
                        Expected::Real(v[k]),
                    ]);
                    if 2 * k != m {
                        e.extend([
                            Expected::Word(1),
                            Expected::Word((m - k) as u64),
                            Expected::Real(v[m - k]),
                        ]);
                    } else {
                        e.extend([Expected::Word(0), Expected::DontCare, Expected::DontCare]);
                    }
                    e.push(Expected::Word((k + 1 == spans[i].clocks()) as u64));
                }
                None => {
                    for _ in 0..2 {
                        e.extend([Expected::Word(0), Expected::DontCare, Expected::DontCare]);
                    }
                    e.push(Expected::Word(0));
                }
            }
            e
        })
        .collect();
    (rows, expected)
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
    /// Raw words anywhere (every saturation), loads at random.
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
                ]
            })
            .collect()
    }
}
