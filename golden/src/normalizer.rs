//! Normalizer without division or square root (SPEC §1, Ukrainian patent 63343):
//! N' = N · f(K), f(K) = c2·K² + c1·K + c0, K = x² + y² + z², valid for K ∈ [0.499, 1];
//! and the multiplier-free K recurrence along a raster line.

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
