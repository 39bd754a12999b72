//! Texture-coordinate block (SPEC §14): the additive, division-free perspective-correct texel
//! (u, v) of every pixel of the address block's walk, with adders and comparators only
//! (golden: `golden::units::texture_coord::block`, whose `TexCoordModel` this block matches bit
//! for bit every clock; the reference is `golden::units::texture_coord::nearest_texel`).
//!
//! # Formula (SPEC §14, Δu = 1: integer texels)
//!
//! u = N/D, N = a·x + b·y + c, D = g·x + h·y + i > 0. With E = 2D and
//! W = u·E − x(2a − g) − y(2b − h) − (2c − i) = 2D·(u + ½ − N/D), u is the nearest texel
//! ⌊N/D + ½⌋ exactly when W > 0 and W − E ≤ 0 (Q = W − E is not kept). The walk makes three
//! moves m (along the line: dx = dir; a line start after a short or a long edge move: dx = f or
//! f + 1, dy = 1), each from the state before it (a line start from the saved state of the
//! previous line's start, as the BVI's RG5). Per move and per correction by j texels:
//!
//! ```text
//!   move m:       E += ΔE_m,  W += P_m                      ΔE_m = 2(g·dx + h·dy)
//!   correction j: u += j,  W += j·E,  P_m += j·ΔE_m (all m)  P_m = u·ΔE_m − dx(2a − g) − dy(2b − h)
//! ```
//!
//! P_m is SPEC §14's 2g·u register for each move: no multiplier. The set-up software
//! (`golden::units::texture_coord::block::TexCoordSetup`) gives E, W, P_m at the first line start
//! (one division there for u0, v0) and the ΔE_m; u and v share E, D and the moves.
//!
//! # The loop in one adder
//!
//! A pixel's correction decides the next pixel's words, so the pixel loop is the critical
//! path. Every word is formed from registers in one adder for every j side by side, and the
//! comparators' decision only selects:
//!
//! - the block keeps W − 1, so "W + j·E > 0" is the sign bit of (W − 1) + j·E;
//! - X = (W − 1) + P_line, the next pixel's W − 1 before its corrections, is a register:
//!   the next pixel's W − 1 is X + j·Z and its X is X + P_line + j·K (one carry-save stage
//!   and an adder, [`Add3`]), with Z = E + ΔE_line and K = E + 2ΔE_line registers beside E;
//! - P_m + j·ΔE_m, u + j, and E's next values (3E, Z, K and the saved line start's Z_short,
//!   Z_long after each kind of move) likewise;
//! - a line start moves from the saved line-start registers only. When it arrives in the
//!   clock its previous line's only pixel settles (the saved state is being written), the
//!   block takes it, keeps `ready` low for one clock and moves in the next (`defer`).
//!
//! # Steps per clock: the build parameter k
//!
//! `tex-k=1` (the seed's one step per clock), `tex-k=2` (the default; `--tex-k` on the
//! command line) or `tex-k=4`. Each clock the comparators look at W + j·E for
//! j ∈ {−(k+1) … k} side by side (2E and 4E shifts, 3E the register E3, 5E = 4E + E) and pick
//! the first j that settles the texel; a pixel needing q steps on an axis stays
//! max(1, ⌈q/k⌉) clocks, both axes in parallel. A pixel that settles with at most k steps per
//! axis costs one clock. For k = 4 the candidates of j = ±3, ±4 (X + j·Z, X + P0 + j·K,
//! P_m + j·ΔE_m) are two adders deep, not formed through one carry-save stage as ±1, ±2 are.
//!
//! # Ports
//!
//! | port | bits | format |
//! |---|---|---|
//! | `load` | 1 | write the shadow set-up (the next triangle's), any clock |
//! | `e0`, `de_line`, `de_short`, `de_long` | 48 each | E at the first line start; ΔE of the three moves |
//! | `u_u0`, `v_u0` | 16 each | start texels (two's complement) |
//! | `u_w0` … `u_p_long`, `v_w0` … `v_p_long` | 48 each | W − 1 and P_line, P_short, P_long at the start |
//! | `valid_in`, `row_start_in`, `step_in` (2), `carry_in`, `x_in` (12), `y_in` (12), `done_in` | | the address block's event (its ports `valid`, `row_start`, `step`, `carry`, `x`, `y`, `done`) |
//! | `hold` | 1 | stall (the consumer's back-pressure): nothing taken or shown this clock; the pending pixel's corrections go on |
//! | `ready` | 1 | the event shown this clock is taken |
//! | `valid_out` | 1 | `u`, `v`, `x`, `y` is a pixel |
//! | `u`, `v` | 16 each | the nearest texel (two's complement; not wrapped) |
//! | `x`, `y` | 12 each | the pixel's address |
//! | `done_out` | 1 | the triangle's last event has passed (with its last pixel, or alone) |
//!
//! Words E, W, P, ΔE: 48-bit two's complement, every addition modulo 2^48 (exact modulo 2^48,
//! so only compared words must be in range). The first event of a triangle (`row_start_in`
//! with `step_in` = 0) copies the shadow set-up in; assert `load` with the address block's
//! accepted load, once the previous triangle's first event has been taken.
//!
//! # Latency, throughput, handshake
//!
//! Handshake: an event (`valid_in`, `row_start_in` or `done_in` high) is taken in a clock with
//! `ready` high; otherwise it must be shown again (the address block's `hold` = !`ready` does
//! that). `ready` is a function of the block's registers (through the comparators) and of
//! `hold` (one AND gate), never of the event: high when `hold` is low, no line start is
//! deferred, and no pixel is pending or the pending one settles this clock. A pixel taken in
//! clock t settles in clock t + c (c = max(1, ⌈q/k⌉) for q steps on its worse axis)
//! and shows in clock t + c + 1 with `valid_out`: one pixel per clock while every pixel needs at
//! most k steps per axis, and the pipe holds only beyond that. A line start moves f or f + 1
//! pixels along the edge at once, so its texel can move by several texels: on shallow edges
//! line starts cost more clocks than pixels along a line; a line of one pixel costs a clock
//! more (the deferred line start after it).
//!
//! Latency (the block's `LATENCY`): 2 clocks, valid_in to valid_out for a pixel that settles in its first clock.
//!
//! # Overflow and error budget
//!
//! Accepted set-ups (`TexCoordSetup::check`): D ∈ [1, 2^30) at every pixel walked, and every
//! texel and |u − N/D| within 2^15 − 4. Then E < 2^31 and |W + j·E| < 2^47 for |j| ≤ 5: every
//! comparison sees the true sign. That covers a 4096-pixel screen with D scaled to 2^29 at the
//! nearest vertex and textures up to 1024 texels repeated 31 times across one triangle.
//! Error budget: exact — the texel is the nearest one of the quotient of the integer
//! coefficients (a tie goes up); against unrounded coefficients it can differ only where N/D
//! lies within their rounding of a texel boundary.

use rust_hdl::prelude::*;

use crate::core::primitives::Add3;
use crate::core::registry::{BlockParams, Options};

/// The build parameter k: correction steps resolved per clock.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexCoordParams {
    pub k: u32,
}

impl Default for TexCoordParams {
    fn default() -> Self {
        TexCoordParams { k: 2 }
    }
}

impl BlockParams for TexCoordParams {
    const KEYS: &'static [&'static str] = &["tex-k"];
    /// `tex-k=1`, `tex-k=2` (default) or `tex-k=4`: k, the correction steps per clock.
    fn from_options(o: &Options) -> Result<Self, String> {
        match o.get("tex-k") {
            None | Some("2") => Ok(TexCoordParams { k: 2 }),
            Some("1") => Ok(TexCoordParams { k: 1 }),
            Some("4") => Ok(TexCoordParams { k: 4 }),
            Some(other) => Err(format!(
                "unknown k {other:?} (expected 1, 2 or 4 correction steps per clock)"
            )),
        }
    }
    fn describe(&self) -> Option<String> {
        Some(format!("k = {} correction steps per clock", self.k))
    }
    fn test_sets() -> Vec<Options> {
        vec![
            Options::new(),
            Options::new().with("tex-k", "1"),
            Options::new().with("tex-k", "4"),
        ]
    }
}

crate::hw_block! {
    /// One coordinate (u or v): its texel, W − 1, X (W − 1 of the next pixel along the line
    /// before corrections), the three P registers, their saved line-start copy and shadow
    /// set-up; the comparators, and every candidate of the next words side by side.
    pub struct TexAxis(clock) {
        in {
            load: Bit, set_u0: Bits<16>, set_w0: Bits<48>,
            set_p0: Bits<48>, set_p1: Bits<48>, set_p2: Bits<48>,
            /// E, 2E, 3E; Z = E + ΔE_line, K = E + 2ΔE_line; the three ΔE.
            e: Bits<48>, e2: Bits<48>, e3: Bits<48>, z: Bits<48>, k: Bits<48>,
            de0: Bits<48>, de1: Bits<48>, de2: Bits<48>,
            k2: Bit, k4: Bit, pending: Bit,
            take_first: Bit, take_row: Bit, take_line: Bit, long_move: Bit, save: Bit,
        }
        out {
            /// The texel settles this clock (always, with nothing pending).
            ok: Bit,
            /// The texel after this clock's correction.
            u_star: Bits<16>,
        }
        u_q: DFF<Bits<16>>, w_q: DFF<Bits<48>>, x_q: DFF<Bits<48>>,
        p0_q: DFF<Bits<48>>, p1_q: DFF<Bits<48>>, p2_q: DFF<Bits<48>>,
        /// The saved line start (W − 1 and P; X is formed at the move).
        ur_q: DFF<Bits<16>>, wr_q: DFF<Bits<48>>,
        pr0_q: DFF<Bits<48>>, pr1_q: DFF<Bits<48>>, pr2_q: DFF<Bits<48>>,
        /// The shadow set-up.
        su_q: DFF<Bits<16>>, sw_q: DFF<Bits<48>>,
        sp0_q: DFF<Bits<48>>, sp1_q: DFF<Bits<48>>, sp2_q: DFF<Bits<48>>,
        /// (W − 1) + j·E side by side (j = +1 … +4, −1 … −5; ±3, ±4 and −5 used by k = 4 only):
        /// "W + j·E > 0" is a sign bit.
        v_p1: Signal<Local, Bits<48>>, v_p2: Signal<Local, Bits<48>>,
        v_p3: Signal<Local, Bits<48>>, v_p4: Signal<Local, Bits<48>>,
        v_m1: Signal<Local, Bits<48>>, v_m2: Signal<Local, Bits<48>>, v_m3: Signal<Local, Bits<48>>,
        v_m4: Signal<Local, Bits<48>>, v_m5: Signal<Local, Bits<48>>,
        /// The chosen correction j (one-hot; none: j = 0), and whether it settles the texel.
        sel_p1: Signal<Local, Bit>, sel_p2: Signal<Local, Bit>,
        sel_p3: Signal<Local, Bit>, sel_p4: Signal<Local, Bit>,
        sel_m1: Signal<Local, Bit>, sel_m2: Signal<Local, Bit>,
        sel_m3: Signal<Local, Bit>, sel_m4: Signal<Local, Bit>,
        ok_w: Signal<Local, Bit>,
        /// The next pixel along the line: X + j·Z (its W − 1), and X + P0 + j·K (its X).
        n_0: Signal<Local, Bits<48>>, n_p1: Signal<Local, Bits<48>>, n_p2: Signal<Local, Bits<48>>,
        n_m1: Signal<Local, Bits<48>>, n_m2: Signal<Local, Bits<48>>,
        n_p3: Signal<Local, Bits<48>>, n_p4: Signal<Local, Bits<48>>,
        n_m3: Signal<Local, Bits<48>>, n_m4: Signal<Local, Bits<48>>,
        c_0: Signal<Local, Bits<48>>,
        /// X + P0 ± 3K, ± 4K (k = 4).
        c_p3: Signal<Local, Bits<48>>, c_p4: Signal<Local, Bits<48>>,
        c_m3: Signal<Local, Bits<48>>, c_m4: Signal<Local, Bits<48>>,
        pub c_p1: Add3, pub c_p2: Add3, pub c_m1: Add3, pub c_m2: Add3,
        /// P_m + j·ΔE_m for each j.
        q0_p1: Signal<Local, Bits<48>>, q0_p2: Signal<Local, Bits<48>>,
        q0_m1: Signal<Local, Bits<48>>, q0_m2: Signal<Local, Bits<48>>,
        q1_p1: Signal<Local, Bits<48>>, q1_p2: Signal<Local, Bits<48>>,
        q1_m1: Signal<Local, Bits<48>>, q1_m2: Signal<Local, Bits<48>>,
        q2_p1: Signal<Local, Bits<48>>, q2_p2: Signal<Local, Bits<48>>,
        q2_m1: Signal<Local, Bits<48>>, q2_m2: Signal<Local, Bits<48>>,
        /// P_m ± 3ΔE_m, ± 4ΔE_m (k = 4).
        q0_p3: Signal<Local, Bits<48>>, q0_p4: Signal<Local, Bits<48>>,
        q0_m3: Signal<Local, Bits<48>>, q0_m4: Signal<Local, Bits<48>>,
        q1_p3: Signal<Local, Bits<48>>, q1_p4: Signal<Local, Bits<48>>,
        q1_m3: Signal<Local, Bits<48>>, q1_m4: Signal<Local, Bits<48>>,
        q2_p3: Signal<Local, Bits<48>>, q2_p4: Signal<Local, Bits<48>>,
        q2_m3: Signal<Local, Bits<48>>, q2_m4: Signal<Local, Bits<48>>,
        /// The selected words: corrected, and moved along the line.
        w_star: Signal<Local, Bits<48>>, x_star: Signal<Local, Bits<48>>,
        p0_star: Signal<Local, Bits<48>>, p1_star: Signal<Local, Bits<48>>, p2_star: Signal<Local, Bits<48>>,
        u_new: Signal<Local, Bits<16>>, x_line: Signal<Local, Bits<48>>,
        /// A line start from the saved state, after a short and after a long edge move: W − 1
        /// and X after it.
        w_row1: Signal<Local, Bits<48>>, w_row2: Signal<Local, Bits<48>>,
        pub x_row1: Add3, pub x_row2: Add3,
        x_first: Signal<Local, Bits<48>>,
    }
}

impl Logic for TexAxis {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, u_q, w_q, x_q, p0_q, p1_q, p2_q, ur_q, wr_q, pr0_q, pr1_q, pr2_q, su_q,
            sw_q, sp0_q, sp1_q, sp2_q
        );
        // The comparators, from registers through one adder each (±3E, ±4E and 5E, k = 4
        // only, through two).
        self.v_p1.next = self.w_q.q.val() + self.e.val();
        self.v_p2.next = self.w_q.q.val() + self.e2.val();
        self.v_p3.next = self.w_q.q.val() + self.e3.val();
        self.v_p4.next = self.w_q.q.val() + (self.e2.val() << 1);
        self.v_m1.next = self.w_q.q.val() - self.e.val();
        self.v_m2.next = self.w_q.q.val() - self.e2.val();
        self.v_m3.next = self.w_q.q.val() - self.e3.val();
        self.v_m4.next = self.w_q.q.val() - (self.e2.val() << 1);
        self.v_m5.next = self.w_q.q.val() - (self.e2.val() << 1) - self.e.val();

        // The correction (golden `correction`): W ≤ 0 steps up, W − E > 0 steps down, by the
        // first j ≤ k whose candidate is on the other side; otherwise the pixel keeps k steps
        // of progress and stays.
        self.sel_p1.next = false;
        self.sel_p2.next = false;
        self.sel_p3.next = false;
        self.sel_p4.next = false;
        self.sel_m1.next = false;
        self.sel_m2.next = false;
        self.sel_m3.next = false;
        self.sel_m4.next = false;
        self.ok_w.next = true;
        if self.pending.val() {
            if self.w_q.q.val().get_bit(47) {
                if !self.v_p1.val().get_bit(47) {
                    self.sel_p1.next = true;
                } else if self.k2.val() & !self.v_p2.val().get_bit(47) {
                    self.sel_p2.next = true;
                } else if self.k4.val() & !self.v_p3.val().get_bit(47) {
                    self.sel_p3.next = true;
                } else if self.k4.val() & !self.v_p4.val().get_bit(47) {
                    self.sel_p4.next = true;
                } else {
                    self.ok_w.next = false;
                    if self.k4.val() {
                        self.sel_p4.next = true;
                    } else if self.k2.val() {
                        self.sel_p2.next = true;
                    } else {
                        self.sel_p1.next = true;
                    }
                }
            } else if !self.v_m1.val().get_bit(47) {
                if self.v_m2.val().get_bit(47) {
                    self.sel_m1.next = true;
                } else if self.k2.val() & self.v_m3.val().get_bit(47) {
                    self.sel_m2.next = true;
                } else if self.k4.val() & self.v_m4.val().get_bit(47) {
                    self.sel_m3.next = true;
                } else if self.k4.val() & self.v_m5.val().get_bit(47) {
                    self.sel_m4.next = true;
                } else {
                    self.ok_w.next = false;
                    if self.k4.val() {
                        self.sel_m4.next = true;
                    } else if self.k2.val() {
                        self.sel_m2.next = true;
                    } else {
                        self.sel_m1.next = true;
                    }
                }
            }
        }
        self.ok.next = self.ok_w.val();

        // Every candidate of the next words, from registers, side by side.
        self.n_0.next = self.x_q.q.val();
        self.n_p1.next = self.x_q.q.val() + self.z.val();
        self.n_p2.next = self.x_q.q.val() + (self.z.val() << 1);
        self.n_m1.next = self.x_q.q.val() - self.z.val();
        self.n_m2.next = self.x_q.q.val() - (self.z.val() << 1);
        self.c_0.next = self.x_q.q.val() + self.p0_q.q.val();
        self.c_p1.a.next = self.x_q.q.val();
        self.c_p1.b.next = self.p0_q.q.val();
        self.c_p1.c.next = self.k.val();
        self.c_p1.cin.next = false;
        self.c_p2.a.next = self.x_q.q.val();
        self.c_p2.b.next = self.p0_q.q.val();
        self.c_p2.c.next = self.k.val() << 1;
        self.c_p2.cin.next = false;
        self.c_m1.a.next = self.x_q.q.val();
        self.c_m1.b.next = self.p0_q.q.val();
        self.c_m1.c.next = !self.k.val();
        self.c_m1.cin.next = true;
        self.c_m2.a.next = self.x_q.q.val();
        self.c_m2.b.next = self.p0_q.q.val();
        self.c_m2.c.next = !(self.k.val() << 1);
        self.c_m2.cin.next = true;
        self.q0_p1.next = self.p0_q.q.val() + self.de0.val();
        self.q0_p2.next = self.p0_q.q.val() + (self.de0.val() << 1);
        self.q0_m1.next = self.p0_q.q.val() - self.de0.val();
        self.q0_m2.next = self.p0_q.q.val() - (self.de0.val() << 1);
        self.q1_p1.next = self.p1_q.q.val() + self.de1.val();
        self.q1_p2.next = self.p1_q.q.val() + (self.de1.val() << 1);
        self.q1_m1.next = self.p1_q.q.val() - self.de1.val();
        self.q1_m2.next = self.p1_q.q.val() - (self.de1.val() << 1);
        self.q2_p1.next = self.p2_q.q.val() + self.de2.val();
        self.q2_p2.next = self.p2_q.q.val() + (self.de2.val() << 1);
        self.q2_m1.next = self.p2_q.q.val() - self.de2.val();
        self.q2_m2.next = self.p2_q.q.val() - (self.de2.val() << 1);
        self.n_p3.next = self.x_q.q.val() + self.z.val() + (self.z.val() << 1);
        self.n_p4.next = self.x_q.q.val() + (self.z.val() << 2);
        self.n_m3.next = self.x_q.q.val() - self.z.val() - (self.z.val() << 1);
        self.n_m4.next = self.x_q.q.val() - (self.z.val() << 2);
        self.c_p3.next = self.c_0.val() + self.k.val() + (self.k.val() << 1);
        self.c_p4.next = self.c_0.val() + (self.k.val() << 2);
        self.c_m3.next = self.c_0.val() - self.k.val() - (self.k.val() << 1);
        self.c_m4.next = self.c_0.val() - (self.k.val() << 2);
        self.q0_p3.next = self.p0_q.q.val() + self.de0.val() + (self.de0.val() << 1);
        self.q0_p4.next = self.p0_q.q.val() + (self.de0.val() << 2);
        self.q0_m3.next = self.p0_q.q.val() - self.de0.val() - (self.de0.val() << 1);
        self.q0_m4.next = self.p0_q.q.val() - (self.de0.val() << 2);
        self.q1_p3.next = self.p1_q.q.val() + self.de1.val() + (self.de1.val() << 1);
        self.q1_p4.next = self.p1_q.q.val() + (self.de1.val() << 2);
        self.q1_m3.next = self.p1_q.q.val() - self.de1.val() - (self.de1.val() << 1);
        self.q1_m4.next = self.p1_q.q.val() - (self.de1.val() << 2);
        self.q2_p3.next = self.p2_q.q.val() + self.de2.val() + (self.de2.val() << 1);
        self.q2_p4.next = self.p2_q.q.val() + (self.de2.val() << 2);
        self.q2_m3.next = self.p2_q.q.val() - self.de2.val() - (self.de2.val() << 1);
        self.q2_m4.next = self.p2_q.q.val() - (self.de2.val() << 2);

        // The selection by j: W + j·E, X + j·Z (X after the correction: the next pixel's
        // W − 1 before its own), X + P0 + j·K (the next pixel's X), P_m + j·ΔE_m, u + j.
        self.u_new.next = self.u_q.q.val();
        self.w_star.next = self.w_q.q.val();
        self.x_star.next = self.n_0.val();
        self.x_line.next = self.c_0.val();
        self.p0_star.next = self.p0_q.q.val();
        self.p1_star.next = self.p1_q.q.val();
        self.p2_star.next = self.p2_q.q.val();
        if self.sel_p1.val() {
            self.u_new.next = self.u_q.q.val() + 1;
            self.w_star.next = self.v_p1.val();
            self.x_star.next = self.n_p1.val();
            self.x_line.next = self.c_p1.sum.val();
            self.p0_star.next = self.q0_p1.val();
            self.p1_star.next = self.q1_p1.val();
            self.p2_star.next = self.q2_p1.val();
        }
        if self.sel_p2.val() {
            self.u_new.next = self.u_q.q.val() + 2;
            self.w_star.next = self.v_p2.val();
            self.x_star.next = self.n_p2.val();
            self.x_line.next = self.c_p2.sum.val();
            self.p0_star.next = self.q0_p2.val();
            self.p1_star.next = self.q1_p2.val();
            self.p2_star.next = self.q2_p2.val();
        }
        if self.sel_m1.val() {
            self.u_new.next = self.u_q.q.val() - 1;
            self.w_star.next = self.v_m1.val();
            self.x_star.next = self.n_m1.val();
            self.x_line.next = self.c_m1.sum.val();
            self.p0_star.next = self.q0_m1.val();
            self.p1_star.next = self.q1_m1.val();
            self.p2_star.next = self.q2_m1.val();
        }
        if self.sel_m2.val() {
            self.u_new.next = self.u_q.q.val() - 2;
            self.w_star.next = self.v_m2.val();
            self.x_star.next = self.n_m2.val();
            self.x_line.next = self.c_m2.sum.val();
            self.p0_star.next = self.q0_m2.val();
            self.p1_star.next = self.q1_m2.val();
            self.p2_star.next = self.q2_m2.val();
        }
        if self.sel_p3.val() {
            self.u_new.next = self.u_q.q.val() + 3;
            self.w_star.next = self.v_p3.val();
            self.x_star.next = self.n_p3.val();
            self.x_line.next = self.c_p3.val();
            self.p0_star.next = self.q0_p3.val();
            self.p1_star.next = self.q1_p3.val();
            self.p2_star.next = self.q2_p3.val();
        }
        if self.sel_p4.val() {
            self.u_new.next = self.u_q.q.val() + 4;
            self.w_star.next = self.v_p4.val();
            self.x_star.next = self.n_p4.val();
            self.x_line.next = self.c_p4.val();
            self.p0_star.next = self.q0_p4.val();
            self.p1_star.next = self.q1_p4.val();
            self.p2_star.next = self.q2_p4.val();
        }
        if self.sel_m3.val() {
            self.u_new.next = self.u_q.q.val() - 3;
            self.w_star.next = self.v_m3.val();
            self.x_star.next = self.n_m3.val();
            self.x_line.next = self.c_m3.val();
            self.p0_star.next = self.q0_m3.val();
            self.p1_star.next = self.q1_m3.val();
            self.p2_star.next = self.q2_m3.val();
        }
        if self.sel_m4.val() {
            self.u_new.next = self.u_q.q.val() - 4;
            self.w_star.next = self.v_m4.val();
            self.x_star.next = self.n_m4.val();
            self.x_line.next = self.c_m4.val();
            self.p0_star.next = self.q0_m4.val();
            self.p1_star.next = self.q1_m4.val();
            self.p2_star.next = self.q2_m4.val();
        }
        self.u_star.next = self.u_new.val();

        // A line start moves from the saved state only (a line start in the clock its
        // previous line's only pixel settles waits a clock: the parent's `defer`).
        self.w_row1.next = self.wr_q.q.val() + self.pr1_q.q.val();
        self.w_row2.next = self.wr_q.q.val() + self.pr2_q.q.val();
        self.x_row1.a.next = self.wr_q.q.val();
        self.x_row1.b.next = self.pr1_q.q.val();
        self.x_row1.c.next = self.pr0_q.q.val();
        self.x_row1.cin.next = false;
        self.x_row2.a.next = self.wr_q.q.val();
        self.x_row2.b.next = self.pr2_q.q.val();
        self.x_row2.c.next = self.pr0_q.q.val();
        self.x_row2.cin.next = false;
        self.x_first.next = self.sw_q.q.val() + self.sp0_q.q.val();

        // Corrected by default; X after the correction is the next pixel's W − 1.
        self.u_q.d.next = self.u_new.val();
        self.w_q.d.next = self.w_star.val();
        self.x_q.d.next = self.x_star.val();
        self.p0_q.d.next = self.p0_star.val();
        self.p1_q.d.next = self.p1_star.val();
        self.p2_q.d.next = self.p2_star.val();
        if self.save.val() {
            self.ur_q.d.next = self.u_new.val();
            self.wr_q.d.next = self.w_star.val();
            self.pr0_q.d.next = self.p0_star.val();
            self.pr1_q.d.next = self.p1_star.val();
            self.pr2_q.d.next = self.p2_star.val();
        }
        if self.take_first.val() {
            self.u_q.d.next = self.su_q.q.val();
            self.w_q.d.next = self.sw_q.q.val();
            self.x_q.d.next = self.x_first.val();
            self.p0_q.d.next = self.sp0_q.q.val();
            self.p1_q.d.next = self.sp1_q.q.val();
            self.p2_q.d.next = self.sp2_q.q.val();
            self.ur_q.d.next = self.su_q.q.val();
            self.wr_q.d.next = self.sw_q.q.val();
            self.pr0_q.d.next = self.sp0_q.q.val();
            self.pr1_q.d.next = self.sp1_q.q.val();
            self.pr2_q.d.next = self.sp2_q.q.val();
        } else if self.take_row.val() {
            self.u_q.d.next = self.ur_q.q.val();
            self.w_q.d.next = self.w_row1.val();
            self.x_q.d.next = self.x_row1.sum.val();
            self.p0_q.d.next = self.pr0_q.q.val();
            self.p1_q.d.next = self.pr1_q.q.val();
            self.p2_q.d.next = self.pr2_q.q.val();
            self.wr_q.d.next = self.w_row1.val();
            if self.long_move.val() {
                self.w_q.d.next = self.w_row2.val();
                self.x_q.d.next = self.x_row2.sum.val();
                self.wr_q.d.next = self.w_row2.val();
            }
        } else if self.take_line.val() {
            self.w_q.d.next = self.x_star.val();
            self.x_q.d.next = self.x_line.val();
        }
        if self.load.val() {
            self.su_q.d.next = self.set_u0.val();
            self.sw_q.d.next = self.set_w0.val();
            self.sp0_q.d.next = self.set_p0.val();
            self.sp1_q.d.next = self.set_p1.val();
            self.sp2_q.d.next = self.set_p2.val();
        }
    }
}

crate::hw_block! {
    /// The texture-coordinate block (see the module header): E, its multiples and the moves'
    /// ΔE shared by the two [`TexAxis`] (0: u, 1: v), the pending pixel and the outputs.
    pub struct TextureCoord(clock) as "texture-coord" {
        summary: "PCT texel (u, v) per pixel of the address block's walk, division-free: E, W and P recurrences, up to k correction steps per clock (SPEC §14)",
        latency: 2 => "valid_in to valid_out for a pixel that settles in its first clock; one pixel per clock while every pixel needs at most k steps per axis",
        multipliers: 0,
        in {
            load: Bit,
            e0: Bits<48>, de_line: Bits<48>, de_short: Bits<48>, de_long: Bits<48>,
            u_u0: Bits<16>, u_w0: Bits<48>, u_p_line: Bits<48>, u_p_short: Bits<48>, u_p_long: Bits<48>,
            v_u0: Bits<16>, v_w0: Bits<48>, v_p_line: Bits<48>, v_p_short: Bits<48>, v_p_long: Bits<48>,
            valid_in: Bit, row_start_in: Bit, step_in: Bits<2>, carry_in: Bit,
            x_in: Bits<12>, y_in: Bits<12>, done_in: Bit,
            hold: Bit,
        }
        out {
            ready: Bit, valid_out: Bit, u: Bits<16>, v: Bits<16>, x: Bits<12>, y: Bits<12>,
            done_out: Bit,
        }
        /// 0: u, 1: v.
        pub axis: [TexAxis; 2],
        k2: Constant<Bit> = Constant::new(p.k >= 2),
        k4: Constant<Bit> = Constant::new(p.k == 4),
        /// E, 3E, Z = E + ΔE_line, K = E + 2ΔE_line; the saved line start's E + ΔE_short and
        /// E + ΔE_long; ΔE of the three moves; the shadow E and ΔE.
        e_q: DFF<Bits<48>>, e3_q: DFF<Bits<48>>, z_q: DFF<Bits<48>>, k_q: DFF<Bits<48>>,
        zr1_q: DFF<Bits<48>>, zr2_q: DFF<Bits<48>>,
        de0_q: DFF<Bits<48>>, de1_q: DFF<Bits<48>>, de2_q: DFF<Bits<48>>,
        se_q: DFF<Bits<48>>, sde0_q: DFF<Bits<48>>, sde1_q: DFF<Bits<48>>, sde2_q: DFF<Bits<48>>,
        /// The pending pixel: whether there is one, whether it starts its line, its address.
        pending_q: DFF<Bit>, first_px_q: DFF<Bit>,
        px_x_q: DFF<Bits<12>>, px_y_q: DFF<Bits<12>>, px_done_q: DFF<Bit>,
        /// A line start waiting a clock for the saved state: its carry, and whether it has a
        /// pixel.
        defer_q: DFF<Bit>, dcarry_q: DFF<Bit>, dvalid_q: DFF<Bit>,
        valid_q: DFF<Bit>, u_q: DFF<Bits<16>>, v_q: DFF<Bits<16>>,
        x_q: DFF<Bits<12>>, y_q: DFF<Bits<12>>, done_q: DFF<Bit>,
        ok: Signal<Local, Bit>, ready_w: Signal<Local, Bit>, emit: Signal<Local, Bit>,
        save: Signal<Local, Bit>, take: Signal<Local, Bit>, first: Signal<Local, Bit>,
        take_first: Signal<Local, Bit>, take_row: Signal<Local, Bit>, take_line: Signal<Local, Bit>,
        row_now: Signal<Local, Bit>, defer_now: Signal<Local, Bit>, long_move: Signal<Local, Bit>,
        /// The moved E-words' candidates: along the line (3Z, K + ΔE_line), from the saved
        /// Z_short or Z_long (3Z_m, Z_m + ΔE_line, Z_m + 2ΔE_line, Z_n + ΔE_m), from the shadow.
        l_e3: Signal<Local, Bits<48>>, l_k: Signal<Local, Bits<48>>,
        r1_e3: Signal<Local, Bits<48>>, r2_e3: Signal<Local, Bits<48>>,
        r1_z: Signal<Local, Bits<48>>, r2_z: Signal<Local, Bits<48>>,
        r1_k: Signal<Local, Bits<48>>, r2_k: Signal<Local, Bits<48>>,
        r11: Signal<Local, Bits<48>>, r12: Signal<Local, Bits<48>>,
        r21: Signal<Local, Bits<48>>, r22: Signal<Local, Bits<48>>,
        f_e3: Signal<Local, Bits<48>>, f_z: Signal<Local, Bits<48>>, f_k: Signal<Local, Bits<48>>,
        f_zr1: Signal<Local, Bits<48>>, f_zr2: Signal<Local, Bits<48>>,
    }
    new(p: &TexCoordParams);
}

impl Logic for TextureCoord {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, e_q, e3_q, z_q, k_q, zr1_q, zr2_q, de0_q, de1_q, de2_q, se_q, sde0_q,
            sde1_q, sde2_q, pending_q, first_px_q, px_x_q, px_y_q, px_done_q, defer_q, dcarry_q,
            dvalid_q, valid_q, u_q, v_q, x_q, y_q, done_q
        );
        self.ok.next = self.axis[0].ok.val() & self.axis[1].ok.val();
        self.ready_w.next =
            !self.defer_q.q.val() & (!self.pending_q.q.val() | self.ok.val()) & !self.hold.val();
        self.emit.next = self.pending_q.q.val() & self.ok.val() & !self.hold.val();
        self.save.next = self.emit.val() & self.first_px_q.q.val();
        self.take.next = self.ready_w.val()
            & (self.valid_in.val() | self.row_start_in.val() | self.done_in.val());
        self.first.next = self.row_start_in.val() & (self.step_in.val() == 0);
        self.take_first.next = self.take.val() & self.first.val();
        self.row_now.next =
            self.take.val() & self.row_start_in.val() & !self.first.val() & !self.save.val();
        self.defer_now.next =
            self.take.val() & self.row_start_in.val() & !self.first.val() & self.save.val();
        self.take_row.next = self.row_now.val() | self.defer_q.q.val();
        self.long_move.next = self.carry_in.val();
        if self.defer_q.q.val() {
            self.long_move.next = self.dcarry_q.q.val();
        }
        self.take_line.next = self.take.val() & self.valid_in.val() & !self.row_start_in.val();

        for i in 0..2 {
            self.axis[i].clock.next = self.clock.val();
            self.axis[i].load.next = self.load.val();
            self.axis[i].e.next = self.e_q.q.val();
            self.axis[i].e2.next = self.e_q.q.val() << 1;
            self.axis[i].e3.next = self.e3_q.q.val();
            self.axis[i].z.next = self.z_q.q.val();
            self.axis[i].k.next = self.k_q.q.val();
            self.axis[i].de0.next = self.de0_q.q.val();
            self.axis[i].de1.next = self.de1_q.q.val();
            self.axis[i].de2.next = self.de2_q.q.val();
            self.axis[i].k2.next = self.k2.val();
            self.axis[i].k4.next = self.k4.val();
            self.axis[i].pending.next = self.pending_q.q.val();
            self.axis[i].take_first.next = self.take_first.val();
            self.axis[i].take_row.next = self.take_row.val();
            self.axis[i].take_line.next = self.take_line.val();
            self.axis[i].long_move.next = self.long_move.val();
            self.axis[i].save.next = self.save.val();
        }
        self.axis[0].set_u0.next = self.u_u0.val();
        self.axis[0].set_w0.next = self.u_w0.val();
        self.axis[0].set_p0.next = self.u_p_line.val();
        self.axis[0].set_p1.next = self.u_p_short.val();
        self.axis[0].set_p2.next = self.u_p_long.val();
        self.axis[1].set_u0.next = self.v_u0.val();
        self.axis[1].set_w0.next = self.v_w0.val();
        self.axis[1].set_p0.next = self.v_p_line.val();
        self.axis[1].set_p1.next = self.v_p_short.val();
        self.axis[1].set_p2.next = self.v_p_long.val();

        // E after a move, every candidate formed from registers side by side so that the
        // decision to move only selects. Along the line: E ← Z, Z ← K, K += ΔE_line. A line
        // start from the saved Z_m (m by the carry): E ← Z_m, Z ← Z_m + ΔE_line,
        // K ← Z_m + 2ΔE_line, and the saved Z_short, Z_long move by ΔE_m. A first event from
        // the shadow E0 and ΔE.
        self.l_e3.next = self.z_q.q.val() + (self.z_q.q.val() << 1);
        self.l_k.next = self.k_q.q.val() + self.de0_q.q.val();
        self.r1_e3.next = self.zr1_q.q.val() + (self.zr1_q.q.val() << 1);
        self.r2_e3.next = self.zr2_q.q.val() + (self.zr2_q.q.val() << 1);
        self.r1_z.next = self.zr1_q.q.val() + self.de0_q.q.val();
        self.r2_z.next = self.zr2_q.q.val() + self.de0_q.q.val();
        self.r1_k.next = self.zr1_q.q.val() + (self.de0_q.q.val() << 1);
        self.r2_k.next = self.zr2_q.q.val() + (self.de0_q.q.val() << 1);
        self.r11.next = self.zr1_q.q.val() + self.de1_q.q.val();
        self.r12.next = self.zr1_q.q.val() + self.de2_q.q.val();
        self.r21.next = self.zr2_q.q.val() + self.de1_q.q.val();
        self.r22.next = self.zr2_q.q.val() + self.de2_q.q.val();
        self.f_e3.next = self.se_q.q.val() + (self.se_q.q.val() << 1);
        self.f_z.next = self.se_q.q.val() + self.sde0_q.q.val();
        self.f_k.next = self.se_q.q.val() + (self.sde0_q.q.val() << 1);
        self.f_zr1.next = self.se_q.q.val() + self.sde1_q.q.val();
        self.f_zr2.next = self.se_q.q.val() + self.sde2_q.q.val();
        if self.take_first.val() {
            self.e_q.d.next = self.se_q.q.val();
            self.e3_q.d.next = self.f_e3.val();
            self.z_q.d.next = self.f_z.val();
            self.k_q.d.next = self.f_k.val();
            self.zr1_q.d.next = self.f_zr1.val();
            self.zr2_q.d.next = self.f_zr2.val();
            self.de0_q.d.next = self.sde0_q.q.val();
            self.de1_q.d.next = self.sde1_q.q.val();
            self.de2_q.d.next = self.sde2_q.q.val();
        } else if self.take_row.val() & !self.long_move.val() {
            self.e_q.d.next = self.zr1_q.q.val();
            self.e3_q.d.next = self.r1_e3.val();
            self.z_q.d.next = self.r1_z.val();
            self.k_q.d.next = self.r1_k.val();
            self.zr1_q.d.next = self.r11.val();
            self.zr2_q.d.next = self.r21.val();
        } else if self.take_row.val() {
            self.e_q.d.next = self.zr2_q.q.val();
            self.e3_q.d.next = self.r2_e3.val();
            self.z_q.d.next = self.r2_z.val();
            self.k_q.d.next = self.r2_k.val();
            self.zr1_q.d.next = self.r12.val();
            self.zr2_q.d.next = self.r22.val();
        } else if self.take_line.val() {
            self.e_q.d.next = self.z_q.q.val();
            self.e3_q.d.next = self.l_e3.val();
            self.z_q.d.next = self.k_q.q.val();
            self.k_q.d.next = self.l_k.val();
        }
        if self.load.val() {
            self.se_q.d.next = self.e0.val();
            self.sde0_q.d.next = self.de_line.val();
            self.sde1_q.d.next = self.de_short.val();
            self.sde2_q.d.next = self.de_long.val();
        }

        // The pending pixel.
        self.defer_q.d.next = self.defer_now.val();
        if self.defer_now.val() {
            self.dcarry_q.d.next = self.carry_in.val();
            self.dvalid_q.d.next = self.valid_in.val();
        }
        if self.defer_q.q.val() {
            self.pending_q.d.next = self.dvalid_q.q.val();
        } else if self.take.val() {
            self.pending_q.d.next = self.valid_in.val() & !self.defer_now.val();
            self.first_px_q.d.next = self.valid_in.val() & self.row_start_in.val();
            self.px_x_q.d.next = self.x_in.val();
            self.px_y_q.d.next = self.y_in.val();
            self.px_done_q.d.next = self.done_in.val();
        } else {
            self.pending_q.d.next = self.pending_q.q.val() & !self.emit.val();
        }
        self.valid_q.d.next = self.emit.val();
        if self.emit.val() {
            self.u_q.d.next = self.axis[0].u_star.val();
            self.v_q.d.next = self.axis[1].u_star.val();
            self.x_q.d.next = self.px_x_q.q.val();
            self.y_q.d.next = self.px_y_q.q.val();
        }
        self.done_q.d.next = (self.emit.val() & self.px_done_q.q.val())
            | (self.take.val() & !self.valid_in.val() & self.done_in.val());

        self.ready.next = self.ready_w.val();
        self.valid_out.next = self.valid_q.q.val();
        self.u.next = self.u_q.q.val();
        self.v.next = self.v_q.q.val();
        self.x.next = self.x_q.q.val();
        self.y.next = self.y_q.q.val();
        self.done_out.next = self.done_q.q.val();
    }
}
