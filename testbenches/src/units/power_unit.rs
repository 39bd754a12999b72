//! Bench of the power unit (`rtl::units::power_unit`) against `golden::units::power_unit` and its bit-exact
//! twin.
//!
//! Stimulus: named cases (cos γ = 0, 1, just below 1, the largest word; n = 1, 2, 50, 1000),
//! then seeded random pixels: cos γ near 1 (the highlight: 1 − u², u ∈ [0, 0.3]), uniform in
//! [0, 1], and slightly above 1 (up to 1.004, the published normalizer's bias); n uniform in
//! 1..=1000 or one of the common exponents; one clock in eight idle.
//! Tolerance: `valid_out` exact; S within its own pixel's `golden::units::power_unit::error_bound`
//! (`Expected::Within`: the bound depends on n and cos γ) for pixels whose S is below 1.9 (no
//! used intermediate saturates); above 2.1 the saturated word exactly; in between unchecked.
//! The run's largest bound is the port's RMS bound.
//! Edge rows for the twin: raw words anywhere (cos up to 0xFFFF, n = 0 and 1001..1023), n
//! changing every clock.

use golden::units::power_unit::{error_bound, power, twin::PowerTwin};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::SCALE;
use rtl::units::power_unit::{PowerParams, PowerUnit};

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use golden::testing::seeded_runner;

const ONE: u64 = 0x8000;

/// Named cases: (name, cos word, n).
pub fn named_cases() -> Vec<(&'static str, u64, u64)> {
    vec![
        ("cos γ = 0, n = 1", 0, 1),
        ("cos γ = 0, n = 1000", 0, 1000),
        ("cos γ = 1, n = 1", ONE, 1),
        ("cos γ = 1, n = 1000", ONE, 1000),
        ("cos γ = 1 − 1 LSB, n = 1000", ONE - 1, 1000),
        ("cos γ = 1 − 1 LSB, n = 50", ONE - 1, 50),
        ("cos γ = 0.5, n = 1", ONE / 2, 1),
        ("cos γ = 0.5, n = 2", ONE / 2, 2),
        ("cos γ = 0.9, n = 50", 29491, 50),
        ("cos γ = 1.003 (published bias), n = 50", 32866, 50),
        ("cos γ = 1.003, n = 1000 (saturates)", 32866, 1000),
        ("largest cos word, n = 1", 0xFFFF, 1),
        ("largest cos word, n = 1000", 0xFFFF, 1000),
        ("cos γ = 0.99, n = 1000", 32440, 1000),
    ]
}

fn cos_strategy() -> impl Strategy<Value = u64> {
    prop_oneof![
        3 => (0.0..=0.3f64).prop_map(|u| SCALE.quantize(1.0 - u * u)),
        2 => 0u64..=ONE,
        1 => ONE..=32900u64,
    ]
}

fn n_strategy() -> impl Strategy<Value = u64> {
    prop_oneof![
        3 => 1u64..=1000,
        1 => prop::sample::select(vec![1u64, 2, 8, 16, 32, 50, 64, 100, 128, 255, 256, 512, 1000]),
    ]
}

struct PowerRows(PowerTwin);

impl Twin for PowerRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (v, s) = self.0.outputs();
        self.0.clock(r[0] != 0, r[1], r[2]);
        vec![v as u64, s]
    }
}

impl Bench for PowerUnit {
    const ITEMS: &'static str = "pixels";
    const DEFAULT_ITEMS: usize = 2000;
    fn stimulus(p: &PowerParams, n: usize, seed: u64) -> Stimulus {
        let mut r = seeded_runner(seed);
        let mut rows: Vec<Vec<u64>> = named_cases()
            .iter()
            .map(|(_, c, n)| vec![1, *c, *n])
            .collect();
        let st = (cos_strategy(), n_strategy());
        for i in 0..n {
            let (c, e) = st.new_tree(&mut r).expect("no rejection").current();
            rows.push(vec![(i % 8 != 7) as u64, c, e]);
        }
        for _ in 0..PowerUnit::LATENCY {
            rows.push(vec![0, 0, 1]);
        }
        let mut worst: f64 = 0.0;
        let expected = (0..rows.len())
            .map(|t| match t.checked_sub(PowerUnit::LATENCY) {
                Some(i) if rows[i][0] == 1 => {
                    let c = SCALE.to_f64(rows[i][1]);
                    let e = rows[i][2] as u32;
                    let v = power(p.mode, e, c);
                    // Below 1.9 no used intermediate saturates and the bound holds; above
                    // 2.1 the output must be the saturated word; in between either.
                    let s = if v < 1.9 {
                        let b = error_bound(p.mode, e, c);
                        worst = worst.max(b);
                        Expected::Within(v, b)
                    } else if v > 2.1 {
                        Expected::Real(SCALE.max())
                    } else {
                        Expected::DontCare
                    };
                    vec![Expected::Word(1), s]
                }
                _ => vec![Expected::Word(0), Expected::DontCare],
            })
            .collect();
        Stimulus {
            rows,
            expected,
            compare: vec![
                Compare::Exact,
                Compare::Fixed {
                    format: SCALE,
                    tol: Tolerance {
                        max_abs: worst,
                        rms: worst,
                    },
                },
            ],
        }
    }
    fn twin(p: &PowerParams) -> Box<dyn Twin> {
        Box::new(PowerRows(PowerTwin::new(p.mode)))
    }
    fn edge_rows(_: &PowerParams, seed: u64) -> Vec<Vec<u64>> {
        let mut r = seeded_runner(seed ^ 0x90_3e5);
        let st = (any::<u16>(), 0u64..1024, any::<u8>());
        let mut rows: Vec<Vec<u64>> = [0u64, 1, 1001, 1023]
            .iter()
            .flat_map(|&n| [0, 1, ONE - 1, ONE, ONE + 1, 0xFFFF].map(|c| vec![1, c, n]))
            .collect();
        for _ in 0..3000 {
            let (c, n, v) = st.new_tree(&mut r).expect("no rejection").current();
            rows.push(vec![(v & 3 != 0) as u64, c as u64, n]);
        }
        rows
    }
}
