//! The block list: every exportable block, once. `shadecore export-verilog`, `synth`, `stream`
//! and `blocks` (the README's table), and the generic tests through the bench side
//! (`testbenches::registry`, which adds stimulus, golden comparison and the bit-exact twin to
//! the same list), are all driven from [`BLOCKS`].
//!
//! A block implements [`rtl::core::registry::RtlBlock`] in its `rtl/src` file (name, parameters,
//! latency, multipliers, build); one line in [`with_blocks!`](crate::with_blocks) lists it.

use std::marker::PhantomData;
use std::path::Path;

use rtl::core::registry::{module_name, BlockParams, Options, RtlBlock};
use rtl::core::sim::{Model, Port};

use crate::engine::Sim;

/// Calls `$m!` with the type of every exportable block, in the README table's order: the one
/// list of blocks, which [`BLOCKS`] and the bench registry (`testbenches::registry::BLOCKS`)
/// are both made from.
#[macro_export]
macro_rules! with_blocks {
    ($m:ident) => {
        $m![
            rtl::units::normalizer::Normalizer,
            rtl::units::normalizer::NormalizerK,
            rtl::units::k_recurrence::KRecurrence,
            rtl::units::k_recurrence::SpanNormalizer,
            rtl::units::address_block::AddressBlock,
            rtl::units::address_block::SubpixelAddressBlock,
            rtl::units::intensity_interpolator::IntensityInterpolator,
            rtl::pipelines::gouraud_raster::GouraudRaster,
            rtl::stream::gouraud_stream::GouraudStream,
            rtl::units::four_triangle::FourTriangle,
            rtl::units::four_triangle::SubpixelFourTriangle,
            rtl::pipelines::subdivision_raster::SubdivisionRaster,
            rtl::stream::subdivision_stream::SubdivisionStream,
            rtl::units::vector_interpolator::VectorInterpolator,
            rtl::units::lighting_unit::LightingUnit,
            rtl::units::colour_combine::ColourCombine,
            rtl::units::power_unit::PowerUnit,
            rtl::units::brzssk::Brzssk,
            rtl::pipelines::pixel_pipeline::PixelPipeline,
            rtl::stream::pixel_stream::PixelStream,
            rtl::units::cos_v_accumulator::CosVAccumulator,
            rtl::units::fast_unit::FastUnit,
            rtl::pipelines::span_pipeline::AngularPipeline,
            rtl::pipelines::span_pipeline::FastPipeline,
            rtl::units::horner_unit::HornerUnit,
            rtl::pipelines::cubic_pipeline::CubicPipeline,
            rtl::stream::cubic_stream::CubicStream,
            rtl::stream::angular_stream::AngularStream,
            rtl::stream::fast_stream::FastStream,
            rtl::stream::quadric_stream::QuadricStream,
            rtl::units::quadric_unit::QuadricUnit,
            rtl::units::texture_coord::TextureCoord,
            rtl::units::texture_quadratic::TextureQuadratic,
            rtl::units::texture_bezier::TextureBezier,
            rtl::units::texture_memory::TextureMemory,
            rtl::pipelines::textured_pipeline::TexturedPipeline,
            rtl::stream::textured_stream::TexturedStream,
        ]
    };
}

/// A registered block, object-safe: what the commands call.
pub trait Block: Sync {
    fn name(&self) -> &'static str;
    fn module_name(&self) -> String {
        module_name(self.name())
    }
    fn summary(&self) -> &'static str;
    fn latency(&self) -> usize;
    fn latency_meaning(&self) -> &'static str;
    /// Multipliers of the default build (the README table's figure).
    fn multipliers(&self) -> usize;
    /// Multipliers of the build with `o`.
    fn multipliers_with(&self, o: &Options) -> Result<usize, String>;
    /// The option sets the generic tests build and check ([`BlockParams::test_sets`]).
    fn test_sets(&self) -> Vec<Options>;
    /// The [`Options`] keys the block's parameters read.
    fn param_keys(&self) -> &'static [&'static str];
    /// Check that the options build this block (errors name the problem).
    fn check_options(&self, o: &Options) -> Result<(), String>;
    /// Input and output ports (the simulation's row order).
    fn ports(&self) -> (Vec<Port>, Vec<Port>);
    fn verilog(&self, o: &Options) -> Result<String, String>;
    /// The rust-hdl simulation's output rows for `rows`.
    fn simulate(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String>;
    /// A fresh instance built with `o` on `sim` (Verilator: compiled first when not cached).
    fn model(&self, o: &Options, sim: Sim) -> Result<Box<dyn Model>, String>;
    /// The Verilator design of the block built with `o`.
    fn design(&self, o: &Options) -> Result<verilated::Design, String>;
    /// [`Block::simulate`] on `sim`.
    fn simulate_on(
        &self,
        o: &Options,
        rows: &[Vec<u64>],
        sim: Sim,
    ) -> Result<Vec<Vec<u64>>, String> {
        rtl::core::sim::run_model(self.model(o, sim)?.as_mut(), rows)
    }
    /// Replay `rows` under rust-hdl writing a VCD of the whole run (every signal) to `path`.
    fn write_vcd(&self, o: &Options, rows: &[Vec<u64>], path: &Path) -> Result<(), String>;
}

/// The [`Block`] of a block type.
pub struct Registered<B>(PhantomData<fn() -> B>);

/// The [`Block`] of `B` (used in [`BLOCKS`]).
pub const fn block<B: RtlBlock>() -> Registered<B> {
    Registered(PhantomData)
}

impl<B: RtlBlock + 'static> Block for Registered<B> {
    fn name(&self) -> &'static str {
        B::NAME
    }
    fn summary(&self) -> &'static str {
        B::SUMMARY
    }
    fn latency(&self) -> usize {
        B::LATENCY
    }
    fn latency_meaning(&self) -> &'static str {
        B::LATENCY_MEANING
    }
    fn multipliers(&self) -> usize {
        B::MULTIPLIERS
    }
    fn multipliers_with(&self, o: &Options) -> Result<usize, String> {
        Ok(B::Params::from_options(o)?
            .multipliers()
            .unwrap_or(B::MULTIPLIERS))
    }
    fn test_sets(&self) -> Vec<Options> {
        B::Params::test_sets()
    }
    fn param_keys(&self) -> &'static [&'static str] {
        B::Params::KEYS
    }
    fn check_options(&self, o: &Options) -> Result<(), String> {
        B::Params::from_options(o).map(|_| ())
    }
    fn ports(&self) -> (Vec<Port>, Vec<Port>) {
        // Ports do not depend on the parameters; build with the defaults.
        let d = B::build(&B::Params::from_options(&Options::new()).expect("default parameters"));
        (d.inputs(), d.outputs())
    }
    fn verilog(&self, o: &Options) -> Result<String, String> {
        rtl::core::export::verilog::<B>(&B::Params::from_options(o)?)
    }
    fn simulate(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String> {
        rtl::core::sim::simulate_rows(B::build(&B::Params::from_options(o)?), rows)
    }
    fn model(&self, o: &Options, sim: Sim) -> Result<Box<dyn Model>, String> {
        crate::engine::model::<B>(&B::Params::from_options(o)?, sim)
    }
    fn design(&self, o: &Options) -> Result<verilated::Design, String> {
        Ok(verilated::design::<B>(&B::Params::from_options(o)?))
    }
    fn write_vcd(&self, o: &Options, rows: &[Vec<u64>], path: &Path) -> Result<(), String> {
        let dut = B::build(&B::Params::from_options(o)?);
        rtl::core::sim::write_vcd_window(dut, rows, 0, rows.len() as u64, path)
    }
}

macro_rules! block_list {
    ($($t:ty),* $(,)?) => {
        &[$(&block::<$t>()),*]
    };
}

/// Every exportable block.
pub static BLOCKS: &[&dyn Block] = with_blocks!(block_list);

/// The block named `name`.
pub fn find(name: &str) -> Result<&'static dyn Block, String> {
    BLOCKS
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| format!("unknown block {name:?} (expected one of: {})", names()))
}

/// `NAME`, several names comma-separated (in that order), or `all`.
pub fn select(name: &str) -> Result<Vec<&'static dyn Block>, String> {
    if name == "all" {
        return Ok(BLOCKS.to_vec());
    }
    let mut chosen: Vec<&'static dyn Block> = Vec::new();
    for n in name.split(',') {
        let b = find(n).map_err(|e| format!("{e}, or all"))?;
        if chosen.iter().any(|c| c.name() == b.name()) {
            return Err(format!("block {n} is named twice"));
        }
        chosen.push(b);
    }
    Ok(chosen)
}

/// The block names, comma-separated.
pub fn names() -> String {
    BLOCKS
        .iter()
        .map(|b| b.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `shadecore synth`: Yosys cell counts, and the nextpnr UP5K Fmax when `pnr` and
/// nextpnr-ice40 is installed (`None` otherwise).
pub fn synth_block(
    block: &dyn Block,
    o: &Options,
    pnr: bool,
) -> Result<(crate::synth::SynthReport, Placement), String> {
    use crate::tools::{self, Tool};
    if !tools::available(Tool::Yosys) {
        return Err("yosys is not installed (apt-get install yosys)".into());
    }
    let v = block.verilog(o)?;
    let module = block.module_name();
    let rep = crate::synth::check_and_synth(&v, &module, &format!("synth-{}", block.name()))?;
    let placement = if !pnr {
        Placement::NotAsked
    } else if rep.mac16() > UP5K_MAC16 {
        Placement::DoesNotFit(format!(
            "{} SB_MAC16 > the iCE40 UP5K's {UP5K_MAC16}",
            rep.mac16()
        ))
    } else if rep.luts() > UP5K_LUT4 {
        Placement::DoesNotFit(format!(
            "{} LUT4 > the iCE40 UP5K's {UP5K_LUT4}",
            rep.luts()
        ))
    } else if rep.ffs() > UP5K_LUT4 {
        // One flip-flop per logic cell.
        Placement::DoesNotFit(format!(
            "{} flip-flops > the iCE40 UP5K's {UP5K_LUT4} logic cells",
            rep.ffs()
        ))
    } else if !tools::available(Tool::NextpnrIce40) {
        Placement::NoTool
    } else {
        let tag = format!("pnr-{}", block.name());
        match crate::synth::fmax_ice40_up5k(&v, &module, &block.ports(), &tag) {
            Ok(f) => Placement::Fmax(f),
            // LUTs and flip-flops that do not pack into the part's logic cells together.
            Err(e) if e.contains("Unable to place cell") => Placement::DoesNotFit(format!(
                "nextpnr-ice40 ran out of the UP5K's {UP5K_LUT4} logic cells ({} LUT4 and {} \
                 flip-flops do not pack)",
                rep.luts(),
                rep.ffs()
            )),
            // The analytic placer's legaliser gives up ("design is probably at utilisation
            // limit"): `gouraud-stream` since the BVI's side-by-side sums, with 3 912 of the
            // 5 280 logic cells packed (seed 1; seed 2 had not legalised after 4 minutes, nor
            // had the annealing placer finished its initial placement after 3).
            Err(e) if e.contains("Unable to find legal placement") => {
                Placement::DoesNotFit(format!(
                    "nextpnr-ice40 found no legal placement in the UP5K's {UP5K_LUT4} logic \
                     cells ({} LUT4, {} flip-flops)",
                    rep.luts(),
                    rep.ffs()
                ))
            }
            Err(e) => return Err(e),
        }
    };
    Ok((rep, placement))
}

/// SB_MAC16 blocks of the iCE40 UP5K, the part `synth` places into.
pub const UP5K_MAC16: u64 = 8;
/// Logic cells (LUT4) of the iCE40 UP5K.
pub const UP5K_LUT4: u64 = 5280;

/// What place-and-route said about a block (`synth_block`).
#[derive(Clone, Debug, PartialEq)]
pub enum Placement {
    /// nextpnr-ice40's maximum clock after routing, MHz.
    Fmax(f64),
    /// More SB_MAC16 or LUT4 than the UP5K has (which, and how many): not placed.
    DoesNotFit(String),
    /// nextpnr-ice40 is not installed.
    NoTool,
    /// `--no-pnr`.
    NotAsked,
}

/// The differential check of a registered block: `rows` through the rust-hdl simulation and
/// through its exported Verilog (built with `o`) under `sim` — Verilator in process (the
/// cached library, no files), Icarus through a generated testbench; identical outputs every
/// clock.
pub fn differential(
    block: &dyn Block,
    o: &Options,
    rows: &[Vec<u64>],
    sim: crate::verilog::Simulator,
    tag: &str,
) -> Result<crate::verilog::DiffReport, crate::verilog::DiffError> {
    use crate::verilog::DiffError;
    let rust_rows = block.simulate(o, rows).map_err(DiffError::Tool)?;
    if sim == crate::verilog::Simulator::Verilator {
        let t = std::time::Instant::now();
        let v = block
            .simulate_on(o, rows, Sim::Verilator)
            .map_err(DiffError::Tool)?;
        let outputs = block.ports().1;
        for (c, (r, w)) in rust_rows.iter().zip(&v).enumerate() {
            if let Some(k) = (0..outputs.len()).find(|&k| r[k] != w[k]) {
                return Err(DiffError::Mismatch(crate::verilog::Mismatch {
                    cycle: c,
                    port: outputs[k].name.into(),
                    rust_hdl: r[k],
                    verilog: format!("{:x}", w[k]),
                    dir: verilated::cache_dir(),
                }));
            }
        }
        return Ok(crate::verilog::DiffReport {
            cycles: rows.len(),
            ports: outputs.len(),
            verilog_sim_time: t.elapsed(),
            dir: verilated::cache_dir(),
        });
    }
    let v = block.verilog(o).map_err(DiffError::Tool)?;
    crate::verilog::differential_rows(
        &v,
        &block.module_name(),
        block.ports(),
        rows,
        &rust_rows,
        sim,
        tag,
    )
}

/// The README's block table, generated from [`BLOCKS`] (`shadecore blocks` prints it; a test
/// keeps the README's copy identical).
pub fn markdown_table() -> String {
    let mut s = String::from(
        "| block | what it is | latency (clocks) | measured from | 16×16 multipliers | parameters |\n\
         |---|---|---:|---|---:|---|\n",
    );
    for b in BLOCKS {
        let params = if b.param_keys().is_empty() {
            "—".to_string()
        } else {
            b.param_keys()
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        s.push_str(&format!(
            "| `{}` | {} | {} | {} | {} | {} |\n",
            b.name(),
            b.summary().replace('|', "\\|"),
            b.latency(),
            b.latency_meaning(),
            b.multipliers(),
            params
        ));
    }
    s
}
