//! The fast two-point unit (SPEC §3), the golden of `rtl/src/units/fast_unit.rs`: along a span,
//! p_x/√q_x two pixels per step — the left pixel x with p = b + g·x, the mirror pixel m − x
//! with p = h − g·x, both sharing 1/√(M_x + 1) from a quadratic in M by Horner, M by the
//! second-order recurrence M += Δ, Δ += 2c (Δ₀ = c + s).
//!
//! Per-span words (software set-up, `crate::shading::fast::span_setup`, quantized here): b, h, g signed
//! Q2.30 (32 bits); Δ₀ = c + s and 2c signed Q2.46 (48 bits: the quadratic recurrence runs up to
//! 2048 steps, so its increments need 2⁻⁴⁷ resolution to stay within 10⁻⁷); m (12 bits).

use crate::shading::fast::FastSpan;
use crate::units::normalizer::{scale, Coeffs};

/// Fraction bits of b, h, g.
pub const P_FRAC: u32 = 30;
/// Fraction bits of M, Δ, 2c.
pub const M_FRAC: u32 = 46;

/// The words one span loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FastWords {
    pub b: i64,
    pub h: i64,
    pub g: i64,
    pub d0: i64,
    pub dd: i64,
    pub m: u32,
}

fn q(v: f64, frac: u32) -> i64 {
    (v * (frac as f64).exp2() + 0.5).floor() as i64
}

impl FastWords {
    pub fn new(s: &FastSpan) -> FastWords {
        FastWords {
            b: q(s.b, P_FRAC),
            h: q(s.h, P_FRAC),
            g: q(s.g, P_FRAC),
            d0: q(s.c + s.s, M_FRAC),
            dd: q(2.0 * s.c, M_FRAC),
            m: s.m,
        }
    }
    /// Clocks the span occupies: ⌊m/2⌋ + 1 steps.
    pub fn clocks(&self) -> usize {
        self.m as usize / 2 + 1
    }
    /// The f64 values at x = 0..=m from the words' real values (exact recurrences). The middle
    /// pixel of an even span is the left run's (b + g·x; the hardware shows it once).
    pub fn values(&self, c: Coeffs) -> Vec<f64> {
        let pf = (-(P_FRAC as f64)).exp2();
        let mf = (-(M_FRAC as f64)).exp2();
        let m = self.m as usize;
        let mut out = vec![0.0; m + 1];
        let mut big_m = 0i128;
        let mut delta = self.d0 as i128;
        for x in 0..=m / 2 {
            let r = scale(big_m as f64 * mf, c);
            out[m - x] = ((self.h - self.g * x as i64) as f64 * pf * r).max(0.0);
            out[x] = ((self.b + self.g * x as i64) as f64 * pf * r).max(0.0);
            big_m += delta;
            delta += self.dd as i128;
        }
        out
    }
}

/// Bound on |cos_hw − value| on the domain (M ∈ [−0.5, 0], |p| ≤ 1): M rounded to Q1.15 moves
/// f by ≤ max|f'|·2⁻¹⁶; c2 quantized (≤ 2⁻¹⁶·M²), t1 rounded (≤ 2⁻¹⁵·|M|), f rounded (2⁻¹⁶);
/// p rounded to Q2.14 (2⁻¹⁵·f); the output rounding 2⁻¹⁶; the recurrences' increments
/// quantized: p by ≤ x·2⁻³¹, M by ≤ x²·2⁻⁴⁷ (x ≤ 2048).
pub fn error_bound(c: Coeffs) -> f64 {
    let e = (-16f64).exp2();
    let fmax = scale(-0.5, c).max(scale(0.0, c));
    let dfmax = (c[1]).abs().max((c[1] - c[0]).abs()); // |2c2·M + c1| on [−0.5, 0]
    dfmax * e
        + 0.25 * e
        + 0.5 * 2.0 * e
        + e
        + 2.0 * e * fmax
        + e
        + 2048.0 * (-31f64).exp2() * fmax
        + 2048.0 * 2048.0 * (-47f64).exp2() * dfmax
}

/// Bit-exact integer twin of `rtl/src/units/fast_unit.rs`, written from its header.
pub mod twin {
    use super::FastWords;
    use crate::units::normalizer::Coeffs;
    use std::collections::VecDeque;

    const M32: i64 = (1 << 32) - 1;
    const M48: i64 = (1 << 48) - 1;

    fn sx(v: i64, bits: u32) -> i64 {
        let s = 64 - bits;
        (v << s) >> s
    }
    fn clamp16s(v: i64) -> i64 {
        v.clamp(-(1 << 15), (1 << 15) - 1)
    }

    /// The coefficient words: (|c2| in UQ1.15, c1 in Q2.30, c0 in Q3.29).
    pub fn coefficient_words(c: Coeffs) -> (i64, i64, i64) {
        let q = |v: f64, f: u32| (v * (f as f64).exp2() + 0.5).floor() as i64;
        (q(c[0].abs(), 15), q(c[1], 30), q(c[2], 29))
    }

    /// One pixel pair in flight.
    #[derive(Clone, Copy, Debug, Default)]
    struct Lane {
        vl: bool,
        vr: bool,
        xl: u64,
        xr: u64,
        last: bool,
        pl: i64,
        pr: i64,
        mm: i64,
        w: i64,
    }

    #[derive(Clone, Debug)]
    pub struct FastTwin {
        c2: i64,
        c1: i64,
        c0: i64,
        busy: bool,
        x: u64,
        m: u64,
        pl: i64,
        pr: i64,
        g: i64,
        big_m: i64,
        delta: i64,
        dd: i64,
        /// S1, S2 (3), S3, S4 (3), S5, S6 (3), S7 (index 0 = S1): every product takes three
        /// clocks (the RTL registers the operands, then the product and its sign correction).
        pipe: VecDeque<Lane>,
    }

    impl FastTwin {
        pub fn new(c: Coeffs) -> Self {
            let (c2, c1, c0) = coefficient_words(c);
            FastTwin {
                c2,
                c1,
                c0,
                busy: false,
                x: 0,
                m: 0,
                pl: 0,
                pr: 0,
                g: 0,
                big_m: 0,
                delta: 0,
                dd: 0,
                pipe: std::iter::repeat_n(Lane::default(), 13).collect(),
            }
        }
        fn active(&self) -> bool {
            self.busy && 2 * self.x <= self.m
        }
        fn more(&self) -> bool {
            self.active() && 2 * (self.x + 1) <= self.m
        }
        /// (ready, valid_a, x_a, cos_a, valid_b, x_b, cos_b, done) shown this clock.
        pub fn outputs(&self) -> Vec<u64> {
            self.outputs_held(false)
        }
        /// [`Self::outputs`] with the `hold` input at `hold` (`ready` is low while held).
        pub fn outputs_held(&self, hold: bool) -> Vec<u64> {
            let o = self.pipe[self.pipe.len() - 1];
            vec![
                (!self.more() && !hold) as u64,
                o.vl as u64,
                o.xl,
                o.pl as u64,
                o.vr as u64,
                o.xr,
                o.pr as u64,
                o.last as u64,
            ]
        }
        pub fn clock(&mut self, load: Option<&FastWords>) {
            self.clock_held(load, false);
        }
        /// One clock; `hold`: the step stands still, emits nothing and takes no span.
        pub fn clock_held(&mut self, load: Option<&FastWords>, hold: bool) {
            let s: Vec<Lane> = self.pipe.iter().copied().collect();
            const L: usize = 3; // clocks per product (the RTL's SIGNED_MUL_LATENCY)
            let mut n = [Lane::default(); 4 + 3 * L];
            // Stage indices: S1 0, S2 1..=L, S3 L+1, S4 L+2..=2L+1, S5 2L+2, S6 2L+3..=3L+2,
            // S7 3L+3.
            let (s2, s3, s4, s5, s6, s7) = (1, L + 1, L + 2, 2 * L + 2, 2 * L + 3, 3 * L + 3);
            // S7: cos = clamp(round(v: Q3.29 → UQ1.15)), v = p·r.
            let out = |v: i64| ((v + (1 << 13)) >> 14).clamp(0, 0xFFFF);
            n[s7] = Lane {
                pl: out(s[s7 - 1].pl),
                pr: out(s[s7 - 1].pr),
                ..s[s7 - 1]
            };
            // S6: p·r (signed Q2.14 × UQ1.15 → Q3.29), L clocks.
            n[s6] = Lane {
                pl: s[s6 - 1].pl * s[s6 - 1].w,
                pr: s[s6 - 1].pr * s[s6 - 1].w,
                ..s[s6 - 1]
            };
            n[s6 + 1..s7].copy_from_slice(&s[s6..s7 - 1]);
            // S5: r = round(c0 + t1·M: Q3.29 → UQ1.15), clamped.
            let r = ((self.c0 + s[s5 - 1].w + (1 << 13)) >> 14).clamp(0, 0xFFFF);
            n[s5] = Lane { w: r, ..s[s5 - 1] };
            // S4: t1·M (signed Q2.14 × signed Q1.15 → Q3.29), L clocks.
            n[s4] = Lane {
                w: s[s4 - 1].w * s[s4 - 1].mm,
                ..s[s4 - 1]
            };
            n[s4 + 1..s5].copy_from_slice(&s[s4..s5 - 1]);
            // S3: t1 = round(c1 + |c2|·M: Q2.30 → Q2.14), saturated.
            let t1 = clamp16s((self.c1 + s[s3 - 1].w + (1 << 15)) >> 16);
            n[s3] = Lane { w: t1, ..s[s3 - 1] };
            // S2: |c2|·M (UQ1.15 × signed Q1.15 → Q2.30), L clocks.
            n[s2] = Lane {
                w: self.c2 * s[0].mm,
                ..s[0]
            };
            n[s2 + 1..s3].copy_from_slice(&s[s2..s3 - 1]);
            // S1: from the state — M rounded to Q1.15 (saturated), p rounded to Q2.14.
            let act = self.active();
            let a = act && !hold;
            let more = self.more();
            let m16 = clamp16s((sx(self.big_m, 48) + (1 << 30)) >> 31);
            let p16 = |p: i64| clamp16s((sx(p, 32) + (1 << 15)) >> 16);
            n[0] = Lane {
                vl: a,
                vr: a && 2 * self.x != self.m,
                xl: self.x & 0xFFF,
                xr: self.m.wrapping_sub(self.x) & 0xFFF,
                last: a && !more,
                pl: p16(self.pl),
                pr: p16(self.pr),
                mm: m16,
                w: 0,
            };
            self.pipe = n.into_iter().collect();
            // State.
            if a {
                self.pl = (self.pl + self.g) & M32;
                self.pr = (self.pr - self.g) & M32;
                self.big_m = (self.big_m + self.delta) & M48;
                self.delta = (self.delta + self.dd) & M48;
                self.x += 1;
            } else if !act {
                self.busy = false;
            }
            if let (Some(w), false) = (load, more || hold) {
                self.busy = true;
                self.x = 0;
                self.m = w.m as u64;
                self.pl = w.b & M32;
                self.pr = w.h & M32;
                self.g = w.g & M32;
                self.big_m = 0;
                self.delta = w.d0 & M48;
                self.dd = w.dd & M48;
            }
        }
    }
}
