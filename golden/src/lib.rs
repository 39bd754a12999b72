//! shadecore golden model: f64 reference of every block and shading method in SPEC.md.
//!
//! Shaped like the hardware: per-triangle / per-span set-up ("software side") is separate from
//! the per-pixel kernels ("hardware side"), so the RTL pipeline is driven by the same set-up.

pub mod address_block;
pub mod intensity_interpolator;
pub mod nmse;
pub mod normalizer;
pub mod testing;
pub mod types;

pub use types::*;
