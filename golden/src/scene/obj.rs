//! Wavefront OBJ meshes: [`load_obj`] through `tobj`, the project's own checks of what `tobj`
//! returns, and smooth area-weighted normals for objects that give none.

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;

use super::mesh::{first_bad_index, first_non_finite, normal_problem, Mesh};
use super::SceneError;

/// Largest OBJ file [`load_obj`] reads (256 MiB: several million triangles).
pub const MAX_OBJ_BYTES: u64 = 256 << 20;

/// Memory a loaded mesh may take, from the file's text to the rendered frames: the budget
/// [`MAX_TRIANGLES`] and [`MAX_VERTICES`] are derived from (2 GiB).
pub const MEMORY_BUDGET_BYTES: u64 = 2 << 30;
/// Peak memory per triangle of the file, measured: `render --engine golden` (every method,
/// 64×48) of 50 000 identical faces peaks at 49 MB, of 200 000 at 182 MB (about 880 bytes a
/// face); rounded up. The RTL engine's span methods hold a set-up per raster line on top
/// (`pipeline::span::BYTES_PER_SPAN_LINE`, capped there).
pub const BYTES_PER_TRIANGLE: u64 = 1024;
/// Peak memory per `v` line of the file, measured as [`BYTES_PER_TRIANGLE`]: 1 000 000
/// vertices and one face peak at 57 MB (about 50 bytes a vertex with the file's text);
/// rounded up.
pub const BYTES_PER_VERTEX: u64 = 128;
/// Most triangles a file may hold (after polygons are split into triangles), so that a mesh of
/// that many fits in [`MEMORY_BUDGET_BYTES`].
pub const MAX_TRIANGLES: u64 = MEMORY_BUDGET_BYTES / BYTES_PER_TRIANGLE;
/// Most `v` lines a file may hold, as [`MAX_TRIANGLES`].
pub const MAX_VERTICES: u64 = MEMORY_BUDGET_BYTES / BYTES_PER_VERTEX;

/// Largest magnitude a coordinate of the file may have. The camera fit squares distances, so
/// coordinates up to 1e30 keep every intermediate far inside f64's range.
pub const MAX_COORDINATE: f64 = 1e30;
/// Smallest extent (the bounding box's longest side) a mesh may have, absolutely and relative
/// to its largest coordinate: below it, the vertices are not distinct enough in f64 to fit a
/// camera (squared distances underflow, or positions far from the origin round together).
pub const MIN_EXTENT: f64 = 1e-30;
/// The extent relative to the largest coordinate below which the mesh is refused (see
/// [`MIN_EXTENT`]); f64 keeps about 1e-16 of a coordinate.
pub const MIN_RELATIVE_EXTENT: f64 = 1e-9;

/// Loads a Wavefront OBJ through `tobj` (polygons triangulated, one index per vertex; points
/// and lines ignored; materials ignored: an `mtllib` line opens nothing). All objects of the
/// file are merged into one mesh. Coordinates are read as f64.
///
/// Only a regular file of at most [`MAX_OBJ_BYTES`] is read, holding at most [`MAX_TRIANGLES`]
/// triangles and [`MAX_VERTICES`] vertices (the memory budget), with coordinates within
/// ±[`MAX_COORDINATE`] and an extent of at least [`MIN_EXTENT`].
///
/// Normals given in the file are normalized; an object without normals gets smooth,
/// area-weighted vertex normals, accumulated over all triangles that share the vertex's
/// *position* (so texture seams do not become shading seams). Vertex numbers in errors are the
/// 0-based indices of the loaded mesh (vertices in order of first use by a face).
pub fn load_obj(path: &Path) -> Result<Mesh, SceneError> {
    load_obj_counting(path).map(|(mesh, _)| mesh)
}

/// The bytes of the regular file `path`, at most `max` of them (errors are `SceneError`'s
/// "OBJ file … cannot be read"). A device (/dev/zero) would be read until memory runs out and a named
/// pipe would block forever, so only a regular file is opened for reading (checked on the open
/// handle, so a file swapped in between is caught too), and at most `max + 1` bytes are read.
pub fn read_regular_file(path: &Path, max: u64) -> Result<Vec<u8>, SceneError> {
    use std::io::Read;
    let shown = path.display().to_string();
    let unreadable = |reason: String| SceneError::ObjUnreadable {
        path: shown.clone(),
        reason,
    };
    // The type is checked before opening: opening a named pipe for reading blocks until a
    // writer comes.
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(SceneError::ObjMissing { path: shown })
        }
        Err(e) => return Err(unreadable(e.to_string())),
    };
    if meta.is_dir() {
        return Err(unreadable("is a directory".into()));
    }
    let not_regular = || unreadable("is not a regular file (a device, pipe or socket)".into());
    if !meta.is_file() {
        return Err(not_regular());
    }
    let too_big = |len: u64| {
        unreadable(format!(
            "is {len} bytes ({:.1} MiB), above the {} MiB limit",
            len as f64 / (1u64 << 20) as f64,
            max >> 20
        ))
    };
    if meta.len() > max {
        return Err(too_big(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(|e| unreadable(e.to_string()))?;
    match file.metadata() {
        Ok(m) if m.is_file() => {}
        Ok(_) => return Err(not_regular()),
        Err(e) => return Err(unreadable(e.to_string())),
    }
    let mut bytes = Vec::new();
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| unreadable(e.to_string()))?;
    if bytes.len() as u64 > max {
        return Err(too_big(bytes.len() as u64));
    }
    Ok(bytes)
}

/// How many triangles and `v` lines `text` holds (a face of n corners is n − 2 triangles),
/// counted before `tobj` allocates anything.
fn count_elements(text: &str) -> (u64, u64) {
    let (mut tris, mut verts) = (0u64, 0u64);
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f") => tris += (words.count() as u64).saturating_sub(2),
            Some("v") => verts += 1,
            _ => {}
        }
    }
    (tris, verts)
}

/// The first `vt` line with a coordinate that reads as NaN or ±infinity (which `tobj` accepts):
/// an error naming the line, counted from 1.
fn check_vt(text: &str, shown: &str) -> Result<(), SceneError> {
    for (k, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("vt") {
            continue;
        }
        if words.any(|w| w.parse::<f64>().is_ok_and(|v| !v.is_finite())) {
            let mut text = line.trim().to_string();
            if text.len() > 60 {
                let cut = (0..=60)
                    .rev()
                    .find(|&i| text.is_char_boundary(i))
                    .unwrap_or(0);
                text.truncate(cut);
                text.push('…');
            }
            return Err(SceneError::BadVt {
                origin: format!("OBJ file {shown}"),
                line: k + 1,
                text,
            });
        }
    }
    Ok(())
}

/// [`load_obj`], also returning how many vertices got their first face's normal because the
/// area-weighted sum of their faces' normals vanished (faces that cancel, common in scans).
pub fn load_obj_counting(path: &Path) -> Result<(Mesh, usize), SceneError> {
    let shown = path.display().to_string();
    let bytes = read_regular_file(path, MAX_OBJ_BYTES)?;
    let text = std::str::from_utf8(&bytes).map_err(|u| {
        // An error means a bad byte exists at `valid_up_to`.
        let at = u.valid_up_to();
        SceneError::ObjUnreadable {
            path: shown.clone(),
            reason: format!(
                "is not UTF-8 text (byte 0x{:02x} at offset {at} is not valid UTF-8)",
                bytes[at]
            ),
        }
    })?;
    // A UTF-8 byte-order mark (some Windows tools write one) is no part of the first line.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let (tris, verts) = count_elements(text);
    check_vt(text, &shown)?;
    let budget = MEMORY_BUDGET_BYTES >> 20;
    for (count, max, what, per) in [
        (tris, MAX_TRIANGLES, "triangles", BYTES_PER_TRIANGLE),
        (verts, MAX_VERTICES, "vertices", BYTES_PER_VERTEX),
    ] {
        if count > max {
            return Err(SceneError::ObjUnreadable {
                path: shown,
                reason: format!(
                    "holds {count} {what}, above the limit of {max} that fits the {budget} MiB memory budget ({per} bytes each)"
                ),
            });
        }
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
    // Materials are not used: `mtllib` names nothing that is opened.
    let (models, _materials) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| match e {
        tobj::LoadError::ReadError => SceneError::ObjUnreadable {
            path: shown.clone(),
            reason: e.to_string(),
        },
        e => SceneError::ObjMalformed {
            path: shown.clone(),
            reason: e.to_string(),
        },
    })?;
    from_models(&models, &shown)
}

/// The mesh of the objects `tobj` loaded from the file `shown`: every check of [`load_obj`] that
/// is the project's own (index range, finite positions, normals: all or none per object, usable),
/// and the smooth normals.
fn from_models(models: &[tobj::Model], shown: &str) -> Result<(Mesh, usize), SceneError> {
    let origin = format!("OBJ file {shown}");
    let mut mesh = Mesh::default();
    let mut fallbacks = 0;
    // Triangles whose corners have texture coordinates: all or none.
    let mut textured = 0;
    for model in models {
        let m = &model.mesh;
        let base = mesh.positions.len();
        let count = m.positions.len() / 3;
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0], c[1], c[2])),
        );
        let tris: Vec<[u32; 3]> = m
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(|i| i + base as u32))
            .collect();
        // tobj's single-index output is in range by construction; checked again here, before
        // `smooth_normals` indexes with it.
        if let Some((triangle, index)) = first_bad_index(&tris, base + count) {
            return Err(SceneError::BadIndex {
                origin,
                triangle: mesh.triangles.len() + triangle,
                index,
                count: base + count,
            });
        }
        if let Some((k, value)) = first_non_finite(&mesh.positions[base..]) {
            return Err(SceneError::BadPosition {
                origin,
                vertex: base + k,
                value,
            });
        }
        if let Some((k, value)) = first_out_of_range(&mesh.positions[base..]) {
            return Err(SceneError::CoordinateRange {
                origin,
                vertex: base + k,
                value,
                max: MAX_COORDINATE,
            });
        }
        if m.normals.is_empty() {
            let computed = smooth_normals(&mesh.positions[base..], &tris, base);
            for (k, n) in computed.into_iter().enumerate() {
                let n = match n {
                    Some(n) => n,
                    None => {
                        // The faces' normals cancel: the first of its faces with an area.
                        fallbacks += 1;
                        face_normal(&mesh.positions, &tris, (base + k) as u32).unwrap_or(DVec3::Z)
                    }
                };
                mesh.normals.push(n);
            }
        } else if m.normals.len() == m.positions.len() {
            for (k, c) in m.normals.chunks_exact(3).enumerate() {
                let n = DVec3::new(c[0], c[1], c[2]);
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
        if m.texcoords.len() == 2 * count && count > 0 {
            textured += tris.len();
            mesh.uvs.extend(tris.iter().map(|t| {
                t.map(|i| {
                    let k = 2 * (i as usize - base);
                    glam::DVec2::new(m.texcoords[k], m.texcoords[k + 1])
                })
            }));
        } else if !m.texcoords.is_empty() {
            return Err(SceneError::ObjMalformed {
                path: shown.into(),
                reason: format!(
                    "texture coordinates (vt) are given for {} of {count} vertices of an object (all or none)",
                    m.texcoords.len() / 2
                ),
            });
        }
        mesh.triangles.extend(tris);
    }
    if textured != 0 && textured != mesh.triangles.len() {
        return Err(SceneError::TexCoordCount {
            origin,
            given: textured,
            triangles: mesh.triangles.len(),
        });
    }
    if mesh.triangles.is_empty() {
        return Err(SceneError::ObjEmpty { path: shown.into() });
    }
    let (lo, hi) = mesh.positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let extent = (hi - lo).max_element();
    let largest = lo.abs().max(hi.abs()).max_element();
    if extent < MIN_EXTENT || extent < MIN_RELATIVE_EXTENT * largest {
        return Err(SceneError::Extent {
            origin,
            extent,
            largest,
        });
    }
    mesh.check(&origin)?;
    Ok((mesh, fallbacks))
}

/// The first position with a coordinate beyond ±[`MAX_COORDINATE`]: its number and that
/// coordinate (as the file gives it: read as f64).
fn first_out_of_range(positions: &[DVec3]) -> Option<(usize, f64)> {
    positions.iter().enumerate().find_map(|(vertex, p)| {
        p.to_array()
            .iter()
            .find(|c| c.abs() > MAX_COORDINATE)
            .map(|&value| (vertex, value))
    })
}

/// The unit normal of the first triangle of `tris` that uses vertex `v` and has an area.
fn face_normal(positions: &[DVec3], tris: &[[u32; 3]], v: u32) -> Option<DVec3> {
    tris.iter().filter(|t| t.contains(&v)).find_map(|t| {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a);
        normal_problem(n).is_none().then(|| n.normalize())
    })
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
    fn obj_texture_coordinates_are_read_per_corner() {
        // Two triangles sharing the edge 1–3, with a texture seam along it: vertex 1 has
        // different vt in the two faces.
        let f = TempObj::new(
            "vt",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0.25 0.75\nvt 5 -2\nf 1/1 2/2 3/3\nf 1/5 3/3 4/4\n",
        );
        let m = load_obj(&f.0).unwrap();
        assert_eq!(m.uvs.len(), 2);
        let uv = |p: [f64; 3], t: usize| {
            let k = m.triangles[t]
                .iter()
                .position(|&i| m.positions[i as usize] == DVec3::from(p))
                .unwrap();
            m.uvs[t][k].to_array()
        };
        assert_eq!(uv([0.0, 0.0, 0.0], 0), [0.0, 0.0]);
        assert_eq!(uv([1.0, 0.0, 0.0], 0), [1.0, 0.0]);
        assert_eq!(uv([1.0, 1.0, 0.0], 0), [1.0, 1.0]);
        assert_eq!(uv([0.0, 0.0, 0.0], 1), [5.0, -2.0]);
        assert_eq!(uv([0.0, 1.0, 0.0], 1), [0.25, 0.75]);
        // Without vt: no texture coordinates.
        let plain = TempObj::new("novt", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        assert!(load_obj(&plain.0).unwrap().uvs.is_empty());
    }

    #[test]
    fn obj_bad_texture_coordinates_are_one_line_errors() {
        for (name, text, want) in [
            (
                "vtnan",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt nan 0\nvt 0 1\nf 1/1 2/2 3/3\n",
                "texture coordinate (vt) on line 5 is not finite: vt nan 0",
            ),
            (
                "vtinf",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 -inf\nf 1/1 2/2 3/3\n",
                "on line 6 is not finite",
            ),
            (
                "vtsome",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2 4 3\n",
                "texture coordinates",
            ),
        ] {
            let f = TempObj::new(name, text);
            let e = load_obj(&f.0).unwrap_err().to_string();
            assert!(e.contains(want), "{name}: {e}");
            assert!(!e.contains('\n'), "{name}: {e}");
        }
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
        ];
        // Faces whose normals cancel at a vertex (a two-sided sheet: the same triangle both
        // ways) load, the vertex taking its first face's normal; counted for the warning.
        let f = TempObj::new("cancel", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n");
        let (mesh, fallbacks) = load_obj_counting(&f.0).unwrap();
        assert_eq!(fallbacks, 3);
        assert!(mesh
            .normals
            .iter()
            .all(|n| (*n - DVec3::Z).length() < 1e-12));
        // Only degenerate faces: no face normal either; +Z, counted.
        let f = TempObj::new("degenerate", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
        assert_eq!(load_obj_counting(&f.0).unwrap().1, 3);
        // Not text: tobj says only "read error"; the message names the first bad byte.
        let bin =
            std::env::temp_dir().join(format!("shadecore-scene-{}-binary.obj", std::process::id()));
        std::fs::write(&bin, b"v 0 0 0\nv 1 0 \xff\xfe\n").unwrap();
        let e = load_obj(&bin).unwrap_err().to_string();
        let _ = std::fs::remove_file(&bin);
        assert!(
            e.contains("not UTF-8 text") && e.contains("0xff at offset 14") && !e.contains('\n'),
            "{e}"
        );
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
    }

    /// Face indices at the edge of what the file holds, as tobj checks them before the project's
    /// own checks: the last position, normal and texture coordinate (also by a relative index)
    /// load; one past any of them is a one-line error that names the problem and the file.
    #[test]
    fn face_indices_at_the_last_element_load_and_one_past_is_an_error() {
        let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 2\nvt 0 0\nvt 1 1\n";
        for (name, last, past, problem) in [
            ("v", "f 1 2 3", "f 1 2 4", "face vertex index out of bounds"),
            (
                "v-rel",
                "f -3 -2 -1",
                "f -4 -2 -1",
                "face vertex index out of bounds",
            ),
            (
                "vn",
                "f 1//1 2//1 3//2",
                "f 1//1 2//1 3//3",
                "face normal index out of bounds",
            ),
            (
                "vt",
                "f 1/1 2/1 3/2",
                "f 1/1 2/1 3/3",
                "face texcoord index out of bounds",
            ),
        ] {
            let ok = TempObj::new(&format!("last-{name}"), &format!("{head}{last}\n"));
            let m = load_obj(&ok.0).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(m.triangles.len(), 1, "{name}");
            let bad = TempObj::new(&format!("past-{name}"), &format!("{head}{past}\n"));
            let e = load_obj(&bad.0).unwrap_err();
            assert!(
                matches!(e, SceneError::ObjMalformed { .. }),
                "{name}: {e:?}"
            );
            let e = e.to_string();
            assert!(e.contains(problem), "{name}: {e}");
            assert!(
                e.contains(&bad.0.display().to_string()) && !e.contains('\n'),
                "{e}"
            );
        }
    }

    /// A `tobj` object built by hand: `positions` and `normals` flattened, faces as given.
    fn model(positions: &[[f64; 3]], normals: &[[f64; 3]], faces: &[[u32; 3]]) -> tobj::Model {
        let mesh = tobj::Mesh {
            positions: positions.concat(),
            normals: normals.concat(),
            indices: faces.concat(),
            ..Default::default()
        };
        tobj::Model::new(mesh, "hand-built".into())
    }

    /// The project's own index check of `load_obj`, at its boundary. tobj's single-index output
    /// is in range by construction (its own check rejects the file first, see above), so no file
    /// reaches this check: the objects are built by hand. The second object's indices are
    /// offset by the first's 3 vertices; without normals an unchecked index would reach
    /// `smooth_normals`.
    #[test]
    fn own_index_check_accepts_the_last_vertex_and_rejects_one_past_it() {
        let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let square = [tri[0], tri[1], tri[2], [1.0, 1.0, 0.0]];
        let up = [[0.0, 0.0, 1.0]; 4];
        for with_normals in [false, true] {
            let normals = |n: usize| if with_normals { &up[..n] } else { &[][..] };
            let first = model(&tri, normals(3), &[[0, 1, 2]]);
            // Vertex 3 is the last of the second object.
            let last = model(&square, normals(4), &[[0, 1, 2], [1, 3, 2]]);
            let (m, _) = from_models(&[first.clone(), last], "hand.obj").unwrap();
            assert_eq!(m.triangles, vec![[0, 1, 2], [3, 4, 5], [4, 6, 5]]);
            let past = model(&square, normals(4), &[[0, 1, 2], [1, 4, 2]]);
            let e = from_models(&[first, past], "hand.obj").unwrap_err();
            assert_eq!(
                e,
                SceneError::BadIndex {
                    origin: "OBJ file hand.obj".into(),
                    triangle: 2,
                    index: 7,
                    count: 7,
                },
                "normals given: {with_normals}"
            );
            assert_eq!(
                e.to_string(),
                "OBJ file hand.obj: triangle 2 refers to vertex 7, but there are 7"
            );
        }
    }
}
