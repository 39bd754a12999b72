//! Address block (SPEC §5, fig. 3.7): walks one triangle and emits its pixel addresses, one per
//! clock, with the step type of the working edge (golden: `golden::units::address_block`, whose
//! `AddressBlockModel` this block matches bit for bit every clock, and `golden::raster::walk`,
//! whose pixels and step types it reproduces).
//!
//! # Structure
//!
//! ```text
//!  load ─► E: two line interpolators  ──row record──►  RGr + start regs ──► P: CTx CTy CTr ──► out
//!          (working, other; third edge  x_start, y, len,  (one-row buffer)     one event/clock
//!           loaded at y_switch)         step, carry
//! ```
//!
//! - **E (edge stage)**: the working-edge and other-edge [`LineInterpolator`]s, the row
//!   register `e_y`, the remaining-row count, and the *step-increment* logic that forms the row
//!   length from the two boundaries: `len = B_o − B_w` (dir +1) or `B_w − B_o` (dir −1), 12 bits
//!   modulo 2^12 (exact: 0 ≤ len ≤ 4095 on every row). Forming the length from the boundaries
//!   rather than accumulating ±1/±2 increments into it costs the same one 12-bit adder and
//!   needs no correction when the third edge takes over. E fires — produces the record of row
//!   `e_y` and advances both interpolators — whenever the buffer is empty or being emptied.
//!   On the row before `y_switch` the other interpolator is loaded with the third edge instead
//!   of advancing (the switch costs no clock).
//! - **Buffer**: the row register RGr (`nb_len`) and start registers (`nb_x`, `nb_y`, step type,
//!   carry) of the next line, filled while the current line is being emitted.
//! - **P (row counter stage)**: CTx, CTy and CTr (`p_ctr`, pixels left after the current one).
//!   While CTr ≠ 0 it steps CTx by ±1; in the clock after a line's last pixel it takes the next
//!   record, so a line start costs no clock. A row with no pixel costs one clock with
//!   `valid = 0, row_start = 1` (the intensity interpolators advance their line start there).
//!
//! # Ports
//!
//! Inputs (sampled on the rising edge of `clock` when `load & ready`; see
//! `golden::units::address_block::AddressSetup`, computed by software, integer only):
//!
//! | port                           | bits     | meaning                                         |
//! |--------------------------------|----------|-------------------------------------------------|
//! | `load`                         | 1        | load one triangle's set-up                      |
//! | `w_b0 w_e0 w_f w_r w_d`        | 12,E,12,E,E | working edge DDA (see [`LineInterpolator`]); E = 13, or 20 in `address-block-subpixel` |
//! | `a_b0 a_e0 a_f a_r a_d`        | same     | other edge on the first row                     |
//! | `t_b0 t_e0 t_f t_r t_d`        | same     | third edge, from row `y_switch`                 |
//! | `y_top`, `rows`, `y_switch`    | 12 each  | first line, number of lines, switch line        |
//! | `dir_neg`                      | 1        | lines run towards −x (working edge on the right)|
//! | `hold`                         | 1        | stall: no event this clock, P keeps it for the next (any clock) |
//!
//! Outputs (functions of flip-flops only, except that `hold` gates the event ports):
//!
//! | port         | bits | meaning                                                            |
//! |--------------|------|--------------------------------------------------------------------|
//! | `ready`      | 1    | a load is accepted in this clock                                    |
//! | `valid`      | 1    | `x`, `y` is a pixel of the triangle                                 |
//! | `x`, `y`     | 12   | pixel address (0 when no event)                                     |
//! | `step`       | 2    | StepType code: 0 Start, 1 H, 2 V, 3 D (working edge's move at a row start) |
//! | `line_start` | 1    | first pixel of a line                                               |
//! | `row_start`  | 1    | first event of a line, also for a line without pixels               |
//! | `carry`      | 1    | with `row_start`: the working edge moved f + 1 (not f) pixels       |
//! | `done`       | 1    | last event of the triangle (a zero-row triangle has one such event) |
//!
//! # Timing
//!
//! ```text
//!  clock        t      t+1        t+2          t+3        t+4 ...
//!  load/ready   1/1    0/0
//!  E            load   row y_top  row y_top+1  ...
//!  P                              takes row 0  shows pixel 0 of row 0 (valid, line_start)
//! ```
//!
//! Latency load → first event: 3 clocks. Throughput: one event per clock; a triangle takes
//! Σ max(len, 1) clocks over its rows. `ready` rises once E has produced the last row and P has
//! taken the first record, so the next triangle's latency hides behind the current one's last
//! rows. **Stall:** while `hold` is high the block shows no event (`valid`, `row_start`,
//! `line_start`, `carry`, `done` low; `x`, `y`, `step` 0) and P keeps the event it would have
//! shown; E still fills the one-row buffer, and a load is still accepted on `load & ready`.
//! The event stream with stalls is the stream without them with empty clocks inserted
//! (the fragment stream's back-pressure in `pixel-stream` uses this). `hold` reaches the
//! event ports through one AND gate (no register): drive it from a register.
//! Whether E's next row is the switch to the third edge comes from a register (`e_at_switch`,
//! formed with each write of E's row counter `e_y`), not from an add and compare in front of the
//! other edge's load (the ECP5 path of the four-triangle lanes in `subdivision-stream`).
//! Overflow: none for set-up values in range (all counters are exact modulo their widths).
//! Error budget: exact (integer).
//!
//! # Two builds: integer and sub-pixel vertices
//!
//! `address-block` ([`AddressBlock`]) takes the set-up of a triangle with integer vertices:
//! E = 13-bit error words e, r, D (D = 2Δy ≤ 8190). `address-block-subpixel`
//! ([`SubpixelAddressBlock`]) is the same text with E = 20, for vertices with
//! `golden::SUBPIXEL_BITS` = 4 fractional bits (`golden::units::address_block::AddressSetup::subpixel`):
//! the rows are those whose centres y + ½ lie in [top.y, bottom.y) (a centre on a vertex's line
//! belongs to the edges below it, the top half of the top-left rule), and each edge's DDA
//! decides on the 2^−4 grid: with Δx, Δy in 2^−4 pixel, D = 2^4·Δy ≤ 2^4·4095·2^4 < 2^20,
//! 2^4·Δx = f·D + r, e the edge function at the boundary pixel's centre in the same units.
//! Boundaries, rows and the event stream are in whole pixels as above, so everything after
//! the block is unchanged; f, B and the 12-bit counters are as in the integer build, and any
//! integer set-up is also a sub-pixel one (the integer words, zero-extended).

use crate::units::line_interpolator::{
    LaneLineInterpolator, LineInterpolator, SubpixelLineInterpolator,
};
use rust_hdl::prelude::*;

/// The sub-pixel address block's set-up ports after `load` (the header's input table with
/// E = 20), one line per edge (`b0 e0 f r d`: see [`LineInterpolator`]), as a port bundle
/// (`crate::core::declare`) for the blocks that contain a [`SubpixelAddressBlock`] and pass its
/// set-up through (`gouraud-raster`, `pixel-pipeline`).
#[macro_export]
macro_rules! address_setup_ports {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [
                w_b0: Bits<12>, w_e0: Bits<20>, w_f: Bits<12>, w_r: Bits<20>, w_d: Bits<20>,
                a_b0: Bits<12>, a_e0: Bits<20>, a_f: Bits<12>, a_r: Bits<20>, a_d: Bits<20>,
                t_b0: Bits<12>, t_e0: Bits<20>, t_f: Bits<12>, t_r: Bits<20>, t_d: Bits<20>,
                y_top: Bits<12>, rows: Bits<12>, y_switch: Bits<12>, dir_neg: Bit,
            ]
            $($then)*
        }
    };
}

/// One address block per error-word width (`$e`, with its line interpolator `$line`): the
/// integer block and [`SubpixelAddressBlock`] are the same text.
macro_rules! address_block {
    (
        $(#[$m:meta])*
        pub struct $name:ident($line:ident, $e:tt) as $export:literal {
            summary: $summary:literal $(,)?
        }
    ) => {
        crate::hw_block! {
            $(#[$m])*
            pub struct $name(clock) as $export {
                summary: $summary,
                latency: 3 => "load to the first event, one address per clock",
                multipliers: 0,
                in {
                    load: Bit,
                    w_b0: Bits<12>, w_e0: Bits<$e>, w_f: Bits<12>, w_r: Bits<$e>, w_d: Bits<$e>,
                    a_b0: Bits<12>, a_e0: Bits<$e>, a_f: Bits<12>, a_r: Bits<$e>, a_d: Bits<$e>,
                    t_b0: Bits<12>, t_e0: Bits<$e>, t_f: Bits<12>, t_r: Bits<$e>, t_d: Bits<$e>,
                    y_top: Bits<12>, rows: Bits<12>, y_switch: Bits<12>, dir_neg: Bit,
                    hold: Bit,
                }
                out {
                    ready: Bit, valid: Bit, x: Bits<12>, y: Bits<12>, step: Bits<2>,
                    line_start: Bit, row_start: Bit, carry: Bit, done: Bit,
                }
                /// Working edge top→bottom.
                working: $line,
                /// Other side: adjacent edge, then the third edge.
                other: $line,

                // E: edge stage, and the third edge's set-up kept for the switch.
                e_busy: DFF<Bit>, e_rows_left: DFF<Bits<12>>, e_y: DFF<Bits<12>>, e_first: DFF<Bit>,
                e_dir_neg: DFF<Bit>, e_y_switch: DFF<Bits<12>>, wait_first: DFF<Bit>,
                /// e_y + 1 = e_y_switch, kept as a register (formed when e_y is written).
                e_at_switch: DFF<Bit>,
                t_b0_q: DFF<Bits<12>>, t_e0_q: DFF<Bits<$e>>, t_f_q: DFF<Bits<12>>,
                t_r_q: DFF<Bits<$e>>, t_d_q: DFF<Bits<$e>>,

                // Buffer: RGr and the start registers of the next line.
                nb_valid: DFF<Bit>, nb_is_row: DFF<Bit>,
                nb_x: DFF<Bits<12>>, nb_y: DFF<Bits<12>>, nb_len: DFF<Bits<12>>, nb_step: DFF<Bits<2>>,
                nb_carry: DFF<Bit>, nb_dir_neg: DFF<Bit>, nb_first: DFF<Bit>, nb_last: DFF<Bit>,

                // P: row counter stage (CTx, CTy, CTr).
                p_busy: DFF<Bit>, p_pix: DFF<Bit>,
                p_x: DFF<Bits<12>>, p_y: DFF<Bits<12>>, p_ctr: DFF<Bits<12>>, p_step: DFF<Bits<2>>,
                p_line_start: DFF<Bit>, p_row_start: DFF<Bit>, p_carry: DFF<Bit>, p_last: DFF<Bit>,
                p_dir_neg: DFF<Bit>,

                /// CTr ≠ 0 on a pixel: the line continues next clock.
                p_more: Signal<Local, Bit>,
                /// P takes the buffered record this clock.
                nb_take: Signal<Local, Bit>,
                /// E produces a record this clock.
                e_fire: Signal<Local, Bit>,
                /// E's record is a row (the triangle has rows left).
                e_has_row: Signal<Local, Bit>,
                ready_now: Signal<Local, Bit>, do_load: Signal<Local, Bit>,
                /// The next line is y_switch: load the third edge into `other`.
                switch_now: Signal<Local, Bit>,
                e_y_next: Signal<Local, Bits<12>>,
                /// e_y + 2 (the next row's e_y + 1) and y_top + 1, for `e_at_switch`.
                e_y_next2: Signal<Local, Bits<12>>, y_top_next: Signal<Local, Bits<12>>,
                /// Row record: x_start (B_w or B_w − 1) and length.
                rec_x: Signal<Local, Bits<12>>, rec_len: Signal<Local, Bits<12>>,
                /// nb_len ≠ 0.
                nb_nonempty: Signal<Local, Bit>,
                /// P shows its event this clock (busy and not held).
                p_show: Signal<Local, Bit>,
            }
        }

        impl Logic for $name {
            #[hdl_gen]
            fn update(&mut self) {
                // E, the third edge, the buffer, P (position, then flags): one call per group keeps
                // each list short enough for rustfmt to leave on one line.
                dff_setup!(
                    self,
                    clock,
                    e_busy,
                    e_rows_left,
                    e_y,
                    e_first,
                    e_dir_neg,
                    e_at_switch
                );
                dff_setup!(self, clock, e_y_switch, wait_first, t_b0_q, t_e0_q, t_f_q, t_r_q, t_d_q);
                dff_setup!(self, clock, nb_valid, nb_is_row, nb_x, nb_y, nb_len, nb_step);
                dff_setup!(self, clock, nb_carry, nb_dir_neg, nb_first, nb_last);
                dff_setup!(self, clock, p_busy, p_pix, p_x, p_y, p_ctr, p_step, p_carry);
                dff_setup!(self, clock, p_line_start, p_row_start, p_last, p_dir_neg);
                clock!(self, clock, working, other);

                // Handshake between the stages.
                self.p_more.next = self.p_busy.q.val() & self.p_pix.q.val() & (self.p_ctr.q.val() != 0);
                // `hold`: P keeps its event (shown as no event) and takes nothing; E may still fill the
                // one-row buffer.
                self.nb_take.next = self.nb_valid.q.val() & !self.p_more.val() & !self.hold.val();
                self.e_fire.next = self.e_busy.q.val() & (!self.nb_valid.q.val() | self.nb_take.val());
                self.e_has_row.next = self.e_rows_left.q.val() != 0;
                self.ready_now.next = !self.e_busy.q.val() & !self.wait_first.q.val();
                self.do_load.next = self.load.val() & self.ready_now.val();
                self.e_y_next.next = self.e_y.q.val() + 1;
                // Whether the next row is y_switch comes from a register, formed whenever e_y is
                // written (a load: y_top + 1 = y_switch; a row: e_y + 2 = e_y_switch), so no add and
                // compare precede the other edge's load multiplexer (ECP5: e_y → e_y_next →
                // other.load → other.err_q was the path of `subdivision-stream`, 11.47 ns).
                self.e_y_next2.next = self.e_y.q.val() + 2;
                self.y_top_next.next = self.y_top.val() + 1;
                self.switch_now.next = self.e_at_switch.q.val();

                // Step-increment: the row's start and length from the two boundaries.
                self.rec_x.next = self.working.bound.val();
                self.rec_len.next = self.other.bound.val() - self.working.bound.val();
                if self.e_dir_neg.q.val() {
                    self.rec_x.next = self.working.bound.val() - 1;
                    self.rec_len.next = self.working.bound.val() - self.other.bound.val();
                }

                // Line interpolators: loaded by `load` (working, other ← adjacent) or at the switch
                // (other ← third); advanced when E produces a row.
                self.working.load.next = self.do_load.val();
                self.working.load_b.next = self.w_b0.val();
                self.working.load_e.next = self.w_e0.val();
                self.working.load_f.next = self.w_f.val();
                self.working.load_r.next = self.w_r.val();
                self.working.load_d.next = self.w_d.val();
                self.working.advance.next = self.e_fire.val() & self.e_has_row.val();
                self.other.load.next =
                    self.do_load.val() | (self.e_fire.val() & self.e_has_row.val() & self.switch_now.val());
                self.other.load_b.next = self.t_b0_q.q.val();
                self.other.load_e.next = self.t_e0_q.q.val();
                self.other.load_f.next = self.t_f_q.q.val();
                self.other.load_r.next = self.t_r_q.q.val();
                self.other.load_d.next = self.t_d_q.q.val();
                if self.do_load.val() {
                    self.other.load_b.next = self.a_b0.val();
                    self.other.load_e.next = self.a_e0.val();
                    self.other.load_f.next = self.a_f.val();
                    self.other.load_r.next = self.a_r.val();
                    self.other.load_d.next = self.a_d.val();
                }
                self.other.advance.next = self.e_fire.val() & self.e_has_row.val();

                // P: row counter stage (frozen while `hold`).
                self.nb_nonempty.next = self.nb_len.q.val() != 0;
                if self.hold.val() {
                    self.p_busy.d.next = self.p_busy.q.val();
                } else if self.p_more.val() {
                    self.p_x.d.next = self.p_x.q.val() + 1;
                    if self.p_dir_neg.q.val() {
                        self.p_x.d.next = self.p_x.q.val() - 1;
                    }
                    self.p_ctr.d.next = self.p_ctr.q.val() - 1;
                    self.p_step.d.next = 1.into();
                    self.p_line_start.d.next = false;
                    self.p_row_start.d.next = false;
                } else if self.nb_take.val() {
                    self.p_busy.d.next = true;
                    self.p_pix.d.next = self.nb_is_row.q.val() & self.nb_nonempty.val();
                    self.p_x.d.next = self.nb_x.q.val();
                    self.p_y.d.next = self.nb_y.q.val();
                    self.p_ctr.d.next = 0.into();
                    if self.nb_nonempty.val() {
                        self.p_ctr.d.next = self.nb_len.q.val() - 1;
                    }
                    self.p_step.d.next = self.nb_step.q.val();
                    self.p_line_start.d.next = self.nb_is_row.q.val() & self.nb_nonempty.val();
                    self.p_row_start.d.next = self.nb_is_row.q.val();
                    self.p_carry.d.next = self.nb_carry.q.val();
                    self.p_last.d.next = self.nb_last.q.val();
                    self.p_dir_neg.d.next = self.nb_dir_neg.q.val();
                    if self.nb_first.q.val() {
                        self.wait_first.d.next = false;
                    }
                } else {
                    // Idle: the flags the event ports show are cleared too, so that each of `valid`,
                    // `row_start`, `carry`, `step` is one register gated by `hold` alone (no `p_busy`
                    // term): the BVI's first-step select, `row_start & step == 0`, is then one LUT4
                    // of `hold` and three registers (with `p_busy` in it, `hold` went through three
                    // LUT levels to the BVI's adders: 95.9 MHz in `subdivision-raster` on ECP5).
                    self.p_busy.d.next = false;
                    self.p_pix.d.next = false;
                    self.p_row_start.d.next = false;
                    self.p_carry.d.next = false;
                    self.p_step.d.next = 0.into();
                }

                // E: edge stage and the buffer.
                if self.e_fire.val() {
                    self.nb_valid.d.next = true;
                    self.nb_first.d.next = self.e_first.q.val();
                    self.nb_dir_neg.d.next = self.e_dir_neg.q.val();
                    if self.e_has_row.val() {
                        self.nb_is_row.d.next = true;
                        self.nb_x.d.next = self.rec_x.val();
                        self.nb_y.d.next = self.e_y.q.val();
                        self.nb_len.d.next = self.rec_len.val();
                        self.nb_step.d.next = self.working.last_step.val();
                        self.nb_carry.d.next = self.working.last_carry.val();
                        self.nb_last.d.next = self.e_rows_left.q.val() == 1;
                        self.e_y.d.next = self.e_y_next.val();
                        self.e_at_switch.d.next = self.e_y_next2.val() == self.e_y_switch.q.val();
                        self.e_rows_left.d.next = self.e_rows_left.q.val() - 1;
                        self.e_first.d.next = false;
                        if self.e_rows_left.q.val() == 1 {
                            self.e_busy.d.next = false;
                        }
                    } else {
                        // A triangle without rows: one record that only carries `done`.
                        self.nb_is_row.d.next = false;
                        self.nb_x.d.next = 0.into();
                        self.nb_y.d.next = 0.into();
                        self.nb_len.d.next = 0.into();
                        self.nb_step.d.next = 0.into();
                        self.nb_carry.d.next = false;
                        self.nb_last.d.next = true;
                        self.e_busy.d.next = false;
                    }
                } else if self.nb_take.val() {
                    self.nb_valid.d.next = false;
                }

                if self.do_load.val() {
                    self.e_busy.d.next = true;
                    self.e_rows_left.d.next = self.rows.val();
                    self.e_y.d.next = self.y_top.val();
                    self.e_at_switch.d.next = self.y_top_next.val() == self.y_switch.val();
                    self.e_first.d.next = true;
                    self.e_dir_neg.d.next = self.dir_neg.val();
                    self.e_y_switch.d.next = self.y_switch.val();
                    self.wait_first.d.next = true;
                    self.t_b0_q.d.next = self.t_b0.val();
                    self.t_e0_q.d.next = self.t_e0.val();
                    self.t_f_q.d.next = self.t_f.val();
                    self.t_r_q.d.next = self.t_r.val();
                    self.t_d_q.d.next = self.t_d.val();
                }

                // Outputs: registers, gated to zero when P shows no event (idle, or held). `p_pix`,
                // `p_row_start`, `p_carry` and `p_step` are 0 while P is idle, so `hold` alone gates
                // them.
                self.p_show.next = self.p_busy.q.val() & !self.hold.val();
                self.ready.next = self.ready_now.val();
                self.valid.next = !self.hold.val() & self.p_pix.q.val();
                self.x.next = 0.into();
                self.y.next = 0.into();
                self.step.next = 0.into();
                if self.p_show.val() {
                    self.x.next = self.p_x.q.val();
                    self.y.next = self.p_y.q.val();
                }
                if !self.hold.val() {
                    self.step.next = self.p_step.q.val();
                }
                self.line_start.next = self.p_show.val() & self.p_line_start.q.val();
                self.row_start.next = !self.hold.val() & self.p_row_start.q.val();
                self.carry.next = !self.hold.val() & self.p_carry.q.val();
                self.done.next = self.p_show.val() & self.p_last.q.val() & !self.p_more.val();
            }
        }
    };
}

address_block! {
    /// The address block: one triangle's set-up in, its events out (see the module header).
    pub struct AddressBlock(LineInterpolator, 13) as "address-block" {
        summary: "one triangle's set-up in, its pixel addresses and step types out (SPEC §5)",
    }
}

address_block! {
    /// The address block for vertices with `SUBPIXEL_BITS` = 4 fractional bits: 20-bit error
    /// words (see the module header).
    pub struct SubpixelAddressBlock(SubpixelLineInterpolator, 20) as "address-block-subpixel" {
        summary: "one triangle's sub-pixel set-up in (vertices with 4 fraction bits), its pixel addresses and step types out (SPEC §5)",
    }
}

address_block! {
    /// The address block with 21-bit error words: a lane of `four-triangle-subpixel`, walking
    /// the sub-triangles (5 fraction bits) of parents with `SUBPIXEL_BITS` = 4. Not in the
    /// block list: it is this text at E = 21, tested every clock as the four lanes of that
    /// block.
    pub struct LaneAddressBlock(LaneLineInterpolator, 21) as "address-block-lane" {
        summary: "one sub-triangle's set-up in (5 fraction bits), its pixel addresses and step types out (SPEC §5, §7)",
    }
}
