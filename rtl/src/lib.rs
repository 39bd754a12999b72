pub mod address_block;
pub mod export;
pub mod fixed;
pub mod gouraud_raster;
pub mod intensity_interpolator;
pub mod k_recurrence;
pub mod line_interpolator;
pub mod normalizer;
