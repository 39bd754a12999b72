//! The camera fitted to a mesh: orthographic ([`Camera::fit`]) or with a perspective divide
//! ([`Camera::fit_perspective`], the `plane` scene). See `projection` for how its addresses are
//! made.

use super::mesh::Mesh;
use glam::{DQuat, DVec2, DVec3};

/// The camera. A model point p goes to view space as `v = rotation · (p − centre)` (viewer
/// looking down −z, y up), then to the continuous screen position
/// `(screen_centre.x + scale·v.x/w, screen_centre.y − scale·v.y/w)` (screen y down) with depth
/// `scale·d·(1 − 1/w)` (smaller is nearer; 0 at `centre`), where w is the perspective divisor:
///
/// - **orthographic** (`eye` = `None`): w = 1 and the depth is `−scale·v.z`. Depth takes the
///   same fit as x and y, so it is in pixels whatever the mesh's size: within ±`scale`·radius,
///   under half the shorter canvas side (at most 2048 for a 4096² canvas), well inside the
///   RTL's depth words.
/// - **perspective** (`eye` = `Some(d)`, the eye at view-space (0, 0, d)): w = (d − v.z)/d,
///   1 in the plane of `centre`. 1/w, and so the depth, is affine in screen space over a
///   planar triangle, as the depth planes need. The shading keeps its viewer at infinity
///   (V = +z): only positions and texture coordinates see the perspective.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub rotation: DQuat,
    /// Model-space point that lands on `screen_centre`.
    pub centre: DVec3,
    /// Pixels per model unit.
    pub scale: f64,
    /// Continuous screen position of `centre`.
    pub screen_centre: DVec2,
    /// View-space z of the eye for a perspective camera; `None` for orthographic.
    pub eye: Option<f64>,
}

/// The `plane` scene's view: the angle between the line of sight and the ground, degrees.
pub const PLANE_ELEVATION_DEG: f64 = 20.0;
/// The `plane` scene's view: the plane turned about its normal, degrees, so that depth changes
/// along the raster lines too (seen square-on, a ground plane's lines each have one depth and
/// the span methods would be exact on it).
pub const PLANE_YAW_DEG: f64 = 30.0;
/// The `plane` scene's eye: its distance from the middle of the plane, in bounding-sphere radii
/// (its corners span w = 0.154 … 1.846, whatever the rez: the nearest is 12 times nearer
/// than the farthest).
pub const PLANE_EYE_RADII: f64 = 1.1;

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
            eye: None,
        }
    }

    /// A perspective camera with the eye `eye_radii` bounding-sphere radii (> 1) from the
    /// bounding sphere's centre along the view axis, after rotating the mesh by `rotation`;
    /// the scale and screen centre put the projected bounding box of the vertices in the middle
    /// of the canvas, its larger relative side `1 − MARGIN` of the canvas's.
    pub fn fit_perspective(
        mesh: &Mesh,
        width: u32,
        height: u32,
        rotation: DQuat,
        eye_radii: f64,
    ) -> Camera {
        assert!(
            eye_radii > 1.0,
            "the eye must be outside the bounding sphere"
        );
        let ortho = Camera::fit(mesh, width, height, rotation);
        let radius = mesh
            .positions
            .iter()
            .map(|&p| (p - ortho.centre).length())
            .fold(0.0, f64::max);
        let radius = if radius > 0.0 && radius.is_finite() {
            radius
        } else {
            1.0
        };
        let mut cam = Camera {
            eye: Some(eye_radii * radius),
            scale: 1.0,
            screen_centre: DVec2::ZERO,
            ..ortho
        };
        // The projected bounding box at scale 1 (x right, y up).
        let (lo, hi) = mesh.positions.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| {
                let v = cam.view(p);
                let s = DVec2::new(v.x, v.y) / cam.w_of_view(v);
                (lo.min(s), hi.max(s))
            },
        );
        let span = (hi - lo).max(DVec2::splat(f64::MIN_POSITIVE));
        let room = DVec2::new(width as f64, height as f64) * (1.0 - Self::MARGIN);
        cam.scale = (room.x / span.x).min(room.y / span.y);
        if !(cam.scale.is_finite() && cam.scale > 0.0) {
            cam.scale = 1.0;
        }
        let mid = (lo + hi) * 0.5 * cam.scale;
        cam.screen_centre = DVec2::new(width as f64 * 0.5 - mid.x, height as f64 * 0.5 + mid.y);
        cam
    }

    /// The `plane` scene's camera ([`PLANE_YAW_DEG`], [`PLANE_ELEVATION_DEG`],
    /// [`PLANE_EYE_RADII`]).
    pub fn plane_view(mesh: &Mesh, width: u32, height: u32) -> Camera {
        Camera::plane_view_at(mesh, width, height, PLANE_EYE_RADII)
    }

    /// The `plane` scene's view with the eye `eye_radii` bounding-sphere radii (> 1) away.
    pub fn plane_view_at(mesh: &Mesh, width: u32, height: u32, eye_radii: f64) -> Camera {
        let rotation = DQuat::from_rotation_x(PLANE_ELEVATION_DEG.to_radians())
            * DQuat::from_rotation_y(PLANE_YAW_DEG.to_radians());
        Camera::fit_perspective(mesh, width, height, rotation, eye_radii)
    }

    /// The perspective divisor w of a view-space point (1 for orthographic).
    fn w_of_view(&self, v: DVec3) -> f64 {
        match self.eye {
            None => 1.0,
            Some(d) => (d - v.z) / d,
        }
    }

    /// The perspective divisor w of a model point: 1 for orthographic, (d − v.z)/d otherwise.
    pub fn w(&self, p: DVec3) -> f64 {
        self.w_of_view(self.view(p))
    }

    /// View-space position of a model point.
    pub fn view(&self, p: DVec3) -> DVec3 {
        self.rotation * (p - self.centre)
    }

    /// Continuous screen position (x, y) and depth (z) of a model point, before rounding.
    pub fn screen(&self, p: DVec3) -> DVec3 {
        let v = self.view(p);
        match self.eye {
            None => DVec3::new(
                self.screen_centre.x + self.scale * v.x,
                self.screen_centre.y - self.scale * v.y,
                -self.scale * v.z,
            ),
            Some(d) => {
                let w = self.w_of_view(v);
                DVec3::new(
                    self.screen_centre.x + self.scale * v.x / w,
                    self.screen_centre.y - self.scale * v.y / w,
                    self.scale * d * (1.0 - 1.0 / w),
                )
            }
        }
    }
}
