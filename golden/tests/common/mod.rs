//! Set-up shared by the textured golden tests: the scenes as the CLI builds them.

use golden::scene::{self, Camera};
use golden::ScreenTriangle;

/// The triangles of `sphere`, `torus` or `plane` (400×400, vertices at 1/16 pixel).
pub fn scene_tris(name: &str) -> Vec<ScreenTriangle> {
    let (w, h) = (400, 400);
    let (mesh, cam) = match name {
        "sphere" => {
            let m = scene::uv_sphere(50).unwrap();
            let c = Camera::fit(&m, w, h, glam::DQuat::IDENTITY);
            (m, c)
        }
        "torus" => {
            let m = scene::torus(50).unwrap();
            let c = Camera::fit(&m, w, h, glam::DQuat::from_rotation_x(55f64.to_radians()));
            (m, c)
        }
        "plane" => {
            let m = scene::plane(50).unwrap();
            let c = Camera::plane_view(&m, w, h);
            (m, c)
        }
        _ => unreachable!(),
    };
    scene::project_subpixel(&mesh, &cam, w, h, golden::SUBPIXEL_BITS).unwrap()
}
