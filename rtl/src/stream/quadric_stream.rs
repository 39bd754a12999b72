//! `quadric-stream`: the quadric forward-difference unit (`quadric-unit`: a 2-D difference
//! tracker over the line starts and a line generator, three channels, two pixels per clock;
//! SPEC §8) behind the AXI4-Stream interfaces of `angular-stream`, in place of
//! `quadric-unit`'s 1 254 flat set-up pins: a short record per raster line, a long one for a
//! triangle's first line (its coefficients), on a 32-bit stream; fragments out on two 64-bit
//! streams, one per lane (depth on each lane's `tuser`), each with its own back-pressure.
//! Golden: `quadric-unit`'s (the same fragments, in the same order on each lane, whatever the
//! stalls), itself checked against the golden `quadric` method.
//!
//! ```text
//!  s_axis ─► header / word count ─► receive bank ─► load bank ─► QuadricUnit ─┬─ lane A ─► FIFO (128) ─► m_axis_a
//!  (32 bit)   (record type, errors)  sw0..sw39       lw0..lw39    ▲ hold      └─ lane B ─► FIFO (128) ─► m_axis_b
//!                                                                 └───── either FIFO's level ◄──┘
//! ```
//!
//! # Ports
//! `angular-stream`'s, the same widths and meaning: `s_axis_tdata` (32), `s_axis_tvalid`,
//! `s_axis_tlast`, `s_axis_tready`; per lane `m_axis_a_*` and `m_axis_b_*`: `tready` in,
//! `tvalid`, `tdata` (64 bits: `x`, `y`, `pixel`, `red`, `green`, `blue`), `tuser` (the depth
//! `z`, signed Q16.16, 32 bits) and `tlast` (the line's last clock) out; `error` (sticky: a
//! record with an unknown type or the wrong length was dropped).
//!
//! # Records (`rtl::stream::layout::QUADRIC_STREAM`, one table for the hardware and the driver)
//! A header word (bits 3..0: 1 a line, 2 a triangle's first line; the other bits 0), then the
//! record's fields packed LSB first: a line is 4 payload words (y, x0, dir; m; z0; dz), a
//! triangle's first line 40 (the same 4 words in the same places, then per channel I, Dx, Dy,
//! 2A, 2B, C, signed Q34.30, each over two words). A type-2 record loads the unit with `first`
//! = 1 (the tracker takes the coefficients); a type-1 record loads with `first` = 0 and the
//! load bank's coefficient words, which the unit does not read then. No registers: the quadric
//! is lit in the set-up (the sources' software part). A record whose `tlast` comes before or
//! after its length, or with an unknown type, is dropped whole (up to its `tlast`) and sets
//! `error`.
//!
//! # Lanes, handshake, latency, throughput
//! The unit's lane A has pixel 2k of the line in its generator's clock k, lane B pixel 2k + 1;
//! both lanes mark the line's last clock with `tlast` (lane B with a `pixel` = 0 beat when it
//! has no pixel then). A record in the load bank loads when the unit is `ready` (a line is taken
//! in its predecessor's hand-over clock); `s_axis_tready` is low only while a complete record
//! waits in the receive bank.
//! - Each lane's beats enter its own 128-entry FIFO (`fragment_fifo`). The unit is held (its
//!   `hold`: the generator stands still, no pixel is lost) in the clock after either FIFO held
//!   more than 122 beats (the hold is registered): from the clock a level first reaches 123, at
//!   most `EVENT_TO_FRAGMENT` + 1 = 5 more beats arrive on a lane, so neither FIFO holds more
//!   than 128 and none overflows. With both `tready` high each FIFO holds at most one beat and
//!   the unit is never held.
//! - Throughput: two fragments per clock along a line while the set-up words keep ahead: a
//!   line's record is 5 words at one word per clock (a triangle's first line 41), and a line of
//!   m + 1 pixels takes ⌊m/2⌋ + 1 clocks after its start's move, so lines shorter than 9 pixels
//!   are set-up bound.
//! - Latency: a line record's last word accepted in clock t → its first beats offered in
//!   clock t + 8 (the record is complete in t + 1, moves to the load bank in t + 1, loads in
//!   t + 2; 4 clocks through `quadric-unit`, 2 through the FIFO and its output register), when
//!   the unit is ready and the line starts where the tracker stands.
//!
//! # Overflow, error budget
//! None of its own: the FIFOs cannot overflow (above); the data are `quadric-unit`'s, bit for
//! bit (colours within its bound of the golden `quadric`, depth within 4096·2⁻¹⁷ + 2⁻¹⁶ of the
//! f64 plane).
//!
//! Latency (the block's `LATENCY`): 8 clocks, a line record's last word to its first fragment beats (the unit ready, no move to the line's start), two fragments per clock.

use rust_hdl::prelude::*;

use crate::units::quadric_unit::QuadricUnit;

crate::two_lane_stream! {
    /// The quadric unit with AXI4-Stream set-up and fragment streams (see the header).
    pub struct QuadricStream as "quadric-stream" {
        summary: "AXI4-Stream top of the quadric unit: 32-bit line records (a triangle's first line with its coefficients) in, two 64-bit fragment streams (one per lane, depth on tuser) out with back-pressure (a FIFO per lane and the generator's hold)",
        latency: "a line record's last word to its first fragment beats (the unit ready, no move to the line's start), two fragments per clock",
        wraps: QuadricUnit,
        core: QuadricStreamCore,
        layout: QUADRIC_STREAM in "quadric_stream_core.rs",
        header: "quadric_stream.rs" with |top| {
            let full = crate::stream::layout::payload_words(&top.full.unwrap());
            vec![format!("first line {full}"), format!("first line {})", full + 1)]
        },
    }
}
