//! Pipelines: leaf units wired into a raster or span pipe, set-up in, fragments out.

pub mod cubic_pipeline;
pub mod gouraud_raster;
pub mod pixel_pipeline;
pub mod span_pipeline;
pub mod subdivision_raster;
pub mod textured_pipeline;
