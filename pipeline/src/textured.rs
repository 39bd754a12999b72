//! The textured pixel pipeline (`rtl::pipelines::textured_pipeline`) as a render driver: the
//! lit pipeline's set-up ([`crate::lit::LitJob`]) plus the texture-coordinate block's
//! (`golden::units::texture_coord::block::TexCoordSetup`, from the coefficients the golden
//! `texture` method walks with), the texture written into the memory first, fragments out in
//! hardware order.
//!
//! Row layout (the top's input ports in order): `load`, the address set-up (19 words), the
//! normal words (12), the depth words (4), the texture-coordinate set-up (14), the shading
//! registers without the ambient and diffuse weights (lx ly lz hx hy hz n spc_r spc_g spc_b:
//! the texel gives the others), `ka`, `kd`, `log_w`, `log_h`,
//! `tex_we`, `tex_waddr`, `tex_wdata`, `line_push` and a line record's nine words
//! ([`LineRecord`]), `hold`. Outputs: ready, valid, x, y, z, red, green, blue, done,
//! line_ready.
//!
//! Built `texture=quadratic` or `texture=bezier` (`texture-quadratic`, `texture-bezier`
//! through the pipeline), a triangle's [`TexJob::lines`] are its line records, one per raster
//! line with a pixel in walk order (`golden::shading::texture::quadratic_line`,
//! `bezier_line`); [`TexturedPipe::run`] pushes them, in the triangles' order, whenever
//! `line_ready` is high, or (through `textured-stream`) sends each triangle's after its
//! triangle record ([`textured_job_records`]).

use golden::methods::Method;
use golden::shade::ShadeContext;
use golden::shading::texture::{bezier_line, quadratic_line};
use golden::texture::Texture;
use golden::types::ScreenTriangle;
use golden::units::colour_combine::Weights;
use golden::units::texture_bezier::{BezierLine, LaneWords};
use golden::units::texture_coord::block::{walk_geometry, TexCoordSetup, SETUP_PORTS};
use golden::units::texture_quadratic::QuadWords;
use rtl::core::registry::{BlockParams, Options};
use rtl::core::sim::Model;
use rtl::pipelines::textured_pipeline::{TexCoord, TexturedParams, TexturedPipeline};
use rtl::stream::layout::{pack, TEXEL, TEXTURED_LINE, TEXTURED_REGISTERS, TEXTURED_TRIANGLE};
use rtl::stream::textured_stream::{TexturedStream, TexturedStreamParams};

use flow::engine::Sim;

use crate::axis::{with_last, PipeStats, Word};
use crate::lit::{lit_row, row_job, Fragment, LitJob, ShadingRegs, REGS_AT};

/// Where the texture-coordinate set-up starts in a row.
pub const TEX_AT: usize = REGS_AT;
/// Where the shading registers start.
pub const TREGS_AT: usize = TEX_AT + SETUP_PORTS;
/// Where `ka` is (then `kd`, `log_w`, `log_h`, `tex_we`, `tex_waddr`, `tex_wdata`).
pub const KA_AT: usize = TREGS_AT + 10;
/// Where `line_push` is (then the line record's words).
pub const LINE_AT: usize = KA_AT + 7;
/// Words of a line record ([`LineRecord`]).
pub const LINE_WORDS: usize = 9;
/// Where `hold` is.
pub const TEX_HOLD_AT: usize = LINE_AT + 1 + LINE_WORDS;
/// Output ports: ready, valid, x, y, z, red, green, blue, done, line_ready.
pub const TEX_OUTPUTS: usize = 10;
/// Input words per row.
pub const TEX_ROW_WIDTH: usize = TEX_HOLD_AT + 1;

/// The methods the textured pipeline renders: `texture` built additive, `texture-quadratic`
/// built quadratic, `texture-bezier` built bezier.
pub const TEXTURED_RTL_METHODS: [Method; 3] = [
    Method::Texture,
    Method::TextureQuadratic,
    Method::TextureBezier,
];

/// The build that renders `method` (one of [`TEXTURED_RTL_METHODS`]).
pub fn coord_of(method: Method) -> TexCoord {
    match method {
        Method::TextureQuadratic => TexCoord::Quadratic,
        Method::TextureBezier => TexCoord::Bezier,
        _ => TexCoord::Additive,
    }
}

/// A line record on the pipeline's `line_…` ports: u's start, Δ, ΔΔ and v's (both per-line
/// builds), then the line's last pixel index and X's Δ, d (the Bézier build's; zero for the
/// quadratic one).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LineRecord {
    pub words: [u64; 6],
    pub end: u64,
    pub x: [u64; 2],
}

impl LineRecord {
    /// The quadratic unit's words of a line (u, then v).
    pub fn quadratic(w: &[QuadWords; 2]) -> LineRecord {
        LineRecord {
            words: [w[0].u, w[0].d, w[0].dd, w[1].u, w[1].d, w[1].dd],
            ..LineRecord::default()
        }
    }

    /// The Bézier block's record of a line.
    pub fn bezier(l: &BezierLine) -> LineRecord {
        let [x, u, v] = l.lanes;
        LineRecord {
            words: [u.start, u.step, u.step2, v.start, v.step, v.step2],
            end: l.end_index as u64,
            x: [x.step, x.step2],
        }
    }

    /// The quadratic unit's words this record carries.
    pub fn quad_words(&self) -> [QuadWords; 2] {
        let w = &self.words;
        [
            QuadWords {
                u: w[0],
                d: w[1],
                dd: w[2],
            },
            QuadWords {
                u: w[3],
                d: w[4],
                dd: w[5],
            },
        ]
    }

    /// The Bézier block's record this one carries.
    pub fn bezier_line(&self) -> BezierLine {
        let w = &self.words;
        let lane = |start, step, step2| LaneWords { start, step, step2 };
        BezierLine {
            end_index: self.end as u32,
            lanes: [
                lane(0, self.x[0], self.x[1]),
                lane(w[0], w[1], w[2]),
                lane(w[3], w[4], w[5]),
            ],
        }
    }

    /// The ports' words in order (the `line_…` ports, and `textured-stream`'s line record).
    pub fn ports(&self) -> [u64; LINE_WORDS] {
        let w = &self.words;
        [
            w[0], w[1], w[2], w[3], w[4], w[5], self.end, self.x[0], self.x[1],
        ]
    }
}

/// The k the engine builds (correction steps per clock: the pipeline's default,
/// `rtl::pipelines::textured_pipeline::DEFAULT_K`).
pub const ENGINE_K: &str = "4";

/// One triangle's set-up: the lit pipeline's, and the texture-coordinate block's or (built
/// quadratic) the quadratic unit's line records.
#[derive(Clone, Debug, PartialEq)]
pub struct TexJob {
    pub lit: LitJob,
    pub tex: TexCoordSetup,
    /// The per-line builds: one record per raster line with a pixel, in walk order (empty for
    /// the additive build).
    pub lines: Vec<LineRecord>,
}

impl TexJob {
    /// The set-up of `tri` for `texture` (the additive build); `None` when the golden method
    /// draws nothing (zero area, or a w that is not finite and positive). Errors (one line): a
    /// vertex depth beyond the depth words, coefficients beyond the texture-coordinate block's
    /// range.
    pub fn new(tri: &ScreenTriangle, texture: &Texture) -> Result<Option<TexJob>, String> {
        Self::of(tri, texture, TexCoord::Additive)
    }

    /// The set-up of `tri` for the build `coord` (as [`TexJob::new`]; for a per-line build the
    /// §14 words are zero and their range does not apply).
    pub fn of(
        tri: &ScreenTriangle,
        texture: &Texture,
        coord: TexCoord,
    ) -> Result<Option<TexJob>, String> {
        let Some(lit) = LitJob::new(tri)? else {
            return Ok(None);
        };
        let Some(s) = golden::shading::texture::setup(tri, texture) else {
            return Ok(None);
        };
        let walk = golden::raster::walk(tri);
        if coord != TexCoord::Additive {
            let rows = walk.rows.iter().filter(|r| r.len > 0);
            return Ok(Some(TexJob {
                lit,
                tex: TexCoordSetup::default(),
                lines: if coord == TexCoord::Quadratic {
                    rows.map(|r| LineRecord::quadratic(&quadratic_line(&s, r)))
                        .collect()
                } else {
                    rows.map(|r| LineRecord::bezier(&bezier_line(&s, r)))
                        .collect()
                },
            }));
        }
        let (_, cu, cv) = golden::shading::texture::checked_coeffs(tri, &s, &walk)?;
        let (_, f, dir) = walk_geometry(&lit.addr);
        Ok(Some(TexJob {
            lit,
            tex: TexCoordSetup::new(&cu, &cv, f, dir),
            lines: Vec::new(),
        }))
    }
}

/// The texture registers: k_a and k_d (unsigned Q1.15) and the texture's sides (log₂).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TexRegs {
    pub ka: u64,
    pub kd: u64,
    pub log_w: u64,
    pub log_h: u64,
}

impl TexRegs {
    /// The registers of `ctx` for `texture`. Errors (one line): a k_a or k_d whose weight for
    /// a white texel (255·k) does not fit the colour combine's Q8.8, a texture of more than
    /// 2^16 texels.
    pub fn of(ctx: &ShadeContext, texture: &Texture) -> Result<TexRegs, String> {
        let mut white = *ctx;
        white.material.diffuse = [255.0; 3];
        Weights::of(&white)
            .words()
            .map_err(|e| format!("with a white texel: {e}"))?;
        let (w, h) = (texture.width(), texture.height());
        if (w as u64) * (h as u64) > 1 << golden::units::texture_memory::ADDRESS_BITS {
            return Err(format!(
                "a {w}x{h} texture does not fit the texture memory (2^16 texels)"
            ));
        }
        let q = |k: f64| (k * 32768.0).round() as u64;
        Ok(TexRegs {
            ka: q(ctx.material.ka),
            kd: q(ctx.material.kd),
            log_w: w.trailing_zeros() as u64,
            log_h: h.trailing_zeros() as u64,
        })
    }
}

/// The pipeline's input row: `load` with a job's set-up (or idle), the registers, a texel
/// write (address, word) or none, `hold`.
pub fn tex_row(
    job: Option<&TexJob>,
    regs: &ShadingRegs,
    t: &TexRegs,
    write: Option<(u32, u32)>,
    hold: bool,
) -> Vec<u64> {
    let mut row = lit_row(job.map(|j| &j.lit), regs);
    row.truncate(REGS_AT);
    row.extend(job.map_or(vec![0; SETUP_PORTS], |j| j.tex.ports()));
    let r = regs.row();
    row.extend(&r[..7]);
    row.extend(&r[13..]);
    row.extend([t.ka, t.kd, t.log_w, t.log_h]);
    match write {
        Some((a, w)) => row.extend([1, a as u64, w as u64]),
        None => row.extend([0, 0, 0]),
    }
    row.extend([0; 1 + LINE_WORDS]);
    row.push(hold as u64);
    debug_assert_eq!(row.len(), TEX_ROW_WIDTH);
    row
}

/// `row` ([`tex_row`]'s) with a line record pushed.
pub fn push_line(row: &mut [u64], line: &LineRecord) {
    row[LINE_AT] = 1;
    row[LINE_AT + 1..LINE_AT + 1 + LINE_WORDS].copy_from_slice(&line.ports());
}

/// One row's fields, as [`tex_row`] packs them.
#[derive(Clone, Debug, PartialEq)]
pub struct TexRow {
    pub job: Option<TexJob>,
    pub regs: ShadingRegs,
    pub t: TexRegs,
    pub write: Option<(u32, u32)>,
    pub line: Option<LineRecord>,
    pub hold: bool,
}

/// The inverse of [`tex_row`] (the registers' ambient and diffuse weights read 0).
pub fn row_tex(row: &[u64]) -> TexRow {
    let mut lit = row[..REGS_AT].to_vec();
    lit.extend(&row[TREGS_AT..TREGS_AT + 7]);
    lit.extend([0; 6]);
    lit.extend(&row[TREGS_AT + 7..KA_AT]);
    lit.push(0);
    let (job, regs) = row_job(&lit);
    let k = &row[KA_AT..];
    TexRow {
        job: job.map(|lit| TexJob {
            lit,
            tex: TexCoordSetup::from_ports(&row[TEX_AT..TREGS_AT]),
            lines: Vec::new(),
        }),
        regs,
        t: TexRegs {
            ka: k[0],
            kd: k[1],
            log_w: k[2],
            log_h: k[3],
        },
        write: (k[4] & 1 != 0).then(|| (k[5] as u32, k[6] as u32)),
        line: (row[LINE_AT] & 1 != 0).then(|| {
            let w = &row[LINE_AT + 1..];
            LineRecord {
                words: [w[0], w[1], w[2], w[3], w[4], w[5]],
                end: w[6],
                x: [w[7], w[8]],
            }
        }),
        hold: row[TEX_HOLD_AT] & 1 != 0,
    }
}

/// The build of `k` (1, 2 or 4), additive; or, `k` = `"quadratic"` or `"bezier"`, that
/// per-line build.
pub fn params(k: &str) -> Result<TexturedParams, String> {
    if k == "quadratic" || k == "bezier" {
        return TexturedParams::from_options(&Options::new().with("texture", k));
    }
    TexturedParams::from_options(&Options::new().with("tex-k", k))
}

/// `textured-pipeline`, or its AXI4-Stream top `textured-stream`, on either simulator.
pub struct TexturedPipe {
    model: Box<dyn Model>,
    /// `textured-stream` (records in, beats out) rather than `textured-pipeline`'s ports.
    stream: bool,
    /// Stream only: the texel records [`TexturedPipe::load_texture`] queued, sent by
    /// [`TexturedPipe::run`] after the register record.
    texels: Vec<Word>,
}

impl TexturedPipe {
    /// The pipeline (or, if `stream`, `textured-stream`) with `tex-k` = `k` (or, `k` =
    /// `"quadratic"` or `"bezier"`, that per-line build), on `sim`.
    pub fn on(k: &str, sim: Sim, stream: bool) -> Result<TexturedPipe, String> {
        let p = params(k)?;
        let model = if stream {
            flow::engine::model::<TexturedStream>(&TexturedStreamParams(p), sim)?
        } else {
            flow::engine::model::<TexturedPipeline>(&p, sim)?
        };
        Ok(TexturedPipe {
            model,
            stream,
            texels: Vec::new(),
        })
    }

    /// The design [`TexturedPipe::on`] builds under Verilator.
    pub fn design(k: &str, stream: bool) -> Result<verilated::Design, String> {
        let p = params(k)?;
        Ok(if stream {
            flow::engine::design::<TexturedStream>(&TexturedStreamParams(p))
        } else {
            flow::engine::design::<TexturedPipeline>(&p)
        })
    }

    /// Write `texture` into the memory: through the ports, one texel per clock, returning the
    /// clocks taken; through the stream top, queued as texel records for [`TexturedPipe::run`]
    /// (four clocks a texel, counted in its clocks), returning 0.
    pub fn load_texture(
        &mut self,
        texture: &Texture,
        regs: &ShadingRegs,
        t: &TexRegs,
    ) -> Result<u64, String> {
        if self.stream {
            self.texels = texel_records(texture)?;
            return Ok(0);
        }
        let words = memory_words(texture)?;
        let mut out = vec![0u64; TEX_OUTPUTS];
        for &w in &words {
            self.model
                .step(&tex_row(None, regs, t, Some(w), false), &mut out)?;
        }
        Ok(words.len() as u64)
    }

    /// Run `jobs` (after [`TexturedPipe::load_texture`]), each loaded as soon as `ready` is
    /// high, their line records (the per-line builds) pushed in order whenever `line_ready`
    /// is high (through the stream top: each triangle's after its record); `fragment` for every valid output, `progress(done_triangles)` after each `done`.
    /// Stops after the last `done`, or with an error after `max_clocks`.
    pub fn run(
        &mut self,
        jobs: &[TexJob],
        regs: &ShadingRegs,
        t: &TexRegs,
        max_clocks: u64,
        mut fragment: impl FnMut(Fragment),
        mut progress: impl FnMut(u64),
    ) -> Result<PipeStats, String> {
        if self.stream {
            let mut words = textured_register_record(regs, t);
            words.extend(std::mem::take(&mut self.texels));
            for j in jobs {
                words.extend(textured_job_records(j));
            }
            // The texture's records take four clocks a texel before the first triangle.
            let budget = max_clocks.saturating_add(4 * words.len() as u64);
            return crate::axis::drive::<TexturedStream>(
                self.model.as_mut(),
                "textured-stream",
                "triangles",
                &words,
                jobs.len() as u64,
                budget,
                &mut |job, b, clock| fragment(Fragment::of_beat(job, b, clock)),
                &mut progress,
            );
        }
        let mut lines = jobs.iter().flat_map(|j| j.lines.iter()).peekable();
        crate::lit::run_ports(
            self.model.as_mut(),
            "textured pipeline",
            jobs.len(),
            TEX_OUTPUTS,
            &tex_row(None, regs, t, None, false),
            &mut |k, model| {
                // `line_ready` (output 9) is a function of the registers.
                let line =
                    (lines.peek().is_some() && model.peek(9) != 0).then(|| lines.next().unwrap());
                if k.is_none() && line.is_none() {
                    return None;
                }
                let mut row = tex_row(k.map(|k| &jobs[k]), regs, t, None, false);
                if let Some(l) = line {
                    push_line(&mut row, l);
                }
                Some(row)
            },
            max_clocks,
            &mut fragment,
            &mut progress,
        )
    }
}

/// `textured-stream`'s triangle record of `job` (the field values `textured-pipeline`'s load
/// row carries: the address, normal, depth and texture-coordinate set-up).
pub fn textured_triangle_record(job: &TexJob) -> Vec<Word> {
    let row = tex_row(
        Some(job),
        &ShadingRegs::default(),
        &TexRegs::default(),
        None,
        false,
    );
    with_last(pack(&TEXTURED_TRIANGLE, &row[1..TREGS_AT]))
}

/// `textured-stream`'s line record of `line` (the per-line builds).
pub fn textured_line_record(line: &LineRecord) -> Vec<Word> {
    with_last(pack(&TEXTURED_LINE, &line.ports()))
}

/// `textured-stream`'s records of `job`: its triangle record, then its line records (the
/// per-line builds; none for the additive one), in walk order.
pub fn textured_job_records(job: &TexJob) -> Vec<Word> {
    let mut w = textured_triangle_record(job);
    for l in &job.lines {
        w.extend(textured_line_record(l));
    }
    w
}

/// `textured-stream`'s register record (L, H, n, the specular colour, k_a, k_d, the sides).
pub fn textured_register_record(regs: &ShadingRegs, t: &TexRegs) -> Vec<Word> {
    let row = tex_row(None, regs, t, None, false);
    with_last(pack(&TEXTURED_REGISTERS, &row[TREGS_AT..KA_AT + 4]))
}

/// The texture memory's writes of `texture` (address, colour word), or a one-line error for a
/// texture beyond its 2^16 texels.
fn memory_words(texture: &Texture) -> Result<Vec<(u32, u32)>, String> {
    golden::units::texture_memory::load_words(texture).ok_or_else(|| {
        format!(
            "a {}x{} texture does not fit the texture memory (2^16 texels)",
            texture.width(),
            texture.height()
        )
    })
}

/// `textured-stream`'s texel records of `texture`, one per texel
/// (`golden::units::texture_memory::load_words`: address v·2^log_w + u, colour 0xRRGGBB).
/// Error (one line): a texture beyond the memory's 2^16 texels.
pub fn texel_records(texture: &Texture) -> Result<Vec<Word>, String> {
    Ok(memory_words(texture)?
        .iter()
        .flat_map(|&(a, w)| with_last(pack(&TEXEL, &[a as u64, w as u64])))
        .collect())
}

/// A textured scene's set-up stream for `textured-stream`: the registers, the texture, then
/// every triangle (each followed by its line records, for the per-line builds).
pub fn textured_scene_words(
    jobs: &[TexJob],
    regs: &ShadingRegs,
    t: &TexRegs,
    texture: &Texture,
) -> Result<Vec<Word>, String> {
    let mut w = textured_register_record(regs, t);
    w.extend(texel_records(texture)?);
    for j in jobs {
        w.extend(textured_job_records(j));
    }
    Ok(w)
}

/// A clock budget for `jobs`: every row at full length, each pixel at the texture-coordinate
/// block's worst rate (a runaway guard, not an estimate), plus the latency.
pub fn tex_clock_budget(jobs: &[TexJob]) -> u64 {
    jobs.iter()
        .map(|j| 8 + j.lines.len() as u64 + j.lit.addr.rows as u64 * 4097 * 64)
        .sum::<u64>()
        + TexturedPipeline::LATENCY as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn rows_round_trip() {
        let mut t = ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        for (k, v) in t.v.iter_mut().enumerate() {
            v.uv = DVec2::new(k as f64 * 0.3, 0.1 + k as f64 * 0.2);
            v.w = 1.0 + k as f64;
        }
        let texture = Texture::builtin();
        let job = TexJob::new(&t, texture).unwrap().unwrap();
        let ctx = ShadeContext::default();
        let regs = ShadingRegs::of(&ctx).unwrap();
        let tr = TexRegs::of(&ctx, texture).unwrap();
        assert_eq!((tr.log_w, tr.log_h), (8, 8));
        let row = tex_row(Some(&job), &regs, &tr, Some((5, 0xABCDEF)), true);
        assert_eq!(row.len(), TEX_ROW_WIDTH);
        let back = row_tex(&row);
        let mut no_amb_dif = regs;
        no_amb_dif.weights[..6].fill(0);
        assert_eq!(back.regs, no_amb_dif);
        assert_eq!(back.t, tr);
        assert_eq!(back.write, Some((5, 0xABCDEF)));
        assert!(back.hold);
        let bj = back.job.unwrap();
        assert_eq!(bj.tex, job.tex);
        assert_eq!(
            (bj.lit.normal, bj.lit.depth),
            (job.lit.normal, job.lit.depth)
        );
        assert_eq!(row_tex(&tex_row(None, &regs, &tr, None, false)).job, None);
        // A k_d whose white-texel weight is 256 or more is an error, not a wrap.
        let mut bright = ctx;
        bright.material.kd = 1.01;
        assert!(TexRegs::of(&bright, texture).unwrap_err().contains("dif"));
    }
}
