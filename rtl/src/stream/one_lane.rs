//! The fragment side the one-lane stream tops with a depth stream share (`pixel-stream`,
//! `cubic-stream`): a FIFO of (beat, z with `tlast`) in distributed RAM behind the generated
//! core, the wrapped top held from the FIFO's level, and the output register.
//! [`one_lane_stream!`](crate::one_lane_stream) writes the struct and its `update`; each top's
//! header states its figures (checked by its own test).
//!
//! Not a block: no ports, no latency of its own.

/// Declare a one-lane stream top with a depth stream. `push` names the signal that writes the
/// FIFO: the local that `events` declares (`valid | done`: every fragment and every end of a
/// triangle is a beat) or `core.valid` (every fragment; `tlast` rides on the last one).
/// `level` is the level counter's width; `core_file` names the generated core `rtl/build.rs`
/// writes into `OUT_DIR` (`rtl::stream::layout::core_file_name`), which the macro includes. The
/// file defines `FIFO_BITS` and `HOLD_ABOVE`.
///
/// The whole `impl Logic` is in this macro's own text; the caller passes names only (see
/// `crate::core::declare` on hygiene).
#[macro_export]
macro_rules! one_lane_stream {
    (
        $(#[$m:meta])*
        pub struct $name:ident as $block:literal {
            summary: $summary:literal,
            latency: $latency:expr => $latency_text:literal,
            multipliers: $mults:expr,
            core: $core:ident = $init:expr,
            core_file: $core_file:literal,
            level: $level:literal,
            $(events: $events:ident,)?
            push: $($push:ident).+,
        }
        new($arg:ident : &$pt:ty);
    ) => {
        $crate::hw_block! {
            $(#[$m])*
            pub struct $name(clock) as $block {
                summary: $summary,
                latency: $latency => $latency_text,
                multipliers: $mults,
                in { s_axis_tdata: Bits<32>, s_axis_tvalid: Bit, s_axis_tlast: Bit, m_axis_tready: Bit }
                out {
                    s_axis_tready: Bit, m_axis_tvalid: Bit, m_axis_tdata: Bits<64>, m_axis_tuser: Bits<32>,
                    m_axis_tlast: Bit, error: Bit,
                }
                /// The record banks, the field selects and the wrapped top (`core.pipe`): generated.
                pub core: $core = $init,
                /// Fragment side: the FIFO of (beat, and z with tlast) and its output register.
                fifo: $crate::stream::fragment_fifo::FragmentFifo<FIFO_BITS, $level>,
                hold_above: Constant<Bits<$level>> = Constant::new((HOLD_ABOVE as u64).into()),
                /// The hold, registered (the comparator, the wrapped top's gating and the depth
                /// channel's adder in one clock ran at 79.8 MHz on ECP5 in `pixel-stream`).
                hold_q: DFF<Bit>,
                $($events: Signal<Local, Bit>,)?
                beat: Signal<Local, Bits<64>>, tail: Signal<Local, Bits<33>>,
                tlast_bit: Constant<Bits<33>> = Constant::new((1u64 << 32).into()),
            }
            new($arg: &$pt);
        }

        // The level counter holds a full FIFO's 2^FIFO_BITS.
        const _: () = assert!($level > FIFO_BITS);

        /// The generated core: `rtl/build.rs` writes it from the top's layout table (the record
        /// banks, the field selects into the wrapped top, the fragment packing).
        mod generated {
            use super::*;
            use $crate::stream::record_reader::{RecordReader, INDEX_BITS};
            include!(concat!(env!("OUT_DIR"), "/", $core_file));
        }
        pub use generated::$core;

        impl Logic for $name {
            #[hdl_gen]
            fn update(&mut self) {
                clock!(self, clock, core, fifo);
                // The fragment beats the generated core packs.
                self.beat.next = self.core.beat.val();
                dff_setup!(self, clock, hold_q);

                // Set-up side: the generated core (record reader, load bank, word banks, field
                // selects).
                self.core.s_axis_tdata.next = self.s_axis_tdata.val();
                self.core.s_axis_tvalid.next = self.s_axis_tvalid.val();
                self.core.s_axis_tlast.next = self.s_axis_tlast.val();
                self.s_axis_tready.next = self.core.s_axis_tready.val();
                self.error.next = self.core.error.val();

                // Fragment side: `push` writes a beat.
                self.fifo.hold_above.next = self.hold_above.val();
                self.hold_q.d.next = self.fifo.over.val();
                self.core.hold.next = self.hold_q.q.val();
                $(self.$events.next = self.core.valid.val() | self.core.done.val();)?
                self.fifo.push.next = self.$($push).+.val();
                self.fifo.beat.next = self.beat.val();
                // The tail (z, and tlast on a triangle's end) formed in a local and driven into
                // the FIFO by one assignment: a port set twice in one `always @(*)` pulses
                // in an event-driven simulator, and the FIFO's outputs (set the same way)
                // lead back into this block, so the two would wake each other for ever
                // (Icarus hung at one time step).
                self.tail.next = bit_cast::<33, 32>(self.core.z.val());
                if self.core.done.val() {
                    self.tail.next = bit_cast::<33, 32>(self.core.z.val()) | self.tlast_bit.val();
                }
                self.fifo.tail.next = self.tail.val();
                self.fifo.tready.next = self.m_axis_tready.val();
                self.m_axis_tvalid.next = self.fifo.tvalid.val();
                self.m_axis_tdata.next = self.fifo.tdata.val();
                self.m_axis_tuser.next = self.fifo.tuser.val();
                self.m_axis_tlast.next = self.fifo.tlast.val();
            }
        }
    };
}
