//! Vendor-specific mappings of the portable blocks (ECP5 DSP).

pub mod ecp5_dsp;
