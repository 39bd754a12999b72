//! Bench of the vector interpolator (`rtl::units::vector_interpolator`) against the golden f64 planes
//! of the normal components (`golden::units::vector_interpolator`) and its bit-exact twin.
//!
//! Stimulus: seeded random triangles ([`triangle_strategy`]) with random unit vertex normals
//! in the viewer's hemisphere, driven by the golden address block's stream (the BVI's rows:
//! the vector interpolator's input ports are laid out like the BVI's).
//! Tolerances: `valid_out` exact; `nx ny nz` (signed Q2.17) within the run's largest
//! `golden::units::vector_interpolator::error_bound` (n·2⁻³⁰ + 2⁻¹⁸ for a pixel reached by n additions),
//! RMS within the RMS of those bounds.

use golden::raster::walk;
use golden::types::ScreenTriangle;
use golden::units::intensity_interpolator::additions;
use golden::units::vector_interpolator::{error_bound, setup, VectorTwin};
use pipeline::gouraud::{row_words, TriangleJob};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::INTERPOLATED;
use rtl::core::registry::NoParams;
use rtl::units::vector_interpolator::VectorInterpolator;

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::address_block::{triangle_run, triangle_strategy, GoldenPixel};
use crate::units::intensity_interpolator::{bvi_rows, row_event};
use golden::testing::seeded_runner;

/// A unit normal facing the viewer (z ≥ 0.05), uniform in angle.
fn unit_normal() -> impl Strategy<Value = [f64; 3]> {
    (0.05..=1.0f64, 0.0..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    })
}

/// `n` seeded random triangles with random unit vertex normals: the jobs (the normal words
/// in place of the BVI's colour words) and the golden value and addition count of every pixel.
pub fn normal_jobs(seed: u64, n: usize) -> (Vec<TriangleJob>, Vec<GoldenPixel>) {
    let mut r = seeded_runner(seed);
    let st = (triangle_strategy(), prop::array::uniform3(unit_normal()));
    let mut jobs = Vec::with_capacity(n);
    let mut golden = Vec::new();
    for _ in 0..n {
        let (p, normals) = st.new_tree(&mut r).expect("no rejection").current();
        let t = ScreenTriangle::from_points(p);
        let planes = crate::units::address_block::channel_planes(&t, &normals);
        let w = walk(&t);
        let per: [Vec<f64>; 3] = std::array::from_fn(|k| {
            golden::units::intensity_interpolator::interpolate(&w, &planes[k])
        });
        for (i, adds) in additions(&w).into_iter().enumerate() {
            golden.push(([per[0][i], per[1][i], per[2][i]], adds));
        }
        let mut job = TriangleJob::new(&t, &planes);
        job.words = setup(&planes, &job.addr);
        jobs.push(job);
    }
    (jobs, golden)
}

/// Row adapter of [`VectorTwin`] (inputs `load`, twelve words, valid, row_start, step, carry).
#[derive(Default)]
struct VectorRows(VectorTwin);

impl Twin for VectorRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (valid, n) = self.0.outputs();
        let w = row_words(r, 1);
        self.0.clock((r[0] != 0).then_some(&w), &row_event(r));
        std::iter::once(valid as u64)
            .chain(n.map(|x| INTERPOLATED.from_int(x)))
            .collect()
    }
}

impl Bench for VectorInterpolator {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let (jobs, golden) = normal_jobs(seed, n);
        let (rows, stream) = bvi_rows(&jobs);
        let mut g = golden.iter();
        let expected = (0..rows.len())
            .map(|c| {
                match c
                    .checked_sub(VectorInterpolator::LATENCY)
                    .map(|k| stream[k].valid)
                {
                    Some(true) => {
                        let (v, _) = g.next().expect("golden pixels and address stream disagree");
                        std::iter::once(Expected::Word(1))
                            .chain(v.map(Expected::Real))
                            .collect()
                    }
                    _ => vec![
                        Expected::Word(0),
                        Expected::DontCare,
                        Expected::DontCare,
                        Expected::DontCare,
                    ],
                }
            })
            .collect();
        let bounds: Vec<f64> = golden.iter().map(|g| error_bound(g.1)).collect();
        let tol = Tolerance {
            max_abs: bounds.iter().copied().fold(error_bound(0), f64::max),
            rms: (bounds.iter().map(|b| b * b).sum::<f64>() / bounds.len().max(1) as f64).sqrt(),
        };
        let fixed = Compare::Fixed {
            format: INTERPOLATED,
            tol,
        };
        triangle_run((rows, expected, vec![Compare::Exact, fixed, fixed, fixed]))
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(VectorRows::default())
    }
}
