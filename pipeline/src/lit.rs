//! The lit pixel pipeline (`rtl::pipelines::pixel_pipeline`) as a render driver: per-triangle set-up in
//! software (address block set-up, the normal planes' Q3.29 words, the depth plane's Q16.16
//! words), per-frame registers (L, H, n, colour weights), fragments out in hardware order.
//!
//! Row layout (the top's input ports in order): `load`, the address set-up (19 words, as
//! [`crate::gouraud::setup_row`]), the normal words (x, y, z × start short long line), the
//! depth words (start short long line), then the shading registers (lx ly lz hx hy hz n,
//! amb r g b, dif r g b, spc r g b). Outputs: ready, valid, x, y, z, red, green, blue, done.

use std::io::Write;

use golden::methods::Method;
use golden::shade::{LightingModel, ShadeContext};
use golden::types::ScreenTriangle;
use golden::units::address_block::AddressSetup;
use golden::units::colour_combine::Weights;
use golden::units::intensity_interpolator::{ChannelSetup, ChannelWords};
use golden::units::vector_interpolator as gvi;
use rtl::core::fixed::NORMAL;
use rtl::core::registry::{BlockParams, Options, RtlBlock};
use rtl::core::sim::Model;
use rtl::pipelines::pixel_pipeline::PixelPipeline;

use flow::engine::Sim;

use crate::axis::PipeStats;
use crate::axis::{balanced_order_of, with_last, Word};
use crate::gouraud::{row_setup, setup_row};
use rtl::stream::layout::{pack, REGISTERS, TRIANGLE};

/// Input words per row: load + 19 address + 12 normal + 4 depth + 16 registers + hold.
pub const ROW_WIDTH: usize = 53;
/// Where `hold` (the address block's stall) is.
pub const HOLD_AT: usize = 52;
/// Where the normal words start in a row.
pub const NORMAL_AT: usize = 20;
/// Where the depth words start.
pub const DEPTH_AT: usize = 32;
/// Where the shading registers start.
pub const REGS_AT: usize = 36;
/// Largest |vertex depth| the depth words hold with margin (signed Q16.16 holds ±2¹⁵).
pub const DEPTH_LIMIT: f64 = 16384.0;

/// The methods the lit pipeline renders, with their build options.
pub const LIT_METHODS: [Method; 7] = [
    Method::Normalizer,
    Method::NormalizerFit,
    Method::NormalizerPw,
    Method::BrdfK4,
    Method::BrdfK8,
    Method::BrdfK16,
    Method::Bump,
];

/// The pipeline build (`coeffs`, `power`) that computes `method`; `None` if it does not.
pub fn method_options(method: Method) -> Option<Options> {
    let (c, p, b) = match method {
        Method::Normalizer => ("published", "exact", "off"),
        Method::NormalizerFit => ("fit", "exact", "off"),
        Method::NormalizerPw => ("piecewise", "exact", "off"),
        Method::BrdfK4 => ("fit", "w4", "off"),
        Method::BrdfK8 => ("fit", "w8", "off"),
        Method::BrdfK16 => ("fit", "w16", "off"),
        Method::Bump => ("fit", "exact", "on"),
        _ => return None,
    };
    Some(
        Options::new()
            .with("coeffs", c)
            .with("power", p)
            .with("bump", b),
    )
}

/// The build parameters of `method`'s pipeline; an error names the methods it has.
fn pipeline_params(method: Method) -> Result<<PixelPipeline as RtlBlock>::Params, String> {
    let o = method_options(method).ok_or_else(|| {
        format!(
            "the RTL pixel pipeline does not compute {method} (it has: {})",
            LIT_METHODS.map(|m| m.name()).join(", ")
        )
    })?;
    <PixelPipeline as RtlBlock>::Params::from_options(&o)
}

/// The shading registers of a frame: L, H (signed Q2.14), n, the nine colour weights.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShadingRegs {
    pub light: [u64; 3],
    pub half: [u64; 3],
    pub n: u64,
    pub weights: [u64; 9],
}

impl ShadingRegs {
    /// The registers of `ctx`. Errors (one line): Phong lighting (not in hardware), a colour
    /// weight beyond the Q8.8 register.
    pub fn of(ctx: &ShadeContext) -> Result<ShadingRegs, String> {
        if ctx.lighting == LightingModel::Phong {
            return Err("the RTL pipeline lights with blinn or lambert; phong (R·V) is not built in hardware".into());
        }
        ctx.validate().map_err(|e| e.to_string())?;
        let q = |v: glam::DVec3| v.to_array().map(|c| NORMAL.quantize(c));
        Ok(ShadingRegs {
            light: q(ctx.light),
            half: q(ctx.half()),
            n: ctx.n() as u64,
            weights: Weights::of(ctx).words().map_err(|e| e.to_string())?,
        })
    }

    /// The sixteen register words in row order.
    pub fn row(&self) -> Vec<u64> {
        let mut r = self.light.to_vec();
        r.extend(self.half);
        r.push(self.n);
        r.extend(self.weights);
        r
    }
}

/// One triangle's set-up for the lit pipeline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LitJob {
    pub addr: AddressSetup,
    pub normal: [ChannelWords; 3],
    pub depth: ChannelWords,
}

impl LitJob {
    /// Set-up of `tri`; `None` for zero area. Error: a vertex depth beyond ±[`DEPTH_LIMIT`].
    pub fn new(tri: &ScreenTriangle) -> Result<Option<LitJob>, String> {
        check_depths(tri)?;
        let (Some(np), Some(dp)) = (tri.normal_plane(), tri.depth_plane()) else {
            return Ok(None);
        };
        let addr = AddressSetup::new(tri);
        Ok(Some(LitJob {
            addr,
            normal: gvi::setup(&[np.x, np.y, np.z], &addr),
            depth: depth_words(&ChannelSetup::new(&dp, &addr)),
        }))
    }
}

/// Check that every vertex depth of `tri` fits the depth words (±[`DEPTH_LIMIT`]); the
/// one-line error names the depth. Shared by every pipeline's set-up.
pub fn check_depths(tri: &ScreenTriangle) -> Result<(), String> {
    match tri
        .v
        .iter()
        .find(|v| v.z.is_nan() || v.z.abs() >= DEPTH_LIMIT)
    {
        Some(v) => Err(format!(
            "vertex depth {} is outside the depth words' range ±{DEPTH_LIMIT}",
            v.z
        )),
        None => Ok(()),
    }
}

/// The depth plane's words: signed Q16.16 in pixels (the camera fit's depth), rounded to nearest, without the
/// BVI's +½ display bias (depth is compared, never displayed).
pub fn depth_words(s: &ChannelSetup) -> ChannelWords {
    use golden::units::intensity_interpolator::quantize;
    ChannelWords {
        start: quantize(s.start),
        short: quantize(s.short),
        long: quantize(s.long),
        line: quantize(s.line),
    }
}

fn channel(w: &ChannelWords) -> [u64; 4] {
    [w.start, w.short, w.long, w.line].map(u64::from)
}

/// The pipeline's input row: `load` with a job's set-up (or idle), then the registers.
pub fn lit_row(job: Option<&LitJob>, regs: &ShadingRegs) -> Vec<u64> {
    let mut row = setup_row(job.map(|j| &j.addr));
    let z = [ChannelWords::default(); 3];
    for c in job.map_or(&z, |j| &j.normal) {
        row.extend(channel(c));
    }
    row.extend(channel(job.map_or(&z[0], |j| &j.depth)));
    row.extend(regs.row());
    row.push(0);
    debug_assert_eq!(row.len(), ROW_WIDTH);
    row
}

/// The inverse of [`lit_row`]: the job a row loads (if `load`) and the registers.
pub fn row_job(row: &[u64]) -> (Option<LitJob>, ShadingRegs) {
    let words = |at: usize| ChannelWords {
        start: row[at] as u32,
        short: row[at + 1] as u32,
        long: row[at + 2] as u32,
        line: row[at + 3] as u32,
    };
    let job = row_setup(row).map(|addr| LitJob {
        addr,
        normal: [0, 1, 2].map(|c| words(NORMAL_AT + 4 * c)),
        depth: words(DEPTH_AT),
    });
    let r = &row[REGS_AT..];
    let regs = ShadingRegs {
        light: [r[0], r[1], r[2]],
        half: [r[3], r[4], r[5]],
        n: r[6],
        weights: std::array::from_fn(|i| r[7 + i]),
    };
    (job, regs)
}

/// One fragment out of the pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fragment {
    /// Index of the triangle (jobs keep their order).
    pub job: usize,
    pub x: u32,
    pub y: u32,
    /// Depth word, signed Q16.16 (+½ LSB bias).
    pub z: i32,
    pub rgb: [u8; 3],
    /// The clock (0 = the run's first) whose outputs show the fragment.
    pub clock: u64,
}

impl Fragment {
    /// The fragment of a stream top's beat `b` of triangle `job`, shown in `clock`.
    pub fn of_beat(job: usize, b: crate::axis::Beat, clock: u64) -> Fragment {
        Fragment {
            job,
            x: b.x,
            y: b.y,
            z: b.z,
            rgb: b.rgb,
            clock,
        }
    }
}

/// The lit pipeline, `pixel-pipeline` or its AXI4-Stream top `pixel-stream`, on either
/// simulator ([`flow::engine::Sim`]).
pub struct LitPipe {
    model: Box<dyn Model>,
    /// `pixel-stream` (records in, beats out) rather than `pixel-pipeline`'s ports.
    stream: bool,
}

impl LitPipe {
    /// The pipeline built for `method` (one of [`LIT_METHODS`]), on rust-hdl.
    pub fn new(method: Method) -> Result<LitPipe, String> {
        LitPipe::on(method, Sim::RustHdl, false)
    }

    /// The AXI4-Stream top `pixel-stream` built for `method`, on rust-hdl: [`LitPipe::run`]
    /// sends the register record and every triangle record on its set-up stream (one word per
    /// clock while `s_axis_tready`) and takes every fragment beat (`m_axis_tready` high).
    pub fn stream(method: Method) -> Result<LitPipe, String> {
        LitPipe::on(method, Sim::RustHdl, true)
    }

    /// `pixel-pipeline` (or `pixel-stream` if `stream`) built for `method`, on `sim`.
    pub fn on(method: Method, sim: Sim, stream: bool) -> Result<LitPipe, String> {
        let p = pipeline_params(method)?;
        let model = if stream {
            flow::engine::model::<rtl::stream::pixel_stream::PixelStream>(&p, sim)?
        } else {
            flow::engine::model::<PixelPipeline>(&p, sim)?
        };
        Ok(LitPipe { model, stream })
    }

    /// The design [`LitPipe::on`] builds under Verilator (to compile ahead of a run).
    pub fn design(method: Method, stream: bool) -> Result<verilated::Design, String> {
        let p = pipeline_params(method)?;
        Ok(if stream {
            flow::engine::design::<rtl::stream::pixel_stream::PixelStream>(&p)
        } else {
            flow::engine::design::<PixelPipeline>(&p)
        })
    }

    /// Trace every following clock into `w` (rust-hdl only: an error on Verilator).
    pub fn start_vcd(&mut self, w: Box<dyn Write>) -> Result<(), String> {
        self.model.start_vcd(w)
    }

    /// The simulated top, for a caller that steps it itself.
    pub fn model(&mut self) -> &mut dyn Model {
        self.model.as_mut()
    }

    /// Run `jobs` with registers `regs`, each job loaded as soon as `ready` is high;
    /// `fragment` for every valid output, `progress(done_triangles)` after each `done`.
    /// Stops after the last `done`, or with an error after `max_clocks`.
    pub fn run(
        &mut self,
        jobs: &[LitJob],
        regs: &ShadingRegs,
        max_clocks: u64,
        mut fragment: impl FnMut(Fragment),
        mut progress: impl FnMut(u64),
    ) -> Result<PipeStats, String> {
        if self.stream {
            return crate::axis::drive::<rtl::stream::pixel_stream::PixelStream>(
                self.model.as_mut(),
                "pixel-stream",
                "triangles",
                &crate::lit::scene_words(jobs, regs),
                jobs.len() as u64,
                max_clocks,
                &mut |job, b, clock| fragment(Fragment::of_beat(job, b, clock)),
                &mut progress,
            );
        }
        let idle = lit_row(None, regs);
        run_ports(
            self.model.as_mut(),
            "pixel pipeline",
            jobs.len(),
            9,
            &idle,
            &mut |k, _| k.map(|k| lit_row(Some(&jobs[k]), regs)),
            max_clocks,
            &mut fragment,
            &mut progress,
        )
    }
}

/// The run loop of a top with `pixel-pipeline`'s outputs (ready, valid, x, y, z, r, g, b,
/// done, then any more: `outputs` in all) on its ports: job k loaded (`row(Some(k), model)`)
/// as soon as `ready` is high, rows without a load (`row(None, model)`) otherwise (`model`
/// for the row to peek at further outputs that are functions of registers; a `None` row is
/// `idle`, so that an idle clock builds no row); `fragment` for every valid output, `progress(done_triangles)`
/// after each `done`. Stops after the last `done`, or with an error naming `what` after
/// `max_clocks`. Shared by `LitPipe` and `crate::textured::TexturedPipe`.
pub fn run_ports(
    model: &mut dyn Model,
    what: &str,
    jobs: usize,
    outputs: usize,
    idle: &[u64],
    row: &mut dyn FnMut(Option<usize>, &dyn Model) -> Option<Vec<u64>>,
    max_clocks: u64,
    fragment: &mut dyn FnMut(Fragment),
    progress: &mut dyn FnMut(u64),
) -> Result<PipeStats, String> {
    let mut st = PipeStats::default();
    let mut out = vec![0u64; outputs];
    let mut next = 0;
    while st.triangles < jobs as u64 {
        if st.clocks >= max_clocks {
            return Err(format!(
                "{what}: {} of {jobs} triangles done after {max_clocks} clocks",
                st.triangles
            ));
        }
        // `ready` (output 0) is a function of registers: settled before the clock's step.
        let ready = model.peek(0) != 0;
        let r = if ready && next < jobs {
            next += 1;
            row(Some(next - 1), &*model)
        } else {
            row(None, &*model)
        };
        model.step(r.as_deref().unwrap_or(idle), &mut out)?;
        st.clocks += 1;
        if out[1] != 0 {
            st.pixels += 1;
            fragment(Fragment {
                job: st.triangles as usize,
                x: out[2] as u32,
                y: out[3] as u32,
                z: out[4] as u32 as i32,
                rgb: [out[5] as u8, out[6] as u8, out[7] as u8],
                clock: st.clocks - 1,
            });
        }
        if out[8] != 0 {
            st.triangles += 1;
            progress(st.triangles);
        }
    }
    model.stop_vcd()?;
    Ok(st)
}

/// A clock budget for `jobs` (every row at full length plus the pipeline's latency).
pub fn lit_clock_budget(jobs: &[LitJob]) -> u64 {
    jobs.iter()
        .map(|j| 8 + j.addr.rows as u64 * 4097)
        .sum::<u64>()
        + PixelPipeline::LATENCY as u64
}

/// The triangle record of `job` (the same field values `pixel-pipeline`'s load row carries).
pub fn triangle_record(job: &LitJob) -> Vec<Word> {
    let row = lit_row(Some(job), &ShadingRegs::default());
    with_last(pack(&TRIANGLE, &row[1..REGS_AT]))
}

/// The register record of `regs`.
pub fn register_record(regs: &ShadingRegs) -> Vec<Word> {
    with_last(pack(&REGISTERS, &regs.row()))
}

/// A scene's set-up stream: the registers, then every triangle.
pub fn scene_words(jobs: &[LitJob], regs: &ShadingRegs) -> Vec<Word> {
    let mut w = register_record(regs);
    for j in jobs {
        w.extend(triangle_record(j));
    }
    w
}

/// The order in which the driver sends `jobs` on the set-up stream (indices into `jobs`):
/// largest walk first, then smallest, then the second largest, the second smallest, and so
/// on.
///
/// Why: a triangle record is 27 words at one word per clock, so a triangle whose walk is
/// shorter than that waits for its set-up, and a mesh sends its small triangles in runs (a
/// sphere's silhouette and poles). The default scene in mesh order gives `pixel-stream` 0.879
/// fragments per clock against `pixel-pipeline`'s 0.986; more buffering cannot fix it (a model
/// of the banks with 1 000 records gives about 0.95, the stall being a run of 27-word records
/// at the front). Pairing each small triangle with a large one lets the large walk cover the
/// small one's words. The depth test's tie rule makes the order invisible in the image: the
/// frame writer keeps the nearer fragment and, at equal depth, the lower triangle index (the
/// mesh-order first writer), whatever the arrival order.
///
/// The walk length is the address block's clock count for the triangle alone
/// (`golden::units::address_block::run`, the cycle model), so the order is set-up software only.
/// Ties keep mesh order (a stable sort), so the order is deterministic.
pub fn balanced_order(jobs: &[LitJob]) -> Vec<usize> {
    balanced_order_of(&jobs.iter().map(|j| j.addr).collect::<Vec<_>>())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lit_rows_round_trip() {
        let t = ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let job = LitJob::new(&t).unwrap().unwrap();
        let regs = ShadingRegs::of(&ShadeContext::default()).unwrap();
        let row = lit_row(Some(&job), &regs);
        assert_eq!(row.len(), ROW_WIDTH);
        let (back, r) = row_job(&row);
        assert_eq!(r, regs);
        let back = back.unwrap();
        assert_eq!((back.normal, back.depth), (job.normal, job.depth));
        assert_eq!(back.addr.w.f_word(), job.addr.w.f_word());
        assert_eq!(row_job(&lit_row(None, &regs)).0, None);
        // Every method the lit pipeline renders has a build; others have none.
        assert!(LIT_METHODS.iter().all(|&m| method_options(m).is_some()));
        assert!(method_options(Method::Gouraud).is_none());
        // A vertex depth beyond the words' range is an error, not a wrap.
        let mut far = t;
        far.v[1].z = 1e6;
        assert!(LitJob::new(&far).unwrap_err().contains("depth"));
    }
}

#[cfg(test)]
mod record_tests {
    use super::*;
    use rtl::stream::layout::{unpack, FRAGMENT};

    #[test]
    fn records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let job = LitJob::new(&t).unwrap().unwrap();
        let rec = triangle_record(&job);
        assert_eq!(rec[0], (1, false));
        assert!(rec.last().unwrap().1);
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = lit_row(Some(&job), &ShadingRegs::default());
        assert_eq!(unpack(&TRIANGLE, &payload), row[1..REGS_AT].to_vec());
        assert_eq!(FRAGMENT[0].name, "x");
    }

    #[test]
    fn balanced_order_alternates_large_and_small() {
        use golden::types::ScreenTriangle;
        // Walks of increasing size: triangle k spans 4k + 2 pixels each way.
        let jobs: Vec<LitJob> = (0..5)
            .map(|k| {
                let s = 4 * k + 2;
                LitJob::new(&ScreenTriangle::from_points([(0, 0), (s, 0), (0, s)]))
                    .unwrap()
                    .unwrap()
            })
            .collect();
        assert_eq!(balanced_order(&jobs), vec![4, 0, 3, 1, 2]);
        assert_eq!(balanced_order(&jobs[..0]), Vec::<usize>::new());
        assert_eq!(balanced_order(&jobs[..1]), vec![0]);
        // Equal walks keep mesh order.
        let same = vec![jobs[2]; 4];
        assert_eq!(balanced_order(&same), vec![0, 3, 1, 2]);
    }
}
