//! Lighting unit (SPEC §0 Blinn/Lambert with the SPEC §1 normalizer in front), the golden of
//! `rtl/src/units/lighting_unit.rs`: N' = N·f(|N|²), then cos φ = N'·L and cos γ = N'·H (Blinn's
//! half vector), each clamped to [0, 2). Lambert uses only cos φ (the colour combine's
//! specular weights are zero); Phong's R·V is not built in hardware.
//!
//! Not a shading method: the per-pixel kernel of the normalizer, `brdf-k*` and `bump` RTL
//! paths. L and H are unit vectors held as signed Q2.14 words; cosines come out unsigned Q1.15.

use crate::units::normalizer::{normalize, Scale};
use glam::DVec3;

/// Fraction bits of the cosine outputs (unsigned Q1.15).
pub const COS_FRAC_BITS: u32 = 15;
/// Largest cosine the output holds (2 − 2⁻¹⁵); larger values saturate.
pub const COS_MAX: f64 = 2.0 - 1.0 / 32768.0;

/// The f64 lighting of an interpolated normal `n`: (cos φ, cos γ) = (N'·L, N'·H) with
/// N' = n·f(|n|²), each clamped to [0, [`COS_MAX`]].
pub fn cosines(n: DVec3, light: DVec3, half: DVec3, c: impl Into<Scale>) -> (f64, f64) {
    let np = normalize(n, c);
    let clamp = |v: f64| v.clamp(0.0, COS_MAX);
    (clamp(np.dot(light)), clamp(np.dot(half)))
}

/// The bound on |cos_hw − cos| given a bound `component` on each component of N'_hw − N' and
/// the unit vector `u` it is dotted with: Σ|u_i|·component (≤ √3·component) plus the output
/// rounding (half an LSB, 2⁻¹⁶) and the floors of the three products' low parts (each
/// < 2⁻²⁸, see the twin's D1). The sums are exact.
pub fn error_bound(component: f64, u: DVec3) -> f64 {
    (u.x.abs() + u.y.abs() + u.z.abs()) * component
        + (-(COS_FRAC_BITS as f64 + 1.0)).exp2()
        + 3.0 * (-28f64).exp2()
}

/// Bit-exact integer twin of `rtl/src/units/lighting_unit.rs`, from its header: the normalizer
/// ([`crate::units::normalizer::twin::NormalizerTwin`], latency 15), then
///
/// ```text
/// D1 p = N'_i·L_i, N'_i·H_i          six signed Q2.17 × Q2.14 products in Q4.28, four clocks
///                                    (ready four registers on): N' split into ⌊N'/8⌋ (exact
///                                    product) and N' − 8·⌊N'/8⌋ (product floored by 8)
/// D2 s = Σ p                         exact (34 bits), registered
/// D3 cos = sat(round(s: Q4.28 → UQ1.15))   +2¹², drop 13 bits, negative → 0, ≥ 2 → 0xFFFF
/// ```
/// L and H are the words present when the pixel enters D1.
pub mod twin {
    use crate::units::normalizer::twin::NormalizerTwin;
    use crate::units::normalizer::Scale;

    /// Round a Q4.28 sum to unsigned Q1.15: add half an LSB, drop 13 bits, clamp.
    pub fn narrow(sum: i64) -> i64 {
        ((sum + (1 << 12)) >> 13).clamp(0, 0xFFFF)
    }

    #[derive(Clone, Debug)]
    pub struct LightingTwin {
        norm: NormalizerTwin,
        /// D1's first three registers.
        prod_a: [[i64; 6]; 3],
        prod: [i64; 6],
        sum: [i64; 2],
        cos: [i64; 2],
        valid: [bool; 6],
    }

    impl LightingTwin {
        pub fn new(c: impl Into<Scale>) -> Self {
            Self {
                norm: NormalizerTwin::new(c),
                prod_a: [[0; 6]; 3],
                prod: [0; 6],
                sum: [0; 2],
                cos: [0; 2],
                valid: [false; 6],
            }
        }
        /// (valid_out, cos φ, cos γ as unsigned Q1.15 integers) shown this clock.
        pub fn outputs(&self) -> (bool, i64, i64) {
            (self.valid[5], self.cos[0], self.cos[1])
        }
        /// One rising edge: `v` the interpolated normal (signed Q2.17 integers), `l` and `h`
        /// the light and half vectors (signed Q2.14 integers).
        pub fn clock(&mut self, valid_in: bool, v: [i64; 3], l: [i64; 3], h: [i64; 3]) {
            let (nv, n) = self.norm.outputs();
            self.cos = [narrow(self.sum[0]), narrow(self.sum[1])];
            self.sum = [
                self.prod[0] + self.prod[1] + self.prod[2],
                self.prod[3] + self.prod[4] + self.prod[5],
            ];
            self.prod = self.prod_a[2];
            self.prod_a[2] = self.prod_a[1];
            self.prod_a[1] = self.prod_a[0];
            // N' (Q2.17) · u (Q2.14) in Q4.28: the high part exact, the low part floored.
            let p = |n: i64, u: i64| (n >> 3) * u + (((n & 7) * u) >> 3);
            self.prod_a[0] = [
                p(n[0], l[0]),
                p(n[1], l[1]),
                p(n[2], l[2]),
                p(n[0], h[0]),
                p(n[1], h[1]),
                p(n[2], h[2]),
            ];
            self.valid = [
                nv,
                self.valid[0],
                self.valid[1],
                self.valid[2],
                self.valid[3],
                self.valid[4],
            ];
            self.norm.clock(valid_in, v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn narrow_rounds_and_saturates() {
        assert_eq!(twin::narrow(1 << 28), 0x8000, "1.0");
        assert_eq!(twin::narrow(-1), 0, "negative clamps to 0");
        assert_eq!(twin::narrow((1 << 12) - 1), 0, "below half an LSB");
        assert_eq!(twin::narrow(1 << 12), 1, "half an LSB rounds up");
        assert_eq!(twin::narrow(3 << 28), 0xFFFF, "3.0 saturates");
        let (d, s) = cosines(DVec3::Z, DVec3::Z, -DVec3::Z, crate::units::normalizer::FIT);
        assert!((d - 1.0).abs() < 1e-12 && s == 0.0);
    }
}
