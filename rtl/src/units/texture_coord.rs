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
//! # Steps per clock: the build parameter k
//!
//! `k=1` (the seed's one step per clock) or `k=2`. Each clock the comparators look at
//! W + j·E for j ∈ {−(k+1) … k} side by side (2E a shift, 3E the register E3) and pick the j
//! that settles the texel; a pixel needing q steps on an axis stays max(1, ⌈q/k⌉) clocks, both
//! axes in parallel. A pixel that settles with at most k steps per axis costs one clock.
//!
//! # Ports
//!
//! | port | bits | format |
//! |---|---|---|
//! | `load` | 1 | write the shadow set-up (the next triangle's), any clock |
//! | `e0`, `de_line`, `de_short`, `de_long` | 48 each | E at the first line start; ΔE of the three moves |
//! | `u_u0`, `v_u0` | 16 each | start texels (two's complement) |
//! | `u_w0` … `u_p_long`, `v_w0` … `v_p_long` | 48 each | W and P_line, P_short, P_long at the start |
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
//! `hold` (one AND gate), never of the event: high when `hold` is low and no pixel is pending or
//! the pending one settles this clock. A pixel
//! taken in clock t settles in clock t + c (c = max(1, ⌈q/k⌉) for q steps on its worse axis)
//! and shows in clock t + c + 1 with `valid_out`: one pixel per clock while every pixel needs at
//! most k steps per axis, and the pipe holds only beyond that.
//!
//! Latency (the block's `LATENCY`): 2 clocks, valid_in to valid_out for a pixel that settles in its first clock.
//!
//! # Overflow and error budget
//!
//! Accepted set-ups (`TexCoordSetup::check`): D ∈ [1, 2^30) at every pixel walked, and every
//! texel and |u − N/D| within 2^15 − 4. Then E < 2^31 and |W + j·E| < 2^47 for |j| ≤ 3: every
//! comparison sees the true sign. That covers a 4096-pixel screen with D scaled to 2^29 at the
//! nearest vertex and textures up to 1024 texels repeated 31 times across one triangle.
//! Error budget: exact — the texel is the nearest one of the quotient of the integer
//! coefficients (a tie goes up); against unrounded coefficients it can differ only where N/D
//! lies within their rounding of a texel boundary.

use rust_hdl::prelude::*;

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
    const KEYS: &'static [&'static str] = &["k"];
    /// `k=1` or `k=2` (default).
    fn from_options(o: &Options) -> Result<Self, String> {
        match o.get("k") {
            None | Some("2") => Ok(TexCoordParams { k: 2 }),
            Some("1") => Ok(TexCoordParams { k: 1 }),
            Some(other) => Err(format!(
                "unknown k {other:?} (expected 1 or 2 correction steps per clock)"
            )),
        }
    }
    fn describe(&self) -> Option<String> {
        Some(format!("k = {} correction steps per clock", self.k))
    }
    fn test_sets() -> Vec<Options> {
        vec![Options::new(), Options::new().with("k", "1")]
    }
}

crate::hw_block! {
    /// One coordinate (u or v): its texel, W, the three P registers, their saved line-start
    /// copy and shadow set-up; the comparators and the correction.
    pub struct TexAxis(clock) {
        in {
            load: Bit, set_u0: Bits<16>, set_w0: Bits<48>,
            set_p0: Bits<48>, set_p1: Bits<48>, set_p2: Bits<48>,
            /// E, 2E, 3E and the three ΔE of the current triangle.
            e: Bits<48>, e2: Bits<48>, e3: Bits<48>,
            de0: Bits<48>, de1: Bits<48>, de2: Bits<48>,
            k2: Bit, pending: Bit,
            take_first: Bit, take_row: Bit, take_line: Bit, long_move: Bit, save: Bit,
        }
        out {
            /// The texel settles this clock (always, with nothing pending).
            ok: Bit,
            /// The texel after this clock's correction.
            u_star: Bits<16>,
        }
        u_q: DFF<Bits<16>>, w_q: DFF<Bits<48>>,
        p0_q: DFF<Bits<48>>, p1_q: DFF<Bits<48>>, p2_q: DFF<Bits<48>>,
        /// The saved line start.
        ur_q: DFF<Bits<16>>, wr_q: DFF<Bits<48>>,
        pr0_q: DFF<Bits<48>>, pr1_q: DFF<Bits<48>>, pr2_q: DFF<Bits<48>>,
        /// The shadow set-up.
        su_q: DFF<Bits<16>>, sw_q: DFF<Bits<48>>,
        sp0_q: DFF<Bits<48>>, sp1_q: DFF<Bits<48>>, sp2_q: DFF<Bits<48>>,
        /// W + j·E side by side (j = +1, +2, −1, −2, −3).
        v_p1: Signal<Local, Bits<48>>, v_p2: Signal<Local, Bits<48>>,
        v_m1: Signal<Local, Bits<48>>, v_m2: Signal<Local, Bits<48>>, v_m3: Signal<Local, Bits<48>>,
        /// "> 0" of W and of each candidate.
        pos_w: Signal<Local, Bit>, pos_p1: Signal<Local, Bit>, pos_p2: Signal<Local, Bit>,
        pos_m1: Signal<Local, Bit>, pos_m2: Signal<Local, Bit>, pos_m3: Signal<Local, Bit>,
        /// The chosen correction: |j| = 2 (else 1 when `step`), its sign, and whether any.
        step: Signal<Local, Bit>, two: Signal<Local, Bit>, neg: Signal<Local, Bit>,
        ok_w: Signal<Local, Bit>,
        /// j as a 16-bit word, |j|·ΔE_m, and the corrected words.
        j16: Signal<Local, Bits<16>>,
        dp0: Signal<Local, Bits<48>>, dp1: Signal<Local, Bits<48>>, dp2: Signal<Local, Bits<48>>,
        w_star: Signal<Local, Bits<48>>,
        p0_star: Signal<Local, Bits<48>>, p1_star: Signal<Local, Bits<48>>, p2_star: Signal<Local, Bits<48>>,
        u_new: Signal<Local, Bits<16>>,
        /// The base of a line start (the saved state, or the settling first pixel's) and W
        /// after the moves.
        rb_u: Signal<Local, Bits<16>>, rb_w: Signal<Local, Bits<48>>,
        rb_p0: Signal<Local, Bits<48>>, rb_p1: Signal<Local, Bits<48>>, rb_p2: Signal<Local, Bits<48>>,
        w_line: Signal<Local, Bits<48>>, w_row: Signal<Local, Bits<48>>,
    }
}

impl Logic for TexAxis {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, u_q, w_q, p0_q, p1_q, p2_q, ur_q, wr_q, pr0_q, pr1_q, pr2_q, su_q, sw_q,
            sp0_q, sp1_q, sp2_q
        );
        self.v_p1.next = self.w_q.q.val() + self.e.val();
        self.v_p2.next = self.w_q.q.val() + self.e2.val();
        self.v_m1.next = self.w_q.q.val() - self.e.val();
        self.v_m2.next = self.w_q.q.val() - self.e2.val();
        self.v_m3.next = self.w_q.q.val() - self.e3.val();
        self.pos_w.next = !self.w_q.q.val().get_bit(47) & self.w_q.q.val().any();
        self.pos_p1.next = !self.v_p1.val().get_bit(47) & self.v_p1.val().any();
        self.pos_p2.next = !self.v_p2.val().get_bit(47) & self.v_p2.val().any();
        self.pos_m1.next = !self.v_m1.val().get_bit(47) & self.v_m1.val().any();
        self.pos_m2.next = !self.v_m2.val().get_bit(47) & self.v_m2.val().any();
        self.pos_m3.next = !self.v_m3.val().get_bit(47) & self.v_m3.val().any();

        // The correction (golden `correction`): W ≤ 0 steps up, W − E > 0 steps down; one
        // step settles when the next candidate is on the other side, two (k = 2) when the one
        // after is; otherwise the pixel keeps k steps of progress and stays.
        self.step.next = false;
        self.two.next = false;
        self.neg.next = false;
        self.ok_w.next = true;
        if self.pending.val() {
            if !self.pos_w.val() {
                self.step.next = true;
                if !self.pos_p1.val() {
                    self.two.next = self.k2.val();
                    if !(self.k2.val() & self.pos_p2.val()) {
                        self.ok_w.next = false;
                    }
                }
            } else if self.pos_m1.val() {
                self.step.next = true;
                self.neg.next = true;
                if self.pos_m2.val() {
                    self.two.next = self.k2.val();
                    if !(self.k2.val() & !self.pos_m3.val()) {
                        self.ok_w.next = false;
                    }
                }
            }
        }
        self.ok.next = self.ok_w.val();

        self.w_star.next = self.w_q.q.val();
        self.j16.next = 0.into();
        self.dp0.next = 0.into();
        self.dp1.next = 0.into();
        self.dp2.next = 0.into();
        if self.step.val() {
            self.j16.next = 1.into();
            self.dp0.next = self.de0.val();
            self.dp1.next = self.de1.val();
            self.dp2.next = self.de2.val();
            if self.two.val() {
                self.j16.next = 2.into();
                self.dp0.next = self.de0.val() << 1;
                self.dp1.next = self.de1.val() << 1;
                self.dp2.next = self.de2.val() << 1;
            }
        }
        self.u_new.next = self.u_q.q.val() + self.j16.val();
        self.p0_star.next = self.p0_q.q.val() + self.dp0.val();
        self.p1_star.next = self.p1_q.q.val() + self.dp1.val();
        self.p2_star.next = self.p2_q.q.val() + self.dp2.val();
        if self.step.val() {
            self.w_star.next = self.v_p1.val();
            if self.two.val() {
                self.w_star.next = self.v_p2.val();
            }
        }
        if self.neg.val() {
            self.u_new.next = self.u_q.q.val() - self.j16.val();
            self.p0_star.next = self.p0_q.q.val() - self.dp0.val();
            self.p1_star.next = self.p1_q.q.val() - self.dp1.val();
            self.p2_star.next = self.p2_q.q.val() - self.dp2.val();
            self.w_star.next = self.v_m1.val();
            if self.two.val() {
                self.w_star.next = self.v_m2.val();
            }
        }
        self.u_star.next = self.u_new.val();

        // Moves: along the line from the settled state; a line start from the saved one (or
        // from the first pixel settling in this very clock).
        self.rb_u.next = self.ur_q.q.val();
        self.rb_w.next = self.wr_q.q.val();
        self.rb_p0.next = self.pr0_q.q.val();
        self.rb_p1.next = self.pr1_q.q.val();
        self.rb_p2.next = self.pr2_q.q.val();
        if self.save.val() {
            self.rb_u.next = self.u_new.val();
            self.rb_w.next = self.w_star.val();
            self.rb_p0.next = self.p0_star.val();
            self.rb_p1.next = self.p1_star.val();
            self.rb_p2.next = self.p2_star.val();
        }
        self.w_line.next = self.w_star.val() + self.p0_star.val();
        self.w_row.next = self.rb_w.val() + self.rb_p1.val();
        if self.long_move.val() {
            self.w_row.next = self.rb_w.val() + self.rb_p2.val();
        }

        self.u_q.d.next = self.u_new.val();
        self.w_q.d.next = self.w_star.val();
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
            self.p0_q.d.next = self.sp0_q.q.val();
            self.p1_q.d.next = self.sp1_q.q.val();
            self.p2_q.d.next = self.sp2_q.q.val();
            self.ur_q.d.next = self.su_q.q.val();
            self.wr_q.d.next = self.sw_q.q.val();
            self.pr0_q.d.next = self.sp0_q.q.val();
            self.pr1_q.d.next = self.sp1_q.q.val();
            self.pr2_q.d.next = self.sp2_q.q.val();
        } else if self.take_row.val() {
            self.u_q.d.next = self.rb_u.val();
            self.w_q.d.next = self.w_row.val();
            self.p0_q.d.next = self.rb_p0.val();
            self.p1_q.d.next = self.rb_p1.val();
            self.p2_q.d.next = self.rb_p2.val();
            self.ur_q.d.next = self.rb_u.val();
            self.wr_q.d.next = self.w_row.val();
            self.pr0_q.d.next = self.rb_p0.val();
            self.pr1_q.d.next = self.rb_p1.val();
            self.pr2_q.d.next = self.rb_p2.val();
        } else if self.take_line.val() {
            self.w_q.d.next = self.w_line.val();
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
        k2: Constant<Bit> = Constant::new(p.k == 2),
        /// E, 3E, Z_m = E + ΔE_m, the saved line start's Z_m, ΔE_m, the shadow E and ΔE.
        e_q: DFF<Bits<48>>, e3_q: DFF<Bits<48>>,
        z0_q: DFF<Bits<48>>, z1_q: DFF<Bits<48>>, z2_q: DFF<Bits<48>>,
        zr0_q: DFF<Bits<48>>, zr1_q: DFF<Bits<48>>, zr2_q: DFF<Bits<48>>,
        de0_q: DFF<Bits<48>>, de1_q: DFF<Bits<48>>, de2_q: DFF<Bits<48>>,
        se_q: DFF<Bits<48>>, sde0_q: DFF<Bits<48>>, sde1_q: DFF<Bits<48>>, sde2_q: DFF<Bits<48>>,
        /// The pending pixel: whether there is one, whether it starts its line, its address.
        pending_q: DFF<Bit>, first_px_q: DFF<Bit>,
        px_x_q: DFF<Bits<12>>, px_y_q: DFF<Bits<12>>, px_done_q: DFF<Bit>,
        valid_q: DFF<Bit>, u_q: DFF<Bits<16>>, v_q: DFF<Bits<16>>,
        x_q: DFF<Bits<12>>, y_q: DFF<Bits<12>>, done_q: DFF<Bit>,
        ok: Signal<Local, Bit>, ready_w: Signal<Local, Bit>, emit: Signal<Local, Bit>,
        take: Signal<Local, Bit>, first: Signal<Local, Bit>,
        take_first: Signal<Local, Bit>, take_row: Signal<Local, Bit>, take_line: Signal<Local, Bit>,
        /// The moved E and Z: base, the ΔE added, the sums.
        e_new: Signal<Local, Bits<48>>,
        zb0: Signal<Local, Bits<48>>, zb1: Signal<Local, Bits<48>>, zb2: Signal<Local, Bits<48>>,
        dz0: Signal<Local, Bits<48>>, dz1: Signal<Local, Bits<48>>, dz2: Signal<Local, Bits<48>>,
        dmove: Signal<Local, Bits<48>>,
    }
    new(p: &TexCoordParams);
}

impl Logic for TextureCoord {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, e_q, e3_q, z0_q, z1_q, z2_q, zr0_q, zr1_q, zr2_q, de0_q, de1_q, de2_q,
            se_q, sde0_q, sde1_q, sde2_q, pending_q, first_px_q, px_x_q, px_y_q, px_done_q,
            valid_q, u_q, v_q, x_q, y_q, done_q
        );
        self.ok.next = self.axis[0].ok.val() & self.axis[1].ok.val();
        self.ready_w.next = (!self.pending_q.q.val() | self.ok.val()) & !self.hold.val();
        self.emit.next = self.pending_q.q.val() & self.ok.val() & !self.hold.val();
        self.take.next = self.ready_w.val()
            & (self.valid_in.val() | self.row_start_in.val() | self.done_in.val());
        self.first.next = self.row_start_in.val() & (self.step_in.val() == 0);
        self.take_first.next = self.take.val() & self.first.val();
        self.take_row.next = self.take.val() & self.row_start_in.val() & !self.first.val();
        self.take_line.next = self.take.val() & self.valid_in.val() & !self.row_start_in.val();

        for i in 0..2 {
            self.axis[i].clock.next = self.clock.val();
            self.axis[i].load.next = self.load.val();
            self.axis[i].e.next = self.e_q.q.val();
            self.axis[i].e2.next = self.e_q.q.val() << 1;
            self.axis[i].e3.next = self.e3_q.q.val();
            self.axis[i].de0.next = self.de0_q.q.val();
            self.axis[i].de1.next = self.de1_q.q.val();
            self.axis[i].de2.next = self.de2_q.q.val();
            self.axis[i].k2.next = self.k2.val();
            self.axis[i].pending.next = self.pending_q.q.val();
            self.axis[i].take_first.next = self.take_first.val();
            self.axis[i].take_row.next = self.take_row.val();
            self.axis[i].take_line.next = self.take_line.val();
            self.axis[i].long_move.next = self.carry_in.val();
            self.axis[i].save.next = self.emit.val() & self.first_px_q.q.val();
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

        // E after the move: from Z_line along the line, from the saved Z_short/Z_long at a line
        // start, the shadow E0 at a triangle's first event; every Z moves by the same ΔE.
        self.e_new.next = self.z0_q.q.val();
        self.zb0.next = self.z0_q.q.val();
        self.zb1.next = self.z1_q.q.val();
        self.zb2.next = self.z2_q.q.val();
        self.dmove.next = self.de0_q.q.val();
        if self.take_row.val() {
            self.zb0.next = self.zr0_q.q.val();
            self.zb1.next = self.zr1_q.q.val();
            self.zb2.next = self.zr2_q.q.val();
            self.e_new.next = self.zr1_q.q.val();
            self.dmove.next = self.de1_q.q.val();
            if self.carry_in.val() {
                self.e_new.next = self.zr2_q.q.val();
                self.dmove.next = self.de2_q.q.val();
            }
        }
        self.dz0.next = self.dmove.val();
        self.dz1.next = self.dmove.val();
        self.dz2.next = self.dmove.val();
        if self.take_first.val() {
            self.e_new.next = self.se_q.q.val();
            self.zb0.next = self.se_q.q.val();
            self.zb1.next = self.se_q.q.val();
            self.zb2.next = self.se_q.q.val();
            self.dz0.next = self.sde0_q.q.val();
            self.dz1.next = self.sde1_q.q.val();
            self.dz2.next = self.sde2_q.q.val();
            self.de0_q.d.next = self.sde0_q.q.val();
            self.de1_q.d.next = self.sde1_q.q.val();
            self.de2_q.d.next = self.sde2_q.q.val();
        }
        if self.take_first.val() | self.take_row.val() | self.take_line.val() {
            self.e_q.d.next = self.e_new.val();
            self.e3_q.d.next = self.e_new.val() + (self.e_new.val() << 1);
            self.z0_q.d.next = self.zb0.val() + self.dz0.val();
            self.z1_q.d.next = self.zb1.val() + self.dz1.val();
            self.z2_q.d.next = self.zb2.val() + self.dz2.val();
        }
        if self.take_first.val() | self.take_row.val() {
            self.zr0_q.d.next = self.zb0.val() + self.dz0.val();
            self.zr1_q.d.next = self.zb1.val() + self.dz1.val();
            self.zr2_q.d.next = self.zb2.val() + self.dz2.val();
        }
        if self.load.val() {
            self.se_q.d.next = self.e0.val();
            self.sde0_q.d.next = self.de_line.val();
            self.sde1_q.d.next = self.de_short.val();
            self.sde2_q.d.next = self.de_long.val();
        }

        // The pending pixel.
        if self.take.val() {
            self.pending_q.d.next = self.valid_in.val();
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
