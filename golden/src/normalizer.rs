//! Normalizer without division or square root (SPEC §1, Ukrainian patent 63343):
//! N' = N · f(K), f(K) = c2·K² + c1·K + c0, K = x² + y² + z², valid for K ∈ [0.499, 1];
//! the multiplier-free K recurrence along a raster line; and the vector interpolator with
//! constant increments ΔN_H, ΔN_V, ΔN_D driven by the walk's step types.

use crate::methods::Emit;
use crate::shade::ShadeContext;
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

/// N' = N · f(|N|²).
pub fn normalize(n: DVec3, c: Coeffs) -> DVec3 {
    n * scale(n.length_squared(), c)
}

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

/// Per-pixel kernel: N' = N·f(K), then the lighting model's cosines with N'.
pub fn pixel(p: &WalkedNormal, ctx: &ShadeContext, c: Coeffs) -> [u8; 3] {
    let n = p.n * scale(p.k, c);
    let cos_s = ctx.specular_vector().map_or(0.0, |x| n.dot(x));
    let (d, s) = ctx.cosines(n.dot(ctx.light), cos_s);
    ctx.combine(d, ctx.specular_power(s))
}

/// The normalizer method (SPEC §1) with coefficients `c` ([`PUBLISHED`] or [`FIT`]).
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, c: Coeffs, emit: Emit) {
    let Some(s) = setup(tri, walk) else { return };
    for p in interpolate(&s, walk) {
        emit(p.x, p.y, pixel(&p, ctx, c));
    }
}
