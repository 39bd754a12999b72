
pub mod address_block;
