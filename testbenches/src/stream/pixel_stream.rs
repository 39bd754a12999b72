//! Bench of `pixel-stream` (`rtl::stream::pixel_stream`), the AXI4-Stream top of the lit pixel
//! pipeline: its bit-exact twin (the record reader, the word bank, the register drain rule and
//! the FIFO with the address block's hold, around `pixel-pipeline`'s twin), and a seeded
//! producer and consumer that respect AXI4-Stream (a word stays until taken; `tready` low in a
//! quarter of the clocks and in long stretches).
//!
//! Golden: the stream adds no arithmetic. Its golden expectation is the protocol (every
//! `tready`, `tvalid`, `tlast`, `error`, exact) and, for the data, the beats in order are
//! `pixel-pipeline`'s fragments without stalls (whose colours and depths its own bench checks
//! against the golden methods): [`reference_beats`], compared by `tests/pixel_stream.rs`.

use golden::shade::ShadeContext;
use pipeline::axis::{Beat, Word};
use pipeline::lit::scene_words;
use pipeline::lit::{LitJob, ShadingRegs, HOLD_AT, ROW_WIDTH};
use rtl::pipelines::pixel_pipeline::PipelineParams;
use rtl::stream::layout::{
    pack_fragment, payload_words, unpack, PIXEL_STREAM, REGISTERS, TRIANGLE,
};
use rtl::stream::pixel_stream::{PixelStream, FIFO_DEPTH, HOLD_ABOVE};

use crate::harness::{Compare, Expected};
use crate::pipelines::pixel_pipeline::{lit_triangles_subpixel, PipelineTwin};
use crate::registry::{Bench, Stimulus, Twin};
use crate::stall::{SplitMix, StallPattern};
use crate::stream::stream_twin::{BeatFifo, RecordReader};

/// Output ports in row order.
pub const OUTPUTS: usize = 6;

/// Twin of `pixel-stream`.
pub struct StreamTwin {
    inner: PipelineTwin,
    reader: RecordReader,
    /// Triangles loaded whose `done` has not left the pipeline.
    outstanding: u64,
    /// The active frame and material registers.
    regs: Vec<u64>,
    /// Beats: tdata, tuser (z), tlast.
    fifo: BeatFifo<(u64, u64, bool)>,
}

impl StreamTwin {
    pub fn new(p: &PipelineParams) -> Self {
        StreamTwin {
            inner: PipelineTwin::new(p),
            reader: RecordReader::new(&PIXEL_STREAM.records()),
            outstanding: 0,
            regs: vec![0; REGISTERS.fields.len()],
            fifo: BeatFifo::new(FIFO_DEPTH, HOLD_ABOVE),
        }
    }

    /// `s_axis_tready` in the current clock.
    pub fn s_ready(&self) -> bool {
        self.reader.s_ready()
    }

    /// Nothing waiting, nothing in flight, nothing to deliver.
    pub fn idle(&self) -> bool {
        self.reader.idle() && self.outstanding == 0 && self.fifo.is_empty()
    }

    fn outputs(&self) -> Vec<u64> {
        crate::stream::stream_twin::one_lane_outputs(&self.reader, &self.fifo)
    }
}

impl Twin for StreamTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (tdata, tvalid, tlast, m_ready) = (r[0] as u32, r[1] != 0, r[2] != 0, r[3] != 0);
        let out = self.outputs();

        // The pipeline's inputs this clock.
        let (pend_b, type_b) = (self.reader.pend_b, self.reader.type_b);
        let mut row = vec![(pend_b && type_b == TRIANGLE.code) as u64];
        row.extend(unpack(&TRIANGLE, &self.reader.load_bank));
        row.extend(&self.regs);
        row.push(self.fifo.hold() as u64);
        debug_assert_eq!(row.len(), ROW_WIDTH);
        debug_assert_eq!(row.len(), HOLD_AT + 1);
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

        // A triangle loads when the address block is ready; registers apply when every
        // triangle loaded before them has left the pipeline.
        let load_taken = pend_b && type_b == TRIANGLE.code && ready;
        let apply = pend_b && type_b == REGISTERS.code && self.outstanding == 0;
        if apply {
            self.regs = unpack(
                &REGISTERS,
                &self.reader.load_bank[..payload_words(&REGISTERS)],
            );
        }
        self.reader.clock(tdata, tvalid, tlast, load_taken || apply);
        self.outstanding = self.outstanding + load_taken as u64 - done as u64;
        let beat = pack_fragment(&[x, y, valid as u64, rgb[0], rgb[1], rgb[2]]) as u64;
        self.fifo
            .clock(m_ready, (valid || done).then_some((beat, z, done)));
        out
    }
}

/// A run: input rows, the twin's outputs, and what happened.
pub struct StreamRun {
    pub rows: Vec<Vec<u64>>,
    pub outputs: Vec<Vec<u64>>,
    /// The beats the consumer took, in order.
    pub beats: Vec<Beat>,
    pub held: usize,
    pub consumer_stalls: usize,
}

/// Drive `words` into the twin with a producer that leaves a gap (tvalid low) with
/// probability `gap` and a consumer stalled by `stalls`, until every word is taken and
/// everything has drained (plus `tail` idle clocks).
pub fn drive(
    p: &PipelineParams,
    words: &[Word],
    seed: u64,
    gap: f64,
    stalls: &mut StallPattern,
    tail: usize,
) -> StreamRun {
    let mut twin = StreamTwin::new(p);
    let mut rng = SplitMix::new(seed ^ 0xA5A5);
    let mut run = StreamRun {
        rows: Vec::new(),
        outputs: Vec::new(),
        beats: Vec::new(),
        held: 0,
        consumer_stalls: 0,
    };
    let (mut next, mut showing, mut idle_clocks) = (0usize, false, 0usize);
    let limit = 200 + words.len() * 50 + 400_000;
    while idle_clocks < tail {
        assert!(run.rows.len() < limit, "the stream does not drain");
        // AXI4-Stream: a shown word stays until taken; a new one may wait a gap.
        if !showing && next < words.len() {
            showing = rng.unit() >= gap;
        }
        let (w, last) = if showing { words[next] } else { (0, false) };
        let m_ready = !stalls.next_stalled();
        let row = vec![w as u64, showing as u64, last as u64, m_ready as u64];
        let s_ready = twin.s_ready();
        let o = twin.step(&row);
        if showing && s_ready {
            next += 1;
            showing = false;
        }
        if o[1] != 0 && m_ready {
            run.beats.push(Beat::read(o[2], o[3], o[4] != 0));
        }
        run.consumer_stalls += !m_ready as usize;
        run.rows.push(row);
        run.outputs.push(o);
        if next == words.len() && twin.idle() {
            idle_clocks += 1;
        }
    }
    run.held = twin.fifo.held;
    run
}

/// `pixel-pipeline`'s fragments for `jobs` without any stall, as beats (the order and
/// content every stalled run must reproduce).
pub fn reference_beats(p: &PipelineParams, jobs: &[LitJob], regs: &ShadingRegs) -> Vec<Beat> {
    let words = scene_words(jobs, regs);
    drive(p, &words, 1, 0.0, &mut StallPattern::never(), 40).beats
}

/// The stimulus's scene: `n` seeded lit triangles, the default shading context.
pub fn scene(seed: u64, n: usize) -> (Vec<LitJob>, ShadingRegs) {
    let regs = ShadingRegs::of(&ShadeContext::default()).expect("default context");
    let jobs = lit_triangles_subpixel(seed, n)
        .iter()
        .map(|t| LitJob::new(t).unwrap().expect("non-degenerate"))
        .collect();
    (jobs, regs)
}

/// The set-up words of a scene with a second (identical) register record in the middle, so
/// the drain rule is exercised.
pub fn stimulus_words(jobs: &[LitJob], regs: &ShadingRegs) -> Vec<Word> {
    let half = jobs.len() / 2;
    let mut w = scene_words(&jobs[..half], regs);
    w.extend(scene_words(&jobs[half..], regs));
    w
}

impl Bench for PixelStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 12;
    fn stimulus(p: &PipelineParams, n: usize, seed: u64) -> Stimulus {
        let (jobs, regs) = scene(seed, n);
        let words = stimulus_words(&jobs, &regs);
        let mut stalls = StallPattern::new(seed, 0.25);
        let run = drive(p, &words, seed, 0.1, &mut stalls, 8);
        // Golden: the protocol (exact), and the beats in the order of the same words through
        // `pixel-pipeline` without a stall (whose colours and depths its own bench checks
        // against the golden methods).
        let reference = drive(p, &words, seed, 0.0, &mut StallPattern::never(), 40).beats;
        assert_eq!(run.beats.len(), reference.len(), "every beat delivered");
        let mut k = 0;
        let expected = run
            .outputs
            .iter()
            .zip(&run.rows)
            .map(|(o, r)| {
                let (data, user) = if o[1] != 0 {
                    let b = &reference[k];
                    k += (r[3] != 0) as usize;
                    let tdata = pack_fragment(&[
                        b.x as u64,
                        b.y as u64,
                        b.pixel as u64,
                        b.rgb[0] as u64,
                        b.rgb[1] as u64,
                        b.rgb[2] as u64,
                    ]) as u64;
                    (Expected::Word(tdata), Expected::Word(b.z as u32 as u64))
                } else {
                    (Expected::DontCare, Expected::DontCare)
                };
                vec![
                    Expected::Word(o[0]),
                    Expected::Word(o[1]),
                    data,
                    user,
                    Expected::Word(o[4]),
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
    fn twin(p: &PipelineParams) -> Box<dyn Twin> {
        Box::new(StreamTwin::new(p))
    }
}
