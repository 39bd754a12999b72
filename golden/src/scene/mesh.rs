//! Triangle meshes: the [`Mesh`] type and its checks, the procedural UV sphere (tessellated as
//! the thesis prototype's `drawSolidSphere`), torus and textured ground [`plane`].
//!
//! Model space is right-handed with y up. Meshes wind counter-clockwise seen from outside.

use glam::{DVec2, DVec3};

use super::SceneError;

/// Tessellation range of the thesis prototype's "Sphere Rez" slider (also used for the torus).
pub const REZ_RANGE: std::ops::RangeInclusive<u32> = 3..=100;

/// Torus radii: distance from the centre to the tube's centre line, and the tube's radius.
pub const TORUS_MAJOR: f64 = 1.0;
pub const TORUS_MINOR: f64 = 0.4;

/// A triangle mesh with per-vertex normals and shared indices.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Mesh {
    pub positions: Vec<DVec3>,
    /// Unit normals, one per position.
    pub normals: Vec<DVec3>,
    /// Counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Texture coordinates (s, t) per triangle corner, in the order of `triangles` (a vertex on
    /// a texture seam has one per side): empty when the mesh has none, else one per triangle.
    pub uvs: Vec<[DVec2; 3]>,
}

impl Mesh {
    /// Checks what [`project`](super::project) relies on: as many normals as positions,
    /// indices in range, finite positions, finite non-zero normals.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.check("mesh")
    }

    /// [`Mesh::validate`] with `origin` (e.g. the OBJ file) named in the error.
    pub(super) fn check(&self, origin: &str) -> Result<(), SceneError> {
        if self.normals.len() != self.positions.len() {
            return Err(SceneError::Inconsistent {
                origin: origin.into(),
                positions: self.positions.len(),
                normals: self.normals.len(),
            });
        }
        if let Some((vertex, value)) = first_non_finite(&self.positions) {
            return Err(SceneError::BadPosition {
                origin: origin.into(),
                vertex,
                value,
            });
        }
        for (vertex, n) in self.normals.iter().enumerate() {
            if let Some(problem) = normal_problem(*n) {
                return Err(SceneError::BadNormal {
                    origin: origin.into(),
                    vertex,
                    problem,
                });
            }
        }
        if !self.uvs.is_empty() && self.uvs.len() != self.triangles.len() {
            return Err(SceneError::TexCoordCount {
                origin: origin.into(),
                given: self.uvs.len(),
                triangles: self.triangles.len(),
            });
        }
        if let Some(triangle) = self
            .uvs
            .iter()
            .position(|t| !t.iter().all(|c| c.is_finite()))
        {
            return Err(SceneError::BadTexCoord {
                origin: origin.into(),
                triangle,
            });
        }
        let count = self.positions.len();
        if let Some((triangle, index)) = first_bad_index(&self.triangles, count) {
            return Err(SceneError::BadIndex {
                origin: origin.into(),
                triangle,
                index,
                count,
            });
        }
        Ok(())
    }
}

/// The first triangle of `triangles` that refers to a vertex outside `0..count`: its number and
/// that index. The one index-range check of the crate (meshes and OBJ files).
pub(super) fn first_bad_index(triangles: &[[u32; 3]], count: usize) -> Option<(usize, u32)> {
    triangles.iter().enumerate().find_map(|(triangle, t)| {
        t.iter()
            .find(|&&i| i as usize >= count)
            .map(|&index| (triangle, index))
    })
}

/// The first position with a non-finite coordinate: its number and that coordinate.
pub(super) fn first_non_finite(positions: &[DVec3]) -> Option<(usize, f64)> {
    positions.iter().enumerate().find_map(|(vertex, p)| {
        p.to_array()
            .iter()
            .find(|c| !c.is_finite())
            .map(|&value| (vertex, value))
    })
}

/// Why `n` cannot be normalized, if it cannot.
pub(super) fn normal_problem(n: DVec3) -> Option<&'static str> {
    if n.is_nan() {
        Some("NaN")
    } else if !n.is_finite() {
        Some("infinite")
    } else if n.length_squared() == 0.0 || !n.length().is_normal() {
        Some("zero-length")
    } else {
        None
    }
}

fn check_rez(shape: &'static str, rez: u32) -> Result<(), SceneError> {
    if REZ_RANGE.contains(&rez) {
        Ok(())
    } else {
        Err(SceneError::Rez { shape, rez })
    }
}

/// Unit UV sphere around the y axis, tessellated like the thesis prototype's
/// `drawSolidSphere(1, rez, rez)`: `rez` slices (longitude segments) × `rez` stacks (latitude
/// bands, pole to pole), `rez` in 3..=100 (default 50 in the prototype).
///
/// Vertices: the two poles plus `rez − 1` rings of `rez` vertices, `rez² − rez + 2` in all.
/// Triangles: a fan of `rez` triangles at each pole (no degenerate quads there) and two per quad
/// in between, `2·rez·(rez − 1)` in all. Normals are the exact unit positions. Index 0 is the
/// north pole (+y); vertex (ring i, slice j) sits at polar angle π·i/rez and azimuth 2π·j/rez
/// measured from +z towards +x.
pub fn uv_sphere(rez: u32) -> Result<Mesh, SceneError> {
    check_rez("sphere", rez)?;
    let n = rez;
    let mut positions = vec![DVec3::Y];
    for i in 1..n {
        let phi = std::f64::consts::PI * i as f64 / n as f64;
        for j in 0..n {
            let theta = std::f64::consts::TAU * j as f64 / n as f64;
            positions.push(DVec3::new(
                phi.sin() * theta.sin(),
                phi.cos(),
                phi.sin() * theta.cos(),
            ));
        }
    }
    positions.push(-DVec3::Y);
    let south = positions.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * n + j % n;
    // Texture coordinates: s = 2·azimuth/2π (two repeats around, so a texel is about square on
    // the equator), t = 1 − polar/π; the seam's corners take s = 2 (j = n), a pole s of its
    // fan triangle's middle.
    let st = |i: u32, j: f64| DVec2::new(2.0 * j / n as f64, 1.0 - i as f64 / n as f64);
    let mut triangles = Vec::with_capacity((2 * n * (n - 1)) as usize);
    let mut uvs = Vec::with_capacity(triangles.capacity());
    for j in 0..n {
        triangles.push([0, ring(1, j), ring(1, j + 1)]);
        let jf = j as f64;
        uvs.push([st(0, jf + 0.5), st(1, jf), st(1, jf + 1.0)]);
    }
    for i in 1..n - 1 {
        for j in 0..n {
            let (a, b) = (ring(i, j), ring(i, j + 1));
            let (c, d) = (ring(i + 1, j), ring(i + 1, j + 1));
            triangles.push([a, c, d]);
            triangles.push([a, d, b]);
            let jf = j as f64;
            let (ta, tb) = (st(i, jf), st(i, jf + 1.0));
            let (tc, td) = (st(i + 1, jf), st(i + 1, jf + 1.0));
            uvs.push([ta, tc, td]);
            uvs.push([ta, td, tb]);
        }
    }
    for j in 0..n {
        triangles.push([ring(n - 1, j), south, ring(n - 1, j + 1)]);
        let jf = j as f64;
        uvs.push([st(n - 1, jf), st(n, jf + 0.5), st(n - 1, jf + 1.0)]);
    }
    let normals = positions.iter().map(|p| p.normalize()).collect();
    Ok(Mesh {
        positions,
        normals,
        triangles,
        uvs,
    })
}

/// Torus around the y axis (lying in the xz plane) with radii [`TORUS_MAJOR`] and
/// [`TORUS_MINOR`]: `2·rez` segments around the y axis × `rez` around the tube, `rez` in
/// 3..=100; `2·rez²` vertices and `4·rez²` triangles. Seen with the identity rotation it is
/// edge-on; tilt it (e.g. `DQuat::from_rotation_x(0.6)`) to see the hole.
pub fn torus(rez: u32) -> Result<Mesh, SceneError> {
    check_rez("torus", rez)?;
    let (nu, nv) = (2 * rez, rez);
    let mut positions = Vec::with_capacity((nu * nv) as usize);
    let mut normals = Vec::with_capacity((nu * nv) as usize);
    for i in 0..nu {
        let u = std::f64::consts::TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = std::f64::consts::TAU * j as f64 / nv as f64;
            let n = DVec3::new(v.cos() * u.cos(), v.sin(), v.cos() * u.sin());
            let centre = DVec3::new(u.cos(), 0.0, u.sin()) * TORUS_MAJOR;
            positions.push(centre + n * TORUS_MINOR);
            normals.push(n.normalize());
        }
    }
    let idx = |i: u32, j: u32| (i % nu) * nv + j % nv;
    // Texture coordinates: s = 3 repeats around the y axis, t = 1 around the tube (a texel is
    // then about square on the outer equator); the seams' corners take s = 3, t = 1.
    let st = |i: u32, j: u32| DVec2::new(3.0 * i as f64 / nu as f64, j as f64 / nv as f64);
    let mut triangles = Vec::with_capacity((2 * nu * nv) as usize);
    let mut uvs = Vec::with_capacity(triangles.capacity());
    for i in 0..nu {
        for j in 0..nv {
            // ∂P/∂v × ∂P/∂u points outwards: step along v first, then along u.
            let (a, b) = (idx(i, j), idx(i, j + 1));
            let (c, d) = (idx(i + 1, j + 1), idx(i + 1, j));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
            let (ta, tb) = (st(i, j), st(i, j + 1));
            let (tc, td) = (st(i + 1, j + 1), st(i + 1, j));
            uvs.push([ta, tb, tc]);
            uvs.push([ta, tc, td]);
        }
    }
    Ok(Mesh {
        positions,
        normals,
        triangles,
        uvs,
    })
}

/// Half the width of the ground [`plane`] (model units).
pub const PLANE_HALF_WIDTH: f64 = 2.0;
/// Depth of the ground [`plane`] (model units).
pub const PLANE_DEPTH: f64 = 10.0;

/// A textured ground plane for the perspective camera: y = 0, x in ±[`PLANE_HALF_WIDTH`], z
/// from 0 (near) to −[`PLANE_DEPTH`] (far), normal +y, a grid of `max(1, rez/10)` quads across
/// and five times as many deep (rez in 3..=100; 5 × 25 quads, 250 triangles at the default
/// 50). Texture coordinates: s = (x + half width)/width, t = −z/width: one repeat across, five
/// deep, square texels on the ground.
pub fn plane(rez: u32) -> Result<Mesh, SceneError> {
    check_rez("plane", rez)?;
    let nx = (rez / 10).max(1);
    let nz = 5 * nx;
    let width = 2.0 * PLANE_HALF_WIDTH;
    let mut m = Mesh::default();
    for k in 0..=nz {
        for i in 0..=nx {
            let x = -PLANE_HALF_WIDTH + width * i as f64 / nx as f64;
            let z = -PLANE_DEPTH * k as f64 / nz as f64;
            m.positions.push(DVec3::new(x, 0.0, z));
            m.normals.push(DVec3::Y);
        }
    }
    let idx = |i: u32, k: u32| k * (nx + 1) + i;
    let st = |i: u32| {
        let p = m.positions[i as usize];
        DVec2::new((p.x + PLANE_HALF_WIDTH) / width, -p.z / width)
    };
    let mut triangles = Vec::new();
    for k in 0..nz {
        for i in 0..nx {
            // Counter-clockwise seen from +y: z decreases away from the viewer.
            let (a, b) = (idx(i, k), idx(i + 1, k));
            let (c, d) = (idx(i + 1, k + 1), idx(i, k + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    m.uvs = triangles.iter().map(|t| t.map(st)).collect();
    m.triangles = triangles;
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn face_normal(m: &Mesh, t: [u32; 3]) -> DVec3 {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        (b - a).cross(c - a)
    }

    #[test]
    fn sphere_counts_follow_rez() {
        for rez in [3u32, 4, 7, 50, 100] {
            let m = uv_sphere(rez).unwrap();
            assert_eq!(m.positions.len() as u32, rez * rez - rez + 2, "rez {rez}");
            assert_eq!(m.normals.len(), m.positions.len());
            assert_eq!(m.triangles.len() as u32, 2 * rez * (rez - 1), "rez {rez}");
        }
    }

    #[test]
    fn sphere_normals_unit_outward_and_faces_outward_nondegenerate() {
        for rez in [3u32, 5, 50, 100] {
            let m = uv_sphere(rez).unwrap();
            m.validate().unwrap();
            for (p, n) in m.positions.iter().zip(&m.normals) {
                assert!((n.length() - 1.0).abs() < 1e-15);
                assert!((p.length() - 1.0).abs() < 1e-15);
                assert!(
                    n.dot(*p) > 1.0 - 1e-15,
                    "normal not along the radius at {p}"
                );
            }
            for &t in &m.triangles {
                let f = face_normal(&m, t);
                assert!(f.length() > 1e-9, "degenerate triangle {t:?} at rez {rez}");
                let centroid = t.iter().map(|&i| m.positions[i as usize]).sum::<DVec3>();
                assert!(
                    f.dot(centroid) > 0.0,
                    "triangle {t:?} winds inwards at rez {rez}"
                );
            }
        }
    }

    #[test]
    fn sphere_is_closed_each_edge_used_once_per_direction() {
        let m = uv_sphere(6).unwrap();
        let mut edges = HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1, "edge {a}->{b} used {n} times");
            assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}->{b} has no twin");
        }
    }

    #[test]
    fn torus_normals_outward_and_closed() {
        let m = torus(8).unwrap();
        assert_eq!(m.positions.len(), 2 * 64);
        assert_eq!(m.triangles.len(), 4 * 64);
        m.validate().unwrap();
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let tube_centre = DVec3::new(p.x, 0.0, p.z).normalize() * TORUS_MAJOR;
            let radial = *p - tube_centre;
            assert!((radial.length() - TORUS_MINOR).abs() < 1e-12);
            assert!((radial.normalize() - *n).length() < 1e-12);
        }
        for &t in &m.triangles {
            let f = face_normal(&m, t);
            let n = t.iter().map(|&i| m.normals[i as usize]).sum::<DVec3>();
            assert!(f.dot(n) > 0.0, "triangle {t:?} winds inwards");
        }
    }

    /// Texture coordinates against the shapes' parametrisation: each corner's (s, t) names its
    /// vertex's angles, and no triangle wraps around a seam (its s and t span one step).
    #[test]
    fn texture_coordinates_follow_the_parametrisation() {
        use std::f64::consts::{PI, TAU};
        let close = |a: f64, b: f64, period: f64| {
            let d = (a - b).rem_euclid(period);
            d.min(period - d) < 1e-9
        };
        for rez in [3, 7, 50] {
            let m = uv_sphere(rez).unwrap();
            assert_eq!(m.uvs.len(), m.triangles.len());
            for (t, uv) in m.triangles.iter().zip(&m.uvs) {
                for (&i, st) in t.iter().zip(uv) {
                    let p = m.positions[i as usize];
                    assert!((st.y - (1.0 - p.y.clamp(-1.0, 1.0).acos() / PI)).abs() < 1e-9);
                    if p.y.abs() < 1.0 - 1e-12 {
                        assert!(close(st.x * PI, p.x.atan2(p.z), TAU), "{p} {st}");
                    }
                }
                let span = |f: fn(&DVec2) -> f64| {
                    let v = uv.map(|c| f(&c));
                    v.iter().cloned().fold(f64::MIN, f64::max)
                        - v.iter().cloned().fold(f64::MAX, f64::min)
                };
                assert!(span(|c| c.x) <= 2.0 / rez as f64 + 1e-12);
                assert!(span(|c| c.y) <= 1.0 / rez as f64 + 1e-12);
            }
            let m = torus(rez).unwrap();
            assert_eq!(m.uvs.len(), m.triangles.len());
            for (t, uv) in m.triangles.iter().zip(&m.uvs) {
                for (&i, st) in t.iter().zip(uv) {
                    let p = m.positions[i as usize];
                    // s = 3·(angle about y)/2π, t = (angle about the tube)/2π.
                    assert!(close(st.x / 3.0 * TAU, p.z.atan2(p.x), TAU), "{p} {st}");
                    let r = (p.x * p.x + p.z * p.z).sqrt() - TORUS_MAJOR;
                    assert!(close(st.y * TAU, p.y.atan2(r), TAU), "{p} {st}");
                }
            }
        }
        let m = plane(50).unwrap();
        m.validate().unwrap();
        assert_eq!(m.triangles.len(), 2 * 5 * 25);
        for (t, uv) in m.triangles.iter().zip(&m.uvs) {
            let p = t.map(|i| m.positions[i as usize]);
            // Counter-clockwise seen from above: the face normal is +y.
            assert!((p[1] - p[0])
                .cross(p[2] - p[0])
                .normalize()
                .abs_diff_eq(DVec3::Y, 1e-12));
            for (q, st) in p.iter().zip(uv) {
                let w = 2.0 * PLANE_HALF_WIDTH;
                assert!((st.x - (q.x + PLANE_HALF_WIDTH) / w).abs() < 1e-12);
                assert!((st.y + q.z / w).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn rez_outside_range_is_an_error() {
        for rez in [0, 2, 101, 1000] {
            let e = uv_sphere(rez).unwrap_err().to_string();
            assert!(e.contains("3..=100") && e.contains(&rez.to_string()), "{e}");
            assert!(torus(rez).is_err());
        }
    }

    /// The index check at its boundary: the last vertex is fine, one past it is an error that
    /// names the triangle, the index and the count.
    #[test]
    fn index_check_accepts_the_last_vertex_and_rejects_one_past_it() {
        let mut m = uv_sphere(3).unwrap();
        let count = m.positions.len() as u32;
        m.triangles[4][2] = count - 1;
        m.validate().unwrap();
        m.triangles[4][2] = count;
        assert_eq!(
            m.validate().unwrap_err(),
            SceneError::BadIndex {
                origin: "mesh".into(),
                triangle: 4,
                index: count,
                count: count as usize,
            }
        );
        assert_eq!(first_bad_index(&[[0, 1, 2]], 3), None);
        assert_eq!(first_bad_index(&[[0, 1, 2], [2, 3, 1]], 3), Some((1, 3)));
    }
}
