//! `subdivision-stream`: the subdivision raster pipe (`subdivision-raster`: the four-triangle
//! block feeding one BVI per lane, SPEC §6–§7) behind AXI4-Stream interfaces, in place of
//! `subdivision-raster`'s 2 250 flat set-up pins: one record per parent triangle in on a
//! 32-bit stream, and fragments out on four 64-bit streams, one per lane (sub-triangle K's
//! pixels on `m_axis_lK_*`), each with its own back-pressure. Golden: `subdivision-raster`'s
//! (the same fragments, in the same order on each lane, whatever the stalls), itself checked
//! against the golden `subdivision` method (and Gouraud through the four-triangle block).
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─► SubdivisionRaster ─┬─ lane 0 ─► FIFO (128) ─► m_axis_l0
//!  (32 bit)   (record type, errors)  sw0..sw85       lw0..lw85         ▲ hold        ├─ lane 1 ─► FIFO (128) ─► m_axis_l1
//!                                                                      │             ├─ lane 2 ─► FIFO (128) ─► m_axis_l2
//!                                                                      │             └─ lane 3 ─► FIFO (128) ─► m_axis_l3
//!                                                                      └──── any FIFO's level ◄──┘
//! ```
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `s_axis_tdata` | in | set-up word, 32 bits (layout: `rtl::stream::layout::SUBDIVISION_STREAM`, `rtl/README.md`) |
//! | `s_axis_tvalid`, `s_axis_tlast` | in | AXI4-Stream; `tlast` on a record's last word |
//! | `s_axis_tready` | out | a word is accepted on `tvalid & tready` |
//! | `m_axis_l0_tready` … `m_axis_l3_tready` | in | each lane's consumer takes its beat on `tvalid & tready`; any may be low for any time |
//! | `m_axis_lK_tvalid` | out | a beat is offered on lane K (held, with its data, until taken) |
//! | `m_axis_lK_tdata` | out | 64 bits: `x`, `y`, `pixel` (1: a fragment), `red`, `green`, `blue` (the `pixel-stream` beat) |
//! | `m_axis_lK_tlast` | out | the beat is the lane's last event of its parent |
//! | `error` | out | sticky: a record with an unknown type or the wrong length was dropped |
//!
//! No `tuser`: the depth stays with the frame writer, as for `gouraud-stream` (the parent's
//! depth plane, in software).
//!
//! # Records (`rtl::stream::layout::SUBDIVISION_STREAM`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1, a parent; the other bits 0), then 86 payload words:
//! `subdivision-raster`'s set-up ports in port order (the shared edge increments, each lane's
//! walk, each lane's twelve signed Q16.16 BVI words), a field never straddling two words. A
//! record whose `tlast` comes before or after its length, or with an unknown type, is dropped
//! whole (up to its `tlast`) and sets `error`. There are no registers: the BVI words carry the
//! colours.
//!
//! # Lanes
//! `subdivision-raster` gives up to four pixels per clock, one per lane. Each lane has its own
//! stream, so a consumer with four write ports takes all four per clock; each lane's beats
//! come in the pipe's order. Lane K marks its last event of a parent with `tlast` (a beat with
//! `pixel` = 0 and every other `tdata` bit 0 when that event has no pixel), so each stream
//! alone counts parents.
//!
//! # Handshake, latency, throughput
//! - Two word banks, as in the other stream tops: the receive bank takes the record being
//!   streamed in; a complete record moves in one clock to the load bank when that is free,
//!   and the receive bank takes the next one. `s_axis_tready` is low only while a complete
//!   record waits in the receive bank. The load bank loads when the four-triangle block is
//!   `ready` (before the current parent's last rows, so the next set-up overlaps the walk).
//! - Each lane's beats enter its own 128-entry FIFO (`fragment_fifo`). The four-triangle
//!   block is held (its `hold`: no event on any lane this clock, none lost) in the clock after
//!   any FIFO held more than 125 beats (the hold is registered): from the clock a level first
//!   reaches 126, at most `EVENT_TO_FRAGMENT` + 1 = 2 more beats arrive on a lane, so no
//!   FIFO holds more than 128 and none overflows. With every `tready` high each FIFO holds at
//!   most one beat and the block is never held.
//! - Throughput: the pipe's — up to four fragments per clock — as long as the set-up words
//!   keep ahead: a parent's record is 87 words at one word per clock, so a run of parents
//!   whose longest lane walk is shorter than that is set-up bound.
//! - Latency: a parent record's last word accepted in clock t → its first beats offered in
//!   clock t + 8 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 4 clocks through `subdivision-raster`, 2 through the FIFO and its output register).
//! - The fragment streams come from output registers (`m_axis_*_t*` are register outputs).
//!
//! # Overflow, error budget
//! None of its own: the FIFOs cannot overflow (above); the data are `subdivision-raster`'s,
//! bit for bit (addresses exact, colours within 1 LSB of the rounded plane value).
//!
//! Latency (the block's `LATENCY`): 8 clocks, a parent record's last word to its first fragment beats, up to four fragments per clock.

use rust_hdl::prelude::*;

use crate::core::registry::RtlBlock;
use crate::pipelines::subdivision_raster::SubdivisionRaster;
use crate::stream::fragment_fifo::LaneFifo;
use crate::stream::record_reader::{RecordReader, INDEX_BITS};
use crate::units::intensity_interpolator::IntensityInterpolator;

/// Clocks from a four-triangle event to its fragment at `subdivision-raster`'s outputs.
pub const EVENT_TO_FRAGMENT: usize = IntensityInterpolator::LATENCY;
/// Each lane's FIFO depth (entries).
pub const FIFO_DEPTH: usize = crate::stream::fragment_fifo::FIFO_DEPTH;
/// The FIFO level above which the four-triangle block is held (the clock after: `hold` is
/// registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::hw_block! {
    /// The subdivision raster pipe with AXI4-Stream set-up and fragment streams (see the
    /// header).
    pub struct SubdivisionStream(clock) as "subdivision-stream" {
        summary: "AXI4-Stream top of the subdivision raster pipe: 32-bit parent records in, four 64-bit fragment streams (one per sub-triangle lane) out with back-pressure (a FIFO per lane and the four-triangle block's hold)",
        latency: 2 + <SubdivisionRaster as RtlBlock>::LATENCY + 2
            => "a parent record's last word to its first fragment beats, up to four fragments per clock",
        multipliers: 0,
        in {
            s_axis_tdata: Bits<32>, s_axis_tvalid: Bit, s_axis_tlast: Bit,
            m_axis_l0_tready: Bit, m_axis_l1_tready: Bit, m_axis_l2_tready: Bit,
            m_axis_l3_tready: Bit,
        }
        out {
            s_axis_tready: Bit,
            m_axis_l0_tvalid: Bit, m_axis_l0_tdata: Bits<64>, m_axis_l0_tlast: Bit,
            m_axis_l1_tvalid: Bit, m_axis_l1_tdata: Bits<64>, m_axis_l1_tlast: Bit,
            m_axis_l2_tvalid: Bit, m_axis_l2_tdata: Bits<64>, m_axis_l2_tlast: Bit,
            m_axis_l3_tvalid: Bit, m_axis_l3_tdata: Bits<64>, m_axis_l3_tlast: Bit,
            error: Bit,
        }
        /// The record banks, the field selects and the wrapped top (`core.pipe`): generated.
        pub core: SubdivisionStreamCore,
        // Fragment side: a FIFO per lane, the hold from any one's level.
        lane0: LaneFifo, lane1: LaneFifo, lane2: LaneFifo, lane3: LaneFifo,
        hold_above: Constant<Bits<8>> = Constant::new((HOLD_ABOVE as u64).into()),
        hold_q: DFF<Bit>,
        beat_l0: Signal<Local, Bits<64>>, beat_l1: Signal<Local, Bits<64>>,
        beat_l2: Signal<Local, Bits<64>>, beat_l3: Signal<Local, Bits<64>>,
        tlast_bit: Constant<Bits<33>> = Constant::new((1u64 << 32).into()),
        no_tail: Constant<Bits<33>> = Constant::new(0u64.into()),
        no_beat: Constant<Bits<64>> = Constant::new(0u64.into()),
        frag_l0: Signal<Local, Bits<64>>, frag_l1: Signal<Local, Bits<64>>,
        frag_l2: Signal<Local, Bits<64>>, frag_l3: Signal<Local, Bits<64>>,
        tail_l0: Signal<Local, Bits<33>>, tail_l1: Signal<Local, Bits<33>>,
        tail_l2: Signal<Local, Bits<33>>, tail_l3: Signal<Local, Bits<33>>,
    }
}

impl Logic for SubdivisionStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, core, lane0, lane1, lane2, lane3);
        // The fragment beats the generated core packs.
        self.beat_l0.next = self.core.beat_l0.val();
        self.beat_l1.next = self.core.beat_l1.val();
        self.beat_l2.next = self.core.beat_l2.val();
        self.beat_l3.next = self.core.beat_l3.val();
        dff_setup!(self, clock, hold_q);
        // Set-up side: the generated core (record reader, load bank, word banks, field
        // selects).
        self.core.s_axis_tdata.next = self.s_axis_tdata.val();
        self.core.s_axis_tvalid.next = self.s_axis_tvalid.val();
        self.core.s_axis_tlast.next = self.s_axis_tlast.val();
        self.s_axis_tready.next = self.core.s_axis_tready.val();
        self.error.next = self.core.error.val();

        // Fragment side: a beat per lane for each pixel and for the lane's last event of a
        // parent (which may carry only its `tlast`: then its tdata is 0).
        // A FIFO's inputs take one assignment each (from the locals `frag_lK`, `tail_lK`):
        // a default-then-override on a sub-block's input glitches it every time this block
        // runs, the FIFO's block reruns and glitches its outputs (default 0, then the
        // register), which this block reads — under Icarus that ping-pong never settled
        // (Verilator, which schedules by block, ran it).
        self.hold_q.d.next = self.lane0.over.val()
            | self.lane1.over.val()
            | self.lane2.over.val()
            | self.lane3.over.val();
        self.core.hold.next = self.hold_q.q.val();
        self.lane0.push.next = self.core.valid_l0.val() | self.core.done_l0.val();
        self.frag_l0.next = self.no_beat.val();
        if self.core.valid_l0.val() {
            self.frag_l0.next = self.beat_l0.val();
        }
        self.tail_l0.next = self.no_tail.val();
        if self.core.done_l0.val() {
            self.tail_l0.next = self.tlast_bit.val();
        }
        self.lane0.beat.next = self.frag_l0.val();
        self.lane0.tail.next = self.tail_l0.val();
        self.lane0.tready.next = self.m_axis_l0_tready.val();
        self.lane0.hold_above.next = self.hold_above.val();
        self.lane1.push.next = self.core.valid_l1.val() | self.core.done_l1.val();
        self.frag_l1.next = self.no_beat.val();
        if self.core.valid_l1.val() {
            self.frag_l1.next = self.beat_l1.val();
        }
        self.tail_l1.next = self.no_tail.val();
        if self.core.done_l1.val() {
            self.tail_l1.next = self.tlast_bit.val();
        }
        self.lane1.beat.next = self.frag_l1.val();
        self.lane1.tail.next = self.tail_l1.val();
        self.lane1.tready.next = self.m_axis_l1_tready.val();
        self.lane1.hold_above.next = self.hold_above.val();
        self.lane2.push.next = self.core.valid_l2.val() | self.core.done_l2.val();
        self.frag_l2.next = self.no_beat.val();
        if self.core.valid_l2.val() {
            self.frag_l2.next = self.beat_l2.val();
        }
        self.tail_l2.next = self.no_tail.val();
        if self.core.done_l2.val() {
            self.tail_l2.next = self.tlast_bit.val();
        }
        self.lane2.beat.next = self.frag_l2.val();
        self.lane2.tail.next = self.tail_l2.val();
        self.lane2.tready.next = self.m_axis_l2_tready.val();
        self.lane2.hold_above.next = self.hold_above.val();
        self.lane3.push.next = self.core.valid_l3.val() | self.core.done_l3.val();
        self.frag_l3.next = self.no_beat.val();
        if self.core.valid_l3.val() {
            self.frag_l3.next = self.beat_l3.val();
        }
        self.tail_l3.next = self.no_tail.val();
        if self.core.done_l3.val() {
            self.tail_l3.next = self.tlast_bit.val();
        }
        self.lane3.beat.next = self.frag_l3.val();
        self.lane3.tail.next = self.tail_l3.val();
        self.lane3.tready.next = self.m_axis_l3_tready.val();
        self.lane3.hold_above.next = self.hold_above.val();
        self.m_axis_l0_tvalid.next = self.lane0.tvalid.val();
        self.m_axis_l0_tdata.next = self.lane0.tdata.val();
        self.m_axis_l0_tlast.next = self.lane0.tlast.val();
        self.m_axis_l1_tvalid.next = self.lane1.tvalid.val();
        self.m_axis_l1_tdata.next = self.lane1.tdata.val();
        self.m_axis_l1_tlast.next = self.lane1.tlast.val();
        self.m_axis_l2_tvalid.next = self.lane2.tvalid.val();
        self.m_axis_l2_tdata.next = self.lane2.tdata.val();
        self.m_axis_l2_tlast.next = self.lane2.tlast.val();
        self.m_axis_l3_tvalid.next = self.lane3.tvalid.val();
        self.m_axis_l3_tdata.next = self.lane3.tdata.val();
        self.m_axis_l3_tlast.next = self.lane3.tlast.val();
    }
}

/// The generated core: `rtl/build.rs` writes it from `rtl::stream::layout::SUBDIVISION_STREAM` (the
/// record banks, the field selects into the wrapped top, the fragment packing).
mod generated {
    use super::*;
    include!(concat!(env!("OUT_DIR"), "/subdivision_stream_core.rs"));
}
pub use generated::SubdivisionStreamCore;

#[cfg(test)]
mod tests {
    use crate::core::registry::RtlBlock;
    use crate::pipelines::subdivision_raster::SubdivisionRaster;

    /// The header's latency, FIFO and record figures are the constants'.
    #[test]
    fn header_figures_are_the_constants() {
        let text = include_str!("subdivision_stream.rs")
            .lines()
            .filter_map(|l| l.strip_prefix("//!"))
            .flat_map(str::split_whitespace)
            .collect::<Vec<_>>()
            .join(" ");
        let (h, e) = (super::HOLD_ABOVE, super::EVENT_TO_FRAGMENT);
        let words =
            crate::stream::layout::payload_words(&crate::stream::layout::SUBDIVISION_PARENT);
        assert!(h + 1 + e < super::FIFO_DEPTH, "the FIFO can overflow");
        for want in [
            format!("{}-entry FIFO", super::FIFO_DEPTH),
            format!("FIFO ({})", super::FIFO_DEPTH),
            format!("more than {h} beats"),
            format!("first reaches {}", h + 1),
            format!("`EVENT_TO_FRAGMENT` + 1 = {} more beats", e + 1),
            format!("holds more than {}", h + 1 + e + 1),
            format!(
                "clock t + {}",
                <super::SubdivisionStream as RtlBlock>::LATENCY
            ),
            format!(
                "{} clocks through `subdivision-raster`",
                <SubdivisionRaster as RtlBlock>::LATENCY
            ),
            format!("then {words} payload words"),
            format!("record is {} words", words + 1),
            format!("sw0..sw{}", words - 1),
        ] {
            assert!(text.contains(&want), "header lacks {want:?}");
        }
    }
}
