pub mod harness;
pub mod pipelines;
pub mod registry;
pub mod stall;
pub mod stream;
pub mod units;
