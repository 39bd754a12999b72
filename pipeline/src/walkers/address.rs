//! The address block (`rtl::units::address_block`, SPEC §5) from the driver's side: its input and
//! output rows, the golden model's schedule of a list of set-ups, and the reactive walk, in
//! which the block's own `ready` paces the loads (what `raster` and the renderer do).

use golden::units::address_block::{AddressBlockModel, AddressOutputs, AddressSetup};
use rtl::core::sim::Model as _;
use rtl::units::address_block::AddressBlock;
use std::io::Write;

pub use crate::gouraud::setup_row;

/// The address block's input row: `load` with a set-up (or idle), then `hold`.
pub fn address_row(load: Option<&AddressSetup>, hold: bool) -> Vec<u64> {
    let mut row = setup_row(load);
    row.push(hold as u64);
    row
}

/// Index of `hold` in [`address_row`].
pub const HOLD_AT: usize = 20;

/// The output row the model predicts (port order of the `impl_dut!` above).
pub fn outputs_row(o: &AddressOutputs) -> Vec<u64> {
    vec![
        o.ready as u64,
        o.valid as u64,
        o.x as u64,
        o.y as u64,
        o.step as u64,
        o.line_start as u64,
        o.row_start as u64,
        o.carry as u64,
        o.done as u64,
    ]
}

/// An output row read back as the model's struct.
pub fn row_outputs(r: &[u64]) -> AddressOutputs {
    AddressOutputs {
        ready: r[0] != 0,
        valid: r[1] != 0,
        x: r[2] as u32,
        y: r[3] as u32,
        step: r[4] as u8,
        line_start: r[5] != 0,
        row_start: r[6] != 0,
        carry: r[7] != 0,
        done: r[8] != 0,
    }
}

/// Input rows and predicted outputs of walking `setups` back to back.
pub struct ModelRun {
    pub rows: Vec<Vec<u64>>,
    pub expected: Vec<AddressOutputs>,
    /// Clock in which each triangle is loaded.
    pub loads: Vec<usize>,
}

/// The model's run of `setups`, each loaded in the first clock its `ready` is high, up to and
/// including the clock showing the last triangle's `done`.
pub fn stimulus(setups: &[AddressSetup]) -> ModelRun {
    stimulus_held(setups, |_| false)
}

/// [`stimulus`] on the sub-pixel block's model (`address-block-subpixel`, the address block
/// of `gouraud-raster` and `pixel-pipeline`; integer set-ups walk on it as on the integer one).
pub fn stimulus_subpixel(setups: &[AddressSetup]) -> ModelRun {
    stimulus_held_on(AddressBlockModel::subpixel(), setups, |_| false)
}

/// [`stimulus`] with `hold(clock)` driving the stall input in every clock.
pub fn stimulus_held(setups: &[AddressSetup], hold: impl FnMut(usize) -> bool) -> ModelRun {
    stimulus_held_on(AddressBlockModel::new(), setups, hold)
}

/// [`stimulus_held`] on a given build of the model (integer or
/// [`AddressBlockModel::subpixel`]).
pub fn stimulus_held_on(
    mut m: AddressBlockModel,
    setups: &[AddressSetup],
    mut hold: impl FnMut(usize) -> bool,
) -> ModelRun {
    let mut st = ModelRun {
        rows: Vec::new(),
        expected: Vec::new(),
        loads: Vec::new(),
    };
    let (mut next, mut dones) = (0, 0);
    while dones < setups.len() {
        let held = hold(st.rows.len());
        let o = m.outputs_held(held);
        let load = (o.ready && next < setups.len()).then(|| &setups[next]);
        if load.is_some() {
            st.loads.push(st.rows.len());
            next += 1;
        }
        dones += o.done as usize;
        st.rows.push(address_row(load, held));
        st.expected.push(o);
        m.clock_held(load, held);
    }
    st
}

/// The model's outputs only (see [`stimulus`]).
pub fn run_model(setups: &[AddressSetup]) -> Vec<AddressOutputs> {
    stimulus(setups).expected
}

/// Walk `setups` through the RTL with its own `ready` pacing the loads (no model involved);
/// stops after the last triangle's `done` (inclusive) or with an error after `max_clocks`.
/// With `vcd`, every clock is traced.
pub fn run_reactive(
    setups: &[AddressSetup],
    max_clocks: usize,
    vcd: Option<Box<dyn Write>>,
) -> Result<Vec<AddressOutputs>, String> {
    let mut s = rtl::core::sim::RustHdlModel::new(AddressBlock::default())?;
    if let Some(w) = vcd {
        s.start_vcd(w)?;
    }
    run_reactive_model(&mut s, setups, max_clocks)
}

/// [`run_reactive`] on a simulator of the caller's choice (`flow::engine::model`).
pub fn run_reactive_on(
    sim: flow::engine::Sim,
    setups: &[AddressSetup],
    max_clocks: usize,
) -> Result<Vec<AddressOutputs>, String> {
    let mut m = flow::engine::model::<AddressBlock>(&Default::default(), sim)?;
    run_reactive_model(m.as_mut(), setups, max_clocks)
}

/// [`run_reactive`] on any simulated address block (`ready` its output 0).
pub fn run_reactive_model(
    s: &mut dyn rtl::core::sim::Model,
    setups: &[AddressSetup],
    max_clocks: usize,
) -> Result<Vec<AddressOutputs>, String> {
    crate::axis::first_output_is(s, "ready")?;
    let mut out = Vec::new();
    let mut row = vec![0u64; 9];
    let (mut next, mut dones) = (0, 0);
    while dones < setups.len() {
        if out.len() >= max_clocks {
            return Err(format!("no `done` after {max_clocks} clocks"));
        }
        // `ready` is a register output: its value for this clock is already settled.
        let load = (s.peek(0) != 0 && next < setups.len()).then(|| &setups[next]);
        next += load.is_some() as usize;
        s.step(&address_row(load, false), &mut row)?;
        let o = row_outputs(&row);
        dones += o.done as usize;
        out.push(o);
    }
    s.stop_vcd()?;
    Ok(out)
}
