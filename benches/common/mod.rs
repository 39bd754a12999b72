//! What the benches share: the default scene (the thesis prototype: sphere rez 50, 400×400,
//! light at 90°, vertices as projected) and Criterion's set-up. `mod common;` in each bench
//! (a folder, so Cargo does not take it for a bench of its own).
#![allow(dead_code)]

pub mod texture;

use glam::DQuat;
use golden::shade::ShadeContext;
use golden::types::ScreenTriangle;

/// The default scene's projected triangles and shading context.
pub fn default_scene() -> (Vec<ScreenTriangle>, ShadeContext) {
    let mesh = golden::scene::uv_sphere(50).unwrap();
    let cam = golden::scene::Camera::fit(&mesh, 400, 400, DQuat::IDENTITY);
    let tris = golden::scene::project(&mesh, &cam, 400, 400).unwrap();
    let ctx = ShadeContext {
        light: golden::scene::light_direction(90.0).unwrap(),
        ..ShadeContext::default()
    };
    (tris, ctx)
}

/// `criterion_main!` over `$target` with plots off (the plotters backend needs fonts the CI
/// image may lack).
#[macro_export]
macro_rules! criterion_without_plots {
    ($target:path) => {
        criterion::criterion_group! {
            name = benches;
            config = criterion::Criterion::default().without_plots();
            targets = $target
        }
        criterion::criterion_main!(benches);
    };
}
