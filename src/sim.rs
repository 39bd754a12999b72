//! The simulator switch of the CLI (`--sim verilator|rust-hdl`) and the parallel compile of
//! the Verilator models a run needs, with progress.
//!
//! Default: Verilator in process when Verilator and a C++ compiler are installed (the exported
//! Verilog, proven bit-exact against rust-hdl by the test suite, about 400 times as fast),
//! otherwise rust-hdl with a one-line notice.

use anyhow::{anyhow, Result};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
pub use pipeline::engine::Sim;

/// `--sim`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SimArg {
    /// The exported Verilog under Verilator, verilated once per block into a shared library
    /// cached under target/verilated/ and stepped in process.
    Verilator,
    /// rust-hdl's own simulation, stepped by hand (no external tool; writes VCDs).
    RustHdl,
}

/// The simulator for `arg` (`None`: the fastest installed). `--sim verilator` without
/// Verilator is an error; the default without it falls back to rust-hdl with a notice on
/// stderr.
pub fn resolve(arg: Option<SimArg>) -> Result<Sim> {
    match arg {
        Some(SimArg::RustHdl) => Ok(Sim::RustHdl),
        Some(SimArg::Verilator) => {
            verilated::toolchain().map_err(|e| anyhow!("--sim verilator: {e}"))?;
            Ok(Sim::Verilator)
        }
        None => match verilated::toolchain() {
            Ok(_) => Ok(Sim::Verilator),
            Err(e) => {
                eprintln!(
                    "note: {e}; simulating on rust-hdl instead, about 400 times slower (the main job: minutes instead of seconds); --sim rust-hdl silences this"
                );
                Ok(Sim::RustHdl)
            }
        },
    }
}

/// Compile (or find in the cache) every design in `designs`, two at a time with a progress
/// bar when any needs building. Nothing to do on rust-hdl.
pub fn prepare(sim: Sim, designs: Vec<verilated::Design>, multi: &MultiProgress) -> Result<()> {
    if sim != Sim::Verilator || designs.is_empty() {
        return Ok(());
    }
    let bar = multi.add(ProgressBar::new(designs.len() as u64));
    bar.set_style(
        ProgressStyle::with_template(
            "verilator models [{bar:30}] {pos}/{len} {msg} {elapsed} (a cold build takes about a minute; cached under target/verilated)",
        )
        .expect("static template")
        .progress_chars("=> "),
    );
    verilated::set_quiet(true);
    let queue = std::sync::Mutex::new(designs.iter());
    let first_error = std::sync::Mutex::new(None);
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| loop {
                let Some(d) = queue.lock().expect("queue").next() else {
                    return;
                };
                bar.set_message(d.name.clone());
                if let Err(e) = verilated::build(d) {
                    first_error.lock().expect("error").get_or_insert(e);
                }
                bar.inc(1);
            });
        }
    });
    bar.finish_and_clear();
    match first_error.into_inner().expect("error") {
        Some(e) => Err(anyhow!(e)),
        None => Ok(()),
    }
}
