//! Texture-coordinate block (SPEC §14): the additive, division-free perspective-correct texture
//! coordinate. The exact coordinate is u = N/D with N = a·x + b·y + c and D = g·x + h·y + i (the
//! PCT coefficients of the triangle); the block keeps u as the nearest texel by correction steps
//! on two comparison words, so its pixel loop has adders and comparators only. This module is
//! the golden face of that block: the exact reference ([`exact_u`], [`nearest_texel`]) and a
//! bit-exact integer model of the recurrences ([`PctWalker`]), which the RTL block will match
//! every clock. Not a block of its own: no ports, no latency.
//!
//! # Formula (SPEC §14 with Δu = 1: integer texel coordinates)
//!
//! ```text
//!   E = 2D
//!   W = u·E − x(2a − g) − y(2b − h) − (2c − i)  =  2D·(u + ½ − N/D)
//!   Q = u·E − x(2a + g) − y(2b + h) − (2c + i)  =  2D·(u − ½ − N/D)
//! ```
//!
//! With D > 0, u is the nearest texel when **Q ≤ 0 < W**, i.e. u − ½ ≤ N/D < u + ½: a tie goes
//! up, u = ⌊N/D + ½⌋ ([`nearest_texel`]). SPEC §14 reconstructs the two comparison operators
//! from a gap in the source; this tie rule is the one chosen, and the reference uses the same.
//!
//! - **Correction step** (q of them per pixel, data-dependent): W ≤ 0 → u += 1, W += E, Q += E;
//!   Q > 0 → u −= 1, W −= E, Q −= E. Each step moves u by one texel towards N/D, so the steps of
//!   a walk are exactly the texels u crosses.
//! - **x → x + 1**: E += 2g; W += G − (2a − g); Q += G − (2a + g), with G = 2g·u kept in a
//!   register and moved by ±2g whenever u steps (no multiplier).
//! - **y → y + 1**: E += 2h; W += H − (2b − h); Q += H − (2b + h), H = 2h·u likewise.
//!
//! The four brackets (2a ∓ g), (2b ∓ h) are set up once per triangle; a walk's start needs one
//! division (or any start guess: the corrections reach the nearest texel from anywhere, at one
//! step per texel). Coefficients are integers — the set-up's fixed point, whose common scale of
//! N and D cancels — and D > 0 on every pixel walked.
//!
//! # Steps per clock
//!
//! The RTL resolves up to k correction steps in one clock (k parallel comparators; the seed's
//! one step per clock is k = 1) and holds the pipe only beyond that: a pixel with q steps costs
//! max(1, ⌈q/k⌉) clocks ([`clocks_for`]).

/// The PCT coefficients of one triangle (integers: the set-up's fixed point).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PctCoeffs {
    pub a: i64,
    pub b: i64,
    pub c: i64,
    pub g: i64,
    pub h: i64,
    pub i: i64,
}

impl PctCoeffs {
    /// N at pixel (x, y).
    pub fn n(&self, x: i64, y: i64) -> i128 {
        self.a as i128 * x as i128 + self.b as i128 * y as i128 + self.c as i128
    }
    /// D at pixel (x, y).
    pub fn d(&self, x: i64, y: i64) -> i128 {
        self.g as i128 * x as i128 + self.h as i128 * y as i128 + self.i as i128
    }
}

/// A screen-space plane value·(X, Y) = kx·X + ky·Y + k0 through three vertices (f64), or
/// `None` for a triangle of zero area.
fn plane(p: [(f64, f64); 3], val: [f64; 3]) -> Option<[f64; 3]> {
    let (x1, y1) = (p[1].0 - p[0].0, p[1].1 - p[0].1);
    let (x2, y2) = (p[2].0 - p[0].0, p[2].1 - p[0].1);
    let det = x1 * y2 - x2 * y1;
    if det == 0.0 {
        return None;
    }
    let (v1, v2) = (val[1] - val[0], val[2] - val[0]);
    let kx = (v1 * y2 - v2 * y1) / det;
    let ky = (x1 * v2 - x2 * v1) / det;
    Some([kx, ky, val[0] - kx * p[0].0 - ky * p[0].1])
}

/// The perspective-correct planes of a triangle in f64: screen vertices `p` (pixel (x, y) has
/// its centre at (x + ½, y + ½)), clip w per vertex (> 0) and texel coordinates `st` per
/// vertex. Returns the planes of 1/w, s/w and t/w: u = (s/w)/(1/w) at any screen point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PctPlanes {
    pub q: [f64; 3],
    pub s: [f64; 3],
    pub t: [f64; 3],
}

impl PctPlanes {
    pub fn new(p: [(f64, f64); 3], w: [f64; 3], st: [(f64, f64); 3]) -> Option<PctPlanes> {
        let q = w.map(|w| 1.0 / w);
        Some(PctPlanes {
            q: plane(p, q)?,
            s: plane(p, [0, 1, 2].map(|k| st[k].0 * q[k]))?,
            t: plane(p, [0, 1, 2].map(|k| st[k].1 * q[k]))?,
        })
    }

    /// The exact (u, v) at pixel (x, y)'s centre, in f64 (the reference).
    pub fn exact(&self, x: i64, y: i64) -> (f64, f64) {
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        let ev = |k: &[f64; 3]| k[0] * cx + k[1] * cy + k[2];
        let d = ev(&self.q);
        (ev(&self.s) / d, ev(&self.t) / d)
    }

    /// Integer coefficients relative to pixel `origin` (x and y in the coefficients are
    /// x − origin.x, y − origin.y at pixel centres), scaled so that D's largest value at the
    /// vertices is `d_max` (N/D is unchanged by the common scale), each rounded to the nearest
    /// integer. `vmax`: the largest 1/w at the vertices.
    pub fn coeffs(&self, origin: (i64, i64), vmax: f64, d_max: f64) -> (PctCoeffs, PctCoeffs) {
        let scale = d_max / vmax;
        let (cx, cy) = (origin.0 as f64 + 0.5, origin.1 as f64 + 0.5);
        let int = |k: &[f64; 3]| {
            (
                (k[0] * scale).round() as i64,
                (k[1] * scale).round() as i64,
                ((k[0] * cx + k[1] * cy + k[2]) * scale).round() as i64,
            )
        };
        let (g, h, i) = int(&self.q);
        let c = |k: &[f64; 3]| {
            let (a, b, c) = int(k);
            PctCoeffs { a, b, c, g, h, i }
        };
        (c(&self.s), c(&self.t))
    }
}

/// Coefficients whose quotients land on half texels at many pixels (D constant,
/// u = x/2 − y/4, v = x/2 + 3y/4): stimulus for the tie rule (a tie goes up).
pub fn tie_coeffs() -> (PctCoeffs, PctCoeffs) {
    let d = 1 << 21;
    let cu = PctCoeffs {
        a: d / 2,
        b: -d / 4,
        c: 0,
        g: 0,
        h: 0,
        i: d,
    };
    let cv = PctCoeffs {
        a: d / 2,
        b: 3 * d / 4,
        ..cu
    };
    (cu, cv)
}

/// The exact texture coordinate N/D at pixel (x, y), in f64 (the float face).
pub fn exact_u(c: &PctCoeffs, x: i64, y: i64) -> f64 {
    c.n(x, y) as f64 / c.d(x, y) as f64
}

/// The nearest texel of the exact quotient, ⌊N/D + ½⌋ = ⌊(2N + D) / 2D⌋, in exact integer
/// arithmetic (D > 0).
pub fn nearest_texel(c: &PctCoeffs, x: i64, y: i64) -> i64 {
    let (n, d) = (c.n(x, y), c.d(x, y));
    assert!(d > 0, "D = {d} at ({x}, {y}): the walk needs D > 0");
    (2 * n + d).div_euclid(2 * d) as i64
}

/// The comparison words W and Q of u at pixel (x, y), straight from their definitions.
pub fn words_at(c: &PctCoeffs, x: i64, y: i64, u: i64) -> (i128, i128) {
    let e = 2 * c.d(x, y);
    let (x, y, u) = (x as i128, y as i128, u as i128);
    let (a, b, cc) = (c.a as i128, c.b as i128, c.c as i128);
    let (g, h, i) = (c.g as i128, c.h as i128, c.i as i128);
    let w = u * e - x * (2 * a - g) - y * (2 * b - h) - (2 * cc - i);
    let q = u * e - x * (2 * a + g) - y * (2 * b + h) - (2 * cc + i);
    (w, q)
}

/// More correction steps than a pixel can need on a 2^20-texel axis: a walk past it is broken.
pub const MAX_STEPS: u32 = 1 << 20;

/// Clocks a pixel with `steps` correction steps costs when k steps resolve per clock.
pub fn clocks_for(steps: u32, k: u32) -> u32 {
    steps.div_ceil(k.max(1)).max(1)
}

/// The block's registers: the bit-exact integer model of the recurrences.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PctWalker {
    /// The brackets, set up once per triangle: 2a − g, 2a + g, 2b − h, 2b + h; and 2g, 2h.
    pub ax_lo: i128,
    pub ax_hi: i128,
    pub by_lo: i128,
    pub by_hi: i128,
    pub g2: i128,
    pub h2: i128,
    /// The current pixel.
    pub x: i64,
    pub y: i64,
    /// The texel, and E, W, Q, G = 2g·u, H = 2h·u at the current pixel.
    pub u: i64,
    pub e: i128,
    pub w: i128,
    pub q: i128,
    pub gu: i128,
    pub hu: i128,
}

impl PctWalker {
    /// Load at pixel (x, y) with the start texel `u0` (any integer: the corrections take it to
    /// the nearest texel). The start words are the set-up's (W and Q from their definitions).
    pub fn start(c: &PctCoeffs, x: i64, y: i64, u0: i64) -> PctWalker {
        let (w, q) = words_at(c, x, y, u0);
        PctWalker {
            ax_lo: 2 * c.a as i128 - c.g as i128,
            ax_hi: 2 * c.a as i128 + c.g as i128,
            by_lo: 2 * c.b as i128 - c.h as i128,
            by_hi: 2 * c.b as i128 + c.h as i128,
            g2: 2 * c.g as i128,
            h2: 2 * c.h as i128,
            x,
            y,
            u: u0,
            e: 2 * c.d(x, y),
            w,
            q,
            gu: 2 * c.g as i128 * u0 as i128,
            hu: 2 * c.h as i128 * u0 as i128,
        }
    }

    /// The texel is the nearest one (Q ≤ 0 < W).
    pub fn settled(&self) -> bool {
        self.q <= 0 && self.w > 0
    }

    /// One correction step, if the texel is not settled; whether one was taken.
    pub fn correct_once(&mut self) -> bool {
        let dir: i128 = if self.w <= 0 {
            1
        } else if self.q > 0 {
            -1
        } else {
            return false;
        };
        self.u += dir as i64;
        self.w += dir * self.e;
        self.q += dir * self.e;
        self.gu += dir * self.g2;
        self.hu += dir * self.h2;
        true
    }

    /// Correct until settled; the number of steps taken. The words keep W − Q = E (their
    /// definitions differ by exactly that), so W ≤ 0 and Q > 0 never hold together and every
    /// step moves towards N/D; a broken invariant, or more steps than [`MAX_STEPS`], panics
    /// rather than loops.
    pub fn settle(&mut self) -> u32 {
        assert_eq!(
            self.w - self.q,
            self.e,
            "W − Q ≠ E at ({}, {})",
            self.x,
            self.y
        );
        let mut steps = 0;
        while self.correct_once() {
            steps += 1;
            assert!(
                steps <= MAX_STEPS,
                "over {MAX_STEPS} steps at ({}, {})",
                self.x,
                self.y
            );
        }
        steps
    }

    /// Move to the next pixel of the line (x + 1).
    pub fn step_x(&mut self) {
        self.x += 1;
        self.e += self.g2;
        self.w += self.gu - self.ax_lo;
        self.q += self.gu - self.ax_hi;
    }

    /// Move to the previous pixel of the line (x − 1): the x step run backwards,
    /// E −= 2g; W −= G − (2a − g); Q −= G − (2a + g) (a line walked right to left).
    pub fn step_x_back(&mut self) {
        self.x -= 1;
        self.e -= self.g2;
        self.w -= self.gu - self.ax_lo;
        self.q -= self.gu - self.ax_hi;
    }

    /// Move to the next line (y + 1).
    pub fn step_y(&mut self) {
        self.y += 1;
        self.e += self.h2;
        self.w += self.hu - self.by_lo;
        self.q += self.hu - self.by_hi;
    }
}

/// One pixel of a walked span: its texel and the correction steps it took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpanTexel {
    pub x: i64,
    pub u: i64,
    pub steps: u32,
}

/// Walk `len` pixels of row `y` from `x0` towards +x, starting from the texel `u0`: per pixel,
/// settle, emit, step.
pub fn walk_span(c: &PctCoeffs, x0: i64, y: i64, len: u32, u0: i64) -> Vec<SpanTexel> {
    let mut wk = PctWalker::start(c, x0, y, u0);
    let mut out = Vec::with_capacity(len as usize);
    for k in 0..len {
        if k > 0 {
            wk.step_x();
        }
        let steps = wk.settle();
        out.push(SpanTexel {
            x: wk.x,
            u: wk.u,
            steps,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_depth_span_is_affine() {
        // D = 4 everywhere, N = 3x + 2: u = (3x + 2)/4, nearest texel ⌊(3x + 2)/4 + ½⌋.
        let c = PctCoeffs {
            a: 3,
            c: 2,
            i: 4,
            ..Default::default()
        };
        let got: Vec<i64> = walk_span(&c, 0, 0, 8, 0).iter().map(|t| t.u).collect();
        let want: Vec<i64> = (0..8)
            .map(|x| ((3 * x + 2) as f64 / 4.0 + 0.5).floor() as i64)
            .collect();
        assert_eq!(got, want);
    }

    #[test]
    fn a_tie_goes_up() {
        // N/D = 1/2 exactly at x = 0: the nearest texel is 1.
        let c = PctCoeffs {
            c: 1,
            i: 2,
            ..Default::default()
        };
        assert_eq!(nearest_texel(&c, 0, 0), 1);
        assert_eq!(walk_span(&c, 0, 0, 1, -5)[0].u, 1);
        assert_eq!(walk_span(&c, 0, 0, 1, 7)[0].u, 1);
    }

    #[test]
    fn clocks_per_pixel() {
        assert_eq!(clocks_for(0, 1), 1);
        assert_eq!(clocks_for(1, 1), 1);
        assert_eq!(clocks_for(2, 1), 2);
        assert_eq!(clocks_for(5, 2), 3);
        assert_eq!(clocks_for(4, 4), 1);
    }
}

pub mod block;
