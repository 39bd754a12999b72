//! Triangle meshes: the [`Mesh`] type and its checks, the procedural UV sphere (tessellated as
//! the thesis prototype's `drawSolidSphere`) and torus.
//!
//! Model space is right-handed with y up. Meshes wind counter-clockwise seen from outside.

use glam::DVec3;

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
    let mut triangles = Vec::with_capacity((2 * n * (n - 1)) as usize);
    for j in 0..n {
        triangles.push([0, ring(1, j), ring(1, j + 1)]);
    }
    for i in 1..n - 1 {
        for j in 0..n {
            let (a, b) = (ring(i, j), ring(i, j + 1));
            let (c, d) = (ring(i + 1, j), ring(i + 1, j + 1));
            triangles.push([a, c, d]);
            triangles.push([a, d, b]);
        }
    }
    for j in 0..n {
        triangles.push([ring(n - 1, j), south, ring(n - 1, j + 1)]);
    }
    let normals = positions.iter().map(|p| p.normalize()).collect();
    Ok(Mesh {
        positions,
        normals,
        triangles,
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
    let mut triangles = Vec::with_capacity((2 * nu * nv) as usize);
    for i in 0..nu {
        for j in 0..nv {
            // ∂P/∂v × ∂P/∂u points outwards: step along v first, then along u.
            let (a, b) = (idx(i, j), idx(i, j + 1));
            let (c, d) = (idx(i + 1, j + 1), idx(i + 1, j));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Ok(Mesh {
        positions,
        normals,
        triangles,
    })
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
