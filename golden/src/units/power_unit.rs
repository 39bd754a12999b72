//! Power unit (SPEC §2, the output path of BRZSSK), the golden of `rtl/src/units/power_unit.rs`:
//! the specular value S from cos γ — the exact cos^n γ (square-and-multiply over the bits of
//! n) or W(n, γ) = [1 − (n+1)/(k+1)·(1 − cos γ)]^k for k = 4, 8, 16 (shift-add division,
//! log2 k squarings; `crate::shading::brdf`). Input and output unsigned Q1.15.

use crate::shading::brdf;

/// Which specular value the unit computes (a build parameter of the hardware).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PowerMode {
    /// cos^n γ, square-and-multiply.
    Exact,
    /// W(n, γ) with k ∈ {4, 8, 16}.
    W(u32),
}

impl PowerMode {
    /// The k of W, `None` for the exact power.
    pub fn k(self) -> Option<u32> {
        match self {
            PowerMode::Exact => None,
            PowerMode::W(k) => Some(k),
        }
    }
}

/// The f64 specular value of `cos` (clamped at 0): cos^n or W with the shift-add division.
pub fn power(mode: PowerMode, n: u32, cos: f64) -> f64 {
    match mode {
        PowerMode::Exact => brdf::cos_pow(n, cos),
        PowerMode::W(k) => brdf::w_shift_add(n, k, cos),
    }
}

/// The W-mode slope word a = (n+1)·(shift-add 1/(k+1)) in units of 2^-`frac` — exact:
/// 51·(n+1) (k = 4, frac 8), 57·(n+1) (k = 8, frac 9), 15·(n+1) (k = 16, frac 8).
pub fn slope_word(k: u32, n: u32) -> (u64, u32) {
    let m = n as u64 + 1;
    match k {
        4 => (51 * m, 8),
        8 => (57 * m, 9),
        16 => (15 * m, 8),
        _ => panic!("k = {k} has no shift-add division (4, 8, 16)"),
    }
}

/// Bound on |S_hw − power(mode, n, c)| for an input word c (the same quantized cosine).
///
/// Every rounding to Q1.15 adds ≤ 2⁻¹⁶ absolute; a value v passed through j later squarings
/// (or multiplies by factors ≤ c_max) has its error scaled by ≤ 2·v^(…) ≤ 2 per squaring and
/// by ≤ c_max per multiply. With c ≤ 1 + ε the scaling per stage is ≤ 2(1 + ε)^(2^j): a sum
/// over the stages, evaluated numerically here from the exact intermediate values.
pub fn error_bound(mode: PowerMode, n: u32, c: f64) -> f64 {
    let e = (-16f64).exp2();
    match mode {
        PowerMode::Exact => {
            // Walk the square-and-multiply chain in f64, propagating a first-order bound:
            // err(x·y) ≤ err(x)·y + err(y)·x + e (the rounding), err(x²) ≤ 2x·err(x) + e.
            let (mut acc, mut acc_e) = (1.0f64, 0.0f64);
            let (mut pw, mut pw_e) = (c, 0.0f64);
            for j in 0..10 {
                if (n >> j) & 1 == 1 {
                    acc_e = if j == 0 {
                        0.0
                    } else {
                        acc_e * pw + pw_e * acc + pw_e * acc_e + e
                    };
                    acc *= pw;
                }
                if j < 9 {
                    pw_e = 2.0 * pw * pw_e + pw_e * pw_e + e;
                    pw *= pw;
                }
            }
            acc_e
        }
        PowerMode::W(k) => {
            let (a, frac) = slope_word(k, n);
            let a = a as f64 / (frac as f64).exp2();
            let b = (1.0 - a * (1.0 - c)).max(0.0);
            let (mut v, mut ve) = (b, e);
            for _ in 0..k.trailing_zeros() {
                ve = 2.0 * v * ve + ve * ve + e;
                v *= v;
            }
            ve
        }
    }
}

/// Bit-exact integer twin of `rtl/src/units/power_unit.rs`, written from its header.
///
/// ```text
/// rnd(p)  = min((p + 2¹⁴) >> 15, 0xFFFF)             UQ2.30 → UQ1.15, ties up, saturate
/// exact:  every multiply-and-round takes five clocks: the exact product four registers on
///         (a), then the rounding and the selection (b).
///         E0a acc = n₀ ? c : 0x8000,  sq = c²             E0b pw = rnd(sq)
///         Eja prod = acc·pw,  sq = pw²                    Ejb acc = n_j ? rnd(prod) : acc,
///                                                             pw = rnd(sq)
///         (j = 1..9; E9 squares nothing): latency 50
/// W:      every multiply takes two clocks (a, a'), the rounding one more (b).
/// W:      W1  a = slope word, t = |c − 0x8000|, above = c > 0x8000, zero = c == 0
///         W2  p = a·t                          (2^-(15+f) units; two clocks)
///         W3a sum = zero ? 0 : above ? 2^(15+f) + p : max(2^(15+f) − p, 0)   (registered)
///         W3b b = min((sum + 2^(f−1)) >> f, 0xFFFF)
///         W4..W7  a: sq = b²; b: b = rnd(sq) in the first log2 k stages, else b
///         then 33 delay registers (latency 50 in both modes)
/// ```
/// n travels with its pixel (each stage reads the n that entered with the pixel).
pub mod twin {
    use super::{slope_word, PowerMode};
    use std::collections::VecDeque;

    /// UQ2.30 product → UQ1.15, rounded to nearest (ties up), saturated.
    pub fn rnd(p: u64) -> u64 {
        ((p + (1 << 14)) >> 15).min(0xFFFF)
    }

    /// Exact mode: clocks per square-and-multiply step (the product four, the rounding one).
    const STEP: usize = 5;
    /// Pipeline stages (exact: ten steps; W uses the first 17, then its padding).
    const STAGES: usize = 10 * STEP;

    /// One pixel in flight: (valid, value, pow or a, n).
    #[derive(Clone, Copy, Debug, Default)]
    struct Stage {
        valid: bool,
        acc: u64,
        pw: u64,
        n: u64,
        above: bool,
        zero: bool,
        /// The raw products of an (a) stage.
        prod: u64,
        sq: u64,
    }

    #[derive(Clone, Debug)]
    pub struct PowerTwin {
        mode: PowerMode,
        /// W mode: fraction bits of the slope word (8 or 9).
        frac: u32,
        stages: [Stage; STAGES],
        /// W mode: (valid, value) of the padding delay (33 registers).
        pad: VecDeque<(bool, u64)>,
    }

    impl PowerTwin {
        pub fn new(mode: PowerMode) -> Self {
            PowerTwin {
                mode,
                frac: mode.k().map_or(8, |k| slope_word(k, 0).1),
                stages: [Stage::default(); STAGES],
                pad: std::iter::repeat_n((false, 0), 33).collect(),
            }
        }

        /// (valid_out, S as a UQ1.15 word) shown this clock.
        pub fn outputs(&self) -> (bool, u64) {
            match self.mode {
                PowerMode::Exact => (self.stages[STAGES - 1].valid, self.stages[STAGES - 1].acc),
                PowerMode::W(_) => self.pad[0],
            }
        }

        /// One rising edge: `cos` a UQ1.15 word, `n` the 10-bit exponent.
        pub fn clock(&mut self, valid_in: bool, cos: u64, n: u64) {
            let s = self.stages;
            let n = n & 0x3FF;
            match self.mode {
                PowerMode::Exact => {
                    let mut next = [Stage::default(); STAGES];
                    next[0] = Stage {
                        valid: valid_in,
                        acc: if n & 1 == 1 { cos } else { 0x8000 },
                        sq: cos * cos,
                        n,
                        ..Stage::default()
                    };
                    next[1..STEP - 1].copy_from_slice(&s[..STEP - 2]);
                    next[STEP - 1] = Stage {
                        pw: rnd(s[STEP - 2].sq),
                        sq: 0,
                        ..s[STEP - 2]
                    };
                    for j in 1..10 {
                        let p = s[STEP * j - 1];
                        next[STEP * j] = Stage {
                            valid: p.valid,
                            acc: p.acc,
                            prod: p.acc * p.pw,
                            sq: if j < 9 { p.pw * p.pw } else { 0 },
                            n: p.n,
                            ..Stage::default()
                        };
                        next[STEP * j + 1..STEP * j + STEP - 1]
                            .copy_from_slice(&s[STEP * j..STEP * j + STEP - 2]);
                        let p = s[STEP * j + STEP - 2];
                        next[STEP * j + STEP - 1] = Stage {
                            valid: p.valid,
                            acc: if (p.n >> j) & 1 == 1 {
                                rnd(p.prod)
                            } else {
                                p.acc
                            },
                            pw: if j < 9 { rnd(p.sq) } else { 0 },
                            n: p.n,
                            ..Stage::default()
                        };
                    }
                    self.stages = next;
                }
                PowerMode::W(k) => {
                    let squarings = k.trailing_zeros() as usize;
                    // Output of W7b (stage index 16) enters the padding delay.
                    self.pad.pop_front();
                    self.pad.push_back((s[16].valid, s[16].acc));
                    let mut next = [Stage::default(); STAGES];
                    // W4..W7: (a) at 5, 8, 11, 14, (a') at 6, 9, 12, 15, (b) at 7, 10, 13, 16.
                    for i in 0..4 {
                        let p = s[4 + 3 * i];
                        next[5 + 3 * i] = Stage {
                            valid: p.valid,
                            acc: p.acc,
                            sq: p.acc * p.acc,
                            ..Stage::default()
                        };
                        next[6 + 3 * i] = s[5 + 3 * i];
                        let p = s[6 + 3 * i];
                        next[7 + 3 * i] = Stage {
                            valid: p.valid,
                            acc: if i < squarings { rnd(p.sq) } else { p.acc },
                            ..Stage::default()
                        };
                    }
                    // W3b (index 4): the bracket rounded to UQ1.15.
                    let frac = self.frac;
                    next[4] = Stage {
                        valid: s[3].valid,
                        acc: ((s[3].acc + (1 << (frac - 1))) >> frac).min(0xFFFF),
                        ..Stage::default()
                    };
                    // W3a (index 3): the bracket 1 ± p in p's units, clamped at 0.
                    let p = s[2];
                    let one = 1u64 << (15 + frac);
                    let b = if p.zero {
                        0
                    } else if p.above {
                        one + p.pw
                    } else {
                        one.saturating_sub(p.pw)
                    };
                    next[3] = Stage {
                        valid: p.valid,
                        acc: b,
                        ..Stage::default()
                    };
                    // W2 (indices 1, 2): p = a·t, two clocks.
                    next[2] = s[1];
                    let p = s[0];
                    next[1] = Stage {
                        valid: p.valid,
                        pw: p.acc * p.pw,
                        above: p.above,
                        zero: p.zero,
                        ..Stage::default()
                    };
                    // W1 (index 0): a (held in `acc`), t (in `pw`).
                    let (a, _) = slope_word(k, n as u32);
                    next[0] = Stage {
                        valid: valid_in,
                        acc: a & 0xFFFF,
                        pw: cos.abs_diff(0x8000),
                        above: cos > 0x8000,
                        zero: cos == 0,
                        n,
                        ..Stage::default()
                    };
                    self.stages = next;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_words_are_the_shift_add_divisions() {
        for k in brdf::KS {
            for n in [1, 50, 1000] {
                let (a, f) = slope_word(k, n);
                assert!(a < 1 << 16, "a fits 16 bits");
                let exact = brdf::slope(n, k, true);
                assert_eq!(a as f64 / (f as f64).exp2(), exact, "k {k} n {n}");
            }
        }
        assert_eq!(twin::rnd(1 << 30), 0x8000);
        assert_eq!(twin::rnd(0xFFFF * 0xFFFF), 0xFFFF);
        assert_eq!(twin::rnd((1 << 14) - 1), 0);
        assert_eq!(twin::rnd(1 << 14), 1);
    }
}
