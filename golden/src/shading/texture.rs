//! The textured methods (SPEC §14, §15, §16): the texel colour takes the place of the
//! material's diffuse colour, and the pixel is lit as `normalizer-fit` lights it (the vector
//! interpolator and the normalizer with [`normalizer::FIT`]), so that only the texture
//! coordinate differs between these methods.
//!
//! | method | texture coordinate per pixel |
//! |---|---|
//! | texture-reference | the exact quotient u = (a·x + b·y + c)/(g·x + h·y + i) in f64, at the pixel centre, from the unquantized planes |
//! | texture | SPEC §14: the additive walker on the integer PCT coefficients (the nearest texel of their exact quotient, no division) |
//! | texture-quadratic | SPEC §15: per raster line the quadratic through the exact u at the line's ends and middle, stepped by forward differences in the block's Q15.32 words |
//! | texture-bezier | SPEC §16: per raster line the quadratic Bézier with the tangents' intersection as control point, sampled at m = 2(n − 1) steps of t by forward differences in the block's Q15.32 words (its twin) |
//! | texture-affine | u, v linear in screen space through the vertices' (the naive form, for comparison) |
//!
//! Every method picks the nearest texel of its coordinate by the texel-centre rule of
//! [`crate::texture`]; u and v are in texel space. The set-up per triangle (software) moves
//! the triangle's texel coordinates by whole repeats of the texture so that their mean lies in
//! the first repeat (GL_REPEAT gives the same texels), then forms the planes of 1/w, u/w and
//! v/w ([`PctPlanes`]).
//!
//! The §14 walker's integer coefficients are [`PctPlanes::coeffs`] relative to the address
//! block's first line start ([`coeff_origin`], as the block's set-up places them), D scaled to
//! 2^29 at the vertex nearest the eye ([`D_MAX`]); a triangle outside the block's range
//! ([`TexCoordSetup::check`]) falls back to the reference's coordinate (the CLI refuses such a
//! scene before rendering: [`range_error`]).
//!
//! The Bézier's per-pixel rule (the rate): a line of n pixels is sampled at m = 2(n − 1) steps
//! of t (dt = 1/m); with the control point inside the line (it is clamped there), x(t) moves
//! at most one pixel a step, so every pixel has a sample within half a pixel of its centre.
//! Pixel x takes the sample whose x(t) is nearest its centre (a comparator on consecutive
//! samples): two samples per pixel.

use crate::shade::ShadeContext;
use crate::shading::{row_end, Emit};
use crate::texture::Texture;
use crate::types::{Plane, Row, ScreenTriangle, Walk};
use crate::units::address_block::AddressSetup;
use crate::units::normalizer;
use crate::units::texture_bezier::{self, BezierLine, BezierTwin};
use crate::units::texture_coord::block::{walk_geometry, TexCoordSetup};
use crate::units::texture_coord::{PctCoeffs, PctPlanes, PctWalker};
use crate::units::texture_quadratic::{self as quad, QuadWords};
use glam::DVec2;

/// D at the vertex nearest the eye in the §14 walker's integer coefficients.
pub const D_MAX: f64 = (1u64 << 29) as f64;

/// How a textured method forms its texture coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coord {
    Reference,
    Additive,
    Quadratic,
    Bezier,
    Affine,
}

/// The per-triangle set-up shared by the textured methods: the vertices' texel coordinates
/// (moved by whole repeats) and the perspective-correct planes.
#[derive(Clone, Copy, Debug)]
pub struct TexSetup {
    /// Texel-space (u, v) per vertex.
    pub uv: [DVec2; 3],
    /// The planes of 1/w, u/w and v/w.
    pub planes: PctPlanes,
    /// The largest 1/w at the vertices.
    pub vmax: f64,
    /// The screen-linear planes of u and v through the vertices (`texture-affine`).
    pub affine: [Plane; 2],
}

/// The set-up of `tri` for `texture`; `None` for a zero-area triangle or a non-finite or
/// non-positive w.
pub fn setup(tri: &ScreenTriangle, texture: &Texture) -> Option<TexSetup> {
    if !tri.v.iter().all(|v| v.w.is_finite() && v.w > 0.0) {
        return None;
    }
    let mut uv = tri.v.map(|v| texture.texel_space(v.uv));
    let mean = (uv[0] + uv[1] + uv[2]) / 3.0;
    let size = DVec2::new(texture.width() as f64, texture.height() as f64);
    let shift = (mean / size).floor() * size;
    if shift.is_finite() {
        for p in &mut uv {
            *p -= shift;
        }
    }
    let p = std::array::from_fn(|k| tri.position(k));
    let planes = PctPlanes::new(p, tri.v.map(|v| v.w), uv.map(|c| (c.x, c.y)))?;
    let vmax = tri.v.iter().map(|v| 1.0 / v.w).fold(0.0, f64::max);
    let affine = [
        tri.scalar_plane(uv.map(|c| c.x))?,
        tri.scalar_plane(uv.map(|c| c.y))?,
    ];
    Some(TexSetup {
        uv,
        planes,
        vmax,
        affine,
    })
}

/// The origin of the §14 block's coefficients for `tri`: the address block's first line start
/// (`walk_geometry`), where the block's set-up places its words.
pub fn coeff_origin(tri: &ScreenTriangle) -> (i64, i64) {
    walk_geometry(&AddressSetup::new(tri)).0
}

/// The §14 walker's integer coefficients of `s` relative to [`coeff_origin`] (the origin and
/// the u and v coefficients), or why the block cannot take them over `walk`'s pixels.
pub fn checked_coeffs(
    tri: &ScreenTriangle,
    s: &TexSetup,
    walk: &Walk,
) -> Result<((i64, i64), PctCoeffs, PctCoeffs), String> {
    let origin = coeff_origin(tri);
    let (cu, cv) = s.planes.coeffs(origin, s.vmax, D_MAX);
    let pixels: Vec<(i64, i64)> = walk
        .pixels()
        .iter()
        .map(|p| (p.x as i64 - origin.0, p.y as i64 - origin.1))
        .collect();
    TexCoordSetup::check(&cu, &cv, &pixels).map(|()| (origin, cu, cv))
}

/// [`checked_coeffs`], if the block accepts them.
pub fn additive_coeffs(
    tri: &ScreenTriangle,
    s: &TexSetup,
    walk: &Walk,
) -> Option<((i64, i64), PctCoeffs, PctCoeffs)> {
    checked_coeffs(tri, s, walk).ok()
}

/// Why the §14 block cannot take a textured triangle of `tris`, if one exists: a one-line
/// message naming the triangle (its texels or its depth beyond the block's range).
pub fn range_error(tris: &[ScreenTriangle], texture: &Texture) -> Option<String> {
    tris.iter().enumerate().find_map(|(k, tri)| {
        let walk = crate::raster::walk(tri);
        let s = setup(tri, texture).filter(|_| walk.pixel_count() > 0)?;
        checked_coeffs(tri, &s, &walk).err().map(|e| {
            format!("triangle {k} cannot be textured by the texture-coordinate block: {e}")
        })
    })
}

/// The texel-space coordinate of every pixel of `walk`, in walk order, by `coord`.
pub fn coordinates(tri: &ScreenTriangle, s: &TexSetup, walk: &Walk, coord: Coord) -> Vec<DVec2> {
    let exact = |x: i32, y: i32| {
        let (u, v) = s.planes.exact(x as i64, y as i64);
        DVec2::new(u, v)
    };
    let mut out = Vec::with_capacity(walk.pixel_count());
    match coord {
        Coord::Reference => {
            for p in walk.pixels() {
                out.push(exact(p.x, p.y));
            }
        }
        Coord::Affine => {
            for p in walk.pixels() {
                out.push(DVec2::new(
                    s.affine[0].at_pixel(p.x, p.y),
                    s.affine[1].at_pixel(p.x, p.y),
                ));
            }
        }
        Coord::Additive => match additive_coeffs(tri, s, walk) {
            Some((origin, cu, cv)) => {
                let mut walkers: Option<[PctWalker; 2]> = None;
                for row in walk.rows.iter().filter(|r| r.len > 0) {
                    for k in 0..row.len as i64 {
                        let x = row.x_start as i64 + k * row.dir as i64 - origin.0;
                        let y = row.y as i64 - origin.1;
                        let ws = walkers.get_or_insert_with(|| {
                            [
                                PctWalker::start(&cu, x, y, 0),
                                PctWalker::start(&cv, x, y, 0),
                            ]
                        });
                        let mut texel = [0i64; 2];
                        for (a, wk) in ws.iter_mut().enumerate() {
                            move_to(wk, x, y);
                            wk.settle();
                            texel[a] = wk.u;
                        }
                        out.push(DVec2::new(texel[0] as f64, texel[1] as f64));
                    }
                }
            }
            None => return coordinates(tri, s, walk, Coord::Reference),
        },
        Coord::Quadratic => {
            for row in walk.rows.iter().filter(|r| r.len > 0) {
                let [u, v] = quadratic_line(s, row).map(|w| quadratic_row(row, &w));
                out.extend(u.into_iter().zip(v).map(|(u, v)| DVec2::new(u, v)));
            }
        }
        Coord::Bezier => {
            for row in walk.rows.iter().filter(|r| r.len > 0) {
                out.extend(bezier_row(s, row));
            }
        }
    }
    out
}

/// Move a walker to pixel (x, y) of the walk by its own steps: down by +1 (the address block
/// never moves up), then along the line by ±1.
fn move_to(wk: &mut PctWalker, x: i64, y: i64) {
    debug_assert!(wk.y <= y, "the walk moved up");
    while wk.y < y {
        wk.step_y();
    }
    while wk.x < x {
        wk.step_x();
    }
    while wk.x > x {
        wk.step_x_back();
    }
}

/// The §15 quadratic's texel-space coordinate at each pixel of `row`, in walk order, for one
/// axis: the line's words ([`quadratic_line`]) stepped by the block's bit-exact twin.
fn quadratic_row(row: &Row, words: &QuadWords) -> Vec<f64> {
    let mut axis = quad::QuadAxis::default();
    let mut out = Vec::with_capacity(row.len as usize);
    for k in 0..row.len {
        axis.clock(true, (k == 0).then_some(words));
        // The word carries +½: its integer part is the texel; return the texel as a
        // texel-space coordinate (its centre).
        out.push(quad::signed_texel(axis.word()) as f64);
    }
    out
}

/// The §15 quadratic's set-up words of `row` (a line of the walk with pixels), u then v, as
/// the block `texture-quadratic` takes them at the line's first pixel: the quadratic in raw
/// screen x through the exact value at the line's first, middle and last pixel (a one-pixel
/// line its exact value, a two-pixel line a straight line), as differences along the walk.
pub fn quadratic_line(s: &TexSetup, row: &Row) -> [QuadWords; 2] {
    [0, 1].map(|a| {
        quadratic_words(row, |x| {
            let (u, v) = s.planes.exact(x as i64, row.y as i64);
            [u, v][a]
        })
    })
}

fn quadratic_words(row: &Row, exact: impl Fn(i32) -> f64) -> QuadWords {
    let (x0, x2) = (row.x_start, row_end(row));
    let n = row.len as usize;
    let a = match n {
        1 => [0.0, 0.0, exact(x0)],
        2 => {
            let (u0, u2) = (exact(x0), exact(x2));
            let slope = (u2 - u0) / (x2 - x0) as f64;
            [0.0, slope, u0 - slope * x0 as f64]
        }
        _ => {
            let x1 = x0 + (n as i32 / 2) * row.dir as i32;
            let xs = [x0, x1, x2].map(|x| x as f64);
            quad::lagrange_coeffs(xs, [exact(x0), exact(x1), exact(x2)])
        }
    };
    QuadWords::of(quad::differences(&a, x0 as f64, row.dir as f64))
}

/// The §16 Bézier's control points of `row` as the block `texture-bezier` takes them: X (the
/// pixel distance along the walk: 0, X1, n − 1), u and v (texel space). x1 is where the
/// tangents to u(x) and v(x) at the line's ends meet, the same for both (it depends on the
/// depth alone: [`texture_bezier::control_x`]); u1, v1 lie on the tangent at the first pixel.
pub fn bezier_points(s: &TexSetup, row: &Row) -> [[f64; 3]; 3] {
    // The planes at pixel indices: value = k0·x + k1·y + (k2 + (k0 + k1)/2).
    let at_index = |k: [f64; 3]| [k[0], k[1], k[2] + 0.5 * (k[0] + k[1])];
    let q = at_index(s.planes.q);
    let (x0, x2) = (row.x_start as f64, row_end(row) as f64);
    let y = row.y as f64;
    let d = |x: f64| q[0] * x + q[1] * y + q[2];
    let x1 = texture_bezier::control_x(d(x0), d(x2), x0, x2).clamp(x0.min(x2), x0.max(x2));
    let points = |k: [f64; 3]| {
        let k = at_index(k);
        let nn = |x: f64| k[0] * x + k[1] * y + k[2];
        let u = |x: f64| nn(x) / d(x);
        let slope = (k[0] * d(x0) - nn(x0) * q[0]) / (d(x0) * d(x0));
        [u(x0), u(x0) + slope * (x1 - x0), u(x2)]
    };
    [
        [0.0, (x1 - x0).abs(), (x2 - x0).abs()],
        points(s.planes.s),
        points(s.planes.t),
    ]
}

/// The §16 Bézier's record of `row` (a line of the walk with pixels), as the block
/// `texture-bezier` takes it: [`bezier_points`] in its words ([`BezierLine`]).
pub fn bezier_line(s: &TexSetup, row: &Row) -> BezierLine {
    let [xp, up, vp] = bezier_points(s, row);
    BezierLine::new(row.len, xp, up, vp)
}

/// The §16 Bézier's texel (u, v) at each pixel of `row`, in walk order: the line's record
/// ([`bezier_points`], [`BezierLine`]) stepped by the block's bit-exact twin ([`BezierTwin`]:
/// forward differences in Q15.32 words, two samples per pixel step, each pixel the sample
/// nearest its centre by the block's comparisons), as `texture-quadratic` steps the quadratic
/// block's words. It differs from the f64 curve's nearest sample only where two samples are
/// as near within the words' rounding (`golden/tests/texture_bezier_block.rs` counts them).
fn bezier_row(s: &TexSetup, row: &Row) -> Vec<DVec2> {
    let n = row.len as usize;
    let mut twin = BezierTwin::default();
    twin.clock(Some(&bezier_line(s, row)), false);
    let mut out = Vec::with_capacity(n);
    let texel = |t: u64| t as u16 as i16 as f64;
    while out.len() < n {
        let o = twin.outputs(false);
        if o.valid {
            out.push(DVec2::new(texel(o.u), texel(o.v)));
        }
        twin.clock(None, false);
    }
    out
}

/// Shade one triangle with a textured method: the texel colour is the diffuse colour, lit as
/// `normalizer-fit` lights the pixel.
pub fn shade(
    tri: &ScreenTriangle,
    walk: &Walk,
    ctx: &ShadeContext,
    texture: &Texture,
    coord: Coord,
    emit: Emit,
) {
    let Some(s) = setup(tri, texture) else { return };
    let uv = coordinates(tri, &s, walk, coord);
    let mut k = 0;
    normalizer::shade_front_end(tri, walk, ctx, normalizer::FIT, emit, |_, _, d, sp| {
        let texel = texture.nearest(uv.get(k).copied().unwrap_or(DVec2::ZERO));
        k += 1;
        let mut c = *ctx;
        c.material.diffuse = texel.map(f64::from);
        c.combine(d, c.specular_power(sp))
    });
}
