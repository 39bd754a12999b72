//! Cycle-by-cycle bench of the address block (`rtl::address_block`) against its cycle-accurate
//! golden model (`golden::address_block`), on the shared harness (`crate::harness`).
//!
//! Stimulus: a list of triangles. The golden model decides in which clock each set-up is
//! loaded (the first clock where its `ready` is high); those loads become the input rows, and
//! the model's outputs the exact expectation of every output port (including `ready`, so an RTL
//! that is not ready when the model is fails at that clock). [`run_reactive`] instead lets the
//! RTL's own `ready` pace the loads (what the `raster` command and the renderer do).

use crate::harness::{CheckSpec, Compare, Expected, Failure, Report};
use crate::normalizer::seeded_runner;
use crate::registry::{self, Bench, Twin};
use golden::address_block::{AddressBlockModel, AddressOutputs, AddressSetup};
use golden::intensity_interpolator::{additions, interpolate};
use golden::raster::walk;
use golden::types::{Plane, ScreenTriangle};
use pipeline::gouraud::{row_setup, TriangleJob};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::address_block::AddressBlock;
use rtl::registry::NoParams;
use rtl::sim::Model as _;
use std::io::Write;

pub use pipeline::gouraud::setup_row;

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

/// [`stimulus`] with `hold(clock)` driving the stall input in every clock.
pub fn stimulus_held(setups: &[AddressSetup], mut hold: impl FnMut(usize) -> bool) -> ModelRun {
    let mut m = AddressBlockModel::new();
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
    let mut s = rtl::sim::RustHdlModel::new(AddressBlock::default())?;
    if let Some(w) = vcd {
        s.start_vcd(w)?;
    }
    run_reactive_model(&mut s, setups, max_clocks)
}

/// [`run_reactive`] on a simulator of the caller's choice (`pipeline::engine::model`).
pub fn run_reactive_on(
    sim: pipeline::engine::Sim,
    setups: &[AddressSetup],
    max_clocks: usize,
) -> Result<Vec<AddressOutputs>, String> {
    let mut m = pipeline::engine::model::<AddressBlock>(&Default::default(), sim)?;
    run_reactive_model(m.as_mut(), setups, max_clocks)
}

/// [`run_reactive`] on any simulated address block (`ready` its output 0).
pub fn run_reactive_model(
    s: &mut dyn rtl::sim::Model,
    setups: &[AddressSetup],
    max_clocks: usize,
) -> Result<Vec<AddressOutputs>, String> {
    pipeline::stream::first_output_is(s, "ready")?;
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

/// The golden value of every pixel of a triangle list's walks, in stream order: per channel
/// f64 intensity (no bias) and the number of additions that reach it.
pub type GoldenPixel = ([f64; 3], u32);

/// `n` seeded random triangles ([`triangle_strategy`]) with random vertex intensities
/// (−40..320 per channel, so both saturation ends are reached): the raster jobs, and the golden
/// f64 value and addition count of every pixel in stream order. The same seed gives the same
/// triangles for the address block, the BVI and the pipe.
pub fn triangle_jobs(seed: u64, n: usize) -> (Vec<TriangleJob>, Vec<GoldenPixel>) {
    let mut r = seeded_runner(seed);
    let st = (
        triangle_strategy(),
        prop::array::uniform3(prop::array::uniform3(-40.0..320.0f64)),
    );
    let mut jobs = Vec::with_capacity(n);
    let mut golden = Vec::new();
    for _ in 0..n {
        let (p, v) = st.new_tree(&mut r).expect("no rejection").current();
        let t = ScreenTriangle::from_points(p);
        let planes = channel_planes(&t, &v);
        let w = walk(&t);
        let per: [Vec<f64>; 3] = std::array::from_fn(|c| interpolate(&w, &planes[c]));
        for (k, adds) in additions(&w).into_iter().enumerate() {
            golden.push(([per[0][k], per[1][k], per[2][k]], adds));
        }
        jobs.push(TriangleJob::new(&t, &planes));
    }
    (jobs, golden)
}

/// The three colour channels' planes through the vertex intensities `v[vertex][channel]`; a
/// zero-area triangle (no plane) gets flat zero planes — the hardware still walks it, with no
/// pixel.
pub fn channel_planes(t: &ScreenTriangle, v: &[[f64; 3]; 3]) -> [Plane; 3] {
    let zero = Plane {
        a: 0.0,
        b: 0.0,
        c: 0.0,
    };
    std::array::from_fn(|c| t.scalar_plane([v[0][c], v[1][c], v[2][c]]).unwrap_or(zero))
}

/// Rows, expectations and comparisons of a triangle block's run.
pub type TriangleRun = (Vec<Vec<u64>>, Vec<Vec<Expected>>, Vec<Compare>);

/// A [`TriangleRun`] as a registry [`Stimulus`](crate::registry::Stimulus).
pub fn triangle_run((rows, expected, compare): TriangleRun) -> registry::Stimulus {
    registry::Stimulus {
        rows,
        expected,
        compare,
    }
}

/// Address block: the cycle model paces the loads and predicts every port exactly.
pub fn address_run(jobs: &[TriangleJob]) -> TriangleRun {
    address_run_held(jobs, &mut crate::stall::StallPattern::never())
}

/// [`address_run`] with `hold` driven by `stalls` (the registry's stimulus stalls a quarter
/// of the clocks, and in long stretches).
pub fn address_run_held(
    jobs: &[TriangleJob],
    stalls: &mut crate::stall::StallPattern,
) -> TriangleRun {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let st = stimulus_held(&setups, |_| stalls.next_stalled());
    let expected = st
        .expected
        .iter()
        .map(|o| outputs_row(o).into_iter().map(Expected::Word).collect())
        .collect();
    (st.rows, expected, vec![Compare::Exact; 9])
}

/// Row adapter of the cycle model [`AddressBlockModel`] (written independently of the RTL:
/// golden/src/address_block.rs).
struct AddressRows(AddressBlockModel);

impl Twin for AddressRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[HOLD_AT] != 0;
        let o = outputs_row(&self.0.outputs_held(hold));
        self.0.clock_held(row_setup(r).as_ref(), hold);
        o
    }
}

impl Bench for AddressBlock {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> registry::Stimulus {
        let (jobs, _) = triangle_jobs(seed, n);
        let mut stalls = crate::stall::StallPattern::new(seed, 0.25);
        triangle_run(address_run_held(&jobs, &mut stalls))
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(AddressRows(AddressBlockModel::new()))
    }
}
