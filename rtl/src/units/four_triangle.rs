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
//!                                               l0_* ◄────┘ l1_* ◄┘ l2_* ◄┘ l3_* ◄┘
//! ```
//!
//! Each lane is an [`AddressBlock`] (SPEC §5: two line interpolators, RGr, CTx/CTy/CTr).
//! Every sub-triangle edge is parallel to a parent edge and half as long, so its DDA
//! increments (f, r, D) are the parent edge's: three shared triples, loaded once. The lanes
//! differ by their start registers (b0, e0 per edge; the patent's register/counter pairs for
//! the sub-triangles' top vertices): the three corner shapes are translated by half-pixel
//! offsets, which changes which pixel centres they cover, so they cannot share one error term
//! (see `golden::units::four_triangle`). Each lane's other and third edge select the adjacent (T→M)
//! or third (M→B) parent triple (`lK_a_third`, `lK_t_adjacent`): the middle lane, turned by
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
//! | `w_f w_r w_d`                      | 12, 13, 13    | increments of the parent's working edge T→B (f two's complement) |
//! | `a_f a_r a_d`, `t_f t_r t_d`       | same          | adjacent edge T→M, third edge M→B          |
//! | `lK_w_b0 lK_w_e0`                  | 12, 13        | lane K's working edge: boundary, error term on its first row |
//! | `lK_a_b0 lK_a_e0`, `lK_a_third`    | 12, 13, 1     | its other edge on the first row; uses the third-edge triple |
//! | `lK_t_b0 lK_t_e0`, `lK_t_adjacent` | 12, 13, 1     | its third edge; uses the adjacent-edge triple |
//! | `lK_y_top lK_rows lK_y_switch`     | 12 each       | first line, number of lines, switch line  |
//! | `lK_dir_neg`                       | 1             | lane K's lines run towards −x             |
//! | `hold`                             | 1             | stall, to every lane (any clock; see below) |
//!
//! Outputs: `ready` (a load is accepted in this clock: all four lanes are ready), and per lane
//! K (= sub-triangle index K: 0 corner at T, 1 at m_tm, 2 at m_tb, 3 middle) the address
//! block's outputs `lK_valid lK_x lK_y` (1, 12, 12), `lK_step` (2), `lK_line_start`,
//! `lK_row_start`, `lK_carry`, `lK_done` (1 each; `done` is the lane's last event of the
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

use crate::units::address_block::AddressBlock;
use rust_hdl::prelude::*;

crate::hw_block! {
    /// The four-triangle address block (see the module header).
    pub struct FourTriangle(clock) as "four-triangle" {
        summary: "one triangle's set-up in, the addresses of its four midpoint sub-triangles out, up to four per clock (SPEC §7)",
        latency: AddressBlock::LATENCY => "load to the first events, up to four addresses per clock",
        multipliers: 0,
        in {
            load: Bit,
            w_f: Bits<12>, w_r: Bits<13>, w_d: Bits<13>,
            a_f: Bits<12>, a_r: Bits<13>, a_d: Bits<13>,
            t_f: Bits<12>, t_r: Bits<13>, t_d: Bits<13>,
            w_b0_l0: Bits<12>, w_e0_l0: Bits<13>, a_b0_l0: Bits<12>, a_e0_l0: Bits<13>, a_third_l0: Bit,
            t_b0_l0: Bits<12>, t_e0_l0: Bits<13>, t_adjacent_l0: Bit,
            y_top_l0: Bits<12>, rows_l0: Bits<12>, y_switch_l0: Bits<12>, dir_neg_l0: Bit,
            w_b0_l1: Bits<12>, w_e0_l1: Bits<13>, a_b0_l1: Bits<12>, a_e0_l1: Bits<13>, a_third_l1: Bit,
            t_b0_l1: Bits<12>, t_e0_l1: Bits<13>, t_adjacent_l1: Bit,
            y_top_l1: Bits<12>, rows_l1: Bits<12>, y_switch_l1: Bits<12>, dir_neg_l1: Bit,
            w_b0_l2: Bits<12>, w_e0_l2: Bits<13>, a_b0_l2: Bits<12>, a_e0_l2: Bits<13>, a_third_l2: Bit,
            t_b0_l2: Bits<12>, t_e0_l2: Bits<13>, t_adjacent_l2: Bit,
            y_top_l2: Bits<12>, rows_l2: Bits<12>, y_switch_l2: Bits<12>, dir_neg_l2: Bit,
            w_b0_l3: Bits<12>, w_e0_l3: Bits<13>, a_b0_l3: Bits<12>, a_e0_l3: Bits<13>, a_third_l3: Bit,
            t_b0_l3: Bits<12>, t_e0_l3: Bits<13>, t_adjacent_l3: Bit,
            y_top_l3: Bits<12>, rows_l3: Bits<12>, y_switch_l3: Bits<12>, dir_neg_l3: Bit,
            hold: Bit,
        }
        out {
            ready: Bit,
            valid_l0: Bit, x_l0: Bits<12>, y_l0: Bits<12>, step_l0: Bits<2>,
            line_start_l0: Bit, row_start_l0: Bit, carry_l0: Bit, done_l0: Bit,
            valid_l1: Bit, x_l1: Bits<12>, y_l1: Bits<12>, step_l1: Bits<2>,
            line_start_l1: Bit, row_start_l1: Bit, carry_l1: Bit, done_l1: Bit,
            valid_l2: Bit, x_l2: Bits<12>, y_l2: Bits<12>, step_l2: Bits<2>,
            line_start_l2: Bit, row_start_l2: Bit, carry_l2: Bit, done_l2: Bit,
            valid_l3: Bit, x_l3: Bits<12>, y_l3: Bits<12>, step_l3: Bits<2>,
            line_start_l3: Bit, row_start_l3: Bit, carry_l3: Bit, done_l3: Bit,
        }
        /// Lane 0: sub-triangle 0.
        pub lane0: AddressBlock,
        /// Lane 1: sub-triangle 1.
        pub lane1: AddressBlock,
        /// Lane 2: sub-triangle 2.
        pub lane2: AddressBlock,
        /// Lane 3: sub-triangle 3.
        pub lane3: AddressBlock,
        /// All four lanes are ready: the load is taken.
        all_ready: Signal<Local, Bit>,
    }
}

impl Logic for FourTriangle {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, lane0, lane1, lane2, lane3);
        self.all_ready.next = self.lane0.ready.val()
            & self.lane1.ready.val()
            & self.lane2.ready.val()
            & self.lane3.ready.val();
        self.ready.next = self.all_ready.val();

        // Lane 0.
        self.lane0.load.next = self.load.val() & self.all_ready.val();
        self.lane0.hold.next = self.hold.val();
        self.lane0.w_b0.next = self.w_b0_l0.val();
        self.lane0.w_e0.next = self.w_e0_l0.val();
        self.lane0.w_f.next = self.w_f.val();
        self.lane0.w_r.next = self.w_r.val();
        self.lane0.w_d.next = self.w_d.val();
        self.lane0.a_b0.next = self.a_b0_l0.val();
        self.lane0.a_e0.next = self.a_e0_l0.val();
        if self.a_third_l0.val() {
            self.lane0.a_f.next = self.t_f.val();
            self.lane0.a_r.next = self.t_r.val();
            self.lane0.a_d.next = self.t_d.val();
        } else {
            self.lane0.a_f.next = self.a_f.val();
            self.lane0.a_r.next = self.a_r.val();
            self.lane0.a_d.next = self.a_d.val();
        }
        self.lane0.t_b0.next = self.t_b0_l0.val();
        self.lane0.t_e0.next = self.t_e0_l0.val();
        if self.t_adjacent_l0.val() {
            self.lane0.t_f.next = self.a_f.val();
            self.lane0.t_r.next = self.a_r.val();
            self.lane0.t_d.next = self.a_d.val();
        } else {
            self.lane0.t_f.next = self.t_f.val();
            self.lane0.t_r.next = self.t_r.val();
            self.lane0.t_d.next = self.t_d.val();
        }
        self.lane0.y_top.next = self.y_top_l0.val();
        self.lane0.rows.next = self.rows_l0.val();
        self.lane0.y_switch.next = self.y_switch_l0.val();
        self.lane0.dir_neg.next = self.dir_neg_l0.val();
        self.valid_l0.next = self.lane0.valid.val();
        self.x_l0.next = self.lane0.x.val();
        self.y_l0.next = self.lane0.y.val();
        self.step_l0.next = self.lane0.step.val();
        self.line_start_l0.next = self.lane0.line_start.val();
        self.row_start_l0.next = self.lane0.row_start.val();
        self.carry_l0.next = self.lane0.carry.val();
        self.done_l0.next = self.lane0.done.val();

        // Lane 1.
        self.lane1.load.next = self.load.val() & self.all_ready.val();
        self.lane1.hold.next = self.hold.val();
        self.lane1.w_b0.next = self.w_b0_l1.val();
        self.lane1.w_e0.next = self.w_e0_l1.val();
        self.lane1.w_f.next = self.w_f.val();
        self.lane1.w_r.next = self.w_r.val();
        self.lane1.w_d.next = self.w_d.val();
        self.lane1.a_b0.next = self.a_b0_l1.val();
        self.lane1.a_e0.next = self.a_e0_l1.val();
        if self.a_third_l1.val() {
            self.lane1.a_f.next = self.t_f.val();
            self.lane1.a_r.next = self.t_r.val();
            self.lane1.a_d.next = self.t_d.val();
        } else {
            self.lane1.a_f.next = self.a_f.val();
            self.lane1.a_r.next = self.a_r.val();
            self.lane1.a_d.next = self.a_d.val();
        }
        self.lane1.t_b0.next = self.t_b0_l1.val();
        self.lane1.t_e0.next = self.t_e0_l1.val();
        if self.t_adjacent_l1.val() {
            self.lane1.t_f.next = self.a_f.val();
            self.lane1.t_r.next = self.a_r.val();
            self.lane1.t_d.next = self.a_d.val();
        } else {
            self.lane1.t_f.next = self.t_f.val();
            self.lane1.t_r.next = self.t_r.val();
            self.lane1.t_d.next = self.t_d.val();
        }
        self.lane1.y_top.next = self.y_top_l1.val();
        self.lane1.rows.next = self.rows_l1.val();
        self.lane1.y_switch.next = self.y_switch_l1.val();
        self.lane1.dir_neg.next = self.dir_neg_l1.val();
        self.valid_l1.next = self.lane1.valid.val();
        self.x_l1.next = self.lane1.x.val();
        self.y_l1.next = self.lane1.y.val();
        self.step_l1.next = self.lane1.step.val();
        self.line_start_l1.next = self.lane1.line_start.val();
        self.row_start_l1.next = self.lane1.row_start.val();
        self.carry_l1.next = self.lane1.carry.val();
        self.done_l1.next = self.lane1.done.val();

        // Lane 2.
        self.lane2.load.next = self.load.val() & self.all_ready.val();
        self.lane2.hold.next = self.hold.val();
        self.lane2.w_b0.next = self.w_b0_l2.val();
        self.lane2.w_e0.next = self.w_e0_l2.val();
        self.lane2.w_f.next = self.w_f.val();
        self.lane2.w_r.next = self.w_r.val();
        self.lane2.w_d.next = self.w_d.val();
        self.lane2.a_b0.next = self.a_b0_l2.val();
        self.lane2.a_e0.next = self.a_e0_l2.val();
        if self.a_third_l2.val() {
            self.lane2.a_f.next = self.t_f.val();
            self.lane2.a_r.next = self.t_r.val();
            self.lane2.a_d.next = self.t_d.val();
        } else {
            self.lane2.a_f.next = self.a_f.val();
            self.lane2.a_r.next = self.a_r.val();
            self.lane2.a_d.next = self.a_d.val();
        }
        self.lane2.t_b0.next = self.t_b0_l2.val();
        self.lane2.t_e0.next = self.t_e0_l2.val();
        if self.t_adjacent_l2.val() {
            self.lane2.t_f.next = self.a_f.val();
            self.lane2.t_r.next = self.a_r.val();
            self.lane2.t_d.next = self.a_d.val();
        } else {
            self.lane2.t_f.next = self.t_f.val();
            self.lane2.t_r.next = self.t_r.val();
            self.lane2.t_d.next = self.t_d.val();
        }
        self.lane2.y_top.next = self.y_top_l2.val();
        self.lane2.rows.next = self.rows_l2.val();
        self.lane2.y_switch.next = self.y_switch_l2.val();
        self.lane2.dir_neg.next = self.dir_neg_l2.val();
        self.valid_l2.next = self.lane2.valid.val();
        self.x_l2.next = self.lane2.x.val();
        self.y_l2.next = self.lane2.y.val();
        self.step_l2.next = self.lane2.step.val();
        self.line_start_l2.next = self.lane2.line_start.val();
        self.row_start_l2.next = self.lane2.row_start.val();
        self.carry_l2.next = self.lane2.carry.val();
        self.done_l2.next = self.lane2.done.val();

        // Lane 3.
        self.lane3.load.next = self.load.val() & self.all_ready.val();
        self.lane3.hold.next = self.hold.val();
        self.lane3.w_b0.next = self.w_b0_l3.val();
        self.lane3.w_e0.next = self.w_e0_l3.val();
        self.lane3.w_f.next = self.w_f.val();
        self.lane3.w_r.next = self.w_r.val();
        self.lane3.w_d.next = self.w_d.val();
        self.lane3.a_b0.next = self.a_b0_l3.val();
        self.lane3.a_e0.next = self.a_e0_l3.val();
        if self.a_third_l3.val() {
            self.lane3.a_f.next = self.t_f.val();
            self.lane3.a_r.next = self.t_r.val();
            self.lane3.a_d.next = self.t_d.val();
        } else {
            self.lane3.a_f.next = self.a_f.val();
            self.lane3.a_r.next = self.a_r.val();
            self.lane3.a_d.next = self.a_d.val();
        }
        self.lane3.t_b0.next = self.t_b0_l3.val();
        self.lane3.t_e0.next = self.t_e0_l3.val();
        if self.t_adjacent_l3.val() {
            self.lane3.t_f.next = self.a_f.val();
            self.lane3.t_r.next = self.a_r.val();
            self.lane3.t_d.next = self.a_d.val();
        } else {
            self.lane3.t_f.next = self.t_f.val();
            self.lane3.t_r.next = self.t_r.val();
            self.lane3.t_d.next = self.t_d.val();
        }
        self.lane3.y_top.next = self.y_top_l3.val();
        self.lane3.rows.next = self.rows_l3.val();
        self.lane3.y_switch.next = self.y_switch_l3.val();
        self.lane3.dir_neg.next = self.dir_neg_l3.val();
        self.valid_l3.next = self.lane3.valid.val();
        self.x_l3.next = self.lane3.x.val();
        self.y_l3.next = self.lane3.y.val();
        self.step_l3.next = self.lane3.step.val();
        self.line_start_l3.next = self.lane3.line_start.val();
        self.row_start_l3.next = self.lane3.row_start.val();
        self.carry_l3.next = self.lane3.carry.val();
        self.done_l3.next = self.lane3.done.val();
    }
}
