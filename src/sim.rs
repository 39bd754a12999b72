//! The simulator switch of the CLI (`--sim verilator|rust-hdl`) and the parallel compile of
//! the Verilator models a run needs, with progress.
//!
//! Default: Verilator in process when Verilator and a C++ compiler are installed (the exported
//! Verilog, proven bit-exact against rust-hdl by the test suite, about 400 times as fast),
//! otherwise rust-hdl with a one-line notice.

use anyhow::{anyhow, Result};
pub use flow::engine::Sim;
use indicatif::MultiProgress;

pub use flow::cli::SimArg;

/// The simulator for `arg` (`None`: the fastest installed): [`flow::engine::resolve`].
pub fn resolve(arg: Option<SimArg>) -> Result<Sim> {
    flow::engine::resolve(arg.map(Sim::from)).map_err(|e| anyhow!(e))
}

/// [`flow::engine::prepare`].
pub fn prepare(sim: Sim, designs: Vec<verilated::Design>, multi: &MultiProgress) -> Result<()> {
    flow::engine::prepare(sim, designs, multi).map_err(|e| anyhow!(e))
}
