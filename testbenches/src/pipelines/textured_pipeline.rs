//! Bench of the textured pixel pipeline (`rtl::pipelines::textured_pipeline`): its bit-exact
//! twin (the address block's and texture-coordinate block's cycle models — built quadratic or
//! bezier, the per-line walk's twin `QuadWalkTwin` or `BezWalkTwin` instead — the event FIFO, the texture memory's
//! twin, the texel weights and the lit pipeline's back end, wired as the top wires them) and
//! the golden `texture` method (`golden::shading::texture::shade` with `Coord::Additive`;
//! built quadratic or bezier, `texture-quadratic` or `texture-bezier`) every clock.
//!
//! Stimulus: a seeded 16×16 texture written first (one texel per clock), then seeded
//! triangles as `pixel-pipeline`'s (`lit_triangles_subpixel`) given perspective w in [1, 4]
//! and texture coordinates spread over 0.5 to 8 repeats, so that pixels need from none to
//! several correction steps; loaded as soon as `ready` allows, `hold` high in a seeded tenth
//! of the clocks after the texture. Built quadratic or bezier, the triangles' line records are pushed
//! while `line_ready` is high except in 40 clocks of every 160, so that first pixels also wait
//! for their records. Lit by the default context.
//!
//! Tolerances: `ready`, `valid`, `x`, `y`, `done` are the twin's (the texture-coordinate
//! block's rate depends on the data, so the clock of each fragment comes from the cycle
//! models); colours within 2 LSB of the golden method's colour, RMS 0.5 LSB (as
//! `pixel-pipeline`); `z` within the depth channel's bound.

use std::collections::VecDeque;

use golden::raster::walk;
use golden::shade::ShadeContext;
use golden::shading::texture::Coord;
use golden::testing::Rng;
use golden::texture::Texture;
use golden::types::ScreenTriangle;
use golden::units::address_block::{AddressBlockModel, AddressOutputs};
use golden::units::texture_bezier::BezWalkTwin;
use golden::units::texture_coord::block::unword_texel;
use golden::units::texture_coord::block::{texel_word, TexCoordModel, TexEvent, TexOutputs};
use golden::units::texture_memory::{load_words, MemoryInputs, MemoryTwin};
use golden::units::texture_quadratic::QuadWalkTwin;
use pipeline::lit::ShadingRegs;
use pipeline::textured::{push_line, row_tex, tex_row, TexJob, TexRegs};
use rtl::core::fixed::{INTENSITY, LEVEL};
use rtl::pipelines::textured_pipeline::{
    TexCoord, TexturedParams, TexturedPipeline, EVENT_FIFO, TEXEL_DELAY, WEIGHT_LATENCY,
};

use super::pixel_pipeline::{lit_triangles_subpixel, DelayLine, LitBack};
use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};

/// An event in the FIFO: the address block's outputs as taken, and whether it is a
/// triangle's first.
#[derive(Clone, Copy, Debug)]
struct Entry {
    a: AddressOutputs,
    first: bool,
}

/// Twin of the textured pipeline.
pub struct TexturedTwin {
    addr: AddressBlockModel,
    coord: TexCoordModel,
    /// The per-line walks: the coordinate of their builds, else idle (all are built).
    quad: QuadWalkTwin,
    bez: BezWalkTwin,
    coord_kind: TexCoord,
    /// The events before the texture-coordinate block takes them.
    waiting: VecDeque<Entry>,
    /// The events taken, until their texels show.
    fifo: VecDeque<Entry>,
    first_wait: bool,
    seen_first: bool,
    memory: MemoryTwin,
    texel: [DelayLine; 3],
    /// The weight stage: dif after [`WEIGHT_LATENCY`] clocks, amb two more.
    dif: [DelayLine; 3],
    amb: [DelayLine; 3],
    back: LitBack,
}

/// amb or dif of a texel channel: ⌊(texel·k + 2⁶)/2⁷⌋, saturated at 2¹⁶ − 1.
pub fn texel_weight(texel: u64, k: u64) -> u64 {
    ((texel * (k & 0xFFFF) + 64) >> 7).min(0xFFFF)
}

impl TexturedTwin {
    pub fn new(p: &TexturedParams) -> Self {
        let mut twin = Self::with_coord(p, TexCoordModel::new(p.k.k));
        twin.coord_kind = p.coord;
        twin
    }

    /// The pipeline with a texture-coordinate model of any k, built or not
    /// (`TexCoordModel::unbuilt`): what a wider comparator set would give (a model, not a
    /// twin of an RTL build).
    pub fn with_k(p: &TexturedParams, k: u32) -> Self {
        Self::with_coord(p, TexCoordModel::unbuilt(k))
    }

    fn with_coord(p: &TexturedParams, coord: TexCoordModel) -> Self {
        TexturedTwin {
            addr: AddressBlockModel::subpixel(),
            coord,
            quad: QuadWalkTwin::default(),
            bez: BezWalkTwin::default(),
            coord_kind: TexCoord::Additive,
            waiting: VecDeque::new(),
            fifo: VecDeque::new(),
            first_wait: false,
            seen_first: false,
            memory: MemoryTwin::default(),
            texel: std::array::from_fn(|_| DelayLine::new(TEXEL_DELAY)),
            dif: std::array::from_fn(|_| DelayLine::new(WEIGHT_LATENCY)),
            amb: std::array::from_fn(|_| DelayLine::new(WEIGHT_LATENCY + 2)),
            back: LitBack::new(&p.lit),
        }
    }

    /// `ready` this clock (a function of the registers).
    pub fn ready(&self) -> bool {
        self.addr.ready() && !self.first_wait
    }

    /// `line_ready` this clock (a function of the registers).
    pub fn line_ready(&self) -> bool {
        match self.coord_kind {
            TexCoord::Bezier => self.bez.line_ready(),
            _ => self.quad.line_ready(),
        }
    }

    /// Line records waiting.
    fn lines(&self) -> usize {
        match self.coord_kind {
            TexCoord::Bezier => self.bez.lines(),
            _ => self.quad.lines(),
        }
    }

    /// The coordinate's outputs this clock, with the first FIFO's head shown (the quadratic
    /// walk's `ready` depends on it).
    fn coord_outputs(&self) -> TexOutputs {
        let ev = self
            .waiting
            .front()
            .map_or(TexEvent::default(), |e| TexEvent::from(&e.a));
        let ((valid, [u, v]), ready) = match self.coord_kind {
            TexCoord::Additive => return self.coord.outputs_held(false),
            TexCoord::Quadratic => (self.quad.outputs(), self.quad.ready(ev.valid, ev.row_start)),
            TexCoord::Bezier => (self.bez.outputs(), self.bez.ready(ev.valid)),
        };
        TexOutputs {
            ready,
            valid,
            u: unword_texel(u),
            v: unword_texel(v),
            ..TexOutputs::default()
        }
    }

    /// The state a stall is diagnosed by: the FIFOs' lengths and heads, the blocks' `ready`,
    /// the load gate.
    pub fn state(&self) -> String {
        let co = self.coord_outputs();
        format!(
            "first FIFO {} (head {:?}), second FIFO {} (head {:?}), texture-coordinate ready {}, address ready {}, first_wait {}, line records {}",
            self.waiting.len(),
            self.waiting.front().map(|e| (e.a.valid, e.a.row_start, e.a.step, e.a.done, e.a.x, e.a.y)),
            self.fifo.len(),
            self.fifo.front().map(|e| (e.a.valid, e.a.row_start, e.a.step, e.a.done, e.a.x, e.a.y)),
            co.ready,
            self.addr.ready(),
            self.first_wait,
            self.lines()
        )
    }
}

impl Twin for TexturedTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let row = row_tex(r);
        let co = self.coord_outputs();
        let line_ready = self.line_ready();
        let gate = !self.first_wait;
        let a_hold = row.hold || self.waiting.len() >= EVENT_FIFO - 1;
        let a = self.addr.outputs_held(a_hold);
        // The texture-coordinate block sees the first FIFO's head and takes it when ready.
        let shown = self.waiting.front().copied();
        let take = co.ready && shown.is_some();
        let ev_in = shown.map_or(TexEvent::default(), |e| TexEvent::from(&e.a));
        let mut o = vec![(a.ready && gate) as u64];
        o.extend(self.back.outputs());
        o.push(line_ready as u64);
        let accepted = row.job.filter(|_| a.ready && gate);

        // The FIFO's pop: a non-pixel at the head, or a pixel whose texel shows.
        let head = self.fifo.front().copied();
        let pop = head.is_some_and(|e| !e.a.valid || co.valid);
        assert!(
            !co.valid || head.is_some_and(|e| e.a.valid),
            "a texel shown without a pixel at the FIFO's head"
        );
        let p = if pop {
            head.unwrap()
        } else {
            Entry {
                a: AddressOutputs::default(),
                first: false,
            }
        };
        // Only the fields the FIFO keeps.
        let popped = AddressOutputs {
            valid: p.a.valid,
            row_start: p.a.row_start,
            step: p.a.step,
            carry: p.a.carry,
            x: p.a.x,
            y: p.a.y,
            done: p.a.done,
            ..AddressOutputs::default()
        };

        // The texel path: memory → delay → weights (read before clocking).
        let (_, rgb) = self.memory.outputs();
        let tex_out: [u64; 3] = std::array::from_fn(|c| self.texel[c].out());
        let mut weights = [0u64; 9];
        for c in 0..3 {
            weights[c] = self.amb[c].out();
            weights[3 + c] = self.dif[c].out();
            weights[6 + c] = row.regs.weights[6 + c];
        }
        for c in 0..3 {
            self.amb[c].clock(texel_weight(tex_out[c], row.t.ka));
            self.dif[c].clock(texel_weight(tex_out[c], row.t.kd));
            self.texel[c].clock(rgb[c] as u64);
        }
        let (we, waddr, wdata) = row.write.map_or((false, 0, 0), |(a, w)| (true, a, w));
        self.memory.clock(&MemoryInputs {
            we,
            waddr,
            wdata,
            log_w: row.t.log_w as u32,
            log_h: row.t.log_h as u32,
            valid: co.valid,
            u: texel_word(co.u) as u32,
            v: texel_word(co.v) as u32,
        });

        self.back.clock(
            &popped,
            accepted.as_ref().map(|j| j.lit),
            &row.regs,
            &weights,
        );

        // The FIFOs and the load gate.
        if pop {
            self.fifo.pop_front();
        }
        if take {
            self.waiting.pop_front();
            assert!(
                self.fifo.len() < EVENT_FIFO,
                "an event pushed into the full second FIFO"
            );
            self.fifo.push_back(shown.unwrap());
        }
        if a.valid || a.row_start || a.done {
            assert!(
                self.waiting.len() < EVENT_FIFO,
                "an event pushed into the full first FIFO"
            );
            self.waiting.push_back(Entry {
                a,
                first: a.row_start && a.step == 0,
            });
        }
        // A triangle starts with its first event, or is a lone `done` (no pixel centre).
        if p.first || (p.a.done && !self.seen_first) {
            self.first_wait = false;
        }
        if p.first {
            self.seen_first = true;
        }
        if p.a.done {
            self.seen_first = false;
        }
        if accepted.is_some() {
            self.first_wait = true;
        }
        let line = row.line.as_ref();
        match self.coord_kind {
            TexCoord::Additive => {
                self.coord
                    .clock_held(accepted.as_ref().map(|j| &j.tex), &ev_in, false);
                self.quad.clock(ev_in.valid, ev_in.row_start, None);
            }
            TexCoord::Quadratic => self.quad.clock(
                ev_in.valid,
                ev_in.row_start,
                line.map(|l| l.quad_words()).as_ref(),
            ),
            TexCoord::Bezier => self
                .bez
                .clock(ev_in.valid, line.map(|l| l.bezier_line()).as_ref()),
        }
        self.addr
            .clock_held(accepted.as_ref().map(|j| &j.lit.addr), a_hold);
        o
    }
}

/// A seeded 16×16 texture.
pub fn bench_texture(seed: u64) -> Texture {
    let mut rng = Rng::new(seed ^ 0x7e47);
    let rgb = (0..256)
        .map(|_| [0; 3].map(|_| rng.below(256) as u8))
        .collect();
    Texture::new(16, 16, rgb).expect("a 16x16 texture")
}

/// `n` seeded textured triangles (see the module doc) with their jobs for the build `coord`.
pub fn textured_triangles(
    seed: u64,
    n: usize,
    texture: &Texture,
    coord: TexCoord,
) -> Vec<(ScreenTriangle, TexJob)> {
    let mut rng = Rng::new(seed ^ 0x51ab);
    let mut out = Vec::with_capacity(n);
    let mut k = 0u64;
    while out.len() < n {
        for mut t in lit_triangles_subpixel(seed.wrapping_add(k), n) {
            let spread = [0.5, 2.0, 8.0][rng.below(3) as usize];
            for v in &mut t.v {
                v.w = 1.0 + 3.0 * rng.unit();
                v.uv = glam::DVec2::new((rng.unit() - 0.5) * spread, (rng.unit() - 0.5) * spread);
            }
            if out.len() % 5 == 1 {
                // A triangle without a pixel centre inside (the address block shows a lone
                // `done` for it): the load gate must not wait for a first event.
                let mut s = t;
                s.frac = 4;
                let (x0, y0) = (16 * (100 + out.len() as i32), 16 * 50);
                for (k, (dx, dy)) in [(1, 1), (14, 3), (8, 6)].into_iter().enumerate() {
                    s.v[k].x = x0 + dx;
                    s.v[k].y = y0 + dy;
                }
                let job = TexJob::of(&s, texture, coord)
                    .expect("the sliver is in range")
                    .expect("the sliver has area");
                assert_eq!(walk(&s).pixel_count(), 0, "the sliver has no pixel");
                out.push((s, job));
            }
            if let Ok(Some(job)) = TexJob::of(&t, texture, coord) {
                if out.len() < n {
                    out.push((t, job));
                }
            }
        }
        k += 1;
    }
    out
}

/// The golden colour of every pixel of `t` (the method of the build `coord`: `texture`,
/// `texture-quadratic` or `texture-bezier`), in walk order.
fn golden_colours(
    t: &ScreenTriangle,
    ctx: &ShadeContext,
    texture: &Texture,
    coord: TexCoord,
) -> Vec<[u8; 3]> {
    let w = walk(t);
    let mut out = Vec::with_capacity(w.pixel_count());
    let coord = match coord {
        TexCoord::Additive => Coord::Additive,
        TexCoord::Quadratic => Coord::Quadratic,
        TexCoord::Bezier => Coord::Bezier,
    };
    golden::shading::texture::shade(t, &w, ctx, texture, coord, &mut |_, _, rgb| out.push(rgb));
    out
}

/// The system run: the texture written, then each job loaded when the twin's `ready` is high,
/// `hold` in a seeded tenth of the clocks, the jobs' line records pushed in order when
/// `line_ready` is high except in 40 clocks of every 160; returns the rows and the twin's
/// outputs.
pub fn textured_system(
    p: &TexturedParams,
    jobs: &[TexJob],
    texture: &Texture,
    regs: &ShadingRegs,
    t: &TexRegs,
    seed: u64,
) -> (Vec<Vec<u64>>, Vec<Vec<u64>>) {
    let mut rng = Rng::new(seed ^ 0x401d);
    let mut twin = TexturedTwin::new(p);
    let mut rows = Vec::new();
    let mut outs = Vec::new();
    for w in load_words(texture).expect("the texture fits") {
        let row = tex_row(None, regs, t, Some(w), false);
        outs.push(twin.step(&row));
        rows.push(row);
    }
    let (mut next, mut done, mut idle, mut since) = (0, 0, 0, 0);
    let mut lines = jobs.iter().flat_map(|j| j.lines.iter()).peekable();
    while idle < 4 {
        let hold = rng.below(10) == 0;
        let load = (twin.ready() && next < jobs.len()).then(|| &jobs[next]);
        next += load.is_some() as usize;
        let mut row = tex_row(load, regs, t, None, hold);
        // Line records stop for 40 clocks in every 160, so that first pixels wait for them.
        if lines.peek().is_some() && twin.line_ready() && (rows.len() / 40) % 4 != 3 {
            push_line(&mut row, lines.next().unwrap());
        }
        let o = twin.step(&row);
        done += o[8] as usize;
        since = if o[8] != 0 { 0 } else { since + 1 };
        idle = if done == jobs.len() { idle + 1 } else { 0 };
        outs.push(o);
        rows.push(row);
        assert!(
            since < 200_000,
            "the textured system stalls after {done} of {} triangles: {}",
            jobs.len(),
            twin.state()
        );
    }
    (rows, outs)
}

impl Bench for TexturedPipeline {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 8;
    fn stimulus(p: &TexturedParams, n: usize, seed: u64) -> Stimulus {
        let ctx = ShadeContext::default();
        let texture = bench_texture(seed);
        let regs = ShadingRegs::of(&ctx).expect("default context fits the registers");
        let t = TexRegs::of(&ctx, &texture).expect("default context fits");
        let tris = textured_triangles(seed, n, &texture, p.coord);
        let jobs: Vec<TexJob> = tris.iter().map(|(_, j)| j.clone()).collect();
        let mut colours = tris
            .iter()
            .flat_map(|(t, _)| golden_colours(t, &ctx, &texture, p.coord))
            .collect::<Vec<_>>()
            .into_iter();
        let mut depths = tris
            .iter()
            .flat_map(|(t, _)| {
                let d = t.depth_plane().unwrap();
                walk(t)
                    .pixels()
                    .into_iter()
                    .map(|px| d.at_pixel(px.x, px.y))
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>()
            .into_iter();
        let (rows, outs) = textured_system(p, &jobs, &texture, &regs, &t, seed);
        let w = |v: u64| Expected::Word(v);
        let expected: Vec<Vec<Expected>> = outs
            .iter()
            .map(|o| {
                let mut e = vec![w(o[0]), w(o[1]), w(o[2]), w(o[3])];
                if o[1] != 0 {
                    let rgb = colours.next().expect("golden colours run out");
                    e.push(Expected::Real(depths.next().expect("depths run out")));
                    e.extend(rgb.map(|v| Expected::Real(v as f64)));
                } else {
                    e.extend([Expected::DontCare; 4]);
                }
                e.push(w(o[8]));
                e.push(w(o[9]));
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
        let mut compare = vec![Compare::Exact; 10];
        compare[4] = depth;
        compare[5..8].copy_from_slice(&[level; 3]);
        Stimulus {
            rows,
            expected,
            compare,
        }
    }
    fn twin(p: &TexturedParams) -> Box<dyn Twin> {
        Box::new(TexturedTwin::new(p))
    }
}
