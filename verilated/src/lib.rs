//! The exported Verilog of a block, verilated once into a shared library and stepped in process:
//! the fast simulator of the project, proven bit-exact against the rust-hdl description by the
//! differential tests, and the default engine of the render drivers and the long tests.
//!
//! - [`Design`]: what to build — a cache key, the top module, its ports and the Verilog (made only
//!   when the cache has no build). [`design`] makes one for a registered block and its
//!   parameters, keyed on the block's name, its parameters and [`rtl::SOURCE_FINGERPRINT`] (a hash
//!   of the sources the Verilog comes from), never on regenerating the Verilog.
//! - [`build`]: Verilator (`--cc`) and the C++ compiler make `lib.so` under
//!   `target/verilated/<module>-<hash>/` with a small C ABI ([`wrapper`]); the entry is written
//!   in a temporary directory and renamed into place (whole or not at all), checked on every
//!   load (size and checksum, ABI version, port list) and rebuilt when broken. A lock file makes
//!   a second process (or thread) wait for a build under way instead of repeating it.
//! - [`VModel`]: one instance of the model, a [`rtl::core::sim::Model`] like rust-hdl's
//!   [`rtl::core::sim::RustHdlModel`], with the same clock timing: inputs applied with the clock low,
//!   outputs sampled, then the rising edge.
//!
//! Why `libloading` rather than a crate made for driving Verilator models from Rust: `verilated`
//! / `verilator` (0.1, Rust 2015) describe a module's ports as a Rust type in `build.rs` and a
//! proc macro, while our port lists come from the registry at run time (a block and its option
//! set); `marlin-verilator` has dynamic models (ports by name at run time, also through
//! `libloading`) whose ports are reached by name one at a time, where a clock here moves every
//! port in one `sc_step` call. It was not tried; the C ABI needed is seven functions, generated
//! with the model.

mod compile;
mod model;

pub use compile::{build, cache_dir, set_quiet, toolchain, wrapper, Toolchain};
pub use model::{Library, VModel};

use rtl::core::registry::{module_name, BlockParams, RtlBlock};
use rtl::core::sim::Port;

/// Version of the C ABI [`wrapper`] generates (part of every cache key).
pub(crate) const ABI_VERSION: u32 = 1;

/// What to build: see the crate's documentation.
pub struct Design {
    /// For messages (`pixel-pipeline`, `pixel-pipeline (coeffs=fit)`).
    pub name: String,
    /// Identifies the hardware: equal keys must mean equal Verilog.
    pub key: String,
    /// The top module.
    pub module: String,
    pub inputs: Vec<Port>,
    pub outputs: Vec<Port>,
    /// The Verilog text, called only when the cache has no build for `key`.
    pub verilog: Box<dyn Fn() -> Result<String, String> + Send + Sync>,
}

impl Design {
    /// A design given by its Verilog text (keyed on the text itself): a mutant, a block outside
    /// the registry.
    pub fn from_verilog(
        name: &str,
        module: &str,
        verilog: String,
        inputs: Vec<Port>,
        outputs: Vec<Port>,
    ) -> Design {
        let key = format!("verilog:{:016x}", compile::fnv(verilog.as_bytes()));
        Design {
            name: name.to_string(),
            key,
            module: module.to_string(),
            inputs,
            outputs,
            verilog: Box::new(move || Ok(verilog.clone())),
        }
    }
}

/// The design of block `B` built with `p`.
pub fn design<B: RtlBlock>(p: &B::Params) -> Design {
    let dut = B::build(p);
    let (inputs, outputs) = (
        rtl::core::sim::Dut::inputs(&dut),
        rtl::core::sim::Dut::outputs(&dut),
    );
    let name = match p.describe() {
        Some(d) => format!("{} ({d})", B::NAME),
        None => B::NAME.to_string(),
    };
    let params = p.clone();
    Design {
        name,
        key: format!("block:{}|{:?}|{}", B::NAME, p, rtl::SOURCE_FINGERPRINT),
        module: module_name(B::NAME),
        inputs,
        outputs,
        verilog: Box::new(move || rtl::core::export::verilog::<B>(&params)),
    }
}

/// A fresh instance of block `B` built with `p`, compiled first if the cache has no build.
pub fn model<B: RtlBlock>(p: &B::Params) -> Result<VModel, String> {
    VModel::new(build(&design::<B>(p))?)
}

/// Whether Verilator and a C++ compiler are installed ([`toolchain`] says what is missing).
pub fn available() -> bool {
    toolchain().is_ok()
}
