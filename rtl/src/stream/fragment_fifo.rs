//! One lane's fragment FIFO of a stream top with a stream per lane (`angular-stream`,
//! `fast-stream`, `quadric-stream`; `subdivision-stream`'s four, whose `tuser` is unused): the
//! AXI4-Stream master side of a fragment stream — a 128-entry FIFO of
//! beats (64-bit `tdata`, and the 32-bit `tuser` with `tlast`), an output register offering
//! one beat, and the level compare the top turns into its pipeline's hold. The same logic `cubic-stream` and `pixel-stream`
//! write inline for their one stream; a top with a stream per lane has one of these per lane.
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

/// Entries of the FIFO, and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 7;

crate::hw_block! {
    /// One lane's fragment FIFO and output register (see the module header).
    pub struct FragmentFifo(clock) {
        in { push: Bit, beat: Bits<64>, tail: Bits<33>, tready: Bit, hold_above: Bits<8> }
        out { tvalid: Bit, tdata: Bits<64>, tuser: Bits<32>, tlast: Bit, over: Bit }
        fifo_beat: Lutram<Bits<64>, FIFO_BITS>,
        fifo_tail: Lutram<Bits<33>, FIFO_BITS>,
        wr_ptr: DFF<Bits<FIFO_BITS>>, rd_ptr: DFF<Bits<FIFO_BITS>>, level: DFF<Bits<8>>,
        pop: Signal<Local, Bit>,
        out_v: DFF<Bit>, out_data: DFF<Bits<64>>, out_tail: DFF<Bits<33>>,
    }
}

impl Logic for FragmentFifo {
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
