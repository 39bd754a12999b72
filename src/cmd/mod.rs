//! One module per CLI subcommand.

pub mod accuracy;
pub mod raster;
pub mod render;
pub mod rtl;
pub mod stream;
pub mod sweep;
