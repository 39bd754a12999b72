//! Which simulator runs the hardware, chosen by one switch: rust-hdl's own simulation
//! ([`rtl::core::sim::RustHdlModel`]) or the exported Verilog under Verilator in process
//! ([`verilated::VModel`], proven bit-exact against rust-hdl by the differential tests). Every
//! driver of this crate steps a `Box<dyn Model>` made here.

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use rtl::core::registry::RtlBlock;
use rtl::core::sim::{Model, RustHdlModel};

/// A simulator of the RTL.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sim {
    /// rust-hdl's simulation, stepped by hand (no external tool; writes VCDs).
    RustHdl,
    /// The exported Verilog verilated into a shared library and stepped in process (cached
    /// under `target/verilated/`; about 400 times as fast as rust-hdl on the lit pipeline).
    Verilator,
}

impl Sim {
    /// Verilator when it (and a C++ compiler) is installed, else rust-hdl; `SHADECORE_SIM=rust-hdl`
    /// in the environment asks for rust-hdl (to run the tests' long runs on it).
    pub fn fastest() -> Sim {
        if std::env::var("SHADECORE_SIM").as_deref() == Ok("rust-hdl") {
            return Sim::RustHdl;
        }
        if verilated::available() {
            Sim::Verilator
        } else {
            Sim::RustHdl
        }
    }

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Sim::RustHdl => "rust-hdl",
            Sim::Verilator => "verilator",
        }
    }

    /// The simulator named `s` (`rust-hdl`, `verilator`).
    pub fn parse(s: &str) -> Result<Sim, String> {
        match s {
            "rust-hdl" => Ok(Sim::RustHdl),
            "verilator" => Ok(Sim::Verilator),
            _ => Err(format!("no simulator {s:?} (rust-hdl, verilator)")),
        }
    }
}

impl std::fmt::Display for Sim {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The simulator for a long run of test `what`: Verilator in process (proven bit-exact against
/// rust-hdl by the registry's test) when it is installed; otherwise rust-hdl — the same
/// verdict, minutes slower — with a notice on stderr, or a failure when `CI` is set.
/// `SHADECORE_SIM=rust-hdl` runs them on rust-hdl on purpose (the one switch for the tests).
pub fn fast_sim(what: &str) -> Sim {
    if std::env::var("SHADECORE_SIM").as_deref() == Ok("rust-hdl") {
        return Sim::RustHdl;
    }
    if verilated::available() {
        return Sim::Verilator;
    }
    if crate::tools::in_ci() {
        panic!("{what}: Verilator is not installed (CI is set, so this is a failure)");
    }
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "SLOW {what}: Verilator is not installed, so this runs on rust-hdl (apt-get install verilator g++)"
    );
    Sim::RustHdl
}

/// Block `B` built with `p`, on `sim` (Verilator: compiled first if its cache has no build).
pub fn model<B: RtlBlock + 'static>(p: &B::Params, sim: Sim) -> Result<Box<dyn Model>, String> {
    Ok(match sim {
        Sim::RustHdl => Box::new(RustHdlModel::new(B::build(p))?),
        Sim::Verilator => Box::new(verilated::model::<B>(p)?),
    })
}

/// The design `verilated` builds for `B` with `p` (to compile several at once before a run).
pub fn design<B: RtlBlock>(p: &B::Params) -> verilated::Design {
    verilated::design::<B>(p)
}

/// A pipe with two tops, `P` on ports and `S` behind AXI4-Stream, both with their default
/// parameters: `S`'s model if `stream`, else `P`'s, on `sim`.
pub fn model_of<P, S>(sim: Sim, stream: bool) -> Result<Box<dyn Model>, String>
where
    P: RtlBlock<Params: Default> + 'static,
    S: RtlBlock<Params: Default> + 'static,
{
    if stream {
        model::<S>(&Default::default(), sim)
    } else {
        model::<P>(&Default::default(), sim)
    }
}

/// The Verilator design [`model_of`] builds.
pub fn design_of<P: RtlBlock<Params: Default>, S: RtlBlock<Params: Default>>(
    stream: bool,
) -> verilated::Design {
    if stream {
        design::<S>(&Default::default())
    } else {
        design::<P>(&Default::default())
    }
}

/// The simulator a command asked for (`None`: the fastest installed). `--sim verilator` without
/// Verilator is an error; the default without it falls back to rust-hdl with a notice on
/// stderr.
pub fn resolve(arg: Option<Sim>) -> Result<Sim, String> {
    match arg {
        Some(Sim::RustHdl) => Ok(Sim::RustHdl),
        Some(Sim::Verilator) => {
            verilated::toolchain().map_err(|e| format!("--sim verilator: {e}"))?;
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
pub fn prepare(
    sim: Sim,
    designs: Vec<verilated::Design>,
    multi: &MultiProgress,
) -> Result<(), String> {
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
    let first_error = std::sync::Mutex::new(None);
    crate::tools::two_at_a_time(designs.iter(), |d| {
        bar.set_message(d.name.clone());
        if let Err(e) = verilated::build(d) {
            first_error.lock().expect("error").get_or_insert(e);
        }
        bar.inc(1);
    });
    bar.finish_and_clear();
    match first_error.into_inner().expect("error") {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Stack for every thread the process spawns (64 MiB), unless `RUST_MIN_STACK` says otherwise.
/// A rust-hdl block is one struct holding its whole hierarchy by value (a stream top is about
/// 400 kB), built on the stack and moved a few times on its way to the heap: a thread's default
/// 2 MiB does not hold a stream top with its generated core and pipeline. Call it first in
/// `main`, before any thread starts (the workspace's `.cargo/config.toml` sets the same for
/// `cargo test`).
pub fn set_thread_stack() {
    if std::env::var_os("RUST_MIN_STACK").is_none() {
        std::env::set_var("RUST_MIN_STACK", (64usize << 20).to_string());
    }
}
