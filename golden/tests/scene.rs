//! Scenes, camera and projection: framing, culling against the geometry, OBJ round trips.

use std::fmt::Write as _;
use std::path::PathBuf;

use glam::{DQuat, DVec3};
use golden::scene::{
    light_direction, load_obj, project, screen_addresses, torus, uv_sphere, Camera, Mesh,
    SceneError, LIGHT_ELEVATION_DEG,
};
use golden::testing::{quaternion, runner, split_vertices};
use proptest::prelude::*;

fn tmp(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("scene-{name}.obj"))
}

/// Writes `text` to the file `tmp(name)` and loads it.
fn load_text(name: &str, text: &str) -> Result<Mesh, SceneError> {
    let path = tmp(name);
    std::fs::write(&path, text).unwrap();
    load_obj(&path)
}

/// OBJ text of a mesh, optionally with its normals.
fn to_obj(m: &Mesh, normals: bool) -> String {
    let mut s = String::new();
    for p in &m.positions {
        writeln!(s, "v {} {} {}", p.x, p.y, p.z).unwrap();
    }
    if normals {
        for n in &m.normals {
            writeln!(s, "vn {} {} {}", n.x, n.y, n.z).unwrap();
        }
    }
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        if normals {
            writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}").unwrap();
        } else {
            writeln!(s, "f {a} {b} {c}").unwrap();
        }
    }
    s
}

/// Culling must agree with the geometry wherever rounding cannot change the answer, and the
/// fitted mesh must sit inside the canvas with the documented margin.
#[test]
fn projection_frames_the_mesh_and_culls_by_orientation() {
    let mut r = runner("projection_frames_the_mesh_and_culls_by_orientation", 300);
    let shape = prop::sample::select(vec!["sphere", "torus"]);
    let rez = prop::sample::select(vec![3u32, 7, 20, 50]);
    let size = 8..=1200u32;
    let totals = std::cell::Cell::new((0usize, 0usize));
    let collapsed_front = std::cell::Cell::new(0usize);
    let result = r.run(
        &(shape, rez, quaternion(), size.clone(), size),
        |(shape, rez, q, w, h)| {
            let mesh = if shape == "sphere" {
                uv_sphere(rez)
            } else {
                torus(rez)
            }
            .unwrap();
            let cam = Camera::fit(&mesh, w, h, q);
            let tris = project(&mesh, &cam, w, h).unwrap();
            // Framing: the bounding sphere spans 95 % of the shorter side, centred. Its radius is
            // about 1 for the sphere and 1.4 for the torus (more when an odd rez leaves the
            // bounding box lopsided), so the mesh reaches at least half of it on screen.
            let radius = if shape == "sphere" { 1.0 } else { 1.0 / 1.4 };
            let r_px = 0.475 * w.min(h) as f64;
            let farthest = mesh
                .positions
                .iter()
                .map(|&p| {
                    let s = cam.screen(p);
                    (s.x - w as f64 / 2.0).hypot(s.y - h as f64 / 2.0)
                })
                .fold(0.0, f64::max);
            prop_assert!(farthest <= r_px * (1.0 + 1e-12), "{} > {}", farthest, r_px);
            prop_assert!(farthest >= r_px * 0.5 * radius, "{} < {}", farthest, r_px);
            let (cx, cy) = (w as f64 / 2.0, h as f64 / 2.0);
            for t in &tris {
                for v in &t.v {
                    let d = (v.x as f64 - cx).hypot(v.y as f64 - cy);
                    // Rounding moves a vertex by at most √½ px; the fold repair may round a
                    // coordinate the other way (within the unit cell: √2) or merge vertices at
                    // the rounded mean of their positions (inside their hull, then √½).
                    prop_assert!(
                        d <= r_px + std::f64::consts::SQRT_2,
                        "vertex ({}, {}) {} px from the centre",
                        v.x,
                        v.y,
                        d
                    );
                    prop_assert!(v.x >= 0 && v.y >= 0 && v.x as u32 <= w && v.y as u32 <= h);
                    prop_assert!((v.normal.length() - 1.0).abs() < 1e-12);
                    // Depth takes the camera's scale: within the bounding sphere's radius in
                    // pixels of the centre's depth 0.
                    prop_assert!(v.z.abs() <= r_px * (1.0 + 1e-12), "depth {}", v.z);
                }
            }
            // Culling against the exact screen area: rounding moves each vertex by at most √½ px
            // (the fold repair of `screen_addresses` more, but never turns a front face back),
            // which changes twice the area by at most √2·(|b − a| + |c − a|) + 2.
            // Oriented key: a back face and a front face can project onto the same three
            // addresses (mirror-symmetric meshes seen edge-on), but never with the same winding.
            let key = |mut k: [(i32, i32); 3]| {
                let m = (0..3).min_by_key(|&i| k[i]).unwrap();
                k.rotate_left(m);
                k
            };
            let kept: std::collections::HashSet<_> =
                tris.iter().map(|t| key(t.v.map(|v| (v.x, v.y)))).collect();
            let addr = screen_addresses(&mesh, &cam);
            let mut decided = 0;
            for t in &mesh.triangles {
                let [a, b, c] = t.map(|i| cam.screen(mesh.positions[i as usize]));
                // In the mesh's order, front faces have a negative area on the y-down screen.
                let area2 = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
                let slack = std::f64::consts::SQRT_2
                    * ((b - a).truncate().length() + (c - a).truncate().length())
                    + 2.0;
                // `project` emits (v0, v2, v1), at the repaired addresses.
                let [aa, ab, ac] = t.map(|i| addr[i as usize]);
                let k = key([aa, ac, ab].map(|s| (s.x as i32, s.y as i32)));
                if area2 < -slack {
                    // Kept, unless the fold repair collapsed it (zero area: it covers nothing).
                    let collapsed = (ab - aa).perp_dot(ac - aa) == 0.0;
                    prop_assert!(kept.contains(&k) || collapsed, "front face {:?} culled", t);
                    collapsed_front.set(collapsed_front.get() + collapsed as usize);
                    decided += 1;
                } else if area2 > slack {
                    prop_assert!(!kept.contains(&k), "back face {:?} kept", t);
                    decided += 1;
                }
                // Independently of the screen: a front face's outward normal points at the viewer
                // (+z in view space), and the screen area has the opposite sign.
                let [pa, pb, pc] = t.map(|i| cam.view(mesh.positions[i as usize]));
                let facing = (pb - pa).cross(pc - pa).z;
                prop_assert!(facing * area2 <= 1e-9 * area2.abs().max(1.0), "orientation");
            }
            totals.set((
                totals.get().0 + decided,
                totals.get().1 + mesh.triangles.len(),
            ));
            Ok(())
        },
    );
    if let Err(e) = result {
        panic!("{e}");
    }
    // The slack must leave most faces decided, or the culling check says little.
    let (decided, all) = totals.get();
    println!(
        "culling decided beyond rounding for {decided} of {all} faces; {} decided front faces \
         collapsed by the fold repair",
        collapsed_front.get()
    );
    assert!(decided * 3 >= all, "{decided} of {all}");
}

#[test]
fn sphere_at_identity_shows_its_front_half() {
    let mesh = uv_sphere(50).unwrap();
    let cam = Camera::fit(&mesh, 400, 400, DQuat::IDENTITY);
    let tris = project(&mesh, &cam, 400, 400).unwrap();
    // Slices are 7.2° wide, centred at (j + ½)·7.2° from +z: 24 of the 50 (98 triangles each)
    // face the viewer, 2 are exactly edge-on (either way after rounding), and near the poles,
    // which sit on the rim, thin faces may collapse to zero area.
    assert!(
        (2352 * 9 / 10..=2352 + 196).contains(&tris.len()),
        "{}",
        tris.len()
    );
    for t in &tris {
        for v in &t.v {
            // A front face reaches at most one slice (7.2°) past the rim: sin 7.2° = 0.125 of
            // the radius, in pixels (depth takes the camera's scale, 190 px per unit here).
            assert!(v.z <= 0.126 * cam.scale, "depth {}", v.z);
            assert!(v.normal.z >= -0.126, "normal {}", v.normal);
        }
    }
    // The vertex nearest the viewer is the one at +z: depth −1 unit, −190 px, straight at the
    // viewer, drawn at the canvas centre.
    let nearest = tris
        .iter()
        .flat_map(|t| t.v)
        .min_by(|a, b| a.z.total_cmp(&b.z))
        .unwrap();
    assert_eq!(cam.scale, 190.0);
    assert!((nearest.z + 190.0).abs() < 1e-9, "{}", nearest.z);
    assert!((nearest.normal - DVec3::Z).length() < 1e-12);
    assert_eq!((nearest.x, nearest.y), (200, 200));
    // y up in view space, y down on screen: the north pole (+y) is drawn at the top.
    let top = tris.iter().flat_map(|t| t.v).min_by_key(|v| v.y).unwrap();
    assert!(top.normal.y > 0.99, "{}", top.normal);
    assert_eq!(top.y, 200 - 190);
}

#[test]
fn tilted_torus_keeps_its_non_convex_front() {
    let mesh = torus(30).unwrap();
    let cam = Camera::fit(&mesh, 500, 300, DQuat::from_rotation_x(0.6));
    let tris = project(&mesh, &cam, 500, 300).unwrap();
    let frac = tris.len() as f64 / mesh.triangles.len() as f64;
    assert!((0.4..0.6).contains(&frac), "{frac}");
    // The hole: the canvas centre is not inside any kept triangle.
    let centre = (250, 150);
    assert!(tris
        .iter()
        .all(|t| !golden::raster::edge_function_pixels(t).contains(&centre)));
}

#[test]
fn light_direction_is_unit_with_constant_elevation() {
    for k in 0..=720 {
        let deg = k as f64 * 0.5;
        let l = light_direction(deg).unwrap();
        assert!((l.length() - 1.0).abs() < 1e-15, "{deg}");
        assert!((l.y - LIGHT_ELEVATION_DEG.to_radians().sin()).abs() < 1e-15);
        let azimuth = l.z.atan2(l.x).to_degrees().rem_euclid(360.0);
        assert!(
            (azimuth - deg.rem_euclid(360.0)).abs() < 1e-9 || deg == 360.0,
            "{deg}"
        );
    }
    // Default 90°: from the front (towards the viewer, +z) and the top.
    let l = light_direction(90.0).unwrap();
    assert!(l.z > 0.7 && l.y > 0.7 && l.x.abs() < 1e-15);
    assert!(matches!(
        light_direction(-1.0),
        Err(SceneError::LightAngle(_))
    ));
    assert!(light_direction(f64::NAN)
        .unwrap_err()
        .to_string()
        .contains("NaN"));
}

#[test]
fn obj_round_trip_of_a_sphere_with_normals() {
    let m = uv_sphere(12).unwrap();
    let l = load_text("sphere-with-normals", &to_obj(&m, true)).unwrap();
    assert_eq!(l.triangles.len(), m.triangles.len());
    assert_eq!(l.positions.len(), m.positions.len());
    // Same triangles (through positions, which tobj keeps in f32), same unit normals.
    for (ta, tb) in m.triangles.iter().zip(&l.triangles) {
        for k in 0..3 {
            let (a, b) = (ta[k] as usize, tb[k] as usize);
            assert!((m.positions[a] - l.positions[b]).length() < 1e-6);
            assert!((m.normals[a] - l.normals[b]).length() < 1e-6);
            assert!((l.normals[b].length() - 1.0).abs() < 1e-15);
        }
    }
}

#[test]
fn obj_sphere_without_normals_gets_smooth_outward_normals() {
    let m = uv_sphere(16).unwrap();
    let l = load_text("sphere-without-normals", &to_obj(&m, false)).unwrap();
    let mut worst = 0.0f64;
    for (p, n) in l.positions.iter().zip(&l.normals) {
        worst = worst.max(p.normalize().angle_between(*n));
    }
    // Area-weighted normals of a UV sphere lean slightly towards the larger band; for rez 16
    // the lean stays within a few degrees of the radius (an inward or face normal would be far
    // off).
    assert!(worst.to_degrees() < 3.0, "worst {}°", worst.to_degrees());
}

#[test]
fn obj_smooth_normals_are_shared_across_texture_seams() {
    // A ridge along x made of two triangles whose shared edge uses different texture
    // coordinates on each side: tobj duplicates those vertices, the normals must still agree.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 1\nv 0 -1 1\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n\
                f 1/1 2/2 3/3\nf 2/4 1/3 4/1\n";
    let l = load_text("seam", text).unwrap();
    assert_eq!(l.positions.len(), 6, "tobj should split the seam vertices");
    for (i, p) in l.positions.iter().enumerate() {
        for (j, q) in l.positions.iter().enumerate() {
            if p == q {
                assert!(
                    (l.normals[i] - l.normals[j]).length() < 1e-12,
                    "{p}: {} vs {}",
                    l.normals[i],
                    l.normals[j]
                );
            }
        }
    }
    // The two faces have normals (0, −1, 1)/√2 and (0, 1, 1)/√2 (equal areas): the ridge
    // vertices get +z.
    let ridge = l.positions.iter().position(|&p| p == DVec3::ZERO).unwrap();
    assert!(
        (l.normals[ridge] - DVec3::Z).length() < 1e-12,
        "{}",
        l.normals[ridge]
    );
}

#[test]
fn obj_errors_are_one_line_and_name_the_path() {
    let missing = tmp("does-not-exist");
    let _ = std::fs::remove_file(&missing);
    let e = load_obj(&missing).unwrap_err();
    assert!(matches!(e, SceneError::ObjMissing { .. }));
    assert!(e.to_string().contains(&missing.display().to_string()));
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let e = load_obj(&dir).unwrap_err().to_string();
    assert!(e.contains("directory") && !e.contains('\n'), "{e}");
    let e = load_text("inf", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("non-finite coordinate inf") && e.contains("scene-inf.obj"),
        "{e}"
    );
}

#[test]
fn hand_built_bad_meshes_are_rejected_by_project() {
    let good = uv_sphere(4).unwrap();
    let cam = Camera::fit(&good, 64, 64, DQuat::IDENTITY);
    let mut m = good.clone();
    m.triangles[3][1] = 999;
    let e = project(&m, &cam, 64, 64).unwrap_err().to_string();
    assert!(e.contains("triangle 3 refers to vertex 999"), "{e}");
    let mut m = good.clone();
    m.positions[2].y = f64::NAN;
    assert!(matches!(
        project(&m, &cam, 64, 64),
        Err(SceneError::BadPosition { vertex: 2, .. })
    ));
    let mut m = good.clone();
    m.normals.pop();
    assert!(matches!(
        project(&m, &cam, 64, 64),
        Err(SceneError::Inconsistent { .. })
    ));
    // Vertices off the canvas but inside the 12-bit range are fine.
    let mut shifted = cam;
    shifted.screen_centre.x += 60.0;
    let tris = project(&good, &shifted, 64, 64).unwrap();
    assert!(tris.iter().flat_map(|t| t.v).any(|v| v.x > 64));
}

/// `screen_addresses` (the fold repair behind `project`), on spheres and tori at random
/// rotations and sizes, shared or split vertices: every address is an integer within a pixel of
/// the continuous position or shared with another vertex, and vertices with identical model
/// positions get identical addresses (no crack opens between the copies). Exactly-once coverage
/// is checked in `tests/raster.rs`.
#[test]
fn fold_repair_keeps_seams_closed_and_addresses_integer() {
    let mut r = runner("fold_repair_keeps_seams_closed_and_addresses_integer", 200);
    let shape = prop::sample::select(vec!["sphere", "torus"]);
    let rez = prop::sample::select(vec![3u32, 8, 20, 50, 100]);
    let size = prop_oneof![8..=60u32, 60..=600u32];
    let moved = std::cell::Cell::new((0usize, 0usize));
    let result = r.run(
        &(shape, rez, quaternion(), size.clone(), size, any::<bool>()),
        |(shape, rez, q, w, h, split_it)| {
            let mesh = if shape == "sphere" {
                uv_sphere(rez)
            } else {
                torus(rez)
            }
            .unwrap();
            let mesh = if split_it {
                split_vertices(&mesh)
            } else {
                mesh
            };
            let cam = Camera::fit(&mesh, w, h, q);
            let addr = screen_addresses(&mesh, &cam);
            prop_assert_eq!(addr.len(), mesh.positions.len());
            let mut by_position = std::collections::HashMap::new();
            let (mut m, mut far) = moved.get();
            for (i, p) in mesh.positions.iter().enumerate() {
                let a = addr[i];
                prop_assert!(a.x.fract() == 0.0 && a.y.fract() == 0.0, "vertex {}", i);
                let s = cam.screen(*p).truncate();
                m += (a != s.round()) as usize;
                // Within the unit cell of the continuous position, or merged with others.
                if (a - s).abs().max_element() >= 1.0 {
                    far += 1;
                    let copies = addr.iter().filter(|&&b| b == a).count();
                    prop_assert!(copies > 1, "vertex {} moved to {:?} alone", i, a);
                }
                let first = *by_position
                    .entry(p.to_array().map(f64::to_bits))
                    .or_insert(a);
                prop_assert_eq!(first, a, "vertex {} split from its twin", i);
            }
            moved.set((m, far));
            Ok(())
        },
    );
    if let Err(e) = result {
        panic!("{e}");
    }
    let (m, far) = moved.get();
    println!(
        "{m} vertices moved off plain rounding, {far} of them beyond their unit cell (merged)"
    );
}

/// The thesis scene (sphere, rez 50, 400×400, identity rotation) has no fold: its addresses are
/// the plain rounded positions, so the repair does not change the default images.
#[test]
fn default_scene_addresses_are_plain_rounding() {
    let mesh = uv_sphere(50).unwrap();
    let cam = Camera::fit(&mesh, 400, 400, DQuat::IDENTITY);
    let addr = screen_addresses(&mesh, &cam);
    for (i, p) in mesh.positions.iter().enumerate() {
        assert_eq!(addr[i], cam.screen(*p).truncate().round(), "vertex {i}");
    }
}
