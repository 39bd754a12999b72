//! The reflectance function W(n, γ) (SPEC §2, seed 000):
//! W(n, γ) = [1 − (n+1)/(k+1) · (1 − cos γ)]^k, 0 where the bracket is negative,
//! an approximation of cos^n γ that is exact when k = n. For k = 4, 8, 16 the power is 2, 3, 4
//! squarings and the division by k + 1 becomes shifts and adds ([`recip_shift_add`]):
//! 1/5 ≈ 1/4 − 1/16 + 1/64 − 1/256, 1/9 ≈ 1/8 − 1/64 + 1/512, 1/17 ≈ 1/16 − 1/256.
//! (n + 1)·(1/(k+1)) is per-material set-up; per pixel: one subtract, one multiply, one
//! subtract, log2(k) squarings.
//!
//! Schlick's function S(n, c) = c/(n − n·c + c) is the comparison the source makes.
//!
//! The `brdf-k*` methods describe the hardware's path: the vector interpolator and the
//! normalizer with the fitted coefficients ([`crate::units::normalizer::FIT`], no division or square
//! root) in front, then W with the shift-add division in place of cos^n of the specular term.
//! (Before the lit pixel pipeline existed they started from the exactly normalized normal. At
//! the default scene the fitted normalizer moved their NMSE against the reference by less than
//! 4·10⁻⁷ (k = 16: 4.88·10⁻⁵ → 4.92·10⁻⁵); on coarse meshes, where K strays further from 1,
//! by more (rez 10, n = 50, light 30°, k = 16: 6.2·10⁻⁵ → 7.3·10⁻⁴; `docs/sweep.md`).) With the Phong lighting
//! model γ is the angle between R and V; with Lambert there is no specular term. When n < k the
//! formula is still applied ((n+1)/(k+1) < 1, so the bracket stays positive); it is exact only
//! at k = n.

use crate::shade::ShadeContext;
use crate::shading::Emit;
use crate::types::{ScreenTriangle, Walk};

/// The k values with shift-add divisions.
pub const KS: [u32; 3] = [4, 8, 16];

/// Shift-add approximation of 1/(k+1) for k = 4, 8, 16 (`None` for other k).
pub fn recip_shift_add(k: u32) -> Option<f64> {
    match k {
        4 => Some(1.0 / 4.0 - 1.0 / 16.0 + 1.0 / 64.0 - 1.0 / 256.0),
        8 => Some(1.0 / 8.0 - 1.0 / 64.0 + 1.0 / 512.0),
        16 => Some(1.0 / 16.0 - 1.0 / 256.0),
        _ => None,
    }
}

/// Per-material set-up: a = (n+1)/(k+1), by shifts and adds when `shift_add` and k ∈ {4, 8, 16},
/// otherwise by an exact division.
pub fn slope(n: u32, k: u32, shift_add: bool) -> f64 {
    let recip = if shift_add { recip_shift_add(k) } else { None };
    (n as f64 + 1.0) * recip.unwrap_or(1.0 / (k as f64 + 1.0))
}

/// Per-pixel kernel: W = [1 − a·(1 − cos γ)]^k (0 for a negative bracket or cos γ ≤ 0).
pub fn w_kernel(a: f64, k: u32, cos_gamma: f64) -> f64 {
    if cos_gamma <= 0.0 {
        return 0.0;
    }
    let bracket = 1.0 - a * (1.0 - cos_gamma);
    if bracket <= 0.0 {
        0.0
    } else {
        bracket.powi(k as i32)
    }
}

/// W(n, γ) with the exact division (n+1)/(k+1).
pub fn w_exact(n: u32, k: u32, cos_gamma: f64) -> f64 {
    w_kernel(slope(n, k, false), k, cos_gamma)
}

/// W(n, γ) with the shift-add division (k ∈ {4, 8, 16}).
pub fn w_shift_add(n: u32, k: u32, cos_gamma: f64) -> f64 {
    w_kernel(slope(n, k, true), k, cos_gamma)
}

/// Schlick's function S(n, c) = c/(n − n·c + c), 0 for c ≤ 0.
pub fn schlick(n: u32, cos_gamma: f64) -> f64 {
    if cos_gamma <= 0.0 {
        return 0.0;
    }
    let n = n as f64;
    cos_gamma / (n - n * cos_gamma + cos_gamma)
}

/// The exact cos^n γ (0 for cos γ ≤ 0).
pub fn cos_pow(n: u32, cos_gamma: f64) -> f64 {
    cos_gamma.max(0.0).powi(n as i32)
}

/// Shade one triangle with W for k (fitted-normalizer front end, shift-add division).
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, k: u32, emit: Emit) {
    let a = slope(ctx.n(), k, true);
    let fit = crate::units::normalizer::FIT;
    crate::units::normalizer::shade_front_end(tri, walk, ctx, fit, emit, |_, _, d, s| {
        ctx.combine(d, w_kernel(a, k, s))
    });
}
