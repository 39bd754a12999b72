//! `textured-stream`: the textured pixel pipeline (`textured_pipeline`, SPEC §14) behind
//! AXI4-Stream interfaces: set-up records and the texture itself in on a 32-bit stream,
//! fragments out on a 64-bit stream with back-pressure. Golden: `textured-pipeline`'s (the same
//! fragments, in the same order, whatever the stalls).
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─┬─ triangle fields ─► TexturedPipeline ─► FIFO (128) ─► m_axis
//!  (32 bit)   (record type, errors)  sw0..sw49       lw0..lw49  ├─ register fields ─► r_* (applied          ▲   │
//!                                                               │                       when drained)    hold ◄┘ (FIFO level)
//!                                                               ├─ texel fields ─► tex_we (when drained)
//!                                                               └─ line fields ─► line_push (when line_ready)
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
//! A header word (bits 3..0: 1 triangle, 2 registers, 3 texel, 4 line; the other bits 0), then the
//! record's fields packed LSB first into words (a field of up to 32 bits never straddles two
//! words; a 48-bit one takes a word and the next one's low 16 bits): a triangle is 50 payload
//! words (the address block's set-up, the normal planes, the depth
//! plane, the texture-coordinate block's set-up), the registers 7 (L, H, n, the specular
//! colour, k_a, k_d, the texture's sides), a texel 2 (its address v·2^log_w + u and its colour
//! 0xRRGGBB), a line 16 (the per-line builds' record of a raster line: the pipeline's
//! `line_…` ports, u's and v's start, Δ, ΔΔ, the Bézier build's last pixel index and X's Δ(0),
//! d; one per raster line with a pixel, in the walk's order, after its triangle's record and
//! before the next triangle's). A record whose `tlast` comes before or after its length, or with an unknown
//! type, is dropped whole (up to its `tlast`) and sets `error`.
//!
//! # Handshake, latency, throughput
//! - Two word banks, as `pixel-stream`: a complete record moves in one clock to the load bank
//!   when that is free. A triangle waits there for the pipeline's `ready`; a register record
//!   and a texel record wait until every triangle loaded before them has left the pipeline
//!   (its `done` seen), so no fragment mixes two register sets and no texel is rewritten under
//!   a triangle that reads it; a texel record is then written in one clock (`tex_we`). A line
//!   record goes into the pipeline's 4-entry line FIFO (`line_push`) when that has room
//!   (`line_ready`); records after it wait behind it, so a triangle's line records are in
//!   the FIFO, in order, before the next triangle's record reaches the load bank.
//!   Registers are 0 after reset, the texture memory is zeros: send the register record and
//!   the texels first.
//! - Loading the texture: three words a texel (header and two payload words), a texel every
//!   four clocks while the producer keeps up (its three words, then the clock in which
//!   `s_axis_tready` is low while the record moves to the load bank): a 256 × 256 texture is
//!   196 608 words in 262 144 clocks.
//! - Fragments (and triangle ends) enter a 128-entry FIFO. The address block is held (the
//!   pipeline's `hold`) in the clock after the FIFO held more than 25 beats: at most
//!   2·`EVENT_FIFO` + `EVENT_TO_FRAGMENT` + 2 = 103 events are then still in flight (the
//!   pipeline's two event FIFOs, its lit path from the pop, the registered hold), so the FIFO
//!   never overflows and never drops a fragment; with `m_axis_tready` high it holds at most one
//!   beat and the address block is never held.
//! - Throughput: `textured-pipeline`'s (one fragment per clock while every pixel needs at most
//!   k correction steps per axis) as long as the set-up words keep ahead of the walk: a
//!   triangle's set-up is 51 words at one word per clock, so a run of triangles smaller than
//!   that is set-up bound. From the first triangle word to the last beat, `tready` high, k = 4,
//!   the engine's balanced order: the default scene (2 352 triangles, 48 fragments each on
//!   average) 0.859 fragments per clock against `textured-pipeline`'s 0.959; `plane` (250
//!   large triangles) 0.975 against 0.976 (`cargo test --release --test rtl_texture --
//!   --include-ignored --nocapture` prints both; full tier). The per-line builds add 17 words
//!   per raster line with a pixel: on the default scene 408 034 set-up words after the
//!   texture for 113 136 fragments, about 0.26 fragments per clock (`docs/measurements.md`).
//! - Latency: a triangle record's last word accepted in clock t → its first beat offered in
//!   clock t + 95 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 91 clocks through `textured-pipeline` for a pixel whose texel settles at once, 2
//!   through the FIFO and its output register).
//!
//! # Overflow, error budget
//! None of its own: the FIFO cannot overflow (above), `outstanding` is 16 bits (triangles
//! loaded and not finished, at most 2 in practice); the data are `textured-pipeline`'s, bit
//! for bit.
//!
//! # Build parameters
//! `textured-pipeline`'s: `tex-k` (1 | 2 | 4, default 4) and `texture` (additive, the default;
//! quadratic or bezier, the per-line builds, whose line records come on the stream; the
//! additive build has no consumer for them: a line record there fills the FIFO and, the fifth,
//! waits in the load bank for good).
//!
//! Latency (the block's `LATENCY`): 95 clocks, a triangle record's last word to its first fragment beat, one fragment per clock.

use rust_hdl::prelude::*;

use crate::core::registry::{BlockParams, Options};
use crate::pipelines::pixel_pipeline::EVENT_TO_FRAGMENT;
use crate::pipelines::textured_pipeline::{TexturedParams, TexturedPipeline, EVENT_FIFO};

/// `textured-stream`'s build parameters: the textured pipeline's (`tex-k`, and `texture`:
/// additive, quadratic or bezier; the per-line builds take their line records on the stream).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TexturedStreamParams(pub TexturedParams);

impl std::ops::Deref for TexturedStreamParams {
    type Target = TexturedParams;
    fn deref(&self) -> &TexturedParams {
        &self.0
    }
}

impl BlockParams for TexturedStreamParams {
    const KEYS: &'static [&'static str] = TexturedParams::KEYS;
    /// As the pipeline's.
    fn from_options(o: &Options) -> Result<Self, String> {
        TexturedParams::from_options(o).map(TexturedStreamParams)
    }
    fn describe(&self) -> Option<String> {
        self.0.describe()
    }
}

/// FIFO depth (entries) and its address width.
pub const FIFO_DEPTH: usize = 1 << FIFO_BITS;
const FIFO_BITS: usize = 7;
/// Events that may still reach the FIFO once the address block is held: both event FIFOs,
/// the lit path from the pop, and the registered hold's clocks.
pub const IN_FLIGHT: usize = 2 * EVENT_FIFO + EVENT_TO_FRAGMENT + 2;
/// The FIFO level above which the address block is held (the clock after: `hold` is
/// registered).
pub const HOLD_ABOVE: usize = FIFO_DEPTH - IN_FLIGHT;

crate::one_lane_stream! {
    /// The textured pixel pipeline with AXI4-Stream set-up and fragment streams (see the
    /// header).
    pub struct TexturedStream as "textured-stream" {
        summary: "AXI4-Stream top of the textured pixel pipeline: 32-bit set-up records and texels in, 64-bit fragment beats out with back-pressure (a FIFO and the address block's hold)",
        latency: 2 + TexturedPipeline::LATENCY + 2
            => "a triangle record's last word to its first fragment beat, one fragment per clock",
        multipliers: 44,
        core: TexturedStreamCore = TexturedStreamCore::new(p),
        core_file: "textured_stream_core.rs",
        level: 8,
        events: ev_beat,
        push: ev_beat,
    }
    new(p: &TexturedStreamParams);
}

#[cfg(test)]
mod tests {
    use crate::pipelines::pixel_pipeline::EVENT_TO_FRAGMENT;
    use crate::pipelines::textured_pipeline::{TexturedPipeline, EVENT_FIFO};
    use crate::stream::layout::{
        payload_words, TEXEL, TEXTURED_LINE, TEXTURED_REGISTERS, TEXTURED_TRIANGLE,
    };

    /// The header's figures are the constants' (they move whenever a block is pipelined
    /// further or a record grows).
    #[test]
    fn header_figures_are_the_constants() {
        let triangle = payload_words(&TEXTURED_TRIANGLE);
        crate::stream::assert_header_states::<super::TexturedStream>(
            include_str!("textured_stream.rs"),
            (super::FIFO_DEPTH, super::HOLD_ABOVE),
            ("textured-pipeline", TexturedPipeline::LATENCY),
            &[
                format!(
                    "2·`EVENT_FIFO` + `EVENT_TO_FRAGMENT` + 2 = {} events",
                    2 * EVENT_FIFO + EVENT_TO_FRAGMENT + 2
                ),
                format!("a triangle is {triangle} payload words"),
                format!("the registers {}", payload_words(&TEXTURED_REGISTERS)),
                format!("a texel {}", payload_words(&TEXEL)),
                format!("a line {}", payload_words(&TEXTURED_LINE)),
                format!("set-up is {} words", triangle + 1),
                format!("sw0..sw{}", triangle - 1),
            ],
        );
    }
}
