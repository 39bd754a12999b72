//! shadecore golden model: f64 reference of every block and shading method in SPEC.md.
//!
//! Shaped like the hardware: per-triangle / per-span set-up ("software side") is separate from
//! the per-pixel kernels ("hardware side"), so the RTL pipeline is driven by the same set-up.

pub mod accuracy;
pub mod files;
mod linalg;
pub mod methods;
pub mod nmse;
pub mod raster;
pub mod render;
pub mod scene;
pub mod seed;
pub mod shade;
pub mod shading;
#[cfg(feature = "testing")]
pub mod testing;
pub mod texture;
pub mod types;
pub mod units;

pub use types::*;
