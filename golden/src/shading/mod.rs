//! The shading methods of the sources as whole-frame golden renderers (each pixel in f64), and the set-up software they share (subdivision, refinement).
//!
//! This file holds what the methods share: where a method sends its pixels ([`Emit`]) and the
//! row helpers.

pub mod angular;
pub mod brdf;
pub mod bump;
pub mod cubic;
pub mod fast;
pub mod gouraud;
pub mod phong;
pub mod quadric;
pub mod refine;
pub mod subdivision;
pub mod texture;

use crate::shade::ShadeContext;
use crate::types::{Row, VecPlane};
use glam::DVec3;

/// Where a method sends its pixels: (x, y, colour).
pub type Emit<'a> = &'a mut dyn FnMut(i32, i32, [u8; 3]);

/// The pixels of one raster line in walk order: `x_start + i·dir`, i in 0..len.
pub fn row_xs(row: &Row) -> impl Iterator<Item = i32> + '_ {
    (0..row.len as i32).map(move |i| row.x_start + i * row.dir as i32)
}

/// x of the last pixel of a non-empty raster line.
pub fn row_end(row: &Row) -> i32 {
    row.x_start + (row.len as i32 - 1) * row.dir as i32
}

/// Span set-up shared by the span methods (fast, angular, cubic): the exactly normalized
/// interpolated normals at the first and last pixel of the line (software side). `None` when
/// either is zero (only possible with opposite vertex normals).
pub fn span_end_normals(plane: &VecPlane, row: &Row) -> Option<(DVec3, DVec3)> {
    let a = crate::shade::unit(plane.at_pixel(row.x_start, row.y))?;
    let b = crate::shade::unit(plane.at_pixel(row_end(row), row.y))?;
    Some((a, b))
}

/// Emit the ambient-only colour for every pixel of a row (used when a set-up degenerates).
pub(crate) fn emit_row_ambient(row: &Row, ctx: &ShadeContext, emit: Emit) {
    let rgb = ctx.combine(0.0, 0.0);
    for x in row_xs(row) {
        emit(x, row.y, rgb);
    }
}
