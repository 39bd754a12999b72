//! Cycle-by-cycle bench of the address block (`rtl::units::address_block`) against its cycle-accurate
//! golden model (`golden::units::address_block`), on the shared harness (`crate::harness`).
//!
//! Stimulus: a list of triangles. The golden model decides in which clock each set-up is
//! loaded (the first clock where its `ready` is high); those loads become the input rows, and
//! the model's outputs the exact expectation of every output port (including `ready`, so an RTL
//! that is not ready when the model is fails at that clock). [`run_reactive`] instead lets the
//! RTL's own `ready` pace the loads (what the `raster` command and the renderer do).

use crate::harness::{CheckSpec, Compare, Expected, Failure, Report};
use crate::registry::{self, Bench, Twin};
use golden::raster::walk;
use golden::testing::seeded_runner;
use golden::types::{Plane, ScreenTriangle, SubpixelTriangle, SUBPIXEL_BITS};
use golden::units::address_block::{AddressBlockModel, AddressOutputs, AddressSetup};
use golden::units::intensity_interpolator::{additions, interpolate};
use pipeline::gouraud::{row_setup, TriangleJob};
pub use pipeline::walkers::address::*;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::registry::NoParams;
use rtl::units::address_block::{AddressBlock, SubpixelAddressBlock};

/// Run the RTL on the model's stimulus and compare every output port every clock, exactly.
/// Returns the harness report and the RTL's outputs per clock.
pub fn check(
    name: &str,
    seed: u64,
    setups: &[AddressSetup],
) -> Result<(Report, Vec<AddressOutputs>), Box<Failure>> {
    check_on(
        AddressBlock::default,
        AddressBlockModel::new(),
        name,
        seed,
        setups,
    )
}

/// [`check`] for the sub-pixel build (`address-block-subpixel`, set-ups from
/// [`AddressSetup::subpixel`]).
pub fn check_subpixel(
    name: &str,
    seed: u64,
    setups: &[AddressSetup],
) -> Result<(Report, Vec<AddressOutputs>), Box<Failure>> {
    check_on(
        SubpixelAddressBlock::default,
        AddressBlockModel::subpixel(),
        name,
        seed,
        setups,
    )
}

fn check_on<B: rtl::core::sim::Dut>(
    build: fn() -> B,
    model: AddressBlockModel,
    name: &str,
    seed: u64,
    setups: &[AddressSetup],
) -> Result<(Report, Vec<AddressOutputs>), Box<Failure>> {
    let st = stimulus_held_on(model, setups, |_| false);
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
    let report = crate::harness::run_rows(build, &spec, &st.rows, &expected).map_err(Box::new)?;
    let outs = report.outputs.iter().map(|r| row_outputs(r)).collect();
    Ok((report, outs))
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
    triangle_jobs_with(seed, n, false)
}

/// [`triangle_jobs`] with every other triangle's vertices moved by a seeded fraction of a pixel
/// (`SUBPIXEL_BITS` fraction bits; [`subpixel_offsets`]): the stimulus of the blocks with the
/// sub-pixel address block (`gouraud-raster`, `pixel-pipeline` and their stream tops).
pub fn subpixel_triangle_jobs(seed: u64, n: usize) -> (Vec<TriangleJob>, Vec<GoldenPixel>) {
    triangle_jobs_with(seed, n, true)
}

/// Offsets of 0..2^SUBPIXEL_BITS per coordinate, for [`subpixel_offsets`].
pub fn offsets_strategy() -> impl Strategy<Value = [(i32, i32); 3]> {
    let one = 1i32 << SUBPIXEL_BITS;
    prop::array::uniform3((0..one, 0..one))
}

/// `t` with its integer vertices moved by `off` (in 2^−SUBPIXEL_BITS pixel, kept within the
/// 12-bit range) and `frac` = `SUBPIXEL_BITS`.
pub fn subpixel_offsets(t: &ScreenTriangle, off: [(i32, i32); 3]) -> ScreenTriangle {
    let max = 4095 << SUBPIXEL_BITS;
    let mut s = *t;
    for (v, (dx, dy)) in s.v.iter_mut().zip(off) {
        v.x = ((v.x << SUBPIXEL_BITS) + dx).min(max);
        v.y = ((v.y << SUBPIXEL_BITS) + dy).min(max);
    }
    s.frac = SUBPIXEL_BITS;
    s
}

fn triangle_jobs_with(seed: u64, n: usize, subpixel: bool) -> (Vec<TriangleJob>, Vec<GoldenPixel>) {
    let mut r = seeded_runner(seed);
    let st = (
        triangle_strategy(),
        prop::array::uniform3(prop::array::uniform3(-40.0..320.0f64)),
    );
    // The offsets come from a runner of their own, so the integer triangles are the same
    // with and without them.
    let mut r_off = seeded_runner(seed ^ 0x5B5B);
    let offsets = offsets_strategy();
    let mut jobs = Vec::with_capacity(n);
    let mut golden = Vec::new();
    for i in 0..n {
        let (p, v) = st.new_tree(&mut r).expect("no rejection").current();
        let mut t = ScreenTriangle::from_points(p);
        if subpixel && i % 2 == 1 {
            let off = offsets
                .new_tree(&mut r_off)
                .expect("no rejection")
                .current();
            t = subpixel_offsets(&t, off);
        }
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
/// golden/src/units/address_block.rs).
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

/// Seeded triangles with `SUBPIXEL_BITS` fractional bits, after the named edge cases: the
/// largest D (an edge spanning all 4095 rows), vertices on pixel centres, a horizontal edge
/// through a row of centres, one-pixel and sub-pixel triangles, a sliver.
pub fn subpixel_triangles(seed: u64, n: usize) -> Vec<SubpixelTriangle> {
    const ONE: i32 = 1 << SUBPIXEL_BITS;
    const MAX: i32 = 4095 * ONE;
    let named: [[(i32, i32); 3]; 6] = [
        [(0, 0), (2 * ONE, MAX), (0, MAX)],
        [(3, 5), (ONE + 7, MAX), (9, MAX - 3)],
        [
            (ONE / 2, ONE / 2),
            (8 * ONE + ONE / 2, ONE / 2),
            (4 * ONE + ONE / 2, 6 * ONE + ONE / 2),
        ],
        [
            (100 * ONE + 3, 50 * ONE + ONE / 2),
            (90 * ONE + 11, 50 * ONE + ONE / 2),
            (95 * ONE, 40 * ONE + 1),
        ],
        [
            (7 * ONE + 1, 7 * ONE + 1),
            (8 * ONE + 2, 7 * ONE + 9),
            (7 * ONE + 3, 8 * ONE + 15),
        ],
        [
            (5, 7),
            (3000 * ONE + 9, 2000 * ONE + 3),
            (3000 * ONE + 11, 2000 * ONE + 5),
        ],
    ];
    let mut r = seeded_runner(seed);
    let pt = |max: i32| (0..=max, 0..=max);
    let st = prop_oneof![
        // General, up to 40 pixels across, anywhere.
        4 => (pt(MAX - 40 * ONE), [pt(40 * ONE), pt(40 * ONE), pt(40 * ONE)])
            .prop_map(|(o, v)| v.map(|p| (o.0 + p.0, o.1 + p.1))),
        // Up to two pixels across: one pixel or none.
        2 => (pt(MAX - 2 * ONE), [pt(2 * ONE), pt(2 * ONE), pt(2 * ONE)])
            .prop_map(|(o, v)| v.map(|p| (o.0 + p.0, o.1 + p.1))),
        // Long slivers over the whole range.
        1 => (pt(MAX), pt(MAX), -ONE..=ONE, -ONE..=ONE).prop_map(|(a, b, ox, oy)| {
            [a, b, ((b.0 + ox).clamp(0, MAX), (b.1 + oy).clamp(0, MAX))]
        }),
    ];
    let mut out: Vec<SubpixelTriangle> = named
        .iter()
        .map(|&v| SubpixelTriangle {
            v,
            frac: SUBPIXEL_BITS,
        })
        .collect();
    for _ in 0..n {
        let v = st.new_tree(&mut r).expect("no rejection").current();
        out.push(SubpixelTriangle {
            v,
            frac: SUBPIXEL_BITS,
        });
    }
    out
}

impl Bench for SubpixelAddressBlock {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> registry::Stimulus {
        let setups: Vec<AddressSetup> = subpixel_triangles(seed, n)
            .iter()
            .map(AddressSetup::subpixel)
            .collect();
        let mut stalls = crate::stall::StallPattern::new(seed, 0.25);
        let st = stimulus_held_on(AddressBlockModel::subpixel(), &setups, |_| {
            stalls.next_stalled()
        });
        let expected = st
            .expected
            .iter()
            .map(|o| outputs_row(o).into_iter().map(Expected::Word).collect())
            .collect();
        triangle_run((st.rows, expected, vec![Compare::Exact; 9]))
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(AddressRows(AddressBlockModel::subpixel()))
    }
}
