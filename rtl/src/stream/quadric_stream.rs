//! `quadric-stream`: the quadric forward-difference unit (`quadric-unit`: a 2-D difference
//! tracker over the line starts and a line generator, three channels, two pixels per clock;
//! SPEC §8) behind the AXI4-Stream interfaces of `angular-stream`, in place of
//! `quadric-unit`'s 1 254 flat set-up pins: a short record per raster line, a long one for a
//! triangle's first line (its coefficients), on a 32-bit stream; fragments out on two 64-bit
//! streams, one per lane (depth on each lane's `tuser`), each with its own back-pressure.
//! Golden: `quadric-unit`'s (the same fragments, in the same order on each lane, whatever the
//! stalls), itself checked against the golden `quadric` method.
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─► QuadricUnit ─┬─ lane A ─► FIFO (128) ─► m_axis_a
//!  (32 bit)   (record type, errors)  sw0..sw39       lw0..lw39    ▲ hold      └─ lane B ─► FIFO (128) ─► m_axis_b
//!                                                                 └───── either FIFO's level ◄──┘
//! ```
//!
//! # Ports
//! `angular-stream`'s, the same widths and meaning: `s_axis_tdata` (32), `s_axis_tvalid`,
//! `s_axis_tlast`, `s_axis_tready`; per lane `m_axis_a_*` and `m_axis_b_*`: `tready` in,
//! `tvalid`, `tdata` (64 bits: `x`, `y`, `pixel`, `red`, `green`, `blue`), `tuser` (the depth
//! `z`, signed Q16.16, 32 bits) and `tlast` (the line's last clock) out; `error` (sticky: a
//! record with an unknown type or the wrong length was dropped).
//!
//! # Records (`rtl::stream::layout::QUADRIC_STREAM`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1 a line, 2 a triangle's first line; the other bits 0), then the
//! record's fields packed LSB first: a line is 4 payload words (y, x0, dir; m; z0; dz), a
//! triangle's first line 40 (the same 4 words in the same places, then per channel I, Dx, Dy,
//! 2A, 2B, C, signed Q34.30, each over two words). A type-2 record loads the unit with `first`
//! = 1 (the tracker takes the coefficients); a type-1 record loads with `first` = 0 and the
//! load bank's coefficient words, which the unit does not read then. No registers: the quadric
//! is lit in the set-up (the sources' software part). A record whose `tlast` comes before or
//! after its length, or with an unknown type, is dropped whole (up to its `tlast`) and sets
//! `error`.
//!
//! # Lanes, handshake, latency, throughput
//! The unit's lane A has pixel 2k of the line in its generator's clock k, lane B pixel 2k + 1;
//! both lanes mark the line's last clock with `tlast` (lane B with a `pixel` = 0 beat when it
//! has no pixel then). A record in the load bank loads when the unit is `ready` (a line is taken
//! in its predecessor's hand-over clock); `s_axis_tready` is low only while a complete record
//! waits in the receive bank.
//! - Each lane's beats enter its own 128-entry FIFO (`fragment_fifo`). The unit is held (its
//!   `hold`: the generator stands still, no pixel is lost) in the clock after either FIFO held
//!   more than 122 beats (the hold is registered): from the clock a level first reaches 123, at
//!   most `EVENT_TO_FRAGMENT` + 1 = 5 more beats arrive on a lane, so neither FIFO holds more
//!   than 128 and none overflows. With both `tready` high each FIFO holds at most one beat and
//!   the unit is never held.
//! - Throughput: two fragments per clock along a line while the set-up words keep ahead: a
//!   line's record is 5 words at one word per clock (a triangle's first line 41), and a line of
//!   m + 1 pixels takes ⌊m/2⌋ + 1 clocks after its start's move, so lines shorter than 9 pixels
//!   are set-up bound.
//! - Latency: a line record's last word accepted in clock t → its first beats offered in
//!   clock t + 8 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 4 clocks through `quadric-unit`, 2 through the FIFO and its output register), when
//!   the unit is ready and the line starts where the tracker stands.
//!
//! # Overflow, error budget
//! None of its own: the FIFOs cannot overflow (above); the data are `quadric-unit`'s, bit for
//! bit (colours within its bound of the golden `quadric`, depth within 4096·2⁻¹⁷ + 2⁻¹⁶ of the
//! f64 plane).
//!
//! Latency (the block's `LATENCY`): 8 clocks, a line record's last word to its first fragment beats (the unit ready, no move to the line's start), two fragments per clock.

use rust_hdl::prelude::*;

use crate::core::registry::RtlBlock;
use crate::stream::fragment_fifo::FragmentFifo;
use crate::stream::record_reader::{RecordReader, INDEX_BITS};
use crate::units::quadric_unit::QuadricUnit;

/// Clocks from a pixel entering the span units to its fragment at `quadric-unit`'s
/// outputs (at most its load-to-first-fragment latency).
pub const EVENT_TO_FRAGMENT: usize = <QuadricUnit as RtlBlock>::LATENCY;
/// Each lane's FIFO depth (entries).
pub const FIFO_DEPTH: usize = crate::stream::fragment_fifo::FIFO_DEPTH;
/// The FIFO level above which the pipeline is held (the clock after: `hold` is registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::hw_block! {
    /// The quadric unit with AXI4-Stream set-up and fragment streams (see the header).
    pub struct QuadricStream(clock) as "quadric-stream" {
        summary: "AXI4-Stream top of the quadric unit: 32-bit line records (a triangle's first line with its coefficients) in, two 64-bit fragment streams (one per lane, depth on tuser) out with back-pressure (a FIFO per lane and the generator's hold)",
        latency: 2 + <QuadricUnit as RtlBlock>::LATENCY + 2
            => "a line record's last word to its first fragment beats (the unit ready, no move to the line's start), two fragments per clock",
        multipliers: <QuadricUnit as RtlBlock>::MULTIPLIERS,
        in {
            s_axis_tdata: Bits<32>, s_axis_tvalid: Bit, s_axis_tlast: Bit,
            m_axis_a_tready: Bit, m_axis_b_tready: Bit,
        }
        out {
            s_axis_tready: Bit,
            m_axis_a_tvalid: Bit, m_axis_a_tdata: Bits<64>, m_axis_a_tuser: Bits<32>, m_axis_a_tlast: Bit,
            m_axis_b_tvalid: Bit, m_axis_b_tdata: Bits<64>, m_axis_b_tuser: Bits<32>, m_axis_b_tlast: Bit,
            error: Bit,
        }
        pub pipe: QuadricUnit,
        /// Set-up side: the record reader (types 1, a line, and 2, a triangle's first line).
        rd: RecordReader,
        /// A record waits in the load bank (`pend_b`), of type `type_b`.
        pend_b: DFF<Bit>, type_b: DFF<Bits<4>>, transfer: Signal<Local, Bit>,
        tri_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::QUADRIC_LINE) as u64).into()),
        full_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::QUADRIC_TRIANGLE) as u64).into()),
        /// The word the reader takes, and which payload word it is (+ 1).
        in_word: Signal<Local, Bits<32>>, take_word: Signal<Local, Bit>,
        word_index: Signal<Local, Bits<INDEX_BITS>>,
        load_taken: Signal<Local, Bit>,
        // Fragment side: a FIFO per lane, the hold from either's level.
        lane_a: FragmentFifo, lane_b: FragmentFifo,
        hold_above: Constant<Bits<8>> = Constant::new((HOLD_ABOVE as u64).into()),
        hold_q: DFF<Bit>,
        beat_a: Signal<Local, Bits<64>>, beat_b: Signal<Local, Bits<64>>,
        tail_a: Signal<Local, Bits<33>>, tail_b: Signal<Local, Bits<33>>,
        tlast_bit: Constant<Bits<33>> = Constant::new((1u64 << 32).into()),
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
        frag_pixel_bit: Constant<Bits<64>> = Constant::new((1u64 << 24).into()),
        beat_a_data: Signal<Local, Bits<64>>,
        beat_b_data: Signal<Local, Bits<64>>,
        // END GENERATED
    }
}

impl Logic for QuadricStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pipe, rd, lane_a, lane_b);
        dff_setup!(self, clock, pend_b, type_b, hold_q);
        // Set-up side: the record reader (`record_reader`) takes a word while no complete
        // record waits in the receive bank, and names the payload word it is.
        self.rd.head.next = self.s_axis_tdata.val().get_bits::<4>(0);
        self.rd.tvalid.next = self.s_axis_tvalid.val();
        self.rd.tlast.next = self.s_axis_tlast.val();
        self.rd.len1.next = self.tri_words.val();
        self.rd.len2.next = self.full_words.val();
        self.s_axis_tready.next = self.rd.tready.val();
        self.in_word.next = self.s_axis_tdata.val();
        self.take_word.next = self.rd.take_word.val();
        self.word_index.next = self.rd.index.val();
        self.error.next = self.rd.error.val();

        // A complete record moves to the load bank when that is free; either type loads when
        // the unit is ready, a triangle's first line (type 2) with `first`.
        self.transfer.next = self.rd.pending.val() & !self.pend_b.q.val();
        self.rd.take_record.next = self.transfer.val();
        if self.transfer.val() {
            self.pend_b.d.next = true;
            self.type_b.d.next = self.rd.rec_type.val();
        }
        self.pipe.load.next = self.pend_b.q.val();
        self.pipe.first.next = self.type_b.q.val() == 2;
        self.load_taken.next = self.pend_b.q.val() & self.pipe.ready.val();
        if self.load_taken.val() {
            self.pend_b.d.next = false;
        }

        // BEGIN GENERATED by rtl::stream::layout::generated_rtl
        dff_setup!(self, clock, sw0, sw1, sw2, sw3, sw4, sw5, sw6, sw7, sw8);
        dff_setup!(self, clock, sw9, sw10, sw11, sw12, sw13, sw14, sw15, sw16, sw17);
        dff_setup!(self, clock, sw18, sw19, sw20, sw21, sw22, sw23, sw24, sw25, sw26);
        dff_setup!(self, clock, sw27, sw28, sw29, sw30, sw31, sw32, sw33, sw34, sw35);
        dff_setup!(self, clock, sw36, sw37, sw38, sw39, lw0, lw1, lw2, lw3, lw4);
        dff_setup!(self, clock, lw5, lw6, lw7, lw8, lw9, lw10, lw11, lw12, lw13);
        dff_setup!(self, clock, lw14, lw15, lw16, lw17, lw18, lw19, lw20, lw21, lw22);
        dff_setup!(self, clock, lw23, lw24, lw25, lw26, lw27, lw28, lw29, lw30, lw31);
        dff_setup!(self, clock, lw32, lw33, lw34, lw35, lw36, lw37, lw38, lw39);
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
        }
        // Triangle fields: the pipeline's set-up ports.
        self.pipe.y.next = self.lw0.q.val().get_bits::<12>(0);
        self.pipe.x0.next = self.lw0.q.val().get_bits::<12>(12);
        self.pipe.dir.next = self.lw0.q.val().get_bit(24);
        self.pipe.m.next = self.lw1.q.val().get_bits::<12>(0);
        self.pipe.z0.next = self.lw2.q.val();
        self.pipe.dz.next = self.lw3.q.val();
        // The quadric triangle record's further fields (loaded with `first`).
        self.pipe.ri.next =
            bit_cast::<64, 32>(self.lw4.q.val()) | (bit_cast::<64, 32>(self.lw5.q.val()) << 32);
        self.pipe.rdx.next =
            bit_cast::<64, 32>(self.lw6.q.val()) | (bit_cast::<64, 32>(self.lw7.q.val()) << 32);
        self.pipe.rdy.next =
            bit_cast::<64, 32>(self.lw8.q.val()) | (bit_cast::<64, 32>(self.lw9.q.val()) << 32);
        self.pipe.ra.next =
            bit_cast::<64, 32>(self.lw10.q.val()) | (bit_cast::<64, 32>(self.lw11.q.val()) << 32);
        self.pipe.rb.next =
            bit_cast::<64, 32>(self.lw12.q.val()) | (bit_cast::<64, 32>(self.lw13.q.val()) << 32);
        self.pipe.rc.next =
            bit_cast::<64, 32>(self.lw14.q.val()) | (bit_cast::<64, 32>(self.lw15.q.val()) << 32);
        self.pipe.gi.next =
            bit_cast::<64, 32>(self.lw16.q.val()) | (bit_cast::<64, 32>(self.lw17.q.val()) << 32);
        self.pipe.gdx.next =
            bit_cast::<64, 32>(self.lw18.q.val()) | (bit_cast::<64, 32>(self.lw19.q.val()) << 32);
        self.pipe.gdy.next =
            bit_cast::<64, 32>(self.lw20.q.val()) | (bit_cast::<64, 32>(self.lw21.q.val()) << 32);
        self.pipe.ga.next =
            bit_cast::<64, 32>(self.lw22.q.val()) | (bit_cast::<64, 32>(self.lw23.q.val()) << 32);
        self.pipe.gb.next =
            bit_cast::<64, 32>(self.lw24.q.val()) | (bit_cast::<64, 32>(self.lw25.q.val()) << 32);
        self.pipe.gc.next =
            bit_cast::<64, 32>(self.lw26.q.val()) | (bit_cast::<64, 32>(self.lw27.q.val()) << 32);
        self.pipe.bi.next =
            bit_cast::<64, 32>(self.lw28.q.val()) | (bit_cast::<64, 32>(self.lw29.q.val()) << 32);
        self.pipe.bdx.next =
            bit_cast::<64, 32>(self.lw30.q.val()) | (bit_cast::<64, 32>(self.lw31.q.val()) << 32);
        self.pipe.bdy.next =
            bit_cast::<64, 32>(self.lw32.q.val()) | (bit_cast::<64, 32>(self.lw33.q.val()) << 32);
        self.pipe.ba.next =
            bit_cast::<64, 32>(self.lw34.q.val()) | (bit_cast::<64, 32>(self.lw35.q.val()) << 32);
        self.pipe.bb.next =
            bit_cast::<64, 32>(self.lw36.q.val()) | (bit_cast::<64, 32>(self.lw37.q.val()) << 32);
        self.pipe.bc.next =
            bit_cast::<64, 32>(self.lw38.q.val()) | (bit_cast::<64, 32>(self.lw39.q.val()) << 32);
        // The fragment beat of lane A (`pixel` is the pipeline's `valid_a`).
        self.beat_a_data.next = bit_cast::<64, 12>(self.pipe.x_a.val())
            | (bit_cast::<64, 12>(self.pipe.y_out.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red_a.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green_a.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue_a.val()) << 48);
        self.beat_a.next = self.beat_a_data.val();
        if self.pipe.valid_a.val() {
            self.beat_a.next = self.beat_a_data.val() | self.frag_pixel_bit.val();
        }
        // The fragment beat of lane B (`pixel` is the pipeline's `valid_b`).
        self.beat_b_data.next = bit_cast::<64, 12>(self.pipe.x_b.val())
            | (bit_cast::<64, 12>(self.pipe.y_out.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red_b.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green_b.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue_b.val()) << 48);
        self.beat_b.next = self.beat_b_data.val();
        if self.pipe.valid_b.val() {
            self.beat_b.next = self.beat_b_data.val() | self.frag_pixel_bit.val();
        }
        // END GENERATED

        // Fragment side: a beat per lane for each fragment, and for the line's last clock
        // (lane B's beat then may carry only its `tlast`).
        self.hold_q.d.next = self.lane_a.over.val() | self.lane_b.over.val();
        self.pipe.hold.next = self.hold_q.q.val();
        self.tail_a.next = bit_cast::<33, 32>(self.pipe.z_a.val());
        self.tail_b.next = bit_cast::<33, 32>(self.pipe.z_b.val());
        if self.pipe.done.val() {
            self.tail_a.next = bit_cast::<33, 32>(self.pipe.z_a.val()) | self.tlast_bit.val();
            self.tail_b.next = bit_cast::<33, 32>(self.pipe.z_b.val()) | self.tlast_bit.val();
        }
        self.lane_a.push.next = self.pipe.valid_a.val() | self.pipe.done.val();
        self.lane_a.beat.next = self.beat_a.val();
        self.lane_a.tail.next = self.tail_a.val();
        self.lane_a.tready.next = self.m_axis_a_tready.val();
        self.lane_a.hold_above.next = self.hold_above.val();
        self.lane_b.push.next = self.pipe.valid_b.val() | self.pipe.done.val();
        self.lane_b.beat.next = self.beat_b.val();
        self.lane_b.tail.next = self.tail_b.val();
        self.lane_b.tready.next = self.m_axis_b_tready.val();
        self.lane_b.hold_above.next = self.hold_above.val();
        self.m_axis_a_tvalid.next = self.lane_a.tvalid.val();
        self.m_axis_a_tdata.next = self.lane_a.tdata.val();
        self.m_axis_a_tuser.next = self.lane_a.tuser.val();
        self.m_axis_a_tlast.next = self.lane_a.tlast.val();
        self.m_axis_b_tvalid.next = self.lane_b.tvalid.val();
        self.m_axis_b_tdata.next = self.lane_b.tdata.val();
        self.m_axis_b_tuser.next = self.lane_b.tuser.val();
        self.m_axis_b_tlast.next = self.lane_b.tlast.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::core::registry::RtlBlock;
    use crate::units::quadric_unit::QuadricUnit;

    /// The header's latency, FIFO and record figures are the constants'.
    #[test]
    fn header_figures_are_the_constants() {
        let top = crate::stream::layout::QUADRIC_STREAM;
        let full = crate::stream::layout::payload_words(&top.full.unwrap());
        let extra = [
            format!("first line {full}"),
            format!("first line {})", full + 1),
        ];
        crate::stream::fragment_fifo::check_two_lane_header(
            include_str!("quadric_stream.rs"),
            &top,
            super::HOLD_ABOVE,
            super::EVENT_TO_FRAGMENT,
            <super::QuadricStream as RtlBlock>::LATENCY,
            <QuadricUnit as RtlBlock>::LATENCY,
            &extra,
        );
    }

    /// The generated regions of this file are what `rtl::stream::layout` gives; with
    /// `SHADECORE_REGENERATE=1` the test rewrites them.
    #[test]
    fn quadric_stream_rtl_is_generated() {
        crate::stream::layout::check_generated(&crate::stream::layout::QUADRIC_STREAM).unwrap();
    }
}
