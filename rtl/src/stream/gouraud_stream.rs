//! `gouraud-stream`: the Gouraud raster pipe (`gouraud_raster`: address block + BVI, SPEC §5–§6)
//! behind AXI4-Stream interfaces, the top an FPGA engineer places instead of `gouraud-raster`'s
//! 673 flat set-up pins (727 ports in all): triangle records in on a 32-bit stream, fragments
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
//! A header word (bits 3..0: 1, a triangle; the other bits 0), then 22 payload words: the
//! sub-pixel address block's set-up (10 words) and the BVI's twelve signed Q16.16 words, a field never
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
//!   set-up words keep ahead of the walk: a triangle's set-up is 23 words at one word per
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
        /// The record banks, the field selects and the wrapped top (`core.pipe`): generated.
        pub core: GouraudStreamCore,
        // Fragment side: the FIFO (beat, tlast), pointers, level.
        fifo_beat: Lutram<Bits<64>, FIFO_BITS>,
        fifo_last: Lutram<Bit, FIFO_BITS>,
        wr_ptr: DFF<Bits<FIFO_BITS>>, rd_ptr: DFF<Bits<FIFO_BITS>>, level: DFF<Bits<5>>,
        hold_above: Constant<Bits<5>> = Constant::new((HOLD_ABOVE as u64).into()),
        hold_q: DFF<Bit>,
        ev_beat: Signal<Local, Bit>, pop: Signal<Local, Bit>, beat: Signal<Local, Bits<64>>,
        /// The output register: a beat (tdata, tlast) offered on `m_axis_*`.
        out_v: DFF<Bit>, out_data: DFF<Bits<64>>, out_last: DFF<Bit>,
    }
}

impl Logic for GouraudStream {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, core, fifo_beat, fifo_last);
        // The fragment beats the generated core packs.
        self.beat.next = self.core.beat.val();
        dff_setup!(self, clock, wr_ptr, rd_ptr, level, hold_q, out_v, out_data, out_last);

        // Set-up side: the generated core (record reader, load bank, word banks, field
        // selects).
        self.core.s_axis_tdata.next = self.s_axis_tdata.val();
        self.core.s_axis_tvalid.next = self.s_axis_tvalid.val();
        self.core.s_axis_tlast.next = self.s_axis_tlast.val();
        self.s_axis_tready.next = self.core.s_axis_tready.val();
        self.error.next = self.core.error.val();

        // Fragment side: every event with a pixel or a triangle end is one beat.
        self.hold_q.d.next = self.level.q.val() > self.hold_above.val();
        self.core.hold.next = self.hold_q.q.val();
        self.ev_beat.next = self.core.valid.val() | self.core.done.val();
        self.pop.next =
            (self.level.q.val() != 0) & (!self.out_v.q.val() | self.m_axis_tready.val());
        self.fifo_beat.write_enable.next = self.ev_beat.val();
        self.fifo_beat.write_address.next = self.wr_ptr.q.val();
        self.fifo_beat.write_data.next = self.beat.val();
        self.fifo_beat.read_address.next = self.rd_ptr.q.val();
        self.fifo_last.write_enable.next = self.ev_beat.val();
        self.fifo_last.write_address.next = self.wr_ptr.q.val();
        self.fifo_last.write_data.next = self.core.done.val();
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

/// The generated core: `rtl/build.rs` writes it from `rtl::stream::layout::GOURAUD_STREAM` (the
/// record banks, the field selects into the wrapped top, the fragment packing).
mod generated {
    use super::*;
    include!(concat!(env!("OUT_DIR"), "/gouraud_stream_core.rs"));
}
pub use generated::GouraudStreamCore;

#[cfg(test)]
mod tests {
    use crate::pipelines::gouraud_raster::GouraudRaster;
    use crate::stream::layout::{payload_words, GOURAUD_TRIANGLE};

    /// The header's latency and FIFO figures are the constants'.
    #[test]
    fn header_figures_are_the_constants() {
        crate::stream::assert_header_states::<super::GouraudStream>(
            include_str!("gouraud_stream.rs"),
            (super::FIFO_DEPTH, super::HOLD_ABOVE),
            ("gouraud-raster", GouraudRaster::LATENCY),
            &[
                format!(
                    "`EVENT_TO_FRAGMENT` + 2 = {} events",
                    super::EVENT_TO_FRAGMENT + 2
                ),
                format!("then {} payload words", payload_words(&GOURAUD_TRIANGLE)),
            ],
        );
    }
}
