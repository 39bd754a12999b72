//! Benches of the two-lane stream tops, `angular-stream` (`rtl::stream::angular_stream`),
//! `fast-stream` (`rtl::stream::fast_stream`) and `quadric-stream` (`rtl::stream::quadric_stream`), the
//! AXI4-Stream tops of the angular and fast span pipelines and the quadric unit: their
//! bit-exact twin (the record reader, the word banks, the active registers, a FIFO per lane
//! with the units' hold, around the wrapped top's twin), driven by the seeded producer and
//! consumers of the other stream tops' benches (a word stays until taken; each lane's `tready`
//! low in a quarter of the clocks and in long stretches, the two lanes independently).
//!
//! Golden: the stream adds no arithmetic. Its golden expectation is the protocol (every
//! `tready`, `tvalid`, `tlast`, `error`, exact) and, for the data, each lane's beats in order
//! are those of the same words without a stall, whose colours and depths the wrapped top's
//! bench checks against the golden `angular` / `fast` / `fast-fit` / `quadric` method and the
//! f64 depth plane every clock (and `tests/span_stream.rs` against that top's RTL run through
//! its own ports).

use golden::units::quadric_unit::twin::QuadricTwin;
use pipeline::axis::{Beat, Word};
use pipeline::lit::ShadingRegs;
use pipeline::span::span_stream_words;
use pipeline::span::{SpanJob, SpanKind};
use rtl::pipelines::span_pipeline::FastPipelineParams;
use rtl::stream::angular_stream::AngularStream;
use rtl::stream::fast_stream::FastStream;
use rtl::stream::layout::{pack_fragment, unpack, StreamTop, SPAN_REGISTERS};
use rtl::stream::quadric_stream::QuadricStream;

use crate::harness::{Compare, Expected};
use crate::pipelines::pixel_pipeline::lit_triangles;
use crate::pipelines::span_pipeline::{GoldenSpans, SpanPipelineTwin};
use crate::registry::{Bench, Stimulus, Twin};
use crate::stall::StallPattern;
use crate::stream::stream_twin::{drive_lanes, BeatFifo, LaneRun, LaneTwin, RecordReader};
use crate::units::quadric_unit::QuadricRows;
use rtl::core::registry::NoParams;

/// Output ports in row order: s_axis_tready; lane A tvalid, tdata, tuser, tlast; lane B the
/// same; error.
pub const OUTPUTS: usize = 10;

/// The stream top of span kind `kind` (angular, fast or quadric): its layout and the level
/// above which it holds the units.
pub fn top_of(kind: SpanKind) -> (StreamTop, usize) {
    match kind {
        SpanKind::Quadric => (
            rtl::stream::layout::QUADRIC_STREAM,
            rtl::stream::quadric_stream::HOLD_ABOVE,
        ),
        SpanKind::Angular => (
            rtl::stream::layout::ANGULAR_STREAM,
            rtl::stream::angular_stream::HOLD_ABOVE,
        ),
        SpanKind::Fast(_) => (
            rtl::stream::layout::FAST_STREAM,
            rtl::stream::fast_stream::HOLD_ABOVE,
        ),
        _ => panic!("{kind:?} has no two-lane stream top"),
    }
}

/// Where the wrapped top's input port takes its value from in [`SpanStreamTwin`].
#[derive(Clone, Copy, Debug)]
enum Source {
    Load,
    /// A type-2 record in the load bank (`quadric-unit`'s `first`).
    First,
    Hold,
    /// Field k of the load record (the type-2 one where the top has it: the line's fields
    /// lead it).
    Field(usize),
    /// Active register k.
    Register(usize),
}

/// Twin of `angular-stream`, `fast-stream` and `quadric-stream`.
pub struct SpanStreamTwin {
    top: StreamTop,
    /// The wrapped top's twin, and where each of its input ports takes its value from (matched
    /// by name once, at construction).
    inner: Box<dyn Twin>,
    sources: Vec<Source>,
    reader: RecordReader,
    /// The active registers: n, the nine weights (0 after reset).
    regs: Vec<u64>,
    /// Beats per lane: tdata, tuser (z), tlast.
    lanes: [BeatFifo<(u64, u64, bool)>; 2],
    /// Lines loaded whose last clock has not left the pipeline.
    outstanding: usize,
    /// Clocks the pipeline was held.
    pub held: usize,
}

impl SpanStreamTwin {
    pub fn new(kind: SpanKind) -> Self {
        let (top, hold_above) = top_of(kind);
        let inner: Box<dyn Twin> = match kind {
            SpanKind::Quadric => Box::new(QuadricRows(QuadricTwin::new())),
            _ => Box::new(SpanPipelineTwin::new(kind)),
        };
        let fields = top.full.unwrap_or(top.triangle).fields;
        let sources = crate::registry::find(top.wraps)
            .expect("the wrapped top is registered")
            .ports()
            .0
            .iter()
            .map(|p| match p.name {
                "load" => Source::Load,
                "first" => Source::First,
                "hold" => Source::Hold,
                n => fields
                    .iter()
                    .position(|f| f.name == n)
                    .map(Source::Field)
                    .or_else(|| {
                        SPAN_REGISTERS
                            .fields
                            .iter()
                            .position(|f| f.name == n)
                            .map(Source::Register)
                    })
                    .unwrap_or_else(|| panic!("{}: no value for port {n}", top.block)),
            })
            .collect();
        SpanStreamTwin {
            top,
            inner,
            sources,
            reader: RecordReader::new(&top.records()),
            regs: vec![0; SPAN_REGISTERS.fields.len()],
            lanes: [0, 1]
                .map(|_| BeatFifo::new(rtl::stream::fragment_fifo::FIFO_DEPTH, hold_above)),
            outstanding: 0,
            held: 0,
        }
    }

    fn outputs(&self) -> Vec<u64> {
        let mut o = vec![self.s_ready() as u64];
        for l in &self.lanes {
            let (tdata, tuser, tlast) = l.out.unwrap_or((0, 0, false));
            o.extend([l.out.is_some() as u64, tdata, tuser, tlast as u64]);
        }
        o.push(self.reader.err as u64);
        o
    }
}

impl LaneTwin for SpanStreamTwin {
    const LANES: usize = 2;
    const TUSER: bool = true;
    fn s_ready(&self) -> bool {
        self.reader.s_ready()
    }
    fn idle(&self) -> bool {
        self.reader.idle() && self.outstanding == 0 && self.lanes.iter().all(|l| l.is_empty())
    }
    fn held(&self) -> usize {
        self.held
    }
    fn max_level(&self) -> usize {
        self.lanes.iter().map(|l| l.max_level).max().unwrap_or(0)
    }
}

impl Twin for SpanStreamTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (tdata, tvalid, tlast) = (r[0] as u32, r[1] != 0, r[2] != 0);
        let m_ready = [r[3] != 0, r[4] != 0];
        let out = self.outputs();

        // The pipeline's inputs this clock, in its port order: load (and `first` for a type-2 load
        // record), the load bank's fields, the active registers, hold (either lane's
        // registered level flag).
        let (pend, t) = (self.reader.pend_b, self.reader.type_b);
        let loads = pend && (t == 1 || (t == 2 && self.top.full.is_some()));
        let hold = self.lanes.iter_mut().fold(false, |h, l| l.hold() | h);
        self.held += hold as usize;
        let fields = unpack(
            &self.top.full.unwrap_or(self.top.triangle),
            &self.reader.load_bank,
        );
        let row: Vec<u64> = self
            .sources
            .iter()
            .map(|s| match *s {
                Source::Load => loads as u64,
                Source::First => (t == 2) as u64,
                Source::Hold => hold as u64,
                Source::Field(i) => fields[i],
                Source::Register(i) => self.regs[i],
            })
            .collect();
        // Outputs: ready; lane A valid, x, z, r, g, b; lane B the same; y; last.
        let o = self.inner.step(&row);
        let (ready, last) = (o[0] != 0, o[14] != 0);

        let load_taken = loads && ready;
        let apply = self.top.registers.is_some() && pend && t == 2 && self.outstanding == 0;
        if apply {
            self.regs = unpack(&SPAN_REGISTERS, &self.reader.load_bank);
        }
        self.reader.clock(tdata, tvalid, tlast, load_taken || apply);
        self.outstanding = self.outstanding + load_taken as usize - last as usize;
        for (k, lane) in self.lanes.iter_mut().enumerate() {
            let at = 1 + 6 * k;
            let valid = o[at] != 0;
            let beat = pack_fragment(&[
                o[at + 1],
                o[13],
                valid as u64,
                o[at + 3],
                o[at + 4],
                o[at + 5],
            ]);
            lane.clock(
                m_ready[k],
                (valid || last).then_some((beat as u64, o[at + 2], last)),
            );
        }
        out
    }
}

/// A run: input rows, the twin's outputs, and what happened (`stream_twin::LaneRun`).
pub type SpanStreamRun = LaneRun<2>;

/// Drive `words` into the twin with a producer that leaves a gap (tvalid low) with
/// probability `gap` and each lane's consumer stalled by its pattern, until every word is
/// taken and everything has drained (plus `tail` idle clocks): `stream_twin::drive_lanes`.
pub fn drive(
    kind: SpanKind,
    words: &[Word],
    seed: u64,
    gap: f64,
    stalls: &mut [StallPattern; 2],
    tail: usize,
) -> SpanStreamRun {
    let mut twin = SpanStreamTwin::new(kind);
    drive_lanes(&mut twin, words, seed ^ 0xA9_6E1A, gap, stalls, tail)
}

/// The stimulus's scene: the lines of `kind` of `n` seeded lit triangles (the span pipeline
/// bench's), in walk order, and the default context's registers.
pub fn scene(kind: SpanKind, seed: u64, n: usize) -> (Vec<SpanJob>, ShadingRegs) {
    let tris = match kind {
        // Triangles whose quadric stays in the unit's range (the quadric bench's).
        SpanKind::Quadric => crate::units::quadric_unit::triangles(n, seed),
        _ => lit_triangles(seed, n),
    };
    let g = GoldenSpans::new(kind, &tris);
    (g.spans, g.regs)
}

/// Each lane's beats of `words` through the stream without a stall (the order and content
/// every stalled run must reproduce).
pub fn reference_beats(kind: SpanKind, words: &[Word]) -> [Vec<Beat>; 2] {
    drive(
        kind,
        words,
        1,
        0.0,
        &mut [StallPattern::never(), StallPattern::never()],
        20,
    )
    .beats
}

/// The stall patterns of a bench run: lane A's and lane B's consumers, independent.
pub fn stalls(seed: u64, p: f64) -> [StallPattern; 2] {
    [
        StallPattern::new(seed, p),
        StallPattern::new(seed ^ 0xB_B0B, p),
    ]
}

/// The bench stimulus of the stream top of `kind`.
fn stimulus(kind: SpanKind, n: usize, seed: u64) -> Stimulus {
    let (spans, regs) = scene(kind, seed, n);
    let words = span_stream_words(kind, &spans, &regs);
    let run = drive(kind, &words, seed, 0.1, &mut stalls(seed, 0.25), 8);
    // Golden: the protocol (exact), and each lane's beats in the order of the same words
    // without a stall (whose colours and depths the span pipeline's bench checks against the
    // golden method, and `tests/span_stream.rs` against that pipeline's RTL).
    let reference = reference_beats(kind, &words);
    let mut k = [0usize; 2];
    let expected = run
        .outputs
        .iter()
        .zip(&run.rows)
        .map(|(o, r)| {
            let mut e = vec![Expected::Word(o[0])];
            for lane in 0..2 {
                let at = 1 + 4 * lane;
                let (data, tuser) = if o[at] != 0 {
                    let b = &reference[lane][k[lane]];
                    k[lane] += (r[3 + lane] != 0) as usize;
                    (Expected::Word(b.tdata()), Expected::Word(b.z as u32 as u64))
                } else {
                    (Expected::DontCare, Expected::DontCare)
                };
                e.extend([
                    Expected::Word(o[at]),
                    data,
                    tuser,
                    Expected::Word(o[at + 3]),
                ]);
            }
            e.push(Expected::Word(o[9]));
            e
        })
        .collect();
    assert_eq!(
        k,
        [0, 1].map(|l| reference[l].len()),
        "every beat delivered"
    );
    Stimulus {
        rows: run.rows,
        expected,
        compare: vec![Compare::Exact; OUTPUTS],
    }
}

/// The span kind of `fast-stream` built with `p`.
pub fn fast_kind(p: &FastPipelineParams) -> SpanKind {
    SpanKind::Fast(p.0.name)
}

impl Bench for AngularStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 3;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        stimulus(SpanKind::Angular, n, seed)
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(SpanStreamTwin::new(SpanKind::Angular))
    }
}

impl Bench for QuadricStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 3;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        stimulus(SpanKind::Quadric, n, seed)
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(SpanStreamTwin::new(SpanKind::Quadric))
    }
}

impl Bench for FastStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 3;
    fn stimulus(p: &FastPipelineParams, n: usize, seed: u64) -> Stimulus {
        stimulus(fast_kind(p), n, seed)
    }
    fn twin(p: &FastPipelineParams) -> Box<dyn Twin> {
        Box::new(SpanStreamTwin::new(fast_kind(p)))
    }
}
