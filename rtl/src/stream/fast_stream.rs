//! `fast-stream`: the fast span pipeline (`fast-pipeline`: two fast two-point units, power
//! unit and colour combine per lane; SPEC §3, §0; build parameter `inv-sqrt`, as the pipeline's)
//! behind the AXI4-Stream interfaces of `angular-stream`, in place of `fast-pipeline`'s 671 flat
//! set-up pins: one record per raster line in on a 32-bit stream, the material registers over
//! the same stream, and fragments out on two 64-bit streams, one per lane (depth on each lane's
//! `tuser`), each with its own back-pressure. Golden: `fast-pipeline`'s (the same fragments, in
//! the same order on each lane, whatever the stalls), itself checked against the golden `fast`
//! and `fast-fit` methods.
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─┬─ line fields ─► FastPipeline ─┬─ lane A ─► FIFO (128) ─► m_axis_a
//!  (32 bit)   (record type, errors)  sw0..sw18       lw0..lw18  └─ register fields ─► r_*  ▲ hold └─ lane B ─► FIFO (128) ─► m_axis_b
//!                                                                  (applied when drained)  └───── either FIFO's level ◄──┘
//! ```
//!
//! # Ports
//! `angular-stream`'s, the same widths and meaning: `s_axis_tdata` (32), `s_axis_tvalid`,
//! `s_axis_tlast`, `s_axis_tready`; per lane `m_axis_a_*` and `m_axis_b_*`: `tready` in,
//! `tvalid`, `tdata` (64 bits: `x`, `y`, `pixel`, `red`, `green`, `blue`), `tuser` (the depth
//! `z`, signed Q16.16, 32 bits) and `tlast` (the line's last clock) out; `error` (sticky: a
//! record with an unknown type or the wrong length was dropped).
//!
//! # Records (`rtl::stream::layout::FAST_STREAM`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1 a line, 2 the registers; the other bits 0), then the record's
//! fields packed LSB first: a line is 19 payload words (`fast-pipeline`'s load ports in port
//! order: y, x0, dir; m; b, h, g, d0, dd for L; the same for H; z0, zm, dz — the 48-bit d0 and
//! dd each take a word and the next one's low 16 bits), the registers 5 (n, the nine UQ8.8
//! colour weights). A record whose `tlast` comes before or after its length, or with an
//! unknown type, is dropped whole (up to its `tlast`) and sets `error`.
//!
//! # Lanes, handshake, latency, throughput
//! As `angular-stream` (see its header): lane A pixel k of the line in its clock k, lane B pixel
//! m − k; both lanes mark the line's last clock with `tlast` (lane B with a `pixel` = 0 beat
//! when it has no pixel then); a line loads when the pipeline is `ready`, a register record
//! when every line before it has left the pipeline (registers are 0 after reset: send a
//! register record first); `s_axis_tready` is low only while a complete record waits in the
//! receive bank.
//! - Each lane's beats enter its own 128-entry FIFO (`fragment_fifo`). The pipeline is held in
//!   the clock after either FIFO held more than 58 beats (the hold is registered): from the
//!   clock a level first reaches 59, at most `EVENT_TO_FRAGMENT` + 1 = 69 more beats arrive on
//!   a lane, so neither FIFO holds more than 128 and none overflows. With both `tready` high
//!   each FIFO holds at most one beat and the pipeline is never held.
//! - Throughput: two fragments per clock along a line while the set-up words keep ahead: a
//!   line's record is 20 words at one word per clock, and a line of m + 1 pixels takes
//!   ⌊m/2⌋ + 1 clocks, so lines shorter than 39 pixels are set-up bound.
//! - Latency: a line record's last word accepted in clock t → its first beats offered in
//!   clock t + 72 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 68 clocks through `fast-pipeline`, 2 through the FIFO and its output register).
//!
//! # Overflow, error budget
//! None of its own: the FIFOs cannot overflow (above); `outstanding` is 16 bits, at most 2 in
//! practice; the data are `fast-pipeline`'s, bit for bit (colours within its bound of the
//! golden `fast` / `fast-fit`, depth within 0.0157 pixels of the f64 plane).
//!
//! Latency (the block's `LATENCY`): 72 clocks, a line record's last word to its first fragment beats, two fragments per clock.

use rust_hdl::prelude::*;

use crate::core::registry::RtlBlock;
use crate::pipelines::span_pipeline::{FastPipeline, FastPipelineParams};
use crate::stream::fragment_fifo::FragmentFifo;
use crate::stream::record_reader::{RecordReader, INDEX_BITS};

/// Clocks from a pixel entering the span units to its fragment at `fast-pipeline`'s
/// outputs (at most its load-to-first-fragment latency).
pub const EVENT_TO_FRAGMENT: usize = <FastPipeline as RtlBlock>::LATENCY;
/// Each lane's FIFO depth (entries).
pub const FIFO_DEPTH: usize = crate::stream::fragment_fifo::FIFO_DEPTH;
/// The FIFO level above which the pipeline is held (the clock after: `hold` is registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::hw_block! {
    /// The fast span pipeline with AXI4-Stream set-up and fragment streams (see the header).
    pub struct FastStream(clock) as "fast-stream" {
        summary: "AXI4-Stream top of the fast span pipeline: 32-bit line and register records in, two 64-bit fragment streams (one per lane, depth on tuser) out with back-pressure (a FIFO per lane and the units' hold)",
        latency: 2 + <FastPipeline as RtlBlock>::LATENCY + 2
            => "a line record's last word to its first fragment beats, two fragments per clock",
        multipliers: <FastPipeline as RtlBlock>::MULTIPLIERS,
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
        pub pipe: FastPipeline = FastPipeline::new(p),
        /// Set-up side: the record reader (types 1, the line, and 2, the registers).
        rd: RecordReader,
        /// A record waits in the load bank (`pend_b`), of type `type_b`.
        pend_b: DFF<Bit>, type_b: DFF<Bits<4>>, transfer: Signal<Local, Bit>,
        /// Lines loaded whose last clock has not left the pipeline.
        outstanding: DFF<Bits<16>>,
        tri_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::FAST_LINE) as u64).into()),
        reg_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::SPAN_REGISTERS) as u64).into()),
        /// The word the reader takes, and which payload word it is (+ 1).
        in_word: Signal<Local, Bits<32>>, take_word: Signal<Local, Bit>,
        word_index: Signal<Local, Bits<INDEX_BITS>>,
        load_taken: Signal<Local, Bit>, apply_regs: Signal<Local, Bit>,
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
        // The active frame and material registers.
        r_n: DFF<Bits<10>>,
        r_amb_r: DFF<Bits<16>>,
        r_amb_g: DFF<Bits<16>>,
        r_amb_b: DFF<Bits<16>>,
        r_dif_r: DFF<Bits<16>>,
        r_dif_g: DFF<Bits<16>>,
        r_dif_b: DFF<Bits<16>>,
        r_spc_r: DFF<Bits<16>>,
        r_spc_g: DFF<Bits<16>>,
        r_spc_b: DFF<Bits<16>>,
        frag_pixel_bit: Constant<Bits<64>> = Constant::new((1u64 << 24).into()),
        beat_a_data: Signal<Local, Bits<64>>,
        beat_b_data: Signal<Local, Bits<64>>,
        // END GENERATED
    }
    new(p: &FastPipelineParams);
}

impl Logic for FastStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pipe, rd, lane_a, lane_b);
        dff_setup!(self, clock, outstanding, pend_b, type_b, hold_q);
        // Set-up side: the record reader (`record_reader`) takes a word while no complete
        // record waits in the receive bank, and names the payload word it is.
        self.rd.head.next = self.s_axis_tdata.val().get_bits::<4>(0);
        self.rd.tvalid.next = self.s_axis_tvalid.val();
        self.rd.tlast.next = self.s_axis_tlast.val();
        self.rd.len1.next = self.tri_words.val();
        self.rd.len2.next = self.reg_words.val();
        self.s_axis_tready.next = self.rd.tready.val();
        self.in_word.next = self.s_axis_tdata.val();
        self.take_word.next = self.rd.take_word.val();
        self.word_index.next = self.rd.index.val();
        self.error.next = self.rd.error.val();

        // A complete record moves to the load bank when that is free. A line loads when the
        // pipeline is ready; registers apply when every line loaded before them has left.
        self.transfer.next = self.rd.pending.val() & !self.pend_b.q.val();
        self.rd.take_record.next = self.transfer.val();
        if self.transfer.val() {
            self.pend_b.d.next = true;
            self.type_b.d.next = self.rd.rec_type.val();
        }
        self.pipe.load.next = self.pend_b.q.val() & (self.type_b.q.val() == 1);
        self.load_taken.next =
            self.pend_b.q.val() & (self.type_b.q.val() == 1) & self.pipe.ready.val();
        self.apply_regs.next =
            self.pend_b.q.val() & (self.type_b.q.val() == 2) & (self.outstanding.q.val() == 0);
        if self.load_taken.val() | self.apply_regs.val() {
            self.pend_b.d.next = false;
        }
        if self.load_taken.val() & !self.pipe.done.val() {
            self.outstanding.d.next = self.outstanding.q.val() + 1;
        } else if !self.load_taken.val() & self.pipe.done.val() {
            self.outstanding.d.next = self.outstanding.q.val() - 1;
        }

        // BEGIN GENERATED by rtl::stream::layout::generated_rtl
        dff_setup!(self, clock, sw0, sw1, sw2, sw3, sw4, sw5, sw6, sw7, sw8);
        dff_setup!(self, clock, sw9, sw10, sw11, sw12, sw13, sw14, sw15, sw16, sw17);
        dff_setup!(self, clock, sw18, lw0, lw1, lw2, lw3, lw4, lw5, lw6, lw7);
        dff_setup!(self, clock, lw8, lw9, lw10, lw11, lw12, lw13, lw14, lw15, lw16);
        dff_setup!(self, clock, lw17, lw18);
        dff_setup!(self, clock, r_n, r_amb_r, r_amb_g, r_amb_b, r_dif_r, r_dif_g);
        dff_setup!(self, clock, r_dif_b, r_spc_r, r_spc_g, r_spc_b);
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
        }
        // Triangle fields: the pipeline's set-up ports.
        self.pipe.y.next = self.lw0.q.val().get_bits::<12>(0);
        self.pipe.x0.next = self.lw0.q.val().get_bits::<12>(12);
        self.pipe.dir.next = self.lw0.q.val().get_bit(24);
        self.pipe.m.next = self.lw1.q.val().get_bits::<12>(0);
        self.pipe.lb.next = self.lw2.q.val();
        self.pipe.lh.next = self.lw3.q.val();
        self.pipe.lg.next = self.lw4.q.val();
        self.pipe.ld0.next = bit_cast::<48, 32>(self.lw5.q.val())
            | (bit_cast::<48, 16>(self.lw6.q.val().get_bits::<16>(0)) << 32);
        self.pipe.ldd.next = bit_cast::<48, 32>(self.lw7.q.val())
            | (bit_cast::<48, 16>(self.lw8.q.val().get_bits::<16>(0)) << 32);
        self.pipe.hb.next = self.lw9.q.val();
        self.pipe.hh.next = self.lw10.q.val();
        self.pipe.hg.next = self.lw11.q.val();
        self.pipe.hd0.next = bit_cast::<48, 32>(self.lw12.q.val())
            | (bit_cast::<48, 16>(self.lw13.q.val().get_bits::<16>(0)) << 32);
        self.pipe.hdd.next = bit_cast::<48, 32>(self.lw14.q.val())
            | (bit_cast::<48, 16>(self.lw15.q.val().get_bits::<16>(0)) << 32);
        self.pipe.z0.next = self.lw16.q.val();
        self.pipe.zm.next = self.lw17.q.val();
        self.pipe.dz.next = self.lw18.q.val();
        // Register fields: applied into the active registers.
        if self.apply_regs.val() {
            self.r_n.d.next = self.lw0.q.val().get_bits::<10>(0);
            self.r_amb_r.d.next = self.lw0.q.val().get_bits::<16>(10);
            self.r_amb_g.d.next = self.lw1.q.val().get_bits::<16>(0);
            self.r_amb_b.d.next = self.lw1.q.val().get_bits::<16>(16);
            self.r_dif_r.d.next = self.lw2.q.val().get_bits::<16>(0);
            self.r_dif_g.d.next = self.lw2.q.val().get_bits::<16>(16);
            self.r_dif_b.d.next = self.lw3.q.val().get_bits::<16>(0);
            self.r_spc_r.d.next = self.lw3.q.val().get_bits::<16>(16);
            self.r_spc_g.d.next = self.lw4.q.val().get_bits::<16>(0);
            self.r_spc_b.d.next = self.lw4.q.val().get_bits::<16>(16);
        }
        self.pipe.n.next = self.r_n.q.val();
        self.pipe.amb_r.next = self.r_amb_r.q.val();
        self.pipe.amb_g.next = self.r_amb_g.q.val();
        self.pipe.amb_b.next = self.r_amb_b.q.val();
        self.pipe.dif_r.next = self.r_dif_r.q.val();
        self.pipe.dif_g.next = self.r_dif_g.q.val();
        self.pipe.dif_b.next = self.r_dif_b.q.val();
        self.pipe.spc_r.next = self.r_spc_r.q.val();
        self.pipe.spc_g.next = self.r_spc_g.q.val();
        self.pipe.spc_b.next = self.r_spc_b.q.val();
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
    use crate::pipelines::span_pipeline::FastPipeline;

    /// The header's latency, FIFO and record figures are the constants'.
    #[test]
    fn header_figures_are_the_constants() {
        let top = crate::stream::layout::FAST_STREAM;
        let regs = crate::stream::layout::payload_words(&top.registers.unwrap());
        let extra = [format!("the registers {regs}")];
        crate::stream::fragment_fifo::check_two_lane_header(
            include_str!("fast_stream.rs"),
            &top,
            super::HOLD_ABOVE,
            super::EVENT_TO_FRAGMENT,
            <super::FastStream as RtlBlock>::LATENCY,
            <FastPipeline as RtlBlock>::LATENCY,
            &extra,
        );
    }

    /// The generated regions of this file are what `rtl::stream::layout` gives; with
    /// `SHADECORE_REGENERATE=1` the test rewrites them.
    #[test]
    fn fast_stream_rtl_is_generated() {
        crate::stream::layout::check_generated(&crate::stream::layout::FAST_STREAM).unwrap();
    }
}
