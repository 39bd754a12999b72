//! Angular interpolation and the cos v accumulator (SPEC §4, thesis §3.2–3.3).
//!
//! On a raster line with unit end normals N_A (pixel t = 0) and N_B (t = m) the normal turns by
//! φ = arccos(N_A·N_B) at the constant rate Δφ = φ/m. For a constant unit vector X (L, H or V)
//! the spherical Pythagoras theorem gives cos v(t) = N̂(t)·X = cos β · cos(ψ − t·Δφ), with
//! cos α = X·N_A, cos λ = X·N_B,
//! cos β = √[(cos²λ − 2·cos λ·cos α·cos φ + cos²α)/(1 − cos²φ)] (β: angle between X and the
//! plane of N_A, N_B) and cos ψ = cos α / cos β (ψ: angle from N_A to X's projection E).
//!
//! Set-up per span (software): arccos, the division, the root. The thesis' cos ψ = cos α/cos β
//! leaves the sign of ψ open; we take it from the in-plane component
//! (cos λ − cos α·cos φ)/sin φ, negative when E lies beyond N_A (outside the arc).
//!
//! Kernel (hardware, fig. 3.6): the accumulating adder PSm in subtract mode holds ψ − t·Δφ and
//! addresses a PROM of cos x; one multiplier forms cos β·PROM(arg). It stops when the argument
//! goes negative (borrow out); the adder is then reloaded with φ − ψ and the rest of the span
//! is produced from the N_B end (cos is even, so the arguments there are |ψ − t·Δφ|). The two
//! parts can run side by side (two pixels per clock). The golden PROM is exact cos.
//!
//! Span end normals: the exactly normalized interpolated normals at the first and last pixel
//! ([`crate::methods::span_end_normals`]). The thesis' alternative set-up — edge angles
//! accumulated along the edges (τ_i, μ_i) and cos φ_i from the spherical law of cosines — is
//! another software route to the same end normals (angle-linear along the edges) and is not
//! needed by the per-pixel hardware.

use crate::shade::ShadeContext;
use crate::shading::Emit;
use crate::types::{ScreenTriangle, Walk};
use glam::DVec3;

/// Per-span, per-vector set-up (software side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngularSpan {
    /// Span length m = pixels − 1.
    pub m: u32,
    /// cos β (≥ 0).
    pub cos_beta: f64,
    /// ψ, signed, radians.
    pub psi: f64,
    /// φ = arccos(N_A·N_B), radians.
    pub phi: f64,
    /// Δφ = φ/m.
    pub delta_phi: f64,
}

/// Below this sin φ the end normals are treated as parallel (cos v constant on the span).
const PARALLEL: f64 = 1e-9;

/// Set-up of one span for the unit vector `x`.
pub fn span_setup(na: DVec3, nb: DVec3, x: DVec3, m: u32) -> AngularSpan {
    let cos_phi = na.dot(nb).clamp(-1.0, 1.0);
    let cos_alpha = x.dot(na);
    let cos_lambda = x.dot(nb);
    let sin2_phi = 1.0 - cos_phi * cos_phi;
    if m == 0 || sin2_phi.sqrt() < PARALLEL {
        // N_A = N_B: cos v = cos α all along; encoded as ψ = 0, Δφ = 0, cos β = cos α.
        return AngularSpan {
            m,
            cos_beta: cos_alpha,
            psi: 0.0,
            phi: 0.0,
            delta_phi: 0.0,
        };
    }
    let phi = cos_phi.acos();
    let radicand = (cos_lambda * cos_lambda - 2.0 * cos_lambda * cos_alpha * cos_phi
        + cos_alpha * cos_alpha)
        / sin2_phi;
    let cos_beta = radicand.max(0.0).sqrt();
    let psi = if cos_beta == 0.0 {
        0.0 // X ⟂ the plane: cos v = 0 whatever ψ is
    } else {
        let cos_psi = (cos_alpha / cos_beta).clamp(-1.0, 1.0);
        let in_plane = cos_lambda - cos_alpha * cos_phi; // ∝ sin ψ (sin φ > 0)
        cos_psi.acos().copysign(in_plane)
    };
    AngularSpan {
        m,
        cos_beta,
        psi,
        phi,
        delta_phi: phi / m as f64,
    }
}

/// The PROM of the block: cos of the accumulator's argument.
pub fn prom_cos(arg: f64) -> f64 {
    arg.cos()
}

/// Per-pixel kernel over a span: cos v(t) for t = 0..=m, produced by the two accumulator runs.
pub fn span_kernel(sp: &AngularSpan) -> Vec<f64> {
    let m = sp.m as usize;
    let mut out = vec![0.0; m + 1];
    // Run 1, from N_A: argument ψ − t·Δφ while it stays ≥ 0.
    let mut arg = sp.psi;
    let mut t = 0usize;
    while t <= m && arg >= 0.0 {
        out[t] = sp.cos_beta * prom_cos(arg);
        arg -= sp.delta_phi;
        t += 1;
    }
    // Run 2, from N_B: the adder reloaded with φ − ψ, counting down towards E.
    let mut arg = sp.phi - sp.psi;
    let mut u = m;
    while u >= t && u <= m {
        out[u] = sp.cos_beta * prom_cos(arg);
        arg -= sp.delta_phi;
        if u == 0 {
            break;
        }
        u -= 1;
    }
    out
}

/// Angular interpolation (SPEC §4) of one triangle.
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    crate::shading::fast::shade_spans(tri, walk, ctx, emit, |na, nb, x, m| {
        span_kernel(&span_setup(na, nb, x, m))
    });
}
