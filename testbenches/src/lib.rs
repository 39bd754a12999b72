
pub mod address_block;
pub mod harness;
pub mod normalizer;
