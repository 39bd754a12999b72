//! Bench of `textured-stream` (`rtl::stream::textured_stream`), the AXI4-Stream top of the
//! textured pixel pipeline: its bit-exact twin (the record reader and word banks, the drain
//! rule for register and texel records, the FIFO with the address block's hold, around
//! `textured-pipeline`'s twin), driven by the seeded producer and consumers of
//! [`drive_lanes`] (a word stays until taken; `tready` low in a quarter of the clocks and in
//! long stretches).
//!
//! Golden: the stream adds no arithmetic. Its golden expectation is the protocol (every
//! `tready`, `tvalid`, `tlast`, `error`, exact) and, for the data, the beats in order are
//! `textured-pipeline`'s fragments (its twin run alone, the texture written through its port,
//! every triangle loaded as soon as `ready`; its own bench checks their colours against the
//! golden `texture` method): [`pipeline_beats`].

use golden::shade::ShadeContext;
use golden::texture::Texture;
use golden::units::texture_memory::load_words;
use pipeline::axis::{Beat, Word};
use pipeline::lit::ShadingRegs;
use pipeline::textured::{
    push_line, tex_row, texel_records, textured_job_records, textured_register_record,
    textured_scene_words, TexJob, TexRegs, LINE_WORDS, TEX_ROW_WIDTH,
};
use rtl::pipelines::textured_pipeline::{TexCoord, TexturedParams};
use rtl::stream::layout::{
    pack_fragment, payload_words, unpack, TEXEL, TEXTURED_LINE, TEXTURED_REGISTERS,
    TEXTURED_STREAM, TEXTURED_TRIANGLE,
};
use rtl::stream::textured_stream::{TexturedStream, TexturedStreamParams, FIFO_DEPTH, HOLD_ABOVE};

use crate::harness::{Compare, Expected};
use crate::pipelines::textured_pipeline::{bench_texture, textured_triangles, TexturedTwin};
use crate::registry::{Bench, Stimulus, Twin};
use crate::stall::StallPattern;
use crate::stream::stream_twin::{drive_lanes, BeatFifo, LaneTwin, RecordReader};

/// Output ports in row order.
pub const OUTPUTS: usize = 6;

/// Twin of `textured-stream`.
pub struct TexturedStreamTwin {
    inner: TexturedTwin,
    reader: RecordReader,
    /// Triangles loaded whose `done` has not left the pipeline.
    outstanding: u64,
    /// The active register fields (`TEXTURED_REGISTERS`, in its order).
    regs: Vec<u64>,
    /// Beats: tdata, tuser (z), tlast.
    fifo: BeatFifo<(u64, u64, bool)>,
}

impl TexturedStreamTwin {
    pub fn new(p: &TexturedParams) -> Self {
        TexturedStreamTwin {
            inner: TexturedTwin::new(p),
            reader: RecordReader::new(&TEXTURED_STREAM.records()),
            outstanding: 0,
            regs: vec![0; TEXTURED_REGISTERS.fields.len()],
            fifo: BeatFifo::new(FIFO_DEPTH, HOLD_ABOVE),
        }
    }

    fn outputs(&self) -> Vec<u64> {
        crate::stream::stream_twin::one_lane_outputs(&self.reader, &self.fifo)
    }
}

impl Twin for TexturedStreamTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (tdata, tvalid, tlast, m_ready) = (r[0] as u32, r[1] != 0, r[2] != 0, r[3] != 0);
        let out = self.outputs();
        let (pend_b, type_b) = (self.reader.pend_b, self.reader.type_b);
        let drained = self.outstanding == 0;
        let write = pend_b && type_b == TEXEL.code && drained;
        let line = pend_b && type_b == TEXTURED_LINE.code && self.inner.line_ready();

        // The pipeline's input row: load, the triangle fields, the registers, the texel write,
        // the line push, hold (`pipeline::textured`'s row layout).
        let mut row = vec![(pend_b && type_b == TEXTURED_TRIANGLE.code) as u64];
        row.extend(unpack(&TEXTURED_TRIANGLE, &self.reader.load_bank));
        row.extend(&self.regs);
        row.push(write as u64);
        row.extend(unpack(
            &TEXEL,
            &self.reader.load_bank[..payload_words(&TEXEL)],
        ));
        row.push(line as u64);
        row.extend(unpack(
            &TEXTURED_LINE,
            &self.reader.load_bank[..payload_words(&TEXTURED_LINE)],
        ));
        debug_assert_eq!(LINE_WORDS, TEXTURED_LINE.fields.len());
        row.push(self.fifo.hold() as u64);
        debug_assert_eq!(row.len(), TEX_ROW_WIDTH);
        let o = self.inner.step(&row);
        let (ready, valid, x, y, z, rgb, done) = (
            o[0] != 0,
            o[1] != 0,
            o[2],
            o[3],
            o[4],
            [o[5], o[6], o[7]],
            o[8] != 0,
        );

        // A triangle loads when the pipeline is ready; registers and texels apply when every
        // triangle loaded before them has left it.
        let load_taken = pend_b && type_b == TEXTURED_TRIANGLE.code && ready;
        let apply = pend_b && type_b == TEXTURED_REGISTERS.code && drained;
        if apply {
            self.regs = unpack(
                &TEXTURED_REGISTERS,
                &self.reader.load_bank[..payload_words(&TEXTURED_REGISTERS)],
            );
        }
        self.reader
            .clock(tdata, tvalid, tlast, load_taken || apply || write || line);
        self.outstanding = self.outstanding + load_taken as u64 - done as u64;
        let beat = pack_fragment(&[x, y, valid as u64, rgb[0], rgb[1], rgb[2]]) as u64;
        self.fifo
            .clock(m_ready, (valid || done).then_some((beat, z, done)));
        out
    }
}

impl LaneTwin for TexturedStreamTwin {
    const LANES: usize = 1;
    const TUSER: bool = true;
    fn s_ready(&self) -> bool {
        self.reader.s_ready()
    }
    fn idle(&self) -> bool {
        self.reader.idle() && self.outstanding == 0 && self.fifo.is_empty()
    }
    fn held(&self) -> usize {
        self.fifo.held
    }
    fn max_level(&self) -> usize {
        self.fifo.max_level
    }
}

/// A seeded textured scene: `n` triangles of the textured pipeline's bench on its seeded
/// 16×16 texture, lit by the default context (the additive build's set-up).
pub fn scene(seed: u64, n: usize) -> (Vec<TexJob>, ShadingRegs, TexRegs, Texture) {
    scene_of(seed, n, TexCoord::Additive)
}

/// [`scene`] with the set-up of the build `coord` (a per-line build's jobs carry their line
/// records).
pub fn scene_of(
    seed: u64,
    n: usize,
    coord: TexCoord,
) -> (Vec<TexJob>, ShadingRegs, TexRegs, Texture) {
    let ctx = ShadeContext::default();
    let texture = bench_texture(seed);
    let regs = ShadingRegs::of(&ctx).expect("default context fits the registers");
    let t = TexRegs::of(&ctx, &texture).expect("default context fits");
    let jobs = textured_triangles(seed, n, &texture, coord)
        .into_iter()
        .map(|(_, j)| j)
        .collect();
    (jobs, regs, t, texture)
}

/// `textured-pipeline`'s output as beats: its twin alone, the texture written through its
/// port, every job loaded as soon as `ready`, the line records (per-line builds) pushed in
/// order whenever `line_ready`, no hold. A fragment is a beat; a `done` without
/// a fragment is a beat with `pixel` = 0; `tlast` on the `done`.
pub fn pipeline_beats(
    p: &TexturedParams,
    jobs: &[TexJob],
    regs: &ShadingRegs,
    t: &TexRegs,
    texture: &Texture,
) -> Vec<Beat> {
    let mut twin = TexturedTwin::new(p);
    for w in load_words(texture).expect("the texture fits") {
        twin.step(&tex_row(None, regs, t, Some(w), false));
    }
    let (mut beats, mut next, mut done, mut clocks) = (Vec::new(), 0, 0, 0u64);
    let mut lines = jobs.iter().flat_map(|j| j.lines.iter()).peekable();
    while done < jobs.len() {
        clocks += 1;
        assert!(clocks < 10_000_000, "the textured pipeline does not finish");
        let load = (twin.ready() && next < jobs.len()).then(|| &jobs[next]);
        next += load.is_some() as usize;
        let mut row = tex_row(load, regs, t, None, false);
        if lines.peek().is_some() && twin.line_ready() {
            push_line(&mut row, lines.next().unwrap());
        }
        let o = twin.step(&row);
        if o[1] != 0 || o[8] != 0 {
            beats.push(Beat {
                pixel: o[1] != 0,
                x: o[2] as u32,
                y: o[3] as u32,
                rgb: [o[5] as u8, o[6] as u8, o[7] as u8],
                z: o[4] as u32 as i32,
                last: o[8] != 0,
            });
        }
        done += (o[8] != 0) as usize;
    }
    beats
}

/// The set-up words of a scene: the registers, the texture, half the triangles, then the
/// registers again and the texture's first four texels again (the same values, so the
/// fragments do not change; both wait for the first half to drain), then the other half.
pub fn stimulus_words(
    jobs: &[TexJob],
    regs: &ShadingRegs,
    t: &TexRegs,
    texture: &Texture,
) -> Vec<Word> {
    let half = jobs.len() / 2;
    let mut w = textured_scene_words(&jobs[..half], regs, t, texture).expect("the texture fits");
    w.extend(textured_register_record(regs, t));
    w.extend(&texel_records(texture).expect("the texture fits")[..4 * 3]);
    for j in &jobs[half..] {
        w.extend(textured_job_records(j));
    }
    w
}

/// A run of `words` through the twin: a producer with gaps in `gap` of the clocks and a
/// consumer stalled by `stalls`.
pub fn run(
    p: &TexturedParams,
    words: &[Word],
    seed: u64,
    gap: f64,
    stalls: StallPattern,
) -> crate::stream::stream_twin::LaneRun<1> {
    let mut twin = TexturedStreamTwin::new(p);
    drive_lanes(&mut twin, words, seed, gap, &mut [stalls], 8)
}

impl Bench for TexturedStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 6;
    fn stimulus(p: &TexturedStreamParams, n: usize, seed: u64) -> Stimulus {
        let (jobs, regs, t, texture) = scene_of(seed, n, p.coord);
        let words = stimulus_words(&jobs, &regs, &t, &texture);
        let run = run(p, &words, seed, 0.1, StallPattern::new(seed, 0.25));
        // Golden: the protocol (exact), and the beats in the order `textured-pipeline` gives
        // them without a stall (whose colours its own bench checks against the golden
        // `texture` method).
        let reference = pipeline_beats(p, &jobs, &regs, &t, &texture);
        assert_eq!(run.beats[0].len(), reference.len(), "every beat delivered");
        let mut k = 0;
        let expected = run
            .outputs
            .iter()
            .zip(&run.rows)
            .map(|(o, r)| {
                let (data, user, last) = if o[1] != 0 {
                    let b = &reference[k];
                    k += (r[3] != 0) as usize;
                    (
                        Expected::Word(b.tdata()),
                        Expected::Word(b.z as u32 as u64),
                        Expected::Word(b.last as u64),
                    )
                } else {
                    (Expected::DontCare, Expected::DontCare, Expected::Word(0))
                };
                vec![
                    Expected::Word(o[0]),
                    Expected::Word(o[1]),
                    data,
                    user,
                    last,
                    Expected::Word(o[5]),
                ]
            })
            .collect();
        Stimulus {
            rows: run.rows,
            expected,
            compare: vec![Compare::Exact; OUTPUTS],
        }
    }
    fn twin(p: &TexturedStreamParams) -> Box<dyn Twin> {
        Box::new(TexturedStreamTwin::new(p))
    }
}
