//! `subdivision-stream`: the subdivision raster pipe (`subdivision-raster`: the four-triangle
//! block feeding one BVI per lane, SPEC §6–§7) behind AXI4-Stream interfaces, in place of
//! `subdivision-raster`'s 2 106 flat set-up pins: one record per parent triangle in on a
//! 32-bit stream, and fragments out on four 64-bit streams, one per lane (sub-triangle K's
//! pixels on `m_axis_lK_*`), each with its own back-pressure. Golden: `subdivision-raster`'s
//! (the same fragments, in the same order on each lane, whatever the stalls), itself checked
//! against the golden `subdivision` method (and Gouraud through the four-triangle block).
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─► SubdivisionRaster ─┬─ lane 0 ─► FIFO (128) ─► m_axis_l0
//!  (32 bit)   (record type, errors)  sw0..sw70       lw0..lw70         ▲ hold        ├─ lane 1 ─► FIFO (128) ─► m_axis_l1
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
//! A header word (bits 3..0: 1, a parent; the other bits 0), then 71 payload words:
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
//!   keep ahead: a parent's record is 72 words at one word per clock, so a run of parents
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
use crate::stream::fragment_fifo::FragmentFifo;
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
        pub pipe: SubdivisionRaster,
        /// Set-up side: the record reader (one record type, the parent).
        rd: RecordReader,
        /// A parent waits in the load bank.
        pend_b: DFF<Bit>, transfer: Signal<Local, Bit>,
        tri_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::SUBDIVISION_PARENT) as u64).into()),
        no_words: Constant<Bits<INDEX_BITS>> = Constant::new(0u64.into()),
        /// The word the reader takes, and which payload word it is (+ 1).
        in_word: Signal<Local, Bits<32>>, take_word: Signal<Local, Bit>,
        word_index: Signal<Local, Bits<INDEX_BITS>>,
        // Fragment side: a FIFO per lane, the hold from any one's level.
        lane0: FragmentFifo, lane1: FragmentFifo, lane2: FragmentFifo, lane3: FragmentFifo,
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
        // BEGIN GENERATED by rtl::stream::layout::generated_rtl
        // The receive bank (payload words of the record being received).
        sw0: DFF<Bits<32>>,
        sw1: DFF<Bits<32>>,
        sw2: DFF<Bits<32>>,
        sw3: DFF<Bits<32>>,
        sw4: DFF<Bits<32>>,
        sw5: DFF<Bits<32>>,
        sw6: DFF<Bits<32>>,
        sw7: DFF<Bits<32>>,
        sw8: DFF<Bits<32>>,
        sw9: DFF<Bits<32>>,
        sw10: DFF<Bits<32>>,
        sw11: DFF<Bits<32>>,
        sw12: DFF<Bits<32>>,
        sw13: DFF<Bits<32>>,
        sw14: DFF<Bits<32>>,
        sw15: DFF<Bits<32>>,
        sw16: DFF<Bits<32>>,
        sw17: DFF<Bits<32>>,
        sw18: DFF<Bits<32>>,
        sw19: DFF<Bits<32>>,
        sw20: DFF<Bits<32>>,
        sw21: DFF<Bits<32>>,
        sw22: DFF<Bits<32>>,
        sw23: DFF<Bits<32>>,
        sw24: DFF<Bits<32>>,
        sw25: DFF<Bits<32>>,
        sw26: DFF<Bits<32>>,
        sw27: DFF<Bits<32>>,
        sw28: DFF<Bits<32>>,
        sw29: DFF<Bits<32>>,
        sw30: DFF<Bits<32>>,
        sw31: DFF<Bits<32>>,
        sw32: DFF<Bits<32>>,
        sw33: DFF<Bits<32>>,
        sw34: DFF<Bits<32>>,
        sw35: DFF<Bits<32>>,
        sw36: DFF<Bits<32>>,
        sw37: DFF<Bits<32>>,
        sw38: DFF<Bits<32>>,
        sw39: DFF<Bits<32>>,
        sw40: DFF<Bits<32>>,
        sw41: DFF<Bits<32>>,
        sw42: DFF<Bits<32>>,
        sw43: DFF<Bits<32>>,
        sw44: DFF<Bits<32>>,
        sw45: DFF<Bits<32>>,
        sw46: DFF<Bits<32>>,
        sw47: DFF<Bits<32>>,
        sw48: DFF<Bits<32>>,
        sw49: DFF<Bits<32>>,
        sw50: DFF<Bits<32>>,
        sw51: DFF<Bits<32>>,
        sw52: DFF<Bits<32>>,
        sw53: DFF<Bits<32>>,
        sw54: DFF<Bits<32>>,
        sw55: DFF<Bits<32>>,
        sw56: DFF<Bits<32>>,
        sw57: DFF<Bits<32>>,
        sw58: DFF<Bits<32>>,
        sw59: DFF<Bits<32>>,
        sw60: DFF<Bits<32>>,
        sw61: DFF<Bits<32>>,
        sw62: DFF<Bits<32>>,
        sw63: DFF<Bits<32>>,
        sw64: DFF<Bits<32>>,
        sw65: DFF<Bits<32>>,
        sw66: DFF<Bits<32>>,
        sw67: DFF<Bits<32>>,
        sw68: DFF<Bits<32>>,
        sw69: DFF<Bits<32>>,
        sw70: DFF<Bits<32>>,
        // The load bank (the complete record waiting for the pipeline).
        lw0: DFF<Bits<32>>,
        lw1: DFF<Bits<32>>,
        lw2: DFF<Bits<32>>,
        lw3: DFF<Bits<32>>,
        lw4: DFF<Bits<32>>,
        lw5: DFF<Bits<32>>,
        lw6: DFF<Bits<32>>,
        lw7: DFF<Bits<32>>,
        lw8: DFF<Bits<32>>,
        lw9: DFF<Bits<32>>,
        lw10: DFF<Bits<32>>,
        lw11: DFF<Bits<32>>,
        lw12: DFF<Bits<32>>,
        lw13: DFF<Bits<32>>,
        lw14: DFF<Bits<32>>,
        lw15: DFF<Bits<32>>,
        lw16: DFF<Bits<32>>,
        lw17: DFF<Bits<32>>,
        lw18: DFF<Bits<32>>,
        lw19: DFF<Bits<32>>,
        lw20: DFF<Bits<32>>,
        lw21: DFF<Bits<32>>,
        lw22: DFF<Bits<32>>,
        lw23: DFF<Bits<32>>,
        lw24: DFF<Bits<32>>,
        lw25: DFF<Bits<32>>,
        lw26: DFF<Bits<32>>,
        lw27: DFF<Bits<32>>,
        lw28: DFF<Bits<32>>,
        lw29: DFF<Bits<32>>,
        lw30: DFF<Bits<32>>,
        lw31: DFF<Bits<32>>,
        lw32: DFF<Bits<32>>,
        lw33: DFF<Bits<32>>,
        lw34: DFF<Bits<32>>,
        lw35: DFF<Bits<32>>,
        lw36: DFF<Bits<32>>,
        lw37: DFF<Bits<32>>,
        lw38: DFF<Bits<32>>,
        lw39: DFF<Bits<32>>,
        lw40: DFF<Bits<32>>,
        lw41: DFF<Bits<32>>,
        lw42: DFF<Bits<32>>,
        lw43: DFF<Bits<32>>,
        lw44: DFF<Bits<32>>,
        lw45: DFF<Bits<32>>,
        lw46: DFF<Bits<32>>,
        lw47: DFF<Bits<32>>,
        lw48: DFF<Bits<32>>,
        lw49: DFF<Bits<32>>,
        lw50: DFF<Bits<32>>,
        lw51: DFF<Bits<32>>,
        lw52: DFF<Bits<32>>,
        lw53: DFF<Bits<32>>,
        lw54: DFF<Bits<32>>,
        lw55: DFF<Bits<32>>,
        lw56: DFF<Bits<32>>,
        lw57: DFF<Bits<32>>,
        lw58: DFF<Bits<32>>,
        lw59: DFF<Bits<32>>,
        lw60: DFF<Bits<32>>,
        lw61: DFF<Bits<32>>,
        lw62: DFF<Bits<32>>,
        lw63: DFF<Bits<32>>,
        lw64: DFF<Bits<32>>,
        lw65: DFF<Bits<32>>,
        lw66: DFF<Bits<32>>,
        lw67: DFF<Bits<32>>,
        lw68: DFF<Bits<32>>,
        lw69: DFF<Bits<32>>,
        lw70: DFF<Bits<32>>,
        frag_pixel_bit: Constant<Bits<64>> = Constant::new((1u64 << 24).into()),
        beat_l0_data: Signal<Local, Bits<64>>,
        beat_l1_data: Signal<Local, Bits<64>>,
        beat_l2_data: Signal<Local, Bits<64>>,
        beat_l3_data: Signal<Local, Bits<64>>,
        // END GENERATED
    }
}

impl Logic for SubdivisionStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pipe, rd, lane0, lane1, lane2, lane3);
        dff_setup!(self, clock, pend_b, hold_q);
        // Set-up side: the record reader (`record_reader`) takes a word while no complete
        // record waits in the receive bank, and names the payload word it is.
        self.rd.head.next = self.s_axis_tdata.val().get_bits::<4>(0);
        self.rd.tvalid.next = self.s_axis_tvalid.val();
        self.rd.tlast.next = self.s_axis_tlast.val();
        self.rd.len1.next = self.tri_words.val();
        self.rd.len2.next = self.no_words.val();
        self.s_axis_tready.next = self.rd.tready.val();
        self.in_word.next = self.s_axis_tdata.val();
        self.take_word.next = self.rd.take_word.val();
        self.word_index.next = self.rd.index.val();
        self.error.next = self.rd.error.val();

        // A complete record moves to the load bank when that is free; it loads when the
        // four-triangle block is ready.
        self.transfer.next = self.rd.pending.val() & !self.pend_b.q.val();
        self.rd.take_record.next = self.transfer.val();
        if self.transfer.val() {
            self.pend_b.d.next = true;
        }
        self.pipe.load.next = self.pend_b.q.val();
        if self.pend_b.q.val() & self.pipe.ready.val() {
            self.pend_b.d.next = false;
        }

        // BEGIN GENERATED by rtl::stream::layout::generated_rtl
        dff_setup!(self, clock, sw0, sw1, sw2, sw3, sw4, sw5, sw6, sw7, sw8);
        dff_setup!(self, clock, sw9, sw10, sw11, sw12, sw13, sw14, sw15, sw16, sw17);
        dff_setup!(self, clock, sw18, sw19, sw20, sw21, sw22, sw23, sw24, sw25, sw26);
        dff_setup!(self, clock, sw27, sw28, sw29, sw30, sw31, sw32, sw33, sw34, sw35);
        dff_setup!(self, clock, sw36, sw37, sw38, sw39, sw40, sw41, sw42, sw43, sw44);
        dff_setup!(self, clock, sw45, sw46, sw47, sw48, sw49, sw50, sw51, sw52, sw53);
        dff_setup!(self, clock, sw54, sw55, sw56, sw57, sw58, sw59, sw60, sw61, sw62);
        dff_setup!(self, clock, sw63, sw64, sw65, sw66, sw67, sw68, sw69, sw70, lw0);
        dff_setup!(self, clock, lw1, lw2, lw3, lw4, lw5, lw6, lw7, lw8, lw9);
        dff_setup!(self, clock, lw10, lw11, lw12, lw13, lw14, lw15, lw16, lw17, lw18);
        dff_setup!(self, clock, lw19, lw20, lw21, lw22, lw23, lw24, lw25, lw26, lw27);
        dff_setup!(self, clock, lw28, lw29, lw30, lw31, lw32, lw33, lw34, lw35, lw36);
        dff_setup!(self, clock, lw37, lw38, lw39, lw40, lw41, lw42, lw43, lw44, lw45);
        dff_setup!(self, clock, lw46, lw47, lw48, lw49, lw50, lw51, lw52, lw53, lw54);
        dff_setup!(self, clock, lw55, lw56, lw57, lw58, lw59, lw60, lw61, lw62, lw63);
        dff_setup!(self, clock, lw64, lw65, lw66, lw67, lw68, lw69, lw70);
        // Payload word k is the (k + 1)-th word of a record.
        if self.take_word.val() & (self.word_index.val() == 1) {
            self.sw0.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 2) {
            self.sw1.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 3) {
            self.sw2.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 4) {
            self.sw3.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 5) {
            self.sw4.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 6) {
            self.sw5.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 7) {
            self.sw6.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 8) {
            self.sw7.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 9) {
            self.sw8.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 10) {
            self.sw9.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 11) {
            self.sw10.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 12) {
            self.sw11.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 13) {
            self.sw12.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 14) {
            self.sw13.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 15) {
            self.sw14.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 16) {
            self.sw15.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 17) {
            self.sw16.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 18) {
            self.sw17.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 19) {
            self.sw18.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 20) {
            self.sw19.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 21) {
            self.sw20.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 22) {
            self.sw21.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 23) {
            self.sw22.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 24) {
            self.sw23.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 25) {
            self.sw24.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 26) {
            self.sw25.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 27) {
            self.sw26.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 28) {
            self.sw27.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 29) {
            self.sw28.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 30) {
            self.sw29.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 31) {
            self.sw30.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 32) {
            self.sw31.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 33) {
            self.sw32.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 34) {
            self.sw33.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 35) {
            self.sw34.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 36) {
            self.sw35.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 37) {
            self.sw36.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 38) {
            self.sw37.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 39) {
            self.sw38.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 40) {
            self.sw39.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 41) {
            self.sw40.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 42) {
            self.sw41.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 43) {
            self.sw42.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 44) {
            self.sw43.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 45) {
            self.sw44.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 46) {
            self.sw45.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 47) {
            self.sw46.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 48) {
            self.sw47.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 49) {
            self.sw48.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 50) {
            self.sw49.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 51) {
            self.sw50.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 52) {
            self.sw51.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 53) {
            self.sw52.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 54) {
            self.sw53.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 55) {
            self.sw54.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 56) {
            self.sw55.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 57) {
            self.sw56.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 58) {
            self.sw57.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 59) {
            self.sw58.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 60) {
            self.sw59.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 61) {
            self.sw60.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 62) {
            self.sw61.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 63) {
            self.sw62.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 64) {
            self.sw63.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 65) {
            self.sw64.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 66) {
            self.sw65.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 67) {
            self.sw66.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 68) {
            self.sw67.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 69) {
            self.sw68.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 70) {
            self.sw69.d.next = self.in_word.val();
        }
        if self.take_word.val() & (self.word_index.val() == 71) {
            self.sw70.d.next = self.in_word.val();
        }
        // A complete record moves to the load bank when that is free.
        if self.transfer.val() {
            self.lw0.d.next = self.sw0.q.val();
            self.lw1.d.next = self.sw1.q.val();
            self.lw2.d.next = self.sw2.q.val();
            self.lw3.d.next = self.sw3.q.val();
            self.lw4.d.next = self.sw4.q.val();
            self.lw5.d.next = self.sw5.q.val();
            self.lw6.d.next = self.sw6.q.val();
            self.lw7.d.next = self.sw7.q.val();
            self.lw8.d.next = self.sw8.q.val();
            self.lw9.d.next = self.sw9.q.val();
            self.lw10.d.next = self.sw10.q.val();
            self.lw11.d.next = self.sw11.q.val();
            self.lw12.d.next = self.sw12.q.val();
            self.lw13.d.next = self.sw13.q.val();
            self.lw14.d.next = self.sw14.q.val();
            self.lw15.d.next = self.sw15.q.val();
            self.lw16.d.next = self.sw16.q.val();
            self.lw17.d.next = self.sw17.q.val();
            self.lw18.d.next = self.sw18.q.val();
            self.lw19.d.next = self.sw19.q.val();
            self.lw20.d.next = self.sw20.q.val();
            self.lw21.d.next = self.sw21.q.val();
            self.lw22.d.next = self.sw22.q.val();
            self.lw23.d.next = self.sw23.q.val();
            self.lw24.d.next = self.sw24.q.val();
            self.lw25.d.next = self.sw25.q.val();
            self.lw26.d.next = self.sw26.q.val();
            self.lw27.d.next = self.sw27.q.val();
            self.lw28.d.next = self.sw28.q.val();
            self.lw29.d.next = self.sw29.q.val();
            self.lw30.d.next = self.sw30.q.val();
            self.lw31.d.next = self.sw31.q.val();
            self.lw32.d.next = self.sw32.q.val();
            self.lw33.d.next = self.sw33.q.val();
            self.lw34.d.next = self.sw34.q.val();
            self.lw35.d.next = self.sw35.q.val();
            self.lw36.d.next = self.sw36.q.val();
            self.lw37.d.next = self.sw37.q.val();
            self.lw38.d.next = self.sw38.q.val();
            self.lw39.d.next = self.sw39.q.val();
            self.lw40.d.next = self.sw40.q.val();
            self.lw41.d.next = self.sw41.q.val();
            self.lw42.d.next = self.sw42.q.val();
            self.lw43.d.next = self.sw43.q.val();
            self.lw44.d.next = self.sw44.q.val();
            self.lw45.d.next = self.sw45.q.val();
            self.lw46.d.next = self.sw46.q.val();
            self.lw47.d.next = self.sw47.q.val();
            self.lw48.d.next = self.sw48.q.val();
            self.lw49.d.next = self.sw49.q.val();
            self.lw50.d.next = self.sw50.q.val();
            self.lw51.d.next = self.sw51.q.val();
            self.lw52.d.next = self.sw52.q.val();
            self.lw53.d.next = self.sw53.q.val();
            self.lw54.d.next = self.sw54.q.val();
            self.lw55.d.next = self.sw55.q.val();
            self.lw56.d.next = self.sw56.q.val();
            self.lw57.d.next = self.sw57.q.val();
            self.lw58.d.next = self.sw58.q.val();
            self.lw59.d.next = self.sw59.q.val();
            self.lw60.d.next = self.sw60.q.val();
            self.lw61.d.next = self.sw61.q.val();
            self.lw62.d.next = self.sw62.q.val();
            self.lw63.d.next = self.sw63.q.val();
            self.lw64.d.next = self.sw64.q.val();
            self.lw65.d.next = self.sw65.q.val();
            self.lw66.d.next = self.sw66.q.val();
            self.lw67.d.next = self.sw67.q.val();
            self.lw68.d.next = self.sw68.q.val();
            self.lw69.d.next = self.sw69.q.val();
            self.lw70.d.next = self.sw70.q.val();
        }
        // Triangle fields: the pipeline's set-up ports.
        self.pipe.w_f.next = self.lw0.q.val().get_bits::<12>(0);
        self.pipe.w_r.next = self.lw0.q.val().get_bits::<13>(12);
        self.pipe.w_d.next = self.lw1.q.val().get_bits::<13>(0);
        self.pipe.a_f.next = self.lw1.q.val().get_bits::<12>(13);
        self.pipe.a_r.next = self.lw2.q.val().get_bits::<13>(0);
        self.pipe.a_d.next = self.lw2.q.val().get_bits::<13>(13);
        self.pipe.t_f.next = self.lw3.q.val().get_bits::<12>(0);
        self.pipe.t_r.next = self.lw3.q.val().get_bits::<13>(12);
        self.pipe.t_d.next = self.lw4.q.val().get_bits::<13>(0);
        self.pipe.w_b0_l0.next = self.lw4.q.val().get_bits::<12>(13);
        self.pipe.w_e0_l0.next = self.lw5.q.val().get_bits::<13>(0);
        self.pipe.a_b0_l0.next = self.lw5.q.val().get_bits::<12>(13);
        self.pipe.a_e0_l0.next = self.lw6.q.val().get_bits::<13>(0);
        self.pipe.a_third_l0.next = self.lw6.q.val().get_bit(13);
        self.pipe.t_b0_l0.next = self.lw6.q.val().get_bits::<12>(14);
        self.pipe.t_e0_l0.next = self.lw7.q.val().get_bits::<13>(0);
        self.pipe.t_adjacent_l0.next = self.lw7.q.val().get_bit(13);
        self.pipe.y_top_l0.next = self.lw7.q.val().get_bits::<12>(14);
        self.pipe.rows_l0.next = self.lw8.q.val().get_bits::<12>(0);
        self.pipe.y_switch_l0.next = self.lw8.q.val().get_bits::<12>(12);
        self.pipe.dir_neg_l0.next = self.lw8.q.val().get_bit(24);
        self.pipe.w_b0_l1.next = self.lw9.q.val().get_bits::<12>(0);
        self.pipe.w_e0_l1.next = self.lw9.q.val().get_bits::<13>(12);
        self.pipe.a_b0_l1.next = self.lw10.q.val().get_bits::<12>(0);
        self.pipe.a_e0_l1.next = self.lw10.q.val().get_bits::<13>(12);
        self.pipe.a_third_l1.next = self.lw10.q.val().get_bit(25);
        self.pipe.t_b0_l1.next = self.lw11.q.val().get_bits::<12>(0);
        self.pipe.t_e0_l1.next = self.lw11.q.val().get_bits::<13>(12);
        self.pipe.t_adjacent_l1.next = self.lw11.q.val().get_bit(25);
        self.pipe.y_top_l1.next = self.lw12.q.val().get_bits::<12>(0);
        self.pipe.rows_l1.next = self.lw12.q.val().get_bits::<12>(12);
        self.pipe.y_switch_l1.next = self.lw13.q.val().get_bits::<12>(0);
        self.pipe.dir_neg_l1.next = self.lw13.q.val().get_bit(12);
        self.pipe.w_b0_l2.next = self.lw13.q.val().get_bits::<12>(13);
        self.pipe.w_e0_l2.next = self.lw14.q.val().get_bits::<13>(0);
        self.pipe.a_b0_l2.next = self.lw14.q.val().get_bits::<12>(13);
        self.pipe.a_e0_l2.next = self.lw15.q.val().get_bits::<13>(0);
        self.pipe.a_third_l2.next = self.lw15.q.val().get_bit(13);
        self.pipe.t_b0_l2.next = self.lw15.q.val().get_bits::<12>(14);
        self.pipe.t_e0_l2.next = self.lw16.q.val().get_bits::<13>(0);
        self.pipe.t_adjacent_l2.next = self.lw16.q.val().get_bit(13);
        self.pipe.y_top_l2.next = self.lw16.q.val().get_bits::<12>(14);
        self.pipe.rows_l2.next = self.lw17.q.val().get_bits::<12>(0);
        self.pipe.y_switch_l2.next = self.lw17.q.val().get_bits::<12>(12);
        self.pipe.dir_neg_l2.next = self.lw17.q.val().get_bit(24);
        self.pipe.w_b0_l3.next = self.lw18.q.val().get_bits::<12>(0);
        self.pipe.w_e0_l3.next = self.lw18.q.val().get_bits::<13>(12);
        self.pipe.a_b0_l3.next = self.lw19.q.val().get_bits::<12>(0);
        self.pipe.a_e0_l3.next = self.lw19.q.val().get_bits::<13>(12);
        self.pipe.a_third_l3.next = self.lw19.q.val().get_bit(25);
        self.pipe.t_b0_l3.next = self.lw20.q.val().get_bits::<12>(0);
        self.pipe.t_e0_l3.next = self.lw20.q.val().get_bits::<13>(12);
        self.pipe.t_adjacent_l3.next = self.lw20.q.val().get_bit(25);
        self.pipe.y_top_l3.next = self.lw21.q.val().get_bits::<12>(0);
        self.pipe.rows_l3.next = self.lw21.q.val().get_bits::<12>(12);
        self.pipe.y_switch_l3.next = self.lw22.q.val().get_bits::<12>(0);
        self.pipe.dir_neg_l3.next = self.lw22.q.val().get_bit(12);
        self.pipe.r_start_l0.next = self.lw23.q.val();
        self.pipe.r_short_l0.next = self.lw24.q.val();
        self.pipe.r_long_l0.next = self.lw25.q.val();
        self.pipe.r_line_l0.next = self.lw26.q.val();
        self.pipe.g_start_l0.next = self.lw27.q.val();
        self.pipe.g_short_l0.next = self.lw28.q.val();
        self.pipe.g_long_l0.next = self.lw29.q.val();
        self.pipe.g_line_l0.next = self.lw30.q.val();
        self.pipe.b_start_l0.next = self.lw31.q.val();
        self.pipe.b_short_l0.next = self.lw32.q.val();
        self.pipe.b_long_l0.next = self.lw33.q.val();
        self.pipe.b_line_l0.next = self.lw34.q.val();
        self.pipe.r_start_l1.next = self.lw35.q.val();
        self.pipe.r_short_l1.next = self.lw36.q.val();
        self.pipe.r_long_l1.next = self.lw37.q.val();
        self.pipe.r_line_l1.next = self.lw38.q.val();
        self.pipe.g_start_l1.next = self.lw39.q.val();
        self.pipe.g_short_l1.next = self.lw40.q.val();
        self.pipe.g_long_l1.next = self.lw41.q.val();
        self.pipe.g_line_l1.next = self.lw42.q.val();
        self.pipe.b_start_l1.next = self.lw43.q.val();
        self.pipe.b_short_l1.next = self.lw44.q.val();
        self.pipe.b_long_l1.next = self.lw45.q.val();
        self.pipe.b_line_l1.next = self.lw46.q.val();
        self.pipe.r_start_l2.next = self.lw47.q.val();
        self.pipe.r_short_l2.next = self.lw48.q.val();
        self.pipe.r_long_l2.next = self.lw49.q.val();
        self.pipe.r_line_l2.next = self.lw50.q.val();
        self.pipe.g_start_l2.next = self.lw51.q.val();
        self.pipe.g_short_l2.next = self.lw52.q.val();
        self.pipe.g_long_l2.next = self.lw53.q.val();
        self.pipe.g_line_l2.next = self.lw54.q.val();
        self.pipe.b_start_l2.next = self.lw55.q.val();
        self.pipe.b_short_l2.next = self.lw56.q.val();
        self.pipe.b_long_l2.next = self.lw57.q.val();
        self.pipe.b_line_l2.next = self.lw58.q.val();
        self.pipe.r_start_l3.next = self.lw59.q.val();
        self.pipe.r_short_l3.next = self.lw60.q.val();
        self.pipe.r_long_l3.next = self.lw61.q.val();
        self.pipe.r_line_l3.next = self.lw62.q.val();
        self.pipe.g_start_l3.next = self.lw63.q.val();
        self.pipe.g_short_l3.next = self.lw64.q.val();
        self.pipe.g_long_l3.next = self.lw65.q.val();
        self.pipe.g_line_l3.next = self.lw66.q.val();
        self.pipe.b_start_l3.next = self.lw67.q.val();
        self.pipe.b_short_l3.next = self.lw68.q.val();
        self.pipe.b_long_l3.next = self.lw69.q.val();
        self.pipe.b_line_l3.next = self.lw70.q.val();
        // The fragment beat of lane L0 (`pixel` is the pipeline's `valid_l0`).
        self.beat_l0_data.next = bit_cast::<64, 12>(self.pipe.x_l0.val())
            | (bit_cast::<64, 12>(self.pipe.y_l0.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red_l0.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green_l0.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue_l0.val()) << 48);
        self.beat_l0.next = self.beat_l0_data.val();
        if self.pipe.valid_l0.val() {
            self.beat_l0.next = self.beat_l0_data.val() | self.frag_pixel_bit.val();
        }
        // The fragment beat of lane L1 (`pixel` is the pipeline's `valid_l1`).
        self.beat_l1_data.next = bit_cast::<64, 12>(self.pipe.x_l1.val())
            | (bit_cast::<64, 12>(self.pipe.y_l1.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red_l1.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green_l1.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue_l1.val()) << 48);
        self.beat_l1.next = self.beat_l1_data.val();
        if self.pipe.valid_l1.val() {
            self.beat_l1.next = self.beat_l1_data.val() | self.frag_pixel_bit.val();
        }
        // The fragment beat of lane L2 (`pixel` is the pipeline's `valid_l2`).
        self.beat_l2_data.next = bit_cast::<64, 12>(self.pipe.x_l2.val())
            | (bit_cast::<64, 12>(self.pipe.y_l2.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red_l2.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green_l2.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue_l2.val()) << 48);
        self.beat_l2.next = self.beat_l2_data.val();
        if self.pipe.valid_l2.val() {
            self.beat_l2.next = self.beat_l2_data.val() | self.frag_pixel_bit.val();
        }
        // The fragment beat of lane L3 (`pixel` is the pipeline's `valid_l3`).
        self.beat_l3_data.next = bit_cast::<64, 12>(self.pipe.x_l3.val())
            | (bit_cast::<64, 12>(self.pipe.y_l3.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red_l3.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green_l3.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue_l3.val()) << 48);
        self.beat_l3.next = self.beat_l3_data.val();
        if self.pipe.valid_l3.val() {
            self.beat_l3.next = self.beat_l3_data.val() | self.frag_pixel_bit.val();
        }
        // END GENERATED

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
        self.pipe.hold.next = self.hold_q.q.val();
        self.lane0.push.next = self.pipe.valid_l0.val() | self.pipe.done_l0.val();
        self.frag_l0.next = self.no_beat.val();
        if self.pipe.valid_l0.val() {
            self.frag_l0.next = self.beat_l0.val();
        }
        self.tail_l0.next = self.no_tail.val();
        if self.pipe.done_l0.val() {
            self.tail_l0.next = self.tlast_bit.val();
        }
        self.lane0.beat.next = self.frag_l0.val();
        self.lane0.tail.next = self.tail_l0.val();
        self.lane0.tready.next = self.m_axis_l0_tready.val();
        self.lane0.hold_above.next = self.hold_above.val();
        self.lane1.push.next = self.pipe.valid_l1.val() | self.pipe.done_l1.val();
        self.frag_l1.next = self.no_beat.val();
        if self.pipe.valid_l1.val() {
            self.frag_l1.next = self.beat_l1.val();
        }
        self.tail_l1.next = self.no_tail.val();
        if self.pipe.done_l1.val() {
            self.tail_l1.next = self.tlast_bit.val();
        }
        self.lane1.beat.next = self.frag_l1.val();
        self.lane1.tail.next = self.tail_l1.val();
        self.lane1.tready.next = self.m_axis_l1_tready.val();
        self.lane1.hold_above.next = self.hold_above.val();
        self.lane2.push.next = self.pipe.valid_l2.val() | self.pipe.done_l2.val();
        self.frag_l2.next = self.no_beat.val();
        if self.pipe.valid_l2.val() {
            self.frag_l2.next = self.beat_l2.val();
        }
        self.tail_l2.next = self.no_tail.val();
        if self.pipe.done_l2.val() {
            self.tail_l2.next = self.tlast_bit.val();
        }
        self.lane2.beat.next = self.frag_l2.val();
        self.lane2.tail.next = self.tail_l2.val();
        self.lane2.tready.next = self.m_axis_l2_tready.val();
        self.lane2.hold_above.next = self.hold_above.val();
        self.lane3.push.next = self.pipe.valid_l3.val() | self.pipe.done_l3.val();
        self.frag_l3.next = self.no_beat.val();
        if self.pipe.valid_l3.val() {
            self.frag_l3.next = self.beat_l3.val();
        }
        self.tail_l3.next = self.no_tail.val();
        if self.pipe.done_l3.val() {
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

    /// The generated regions of this file are what `rtl::stream::layout` gives; with
    /// `SHADECORE_REGENERATE=1` the test rewrites them.
    #[test]
    fn subdivision_stream_rtl_is_generated() {
        crate::stream::layout::check_generated(&crate::stream::layout::SUBDIVISION_STREAM).unwrap();
    }
}
