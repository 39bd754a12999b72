//! Bench of `cubic-stream` (`rtl::stream::cubic_stream`), the AXI4-Stream top of the cubic span
//! pipeline: its bit-exact twin (the record reader, the word banks and the FIFO with the
//! units' hold, around `cubic-pipeline`'s twin), driven by the seeded producer and consumer of
//! the other stream tops' benches (a word stays until taken; `tready` low in a quarter of the
//! clocks and in long stretches).
//!
//! Golden: the stream adds no arithmetic. Its golden expectation is the protocol (every
//! `tready`, `tvalid`, `tlast`, `error`, exact) and, for the data, the beats in order are
//! `cubic-pipeline`'s fragments without stalls, whose colours and depths `cubic-pipeline`'s
//! bench checks against the golden `cubic` method and the f64 depth plane every clock (and
//! `tests/cubic_stream.rs` against its RTL run through its own ports).

use pipeline::axis::{Beat, Word};
use pipeline::span::cubic_words;
use pipeline::span::{span_row, SpanJob, SpanKind};
use rtl::pipelines::cubic_pipeline::CubicParams;
use rtl::stream::cubic_stream::{CubicStream, FIFO_DEPTH, HOLD_ABOVE};
use rtl::stream::layout::{pack_fragment, unpack, CUBIC_LINE, CUBIC_STREAM};

use crate::harness::{Compare, Expected};
use crate::pipelines::cubic_pipeline::CubicPipelineTwin;
use crate::pipelines::pixel_pipeline::lit_triangles;
use crate::pipelines::span_pipeline::GoldenSpans;
use crate::registry::{Bench, Stimulus, Twin};
use crate::stall::{SplitMix, StallPattern};
use crate::stream::stream_twin::{BeatFifo, RecordReader};

/// Output ports in row order: s_axis_tready, m_axis_tvalid, tdata, tuser, tlast, error.
pub const OUTPUTS: usize = 6;

/// Twin of `cubic-stream`.
pub struct CubicStreamTwin {
    inner: CubicPipelineTwin,
    reader: RecordReader,
    /// Beats: tdata, tuser (z), tlast.
    fifo: BeatFifo<(u64, u64, bool)>,
    /// Lines loaded whose last pixel has not been seen.
    outstanding: usize,
}

impl CubicStreamTwin {
    pub fn new(p: &CubicParams) -> Self {
        CubicStreamTwin {
            inner: CubicPipelineTwin::new(p),
            reader: RecordReader::new(&CUBIC_STREAM.records()),
            fifo: BeatFifo::new(FIFO_DEPTH, HOLD_ABOVE),
            outstanding: 0,
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

impl Twin for CubicStreamTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (tdata, tvalid, tlast, m_ready) = (r[0] as u32, r[1] != 0, r[2] != 0, r[3] != 0);
        let out = self.outputs();

        // The pipeline's inputs this clock: load, the load bank's fields, hold.
        let mut row = vec![self.reader.pend_b as u64];
        row.extend(unpack(&CUBIC_LINE, &self.reader.load_bank));
        row.push(self.fifo.hold() as u64);
        // Outputs: ready, valid, x, z, r, g, b, y, last.
        let o = self.inner.step(&row);
        let (ready, valid, last) = (o[0] != 0, o[1] != 0, o[8] != 0);

        let load_taken = self.reader.pend_b && ready;
        self.reader.clock(tdata, tvalid, tlast, load_taken);
        self.outstanding = self.outstanding + load_taken as usize - (valid && last) as usize;
        let beat = pack_fragment(&[o[2], o[7], 1, o[4], o[5], o[6]]) as u64;
        self.fifo
            .clock(m_ready, valid.then_some((beat, o[3], last)));
        out
    }
}

/// A run: input rows, the twin's outputs, and what happened.
pub struct CubicStreamRun {
    pub rows: Vec<Vec<u64>>,
    pub outputs: Vec<Vec<u64>>,
    /// The beats the consumer took, in order.
    pub beats: Vec<Beat>,
    pub held: usize,
    pub consumer_stalls: usize,
    /// The most beats the FIFO held.
    pub max_level: usize,
}

/// Drive `words` into the twin with a producer that leaves a gap (tvalid low) with
/// probability `gap` and a consumer stalled by `stalls`, until every word is taken and
/// everything has drained (plus `tail` idle clocks, and up to two more to end on the serial
/// units' slot boundary).
pub fn drive(
    p: &CubicParams,
    words: &[Word],
    seed: u64,
    gap: f64,
    stalls: &mut StallPattern,
    tail: usize,
) -> CubicStreamRun {
    let mut twin = CubicStreamTwin::new(p);
    let mut rng = SplitMix::new(seed ^ 0xC0B1C);
    let mut run = CubicStreamRun {
        rows: Vec::new(),
        outputs: Vec::new(),
        beats: Vec::new(),
        held: 0,
        consumer_stalls: 0,
        max_level: 0,
    };
    let (mut next, mut showing, mut idle_clocks) = (0usize, false, 0usize);
    let limit = 200 + words.len() * 200 + 400_000;
    // Serial units take a line in the last clock of a three-clock slot, their phase running
    // free from reset: a run ends on a slot boundary, so a batch that follows in the same
    // simulation (`shadecore-sim` streams) meets the phase a fresh twin has.
    while idle_clocks < tail || !run.rows.len().is_multiple_of(3) {
        assert!(run.rows.len() < limit, "the stream does not drain");
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
    run.max_level = twin.fifo.max_level;
    run
}

/// The span kind of `p`.
pub fn kind(p: &CubicParams) -> SpanKind {
    SpanKind::Cubic {
        pipelined: p.0.pipelined,
    }
}

/// The stimulus's scene: the cubic lines of `n` seeded lit triangles (the `cubic-pipeline`
/// bench's), in walk order.
pub fn scene(p: &CubicParams, seed: u64, n: usize) -> Vec<SpanJob> {
    GoldenSpans::new(kind(p), &lit_triangles(seed, n)).spans
}

/// The beats of `spans` through the stream without a stall (the order and content every
/// stalled run must reproduce).
pub fn reference_beats(p: &CubicParams, spans: &[SpanJob]) -> Vec<Beat> {
    drive(
        p,
        &cubic_words(spans),
        1,
        0.0,
        &mut StallPattern::never(),
        20,
    )
    .beats
}

/// `cubic-pipeline`'s load row of `span` (the fields the record carries), for tests.
pub fn load_row(p: &CubicParams, span: &SpanJob) -> Vec<u64> {
    span_row(kind(p), Some(span), &Default::default())
}

impl Bench for CubicStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 3;
    fn stimulus(p: &CubicParams, n: usize, seed: u64) -> Stimulus {
        let spans = scene(p, seed, n);
        let words = cubic_words(&spans);
        let mut stalls = StallPattern::new(seed, 0.25);
        let run = drive(p, &words, seed, 0.1, &mut stalls, 8);
        // Golden: the protocol (exact), and the beats in the order of the same words without
        // a stall (whose colours and depths `cubic-pipeline`'s bench checks against the golden
        // method, and `tests/cubic_stream.rs` against that pipeline's RTL).
        let reference = reference_beats(p, &spans);
        assert_eq!(run.beats.len(), reference.len(), "every beat delivered");
        let mut k = 0;
        let expected = run
            .outputs
            .iter()
            .zip(&run.rows)
            .map(|(o, r)| {
                let (data, tuser) = if o[1] != 0 {
                    let b = &reference[k];
                    k += (r[3] != 0) as usize;
                    (
                        Expected::Word(pack_fragment(&[
                            b.x as u64,
                            b.y as u64,
                            b.pixel as u64,
                            b.rgb[0] as u64,
                            b.rgb[1] as u64,
                            b.rgb[2] as u64,
                        ]) as u64),
                        Expected::Word(b.z as u32 as u64),
                    )
                } else {
                    (Expected::DontCare, Expected::DontCare)
                };
                vec![
                    Expected::Word(o[0]),
                    Expected::Word(o[1]),
                    data,
                    tuser,
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
    fn twin(p: &CubicParams) -> Box<dyn Twin> {
        Box::new(CubicStreamTwin::new(p))
    }
}
