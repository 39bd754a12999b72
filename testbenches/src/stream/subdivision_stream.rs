//! Bench of `subdivision-stream` (`rtl::stream::subdivision_stream`), the AXI4-Stream top of the
//! subdivision raster pipe: its bit-exact twin (the record reader, the word banks and a FIFO
//! per lane with the four-triangle block's hold, around `subdivision-raster`'s twin), driven
//! by the seeded producer and consumers of the other stream tops' benches (a word stays until
//! taken; each lane's `tready` low in a quarter of the clocks and in long stretches, the four
//! lanes independently).
//!
//! Golden: the stream adds no arithmetic. Its golden expectation is the protocol (every
//! `tready`, `tvalid`, `tlast`, `error`, exact) and, for the data, each lane's beats in order
//! are those of the same words without a stall, whose colours `subdivision-raster`'s bench
//! checks against the golden `subdivision` planes (and `tests/subdivision_stream.rs` against
//! that pipe's RTL run through its own ports and the golden planes).

use golden::shading::subdivision::SubdivisionSetup;
use golden::units::four_triangle::LANES;
use pipeline::axis::{Beat, Word};
use pipeline::subdivision::subdivision_words;
use pipeline::subdivision::{SubJob, PIPE_HOLD_AT};
use rtl::core::registry::NoParams;
use rtl::stream::layout::{pack_fragment, unpack, SUBDIVISION_PARENT, SUBDIVISION_STREAM};
use rtl::stream::subdivision_stream::{SubdivisionStream, FIFO_DEPTH, HOLD_ABOVE};

use crate::harness::{Compare, Expected};
use crate::pipelines::subdivision_raster::SubRows;
use crate::registry::{Bench, Stimulus, Twin};
use crate::stall::StallPattern;
use crate::stream::stream_twin::{drive_lanes, BeatFifo, LaneRun, LaneTwin, RecordReader};

/// Output ports in row order: s_axis_tready; per lane tvalid, tdata, tlast; error.
pub const OUTPUTS: usize = 2 + 3 * LANES;
/// Input ports: s_axis_tdata, tvalid, tlast, each lane's `m_axis_lK_tready`.
pub const INPUTS: usize = 3 + LANES;

/// Twin of `subdivision-stream`.
pub struct SubdivisionStreamTwin {
    inner: SubRows,
    reader: RecordReader,
    /// Beats per lane: tdata, tlast.
    lanes: Vec<BeatFifo<(u64, bool)>>,
    /// Parents loaded, and each lane's parent ends seen.
    loaded: usize,
    ends: [usize; LANES],
    /// Clocks the four-triangle block was held.
    held: usize,
}

impl Default for SubdivisionStreamTwin {
    fn default() -> Self {
        Self::new()
    }
}

impl SubdivisionStreamTwin {
    pub fn new() -> Self {
        SubdivisionStreamTwin {
            inner: SubRows::default(),
            reader: RecordReader::new(&SUBDIVISION_STREAM.records()),
            lanes: (0..LANES)
                .map(|_| BeatFifo::new(FIFO_DEPTH, HOLD_ABOVE))
                .collect(),
            loaded: 0,
            ends: [0; LANES],
            held: 0,
        }
    }

    fn outputs(&self) -> Vec<u64> {
        let mut o = vec![self.s_ready() as u64];
        for l in &self.lanes {
            let (tdata, tlast) = l.out.unwrap_or((0, false));
            o.extend([l.out.is_some() as u64, tdata, tlast as u64]);
        }
        o.push(self.reader.err as u64);
        o
    }
}

impl LaneTwin for SubdivisionStreamTwin {
    const LANES: usize = LANES;
    const TUSER: bool = false;
    fn s_ready(&self) -> bool {
        self.reader.s_ready()
    }
    fn idle(&self) -> bool {
        self.reader.idle()
            && self.ends.iter().all(|&e| e == self.loaded)
            && self.lanes.iter().all(|l| l.is_empty())
    }
    fn held(&self) -> usize {
        self.held
    }
    fn max_level(&self) -> usize {
        self.lanes.iter().map(|l| l.max_level).max().unwrap_or(0)
    }
}

impl Twin for SubdivisionStreamTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (tdata, tvalid, tlast) = (r[0] as u32, r[1] != 0, r[2] != 0);
        let out = self.outputs();
        // The raster pipe's inputs this clock: load, the load bank's fields, hold (any lane's
        // registered level flag).
        let pend = self.reader.pend_b;
        let hold = self.lanes.iter_mut().fold(false, |h, l| l.hold() | h);
        self.held += hold as usize;
        let mut row = vec![pend as u64];
        row.extend(unpack(&SUBDIVISION_PARENT, &self.reader.load_bank));
        debug_assert_eq!(row.len(), PIPE_HOLD_AT);
        row.push(hold as u64);
        // Outputs: ready, then per lane valid x y red green blue done.
        let o = self.inner.step(&row);
        let load_taken = pend && o[0] != 0;
        self.reader.clock(tdata, tvalid, tlast, load_taken);
        self.loaded += load_taken as usize;
        for (k, lane) in self.lanes.iter_mut().enumerate() {
            let at = 1 + 7 * k;
            let (valid, done) = (o[at] != 0, o[at + 6] != 0);
            // A beat without a pixel (the lane's parent end) carries only its `tlast`.
            let beat = if valid {
                pack_fragment(&[o[at + 1], o[at + 2], 1, o[at + 3], o[at + 4], o[at + 5]]) as u64
            } else {
                0
            };
            lane.clock(r[3 + k] != 0, (valid || done).then_some((beat, done)));
            self.ends[k] += done as usize;
        }
        out
    }
}

/// A run: input rows, the twin's outputs, and what happened (`stream_twin::LaneRun`).
pub type SubdivisionStreamRun = LaneRun<LANES>;

/// Drive `words` into the twin with a producer that leaves a gap (tvalid low) with
/// probability `gap` and each lane's consumer stalled by its pattern, until every word is
/// taken and everything has drained (plus `tail` idle clocks): `stream_twin::drive_lanes`.
pub fn drive(
    words: &[Word],
    seed: u64,
    gap: f64,
    stalls: &mut [StallPattern; LANES],
    tail: usize,
) -> SubdivisionStreamRun {
    let mut twin = SubdivisionStreamTwin::new();
    drive_lanes(&mut twin, words, seed ^ 0x5_0B_D1, gap, stalls, tail)
}

/// `n` seeded parents shaded by the `subdivision` method (the raster pipe's bench's), with
/// their golden set-ups.
pub fn scene(seed: u64, n: usize) -> Vec<(SubJob, Option<SubdivisionSetup>)> {
    crate::pipelines::subdivision_raster::random_jobs(seed, n)
}

/// Each lane's beats of `words` through the stream without a stall (the order and content
/// every stalled run must reproduce).
pub fn reference_beats(words: &[Word]) -> [Vec<Beat>; LANES] {
    drive(
        words,
        1,
        0.0,
        &mut std::array::from_fn(|_| StallPattern::never()),
        20,
    )
    .beats
}

/// The stall patterns of a bench run: each lane's consumer, independent.
pub fn stalls(seed: u64, p: f64) -> [StallPattern; LANES] {
    std::array::from_fn(|k| StallPattern::new(seed ^ (0xB_B0B * k as u64), p))
}

impl Bench for SubdivisionStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 4;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let jobs: Vec<SubJob> = scene(seed, n).into_iter().map(|j| j.0).collect();
        let words = subdivision_words(&jobs);
        let run = drive(&words, seed, 0.1, &mut stalls(seed, 0.25), 8);
        // Golden: the protocol (exact), and each lane's beats in the order of the same words
        // without a stall (whose colours the raster pipe's bench checks against the golden
        // planes, and `tests/subdivision_stream.rs` against that pipe's RTL).
        let reference = reference_beats(&words);
        let mut k = [0usize; LANES];
        let expected = run
            .outputs
            .iter()
            .zip(&run.rows)
            .map(|(o, r)| {
                let mut e = vec![Expected::Word(o[0])];
                for lane in 0..LANES {
                    let at = 1 + 3 * lane;
                    let data = if o[at] != 0 {
                        let b = &reference[lane][k[lane]];
                        k[lane] += (r[3 + lane] != 0) as usize;
                        Expected::Word(b.tdata())
                    } else {
                        Expected::DontCare
                    };
                    e.extend([Expected::Word(o[at]), data, Expected::Word(o[at + 2])]);
                }
                e.push(Expected::Word(o[OUTPUTS - 1]));
                e
            })
            .collect();
        assert_eq!(
            k,
            std::array::from_fn(|l| reference[l].len()),
            "every beat delivered"
        );
        Stimulus {
            rows: run.rows,
            expected,
            compare: vec![Compare::Exact; OUTPUTS],
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(SubdivisionStreamTwin::new())
    }
}
