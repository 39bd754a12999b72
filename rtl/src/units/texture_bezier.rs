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
//! Each lane keeps a window of four samples j … j + 3, Δ(j + 3), d and 3d (registers). Three
//! comparisons side by side, X(j + k − 1) + X(j + k) ≤ 2i for k = 1, 2, 3 (sample j + k
//! existing), give r, the number that hold in a row. For r < 3 the block shows pixel i with
//! sample j + r, moves the window by r and goes to pixel i + 1; for r = 3 it moves the window
//! by 3 and shows nothing. The samples j + 4 … j + 6 beyond the window are w3 + Δ,
//! w3 + 2Δ + d and w3 + 3Δ + 3d, two adders deep; the comparison is the sign of
//! X(j + k − 1) + X(j + k) + ¬(2i·2^32), a three-operand sum. On a load the same adders form
//! the window from the line's words (samples 0 … 3).
//!
//! # Ports
//!
//! | port | bits | format |
//! |---|---|---|
//! | `load` | 1 | take a line's record (when `ready`) |
//! | `end_index` | 12 | n − 1, the line's last pixel index (n ≤ 4096) |
//! | `x_start`, `x_step`, `x_step2` | 48 each | signed Q15.32: X(0) = 0, Δ(0), d |
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

use rust_hdl::prelude::*;

crate::hw_block! {
    /// One lane: the window of samples j … j + 3, Δ(j + 3), d and 3d.
    pub struct BezLane(clock) {
        in {
            load: Bit, step_in: Bit, r: Bits<2>,
            start: Bits<48>, step: Bits<48>, step2: Bits<48>,
        }
        out { w0: Bits<48>, w1: Bits<48>, w2: Bits<48>, w3: Bits<48> }
        w0_q: DFF<Bits<48>>, w1_q: DFF<Bits<48>>, w2_q: DFF<Bits<48>>, w3_q: DFF<Bits<48>>,
        d_q: DFF<Bits<48>>, dd_q: DFF<Bits<48>>, dd3_q: DFF<Bits<48>>,
        /// The adders' operands: the window's last sample, Δ, d, 3d (or the load's words).
        base: Signal<Local, Bits<48>>, bd: Signal<Local, Bits<48>>,
        bdd: Signal<Local, Bits<48>>, bdd3: Signal<Local, Bits<48>>,
        two_bd: Signal<Local, Bits<48>>, dd3_in: Signal<Local, Bits<48>>,
        /// Samples j + 4, j + 5, j + 6.
        x4: Signal<Local, Bits<48>>, x5: Signal<Local, Bits<48>>, x6: Signal<Local, Bits<48>>,
        /// Δ after a move by 1, 2, 3 (3: also the load's Δ(3)).
        d_p1: Signal<Local, Bits<48>>, d_p2: Signal<Local, Bits<48>>, d_p3: Signal<Local, Bits<48>>,
    }
}

impl Logic for BezLane {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, w0_q, w1_q, w2_q, w3_q, d_q, dd_q, dd3_q);
        self.dd3_in.next = self.step2.val() + (self.step2.val() << 1);
        self.base.next = self.w3_q.q.val();
        self.bd.next = self.d_q.q.val();
        self.bdd.next = self.dd_q.q.val();
        self.bdd3.next = self.dd3_q.q.val();
        if self.load.val() {
            self.base.next = self.start.val();
            self.bd.next = self.step.val();
            self.bdd.next = self.step2.val();
            self.bdd3.next = self.dd3_in.val();
        }
        self.two_bd.next = self.bd.val() << 1;
        self.x4.next = self.base.val() + self.bd.val();
        self.x5.next = self.base.val() + self.two_bd.val() + self.bdd.val();
        self.x6.next = self.x4.val() + self.two_bd.val() + self.bdd3.val();
        self.d_p1.next = self.d_q.q.val() + self.dd_q.q.val();
        self.d_p2.next = self.d_q.q.val() + (self.dd_q.q.val() << 1);
        self.d_p3.next = self.bd.val() + self.bdd3.val();
        if self.load.val() {
            self.w0_q.d.next = self.start.val();
            self.w1_q.d.next = self.x4.val();
            self.w2_q.d.next = self.x5.val();
            self.w3_q.d.next = self.x6.val();
            self.d_q.d.next = self.d_p3.val();
            self.dd_q.d.next = self.step2.val();
            self.dd3_q.d.next = self.dd3_in.val();
        } else if self.step_in.val() {
            if self.r.val() == 1 {
                self.w0_q.d.next = self.w1_q.q.val();
                self.w1_q.d.next = self.w2_q.q.val();
                self.w2_q.d.next = self.w3_q.q.val();
                self.w3_q.d.next = self.x4.val();
                self.d_q.d.next = self.d_p1.val();
            } else if self.r.val() == 2 {
                self.w0_q.d.next = self.w2_q.q.val();
                self.w1_q.d.next = self.w3_q.q.val();
                self.w2_q.d.next = self.x4.val();
                self.w3_q.d.next = self.x5.val();
                self.d_q.d.next = self.d_p2.val();
            } else if self.r.val() == 3 {
                self.w0_q.d.next = self.w3_q.q.val();
                self.w1_q.d.next = self.x4.val();
                self.w2_q.d.next = self.x5.val();
                self.w3_q.d.next = self.x6.val();
                self.d_q.d.next = self.d_p3.val();
            }
        }
        self.w0.next = self.w0_q.q.val();
        self.w1.next = self.w1_q.q.val();
        self.w2.next = self.w2_q.q.val();
        self.w3.next = self.w3_q.q.val();
    }
}

crate::hw_block! {
    /// The Bézier texture-coordinate unit: lanes X, u, v ([`BezLane`]), the comparisons, the
    /// pixel counter and the output register.
    pub struct TextureBezier(clock) as "texture-bezier" {
        summary: "per-line quadratic-Bézier texel (u, v) along a raster line by forward differences in t, a window of samples compared against the pixel centre, adders only (SPEC §16)",
        latency: 2 => "load to the line's first valid_out; one pixel per clock while a pixel moves the window by at most two samples",
        multipliers: 0,
        in {
            load: Bit, end_index: Bits<12>,
            x_start: Bits<48>, x_step: Bits<48>, x_step2: Bits<48>,
            u_start: Bits<48>, u_step: Bits<48>, u_step2: Bits<48>,
            v_start: Bits<48>, v_step: Bits<48>, v_step2: Bits<48>,
            hold: Bit,
        }
        out { ready: Bit, valid_out: Bit, u: Bits<16>, v: Bits<16>, index: Bits<12>, done: Bit }
        /// 0: X, 1: u, 2: v.
        pub lane: [BezLane; 3],
        busy_q: DFF<Bit>, end_q: DFF<Bits<12>>, i_q: DFF<Bits<12>>,
        /// ¬(2i·2^32) and m − j (the samples after the window's first).
        ni_q: DFF<Bits<48>>, rem_q: DFF<Bits<13>>,
        valid_q: DFF<Bit>, u_q: DFF<Bits<16>>, v_q: DFF<Bits<16>>, index_q: DFF<Bits<12>>,
        done_q: DFF<Bit>,
        ni_step: Constant<Bits<48>> = Constant::new((1u64 << 33).into()),
        ones: Constant<Bits<48>> = Constant::new(((1u64 << 48) - 1).into()),
        /// The three comparisons' sums and outcomes, r, and the clock's decisions.
        s1: Signal<Local, Bits<48>>, s2: Signal<Local, Bits<48>>, s3: Signal<Local, Bits<48>>,
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
            self, clock, busy_q, end_q, i_q, ni_q, rem_q, valid_q, u_q, v_q, index_q, done_q
        );
        self.s1.next = self.lane[0].w0.val() + self.lane[0].w1.val() + self.ni_q.q.val();
        self.s2.next = self.lane[0].w1.val() + self.lane[0].w2.val() + self.ni_q.q.val();
        self.s3.next = self.lane[0].w2.val() + self.lane[0].w3.val() + self.ni_q.q.val();
        self.c1.next = self.s1.val().get_bit(47) & (self.rem_q.q.val() != 0);
        self.c2.next =
            self.s2.val().get_bit(47) & (self.rem_q.q.val() != 0) & (self.rem_q.q.val() != 1);
        self.c3.next = self.s3.val().get_bit(47)
            & (self.rem_q.q.val() != 0)
            & (self.rem_q.q.val() != 1)
            & (self.rem_q.q.val() != 2);
        self.r.next = 3.into();
        if !self.c1.val() {
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
            self.lane[k].load.next = self.take.val();
            self.lane[k].step_in.next = self.step_now.val();
            self.lane[k].r.next = self.r.val();
        }
        self.lane[0].start.next = self.x_start.val();
        self.lane[0].step.next = self.x_step.val();
        self.lane[0].step2.next = self.x_step2.val();
        self.lane[1].start.next = self.u_start.val();
        self.lane[1].step.next = self.u_step.val();
        self.lane[1].step2.next = self.u_step2.val();
        self.lane[2].start.next = self.v_start.val();
        self.lane[2].step.next = self.v_step.val();
        self.lane[2].step2.next = self.v_step2.val();
        self.su.next = self.lane[1].w0.val().get_bits::<16>(32);
        self.sv.next = self.lane[2].w0.val().get_bits::<16>(32);
        if self.r.val() == 1 {
            self.su.next = self.lane[1].w1.val().get_bits::<16>(32);
            self.sv.next = self.lane[2].w1.val().get_bits::<16>(32);
        } else if self.r.val() == 2 {
            self.su.next = self.lane[1].w2.val().get_bits::<16>(32);
            self.sv.next = self.lane[2].w2.val().get_bits::<16>(32);
        }
        self.valid_q.d.next = self.emit.val();
        if self.emit.val() {
            self.u_q.d.next = self.su.val();
            self.v_q.d.next = self.sv.val();
            self.index_q.d.next = self.i_q.q.val();
            self.done_q.d.next = self.is_last.val();
            if self.is_last.val() {
                self.busy_q.d.next = false;
            } else {
                self.i_q.d.next = self.i_q.q.val() + 1;
                self.ni_q.d.next = self.ni_q.q.val() - self.ni_step.val();
            }
        }
        if self.step_now.val() {
            self.rem_q.d.next = self.rem_q.q.val() - bit_cast::<13, 2>(self.r.val());
        }
        if self.take.val() {
            self.busy_q.d.next = true;
            self.end_q.d.next = self.end_index.val();
            self.i_q.d.next = 0.into();
            self.ni_q.d.next = self.ones.val();
            self.rem_q.d.next = bit_cast::<13, 12>(self.end_index.val()) << 1;
        }
        self.ready.next = self.rdy.val();
        self.valid_out.next = self.valid_q.q.val();
        self.u.next = self.u_q.q.val();
        self.v.next = self.v_q.q.val();
        self.index.next = self.index_q.q.val();
        self.done.next = self.done_q.q.val();
    }
}
