//! Shading by subdivision (seed 001, the thesis' use of the four-triangle block, SPEC §7): a
//! triangle is split into four by its edge midpoints ([`crate::units::four_triangle`]); the normal
//! at each midpoint is the exactly normalized sum of the edge's two vertex normals, lit
//! exactly like a vertex; each sub-triangle is then Gouraud-shaded (one plane per channel
//! through its own three vertex intensities), over the pixels the four-triangle block gives it.
//!
//! The sub-triangles tile the parent's pixel set exactly (the fill rule in
//! [`crate::units::four_triangle`]), so the method writes the same pixels as every other method;
//! lane by lane, not in the parent's walk order.

use crate::raster::walk_subpixel;
use crate::shade::{to_u8, ShadeContext};
use crate::shading::Emit;
use crate::types::{Plane, ScreenTriangle, ScreenVertex, SubpixelTriangle};
use crate::units::four_triangle::{self, LANES};
use glam::DVec3;

/// Per-parent set-up: each lane's sub-triangle (at the parent's fraction bits + 1) and its
/// three channel planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubdivisionSetup {
    pub subs: [SubpixelTriangle; 4],
    /// `planes[lane][channel]`.
    pub planes: [[Plane; 3]; 4],
}

/// The parent's vertices sorted as [`crate::raster::orientation`] sorts them (by (y, x)).
fn sorted(tri: &ScreenTriangle) -> [ScreenVertex; 3] {
    let mut v = tri.v;
    v.sort_by_key(|p| (p.y, p.x));
    v
}

/// The normal at the midpoint of a and b: their sum, exactly normalized (a's normal if the
/// two cancel).
pub fn midpoint_normal(a: DVec3, b: DVec3) -> DVec3 {
    let s = a.normalize_or_zero() + b.normalize_or_zero();
    let u = s.normalize_or_zero();
    if u == DVec3::ZERO {
        a.normalize_or_zero()
    } else {
        u
    }
}

/// Set-up of `tri` (integer or sub-pixel vertices); `None` for a zero-area triangle.
pub fn setup(tri: &ScreenTriangle, ctx: &ShadeContext) -> Option<SubdivisionSetup> {
    let subs = four_triangle::subdivide_subpixel(&SubpixelTriangle::of(tri))?;
    let [t, m, b] = sorted(tri);
    let i = |n: DVec3| ctx.exact_intensity(n.normalize_or_zero());
    let (it, im, ib) = (i(t.normal), i(m.normal), i(b.normal));
    let (i_tm, i_tb, i_mb) = (
        i(midpoint_normal(t.normal, m.normal)),
        i(midpoint_normal(t.normal, b.normal)),
        i(midpoint_normal(m.normal, b.normal)),
    );
    // The lanes' vertices in `four_triangle::subdivide_subpixel`'s order.
    let values: [[[f64; 3]; 3]; 4] = [
        [it, i_tm, i_tb],
        [i_tm, im, i_mb],
        [i_tb, i_mb, ib],
        [i_tm, i_mb, i_tb],
    ];
    let mut planes = [[Plane {
        a: 0.0,
        b: 0.0,
        c: 0.0,
    }; 3]; 4];
    for k in 0..LANES {
        let unit = 1.0 / (1u32 << subs[k].frac) as f64;
        let p = subs[k].v.map(|(x, y)| (x as f64 * unit, y as f64 * unit));
        for c in 0..3 {
            planes[k][c] = Plane::through([
                (p[0].0, p[0].1, values[k][0][c]),
                (p[1].0, p[1].1, values[k][1][c]),
                (p[2].0, p[2].1, values[k][2][c]),
            ])?;
        }
    }
    Some(SubdivisionSetup { subs, planes })
}

/// Shade one parent: every pixel of each sub-triangle, lane by lane.
pub fn shade(tri: &ScreenTriangle, ctx: &ShadeContext, emit: Emit) {
    let Some(s) = setup(tri, ctx) else { return };
    for k in 0..LANES {
        for p in walk_subpixel(&s.subs[k]).pixels() {
            emit(p.x, p.y, s.planes[k].map(|pl| to_u8(pl.at_pixel(p.x, p.y))));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::walk;
    use std::collections::HashSet;

    #[test]
    fn same_pixels_as_the_parent_and_exact_at_the_vertices() {
        let n = |x: f64, y: f64| DVec3::new(x, y, 1.0).normalize();
        let mut tri = ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        tri.v[0].normal = n(-0.5, -0.4);
        tri.v[1].normal = n(0.6, -0.2);
        tri.v[2].normal = n(0.1, 0.7);
        let ctx = ShadeContext::default();
        let mut got = Vec::new();
        shade(&tri, &ctx, &mut |x, y, _| got.push((x, y)));
        let set: HashSet<_> = got.iter().copied().collect();
        assert_eq!(set.len(), got.len(), "a pixel twice");
        let parent: HashSet<_> = walk(&tri).pixels().iter().map(|p| (p.x, p.y)).collect();
        assert_eq!(set, parent);
        // Lane 0's plane takes the exact intensity at the parent's top vertex.
        let s = setup(&tri, &ctx).unwrap();
        let top = ctx.exact_intensity(tri.v[0].normal);
        let pl = s.planes[0][1];
        assert!((pl.a * 3.0 + pl.b * 1.0 + pl.c - top[1]).abs() < 1e-9);
        // And the midpoint of the top and middle vertices (a half-integer point): there the
        // normal is the bisector of the two unit normals, written out here (not through
        // `midpoint_normal`, which this checks; golden/tests/setup_independent.rs checks it
        // at every lane vertex).
        let (a, b) = (tri.v[0].normal, tri.v[1].normal);
        let sum = a / a.length() + b / b.length();
        let mid = ctx.exact_intensity(sum / sum.length());
        let pl = s.planes[1][2];
        assert!((pl.a * 21.5 + pl.b * 4.0 + pl.c - mid[2]).abs() < 1e-9);
    }
}
