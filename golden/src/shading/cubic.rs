//! Cubic-polynomial shading and the Horner unit (SPEC §9, thesis §2.2, fig. 2.6).
//!
//! On one raster line, per colour channel, I(p) = A·p³ + B·p² + C·p + D for p ∈ [0, 1] from the
//! first pixel centre (p = 0) to the last (p = 1), through four exactly lit samples
//! I1 = I(0), I2 = I(1), I3 = I(1/2), I4 = I(1/4) (the interpolated normal at those points,
//! exactly normalized). Set-up per line (software, shifts and adds plus one "division by 3"):
//! A = 8(I2 + 8·I4)/3 − 8(I1 + 2·I3), B = 2(7·I1 − I2 + 10·I3 − 16·I4),
//! C = (I2 + 32·I4)/3 − 7·I1 − 4·I3, D = I1, with 1/3 ≈ 1/2 − 1/8 − 1/32 − 1/128 ([`THIRD`]).
//!
//! **Grouping of the division.** Applied literally to (I2 + 8·I4) and (I2 + 32·I4), the 0.78%
//! error of [`THIRD`] is multiplied by the full intensity and does not cancel: for a constant
//! intensity I the printed grouping gives A = 0.1875·I and C = 0.0859·I instead of 0, i.e. 27%
//! too bright at p = 1 ([`coefficients_as_printed`]; `tests/methods.rs` shows it). We use the
//! algebraically identical grouping A = 8·(I2 + 8·I4 − 3·I1 − 6·I3)/3,
//! C = (I2 + 32·I4 − 21·I1 − 12·I3)/3, where the numerators are differences (zero for a
//! constant, small for smooth shading), so the approximation only perturbs A and C by 0.78%.
//! Same shift-and-add cost.
//!
//! Kernel (hardware, fig. 2.6): p advances by 1/m per pixel (m = pixels − 1, 1/m from the
//! set-up), and the Horner unit (MUL, Sm, register RG, multiplexers MX1/MX2, pass/zero block
//! BK) forms ((A·p + B)·p + C)·p + D over successive clocks.

use crate::shade::{to_u8, unit, ShadeContext};
use crate::shading::{row_end, row_xs, Emit};
use crate::types::{Row, ScreenTriangle, VecPlane, Walk};

/// 1/3 ≈ 1/2 − 1/8 − 1/32 − 1/128 = 0.3359375 (relative error +0.78125%).
pub const THIRD: f64 = 0.5 - 0.125 - 0.03125 - 0.0078125;

/// (A, B, C, D) from I1 = I(0), I2 = I(1), I3 = I(1/2), I4 = I(1/4), with `third` ≈ 1/3 applied
/// to the difference numerators (see the module doc).
pub fn coefficients(i1: f64, i2: f64, i3: f64, i4: f64, third: f64) -> [f64; 4] {
    let a = 8.0 * third * (i2 + 8.0 * i4 - 3.0 * i1 - 6.0 * i3);
    let b = 2.0 * (7.0 * i1 - i2 + 10.0 * i3 - 16.0 * i4);
    let c = third * (i2 + 32.0 * i4 - 21.0 * i1 - 12.0 * i3);
    [a, b, c, i1]
}

/// The coefficients exactly as the thesis prints them, with `third` applied to the sums
/// (I2 + 8·I4) and (I2 + 32·I4). Kept to document why [`coefficients`] regroups.
pub fn coefficients_as_printed(i1: f64, i2: f64, i3: f64, i4: f64, third: f64) -> [f64; 4] {
    let a = 8.0 * (i2 + 8.0 * i4) * third - 8.0 * (i1 + 2.0 * i3);
    let b = 2.0 * (7.0 * i1 - i2 + 10.0 * i3 - 16.0 * i4);
    let c = (i2 + 32.0 * i4) * third - 7.0 * i1 - 4.0 * i3;
    [a, b, c, i1]
}

/// The Horner unit: ((A·p + B)·p + C)·p + D.
pub fn horner(k: &[f64; 4], p: f64) -> f64 {
    ((k[0] * p + k[1]) * p + k[2]) * p + k[3]
}

/// Per-line set-up: the four exact samples and A..D per channel (`coeffs[c]`), and m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicSpan {
    pub m: u32,
    pub coeffs: [[f64; 4]; 3],
}

/// The four exactly lit samples of one non-empty raster line per channel: `[c]` = [I(0), I(1),
/// I(1/2), I(1/4)] of channel c (the set-up's input; a vanishing normal gets the ambient colour).
pub fn span_samples(plane: &VecPlane, row: &Row, ctx: &ShadeContext) -> [[f64; 4]; 3] {
    let na = plane.at_pixel(row.x_start, row.y);
    let nb = plane.at_pixel(row_end(row), row.y);
    // The plane is linear, so the normal at fraction p of the span is na + p·(nb − na).
    let sample = |p: f64| match unit(na + (nb - na) * p) {
        Some(n) => ctx.exact_intensity(n),
        None => ctx.intensity(0.0, 0.0),
    };
    let (i1, i2, i3, i4) = (sample(0.0), sample(1.0), sample(0.5), sample(0.25));
    std::array::from_fn(|c| [i1[c], i2[c], i3[c], i4[c]])
}

/// Set-up of one non-empty raster line.
pub fn span_setup(plane: &VecPlane, row: &Row, ctx: &ShadeContext) -> CubicSpan {
    let s = span_samples(plane, row, ctx);
    let coeffs = std::array::from_fn(|c| coefficients(s[c][0], s[c][1], s[c][2], s[c][3], THIRD));
    CubicSpan {
        m: row.len - 1,
        coeffs,
    }
}

/// Kernel: unclamped intensities of the line's pixels (p = i/m), per channel.
pub fn span_kernel(sp: &CubicSpan) -> Vec<[f64; 3]> {
    let step = if sp.m == 0 { 0.0 } else { 1.0 / sp.m as f64 };
    (0..=sp.m)
        .map(|i| sp.coeffs.map(|k| horner(&k, i as f64 * step)))
        .collect()
}

/// Cubic shading (SPEC §9) of one triangle.
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    let Some(plane) = tri.normal_plane() else {
        return;
    };
    for row in walk.rows.iter().filter(|r| r.len > 0) {
        let values = span_kernel(&span_setup(&plane, row, ctx));
        for (x, v) in row_xs(row).zip(values) {
            emit(x, row.y, v.map(to_u8));
        }
    }
}
