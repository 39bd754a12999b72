//! Yosys and nextpnr flows on exported Verilog: lint-style checks (no latches, no undriven
//! wires, no multiple drivers or loops), cell counts (generic and iCE40) and the estimated
//! maximum clock of an iCE40 UP5K placement.
//!
//! One module per target: [`ice40`] (cell counts, UP5K placement), [`ecp5`] (LFE5U parts,
//! `synth_ecp5`, nextpnr-ecp5 in a timing shell), [`pins`] (a top on its own package pins).
//! This file holds what they share: the Yosys runner, its `stat` parser and the timing shell.

pub mod ecp5;
pub mod ice40;
pub mod pins;

pub use ecp5::*;
pub use ice40::*;
pub use pins::*;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;

use crate::tools;
use rtl::core::sim::Port;

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
    /// Whether `synth_ice40 -dsp` stopped after its `coarse` step ([`check_and_map_ice40_dsp`]):
    /// then its table holds coarse cells and SB_MAC16, no LUT or iCE40 flip-flop.
    pub ice40_coarse: bool,
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
        if self.ice40_coarse {
            return writeln!(
                f,
                "{}: Yosys synth_ice40 -dsp up to its coarse step: {} SB_MAC16 ({} cells)",
                self.top,
                self.mac16(),
                self.ice40_total
            );
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

pub(crate) fn yosys(dir: &std::path::Path, script: &str, log: &str) -> Result<String, String> {
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

/// nextpnr's last "Max frequency for clock" figure in MHz ("Max frequency for clock
/// 'clock$SB_IO_IN_$glb_clk': 23.45 MHz (PASS at 12.00 MHz)"; the last occurrence is after
/// routing), for nextpnr-ice40 and nextpnr-ecp5 alike.
pub(crate) fn parse_fmax(log: &str) -> Option<f64> {
    log.lines()
        .rfind(|l| l.contains("Max frequency for clock"))
        .and_then(|l| l.split("': ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok())
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
                vec![rtl::core::sim::Port {
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

    /// The last figure counts (nextpnr prints one before and one after routing); none: None.
    #[test]
    fn fmax_is_the_last_figure() {
        let log = "\
Info: Max frequency for clock 'clk': 120.50 MHz (PASS at 12.00 MHz)
Info: Routing..
Info: Max frequency for clock '$glbnet$clock$TRELLIS_IO_IN': 95.24 MHz (FAIL at 100.00 MHz)
";
        assert_eq!(parse_fmax(log), Some(95.24));
        assert_eq!(parse_fmax("Info: Routing..\n"), None);
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
