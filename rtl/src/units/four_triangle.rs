//! Four-triangle address block (SPEC §7, figs. 3.9–3.10): one parent triangle's set-up in,
//! the pixel addresses of its four midpoint sub-triangles out, up to four per clock
//! (golden: `golden::units::four_triangle`, whose `FourTriangleModel` this block matches bit for bit
//! every clock; the fill rule that makes the four lanes tile the parent's pixel set exactly is
//! in that module's doc).
//!
//! # Structure
//!
//! ```text
//!                 shared increments (CT1/CT2 of the patent, "shifted right by one")
//!  load ─► w_f w_r w_d │ a_f a_r a_d │ t_f t_r t_d ───────┬──────┬──────┬──────┐
//!                                                         ▼      ▼      ▼      ▼
//!  per lane: (b0, e0) of its three edges, rows ──►     lane 0  lane 1  lane 2  lane 3
//!                                                     corner  corner  corner  middle
//!                                                     at T    at m_tm at m_tb (180°)
//!                                                         │      │      │      │
//!                                               *_l0 ◄────┘ *_l1 ◄┘ *_l2 ◄┘ *_l3 ◄┘
//! ```
//!
//! Each lane is an [`AddressBlock`] (SPEC §5: two line interpolators, RGr, CTx/CTy/CTr).
//! Every sub-triangle edge is parallel to a parent edge and half as long, so its DDA
//! increments (f, r, D) are the parent edge's: three shared triples, loaded once. The lanes
//! differ by their start registers (b0, e0 per edge; the patent's register/counter pairs for
//! the sub-triangles' top vertices): the three corner shapes are translated by half-pixel
//! offsets, which changes which pixel centres they cover, so they cannot share one error term
//! (see `golden::units::four_triangle`). Each lane's other and third edge select the adjacent (T→M)
//! or third (M→B) parent triple (`a_third_lK`, `t_adjacent_lK`): the middle lane, turned by
//! 180°, takes them the other way round, and a lane whose adjacent edge holds no row starts on
//! its third edge. The patent walks the middle sub-triangle upwards from its bottom point
//! (RG10, RG11); here it is walked downwards from its top like the others, so that all four
//! lanes are the same address block and share the fill rule's tie-breaking (walking it
//! upwards would need the mirrored rule to tile exactly).
//!
//! # Ports
//!
//! Inputs, sampled on the rising edge of `clock` when `load & ready`:
//!
//! | port                               | bits          | meaning                                   |
//! |------------------------------------|---------------|-------------------------------------------|
//! | `load`                             | 1             | load one parent triangle                  |
//! | `w_f w_r w_d`                      | 12, E, E      | increments of the parent's working edge T→B (f two's complement); E = 13, or 21 in `four-triangle-subpixel` |
//! | `a_f a_r a_d`, `t_f t_r t_d`       | same          | adjacent edge T→M, third edge M→B          |
//! | `w_b0_lK w_e0_lK`                  | 12, E         | lane K's working edge: boundary, error term on its first row |
//! | `a_b0_lK a_e0_lK`, `a_third_lK`    | 12, E, 1      | its other edge on the first row; uses the third-edge triple |
//! | `t_b0_lK t_e0_lK`, `t_adjacent_lK` | 12, E, 1      | its third edge; uses the adjacent-edge triple |
//! | `y_top_lK rows_lK y_switch_lK`     | 12 each       | first line, number of lines, switch line  |
//! | `dir_neg_lK`                       | 1             | lane K's lines run towards −x             |
//! | `hold`                             | 1             | stall, to every lane (any clock; see below) |
//!
//! Outputs: `ready` (a load is accepted in this clock: all four lanes are ready), and per lane
//! K (= sub-triangle index K: 0 corner at T, 1 at m_tm, 2 at m_tb, 3 middle) the address
//! block's outputs `valid_lK x_lK y_lK` (1, 12, 12), `step_lK` (2), `line_start_lK`,
//! `row_start_lK`, `carry_lK`, `done_lK` (1 each; `done` is the lane's last event of the
//! triangle). All are registers of the lanes, or the AND of their `ready` registers.
//!
//! # Timing
//!
//! Latency: load → first events 3 clocks (the address block's). Throughput: up to four
//! addresses per clock; a parent takes max over the lanes of Σ max(len, 1) over the lane's
//! rows (the sub-triangles are congruent, so the lanes are nearly balanced). The next parent is
//! accepted when every lane has produced its last row and taken its first record, so a lane
//! that finishes early idles (valid = 0) until then.
//! **Stall:** `hold` goes to the four lanes' `hold` (the address block's stall: a held clock
//! shows no event on any lane, each lane keeps the event it would have shown, a load is still
//! accepted on `load & ready`), so each lane's event stream under holds is its stream without
//! them with empty clocks inserted; 0 in every use without a stream top. It reaches the event
//! ports through one AND gate: drive it from a register.
//! Overflow: none for set-ups in range (every counter exact modulo its width). Error budget:
//! exact (integer).
//!
//! # Sub-pixel parents
//!
//! `four-triangle-subpixel` ([`SubpixelFourTriangle`]) is the same text with E = 21 and
//! [`LaneAddressBlock`] lanes: a parent with F = `SUBPIXEL_BITS` = 4 fraction bits has
//! sub-triangles with F + 1 = 5 (its doubled coordinates), each sub-edge's (Δx, Δy) in 2^−5
//! pixel is its parent edge's in 2^−4 pixel, so the increments are still shared, with D =
//! 2^5·Δy < 4095·2^9 < 2^21 (`golden::units::four_triangle::FourTriangleSetup::subpixel`).
//! Integer parents load the same words into either block, so it walks them identically.

use crate::units::address_block::{AddressBlock, LaneAddressBlock};
use rust_hdl::prelude::*;

/// One four-triangle block per lane type (`$lane`, an address block with `$e`-bit error
/// words): the integer block and [`SubpixelFourTriangle`] are the same text. The four lanes are
/// one text repeated by `seq!` (lane `L` is `laneL`, its ports end in `_lL`), so they cannot
/// drift apart; the exported Verilog is the same as the text written out four times.
macro_rules! four_triangle {
    (
        $(#[$m:meta])*
        pub struct $name:ident($lane:ident, $e:tt) as $export:literal {
            summary: $summary:literal $(,)?
        }
    ) => {
seq_macro::seq!(L in 0..4 {
crate::hw_block! {
    $(#[$m])*
    pub struct $name(clock) as $export {
        summary: $summary,
        latency: $lane::LATENCY => "load to the first events, up to four addresses per clock",
        multipliers: 0,
        in {
            load: Bit,
            w_f: Bits<12>, w_r: Bits<$e>, w_d: Bits<$e>,
            a_f: Bits<12>, a_r: Bits<$e>, a_d: Bits<$e>,
            t_f: Bits<12>, t_r: Bits<$e>, t_d: Bits<$e>,
            #(
            w_b0_l~L: Bits<12>, w_e0_l~L: Bits<$e>, a_b0_l~L: Bits<12>, a_e0_l~L: Bits<$e>, a_third_l~L: Bit,
            t_b0_l~L: Bits<12>, t_e0_l~L: Bits<$e>, t_adjacent_l~L: Bit,
            y_top_l~L: Bits<12>, rows_l~L: Bits<12>, y_switch_l~L: Bits<12>, dir_neg_l~L: Bit,
            )*
            hold: Bit,
        }
        out {
            ready: Bit,
            #(
            valid_l~L: Bit, x_l~L: Bits<12>, y_l~L: Bits<12>, step_l~L: Bits<2>,
            line_start_l~L: Bit, row_start_l~L: Bit, carry_l~L: Bit, done_l~L: Bit,
            )*
        }
        #(
        /// One lane: sub-triangle `L`.
        pub lane~L: $lane,
        )*
        /// All four lanes are ready: the load is taken.
        all_ready: Signal<Local, Bit>,
    }
}

impl Logic for $name {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, lane0, lane1, lane2, lane3);
        self.all_ready.next = self.lane0.ready.val()
            & self.lane1.ready.val()
            & self.lane2.ready.val()
            & self.lane3.ready.val();
        self.ready.next = self.all_ready.val();
        #(
        self.lane~L.load.next = self.load.val() & self.all_ready.val();
        self.lane~L.hold.next = self.hold.val();
        self.lane~L.w_b0.next = self.w_b0_l~L.val();
        self.lane~L.w_e0.next = self.w_e0_l~L.val();
        self.lane~L.w_f.next = self.w_f.val();
        self.lane~L.w_r.next = self.w_r.val();
        self.lane~L.w_d.next = self.w_d.val();
        self.lane~L.a_b0.next = self.a_b0_l~L.val();
        self.lane~L.a_e0.next = self.a_e0_l~L.val();
        if self.a_third_l~L.val() {
            self.lane~L.a_f.next = self.t_f.val();
            self.lane~L.a_r.next = self.t_r.val();
            self.lane~L.a_d.next = self.t_d.val();
        } else {
            self.lane~L.a_f.next = self.a_f.val();
            self.lane~L.a_r.next = self.a_r.val();
            self.lane~L.a_d.next = self.a_d.val();
        }
        self.lane~L.t_b0.next = self.t_b0_l~L.val();
        self.lane~L.t_e0.next = self.t_e0_l~L.val();
        if self.t_adjacent_l~L.val() {
            self.lane~L.t_f.next = self.a_f.val();
            self.lane~L.t_r.next = self.a_r.val();
            self.lane~L.t_d.next = self.a_d.val();
        } else {
            self.lane~L.t_f.next = self.t_f.val();
            self.lane~L.t_r.next = self.t_r.val();
            self.lane~L.t_d.next = self.t_d.val();
        }
        self.lane~L.y_top.next = self.y_top_l~L.val();
        self.lane~L.rows.next = self.rows_l~L.val();
        self.lane~L.y_switch.next = self.y_switch_l~L.val();
        self.lane~L.dir_neg.next = self.dir_neg_l~L.val();
        self.valid_l~L.next = self.lane~L.valid.val();
        self.x_l~L.next = self.lane~L.x.val();
        self.y_l~L.next = self.lane~L.y.val();
        self.step_l~L.next = self.lane~L.step.val();
        self.line_start_l~L.next = self.lane~L.line_start.val();
        self.row_start_l~L.next = self.lane~L.row_start.val();
        self.carry_l~L.next = self.lane~L.carry.val();
        self.done_l~L.next = self.lane~L.done.val();
        )*
    }
}
});
    };
}

four_triangle! {
    /// The four-triangle address block (see the module header).
    pub struct FourTriangle(AddressBlock, 13) as "four-triangle" {
        summary: "one triangle's set-up in, the addresses of its four midpoint sub-triangles out, up to four per clock (SPEC §7)",
    }
}

four_triangle! {
    /// The four-triangle address block for parents with `SUBPIXEL_BITS` = 4 fractional bits:
    /// lanes with 21-bit error words (see the module header).
    pub struct SubpixelFourTriangle(LaneAddressBlock, 21) as "four-triangle-subpixel" {
        summary: "one sub-pixel triangle's set-up in (vertices with 4 fraction bits), the addresses of its four midpoint sub-triangles out, up to four per clock (SPEC §7)",
    }
}
