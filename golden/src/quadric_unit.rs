//! The quadric forward-difference unit (SPEC §8), the golden of `rtl/src/quadric_unit.rs`:
//! along a raster line, per colour channel, I(x + 2d) = 2·I(x + d) − I(x) + 2A, two pixels per
//! clock — the pair (I_k, I_{k+1}) steps to (I_{k+2}, I_{k+3}) with
//! I_{k+2} = 2·I_{k+1} − I_k + 2A and I_{k+3} = 3·I_{k+1} − 2·I_k + 6A (shifts and adds).
//!
//! Words per line and channel (software set-up, `crate::quadric`): I0 = I(x0) by the direct
//! form (2.2), I1 = I(x0 + d) by (2.3), and 2A; signed Q34.30 in 64 bits (LSB units of the
//! 8-bit channel: a quadric fitted on a sliver triangle overshoots by orders of magnitude at
//! pixel centres just outside it, where the image saturates anyway). The recurrence on the words is exact (integers); the output rounds to an
//! integer (+2²⁹, drop 30 bits, ties up) and saturates to 0..=255. Depth runs beside it: lane A
//! from z0 by 2·dz, lane B from z0 + dz by 2·dz (signed Q16.16).

use crate::quadric::{direct, QuadricSetup};
use crate::types::Row;

/// Fraction bits of the intensity words.
pub const FRAC: u32 = 30;
/// Width of the intensity words.
pub const BITS: u32 = 64;
/// Largest |intensity| (LSB units) the set-up accepts on a line: the words hold ±2³³; the
/// recurrence is exact modulo 2⁶⁴ (its intermediates may wrap), so only the values themselves
/// must fit, with a margin for the output rounding.
pub const RANGE: f64 = 2147483648.0;

/// One channel's words for one line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct QuadricWords {
    /// I(x0), I(x0 + d), 2A as signed Q34.30.
    pub i0: i64,
    pub i1: i64,
    pub a2: i64,
}

fn word(v: f64) -> i64 {
    (v * (FRAC as f64).exp2() + 0.5).floor() as i64
}

/// The words of channel `channel` on `row` (its first two pixels by (2.2) and (2.3), as
/// `crate::quadric::row_kernel`), or an error when the line's intensities leave ±[`RANGE`].
pub fn line_words(s: &QuadricSetup, channel: usize, row: &Row) -> Result<QuadricWords, String> {
    let k = &s.coeffs[channel];
    let (a, c, d) = (k[0], k[2], k[3]);
    let x0 = row.x_start as f64 + 0.5 - s.origin.0;
    let y = row.y as f64 + 0.5 - s.origin.1;
    let dir = row.dir as f64;
    let i0 = direct(k, x0, y);
    let i1 = i0 + dir * (2.0 * a * x0 + c * y + d) + a;
    // The line's extreme values: both ends and the parabola's vertex.
    let m = row.len.saturating_sub(1) as f64;
    let at = |t: f64| direct(k, x0 + dir * t, y);
    let mut worst = i0.abs().max(i1.abs()).max(at(m).abs());
    if a != 0.0 {
        let t = -(2.0 * a * x0 + c * y + d) * dir / (2.0 * a);
        if (0.0..=m).contains(&t) {
            worst = worst.max(at(t).abs());
        }
    }
    if !worst.is_finite() || worst >= RANGE || !(2.0 * a).is_finite() || (2.0 * a).abs() >= RANGE {
        return Err(format!(
            "quadric intensity {worst:.0} on line y = {} is beyond the unit's ±{RANGE} range",
            row.y
        ));
    }
    Ok(QuadricWords {
        i0: word(i0),
        i1: word(i1),
        a2: word(2.0 * a),
    })
}

impl QuadricWords {
    /// The f64 values the words stand for at pixels 0..=m (the exact recurrence on them).
    pub fn values(&self, m: u32) -> Vec<f64> {
        let f = (-(FRAC as f64)).exp2();
        let mut out = Vec::with_capacity(m as usize + 1);
        let (mut p, mut q) = (self.i0 as i128, self.i1 as i128);
        for _ in 0..=m {
            out.push(p as f64 * f);
            let r = 2 * q - p + self.a2 as i128;
            p = q;
            q = r;
        }
        out
    }
}

/// Bit-exact twin of `rtl::quadric_unit::QuadricUnit`.
pub mod twin {
    use super::{QuadricWords, BITS, FRAC};

    const MASK: i128 = (1 << BITS) - 1;

    fn wrap(v: i128) -> i128 {
        let v = v & MASK;
        if v >> (BITS - 1) != 0 {
            v - (1 << BITS)
        } else {
            v
        }
    }

    /// A Q34.30 word → 8 bits: +2²⁹, drop 30, saturate to 0..=255.
    pub fn out8(v: i128) -> u64 {
        ((wrap(v + (1 << (FRAC - 1)))) >> FRAC).clamp(0, 255) as u64
    }

    /// The line a load carries.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct QuadricLine {
        pub y: u64,
        pub x0: u64,
        pub leftward: bool,
        pub m: u32,
        pub ch: [QuadricWords; 3],
        pub z0: u64,
        pub dz: u64,
    }

    #[derive(Clone, Debug, Default)]
    pub struct QuadricTwin {
        busy: bool,
        t: u32,
        line: QuadricLine,
        p: [i128; 3],
        q: [i128; 3],
        a2: [i128; 3],
        za: u64,
        zb: u64,
        out: Vec<u64>,
    }

    impl QuadricTwin {
        pub fn new() -> Self {
            QuadricTwin {
                out: vec![0; 14],
                ..Default::default()
            }
        }
        fn last(&self) -> bool {
            self.t + 2 > self.line.m
        }
        pub fn ready(&self) -> bool {
            !self.busy || self.last()
        }
        /// ready, lane A (valid x z r g b), lane B (valid x z r g b), y, last.
        pub fn outputs(&self) -> Vec<u64> {
            let mut o = vec![self.ready() as u64];
            o.extend(&self.out);
            o
        }
        pub fn clock(&mut self, load: Option<&QuadricLine>) {
            let l = &self.line;
            let x = |t: u32| {
                if l.leftward {
                    l.x0.wrapping_sub(t as u64) & 0xfff
                } else {
                    (l.x0 + t as u64) & 0xfff
                }
            };
            let vb = self.busy && self.t < l.m;
            let mut o = vec![self.busy as u64, x(self.t), self.za];
            o.extend(self.p.map(out8));
            o.extend([vb as u64, x(self.t + 1), self.zb]);
            o.extend(self.q.map(out8));
            o.extend([l.y, (self.busy && self.last()) as u64]);
            self.out = o;
            let ready = self.ready();
            if self.busy {
                if self.last() {
                    self.busy = false;
                } else {
                    for c in 0..3 {
                        let (p, q, a2) = (self.p[c], self.q[c], self.a2[c]);
                        self.p[c] = wrap(2 * q - p + a2);
                        self.q[c] = wrap(3 * q - 2 * p + 3 * a2);
                    }
                    self.t += 2;
                    let dz2 = self.line.dz.wrapping_mul(2);
                    self.za = self.za.wrapping_add(dz2) & 0xffff_ffff;
                    self.zb = self.zb.wrapping_add(dz2) & 0xffff_ffff;
                }
            }
            if let Some(l) = load.filter(|_| ready) {
                self.busy = true;
                self.t = 0;
                self.line = *l;
                self.p = l.ch.map(|w| w.i0 as i128);
                self.q = l.ch.map(|w| w.i1 as i128);
                self.a2 = l.ch.map(|w| w.a2 as i128);
                self.za = l.z0;
                self.zb = l.z0.wrapping_add(l.dz) & 0xffff_ffff;
            }
        }
    }
}
