//! What every exportable block states about itself, once, in its own file: its name, what it is
//! built from (its own parameter type), latency and what the latency measures, and how many
//! 16×16 multipliers it instantiates. The bench side (`testbenches::registry`) adds stimulus,
//! golden comparison and the bit-exact twin, and lists every block in one place; the commands
//! (`export-verilog`, `synth`, `sim`) and the generic tests are driven from that list.
//!
//! Not a block: no ports, no latency of its own.

use std::collections::BTreeMap;
use std::fmt::Debug;

use crate::core::sim::Dut;

/// `key=value` build options from the command line (`--coeffs fit` is `coeffs=fit`). A block's
/// parameter type reads the keys it knows and ignores the others.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Options(BTreeMap<String, String>);

impl Options {
    pub fn new() -> Self {
        Self::default()
    }
    /// Set `key` to `value` (builder style).
    pub fn with(mut self, key: &str, value: &str) -> Self {
        self.0.insert(key.to_string(), value.to_string());
        self
    }
    pub fn get(&self, key: &str) -> Option<&str> {
        self.0.get(key).map(String::as_str)
    }
}

/// A block's build parameters. `KEYS` are the [`Options`] it reads; a missing key means the
/// default.
pub trait BlockParams: Clone + Debug + Send + Sync + 'static {
    const KEYS: &'static [&'static str];
    fn from_options(o: &Options) -> Result<Self, String>;
    /// One line for the exported Verilog's header naming the parameters (`None`: none).
    fn describe(&self) -> Option<String>;
    /// The parameter sets the generic tests build and check (every value that changes the
    /// hardware): by default only the defaults.
    fn test_sets() -> Vec<Options> {
        vec![Options::new()]
    }
    /// 16×16 multipliers of the block built with these parameters, when they change the
    /// count; `None`: the block's [`RtlBlock::MULTIPLIERS`].
    fn multipliers(&self) -> Option<usize> {
        None
    }
}

/// The parameters of a block that has none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoParams;

impl BlockParams for NoParams {
    const KEYS: &'static [&'static str] = &[];
    fn from_options(_: &Options) -> Result<Self, String> {
        Ok(NoParams)
    }
    fn describe(&self) -> Option<String> {
        None
    }
}

/// One exportable block: implemented once, in the block's `rtl/src` file.
pub trait RtlBlock: Dut + Sized {
    type Params: BlockParams;
    /// CLI name (`--block NAME`); the Verilog module is the same with `_` for `-`.
    const NAME: &'static str;
    /// One line: what goes in and what comes out, with the SPEC section.
    const SUMMARY: &'static str;
    /// Clocks from an input to its output ([`RtlBlock::LATENCY_MEANING`] says which).
    const LATENCY: usize;
    /// What [`RtlBlock::LATENCY`] measures, and the block's throughput.
    const LATENCY_MEANING: &'static str;
    /// 16×16 multipliers instantiated (one DSP slice each: SB_MAC16 on iCE40) by the default
    /// build; a parameter set may change it ([`BlockParams::multipliers`]).
    const MULTIPLIERS: usize;
    fn build(p: &Self::Params) -> Self;
}

/// The Verilog module name of a block name.
pub fn module_name(name: &str) -> String {
    name.replace('-', "_")
}
