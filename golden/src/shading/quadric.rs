//! Quadric-surface shading with forward differences (SPEC §8, thesis §2.1).
//!
//! I(x, y) = A·x² + B·y² + C·x·y + D·x + E·y + F per colour channel, in coordinates relative to
//! the triangle's first vertex (so F = I₁). Set-up per triangle (software): exact lighting at
//! the three vertices (unit vertex normals) and at the three edge midpoints (normalized mean
//! of the two vertex normals: the reference normal there), then the 6×6 system solved by
//! Gaussian elimination with partial pivoting (the six nodes of a non-degenerate triangle
//! always determine the quadric).
//!
//! Kernel per raster line (hardware): the first pixel by the direct form (2.2) — the thesis
//! notes it is always needed — the second by (2.3), I(x+d) = I(x) + d·(2A·x + C·y + D) + A for a
//! step d = ±1 (the line's direction), and every further pixel by (2.5),
//! I(x+2d) = 2·I(x+d) − I(x) + 2A: two shifts and two adds, no multiplier. Pixel centres are at
//! (x + 0.5, y + 0.5). The result is rounded and clamped to 8 bits.

use crate::shade::{to_u8, unit, ShadeContext};
use crate::shading::{row_xs, Emit};
use crate::types::{Row, ScreenTriangle, Walk};

/// Per-triangle set-up: origin and the six coefficients per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadricSetup {
    /// The first vertex (x, y): the coordinate origin.
    pub origin: (f64, f64),
    /// `coeffs[c]` = [A, B, C, D, E, F] of channel c.
    pub coeffs: [[f64; 6]; 3],
}

/// The six sample points (relative to the origin) and their unit normals: vertices 1, 2, 3,
/// then the midpoints of edges 12, 13, 23.
pub fn nodes(tri: &ScreenTriangle) -> [((f64, f64), glam::DVec3); 6] {
    let (x0, y0) = tri.position(0);
    let p = |i: usize| (tri.position(i).0 - x0, tri.position(i).1 - y0);
    let mid = |i: usize, j: usize| {
        let (a, b) = (p(i), p(j));
        ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0)
    };
    let n = |i: usize| tri.v[i].normal.normalize_or_zero();
    let nm = |i: usize, j: usize| unit(tri.v[i].normal + tri.v[j].normal).unwrap_or_default();
    [
        (p(0), n(0)),
        (p(1), n(1)),
        (p(2), n(2)),
        (mid(0, 1), nm(0, 1)),
        (mid(0, 2), nm(0, 2)),
        (mid(1, 2), nm(1, 2)),
    ]
}

/// Set-up: sample intensities at the six nodes and solve for A..F per channel; `None` for a
/// zero-area triangle.
pub fn setup(tri: &ScreenTriangle, ctx: &ShadeContext) -> Option<QuadricSetup> {
    if tri.area2() == 0 {
        return None;
    }
    let nodes = nodes(tri);
    let rows: [[f64; 6]; 6] = nodes.map(|((x, y), _)| [x * x, y * y, x * y, x, y, 1.0]);
    let samples = nodes.map(|(_, n)| ctx.exact_intensity(n));
    let mut coeffs = [[0.0; 6]; 3];
    for (c, out) in coeffs.iter_mut().enumerate() {
        *out = crate::linalg::solve(rows, samples.map(|s| s[c]))?;
    }
    Some(QuadricSetup {
        origin: tri.position(0),
        coeffs,
    })
}

/// Direct form (2.2) at a continuous point relative to the origin.
pub fn direct(k: &[f64; 6], x: f64, y: f64) -> f64 {
    let [a, b, c, d, e, f] = *k;
    a * x * x + b * y * y + c * x * y + d * x + e * y + f
}

/// Kernel along one raster line for one channel: unclamped intensities in walk order.
pub fn row_kernel(setup: &QuadricSetup, channel: usize, row: &Row) -> Vec<f64> {
    let k = &setup.coeffs[channel];
    let (a, c, d) = (k[0], k[2], k[3]);
    let n = row.len as usize;
    let mut out = Vec::with_capacity(n);
    if n == 0 {
        return out;
    }
    let x0 = row.x_start as f64 + 0.5 - setup.origin.0;
    let y = row.y as f64 + 0.5 - setup.origin.1;
    let dir = row.dir as f64;
    out.push(direct(k, x0, y)); // (2.2)
    if n > 1 {
        out.push(out[0] + dir * (2.0 * a * x0 + c * y + d) + a); // (2.3)
    }
    for i in 2..n {
        out.push(2.0 * out[i - 1] - out[i - 2] + 2.0 * a); // (2.5)
    }
    out
}

/// Quadric shading (SPEC §8) of one triangle.
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    let Some(s) = setup(tri, ctx) else { return };
    for row in walk.rows.iter().filter(|r| r.len > 0) {
        let ch: [Vec<f64>; 3] = std::array::from_fn(|c| row_kernel(&s, c, row));
        for (i, x) in row_xs(row).enumerate() {
            emit(
                x,
                row.y,
                [to_u8(ch[0][i]), to_u8(ch[1][i]), to_u8(ch[2][i])],
            );
        }
    }
}
