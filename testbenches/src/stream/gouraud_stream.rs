//! Bench of `gouraud-stream` (`rtl::stream::gouraud_stream`), the AXI4-Stream top of the Gouraud raster
//! pipe: its bit-exact twin (the record reader, the word banks and the FIFO with the address
//! block's hold, around `gouraud-raster`'s twin), driven by the seeded producer and consumer of
//! `pixel-stream`'s bench (a word stays until taken; `tready` low in a quarter of the clocks
//! and in long stretches).
//!
//! Golden: the stream adds no arithmetic. Its golden expectation is the protocol (every
//! `tready`, `tvalid`, `tlast`, `error`, exact) and, for the data, the beats in order are
//! `gouraud-raster`'s events without stalls, whose colours `tests/gouraud_stream.rs` checks
//! against the golden f64 Gouraud planes (within 1 LSB, addresses exact).

use pipeline::axis::{Beat, Word};
use pipeline::gouraud::gouraud_words;
use pipeline::gouraud::{TriangleJob, PIPE_HOLD_AT};
use rtl::core::registry::NoParams;
use rtl::stream::gouraud_stream::{GouraudStream, FIFO_DEPTH, HOLD_ABOVE};
use rtl::stream::layout::{pack_fragment, unpack, GOURAUD_STREAM, GOURAUD_TRIANGLE};

use crate::harness::{Compare, Expected};
use crate::registry::{Bench, Stimulus, Twin};
use crate::stall::{SplitMix, StallPattern};
use crate::stream::stream_twin::{BeatFifo, RecordReader};
use crate::units::address_block::{subpixel_triangle_jobs, GoldenPixel};
use crate::units::intensity_interpolator::PipeRows;

/// Output ports in row order.
pub const OUTPUTS: usize = 5;

/// Twin of `gouraud-stream`.
pub struct GouraudStreamTwin {
    inner: PipeRows,
    reader: RecordReader,
    /// Beats: tdata, tlast.
    fifo: BeatFifo<(u64, bool)>,
    /// Triangles loaded whose `done` has not been seen.
    outstanding: usize,
}

impl Default for GouraudStreamTwin {
    fn default() -> Self {
        Self::new()
    }
}

impl GouraudStreamTwin {
    pub fn new() -> Self {
        GouraudStreamTwin {
            inner: PipeRows::default(),
            reader: RecordReader::new(&GOURAUD_STREAM.records()),
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

    /// Clocks the address block was held.
    pub fn held(&self) -> usize {
        self.fifo.held
    }

    fn outputs(&self) -> Vec<u64> {
        let (tdata, tlast) = self.fifo.out.unwrap_or((0, false));
        vec![
            self.s_ready() as u64,
            self.fifo.out.is_some() as u64,
            tdata,
            tlast as u64,
            self.reader.err as u64,
        ]
    }
}

impl Twin for GouraudStreamTwin {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (tdata, tvalid, tlast, m_ready) = (r[0] as u32, r[1] != 0, r[2] != 0, r[3] != 0);
        let out = self.outputs();

        // The raster pipe's inputs this clock.
        let mut row = vec![self.reader.pend_b as u64];
        row.extend(unpack(&GOURAUD_TRIANGLE, &self.reader.load_bank));
        debug_assert_eq!(row.len(), PIPE_HOLD_AT);
        row.push(self.fifo.hold() as u64);
        let o = self.inner.step(&row);
        let (ready, valid, x, y, rgb, done) = (
            o[0] != 0,
            o[1] != 0,
            o[2],
            o[3],
            [o[4], o[5], o[6]],
            o[7] != 0,
        );

        let load_taken = self.reader.pend_b && ready;
        self.reader.clock(tdata, tvalid, tlast, load_taken);
        self.outstanding = self.outstanding + load_taken as usize - done as usize;
        let beat = pack_fragment(&[x, y, valid as u64, rgb[0], rgb[1], rgb[2]]) as u64;
        self.fifo
            .clock(m_ready, (valid || done).then_some((beat, done)));
        out
    }
}

/// A run: input rows, the twin's outputs, and what happened.
pub struct GouraudStreamRun {
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
    words: &[Word],
    seed: u64,
    gap: f64,
    stalls: &mut StallPattern,
    tail: usize,
) -> GouraudStreamRun {
    let mut twin = GouraudStreamTwin::new();
    let mut rng = SplitMix::new(seed ^ 0x5A5A);
    let mut run = GouraudStreamRun {
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
            run.beats.push(Beat::read(o[2], 0, o[3] != 0));
        }
        run.consumer_stalls += !m_ready as usize;
        run.rows.push(row);
        run.outputs.push(o);
        if next == words.len() && twin.idle() {
            idle_clocks += 1;
        }
    }
    run.held = twin.held();
    run
}

/// `gouraud-raster`'s events for `jobs` without any stall, as beats (the order and content
/// every stalled run must reproduce).
pub fn reference_beats(jobs: &[TriangleJob]) -> Vec<Beat> {
    drive(&gouraud_words(jobs), 1, 0.0, &mut StallPattern::never(), 20).beats
}

/// The stimulus's scene: `n` seeded triangles with random vertex intensities (the
/// `gouraud-raster` bench's) and their golden pixels in walk order.
pub fn scene(seed: u64, n: usize) -> (Vec<TriangleJob>, Vec<GoldenPixel>) {
    subpixel_triangle_jobs(seed, n)
}

impl Bench for GouraudStream {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 20;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let (jobs, _) = scene(seed, n);
        let words = gouraud_words(&jobs);
        let mut stalls = StallPattern::new(seed, 0.25);
        let run = drive(&words, seed, 0.1, &mut stalls, 8);
        // Golden: the protocol (exact), and the beats in the order of the same words through
        // `gouraud-raster` without a stall (whose colours its own bench, and
        // `tests/gouraud_stream.rs`, check against the golden planes).
        let reference = reference_beats(&jobs);
        assert_eq!(run.beats.len(), reference.len(), "every beat delivered");
        let mut k = 0;
        let expected = run
            .outputs
            .iter()
            .zip(&run.rows)
            .map(|(o, r)| {
                let data = if o[1] != 0 {
                    let b = &reference[k];
                    k += (r[3] != 0) as usize;
                    Expected::Word(pack_fragment(&[
                        b.x as u64,
                        b.y as u64,
                        b.pixel as u64,
                        b.rgb[0] as u64,
                        b.rgb[1] as u64,
                        b.rgb[2] as u64,
                    ]) as u64)
                } else {
                    Expected::DontCare
                };
                vec![
                    Expected::Word(o[0]),
                    Expected::Word(o[1]),
                    data,
                    Expected::Word(o[3]),
                    Expected::Word(o[4]),
                ]
            })
            .collect();
        Stimulus {
            rows: run.rows,
            expected,
            compare: vec![Compare::Exact; OUTPUTS],
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(GouraudStreamTwin::new())
    }
}
