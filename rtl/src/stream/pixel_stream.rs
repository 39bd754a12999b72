//! `pixel-stream`: the lit pixel pipeline (`pixel_pipeline`) behind AXI4-Stream interfaces, the
//! top an FPGA engineer instantiates: set-up records in on a 32-bit stream, fragments out on a
//! 64-bit stream with back-pressure. Golden: `pixel-pipeline`'s (the same fragments, in the
//! same order, whatever the stalls).
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─┬─ triangle fields ─► PixelPipeline ─► FIFO (128) ─► m_axis
//!  (32 bit)   (record type, errors)  sw0..sw24       lw0..lw24  └─ register fields ─► r_* (applied      ▲   │
//!                                                                                      when drained)  hold ◄┘ (FIFO level)
//! ```
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `s_axis_tdata` | in | set-up word, 32 bits (layouts: `rtl::stream::layout`, `rtl/README.md`) |
//! | `s_axis_tvalid`, `s_axis_tlast` | in | AXI4-Stream; `tlast` on a record's last word |
//! | `s_axis_tready` | out | a word is accepted on `tvalid & tready` |
//! | `m_axis_tready` | in | the consumer takes the beat on `tvalid & tready`; may be low for any time |
//! | `m_axis_tvalid` | out | a beat is offered (held, with its data, until taken) |
//! | `m_axis_tdata` | out | 64 bits: `x`, `y`, `pixel` (1: a fragment), `red`, `green`, `blue` |
//! | `m_axis_tuser` | out | the fragment's depth `z`, 32 bits (signed Q16.16 pixels) |
//! | `m_axis_tlast` | out | the beat is its triangle's last event (a beat with `pixel` = 0 carries only that) |
//! | `error` | out | sticky: a record with an unknown type or the wrong length was dropped |
//!
//! # Records (`rtl::stream::layout`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1 triangle, 2 registers; the other bits 0), then the record's
//! fields packed LSB first into words, a field never straddling two words: a triangle is 25
//! payload words (the address block's set-up, the normal planes, the depth plane), the
//! registers 8 (L, H, n, the colour weights). A record whose `tlast` comes before or after its
//! length, or with an unknown type, is dropped whole (up to its `tlast`) and sets `error`.
//!
//! # Handshake, latency, throughput
//! - Two word banks: the receive bank takes the record being streamed in; a complete record
//!   moves in one clock to the load bank when that is free, and the receive bank takes the
//!   next one. `s_axis_tready` is low only while a complete record waits in the receive bank.
//!   In the load bank a triangle waits for the address block's `ready` (which rises before the
//!   current triangle's last rows, so the next one's set-up overlaps its walk); a register
//!   record waits until every triangle loaded before it has left the pipeline (its `done`
//!   seen), so no fragment mixes two register sets. Registers are 0 after reset: send a
//!   register record first.
//! - Fragments (and triangle ends) enter a 128-entry FIFO. The address block is held (its
//!   `hold`: no event this clock, none lost) in the clock after the FIFO held
//!   more than 41 beats (the hold is registered, for ECP5 timing): at most
//!   `EVENT_TO_FRAGMENT` + 2 = 87 events are then still in flight, so the FIFO never
//!   overflows and never drops a fragment, and with `m_axis_tready` high it holds at most one beat and
//!   the address block is never held.
//! - Throughput: one fragment per clock along a line, as `pixel-pipeline`, as long as the
//!   set-up words keep ahead of the walk: a triangle's set-up is 26 words at one word per
//!   clock, so a run of triangles smaller than that is set-up bound. In mesh order the default
//!   scene (2 288 triangles, 49 fragments each on average, small ones in runs along the
//!   silhouette) gives 0.885 fragments per clock against `pixel-pipeline`'s 0.986; more
//!   buffering does not help (input FIFOs of 64 to 100 000 words measured: unchanged). The
//!   driver therefore sends large and small triangles alternately
//!   (`pipeline::lit::balanced_order`): 0.985, 114 847 clocks against `pixel-pipeline`'s
//!   114 808 (`cargo bench --bench rtl_lit`, both orders printed).
//! - Latency: a triangle record's last word accepted in clock t → its first beat offered in
//!   clock t + 92 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 88 clocks through `pixel-pipeline`, 2 through the FIFO and its output register).
//! - The fragment stream comes from an output register (`m_axis_t*` are register outputs):
//!   it is loaded from the FIFO when empty or when its beat is taken, so a beat per clock
//!   still flows with `m_axis_tready` high. (The FIFO's read port maps to block RAM on ECP5,
//!   5.8 ns from the clock: driving the ports from it ran at 87 MHz.)
//!
//! # Overflow, error budget
//! None of its own: the FIFO cannot overflow (above), counters are wide enough (`outstanding`
//! 16 bits: triangles loaded and not finished, at most 2 in practice); the data are
//! `pixel-pipeline`'s, bit for bit.
//!
//! Latency (the block's `LATENCY`): 92 clocks, a triangle record's last word to its first fragment beat, one fragment per clock.

use rust_hdl::prelude::*;

use crate::core::primitives::Lutram;
use crate::pipelines::pixel_pipeline::{PipelineParams, PixelPipeline, EVENT_TO_FRAGMENT};
use crate::stream::record_reader::{RecordReader, INDEX_BITS};

/// FIFO depth (entries) and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 7;
/// The FIFO level above which the address block is held (the clock after: `hold` is
/// registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::hw_block! {
    /// The lit pixel pipeline with AXI4-Stream set-up and fragment streams (see the header).
    pub struct PixelStream(clock) as "pixel-stream" {
        summary: "AXI4-Stream top of the lit pixel pipeline: 32-bit set-up records in, 64-bit fragment beats out with back-pressure (a FIFO and the address block's hold)",
        latency: 2 + PixelPipeline::LATENCY + 2
            => "a triangle record's last word to its first fragment beat, one fragment per clock",
        multipliers: 38,
        in { s_axis_tdata: Bits<32>, s_axis_tvalid: Bit, s_axis_tlast: Bit, m_axis_tready: Bit }
        out {
            s_axis_tready: Bit, m_axis_tvalid: Bit, m_axis_tdata: Bits<64>, m_axis_tuser: Bits<32>,
            m_axis_tlast: Bit, error: Bit,
        }
        pub pipe: PixelPipeline = PixelPipeline::new(p),
        /// Set-up side: the record reader (types 1, the triangle, and 2, the registers).
        rd: RecordReader,
        /// A record waits in the load bank (`pend_b`), of type `type_b`.
        pend_b: DFF<Bit>, type_b: DFF<Bits<4>>, transfer: Signal<Local, Bit>,
        /// Triangles loaded whose `done` has not left the pipeline.
        outstanding: DFF<Bits<16>>,
        tri_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::TRIANGLE) as u64).into()),
        reg_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::REGISTERS) as u64).into()),
        /// The word the reader takes, and which payload word it is (+ 1).
        in_word: Signal<Local, Bits<32>>, take_word: Signal<Local, Bit>,
        word_index: Signal<Local, Bits<INDEX_BITS>>,
        load_taken: Signal<Local, Bit>, apply_regs: Signal<Local, Bit>,
        // Fragment side: the FIFO (beat, and z with tlast), pointers, level.
        fifo_beat: Lutram<Bits<64>, FIFO_BITS>,
        fifo_tail: Lutram<Bits<33>, FIFO_BITS>,
        wr_ptr: DFF<Bits<FIFO_BITS>>, rd_ptr: DFF<Bits<FIFO_BITS>>, level: DFF<Bits<8>>,
        hold_above: Constant<Bits<8>> = Constant::new((HOLD_ABOVE as u64).into()),
        /// The hold, registered (the comparator, the address block's gating and the depth
        /// channel's adder in one clock ran at 79.8 MHz on ECP5).
        hold_q: DFF<Bit>,
        ev_beat: Signal<Local, Bit>, pop: Signal<Local, Bit>, beat: Signal<Local, Bits<64>>,
        /// The output register: a beat (tdata, and z with tlast) offered on `m_axis_*`.
        out_v: DFF<Bit>, out_data: DFF<Bits<64>>, out_tail: DFF<Bits<33>>,
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
        // The active frame and material registers.
        r_lx: DFF<Bits<16>>,
        r_ly: DFF<Bits<16>>,
        r_lz: DFF<Bits<16>>,
        r_hx: DFF<Bits<16>>,
        r_hy: DFF<Bits<16>>,
        r_hz: DFF<Bits<16>>,
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
        beat_data: Signal<Local, Bits<64>>,
        // END GENERATED
    }
    new(p: &PipelineParams);
}

impl Logic for PixelStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pipe, rd, fifo_beat, fifo_tail);
        dff_setup!(self, clock, outstanding, pend_b, type_b);
        dff_setup!(self, clock, wr_ptr, rd_ptr, level, hold_q, out_v, out_data, out_tail);

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

        // A complete record moves to the load bank when that is free, and the receive bank
        // takes the next record. In the load bank a triangle loads when the address block is
        // ready; registers apply when every earlier triangle has left the pipeline.
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
        dff_setup!(self, clock, sw18, sw19, sw20, sw21, sw22, sw23, sw24, lw0, lw1);
        dff_setup!(self, clock, lw2, lw3, lw4, lw5, lw6, lw7, lw8, lw9, lw10);
        dff_setup!(self, clock, lw11, lw12, lw13, lw14, lw15, lw16, lw17, lw18, lw19);
        dff_setup!(self, clock, lw20, lw21, lw22, lw23, lw24);
        dff_setup!(self, clock, r_lx, r_ly, r_lz, r_hx, r_hy, r_hz);
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
        }
        // Triangle fields: the pipeline's set-up ports.
        self.pipe.w_b0.next = self.lw0.q.val().get_bits::<12>(0);
        self.pipe.w_e0.next = self.lw0.q.val().get_bits::<13>(12);
        self.pipe.w_f.next = self.lw1.q.val().get_bits::<12>(0);
        self.pipe.w_r.next = self.lw1.q.val().get_bits::<13>(12);
        self.pipe.w_d.next = self.lw2.q.val().get_bits::<13>(0);
        self.pipe.a_b0.next = self.lw2.q.val().get_bits::<12>(13);
        self.pipe.a_e0.next = self.lw3.q.val().get_bits::<13>(0);
        self.pipe.a_f.next = self.lw3.q.val().get_bits::<12>(13);
        self.pipe.a_r.next = self.lw4.q.val().get_bits::<13>(0);
        self.pipe.a_d.next = self.lw4.q.val().get_bits::<13>(13);
        self.pipe.t_b0.next = self.lw5.q.val().get_bits::<12>(0);
        self.pipe.t_e0.next = self.lw5.q.val().get_bits::<13>(12);
        self.pipe.t_f.next = self.lw6.q.val().get_bits::<12>(0);
        self.pipe.t_r.next = self.lw6.q.val().get_bits::<13>(12);
        self.pipe.t_d.next = self.lw7.q.val().get_bits::<13>(0);
        self.pipe.y_top.next = self.lw7.q.val().get_bits::<12>(13);
        self.pipe.rows.next = self.lw8.q.val().get_bits::<12>(0);
        self.pipe.y_switch.next = self.lw8.q.val().get_bits::<12>(12);
        self.pipe.dir_neg.next = self.lw8.q.val().get_bit(24);
        self.pipe.x_start.next = self.lw9.q.val();
        self.pipe.x_short.next = self.lw10.q.val();
        self.pipe.x_long.next = self.lw11.q.val();
        self.pipe.x_line.next = self.lw12.q.val();
        self.pipe.y_start.next = self.lw13.q.val();
        self.pipe.y_short.next = self.lw14.q.val();
        self.pipe.y_long.next = self.lw15.q.val();
        self.pipe.y_line.next = self.lw16.q.val();
        self.pipe.z_start.next = self.lw17.q.val();
        self.pipe.z_short.next = self.lw18.q.val();
        self.pipe.z_long.next = self.lw19.q.val();
        self.pipe.z_line.next = self.lw20.q.val();
        self.pipe.d_start.next = self.lw21.q.val();
        self.pipe.d_short.next = self.lw22.q.val();
        self.pipe.d_long.next = self.lw23.q.val();
        self.pipe.d_line.next = self.lw24.q.val();
        // Register fields: applied into the active registers.
        if self.apply_regs.val() {
            self.r_lx.d.next = self.lw0.q.val().get_bits::<16>(0);
            self.r_ly.d.next = self.lw0.q.val().get_bits::<16>(16);
            self.r_lz.d.next = self.lw1.q.val().get_bits::<16>(0);
            self.r_hx.d.next = self.lw1.q.val().get_bits::<16>(16);
            self.r_hy.d.next = self.lw2.q.val().get_bits::<16>(0);
            self.r_hz.d.next = self.lw2.q.val().get_bits::<16>(16);
            self.r_n.d.next = self.lw3.q.val().get_bits::<10>(0);
            self.r_amb_r.d.next = self.lw3.q.val().get_bits::<16>(10);
            self.r_amb_g.d.next = self.lw4.q.val().get_bits::<16>(0);
            self.r_amb_b.d.next = self.lw4.q.val().get_bits::<16>(16);
            self.r_dif_r.d.next = self.lw5.q.val().get_bits::<16>(0);
            self.r_dif_g.d.next = self.lw5.q.val().get_bits::<16>(16);
            self.r_dif_b.d.next = self.lw6.q.val().get_bits::<16>(0);
            self.r_spc_r.d.next = self.lw6.q.val().get_bits::<16>(16);
            self.r_spc_g.d.next = self.lw7.q.val().get_bits::<16>(0);
            self.r_spc_b.d.next = self.lw7.q.val().get_bits::<16>(16);
        }
        self.pipe.lx.next = self.r_lx.q.val();
        self.pipe.ly.next = self.r_ly.q.val();
        self.pipe.lz.next = self.r_lz.q.val();
        self.pipe.hx.next = self.r_hx.q.val();
        self.pipe.hy.next = self.r_hy.q.val();
        self.pipe.hz.next = self.r_hz.q.val();
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
        // The fragment beat (`pixel` is the pipeline's `valid`).
        self.beat_data.next = bit_cast::<64, 12>(self.pipe.x.val())
            | (bit_cast::<64, 12>(self.pipe.y.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue.val()) << 48);
        self.beat.next = self.beat_data.val();
        if self.pipe.valid.val() {
            self.beat.next = self.beat_data.val() | self.frag_pixel_bit.val();
        }
        // END GENERATED

        // Fragment side: every event with a pixel or a triangle end is one beat.
        self.hold_q.d.next = self.level.q.val() > self.hold_above.val();
        self.pipe.hold.next = self.hold_q.q.val();
        self.ev_beat.next = self.pipe.valid.val() | self.pipe.done.val();
        self.pop.next =
            (self.level.q.val() != 0) & (!self.out_v.q.val() | self.m_axis_tready.val());
        self.fifo_beat.write_enable.next = self.ev_beat.val();
        self.fifo_beat.write_address.next = self.wr_ptr.q.val();
        self.fifo_beat.write_data.next = self.beat.val();
        self.fifo_beat.read_address.next = self.rd_ptr.q.val();
        self.fifo_tail.write_enable.next = self.ev_beat.val();
        self.fifo_tail.write_address.next = self.wr_ptr.q.val();
        self.fifo_tail.write_data.next = bit_cast::<33, 32>(self.pipe.z.val());
        if self.pipe.done.val() {
            self.fifo_tail.write_data.next =
                bit_cast::<33, 32>(self.pipe.z.val()) | self.tlast_bit.val();
        }
        self.fifo_tail.read_address.next = self.rd_ptr.q.val();
        if self.ev_beat.val() {
            self.wr_ptr.d.next = self.wr_ptr.q.val() + 1;
        }
        if self.pop.val() {
            self.rd_ptr.d.next = self.rd_ptr.q.val() + 1;
        }
        if self.ev_beat.val() & !self.pop.val() {
            self.level.d.next = self.level.q.val() + 1;
        } else if !self.ev_beat.val() & self.pop.val() {
            self.level.d.next = self.level.q.val() - 1;
        }
        if self.pop.val() {
            self.out_v.d.next = true;
            self.out_data.d.next = self.fifo_beat.read_data.val();
            self.out_tail.d.next = self.fifo_tail.read_data.val();
        } else if self.m_axis_tready.val() {
            self.out_v.d.next = false;
        }
        self.m_axis_tvalid.next = self.out_v.q.val();
        self.m_axis_tdata.next = 0.into();
        self.m_axis_tuser.next = 0.into();
        self.m_axis_tlast.next = false;
        if self.out_v.q.val() {
            self.m_axis_tdata.next = self.out_data.q.val();
            self.m_axis_tuser.next = self.out_tail.q.val().get_bits::<32>(0);
            self.m_axis_tlast.next = self.out_tail.q.val().get_bit(32);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::core::registry::RtlBlock;
    use crate::pipelines::pixel_pipeline::{PixelPipeline, EVENT_TO_FRAGMENT};

    /// The headers' latency and FIFO figures are the constants' (they move whenever a block
    /// is pipelined further).
    #[test]
    fn header_figures_are_the_constants() {
        let stream = include_str!("pixel_stream.rs").replace("\n//!  ", " ");
        let pipe = include_str!("../pipelines/pixel_pipeline.rs").replace("\n//! ", " ");
        let lat = <PixelPipeline as RtlBlock>::LATENCY;
        for (text, want) in [
            (&stream, format!("{}-entry FIFO", super::FIFO_DEPTH)),
            (&stream, format!("more than {} beats", super::HOLD_ABOVE)),
            (
                &stream,
                format!("`EVENT_TO_FRAGMENT` + 2 = {} events", EVENT_TO_FRAGMENT + 2),
            ),
            (
                &stream,
                format!("clock t + {}", <super::PixelStream as RtlBlock>::LATENCY),
            ),
            (&stream, format!("{lat} clocks through `pixel-pipeline`")),
            (
                &pipe,
                format!("Event → fragment {EVENT_TO_FRAGMENT} clocks"),
            ),
            (&pipe, format!("load → first fragment {lat}")),
        ] {
            assert!(text.contains(&want), "header lacks {want:?}");
        }
    }

    /// The generated regions of this file are what `rtl::stream::layout` gives; with
    /// `SHADECORE_REGENERATE=1` the test rewrites them.
    #[test]
    fn pixel_stream_rtl_is_generated() {
        crate::stream::layout::check_generated(&crate::stream::layout::PIXEL_STREAM).unwrap();
    }
}
