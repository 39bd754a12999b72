//! Bench of the lit pixel pipeline (`rtl::pipelines::pixel_pipeline`): its bit-exact twin (the address
//! block's cycle model and the twins of every block, wired as the top wires them) and the
//! golden method of the same build (the normalizer front end with the build's coefficients,
//! then cos^n or W(n, γ) with k), every clock.
//!
//! Stimulus: seeded random triangles (`crate::units::address_block::triangle_strategy`) with random
//! unit vertex normals facing the viewer and random depths, lit by the default context (Blinn,
//! n = 50, the thesis material) with L along (0.8, 0.35, 1) and specular colour (1, 0.75, 0.5),
//! so that no two channels of L, H or the weights are equal, loaded as soon as `ready` allows.
//! Tolerances: `ready`, `valid`, `x`, `y`, `done` exact; colours within 2 LSB of the golden
//! method's colour (the bound for the image), RMS 0.5 LSB; `z` within the depth
//! channel's bound (n·2⁻¹⁷ for n ≤ 8189 additions, ≤ 0.0625 pixels).

use std::collections::VecDeque;

use golden::raster::walk;
use golden::shade::ShadeContext;
use golden::types::ScreenTriangle;
use golden::units::address_block::{AddressBlockModel, AddressOutputs, AddressSetup};
use golden::units::brzssk::twin::BrzsskTwin;
use golden::units::colour_combine::twin::ColourTwin;
use golden::units::intensity_interpolator::ChannelTwin;
use golden::units::lighting_unit::twin::LightingTwin;
use golden::units::normalizer::Scale;
use golden::units::power_unit::twin::PowerTwin;
use golden::units::vector_interpolator::VectorTwin;
use pipeline::lit::{lit_row, row_job, LitJob, ShadingRegs};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use rtl::core::fixed::{INTENSITY, LEVEL, NORMAL};
use rtl::pipelines::pixel_pipeline::{
    PipelineParams, PixelPipeline, EVENT_TO_BRZSSK, EVENT_TO_FRAGMENT,
};

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use crate::units::address_block::triangle_strategy;
use golden::testing::seeded_runner;

/// A delay line of `n` registers (reset 0): `out` is what went in `n` clocks ago.
pub(crate) struct DelayLine(VecDeque<u64>);

impl DelayLine {
    pub(crate) fn new(n: usize) -> Self {
        DelayLine(std::iter::repeat_n(0, n).collect())
    }
    pub(crate) fn out(&self) -> u64 {
        self.0[0]
    }
    pub(crate) fn clock(&mut self, d: u64) {
        self.0.pop_front();
        self.0.push_back(d);
    }
}

/// Twin of the whole pipeline.
pub struct PipelineTwin {
    addr: AddressBlockModel,
    back: LitBack,
}

/// Twin of the pipeline after the address block: the event register, the interpolators, the
/// lighting, BRZSSK, power and colour stages and the delay lines beside them (shared with the
/// textured pipeline, whose events come from its FIFO).
pub struct LitBack {
    /// The register on the address block's event before the interpolators.
    ev: AddressOutputs,
    /// The accepted load's interpolator words, registered with the event.
    ld: Option<LitJob>,
    normal: VectorTwin,
    /// The register on the normal (valid, x, y, z) before the lighting unit.
    n_reg: (bool, [i64; 3]),
    depth: ChannelTwin,
    light: LightingTwin,
    bump: BrzsskTwin,
    bx: DelayLine,
    by: DelayLine,
    power: PowerTwin,
    colour: ColourTwin,
    cos_phi: DelayLine,
    z: DelayLine,
    x: DelayLine,
    y: DelayLine,
    done: DelayLine,
}

impl PipelineTwin {
    pub fn new(p: &PipelineParams) -> Self {
        PipelineTwin {
            addr: AddressBlockModel::subpixel(),
            back: LitBack::new(p),
        }
    }
}

impl LitBack {
    pub fn new(p: &PipelineParams) -> Self {
        LitBack {
            ev: AddressOutputs::default(),
            ld: None,
            normal: VectorTwin::default(),
            n_reg: (false, [0; 3]),
            depth: ChannelTwin::default(),
            light: LightingTwin::new(p.coeffs.requested),
            bump: BrzsskTwin::new(p.bump.enable),
            bx: DelayLine::new(EVENT_TO_BRZSSK),
            by: DelayLine::new(EVENT_TO_BRZSSK),
            power: PowerTwin::new(p.power.mode),
            colour: ColourTwin::default(),
            cos_phi: DelayLine::new(rtl::units::power_unit::PowerUnit::LATENCY),
            z: DelayLine::new(
                EVENT_TO_FRAGMENT - rtl::pipelines::pixel_pipeline::EVENT_REGISTER - 1,
            ),
            x: DelayLine::new(EVENT_TO_FRAGMENT),
            y: DelayLine::new(EVENT_TO_FRAGMENT),
            done: DelayLine::new(EVENT_TO_FRAGMENT),
        }
    }

    /// This clock's outputs: valid, x, y, z, red, green, blue, done.
    pub fn outputs(&self) -> [u64; 8] {
        let (cv, rgb) = self.colour.outputs();
        [
            cv as u64,
            self.x.out(),
            self.y.out(),
            self.z.out(),
            rgb[0],
            rgb[1],
            rgb[2],
            self.done.out(),
        ]
    }

    /// One clock: the event `a` (the address block's, or what takes its place), the load
    /// accepted this clock, the frame registers and this clock's colour weights (amb, dif,
    /// spc words as the colour combine's inputs show them).
    pub fn clock(
        &mut self,
        a: &AddressOutputs,
        accepted: Option<LitJob>,
        regs: &ShadingRegs,
        weights: &[u64; 9],
    ) {
        let (nv, n) = self.n_reg;
        self.n_reg = self.normal.outputs();
        let (lv, cos_phi, cos_gamma) = self.light.outputs();
        let (bv, cos_phi_b, cos_gamma_b) = self.bump.outputs();
        let (pv, spec) = self.power.outputs();
        self.colour.clock(pv, self.cos_phi.out(), spec, weights);
        self.power.clock(bv, cos_gamma_b, regs.n);
        self.cos_phi.clock(cos_phi_b);
        self.bump.clock(
            lv,
            cos_phi as u64,
            cos_gamma as u64,
            self.bx.out(),
            self.by.out(),
        );
        self.bx.clock(a.x as u64);
        self.by.clock(a.y as u64);
        let s = |w: [u64; 3]| w.map(|x| NORMAL.to_int(x));
        self.light.clock(nv, n, s(regs.light), s(regs.half));
        self.z.clock(self.depth.word() as u64);
        let ev = std::mem::replace(&mut self.ev, *a);
        let ld = std::mem::replace(&mut self.ld, accepted);
        self.normal.clock(ld.as_ref().map(|j| &j.normal), &ev);
        let first = ev.row_start && ev.step == 0;
        self.depth.clock(
            ld.as_ref().map(|j| &j.depth),
            first,
            ev.row_start,
            ev.carry,
            ev.valid,
        );
        self.x.clock(a.x as u64);
        self.y.clock(a.y as u64);
        self.done.clock(a.done as u64);
    }
}

impl Twin for PipelineTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[pipeline::lit::HOLD_AT] != 0;
        let a = self.addr.outputs_held(hold);
        let mut o = vec![a.ready as u64];
        o.extend(self.back.outputs());
        let (job, regs) = row_job(r);
        let accepted = job.filter(|_| a.ready);
        self.back.clock(&a, accepted, &regs, &regs.weights);
        self.addr
            .clock_held(accepted.as_ref().map(|j| &j.addr), hold);
        o
    }
}

/// A unit normal facing the viewer (z ≥ 0.05).
fn unit_normal() -> impl Strategy<Value = [f64; 3]> {
    (0.05..=1.0f64, 0.0..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    })
}

/// `n` seeded triangles with unit vertex normals and depths in [−2, 2].
pub fn lit_triangles(seed: u64, n: usize) -> Vec<ScreenTriangle> {
    lit_triangles_with(seed, n, false)
}

/// [`lit_triangles`] with every other triangle's vertices moved by a seeded fraction of a
/// pixel (`SUBPIXEL_BITS` fraction bits): the stimulus of `pixel-pipeline` and `pixel-stream`,
/// whose address block is the sub-pixel one.
pub fn lit_triangles_subpixel(seed: u64, n: usize) -> Vec<ScreenTriangle> {
    lit_triangles_with(seed, n, true)
}

fn lit_triangles_with(seed: u64, n: usize, subpixel: bool) -> Vec<ScreenTriangle> {
    let mut r = seeded_runner(seed);
    let st = (
        triangle_strategy(),
        prop::array::uniform3(unit_normal()),
        prop::array::uniform3(-2.0..=2.0f64),
    );
    // The offsets come from a runner of their own, so the integer triangles are the same
    // with and without them.
    let mut r_off = seeded_runner(seed ^ 0x5B5B);
    let offsets = crate::units::address_block::offsets_strategy();
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let (p, normals, z) = st.new_tree(&mut r).expect("no rejection").current();
        let mut t = ScreenTriangle::from_points(p);
        if subpixel && out.len() % 2 == 1 {
            let off = offsets
                .new_tree(&mut r_off)
                .expect("no rejection")
                .current();
            t = crate::units::address_block::subpixel_offsets(&t, off);
        }
        for k in 0..3 {
            t.v[k].normal = glam::DVec3::from_array(normals[k]);
            t.v[k].z = z[k];
        }
        if t.normal_plane().is_some() {
            out.push(t);
        }
    }
    out
}

/// The golden colour of every pixel of `t`, in walk order, for the build's coefficients,
/// bump setting and power mode (`k` = None: exact cos^n).
fn golden_colours(
    t: &ScreenTriangle,
    ctx: &ShadeContext,
    c: Scale,
    bump: bool,
    k: Option<u32>,
) -> Vec<[u8; 3]> {
    let w = walk(t);
    let mut out = Vec::with_capacity(w.pixel_count());
    let a = k.map(|k| golden::shading::brdf::slope(ctx.n(), k, true));
    golden::units::normalizer::shade_front_end(
        t,
        &w,
        ctx,
        c,
        &mut |_, _, rgb| out.push(rgb),
        |x, y, d, s| {
            let (d, s) = if bump {
                golden::units::brzssk::brzssk(d.max(0.0), s.max(0.0), x, y)
            } else {
                (d, s)
            };
            let spec = match (k, a) {
                (Some(k), Some(a)) => golden::shading::brdf::w_kernel(a, k, s),
                _ => ctx.specular_power(s),
            };
            ctx.combine(d, spec)
        },
    );
    out
}

/// The pipeline's rows for `jobs` under `regs`: each job loaded in the clock the address
/// block accepts it, then idle clocks to flush. Returns the rows and the address stream.
fn pipeline_rows(jobs: &[LitJob], regs: &ShadingRegs) -> (Vec<Vec<u64>>, Vec<AddressOutputs>) {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let st = crate::units::address_block::stimulus_subpixel(&setups);
    let mut rows = Vec::new();
    let mut next = 0;
    for c in 0..st.rows.len() + EVENT_TO_FRAGMENT + 1 {
        let load = (st.loads.get(next) == Some(&c)).then(|| &jobs[next]);
        next += load.is_some() as usize;
        rows.push(lit_row(load, regs));
    }
    // The address block's cycle model over all the rows (its idle clocks show `ready`).
    let mut m = AddressBlockModel::subpixel();
    let mut stream = Vec::with_capacity(rows.len());
    let mut next = 0;
    for row in &rows {
        stream.push(m.outputs());
        let load = (row[0] != 0).then(|| &setups[next]);
        next += load.is_some() as usize;
        m.clock(load);
    }
    debug_assert_eq!(stream[..st.expected.len()], st.expected[..]);
    (rows, stream)
}

impl Bench for PixelPipeline {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 12;
    fn stimulus(p: &PipelineParams, n: usize, seed: u64) -> Stimulus {
        // L off the diagonal (so L's and H's components differ) and a specular colour with
        // three different weights: a swap of two channels' wiring changes the output.
        let mut ctx = ShadeContext::default();
        ctx.light = glam::DVec3::new(0.8, 0.35, 1.0).normalize();
        ctx.material.specular = [1.0, 0.75, 0.5];
        let regs = ShadingRegs::of(&ctx).expect("the bench's context fits the registers");
        let tris = lit_triangles_subpixel(seed, n);
        let jobs: Vec<LitJob> = tris
            .iter()
            .map(|t| LitJob::new(t).unwrap().expect("non-degenerate"))
            .collect();
        let k = p.power.k();
        let mut colours = tris
            .iter()
            .flat_map(|t| golden_colours(t, &ctx, p.coeffs.requested, p.bump.enable, k))
            .collect::<Vec<_>>()
            .into_iter();
        let mut depths = tris
            .iter()
            .flat_map(|t| {
                let d = t.depth_plane().unwrap();
                walk(t)
                    .pixels()
                    .into_iter()
                    .map(|px| d.at_pixel(px.x, px.y))
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>()
            .into_iter();
        let (rows, stream) = pipeline_rows(&jobs, &regs);
        let w = |v: u64| Expected::Word(v);
        let expected: Vec<Vec<Expected>> = (0..rows.len())
            .map(|c| {
                let ready = stream[c].ready as u64;
                let d = c
                    .checked_sub(EVENT_TO_FRAGMENT)
                    .map_or(AddressOutputs::default(), |k| stream[k]);
                let mut e = vec![w(ready), w(d.valid as u64), w(d.x as u64), w(d.y as u64)];
                if d.valid {
                    let rgb = colours.next().expect("golden colours run out");
                    e.push(Expected::Real(depths.next().expect("depths run out")));
                    e.extend(rgb.map(|v| Expected::Real(v as f64)));
                } else {
                    e.extend([Expected::DontCare; 4]);
                }
                e.push(w(d.done as u64));
                e
            })
            .collect();
        assert!(colours.next().is_none(), "golden colours left over");
        let level = Compare::Fixed {
            format: LEVEL,
            tol: Tolerance {
                max_abs: 2.0,
                rms: 0.5,
            },
        };
        let bound =
            golden::units::vector_interpolator::error_bound(0).max(8189.0 * (-17f64).exp2());
        let depth = Compare::Fixed {
            format: INTENSITY,
            tol: Tolerance {
                max_abs: bound,
                rms: bound,
            },
        };
        let mut compare = vec![Compare::Exact; 9];
        compare[4] = depth;
        compare[5..8].copy_from_slice(&[level; 3]);
        Stimulus {
            rows,
            expected,
            compare,
        }
    }
    fn twin(p: &PipelineParams) -> Box<dyn Twin> {
        Box::new(PipelineTwin::new(p))
    }
}
