//! Reference Phong shading and flat shading (SPEC §0).
//!
//! Reference ("etalon" of the thesis): the normal is interpolated linearly in screen space
//! ([`ScreenTriangle::normal_plane`]) and normalized exactly at every pixel; lighting by
//! Blinn (default), Phong (R·V) or Lambert, combined by [`ShadeContext::combine`].
//!
//! Flat: one colour per face, lit with the normalized mean of the three vertex normals (for a
//! mesh with smooth vertex normals this is the normal at the centroid, i.e. the reference
//! normal there; the geometric face normal would need the view-space positions, which a
//! [`ScreenTriangle`] does not carry).

use crate::shade::{unit, ShadeContext};
use crate::shading::{emit_row_ambient, row_xs, Emit};
use crate::types::{ScreenTriangle, VecPlane, Walk};
use glam::DVec3;

/// Set-up of the reference: the normal's planes (per triangle).
pub fn setup(tri: &ScreenTriangle) -> Option<VecPlane> {
    tri.normal_plane()
}

/// Per-pixel kernel of the reference: exact normalization and exact lighting.
pub fn pixel(plane: &VecPlane, ctx: &ShadeContext, x: i32, y: i32) -> [u8; 3] {
    match exact_cosines(plane, ctx, x, y) {
        Some((d, s)) => ctx.combine(d, ctx.specular_power(s)),
        None => ctx.combine(0.0, 0.0),
    }
}

/// The reference's per-pixel front end: (cos ψ, cos λ) from the exactly normalized
/// interpolated normal (`None` where it vanishes).
pub fn exact_cosines(plane: &VecPlane, ctx: &ShadeContext, x: i32, y: i32) -> Option<(f64, f64)> {
    unit(plane.at_pixel(x, y)).map(|n| ctx.exact_cosines(n))
}

/// Walk every pixel of `walk` with the reference's front end and colour it with `back_end`
/// (x, y, cos ψ, cos λ) → RGB. Methods that change only what follows the exact normal
/// (W(n, γ), the perturbed reflectance) share this loop; a vanishing normal gets ambient.
pub fn shade_exact_front_end(
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    emit: Emit,
    mut back_end: impl FnMut(i32, i32, f64, f64) -> [u8; 3],
) {
    let Some(plane) = setup(tri) else { return };
    for row in &walk.rows {
        for x in row_xs(row) {
            let rgb = match exact_cosines(&plane, ctx, x, row.y) {
                Some((d, s)) => back_end(x, row.y, d, s),
                None => ctx.combine(0.0, 0.0),
            };
            emit(x, row.y, rgb);
        }
    }
}

/// Reference Phong shading of one triangle.
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    shade_exact_front_end(tri, walk, ctx, emit, |_, _, d, s| {
        ctx.combine(d, ctx.specular_power(s))
    });
}

/// The flat-shading normal: normalized mean of the vertex normals (`None` if they cancel).
pub fn flat_normal(tri: &ScreenTriangle) -> Option<DVec3> {
    unit(tri.v.iter().map(|v| v.normal).sum::<DVec3>())
}

/// Flat shading: one colour for the whole face.
pub fn shade_flat(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    let Some(n) = flat_normal(tri) else {
        for row in &walk.rows {
            emit_row_ambient(row, ctx, emit);
        }
        return;
    };
    let (d, s) = ctx.exact_terms(n);
    let rgb = ctx.combine(d, s);
    for row in &walk.rows {
        for x in row_xs(row) {
            emit(x, row.y, rgb);
        }
    }
}
