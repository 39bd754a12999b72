//! A fragment FIFO of a stream top: the AXI4-Stream master side of a fragment stream — a
//! FIFO of beats (64-bit `tdata`, and the 32-bit `tuser` with `tlast`), an output register
//! offering one beat, and the level compare the top turns into its pipeline's hold. The
//! two-lane tops (`angular-stream`, `fast-stream`, `quadric-stream`) and `subdivision-stream`
//! (four lanes, `tuser` unused) have one [`LaneFifo`] (128 entries) per lane; the one-lane tops
//! (`pixel-stream`, `cubic-stream`, `textured-stream`, through `one_lane_stream!`) one
//! [`FragmentFifo`] of their own depth. The figures below are [`LaneFifo`]'s.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `push` | in | a beat enters this clock (`beat`, `tail`) |
//! | `beat` | in | 64 bits: the fragment beat (`rtl::stream::layout::FRAGMENT`) |
//! | `tail` | in | 33 bits: bit 32 `tlast`, bits 31..0 `tuser` (the depth) |
//! | `tready` | in | the consumer takes the offered beat on `tvalid & tready` |
//! | `hold_above` | in | 8 bits: the level above which `over` is set |
//! | `tvalid`, `tdata`, `tuser`, `tlast` | out | the offered beat (register outputs; data 0 while `tvalid` is low) |
//! | `over` | out | the FIFO holds more than `hold_above` beats (from the level register) |
//!
//! # Latency, throughput, overflow
//! A beat pushed in clock t is offered from clock t + 2 at the earliest (FIFO, then the output
//! register, which is loaded when empty or when its beat is taken, so a beat per clock flows
//! with `tready` high). A FIFO of 128 entries and an 8-bit level: the top must stop pushing
//! before 128 (it holds its pipeline on `over`; its header gives the bound). No arithmetic.

use rust_hdl::prelude::*;

use crate::core::primitives::Lutram;

/// Entries of a lane's FIFO ([`LaneFifo`]), and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 7;

/// The per-lane FIFO of the two- and four-lane tops: 128 entries, an 8-bit level.
pub type LaneFifo = FragmentFifo<FIFO_BITS, 8>;
const _: () = assert!(8 > FIFO_BITS);

/// A fragment FIFO of 2^`BITS` entries and its output register (see the module header, whose
/// figures are [`LaneFifo`]'s): `LEVEL` is the width of the level counter and of `hold_above`
/// (at least `BITS` + 1, so that a full FIFO's level does not wrap: each user asserts it at
/// compile time). The one-lane tops
/// (`one_lane_stream!`) instantiate it with their own depth.
#[derive(LogicBlock, Default)]
pub struct FragmentFifo<const BITS: usize, const LEVEL: usize> {
    pub clock: Signal<In, Clock>,
    pub push: Signal<In, Bit>,
    pub beat: Signal<In, Bits<64>>,
    pub tail: Signal<In, Bits<33>>,
    pub tready: Signal<In, Bit>,
    pub hold_above: Signal<In, Bits<LEVEL>>,
    pub tvalid: Signal<Out, Bit>,
    pub tdata: Signal<Out, Bits<64>>,
    pub tuser: Signal<Out, Bits<32>>,
    pub tlast: Signal<Out, Bit>,
    pub over: Signal<Out, Bit>,
    fifo_beat: Lutram<Bits<64>, BITS>,
    fifo_tail: Lutram<Bits<33>, BITS>,
    wr_ptr: DFF<Bits<BITS>>,
    rd_ptr: DFF<Bits<BITS>>,
    level: DFF<Bits<LEVEL>>,
    pop: Signal<Local, Bit>,
    out_v: DFF<Bit>,
    out_data: DFF<Bits<64>>,
    out_tail: DFF<Bits<33>>,
}

impl<const BITS: usize, const LEVEL: usize> Logic for FragmentFifo<BITS, LEVEL> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, fifo_beat, fifo_tail);
        dff_setup!(self, clock, wr_ptr, rd_ptr, level, out_v, out_data, out_tail);
        self.over.next = self.level.q.val() > self.hold_above.val();
        self.pop.next = (self.level.q.val() != 0) & (!self.out_v.q.val() | self.tready.val());
        self.fifo_beat.write_enable.next = self.push.val();
        self.fifo_beat.write_address.next = self.wr_ptr.q.val();
        self.fifo_beat.write_data.next = self.beat.val();
        self.fifo_beat.read_address.next = self.rd_ptr.q.val();
        self.fifo_tail.write_enable.next = self.push.val();
        self.fifo_tail.write_address.next = self.wr_ptr.q.val();
        self.fifo_tail.write_data.next = self.tail.val();
        self.fifo_tail.read_address.next = self.rd_ptr.q.val();
        if self.push.val() {
            self.wr_ptr.d.next = self.wr_ptr.q.val() + 1;
        }
        if self.pop.val() {
            self.rd_ptr.d.next = self.rd_ptr.q.val() + 1;
        }
        if self.push.val() & !self.pop.val() {
            self.level.d.next = self.level.q.val() + 1;
        } else if !self.push.val() & self.pop.val() {
            self.level.d.next = self.level.q.val() - 1;
        }
        if self.pop.val() {
            self.out_v.d.next = true;
            self.out_data.d.next = self.fifo_beat.read_data.val();
            self.out_tail.d.next = self.fifo_tail.read_data.val();
        } else if self.tready.val() {
            self.out_v.d.next = false;
        }
        self.tvalid.next = self.out_v.q.val();
        self.tdata.next = 0.into();
        self.tuser.next = 0.into();
        self.tlast.next = false;
        if self.out_v.q.val() {
            self.tdata.next = self.out_data.q.val();
            self.tuser.next = self.out_tail.q.val().get_bits::<32>(0);
            self.tlast.next = self.out_tail.q.val().get_bit(32);
        }
    }
}

/// Checks a two-lane stream top's header (its source `source`) against its constants: the
/// FIFO and hold figures, the overflow bound, the latencies, the line record's words and the
/// line length below which it is set-up bound, and `extra` phrases. Panics naming the first
/// phrase missing.
#[cfg(test)]
pub(crate) fn check_two_lane_header(
    source: &str,
    top: &crate::stream::layout::StreamTop,
    hold_above: usize,
    event_to_fragment: usize,
    latency: usize,
    wrapped_latency: usize,
    extra: &[String],
) {
    // The header as one line of words.
    let text = source
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .flat_map(str::split_whitespace)
        .collect::<Vec<_>>()
        .join(" ");
    let words = crate::stream::layout::payload_words(&top.triangle);
    let wants = [
        format!("{FIFO_DEPTH}-entry FIFO"),
        format!("FIFO ({FIFO_DEPTH})"),
        format!("more than {hold_above} beats"),
        format!("first reaches {}", hold_above + 1),
        format!(
            "`EVENT_TO_FRAGMENT` + 1 = {} more beats",
            event_to_fragment + 1
        ),
        format!("holds more than {}", hold_above + 1 + event_to_fragment + 1),
        format!("clock t + {latency}"),
        format!("{wrapped_latency} clocks through `{}`", top.wraps),
        format!("a line is {words} payload words"),
        format!("record is {} words", words + 1),
        format!("shorter than {} pixels", 2 * (words + 1) - 1),
    ];
    assert!(
        hold_above + 1 + event_to_fragment < FIFO_DEPTH,
        "{}: the FIFO can overflow",
        top.block
    );
    for want in wants.iter().chain(extra) {
        assert!(
            text.contains(want.as_str()),
            "{}: header lacks {want:?}",
            top.block
        );
    }
}
