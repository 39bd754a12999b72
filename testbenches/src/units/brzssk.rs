//! Bench of BRZSSK (`rtl::units::brzssk`) against `golden::units::brzssk` and its bit-exact twin.
//!
//! Stimulus: named cases first — dγ at its largest positive and negative code, and a zero
//! code, each with cos γ at 0, 1, just below 1 and above 1 — then seeded random pixels
//! (cosines mostly near 1, where the highlight is, the rest uniform in [0, 1.004]; random
//! addresses), one clock in eight idle.
//! Tolerance: `valid_out` exact; the cosines within 2⁻¹⁶ (the block's one rounding: the PROM
//! words and addresses are the golden's exactly), RMS the same.
//! Edge rows for the twin: raw words anywhere (cosines up to 0xFFFF), valid toggling.

use golden::units::brzssk::{brzssk, code_rom, twin::BrzsskTwin};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::SCALE;
use rtl::units::brzssk::{Brzssk, BrzsskParams};

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use golden::testing::seeded_runner;

const ONE: u64 = 0x8000;

/// (x, y) of a pixel whose code is the largest positive, the largest negative, and zero.
pub fn extreme_codes() -> [(&'static str, u64, u64); 3] {
    let rom = code_rom();
    let find = |f: &dyn Fn(u64) -> bool| {
        let i = rom.iter().position(|&c| f(c)).expect("code present") as u64;
        (i & 15, i >> 4)
    };
    let pos = find(&|c| c == 255);
    let neg = find(&|c| c == 256 + 255);
    let zero = find(&|c| c & 0xFF == 0);
    [
        ("largest dγ > 0", pos.0, pos.1),
        ("largest dγ < 0", neg.0, neg.1),
        ("dγ = 0", zero.0, zero.1),
    ]
}

fn row(valid: bool, cp: u64, cg: u64, x: u64, y: u64) -> Vec<u64> {
    vec![valid as u64, cp, cg, x, y]
}

struct BrzsskRows(BrzsskTwin);

impl Twin for BrzsskRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (v, p, g) = self.0.outputs();
        self.0.clock(r[0] != 0, r[1], r[2], r[3], r[4]);
        vec![v as u64, p, g]
    }
}

fn cos_strategy() -> impl Strategy<Value = u64> {
    prop_oneof![
        2 => (0.0..=0.25f64).prop_map(|u| SCALE.quantize(1.0 - u * u)),
        1 => 0u64..=32900,
    ]
}

impl Bench for Brzssk {
    const ITEMS: &'static str = "pixels";
    const DEFAULT_ITEMS: usize = 2000;
    fn stimulus(p: &BrzsskParams, n: usize, seed: u64) -> Stimulus {
        let mut r = seeded_runner(seed);
        let mut rows = Vec::new();
        for (_, x, y) in extreme_codes() {
            for c in [0, ONE, ONE - 1, ONE - 8, ONE + 40, ONE / 2] {
                rows.push(row(true, c, c, x + 16, y + 32));
                rows.push(row(true, ONE - c.min(ONE), c, x, y));
            }
        }
        let st = (cos_strategy(), cos_strategy(), 0u64..4096, 0u64..4096);
        for i in 0..n {
            let (cp, cg, x, y) = st.new_tree(&mut r).expect("no rejection").current();
            rows.push(row(i % 8 != 7, cp, cg, x, y));
        }
        for _ in 0..Brzssk::LATENCY {
            rows.push(row(false, 0, 0, 0, 0));
        }
        let expected = (0..rows.len())
            .map(|t| match t.checked_sub(Brzssk::LATENCY) {
                Some(i) if rows[i][0] == 1 => {
                    let q = |w: u64| SCALE.to_f64(w);
                    let (d, s) = if p.enable {
                        brzssk(
                            q(rows[i][1]),
                            q(rows[i][2]),
                            rows[i][3] as i32,
                            rows[i][4] as i32,
                        )
                    } else {
                        (q(rows[i][1]), q(rows[i][2]))
                    };
                    vec![Expected::Word(1), Expected::Real(d), Expected::Real(s)]
                }
                _ => vec![Expected::Word(0), Expected::DontCare, Expected::DontCare],
            })
            .collect();
        let fixed = Compare::Fixed {
            format: SCALE,
            tol: Tolerance {
                max_abs: (-16f64).exp2(),
                rms: (-16f64).exp2(),
            },
        };
        Stimulus {
            rows,
            expected,
            compare: vec![Compare::Exact, fixed, fixed],
        }
    }
    fn twin(p: &BrzsskParams) -> Box<dyn Twin> {
        Box::new(BrzsskRows(BrzsskTwin::new(p.enable)))
    }
    fn edge_rows(_: &BrzsskParams, seed: u64) -> Vec<Vec<u64>> {
        let mut r = seeded_runner(seed ^ 0xb2_2551);
        let st = (
            any::<u16>(),
            any::<u16>(),
            0u64..4096,
            0u64..4096,
            any::<u8>(),
        );
        let mut rows: Vec<Vec<u64>> = [0u64, 1, ONE - 1, ONE, ONE + 1, 0xFFFF]
            .iter()
            .flat_map(|&c| (0..16).map(move |k| row(true, c, 0xFFFF - c, k, 15 - k)))
            .collect();
        for _ in 0..2000 {
            let (cp, cg, x, y, v) = st.new_tree(&mut r).expect("no rejection").current();
            rows.push(row(v & 3 != 0, cp as u64, cg as u64, x, y));
        }
        rows
    }
}
