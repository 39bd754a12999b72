//! Bump effect by perturbing the reflectance function instead of the normal (SPEC §2, seed 000
//! formula (2), block BRZSSK of patent 60139):
//! cos^n(γ ± dγ) = (cos γ·cos dγ ∓ sin γ·sin dγ)^n, and the diffuse term the same way from
//! cos φ = N̂·L. No perturbed normal is built or normalized.
//!
//! The block has no trigonometric units; everything trigonometric comes from a PROM, as the
//! hardware (`rtl/src/units/brzssk.rs`) holds it — every word unsigned Q1.15:
//! - sin γ for the given cos γ ([`SinProm`]: the address is cos γ ∈ [0, 1] truncated to
//!   [`SIN_ADDR_BITS`] fraction bits, the word sin(arccos(address)) rounded to Q1.15 beside its
//!   difference to the next word, and the next [`SIN_INTERP_BITS`] bits of cos γ interpolate
//!   linearly between the two: sin γ near cos γ = 1 is steep, and the power n after it would
//!   turn a PROM step into a visible ring); the diffuse term's sin φ comes from a smaller PROM
//!   of [`SIN_PHI_ADDR_BITS`] rounded address bits, without interpolation (no power follows it);
//! - cos dγ and sin dγ for the perturbation code ([`BumpMap::code`]: a sign bit, held by the
//!   trigger TG, and an unsigned magnitude of [`CODE_BITS`] bits).
//!
//! The cosines enter clamped at 0, as the lighting unit delivers them (a surface turned away
//! from the light or the half vector is perturbed from 0, not from its negative cosine).
//!
//! Then two multipliers and an add/subtract selected by TG form cos(γ ± dγ), which is raised to
//! n (square-and-multiply over the bits of n; exact power here) and scaled by k_s·I_l.
//!
//! The perturbation map is procedural and lives in screen space (the hardware's pixel address
//! is what it has; the golden scenes carry no texture coordinates): an egg-crate
//! dγ(x, y) = D·sin(2πx/P)·sin(2πy/P) (x, y the integer pixel address) with amplitude D = [`BumpMap::default`]'s 0.12 rad and
//! period P = 16 pixels, so the code of a pixel depends on its address modulo 16 (a 256-entry
//! code ROM in hardware). The base normal comes from the hardware's front end: the vector
//! interpolator and the normalizer with the fitted coefficients
//! (`crate::units::normalizer::shade_front_end`); the specular power is the exact cos^n.

use crate::shade::ShadeContext;
use crate::shading::Emit;
use crate::types::{ScreenTriangle, Walk};
use std::f64::consts::TAU;

/// Address fraction bits of the sin γ PROM (2048 words of 27 bits: 14 iCE40 block RAMs).
pub const SIN_ADDR_BITS: u32 = 11;
/// Bits of cos γ below the sin γ PROM's address that interpolate between its words.
pub const SIN_INTERP_BITS: u32 = 4;
/// Address fraction bits of the sin φ PROM (1025 words).
pub const SIN_PHI_ADDR_BITS: u32 = 10;

/// `v` rounded to the nearest unsigned Q1.15 word (ties up), as a real.
pub fn q15(v: f64) -> f64 {
    (v * 32768.0 + 0.5).floor() / 32768.0
}

/// Magnitude bits of the perturbation code (plus one sign bit).
pub const CODE_BITS: u32 = 8;

/// The PROM word for sin γ, addressed by cos γ ∈ [0, 1]: rounded to `addr_bits` fraction bits
/// when `interp_bits` is 0; otherwise truncated to them, the next `interp_bits` bits (after
/// rounding cos γ to `addr_bits + interp_bits`) interpolating linearly to the next word.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SinProm {
    pub addr_bits: u32,
    pub interp_bits: u32,
}

impl SinProm {
    /// Largest address: cos γ = 1 (2^addr_bits).
    pub fn top(&self) -> f64 {
        (1u64 << self.addr_bits) as f64
    }
    /// Address of cos γ: clamp to [0, 1], then round to nearest (ties up) in 2^-addr_bits.
    pub fn address(&self, cos_gamma: f64) -> i64 {
        (cos_gamma.clamp(0.0, 1.0) * self.top() + 0.5).floor() as i64
    }
    /// The stored word: sin(arccos(address/top)) rounded to Q1.15.
    pub fn word(&self, address: i64) -> f64 {
        let c = address as f64 / self.top();
        q15((1.0 - c * c).max(0.0).sqrt())
    }
    /// sin γ for cos γ, as the PROM (and its interpolator) delivers it.
    pub fn sin(&self, cos_gamma: f64) -> f64 {
        let f = self.interp_bits;
        if f == 0 {
            return self.word(self.address(cos_gamma));
        }
        let scale = (1u64 << (self.addr_bits + f)) as f64;
        let u = (cos_gamma.clamp(0.0, 1.0) * scale + 0.5).floor() as i64;
        let (a, frac) = (u >> f, u & ((1 << f) - 1));
        if a >= 1 << self.addr_bits {
            return 0.0;
        }
        let (s0, s1) = (self.word(a), self.word(a + 1));
        let d = ((s0 - s1) * 32768.0).round() as i64;
        s0 - ((d * frac + (1 << (f - 1))) >> f) as f64 / 32768.0
    }
}

/// The procedural perturbation map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BumpMap {
    /// Largest |dγ|, radians.
    pub amplitude: f64,
    /// Period of the pattern, pixels.
    pub period: f64,
}

impl Default for BumpMap {
    fn default() -> Self {
        BumpMap {
            amplitude: 0.12,
            period: 16.0,
        }
    }
}

/// A perturbation code: sign (the trigger TG) and magnitude (PROM address).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Code {
    pub negative: bool,
    pub magnitude: u32,
}

impl BumpMap {
    /// dγ at the corner (x, y) of the pixel grid, before quantization: sampled on the grid
    /// itself so that the 16-pixel period holds exactly dγ = 0 (x or y ≡ 0, 8) and both
    /// extremes ±D (x, y ≡ 4, 12).
    pub fn d_gamma(&self, x: i32, y: i32) -> f64 {
        let (px, py) = (x as f64, y as f64);
        self.amplitude * (TAU * px / self.period).sin() * (TAU * py / self.period).sin()
    }
    /// The stored code of pixel (x, y).
    pub fn code(&self, x: i32, y: i32) -> Code {
        let d = self.d_gamma(x, y);
        let top = ((1u32 << CODE_BITS) - 1) as f64;
        let magnitude = (d.abs() / self.amplitude * top).round().min(top) as u32;
        Code {
            negative: d < 0.0,
            magnitude,
        }
    }
    /// The PROM words (cos dγ, sin |dγ|) of a code, each rounded to Q1.15.
    pub fn prom(&self, code: Code) -> (f64, f64) {
        let top = ((1u32 << CODE_BITS) - 1) as f64;
        let angle = code.magnitude as f64 / top * self.amplitude;
        (q15(angle.cos()), q15(angle.sin()))
    }
}

/// Per-pixel kernel: cos(γ + dγ) from cos γ (clamped at 0 first) and the code, without
/// trigonometric units.
pub fn perturb(cos_gamma: f64, code: Code, map: &BumpMap, prom: &SinProm) -> f64 {
    let cos_gamma = cos_gamma.max(0.0);
    let (cos_d, sin_d) = map.prom(code);
    let sin_g = prom.sin(cos_gamma);
    let product = sin_g * sin_d;
    // TG: cos(γ + dγ) = cos γ cos dγ − sin γ sin dγ; a negative dγ turns it into an add.
    if code.negative {
        cos_gamma * cos_d + product
    } else {
        cos_gamma * cos_d - product
    }
}

/// The default PROMs: (sin φ, sin γ).
pub fn default_proms() -> (SinProm, SinProm) {
    (
        SinProm {
            addr_bits: SIN_PHI_ADDR_BITS,
            interp_bits: 0,
        },
        SinProm {
            addr_bits: SIN_ADDR_BITS,
            interp_bits: SIN_INTERP_BITS,
        },
    )
}

/// Bump shading of one triangle with the default map and PROMs.
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    let (phi, gamma) = default_proms();
    shade_with(tri, walk, ctx, &BumpMap::default(), &phi, &gamma, emit)
}

/// Bump shading with a given map and PROMs (sin φ, sin γ), behind the hardware's front end.
pub fn shade_with(
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    map: &BumpMap,
    prom_phi: &SinProm,
    prom_gamma: &SinProm,
    emit: Emit,
) {
    let fit = crate::units::normalizer::FIT;
    crate::units::normalizer::shade_front_end(tri, walk, ctx, fit, emit, |x, y, d, s| {
        let code = map.code(x, y);
        let d = perturb(d, code, map, prom_phi);
        let s = perturb(s, code, map, prom_gamma);
        ctx.combine(d, ctx.specular_power(s))
    });
}
