//! The command-line vocabulary shared by `shadecore` and `shadecore-sim`: the build options of
//! a block and the simulator switch.

use rtl::core::registry::Options;

use crate::blocks::Block;
use crate::engine::Sim;

/// The build options every RTL command takes (each block reads the ones it knows). A flag
/// left out takes its default; a flag given must be read by one of the chosen blocks and name a
/// value that block accepts ([`BuildArgs::checked_options`]).
#[derive(clap::Args, Debug)]
pub struct BuildArgs {
    /// Normalizer coefficients: published (0.822, −2.046, 2.227; the default), fit (golden
    /// FIT) or piecewise (four segments of K, golden PIECEWISE).
    #[arg(long)]
    pub coeffs: Option<String>,
    /// Power unit mode: exact (cos^n; the default) or w4, w8, w16 (W(n, γ) with that k).
    #[arg(long)]
    pub power: Option<String>,
    /// BRZSSK on or off (default: on for `brzssk`, off in `pixel-pipeline`).
    #[arg(long)]
    pub bump: Option<String>,
    /// The fast unit's 1/sqrt(M+1) set: chebyshev (the default), shift-add or fit.
    #[arg(long)]
    pub inv_sqrt: Option<String>,
    /// The Horner unit's variant: serial (fig. 2.6, one multiplier, 3 clocks per pixel; the
    /// default) or pipelined (three multipliers, one pixel per clock).
    #[arg(long)]
    pub horner: Option<String>,
    /// The texture-coordinate block's k: correction steps resolved per clock, 1 (the seed's),
    /// 2 or 4 (the default: 2 for `texture-coord`, 4 for `textured-pipeline`).
    #[arg(long)]
    pub tex_k: Option<String>,
    /// The textured pipeline's texture coordinate (`textured-pipeline`, `textured-stream`):
    /// additive (SPEC §14's block; the default), quadratic (§15's unit on per-line records) or
    /// bezier (§16's unit on per-line records).
    #[arg(long)]
    pub tex_coord: Option<String>,
}

impl BuildArgs {
    /// The flags given on the command line: (option key, flag, value).
    fn given(&self) -> Vec<(&'static str, &'static str, &str)> {
        [
            ("coeffs", "--coeffs", &self.coeffs),
            ("power", "--power", &self.power),
            ("bump", "--bump", &self.bump),
            ("inv-sqrt", "--inv-sqrt", &self.inv_sqrt),
            ("horner", "--horner", &self.horner),
            ("tex-k", "--tex-k", &self.tex_k),
            ("texture", "--tex-coord", &self.tex_coord),
        ]
        .into_iter()
        .filter_map(|(k, f, v)| v.as_deref().map(|v| (k, f, v)))
        .collect()
    }

    /// The options as `key=value` pairs: the defaults (coeffs published, power exact, inv-sqrt
    /// chebyshev, horner serial) with the flags given over them; without --bump each block
    /// keeps its own default (on for brzssk, off in the pipeline).
    pub fn options(&self) -> Options {
        let mut o = Options::new()
            .with("coeffs", "published")
            .with("power", "exact")
            .with("inv-sqrt", "chebyshev")
            .with("horner", "serial");
        for (k, _, v) in self.given() {
            o = o.with(k, v);
        }
        o
    }

    /// [`BuildArgs::options`], checked against `blocks` (the ones the command builds): every
    /// flag given is read by one of them (else it would be silently ignored) and its value is
    /// one that block accepts; each block builds with the options. Errors are one line naming
    /// the flag.
    pub fn checked_options(&self, blocks: &[&'static dyn Block]) -> Result<Options, String> {
        for (key, flag, value) in self.given() {
            let readers: Vec<&&dyn Block> = blocks
                .iter()
                .filter(|b| b.param_keys().contains(&key))
                .collect();
            let Some(first) = readers.first() else {
                let names: Vec<&str> = blocks.iter().map(|b| b.name()).collect();
                let users: Vec<&str> = crate::blocks::BLOCKS
                    .iter()
                    .filter(|b| b.param_keys().contains(&key))
                    .map(|b| b.name())
                    .collect();
                return Err(format!(
                    "{flag} has no effect on {} (it is read by {})",
                    names.join(", "),
                    users.join(", ")
                ));
            };
            first
                .check_options(&Options::new().with(key, value))
                .map_err(|e| format!("{flag} {value}: {e}"))?;
        }
        let o = self.options();
        for b in blocks {
            if !b.param_keys().is_empty() {
                b.check_options(&o)?;
            }
        }
        Ok(o)
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
