//! The four-triangle block (`rtl::units::four_triangle`, SPEC §7) from the driver's side: its input and
//! output rows, the golden model's schedule, and the reactive walk (the block's `ready` paces
//! the loads; stops once every lane has shown its last `done`).

use golden::units::address_block::AddressOutputs;
use golden::units::four_triangle::{FourOutputs, FourTriangleModel, FourTriangleSetup};
use rtl::core::sim::Model as _;
use rtl::units::four_triangle::FourTriangle;
use std::io::Write;

/// Output ports: `ready`, then eight per lane.
pub const OUTPUTS: usize = 1 + 4 * 8;

pub use crate::subdivision::{row_setup, setup_row, SETUP_ROW};

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
    stimulus_on(FourTriangleModel::new(), setups)
}

/// [`stimulus`] from a given model (the integer or the sub-pixel block).
pub fn stimulus_on(
    model: FourTriangleModel,
    setups: &[FourTriangleSetup],
) -> (Vec<Vec<u64>>, Vec<FourOutputs>) {
    golden::units::four_triangle::schedule_on(model, setups, 0)
        .into_iter()
        .map(|(o, load)| (four_row(load.map(|k| &setups[k]), false), o))
        .unzip()
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

/// [`run_reactive`] on a simulator of the caller's choice (`flow::engine::model`).
pub fn run_reactive_on(
    sim: flow::engine::Sim,
    setups: &[FourTriangleSetup],
    max_clocks: usize,
) -> Result<Vec<FourOutputs>, String> {
    let mut m = flow::engine::model::<FourTriangle>(&Default::default(), sim)?;
    run_reactive_model(m.as_mut(), setups, max_clocks, |_| false).map(|(_, o)| o)
}

/// [`run_reactive`] with `hold(clock)` on the stall input: the input rows and the outputs.
pub fn run_reactive_held(
    setups: &[FourTriangleSetup],
    max_clocks: usize,
    vcd: Option<Box<dyn Write>>,
    hold: impl FnMut(usize) -> bool,
) -> Result<(Vec<Vec<u64>>, Vec<FourOutputs>), String> {
    let mut s = rtl::core::sim::RustHdlModel::new(FourTriangle::default())?;
    if let Some(w) = vcd {
        s.start_vcd(w)?;
    }
    run_reactive_model(&mut s, setups, max_clocks, hold)
}

/// [`run_reactive_held`] on any simulated four-triangle block (`ready` its output 0).
pub fn run_reactive_model(
    s: &mut dyn rtl::core::sim::Model,
    setups: &[FourTriangleSetup],
    max_clocks: usize,
    mut hold: impl FnMut(usize) -> bool,
) -> Result<(Vec<Vec<u64>>, Vec<FourOutputs>), String> {
    crate::axis::first_output_is(s, "ready")?;
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
    s.stop_vcd()?;
    Ok((rows, out))
}
