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

use crate::pipelines::span_pipeline::{FastPipeline, FastPipelineParams};

crate::two_lane_stream! {
    /// The fast span pipeline with AXI4-Stream set-up and fragment streams (see the header).
    pub struct FastStream as "fast-stream" {
        summary: "AXI4-Stream top of the fast span pipeline: 32-bit line and register records in, two 64-bit fragment streams (one per lane, depth on tuser) out with back-pressure (a FIFO per lane and the units' hold)",
        latency: "a line record's last word to its first fragment beats, two fragments per clock",
        wraps: FastPipeline,
        core: FastStreamCore = FastStreamCore::new(p),
        layout: FAST_STREAM in "fast_stream_core.rs",
        header: "fast_stream.rs" with |top| vec![format!("the registers {}", crate::stream::layout::payload_words(&top.registers.unwrap()))],
    }
    new(p: &FastPipelineParams);
}
