//! Yosys and nextpnr flows on exported Verilog: lint-style checks (no latches, no undriven
//! wires, no multiple drivers or loops), cell counts (generic and iCE40) and the estimated
//! maximum clock of an iCE40 UP5K placement.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;

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
    /// Generic `synth` cell count and table.
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
        writeln!(
            f,
            "{}: Yosys generic synth: {} cells ({} flip-flops)",
            self.top,
            self.generic_total,
            self.generic_ffs()
        )?;
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
    let dir = tools::unique_dir(tag)?;
    std::fs::write(dir.join("dut.v"), verilog).map_err(|e| e.to_string())?;
    let generic = yosys(
        &dir,
        &format!(
            "read_verilog dut.v\n\
             hierarchy -check -top {top}\n\
             proc\n\
             select -assert-none t:$dlatch t:$adlatch t:$dlatchsr\n\
             check -assert\n\
             synth -top {top}\n\
             select -assert-none t:$_DLATCH_*\n\
             check -assert\n\
             tee -o generic_stat.txt stat\n"
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
    let stat = std::fs::read_to_string(dir.join("generic_stat.txt")).unwrap_or(generic);
    let (generic_total, generic_cells) = parse_stat(&stat);
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
