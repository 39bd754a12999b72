//! shadecore golden model: f64 reference of every block and shading method in SPEC.md.
//!
//! Shaped like the hardware: per-triangle / per-span set-up ("software side") is separate from
//! the per-pixel kernels ("hardware side"), so the RTL pipeline is driven by the same set-up.

pub mod accuracy;
pub mod address_block;
pub mod angular;
pub mod brdf;
pub mod brzssk;
pub mod bump;
pub mod colour_combine;
pub mod cos_v_accumulator;
pub mod cubic;
pub mod fast;
pub mod fast_unit;
pub mod four_triangle;
pub mod gouraud;
pub mod horner_unit;
pub mod intensity_interpolator;
pub mod lighting_unit;
pub mod methods;
pub mod nmse;
pub mod normalizer;
pub mod phong;
pub mod power_unit;
pub mod quadric;
pub mod quadric_unit;
pub mod raster;
pub mod refine;
pub mod render;
pub mod scene;
pub mod seed;
pub mod shade;
pub mod subdivision;
#[cfg(feature = "testing")]
pub mod testing;
pub mod types;
pub mod vector_interpolator;

pub use types::*;
