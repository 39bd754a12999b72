//! The shading methods by name, and the single entry point the renderer calls.
//!
//! Each method lives in the file named after its SPEC block and is split the way the hardware
//! is: a set-up function per triangle or per span (the "software side": divisions, square
//! roots, arccos, solving for coefficients) and a per-pixel kernel (the "hardware side": adds,
//! shifts, small multipliers, ROM look-ups). Interpolated normals are screen-space linear
//! ([`ScreenTriangle::normal_plane`]), as the hardware's vector interpolator produces them.
//!
//! | method | file | per pixel |
//! |---|---|---|
//! | reference, flat | [`crate::shading::phong`] | exact normalization / one normal per face |
//! | gouraud | [`crate::shading::gouraud`] | plane per colour channel |
//! | subdivision | [`crate::shading::subdivision`] (§7) | four sub-triangles, a plane each |
//! | normalizer, normalizer-fit, normalizer-pw | [`crate::units::normalizer`] (§1) | N·f(K), K by recurrence |
//! | fast, fast-fit | [`crate::shading::fast`] (§3) | p/√q, two points per step |
//! | angular | [`crate::shading::angular`] (§4) | cos β·cos(ψ − tΔφ) |
//! | quadric | [`crate::shading::quadric`] (§8) | forward differences |
//! | cubic | [`crate::shading::cubic`] (§9) | Horner per span |
//! | brdf-k4/8/16 | [`crate::shading::brdf`] (§2) | W(n, γ) |
//! | bump | [`crate::shading::bump`] (§2) | cos(γ ± dγ) |
//! | texture-reference, texture, texture-quadratic, texture-bezier, texture-affine | [`crate::shading::texture`] (§14–§16) | a texel as the diffuse colour, lit as normalizer-fit |
//!
//! The textured methods read a texture: [`shade_triangle_textured`] takes it,
//! [`shade_triangle`] uses the built-in one ([`Texture::builtin`]). Their reference is
//! `texture-reference` ([`Method::reference_of`]), not the untextured `reference`.

use crate::shade::ShadeContext;
pub use crate::shading::{row_end, row_xs, span_end_normals, Emit};
use crate::texture::Texture;
use crate::types::{ScreenTriangle, Walk};
use std::fmt;
use std::str::FromStr;

/// Every shading method of the golden model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Method {
    /// Phong shading: per-pixel interpolated normal, exactly normalized (the thesis' etalon).
    Reference,
    Flat,
    Gouraud,
    /// Midpoint subdivision into four (SPEC §7), each sub-triangle Gouraud-shaded.
    Subdivision,
    /// SPEC §1 with the published f(K) = 0.822K² − 2.046K + 2.227.
    Normalizer,
    /// SPEC §1 with [`crate::units::normalizer::FIT`] (same hardware, exact at K = 1).
    NormalizerFit,
    /// SPEC §1 with [`crate::units::normalizer::PIECEWISE`]: four segments of K (a coefficient
    /// mux, the same multipliers).
    NormalizerPw,
    /// SPEC §3 with the published Chebyshev 1/√(M+1) ≈ 1.003 − 0.403M + 0.82M².
    Fast,
    /// SPEC §3 with [`crate::shading::fast::FIT`] (same hardware, exact at M = 0).
    FastFit,
    Angular,
    Quadric,
    Cubic,
    BrdfK4,
    BrdfK8,
    BrdfK16,
    Bump,
    /// The textured reference: the exact perspective-correct texture coordinate in f64.
    TextureReference,
    /// SPEC §14: the additive, division-free perspective-correct texture coordinate.
    Texture,
    /// SPEC §15: quadratic along the raster line.
    TextureQuadratic,
    /// SPEC §16: quadratic Bézier along the raster line.
    TextureBezier,
    /// Screen-linear texture coordinates (no perspective correction).
    TextureAffine,
}

impl Method {
    /// Every method except the reference, in the order reports list them.
    pub const ALL_NON_REFERENCE: [Method; 15] = [
        Method::Flat,
        Method::Gouraud,
        Method::Subdivision,
        Method::Normalizer,
        Method::NormalizerFit,
        Method::NormalizerPw,
        Method::Fast,
        Method::FastFit,
        Method::Angular,
        Method::Quadric,
        Method::Cubic,
        Method::BrdfK4,
        Method::BrdfK8,
        Method::BrdfK16,
        Method::Bump,
    ];

    /// The textured methods, compared with [`Method::TextureReference`].
    pub const TEXTURED: [Method; 4] = [
        Method::Texture,
        Method::TextureQuadratic,
        Method::TextureBezier,
        Method::TextureAffine,
    ];

    /// Every method: the reference, the shading methods, the textured reference, the textured
    /// methods.
    pub fn all() -> impl Iterator<Item = Method> {
        std::iter::once(Method::Reference)
            .chain(Method::ALL_NON_REFERENCE)
            .chain(std::iter::once(Method::TextureReference))
            .chain(Method::TEXTURED)
    }

    /// Whether the method reads a texture.
    pub fn is_textured(self) -> bool {
        self == Method::TextureReference || Method::TEXTURED.contains(&self)
    }

    /// The image a method is judged against: `texture-reference` for the textured methods,
    /// `reference` for every other.
    pub fn reference_of(self) -> Method {
        if self.is_textured() {
            Method::TextureReference
        } else {
            Method::Reference
        }
    }

    /// The name used on the command line and in file names.
    pub fn name(self) -> &'static str {
        match self {
            Method::Reference => "reference",
            Method::Flat => "flat",
            Method::Gouraud => "gouraud",
            Method::Subdivision => "subdivision",
            Method::Normalizer => "normalizer",
            Method::NormalizerFit => "normalizer-fit",
            Method::NormalizerPw => "normalizer-pw",
            Method::Fast => "fast",
            Method::FastFit => "fast-fit",
            Method::Angular => "angular",
            Method::Quadric => "quadric",
            Method::Cubic => "cubic",
            Method::BrdfK4 => "brdf-k4",
            Method::BrdfK8 => "brdf-k8",
            Method::BrdfK16 => "brdf-k16",
            Method::Bump => "bump",
            Method::TextureReference => "texture-reference",
            Method::Texture => "texture",
            Method::TextureQuadratic => "texture-quadratic",
            Method::TextureBezier => "texture-bezier",
            Method::TextureAffine => "texture-affine",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown method name; the message lists the valid ones.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown method {name:?} (valid: {})", valid_names())]
pub struct UnknownMethod {
    pub name: String,
}

fn valid_names() -> String {
    Method::all()
        .map(Method::name)
        .collect::<Vec<_>>()
        .join(", ")
}

impl FromStr for Method {
    type Err = UnknownMethod;
    fn from_str(s: &str) -> Result<Method, UnknownMethod> {
        Method::all()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownMethod {
                name: s.to_string(),
            })
    }
}

/// Shade one triangle: emits exactly one colour for every pixel of `walk.pixels()`, in walk
/// order. `walk` must be the golden walk of `tri` (SPEC §5 contract in [`crate::types::Row`]).
/// A zero-area triangle has no pixels and emits nothing. Textured methods read the built-in
/// texture.
pub fn shade_triangle(
    method: Method,
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    emit: &mut dyn FnMut(i32, i32, [u8; 3]),
) {
    shade_triangle_textured(method, tri, walk, ctx, Texture::builtin(), emit)
}

/// [`shade_triangle`] with the texture the textured methods read.
pub fn shade_triangle_textured(
    method: Method,
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    texture: &Texture,
    emit: &mut dyn FnMut(i32, i32, [u8; 3]),
) {
    use crate::shading::texture::Coord;
    use crate::shading::*;
    use crate::units::normalizer;
    if walk.pixel_count() == 0 {
        return;
    }
    match method {
        Method::Reference => phong::shade(tri, walk, ctx, emit),
        Method::Flat => phong::shade_flat(tri, walk, ctx, emit),
        Method::Gouraud => gouraud::shade(tri, walk, ctx, emit),
        Method::Subdivision => subdivision::shade(tri, ctx, emit),
        Method::Normalizer => normalizer::shade(tri, walk, ctx, normalizer::PUBLISHED, emit),
        Method::NormalizerFit => normalizer::shade(tri, walk, ctx, normalizer::FIT, emit),
        Method::NormalizerPw => normalizer::shade(tri, walk, ctx, normalizer::PIECEWISE, emit),
        Method::Fast => fast::shade(tri, walk, ctx, fast::CHEBYSHEV, emit),
        Method::FastFit => fast::shade(tri, walk, ctx, fast::FIT, emit),
        Method::Angular => angular::shade(tri, walk, ctx, emit),
        Method::Quadric => quadric::shade(tri, walk, ctx, emit),
        Method::Cubic => cubic::shade(tri, walk, ctx, emit),
        Method::BrdfK4 => brdf::shade(tri, walk, ctx, 4, emit),
        Method::BrdfK8 => brdf::shade(tri, walk, ctx, 8, emit),
        Method::BrdfK16 => brdf::shade(tri, walk, ctx, 16, emit),
        Method::Bump => bump::shade(tri, walk, ctx, emit),
        Method::TextureReference => texture::shade(tri, walk, ctx, texture, Coord::Reference, emit),
        Method::Texture => texture::shade(tri, walk, ctx, texture, Coord::Additive, emit),
        Method::TextureQuadratic => texture::shade(tri, walk, ctx, texture, Coord::Quadratic, emit),
        Method::TextureBezier => texture::shade(tri, walk, ctx, texture, Coord::Bezier, emit),
        Method::TextureAffine => texture::shade(tri, walk, ctx, texture, Coord::Affine, emit),
    }
}
