//! Which simulator runs the hardware, chosen by one switch: rust-hdl's own simulation
//! ([`rtl::sim::RustHdlModel`]) or the exported Verilog under Verilator in process
//! ([`verilated::VModel`], proven bit-exact against rust-hdl by the differential tests). Every
//! driver of this crate steps a `Box<dyn Model>` made here.

use rtl::registry::RtlBlock;
use rtl::sim::{Model, RustHdlModel};

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
