//! The quadric forward-difference unit (SPEC §8), the golden of `rtl/src/units/quadric_unit.rs`:
//! quadric shading by forward differences only — the line starts by a 2-D difference tracker
//! that moves to the next line with the y terms, each line two pixels per clock.
//!
//! Per triangle and channel (software set-up, `crate::shading::quadric`): at the first line's first pixel
//! (u, v) (relative to the first vertex, pixel centres) I0 = I(u, v) by the direct form (2.2),
//! Dx = I(u + 1, v) − I(u, v) = 2A·u + A + C·v + D (2.3), Dy = I(u, v + 1) − I(u, v) =
//! 2B·v + B + C·u + E, and the second differences 2A, 2B, C. The tracker holds (I, Dx, Dy) at
//! the current line start and moves by adds only:
//! y-step: I += Dy, Dy += 2B, Dx += C; x-step (±1): I ± …, Dx ± 2A, Dy ± C (and a double
//! x-step of ±2 per clock). Along a line (direction d) the generator holds (I_k, I_{k+1}) and
//! steps to (I_{k+2}, I_{k+3}) = (2·I_{k+1} − I_k + 2A, 3·I_{k+1} − 2·I_k + 6A): two pixels per
//! clock. All words signed Q34.30 in 64 bits, LSB units of the 8-bit channel; every update is
//! an exact integer add modulo 2⁶⁴, so the values equal the exact quadric of the words wherever
//! they fit (the front end checks each line's range). Output: +2²⁹, drop 30, saturate 0..=255.
//! Depth per line (z0, dz, software) runs beside it: lane A from z0 by 2·dz, lane B from
//! z0 + dz.

use crate::shading::quadric::{direct, QuadricSetup};
use crate::types::Row;

/// Fraction bits of the intensity words.
pub const FRAC: u32 = 30;
/// Width of the intensity words.
pub const BITS: u32 = 64;
/// Largest |intensity| (LSB units) the set-up accepts on a line: the words hold ±2³³; the
/// recurrence is exact modulo 2⁶⁴ (its intermediates may wrap), so only the values themselves
/// must fit, with a margin for the output rounding.
pub const RANGE: f64 = 2147483648.0;

/// One channel's words for one triangle: I, Dx, Dy at its first line's first pixel, and the
/// second differences 2A, 2B, C (signed Q34.30).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct QuadricWords {
    pub i0: i64,
    pub dx: i64,
    pub dy: i64,
    pub a2: i64,
    pub b2: i64,
    pub c: i64,
}

fn word(v: f64) -> i64 {
    (v * (FRAC as f64).exp2() + 0.5).floor() as i64
}

/// The words of channel `channel` with the tracker starting at `row`'s first pixel.
pub fn triangle_words(s: &QuadricSetup, channel: usize, row: &Row) -> QuadricWords {
    let [a, b, c, d, e, _] = s.coeffs[channel];
    let u = row.x_start as f64 + 0.5 - s.origin.0;
    let v = row.y as f64 + 0.5 - s.origin.1;
    QuadricWords {
        i0: word(direct(&s.coeffs[channel], u, v)),
        dx: word(2.0 * a * u + a + c * v + d),
        dy: word(2.0 * b * v + b + c * u + e),
        a2: word(2.0 * a),
        b2: word(2.0 * b),
        c: word(c),
    }
}

/// Check that channel `channel`'s intensities on `row` (both ends and the parabola's vertex)
/// and its coefficients stay within ±[`RANGE`]; a one-line error otherwise.
pub fn check_line(s: &QuadricSetup, channel: usize, row: &Row) -> Result<(), String> {
    let k = &s.coeffs[channel];
    let (a, c, d) = (k[0], k[2], k[3]);
    let x0 = row.x_start as f64 + 0.5 - s.origin.0;
    let y = row.y as f64 + 0.5 - s.origin.1;
    let dir = row.dir as f64;
    let m = row.len.saturating_sub(1) as f64;
    let at = |t: f64| direct(k, x0 + dir * t, y);
    let mut worst = at(0.0).abs().max(at(m).abs());
    if a != 0.0 {
        let t = -(2.0 * a * x0 + c * y + d) * dir / (2.0 * a);
        if (0.0..=m).contains(&t) {
            worst = worst.max(at(t).abs());
        }
    }
    let coeff_max = k.iter().fold(0.0f64, |w, v| w.max(v.abs()));
    if !worst.is_finite() || worst >= RANGE || !coeff_max.is_finite() || coeff_max >= RANGE {
        return Err(format!(
            "quadric intensity {worst:.0} on line y = {} is beyond the unit's ±{RANGE} range",
            row.y
        ));
    }
    Ok(())
}

/// Bit-exact twin of `rtl::units::quadric_unit::QuadricUnit`.
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

    /// The line a load carries (`first`: the triangle's first line, with its words).
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct QuadricLine {
        pub y: u64,
        pub x0: u64,
        pub leftward: bool,
        pub m: u32,
        pub first: bool,
        pub ch: [QuadricWords; 3],
        pub z0: u64,
        pub dz: u64,
    }

    /// The 2-D tracker's state per channel: I, Dx, Dy and the second differences.
    #[derive(Clone, Copy, Debug, Default)]
    struct Track {
        i: i128,
        dx: i128,
        dy: i128,
        a2: i128,
        b2: i128,
        c: i128,
    }

    impl Track {
        fn y_step(&mut self) {
            self.i = wrap(self.i + self.dy);
            self.dy = wrap(self.dy + self.b2);
            self.dx = wrap(self.dx + self.c);
        }
        /// An x-step of `s` ∈ {−2, −1, 1, 2} pixels.
        fn x_step(&mut self, s: i64) {
            let (i, dx, a2) = (self.i, self.dx, self.a2);
            self.i = wrap(match s {
                2 => i + 2 * dx + a2,
                1 => i + dx,
                -1 => i - dx + a2,
                _ => i - 2 * dx + 3 * a2,
            });
            self.dx = wrap(dx + s as i128 * a2);
            self.dy = wrap(self.dy + s as i128 * self.c);
        }
    }

    #[derive(Clone, Debug, Default)]
    pub struct QuadricTwin {
        // tracker
        tbusy: bool,
        tx: u64,
        ty: u64,
        line: QuadricLine,
        tr: [Track; 3],
        // generator
        gbusy: bool,
        t: u32,
        gline: QuadricLine,
        p: [i128; 3],
        q: [i128; 3],
        ga2: [i128; 3],
        za: u64,
        zb: u64,
        out: Vec<u64>,
        /// `out` a clock later: the colours are rounded from the words' high halves, which run a
        /// clock behind, so every output is registered twice.
        out_d: Vec<u64>,
    }

    impl QuadricTwin {
        pub fn new() -> Self {
            QuadricTwin {
                out: vec![0; 14],
                out_d: vec![0; 14],
                ..Default::default()
            }
        }
        fn glast(&self) -> bool {
            self.t + 2 > self.gline.m
        }
        fn handover(&self) -> bool {
            let positioned = self.tbusy && self.ty == self.line.y && self.tx == self.line.x0;
            positioned && (!self.gbusy || self.glast())
        }
        pub fn ready(&self) -> bool {
            self.ready_held(false)
        }
        /// `ready` with the `hold` input at `hold` (a held hand-over takes no line).
        pub fn ready_held(&self, hold: bool) -> bool {
            !self.tbusy || (self.handover() && !hold)
        }
        /// ready, lane A (valid x z r g b), lane B (valid x z r g b), y, last.
        pub fn outputs(&self) -> Vec<u64> {
            self.outputs_held(false)
        }
        /// [`Self::outputs`] with the `hold` input at `hold`.
        pub fn outputs_held(&self, hold: bool) -> Vec<u64> {
            let mut o = vec![self.ready_held(hold) as u64];
            o.extend(&self.out_d);
            o
        }
        /// One clock without `hold`.
        pub fn clock(&mut self, load: Option<&QuadricLine>) {
            self.clock_held(load, false);
        }
        /// One clock; `hold`: the generator stands still (no step, no hand-over) and the next
        /// outputs two clocks later carry no pixel.
        pub fn clock_held(&mut self, load: Option<&QuadricLine>, hold: bool) {
            let l = &self.gline;
            let x = |t: u32| {
                if l.leftward {
                    l.x0.wrapping_sub(t as u64) & 0xfff
                } else {
                    (l.x0 + t as u64) & 0xfff
                }
            };
            let shown = self.gbusy && !hold;
            let vb = shown && self.t < l.m;
            let mut o = vec![shown as u64, x(self.t), self.za];
            o.extend(self.p.map(out8));
            o.extend([vb as u64, x(self.t + 1), self.zb]);
            o.extend(self.q.map(out8));
            o.extend([l.y, (shown && self.glast()) as u64]);
            self.out_d = std::mem::replace(&mut self.out, o);
            let handover = self.handover() && !hold;
            let ready = !self.tbusy || handover;
            // Generator.
            if shown {
                if self.glast() {
                    self.gbusy = false;
                } else {
                    for c in 0..3 {
                        let (p, q, a2) = (self.p[c], self.q[c], self.ga2[c]);
                        self.p[c] = wrap(2 * q - p + a2);
                        self.q[c] = wrap(3 * q - 2 * p + 3 * a2);
                    }
                    self.t += 2;
                    let dz2 = self.gline.dz.wrapping_mul(2);
                    self.za = self.za.wrapping_add(dz2) & 0xffff_ffff;
                    self.zb = self.zb.wrapping_add(dz2) & 0xffff_ffff;
                }
            }
            if handover {
                let l = self.line;
                self.gbusy = true;
                self.t = 0;
                self.gline = l;
                for c in 0..3 {
                    let tr = &self.tr[c];
                    self.p[c] = tr.i;
                    self.q[c] = if l.leftward {
                        wrap(tr.i - tr.dx + tr.a2)
                    } else {
                        wrap(tr.i + tr.dx)
                    };
                    self.ga2[c] = tr.a2;
                }
                self.za = l.z0;
                self.zb = l.z0.wrapping_add(l.dz) & 0xffff_ffff;
                self.tbusy = false;
            } else if self.tbusy && !self.handover() {
                // Move one step toward the line start: down first, then across (nothing to do
                // when positioned: a held hand-over waits).
                if self.ty != self.line.y {
                    self.tr.iter_mut().for_each(Track::y_step);
                    self.ty = (self.ty + 1) & 0xfff;
                } else if self.tx != self.line.x0 {
                    let d = self.line.x0 as i64 - self.tx as i64;
                    let s = d.clamp(-2, 2);
                    self.tr.iter_mut().for_each(|t| t.x_step(s));
                    self.tx = (self.tx as i64 + s) as u64 & 0xfff;
                }
            }
            if let Some(l) = load.filter(|_| ready) {
                self.tbusy = true;
                self.line = *l;
                if l.first {
                    for c in 0..3 {
                        let w = &l.ch[c];
                        self.tr[c] = Track {
                            i: w.i0 as i128,
                            dx: w.dx as i128,
                            dy: w.dy as i128,
                            a2: w.a2 as i128,
                            b2: w.b2 as i128,
                            c: w.c as i128,
                        };
                    }
                    self.tx = l.x0;
                    self.ty = l.y;
                } else if self.ty != l.y {
                    self.tr.iter_mut().for_each(Track::y_step);
                    self.ty = (self.ty + 1) & 0xfff;
                }
            }
        }
    }
}
