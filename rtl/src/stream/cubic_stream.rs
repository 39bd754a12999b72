//! `cubic-stream`: the cubic span pipeline (`cubic_pipeline`: three Horner units, SPEC §9, §0)
//! behind AXI4-Stream interfaces, in place of `cubic-pipeline`'s 321 flat set-up pins: one
//! record per raster line in on a 32-bit stream, fragments out on a 64-bit stream (depth on
//! `m_axis_tuser`) with back-pressure. Golden: `cubic-pipeline`'s (the same fragments, in the
//! same order, whatever the stalls), itself checked against the golden `cubic` method.
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─► CubicPipeline ─► FIFO (32) ─► m_axis
//!  (32 bit)   (record type, errors)  sw0..sw10       lw0..lw10       ▲ hold          │ (level)
//!                                                                     └──────────────┘
//! ```
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `s_axis_tdata` | in | set-up word, 32 bits (layout: `rtl::stream::layout::CUBIC_LINE`, `rtl/README.md`) |
//! | `s_axis_tvalid`, `s_axis_tlast` | in | AXI4-Stream; `tlast` on a record's last word |
//! | `s_axis_tready` | out | a word is accepted on `tvalid & tready` |
//! | `m_axis_tready` | in | the consumer takes the beat on `tvalid & tready`; may be low for any time |
//! | `m_axis_tvalid` | out | a beat is offered (held, with its data, until taken) |
//! | `m_axis_tdata` | out | 64 bits: `x`, `y`, `pixel` (always 1 here), `red`, `green`, `blue` (the `pixel-stream` beat) |
//! | `m_axis_tuser` | out | the fragment's depth `z`, 32 bits (signed Q16.16 pixels) |
//! | `m_axis_tlast` | out | the beat is its line's last pixel |
//! | `error` | out | sticky: a record with an unknown type or the wrong length was dropped |
//!
//! # Records (`rtl::stream::layout::CUBIC_STREAM`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1, a line; the other bits 0), then 11 payload words:
//! `cubic-pipeline`'s load ports in port order (y, x0, dir; m; round(2²⁷/m); the four Q11.5
//! samples of red, green and blue, two per word; z0; dz), a field never straddling two words.
//! A record whose `tlast` comes before or after its length, or with an unknown type, is
//! dropped whole (up to its `tlast`) and sets `error`. There are no registers: the samples
//! are lit in the set-up (the thesis's software part), so a line carries its colours.
//!
//! # Handshake, latency, throughput
//! - Two word banks, as in `gouraud-stream`: the receive bank takes the record being streamed
//!   in; a complete record moves in one clock to the load bank when that is free, and the
//!   receive bank takes the next one. `s_axis_tready` is low only while a complete record
//!   waits in the receive bank. The load bank loads when the pipeline is `ready` (its units
//!   take the next line so that it follows the current one without a gap).
//! - Fragments enter a 32-entry FIFO. The pipeline is held (its `hold`: no pixel enters the
//!   units this clock, none lost; pixels already in them run on) in the clock after the FIFO
//!   held more than 15 beats (the hold is registered): from the clock its level first
//!   reaches 16, at most `EVENT_TO_FRAGMENT` + 1 = 16 more fragments arrive (the pixels that
//!   entered the units in that clock and the 15 before),
//!   so the FIFO never holds more than 32 and never overflows (`tests/cubic_stream.rs`
//!   measures 31 under 90 % stalls); with `m_axis_tready` high it holds at most one beat and
//!   the pipeline is never held.
//! - Throughput: the pipeline's — one fragment per clock along a line with the pipelined
//!   Horner units, one per three clocks with the serial ones — as long as the set-up words
//!   keep ahead: a line's record is 12 words at one word per clock, so lines shorter than 12
//!   pixels (pipelined) or 4 pixels (serial) are set-up bound.
//! - Latency: a record's last word accepted in clock t → its first beat offered in
//!   clock t + 19 with the pipelined units (the record is complete in t + 1, moves to the load bank
//!   in t + 1, loads in t + 2; 15 clocks through `cubic-pipeline`, 2 through the FIFO and its
//!   output register); serial units take a line only in their slot's last clock, up to 2
//!   clocks more.
//! - The fragment stream comes from an output register (`m_axis_t*` are register outputs),
//!   loaded from the FIFO when empty or when its beat is taken, so a beat per clock still
//!   flows with `m_axis_tready` high.
//!
//! # Overflow, error budget
//! None of its own: the FIFO cannot overflow (above); the data are `cubic-pipeline`'s, bit for
//! bit (colours within its units' bound of the golden `cubic`, depth within 4096·2⁻¹⁷ + 2⁻¹⁶
//! of the f64 plane).
//!
//! Latency (the block's `LATENCY`): 19 clocks, a line record's last word to its first fragment beat (pipelined units; serial: up to 2 more).

use rust_hdl::prelude::*;

use crate::core::primitives::Lutram;
use crate::core::registry::RtlBlock;
use crate::pipelines::cubic_pipeline::{CubicParams, CubicPipeline};
use crate::stream::record_reader::{RecordReader, INDEX_BITS};

/// Clocks from a pixel entering the units to its fragment at `cubic-pipeline`'s outputs (at
/// most its load-to-first-fragment latency).
pub const EVENT_TO_FRAGMENT: usize = <CubicPipeline as RtlBlock>::LATENCY;
/// FIFO depth (entries) and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 5;
/// The FIFO level above which the pipeline is held (the clock after: `hold` is registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::hw_block! {
    /// The cubic span pipeline with AXI4-Stream set-up and fragment streams (see the header).
    pub struct CubicStream(clock) as "cubic-stream" {
        summary: "AXI4-Stream top of the cubic span pipeline: 32-bit line records in, 64-bit fragment beats (depth on tuser) out with back-pressure (a FIFO and the units' hold)",
        latency: 2 + <CubicPipeline as RtlBlock>::LATENCY + 2
            => "a line record's last word to its first fragment beat (pipelined units; serial: up to 2 more)",
        multipliers: 6,
        in { s_axis_tdata: Bits<32>, s_axis_tvalid: Bit, s_axis_tlast: Bit, m_axis_tready: Bit }
        out {
            s_axis_tready: Bit, m_axis_tvalid: Bit, m_axis_tdata: Bits<64>, m_axis_tuser: Bits<32>,
            m_axis_tlast: Bit, error: Bit,
        }
        pub pipe: CubicPipeline = CubicPipeline::new(p),
        /// Set-up side: the record reader (one record type, the line).
        rd: RecordReader,
        /// A line waits in the load bank.
        pend_b: DFF<Bit>, transfer: Signal<Local, Bit>,
        tri_words: Constant<Bits<INDEX_BITS>> =
            Constant::new((crate::stream::layout::payload_words(&crate::stream::layout::CUBIC_LINE) as u64).into()),
        no_words: Constant<Bits<INDEX_BITS>> = Constant::new(0u64.into()),
        /// The word the reader takes, and which payload word it is (+ 1).
        in_word: Signal<Local, Bits<32>>, take_word: Signal<Local, Bit>,
        word_index: Signal<Local, Bits<INDEX_BITS>>,
        // Fragment side: the FIFO (beat, and z with tlast), pointers, level.
        fifo_beat: Lutram<Bits<64>, FIFO_BITS>,
        fifo_tail: Lutram<Bits<33>, FIFO_BITS>,
        wr_ptr: DFF<Bits<FIFO_BITS>>, rd_ptr: DFF<Bits<FIFO_BITS>>, level: DFF<Bits<6>>,
        hold_above: Constant<Bits<6>> = Constant::new((HOLD_ABOVE as u64).into()),
        hold_q: DFF<Bit>,
        pop: Signal<Local, Bit>, beat: Signal<Local, Bits<64>>,
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
        frag_pixel_bit: Constant<Bits<64>> = Constant::new((1u64 << 24).into()),
        beat_data: Signal<Local, Bits<64>>,
        // END GENERATED
    }
    new(p: &CubicParams);
}

impl Logic for CubicStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pipe, rd, fifo_beat, fifo_tail);
        dff_setup!(self, clock, pend_b);
        dff_setup!(self, clock, wr_ptr, rd_ptr, level, hold_q, out_v, out_data, out_tail);
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
        // pipeline is ready.
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
        dff_setup!(self, clock, sw9, sw10, lw0, lw1, lw2, lw3, lw4, lw5, lw6);
        dff_setup!(self, clock, lw7, lw8, lw9, lw10);
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
        }
        // Triangle fields: the pipeline's set-up ports.
        self.pipe.y.next = self.lw0.q.val().get_bits::<12>(0);
        self.pipe.x0.next = self.lw0.q.val().get_bits::<12>(12);
        self.pipe.dir.next = self.lw0.q.val().get_bit(24);
        self.pipe.m.next = self.lw1.q.val().get_bits::<12>(0);
        self.pipe.step.next = self.lw2.q.val().get_bits::<28>(0);
        self.pipe.r1.next = self.lw3.q.val().get_bits::<16>(0);
        self.pipe.r2.next = self.lw3.q.val().get_bits::<16>(16);
        self.pipe.r3.next = self.lw4.q.val().get_bits::<16>(0);
        self.pipe.r4.next = self.lw4.q.val().get_bits::<16>(16);
        self.pipe.g1.next = self.lw5.q.val().get_bits::<16>(0);
        self.pipe.g2.next = self.lw5.q.val().get_bits::<16>(16);
        self.pipe.g3.next = self.lw6.q.val().get_bits::<16>(0);
        self.pipe.g4.next = self.lw6.q.val().get_bits::<16>(16);
        self.pipe.b1.next = self.lw7.q.val().get_bits::<16>(0);
        self.pipe.b2.next = self.lw7.q.val().get_bits::<16>(16);
        self.pipe.b3.next = self.lw8.q.val().get_bits::<16>(0);
        self.pipe.b4.next = self.lw8.q.val().get_bits::<16>(16);
        self.pipe.z0.next = self.lw9.q.val();
        self.pipe.dz.next = self.lw10.q.val();
        // The fragment beat (`pixel` is the pipeline's `valid`).
        self.beat_data.next = bit_cast::<64, 12>(self.pipe.x.val())
            | (bit_cast::<64, 12>(self.pipe.y_out.val()) << 12)
            | (bit_cast::<64, 8>(self.pipe.red.val()) << 32)
            | (bit_cast::<64, 8>(self.pipe.green.val()) << 40)
            | (bit_cast::<64, 8>(self.pipe.blue.val()) << 48);
        self.beat.next = self.beat_data.val();
        if self.pipe.valid.val() {
            self.beat.next = self.beat_data.val() | self.frag_pixel_bit.val();
        }
        // END GENERATED

        // Fragment side: every fragment is one beat; tlast with the line's last pixel.
        self.hold_q.d.next = self.level.q.val() > self.hold_above.val();
        self.pipe.hold.next = self.hold_q.q.val();
        self.pop.next =
            (self.level.q.val() != 0) & (!self.out_v.q.val() | self.m_axis_tready.val());
        self.fifo_beat.write_enable.next = self.pipe.valid.val();
        self.fifo_beat.write_address.next = self.wr_ptr.q.val();
        self.fifo_beat.write_data.next = self.beat.val();
        self.fifo_beat.read_address.next = self.rd_ptr.q.val();
        self.fifo_tail.write_enable.next = self.pipe.valid.val();
        self.fifo_tail.write_address.next = self.wr_ptr.q.val();
        self.fifo_tail.write_data.next = bit_cast::<33, 32>(self.pipe.z.val());
        if self.pipe.done.val() {
            self.fifo_tail.write_data.next =
                bit_cast::<33, 32>(self.pipe.z.val()) | self.tlast_bit.val();
        }
        self.fifo_tail.read_address.next = self.rd_ptr.q.val();
        if self.pipe.valid.val() {
            self.wr_ptr.d.next = self.wr_ptr.q.val() + 1;
        }
        if self.pop.val() {
            self.rd_ptr.d.next = self.rd_ptr.q.val() + 1;
        }
        if self.pipe.valid.val() & !self.pop.val() {
            self.level.d.next = self.level.q.val() + 1;
        } else if !self.pipe.valid.val() & self.pop.val() {
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
    use crate::pipelines::cubic_pipeline::CubicPipeline;

    /// The header's latency, FIFO and record figures are the constants'.
    #[test]
    fn header_figures_are_the_constants() {
        let text = include_str!("cubic_stream.rs").replace("\n//!  ", " ");
        let words = crate::stream::layout::payload_words(&crate::stream::layout::CUBIC_LINE);
        for want in [
            format!("{}-entry FIFO", super::FIFO_DEPTH),
            format!("more than {} beats", super::HOLD_ABOVE),
            format!(
                "`EVENT_TO_FRAGMENT` + 1 = {} more fragments",
                super::EVENT_TO_FRAGMENT + 1
            ),
            format!(
                "never holds more than {}",
                super::HOLD_ABOVE + 1 + super::EVENT_TO_FRAGMENT + 1
            ),
            format!("clock t + {}", <super::CubicStream as RtlBlock>::LATENCY),
            format!(
                "{} clocks through `cubic-pipeline`",
                <CubicPipeline as RtlBlock>::LATENCY
            ),
            format!("then {words} payload words"),
            format!("record is {} words", words + 1),
            format!("FIFO ({})", super::FIFO_DEPTH),
        ] {
            assert!(text.contains(&want), "header lacks {want:?}");
        }
    }

    /// The generated regions of this file are what `rtl::stream::layout` gives; with
    /// `SHADECORE_REGENERATE=1` the test rewrites them.
    #[test]
    fn cubic_stream_rtl_is_generated() {
        crate::stream::layout::check_generated(&crate::stream::layout::CUBIC_STREAM).unwrap();
    }
}
