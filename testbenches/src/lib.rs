
pub mod address_block;
pub mod intensity_interpolator;
pub mod harness;
pub mod normalizer;
pub mod synth;
pub mod tools;
pub mod verilog;
pub mod k_recurrence;
pub mod blocks;
pub mod vcd_check;
