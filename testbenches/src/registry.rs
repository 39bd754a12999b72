//! The block registry: every exportable block, once. `shadecore export-verilog`, `synth`, `sim`
//! (with its VCD), the generic tests (twin every clock, golden every clock, Yosys, Icarus,
//! Verilator differential, SB_MAC16 count) and the README's block table are all driven from
//! [`BLOCKS`].
//!
//! A block implements [`rtl::registry::RtlBlock`] in its `rtl/src` file (name, parameters,
//! latency, multipliers, build) and [`Bench`] in its `testbenches/src` file (stimulus with
//! golden expectations, its bit-exact twin); then one line in [`BLOCKS`] registers it.

use std::marker::PhantomData;
use std::path::Path;

use rtl::registry::{module_name, BlockParams, Options, RtlBlock};

use crate::harness::{self, CheckSpec, Compare, Expected, Failure, Port, Report};

/// A checked run: its report, or the first failure (with its VCD).
pub type Checked = Result<Report, Box<Failure>>;

/// A seeded stimulus with golden expectations and how to compare them.
pub struct Stimulus {
    pub rows: Vec<Vec<u64>>,
    pub expected: Vec<Vec<Expected>>,
    pub compare: Vec<Compare>,
}

/// A block's bit-exact integer twin, written independently of the RTL (same rounding and
/// saturation): one input row per clock in, the output row the block shows in that clock
/// (sampled before the rising edge, as `rtl::sim::Stepper::step` samples) out. It starts
/// from the reset state (every register 0, as rust-hdl's and the exported Verilog's).
pub trait Twin {
    fn step(&mut self, inputs: &[u64]) -> Vec<u64>;
}

/// The bench side of a block: implemented once, in its `testbenches/src` file.
pub trait Bench: RtlBlock {
    /// What one stimulus item is ("vectors", "pixels", "triangles").
    const ITEMS: &'static str;
    /// Items `shadecore sim` simulates by default.
    const DEFAULT_ITEMS: usize;
    /// `n` items of seeded random stimulus (plus the block's named cases where it has them)
    /// with the golden (f64) expectation of every output port in every clock.
    fn stimulus(p: &Self::Params, n: usize, seed: u64) -> Stimulus;
    /// The block's bit-exact twin.
    fn twin(p: &Self::Params) -> Box<dyn Twin>;
    /// Extra rows for the twin comparison beyond the stimulus: named edge cases and inputs
    /// outside the formula's domain (saturation paths). None by default.
    fn edge_rows(_p: &Self::Params, _seed: u64) -> Vec<Vec<u64>> {
        Vec::new()
    }
}

/// A registered block, object-safe: what the commands and generic tests call.
pub trait Entry: Sync {
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
    fn items(&self) -> &'static str;
    fn default_items(&self) -> usize;
    /// The [`Options`] keys the block's parameters read.
    fn param_keys(&self) -> &'static [&'static str];
    /// Check that the options build this block (errors name the problem).
    fn check_options(&self, o: &Options) -> Result<(), String>;
    /// Input and output ports (the harness's row order).
    fn ports(&self) -> (Vec<Port>, Vec<Port>);
    fn verilog(&self, o: &Options) -> Result<String, String>;
    fn stimulus(&self, o: &Options, n: usize, seed: u64) -> Result<Stimulus, String>;
    /// Run `stim` through the RTL, checking every clock against the golden expectations.
    fn run_golden(&self, o: &Options, stim: &Stimulus, name: &str, seed: u64) -> Checked;
    /// Check `outputs`, recorded from `stim.rows` (a longer run may follow them), against the
    /// golden expectations without simulating again (a failure replays into a VCD).
    fn check_golden(
        &self,
        o: &Options,
        stim: &Stimulus,
        outputs: &[Vec<u64>],
        name: &str,
        seed: u64,
    ) -> Checked;
    /// [`Bench::edge_rows`].
    fn edge_rows(&self, o: &Options, seed: u64) -> Result<Vec<Vec<u64>>, String>;
    /// Run `rows` through the RTL, requiring every output port in every clock to equal the
    /// twin's bit for bit.
    fn run_twin(&self, o: &Options, rows: &[Vec<u64>], name: &str, seed: u64) -> Checked;
    /// The twin's output rows for `rows` (what the hardware must show, clock by clock).
    fn twin_rows(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String>;
    /// The rust-hdl simulation's output rows for `rows`.
    fn simulate(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String>;
    /// A fresh instance built with `o` on `sim` (Verilator: compiled first when not cached).
    fn model(
        &self,
        o: &Options,
        sim: pipeline::engine::Sim,
    ) -> Result<Box<dyn rtl::sim::Model>, String>;
    /// The Verilator design of the block built with `o`.
    fn design(&self, o: &Options) -> Result<verilated::Design, String>;
    /// [`Entry::simulate`] on `sim`.
    fn simulate_on(
        &self,
        o: &Options,
        rows: &[Vec<u64>],
        sim: pipeline::engine::Sim,
    ) -> Result<Vec<Vec<u64>>, String> {
        rtl::sim::run_model(self.model(o, sim)?.as_mut(), rows)
    }
    /// Replay `rows` writing a VCD of the whole run (every signal) to `path`.
    fn write_vcd(&self, o: &Options, rows: &[Vec<u64>], path: &Path) -> Result<(), String>;
    /// `n` seeded items in constant memory: batches of the block's default size (batch k
    /// seeded `seed + k`) driven back to back into one simulation, checked every clock against
    /// the twin (exactly) and the golden model, on `sim`, the VCD written to `vcd` as the clocks
    /// go (rust-hdl only); `progress(clocks)` after each batch. A failure's VCD is that file.
    fn sim_stream(
        &self,
        o: &Options,
        n: usize,
        seed: u64,
        vcd: Option<&Path>,
        sim: pipeline::engine::Sim,
        progress: &mut dyn FnMut(u64),
    ) -> Result<crate::harness::StreamReport, String>;
}

/// The [`Entry`] of a block type.
pub struct Registered<B>(PhantomData<fn() -> B>);

/// The registry entry of `B` (used in [`BLOCKS`]).
pub const fn entry<B: Bench>() -> Registered<B> {
    Registered(PhantomData)
}

fn failure(name: &str, seed: u64, detail: String) -> Box<Failure> {
    Box::new(Failure {
        name: name.into(),
        seed,
        cycle: 0,
        signal: "(set-up)".into(),
        expected: "-".into(),
        actual: "-".into(),
        vcd: None,
        detail,
    })
}

impl<B: Bench + 'static> Entry for Registered<B> {
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
    fn items(&self) -> &'static str {
        B::ITEMS
    }
    fn default_items(&self) -> usize {
        B::DEFAULT_ITEMS
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
        rtl::export::verilog::<B>(&B::Params::from_options(o)?)
    }
    fn stimulus(&self, o: &Options, n: usize, seed: u64) -> Result<Stimulus, String> {
        Ok(B::stimulus(&B::Params::from_options(o)?, n, seed))
    }
    fn run_golden(&self, o: &Options, stim: &Stimulus, name: &str, seed: u64) -> Checked {
        let p = B::Params::from_options(o).map_err(|e| failure(name, seed, e))?;
        let spec = CheckSpec {
            name: name.into(),
            seed,
            compare: stim.compare.clone(),
        };
        harness::run_rows(|| B::build(&p), &spec, &stim.rows, &stim.expected).map_err(Box::new)
    }
    fn check_golden(
        &self,
        o: &Options,
        stim: &Stimulus,
        outputs: &[Vec<u64>],
        name: &str,
        seed: u64,
    ) -> Checked {
        let p = B::Params::from_options(o).map_err(|e| failure(name, seed, e))?;
        let spec = CheckSpec {
            name: name.into(),
            seed,
            compare: stim.compare.clone(),
        };
        let n = stim.rows.len().min(outputs.len());
        harness::check_recorded(
            || B::build(&p),
            &spec,
            &stim.rows[..n],
            &outputs[..n],
            &stim.expected,
        )
        .map_err(Box::new)
    }
    fn edge_rows(&self, o: &Options, seed: u64) -> Result<Vec<Vec<u64>>, String> {
        Ok(B::edge_rows(&B::Params::from_options(o)?, seed))
    }
    fn run_twin(&self, o: &Options, rows: &[Vec<u64>], name: &str, seed: u64) -> Checked {
        let p = B::Params::from_options(o).map_err(|e| failure(name, seed, e))?;
        let mut twin = B::twin(&p);
        let n_out = self.ports().1.len();
        let spec = CheckSpec {
            name: name.into(),
            seed,
            compare: vec![Compare::Exact; n_out],
        };
        harness::run(
            || B::build(&p),
            &spec,
            |c, _| rows.get(c as usize).cloned(),
            |_, row| twin.step(row).into_iter().map(Expected::Word).collect(),
        )
        .map_err(Box::new)
    }
    fn twin_rows(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String> {
        let mut twin = B::twin(&B::Params::from_options(o)?);
        Ok(rows.iter().map(|r| twin.step(r)).collect())
    }
    fn simulate(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String> {
        harness::simulate_rows(B::build(&B::Params::from_options(o)?), rows)
    }
    fn model(
        &self,
        o: &Options,
        sim: pipeline::engine::Sim,
    ) -> Result<Box<dyn rtl::sim::Model>, String> {
        pipeline::engine::model::<B>(&B::Params::from_options(o)?, sim)
    }
    fn design(&self, o: &Options) -> Result<verilated::Design, String> {
        Ok(verilated::design::<B>(&B::Params::from_options(o)?))
    }
    fn write_vcd(&self, o: &Options, rows: &[Vec<u64>], path: &Path) -> Result<(), String> {
        let dut = B::build(&B::Params::from_options(o)?);
        harness::write_vcd_window(dut, rows, 0, rows.len() as u64, path)
    }
    fn sim_stream(
        &self,
        o: &Options,
        n: usize,
        seed: u64,
        vcd: Option<&Path>,
        sim: pipeline::engine::Sim,
        progress: &mut dyn FnMut(u64),
    ) -> Result<crate::harness::StreamReport, String> {
        let p = B::Params::from_options(o)?;
        let per = B::DEFAULT_ITEMS.max(1);
        let batches = n.div_ceil(per);
        let first = B::stimulus(&p, per.min(n), seed);
        let spec = CheckSpec {
            name: format!("sim-{}", B::NAME),
            seed,
            compare: first.compare.clone(),
        };
        let mut first = Some(first);
        let next = |k: usize| {
            if k >= batches {
                return None;
            }
            let st = match first.take() {
                Some(st) => st,
                None => B::stimulus(&p, per.min(n - k * per), seed.wrapping_add(k as u64)),
            };
            Some(harness::Batch {
                rows: st.rows,
                expected: st.expected,
            })
        };
        let mut twin = B::twin(&p);
        let mut model = pipeline::engine::model::<B>(&p, sim)?;
        if let Some(path) = vcd {
            let f = std::fs::File::create(path)
                .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
            model.start_vcd(Box::new(std::io::BufWriter::new(f)))?;
        }
        harness::run_stream_on(
            model.as_mut(),
            &spec,
            next,
            &mut |row| twin.step(row),
            progress,
        )
        .map_err(|mut f| {
            f.vcd = vcd.map(Path::to_path_buf);
            f.to_string()
        })
    }
}

/// Every exportable block. Adding a block: its `rtl/src` file (with `impl RtlBlock`), its
/// `testbenches/src` file (with `impl Bench`), and one line here.
pub static BLOCKS: &[&dyn Entry] = &[
    &entry::<rtl::normalizer::Normalizer>(),
    &entry::<rtl::normalizer::NormalizerK>(),
    &entry::<rtl::k_recurrence::KRecurrence>(),
    &entry::<rtl::k_recurrence::SpanNormalizer>(),
    &entry::<rtl::address_block::AddressBlock>(),
    &entry::<rtl::intensity_interpolator::IntensityInterpolator>(),
    &entry::<rtl::gouraud_raster::GouraudRaster>(),
    &entry::<rtl::gouraud_stream::GouraudStream>(),
    &entry::<rtl::four_triangle::FourTriangle>(),
    &entry::<rtl::subdivision_raster::SubdivisionRaster>(),
    &entry::<rtl::subdivision_stream::SubdivisionStream>(),
    &entry::<rtl::vector_interpolator::VectorInterpolator>(),
    &entry::<rtl::lighting_unit::LightingUnit>(),
    &entry::<rtl::colour_combine::ColourCombine>(),
    &entry::<rtl::power_unit::PowerUnit>(),
    &entry::<rtl::brzssk::Brzssk>(),
    &entry::<rtl::pixel_pipeline::PixelPipeline>(),
    &entry::<rtl::pixel_stream::PixelStream>(),
    &entry::<rtl::cos_v_accumulator::CosVAccumulator>(),
    &entry::<rtl::fast_unit::FastUnit>(),
    &entry::<rtl::span_pipeline::AngularPipeline>(),
    &entry::<rtl::span_pipeline::FastPipeline>(),
    &entry::<rtl::horner_unit::HornerUnit>(),
    &entry::<rtl::cubic_pipeline::CubicPipeline>(),
    &entry::<rtl::cubic_stream::CubicStream>(),
    &entry::<rtl::angular_stream::AngularStream>(),
    &entry::<rtl::fast_stream::FastStream>(),
    &entry::<rtl::quadric_stream::QuadricStream>(),
    &entry::<rtl::quadric_unit::QuadricUnit>(),
];

/// The entry named `name`.
pub fn find(name: &str) -> Result<&'static dyn Entry, String> {
    BLOCKS
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| format!("unknown block {name:?} (expected one of: {})", names()))
}

/// `NAME` or `all`.
pub fn select(name: &str) -> Result<Vec<&'static dyn Entry>, String> {
    if name == "all" {
        Ok(BLOCKS.to_vec())
    } else {
        find(name)
            .map(|b| vec![b])
            .map_err(|e| format!("{e}, or all"))
    }
}

/// The block names, comma-separated.
pub fn names() -> String {
    BLOCKS
        .iter()
        .map(|b| b.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Outcome of [`sim_to_vcd`].
pub struct SimOutcome {
    pub report: Report,
    pub vcd: std::path::PathBuf,
}

/// `shadecore sim`: `n` seeded items through `block`, checked every clock against its twin
/// (exactly) and the golden model (within the format's bound), then replayed into a VCD at
/// `vcd`. A check failure is returned as the error (its own VCD is under `target/sims/`).
pub fn sim_to_vcd(
    block: &dyn Entry,
    o: &Options,
    n: usize,
    seed: u64,
    vcd: &Path,
) -> Result<SimOutcome, String> {
    let stim = block.stimulus(o, n, seed)?;
    let name = format!("sim-{}", block.name());
    block
        .run_twin(o, &stim.rows, &format!("{name}-twin"), seed)
        .map_err(|f| f.to_string())?;
    let report = block
        .run_golden(o, &stim, &name, seed)
        .map_err(|f| f.to_string())?;
    block.write_vcd(o, &report.inputs, vcd)?;
    Ok(SimOutcome {
        report,
        vcd: vcd.to_path_buf(),
    })
}

/// `shadecore synth`: Yosys cell counts, and the nextpnr UP5K Fmax when `pnr` and
/// nextpnr-ice40 is installed (`None` otherwise).
pub fn synth_block(
    block: &dyn Entry,
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
    block: &dyn Entry,
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
            .simulate_on(o, rows, pipeline::engine::Sim::Verilator)
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

/// The rows every generic test of a block drives: `n` items of its seeded stimulus, then its
/// edge rows.
pub fn test_rows(
    block: &dyn Entry,
    o: &Options,
    n: usize,
    seed: u64,
) -> Result<Vec<Vec<u64>>, String> {
    let mut rows = block.stimulus(o, n, seed)?.rows;
    rows.extend(block.edge_rows(o, seed)?);
    Ok(rows)
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

/// The mutation check of a block's export: on `rows` under Icarus, the unmodified Verilog
/// equals the rust-hdl simulation, and every one of `mutants` differs from it somewhere
/// (panics otherwise, naming the mutant). Prints where each was caught.
pub fn assert_mutants_caught(
    block: &dyn Entry,
    rows: &[Vec<u64>],
    mutants: &[crate::verilog::Mutant],
) {
    use crate::verilog::{differential_rows, DiffError, Simulator};
    let o = Options::new();
    let good = block.verilog(&o).expect("export");
    let expected = block.simulate(&o, rows).expect("rust-hdl simulation");
    let run = |v: &str, tag: &str| {
        let m = block.module_name();
        differential_rows(
            v,
            &m,
            block.ports(),
            rows,
            &expected,
            Simulator::Icarus,
            tag,
        )
    };
    run(&good, &format!("mutant-control-{}", block.name()))
        .unwrap_or_else(|e| panic!("control: {e}"));
    for m in mutants {
        match run(&m.apply(&good), &format!("mutant-{}", block.name())) {
            Err(DiffError::Mismatch(d)) => println!("caught mutant [{}]: {d}", m.what),
            Err(DiffError::Tool(e)) => panic!("mutant [{}] did not run: {e}", m.what),
            Ok(_) => panic!(
                "mutant [{}] was NOT caught by the differential test",
                m.what
            ),
        }
    }
}

/// The twin catches a wrong rounding: `block` (built with `o`) runs its test rows (`n` items,
/// seeded by `name`) under Icarus; the unmodified Verilog must equal the twin's outputs every
/// clock, and each of `mutants` (typically a rounding constant moved by a quarter LSB) must
/// differ from them somewhere. Panics otherwise; prints where each was caught.
pub fn assert_mutants_caught_by_twin(
    block: &str,
    o: &Options,
    n: usize,
    mutants: &[crate::verilog::Mutant],
) {
    use crate::verilog::{differential_rows, DiffError, Simulator};
    let b = find(block).unwrap();
    let name = format!("quarter-lsb-{block}");
    let seed = golden::seed::seed_for(&name);
    let rows = test_rows(b, o, n, seed).unwrap();
    let twin = b.twin_rows(o, &rows).unwrap();
    let v = b.verilog(o).unwrap();
    let run = |text: &str, tag: &str| {
        differential_rows(
            text,
            &b.module_name(),
            b.ports(),
            &rows,
            &twin,
            Simulator::Icarus,
            tag,
        )
    };
    run(&v, &format!("{name}-control")).unwrap_or_else(|e| panic!("{block} control: {e}"));
    for m in mutants {
        match run(&m.apply(&v), &name) {
            Err(DiffError::Mismatch(d)) => println!("{block}: caught [{}]: {d}", m.what),
            Err(DiffError::Tool(e)) => panic!("{block} [{}] did not run: {e}", m.what),
            Ok(_) => panic!(
                "{block} [{}] was NOT caught by the twin (seed {seed})",
                m.what
            ),
        }
    }
}
