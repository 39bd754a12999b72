//! Leaf blocks: one formula of the sources each (SPEC §1–§9), with their ports and headers.

pub mod address_block;
pub mod brzssk;
pub mod colour_combine;
pub mod cos_v_accumulator;
pub mod fast_unit;
pub mod four_triangle;
pub mod horner_unit;
pub mod intensity_interpolator;
pub mod k_recurrence;
pub mod lighting_unit;
pub mod line_interpolator;
pub mod normalizer;
pub mod power_unit;
pub mod quadric_unit;
pub mod texture_bezier;
pub mod texture_coord;
pub mod texture_memory;
pub mod texture_quadratic;
pub mod vector_interpolator;
