//! Normalizer without division or square root (SPEC §1, Ukrainian patent 63343):
//! N' = N · f(K), f(K) = c2·K² + c1·K + c0, K = x² + y² + z², valid for K ∈ [0.499, 1];
//! the multiplier-free K recurrence along a raster line; and the vector interpolator with
//! constant increments ΔN_H, ΔN_V, ΔN_D driven by the walk's step types.

use crate::shade::ShadeContext;
use crate::shading::Emit;
use crate::types::{EdgeStep, ScreenTriangle, StepType, Walk};
use glam::DVec3;

/// Coefficients (c2, c1, c0) of f(K) = c2·K² + c1·K + c0, evaluated by Horner as
/// (c2·K + c1)·K + c0.
pub type Coeffs = [f64; 3];

/// The published coefficients: f(K) = 0.822·K² − 2.046·K + 2.227.
pub const PUBLISHED: Coeffs = [0.822, -2.046, 2.227];

/// Domain of K on which the formula is stated.
pub const K_DOMAIN: (f64, f64) = (0.499, 1.0);

/// f(K) by Horner, as the hardware evaluates it.
pub fn scale(k: f64, c: Coeffs) -> f64 {
    (c[0] * k + c[1]) * k + c[2]
}

/// N' = N · f(|N|²), with one quadratic or by segments.
pub fn normalize(n: DVec3, c: impl Into<Scale>) -> DVec3 {
    n * c.into().at(n.length_squared())
}

/// Segments of a [`Scale`].
pub const SEGMENTS: usize = 4;

/// One segment of a [`Scale`]: f(K) = (c2·K + c1)·(K − base) + c0 with `c` = (c2, c1, c0).
/// With base 0 this is the plain Horner form (c2·K + c1)·K + c0. A base moves the second
/// multiplication's operand to the segment (K − base ≥ 0, clamped at 0 below the base), which
/// keeps t1 = c2·K + c1 inside the hardware's [−2, 2) where a plain quadratic fitted to the
/// low end of the domain needs t1 ≈ −2.2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    pub base: f64,
    pub c: Coeffs,
}

impl Segment {
    /// f(K) on this segment, in the hardware's order.
    pub fn at(&self, k: f64) -> f64 {
        (self.c[0] * k + self.c[1]) * (k - self.base).max(0.0) + self.c[2]
    }
    /// The same polynomial in the plain form (c2, c1, c0) of K (for the error analysis).
    pub fn plain(&self) -> Coeffs {
        let [c2, c1, c0] = self.c;
        [c2, c1 - c2 * self.base, c0 - c1 * self.base]
    }
}

/// The normalizer's f(K): a quadratic per segment of K (SPEC §1 and §10, extended). The
/// segment is chosen by K's leading bits, as the hardware does on K in unsigned Q1.15: K ≥ 1
/// (bit 15) is segment 3, K < 0.5 (bit 14 clear) segment 0, otherwise bits 13..12, i.e.
/// [0.5, 0.625) → 0, [0.625, 0.75) → 1, [0.75, 0.875) → 2, [0.875, 1) → 3. A single quadratic
/// is the same in every segment with base 0 (`From<Coeffs>`); [`PIECEWISE`] differs per
/// segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale(pub [Segment; SEGMENTS]);

impl From<Coeffs> for Scale {
    fn from(c: Coeffs) -> Scale {
        Scale([Segment { base: 0.0, c }; SEGMENTS])
    }
}

impl Scale {
    /// The segment of K (see the type's documentation).
    pub fn segment(k: f64) -> usize {
        if k >= 1.0 {
            3
        } else if k < 0.5 {
            0
        } else {
            (((k - 0.5) * 8.0).floor() as usize).min(3)
        }
    }
    /// Where segment `s` holds on the domain's K: [lo, hi).
    pub fn segment_range(s: usize) -> (f64, f64) {
        match s {
            0 => (K_DOMAIN.0, 0.625),
            3 => (0.875, K_DOMAIN.1),
            _ => (0.5 + 0.125 * s as f64, 0.625 + 0.125 * s as f64),
        }
    }
    /// f(K) as the hardware evaluates it, with K's segment.
    pub fn at(&self, k: f64) -> f64 {
        self.0[Self::segment(k)].at(k)
    }
    /// Whether the segments differ (a piecewise set, not one quadratic).
    pub fn is_piecewise(&self) -> bool {
        self.0.iter().any(|g| *g != self.0[0])
    }
}

/// The piecewise normalizer (`normalizer-pw`): four segments of K ([`Scale`]), each the
/// quadratic minimax in the relative error √K·f(K) − 1 on its segment, the last one exact at
/// K = 1 (f(1) = 1, where almost every pixel of a fine mesh lies). Derived by
/// [`crate::accuracy::derive_piecewise`] (`tests/approx.rs` checks these constants against
/// the derivation); every coefficient is a multiple of 2⁻²⁸ (c2 of 2⁻¹⁵), so the hardware
/// holds them exactly (|c2| in Q1.15, c1 in Q3.29, c0 in Q4.28). Max relative error
/// 1.12·10⁻⁴ on [0.499, 1] (segment 0), against 0.82 % for [`FIT`] (`accuracy`).
pub const PIECEWISE: Scale = Scale([pw_segment(0), pw_segment(1), pw_segment(2), pw_segment(3)]);

const fn pw_segment(s: usize) -> Segment {
    Segment {
        base: PIECEWISE_BASES[s],
        c: [PW[s][0] / Q15, PW[s][1] / Q28, PW[s][2] / Q28],
    }
}

/// [`PIECEWISE`]'s words: c2 in units of 2⁻¹⁵, c1 and c0 in units of 2⁻²⁸.
const PW: [[f64; 3]; SEGMENTS] = [
    [52360.0, -641731384.0, 432997175.0],
    [31538.0, -430136484.0, 339526910.0],
    [20736.0, -332412000.0, 309951489.0],
    [14316.0, -265486416.0, 286961674.0],
];
const Q15: f64 = 32768.0;
const Q28: f64 = 268435456.0;

/// The bases of [`PIECEWISE`]'s segments.
pub const PIECEWISE_BASES: [f64; SEGMENTS] = [0.375, 0.625, 0.75, 0.875];

/// K along a raster line by additions only: K_{i+1} = K_i + 2α + β_i, β_{i+1} = β_i + 2β,
/// β_0 = β, with α = N0·Δ and β = Δ·Δ (SPEC §1). Returns K_0..K_{len-1}.
pub fn k_recurrence(n0: DVec3, delta: DVec3, len: usize) -> Vec<f64> {
    let alpha = n0.dot(delta);
    let beta = delta.length_squared();
    let mut k = n0.length_squared();
    let mut beta_i = beta;
    let mut out = Vec::with_capacity(len);
    for _ in 0..len {
        out.push(k);
        k += 2.0 * alpha + beta_i;
        beta_i += 2.0 * beta;
    }
    out
}

/// Fitted coefficients of the same hardware (SPEC §10): f(K) = 1 − u/2 + c·u², u = K − 1,
/// i.e. exact in value *and slope* at K = 1 (√K·f(K) − 1 = O((1 − K)²) there, where almost every
/// pixel of a finely tessellated mesh lies), and c chosen minimax for the relative error on
/// [0.499, 1]. c is derived by [`crate::accuracy::derive_tangent_fit`] (golden-section search
/// of the convex max-error in c over dense samples; the optimum equioscillates between the
/// interior maximum and K = 0.499) and rounded to 14 fractional bits, so that all three
/// coefficients are exact in a Q·14 format and the constraints hold bit-exactly;
/// `tests/approx.rs` checks the constant against the derivation. In (c2, c1, c0) form:
/// (c, −1/2 − 2c, 3/2 + c).
pub const FIT: Coeffs = [FIT_C, -0.5 - 2.0 * FIT_C, 1.5 + FIT_C];

/// The free coefficient c of [`FIT`] (10019 / 2^14 ≈ 0.61151).
pub const FIT_C: f64 = 10019.0 / 16384.0;

/// Per-triangle set-up of the vector interpolator (SPEC §1, software side): the normal at the
/// walk's start point and the constant increments. ΔN_D is ΔN_V ± ΔN_H by the step's x sign.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalizerSetup {
    /// Interpolated (unnormalized) normal at the first row's `x_start`, placed by set-up.
    pub n_start: DVec3,
    /// ΔN_H: increment per step of +1 in x.
    pub delta_h: DVec3,
    /// ΔN_V: increment per step of +1 in y.
    pub delta_v: DVec3,
}

impl NormalizerSetup {
    /// Increment for one move of the working edge.
    pub fn edge_increment(&self, step: EdgeStep) -> DVec3 {
        match step.step {
            StepType::Start => DVec3::ZERO,
            StepType::Horizontal => self.delta_h * step.dx as f64,
            StepType::Vertical => self.delta_v,
            StepType::Diagonal => self.delta_v + self.delta_h * step.dx as f64,
        }
    }
    /// ΔN_D for a diagonal step in x direction `dx` (±1): ΔN_V + dx·ΔN_H.
    pub fn delta_d(&self, dx: i8) -> DVec3 {
        self.delta_v + self.delta_h * dx as f64
    }
    /// β = Δ·Δ of the K recurrence (once per triangle; the same for both span directions).
    pub fn beta(&self) -> f64 {
        self.delta_h.length_squared()
    }
}

/// Set-up for `walk` of `tri`; `None` for a zero-area triangle or an empty walk.
pub fn setup(tri: &ScreenTriangle, walk: &Walk) -> Option<NormalizerSetup> {
    let plane = tri.normal_plane()?;
    let first = walk.rows.first()?;
    Some(NormalizerSetup {
        n_start: plane.at_pixel(first.x_start, first.y),
        delta_h: plane.delta_h(),
        delta_v: plane.delta_v(),
    })
}

/// One pixel out of the vector interpolator and the simplified-radicand block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WalkedNormal {
    pub x: i32,
    pub y: i32,
    /// Interpolated, unnormalized normal, accumulated by constant increments.
    pub n: DVec3,
    /// K = |N|² by the recurrence (K₀ = |N|² at the line start, squares once per line).
    pub k: f64,
}

/// The hardware side of SPEC §1 before the normalizer: walk the working edge adding ΔN_H,
/// ΔN_V or ΔN_D per step, then each raster line adding dir·ΔN_H per pixel, with K by the
/// recurrence (α = N₀·Δ once per line, β = Δ·Δ once per triangle). Pixels in walk order.
pub fn interpolate(setup: &NormalizerSetup, walk: &Walk) -> Vec<WalkedNormal> {
    let mut out = Vec::with_capacity(walk.pixel_count());
    let mut n_edge = setup.n_start;
    for (r, row) in walk.rows.iter().enumerate() {
        if r > 0 {
            for &s in &row.edge_steps {
                n_edge += setup.edge_increment(s);
            }
        }
        let delta = setup.delta_h * row.dir as f64;
        let ks = k_recurrence(n_edge, delta, row.len as usize);
        let mut n = n_edge;
        for (i, k) in ks.into_iter().enumerate() {
            out.push(WalkedNormal {
                x: row.x_start + i as i32 * row.dir as i32,
                y: row.y,
                n,
                k,
            });
            n += delta;
        }
    }
    out
}

/// The lighting model's cosines (cos φ, cos λ) of N' = N·f(K), unclamped.
pub fn cosines(p: &WalkedNormal, ctx: &ShadeContext, c: &Scale) -> (f64, f64) {
    let n = p.n * c.at(p.k);
    let cos_s = ctx.specular_vector().map_or(0.0, |x| n.dot(x));
    ctx.cosines(n.dot(ctx.light), cos_s)
}

/// Per-pixel kernel: N' = N·f(K), then the lighting model's cosines with N'.
pub fn pixel(p: &WalkedNormal, ctx: &ShadeContext, c: &Scale) -> [u8; 3] {
    let (d, s) = cosines(p, ctx, c);
    ctx.combine(d, ctx.specular_power(s))
}

/// The normalizer method (SPEC §1) with coefficients `c` ([`PUBLISHED`], [`FIT`] or
/// [`PIECEWISE`]).
pub fn shade(
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    c: impl Into<Scale>,
    emit: Emit,
) {
    shade_front_end(tri, walk, ctx, c, emit, |_, _, d, s| {
        ctx.combine(d, ctx.specular_power(s))
    });
}

/// The hardware's front end for the methods built on it (`brdf-k*`, `bump`): the vector
/// interpolator and the normalizer with coefficients `c`, then the lighting model's cosines;
/// `back_end(x, y, cos φ, cos λ)` forms the colour. (The reference's front end normalizes
/// exactly: `crate::shading::phong::shade_exact_front_end`.)
pub fn shade_front_end(
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    c: impl Into<Scale>,
    emit: Emit,
    mut back_end: impl FnMut(i32, i32, f64, f64) -> [u8; 3],
) {
    let c = c.into();
    let Some(s) = setup(tri, walk) else { return };
    for p in interpolate(&s, walk) {
        let (d, sp) = cosines(&p, ctx, &c);
        emit(p.x, p.y, back_end(p.x, p.y, d, sp));
    }
}

/// Bit-exact integer twins of the SPEC §1 blocks in `rtl/src/units/normalizer.rs` and
/// `rtl/src/units/k_recurrence.rs`, written from their headers' formats (not from the RTL): every
/// register, every rounding (add half an LSB, drop, ties toward +∞) and every saturation, in
/// plain `i64` arithmetic. The benches compare them with the RTL exactly, every port, every
/// clock; the f64 functions above are the second check. Words are raw integers (input and
/// output components signed Q2.17, `i64` in −2¹⁸..2¹⁸; K in Q4.28 units; the span
/// normalizer's N₀ and Δ signed Q2.14).
pub mod twin {
    use super::{Scale, SEGMENTS};

    /// `v·2^frac` rounded to nearest, ties toward +∞ (the quantization of a constant).
    fn quantize(v: f64, frac: u32) -> i64 {
        (v * (frac as f64).exp2() + 0.5).floor() as i64
    }

    /// Drop `bits` LSBs of `v` rounding to nearest (ties toward +∞), then clamp to [lo, hi].
    fn round_sat(v: i64, bits: u32, lo: i64, hi: i64) -> i64 {
        ((v + (1 << (bits - 1))) >> bits).clamp(lo, hi)
    }

    const Q217_MIN: i64 = -(1 << 18);
    const Q217_MAX: i64 = (1 << 18) - 1;
    const U16_MAX: i64 = 0xFFFF;
    const U19_MAX: i64 = 0x7FFFF;

    /// One segment's words: |c2| in Q1.15, c2 < 0, c1 in Q3.29, c0 in Q4.28, the base in
    /// unsigned Q1.15 (each rounded to nearest).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct SegmentWords {
        pub c2_mag: i64,
        pub c2_neg: bool,
        pub c1: i64,
        pub c0: i64,
        pub base: i64,
    }

    /// The segment of K in unsigned Q1.15 (`k_narrow`): bit 15 → 3, bit 14 clear → 0, else
    /// bits 13..12 (see [`Scale`]).
    pub fn segment_of(k_narrow: i64) -> usize {
        if k_narrow & 0x8000 != 0 {
            3
        } else if k_narrow & 0x4000 == 0 {
            0
        } else {
            ((k_narrow >> 12) & 3) as usize
        }
    }

    /// The normalizer back end (`NormalizerK`): N and K in, N·f(K) out, latency 11 (B4 and B6
    /// take three clocks: the product is ready three registers on).
    ///
    /// ```text
    /// B1 k_narrow = sat(round(K: Q4.28 → Q1.15)), s = its segment (coefficients c2, c1, c0, base)
    /// B2 c2k = |c2|·k_narrow (Q2.30); k_local = max(k_narrow − base, 0) (Q1.15)
    /// B3 t1 = sat(round(c1 ± c2k/2: Q3.29 → Q2.17))
    /// B4 t1h = ⌊t1/8⌋, t1l = t1 − 8·t1h: t1h·k_local (Q3.29), t1l·k_local (units 2⁻³²)
    /// B5 f = sat(round(c0 + ⌊t1h·k_local/2⌋ + ⌊t1l·k_local/16⌋: Q4.28 → Q1.18))
    /// B6 xf = ⌊x·f / 64⌋ (x Q2.17 · f Q1.18 → Q3.29, floored)
    /// B7 nx = sat(round(xf: Q3.29 → Q2.17))
    /// ```
    /// The halvings and the floors of the low parts floor, as an arithmetic shift does. Each
    /// vector's coefficients are those of its own segment at every stage.
    #[derive(Clone, Debug)]
    pub struct NormalizerKTwin {
        words: [SegmentWords; SEGMENTS],
        k_narrow: i64,
        seg: usize,
        c2k: i64,
        seg_p1: usize,
        k_local_p1: i64,
        t1: i64,
        seg_p2: usize,
        k_local_p2: i64,
        t1k_a: [(i64, usize); 2],
        t1k: (i64, usize),
        f: i64,
        xf_a: [[i64; 3]; 2],
        xf: [i64; 3],
        n: [i64; 3],
        valid: [bool; 11],
        vec: [[i64; 3]; 7],
    }

    impl NormalizerKTwin {
        /// The back end built with `c`: one quadratic (`Coeffs`) or a piecewise [`Scale`].
        pub fn new(c: impl Into<Scale>) -> Self {
            let c: Scale = c.into();
            Self {
                words: c.0.map(|g| SegmentWords {
                    c2_mag: quantize(g.c[0].abs(), 15),
                    c2_neg: g.c[0] < 0.0,
                    c1: quantize(g.c[1], 29),
                    c0: quantize(g.c[2], 28),
                    base: quantize(g.base, 15),
                }),
                k_narrow: 0,
                seg: 0,
                c2k: 0,
                seg_p1: 0,
                k_local_p1: 0,
                t1: 0,
                seg_p2: 0,
                k_local_p2: 0,
                t1k_a: [(0, 0); 2],
                t1k: (0, 0),
                f: 0,
                xf_a: [[0; 3]; 2],
                xf: [0; 3],
                n: [0; 3],
                valid: [false; 11],
                vec: [[0; 3]; 7],
            }
        }

        /// What the outputs show this clock: (valid_out, [nx, ny, nz]).
        pub fn outputs(&self) -> (bool, [i64; 3]) {
            (self.valid[10], self.n)
        }

        /// The words this twin computes with, per segment.
        pub fn segment_words(&self) -> [SegmentWords; SEGMENTS] {
            self.words
        }

        /// One rising edge with inputs `valid_in`, N = `v` (signed Q2.17 integers) and
        /// `k` (Q4.28 units).
        pub fn clock(&mut self, valid_in: bool, v: [i64; 3], k: i64) {
            let s = self.clone();
            let w = &s.words;
            self.k_narrow = ((k + (1 << 12)) >> 13).min(U16_MAX);
            self.seg = segment_of(self.k_narrow);
            self.c2k = w[s.seg].c2_mag * s.k_narrow;
            self.seg_p1 = s.seg;
            self.k_local_p1 = (s.k_narrow - w[s.seg].base).max(0);
            let half = s.c2k >> 1;
            let g = w[s.seg_p1];
            let t1_wide = g.c1 + if g.c2_neg { -half } else { half };
            self.t1 = round_sat(t1_wide, 12, Q217_MIN, Q217_MAX);
            self.seg_p2 = s.seg_p1;
            self.k_local_p2 = s.k_local_p1;
            // t1·k_local in Q4.28: the high part halved, the low part (units 2⁻³²) shifted by 4.
            let (t1h, t1l) = (s.t1 >> 3, s.t1 & 7);
            let t1k = ((t1h * s.k_local_p2) >> 1) + ((t1l * s.k_local_p2) >> 4);
            self.t1k_a = [(t1k, s.seg_p2), s.t1k_a[0]];
            self.t1k = s.t1k_a[1];
            self.f = round_sat(w[s.t1k.1].c0 + s.t1k.0, 10, 0, U19_MAX);
            self.xf_a = [s.vec[6].map(|x| (x * s.f) >> 6), s.xf_a[0]];
            self.xf = s.xf_a[1];
            self.n = s.xf.map(|p| round_sat(p, 12, Q217_MIN, Q217_MAX));
            self.valid = [
                valid_in, s.valid[0], s.valid[1], s.valid[2], s.valid[3], s.valid[4], s.valid[5],
                s.valid[6], s.valid[7], s.valid[8], s.valid[9],
            ];
            self.vec = [
                v, s.vec[0], s.vec[1], s.vec[2], s.vec[3], s.vec[4], s.vec[5],
            ];
        }
    }

    /// The full normalizer: three squarers (three clocks: the square is ready three registers
    /// on) and Sm1 (K = ⌊x² + y² + z²⌋ in Q4.28) in front of [`NormalizerKTwin`]; latency 15.
    #[derive(Clone, Debug)]
    pub struct NormalizerTwin {
        sq_a: [[i64; 3]; 2],
        sq: [i64; 3],
        k_full: i64,
        valid: [bool; 4],
        vec: [[i64; 3]; 4],
        back: NormalizerKTwin,
    }

    impl NormalizerTwin {
        pub fn new(c: impl Into<Scale>) -> Self {
            Self {
                sq_a: [[0; 3]; 2],
                sq: [0; 3],
                k_full: 0,
                valid: [false; 4],
                vec: [[0; 3]; 4],
                back: NormalizerKTwin::new(c),
            }
        }
        pub fn outputs(&self) -> (bool, [i64; 3]) {
            self.back.outputs()
        }
        pub fn clock(&mut self, valid_in: bool, v: [i64; 3]) {
            self.back.clock(self.valid[3], self.vec[3], self.k_full);
            // Q2.17 squares are in units of 2⁻³⁴: floor the sum to Q4.28.
            self.k_full = self.sq.iter().sum::<i64>() >> 6;
            self.sq = self.sq_a[1];
            self.sq_a = [v.map(|x| x * x), self.sq_a[0]];
            self.valid = [valid_in, self.valid[0], self.valid[1], self.valid[2]];
            self.vec = [v, self.vec[0], self.vec[1], self.vec[2]];
        }
    }

    /// K along a span (SPEC §1): K_{i+1} = K_i + 2α + β_i, β_{i+1} = β_i + 2β, modulo 2³²;
    /// an input register stage, then the recurrence (which freezes while `valid` is low) with
    /// its output register; latency 2.
    #[derive(Clone, Debug, Default)]
    pub struct KRecurrenceTwin {
        valid_p1: bool,
        load_p1: bool,
        k0_p1: u32,
        alpha_p1: u32,
        beta_p1: u32,
        k_next: u32,
        beta_i: u32,
        alpha2: u32,
        beta2: u32,
        k_out: u32,
        valid_p2: bool,
    }

    impl KRecurrenceTwin {
        pub fn new() -> Self {
            Self::default()
        }
        /// (valid_out, k) shown this clock.
        pub fn outputs(&self) -> (bool, u32) {
            (self.valid_p2, self.k_out)
        }
        /// One rising edge; `load` starts a new line (with `valid_in`) from K_0 = `k0`, α, β.
        pub fn clock(&mut self, valid_in: bool, load: bool, k0: u32, alpha: u32, beta: u32) {
            let s = self.clone();
            if s.valid_p1 {
                let (k, b, a2, b2) = if s.load_p1 {
                    let a2 = s.alpha_p1.wrapping_mul(2);
                    (s.k0_p1, s.beta_p1, a2, s.beta_p1.wrapping_mul(2))
                } else {
                    (s.k_next, s.beta_i, s.alpha2, s.beta2)
                };
                self.k_out = k;
                self.k_next = k.wrapping_add(a2).wrapping_add(b);
                self.beta_i = b.wrapping_add(b2);
                self.alpha2 = a2;
                self.beta2 = b2;
            }
            self.valid_p2 = s.valid_p1;
            self.valid_p1 = valid_in;
            self.load_p1 = load && valid_in;
            self.k0_p1 = k0;
            self.alpha_p1 = alpha;
            self.beta_p1 = beta;
        }
    }

    /// The span normalizer: [`KRecurrenceTwin`] beside the vector interpolator
    /// N_{i+1} = N_i + Δ (16-bit wrap-around, as the caller keeps N_i representable), both
    /// feeding [`NormalizerKTwin`]; latency 13.
    #[derive(Clone, Debug)]
    pub struct SpanNormalizerTwin {
        krec: KRecurrenceTwin,
        valid_p1: bool,
        load_p1: bool,
        n0_p1: [i64; 3],
        d_p1: [i64; 3],
        n_next: [i64; 3],
        d_hold: [i64; 3],
        n_out: [i64; 3],
        back: NormalizerKTwin,
    }

    /// Wrap to a signed 16-bit value.
    fn wrap16(v: i64) -> i64 {
        ((v + (1 << 15)).rem_euclid(1 << 16)) - (1 << 15)
    }

    impl SpanNormalizerTwin {
        pub fn new(c: impl Into<Scale>) -> Self {
            Self {
                krec: KRecurrenceTwin::new(),
                valid_p1: false,
                load_p1: false,
                n0_p1: [0; 3],
                d_p1: [0; 3],
                n_next: [0; 3],
                d_hold: [0; 3],
                n_out: [0; 3],
                back: NormalizerKTwin::new(c),
            }
        }
        pub fn outputs(&self) -> (bool, [i64; 3]) {
            self.back.outputs()
        }
        /// One rising edge: N₀ = `n0`, Δ = `d` (signed Q2.14) and K_0, α, β taken with `load`.
        #[allow(clippy::too_many_arguments)]
        pub fn clock(
            &mut self,
            valid_in: bool,
            load: bool,
            n0: [i64; 3],
            d: [i64; 3],
            k0: u32,
            alpha: u32,
            beta: u32,
        ) {
            let (kv, k) = self.krec.outputs();
            // N_i enters the back end as Q2.17: the Q2.14 word times 8.
            self.back.clock(kv, self.n_out.map(|x| x * 8), k as i64);
            self.krec.clock(valid_in, load, k0, alpha, beta);
            if self.valid_p1 {
                let (n, dd) = if self.load_p1 {
                    (self.n0_p1, self.d_p1)
                } else {
                    (self.n_next, self.d_hold)
                };
                self.n_out = n;
                self.n_next = [0, 1, 2].map(|i| wrap16(n[i] + dd[i]));
                self.d_hold = dd;
            }
            self.valid_p1 = valid_in;
            self.load_p1 = load && valid_in;
            self.n0_p1 = n0;
            self.d_p1 = d;
        }
    }
}
