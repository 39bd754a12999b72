//! Quadratic-Bézier texture coordinate (SPEC §16): the texel (u, v) of each pixel of a raster
//! line from a per-line quadratic Bézier (x(t), u(t), v(t)) stepped in t by forward
//! differences, additions only, x(t) rounded to the pixel (golden:
//! `golden::units::texture_bezier`, whose `BezierTwin` this block matches bit for bit every
//! clock).
//!
//! # Formula
//!
//! The set-up software takes the control point at the intersection of the tangents to u(x) at
//! the line's ends (SPEC §16; `golden::units::texture_bezier::control_point`) and hands the
//! block, per line, n − 1 (the last pixel's index) and for each of three lanes, X (the pixel
//! distance along the walk, 0 at the first pixel, n − 1 at the last), u + ½ and v + ½, the
//! curve's value at t = 0, its first difference Δ(0) and second difference d in dt = 1/m,
//! m = 2(n − 1): two samples per pixel step.
//!
//! ```text
//!   sample j + 1:   value += Δ,   Δ += d                                  (j = 0 … m)
//!   pixel i takes sample j, j walked up from the previous pixel's while
//!                   X(j) + X(j + 1) ≤ 2i   (sample j + 1 at least as near X = i as sample j)
//!   texel = ⌊u + ½⌋ of the sample's word
//! ```
//!
//! # The window: several samples per clock
//!
//! Each lane keeps a window of four samples j … j + 3 and, for the moves, Δ = Δ(j + 3),
//! E2 = 2Δ + d and E3 = 3Δ + 3d (the steps to samples j + 5 and j + 6), d, 3d and 9d. Three
//! comparisons side by side, X(j + k − 1) + X(j + k) ≤ 2i for k = 1, 2, 3 (sample j + k
//! existing), give r, the number that hold in a row. For r < 3 the block shows pixel i with
//! sample j + r, moves the window by r and goes to pixel i + 1; for r = 3 it moves the window
//! by 3 and shows nothing. The line's first pixel takes sample 0 (its record's start; X(1) > 0
//! on every line of more than one pixel).
//!
//! The loop in short paths: the comparison sums X(j + k − 1) + X(j + k) + ¬(2i·2^32) are
//! registers, and so are flags of the count of samples left (after a move by r the count is
//! at least t when it was at least t + r): r is a function of register bits. Every register's
//! candidate after a move is one carry chain from the registers (a three-operand sum through
//! a carry-save level first, `primitives::Add3`): samples j + 4 … j + 6 are w3 + Δ, w3 + E2,
//! w3 + E3; Δ, E2, E3 move by r·d, 2r·d, 3r·d; the sums of the samples beyond the window come
//! from Z = 2·X(j + 3) + ¬(2i·2^32), kept beside Z − 2^33 (the next pixel's). The lanes capture
//! the record shown with `load`, with sums at most two adders deep, whether or not it is taken:
//! they are read only from the clock after a take until the first pixel shows and are kept
//! while it is held, so the take, a function of the comparisons, reaches only the control
//! registers. The first pixel's clock forms the window from them (samples 0 … 3 and the second
//! pixel's sums, one carry chain each).
//!
//! # Ports
//!
//! | port | bits | format |
//! |---|---|---|
//! | `load` | 1 | take a line's record (when `ready`) |
//! | `end_index` | 12 | n − 1, the line's last pixel index (n ≤ 4096) |
//! | `x_step`, `x_step2` | 48 each | signed Q15.32: X's Δ(0), d (X(0) = 0: no port) |
//! | `u_start`, `u_step`, `u_step2` (and `v_…`) | 48 each | signed Q15.32: u(0) + ½, Δ(0), d |
//! | `hold` | 1 | stall (the consumer's back-pressure): nothing taken, no step, nothing shown in the next clock |
//! | `ready` | 1 | a `load` shown this clock is taken |
//! | `valid_out` | 1 | `u`, `v`, `index` is a pixel |
//! | `u`, `v` | 16 each | the texel ⌊u + ½⌋, two's complement (not wrapped) |
//! | `index` | 12 | the pixel's index i along its line |
//! | `done` | 1 | with `valid_out`: the line's last pixel |
//!
//! Words: signed Q15.32 in 48 bits, additions modulo 2^48 (a value must lie in
//! [−2^14, 2^14): then every comparison's sum sees its true sign).
//!
//! # Latency, throughput, handshake
//!
//! `load`/`ready`/`hold` and `done`, as the address block. `ready` is high when `hold` is low
//! and no line is walked, or the line's last pixel is decided in this clock (then the next
//! line's record is taken in the same clock: lines back to back cost no clock between them).
//! A load in clock t shows the line's first pixel in clock t + 2. A pixel whose sample lies s
//! samples beyond the previous pixel's (the first pixel's: beyond sample 0) costs 1 + ⌊s/3⌋
//! clocks: one pixel per clock while s ≤ 2. With the control point inside the line x(t) moves
//! at most one pixel per sample, so s > 2 only where samples crowd (near the end the control
//! point lies close to). Measured on every line of the sphere, the torus and `plane`
//! (`golden/tests/texture_bezier_block.rs`): 1.000 pixels per clock.
//!
//! Latency (the block's `LATENCY`): 2 clocks, load to the line's first valid_out.
//!
//! # Overflow and error budget
//!
//! Exact modulo 2^48 on the words. The set-up's rounding of the start, Δ(0) and d to 2^−32
//! puts sample j within 2^−33·(1 + j + j(j − 1)/2) of the f64 curve
//! (`golden::units::texture_bezier::error_bound`: under 0.004 on a 4096-pixel line). The sample
//! a pixel takes can then differ from the f64 curve's nearest one only for another sample as
//! near the pixel centre within 4·`error_bound` (`golden::units::texture_bezier::may_show`:
//! each comparison sees two samples' deviations, and the bound covers a run of crowded
//! samples), and its texel from that f64 sample's nearest texel only within that bound of a
//! half texel. The Bézier's own error
//! against the perspective-correct u is the method's (SPEC §16's table), not the block's.
//!
//! This file also holds [`BezWalk`], this block beside the address block's walk in
//! `textured-pipeline`'s `texture=bezier` build (checked through that pipeline's registry
//! set).

use rust_hdl::prelude::*;

use crate::core::primitives::Add3;

crate::hw_block! {
    /// One lane: the record's words captured while a load is shown (with sums one adder
    /// deep), and the window of samples j … j + 3 with Δ(j + 3), E2 = 2Δ(j + 3) + d,
    /// E3 = 3Δ(j + 3) + 3d, d, 3d and 9d.
    pub struct BezLane(clock) {
        in {
            /// A record is shown (`load`) and the line's first pixel is not held: the words
            /// are captured whether or not the record is taken. They are read only from the
            /// clock after a take until the first pixel shows, a taken record is the one shown
            /// in its take's clock, and no take happens while held, so no take needs to reach
            /// these registers.
            capture: Bit, first: Bit, step_in: Bit, r: Bits<2>,
            start: Bits<48>, step: Bits<48>, step2: Bits<48>,
        }
        out {
            w0: Bits<48>, w1: Bits<48>, w2: Bits<48>, w3: Bits<48>,
            d: Bits<48>, e2: Bits<48>, e3: Bits<48>,
            /// The taken record's start, start + Δ(0), 2Δ(0) + d and 3Δ(0) + 3d.
            head: Bits<48>, head1: Bits<48>, head_c: Bits<48>, head_t3: Bits<48>,
        }
        ps0: DFF<Bits<48>>, ps1: DFF<Bits<48>>, pc: DFF<Bits<48>>, pt3: DFF<Bits<48>>,
        pstep: DFF<Bits<48>>, pdd: DFF<Bits<48>>, pdd3: DFF<Bits<48>>, pdd9: DFF<Bits<48>>,
        w0_q: DFF<Bits<48>>, w1_q: DFF<Bits<48>>, w2_q: DFF<Bits<48>>, w3_q: DFF<Bits<48>>,
        d_q: DFF<Bits<48>>, e2_q: DFF<Bits<48>>, e3_q: DFF<Bits<48>>,
        dd_q: DFF<Bits<48>>, dd3_q: DFF<Bits<48>>, dd9_q: DFF<Bits<48>>,
        /// On the load: 3d, 9d, start + Δ(0), 2Δ(0) + d, 3Δ(0) + 3d.
        dd3_in: Signal<Local, Bits<48>>, dd9_in: Signal<Local, Bits<48>>,
        s1_in: Signal<Local, Bits<48>>,
        c_in: Signal<Local, Bits<48>>, t3_in: Signal<Local, Bits<48>>,
        /// The first pixel's clock: samples 2 and 3, Δ(3), E2, E3.
        fw2: Signal<Local, Bits<48>>, fw3: Signal<Local, Bits<48>>, fd: Signal<Local, Bits<48>>,
        fe2: Signal<Local, Bits<48>>, fe3: Signal<Local, Bits<48>>,
        /// Samples j + 4, j + 5, j + 6.
        x4: Signal<Local, Bits<48>>, x5: Signal<Local, Bits<48>>, x6: Signal<Local, Bits<48>>,
        /// Δ, E2, E3 after a move by 1, 2, 3.
        d_1: Signal<Local, Bits<48>>, d_2: Signal<Local, Bits<48>>, d_3: Signal<Local, Bits<48>>,
        e2_1: Signal<Local, Bits<48>>, e2_2: Signal<Local, Bits<48>>, e2_3: Signal<Local, Bits<48>>,
        e3_1: Signal<Local, Bits<48>>, e3_2: Signal<Local, Bits<48>>, e3_3: Signal<Local, Bits<48>>,
    }
}

impl Logic for BezLane {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, ps0, ps1, pc, pt3, pstep, pdd, pdd3, pdd9, w0_q, w1_q, w2_q, w3_q, d_q,
            e2_q, e3_q, dd_q, dd3_q, dd9_q
        );
        // The load: the words and sums of them at most two adders deep.
        self.dd3_in.next = self.step2.val() + (self.step2.val() << 1);
        self.dd9_in.next = self.step2.val() + (self.step2.val() << 3);
        self.s1_in.next = self.start.val() + self.step.val();
        self.c_in.next = (self.step.val() << 1) + self.step2.val();
        // One expression: synthesis forms it through carry-save levels and one carry chain.
        self.t3_in.next =
            self.step.val() + (self.step.val() << 1) + self.step2.val() + (self.step2.val() << 1);
        if self.capture.val() {
            self.ps0.d.next = self.start.val();
            self.ps1.d.next = self.s1_in.val();
            self.pc.d.next = self.c_in.val();
            self.pt3.d.next = self.t3_in.val();
            self.pstep.d.next = self.step.val();
            self.pdd.d.next = self.step2.val();
            self.pdd3.d.next = self.dd3_in.val();
            self.pdd9.d.next = self.dd9_in.val();
        }
        // The first pixel's clock forms the window (samples 0 … 3) from those.
        self.fw2.next = self.ps0.q.val() + self.pc.q.val();
        self.fw3.next = self.ps0.q.val() + self.pt3.q.val();
        self.fd.next = self.pstep.q.val() + self.pdd3.q.val();
        self.fe2.next = self.pc.q.val() + (self.pdd3.q.val() << 1);
        self.fe3.next = self.pt3.q.val() + self.pdd9.q.val();
        // A move: one adder from the registers for every candidate.
        self.x4.next = self.w3_q.q.val() + self.d_q.q.val();
        self.x5.next = self.w3_q.q.val() + self.e2_q.q.val();
        self.x6.next = self.w3_q.q.val() + self.e3_q.q.val();
        self.d_1.next = self.d_q.q.val() + self.dd_q.q.val();
        self.d_2.next = self.d_q.q.val() + (self.dd_q.q.val() << 1);
        self.d_3.next = self.d_q.q.val() + self.dd3_q.q.val();
        self.e2_1.next = self.e2_q.q.val() + (self.dd_q.q.val() << 1);
        self.e2_2.next = self.e2_q.q.val() + (self.dd_q.q.val() << 2);
        self.e2_3.next = self.e2_q.q.val() + (self.dd3_q.q.val() << 1);
        self.e3_1.next = self.e3_q.q.val() + self.dd3_q.q.val();
        self.e3_2.next = self.e3_q.q.val() + (self.dd3_q.q.val() << 1);
        self.e3_3.next = self.e3_q.q.val() + self.dd9_q.q.val();
        if self.first.val() {
            self.w0_q.d.next = self.ps0.q.val();
            self.w1_q.d.next = self.ps1.q.val();
            self.w2_q.d.next = self.fw2.val();
            self.w3_q.d.next = self.fw3.val();
            self.d_q.d.next = self.fd.val();
            self.e2_q.d.next = self.fe2.val();
            self.e3_q.d.next = self.fe3.val();
            self.dd_q.d.next = self.pdd.q.val();
            self.dd3_q.d.next = self.pdd3.q.val();
            self.dd9_q.d.next = self.pdd9.q.val();
        } else if self.step_in.val() {
            if self.r.val() == 1 {
                self.w0_q.d.next = self.w1_q.q.val();
                self.w1_q.d.next = self.w2_q.q.val();
                self.w2_q.d.next = self.w3_q.q.val();
                self.w3_q.d.next = self.x4.val();
                self.d_q.d.next = self.d_1.val();
                self.e2_q.d.next = self.e2_1.val();
                self.e3_q.d.next = self.e3_1.val();
            } else if self.r.val() == 2 {
                self.w0_q.d.next = self.w2_q.q.val();
                self.w1_q.d.next = self.w3_q.q.val();
                self.w2_q.d.next = self.x4.val();
                self.w3_q.d.next = self.x5.val();
                self.d_q.d.next = self.d_2.val();
                self.e2_q.d.next = self.e2_2.val();
                self.e3_q.d.next = self.e3_2.val();
            } else if self.r.val() == 3 {
                self.w0_q.d.next = self.w3_q.q.val();
                self.w1_q.d.next = self.x4.val();
                self.w2_q.d.next = self.x5.val();
                self.w3_q.d.next = self.x6.val();
                self.d_q.d.next = self.d_3.val();
                self.e2_q.d.next = self.e2_3.val();
                self.e3_q.d.next = self.e3_3.val();
            }
        }
        self.w0.next = self.w0_q.q.val();
        self.w1.next = self.w1_q.q.val();
        self.w2.next = self.w2_q.q.val();
        self.w3.next = self.w3_q.q.val();
        self.d.next = self.d_q.q.val();
        self.e2.next = self.e2_q.q.val();
        self.e3.next = self.e3_q.q.val();
        self.head.next = self.ps0.q.val();
        self.head1.next = self.ps1.q.val();
        self.head_c.next = self.pc.q.val();
        self.head_t3.next = self.pt3.q.val();
    }
}

crate::hw_block! {
    /// The Bézier texture-coordinate unit: lanes X, u, v ([`BezLane`]), X's comparison sums
    /// kept as registers, the pixel counter and the output register.
    pub struct TextureBezier(clock) as "texture-bezier" {
        summary: "per-line quadratic-Bézier texel (u, v) along a raster line by forward differences in t, a window of samples compared against the pixel centre, adders only (SPEC §16)",
        latency: 2 => "load to the line's first valid_out; one pixel per clock while a pixel moves the window by at most two samples",
        multipliers: 0,
        in {
            load: Bit, end_index: Bits<12>,
            x_step: Bits<48>, x_step2: Bits<48>,
            u_start: Bits<48>, u_step: Bits<48>, u_step2: Bits<48>,
            v_start: Bits<48>, v_step: Bits<48>, v_step2: Bits<48>,
            hold: Bit,
        }
        out { ready: Bit, valid_out: Bit, u: Bits<16>, v: Bits<16>, index: Bits<12>, done: Bit }
        /// 0: X, 1: u, 2: v.
        pub lane: [BezLane; 3],
        busy_q: DFF<Bit>, first_q: DFF<Bit>, end_q: DFF<Bits<12>>, i_q: DFF<Bits<12>>,
        /// m − j (the samples after the window's first), and whether it is at least 1, 2, 3.
        rem_q: DFF<Bits<13>>, g1_q: DFF<Bit>, g2_q: DFF<Bit>, g3_q: DFF<Bit>,
        /// rem − 1, rem − 2, rem − 3 (formed from the register, selected by r).
        rem_1: Signal<Local, Bits<13>>, rem_2: Signal<Local, Bits<13>>,
        rem_3: Signal<Local, Bits<13>>,
        /// rem ≥ t for t = 2 … 6 (the flags after a move by r are rem ≥ t + r).
        ge: [Signal<Local, Bit>; 5],
        lim: [Constant<Bits<13>>; 5] = [1u64, 2, 3, 4, 5].map(|t| Constant::new(t.into())),
        one12: Constant<Bits<12>> = Constant::new(1u64.into()),
        /// X(j + k − 1) + X(j + k) + ¬(2i·2^32) for k = 1, 2, 3, and 2·X(j + 3) + ¬(2i·2^32)
        /// and that − 2^33 (the next pixel's).
        p1_q: DFF<Bits<48>>, p2_q: DFF<Bits<48>>, p3_q: DFF<Bits<48>>,
        z_q: DFF<Bits<48>>, zm_q: DFF<Bits<48>>,
        valid_q: DFF<Bit>, u_q: DFF<Bits<16>>, v_q: DFF<Bits<16>>, index_q: DFF<Bits<12>>,
        done_q: DFF<Bit>,
        zero: Constant<Bits<48>> = Constant::new(0u64.into()),
        /// ¬(2·1·2^32) = −2^33 − 1 (the second pixel's), that − 2^33, and −2^33.
        k1: Constant<Bits<48>> = Constant::new(((1u64 << 48) - (1u64 << 33) - 1).into()),
        k1m: Constant<Bits<48>> = Constant::new(((1u64 << 48) - (1u64 << 34) - 1).into()),
        minus2: Constant<Bits<48>> = Constant::new(((1u64 << 48) - (1u64 << 33)).into()),
        /// The first pixel's clock: the sums for the second pixel (three-operand ones through
        /// one carry-save level and one adder, [`Add3`]).
        f_p1: Signal<Local, Bits<48>>, pub f_p2: Add3, pub f_p3: Add3,
        f_z: Signal<Local, Bits<48>>, f_zm: Signal<Local, Bits<48>>,
        /// Candidates: the sums less 2^33, the sums of samples beyond the window, z and zm next.
        p1m: Signal<Local, Bits<48>>, p2m: Signal<Local, Bits<48>>, p3m: Signal<Local, Bits<48>>,
        q4: Signal<Local, Bits<48>>, pub q5: Add3, pub q6: Add3,
        q4m: Signal<Local, Bits<48>>, pub q5m: Add3,
        zm_1: Signal<Local, Bits<48>>, zm_2: Signal<Local, Bits<48>>,
        zmm_0: Signal<Local, Bits<48>>, pub zmm_1: Add3, pub zmm_2: Add3,
        z_3: Signal<Local, Bits<48>>, zm_3: Signal<Local, Bits<48>>,
        /// The comparisons, r, and the clock's decisions.
        c1: Signal<Local, Bit>, c2: Signal<Local, Bit>, c3: Signal<Local, Bit>,
        r: Signal<Local, Bits<2>>, step_now: Signal<Local, Bit>, emit: Signal<Local, Bit>,
        is_last: Signal<Local, Bit>, rdy: Signal<Local, Bit>, take: Signal<Local, Bit>,
        /// The texels of sample j + r of u and v.
        su: Signal<Local, Bits<16>>, sv: Signal<Local, Bits<16>>,
    }
}

impl Logic for TextureBezier {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, busy_q, first_q, end_q, i_q, rem_q, g1_q, g2_q, g3_q, p1_q, p2_q, p3_q,
            z_q, zm_q, valid_q, u_q, v_q, index_q, done_q
        );
        // The comparisons are the sums' sign bits: r from registers alone.
        self.c1.next = self.p1_q.q.val().get_bit(47) & self.g1_q.q.val();
        self.c2.next = self.p2_q.q.val().get_bit(47) & self.g2_q.q.val();
        self.c3.next = self.p3_q.q.val().get_bit(47) & self.g3_q.q.val();
        for t in 0..5 {
            self.ge[t].next = self.rem_q.q.val() > self.lim[t].val();
        }
        self.rem_1.next = self.rem_q.q.val() - 1;
        self.rem_2.next = self.rem_q.q.val() - 2;
        self.rem_3.next = self.rem_q.q.val() - 3;
        self.r.next = 3.into();
        if self.first_q.q.val() | !self.c1.val() {
            self.r.next = 0.into();
        } else if !self.c2.val() {
            self.r.next = 1.into();
        } else if !self.c3.val() {
            self.r.next = 2.into();
        }
        self.is_last.next = self.i_q.q.val() == self.end_q.q.val();
        self.step_now.next = self.busy_q.q.val() & !self.hold.val();
        self.emit.next = self.step_now.val() & (self.r.val() != 3);
        self.rdy.next =
            !self.hold.val() & (!self.busy_q.q.val() | (self.emit.val() & self.is_last.val()));
        self.take.next = self.load.val() & self.rdy.val();
        for k in 0..3 {
            self.lane[k].clock.next = self.clock.val();
            self.lane[k].capture.next = self.load.val() & !(self.first_q.q.val() & self.hold.val());
            self.lane[k].first.next = self.first_q.q.val();
            self.lane[k].step_in.next = self.step_now.val() & !self.first_q.q.val();
            self.lane[k].r.next = self.r.val();
        }
        self.lane[0].start.next = self.zero.val();
        self.lane[0].step.next = self.x_step.val();
        self.lane[0].step2.next = self.x_step2.val();
        self.lane[1].start.next = self.u_start.val();
        self.lane[1].step.next = self.u_step.val();
        self.lane[1].step2.next = self.u_step2.val();
        self.lane[2].start.next = self.v_start.val();
        self.lane[2].step.next = self.v_step.val();
        self.lane[2].step2.next = self.v_step2.val();
        // The first pixel's clock: X's window is 0, Δ(0), 2Δ(0) + d, 3Δ(0) + 3d.
        self.f_p1.next = self.lane[0].head1.val() + self.k1.val();
        self.f_p2.a.next = self.lane[0].head1.val();
        self.f_p2.b.next = self.lane[0].head_c.val();
        self.f_p2.c.next = self.k1.val();
        self.f_p2.cin.next = false;
        self.f_p3.a.next = self.lane[0].head_c.val();
        self.f_p3.b.next = self.lane[0].head_t3.val();
        self.f_p3.c.next = self.k1.val();
        self.f_p3.cin.next = false;
        self.f_z.next = (self.lane[0].head_t3.val() << 1) + self.k1.val();
        self.f_zm.next = (self.lane[0].head_t3.val() << 1) + self.k1m.val();
        // Later pixels: every candidate one carry chain from the registers (a three-operand
        // sum through a carry-save level first).
        self.p1m.next = self.p1_q.q.val() + self.minus2.val();
        self.p2m.next = self.p2_q.q.val() + self.minus2.val();
        self.p3m.next = self.p3_q.q.val() + self.minus2.val();
        self.q4.next = self.z_q.q.val() + self.lane[0].d.val();
        self.q5.a.next = self.z_q.q.val();
        self.q5.b.next = self.lane[0].d.val();
        self.q5.c.next = self.lane[0].e2.val();
        self.q5.cin.next = false;
        self.q6.a.next = self.z_q.q.val();
        self.q6.b.next = self.lane[0].e2.val();
        self.q6.c.next = self.lane[0].e3.val();
        self.q6.cin.next = false;
        self.q4m.next = self.zm_q.q.val() + self.lane[0].d.val();
        self.q5m.a.next = self.zm_q.q.val();
        self.q5m.b.next = self.lane[0].d.val();
        self.q5m.c.next = self.lane[0].e2.val();
        self.q5m.cin.next = false;
        self.zm_1.next = self.zm_q.q.val() + (self.lane[0].d.val() << 1);
        self.zm_2.next = self.zm_q.q.val() + (self.lane[0].e2.val() << 1);
        self.zmm_0.next = self.zm_q.q.val() + self.minus2.val();
        self.zmm_1.a.next = self.zm_q.q.val();
        self.zmm_1.b.next = self.lane[0].d.val() << 1;
        self.zmm_1.c.next = self.minus2.val();
        self.zmm_1.cin.next = false;
        self.zmm_2.a.next = self.zm_q.q.val();
        self.zmm_2.b.next = self.lane[0].e2.val() << 1;
        self.zmm_2.c.next = self.minus2.val();
        self.zmm_2.cin.next = false;
        self.z_3.next = self.z_q.q.val() + (self.lane[0].e3.val() << 1);
        self.zm_3.next = self.zm_q.q.val() + (self.lane[0].e3.val() << 1);
        if self.first_q.q.val() {
            self.p1_q.d.next = self.f_p1.val();
            self.p2_q.d.next = self.f_p2.sum.val();
            self.p3_q.d.next = self.f_p3.sum.val();
            self.z_q.d.next = self.f_z.val();
            self.zm_q.d.next = self.f_zm.val();
        } else if self.step_now.val() {
            if self.r.val() == 0 {
                self.p1_q.d.next = self.p1m.val();
                self.p2_q.d.next = self.p2m.val();
                self.p3_q.d.next = self.p3m.val();
                self.z_q.d.next = self.zm_q.q.val();
                self.zm_q.d.next = self.zmm_0.val();
            } else if self.r.val() == 1 {
                self.p1_q.d.next = self.p2m.val();
                self.p2_q.d.next = self.p3m.val();
                self.p3_q.d.next = self.q4m.val();
                self.z_q.d.next = self.zm_1.val();
                self.zm_q.d.next = self.zmm_1.sum.val();
            } else if self.r.val() == 2 {
                self.p1_q.d.next = self.p3m.val();
                self.p2_q.d.next = self.q4m.val();
                self.p3_q.d.next = self.q5m.sum.val();
                self.z_q.d.next = self.zm_2.val();
                self.zm_q.d.next = self.zmm_2.sum.val();
            } else {
                self.p1_q.d.next = self.q4.val();
                self.p2_q.d.next = self.q5.sum.val();
                self.p3_q.d.next = self.q6.sum.val();
                self.z_q.d.next = self.z_3.val();
                self.zm_q.d.next = self.zm_3.val();
            }
        }
        // The texels: the first pixel's is the record's start; later ones sample j + r.
        self.su.next = self.lane[1].w0.val().get_bits::<16>(32);
        self.sv.next = self.lane[2].w0.val().get_bits::<16>(32);
        if self.first_q.q.val() {
            self.su.next = self.lane[1].head.val().get_bits::<16>(32);
            self.sv.next = self.lane[2].head.val().get_bits::<16>(32);
        } else if self.r.val() == 1 {
            self.su.next = self.lane[1].w1.val().get_bits::<16>(32);
            self.sv.next = self.lane[2].w1.val().get_bits::<16>(32);
        } else if self.r.val() == 2 {
            self.su.next = self.lane[1].w2.val().get_bits::<16>(32);
            self.sv.next = self.lane[2].w2.val().get_bits::<16>(32);
        }
        self.valid_q.d.next = self.emit.val();
        if self.emit.val() {
            self.first_q.d.next = false;
            self.u_q.d.next = self.su.val();
            self.v_q.d.next = self.sv.val();
            self.index_q.d.next = self.i_q.q.val();
            self.done_q.d.next = self.is_last.val();
            if self.is_last.val() {
                self.busy_q.d.next = false;
            } else {
                self.i_q.d.next = self.i_q.q.val() + 1;
            }
        }
        if self.step_now.val() {
            self.rem_q.d.next = self.rem_q.q.val();
            if self.r.val() == 1 {
                self.rem_q.d.next = self.rem_1.val();
                self.g1_q.d.next = self.ge[0].val();
                self.g2_q.d.next = self.ge[1].val();
                self.g3_q.d.next = self.ge[2].val();
            } else if self.r.val() == 2 {
                self.rem_q.d.next = self.rem_2.val();
                self.g1_q.d.next = self.ge[1].val();
                self.g2_q.d.next = self.ge[2].val();
                self.g3_q.d.next = self.ge[3].val();
            } else if self.r.val() == 3 {
                self.rem_q.d.next = self.rem_3.val();
                self.g1_q.d.next = self.ge[2].val();
                self.g2_q.d.next = self.ge[3].val();
                self.g3_q.d.next = self.ge[4].val();
            }
        }
        if self.take.val() {
            self.busy_q.d.next = true;
            self.first_q.d.next = true;
            self.end_q.d.next = self.end_index.val();
            self.i_q.d.next = 0.into();
            self.rem_q.d.next = bit_cast::<13, 12>(self.end_index.val()) << 1;
            // m = 2(n − 1) is at least 1 and 2 when n ≥ 2, at least 3 when n ≥ 3.
            self.g1_q.d.next = self.end_index.val() != 0;
            self.g2_q.d.next = self.end_index.val() != 0;
            self.g3_q.d.next = self.end_index.val() > self.one12.val();
        }
        self.ready.next = self.rdy.val();
        self.valid_out.next = self.valid_q.q.val();
        self.u.next = self.u_q.q.val();
        self.v.next = self.v_q.q.val();
        self.index.next = self.index_q.q.val();
        self.done.next = self.done_q.q.val();
    }
}

/// Texels a [`BezWalk`] keeps between the Bézier block and the walk's pixels.
pub const TEXEL_FIFO: usize = 4;

crate::hw_block! {
    /// The Bézier unit beside the address block's walk: the textured pipeline's
    /// `texture=bezier` coordinate (`textured_pipeline`). Its event side is the
    /// texture-coordinate block's (`texture_coord`): `valid_in` is the event shown, `ready`
    /// says it is taken this clock, `valid_out`, `u`, `v` show the pixel's texel 2 clocks after
    /// it was taken.
    ///
    /// Line records (the [`TextureBezier`] words) wait in the pipeline's line FIFO
    /// (`texture_quadratic::LineFifo`), one per raster line with a pixel, in the walk's order;
    /// the block sees its head (`line_any` and the words) and pops it with `pull`, which is the
    /// Bézier block's load taken. The Bézier block walks each line on its own, a texel per
    /// pixel in walk order, into a [`TEXEL_FIFO`]-entry texel FIFO; it is held while two or
    /// more texels wait (a held clock shows nothing in the next one, so at most three are ever
    /// in the FIFO). Each pixel the walk shows takes the FIFO's head texel: `ready` is low while
    /// a pixel is shown with the FIFO empty (a function of the registers and the event shown).
    /// Line starts and ends need nothing here: the texels come in the walk's pixel order.
    pub struct BezWalk(clock) {
        in {
            valid_in: Bit,
            line_any: Bit, us: Bits<48>, ud: Bits<48>, udd: Bits<48>,
            vs: Bits<48>, vd: Bits<48>, vdd: Bits<48>,
            last: Bits<12>, xd: Bits<48>, xdd: Bits<48>,
        }
        out { ready: Bit, pull: Bit, valid_out: Bit, u: Bits<16>, v: Bits<16> }
        pub bez: TextureBezier,
        occ: [DFF<Bit>; TEXEL_FIFO],
        t_u: [DFF<Bits<16>>; TEXEL_FIFO], t_v: [DFF<Bits<16>>; TEXEL_FIFO],
        /// The taken pixel's texel, then the output register.
        s_v: DFF<Bit>, s_u: DFF<Bits<16>>, s_w: DFF<Bits<16>>,
        out_v: DFF<Bit>, out_u: DFF<Bits<16>>, out_w: DFF<Bits<16>>,
        pix: Signal<Local, Bit>,
        kept: [Signal<Local, Bit>; TEXEL_FIFO],
        put: [Signal<Local, Bit>; TEXEL_FIFO],
    }
}

impl Logic for BezWalk {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, s_v, s_u, s_w, out_v, out_u, out_w);
        self.bez.clock.next = self.clock.val();
        for i in 0..4 {
            clock!(self, clock, occ[i], t_u[i], t_v[i]);
            self.kept[i].next = self.occ[i].q.val();
            self.t_u[i].d.next = self.t_u[i].q.val();
            self.t_v[i].d.next = self.t_v[i].q.val();
        }
        // The Bézier block: the head record loads when it is ready; held while two or more
        // texels wait.
        self.bez.load.next = self.line_any.val();
        self.bez.end_index.next = self.last.val();
        self.bez.x_step.next = self.xd.val();
        self.bez.x_step2.next = self.xdd.val();
        self.bez.u_start.next = self.us.val();
        self.bez.u_step.next = self.ud.val();
        self.bez.u_step2.next = self.udd.val();
        self.bez.v_start.next = self.vs.val();
        self.bez.v_step.next = self.vd.val();
        self.bez.v_step2.next = self.vdd.val();
        self.bez.hold.next = self.occ[1].q.val();
        self.pull.next = self.line_any.val() & self.bez.ready.val();
        // The walk's pixel takes the head texel.
        self.ready.next = !self.valid_in.val() | self.occ[0].q.val();
        self.pix.next = self.valid_in.val() & self.occ[0].q.val();
        for i in 0..3 {
            if self.pix.val() {
                self.kept[i].next = self.occ[i + 1].q.val();
                self.t_u[i].d.next = self.t_u[i + 1].q.val();
                self.t_v[i].d.next = self.t_v[i + 1].q.val();
            }
        }
        if self.pix.val() {
            self.kept[3].next = false;
        }
        self.put[0].next = self.bez.valid_out.val() & !self.kept[0].val();
        for i in 1..4 {
            self.put[i].next =
                self.bez.valid_out.val() & !self.kept[i].val() & self.kept[i - 1].val();
        }
        for i in 0..4 {
            self.occ[i].d.next = self.kept[i].val() | self.put[i].val();
            if self.put[i].val() {
                self.t_u[i].d.next = self.bez.u.val();
                self.t_v[i].d.next = self.bez.v.val();
            }
        }
        self.s_v.d.next = self.pix.val();
        self.s_u.d.next = self.t_u[0].q.val();
        self.s_w.d.next = self.t_v[0].q.val();
        self.out_v.d.next = self.s_v.q.val();
        self.out_u.d.next = self.s_u.q.val();
        self.out_w.d.next = self.s_w.q.val();
        self.valid_out.next = self.out_v.q.val();
        self.u.next = self.out_u.q.val();
        self.v.next = self.out_w.q.val();
    }
}
