//! The four method families: their set-up records, their top and their fragment-to-frame step.

use golden::methods::Method;
use golden::render::Frame;

use super::frame::{jobs_with_depth, FrameWriter, PlaneWriter};
use super::{Family, LitTop, Options, Progress, Rendered, Scene, Tick};
use crate::gouraud::{clock_budget, Pipe, TriangleJob};
use crate::lit::{lit_clock_budget, LitJob, LitPipe, ShadingRegs};
use crate::span::{span_clock_budget, span_jobs, SpanPipe};
use crate::subdivision::{SubJob, SubPipe};
use crate::textured::{coord_of, tex_clock_budget, TexJob, TexRegs, TexturedPipe, ENGINE_K};
use rtl::pipelines::textured_pipeline::TexCoord;

/// `gouraud` through the raster pipe (`rtl::pipelines::gouraud_raster`: address block + BVI),
/// by default through its AXI4-Stream top `gouraud-stream`: the address set-up
/// (`golden::units::address_block::AddressSetup`) and the Gouraud planes quantized for the BVI
/// per triangle, sent in the set-up order; depth from the f64 planes.
pub(super) struct Gouraud;

impl Family for Gouraud {
    fn design(&self, o: &Options) -> Result<verilated::Design, String> {
        Ok(Pipe::design(o.lit_top.resolve() == LitTop::Stream))
    }

    fn render(&self, s: &Scene, o: &Options, progress: Progress) -> Result<Rendered, String> {
        // Same triangles as the golden renderer: those with a depth plane (non-zero area).
        let (jobs, depth) = jobs_with_depth(s.tris, |t| Ok(TriangleJob::gouraud(t, s.ctx)))?;
        progress(Tick::Total(jobs.len() as u64));
        // The triangles are sent in the set-up order (balanced by default: a 22-word record per
        // triangle streams in while a larger one is walked); the frame keeps, at equal depth,
        // the lower mesh index, so the image does not depend on the order.
        let order = o
            .setup_order
            .of_addrs(&jobs.iter().map(|j| j.addr).collect::<Vec<_>>());
        let sent: Vec<TriangleJob> = order.iter().map(|&i| jobs[i]).collect();
        let stream = o.lit_top.resolve() == LitTop::Stream;
        let mut pipe = Pipe::on(o.sim, stream).map_err(|e| format!("RTL set-up: {e}"))?;
        let mut writer = PlaneWriter::new(s.width, s.height);
        let stats = pipe
            .run(
                &sent,
                clock_budget(&sent),
                |k, x, y, rgb| {
                    let k = order[k];
                    writer.put(k, x, y, rgb, &depth[k]);
                },
                |done| progress(Tick::Done(done)),
            )
            .map_err(|e| format!("RTL simulation: {e}"))?;
        Ok(writer.finish(stats))
    }
}

/// `subdivision` (each lane its sub-triangle's planes) and `gouraud` with the four-triangle
/// block (every lane the parent's) through the subdivision raster pipe
/// (`rtl::pipelines::subdivision_raster`: the four-triangle block and a BVI per lane), by
/// default through its ports (`--lit-top stream`: `subdivision-stream`, whose 87-word
/// records make small parents set-up bound); depth from the parent's f64 plane, parents sent in
/// mesh order (the first writer keeps a tie).
pub(super) struct Subdivision(pub Method);

impl Family for Subdivision {
    fn design(&self, o: &Options) -> Result<verilated::Design, String> {
        Ok(SubPipe::design(o.lit_top == LitTop::Stream))
    }

    fn render(&self, s: &Scene, o: &Options, progress: Progress) -> Result<Rendered, String> {
        let (jobs, depth) = jobs_with_depth(s.tris, |t| match self.0 {
            Method::Gouraud => Ok(SubJob::gouraud(t, s.ctx)),
            Method::Subdivision => Ok(SubJob::subdivision(t, s.ctx)),
            m => Err(format!("the subdivision pipe has no set-up for method {m}")),
        })?;
        progress(Tick::Total(jobs.len() as u64));
        let mut frame = Frame::new(s.width, s.height);
        let mut pipe = SubPipe::on(o.sim, o.lit_top == LitTop::Stream)
            .map_err(|e| format!("RTL set-up: {e}"))?;
        let stats = pipe
            .run(
                &jobs,
                crate::subdivision::clock_budget(&jobs),
                |k, x, y, rgb| {
                    let (x, y) = (x as i32, y as i32);
                    frame.put(x, y, depth[k].at_pixel(x, y), rgb);
                },
                |done| progress(Tick::Done(done)),
            )
            .map_err(|e| format!("RTL simulation: {e}"))?;
        Ok(Rendered {
            frame,
            stats,
            visibility_mismatches: 0,
            visibility_depth_gap: 0.0,
        })
    }
}

/// A lit method (`crate::lit::LIT_METHODS`) through the lit pixel pipeline
/// (`rtl::pipelines::pixel_pipeline`, by default behind `pixel-stream`) built for it: one
/// `LitJob` per triangle, sent in the set-up order; depth from the hardware's z words.
///
/// Errors (one line): as every family, plus a lighting model or material the registers cannot
/// hold (Phong lighting, a colour weight ≥ 256, a vertex depth beyond the depth words' range).
pub(super) struct Lit(pub Method);

impl Family for Lit {
    fn design(&self, o: &Options) -> Result<verilated::Design, String> {
        LitPipe::design(self.0, o.lit_top.resolve() == LitTop::Stream)
    }

    fn render(&self, s: &Scene, o: &Options, progress: Progress) -> Result<Rendered, String> {
        let regs = ShadingRegs::of(s.ctx).map_err(|e| format!("RTL set-up: {e}"))?;
        let (jobs, depth) = jobs_with_depth(s.tris, LitJob::new)?;
        let order = o.setup_order.of(&jobs);
        let stream = o.lit_top.resolve() == LitTop::Stream;
        let mut pipe =
            LitPipe::on(self.0, o.sim, stream).map_err(|e| format!("RTL set-up: {e}"))?;
        render_in_order(s, &jobs, &depth, &order, progress, |sent, put, done| {
            pipe.run(sent, &regs, lit_clock_budget(sent), put, done)
        })
    }
}

/// Send `jobs` in `order` through `run` (its fragments' `job` indices count the sent jobs)
/// and write each fragment into the frame as its triangle's (mesh order: the depth test's tie
/// rule), depth from `depth`.
fn render_in_order<J: Clone>(
    s: &Scene,
    jobs: &[J],
    depth: &[golden::types::Plane],
    order: &[usize],
    progress: &mut dyn FnMut(Tick),
    run: impl FnOnce(
        &[J],
        &mut dyn FnMut(crate::lit::Fragment),
        &mut dyn FnMut(u64),
    ) -> Result<crate::axis::PipeStats, String>,
) -> Result<Rendered, String> {
    progress(Tick::Total(jobs.len() as u64));
    let sent: Vec<J> = order.iter().map(|&i| jobs[i].clone()).collect();
    let mut writer = FrameWriter::new(s.width, s.height);
    let stats = run(
        &sent,
        &mut |f| {
            let k = order[f.job];
            writer.put(k, f.x, f.y, f.z, f.rgb, &depth[k])
        },
        &mut |done| progress(Tick::Done(done)),
    )
    .map_err(|e| format!("RTL simulation: {e}"))?;
    Ok(writer.finish(stats))
}

/// A span method (`crate::span::SPAN_METHODS`): `angular`, `fast`, `fast-fit` through
/// `rtl::pipelines::span_pipeline` (two fragments per clock), `quadric` through
/// `rtl::units::quadric_unit`, `cubic` through `rtl::pipelines::cubic_pipeline` (Horner
/// variant from the options): the span front end (`crate::span::span_jobs`, the golden
/// method's per-line set-up in software) loads one raster line at a time; depth from the
/// hardware's z words. Through the stream tops only when asked (`--lit-top stream`): a line's
/// record is 12 (cubic), 14, 20 or 5 words (a quadric triangle's first line 41) and a line of
/// m + 1 pixels takes ⌊m/2⌋ + 1 clocks, so short lines are set-up bound.
pub(super) struct Span(pub Method);

impl Family for Span {
    fn design(&self, o: &Options) -> Result<verilated::Design, String> {
        SpanPipe::design(self.0, o.horner_pipelined, o.lit_top == LitTop::Stream)
    }

    fn render(&self, s: &Scene, o: &Options, progress: Progress) -> Result<Rendered, String> {
        // The cubic's samples and the quadric's coefficients are lit in software (any lighting
        // model); the other span tops light in hardware and need the registers.
        let regs = if matches!(self.0, Method::Cubic | Method::Quadric) {
            ShadingRegs {
                light: [0; 3],
                half: [0; 3],
                n: 0,
                weights: [0; 9],
            }
        } else {
            ShadingRegs::of(s.ctx).map_err(|e| format!("RTL set-up: {e}"))?
        };
        let stream = o.lit_top == LitTop::Stream;
        let mut pipe = SpanPipe::on(self.0, o.horner_pipelined, o.sim, stream)
            .map_err(|e| format!("RTL set-up: {e}"))?;
        let mut spans = Vec::new();
        let mut depth = Vec::with_capacity(s.tris.len());
        for (i, t) in s.tris.iter().enumerate() {
            let Some(d) = t.depth_plane() else { continue };
            let k = depth.len();
            spans.extend(
                span_jobs(t, k, pipe.kind(), s.ctx).map_err(|e| format!("triangle {i}: {e}"))?,
            );
            depth.push(d);
        }
        progress(Tick::Total(spans.len() as u64));
        let mut writer = FrameWriter::new(s.width, s.height);
        let stats = pipe
            .run(
                &spans,
                &regs,
                span_clock_budget(&spans),
                |f| writer.put(f.triangle, f.x, f.y, f.z, f.rgb, &depth[f.triangle]),
                |done| progress(Tick::Done(done)),
            )
            .map_err(|e| format!("RTL simulation: {e}"))?;
        Ok(writer.finish(stats))
    }
}

/// `texture` through `textured-pipeline` (tex-k = [`ENGINE_K`]), on its ports by default: the
/// texture written into the memory first (one texel per clock, not counted in the clocks),
/// then one `TexJob` per triangle in the set-up order; depth from the hardware's z words. With
/// `--lit-top stream` (only when asked: the texture's records would dominate the clocks),
/// through `textured-stream`: the register record, a texel record per texel (four clocks a
/// texel, counted), then the triangle records. `texture-quadratic` and `texture-bezier`
/// through `textured-pipeline` built `texture=quadratic` and `texture=bezier`: each
/// triangle's line records pushed beside the loads on its ports, or (`--lit-top stream`) sent
/// as line records after the triangle's record.
///
/// Errors (one line): as the lit family, plus a triangle beyond the texture-coordinate block's
/// range (`texture`), a k_a or k_d whose white-texel weight does not fit Q8.8, a texture over
/// 2^16 texels.
pub(super) struct Textured(pub(super) Method);

impl Textured {
    /// The build's [`crate::textured::params`] name.
    fn build(&self) -> &'static str {
        match coord_of(self.0) {
            TexCoord::Additive => ENGINE_K,
            c => c.name(),
        }
    }
}

impl Family for Textured {
    fn design(&self, o: &Options) -> Result<verilated::Design, String> {
        TexturedPipe::design(self.build(), o.lit_top == LitTop::Stream)
    }

    fn render(&self, s: &Scene, o: &Options, progress: Progress) -> Result<Rendered, String> {
        let texture = s.texture.unwrap_or(golden::texture::Texture::builtin());
        let regs = ShadingRegs::of(s.ctx).map_err(|e| format!("RTL set-up: {e}"))?;
        let tregs = TexRegs::of(s.ctx, texture).map_err(|e| format!("RTL set-up: {e}"))?;
        let coord = coord_of(self.0);
        let (jobs, depth) = jobs_with_depth(s.tris, |t| TexJob::of(t, texture, coord))?;
        let order = o
            .setup_order
            .of_addrs(&jobs.iter().map(|j| j.lit.addr).collect::<Vec<_>>());
        let stream = o.lit_top == LitTop::Stream;
        let mut pipe = TexturedPipe::on(self.build(), o.sim, stream)
            .map_err(|e| format!("RTL set-up: {e}"))?;
        pipe.load_texture(texture, &regs, &tregs)
            .map_err(|e| format!("RTL simulation: {e}"))?;
        render_in_order(s, &jobs, &depth, &order, progress, |sent, put, done| {
            pipe.run(sent, &regs, &tregs, tex_clock_budget(sent), put, done)
        })
    }
}
