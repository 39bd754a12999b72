//! The bench side of the block list: every block of `flow::blocks::BLOCKS` with its stimulus,
//! golden expectations and bit-exact twin. `shadecore-sim` (with its VCD) and the generic tests
//! (twin every clock, golden every clock, Yosys, Icarus, Verilator differential, SB_MAC16
//! count) are driven from [`BLOCKS`].
//!
//! A block implements [`rtl::core::registry::RtlBlock`] in its `rtl/src` file (name, parameters,
//! latency, multipliers, build) and [`Bench`] in its `testbenches/src` file (stimulus with
//! golden expectations, its bit-exact twin); then one line in [`flow::with_blocks!`] lists it.

use std::path::Path;

use flow::blocks::{Block, Registered};
use flow::engine::Sim;
use rtl::core::registry::{BlockParams, Options, RtlBlock};

use crate::harness::{self, CheckSpec, Compare, Expected, Failure, Report};

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
/// (sampled before the rising edge, as `rtl::core::sim::Stepper::step` samples) out. It starts
/// from the reset state (every register 0, as rust-hdl's and the exported Verilog's).
pub trait Twin {
    fn step(&mut self, inputs: &[u64]) -> Vec<u64>;
}

/// The bench side of a block: implemented once, in its `testbenches/src` file.
pub trait Bench: RtlBlock {
    /// What one stimulus item is ("vectors", "pixels", "triangles").
    const ITEMS: &'static str;
    /// Items `shadecore-sim` simulates by default.
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

/// A registered block with its bench side, object-safe: what the generic tests call. The
/// product side ([`Block`]: ports, Verilog, models, synthesis) is `flow::blocks`'.
pub trait Entry: Block {
    fn items(&self) -> &'static str;
    fn default_items(&self) -> usize;
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
    /// Check `outputs`, recorded from `rows` on any simulator, against the twin every port
    /// every clock without simulating again (a failure replays `rows` under rust-hdl into the
    /// failure's VCD).
    fn check_twin(
        &self,
        o: &Options,
        rows: &[Vec<u64>],
        outputs: &[Vec<u64>],
        name: &str,
        seed: u64,
    ) -> Checked;
    /// The twin's output rows for `rows` (what the hardware must show, clock by clock).
    fn twin_rows(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String>;
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
        sim: Sim,
        progress: &mut dyn FnMut(u64),
    ) -> Result<crate::harness::StreamReport, String>;
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
    fn items(&self) -> &'static str {
        B::ITEMS
    }
    fn default_items(&self) -> usize {
        B::DEFAULT_ITEMS
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
    fn check_twin(
        &self,
        o: &Options,
        rows: &[Vec<u64>],
        outputs: &[Vec<u64>],
        name: &str,
        seed: u64,
    ) -> Checked {
        let p = B::Params::from_options(o).map_err(|e| failure(name, seed, e))?;
        let expected: Vec<Vec<Expected>> = self
            .twin_rows(o, rows)
            .map_err(|e| failure(name, seed, e))?
            .into_iter()
            .map(|r| r.into_iter().map(Expected::Word).collect())
            .collect();
        let spec = CheckSpec {
            name: name.into(),
            seed,
            compare: vec![Compare::Exact; self.ports().1.len()],
        };
        harness::check_recorded(|| B::build(&p), &spec, rows, outputs, &expected).map_err(Box::new)
    }
    fn twin_rows(&self, o: &Options, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String> {
        let mut twin = B::twin(&B::Params::from_options(o)?);
        Ok(rows.iter().map(|r| twin.step(r)).collect())
    }
    fn sim_stream(
        &self,
        o: &Options,
        n: usize,
        seed: u64,
        vcd: Option<&Path>,
        sim: Sim,
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
        let mut model = flow::engine::model::<B>(&p, sim)?;
        let run = |model: &mut dyn rtl::core::sim::Model| {
            harness::run_stream_on(model, &spec, next, &mut |row| twin.step(row), progress)
        };
        match vcd {
            None => run(model.as_mut()).map_err(|f| f.to_string()),
            // Written whole (`golden::files`): a failing check keeps its VCD, a write error
            // (a full disk) leaves none.
            Some(path) => golden::files::write_through(path, |temp| {
                let f = std::fs::File::create(temp)
                    .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
                model.start_vcd(Box::new(std::io::BufWriter::new(f)))?;
                let checked = run(model.as_mut());
                model
                    .stop_vcd()
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                Ok(checked)
            })?
            .map_err(|mut f| {
                f.vcd = Some(path.to_path_buf());
                f.to_string()
            }),
        }
    }
}

macro_rules! entry_list {
    ($($t:ty),* $(,)?) => {
        &[$(&flow::blocks::block::<$t>()),*]
    };
}

/// Every exportable block with its bench: `flow::blocks`' one list ([`flow::with_blocks!`]).
/// Adding a block: its `rtl/src` file (with `impl RtlBlock`), its `testbenches/src` file (with
/// `impl Bench`), and one line in that list.
pub static BLOCKS: &[&dyn Entry] = flow::with_blocks!(entry_list);

/// (pipeline top, the stream top that wraps it whole): the pipeline's Verilog is a submodule of
/// the stream's, built from the same options.
pub const INSIDE_STREAM: [(&str, &str); 8] = [
    ("gouraud-raster", "gouraud-stream"),
    ("subdivision-raster", "subdivision-stream"),
    ("pixel-pipeline", "pixel-stream"),
    ("angular-pipeline", "angular-stream"),
    ("fast-pipeline", "fast-stream"),
    ("cubic-pipeline", "cubic-stream"),
    ("quadric-unit", "quadric-stream"),
    ("textured-pipeline", "textured-stream"),
];

/// The stream top that wraps `block` whole (see [`INSIDE_STREAM`]) and lists `o` among its own
/// test sets: a test that runs every block in every test set runs `block` with `o` inside it.
pub fn wrapped_by_tested_stream(block: &str, o: &Options) -> Option<&'static str> {
    let (_, outer) = INSIDE_STREAM.iter().find(|(inner, _)| *inner == block)?;
    find(outer).ok()?.test_sets().contains(o).then_some(*outer)
}

/// The entry named `name` (the same lookup and error as [`flow::blocks::find`]: both lists are
/// made from one).
pub fn find(name: &str) -> Result<&'static dyn Entry, String> {
    let b = flow::blocks::find(name)?;
    Ok(BLOCKS
        .iter()
        .copied()
        .find(|e| e.name() == b.name())
        .expect("the bench list is the block list"))
}

/// Outcome of [`sim_to_vcd`].
pub struct SimOutcome {
    pub report: Report,
    pub vcd: std::path::PathBuf,
}

/// `shadecore-sim`: `n` seeded items through `block`, checked every clock against its twin
/// (exactly) and the golden model (within the format's bound), then replayed into a VCD at
/// `vcd`. A check failure is returned as the error (its own VCD is under `target/sims/`).
pub fn sim_to_vcd(
    block: &dyn Entry,
    o: &Options,
    n: usize,
    seed: u64,
    vcd: &Path,
) -> Result<SimOutcome, String> {
    sim_stimulus_to_vcd(block, o, &block.stimulus(o, n, seed)?, seed, vcd)
}

/// [`sim_to_vcd`] on a stimulus of the caller's (e.g. cut short after its first valid clock).
pub fn sim_stimulus_to_vcd(
    block: &dyn Entry,
    o: &Options,
    stim: &Stimulus,
    seed: u64,
    vcd: &Path,
) -> Result<SimOutcome, String> {
    let name = format!("sim-{}", block.name());
    // One rust-hdl run checked two ways: against the twin, and its recorded outputs against
    // the golden expectations.
    let twin = block
        .run_twin(o, &stim.rows, &format!("{name}-twin"), seed)
        .map_err(|f| f.to_string())?;
    let report = block
        .check_golden(o, stim, &twin.outputs, &name, seed)
        .map_err(|f| f.to_string())?;
    block.write_vcd(o, &report.inputs, vcd)?;
    Ok(SimOutcome {
        report,
        vcd: vcd.to_path_buf(),
    })
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

/// The mutation check of a block's export: on `rows` under Icarus, the unmodified Verilog
/// equals the rust-hdl simulation, and every one of `mutants` differs from it somewhere
/// (panics otherwise, naming the mutant). Prints where each was caught.
pub fn assert_mutants_caught(
    block: &dyn Entry,
    rows: &[Vec<u64>],
    mutants: &[flow::verilog::Mutant],
) {
    let o = Options::new();
    let good = block.verilog(&o).expect("export");
    let expected = block.simulate(&o, rows).expect("rust-hdl simulation");
    let tag = format!("mutant-{}", block.name());
    for (what, caught) in icarus_mutant_runs(block, &good, rows, &expected, mutants, &tag) {
        match caught {
            Ok(d) => println!("caught mutant [{what}]: {d}"),
            Err(e) => panic!("{e}"),
        }
    }
}

/// The unmodified Verilog `good` of `block`, then each of `mutants` applied to it, under
/// Icarus on `rows` against `expected`, two runs at a time (each an Icarus process in its own
/// folder). Panics when the unmodified Verilog differs or fails to run; returns, per mutant in
/// order, where it was caught, or why it was not.
fn icarus_mutant_runs(
    block: &dyn Entry,
    good: &str,
    rows: &[Vec<u64>],
    expected: &[Vec<u64>],
    mutants: &[flow::verilog::Mutant],
    tag: &str,
) -> Vec<(String, Result<String, String>)> {
    use flow::verilog::{differential_rows, DiffError, Simulator};
    let run = |v: &str, tag: &str| {
        differential_rows(
            v,
            &block.module_name(),
            block.ports(),
            rows,
            expected,
            Simulator::Icarus,
            tag,
        )
    };
    // Job 0 is the control: the unmodified Verilog.
    let texts: Vec<String> = std::iter::once(good.to_string())
        .chain(mutants.iter().map(|m| m.apply(good)))
        .collect();
    let results: Vec<std::sync::Mutex<Option<Result<_, DiffError>>>> =
        texts.iter().map(|_| std::sync::Mutex::new(None)).collect();
    flow::tools::two_at_a_time(texts.iter().enumerate(), |(k, text)| {
        let t = if k == 0 {
            format!("{tag}-control")
        } else {
            tag.to_string()
        };
        *results[k].lock().unwrap() = Some(run(text, &t));
    });
    let mut results = results
        .into_iter()
        .map(|r| r.into_inner().unwrap().expect("every job ran"));
    match results.next().expect("the control ran") {
        Ok(_) => {}
        Err(e) => panic!("{} control: {e}", block.name()),
    }
    mutants
        .iter()
        .zip(results)
        .map(|(m, r)| {
            let caught = match r {
                Err(DiffError::Mismatch(d)) => Ok(d.to_string()),
                Err(DiffError::Tool(e)) => Err(format!("mutant [{}] did not run: {e}", m.what)),
                Ok(_) => Err(format!(
                    "mutant [{}] was NOT caught: its outputs equal the expected ones every clock",
                    m.what
                )),
            };
            (m.what.to_string(), caught)
        })
        .collect()
}

/// The twin catches a wrong rounding: `block` (built with `o`) runs its test rows (`n` items,
/// seeded by `name`) under Icarus; the unmodified Verilog must equal the twin's outputs every
/// clock, and each of `mutants` (typically a rounding constant moved by a quarter LSB) must
/// differ from them somewhere. Panics otherwise; prints where each was caught.
pub fn assert_mutants_caught_by_twin(
    block: &str,
    o: &Options,
    n: usize,
    mutants: &[flow::verilog::Mutant],
) {
    let b = find(block).unwrap();
    let name = format!("quarter-lsb-{block}");
    let seed = golden::seed::seed_for(&name);
    let rows = test_rows(b, o, n, seed).unwrap();
    let twin = b.twin_rows(o, &rows).unwrap();
    let v = b.verilog(o).unwrap();
    for (what, caught) in icarus_mutant_runs(b, &v, &rows, &twin, mutants, &name) {
        match caught {
            Ok(d) => println!("{block}: caught [{what}]: {d}"),
            Err(e) => panic!("{block}: {e} (seed {seed})"),
        }
    }
}
