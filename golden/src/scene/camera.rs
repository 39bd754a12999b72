//! The orthographic camera fitted to a mesh (see `projection` for how its addresses are made).

use super::mesh::Mesh;
use glam::{DQuat, DVec2, DVec3};

/// Orthographic camera. A model point p goes to view space as `rotation · (p − centre)`
/// (viewer looking down −z, y up), then to the continuous screen position
/// `(screen_centre.x + scale·v.x, screen_centre.y − scale·v.y)` (screen y down) with depth
/// `−scale·v.z` (smaller is nearer; 0 at `centre`). Depth takes the same fit as x and y, so it
/// is in pixels whatever the mesh's size: within ±`scale`·radius, under half the shorter canvas
/// side (at most 2048 for a 4096² canvas), well inside the RTL's depth words.
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
            -self.scale * v.z,
        )
    }
}
