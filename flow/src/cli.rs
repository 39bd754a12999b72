//! The command-line vocabulary shared by `shadecore` and `shadecore-sim`: the build options of
//! a block and the simulator switch.

use rtl::core::registry::Options;

use crate::engine::Sim;

/// The build options every RTL command takes (each block reads the ones it knows).
#[derive(clap::Args, Debug)]
pub struct BuildArgs {
    /// Normalizer coefficients: published (0.822, −2.046, 2.227) or fit (golden FIT).
    #[arg(long, default_value = "published")]
    pub coeffs: String,
    /// Power unit mode: exact (cos^n) or w4, w8, w16 (W(n, γ) with that k).
    #[arg(long, default_value = "exact")]
    pub power: String,
    /// BRZSSK on or off (default: on for `brzssk`, off in `pixel-pipeline`).
    #[arg(long)]
    pub bump: Option<String>,
    /// The fast unit's 1/sqrt(M+1) set: chebyshev, shift-add or fit.
    #[arg(long, default_value = "chebyshev")]
    pub inv_sqrt: String,
    /// The Horner unit's variant: serial (fig. 2.6, one multiplier, 3 clocks per pixel) or
    /// pipelined (three multipliers, one pixel per clock).
    #[arg(long, default_value = "serial")]
    pub horner: String,
}

impl BuildArgs {
    /// The options as `key=value` pairs; without --bump each block keeps its own default (on
    /// for brzssk, off in the pipeline).
    pub fn options(&self) -> Options {
        let o = Options::new()
            .with("coeffs", &self.coeffs)
            .with("power", &self.power)
            .with("inv-sqrt", &self.inv_sqrt)
            .with("horner", &self.horner);
        match &self.bump {
            Some(b) => o.with("bump", b),
            None => o,
        }
    }
}

/// `--sim`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SimArg {
    /// The exported Verilog under Verilator, verilated once per block into a shared library
    /// cached under target/verilated/ and stepped in process.
    Verilator,
    /// rust-hdl's own simulation, stepped by hand (no external tool; writes VCDs).
    RustHdl,
}

impl From<SimArg> for Sim {
    fn from(a: SimArg) -> Sim {
        match a {
            SimArg::Verilator => Sim::Verilator,
            SimArg::RustHdl => Sim::RustHdl,
        }
    }
}
