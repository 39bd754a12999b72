//! Scenes: procedural UV sphere and torus, OBJ meshes, the camera, projection to integer screen
//! addresses with back-face culling, and the directional light.
//!
//! Model space is right-handed with y up. Meshes wind counter-clockwise seen from outside.
//!
//! **Camera model: orthographic.** The shading model puts the viewer at infinity (V = +z in view
//! space, constant over the frame, see `types.rs`); an orthographic projection is the projection
//! that matches it, so the faces kept by screen-space culling are exactly those whose geometric
//! normal faces V (up to the rounding of vertex addresses), and the depth is affine in screen
//! space, so a depth plane per triangle is exact. The thesis prototype used a 45° perspective
//! with the eye about 4 radii away; at that distance the difference in silhouette is a few
//! percent and the shading methods compared here do not depend on it.

use std::collections::HashMap;
use std::path::Path;

use glam::{DQuat, DVec2, DVec3};

use crate::types::{ScreenTriangle, ScreenVertex, MAX_ADDRESS};

/// Tessellation range of the thesis prototype's "Sphere Rez" slider (also used for the torus).
pub const REZ_RANGE: std::ops::RangeInclusive<u32> = 3..=100;

/// Largest canvas side: every pixel address must fit 12 bits.
pub const MAX_CANVAS: u32 = MAX_ADDRESS as u32 + 1;

/// Elevation of the light above the view-space xz plane, in degrees (see [`light_direction`]).
pub const LIGHT_ELEVATION_DEG: f64 = 45.0;

/// Torus radii: distance from the centre to the tube's centre line, and the tube's radius.
pub const TORUS_MAJOR: f64 = 1.0;
pub const TORUS_MINOR: f64 = 0.4;

/// Everything that can go wrong building or projecting a scene. Messages are one line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    #[error("{shape} rez {rez} is outside the allowed range 3..=100")]
    Rez { shape: &'static str, rez: u32 },
    #[error("light angle {0}° is outside the allowed range 0..=360")]
    LightAngle(f64),
    #[error("OBJ file {path} not found")]
    ObjMissing { path: String },
    #[error("OBJ file {path} cannot be read: {reason}")]
    ObjUnreadable { path: String, reason: String },
    #[error("OBJ file {path} is malformed: {reason}")]
    ObjMalformed { path: String, reason: String },
    #[error("OBJ file {path} holds no triangles")]
    ObjEmpty { path: String },
    #[error("{origin}: normals are given for {normals} of {vertices} vertices (all or none)")]
    NormalCount {
        origin: String,
        normals: usize,
        vertices: usize,
    },
    #[error("{origin}: vertex {vertex} has a non-finite coordinate {value}")]
    BadPosition {
        origin: String,
        vertex: usize,
        value: f64,
    },
    #[error("{origin}: vertex {vertex} has a {problem} normal")]
    BadNormal {
        origin: String,
        vertex: usize,
        problem: &'static str,
    },
    #[error("{origin}: triangle {triangle} refers to vertex {index}, but there are {count}")]
    BadIndex {
        origin: String,
        triangle: usize,
        index: u32,
        count: usize,
    },
    #[error("{origin}: {positions} positions but {normals} normals")]
    Inconsistent {
        origin: String,
        positions: usize,
        normals: usize,
    },
    #[error("canvas {width}x{height} is empty")]
    CanvasEmpty { width: u32, height: u32 },
    #[error(
        "canvas {width}x{height} exceeds the 12-bit address range (at most 4096 pixels per side)"
    )]
    CanvasTooLarge { width: u32, height: u32 },
    #[error(
        "triangle {triangle}: vertex {vertex} projects to screen {axis} = {value}, outside the 12-bit address range 0..=4095"
    )]
    AddressRange {
        triangle: usize,
        vertex: u32,
        axis: char,
        value: f64,
    },
}

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
    /// Checks what [`project`] relies on: as many normals as positions, indices in range,
    /// finite positions, finite non-zero normals.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.check("mesh")
    }

    fn check(&self, origin: &str) -> Result<(), SceneError> {
        if self.normals.len() != self.positions.len() {
            return Err(SceneError::Inconsistent {
                origin: origin.into(),
                positions: self.positions.len(),
                normals: self.normals.len(),
            });
        }
        for (vertex, p) in self.positions.iter().enumerate() {
            if let Some(&value) = p.to_array().iter().find(|c| !c.is_finite()) {
                return Err(SceneError::BadPosition {
                    origin: origin.into(),
                    vertex,
                    value,
                });
            }
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
        for (triangle, t) in self.triangles.iter().enumerate() {
            if let Some(&index) = t.iter().find(|&&i| i as usize >= count) {
                return Err(SceneError::BadIndex {
                    origin: origin.into(),
                    triangle,
                    index,
                    count,
                });
            }
        }
        Ok(())
    }
}

/// Why `n` cannot be normalized, if it cannot.
fn normal_problem(n: DVec3) -> Option<&'static str> {
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

/// Loads a Wavefront OBJ through `tobj` (polygons triangulated, one index per vertex; points
/// and lines ignored; materials ignored). All objects of the file are merged into one mesh.
///
/// Normals given in the file are normalized; an object without normals gets smooth,
/// area-weighted vertex normals, accumulated over all triangles that share the vertex's
/// *position* (so texture seams do not become shading seams). Vertex numbers in errors are the
/// 0-based indices of the loaded mesh (vertices in order of first use by a face).
pub fn load_obj(path: &Path) -> Result<Mesh, SceneError> {
    let shown = path.display().to_string();
    if path.is_dir() {
        return Err(SceneError::ObjUnreadable {
            path: shown,
            reason: "is a directory".into(),
        });
    }
    // `..Default::default()` keeps this compiling if a tobj feature adds option fields.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let (models, _materials) = tobj::load_obj(path, &options).map_err(|e| match e {
        tobj::LoadError::OpenFileFailed if !path.exists() => SceneError::ObjMissing {
            path: shown.clone(),
        },
        tobj::LoadError::OpenFileFailed | tobj::LoadError::ReadError => SceneError::ObjUnreadable {
            path: shown.clone(),
            reason: e.to_string(),
        },
        e => SceneError::ObjMalformed {
            path: shown.clone(),
            reason: e.to_string(),
        },
    })?;
    let origin = format!("OBJ file {shown}");
    let mut mesh = Mesh::default();
    for model in &models {
        let m = &model.mesh;
        let base = mesh.positions.len();
        let count = m.positions.len() / 3;
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64)),
        );
        let tris: Vec<[u32; 3]> = m
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(|i| i + base as u32))
            .collect();
        for (triangle, t) in tris.iter().enumerate() {
            if let Some(&index) = t.iter().find(|&&i| i as usize >= base + count) {
                let triangle = mesh.triangles.len() + triangle;
                let count = base + count;
                return Err(SceneError::BadIndex {
                    origin,
                    triangle,
                    index,
                    count,
                });
            }
        }
        for (k, p) in mesh.positions[base..].iter().enumerate() {
            if let Some(&value) = p.to_array().iter().find(|c| !c.is_finite()) {
                return Err(SceneError::BadPosition {
                    origin,
                    vertex: base + k,
                    value,
                });
            }
        }
        if m.normals.is_empty() {
            let computed = smooth_normals(&mesh.positions[base..], &tris, base);
            for (k, n) in computed.into_iter().enumerate() {
                mesh.normals.push(n.ok_or_else(|| SceneError::BadNormal {
                    origin: origin.clone(),
                    vertex: base + k,
                    problem: "zero-length computed",
                })?);
            }
        } else if m.normals.len() == m.positions.len() {
            for (k, c) in m.normals.chunks_exact(3).enumerate() {
                let n = DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64);
                if let Some(problem) = normal_problem(n) {
                    return Err(SceneError::BadNormal {
                        origin,
                        vertex: base + k,
                        problem,
                    });
                }
                mesh.normals.push(n.normalize());
            }
        } else {
            return Err(SceneError::NormalCount {
                origin,
                normals: m.normals.len() / 3,
                vertices: count,
            });
        }
        mesh.triangles.extend(tris);
    }
    if mesh.triangles.is_empty() {
        return Err(SceneError::ObjEmpty { path: shown });
    }
    mesh.check(&origin)?;
    Ok(mesh)
}

/// Area-weighted vertex normals of the triangles `tris` (indices offset by `base`) over
/// `positions`, shared by vertices at the same position; `None` where the sum vanishes.
fn smooth_normals(positions: &[DVec3], tris: &[[u32; 3]], base: usize) -> Vec<Option<DVec3>> {
    let key = |p: DVec3| p.to_array().map(|c| (c + 0.0).to_bits());
    let mut sums: HashMap<[u64; 3], DVec3> = HashMap::new();
    for t in tris {
        let [a, b, c] = t.map(|i| positions[i as usize - base]);
        // |(b − a) × (c − a)| is twice the area: the weight.
        let n = (b - a).cross(c - a);
        for p in [a, b, c] {
            *sums.entry(key(p)).or_insert(DVec3::ZERO) += n;
        }
    }
    positions
        .iter()
        .map(|&p| {
            let s = sums.get(&key(p)).copied().unwrap_or(DVec3::ZERO);
            (normal_problem(s).is_none()).then(|| s.normalize())
        })
        .collect()
}

/// Orthographic camera. A model point p goes to view space as `rotation · (p − centre)`
/// (viewer looking down −z, y up), then to the continuous screen position
/// `(screen_centre.x + scale·v.x, screen_centre.y − scale·v.y)` (screen y down) with depth
/// `−v.z` (smaller is nearer; 0 at `centre`, in model units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub rotation: DQuat,
    /// Model-space point that lands on `screen_centre`.
    pub centre: DVec3,
    /// Pixels per model unit.
    pub scale: f64,
    /// Continuous screen position of `centre`.
    pub screen_centre: DVec2,
}

impl Camera {
    /// Fraction of the shorter canvas side left free around the bounding sphere (half on each
    /// side): the sphere's diameter spans 95 % of it.
    pub const MARGIN: f64 = 0.05;

    /// Frames the mesh's bounding sphere (centre of the bounding box, radius to the farthest
    /// vertex) in the middle of a `width`×`height` canvas, its diameter `1 − MARGIN` of the
    /// shorter side, after rotating the mesh by `rotation` about that centre. The rotation is
    /// normalized; a mesh of zero extent gets scale 1.
    pub fn fit(mesh: &Mesh, width: u32, height: u32, rotation: DQuat) -> Camera {
        let (lo, hi) = mesh.positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let centre = if mesh.positions.is_empty() {
            DVec3::ZERO
        } else {
            (lo + hi) * 0.5
        };
        let radius = mesh
            .positions
            .iter()
            .map(|&p| (p - centre).length())
            .fold(0.0, f64::max);
        let half = width.min(height) as f64 * 0.5 * (1.0 - Self::MARGIN);
        let scale = if radius > 0.0 && radius.is_finite() {
            half / radius
        } else {
            1.0
        };
        Camera {
            rotation: rotation.normalize(),
            centre,
            scale,
            screen_centre: DVec2::new(width as f64 * 0.5, height as f64 * 0.5),
        }
    }

    /// View-space position of a model point.
    pub fn view(&self, p: DVec3) -> DVec3 {
        self.rotation * (p - self.centre)
    }

    /// Continuous screen position (x, y) and depth (z) of a model point, before rounding.
    pub fn screen(&self, p: DVec3) -> DVec3 {
        let v = self.view(p);
        DVec3::new(
            self.screen_centre.x + self.scale * v.x,
            self.screen_centre.y - self.scale * v.y,
            -v.z,
        )
    }
}

/// Integer screen addresses of every mesh vertex: the continuous screen positions rounded to the
/// nearest integer, then *repaired* where rounding folds the projected surface over itself.
///
/// Why. Rounding moves each vertex by up to half a pixel. That can reverse the orientation of a
/// sub-pixel-thin triangle (at the silhouette, where faces are seen edge-on, and in the slivers
/// around a sphere's poles). The projected surface then folds: two front faces cover the same
/// pixels, and a back-face-culled convex mesh is no longer written exactly once.
///
/// What makes coverage exact. Let D be the faces drawn (negative area in mesh order, see
/// [`project`]), plus the zero-area faces that are front faces before rounding (they cover no
/// pixel). At any sample point, the number of faces of D covering it equals the winding number
/// of the boundary of D (its directed edges whose reverse is not in D) around it, whatever the
/// vertex positions; the fill convention makes that hold pixel by pixel. So each pixel is
/// written at most once exactly when that boundary winds 0 or 1 times around every pixel centre,
/// and the repair below runs exactly when plain rounding would write some pixel twice.
///
/// Repair. Only for views whose continuous projection is single-layer (the boundary of the
/// continuous front faces winds 0 or 1 times around every pixel centre: any convex mesh, e.g.
/// the sphere; a non-convex mesh that overlaps itself keeps plain rounding, and the depth buffer
/// resolves its overlaps). In passes, while the rounded boundary winds otherwise around some
/// pixel centre (`overlaps` finds the row spans and the two boundary edges bounding each),
/// every *broken* face (rounded to the other orientation than before rounding) on either side
/// of those edges is mended:
/// 1. *re-snap*: one of its vertices rounds the other way in x, in y or both (a corner of the
///    unit cell holding its continuous position): the corner nearest that position that mends
///    the face and breaks no other face around that vertex (among its three vertices, the
///    smallest move wins); each re-snap lowers the number of broken faces;
/// 2. if no such move exists, its shortest edge *collapses*: both end vertices (with every
///    vertex already merged with them) take one address, that of whichever end is nearer the
///    mean of their continuous positions; each collapse lowers the number of vertex groups.
///
/// A pass that finds no broken face collapses the shorter of its first span's two boundary
/// edges instead. Every step lowers (vertex groups, broken faces) lexicographically, so the
/// loop ends.
///
/// Vertices with bit-identical model positions (OBJ seams) start in one group, so the repair
/// never opens a crack between them. Where rounding folds nothing (e.g. the default scene) the
/// result is exactly the rounded positions; otherwise a vertex only ever moves to a corner of its
/// own unit cell or to the address of a vertex it is merged with. Addresses stay in 0..=4095 when the rounded
/// ones are; [`project`] checks the 12-bit range. The mesh must be valid ([`Mesh::validate`]:
/// indices in range, finite positions), as [`project`] ensures before calling this.
pub fn screen_addresses(mesh: &Mesh, camera: &Camera) -> Vec<DVec2> {
    let exact: Vec<DVec2> = mesh
        .positions
        .iter()
        .map(|&p| camera.screen(p).truncate())
        .collect();
    Snapper::new(mesh, exact).run()
}

/// Working state of [`screen_addresses`]: a union-find over vertices with, per group (root), the
/// sum and count of the continuous positions, the current address and the incident faces.
struct Snapper<'m> {
    tris: &'m [[u32; 3]],
    exact: Vec<DVec2>,
    /// Whether each face is a front face before rounding.
    front: Vec<bool>,
    parent: Vec<usize>,
    sum: Vec<DVec2>,
    count: Vec<f64>,
    addr: Vec<DVec2>,
    incident: Vec<Vec<usize>>,
}

/// A directed boundary edge between two vertex groups, and the face of D it belongs to.
struct BoundaryEdge {
    ends: [usize; 2],
    face: usize,
}

fn area2(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Every span of a pixel-centre row (y = r + 0.5) that holds a pixel centre around which the
/// closed chain of directed `edges` winds other than 0 or 1 times, as the indices of the two
/// edges bounding it. Winding counts +1 for each edge crossed going down the screen (y
/// increasing), −1 going up, sweeping from the left; a front face (negative area) alone winds
/// +1. For integer end points the crossings, and so the tie with a centre lying exactly on an
/// edge, are computed exactly.
fn overlaps(edges: &[[DVec2; 2]]) -> Vec<[usize; 2]> {
    // Rows r with r + 0.5 inside the 12-bit range (and one beyond); edges bucketed per row.
    let row = |y: f64| (y - 0.5).clamp(-2.0, MAX_ADDRESS as f64 + 2.0);
    let (r0, r1) = (-1i64, MAX_ADDRESS as i64 + 1);
    let mut rows: Vec<Vec<usize>> = vec![Vec::new(); (r1 - r0 + 1) as usize];
    for (k, &[a, b]) in edges.iter().enumerate() {
        if a.y == b.y || !(a.y.is_finite() && b.y.is_finite()) {
            continue;
        }
        let (lo, hi) = (
            row(a.y.min(b.y)).ceil() as i64,
            row(a.y.max(b.y)).floor() as i64,
        );
        for r in lo.max(r0)..=hi.min(r1) {
            rows[(r - r0) as usize].push(k);
        }
    }
    let mut xs: Vec<(f64, i32, usize)> = Vec::new();
    let mut found = Vec::new();
    for (i, ks) in rows.iter().enumerate() {
        let y = (r0 + i as i64) as f64 + 0.5;
        xs.clear();
        for &k in ks {
            let [a, b] = edges[k];
            if (a.y <= y) != (b.y <= y) {
                // From the upper end, so that a segment and its reverse cross at the same x.
                let (p, q) = if a.y < b.y { (a, b) } else { (b, a) };
                let x = p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y);
                xs.push((x, if a.y < b.y { 1 } else { -1 }, k));
            }
        }
        xs.sort_by(|p, q| p.0.total_cmp(&q.0));
        let mut w = 0;
        for j in 0..xs.len() {
            w += xs[j].1;
            // The span [x_j, x_j+1) holds a pixel centre c + 0.5 (a centre exactly on a
            // crossing belongs to the span on its right, as the fill convention has it).
            let holds_centre = j + 1 < xs.len() && (xs[j].0 - 0.5).ceil() + 0.5 < xs[j + 1].0;
            if holds_centre && !(0..=1).contains(&w) {
                found.push([xs[j].2, xs[j + 1].2]);
            }
        }
    }
    found
}

impl<'m> Snapper<'m> {
    fn new(mesh: &'m Mesh, exact: Vec<DVec2>) -> Self {
        let n = exact.len();
        let front = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| exact[i as usize]);
                area2(a, b, c) < 0.0
            })
            .collect();
        let mut incident = vec![Vec::new(); n];
        for (k, t) in mesh.triangles.iter().enumerate() {
            for &i in t {
                incident[i as usize].push(k);
            }
        }
        let mut s = Snapper {
            tris: &mesh.triangles,
            front,
            parent: (0..n).collect(),
            addr: exact.iter().map(|p| p.round()).collect(),
            sum: exact.clone(),
            exact,
            count: vec![1.0; n],
            incident,
        };
        let mut seen: HashMap<[u64; 3], usize> = HashMap::new();
        for (i, p) in mesh.positions.iter().enumerate() {
            match seen.entry(p.to_array().map(f64::to_bits)) {
                std::collections::hash_map::Entry::Occupied(e) => s.union(*e.get(), i),
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(i);
                }
            }
        }
        s
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        self.parent[rb] = ra;
        let (s, c) = (self.sum[rb], self.count[rb]);
        self.sum[ra] += s;
        self.count[ra] += c;
        let mean = self.sum[ra] / self.count[ra];
        if self.addr[rb].distance_squared(mean) < self.addr[ra].distance_squared(mean) {
            self.addr[ra] = self.addr[rb];
        }
        let moved = std::mem::take(&mut self.incident[rb]);
        self.incident[ra].extend(moved);
    }

    fn groups(&mut self, t: usize) -> [usize; 3] {
        self.tris[t].map(|i| self.find(i as usize))
    }

    /// Whether face `t` is broken with group `g` placed at `at` (the others where they are): a
    /// front face rounded to a back face, or the reverse.
    fn broken_with(&mut self, t: usize, g: usize, at: DVec2) -> bool {
        let p = self
            .groups(t)
            .map(|r| if r == g { at } else { self.addr[r] });
        let a = area2(p[0], p[1], p[2]);
        if self.front[t] {
            a > 0.0
        } else {
            a < 0.0
        }
    }

    fn broken(&mut self, t: usize) -> bool {
        let g = self.find(self.tris[t][0] as usize);
        let at = self.addr[g];
        self.broken_with(t, g, at)
    }

    /// Whether face `t` belongs to D: drawn, or of zero area and a front face before rounding.
    fn in_chain(&mut self, t: usize, rounded: bool) -> bool {
        if !rounded {
            return self.front[t];
        }
        let p = self.groups(t).map(|g| self.addr[g]);
        let a = area2(p[0], p[1], p[2]);
        a < 0.0 || (a == 0.0 && self.front[t])
    }

    /// The boundary of D (rounded addresses, or the continuous positions), in a fixed order.
    fn boundary(&mut self, rounded: bool) -> Vec<BoundaryEdge> {
        let mut count: HashMap<[usize; 2], (i32, usize)> = HashMap::new();
        for t in 0..self.tris.len() {
            if !self.in_chain(t, rounded) {
                continue;
            }
            let r = self.groups(t);
            for k in 0..3 {
                let e = [r[k], r[(k + 1) % 3]];
                if e[0] != e[1] {
                    count.entry(e).or_insert((0, t)).0 += 1;
                }
            }
        }
        let mut out = Vec::new();
        for (&[u, v], &(n, face)) in &count {
            let m = n - count.get(&[v, u]).map_or(0, |c| c.0);
            for _ in 0..m.max(0) {
                out.push(BoundaryEdge { ends: [u, v], face });
            }
        }
        out.sort_by_key(|e| (e.ends, e.face));
        out
    }

    fn segments(&self, edges: &[BoundaryEdge], rounded: bool) -> Vec<[DVec2; 2]> {
        let pos = if rounded { &self.addr } else { &self.exact };
        edges.iter().map(|e| e.ends.map(|g| pos[g])).collect()
    }

    /// The nearest address to the group's continuous position, among the four corners of the
    /// unit cell holding it (so no coordinate moves by a pixel or more), that mends `t` and
    /// breaks no other face of the group, with its distance.
    fn resnap(&mut self, t: usize, g: usize) -> Option<(f64, DVec2)> {
        let here = self.addr[g];
        let centre = self.sum[g] / self.count[g];
        let in_range = |p: DVec2| {
            (0.0..=MAX_ADDRESS as f64).contains(&p.x) && (0.0..=MAX_ADDRESS as f64).contains(&p.y)
        };
        let (lo, hi) = (centre.floor(), centre.ceil());
        let mut candidates: Vec<DVec2> = [(lo.x, lo.y), (hi.x, lo.y), (lo.x, hi.y), (hi.x, hi.y)]
            .into_iter()
            .map(|(x, y)| DVec2::new(x, y))
            .filter(|&p| p != here && (in_range(p) || !in_range(here)))
            .collect();
        candidates.sort_by(|a, b| a.distance(centre).total_cmp(&b.distance(centre)));
        candidates.dedup();
        let around = self.incident[g].clone();
        candidates.into_iter().find_map(|at| {
            let ok =
                !self.broken_with(t, g, at) && around.iter().all(|&u| !self.broken_with(u, g, at));
            ok.then(|| (at.distance(centre), at))
        })
    }

    /// Mends broken face `t`: a re-snap if one exists, else the collapse of its shortest edge.
    fn mend(&mut self, t: usize) {
        let groups = self.groups(t);
        let best = groups
            .iter()
            .filter_map(|&g| self.resnap(t, g).map(|(d, at)| (d, g, at)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, g, at)) = best {
            self.addr[g] = at;
            return;
        }
        let p = groups.map(|g| self.addr[g]);
        let (a, b) = [(0, 1), (1, 2), (2, 0)]
            .into_iter()
            .min_by(|&(a, b), &(c, d)| {
                p[a].distance_squared(p[b])
                    .total_cmp(&p[c].distance_squared(p[d]))
            })
            .expect("three edges");
        self.union(groups[a], groups[b]);
    }

    /// One repair pass; false when the rounded boundary of D winds 0 or 1 times everywhere.
    /// Every broken face beside an offending span is mended (state is re-read face by face);
    /// only if none was broken does the first span's shorter boundary edge collapse.
    fn mend_folds(&mut self) -> bool {
        let edges = self.boundary(true);
        let segments = self.segments(&edges, true);
        let spans = overlaps(&segments);
        if spans.is_empty() {
            return false;
        }
        let mut mended = false;
        let mut seen = std::collections::HashSet::new();
        for pair in &spans {
            // The faces on both sides of the two edges: the face of D, and the faces across.
            for &k in pair {
                if !seen.insert(k) {
                    continue;
                }
                // Earlier mends of this pass may have merged groups.
                let [u, v] = edges[k].ends.map(|g| self.find(g));
                let mut suspects = vec![edges[k].face];
                for t in self.incident[v].clone() {
                    let r = self.groups(t);
                    if (0..3).any(|i| r[i] == v && r[(i + 1) % 3] == u) {
                        suspects.push(t);
                    }
                }
                for t in suspects {
                    if self.broken(t) {
                        self.mend(t);
                        mended = true;
                    }
                }
            }
        }
        if !mended {
            let pair = spans[0];
            let length = |k: usize| segments[k][0].distance(segments[k][1]);
            let k = if length(pair[0]) <= length(pair[1]) {
                pair[0]
            } else {
                pair[1]
            };
            // A crossing edge has distinct end addresses, so its ends are in distinct groups.
            self.union(edges[k].ends[0], edges[k].ends[1]);
        }
        true
    }

    fn run(mut self) -> Vec<DVec2> {
        let continuous = self.boundary(false);
        if overlaps(&self.segments(&continuous, false)).is_empty() {
            while self.mend_folds() {}
        }
        (0..self.parent.len())
            .map(|i| {
                let r = self.find(i);
                self.addr[r]
            })
            .collect()
    }
}

/// Projects the mesh through the camera onto a `width`×`height` canvas.
///
/// - Vertex addresses are the continuous screen positions rounded to the nearest integer and
///   repaired where rounding would fold a triangle ([`screen_addresses`]).
/// - Back-face culling by the sign of the screen-space area of the vertex addresses: a face
///   whose outside faces the viewer winds counter-clockwise as seen, which in y-down screen
///   coordinates is a *negative* [`ScreenTriangle::area2`] in the mesh's vertex order. Those are
///   kept; positive ones (back faces) and zero-area ones (edge-on, or collapsed by rounding: they
///   cover no pixel centre) are dropped.
/// - Kept triangles are emitted as (v0, v2, v1), so every returned triangle has `area2() > 0`
///   (clockwise on screen, y down), whatever the mesh. The walk does not depend on the order.
/// - Normals are rotated into view space (unit, viewer looking down −z).
/// - Every vertex of a kept triangle must lie in 0..=4095 in x and y (12-bit addresses);
///   vertices off the canvas but inside that range are fine (the renderer discards off-canvas
///   pixels). The canvas itself must be at most 4096×4096.
pub fn project(
    mesh: &Mesh,
    camera: &Camera,
    width: u32,
    height: u32,
) -> Result<Vec<ScreenTriangle>, SceneError> {
    if width == 0 || height == 0 {
        return Err(SceneError::CanvasEmpty { width, height });
    }
    if width > MAX_CANVAS || height > MAX_CANVAS {
        return Err(SceneError::CanvasTooLarge { width, height });
    }
    mesh.validate()?;
    let screen: Vec<DVec3> = mesh.positions.iter().map(|&p| camera.screen(p)).collect();
    let rounded: Vec<(f64, f64)> = screen_addresses(mesh, camera)
        .iter()
        .map(|a| (a.x, a.y))
        .collect();
    let mut out = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|i| rounded[i as usize]);
        // Exact for in-range integers; for wild values only the range error below matters.
        let area2 = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
        if area2 >= 0.0 {
            continue; // back-facing or zero area (a NaN area falls through to the range check)
        }
        let mut v = [ScreenVertex {
            x: 0,
            y: 0,
            z: 0.0,
            normal: DVec3::Z,
        }; 3];
        for (k, &i) in [tri[0], tri[2], tri[1]].iter().enumerate() {
            let s = screen[i as usize];
            for (axis, value, r) in [
                ('x', s.x, rounded[i as usize].0),
                ('y', s.y, rounded[i as usize].1),
            ] {
                if !(0.0..=MAX_ADDRESS as f64).contains(&r) {
                    return Err(SceneError::AddressRange {
                        triangle: t,
                        vertex: i,
                        axis,
                        value,
                    });
                }
            }
            v[k] = ScreenVertex {
                x: rounded[i as usize].0 as i32,
                y: rounded[i as usize].1 as i32,
                z: s.z,
                normal: (camera.rotation * mesh.normals[i as usize]).normalize(),
            };
        }
        let st = ScreenTriangle { v };
        debug_assert!(st.area2() > 0);
        out.push(st);
    }
    Ok(out)
}

/// Unit view-space vector towards the light for the prototype's light angle `deg` in 0..=360:
/// `(cos θ·cos ε, sin ε, sin θ·cos ε)` with elevation ε = [`LIGHT_ELEVATION_DEG`] = 45°.
/// At the default 90° the light comes from the front-top, at 0° from the right, at 180° from the
/// left. The 45° matches the prototype, which rotates the vector (1, 1, 0) about y by the
/// angle: `rotateY(θ)·(1, 1, 0, 0) = (cos θ, 1, sin θ, 0)`.
pub fn light_direction(deg: f64) -> Result<DVec3, SceneError> {
    if !(0.0..=360.0).contains(&deg) {
        return Err(SceneError::LightAngle(deg));
    }
    let (t, e) = (deg.to_radians(), LIGHT_ELEVATION_DEG.to_radians());
    Ok(DVec3::new(t.cos() * e.cos(), e.sin(), t.sin() * e.cos()).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// A file in the system temp directory, removed on drop.
    struct TempObj(PathBuf);
    impl TempObj {
        fn new(name: &str, text: &str) -> TempObj {
            let p = std::env::temp_dir()
                .join(format!("shadecore-scene-{}-{name}.obj", std::process::id()));
            std::fs::write(&p, text).unwrap();
            TempObj(p)
        }
    }
    impl Drop for TempObj {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

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

    #[test]
    fn obj_round_trip_with_and_without_normals() {
        // A unit square in the z = 0 plane as two triangles, with normals given as (0, 0, 2).
        let with = TempObj::new(
            "with",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 2\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n",
        );
        let m = load_obj(&with.0).unwrap();
        assert_eq!(m.triangles.len(), 2);
        assert_eq!(m.positions.len(), 4);
        let want = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        for t in &m.triangles {
            for &i in t {
                assert!(want.contains(&m.positions[i as usize]));
            }
        }
        assert!(m.normals.iter().all(|&n| n == DVec3::Z), "{:?}", m.normals);

        // Without normals: two triangles meeting at a ridge along x, one with twice the area
        // of the other, get smooth area-weighted normals.
        let without = TempObj::new(
            "without",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 2\nf 1 2 3\nf 1 4 2\n",
        );
        let m = load_obj(&without.0).unwrap();
        assert_eq!(m.triangles.len(), 2);
        // Triangle 1 (in z = 0, area 1/2) has normal +z; triangle 2 (in y = 0, area 1) has
        // normal +y. Shared vertices 1 and 2 get (0, 1, 1/2)/|..| (area-weighted), vertex 3
        // only +z, vertex 4 only +y.
        let by_pos = |p: DVec3| m.normals[m.positions.iter().position(|&q| q == p).unwrap()];
        let shared = DVec3::new(0.0, 1.0, 0.5).normalize();
        assert!(
            (by_pos(DVec3::ZERO) - shared).length() < 1e-12,
            "{}",
            by_pos(DVec3::ZERO)
        );
        assert!((by_pos(DVec3::X) - shared).length() < 1e-12);
        assert!((by_pos(DVec3::Y) - DVec3::Z).length() < 1e-12);
        assert!((by_pos(DVec3::new(0.0, 0.0, 2.0)) - DVec3::Y).length() < 1e-12);
    }

    #[test]
    fn obj_quads_are_triangulated() {
        let f = TempObj::new("quad", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
        let m = load_obj(&f.0).unwrap();
        assert_eq!(m.triangles.len(), 2);
        assert!(m.normals.iter().all(|&n| (n - DVec3::Z).length() < 1e-12));
    }

    #[test]
    fn obj_errors_name_problem_and_path() {
        let missing = std::env::temp_dir().join("shadecore-definitely-missing.obj");
        let e = load_obj(&missing).unwrap_err().to_string();
        assert!(
            e.contains("not found") && e.contains("shadecore-definitely-missing"),
            "{e}"
        );

        let cases = [
            ("short-v", "v 1 2\nf 1 1 1\n", "position parse error"),
            (
                "bad-face",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
                "face parse error",
            ),
            (
                "oob",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n",
                "out of bounds",
            ),
            (
                "zero-index",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                "out of bounds",
            ),
            ("empty", "# nothing\nv 0 0 0\n", "no triangles"),
            (
                "nan",
                "v 0 0 0\nv NaN 0 0\nv 0 1 0\nf 1 2 3\n",
                "non-finite coordinate NaN",
            ),
            (
                "nan-normal",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn nan 0 1\nf 1//1 2//2 3//1\n",
                "NaN normal",
            ),
            (
                "zero-normal",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 0\nf 1//1 2//1 3//2\n",
                "zero-length normal",
            ),
            (
                "partial-normals",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3//1\n",
                "normals are given for",
            ),
            (
                "degenerate",
                "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
                "zero-length computed normal",
            ),
        ];
        for (name, text, want) in cases {
            let f = TempObj::new(name, text);
            let e = load_obj(&f.0).unwrap_err().to_string();
            assert!(e.contains(want), "{name}: {e}");
            assert!(
                e.contains(&f.0.display().to_string()),
                "{name}: path missing in {e}"
            );
            assert!(!e.contains('\n'), "{name}: not one line: {e}");
        }
    }

    #[test]
    fn nan_normal_error_names_the_vertex() {
        let f = TempObj::new(
            "nan-vertex",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn nan 0 1\nf 1//1 2//1 3//2\n",
        );
        match load_obj(&f.0).unwrap_err() {
            // Vertices are numbered in order of first use: the third corner is vertex 2.
            SceneError::BadNormal {
                vertex, problem, ..
            } => assert_eq!((vertex, problem), (2, "NaN")),
            e => panic!("unexpected error {e}"),
        }
        let mut m = uv_sphere(3).unwrap();
        m.normals[5] = DVec3::new(f64::NAN, 0.0, 1.0);
        let e = project(&m, &Camera::fit(&m, 64, 64, DQuat::IDENTITY), 64, 64).unwrap_err();
        assert_eq!(
            e,
            SceneError::BadNormal {
                origin: "mesh".into(),
                vertex: 5,
                problem: "NaN"
            }
        );
        m.normals[5] = DVec3::ZERO;
        assert!(
            project(&m, &Camera::fit(&m, 64, 64, DQuat::IDENTITY), 64, 64)
                .unwrap_err()
                .to_string()
                .contains("vertex 5 has a zero-length normal")
        );
    }

    #[test]
    fn out_of_range_coordinates_are_an_error() {
        let m = uv_sphere(8).unwrap();
        let mut cam = Camera::fit(&m, 100, 100, DQuat::IDENTITY);
        assert!(project(&m, &cam, 100, 100).is_ok());
        // Blow the sphere up so it spans ~ ±5000 pixels around the centre.
        cam.scale = 5000.0;
        let e = project(&m, &cam, 100, 100).unwrap_err();
        let s = e.to_string();
        assert!(s.contains("0..=4095") && s.contains("12-bit"), "{s}");
        match e {
            SceneError::AddressRange { value, .. } => {
                assert!(value.round() < 0.0 || value.round() > 4095.0, "{value}")
            }
            e => panic!("unexpected {e}"),
        }
        // Canvas limits.
        assert_eq!(
            project(&m, &cam, 4097, 10).unwrap_err(),
            SceneError::CanvasTooLarge {
                width: 4097,
                height: 10
            }
        );
        assert!(project(&m, &cam, 0, 10).is_err());
        // A 4096×4096 canvas is fine, and the fitted sphere stays inside it.
        let cam = Camera::fit(&m, 4096, 4096, DQuat::IDENTITY);
        assert!(!project(&m, &cam, 4096, 4096).unwrap().is_empty());
    }

    #[test]
    fn light_direction_matches_the_prototype_angles() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let l = light_direction(90.0).unwrap();
        assert!((l - DVec3::new(0.0, s, s)).length() < 1e-15, "{l}");
        assert!((light_direction(0.0).unwrap() - DVec3::new(s, s, 0.0)).length() < 1e-15);
        assert!((light_direction(180.0).unwrap() - DVec3::new(-s, s, 0.0)).length() < 1e-15);
        assert!((light_direction(360.0).unwrap() - DVec3::new(s, s, 0.0)).length() < 1e-15);
        for bad in [-0.5, 360.5, f64::NAN, f64::INFINITY] {
            let e = light_direction(bad).unwrap_err().to_string();
            assert!(e.contains("0..=360"), "{e}");
        }
    }
}
