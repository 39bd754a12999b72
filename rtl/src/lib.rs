pub mod core;
pub mod pipelines;
pub mod stream;
pub mod targets;
pub mod units;

/// A hash of every source the exported Verilog depends on (this crate, `golden`, the vendored
/// rust-hdl-core, Cargo.lock), made by `build.rs`: the in-process Verilator cache keys on it.
pub const SOURCE_FINGERPRINT: &str = env!("SHADECORE_RTL_FINGERPRINT");
