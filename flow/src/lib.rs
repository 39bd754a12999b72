//! The hardware flow: what the CLI and the tests both do with the RTL, outside any test
//! framework.
//!
//! - [`blocks`]: every exportable block, once ([`blocks::BLOCKS`]), as an object the commands
//!   call (ports, Verilog, a simulation model, synthesis).
//! - [`engine`]: which simulator runs the hardware (rust-hdl or Verilator in process).
//! - [`tools`]: finding the external tools, running them, the skip-or-fail policy.
//! - [`verilog`]: exported Verilog under Icarus or Verilator against the rust-hdl simulation.
//! - [`synth`]: Yosys and nextpnr, one module per target (iCE40, ECP5) and pin fitting.
//! - [`vcd_check`]: reading a VCD back.

use std::path::PathBuf;

pub mod blocks;
pub mod cli;
pub mod engine;
pub mod synth;
pub mod tools;
pub mod vcd_check;
pub mod verilog;

/// The workspace's `target/` directory (`CARGO_TARGET_DIR` if set).
pub fn target_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(d);
    }
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(|p| p.join("target"))
        .unwrap_or_else(|| "target".into())
}

/// `name` with every character other than ASCII letters, digits, `-` and `_` replaced by `_`
/// (a file name on any system).
pub fn file_safe(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
