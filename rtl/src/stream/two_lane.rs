//! The fragment side the two-lane stream tops share (`angular-stream`, `fast-stream`,
//! `quadric-stream`): a [`LaneFifo`](crate::stream::fragment_fifo::LaneFifo) per lane,
//! the wrapped top held from either FIFO's level, a beat per lane for each fragment and for a
//! line's last clock. [`two_lane_stream!`](crate::two_lane_stream) writes the whole top around
//! its generated core; each top's header states the figures (checked by
//! `check_two_lane_header`).
//!
//! Not a block: no ports, no latency of its own.

/// Declare a two-lane stream top: its struct (ports, the generated `core`, a FIFO per lane)
/// and its `update`. The core (`rtl/build.rs`, from the top's layout table) gives `beat_a`,
/// `beat_b`, `z_a`, `z_b`, `valid_a`, `valid_b`, `done` and takes `hold`.
///
/// The whole `impl Logic` is in this macro's own text, so `#[hdl_gen]`'s `self` and the
/// statements' `self` share one hygiene (see `crate::core::declare`).
#[macro_export]
macro_rules! two_lane_stream {
    (
        $(#[$m:meta])*
        pub struct $name:ident as $block:literal {
            summary: $summary:literal,
            latency: $latency_text:literal,
            wraps: $wraps:ty,
            core: $core:ident $(= $init:expr)?,
            layout: $layout:ident in $core_file:literal,
            header: $source:literal with |$top:ident| $extra:expr,
        }
        $(new($arg:ident : &$pt:ty);)?
    ) => {
        /// Clocks from a pixel entering the wrapped top's units to its fragment at the wrapped
        /// top's outputs (at most its load-to-first-fragment latency).
        pub const EVENT_TO_FRAGMENT: usize = <$wraps as $crate::core::registry::RtlBlock>::LATENCY;
        /// Each lane's FIFO depth (entries).
        pub const FIFO_DEPTH: usize = $crate::stream::fragment_fifo::FIFO_DEPTH;
        /// The FIFO level above which the pipeline is held (the clock after: `hold` is
        /// registered).
        pub const HOLD_ABOVE: usize = FIFO_DEPTH - EVENT_TO_FRAGMENT - 2;

        $crate::hw_block! {
            $(#[$m])*
            pub struct $name(clock) as $block {
                summary: $summary,
                latency: 2 + <$wraps as $crate::core::registry::RtlBlock>::LATENCY + 2 => $latency_text,
                multipliers: <$wraps as $crate::core::registry::RtlBlock>::MULTIPLIERS,
                in {
                    s_axis_tdata: Bits<32>, s_axis_tvalid: Bit, s_axis_tlast: Bit,
                    m_axis_a_tready: Bit, m_axis_b_tready: Bit,
                }
                out {
                    s_axis_tready: Bit,
                    m_axis_a_tvalid: Bit, m_axis_a_tdata: Bits<64>, m_axis_a_tuser: Bits<32>, m_axis_a_tlast: Bit,
                    m_axis_b_tvalid: Bit, m_axis_b_tdata: Bits<64>, m_axis_b_tuser: Bits<32>, m_axis_b_tlast: Bit,
                    error: Bit,
                }
                /// The record banks, the field selects and the wrapped top (`core.pipe`): generated.
                pub core: $core $(= $init)?,
                // Fragment side: a FIFO per lane, the hold from either's level.
                lane_a: $crate::stream::fragment_fifo::LaneFifo,
                lane_b: $crate::stream::fragment_fifo::LaneFifo,
                hold_above: Constant<Bits<8>> = Constant::new((HOLD_ABOVE as u64).into()),
                hold_q: DFF<Bit>,
                beat_a: Signal<Local, Bits<64>>, beat_b: Signal<Local, Bits<64>>,
                tail_a: Signal<Local, Bits<33>>, tail_b: Signal<Local, Bits<33>>,
                tlast_bit: Constant<Bits<33>> = Constant::new((1u64 << 32).into()),
            }
            $(new($arg: &$pt);)?
        }

        impl Logic for $name {
            #[hdl_gen]
            fn update(&mut self) {
                clock!(self, clock, core, lane_a, lane_b);
                // The fragment beats the generated core packs.
                self.beat_a.next = self.core.beat_a.val();
                self.beat_b.next = self.core.beat_b.val();
                dff_setup!(self, clock, hold_q);
                // Set-up side: the generated core (record reader, load bank, word banks, field
                // selects).
                self.core.s_axis_tdata.next = self.s_axis_tdata.val();
                self.core.s_axis_tvalid.next = self.s_axis_tvalid.val();
                self.core.s_axis_tlast.next = self.s_axis_tlast.val();
                self.s_axis_tready.next = self.core.s_axis_tready.val();
                self.error.next = self.core.error.val();

                // Fragment side: a beat per lane for each fragment, and for the line's last clock
                // (lane B's beat then may carry only its `tlast`).
                self.hold_q.d.next = self.lane_a.over.val() | self.lane_b.over.val();
                self.core.hold.next = self.hold_q.q.val();
                self.tail_a.next = bit_cast::<33, 32>(self.core.z_a.val());
                self.tail_b.next = bit_cast::<33, 32>(self.core.z_b.val());
                if self.core.done.val() {
                    self.tail_a.next = bit_cast::<33, 32>(self.core.z_a.val()) | self.tlast_bit.val();
                    self.tail_b.next = bit_cast::<33, 32>(self.core.z_b.val()) | self.tlast_bit.val();
                }
                self.lane_a.push.next = self.core.valid_a.val() | self.core.done.val();
                self.lane_a.beat.next = self.beat_a.val();
                self.lane_a.tail.next = self.tail_a.val();
                self.lane_a.tready.next = self.m_axis_a_tready.val();
                self.lane_a.hold_above.next = self.hold_above.val();
                self.lane_b.push.next = self.core.valid_b.val() | self.core.done.val();
                self.lane_b.beat.next = self.beat_b.val();
                self.lane_b.tail.next = self.tail_b.val();
                self.lane_b.tready.next = self.m_axis_b_tready.val();
                self.lane_b.hold_above.next = self.hold_above.val();
                self.m_axis_a_tvalid.next = self.lane_a.tvalid.val();
                self.m_axis_a_tdata.next = self.lane_a.tdata.val();
                self.m_axis_a_tuser.next = self.lane_a.tuser.val();
                self.m_axis_a_tlast.next = self.lane_a.tlast.val();
                self.m_axis_b_tvalid.next = self.lane_b.tvalid.val();
                self.m_axis_b_tdata.next = self.lane_b.tdata.val();
                self.m_axis_b_tuser.next = self.lane_b.tuser.val();
                self.m_axis_b_tlast.next = self.lane_b.tlast.val();
            }
        }

        /// The generated core: `rtl/build.rs` writes it from the top's layout table (the
        /// record banks, the field selects into the wrapped top, the fragment packing).
        mod generated {
            use super::*;
            use $crate::stream::record_reader::{RecordReader, INDEX_BITS};
            include!(concat!(env!("OUT_DIR"), "/", $core_file));
        }
        pub use generated::$core;

        #[cfg(test)]
        mod two_lane_tests {
            use super::*;
            use $crate::core::registry::RtlBlock;

            /// The header's latency, FIFO and record figures are the constants'.
            #[test]
            fn header_figures_are_the_constants() {
                let $top = $crate::stream::layout::$layout;
                let extra: Vec<String> = $extra;
                $crate::stream::fragment_fifo::check_two_lane_header(
                    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/stream/", $source)),
                    &$top,
                    super::HOLD_ABOVE,
                    super::EVENT_TO_FRAGMENT,
                    <super::$name as RtlBlock>::LATENCY,
                    <$wraps as RtlBlock>::LATENCY,
                    &extra,
                );
            }
        }
    };
}
