//! `gouraud-stream`: the Gouraud raster pipe (`gouraud_raster`: address block + BVI, SPEC §5–§6)
//! behind AXI4-Stream interfaces, the top an FPGA engineer places instead of `gouraud-raster`'s
//! 610 flat set-up pins (664 ports in all): triangle records in on a 32-bit stream, fragments
//! out on a 64-bit stream with back-pressure. Golden: `gouraud-raster`'s (the same fragments,
//! in the same order, whatever the stalls).
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─► GouraudRaster ─► FIFO (16) ─► m_axis
//!  (32 bit)   (record type, errors)  sw0..sw20       lw0..lw20       ▲ hold          │ (level)
//!                                                                     └──────────────┘
//! ```
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `s_axis_tdata` | in | set-up word, 32 bits (layout: `rtl::stream::layout::GOURAUD_TRIANGLE`, `rtl/README.md`) |
//! | `s_axis_tvalid`, `s_axis_tlast` | in | AXI4-Stream; `tlast` on a record's last word |
//! | `s_axis_tready` | out | a word is accepted on `tvalid & tready` |
//! | `m_axis_tready` | in | the consumer takes the beat on `tvalid & tready`; may be low for any time |
//! | `m_axis_tvalid` | out | a beat is offered (held, with its data, until taken) |
//! | `m_axis_tdata` | out | 64 bits: `x`, `y`, `pixel` (1: a fragment), `red`, `green`, `blue` (the `pixel-stream` beat) |
//! | `m_axis_tlast` | out | the beat is its triangle's last event (a beat with `pixel` = 0 carries only that) |
//! | `error` | out | sticky: a record with an unknown type or the wrong length was dropped |
//!
//! # Records (`rtl::stream::layout::GOURAUD_STREAM`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1, a triangle; the other bits 0), then 21 payload words: the
//! address block's set-up (9 words) and the BVI's twelve signed Q16.16 words, a field never
//! straddling two words. A record whose `tlast` comes before or after its length, or with an
//! unknown type, is dropped whole (up to its `tlast`) and sets `error`. There are no
//! registers: a Gouraud triangle carries its colours.
//!
//! # Handshake, latency, throughput
//! - Two word banks, as in `pixel-stream`: the receive bank takes the record being streamed
//!   in; a complete record moves in one clock to the load bank when that is free, and the
//!   receive bank takes the next one. `s_axis_tready` is low only while a complete record
//!   waits in the receive bank. The load bank loads when the address block is `ready` (which
//!   rises before the current triangle's last rows, so the next set-up overlaps the walk).
//! - Fragments (and triangle ends) enter a 16-entry FIFO. The address block is held (its
//!   `hold`: no event this clock, none lost) in the clock after the FIFO held
//!   more than 13 beats (the hold is registered): at most `EVENT_TO_FRAGMENT` + 2 = 3 events are then
//!   still in flight, so the FIFO never overflows and never drops a fragment, and with
//!   `m_axis_tready` high it holds at most one beat and the address block is never held.
//! - Throughput: one fragment per clock along a line, as `gouraud-raster`, as long as the
//!   set-up words keep ahead of the walk: a triangle's set-up is 22 words at one word per
//!   clock, so a run of triangles smaller than that is set-up bound.
//! - Latency: a triangle record's last word accepted in clock t → its first beat offered in
//!   clock t + 8 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 4 clocks through `gouraud-raster`, 2 through the FIFO and its output register).
//! - The fragment stream comes from an output register (`m_axis_t*` are register outputs),
//!   loaded from the FIFO when empty or when its beat is taken, so a beat per clock still
//!   flows with `m_axis_tready` high.
//!
//! # Overflow, error budget
//! None of its own: the FIFO cannot overflow (above); the data are `gouraud-raster`'s, bit
//! for bit (addresses exact, colours within 1 LSB of the rounded plane value).
//!
//! Latency (the block's `LATENCY`): 8 clocks, a triangle record's last word to its first fragment beat, one fragment per clock.

use rust_hdl::prelude::*;

use crate::core::primitives::Lutram;
use crate::pipelines::gouraud_raster::GouraudRaster;
use crate::stream::record_reader::{RecordReader, INDEX_BITS};
use crate::units::intensity_interpolator::IntensityInterpolator;

/// Clocks from an address-block event to its fragment at `gouraud-raster`'s outputs.
pub const EVENT_TO_FRAGMENT: usize = IntensityInterpolator::LATENCY;
/// FIFO depth (entries) and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 4;
/// The FIFO level above which the address block is held (the clock after: `hold` is
/// registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::hw_block! {
    /// The Gouraud raster pipe with AXI4-Stream set-up and fragment streams (see the header).
    pub struct GouraudStream(clock) as "gouraud-stream" {
        summary: "AXI4-Stream top of the Gouraud raster pipe: 32-bit triangle records in, 64-bit fragment beats out with back-pressure (a FIFO and the address block's hold)",
        latency: 2 + GouraudRaster::LATENCY + 2
            => "a triangle record's last word to its first fragment beat, one fragment per clock",
        multipliers: 0,
        in { s_axis_tdata: Bits<32>, s_axis_tvalid: Bit, s_axis_tlast: Bit, m_axis_tready: Bit }
        out {
            s_axis_tready: Bit, m_axis_tvalid: Bit, m_axis_tdata: Bits<64>, m_axis_tlast: Bit,
            error: Bit,
        }
        pub pipe: GouraudRaster,
        /// Set-up side: the record reader (one record type, the triangle).
        rd: RecordReader,
        /// A triangle waits in the load bank.
        pend_b: DFF<Bit>, transfer: Signal<Local, Bit>,
        tri_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::GOURAUD_TRIANGLE) as u64).into()),
        no_words: Constant<Bits<INDEX_BITS>> = Constant::new(0u64.into()),
        /// The word the reader takes, and which payload word it is (+ 1).
        in_word: Signal<Local, Bits<32>>, take_word: Signal<Local, Bit>,
        word_index: Signal<Local, Bits<INDEX_BITS>>,
        // Fragment side: the FIFO (beat, tlast), pointers, level.
        fifo_beat: Lutram<Bits<64>, FIFO_BITS>,
        fifo_last: Lutram<Bit, FIFO_BITS>,
        wr_ptr: DFF<Bits<FIFO_BITS>>, rd_ptr: DFF<Bits<FIFO_BITS>>, level: DFF<Bits<5>>,
        hold_above: Constant<Bits<5>> = Constant::new((HOLD_ABOVE as u64).into()),
        hold_q: DFF<Bit>,
        ev_beat: Signal<Local, Bit>, pop: Signal<Local, Bit>, beat: Signal<Local, Bits<64>>,
        /// The output register: a beat (tdata, tlast) offered on `m_axis_*`.
        out_v: DFF<Bit>, out_data: DFF<Bits<64>>, out_last: DFF<Bit>,
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
        frag_pixel_bit: Constant<Bits<64>> = Constant::new((1u64 << 24).into()),
        beat_data: Signal<Local, Bits<64>>,
        // END GENERATED
    }
}

impl Logic for GouraudStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pipe, rd, fifo_beat, fifo_last);
        dff_setup!(self, clock, pend_b);
        dff_setup!(self, clock, wr_ptr, rd_ptr, level, hold_q, out_v, out_data, out_last);

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
        // address block is ready.
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
        dff_setup!(self, clock, sw18, sw19, sw20, lw0, lw1, lw2, lw3, lw4, lw5);
        dff_setup!(self, clock, lw6, lw7, lw8, lw9, lw10, lw11, lw12, lw13, lw14);
        dff_setup!(self, clock, lw15, lw16, lw17, lw18, lw19, lw20);
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
        self.pipe.r_start.next = self.lw9.q.val();
        self.pipe.r_short.next = self.lw10.q.val();
        self.pipe.r_long.next = self.lw11.q.val();
        self.pipe.r_line.next = self.lw12.q.val();
        self.pipe.g_start.next = self.lw13.q.val();
        self.pipe.g_short.next = self.lw14.q.val();
        self.pipe.g_long.next = self.lw15.q.val();
        self.pipe.g_line.next = self.lw16.q.val();
        self.pipe.b_start.next = self.lw17.q.val();
        self.pipe.b_short.next = self.lw18.q.val();
        self.pipe.b_long.next = self.lw19.q.val();
        self.pipe.b_line.next = self.lw20.q.val();
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
        self.fifo_last.write_enable.next = self.ev_beat.val();
        self.fifo_last.write_address.next = self.wr_ptr.q.val();
        self.fifo_last.write_data.next = self.pipe.done.val();
        self.fifo_last.read_address.next = self.rd_ptr.q.val();
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
            self.out_last.d.next = self.fifo_last.read_data.val();
        } else if self.m_axis_tready.val() {
            self.out_v.d.next = false;
        }
        self.m_axis_tvalid.next = self.out_v.q.val();
        self.m_axis_tdata.next = 0.into();
        self.m_axis_tlast.next = false;
        if self.out_v.q.val() {
            self.m_axis_tdata.next = self.out_data.q.val();
            self.m_axis_tlast.next = self.out_last.q.val();
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::core::registry::RtlBlock;
    use crate::pipelines::gouraud_raster::GouraudRaster;

    /// The header's latency and FIFO figures are the constants'.
    #[test]
    fn header_figures_are_the_constants() {
        let text = include_str!("gouraud_stream.rs").replace("\n//!  ", " ");
        for want in [
            format!("{}-entry FIFO", super::FIFO_DEPTH),
            format!("more than {} beats", super::HOLD_ABOVE),
            format!(
                "`EVENT_TO_FRAGMENT` + 2 = {} events",
                super::EVENT_TO_FRAGMENT + 2
            ),
            format!("clock t + {}", <super::GouraudStream as RtlBlock>::LATENCY),
            format!(
                "{} clocks through `gouraud-raster`",
                <GouraudRaster as RtlBlock>::LATENCY
            ),
            format!(
                "then {} payload words",
                crate::stream::layout::payload_words(&crate::stream::layout::GOURAUD_TRIANGLE)
            ),
        ] {
            assert!(text.contains(&want), "header lacks {want:?}");
        }
    }

    /// The generated regions of this file are what `rtl::stream::layout` gives; with
    /// `SHADECORE_REGENERATE=1` the test rewrites them.
    #[test]
    fn gouraud_stream_rtl_is_generated() {
        crate::stream::layout::check_generated(&crate::stream::layout::GOURAUD_STREAM).unwrap();
    }
}
