//! The Gouraud raster pipe (`rtl::pipelines::gouraud_raster`: address block + BVI) as a render driver:
//! triangle set-up in software (`golden::units::address_block::AddressSetup` for the address block,
//! `golden::units::intensity_interpolator` words for the BVI), loaded whenever the pipe's `ready` is
//! high, pixels out in the order the hardware emits them.
//!
//! Row layouts (the order of the blocks' input ports, `rtl::impl_dut!` beside each block):
//! [`setup_row`] is the address block's (`load`, then w, a, t edges as b0 e0 f r d, then
//! y_top rows y_switch dir_neg); [`words_row`] the BVI's twelve words (r, g, b × start short
//! long line); [`pipe_row`] the raster pipe's (the two concatenated).

use std::io::Write;

use golden::shade::ShadeContext;
use golden::types::{Plane, ScreenTriangle};
use golden::units::address_block::{AddressSetup, EdgeSetup};
use golden::units::intensity_interpolator::{self as gbvi, ChannelWords};
use rtl::core::sim::Model;
use rtl::pipelines::gouraud_raster::GouraudRaster;

use crate::axis::{with_last, PipeStats, Word};
use flow::engine::Sim;
use rtl::stream::layout::{pack, GOURAUD_TRIANGLE};

/// One triangle's complete set-up for the raster pipe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleJob {
    pub addr: AddressSetup,
    pub words: [ChannelWords; 3],
}

impl TriangleJob {
    /// Set-up of `tri` with the channel planes `planes` (LSB units).
    pub fn new(tri: &ScreenTriangle, planes: &[Plane; 3]) -> TriangleJob {
        let addr = AddressSetup::new(tri);
        let words = gbvi::setup(planes, &addr).map(|c| c.words());
        TriangleJob { addr, words }
    }

    /// Gouraud set-up of `tri` under `ctx` (`golden::shading::gouraud`); `None` for zero area.
    pub fn gouraud(tri: &ScreenTriangle, ctx: &ShadeContext) -> Option<TriangleJob> {
        golden::shading::gouraud::setup(tri, ctx).map(|g| TriangleJob::new(tri, &g.planes))
    }
}

fn edge_words(e: &EdgeSetup) -> [u64; 5] {
    [
        e.b0 as u64,
        e.e0 as u64,
        e.f_word() as u64,
        e.r as u64,
        e.d as u64,
    ]
}

/// The address block's input row of one clock: `load` and the set-up words (all zero
/// without a load).
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

/// The inverse of [`setup_row`]: the set-up a row loads, if its `load` bit is set (`f` is
/// read back as the 12-bit two's-complement word the hardware holds).
pub fn row_setup(row: &[u64]) -> Option<AddressSetup> {
    if row[0] == 0 {
        return None;
    }
    let edge = |k: usize| EdgeSetup {
        b0: row[k] as u32,
        e0: row[k + 1] as u32,
        f: ((row[k + 2] as u32) << 20) as i32 >> 20,
        r: row[k + 3] as u32,
        d: row[k + 4] as u32,
    };
    Some(AddressSetup {
        w: edge(1),
        a: edge(6),
        t: edge(11),
        y_top: row[16] as u32,
        rows: row[17] as u32,
        y_switch: row[18] as u32,
        dir_neg: row[19] != 0,
    })
}

/// The BVI's twelve set-up words (zero without a triangle).
pub fn words_row(w: Option<&[ChannelWords; 3]>) -> Vec<u64> {
    let z = [ChannelWords::default(); 3];
    w.unwrap_or(&z)
        .iter()
        .flat_map(|c| [c.start, c.short, c.long, c.line].map(u64::from))
        .collect()
}

/// The inverse of [`words_row`], from `row[at..at + 12]`.
pub fn row_words(row: &[u64], at: usize) -> [ChannelWords; 3] {
    std::array::from_fn(|c| {
        let w = |i: usize| row[at + 4 * c + i] as u32;
        ChannelWords {
            start: w(0),
            short: w(1),
            long: w(2),
            line: w(3),
        }
    })
}

/// The pipe's input row: `load`, the address set-up, the twelve BVI words, `hold` (0).
pub fn pipe_row(job: Option<&TriangleJob>) -> Vec<u64> {
    let mut row = setup_row(job.map(|j| &j.addr));
    row.extend(words_row(job.map(|j| &j.words)));
    row.push(0);
    row
}

/// Index of `hold` in a [`pipe_row`].
pub const PIPE_HOLD_AT: usize = 32;

/// The raster pipe, `gouraud-raster` or its AXI4-Stream top `gouraud-stream`, on either
/// simulator ([`Sim`]).
pub struct Pipe {
    model: Box<dyn Model>,
    stream: bool,
}

impl Pipe {
    /// `gouraud-raster` on rust-hdl.
    pub fn new() -> Result<Pipe, String> {
        Pipe::on(Sim::RustHdl, false)
    }

    /// The AXI4-Stream top `gouraud-stream` on rust-hdl: [`Pipe::run`] sends every triangle
    /// record on its set-up stream (one word per clock while `s_axis_tready`) and takes every
    /// fragment beat (`m_axis_tready` high).
    pub fn stream() -> Result<Pipe, String> {
        Pipe::on(Sim::RustHdl, true)
    }

    /// `gouraud-raster` (or `gouraud-stream` if `stream`) on `sim`.
    pub fn on(sim: Sim, stream: bool) -> Result<Pipe, String> {
        let model = flow::engine::model_of::<
            GouraudRaster,
            rtl::stream::gouraud_stream::GouraudStream,
        >(sim, stream)?;
        Ok(Pipe { model, stream })
    }

    /// The design [`Pipe::on`] builds under Verilator.
    pub fn design(stream: bool) -> verilated::Design {
        flow::engine::design_of::<GouraudRaster, rtl::stream::gouraud_stream::GouraudStream>(stream)
    }

    /// Trace every following clock into `w` (rust-hdl only: an error on Verilator).
    pub fn start_vcd(&mut self, w: Box<dyn Write>) -> Result<(), String> {
        self.model.start_vcd(w)
    }

    /// Run `jobs` through the pipe, each loaded as soon as `ready` is high;
    /// `pixel(job_index, x, y, rgb)` for every valid output (the pipe keeps the jobs' order,
    /// so the index counts the `done` markers seen before the pixel),
    /// `progress(done_triangles)` after each triangle's `done`. Stops after the last `done`,
    /// or with an error after `max_clocks`.
    pub fn run(
        &mut self,
        jobs: &[TriangleJob],
        max_clocks: u64,
        mut pixel: impl FnMut(usize, u32, u32, [u8; 3]),
        mut progress: impl FnMut(u64),
    ) -> Result<PipeStats, String> {
        if self.stream {
            return crate::axis::drive::<rtl::stream::gouraud_stream::GouraudStream>(
                self.model.as_mut(),
                "gouraud-stream",
                "triangles",
                &crate::gouraud::gouraud_words(jobs),
                jobs.len() as u64,
                max_clocks,
                &mut |job, b, _| pixel(job, b.x, b.y, b.rgb),
                &mut progress,
            );
        }
        crate::axis::first_output_is(self.model.as_ref(), "ready")?;
        let mut st = PipeStats::default();
        let mut out = vec![0u64; 8];
        let idle = pipe_row(None);
        let mut next = 0;
        while st.triangles < jobs.len() as u64 {
            if st.clocks >= max_clocks {
                return Err(format!(
                    "raster pipe: {} of {} triangles done after {max_clocks} clocks",
                    st.triangles,
                    jobs.len()
                ));
            }
            // `ready` is a register output: its value for this clock is already settled.
            let load = (self.model.peek(0) != 0 && next < jobs.len()).then(|| &jobs[next]);
            next += load.is_some() as usize;
            match load {
                Some(j) => self.model.step(&pipe_row(Some(j)), &mut out)?,
                None => self.model.step(&idle, &mut out)?,
            }
            st.clocks += 1;
            if out[1] != 0 {
                st.pixels += 1;
                pixel(
                    st.triangles as usize,
                    out[2] as u32,
                    out[3] as u32,
                    [out[4] as u8, out[5] as u8, out[6] as u8],
                );
            }
            if out[7] != 0 {
                st.triangles += 1;
                progress(st.triangles);
            }
        }
        self.model.stop_vcd()?;
        Ok(st)
    }
}

/// A clock budget for `jobs`: every row at the full line length plus latency, so a hung pipe
/// stops instead of spinning.
pub fn clock_budget(jobs: &[TriangleJob]) -> u64 {
    jobs.iter().map(|j| 8 + j.addr.rows as u64 * 4097).sum()
}

/// The `gouraud-stream` record of `job` (the same field values `gouraud-raster`'s load row
/// carries).
pub fn gouraud_record(job: &TriangleJob) -> Vec<Word> {
    let row = pipe_row(Some(job));
    with_last(pack(&GOURAUD_TRIANGLE, &row[1..PIPE_HOLD_AT]))
}

/// A Gouraud scene's set-up stream: every triangle, in order.
pub fn gouraud_words(jobs: &[TriangleJob]) -> Vec<Word> {
    jobs.iter().flat_map(gouraud_record).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn row_layouts_round_trip() {
        let e = |b0, f| EdgeSetup {
            b0,
            e0: 5,
            f,
            r: 7,
            d: 8190,
        };
        let s = AddressSetup {
            w: e(4095, -4095),
            a: e(1, 2047),
            t: e(0, -1),
            y_top: 9,
            rows: 4095,
            y_switch: 12,
            dir_neg: true,
        };
        let back = row_setup(&setup_row(Some(&s))).unwrap();
        // f is held modulo 4096: −4095 comes back as 1, which walks identically.
        assert_eq!(back.w.f_word(), s.w.f_word());
        assert_eq!(back.w.f, 1);
        assert_eq!(AddressSetup { w: s.w, ..back }, s);
        assert_eq!(row_setup(&setup_row(None)), None);
        let w = [1u32, 2, 3].map(|k| ChannelWords {
            start: k,
            short: 10 * k,
            long: 100 * k,
            line: u32::MAX - k,
        });
        assert_eq!(row_words(&words_row(Some(&w)), 0), w);
    }
}

#[cfg(test)]
mod record_tests {
    use super::*;
    use rtl::stream::layout::unpack;

    #[test]
    fn gouraud_records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let ctx = golden::shade::ShadeContext::default();
        let job = TriangleJob::gouraud(&t, &ctx).unwrap();
        let rec = gouraud_record(&job);
        assert_eq!(rec.len(), 23);
        assert_eq!(rec[0], (1, false));
        assert!(rec.last().unwrap().1);
        assert!(rec[..22].iter().all(|w| !w.1));
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = pipe_row(Some(&job));
        assert_eq!(
            unpack(&GOURAUD_TRIANGLE, &payload),
            row[1..PIPE_HOLD_AT].to_vec()
        );
        assert_eq!(gouraud_words(&[job, job]).len(), 46);
    }
}
