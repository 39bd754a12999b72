
pub mod address_block;
pub mod intensity_interpolator;
pub mod harness;
pub mod normalizer;
