//! The benches of `rtl::pipelines`: the pipelines’ stimulus, twins and held runs.

pub mod cubic_pipeline;
pub mod pixel_pipeline;
pub mod span_held;
pub mod span_pipeline;
pub mod subdivision_raster;
pub mod textured_pipeline;
