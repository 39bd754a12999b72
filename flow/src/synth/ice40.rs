//! iCE40: Yosys `synth_ice40 -dsp` cell counts with the structural checks, and nextpnr-ice40
//! placement of a block on an UP5K inside the timing shell.

use super::{parse_stat, timing_shell, yosys, SynthReport};
use crate::tools;
use rtl::core::sim::Port;

/// Read `verilog` into Yosys, elaborate `top` and fail on latches, undriven or multiply
/// driven wires and combinational loops (`check -assert`, before and after synthesis);
/// then count cells of a generic `synth` and of `synth_ice40 -dsp`.
pub fn check_and_synth(verilog: &str, top: &str, tag: &str) -> Result<SynthReport, String> {
    check_and_synth_with(verilog, top, tag, Stage::GenericAndIce40)
}

/// [`check_and_synth`] without the generic gate-level `synth` (its cell count stays 0): the
/// latch and `check -assert` checks on the elaborated design, then `synth_ice40 -dsp` and its
/// `check -assert`. The generic `synth` expands every multiplier into gates and takes 80–90 %
/// of the time on the large tops; the generic tests need only the checks and the iCE40 map.
pub fn check_and_map_ice40(verilog: &str, top: &str, tag: &str) -> Result<SynthReport, String> {
    check_and_synth_with(verilog, top, tag, Stage::Ice40)
}

/// The checks of [`check_and_map_ice40`] with `synth_ice40 -dsp` stopped after its `coarse`
/// step (`-run begin:map_ram`), where `ice40_dsp` has packed the products into SB_MAC16: the
/// returned cells are coarse ones (`$add`, `$dff`, …, and SB_MAC16), with no LUT or iCE40
/// flip-flop yet. The LUT mapping that follows takes about two thirds of the map's time on the
/// large tops (pixel-stream: 27 s coarse, 76 s whole, one core) and packs no multiplier: on
/// each block's first option set (27 builds) the two SB_MAC16 counts were equal.
pub fn check_and_map_ice40_dsp(verilog: &str, top: &str, tag: &str) -> Result<SynthReport, String> {
    check_and_synth_with(verilog, top, tag, Stage::Ice40Coarse)
}

/// How far [`check_and_synth_with`] synthesizes.
#[derive(Clone, Copy, PartialEq)]
enum Stage {
    /// Generic `synth`, then the whole `synth_ice40 -dsp`.
    GenericAndIce40,
    /// The whole `synth_ice40 -dsp`.
    Ice40,
    /// `synth_ice40 -dsp` up to its multiplier packing.
    Ice40Coarse,
}

fn check_and_synth_with(
    verilog: &str,
    top: &str,
    tag: &str,
    stage: Stage,
) -> Result<SynthReport, String> {
    let generic_synth = stage == Stage::GenericAndIce40;
    let dir = tools::unique_dir(tag)?;
    std::fs::write(dir.join("dut.v"), verilog).map_err(|e| e.to_string())?;
    // One Yosys run: the checks on the elaborated design, then (when asked) the generic `synth`
    // on a copy of it, then `synth_ice40` on the elaborated design as `design -load` gives it
    // back (its own `hierarchy` and `proc` find nothing left to do). Reading and elaborating
    // the Verilog once is a quarter of the time on the large tops.
    let generic = if generic_synth {
        format!(
            "design -save elaborated\n\
             synth -top {top}\n\
             select -assert-none t:$_DLATCH_*\n\
             check -assert\n\
             tee -o generic_stat.txt stat\n\
             design -load elaborated\n"
        )
    } else {
        String::new()
    };
    let ice40 = format!(
        "synth_ice40 -dsp -top {top}{}\ntee -o ice40_stat.txt stat\n",
        // After the coarse step alone, `check` reports wire bits that the step's width
        // reduction left undriven and the later clean-up removes (lighting-unit and
        // textured-pipeline, whose whole map passes `check -assert`): a stopped map is
        // checked on the elaborated design only.
        if stage == Stage::Ice40Coarse {
            " -run begin:map_ram"
        } else {
            "\ncheck -assert"
        }
    );
    let log = yosys(
        &dir,
        &format!(
            "read_verilog dut.v\n\
             hierarchy -check -top {top}\n\
             proc\n\
             select -assert-none t:$dlatch t:$adlatch t:$dlatchsr\n\
             check -assert\n\
             {generic}{ice40}"
        ),
        "yosys",
    )
    .map_err(|e| format!("Yosys check/synth of {top} failed: {e}"))?;
    if log.contains("Latch inferred") {
        return Err(format!(
            "Yosys inferred a latch in {top} (see {})",
            dir.display()
        ));
    }
    let (generic_total, generic_cells) = if generic_synth {
        let stat =
            std::fs::read_to_string(dir.join("generic_stat.txt")).map_err(|e| e.to_string())?;
        parse_stat(&stat)
    } else {
        Default::default()
    };
    let stat = std::fs::read_to_string(dir.join("ice40_stat.txt")).map_err(|e| e.to_string())?;
    let (ice40_total, ice40_cells) = parse_stat(&stat);
    Ok(SynthReport {
        top: top.into(),
        generic_run: generic_synth,
        generic_total,
        generic: generic_cells,
        ice40_coarse: stage == Stage::Ice40Coarse,
        ice40_total,
        ice40: ice40_cells,
        dir,
    })
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
    super::parse_fmax(&text).ok_or_else(|| {
        format!(
            "no 'Max frequency' line in nextpnr's output (see {})",
            dir.display()
        )
    })
}
