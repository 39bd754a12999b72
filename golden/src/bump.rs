//! Bump effect by perturbing the reflectance function instead of the normal (SPEC §2, seed 000
//! formula (2), block BRZSSK of patent 60139):
//! cos^n(γ ± dγ) = (cos γ·cos dγ ∓ sin γ·sin dγ)^n, and the diffuse term the same way from
//! cos φ = N̂·L. No perturbed normal is built or normalized.
//!
//! The block has no trigonometric units; everything trigonometric comes from a PROM:
//! - sin γ for the given cos γ ([`SinProm`]: the address is cos γ quantized to
//!   [`SIN_ADDR_BITS`] bits, the word is sin(arccos(address)));
//! - cos dγ and sin dγ for the perturbation code ([`BumpMap::code`]: a sign bit, held by the
//!   trigger TG, and an unsigned magnitude of [`CODE_BITS`] bits).
//!
//! Then two multipliers and an add/subtract selected by TG form cos(γ ± dγ), which is raised to
//! n (square-and-multiply over the bits of n; exact power here) and scaled by k_s·I_l.
//!
//! The perturbation map is procedural and lives in screen space (the hardware's pixel address
//! is what it has; the golden scenes carry no texture coordinates): an egg-crate
//! dγ(x, y) = D·sin(2πx/P)·sin(2πy/P) with amplitude D = [`BumpMap::default`]'s 0.12 rad and
//! period P = 16 pixels. The base normal is the reference one (exact normalization).

use crate::methods::Emit;
use crate::shade::ShadeContext;
use crate::types::{ScreenTriangle, Walk};
use std::f64::consts::TAU;

/// Address width of the sin-from-cos PROM.
pub const SIN_ADDR_BITS: u32 = 16;

/// Magnitude bits of the perturbation code (plus one sign bit).
pub const CODE_BITS: u32 = 8;

/// The PROM word for sin γ, addressed by cos γ ∈ [−1, 1] quantized to `addr_bits`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SinProm {
    pub addr_bits: u32,
}

impl SinProm {
    /// Largest address: cos γ = 1.
    pub fn top(&self) -> f64 {
        ((1u64 << self.addr_bits) - 1) as f64
    }
    /// Address of cos γ (cos γ = −1..1 mapped to −top..top, rounded).
    pub fn address(&self, cos_gamma: f64) -> i64 {
        (cos_gamma.clamp(-1.0, 1.0) * self.top()).round() as i64
    }
    /// The stored word: sin(arccos(address/top)) ≥ 0.
    pub fn word(&self, address: i64) -> f64 {
        let c = address as f64 / self.top();
        (1.0 - c * c).max(0.0).sqrt()
    }
    /// sin γ for cos γ, as the PROM delivers it.
    pub fn sin(&self, cos_gamma: f64) -> f64 {
        self.word(self.address(cos_gamma))
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
    /// dγ at the centre of pixel (x, y), before quantization.
    pub fn d_gamma(&self, x: i32, y: i32) -> f64 {
        let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
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
    /// The PROM words (cos dγ, sin |dγ|) of a code.
    pub fn prom(&self, code: Code) -> (f64, f64) {
        let top = ((1u32 << CODE_BITS) - 1) as f64;
        let angle = code.magnitude as f64 / top * self.amplitude;
        (angle.cos(), angle.sin())
    }
}

/// Per-pixel kernel: cos(γ + dγ) from cos γ and the code, without trigonometric units.
pub fn perturb(cos_gamma: f64, code: Code, map: &BumpMap, prom: &SinProm) -> f64 {
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

/// Bump shading of one triangle with the default map and PROM.
pub fn shade(tri: &ScreenTriangle, walk: &Walk, ctx: &ShadeContext, emit: Emit) {
    shade_with(
        tri,
        walk,
        ctx,
        &BumpMap::default(),
        &SinProm {
            addr_bits: SIN_ADDR_BITS,
        },
        emit,
    )
}

/// Bump shading with a given map and PROM.
pub fn shade_with(
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    map: &BumpMap,
    prom: &SinProm,
    emit: Emit,
) {
    crate::phong::shade_exact_front_end(tri, walk, ctx, emit, |x, y, d, s| {
        let code = map.code(x, y);
        let d = perturb(d, code, map, prom);
        let s = perturb(s, code, map, prom);
        ctx.combine(d, ctx.specular_power(s))
    });
}
