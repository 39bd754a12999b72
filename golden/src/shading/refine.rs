//! Adaptive subdivision of a projected mesh (set-up software, `--subdivide`): large triangles
//! whose vertex normals are far apart are split by their edge midpoints, recursively, so that
//! every method's per-triangle approximation (the normalizer's f(K) near K = 1, the angular,
//! fast, quadric and cubic fits over small normal spans) is used in the range it was made for.
//! The reference stays the Phong image of the undivided mesh.
//!
//! # How a level splits
//!
//! An *edge* is split, not a triangle, so two neighbours always agree: an edge is keyed by its
//! two end points' screen addresses, and split when
//! - two front-facing triangles share it (a silhouette or open edge is never split, so the
//!   mesh's outline and its occlusion edges keep exactly the pixels they had),
//! - it is at least [`MIN_SPLIT`] pixels long (along x or y), and
//! - the level asks for it: every such edge for `--subdivide 1` / `2`, or, with `auto`, those
//!   whose end normals are more than [`AUTO_ANGLE_DEG`] apart (up to [`AUTO_MAX_LEVELS`]
//!   levels; the depth per triangle follows from its own normals).
//!
//! A triangle with three split edges becomes four (the midpoint subdivision of SPEC §7), with
//! two becomes three, with one becomes two (red–green refinement: no T-junction, so no crack).
//! The midpoint's address is the rounded mean of the end points' (`⌊(a + b + 1)/2⌋` in the
//! triangle's units, the same from either side), its depth and normal the parent's planes at
//! that address — the parent's interpolated normal there, so the sub-triangles' normal field
//! has the parent's direction everywhere and the reference image is unchanged — kept within
//! the parent's vertex values (a rounded address can lie just off a sliver's edge, where its
//! steep planes would extrapolate far). After the last level
//! each triangle's three normals are scaled by one factor so the longest is a unit vector:
//! directions stay, and K = |N|² comes back near 1 (where the normalizer's f(K) is exact),
//! which is what the normalizer methods gain. The sub-triangles
//! cover the parent's pixel set except where a rounded midpoint moves an *interior* edge by
//! up to half a unit: there a pixel changes owner between the two neighbours, never becomes
//! uncovered (the split edge's two sides move together).
//!
//! With integer vertices (frac = 0) a midpoint moves by up to half a pixel and edges under
//! [`MIN_SPLIT`] pixels stay whole; with sub-pixel vertices (`--subpixel 4`) it moves by up to
//! 1/32 pixel and edges down to one pixel are split ([`min_split`]).

use std::collections::HashMap;

use crate::types::{Plane, ScreenTriangle, ScreenVertex};
use glam::DVec3;

/// Shortest edge (pixels along its longer axis) that is split.
pub const MIN_SPLIT: i32 = 4;
/// The same with sub-pixel vertices (`ScreenTriangle::frac` > 0), in 2^−frac pixel: one
/// pixel, since a midpoint is then placed to 2^−frac pixel, not moved by up to half a pixel.
pub fn min_split(frac: u32) -> i32 {
    if frac == 0 {
        MIN_SPLIT
    } else {
        1 << frac
    }
}
/// `auto`: split an edge whose end normals are more than this many degrees apart.
pub const AUTO_ANGLE_DEG: f64 = 15.0;
/// `auto`: at most this many levels.
pub const AUTO_MAX_LEVELS: u32 = 4;

/// `--subdivide`: a fixed number of levels, or `auto`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Subdivide {
    /// Levels 0 (off, the default), 1 or 2: split every interior edge that is long enough.
    Levels(u32),
    /// Split edges whose normals are more than [`AUTO_ANGLE_DEG`] apart, up to
    /// [`AUTO_MAX_LEVELS`] levels.
    Auto,
}

impl Subdivide {
    pub const OFF: Subdivide = Subdivide::Levels(0);
}

impl Default for Subdivide {
    fn default() -> Self {
        Subdivide::OFF
    }
}

impl serde::Serialize for Subdivide {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl std::fmt::Display for Subdivide {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Subdivide::Levels(n) => write!(f, "{n}"),
            Subdivide::Auto => f.write_str("auto"),
        }
    }
}

impl std::str::FromStr for Subdivide {
    type Err = String;
    fn from_str(s: &str) -> Result<Subdivide, String> {
        match s {
            "auto" => Ok(Subdivide::Auto),
            "0" | "1" | "2" => Ok(Subdivide::Levels(s.parse().unwrap())),
            _ => Err(format!("subdivide {s:?}: expected 0, 1, 2 or auto")),
        }
    }
}

type Key = ((i32, i32), (i32, i32));

fn key(a: &ScreenVertex, b: &ScreenVertex) -> Key {
    let (p, q) = ((a.x, a.y), (b.x, b.y));
    if p <= q {
        (p, q)
    } else {
        (q, p)
    }
}

/// Angle between two normals, degrees.
fn angle_deg(a: &ScreenVertex, b: &ScreenVertex) -> f64 {
    let (u, v) = (a.normal.normalize_or_zero(), b.normal.normalize_or_zero());
    u.dot(v).clamp(-1.0, 1.0).acos().to_degrees()
}

/// The rounded midpoint of edge a→b of `t`, with the normal and depth of `t`'s own linear
/// fields *at that rounded address* (not the mean of the end values): every point of the
/// sub-triangles then lies on the parent's planes, so their interpolated normal and depth are
/// the parent's, exactly, wherever a pixel is.
fn midpoint(t: &ScreenTriangle, a: &ScreenVertex, b: &ScreenVertex) -> ScreenVertex {
    let (x, y) = ((a.x + b.x + 1).div_euclid(2), (a.y + b.y + 1).div_euclid(2));
    let u = t.unit();
    // The plane's value, kept within the triangle's vertex values: a rounded address can lie
    // just off the edge, where a sliver's steep plane would extrapolate far.
    let at = |p: Option<Plane>, fallback: f64, of: fn(&ScreenVertex) -> f64| {
        let (lo, hi) =
            t.v.iter()
                .map(of)
                .fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(v), h.max(v)));
        p.map_or(fallback, |p| p.a * x as f64 * u + p.b * y as f64 * u + p.c)
            .clamp(lo, hi)
    };
    let mean = 0.5 * (a.normal + b.normal);
    let np = t.normal_plane();
    // The perspective-correct texture coordinates: 1/w, s/w and t/w on the parent's screen
    // planes, so the sub-triangles texture exactly as the parent does.
    let over_w = |f: fn(&ScreenVertex) -> f64, v: &ScreenVertex| f(v) / v.w;
    let at_q = |f: fn(&ScreenVertex) -> f64| {
        let vals = t.v.map(|v| over_w(f, &v));
        let (lo, hi) = vals
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
        t.scalar_plane(vals)
            .map_or(0.5 * (over_w(f, a) + over_w(f, b)), |p| {
                p.a * x as f64 * u + p.b * y as f64 * u + p.c
            })
            .clamp(lo, hi)
    };
    let q = at_q(|_| 1.0);
    ScreenVertex {
        x,
        y,
        z: at(t.depth_plane(), 0.5 * (a.z + b.z), |v| v.z),
        normal: DVec3::new(
            at(np.map(|p| p.x), mean.x, |v| v.normal.x),
            at(np.map(|p| p.y), mean.y, |v| v.normal.y),
            at(np.map(|p| p.z), mean.z, |v| v.normal.z),
        ),
        uv: glam::DVec2::new(at_q(|v| v.uv.x), at_q(|v| v.uv.y)) / q,
        w: 1.0 / q,
    }
}

/// Scale a triangle's three vertex normals by one factor so the longest is a unit vector:
/// the direction of the interpolated normal is unchanged everywhere in the triangle, and the
/// normalizer's K = |N|² is brought back near 1, where its f(K) is accurate.
fn rescale(t: &mut ScreenTriangle) {
    let longest = t.v.iter().map(|v| v.normal.length()).fold(0.0, f64::max);
    if longest > 0.0 && longest.is_finite() {
        for v in &mut t.v {
            v.normal /= longest;
        }
    }
}

/// The triangles `t` becomes when its edges `s[i]` (v[i] → v[i+1]) are split.
fn children(t: &ScreenTriangle, s: [bool; 3]) -> Vec<ScreenTriangle> {
    let m: [ScreenVertex; 3] = std::array::from_fn(|i| midpoint(t, &t.v[i], &t.v[(i + 1) % 3]));
    let v = t.v;
    let tri = |a: ScreenVertex, b: ScreenVertex, c: ScreenVertex| ScreenTriangle {
        v: [a, b, c],
        frac: t.frac,
    };
    match s.iter().filter(|&&x| x).count() {
        0 => vec![*t],
        3 => vec![
            tri(v[0], m[0], m[2]),
            tri(m[0], v[1], m[1]),
            tri(m[2], m[1], v[2]),
            tri(m[0], m[1], m[2]),
        ],
        1 => {
            // Edge i (v[i] → v[i+1]) splits; the opposite vertex is v[i+2].
            let i = s.iter().position(|&x| x).unwrap();
            let (a, b, c) = (v[i], v[(i + 1) % 3], v[(i + 2) % 3]);
            vec![tri(a, m[i], c), tri(m[i], b, c)]
        }
        _ => {
            // Edges i and i+1 split (they share v[i+1]); edge i+2 (v[i+2] → v[i]) does not.
            let k = s.iter().position(|&x| !x).unwrap();
            let i = (k + 1) % 3;
            let (a, b, c) = (v[i], v[(i + 1) % 3], v[(i + 2) % 3]);
            let (m1, m2) = (m[i], m[(i + 1) % 3]);
            // The quad a, m1, m2, c: cut along its shorter diagonal.
            let d = |p: &ScreenVertex, q: &ScreenVertex| {
                ((p.x - q.x) as i64).pow(2) + ((p.y - q.y) as i64).pow(2)
            };
            if d(&a, &m2) <= d(&m1, &c) {
                vec![tri(m1, b, m2), tri(a, m1, m2), tri(a, m2, c)]
            } else {
                vec![tri(m1, b, m2), tri(a, m1, c), tri(m1, m2, c)]
            }
        }
    }
}

/// One level: which edges split, then each triangle split by its split edges. Returns `None`
/// when no edge splits.
fn level(tris: &[ScreenTriangle], split_all: bool) -> Option<Vec<ScreenTriangle>> {
    let mut edges: HashMap<Key, (u32, f64)> = HashMap::new();
    for t in tris {
        for i in 0..3 {
            let (a, b) = (&t.v[i], &t.v[(i + 1) % 3]);
            let e = edges.entry(key(a, b)).or_insert((0, 0.0));
            e.0 += 1;
            e.1 = e.1.max(angle_deg(a, b));
        }
    }
    let min = min_split(tris.first().map_or(0, |t| t.frac));
    let mut split: std::collections::HashSet<Key> = edges
        .iter()
        .filter(|(k, &(uses, angle))| {
            let long = (k.0 .0 - k.1 .0).abs().max((k.0 .1 - k.1 .1).abs()) >= min;
            uses == 2 && long && (split_all || angle > AUTO_ANGLE_DEG)
        })
        .map(|(k, _)| *k)
        .collect();
    // A rounded midpoint may fold a thin triangle (a child with the opposite orientation or
    // none): such a triangle keeps all its edges whole, and so do its neighbours on them.
    loop {
        let mut dropped = false;
        for t in tris {
            let s: [bool; 3] =
                std::array::from_fn(|i| split.contains(&key(&t.v[i], &t.v[(i + 1) % 3])));
            if !s.iter().any(|&x| x) {
                continue;
            }
            let sign = t.area2().signum();
            if children(t, s).iter().any(|c| c.area2().signum() != sign) {
                for i in 0..3 {
                    dropped |= split.remove(&key(&t.v[i], &t.v[(i + 1) % 3]));
                }
            }
        }
        if !dropped {
            break;
        }
    }
    let mut out = Vec::with_capacity(tris.len() * 2);
    let mut any = false;
    for t in tris {
        let s: [bool; 3] =
            std::array::from_fn(|i| split.contains(&key(&t.v[i], &t.v[(i + 1) % 3])));
        any |= s.iter().any(|&x| x);
        out.extend(children(t, s));
    }
    any.then_some(out)
}

/// The mesh `tris` (front-facing, projected) refined as `mode` asks.
pub fn refine(tris: &[ScreenTriangle], mode: Subdivide) -> Vec<ScreenTriangle> {
    let (levels, all) = match mode {
        Subdivide::Levels(n) => (n, true),
        Subdivide::Auto => (AUTO_MAX_LEVELS, false),
    };
    let mut cur = tris.to_vec();
    let mut split = false;
    for _ in 0..levels {
        match level(&cur, all) {
            Some(next) => {
                cur = next;
                split = true;
            }
            None => break,
        }
    }
    if split {
        cur.iter_mut().for_each(rescale);
    }
    cur
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::edge_function_pixels;
    use glam::DVec3;

    fn v(x: i32, y: i32, n: DVec3) -> ScreenVertex {
        ScreenVertex {
            x,
            y,
            z: 0.0,
            normal: n.normalize(),
            uv: glam::DVec2::ZERO,
            w: 1.0,
        }
    }

    /// A fan of triangles around (50, 50) with normals tilting outwards: refined at each mode,
    /// every pixel of the fan is still covered, none twice, and the outline (never split)
    /// keeps its pixels.
    #[test]
    fn fan_keeps_its_pixels() {
        let ring: Vec<(i32, i32)> = (0..8)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 8.0;
                (
                    (50.0 + 40.0 * a.cos()).round() as i32,
                    (50.0 + 40.0 * a.sin()).round() as i32,
                )
            })
            .collect();
        let c = v(50, 50, DVec3::Z);
        let tris: Vec<ScreenTriangle> = (0..8)
            .map(|k| {
                let (p, q) = (ring[k], ring[(k + 1) % 8]);
                let n = |p: (i32, i32)| DVec3::new((p.0 - 50) as f64, (p.1 - 50) as f64, 60.0);
                ScreenTriangle {
                    v: [c, v(p.0, p.1, n(p)), v(q.0, q.1, n(q))],
                    frac: 0,
                }
            })
            .collect();
        let cover = |ts: &[ScreenTriangle]| {
            let mut m: HashMap<(i32, i32), u32> = HashMap::new();
            for t in ts {
                for p in edge_function_pixels(t) {
                    *m.entry(p).or_default() += 1;
                }
            }
            m
        };
        let base = cover(&tris);
        assert!(base.values().all(|&n| n == 1));
        for mode in [Subdivide::Levels(1), Subdivide::Levels(2), Subdivide::Auto] {
            let r = refine(&tris, mode);
            assert!(r.len() > tris.len(), "{mode}: nothing split");
            let got = cover(&r);
            assert_eq!(got.len(), base.len(), "{mode}: coverage changed");
            assert!(got.values().all(|&n| n == 1), "{mode}: a pixel twice");
            for t in &r {
                let longest = t.v.iter().map(|p| p.normal.length()).fold(0.0, f64::max);
                assert!(
                    (longest - 1.0).abs() < 1e-12,
                    "{mode}: longest normal {longest}"
                );
            }
        }
        assert_eq!(refine(&tris, Subdivide::OFF), tris);
    }

    #[test]
    fn parse_and_print() {
        for s in ["0", "1", "2", "auto"] {
            assert_eq!(s.parse::<Subdivide>().unwrap().to_string(), s);
        }
        assert!("3"
            .parse::<Subdivide>()
            .unwrap_err()
            .contains("0, 1, 2 or auto"));
    }
}
