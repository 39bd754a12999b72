//! Cycle-by-cycle bench of the address block (`rtl::address_block`) against its cycle-accurate
//! golden model (`golden::address_block`), on the shared harness (`crate::harness`).
//!
//! Stimulus: a list of triangles. The golden model decides in which clock each set-up is
//! loaded (the first clock where its `ready` is high); those loads become the input rows, and
//! the model's outputs the exact expectation of every output port (including `ready`, so an RTL
//! that is not ready when the model is fails at that clock). [`run_reactive`] instead lets the
//! RTL's own `ready` pace the loads (what the `raster` command and the renderer do).

use crate::harness::{CheckSpec, Compare, Expected, Failure, Report, Stepper};
use crate::impl_dut;
use golden::address_block::{AddressBlockModel, AddressOutputs, AddressSetup, EdgeSetup};
use proptest::prelude::*;
use rtl::address_block::AddressBlock;
use std::io::Write;

impl_dut!(AddressBlock, clock: clock,
    inputs: [load, w_b0, w_e0, w_f, w_r, w_d, a_b0, a_e0, a_f, a_r, a_d,
             t_b0, t_e0, t_f, t_r, t_d, y_top, rows, y_switch, dir_neg],
    outputs: [ready, valid, x, y, step, line_start, row_start, carry, done]);

fn edge_words(e: &EdgeSetup) -> [u64; 5] {
    [
        e.b0 as u64,
        e.e0 as u64,
        e.f_word() as u64,
        e.r as u64,
        e.d as u64,
    ]
}

/// The input row of one clock: `load` and the set-up words (all zero without a load).
pub fn setup_row(s: Option<&AddressSetup>) -> Vec<u64> {
    let z = AddressSetup::default();
    let (load, s) = (s.is_some() as u64, s.unwrap_or(&z));
    let mut row = vec![load];
    for e in [&s.w, &s.a, &s.t] {
        row.extend(edge_words(e));
    }
    row.extend([
        s.y_top as u64,
        s.rows as u64,
        s.y_switch as u64,
        s.dir_neg as u64,
    ]);
    row
}

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
pub struct Stimulus {
    pub rows: Vec<Vec<u64>>,
    pub expected: Vec<AddressOutputs>,
    /// Clock in which each triangle is loaded.
    pub loads: Vec<usize>,
}

/// The model's run of `setups`, each loaded in the first clock its `ready` is high, up to and
/// including the clock showing the last triangle's `done`.
pub fn stimulus(setups: &[AddressSetup]) -> Stimulus {
    let mut m = AddressBlockModel::new();
    let mut st = Stimulus {
        rows: Vec::new(),
        expected: Vec::new(),
        loads: Vec::new(),
    };
    let (mut next, mut dones) = (0, 0);
    while dones < setups.len() {
        let o = m.outputs();
        let load = (o.ready && next < setups.len()).then(|| &setups[next]);
        if load.is_some() {
            st.loads.push(st.rows.len());
            next += 1;
        }
        dones += o.done as usize;
        st.rows.push(setup_row(load));
        st.expected.push(o);
        m.clock(load);
    }
    st
}

/// The model's outputs only (see [`stimulus`]).
pub fn run_model(setups: &[AddressSetup]) -> Vec<AddressOutputs> {
    stimulus(setups).expected
}

/// Run the RTL on the model's stimulus and compare every output port every clock, exactly.
/// Returns the harness report and the RTL's outputs per clock.
pub fn check(
    name: &str,
    seed: u64,
    setups: &[AddressSetup],
) -> Result<(Report, Vec<AddressOutputs>), Box<Failure>> {
    let st = stimulus(setups);
    let spec = CheckSpec {
        name: name.into(),
        seed,
        compare: vec![Compare::Exact; 9],
    };
    let expected: Vec<Vec<Expected>> = st
        .expected
        .iter()
        .map(|o| outputs_row(o).into_iter().map(Expected::Word).collect())
        .collect();
    let report = crate::harness::run_rows(AddressBlock::default, &spec, &st.rows, &expected)
        .map_err(Box::new)?;
    let outs = report.outputs.iter().map(|r| row_outputs(r)).collect();
    Ok((report, outs))
}

/// Walk `setups` through the RTL with its own `ready` pacing the loads (no model involved);
/// stops after the last triangle's `done` (inclusive) or with an error after `max_clocks`.
/// With `vcd`, every clock is traced.
pub fn run_reactive(
    setups: &[AddressSetup],
    max_clocks: usize,
    vcd: Option<Box<dyn Write>>,
) -> Result<Vec<AddressOutputs>, String> {
    let mut s = Stepper::new(AddressBlock::default())?;
    if let Some(w) = vcd {
        s.start_vcd(w);
    }
    let mut out = Vec::new();
    let mut row = vec![0u64; 9];
    let (mut next, mut dones) = (0, 0);
    while dones < setups.len() {
        if out.len() >= max_clocks {
            return Err(format!("no `done` after {max_clocks} clocks"));
        }
        // `ready` is a register output: its value for this clock is already settled.
        let load = (s.dut().ready.val() && next < setups.len()).then(|| &setups[next]);
        next += load.is_some() as usize;
        s.step(&setup_row(load), &mut row)?;
        let o = row_outputs(&row);
        dones += o.done as usize;
        out.push(o);
    }
    s.stop_vcd();
    Ok(out)
}

/// Random triangles from several families: general small ones, axis-aligned edges, one-pixel
/// ones, degenerate ones, long slivers up to the full 4095 extent.
pub fn triangle_strategy() -> impl Strategy<Value = [(i32, i32); 3]> {
    let pt = |max: i32| (0..=max, 0..=max);
    prop_oneof![
        // General, small box.
        4 => [pt(40), pt(40), pt(40)],
        // General, medium box.
        2 => [pt(200), pt(200), pt(200)],
        // Horizontal and vertical edges.
        1 => (pt(100), 1..60i32, 1..60i32, any::<bool>()).prop_map(|((x, y), w, h, flip)| {
            if flip { [(x, y), (x + w, y), (x, y + h)] } else { [(x + w, y), (x + w, y + h), (x, y + h)] }
        }),
        // Tiny: one pixel or nothing.
        1 => (pt(4093), 0..3usize).prop_map(|((x, y), k)| {
            [[(x, y), (x + 1, y), (x, y + 1)], [(x, y), (x + 1, y + 1), (x, y + 1)], [(x + 1, y), (x + 1, y + 1), (x, y + 1)]][k]
        }),
        // Degenerate: collinear.
        1 => (pt(2000), -40..40i32, -40..40i32, 0..4i32, 0..4i32).prop_map(|((x, y), dx, dy, k, m)| {
            let p = |t: i32| ((x + 2000 + t * dx).clamp(0, 4095), (y + t * dy).clamp(0, 4095));
            [p(0), p(k), p(k + m)]
        }),
        // Long slivers spanning up to the full address range.
        1 => (pt(4095), pt(4095), -3..=3i32, -3..=3i32).prop_map(|(a, b, ox, oy)| {
            [a, b, ((b.0 + ox).clamp(0, 4095), (b.1 + oy).clamp(0, 4095))]
        }),
    ]
}
