//! Bench of the intensity interpolator BVI (`rtl::intensity_interpolator`) against the golden
//! f64 BVI (`golden::intensity_interpolator`) on the shared harness, and the driver of the whole
//! Gouraud raster pipe (`rtl::gouraud_raster`: address block + BVI) that renders triangles
//! through the RTL.
//!
//! # Tolerances (derived from the formats, see the RTL header)
//!
//! - `valid_out`: exact (the address block's `valid` one clock later).
//! - `red_word` … `blue_word` (signed Q16.16, +½ bias): a pixel reached by `n` additions is
//!   within `n·2⁻¹⁷` of I + ½ (each quantized term is off by ≤ 2⁻¹⁷), plus 1e-6 for the f64
//!   golden itself on giant-gradient slivers. The harness checks the run's largest bound every
//!   clock and RMS ≤ √(mean bound²); [`check_words`] then checks each pixel's own bound.
//! - `red` … `blue` (8 bits): within 1 LSB of the golden value rounded and clamped (the word's
//!   error is < ½ LSB, so rounding can differ by at most one step); and [`check_words`] requires
//!   them to equal the saturated word exactly.

use crate::address_block::{setup_row, stimulus};
use crate::harness::{CheckSpec, Compare, Expected, Failure, QFormat, Report, Stepper, Tolerance};
use crate::impl_dut;
use golden::address_block::{AddressOutputs, AddressSetup};
use golden::intensity_interpolator::{self as gbvi, error_bound, saturate, ChannelWords};
use golden::shade::{to_u8, ShadeContext};
use golden::types::{Plane, ScreenTriangle};
use rtl::gouraud_raster::GouraudRaster;
use rtl::intensity_interpolator::IntensityInterpolator;
use std::io::Write;

impl_dut!(IntensityInterpolator, clock: clock,
    inputs: [load, r_start, r_short, r_long, r_line, g_start, g_short, g_long, g_line,
             b_start, b_short, b_long, b_line, in_valid, in_row_start, in_step, in_carry],
    outputs: [valid_out, red, green, blue, red_word, green_word, blue_word]);

impl_dut!(GouraudRaster, clock: clock,
    inputs: [load, w_b0, w_e0, w_f, w_r, w_d, a_b0, a_e0, a_f, a_r, a_d,
             t_b0, t_e0, t_f, t_r, t_d, y_top, rows, y_switch, dir_neg,
             r_start, r_short, r_long, r_line, g_start, g_short, g_long, g_line,
             b_start, b_short, b_long, b_line],
    outputs: [ready, valid, x, y, red, green, blue, done]);

/// Format of the BVI's words (`rtl::intensity_interpolator` header).
pub const INTENSITY: QFormat = QFormat::signed(16, 16);
/// The 8-bit outputs read as integers.
pub const LEVEL: QFormat = QFormat::unsigned(8, 0);

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

fn words_row(w: Option<&[ChannelWords; 3]>) -> Vec<u64> {
    let z = [ChannelWords::default(); 3];
    w.unwrap_or(&z)
        .iter()
        .flat_map(|c| [c.start, c.short, c.long, c.line].map(u64::from))
        .collect()
}

/// The BVI's input row of one clock: `load` + words, then the address block's event.
pub fn bvi_row(w: Option<&[ChannelWords; 3]>, o: &AddressOutputs) -> Vec<u64> {
    let mut row = vec![w.is_some() as u64];
    row.extend(words_row(w));
    row.extend([
        o.valid as u64,
        o.row_start as u64,
        o.step as u64,
        o.carry as u64,
    ]);
    row
}

/// The BVI's input rows for `jobs`: the golden address block's stream (plus one idle clock to
/// see the last colour), each triangle's words loaded in the clock the address block accepts
/// its set-up. Returns the rows and the address stream they carry.
pub fn bvi_rows(jobs: &[TriangleJob]) -> (Vec<Vec<u64>>, Vec<AddressOutputs>) {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let st = stimulus(&setups);
    let mut stream = st.expected;
    stream.push(AddressOutputs::default());
    let mut rows = Vec::with_capacity(stream.len());
    let mut next = 0;
    for (c, o) in stream.iter().enumerate() {
        let load = (st.loads.get(next) == Some(&c)).then(|| &jobs[next].words);
        next += load.is_some() as usize;
        rows.push(bvi_row(load, o));
    }
    (rows, stream)
}

/// The pipe's input rows for `jobs`, loads in the clocks the golden address block accepts
/// them (the pipe's `ready` is the address block's), plus two idle clocks to flush.
pub fn pipe_rows(jobs: &[TriangleJob]) -> Vec<Vec<u64>> {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let st = stimulus(&setups);
    let mut rows = Vec::with_capacity(st.rows.len() + 2);
    let mut next = 0;
    for c in 0..st.rows.len() + 2 {
        let load = (st.loads.get(next) == Some(&c)).then(|| &jobs[next]);
        next += load.is_some() as usize;
        rows.push(pipe_row(load));
    }
    rows
}

/// The golden value of every pixel of `jobs`' walks, in stream order: per channel f64
/// intensity (no bias) and the number of additions that reach it.
pub type GoldenPixel = ([f64; 3], u32);

/// The BVI alone, driven by the golden address block's stream for `jobs` (each triangle's
/// BVI set-up loaded in the clock the address block accepts it), compared every clock with
/// `golden` (one entry per pixel, in stream order; see the module doc for the tolerances).
pub fn check_bvi(
    name: &str,
    seed: u64,
    jobs: &[TriangleJob],
    golden: &[GoldenPixel],
) -> Result<Report, Box<Failure>> {
    let (rows, stream) = bvi_rows(jobs);
    let bounds: Vec<f64> = golden.iter().map(|g| error_bound(g.1) + 1e-6).collect();
    let max_bound = bounds.iter().copied().fold(0.0, f64::max).max(1e-6);
    let rms_bound = (bounds.iter().map(|b| b * b).sum::<f64>() / bounds.len().max(1) as f64)
        .sqrt()
        .max(1e-6);
    let word = Compare::Fixed {
        format: INTENSITY,
        tol: Tolerance {
            max_abs: max_bound,
            rms: rms_bound,
        },
    };
    let level = Compare::Fixed {
        format: LEVEL,
        tol: Tolerance {
            max_abs: 1.0,
            rms: 1.0,
        },
    };
    let spec = CheckSpec {
        name: name.into(),
        seed,
        compare: vec![Compare::Exact, level, level, level, word, word, word],
    };
    let mut expected = Vec::with_capacity(rows.len());
    let mut k = 0;
    for c in 0..rows.len() {
        let valid = c > 0 && stream[c - 1].valid;
        let mut e = vec![Expected::Word(valid as u64)];
        if valid {
            let (v, _) = golden[k];
            k += 1;
            e.extend(v.map(|x| Expected::Real(to_u8(x) as f64)));
            e.extend(v.map(|x| Expected::Real(x + 0.5)));
        } else {
            e.extend([Expected::DontCare; 6]);
        }
        expected.push(e);
    }
    assert_eq!(k, golden.len(), "golden pixels and address stream disagree");
    crate::harness::run_rows(IntensityInterpolator::default, &spec, &rows, &expected)
        .map_err(Box::new)
}

/// Per-pixel checks on a passed [`check_bvi`] report: each word within its own bound, and the
/// 8-bit outputs equal to the saturated words. Returns (max |err|, RMS err, max err/bound).
pub fn check_words(report: &Report, golden: &[GoldenPixel]) -> Result<(f64, f64, f64), String> {
    let (mut max, mut sum_sq, mut ratio, mut n) = (0.0f64, 0.0, 0.0f64, 0usize);
    let mut k = 0;
    for (c, o) in report.outputs.iter().enumerate() {
        if o[0] == 0 {
            continue;
        }
        let (v, adds) = golden[k];
        k += 1;
        let bound = error_bound(adds) + 1e-6;
        for ch in 0..3 {
            let w = o[4 + ch] as u32;
            let err = INTENSITY.to_f64(w as u64) - 0.5 - v[ch];
            if err.abs() > bound {
                return Err(format!(
                    "[{}] cycle {c}: word[{ch}] {:.6} not within {bound:.3e} of {:.6} ({adds} additions)",
                    report.name,
                    INTENSITY.to_f64(w as u64),
                    v[ch] + 0.5
                ));
            }
            if o[1 + ch] != saturate(w) as u64 {
                return Err(format!(
                    "[{}] cycle {c}: level[{ch}] {} is not the saturated word {}",
                    report.name,
                    o[1 + ch],
                    saturate(w)
                ));
            }
            max = max.max(err.abs());
            ratio = ratio.max(err.abs() / bound);
            sum_sq += err * err;
            n += 1;
        }
    }
    Ok((max, (sum_sq / n.max(1) as f64).sqrt(), ratio))
}

/// The pipe's input row: `load`, the address set-up, the twelve BVI words.
pub fn pipe_row(job: Option<&TriangleJob>) -> Vec<u64> {
    let mut row = setup_row(job.map(|j| &j.addr));
    row.extend(words_row(job.map(|j| &j.words)));
    row
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

/// The raster pipe, stepped by hand through the harness's [`Stepper`].
pub struct Pipe {
    stepper: Stepper<GouraudRaster>,
}

impl Pipe {
    pub fn new() -> Result<Pipe, String> {
        Ok(Pipe {
            stepper: Stepper::new(GouraudRaster::default())?,
        })
    }

    /// Trace every following clock into `w`.
    pub fn start_vcd(&mut self, w: Box<dyn Write>) {
        self.stepper.start_vcd(w);
    }

    /// Run `jobs` through the pipe, each loaded as soon as `ready` is high;
    /// `pixel(job_index, x, y, rgb)` for every valid output (the pipe keeps the jobs' order,
    /// so the index counts the `done` markers seen before the pixel), `progress(done_triangles)` after each triangle's `done`. Stops
    /// after the last `done`, or with an error after `max_clocks`.
    pub fn run(
        &mut self,
        jobs: &[TriangleJob],
        max_clocks: u64,
        mut pixel: impl FnMut(usize, u32, u32, [u8; 3]),
        mut progress: impl FnMut(u64),
    ) -> Result<PipeStats, String> {
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
            let load = (self.stepper.dut().ready.val() && next < jobs.len()).then(|| &jobs[next]);
            next += load.is_some() as usize;
            match load {
                Some(j) => self.stepper.step(&pipe_row(Some(j)), &mut out)?,
                None => self.stepper.step(&idle, &mut out)?,
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
        self.stepper.stop_vcd();
        Ok(st)
    }
}

/// A clock budget for `jobs`: every row at the full line length plus latency, so a hung pipe
/// stops instead of spinning.
pub fn clock_budget(jobs: &[TriangleJob]) -> u64 {
    jobs.iter().map(|j| 8 + j.addr.rows as u64 * 4097).sum()
}
