//! Gouraud shading: exact lighting at the three vertices, intensities interpolated linearly in
//! screen space, one plane per colour channel (the intensity interpolator BVI of SPEC §6
//! accumulates exactly these planes' increments along the walk).

use crate::shade::{to_u8, ShadeContext};
use crate::shading::{row_xs, Emit};
use crate::types::{Plane, ScreenTriangle, Walk};

/// Per-triangle set-up: the vertex intensities and their planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GouraudSetup {
    /// `vertex[i][c]`: intensity of channel c at vertex i, 0..255 scale, unclamped.
    pub vertex: [[f64; 3]; 3],
    /// `planes[c]`: screen-space plane of channel c.
    pub planes: [Plane; 3],
}

/// Exact lighting at the vertices (unit vertex normals): `[vertex][channel]`, unclamped.
pub fn vertex_intensities(tri: &ScreenTriangle, ctx: &ShadeContext) -> [[f64; 3]; 3] {
    tri.v
        .map(|v| ctx.exact_intensity(v.normal.normalize_or_zero()))
}

/// Set-up: vertex intensities and one plane per channel; `None` for a zero-area triangle.
pub fn setup(tri: &ScreenTriangle, ctx: &ShadeContext) -> Option<GouraudSetup> {
    let vertex = vertex_intensities(tri, ctx);
    let p0 = tri.scalar_plane([vertex[0][0], vertex[1][0], vertex[2][0]])?;
    let p1 = tri.scalar_plane([vertex[0][1], vertex[1][1], vertex[2][1]])?;
    let p2 = tri.scalar_plane([vertex[0][2], vertex[1][2], vertex[2][2]])?;
    Some(GouraudSetup {
        vertex,
        planes: [p0, p1, p2],
    })
}

/// Unclamped interpolated intensity at a pixel centre.
pub fn intensity(setup: &GouraudSetup, x: i32, y: i32) -> [f64; 3] {
    setup.planes.map(|p| p.at_pixel(x, y))
}

/// Per-pixel kernel: interpolated intensity, rounded and clamped to 8 bits.
pub fn pixel(setup: &GouraudSetup, x: i32, y: i32) -> [u8; 3] {
    intensity(setup, x, y).map(to_u8)
}

/// Gouraud shading of one triangle.
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    let Some(s) = setup(tri, ctx) else { return };
    for row in &walk.rows {
        for x in row_xs(row) {
            emit(x, row.y, pixel(&s, x, row.y));
        }
    }
}
