//! Cycle-by-cycle bench of the four-triangle address block (`rtl::units::four_triangle`) against its
//! cycle-accurate golden model (`golden::units::four_triangle::FourTriangleModel`), on the shared
//! harness. As for the address block, the model decides in which clock each parent is loaded
//! (its `ready`), and predicts every output port exactly; [`run_reactive`] lets the RTL's own
//! `ready` pace the loads instead (what `raster --address four-triangle` and the renderer do).

use crate::harness::{CheckSpec, Compare, Expected, Failure, Report};
use crate::registry::{self, Bench, Twin};
use crate::units::address_block::subpixel_triangles;
use golden::testing::seeded_runner;
use golden::types::ScreenTriangle;
use golden::units::four_triangle::{FourOutputs, FourTriangleModel, FourTriangleSetup};
pub use pipeline::walkers::four_triangle::*;
use proptest::strategy::{Strategy, ValueTree};
use rtl::core::registry::NoParams;
use rtl::units::four_triangle::{FourTriangle, SubpixelFourTriangle};

/// Run the RTL on the model's stimulus, every output port compared exactly every clock.
pub fn check(
    name: &str,
    seed: u64,
    setups: &[FourTriangleSetup],
) -> Result<(Report, Vec<FourOutputs>), Box<Failure>> {
    check_on(
        FourTriangle::default,
        FourTriangleModel::new(),
        name,
        seed,
        setups,
    )
}

/// [`check`] for the sub-pixel build (`four-triangle-subpixel`, set-ups from
/// [`FourTriangleSetup::subpixel`] or integer ones).
pub fn check_subpixel(
    name: &str,
    seed: u64,
    setups: &[FourTriangleSetup],
) -> Result<(Report, Vec<FourOutputs>), Box<Failure>> {
    check_on(
        SubpixelFourTriangle::default,
        FourTriangleModel::subpixel(),
        name,
        seed,
        setups,
    )
}

fn check_on<B: rtl::core::sim::Dut>(
    build: fn() -> B,
    model: FourTriangleModel,
    name: &str,
    seed: u64,
    setups: &[FourTriangleSetup],
) -> Result<(Report, Vec<FourOutputs>), Box<Failure>> {
    let (rows, expected) = stimulus_on(model, setups);
    let spec = CheckSpec {
        name: name.into(),
        seed,
        compare: vec![Compare::Exact; OUTPUTS],
    };
    let report = crate::harness::run_rows(build, &spec, &rows, &expected_rows(&expected))
        .map_err(Box::new)?;
    let outs = report.outputs.iter().map(|r| row_outputs(r)).collect();
    Ok((report, outs))
}

/// `n` seeded random parents from the address block's triangle families
/// ([`crate::units::address_block::triangle_strategy`]: small, medium, axis-aligned, one-pixel,
/// degenerate, slivers up to 4095).
pub fn random_triangles(seed: u64, n: usize) -> Vec<ScreenTriangle> {
    let mut r = seeded_runner(seed);
    let st = crate::units::address_block::triangle_strategy();
    (0..n)
        .map(|_| ScreenTriangle::from_points(st.new_tree(&mut r).expect("no rejection").current()))
        .collect()
}

/// Row adapter of the cycle model (written independently of the RTL:
/// golden/src/units/four_triangle.rs).
struct FourRows(FourTriangleModel);

impl Twin for FourRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[HOLD_AT] != 0;
        let o = outputs_row(&self.0.outputs_held(hold));
        self.0.clock_held(row_setup(r).as_ref(), hold);
        o
    }
}

/// Every output port of every clock the model predicts, as exact expectations.
fn expected_rows(outputs: &[FourOutputs]) -> Vec<Vec<Expected>> {
    outputs
        .iter()
        .map(|o| outputs_row(o).into_iter().map(Expected::Word).collect())
        .collect()
}

/// The registry's stimulus for either build: `setups` back to back as `model` schedules them.
fn bench_stimulus(model: FourTriangleModel, setups: &[FourTriangleSetup]) -> registry::Stimulus {
    let (rows, expected) = stimulus_on(model, setups);
    registry::Stimulus {
        rows,
        expected: expected_rows(&expected),
        compare: vec![Compare::Exact; OUTPUTS],
    }
}

/// The registry's edge rows for either build: `setups` presented in half the clocks (taken
/// when `ready`), `hold` in a quarter.
fn bench_edge_rows(setups: &[FourTriangleSetup], seed: u64) -> Vec<Vec<u64>> {
    held_edge_rows(seed, 1500, |k, hold| {
        four_row(k.map(|k| &setups[k % setups.len()]), hold)
    })
}

impl Bench for FourTriangle {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> registry::Stimulus {
        let tris = random_triangles(seed, n);
        let setups: Vec<_> = tris.iter().map(FourTriangleSetup::new).collect();
        bench_stimulus(FourTriangleModel::new(), &setups)
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(FourRows(FourTriangleModel::new()))
    }
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let tris = random_triangles(seed ^ 0x4e1d, 12);
        let setups: Vec<_> = tris.iter().map(FourTriangleSetup::new).collect();
        bench_edge_rows(&setups, seed)
    }
}

/// `four-triangle-subpixel` on parents with `SUBPIXEL_BITS` fractional bits: the address
/// block's sub-pixel families ([`subpixel_triangles`]: the largest D, vertices on centres,
/// horizontal edges through centres, one-pixel and sub-pixel triangles, slivers).
impl Bench for SubpixelFourTriangle {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> registry::Stimulus {
        let tris = subpixel_triangles(seed, n);
        let setups: Vec<_> = tris.iter().map(FourTriangleSetup::subpixel).collect();
        bench_stimulus(FourTriangleModel::subpixel(), &setups)
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(FourRows(FourTriangleModel::subpixel()))
    }
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let tris = subpixel_triangles(seed ^ 0x4e1d, 12);
        let setups: Vec<_> = tris.iter().map(FourTriangleSetup::subpixel).collect();
        bench_edge_rows(&setups, seed)
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
