//! Fast diffuse and specular with two points per step (SPEC §3, thesis §3.1).
//!
//! On a raster line with unit end normals N_a (first pixel, x = 0) and N_b (last, x = m):
//! N_x·X/|N_x| = p_x/√q_x, p_x = g·x + b, q_x = 1 + M_x, M_x = c·x² + s·x, with
//! b = N_a·X, h = N_b·X, g = (N_b − N_a)·X/m, s = 2(N_b − N_a)·N_a/m, c = |N_b − N_a|²/m²
//! (per-span set-up, software). Per step (hardware): p += g, M += 2c·x + (c + s), and since
//! q(x) = q(m − x) the same 1/√q serves the mirror pixel m − x, whose numerator h − g·x runs
//! down by g: two pixels per step, no division or root. 1/√(M + 1) comes from a quadratic in M
//! ([`CHEBYSHEV`], [`SHIFT_ADD`], [`TAYLOR`] or [`FIT`]), evaluated by Horner like the
//! normalizer's f(K). X is L for the diffuse term and H (Blinn) or V (Phong's R·V) for the
//! specular one; the specular cosine is then raised to n.
//!
//! Span end normals are the exactly normalized interpolated normals at the line's first and
//! last pixel ([`crate::methods::span_end_normals`], software set-up per span).

use crate::shade::ShadeContext;
use crate::shading::{emit_row_ambient, row_xs, span_end_normals, Emit};
use crate::types::{ScreenTriangle, Walk};
use crate::units::normalizer::{scale, Coeffs};
use glam::DVec3;

/// Published Chebyshev approximation 1/√(M+1) ≈ 1.003 − 0.403·M + 0.82·M² on M ∈ [−0.5, 0],
/// as (c2, c1, c0).
pub const CHEBYSHEV: Coeffs = [0.82, -0.403, 1.003];

/// l = 1/4 + 1/8 + 1/32 of the shift-add form.
pub const SHIFT_ADD_L: f64 = 0.25 + 0.125 + 0.03125;

/// Shift-add approximation 1 − l·M + 2l·M² (thesis: 2l written as 1/2 + 1/4 + 1/16).
pub const SHIFT_ADD: Coeffs = [2.0 * SHIFT_ADD_L, -SHIFT_ADD_L, 1.0];

/// Taylor polynomial of the same degree: 1 − M/2 + 3M²/8.
pub const TAYLOR: Coeffs = [0.375, -0.5, 1.0];

/// Fitted form of the same cost: 1 − M/2 + c·M², exact in value and slope at M = 0 (where
/// nearly every pixel of a fine mesh lies), c minimax for the relative error on [−0.5, 0]
/// (derived by [`crate::accuracy::derive_tangent_fit`], rounded to 14 fractional bits; checked
/// in `tests/approx.rs`). The constant term 1 and the 1/2 are shifts, so it is cheaper than
/// [`CHEBYSHEV`].
pub const FIT: Coeffs = [FIT_C, -0.5, 1.0];

/// The free coefficient c of [`FIT`] (10005 / 2^14 ≈ 0.61066).
pub const FIT_C: f64 = 10005.0 / 16384.0;

/// Domain of M on which the approximations are stated (N_a·N_b ≥ 0).
pub const M_DOMAIN: (f64, f64) = (-0.5, 0.0);

/// Per-span, per-vector set-up (software side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastSpan {
    /// Span length m = pixels − 1 (x runs 0..=m).
    pub m: u32,
    /// b = N_a·X.
    pub b: f64,
    /// h = N_b·X.
    pub h: f64,
    /// g = (N_b − N_a)·X/m.
    pub g: f64,
    /// s = 2(N_b − N_a)·N_a/m.
    pub s: f64,
    /// c = |N_b − N_a|²/m².
    pub c: f64,
}

/// Set-up of one span for vector `x` (L, H or V); `m` is the number of pixels minus one.
pub fn span_setup(na: DVec3, nb: DVec3, x: DVec3, m: u32) -> FastSpan {
    let d = nb - na;
    let (g, s, c) = if m == 0 {
        (0.0, 0.0, 0.0)
    } else {
        let mf = m as f64;
        (
            d.dot(x) / mf,
            2.0 * d.dot(na) / mf,
            d.length_squared() / (mf * mf),
        )
    };
    FastSpan {
        m,
        b: na.dot(x),
        h: nb.dot(x),
        g,
        s,
        c,
    }
}

/// Per-pixel kernel over a span: the approximate N̂_x·X for x = 0..=m, computed two points per
/// step from both ends with `inv_sqrt` ≈ 1/√(M+1) (c2, c1, c0).
pub fn span_kernel(sp: &FastSpan, inv_sqrt: Coeffs) -> Vec<f64> {
    let m = sp.m as usize;
    let mut out = vec![0.0; m + 1];
    let (mut p_left, mut p_right) = (sp.b, sp.h);
    let mut big_m = 0.0; // M_x
    let mut x = 0usize;
    // Left pixel x and right pixel m − x share q_x; the middle pixel (m even) is computed once.
    while 2 * x <= m {
        let r = scale(big_m, inv_sqrt);
        out[x] = p_left * r;
        out[m - x] = p_right * r;
        p_left += sp.g;
        p_right -= sp.g;
        big_m += 2.0 * sp.c * x as f64 + (sp.c + sp.s);
        x += 1;
    }
    out
}

/// The fast method (SPEC §3) with 1/√(M+1) ≈ `inv_sqrt` ([`CHEBYSHEV`] or [`FIT`]).
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, inv_sqrt: Coeffs, emit: Emit) {
    shade_spans(tri, walk, ctx, emit, |na, nb, x, m| {
        span_kernel(&span_setup(na, nb, x, m), inv_sqrt)
    });
}

/// Shades a triangle span by span, as the span methods with a cosine kernel do (this one and
/// [`crate::shading::angular`]): per raster line the exactly normalized end normals N_a, N_b (software
/// set-up), then `kernel(N_a, N_b, X, m)`, the approximate N̂·X at the line's m + 1 pixels, for
/// X = L and for the specular vector; a line whose end normals vanish gets the ambient colour.
pub(crate) fn shade_spans(
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    emit: Emit,
    kernel: impl Fn(DVec3, DVec3, DVec3, u32) -> Vec<f64>,
) {
    let Some(plane) = tri.normal_plane() else {
        return;
    };
    let spec_vec = ctx.specular_vector();
    for row in walk.rows.iter().filter(|r| r.len > 0) {
        let Some((na, nb)) = span_end_normals(&plane, row) else {
            emit_row_ambient(row, ctx, emit);
            continue;
        };
        let m = row.len - 1;
        let diffuse = kernel(na, nb, ctx.light, m);
        let spec = spec_vec.map(|x| kernel(na, nb, x, m));
        for (i, x) in row_xs(row).enumerate() {
            let cos_s = spec.as_ref().map_or(0.0, |v| v[i]);
            let (d, s) = ctx.cosines(diffuse[i], cos_s);
            emit(x, row.y, ctx.combine(d, ctx.specular_power(s)));
        }
    }
}
