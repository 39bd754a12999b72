//! Line interpolator: a Bresenham-style DDA tracking one triangle edge, one raster line per
//! clock (SPEC §5, fig. 3.7; golden: `golden::units::address_block`, `golden::raster::EdgeDda`).
//!
//! # Formula
//!
//! The edge's boundary on raster line y — the smallest x whose pixel centre is on or right of
//! the edge — is `B = ⌈N/D⌉`, `D = 2Δy`, and N grows by `2Δx = f·D + r` per line. With the
//! error term `e = B·D − N ∈ [0, D)` one line down is
//!
//! ```text
//!   carry = e < r
//!   B    ← B + f + carry                    (the move: f or f + 1 pixels)
//!   e    ← e − r + (carry ? D : 0)
//!   step ← V if f + carry = 0, else D       (StepType code 2 / 3)
//! ```
//!
//! A classic Bresenham interpolator would spend one clock per horizontal step; here the run of
//! |move| − 1 horizontal steps and the closing diagonal step are one clock, because the set-up
//! software did the division (`f`, `r`). So the address block never waits for an edge, whatever
//! its slope, and the step information the interpolators need is (step, carry): the move into
//! the line is `f` pixels when carry = 0 and `f + 1` when carry = 1.
//!
//! # Ports and formats (all unsigned integers unless noted)
//!
//! | port        | bits | meaning                                                        |
//! |-------------|------|----------------------------------------------------------------|
//! | `load`      | 1    | load the set-up below (has priority over `advance`)             |
//! | `load_b`    | 12   | B on the first line, 0..=4095                                   |
//! | `load_e`    | E    | e on the first line, 0..D (E = 13; 20 in [`SubpixelLineInterpolator`]) |
//! | `load_f`    | 12   | f = ⌊Δx/Δy⌋ as 12-bit two's complement (used modulo 4096)       |
//! | `load_r`    | E    | r = 2Δx − f·D, 0..D                                             |
//! | `load_d`    | E    | D = 2Δy, 0..=8190 (0: unused edge, never advanced); sub-pixel: D = 2^4·Δy with Δy in 2^−4 pixel, < 2^20 |
//! | `advance`   | 1    | move to the next raster line                                     |
//! | `bound`     | 12   | current B                                                        |
//! | `last_step` | 2    | StepType code of the last move: 0 Start (after load), 2 V, 3 D  |
//! | `last_carry`| 1    | the last move was the long one (f + 1)                           |
//!
//! Intermediates: `e − r` is E bits modulo 2^E (it is in (−D, D); adding D when it is
//! negative brings it back to [0, D), so the modulo arithmetic is exact); `f + carry` and
//! `B + move` are 12 bits modulo 2^12 (exact, since every boundary used is in 0..=4095).
//!
//! For ECP5 timing the recurrence has one carry chain per clock, not three: f + 1, D − r and
//! the flags f = 0, f + 1 = 0 are registered at the load, so the next B is B + f or B + (f + 1)
//! and the next e is e − r or e + (D − r), both formed beside the comparison e < r and selected
//! by it (the same words modulo 2^12 and 2^E as the formula; chained, the compare, the move
//! and the boundary add ran at 94.6 MHz in the four-triangle block).
//!
//! Latency: outputs are registers; a load or advance in clock t shows in clock t + 1.
//! Throughput: one line per clock. Overflow: none for in-range set-up (argued above).
//! Error budget: exact (integer).

use rust_hdl::prelude::*;

/// One line interpolator per error-word width `$e` (the header's 13 for integer vertices;
/// [`SubpixelLineInterpolator`] is the sub-pixel address block's): the same text, so the two
/// builds cannot drift.
macro_rules! line_interpolator {
    ($(#[$m:meta])* $name:ident, $e:tt) => {
        crate::hw_block! {
            $(#[$m])*
            pub struct $name(clock) {
                in {
                    load: Bit,
                    load_b: Bits<12>, load_e: Bits<$e>, load_f: Bits<12>, load_r: Bits<$e>, load_d: Bits<$e>,
                    advance: Bit,
                }
                out { bound: Bits<12>, last_step: Bits<2>, last_carry: Bit }
                /// B, the boundary.
                bound_q: DFF<Bits<12>>,
                /// e, the error term.
                err_q: DFF<Bits<$e>>,
                /// f, the whole move per line (two's complement).
                quot_q: DFF<Bits<12>>,
                /// r, the remainder added to the error per line.
                rem_q: DFF<Bits<$e>>,
                /// f + 1 (12 bits), D − r (E bits), and whether f or f + 1 is 0 (a vertical move).
                quot1_q: DFF<Bits<12>>,
                den_rem_q: DFF<Bits<$e>>,
                f_zero_q: DFF<Bit>,
                f1_zero_q: DFF<Bit>,
                step_q: DFF<Bits<2>>, carry_q: DFF<Bit>,
                /// carry of the next move: e < r.
                carry_next: Signal<Local, Bit>,
                /// f + 1 and D − r of the words being loaded.
                load_f1: Signal<Local, Bits<12>>,
                load_dr: Signal<Local, Bits<$e>>,
                /// B + f and B + f + 1, 12 bits modulo 2^12.
                bound_f: Signal<Local, Bits<12>>,
                bound_f1: Signal<Local, Bits<12>>,
                /// e − r and e + (D − r), E bits modulo 2^E.
                err_diff: Signal<Local, Bits<$e>>,
                err_wrap: Signal<Local, Bits<$e>>,
            }
        }

        impl Logic for $name {
            #[hdl_gen]
            fn update(&mut self) {
                dff_setup!(
                    self, clock, bound_q, err_q, quot_q, rem_q, quot1_q, den_rem_q, f_zero_q, f1_zero_q,
                    step_q, carry_q
                );
                self.carry_next.next = self.err_q.q.val() < self.rem_q.q.val();
                self.bound_f.next = self.bound_q.q.val() + self.quot_q.q.val();
                self.bound_f1.next = self.bound_q.q.val() + self.quot1_q.q.val();
                self.err_diff.next = self.err_q.q.val() - self.rem_q.q.val();
                self.err_wrap.next = self.err_q.q.val() + self.den_rem_q.q.val();
                self.load_f1.next = self.load_f.val() + 1;
                self.load_dr.next = self.load_d.val() - self.load_r.val();
                if self.load.val() {
                    self.bound_q.d.next = self.load_b.val();
                    self.err_q.d.next = self.load_e.val();
                    self.quot_q.d.next = self.load_f.val();
                    self.rem_q.d.next = self.load_r.val();
                    self.quot1_q.d.next = self.load_f1.val();
                    self.den_rem_q.d.next = self.load_dr.val();
                    self.f_zero_q.d.next = self.load_f.val() == 0;
                    self.f1_zero_q.d.next = self.load_f1.val() == 0;
                    self.step_q.d.next = 0.into();
                    self.carry_q.d.next = false;
                } else if self.advance.val() {
                    // carry: B + f + 1, e − r + D; else B + f, e − r; a vertical move is step V (2).
                    self.step_q.d.next = 3.into();
                    if self.carry_next.val() {
                        self.bound_q.d.next = self.bound_f1.val();
                        self.err_q.d.next = self.err_wrap.val();
                        if self.f1_zero_q.q.val() {
                            self.step_q.d.next = 2.into();
                        }
                    } else {
                        self.bound_q.d.next = self.bound_f.val();
                        self.err_q.d.next = self.err_diff.val();
                        if self.f_zero_q.q.val() {
                            self.step_q.d.next = 2.into();
                        }
                    }
                    self.carry_q.d.next = self.carry_next.val();
                }
                self.bound.next = self.bound_q.q.val();
                self.last_step.next = self.step_q.q.val();
                self.last_carry.next = self.carry_q.q.val();
            }
        }
    };
}

line_interpolator!(
    /// One edge's DDA (the header's formula) with 13-bit error words; not exported alone.
    LineInterpolator,
    13
);
line_interpolator!(
    /// One edge's DDA with 20-bit error words, for vertices with `SUBPIXEL_BITS` = 4
    /// fractional bits (D = 2^4·Δy, Δy ≤ 4095·2^4 in 2^−4 pixel; see
    /// `crate::units::address_block`); not exported alone.
    SubpixelLineInterpolator,
    20
);
line_interpolator!(
    /// One edge's DDA with 21-bit error words, for the lanes of `four-triangle-subpixel`
    /// (sub-triangles of parents with `SUBPIXEL_BITS` = 4 fractional bits have 5: D =
    /// 2^5·Δy < 2^21; see `crate::units::four_triangle`); not exported alone.
    LaneLineInterpolator,
    21
);
