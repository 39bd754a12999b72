//! `angular-stream`: the angular span pipeline (`angular-pipeline`: two cos v accumulators,
//! power unit and colour combine per lane; SPEC §4, §0) behind AXI4-Stream interfaces, in place
//! of `angular-pipeline`'s 511 flat set-up pins: one record per raster line in on a 32-bit
//! stream, the material registers over the same stream, and fragments out on two 64-bit
//! streams, one per lane (depth on each lane's `tuser`), each with its own back-pressure.
//! Golden: `angular-pipeline`'s (the same fragments, in the same order on each lane, whatever
//! the stalls), itself checked against the golden `angular` method.
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─┬─ line fields ─► AngularPipeline ─┬─ lane A ─► FIFO (128) ─► m_axis_a
//!  (32 bit)   (record type, errors)  sw0..sw12       lw0..lw12  └─ register fields ─► r_*  ▲ hold  └─ lane B ─► FIFO (128) ─► m_axis_b
//!                                                                  (applied when drained)  └────── either FIFO's level ◄──┘
//! ```
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `s_axis_tdata` | in | set-up word, 32 bits (layout: `rtl::stream::layout::ANGULAR_STREAM`, `rtl/README.md`) |
//! | `s_axis_tvalid`, `s_axis_tlast` | in | AXI4-Stream; `tlast` on a record's last word |
//! | `s_axis_tready` | out | a word is accepted on `tvalid & tready` |
//! | `m_axis_a_tready`, `m_axis_b_tready` | in | each lane's consumer takes its beat on `tvalid & tready`; either may be low for any time |
//! | `m_axis_a_tvalid`, `m_axis_b_tvalid` | out | a beat is offered on the lane (held, with its data, until taken) |
//! | `m_axis_a_tdata`, `m_axis_b_tdata` | out | 64 bits: `x`, `y`, `pixel` (1: a fragment), `red`, `green`, `blue` (the `pixel-stream` beat) |
//! | `m_axis_a_tuser`, `m_axis_b_tuser` | out | the fragment's depth `z`, 32 bits (signed Q16.16 pixels) |
//! | `m_axis_a_tlast`, `m_axis_b_tlast` | out | the beat is from its line's last clock |
//! | `error` | out | sticky: a record with an unknown type or the wrong length was dropped |
//!
//! # Records (`rtl::stream::layout::ANGULAR_STREAM`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1 a line, 2 the registers; the other bits 0), then the record's
//! fields packed LSB first, a field never straddling two words: a line is 13 payload words
//! (`angular-pipeline`'s load ports in port order: y, x0, dir; m; p, q, d, cos β for L; the
//! same for H; z0, zm, dz), the registers 5 (n, the nine UQ8.8 colour weights). A record
//! whose `tlast` comes before or after its length, or with an unknown type, is dropped whole
//! (up to its `tlast`) and sets `error`.
//!
//! # Lanes
//! `angular-pipeline` gives up to two fragments per clock: lane A pixel k of the line in the
//! line's clock k, lane B pixel m − k (while m − k > k). Each lane has its own stream, so a
//! consumer with two write ports (a frame writer's two banks, say) takes both per clock; each
//! lane's beats come in the pipeline's order. Both lanes mark the line's last clock with
//! `tlast`: lane A always has a pixel then; when lane B has none (m even), it sends a beat
//! with `pixel` = 0 carrying only that `tlast` (as `pixel-stream` does for a triangle end
//! without a pixel), so each stream alone counts lines.
//!
//! # Handshake, latency, throughput
//! - Two word banks, as in the other stream tops: the receive bank takes the record being
//!   streamed in; a complete record moves in one clock to the load bank when that is free,
//!   and the receive bank takes the next one. `s_axis_tready` is low only while a complete
//!   record waits in the receive bank. A line in the load bank loads when the pipeline is
//!   `ready` (the units take the next line in the current one's last clock, without a gap);
//!   a register record waits until every line loaded before it has left the pipeline (its
//!   `done` seen), so no fragment mixes two register sets. Registers are 0 after reset: send
//!   a register record first.
//! - Each lane's beats enter its own 128-entry FIFO (`fragment_fifo`). The pipeline is held
//!   (its `hold`: the span units stand still, no pixel enters the shading, none lost; pixels
//!   already past them run on) in the clock after either FIFO held more than 66 beats (the
//!   hold is registered): from the clock a level first reaches 67, at most
//!   `EVENT_TO_FRAGMENT` + 1 = 61 more beats arrive on a lane, so neither FIFO holds more than
//!   128 and none overflows (`tests/span_stream.rs` measures the most under 90 % stalls and
//!   1 500-clock stretches). With both `tready` high each FIFO holds at most one beat and the
//!   pipeline is never held.
//! - Throughput: the pipeline's — two fragments per clock along a line — as long as the set-up
//!   words keep ahead: a line's record is 14 words at one word per clock, and a line of m + 1
//!   pixels takes ⌊m/2⌋ + 1 clocks, so lines shorter than 27 pixels are set-up bound.
//! - Latency: a line record's last word accepted in clock t → its first beats offered in
//!   clock t + 64 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 60 clocks through `angular-pipeline`, 2 through the FIFO and its output register).
//! - The fragment streams come from output registers (`m_axis_*_t*` are register outputs).
//!
//! # Overflow, error budget
//! None of its own: the FIFOs cannot overflow (above); `outstanding` (lines loaded whose last
//! clock has not left the pipeline) is 16 bits, at most 2 in practice; the data are
//! `angular-pipeline`'s, bit for bit (colours within its bound of the golden `angular`, depth
//! within 0.0157 pixels of the f64 plane).
//!
//! Latency (the block's `LATENCY`): 64 clocks, a line record's last word to its first fragment beats, two fragments per clock.

use rust_hdl::prelude::*;

use crate::pipelines::span_pipeline::AngularPipeline;

crate::two_lane_stream! {
    /// The angular span pipeline with AXI4-Stream set-up and fragment streams (see the header).
    pub struct AngularStream as "angular-stream" {
        summary: "AXI4-Stream top of the angular span pipeline: 32-bit line and register records in, two 64-bit fragment streams (one per lane, depth on tuser) out with back-pressure (a FIFO per lane and the units' hold)",
        latency: "a line record's last word to its first fragment beats, two fragments per clock",
        wraps: AngularPipeline,
        core: AngularStreamCore,
        layout: ANGULAR_STREAM in "angular_stream_core.rs",
        header: "angular_stream.rs" with |top| vec![format!(
            "the registers {}",
            crate::stream::layout::payload_words(&top.registers.unwrap())
        )],
    }
}
