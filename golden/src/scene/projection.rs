//! The projection: the [`Camera`] fitted to a mesh, [`project`] to
//! integer 12-bit screen addresses (through the fold repair of [`screen_addresses`]) with
//! back-face culling, and the directional light.
//!
//! **Camera model: orthographic** (the `plane` scene alone has a perspective camera, for its
//! texture: [`Camera::fit_perspective`]). The shading model puts the viewer at infinity (V = +z in view
//! space, constant over the frame, see `types.rs`); an orthographic projection is the projection
//! that matches it, so the faces kept by screen-space culling are exactly those whose geometric
//! normal faces V (up to the rounding of vertex addresses), and the depth is affine in screen
//! space, so a depth plane per triangle is exact. The thesis prototype used a 45° perspective
//! with the eye about 4 radii away; at that distance the difference in silhouette is a few
//! percent and the shading methods compared here do not depend on it.

use glam::DVec3;

use super::camera::Camera;
use super::mesh::Mesh;
use super::snap::screen_addresses;
use super::SceneError;
use crate::types::{ScreenTriangle, ScreenVertex, MAX_ADDRESS};

/// Largest canvas side: every pixel address must fit 12 bits.
pub const MAX_CANVAS: u32 = MAX_ADDRESS as u32 + 1;

/// Elevation of the light above the view-space xz plane, in degrees (see [`light_direction`]).
pub const LIGHT_ELEVATION_DEG: f64 = 45.0;

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
    project_subpixel(mesh, camera, width, height, 0)
}

/// [`project`] with vertex coordinates of `frac` fraction bits (0: integer addresses through
/// the fold repair, as [`project`]; otherwise the continuous positions rounded to the nearest
/// 2^−frac pixel, ties up, without a repair: a fold needs a triangle thinner than 2^−frac
/// pixel, and the depth test resolves it). Culling and the range check are as in [`project`],
/// on the rounded positions; the range is 0..=4095 pixels.
pub fn project_subpixel(
    mesh: &Mesh,
    camera: &Camera,
    width: u32,
    height: u32,
    frac: u32,
) -> Result<Vec<ScreenTriangle>, SceneError> {
    if width == 0 || height == 0 {
        return Err(SceneError::CanvasEmpty { width, height });
    }
    if width > MAX_CANVAS || height > MAX_CANVAS {
        return Err(SceneError::CanvasTooLarge { width, height });
    }
    mesh.validate()?;
    let screen: Vec<DVec3> = mesh.positions.iter().map(|&p| camera.screen(p)).collect();
    let one = (1u64 << frac) as f64;
    let rounded: Vec<(f64, f64)> = if frac == 0 {
        screen_addresses(mesh, camera)
            .iter()
            .map(|a| (a.x, a.y))
            .collect()
    } else {
        screen
            .iter()
            .map(|p| ((p.x * one + 0.5).floor(), (p.y * one + 0.5).floor()))
            .collect()
    };
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
            uv: glam::DVec2::ZERO,
            w: 1.0,
        }; 3];
        for (k, &(corner, i)) in [(0, tri[0]), (2, tri[2]), (1, tri[1])].iter().enumerate() {
            let s = screen[i as usize];
            for (axis, value, r) in [
                ('x', s.x, rounded[i as usize].0),
                ('y', s.y, rounded[i as usize].1),
            ] {
                if !(0.0..=MAX_ADDRESS as f64 * one).contains(&r) {
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
                uv: mesh.uvs.get(t).map_or(glam::DVec2::ZERO, |uv| uv[corner]),
                w: camera.w(mesh.positions[i as usize]),
            };
        }
        let st = ScreenTriangle { v, frac };
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
    use crate::scene::uv_sphere;
    use glam::DQuat;

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

    #[test]
    fn project_rejects_bad_normals_naming_the_vertex() {
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
}
