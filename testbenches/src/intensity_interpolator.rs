//! Cycle-by-cycle bench of the intensity interpolator BVI (`rtl::intensity_interpolator`)
//! against the golden f64 BVI (`golden::intensity_interpolator`), and the driver of the whole
//! Gouraud raster pipe (`rtl::gouraud_raster`: address block + BVI) that renders triangles
//! through the RTL.

use crate::address_block::{run_model, settle};
use golden::address_block::{AddressOutputs, AddressSetup};
use golden::intensity_interpolator::{self as gbvi, ChannelWords};
use golden::shade::ShadeContext;
use golden::types::{Plane, ScreenTriangle};
use rtl::gouraud_raster::GouraudRaster;
use rtl::intensity_interpolator::IntensityInterpolator;
use rust_hdl::prelude::*;
use std::io::Write;

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

    /// Gouraud set-up of `tri` under `ctx` (`golden::gouraud`); `None` for zero area.
    pub fn gouraud(tri: &ScreenTriangle, ctx: &ShadeContext) -> Option<TriangleJob> {
        golden::gouraud::setup(tri, ctx).map(|g| TriangleJob::new(tri, &g.planes))
    }
}

fn w32(v: u32) -> Bits<32> {
    Bits::<32>::from(v as u64)
}

/// Drive the BVI's load port with `w` (or deassert it).
pub fn apply_bvi_load(uut: &mut IntensityInterpolator, w: Option<&[ChannelWords; 3]>) {
    uut.load.next = w.is_some();
    let z = [ChannelWords::default(); 3];
    let [r, g, b] = w.unwrap_or(&z);
    (
        uut.r_start.next,
        uut.r_short.next,
        uut.r_long.next,
        uut.r_line.next,
    ) = (w32(r.start), w32(r.short), w32(r.long), w32(r.line));
    (
        uut.g_start.next,
        uut.g_short.next,
        uut.g_long.next,
        uut.g_line.next,
    ) = (w32(g.start), w32(g.short), w32(g.long), w32(g.line));
    (
        uut.b_start.next,
        uut.b_short.next,
        uut.b_long.next,
        uut.b_line.next,
    ) = (w32(b.start), w32(b.short), w32(b.long), w32(b.line));
}

/// Drive the BVI's event inputs with one clock of the address block's outputs.
pub fn apply_events(uut: &mut IntensityInterpolator, o: &AddressOutputs) {
    uut.in_valid.next = o.valid;
    uut.in_row_start.next = o.row_start;
    uut.in_step.next = (o.step as u64).into();
    uut.in_carry.next = o.carry;
}

/// BVI outputs in one clock, with the running words RG4 of the three channels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BviOutputs {
    pub valid: bool,
    pub rgb: [u8; 3],
    pub rg4: [u32; 3],
}

pub fn read_bvi(uut: &IntensityInterpolator) -> BviOutputs {
    BviOutputs {
        valid: uut.valid_out.val(),
        rgb: [uut.red.val(), uut.green.val(), uut.blue.val()].map(|v| v.index() as u8),
        rg4: [&uut.chan_r, &uut.chan_g, &uut.chan_b].map(|c| c.rg4.q.val().index() as u32),
    }
}

/// The BVI alone, driven clock by clock by the golden address block's stream for `jobs`
/// (each triangle's BVI set-up loaded in the clock the address block accepts its set-up).
/// Returns the address stream and the BVI's outputs, one entry per clock.
pub fn run_bvi(
    jobs: &[TriangleJob],
    vcd: Option<&mut dyn Write>,
) -> (Vec<AddressOutputs>, Vec<BviOutputs>) {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let stream = run_model(&setups, 1 << 28);
    let mut uut = IntensityInterpolator::default();
    uut.connect_all();
    settle(&mut uut);
    let mut probe = vcd.map(|w| write_vcd_dump(write_vcd_header(w, &uut), &uut));
    let mut out = Vec::with_capacity(stream.len() + 1);
    let mut next = 0;
    // One extra clock at the end to see the last pixel's colour.
    for c in 0..=stream.len() {
        let o = stream.get(c).copied().unwrap_or_default();
        let load = (o.ready && next < jobs.len()).then(|| &jobs[next].words);
        next += load.is_some() as usize;
        apply_bvi_load(&mut uut, load);
        apply_events(&mut uut, &o);
        settle(&mut uut);
        out.push(read_bvi(&uut));
        let t = 20 * c as u64;
        uut.clock.next = true.into();
        settle(&mut uut);
        probe = probe.map(|mut p| {
            p.timestamp(t + 10).ok();
            write_vcd_change(p, &uut)
        });
        uut.clock.next = false.into();
        settle(&mut uut);
        probe = probe.map(|mut p| {
            p.timestamp(t + 20).ok();
            write_vcd_change(p, &uut)
        });
    }
    (stream, out)
}

/// Drive the pipe's load port with `job` (or deassert it).
pub fn apply_pipe_load(uut: &mut GouraudRaster, job: Option<&TriangleJob>) {
    let z = TriangleJob {
        addr: AddressSetup::default(),
        words: [ChannelWords::default(); 3],
    };
    let j = job.unwrap_or(&z);
    uut.load.next = job.is_some();
    let edge = |e: &golden::address_block::EdgeSetup| {
        (
            Bits::<12>::from(e.b0 as u64),
            Bits::<13>::from(e.e0 as u64),
            Bits::<12>::from(e.f_word() as u64),
            Bits::<13>::from(e.r as u64),
            Bits::<13>::from(e.d as u64),
        )
    };
    let s = &j.addr;
    (
        uut.w_b0.next,
        uut.w_e0.next,
        uut.w_f.next,
        uut.w_r.next,
        uut.w_d.next,
    ) = edge(&s.w);
    (
        uut.a_b0.next,
        uut.a_e0.next,
        uut.a_f.next,
        uut.a_r.next,
        uut.a_d.next,
    ) = edge(&s.a);
    (
        uut.t_b0.next,
        uut.t_e0.next,
        uut.t_f.next,
        uut.t_r.next,
        uut.t_d.next,
    ) = edge(&s.t);
    uut.y_top.next = (s.y_top as u64).into();
    uut.rows.next = (s.rows as u64).into();
    uut.y_switch.next = (s.y_switch as u64).into();
    uut.dir_neg.next = s.dir_neg;
    let [r, g, b] = &j.words;
    (
        uut.r_start.next,
        uut.r_short.next,
        uut.r_long.next,
        uut.r_line.next,
    ) = (w32(r.start), w32(r.short), w32(r.long), w32(r.line));
    (
        uut.g_start.next,
        uut.g_short.next,
        uut.g_long.next,
        uut.g_line.next,
    ) = (w32(g.start), w32(g.short), w32(g.long), w32(g.line));
    (
        uut.b_start.next,
        uut.b_short.next,
        uut.b_long.next,
        uut.b_line.next,
    ) = (w32(b.start), w32(b.short), w32(b.long), w32(b.line));
}

/// Counters of one pipe run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PipeStats {
    /// Clocks from the first load to the clock showing the last triangle's `done`, inclusive.
    pub clocks: u64,
    pub pixels: u64,
    pub triangles: u64,
}

impl PipeStats {
    pub fn pixels_per_clock(&self) -> f64 {
        self.pixels as f64 / self.clocks.max(1) as f64
    }
}

/// A connected, settled raster pipe, stepped by hand.
pub struct Pipe {
    pub uut: GouraudRaster,
}

impl Default for Pipe {
    fn default() -> Self {
        Self::new()
    }
}

impl Pipe {
    pub fn new() -> Pipe {
        let mut uut = GouraudRaster::default();
        uut.connect_all();
        settle(&mut uut);
        Pipe { uut }
    }

    /// Run `jobs` through the pipe, each loaded as soon as `ready` is high; `pixel(x, y, rgb)`
    /// for every valid output, `progress(done_triangles)` after each triangle's `done`. Stops
    /// after the last `done` or `max_clocks` (then `Err` with the stats so far).
    pub fn run(
        &mut self,
        jobs: &[TriangleJob],
        max_clocks: u64,
        mut pixel: impl FnMut(u32, u32, [u8; 3]),
        mut progress: impl FnMut(u64),
    ) -> Result<PipeStats, PipeStats> {
        let uut = &mut self.uut;
        let mut st = PipeStats::default();
        let mut next = 0;
        if jobs.is_empty() {
            return Ok(st);
        }
        loop {
            let load = (uut.ready.val() && next < jobs.len()).then(|| &jobs[next]);
            next += load.is_some() as usize;
            apply_pipe_load(uut, load);
            settle(uut);
            st.clocks += 1;
            if uut.valid.val() {
                st.pixels += 1;
                let rgb = [uut.red.val(), uut.green.val(), uut.blue.val()];
                pixel(
                    uut.x.val().index() as u32,
                    uut.y.val().index() as u32,
                    rgb.map(|v| v.index() as u8),
                );
            }
            if uut.done.val() {
                st.triangles += 1;
                progress(st.triangles);
                if st.triangles == jobs.len() as u64 {
                    return Ok(st);
                }
            }
            if st.clocks >= max_clocks {
                return Err(st);
            }
            uut.clock.next = true.into();
            settle(uut);
            uut.clock.next = false.into();
            settle(uut);
        }
    }
}

/// A clock budget for `jobs`: all rows and bounding-box pixels plus latency, so a hung pipe
/// stops instead of spinning.
pub fn clock_budget(jobs: &[TriangleJob]) -> u64 {
    jobs.iter().map(|j| 8 + j.addr.rows as u64 * 4097).sum()
}
