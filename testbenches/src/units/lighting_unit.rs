//! Bench of the lighting unit (`rtl::units::lighting_unit`) against `golden::units::lighting_unit` and its
//! bit-exact twin.
//!
//! Stimulus: named cases first (cos at 1, 0 and negative, K at both ends of the domain), then
//! seeded domain vectors (`crate::units::normalizer::domain_vector`) with random unit L and H that
//! change every 64 clocks. Tolerance: `valid_out` exact; each cosine within
//! `golden::units::lighting_unit::error_bound` of the normalizer's domain budget for the unit vector
//! it is dotted with (max), and the same bound built from the budget's RMS (RMS).
//! Edge rows for the twin: raw words anywhere (K up to 12, non-unit L and H: the saturation
//! paths at 0 and 2).

use glam::DVec3;
use golden::units::lighting_unit::{error_bound, twin::LightingTwin, COS_MAX};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::{INTERPOLATED, NORMAL, SCALE};
use rtl::units::lighting_unit::LightingUnit;
use rtl::units::normalizer::NormalizerCoeffs;

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::normalizer::{
    domain_budget, domain_vector, edge_cases, quantize, saturating_model, seeded_runner,
};

/// Clocks between changes of L and H in the random stimulus.
const LIGHT_PERIOD: usize = 64;

fn to_vec(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// A uniformly random unit vector.
fn unit_vector() -> impl Strategy<Value = [f64; 3]> {
    (-1.0..=1.0f64, 0.0..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).max(0.0).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    })
}

/// Raw signed Q2.14 words of a unit vector (L, H).
fn quantize_unit(v: [f64; 3]) -> [u64; 3] {
    v.map(|c| NORMAL.quantize(c))
}

/// Real values of raw Q2.14 words (L, H).
fn dequantize_unit(raw: [u64; 3]) -> [f64; 3] {
    raw.map(|r| NORMAL.to_f64(r))
}

/// One input row: valid, N (signed Q2.17), L, H (signed Q2.14) as raw words.
fn row(valid: bool, n: [u64; 3], l: [u64; 3], h: [u64; 3]) -> Vec<u64> {
    let mut r = vec![valid as u64];
    r.extend(n);
    r.extend(l);
    r.extend(h);
    r
}

/// A named case: (name, N, L, H) in f64, quantized before use.
pub type NamedCase = (String, [f64; 3], [f64; 3], [f64; 3]);

/// The named cases.
pub fn named_cases() -> Vec<NamedCase> {
    let mut out = Vec::new();
    for (name, v) in edge_cases() {
        let u = to_vec(v).normalize();
        let perp = u.any_orthonormal_vector();
        out.push((
            format!("{name}: cos φ = 1, cos γ < 0"),
            v,
            u.to_array(),
            (-u).to_array(),
        ));
        out.push((
            format!("{name}: cos φ = 0, cos γ = 1"),
            v,
            perp.to_array(),
            u.to_array(),
        ));
    }
    out
}

/// The golden cosines of raw words (N through the normalizer's saturating f64 model).
fn golden_cos(n: [u64; 3], l: [u64; 3], h: [u64; 3], c: &NormalizerCoeffs) -> (f64, f64) {
    let np = to_vec(saturating_model(n, c.requested));
    let clamp = |v: f64| v.clamp(0.0, COS_MAX);
    (
        clamp(np.dot(to_vec(dequantize_unit(l)))),
        clamp(np.dot(to_vec(dequantize_unit(h)))),
    )
}

struct LightingRows(LightingTwin);

impl Twin for LightingRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (v, d, s) = self.0.outputs();
        let w = |i: usize| [r[i], r[i + 1], r[i + 2]].map(|x| NORMAL.to_int(x));
        let n = [r[1], r[2], r[3]].map(|x| INTERPOLATED.to_int(x));
        self.0.clock(r[0] != 0, n, w(4), w(7));
        vec![v as u64, d as u64, s as u64]
    }
}

impl Bench for LightingUnit {
    const ITEMS: &'static str = "pixels";
    const DEFAULT_ITEMS: usize = 2000;
    fn stimulus(c: &NormalizerCoeffs, n: usize, seed: u64) -> Stimulus {
        let mut r = seeded_runner(seed);
        let mut rows: Vec<Vec<u64>> = named_cases()
            .into_iter()
            .map(|(_, v, l, h)| row(true, quantize(v), quantize_unit(l), quantize_unit(h)))
            .collect();
        let nv = domain_vector();
        let uv = unit_vector();
        let (mut l, mut h) = ([0; 3], [0; 3]);
        for i in 0..n {
            if i % LIGHT_PERIOD == 0 {
                l = quantize_unit(uv.new_tree(&mut r).expect("no rejection").current());
                h = quantize_unit(uv.new_tree(&mut r).expect("no rejection").current());
            }
            let v = quantize(nv.new_tree(&mut r).expect("no rejection").current());
            // One clock in eight idle: valid_out must follow.
            rows.push(row(i % 8 != 7, v, l, h));
        }
        // Flush with L, H held.
        let last = rows
            .last()
            .cloned()
            .unwrap_or_else(|| row(false, [0; 3], l, h));
        for _ in 0..LightingUnit::LATENCY {
            let mut f = last.clone();
            f[0] = 0;
            rows.push(f);
        }
        // The expectation of clock t is the pixel that entered at t − latency, lit with the
        // L, H present when it reached D1 (the normalizer's output: clock t − at_d1).
        let at_d1 = LightingUnit::LATENCY - rtl::units::normalizer::Normalizer::LATENCY;
        let budget = domain_budget(c);
        let mut worst: f64 = 0.0;
        let mut worst_rms: f64 = 0.0;
        let expected = (0..rows.len())
            .map(|t| match t.checked_sub(LightingUnit::LATENCY) {
                Some(i) if rows[i][0] == 1 => {
                    let at = &rows[t - at_d1];
                    let l = [at[4], at[5], at[6]];
                    let h = [at[7], at[8], at[9]];
                    for u in [l, h] {
                        let u = to_vec(dequantize_unit(u));
                        worst = worst.max(error_bound(budget.component_max, u));
                        worst_rms = worst_rms.max(
                            (u.x.abs() + u.y.abs() + u.z.abs()) * budget.component_rms
                                + SCALE.lsb() / 12f64.sqrt(),
                        );
                    }
                    let (d, s) = golden_cos([rows[i][1], rows[i][2], rows[i][3]], l, h, c);
                    vec![Expected::Word(1), Expected::Real(d), Expected::Real(s)]
                }
                _ => vec![Expected::Word(0), Expected::DontCare, Expected::DontCare],
            })
            .collect();
        let fixed = Compare::Fixed {
            format: SCALE,
            tol: Tolerance {
                max_abs: worst,
                rms: worst_rms,
            },
        };
        Stimulus {
            rows,
            expected,
            compare: vec![Compare::Exact, fixed, fixed],
        }
    }
    fn twin(c: &NormalizerCoeffs) -> Box<dyn Twin> {
        Box::new(LightingRows(LightingTwin::new(c.requested)))
    }
    fn edge_rows(_: &NormalizerCoeffs, seed: u64) -> Vec<Vec<u64>> {
        let mut r = seeded_runner(seed ^ 0x11_6417);
        let words = prop::array::uniform10(any::<u32>());
        let mut rows: Vec<Vec<u64>> = crate::units::normalizer::extreme_cases()
            .into_iter()
            .flat_map(|(_, v)| {
                [
                    row(true, v, [0x7FFF; 3], [0x8000; 3]),
                    row(true, v, [0x8000; 3], [0x4000, 0, 0]),
                ]
            })
            .collect();
        for _ in 0..3000 {
            let raw = words.new_tree(&mut r).expect("no rejection").current();
            // N 19 bits, L and H 16.
            let n = |x: u32| (x & 0x7_FFFF) as u64;
            let w = raw.map(|x| (x & 0xFFFF) as u64);
            rows.push(row(
                w[9] & 3 != 0,
                [n(raw[0]), n(raw[1]), n(raw[2])],
                [w[3], w[4], w[5]],
                [w[6], w[7], w[8]],
            ));
        }
        rows
    }
}
