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

use crate::core::registry::RtlBlock;
use crate::pipelines::cubic_pipeline::{CubicParams, CubicPipeline};

/// Clocks from a pixel entering the units to its fragment at `cubic-pipeline`'s outputs (at
/// most its load-to-first-fragment latency).
pub const EVENT_TO_FRAGMENT: usize = <CubicPipeline as RtlBlock>::LATENCY;
/// FIFO depth (entries) and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 5;
/// The FIFO level above which the pipeline is held (the clock after: `hold` is registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

crate::one_lane_stream! {
    /// The cubic span pipeline with AXI4-Stream set-up and fragment streams (see the header).
    pub struct CubicStream as "cubic-stream" {
        summary: "AXI4-Stream top of the cubic span pipeline: 32-bit line records in, 64-bit fragment beats (depth on tuser) out with back-pressure (a FIFO and the units' hold)",
        latency: 2 + <CubicPipeline as RtlBlock>::LATENCY + 2
            => "a line record's last word to its first fragment beat (pipelined units; serial: up to 2 more)",
        multipliers: 6,
        core: CubicStreamCore = CubicStreamCore::new(p),
        core_file: "cubic_stream_core.rs",
        level: 6,
        push: core.valid,
    }
    new(p: &CubicParams);
}

#[cfg(test)]
mod tests {
    use crate::pipelines::cubic_pipeline::CubicPipeline;

    /// The header's latency, FIFO and record figures are the constants'.
    #[test]
    fn header_figures_are_the_constants() {
        let words = crate::stream::layout::payload_words(&crate::stream::layout::CUBIC_LINE);
        let ev = super::EVENT_TO_FRAGMENT;
        crate::stream::assert_header_states::<super::CubicStream>(
            include_str!("cubic_stream.rs"),
            (super::FIFO_DEPTH, super::HOLD_ABOVE),
            ("cubic-pipeline", CubicPipeline::LATENCY),
            &[
                format!("`EVENT_TO_FRAGMENT` + 1 = {} more fragments", ev + 1),
                format!("never holds more than {}", super::HOLD_ABOVE + 1 + ev + 1),
                format!("then {words} payload words"),
                format!("record is {} words", words + 1),
                format!("FIFO ({})", super::FIFO_DEPTH),
            ],
        );
    }
}
