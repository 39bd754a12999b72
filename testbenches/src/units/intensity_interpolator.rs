//! Bench of the intensity interpolator BVI (`rtl::units::intensity_interpolator`) against the golden
//! f64 BVI (`golden::units::intensity_interpolator`) and its bit-exact twin on the shared harness, and
//! of the Gouraud raster pipe (`rtl::pipelines::gouraud_raster`: address block + BVI; its render driver is
//! `pipeline::gouraud`).
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

use crate::harness::{CheckSpec, Compare, Expected, Failure, Report, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::address_block::{
    stimulus_subpixel, subpixel_triangle_jobs, triangle_jobs, triangle_run, GoldenPixel,
    TriangleRun,
};
use golden::shade::to_u8;
use golden::units::address_block::{AddressBlockModel, AddressOutputs, AddressSetup};
use golden::units::intensity_interpolator::{error_bound, saturate, BviTwin, ChannelWords};
use pipeline::gouraud::{pipe_row, row_setup, row_words, words_row, TriangleJob, PIPE_HOLD_AT};
use rtl::core::registry::NoParams;
use rtl::pipelines::gouraud_raster::GouraudRaster;
use rtl::units::intensity_interpolator::IntensityInterpolator;

pub use rtl::core::fixed::{INTENSITY, LEVEL};

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

/// The address block's event a BVI input row carries (`row[13..17]`: valid, row_start,
/// step, carry), the inverse of [`bvi_row`]'s tail.
pub fn row_event(row: &[u64]) -> AddressOutputs {
    AddressOutputs {
        valid: row[13] != 0,
        row_start: row[14] != 0,
        step: row[15] as u8,
        carry: row[16] != 0,
        ..Default::default()
    }
}

/// The BVI's input rows for `jobs`: the golden address block's stream (plus one idle clock to
/// see the last colour), each triangle's words loaded in the clock the address block accepts
/// its set-up. Returns the rows and the address stream they carry.
pub fn bvi_rows(jobs: &[TriangleJob]) -> (Vec<Vec<u64>>, Vec<AddressOutputs>) {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let st = stimulus_subpixel(&setups);
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
    let st = stimulus_subpixel(&setups);
    let mut rows = Vec::with_capacity(st.rows.len() + 2);
    let mut next = 0;
    for c in 0..st.rows.len() + 2 {
        let load = (st.loads.get(next) == Some(&c)).then(|| &jobs[next]);
        next += load.is_some() as usize;
        rows.push(pipe_row(load));
    }
    rows
}

/// The BVI alone, driven by the golden address block's stream for `jobs` (each triangle's
/// BVI set-up loaded in the clock the address block accepts it), compared every clock with
/// `golden` (one entry per pixel, in stream order; see the module doc for the tolerances).
pub fn check_bvi(
    name: &str,
    seed: u64,
    jobs: &[TriangleJob],
    golden: &[GoldenPixel],
) -> Result<Report, Box<Failure>> {
    let (rows, expected, compare) = bvi_run(jobs, golden);
    let spec = CheckSpec {
        name: name.into(),
        seed,
        compare,
    };
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

/// The BVI's word tolerance for `golden` (module doc): the run's largest per-pixel bound, and
/// its RMS.
fn word_tolerance(golden: &[GoldenPixel]) -> Tolerance {
    let bounds: Vec<f64> = golden.iter().map(|g| error_bound(g.1) + 1e-6).collect();
    Tolerance {
        max_abs: bounds.iter().copied().fold(0.0, f64::max).max(1e-6),
        rms: (bounds.iter().map(|b| b * b).sum::<f64>() / bounds.len().max(1) as f64)
            .sqrt()
            .max(1e-6),
    }
}

/// 8-bit outputs: within 1 LSB of the rounded, clamped golden value.
pub const LEVEL_1LSB: Compare = Compare::Fixed {
    format: LEVEL,
    tol: Tolerance {
        max_abs: 1.0,
        rms: 1.0,
    },
};

/// Expected colours of one output clock: the next golden pixel when `valid`, else don't care.
fn colour_expectations(
    valid: bool,
    golden: &mut std::slice::Iter<'_, GoldenPixel>,
    words: bool,
) -> Vec<Expected> {
    let n = if words { 6 } else { 3 };
    if !valid {
        return vec![Expected::DontCare; n];
    }
    let (v, _) = golden
        .next()
        .expect("golden pixels and address stream disagree");
    let mut e: Vec<Expected> = v.map(|x| Expected::Real(to_u8(x) as f64)).to_vec();
    if words {
        // RG4 carries the +½ LSB rounding bias.
        e.extend(v.map(|x| Expected::Real(x + 0.5)));
    }
    e
}

/// BVI, driven by the golden address block's stream: the colour of event c in clock c + L.
pub fn bvi_run(jobs: &[TriangleJob], golden: &[GoldenPixel]) -> TriangleRun {
    let lat = IntensityInterpolator::LATENCY;
    let (rows, stream) = bvi_rows(jobs);
    let mut g = golden.iter();
    let expected: Vec<Vec<Expected>> = (0..rows.len())
        .map(|c| {
            let valid = c >= lat && stream[c - lat].valid;
            let mut e = vec![Expected::Word(valid as u64)];
            e.extend(colour_expectations(valid, &mut g, true));
            e
        })
        .collect();
    assert!(g.next().is_none(), "golden pixels left over");
    let word = Compare::Fixed {
        format: INTENSITY,
        tol: word_tolerance(golden),
    };
    let compare = vec![
        Compare::Exact,
        LEVEL_1LSB,
        LEVEL_1LSB,
        LEVEL_1LSB,
        word,
        word,
        word,
    ];
    (rows, expected, compare)
}

/// Raster pipe: the address block's cycle model, loaded in the clocks [`pipe_rows`] loads; the
/// pipe shows `ready` as is and the address stream one BVI latency later, with its colours.
pub fn pipe_run(jobs: &[TriangleJob], golden: &[GoldenPixel]) -> TriangleRun {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let rows = pipe_rows(jobs);
    let delay = IntensityInterpolator::LATENCY;
    let mut m = AddressBlockModel::subpixel();
    let mut addr: Vec<AddressOutputs> = Vec::with_capacity(rows.len());
    let mut next = 0;
    for row in &rows {
        let o = m.outputs();
        let load = (row[0] != 0).then(|| &setups[next]);
        next += load.is_some() as usize;
        addr.push(o);
        m.clock(load);
    }
    let mut g = golden.iter();
    let expected: Vec<Vec<Expected>> = (0..rows.len())
        .map(|c| {
            let d = match c.checked_sub(delay) {
                Some(k) => addr[k],
                None => AddressOutputs::default(),
            };
            let w = |v: u32| Expected::Word(v as u64);
            let mut e = vec![w(addr[c].ready as u32), w(d.valid as u32), w(d.x), w(d.y)];
            e.extend(colour_expectations(d.valid, &mut g, false));
            e.push(w(d.done as u32));
            e
        })
        .collect();
    assert!(g.next().is_none(), "golden pixels left over");
    let mut compare = vec![Compare::Exact; 8];
    compare[4..7].copy_from_slice(&[LEVEL_1LSB; 3]);
    (rows, expected, compare)
}

/// The BVI's twin output row.
fn bvi_outputs(t: &BviTwin) -> Vec<u64> {
    let (v, levels, words) = t.outputs();
    let mut o = vec![v as u64];
    o.extend(levels.map(u64::from));
    o.extend(words.map(u64::from));
    o
}

/// Row adapter of [`BviTwin`] (inputs `load`, twelve words, valid, row_start, step, carry).
struct BviRows(BviTwin);

impl Twin for BviRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let o = bvi_outputs(&self.0);
        let w = row_words(r, 1);
        self.0.clock((r[0] != 0).then_some(&w), &row_event(r));
        o
    }
}

/// Twin of the raster pipe: the address block's cycle model (with its `hold`) feeding
/// [`BviTwin`] (loaded on the accepted load), with x, y and done delayed one clock beside the
/// BVI.
pub struct PipeRows {
    addr: AddressBlockModel,
    bvi: BviTwin,
    xy_done: (u32, u32, bool),
}

impl Default for PipeRows {
    /// The raster pipe's address block is the sub-pixel one (20-bit error words).
    fn default() -> Self {
        PipeRows {
            addr: AddressBlockModel::subpixel(),
            bvi: BviTwin::default(),
            xy_done: (0, 0, false),
        }
    }
}

impl Twin for PipeRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[PIPE_HOLD_AT] != 0;
        let a = self.addr.outputs_held(hold);
        let (valid, levels, _) = self.bvi.outputs();
        let (x, y, done) = self.xy_done;
        let mut o = vec![a.ready as u64, valid as u64, x as u64, y as u64];
        o.extend(levels.map(u64::from));
        o.push(done as u64);
        let setup = row_setup(r);
        let words = row_words(r, 20);
        let accepted = setup.is_some() && a.ready;
        self.bvi.clock(accepted.then_some(&words), &a);
        self.xy_done = (a.x, a.y, a.done);
        self.addr.clock_held(setup.as_ref(), hold);
        o
    }
}

/// The BVI and the raster pipe share their bench: seeded triangles with random vertex
/// intensities, run as `$run` builds them, checked against `$twin`.
macro_rules! triangle_bench {
    ($block:ty, $jobs:ident, $run:ident, $twin:expr) => {
        impl Bench for $block {
            const ITEMS: &'static str = "triangles";
            const DEFAULT_ITEMS: usize = 20;
            fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
                let (jobs, golden) = $jobs(seed, n);
                triangle_run($run(&jobs, &golden))
            }
            fn twin(_: &NoParams) -> Box<dyn Twin> {
                Box::new($twin)
            }
        }
    };
}

triangle_bench!(
    IntensityInterpolator,
    triangle_jobs,
    bvi_run,
    BviRows(BviTwin::default())
);
triangle_bench!(
    GouraudRaster,
    subpixel_triangle_jobs,
    pipe_run,
    PipeRows::default()
);
