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
//!   set-up words keep ahead of the walk: a triangle's set-up is 27 words at one word per
//!   clock, so a run of triangles smaller than that is set-up bound. In mesh order the default
//!   scene (2 288 triangles, 49 fragments each on average, small ones in runs along the
//!   silhouette) gives 0.879 fragments per clock against `pixel-pipeline`'s 0.986; more
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

use crate::pipelines::pixel_pipeline::{PipelineParams, PixelPipeline, EVENT_TO_FRAGMENT};

/// FIFO depth (entries) and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 7;
/// The FIFO level above which the address block is held (the clock after: `hold` is
/// registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::one_lane_stream! {
    /// The lit pixel pipeline with AXI4-Stream set-up and fragment streams (see the header).
    pub struct PixelStream as "pixel-stream" {
        summary: "AXI4-Stream top of the lit pixel pipeline: 32-bit set-up records in, 64-bit fragment beats out with back-pressure (a FIFO and the address block's hold)",
        latency: 2 + PixelPipeline::LATENCY + 2
            => "a triangle record's last word to its first fragment beat, one fragment per clock",
        multipliers: 38,
        core: PixelStreamCore = PixelStreamCore::new(p),
        core_file: "pixel_stream_core.rs",
        level: 8,
        events: ev_beat,
        push: ev_beat,
    }
    new(p: &PipelineParams);
}

#[cfg(test)]
mod tests {
    use crate::core::registry::RtlBlock;
    use crate::pipelines::pixel_pipeline::{PixelPipeline, EVENT_TO_FRAGMENT};

    /// The headers' latency and FIFO figures are the constants' (they move whenever a block
    /// is pipelined further).
    #[test]
    fn header_figures_are_the_constants() {
        let lat = <PixelPipeline as RtlBlock>::LATENCY;
        crate::stream::assert_header_states::<super::PixelStream>(
            include_str!("pixel_stream.rs"),
            (super::FIFO_DEPTH, super::HOLD_ABOVE),
            ("pixel-pipeline", lat),
            &[format!(
                "`EVENT_TO_FRAGMENT` + 2 = {} events",
                EVENT_TO_FRAGMENT + 2
            )],
        );
        let pipe = include_str!("../pipelines/pixel_pipeline.rs").replace("\n//! ", " ");
        for want in [
            format!("Event → fragment {EVENT_TO_FRAGMENT} clocks"),
            format!("load → first fragment {lat}"),
        ] {
            assert!(pipe.contains(&want), "header lacks {want:?}");
        }
    }
}
