//! Cycle-by-cycle bench of the four-triangle address block (`rtl::four_triangle`) against its
//! cycle-accurate golden model (`golden::four_triangle::FourTriangleModel`), on the shared
//! harness. As for the address block, the model decides in which clock each parent is loaded
//! (its `ready`), and predicts every output port exactly; [`run_reactive`] lets the RTL's own
//! `ready` pace the loads instead (what `raster --address four-triangle` and the renderer do).

use crate::harness::{CheckSpec, Compare, Expected, Failure, Report};
use crate::normalizer::seeded_runner;
use crate::registry::{self, Bench, Twin};
use golden::address_block::AddressOutputs;
use golden::four_triangle::{FourOutputs, FourTriangleModel, FourTriangleSetup};
use golden::types::ScreenTriangle;
use proptest::strategy::{Strategy, ValueTree};
use rtl::four_triangle::FourTriangle;
use rtl::registry::NoParams;
use rtl::sim::Model as _;
use std::io::Write;

/// Output ports: `ready`, then eight per lane.
pub const OUTPUTS: usize = 1 + 4 * 8;

pub use pipeline::subdivision::{row_setup, setup_row, SETUP_ROW};

/// The block's input row: `load` with a parent's set-up (or idle), then `hold`.
pub fn four_row(load: Option<&FourTriangleSetup>, hold: bool) -> Vec<u64> {
    let mut row = setup_row(load);
    row.push(hold as u64);
    row
}

/// Index of `hold` in [`four_row`].
pub const HOLD_AT: usize = SETUP_ROW;

/// The output row the model predicts.
pub fn outputs_row(o: &FourOutputs) -> Vec<u64> {
    let mut row = vec![o.ready as u64];
    for l in &o.lanes {
        row.extend([
            l.valid as u64,
            l.x as u64,
            l.y as u64,
            l.step as u64,
            l.line_start as u64,
            l.row_start as u64,
            l.carry as u64,
            l.done as u64,
        ]);
    }
    row
}

/// An output row read back as the model's struct.
pub fn row_outputs(r: &[u64]) -> FourOutputs {
    FourOutputs {
        ready: r[0] != 0,
        lanes: std::array::from_fn(|k| {
            let b = 1 + 8 * k;
            AddressOutputs {
                ready: r[0] != 0,
                valid: r[b] != 0,
                x: r[b + 1] as u32,
                y: r[b + 2] as u32,
                step: r[b + 3] as u8,
                line_start: r[b + 4] != 0,
                row_start: r[b + 5] != 0,
                carry: r[b + 6] != 0,
                done: r[b + 7] != 0,
            }
        }),
    }
}

/// Input rows and the model's outputs of walking `setups` back to back (each loaded in the
/// first clock the model is ready), up to the clock in which every lane has shown its last
/// `done`.
pub fn stimulus(setups: &[FourTriangleSetup]) -> (Vec<Vec<u64>>, Vec<FourOutputs>) {
    golden::four_triangle::schedule(setups, 0)
        .into_iter()
        .map(|(o, load)| (four_row(load.map(|k| &setups[k]), false), o))
        .unzip()
}

/// Run the RTL on the model's stimulus, every output port compared exactly every clock.
pub fn check(
    name: &str,
    seed: u64,
    setups: &[FourTriangleSetup],
) -> Result<(Report, Vec<FourOutputs>), Box<Failure>> {
    let (rows, expected) = stimulus(setups);
    let spec = CheckSpec {
        name: name.into(),
        seed,
        compare: vec![Compare::Exact; OUTPUTS],
    };
    let expected: Vec<Vec<Expected>> = expected
        .iter()
        .map(|o| outputs_row(o).into_iter().map(Expected::Word).collect())
        .collect();
    let report = crate::harness::run_rows(FourTriangle::default, &spec, &rows, &expected)
        .map_err(Box::new)?;
    let outs = report.outputs.iter().map(|r| row_outputs(r)).collect();
    Ok((report, outs))
}

/// Walk `setups` through the RTL with its own `ready` pacing the loads (no model); stops once
/// every lane has shown its last `done`, or with an error after `max_clocks`.
pub fn run_reactive(
    setups: &[FourTriangleSetup],
    max_clocks: usize,
    vcd: Option<Box<dyn Write>>,
) -> Result<Vec<FourOutputs>, String> {
    run_reactive_held(setups, max_clocks, vcd, |_| false).map(|(_, o)| o)
}

/// [`run_reactive`] on a simulator of the caller's choice (`pipeline::engine::model`).
pub fn run_reactive_on(
    sim: pipeline::engine::Sim,
    setups: &[FourTriangleSetup],
    max_clocks: usize,
) -> Result<Vec<FourOutputs>, String> {
    let mut m = pipeline::engine::model::<FourTriangle>(&Default::default(), sim)?;
    run_reactive_model(m.as_mut(), setups, max_clocks, |_| false).map(|(_, o)| o)
}

/// [`run_reactive`] with `hold(clock)` on the stall input: the input rows and the outputs.
pub fn run_reactive_held(
    setups: &[FourTriangleSetup],
    max_clocks: usize,
    vcd: Option<Box<dyn Write>>,
    hold: impl FnMut(usize) -> bool,
) -> Result<(Vec<Vec<u64>>, Vec<FourOutputs>), String> {
    let mut s = rtl::sim::RustHdlModel::new(FourTriangle::default())?;
    if let Some(w) = vcd {
        s.start_vcd(w)?;
    }
    run_reactive_model(&mut s, setups, max_clocks, hold)
}

/// [`run_reactive_held`] on any simulated four-triangle block (`ready` its output 0).
pub fn run_reactive_model(
    s: &mut dyn rtl::sim::Model,
    setups: &[FourTriangleSetup],
    max_clocks: usize,
    mut hold: impl FnMut(usize) -> bool,
) -> Result<(Vec<Vec<u64>>, Vec<FourOutputs>), String> {
    pipeline::stream::first_output_is(s, "ready")?;
    let (mut out, mut rows) = (Vec::new(), Vec::new());
    let mut row = vec![0u64; OUTPUTS];
    let (mut next, mut dones) = (0, [0usize; 4]);
    while dones.iter().any(|&d| d < setups.len()) {
        if out.len() >= max_clocks {
            return Err(format!("not every lane done after {max_clocks} clocks"));
        }
        let load = (s.peek(0) != 0 && next < setups.len()).then(|| &setups[next]);
        next += load.is_some() as usize;
        let input = four_row(load, hold(out.len()));
        s.step(&input, &mut row)?;
        rows.push(input);
        let o = row_outputs(&row);
        for (d, l) in dones.iter_mut().zip(&o.lanes) {
            *d += l.done as usize;
        }
        out.push(o);
    }
    s.stop_vcd();
    Ok((rows, out))
}

/// `n` seeded random parents from the address block's triangle families
/// ([`crate::address_block::triangle_strategy`]: small, medium, axis-aligned, one-pixel,
/// degenerate, slivers up to 4095).
pub fn random_triangles(seed: u64, n: usize) -> Vec<ScreenTriangle> {
    let mut r = seeded_runner(seed);
    let st = crate::address_block::triangle_strategy();
    (0..n)
        .map(|_| ScreenTriangle::from_points(st.new_tree(&mut r).expect("no rejection").current()))
        .collect()
}

/// Row adapter of the cycle model (written independently of the RTL:
/// golden/src/four_triangle.rs).
struct FourRows(FourTriangleModel);

impl Twin for FourRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[HOLD_AT] != 0;
        let o = outputs_row(&self.0.outputs_held(hold));
        self.0.clock_held(row_setup(r).as_ref(), hold);
        o
    }
}

impl Bench for FourTriangle {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> registry::Stimulus {
        let setups: Vec<FourTriangleSetup> = random_triangles(seed, n)
            .iter()
            .map(FourTriangleSetup::new)
            .collect();
        let (rows, expected) = stimulus(&setups);
        registry::Stimulus {
            rows,
            expected: expected
                .iter()
                .map(|o| outputs_row(o).into_iter().map(Expected::Word).collect())
                .collect(),
            compare: vec![Compare::Exact; OUTPUTS],
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(FourRows(FourTriangleModel::new()))
    }
    /// Parents presented in half the clocks (taken when `ready`), `hold` in a quarter.
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let setups: Vec<FourTriangleSetup> = random_triangles(seed ^ 0x4e1d, 12)
            .iter()
            .map(FourTriangleSetup::new)
            .collect();
        held_edge_rows(seed, 1500, |k, hold| {
            four_row(k.map(|k| &setups[k % setups.len()]), hold)
        })
    }
}

/// `n` rows for a twin comparison under stalls: in half the clocks a load of item `k` (the
/// next one each time; the block ignores it unless `ready`), `hold` in a quarter.
pub fn held_edge_rows(
    seed: u64,
    n: usize,
    mut row: impl FnMut(Option<usize>, bool) -> Vec<u64>,
) -> Vec<Vec<u64>> {
    let mut r = seeded_runner(seed ^ 0x401d);
    let mut next = 0;
    (0..n)
        .map(|_| {
            let v = (0u8..8).new_tree(&mut r).expect("no rejection").current();
            let load = (v & 1 == 0).then(|| {
                next += 1;
                next - 1
            });
            row(load, v >> 1 == 3)
        })
        .collect()
}
