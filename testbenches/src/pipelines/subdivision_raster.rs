//! Bench of the subdivision raster pipe (`rtl::pipelines::subdivision_raster`: four-triangle block + a
//! BVI per lane). Stimulus: seeded random parents (the address block's families) with random
//! front-facing vertex normals, shaded by the `subdivision` method (`golden::shading::subdivision`).
//! The four-triangle block's cycle model schedules the loads and predicts `ready`, each lane's
//! valid/x/y/done exactly (one BVI latency later) and its colours: the golden sub-triangle
//! plane at the pixel, rounded, within 1 LSB (the BVI's budget). The twin is the cycle model
//! feeding four bit-exact BVI twins (`golden::units::intensity_interpolator::BviTwin`).

use crate::harness::{Compare, Expected};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::intensity_interpolator::LEVEL_1LSB;
use golden::shade::{to_u8, ShadeContext};
use golden::shading::subdivision::SubdivisionSetup;
use golden::testing::seeded_runner;
use golden::types::ScreenTriangle;
use golden::units::four_triangle::{FourOutputs, FourTriangleModel, LANES};
use golden::units::intensity_interpolator::BviTwin;
use pipeline::subdivision::{pipe_row, row_job, SubJob, OUTPUTS, PIPE_HOLD_AT};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::registry::NoParams;
use rtl::pipelines::subdivision_raster::SubdivisionRaster;
use rtl::units::intensity_interpolator::IntensityInterpolator;

/// `n` seeded parents with random unit vertex normals (n.z ≥ 0.2): their jobs and golden
/// set-ups (zero-area parents are kept: the hardware walks them, with no pixel).
pub fn random_jobs(seed: u64, n: usize) -> Vec<(SubJob, Option<SubdivisionSetup>)> {
    let tris = crate::units::four_triangle::random_triangles(seed, n);
    let mut r = seeded_runner(seed ^ 0x5eed);
    let normal = (-1.0..1.0f64, -1.0..1.0f64, 0.2..1.0f64);
    let ctx = ShadeContext::default();
    tris.into_iter()
        .map(|mut t| {
            for v in &mut t.v {
                let (x, y, z) = normal.new_tree(&mut r).unwrap().current();
                v.normal = glam::DVec3::new(x, y, z).normalize();
            }
            let job = SubJob::subdivision(&t, &ctx).unwrap_or_else(|| zero_job(&t));
            (job, golden::shading::subdivision::setup(&t, &ctx))
        })
        .collect()
}

/// The job of a zero-area parent: four lanes without rows, zero words.
fn zero_job(t: &ScreenTriangle) -> SubJob {
    SubJob {
        addr: golden::units::four_triangle::FourTriangleSetup::new(t),
        words: Default::default(),
    }
}

/// Input rows (loads where the cycle model is ready) and the model's outputs per clock, up to
/// one BVI latency past the last lane's last `done`.
fn schedule(jobs: &[SubJob]) -> (Vec<Vec<u64>>, Vec<FourOutputs>) {
    let setups: Vec<_> = jobs.iter().map(|j| j.addr).collect();
    golden::units::four_triangle::schedule_on(
        FourTriangleModel::subpixel(),
        &setups,
        IntensityInterpolator::LATENCY + 1,
    )
    .into_iter()
    .map(|(o, load)| (pipe_row(load.map(|k| &jobs[k])), o))
    .unzip()
}

/// The pipe's stimulus with golden expectations (see the module doc).
pub fn run(jobs: &[(SubJob, Option<SubdivisionSetup>)]) -> Stimulus {
    let only: Vec<SubJob> = jobs.iter().map(|j| j.0).collect();
    let (rows, addr) = schedule(&only);
    let lat = IntensityInterpolator::LATENCY;
    let mut parent = [0usize; LANES];
    let expected =
        (0..rows.len())
            .map(|c| {
                let w = |v: u64| Expected::Word(v);
                let mut e = vec![w(addr[c].ready as u64)];
                for (k, p) in parent.iter_mut().enumerate() {
                    let d = c
                        .checked_sub(lat)
                        .map(|i| addr[i].lanes[k])
                        .unwrap_or_default();
                    e.extend([w(d.valid as u64), w(d.x as u64), w(d.y as u64)]);
                    if d.valid {
                        let s = jobs[*p].1.as_ref().expect("pixels of a zero-area parent");
                        let pl = s.planes[k];
                        e.extend(pl.map(|q| {
                            Expected::Real(to_u8(q.at_pixel(d.x as i32, d.y as i32)) as f64)
                        }));
                    } else {
                        e.extend([Expected::DontCare; 3]);
                    }
                    e.push(w(d.done as u64));
                    *p += d.done as usize;
                }
                e
            })
            .collect();
    let mut compare = vec![Compare::Exact; OUTPUTS];
    for k in 0..LANES {
        compare[1 + 7 * k + 3..1 + 7 * k + 6].copy_from_slice(&[LEVEL_1LSB; 3]);
    }
    Stimulus {
        rows,
        expected,
        compare,
    }
}

/// Twin of the pipe: the four-triangle cycle model feeding one [`BviTwin`] per lane (loaded on
/// the accepted load), with each lane's x, y and done delayed one clock.
pub struct SubRows {
    addr: FourTriangleModel,
    bvi: [BviTwin; LANES],
    xy_done: [(u32, u32, bool); LANES],
}

impl Default for SubRows {
    /// The pipe's four-triangle block is the sub-pixel one (21-bit lanes).
    fn default() -> Self {
        SubRows {
            addr: FourTriangleModel::subpixel(),
            bvi: Default::default(),
            xy_done: Default::default(),
        }
    }
}

impl Twin for SubRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[PIPE_HOLD_AT] != 0;
        let a = self.addr.outputs_held(hold);
        let mut o = vec![a.ready as u64];
        for k in 0..LANES {
            let (valid, levels, _) = self.bvi[k].outputs();
            let (x, y, done) = self.xy_done[k];
            o.extend([valid as u64, x as u64, y as u64]);
            o.extend(levels.map(u64::from));
            o.push(done as u64);
        }
        let job = row_job(r);
        let accepted = job.is_some() && a.ready;
        for k in 0..LANES {
            self.bvi[k].clock(
                job.as_ref().filter(|_| accepted).map(|j| &j.words[k]),
                &a.lanes[k],
            );
            let l = a.lanes[k];
            self.xy_done[k] = (l.x, l.y, l.done);
        }
        self.addr.clock_held(job.as_ref().map(|j| &j.addr), hold);
        o
    }
}

impl Bench for SubdivisionRaster {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        run(&random_jobs(seed, n))
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(SubRows::default())
    }
    /// Parents presented in half the clocks (taken when `ready`), `hold` in a quarter.
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let jobs: Vec<SubJob> = random_jobs(seed ^ 0x5d1d, 8)
            .into_iter()
            .map(|j| j.0)
            .collect();
        crate::units::four_triangle::held_edge_rows(seed, 1500, |k, hold| {
            let mut row = pipe_row(k.map(|k| &jobs[k % jobs.len()]));
            row[PIPE_HOLD_AT] = hold as u64;
            row
        })
    }
}
