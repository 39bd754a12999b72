//! Material, lighting model and the colour combine shared by every shading method (SPEC §0):
//! I = I_a·k_a + I_l·(k_d·cos ψ + k_s·cos^n λ), per channel, into 8-bit TrueColor.
//!
//! Every method reduces its pixel to two numbers — the diffuse cosine cos ψ = N̂·L and the
//! specular value (cos^n λ, or an approximation of it such as W(n, γ)) — and hands them to
//! [`ShadeContext::combine`], the single place where colours are formed, rounded and clamped.
//! Methods that interpolate intensities instead of normals (Gouraud, quadric, cubic) sample
//! [`ShadeContext::intensity`] (unclamped, 0..255 scale) and round/clamp with [`to_rgb8`].
//!
//! Defaults follow the thesis prototype (seed 001, appendix B, `Prototype.html`): material
//! diffuse colour rgb(64, 77, 90), specular colour white, shininess 50; one white light
//! (I_l = 1 for diffuse and specular) and an ambient light rgb(50, 50, 50) acting on the
//! material's ambient colour, which the prototype sets equal to the diffuse colour. In the
//! SPEC §0 form that is k_a = 50/255 (applied to the diffuse colour), k_d = 1, k_s = 1.
//! The prototype's shader also does not gate the specular term by N·L, and neither do we:
//! the specular cosine is clamped at 0 on its own, the diffuse cosine on its own.

use glam::DVec3;
use thiserror::Error;

/// Surface material. Colours are channel intensities on the 8-bit scale 0..=255.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Material {
    /// Ambient coefficient k_a (applied to the diffuse colour, as in the thesis prototype).
    pub ka: f64,
    /// Diffuse coefficient k_d.
    pub kd: f64,
    /// Specular coefficient k_s.
    pub ks: f64,
    /// Diffuse (and ambient) colour, 0..=255 per channel.
    pub diffuse: [f64; 3],
    /// Specular colour, 0..=255 per channel.
    pub specular: [f64; 3],
    /// Specular exponent n ("shininess"), 1..=1000.
    pub shininess: u32,
}

impl Default for Material {
    /// The thesis prototype's material and lights (see the module doc).
    fn default() -> Self {
        Material {
            ka: 50.0 / 255.0,
            kd: 1.0,
            ks: 1.0,
            diffuse: [64.0, 77.0, 90.0],
            specular: [255.0, 255.0, 255.0],
            shininess: 50,
        }
    }
}

/// Allowed range of the specular exponent n (SPEC §2: n ∈ [1, 1000]).
pub const SHININESS_RANGE: std::ops::RangeInclusive<u32> = 1..=1000;

/// Which cosine the specular term uses (SPEC §0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LightingModel {
    /// cos λ = N̂·H, H = (L + V)/|L + V| (the thesis' choice: H is constant per frame).
    #[default]
    Blinn,
    /// cos λ = R·V = 2(N̂·L)(N̂·V) − L·V.
    Phong,
    /// Diffuse only: no specular term.
    Lambert,
}

impl LightingModel {
    pub fn name(self) -> &'static str {
        match self {
            LightingModel::Blinn => "blinn",
            LightingModel::Phong => "phong",
            LightingModel::Lambert => "lambert",
        }
    }
}

impl std::str::FromStr for LightingModel {
    type Err = ShadeError;
    fn from_str(s: &str) -> Result<Self, ShadeError> {
        match s {
            "blinn" => Ok(LightingModel::Blinn),
            "phong" => Ok(LightingModel::Phong),
            "lambert" => Ok(LightingModel::Lambert),
            _ => Err(ShadeError::UnknownLighting(s.to_string())),
        }
    }
}

/// Bad shading input: each a one-line message.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ShadeError {
    #[error("light direction must be finite and non-zero, got {0:?}")]
    BadLight([f64; 3]),
    #[error("view direction must be finite and non-zero, got {0:?}")]
    BadView([f64; 3]),
    #[error("shininess n = {0} is outside 1..=1000")]
    Shininess(u32),
    #[error("material coefficient {name} = {value} must be finite and >= 0")]
    Coefficient { name: &'static str, value: f64 },
    #[error("material {name} colour {value:?} must have finite channels in 0..=255")]
    Colour { name: &'static str, value: [f64; 3] },
    #[error("unknown lighting model {0:?} (valid: blinn, phong, lambert)")]
    UnknownLighting(String),
}

/// Everything a method needs besides the triangle: material, lighting model, and the constant
/// unit vectors L (to the light) and V (to the viewer); light and viewer are at infinity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadeContext {
    pub material: Material,
    pub lighting: LightingModel,
    /// Unit vector to the light, L.
    pub light: DVec3,
    /// Unit vector to the viewer, V (the viewer looks down −z, so V = (0, 0, 1)).
    pub view: DVec3,
}

impl Default for ShadeContext {
    /// Default material, Blinn lighting, viewer on +z, light from the right (the prototype's
    /// default 90°: L = (1, 0, 0) in view space is the scene code's business; this is only a
    /// convenient default for tests).
    fn default() -> Self {
        ShadeContext {
            material: Material::default(),
            lighting: LightingModel::Blinn,
            light: DVec3::new(1.0, 1.0, 1.0).normalize(),
            view: DVec3::Z,
        }
    }
}

fn check_dir(v: DVec3) -> Option<DVec3> {
    if v.is_finite() && v.length_squared() > 0.0 {
        Some(v.normalize())
    } else {
        None
    }
}

impl ShadeContext {
    /// Build a context: L and V are normalized here; the result is validated.
    pub fn new(
        material: Material,
        lighting: LightingModel,
        light: DVec3,
        view: DVec3,
    ) -> Result<ShadeContext, ShadeError> {
        let light = check_dir(light).ok_or(ShadeError::BadLight(light.to_array()))?;
        let view = check_dir(view).ok_or(ShadeError::BadView(view.to_array()))?;
        let ctx = ShadeContext {
            material,
            lighting,
            light,
            view,
        };
        ctx.validate()?;
        Ok(ctx)
    }

    /// Check every input a method relies on.
    pub fn validate(&self) -> Result<(), ShadeError> {
        let m = &self.material;
        if check_dir(self.light).is_none() {
            return Err(ShadeError::BadLight(self.light.to_array()));
        }
        if check_dir(self.view).is_none() {
            return Err(ShadeError::BadView(self.view.to_array()));
        }
        if !SHININESS_RANGE.contains(&m.shininess) {
            return Err(ShadeError::Shininess(m.shininess));
        }
        for (name, value) in [("k_a", m.ka), ("k_d", m.kd), ("k_s", m.ks)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(ShadeError::Coefficient { name, value });
            }
        }
        for (name, value) in [("diffuse", m.diffuse), ("specular", m.specular)] {
            if !value
                .iter()
                .all(|c| c.is_finite() && (0.0..=255.0).contains(c))
            {
                return Err(ShadeError::Colour { name, value });
            }
        }
        Ok(())
    }

    /// Blinn's half vector H = (L + V)/|L + V|; the zero vector when L = −V (light exactly
    /// behind the object as seen by the viewer: no highlight can be seen).
    pub fn half(&self) -> DVec3 {
        let s = self.light + self.view;
        if s.length_squared() < 1e-24 {
            DVec3::ZERO
        } else {
            s.normalize()
        }
    }

    /// The specular exponent n.
    pub fn n(&self) -> u32 {
        self.material.shininess
    }

    /// The constant vectors whose cosines with the unit normal a method must approximate:
    /// L always; H for Blinn, V for Phong (R·V = 2(N̂·L)(N̂·V) − L·V), none for Lambert.
    pub fn specular_vector(&self) -> Option<DVec3> {
        match self.lighting {
            LightingModel::Blinn => Some(self.half()),
            LightingModel::Phong => Some(self.view),
            LightingModel::Lambert => None,
        }
    }

    /// Lighting-model cosines from a method's cosines: `cos_l` ≈ N̂·L and `cos_s` ≈ N̂·X with X
    /// = [`Self::specular_vector`] (ignored for Lambert). Returns (cos ψ, cos λ), unclamped.
    pub fn cosines(&self, cos_l: f64, cos_s: f64) -> (f64, f64) {
        match self.lighting {
            LightingModel::Blinn => (cos_l, cos_s),
            LightingModel::Phong => (cos_l, 2.0 * cos_l * cos_s - self.light.dot(self.view)),
            LightingModel::Lambert => (cos_l, 0.0),
        }
    }

    /// The exact specular value max(cos λ, 0)^n (0 for Lambert).
    pub fn specular_power(&self, cos_lambda: f64) -> f64 {
        if self.lighting == LightingModel::Lambert {
            return 0.0;
        }
        cos_lambda.max(0.0).powi(self.material.shininess as i32)
    }

    /// Exact per-pixel lighting of a unit normal: (cos ψ, specular value).
    pub fn exact_terms(&self, unit_normal: DVec3) -> (f64, f64) {
        let (d, s) = self.exact_cosines(unit_normal);
        (d, self.specular_power(s))
    }

    /// The exact (cos ψ, cos λ) of a unit normal, before the specular power.
    pub fn exact_cosines(&self, unit_normal: DVec3) -> (f64, f64) {
        let cos_s = self.specular_vector().map_or(0.0, |x| unit_normal.dot(x));
        self.cosines(unit_normal.dot(self.light), cos_s)
    }

    /// Channel intensities on the 0..255 scale, unclamped:
    /// I_c = k_a·D_c + k_d·D_c·max(cos ψ, 0) + k_s·S_c·specular (D, S the material colours;
    /// I_a = I_l = 1, white lights). `specular` is cos^n λ or the method's approximation of it.
    /// The Lambert model has no specular term whatever `specular` says.
    pub fn intensity(&self, cos_psi: f64, specular: f64) -> [f64; 3] {
        let m = &self.material;
        let d = cos_psi.max(0.0);
        let s = if self.lighting == LightingModel::Lambert {
            0.0
        } else {
            specular.max(0.0)
        };
        std::array::from_fn(|c| {
            m.ka * m.diffuse[c] + m.kd * m.diffuse[c] * d + m.ks * m.specular[c] * s
        })
    }

    /// The one colour combine: [`Self::intensity`] rounded and clamped to 8 bits.
    pub fn combine(&self, cos_psi: f64, specular: f64) -> [u8; 3] {
        to_rgb8(self.intensity(cos_psi, specular))
    }

    /// Exact lighting of a unit normal as an unclamped intensity (samples for the
    /// intensity-interpolating methods).
    pub fn exact_intensity(&self, unit_normal: DVec3) -> [f64; 3] {
        let (d, s) = self.exact_terms(unit_normal);
        self.intensity(d, s)
    }
}

/// Round to nearest and clamp to 0..=255 (NaN maps to 0).
pub fn to_u8(v: f64) -> u8 {
    if v.is_nan() {
        0
    } else {
        v.round().clamp(0.0, 255.0) as u8
    }
}

/// [`to_u8`] per channel.
pub fn to_rgb8(v: [f64; 3]) -> [u8; 3] {
    v.map(to_u8)
}

/// Normalize, or `None` for a zero or non-finite vector.
pub fn unit(v: DVec3) -> Option<DVec3> {
    check_dir(v)
}
