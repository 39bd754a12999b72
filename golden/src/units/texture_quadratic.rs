//! Quadratic texture coordinate along a raster line (SPEC §15), golden face: the per-line
//! quadratic u = A1·x² + A2·x + A3 through three exact values (the span's ends and an inner
//! pixel), in raw screen x; the forward differences the hardware steps with two additions per
//! pixel; and the bit-exact integer twin of the RTL block `texture-quadratic`
//! (`rtl::units::texture_quadratic`).
//!
//! # Formula (SPEC §15)
//!
//! ```text
//!   ρ  = 1/[x0²(x1 − x2) + x1²(x2 − x0) + x2²(x0 − x1)]
//!   A1 = ρ[u0(x1 − x2) + u1(x2 − x0) + u2(x0 − x1)]
//!   A2 = ρ[x0²(u1 − u2) + x1²(u2 − u0) + x2²(u0 − u1)]
//!   A3 = ρ[x0²(x1u2 − x2u1) + x1²(x2u0 − x0u2) + x2²(x0u1 − x1u0)]
//! ```
//!
//! Along the line from pixel x_s in steps of `dir` (±1): u(x_s), Δ = u(x_s + dir) − u(x_s),
//! ΔΔ = 2·A1 (dir² = 1); per pixel u += Δ, Δ += ΔΔ.
//!
//! # Words
//!
//! u, Δ, ΔΔ: signed Q15.32 in 48 bits ([`FRAC_BITS`] = 32), each rounded to the nearest 2^−32
//! by the set-up; u carries +½ so that the texel ⌊u + ½⌋ is the word's integer part (bits
//! 47..32). Additions wrap modulo 2^48; a value must lie in [−2^15, 2^15) texels.
//!
//! # Error budget
//!
//! At the n-th pixel after the load (n = 0 at the load) the word differs from the f64
//! recurrence by at most 2^−33·(1 + n + n(n − 1)/2) ([`error_bound`]): under 2^−9 texel for
//! n < 4096. The texel is ⌊u + ½⌋ of the word, so it can differ from the f64 quadratic's
//! rounding only where that lies within the bound of a half texel.

/// Fraction bits of u, Δ and ΔΔ.
pub const FRAC_BITS: u32 = 32;
const BITS: u32 = 48;
const MASK: u64 = (1 << BITS) - 1;

/// The quadratic's coefficients [A1, A2, A3] through (x_k, u_k), k = 0, 1, 2 (SPEC §15).
pub fn lagrange_coeffs(x: [f64; 3], u: [f64; 3]) -> [f64; 3] {
    let [x0, x1, x2] = x;
    let [u0, u1, u2] = u;
    let (s0, s1, s2) = (x0 * x0, x1 * x1, x2 * x2);
    let rho = 1.0 / (s0 * (x1 - x2) + s1 * (x2 - x0) + s2 * (x0 - x1));
    [
        rho * (u0 * (x1 - x2) + u1 * (x2 - x0) + u2 * (x0 - x1)),
        rho * (s0 * (u1 - u2) + s1 * (u2 - u0) + s2 * (u0 - u1)),
        rho * (s0 * (x1 * u2 - x2 * u1) + s1 * (x2 * u0 - x0 * u2) + s2 * (x0 * u1 - x1 * u0)),
    ]
}

/// The quadratic at x.
pub fn eval(a: &[f64; 3], x: f64) -> f64 {
    (a[0] * x + a[1]) * x + a[2]
}

/// The forward differences from pixel `xs` in steps of `dir` (±1): (u, Δ, ΔΔ), with
/// Δ = A1·(2·xs·dir + 1) + A2·dir formed directly (not as a difference of two values of u,
/// which would cancel).
pub fn differences(a: &[f64; 3], xs: f64, dir: f64) -> (f64, f64, f64) {
    (
        eval(a, xs),
        a[0] * (2.0 * xs * dir + 1.0) + a[1] * dir,
        2.0 * a[0],
    )
}

/// `v` as a signed Q15.32 word, rounded to nearest.
pub fn word(v: f64) -> u64 {
    ((v * (1u64 << FRAC_BITS) as f64).round() as i64 as u64) & MASK
}

/// One coordinate's set-up words: u (with the +½), Δ, ΔΔ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadWords {
    pub u: u64,
    pub d: u64,
    pub dd: u64,
}

impl QuadWords {
    /// The words of the differences (u, Δ, ΔΔ).
    pub fn of((u, d, dd): (f64, f64, f64)) -> QuadWords {
        QuadWords {
            u: word(u + 0.5),
            d: word(d),
            dd: word(dd),
        }
    }
}

/// Largest deviation of the n-th pixel's word from the f64 recurrence (the module doc).
pub fn error_bound(n: u64) -> f64 {
    let n = n as f64;
    (1.0 + n + n * (n - 1.0) / 2.0) / (1u64 << (FRAC_BITS + 1)) as f64
}

/// A bound on the f64 arithmetic's own error in the n-th pixel's value from `xs` (the
/// reference [`eval`] at x and the set-up's u and Δ, each a few roundings of terms as large as
/// |A1|x² + |A2||x| + |A3|; Δ's error repeats n times): what a comparison with the f64
/// quadratic must allow beside [`error_bound`].
pub fn f64_slack(a: &[f64; 3], xs: f64, x: f64, n: u64) -> f64 {
    let m = |x: f64| a[0].abs() * x * x + a[1].abs() * x.abs() + a[2].abs();
    let d = a[0].abs() * (2.0 * xs.abs() + 1.0) + a[1].abs();
    4.0 * f64::EPSILON * (m(x) + m(xs) + n as f64 * d)
}

/// The texel of a word: its integer part (two's complement, 16 bits).
pub fn texel(w: u64) -> u64 {
    (w >> FRAC_BITS) & 0xFFFF
}

/// The texel of a word as a signed integer (its integer part, 16-bit two's complement).
pub fn signed_texel(w: u64) -> i64 {
    texel(w) as u16 as i16 as i64
}

/// One axis of the twin: the running u and Δ, and ΔΔ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadAxis {
    u: u64,
    d: u64,
    dd: u64,
}

impl QuadAxis {
    /// The running u word.
    pub fn word(&self) -> u64 {
        self.u
    }

    /// One clock: on `valid` with `load`, take the words; on `valid` alone, step.
    pub fn clock(&mut self, valid: bool, load: Option<&QuadWords>) {
        if !valid {
            return;
        }
        match load {
            Some(w) => {
                *self = QuadAxis {
                    u: w.u,
                    d: w.d,
                    dd: w.dd,
                }
            }
            None => {
                self.u = (self.u + self.d) & MASK;
                self.d = (self.d + self.dd) & MASK;
            }
        }
    }
}

/// The bit-exact twin of `texture-quadratic`: u and v, and the output register one clock
/// behind (`valid_out`, the two texels, the two words).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadTwin {
    pub axes: [QuadAxis; 2],
    valid: bool,
    out: [u64; 2],
}

impl QuadTwin {
    /// (valid_out, [u texel, v texel], [u word, v word]) shown this clock.
    pub fn outputs(&self) -> (bool, [u64; 2], [u64; 2]) {
        (self.valid, self.out.map(texel), self.out)
    }

    /// One rising edge: `valid` a pixel, `load` its line's words (the line's first pixel).
    pub fn clock(&mut self, valid: bool, load: Option<&[QuadWords; 2]>) {
        for (k, a) in self.axes.iter_mut().enumerate() {
            a.clock(valid, load.map(|w| &w[k]));
        }
        self.valid = valid;
        if valid {
            self.out = self.axes.map(|a| a.u);
        }
    }
}

/// Line records the textured pipeline's quadratic walk holds (`rtl`'s `QuadWalk`).
pub const LINE_FIFO: usize = 4;

/// The bit-exact twin of the textured pipeline's quadratic walk (`rtl`'s `QuadWalk`,
/// written from its header): a [`LINE_FIFO`]-entry FIFO of line records, the unit
/// ([`QuadTwin`]) loaded by each line's first pixel and stepped by the others, and one output
/// register after it.
#[derive(Clone, Debug, Default)]
pub struct QuadWalkTwin {
    lines: std::collections::VecDeque<[QuadWords; 2]>,
    /// The next pixel is its line's first.
    need: bool,
    quad: QuadTwin,
    /// The output register: valid_out, the u and v texels (16-bit two's complement).
    out: (bool, [u64; 2]),
}

impl QuadWalkTwin {
    /// `line_ready`: the FIFO takes a record this clock.
    pub fn line_ready(&self) -> bool {
        self.lines.len() < LINE_FIFO
    }

    /// Line records waiting.
    pub fn lines(&self) -> usize {
        self.lines.len()
    }

    /// `ready` with the event (`valid`, `row_start`) shown: low only for a line's first pixel
    /// while no record waits.
    pub fn ready(&self, valid: bool, row_start: bool) -> bool {
        !(valid && (self.need || row_start)) || !self.lines.is_empty()
    }

    /// (valid_out, [u, v]) shown this clock.
    pub fn outputs(&self) -> (bool, [u64; 2]) {
        self.out
    }

    /// One rising edge with the event (`valid`, `row_start`) shown and a record pushed or not.
    pub fn clock(&mut self, valid: bool, row_start: bool, push: Option<&[QuadWords; 2]>) {
        let ready = self.ready(valid, row_start);
        let pix = valid && ready;
        let pull = valid && (self.need || row_start) && ready;
        self.out = (self.quad.outputs().0, self.quad.outputs().1);
        let load = if pull { self.lines.pop_front() } else { None };
        self.quad.clock(pix, load.as_ref());
        if row_start && ready {
            self.need = true;
        }
        if pix {
            self.need = false;
        }
        if let Some(w) = push {
            if self.lines.len() < LINE_FIFO {
                self.lines.push_back(*w);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lagrange_goes_through_its_points() {
        let (x, u) = ([13.0, 57.0, 140.0], [3.0, 7.0, 30.0]);
        let a = lagrange_coeffs(x, u);
        for k in 0..3 {
            assert!((eval(&a, x[k]) - u[k]).abs() < 1e-9);
        }
    }

    #[test]
    fn differences_step_the_quadratic() {
        let a = [0.001, -0.3, 17.0];
        let (mut u, mut d, dd) = differences(&a, 40.0, -1.0);
        for n in 0..100 {
            assert!((u - eval(&a, 40.0 - n as f64)).abs() < 1e-9);
            u += d;
            d += dd;
        }
    }

    #[test]
    fn the_texel_is_the_integer_part() {
        assert_eq!(texel(word(3.0 + 0.5)), 3);
        assert_eq!(texel(word(-0.2 + 0.5)), 0);
        assert_eq!(texel(word(-0.7 + 0.5)), 0xFFFF);
    }
}
