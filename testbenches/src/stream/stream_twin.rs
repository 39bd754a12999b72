//! The parts every stream top's twin shares (`pixel_stream`, `gouraud_stream`, `cubic_stream`,
//! `span_stream`, `subdivision_stream`): the record reader with its two word banks, and the
//! fragment FIFO with its output register and the registered hold — written once, as the
//! hardware's are the same in each top (`rtl/src/stream/*_stream.rs`) — and the seeded producer and
//! consumers that drive a top with a fragment stream per lane ([`drive_lanes`]).

use std::collections::VecDeque;

use pipeline::axis::{Beat, Word};
use rtl::stream::layout::{payload_words, Record};

use crate::registry::Twin;
use crate::stall::{SplitMix, StallPattern};

/// The twin of a stream top with a fragment stream per lane (`angular-stream`, `fast-stream`,
/// `quadric-stream`, `subdivision-stream`), for [`drive_lanes`]. Its input rows are
/// `s_axis_tdata`, `tvalid`, `tlast`, then each lane's `tready`; its outputs
/// `s_axis_tready`, then per lane `tvalid`, `tdata`, `tuser` (where the top has it), `tlast`, then
/// `error`.
pub trait LaneTwin: Twin {
    /// Fragment streams.
    const LANES: usize;
    /// Whether each lane's outputs include `tuser`.
    const TUSER: bool;
    /// `s_axis_tready` in the current clock.
    fn s_ready(&self) -> bool;
    /// Nothing waiting, nothing in flight, nothing to deliver.
    fn idle(&self) -> bool;
    /// Clocks the wrapped top was held so far.
    fn held(&self) -> usize;
    /// The most beats a lane's FIFO held.
    fn max_level(&self) -> usize;
}

/// A run of [`drive_lanes`] over `L` lanes: input rows, the twin's outputs, and what happened.
pub struct LaneRun<const L: usize> {
    pub rows: Vec<Vec<u64>>,
    pub outputs: Vec<Vec<u64>>,
    /// The beats each lane's consumer took, in order.
    pub beats: [Vec<Beat>; L],
    /// Clocks the wrapped top was held.
    pub held: usize,
    /// Clocks each lane's consumer was stalled.
    pub consumer_stalls: [usize; L],
    /// The most beats a lane's FIFO held.
    pub max_level: usize,
}

/// Drive `words` into `twin` with a producer that leaves a gap (tvalid low) with probability
/// `gap` (its draws seeded by `seed`) and each lane's consumer stalled by its pattern in
/// `stalls`, until every word is taken and everything has drained (plus `tail` idle clocks).
pub fn drive_lanes<T: LaneTwin, const L: usize>(
    twin: &mut T,
    words: &[Word],
    seed: u64,
    gap: f64,
    stalls: &mut [StallPattern; L],
    tail: usize,
) -> LaneRun<L> {
    assert_eq!(L, T::LANES, "a stall pattern per lane");
    let per = 3 + T::TUSER as usize;
    let mut rng = SplitMix::new(seed);
    let mut run = LaneRun {
        rows: Vec::new(),
        outputs: Vec::new(),
        beats: std::array::from_fn(|_| Vec::new()),
        held: 0,
        consumer_stalls: [0; L],
        max_level: 0,
    };
    let (mut next, mut showing, mut idle_clocks) = (0usize, false, 0usize);
    let limit = 200 + words.len() * 200 + 400_000;
    while idle_clocks < tail {
        assert!(run.rows.len() < limit, "the stream does not drain");
        if !showing && next < words.len() {
            showing = rng.unit() >= gap;
        }
        let (w, last) = if showing { words[next] } else { (0, false) };
        let m_ready: Vec<bool> = stalls.iter_mut().map(|s| !s.next_stalled()).collect();
        let mut row = vec![w as u64, showing as u64, last as u64];
        row.extend(m_ready.iter().map(|&r| r as u64));
        let s_ready = twin.s_ready();
        let o = twin.step(&row);
        if showing && s_ready {
            next += 1;
            showing = false;
        }
        for (k, &ready) in m_ready.iter().enumerate() {
            let at = 1 + per * k;
            if o[at] != 0 && ready {
                let tuser = if T::TUSER { o[at + 2] } else { 0 };
                run.beats[k].push(Beat::read(o[at + 1], tuser, o[at + per - 1] != 0));
            }
            run.consumer_stalls[k] += !ready as usize;
        }
        run.rows.push(row);
        run.outputs.push(o);
        if next == words.len() && twin.idle() {
            idle_clocks += 1;
        }
    }
    run.held = twin.held();
    run.max_level = twin.max_level();
    run
}

/// The set-up side: header / word count, the receive bank, the load bank.
pub struct RecordReader {
    /// (header code, payload words) of each record type.
    types: Vec<(u32, usize)>,
    count: usize,
    rec_type: u32,
    /// A complete record waits in the receive bank (`s_axis_tready` low).
    pending: bool,
    skip: bool,
    /// Sticky: a record was dropped.
    pub err: bool,
    bank: Vec<u32>,
    /// The load bank and its record's type, valid while `pend_b`.
    pub load_bank: Vec<u32>,
    pub pend_b: bool,
    pub type_b: u32,
}

impl RecordReader {
    pub fn new(records: &[Record]) -> Self {
        let types: Vec<(u32, usize)> = records.iter().map(|r| (r.code, payload_words(r))).collect();
        let n = types.iter().map(|t| t.1).max().unwrap_or(0);
        RecordReader {
            types,
            count: 0,
            rec_type: 0,
            pending: false,
            skip: false,
            err: false,
            bank: vec![0; n],
            load_bank: vec![0; n],
            pend_b: false,
            type_b: 0,
        }
    }

    /// `s_axis_tready` in the current clock.
    pub fn s_ready(&self) -> bool {
        !self.pending
    }

    /// No record being received or waiting in either bank.
    pub fn idle(&self) -> bool {
        !self.pending && !self.pend_b && self.count == 0
    }

    /// One clock edge: the set-up stream's word, and whether the load bank's record was used
    /// this clock (loaded or applied; decided from the registers before the edge).
    pub fn clock(&mut self, tdata: u32, tvalid: bool, tlast: bool, consumed: bool) {
        let transfer = self.pending && !self.pend_b;
        let (bank0, type0) = (self.bank.clone(), self.rec_type);
        let accept = tvalid && !self.pending;
        let size = |t: u32| self.types.iter().find(|k| k.0 == t).map(|k| k.1);
        let expected = size(self.rec_type);
        if accept && self.skip {
            if tlast {
                self.skip = false;
            }
        } else if accept && self.count == 0 {
            self.rec_type = tdata & 0xF;
            self.count = 1;
            if tlast {
                // A record without payload.
                self.err = true;
                self.count = 0;
            } else if size(self.rec_type).is_none() {
                self.err = true;
                self.skip = true;
                self.count = 0;
            }
        } else if accept {
            self.bank[self.count - 1] = tdata;
            let at_end = Some(self.count) == expected;
            self.count += 1;
            if tlast {
                self.count = 0;
                if at_end {
                    self.pending = true;
                } else {
                    self.err = true;
                }
            } else if at_end {
                // Longer than its type: drop the rest.
                self.err = true;
                self.skip = true;
                self.count = 0;
            }
        }
        if consumed {
            self.pend_b = false;
        }
        if transfer {
            self.pending = false;
            self.pend_b = true;
            self.type_b = type0;
            self.load_bank = bank0;
        }
    }
}

/// The fragment side: the FIFO of beats `T`, the output register offering one on `m_axis_*`,
/// and the hold registered from the FIFO's level.
pub struct BeatFifo<T> {
    depth: usize,
    hold_above: usize,
    fifo: VecDeque<T>,
    /// The output register: the beat offered.
    pub out: Option<T>,
    hold_q: bool,
    /// Clocks the pipeline was held.
    pub held: usize,
    /// The most beats the FIFO held.
    pub max_level: usize,
}

impl<T: Copy> BeatFifo<T> {
    pub fn new(depth: usize, hold_above: usize) -> Self {
        BeatFifo {
            depth,
            hold_above,
            fifo: VecDeque::new(),
            out: None,
            hold_q: false,
            held: 0,
            max_level: 0,
        }
    }

    /// The pipeline's `hold` this clock (the level register above `hold_above` in the clock
    /// before); registers the next one.
    pub fn hold(&mut self) -> bool {
        let h = self.hold_q;
        self.hold_q = self.fifo.len() > self.hold_above;
        self.held += h as usize;
        h
    }

    /// Nothing in the FIFO or the output register.
    pub fn is_empty(&self) -> bool {
        self.fifo.is_empty() && self.out.is_none()
    }

    /// One clock edge: the consumer's `tready`, and the beat the pipeline gives this clock.
    pub fn clock(&mut self, m_ready: bool, push: Option<T>) {
        if !self.fifo.is_empty() && (self.out.is_none() || m_ready) {
            self.out = self.fifo.pop_front();
        } else if m_ready {
            self.out = None;
        }
        if let Some(b) = push {
            self.fifo.push_back(b);
            assert!(self.fifo.len() <= self.depth, "twin FIFO overflow");
            self.max_level = self.max_level.max(self.fifo.len());
        }
    }
}

/// A one-lane top's outputs with a depth stream (`pixel-stream`, `cubic-stream`,
/// `textured-stream`): `s_axis_tready`, `m_axis_tvalid`, `tdata`, `tuser`, `tlast`, `error`.
pub fn one_lane_outputs(reader: &RecordReader, fifo: &BeatFifo<(u64, u64, bool)>) -> Vec<u64> {
    let (tdata, tuser, tlast) = fifo.out.unwrap_or((0, 0, false));
    vec![
        reader.s_ready() as u64,
        fifo.out.is_some() as u64,
        tdata,
        tuser,
        tlast as u64,
        reader.err as u64,
    ]
}
