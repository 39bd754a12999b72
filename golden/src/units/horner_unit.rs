//! The Horner unit of fig. 2.6 (SPEC §9), the golden of `rtl/src/units/horner_unit.rs`: one colour
//! channel of cubic shading along a span, I(p) = ((A·p + B)·p + C)·p + D at p = t/m, with the
//! coefficients formed from the four samples I1 = I(0), I2 = I(1), I3 = I(1/2), I4 = I(1/4) by
//! shifts and adds in hardware.
//!
//! # Words
//! - Samples I1..I4: signed Q11.5 (16 bits, LSB units of the 8-bit channel; ±1024).
//! - `step` = round(2²⁷/m) (UQ1.27, 28 bits; 0 for m = 0); the unit accumulates p = t·step and
//!   rounds it to UQ1.15 (clamped at 1.0) for the multiplier.
//! - Coefficients (exact, signed, units of 2⁻¹² LSB, 32 bits), with T(v) = 64v − 16v − 4v − v =
//!   128·(1/2 − 1/8 − 1/32 − 1/128)·v, the thesis' 1/3 by shifts and adds, applied to the
//!   project's grouping (difference numerators; `crate::shading::cubic` explains why):
//!   A = 8·T(I2 + 8·I4 − 3·I1 − 6·I3), B = 256·(7·I1 − I2 + 10·I3 − 16·I4),
//!   C = T(I2 + 32·I4 − 21·I1 − 12·I3), D = 128·I1 (I in Q11.5 integer units). |A| < 2²⁹,
//!   |B| < 2²⁹, |C| < 2²⁷ for any input words, so every Horner value stays below 2³¹: nothing
//!   wraps, nothing needs saturating before the output.
//! - Each product x·p (signed 32 × UQ1.15) is rounded to 2⁻¹² (+2¹⁴, drop 15 bits, ties up);
//!   the output rounds to an integer (+2¹¹, drop 12) and saturates to 0..=255.

use crate::shading::cubic::{coefficients, horner, THIRD};

/// Fraction bits of the sample words.
pub const SAMPLE_FRAC: u32 = 5;
/// Fraction bits of the coefficient and Horner words.
pub const COEFF_FRAC: u32 = 12;
/// Fraction bits of `step` and the p accumulator.
pub const STEP_FRAC: u32 = 27;

/// The words one span loads into one channel's unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct HornerWords {
    /// I1, I2, I3, I4 (signed Q11.5 as i64).
    pub i: [i64; 4],
    /// round(2²⁷/m), 0 for m = 0.
    pub step: u64,
    /// pixels − 1.
    pub m: u32,
}

/// A sample in LSB units → Q11.5, rounded, saturated to the 16-bit word.
pub fn sample_word(v: f64) -> i64 {
    let q = (v * (SAMPLE_FRAC as f64).exp2() + 0.5).floor();
    if q.is_nan() {
        0
    } else {
        q.clamp(-32768.0, 32767.0) as i64
    }
}

/// round(2²⁷/m), 0 for m = 0.
pub fn step_word(m: u32) -> u64 {
    if m == 0 {
        0
    } else {
        ((1u64 << STEP_FRAC) + m as u64 / 2) / m as u64
    }
}

impl HornerWords {
    /// The words of samples `s` (LSB units) on a span of m + 1 pixels.
    pub fn new(s: [f64; 4], m: u32) -> HornerWords {
        HornerWords {
            i: s.map(sample_word),
            step: step_word(m),
            m,
        }
    }
    /// The samples the words stand for (LSB units).
    pub fn samples(&self) -> [f64; 4] {
        self.i.map(|w| w as f64 / (SAMPLE_FRAC as f64).exp2())
    }
    /// The f64 coefficients of the words' samples, as `crate::shading::cubic::coefficients` (THIRD).
    pub fn coefficients(&self) -> [f64; 4] {
        let [i1, i2, i3, i4] = self.samples();
        coefficients(i1, i2, i3, i4, THIRD)
    }
    /// The f64 value at pixel t (p = t/m exactly; p = 0 for m = 0), unclamped.
    pub fn value(&self, t: u32) -> f64 {
        let p = if self.m == 0 {
            0.0
        } else {
            t as f64 / self.m as f64
        };
        horner(&self.coefficients(), p)
    }
    /// Bound on |hardware − clamp(value)| in LSB: the final rounding (½), three product
    /// roundings (2⁻¹³ each, the later ones scaled by p ≤ 1), and p's error (≤ 2⁻¹⁵: the
    /// accumulated step ≤ m·2⁻²⁸, then rounding to UQ1.15) times max |I'(p)| ≤ 3|A| + 2|B| + |C|.
    pub fn error_bound(&self) -> f64 {
        let [a, b, c, _] = self.coefficients();
        0.5 + 3.0 * (-13f64).exp2() + (3.0 * a.abs() + 2.0 * b.abs() + c.abs()) * (-15f64).exp2()
    }
}

/// The exact coefficient words (units of 2⁻¹²) of sample words i1..i4, by the hardware's
/// shifts and adds.
pub fn coefficient_words(i: [i64; 4]) -> [i64; 4] {
    let [i1, i2, i3, i4] = i;
    let t = |v: i64| (v << 6) - (v << 4) - (v << 2) - v; // 128·THIRD·v
    let na = i2 + (i4 << 3) - ((i1 << 1) + i1) - ((i3 << 2) + (i3 << 1));
    let nb = ((i1 << 3) - i1) - i2 + ((i3 << 3) + (i3 << 1)) - (i4 << 4);
    let nc = i2 + (i4 << 5) - ((i1 << 4) + (i1 << 2) + i1) - ((i3 << 3) + (i3 << 2));
    [t(na) << 3, nb << 8, t(nc), i1 << 7]
}

/// Bit-exact twin of `rtl::units::horner_unit::HornerUnit` (both variants).
pub mod twin {
    use super::{coefficient_words, HornerWords};

    /// x·p rounded to 2⁻¹² (x signed, p UQ1.15): (x·p + 2¹⁴) >> 15, arithmetic.
    pub fn mul_round(x: i64, p: u64) -> i64 {
        (x * p as i64 + (1 << 14)) >> 15
    }

    /// The p word of accumulator `acc` (UQ1.27, 29 bits, wrapping): (acc + 2¹¹) >> 12, clamped
    /// at 0x8000.
    pub fn p_word(acc: u64) -> u64 {
        ((acc + (1 << 11)) >> 12).min(0x8000)
    }

    /// The output of a Horner value (units 2⁻¹²): rounded, saturated to 0..=255.
    pub fn out8(v: i64) -> u64 {
        ((v + (1 << 11)) >> 12).clamp(0, 255) as u64
    }

    /// A value in the serial loop: (valid, t, last, p, value, c, d).
    type Item = (bool, u32, bool, u64, i64, i64, i64);

    #[derive(Clone, Debug, Default)]
    pub struct HornerTwin {
        pipelined: bool,
        busy: bool,
        /// Runs free from reset: 1 issues step 0 of the walk's pixel, 2 step 1, 0 step 2.
        phase: u8,
        /// Serial: the walk's pixel went into the loop in the last phase 1 (not held).
        issued: bool,
        t: u32,
        m: u32,
        acc: u64,
        step: u64,
        k: [i64; 4],
        /// Serial: the loop's four registers (OP, PR, PT, RG), each value already the result
        /// its step will have in RG.
        ring: std::collections::VecDeque<Item>,
        // pipelined stages: (valid, t, last, p, x, c, d)
        s1: (bool, u32, bool, u64, i64, i64, i64),
        s2: (bool, u32, bool, u64, i64, i64),
        /// Pipelined: the ten registers padding its output to the serial latency.
        pad: std::collections::VecDeque<(bool, u32, u64, bool)>,
        // output register
        out: (bool, u32, u64, bool),
    }

    impl HornerTwin {
        pub fn new(pipelined: bool) -> Self {
            HornerTwin {
                pipelined,
                ring: std::iter::repeat_n(Item::default(), 4).collect(),
                pad: std::iter::repeat_n((false, 0, 0, false), 10).collect(),
                ..Default::default()
            }
        }
        fn adv(&self) -> bool {
            self.pipelined || self.phase == 0
        }
        pub fn ready(&self) -> bool {
            self.ready_held(false)
        }
        /// `ready` with the `hold` input of this clock: low under `hold`; busy, only once the
        /// span's last pixel is issued (serial: it went into the loop in the last slot).
        pub fn ready_held(&self, hold: bool) -> bool {
            let fin = self.t == self.m && (self.pipelined || self.issued);
            self.adv() && !hold && (!self.busy || fin)
        }
        /// ready, valid, t, value, last.
        pub fn outputs(&self) -> Vec<u64> {
            self.outputs_held(false)
        }
        /// [`Self::outputs`] with the `hold` input of this clock (it reaches only `ready`).
        pub fn outputs_held(&self, hold: bool) -> Vec<u64> {
            let (v, t, val, last) = self.out;
            vec![
                self.ready_held(hold) as u64,
                v as u64,
                t as u64,
                val,
                last as u64,
            ]
        }
        pub fn clock(&mut self, load: Option<&HornerWords>) {
            self.clock_held(load, false)
        }
        /// One clock with `hold`: pipelined, no pixel issued and t stays; serial, a held phase 1
        /// issues an empty slot and the walk does not move on at the next phase 0; no load.
        pub fn clock_held(&mut self, load: Option<&HornerWords>, hold: bool) {
            let p = p_word(self.acc);
            let last = self.t == self.m;
            let go = self.busy && !hold;
            if self.pipelined {
                let (v2, t2, l2, p2, x2, d2) = self.s2;
                self.out = self.pad.pop_front().unwrap();
                self.pad
                    .push_back((v2, t2, out8(mul_round(x2, p2) + d2), v2 && l2));
                let (v1, t1, l1, p1, x1, c1, d1) = self.s1;
                self.s2 = (v1, t1, l1, p1, mul_round(x1, p1) + c1, d1);
                let [a, b, c, d] = self.k;
                self.s1 = (go, self.t, last, p, mul_round(a, p) + b, c, d);
            } else {
                let [a, b, c, d] = self.k;
                let rg = *self.ring.back().unwrap();
                let (rv, rt, rl, rp, rval, rc, rd) = rg;
                if self.phase == 1 {
                    self.out = (
                        rv,
                        if rv { rt } else { self.out.1 },
                        if rv { out8(rval) } else { self.out.2 },
                        rv && rl,
                    );
                } else {
                    self.out.0 = false;
                    self.out.3 = false;
                }
                // Issue: the value RG will hold four clocks on, wrapped to the 32-bit word.
                let wrap = |v: i64| v as i32 as i64;
                let issued = match self.phase {
                    1 => (go, self.t, last, p, wrap(mul_round(a, p) + b), c, d),
                    2 => (rv, rt, rl, rp, wrap(mul_round(rval, rp) + rc), rc, rd),
                    _ => (rv, rt, rl, rp, wrap(mul_round(rval, rp) + rd), rc, rd),
                };
                self.ring.pop_back();
                self.ring.push_front(issued);
            }
            let ready = self.ready_held(hold);
            let walk = if self.pipelined {
                go
            } else {
                self.phase == 0 && self.busy && self.issued
            };
            if self.phase == 1 {
                self.issued = go;
            }
            if walk {
                if last {
                    self.busy = false;
                } else {
                    self.t += 1;
                    self.acc = (self.acc + self.step) & ((1 << 29) - 1);
                }
            }
            self.phase = if self.phase == 2 { 0 } else { self.phase + 1 };
            if let Some(w) = load.filter(|_| ready) {
                self.busy = true;
                self.t = 0;
                self.acc = 0;
                self.m = w.m;
                self.step = w.step;
                self.k = coefficient_words(w.i);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coefficient_words_are_the_f64_coefficients() {
        let w = HornerWords::new([100.25, 37.5, 80.0, 91.125], 9);
        let k = coefficient_words(w.i);
        let f = w.coefficients();
        for j in 0..4 {
            assert!(
                (k[j] as f64 / 4096.0 - f[j]).abs() < 1e-9,
                "{j}: {} vs {}",
                k[j] as f64 / 4096.0,
                f[j]
            );
        }
        // Constant intensity: A = B = C = 0 (the project's grouping).
        let c = coefficient_words(HornerWords::new([77.0; 4], 5).i);
        assert_eq!(&c[..3], &[0, 0, 0]);
        // Ranges: the extreme words keep every coefficient within its stated width.
        for i in [
            [-32768, 32767, -32768, 32767],
            [32767, -32768, 32767, -32768],
        ] {
            let [a, b, c, _] = coefficient_words(i);
            assert!(a.abs() < 1 << 29 && b.abs() < 1 << 29 && c.abs() < 1 << 27);
        }
    }
}
