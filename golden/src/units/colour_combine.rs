//! Colour combine (SPEC §0), the golden of `rtl/src/units/colour_combine.rs`:
//! I_c = I_a·k_a·D_c + I_l·(k_d·D_c·cos φ + k_s·S_c·S) per channel, into TrueColor 8 bits,
//! rounded to nearest and saturated — [`crate::shade::ShadeContext::combine`] with the three
//! per-channel weights as hardware registers.
//!
//! The weights (`amb` = k_a·D_c, `dif` = k_d·D_c, `spc` = k_s·S_c, with white lights) are
//! unsigned Q8.8 words (0 ≤ w < 256); the cosines and S come in unsigned Q1.15.

use crate::shade::{LightingModel, ShadeContext};

/// Fraction bits of the weight words (unsigned Q8.8).
pub const WEIGHT_FRAC_BITS: u32 = 8;

/// The nine weights of a material and lighting model, as reals: (amb, dif, spc) per channel.
/// Lambert's specular weights are 0 (it drops the specular term).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weights {
    pub amb: [f64; 3],
    pub dif: [f64; 3],
    pub spc: [f64; 3],
}

/// A weight that the Q8.8 register cannot hold.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("colour weight {name} = {value} does not fit the colour combine's unsigned Q8.8 register (0 to 255.996)")]
pub struct WeightRange {
    pub name: String,
    pub value: f64,
}

impl Weights {
    /// The weights of `ctx` (white lights: I_a = I_l = 1).
    pub fn of(ctx: &ShadeContext) -> Weights {
        let m = &ctx.material;
        let lambert = ctx.lighting == LightingModel::Lambert;
        Weights {
            amb: m.diffuse.map(|d| m.ka * d),
            dif: m.diffuse.map(|d| m.kd * d),
            spc: m.specular.map(|s| if lambert { 0.0 } else { m.ks * s }),
        }
    }

    /// The nine register words (amb r g b, dif r g b, spc r g b), each rounded to nearest
    /// Q8.8; an error names the first weight out of range.
    pub fn words(&self) -> Result<[u64; 9], WeightRange> {
        let all = [self.amb, self.dif, self.spc].concat();
        let names = ["amb", "dif", "spc"];
        let mut out = [0u64; 9];
        for (i, v) in all.iter().enumerate() {
            let w = (v * (WEIGHT_FRAC_BITS as f64).exp2() + 0.5).floor();
            if !(0.0..65536.0).contains(&w) {
                return Err(WeightRange {
                    name: format!("{}_{}", names[i / 3], ["r", "g", "b"][i % 3]),
                    value: *v,
                });
            }
            out[i] = w as u64;
        }
        Ok(out)
    }

    /// The weights the words hold (what the hardware computes with).
    pub fn from_words(w: &[u64; 9]) -> Weights {
        let f = |i: usize| w[i] as f64 / (WEIGHT_FRAC_BITS as f64).exp2();
        Weights {
            amb: [f(0), f(1), f(2)],
            dif: [f(3), f(4), f(5)],
            spc: [f(6), f(7), f(8)],
        }
    }
}

/// The unrounded channel intensities amb + dif·cos φ + spc·S (cos φ, S ≥ 0).
pub fn intensity(w: &Weights, cos_phi: f64, spec: f64) -> [f64; 3] {
    std::array::from_fn(|c| w.amb[c] + w.dif[c] * cos_phi + w.spc[c] * spec)
}

/// Bit-exact integer twin of `rtl/src/units/colour_combine.rs`, from its header:
///
/// ```text
/// C1 pd = dif·cos φ, ps = spc·S          UQ8.8 × UQ1.15 → UQ9.23, exact (six products),
///                                        two clocks
/// C2 sum = amb·2¹⁵ + pd + ps              UQ11.23 in 34 bits, exact, registered
/// C3 rgb = sum + 2²²: ≥ 256 → 255, else bits 30..23 (round to nearest, ties up)
/// ```
/// The weights are the words present when a pixel enters C1 (dif, spc) and C2 (amb).
pub mod twin {
    /// Round a UQ11.23 sum (half LSB not yet added) to 8 bits, saturating at 255.
    pub fn narrow(sum: u64) -> u64 {
        ((sum + (1 << 22)) >> 23).min(255)
    }

    #[derive(Clone, Debug, Default)]
    pub struct ColourTwin {
        /// C1's first register (the products of the words that entered a clock ago).
        pd_a: [u64; 3],
        ps_a: [u64; 3],
        pd: [u64; 3],
        ps: [u64; 3],
        /// C2: the exact sum before the half LSB.
        sum: [u64; 3],
        rgb: [u64; 3],
        valid: [bool; 4],
    }

    impl ColourTwin {
        /// (valid_out, [r, g, b]) shown this clock.
        pub fn outputs(&self) -> (bool, [u64; 3]) {
            (self.valid[3], self.rgb)
        }
        /// One rising edge: cosines as UQ1.15 words, `w` the nine weight words.
        pub fn clock(&mut self, valid_in: bool, cos_phi: u64, spec: u64, w: &[u64; 9]) {
            self.rgb = self.sum.map(narrow);
            self.sum = std::array::from_fn(|c| (w[c] << 15) + self.pd[c] + self.ps[c]);
            self.pd = self.pd_a;
            self.ps = self.ps_a;
            self.pd_a = std::array::from_fn(|c| w[3 + c] * cos_phi);
            self.ps_a = std::array::from_fn(|c| w[6 + c] * spec);
            self.valid = [valid_in, self.valid[0], self.valid[1], self.valid[2]];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_of_the_default_material() {
        let w = Weights::of(&ShadeContext::default());
        let words = w.words().unwrap();
        assert_eq!(words[3], 64 << 8, "dif_r = 64");
        assert_eq!(words[6], 255 << 8, "spc_r = 255");
        assert_eq!(
            words[0],
            (50.0 / 255.0 * 64.0 * 256.0 + 0.5f64).floor() as u64
        );
        let mut ctx = ShadeContext::default();
        ctx.material.ks = 2.0;
        let e = Weights::of(&ctx).words().unwrap_err();
        assert_eq!(e.name, "spc_r");
        assert_eq!(twin::narrow(255 << 23), 255);
        assert_eq!(
            twin::narrow((255 << 23) + (1 << 22)),
            255,
            "255.5 saturates"
        );
        assert_eq!(twin::narrow((1 << 22) - 1), 0);
        assert_eq!(twin::narrow(1 << 22), 1, "ties round up");
    }
}
