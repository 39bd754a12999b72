//! The subdivision raster pipe (`rtl::pipelines::subdivision_raster`: four-triangle block + one BVI per
//! lane) as a render driver: per parent, the four-triangle set-up in software
//! (`golden::units::four_triangle::FourTriangleSetup`) and each lane's BVI words, loaded whenever the
//! pipe's `ready` is high; up to four pixels per clock out.
//!
//! Two job kinds, the same hardware: [`SubJob::gouraud`] (Gouraud through the four-triangle
//! block: every lane interpolates the parent's planes) and [`SubJob::subdivision`] (the
//! `subdivision` method: lane K interpolates sub-triangle K's own planes,
//! `golden::shading::subdivision`).
//!
//! Row layouts (the order of the blocks' input ports): [`setup_row`] is the four-triangle
//! block's (`load`, the shared increments of the parent's working, adjacent and third edge as
//! f r d, then per lane w_b0 w_e0 a_b0 a_e0 a_third t_b0 t_e0 t_adjacent y_top rows
//! y_switch dir_neg); [`pipe_row`] the pipe's (that, then each lane's twelve BVI words).

use golden::shade::ShadeContext;
use golden::types::{Plane, ScreenTriangle};
use golden::units::four_triangle::{EdgeIncrements, FourTriangleSetup, LaneSetup, LANES};
use golden::units::intensity_interpolator::{self as gbvi, ChannelWords};
use rtl::core::sim::Model;

use flow::engine::Sim;
use rtl::pipelines::subdivision_raster::SubdivisionRaster;

use crate::axis::PipeStats;
use crate::axis::{with_last, Word};
use crate::gouraud::{row_words, words_row};
use rtl::stream::layout::{pack, SUBDIVISION_PARENT};

/// One parent's complete set-up for the subdivision pipe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubJob {
    pub addr: FourTriangleSetup,
    /// `words[lane]`: the lane's BVI words (r, g, b).
    pub words: [[ChannelWords; 3]; 4],
}

impl SubJob {
    /// Lane K interpolates `planes[K]` over sub-triangle K's walk (integer or sub-pixel
    /// parents: `four-triangle-subpixel` takes both).
    pub fn new(tri: &ScreenTriangle, planes: &[[Plane; 3]; 4]) -> SubJob {
        let addr = FourTriangleSetup::new(tri);
        let words =
            std::array::from_fn(|k| gbvi::setup(&planes[k], &addr.lane(k)).map(|c| c.words()));
        SubJob { addr, words }
    }

    /// Gouraud through the four-triangle block: every lane takes the parent's planes
    /// (`golden::shading::gouraud`); `None` for zero area.
    pub fn gouraud(tri: &ScreenTriangle, ctx: &ShadeContext) -> Option<SubJob> {
        golden::shading::gouraud::setup(tri, ctx).map(|g| SubJob::new(tri, &[g.planes; LANES]))
    }

    /// The `subdivision` method (`golden::shading::subdivision`); `None` for zero area.
    pub fn subdivision(tri: &ScreenTriangle, ctx: &ShadeContext) -> Option<SubJob> {
        golden::shading::subdivision::setup(tri, ctx).map(|s| SubJob::new(tri, &s.planes))
    }
}

/// The four-triangle block's input row of one clock: `load` and the set-up words (all zero
/// without a load).
pub fn setup_row(s: Option<&FourTriangleSetup>) -> Vec<u64> {
    let z = FourTriangleSetup::default();
    let (load, s) = (s.is_some() as u64, s.unwrap_or(&z));
    let mut row = vec![load];
    for i in [&s.w, &s.a, &s.t] {
        row.extend([i.f_word() as u64, i.r as u64, i.d as u64]);
    }
    for l in &s.lanes {
        row.extend([
            l.w_b0 as u64,
            l.w_e0 as u64,
            l.a_b0 as u64,
            l.a_e0 as u64,
            l.a_third as u64,
            l.t_b0 as u64,
            l.t_e0 as u64,
            l.t_adjacent as u64,
            l.y_top as u64,
            l.rows as u64,
            l.y_switch as u64,
            l.dir_neg as u64,
        ]);
    }
    row
}

/// Length of [`setup_row`].
pub const SETUP_ROW: usize = 1 + 9 + 12 * LANES;

/// The inverse of [`setup_row`] (`f` read back as the 12-bit two's-complement word).
pub fn row_setup(r: &[u64]) -> Option<FourTriangleSetup> {
    if r[0] == 0 {
        return None;
    }
    let inc = |k: usize| EdgeIncrements {
        f: ((r[k] as u32) << 20) as i32 >> 20,
        r: r[k + 1] as u32,
        d: r[k + 2] as u32,
    };
    let lane = |k: usize| {
        let b = 10 + 12 * k;
        LaneSetup {
            w_b0: r[b] as u32,
            w_e0: r[b + 1] as u32,
            a_b0: r[b + 2] as u32,
            a_e0: r[b + 3] as u32,
            a_third: r[b + 4] != 0,
            t_b0: r[b + 5] as u32,
            t_e0: r[b + 6] as u32,
            t_adjacent: r[b + 7] != 0,
            y_top: r[b + 8] as u32,
            rows: r[b + 9] as u32,
            y_switch: r[b + 10] as u32,
            dir_neg: r[b + 11] != 0,
        }
    };
    Some(FourTriangleSetup {
        w: inc(1),
        a: inc(4),
        t: inc(7),
        lanes: std::array::from_fn(lane),
    })
}

/// The pipe's input row: the four-triangle set-up, then each lane's twelve BVI words, then
/// `hold` low (a stream top's back-pressure; never here).
pub fn pipe_row(job: Option<&SubJob>) -> Vec<u64> {
    let mut row = setup_row(job.map(|j| &j.addr));
    for k in 0..LANES {
        row.extend(words_row(job.map(|j| &j.words[k])));
    }
    row.push(0);
    row
}

/// Index of `hold` in [`pipe_row`].
pub const PIPE_HOLD_AT: usize = SETUP_ROW + 12 * LANES;

/// The inverse of [`pipe_row`].
pub fn row_job(row: &[u64]) -> Option<SubJob> {
    let addr = row_setup(row)?;
    Some(SubJob {
        addr,
        words: std::array::from_fn(|k| row_words(row, SETUP_ROW + 12 * k)),
    })
}

/// Output ports of the pipe: `ready`, then per lane valid x y red green blue done.
pub const OUTPUTS: usize = 1 + 7 * LANES;

/// The subdivision raster pipe, `subdivision-raster` or its AXI4-Stream top
/// `subdivision-stream`, on either simulator ([`Sim`]).
pub struct SubPipe {
    model: Box<dyn Model>,
    stream: bool,
}

impl SubPipe {
    /// `subdivision-raster` on rust-hdl.
    pub fn new() -> Result<SubPipe, String> {
        SubPipe::on(Sim::RustHdl, false)
    }

    /// The pipe through its AXI4-Stream top `subdivision-stream` on rust-hdl: each parent a
    /// 87-word record on the set-up stream, each lane's fragments on its own stream (every
    /// `tready` high).
    pub fn stream() -> Result<SubPipe, String> {
        SubPipe::on(Sim::RustHdl, true)
    }

    /// `subdivision-raster` (or `subdivision-stream` if `stream`) on `sim`.
    pub fn on(sim: Sim, stream: bool) -> Result<SubPipe, String> {
        let model = flow::engine::model_of::<
            SubdivisionRaster,
            rtl::stream::subdivision_stream::SubdivisionStream,
        >(sim, stream)?;
        Ok(SubPipe { model, stream })
    }

    /// The design [`SubPipe::on`] builds under Verilator.
    pub fn design(stream: bool) -> verilated::Design {
        flow::engine::design_of::<
            SubdivisionRaster,
            rtl::stream::subdivision_stream::SubdivisionStream,
        >(stream)
    }

    /// Run `jobs`, each loaded as soon as `ready` is high; `pixel(job, x, y, rgb)` for every
    /// valid lane output (a lane's job index counts that lane's `done` markers);
    /// `progress(parents done by every lane)`. Stops once every lane has shown the last
    /// parent's `done`, or with an error after `max_clocks`. `stats.triangles` counts parents.
    pub fn run(
        &mut self,
        jobs: &[SubJob],
        max_clocks: u64,
        mut pixel: impl FnMut(usize, u32, u32, [u8; 3]),
        mut progress: impl FnMut(u64),
    ) -> Result<PipeStats, String> {
        if self.stream {
            let n = jobs.len() as u64;
            return crate::axis::drive_lanes::<rtl::stream::subdivision_stream::SubdivisionStream>(
                self.model.as_mut(),
                &crate::subdivision::subdivision_words(jobs),
                n,
                max_clocks,
                &mut |k, b, _, _| pixel(k, b.x, b.y, b.rgb),
                &mut |done| progress(done),
            );
        }
        crate::axis::first_output_is(self.model.as_ref(), "ready")?;
        let mut st = PipeStats::default();
        let mut out = vec![0u64; OUTPUTS];
        let idle = pipe_row(None);
        let mut next = 0;
        let mut dones = [0usize; LANES];
        let n = jobs.len();
        while dones.iter().any(|&d| d < n) {
            if st.clocks >= max_clocks {
                return Err(format!(
                    "subdivision pipe: lanes done {dones:?} of {n} parents after {max_clocks} clocks"
                ));
            }
            let load = (self.model.peek(0) != 0 && next < n).then(|| &jobs[next]);
            next += load.is_some() as usize;
            match load {
                Some(j) => self.model.step(&pipe_row(Some(j)), &mut out)?,
                None => self.model.step(&idle, &mut out)?,
            }
            st.clocks += 1;
            let before = *dones.iter().min().unwrap();
            for (k, d) in dones.iter_mut().enumerate() {
                let o = &out[1 + 7 * k..1 + 7 * (k + 1)];
                if o[0] != 0 {
                    st.pixels += 1;
                    pixel(
                        *d,
                        o[1] as u32,
                        o[2] as u32,
                        [o[3] as u8, o[4] as u8, o[5] as u8],
                    );
                }
                *d += (o[6] != 0) as usize;
            }
            let after = *dones.iter().min().unwrap();
            if after > before {
                st.triangles = after as u64;
                progress(st.triangles);
            }
        }
        Ok(st)
    }
}

/// A clock budget for `jobs`: every lane row at the full line length plus latency (and the
/// stream top's record, 87 words, per parent).
pub fn clock_budget(jobs: &[SubJob]) -> u64 {
    jobs.iter()
        .map(|j| {
            80 + j
                .addr
                .lanes
                .iter()
                .map(|l| l.rows as u64)
                .max()
                .unwrap_or(0)
                * 4097
        })
        .sum()
}

/// The `subdivision-stream` record of a parent (the same field values `subdivision-raster`'s
/// load row carries).
pub fn subdivision_record(job: &crate::subdivision::SubJob) -> Vec<Word> {
    let row = crate::subdivision::pipe_row(Some(job));
    with_last(pack(
        &SUBDIVISION_PARENT,
        &row[1..crate::subdivision::PIPE_HOLD_AT],
    ))
}

/// A subdivision scene's set-up stream: every parent, in order.
pub fn subdivision_words(jobs: &[crate::subdivision::SubJob]) -> Vec<Word> {
    jobs.iter().flat_map(subdivision_record).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn row_layouts_round_trip() {
        let mut tri = ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        tri.v[1].normal = glam::DVec3::new(0.3, 0.1, 1.0).normalize();
        let j = SubJob::subdivision(&tri, &ShadeContext::default()).unwrap();
        assert_eq!(pipe_row(Some(&j)).len(), SETUP_ROW + 48 + 1);
        assert_eq!(pipe_row(Some(&j))[PIPE_HOLD_AT], 0);
        assert_eq!(row_job(&pipe_row(Some(&j))), Some(j));
        assert_eq!(row_job(&pipe_row(None)), None);
    }
}

#[cfg(test)]
mod record_tests {
    use super::*;
    use rtl::stream::layout::unpack;

    #[test]
    fn subdivision_records_carry_the_load_row() {
        let mut t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        t.v[1].normal = glam::DVec3::new(0.3, 0.1, 1.0).normalize();
        let ctx = golden::shade::ShadeContext::default();
        let job = crate::subdivision::SubJob::subdivision(&t, &ctx).unwrap();
        let rec = subdivision_record(&job);
        assert_eq!(rec.len(), 87);
        assert_eq!(rec[0], (1, false));
        assert!(rec.last().unwrap().1);
        assert!(rec[..86].iter().all(|w| !w.1));
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = crate::subdivision::pipe_row(Some(&job));
        assert_eq!(
            unpack(&SUBDIVISION_PARENT, &payload),
            row[1..crate::subdivision::PIPE_HOLD_AT].to_vec()
        );
        assert_eq!(subdivision_words(&[job, job]).len(), 174);
    }
}
