//! The cos v accumulator (SPEC §4, thesis fig. 3.6), the golden of
//! `rtl/src/units/cos_v_accumulator.rs`: cos v(t) = cos β·cos(ψ − t·Δφ) along a span, from both ends
//! at once — two pixels per clock.
//!
//! Per-span words (software set-up from [`crate::shading::angular::span_setup`]): ψ as `p`, Δφ as `d`
//! (binary angles: 2³² is a whole turn, so the 32-bit words wrap exactly as angles do; rounded),
//! `q = m·d − p` (run B's argument u·Δφ − ψ at u = m, the exact negative of run A's
//! ψ − u·Δφ), cos β in unsigned Q1.15, m.
//!
//! The runs split the span at its midpoint: run A takes t = 0 … ⌈(m+1)/2⌉ − 1 upward, run B
//! the rest downward from m, so every span of two or more pixels goes at two pixels per clock.
//! (Splitting at the symmetry point E, as the thesis words it, gives two per clock only when E
//! lies inside the span — on the default scene's spans that is 0 of 17 199 for H and 222 for L,
//! `benches/rtl_span.rs` — so each run instead lets its argument pass through zero at E: cos is
//! even, the PROM is addressed by |argument|, the reload with φ − ψ of fig. 3.6 in another form.)
//!
//! The PROM holds cos x for x = a·(π/2)/2048, a = 0..2047 (a quarter turn: cos is negative from
//! π/2 on and every lighting cosine is clamped at 0), Q1.15 words; addressed by the argument
//! folded to [0, π] (its two's complement negation when it is past a half turn: cos is even and
//! 2π-periodic) and rounded to the PROM's step; arguments from π/2 − half a step on read 0.
//! Any span's argument is then exact, however far apart its end normals are.

use crate::shading::angular::AngularSpan;

/// Bits of the angle words: 2³² is a whole turn (binary angle).
pub const ANGLE_BITS: u32 = 32;
/// The PROM address is bits 29..19 of the folded argument: 2¹⁹ angle units (π/4096) a step.
pub const PROM_SHIFT: u32 = 19;
/// Words in the cos PROM.
pub const PROM_WORDS: usize = 1 << 11;

/// The words one span loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SpanWords {
    pub p: i64,
    pub d: i64,
    pub q: i64,
    pub cos_beta: u64,
    pub m: u32,
}

/// An angle in radians as a binary-angle word (2³² a turn), rounded to nearest.
fn angle(v: f64) -> i64 {
    (v / std::f64::consts::TAU * (ANGLE_BITS as f64).exp2() + 0.5).floor() as i64
}

impl SpanWords {
    /// Quantize a span's set-up (cos β clamped to [0, 1]).
    pub fn new(s: &AngularSpan) -> SpanWords {
        let p = angle(s.psi);
        let d = angle(s.delta_phi);
        SpanWords {
            p,
            d,
            q: s.m as i64 * d - p,
            cos_beta: (s.cos_beta.clamp(0.0, 1.0) * 32768.0 + 0.5).floor() as u64,
            m: s.m,
        }
    }
    /// The first index of run B: h = ⌈(m + 1)/2⌉.
    pub fn half(&self) -> u32 {
        (self.m + 2) / 2
    }
    /// Run A's indices: t = 0 … h − 1.
    pub fn run_a(&self) -> Vec<u32> {
        (0..self.half()).collect()
    }
    /// Run B's indices: u = m, m − 1, … h.
    pub fn run_b(&self) -> Vec<u32> {
        (self.half()..=self.m).rev().collect()
    }
    /// Clocks the span occupies: run A's length, h.
    pub fn clocks(&self) -> usize {
        self.half() as usize
    }
    /// The argument of pixel t as a real in [0, π]: p − t·d (run A; run B's is its negation)
    /// modulo a turn, folded to the nearer way round.
    pub fn argument(&self, t: u32) -> f64 {
        let turn = 1i64 << ANGLE_BITS;
        let a = (self.p - t as i64 * self.d).rem_euclid(turn);
        a.min(turn - a) as f64 * std::f64::consts::TAU / turn as f64
    }
}

/// The f64 value of pixel t: cos β·max(cos(arg), 0) with the words' cos β and argument.
pub fn cos_v(w: &SpanWords, t: u32) -> f64 {
    w.cos_beta as f64 / 32768.0 * w.argument(t).cos().max(0.0)
}

/// Bound on |cos_hw − cos_v|: the PROM address rounding moves the argument by ≤ half a step,
/// π/8192 (cos by ≤ π/8192), the word and the product roundings add 2⁻¹⁶ each.
pub const ERROR_BOUND: f64 = std::f64::consts::PI / 8192.0 + 2.0 / 65536.0;

/// The PROM contents.
pub fn prom() -> Vec<u64> {
    (0..PROM_WORDS)
        .map(|a| {
            let c = (a as f64 * std::f64::consts::FRAC_PI_2 / PROM_WORDS as f64).cos();
            (c * 32768.0 + 0.5).floor() as u64
        })
        .collect()
}

/// Bit-exact integer twin of `rtl/src/units/cos_v_accumulator.rs`, written from its header.
pub mod twin {
    use super::{prom, SpanWords, PROM_SHIFT, PROM_WORDS};

    const MASK: i64 = (1 << 32) - 1;

    /// The PROM address of a 32-bit argument word: its magnitude (two's complement negation
    /// when bit 31 is set, modulo 2³²: the angle folded to [0, π]) + half an address step,
    /// bits 29..19; `None` (read 0) when bits 31..30 of that sum are not both 0 (the folded
    /// angle ≥ π/2 − half a step).
    fn addr(arg: i64) -> Option<usize> {
        let mag = if arg & (1 << 31) != 0 {
            (-arg) & MASK
        } else {
            arg & MASK
        };
        let r = (mag + (1 << (PROM_SHIFT - 1))) & MASK;
        (r >> 30 == 0).then_some(((r >> PROM_SHIFT) as usize) & (PROM_WORDS - 1))
    }

    fn rnd(p: u64) -> u64 {
        ((p + (1 << 14)) >> 15).min(0xFFFF)
    }

    /// Both lanes' outputs in a clock: (valid, index, cosine word) each.
    type LaneOuts = [(bool, u32, u64); 2];

    #[derive(Clone, Debug)]
    pub struct CosVTwin {
        prom: Vec<u64>,
        // State (S0).
        busy_a: bool,
        busy_b: bool,
        arg_a: i64,
        arg_b: i64,
        t: u32,
        u: u32,
        m: u32,
        h: u32,
        d: i64,
        cb: u64,
        // S1: PROM data, the flags and indices carried.
        s1: [(bool, u32, u64, bool); 2],
        cb1: u64,
        last1: bool,
        // S2 .. S4: the outputs, formed from S1 and carried three registers (the RTL
        // registers the PROM word, then the product twice, then rounds: the same value).
        pipe: std::collections::VecDeque<(LaneOuts, bool)>,
        out: [(bool, u32, u64); 2],
        last2: bool,
    }

    impl Default for CosVTwin {
        fn default() -> Self {
            CosVTwin {
                prom: prom(),
                busy_a: false,
                busy_b: false,
                arg_a: 0,
                arg_b: 0,
                t: 0,
                u: 0,
                m: 0,
                h: 0,
                d: 0,
                cb: 0,
                s1: [(false, 0, 0, false); 2],
                cb1: 0,
                last1: false,
                pipe: std::iter::repeat_n(([(false, 0, 0); 2], false), 3).collect(),
                out: [(false, 0, 0); 2],
                last2: false,
            }
        }
    }

    impl CosVTwin {
        fn active(&self) -> (bool, bool) {
            let a = self.busy_a && self.t < self.h;
            let b = self.busy_b && self.u >= self.h;
            (a, b)
        }
        /// Whether either run emits after this clock.
        fn more(&self) -> bool {
            let (a, b) = self.active();
            (a && self.t + 1 < self.h) || (b && self.u > self.h)
        }
        /// `ready` shown this clock: nothing to emit after this clock.
        pub fn ready(&self) -> bool {
            !self.more()
        }
        /// This clock emits the span's last pixel(s).
        fn last_now(&self) -> bool {
            let (a, b) = self.active();
            (a || b) && !self.more()
        }
        /// (ready, [valid, index, cos] for A and B, last) shown this clock.
        pub fn outputs(&self) -> Vec<u64> {
            self.outputs_held(false)
        }
        /// [`Self::outputs`] with the `hold` input at `hold` (`ready` is low while held).
        pub fn outputs_held(&self, hold: bool) -> Vec<u64> {
            vec![
                (self.ready() && !hold) as u64,
                self.out[0].0 as u64,
                self.out[0].1 as u64,
                self.out[0].2,
                self.out[1].0 as u64,
                self.out[1].1 as u64,
                self.out[1].2,
                self.last2 as u64,
            ]
        }
        /// One rising edge with `load` (taken only when ready) and the span's words.
        pub fn clock(&mut self, load: Option<&SpanWords>) {
            self.clock_held(load, false);
        }
        /// One clock; `hold`: the runs stand still, emit nothing and take no span.
        pub fn clock_held(&mut self, load: Option<&SpanWords>, hold: bool) {
            // S4 ← S2, S3 ← S1
            (self.out, self.last2) = self.pipe.pop_front().expect("three stages");
            self.pipe.push_back((
                self.s1
                    .map(|(v, i, w, top)| (v, i, if top { 0 } else { rnd(self.cb1 * w) })),
                self.last1,
            ));
            // S1 ← S0
            let (act_a, act_b) = self.active();
            let (a, b) = (act_a && !hold, act_b && !hold);
            let read = |arg: i64| match addr(arg) {
                Some(x) => (self.prom[x], false),
                None => (0, true),
            };
            let (wa, ta) = read(self.arg_a);
            let (wb, tb) = read(self.arg_b);
            let last = self.last_now() && !hold;
            let ready = self.ready() && !hold;
            self.s1 = [(a, self.t & 0xFFF, wa, ta), (b, self.u, wb, tb)];
            self.cb1 = self.cb;
            self.last1 = last;
            // S0
            if a {
                self.arg_a = (self.arg_a - self.d) & MASK;
                self.t += 1;
            } else if !act_a {
                self.busy_a = false;
            }
            if b {
                self.arg_b = (self.arg_b - self.d) & MASK;
                if self.u == 0 {
                    self.busy_b = false;
                } else {
                    self.u -= 1;
                }
            } else if !act_b {
                self.busy_b = false;
            }
            if let (Some(w), true) = (load, ready) {
                self.busy_a = true;
                self.busy_b = true;
                self.arg_a = w.p & MASK;
                self.arg_b = w.q & MASK;
                self.t = 0;
                self.u = w.m;
                self.m = w.m;
                self.h = (w.m + 2) >> 1;
                self.d = w.d & MASK;
                self.cb = w.cos_beta;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::angular::{span_kernel, span_setup};
    use glam::DVec3;

    /// The words' value of every pixel (`cos_v`) is the angular method's kernel on the same span
    /// (clamped at 0) within the words' rounding, for random end normals at any angle (the
    /// argument past a half turn among them). The hardware's side of those spans is the
    /// testbench's named span "end normals 158° apart".
    #[test]
    fn words_follow_the_kernel_at_any_angle() {
        let mut worst = 0f64;
        for i in 0..2000 {
            let f = |k: u32| ((i * 7919 + k * 104_729) % 2001) as f64 / 1000.0 - 1.0;
            let n = |k: u32| DVec3::new(f(k), f(k + 1), f(k + 2) + 0.01).normalize();
            let (na, nb, x) = (n(0), n(3), n(6));
            let m = 1 + i % 40;
            let sp = span_setup(na, nb, x, m);
            let w = SpanWords::new(&sp);
            for (t, k) in span_kernel(&sp).into_iter().enumerate() {
                // cos β rounded to Q1.15 (and clamped to 1) in the words.
                let e = (cos_v(&w, t as u32) - k.max(0.0)).abs();
                worst = worst.max(e);
            }
        }
        // cos β's rounding to Q1.15 (≤ 2⁻¹⁶) dominates; the angle words (half a unit, 2π·2⁻³³
        // rad, each) move the argument by less than 10⁻⁸.
        assert!(worst < 2e-5, "{worst}");
    }
}
