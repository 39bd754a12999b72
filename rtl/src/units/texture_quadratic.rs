//! Quadratic texture coordinate (SPEC §15): the texel (u, v) of each pixel along a raster line
//! from a per-line quadratic u = A1·x² + A2·x + A3 in raw screen x, stepped by second-order
//! forward differences: two additions per pixel and coordinate, no multiplier (golden:
//! `golden::units::texture_quadratic`, whose `QuadTwin` this block matches bit for bit every
//! clock).
//!
//! # Formula
//!
//! The set-up software fits the quadratic through three exact values of the line (its two
//! ends and an inner pixel; SPEC §15's ρ, A1, A2, A3) and hands the block, per line and
//! coordinate, u at the first pixel, Δ = u(x + dir) − u(x) there and ΔΔ = 2·A1. Per pixel:
//!
//! ```text
//!   first pixel of a line (load):  U ← u_start,  D ← u_step,  DD ← u_step2
//!   next pixel:                    U ← U + D,    D ← D + DD
//!   texel = ⌊U⌋                    (u_start carries +½: the nearest texel of u)
//! ```
//!
//! # Ports
//!
//! | port | bits | format |
//! |---|---|---|
//! | `valid_in` | 1 | a pixel of the line |
//! | `load` | 1 | with `valid_in`: the line's first pixel, take its set-up words |
//! | `u_start`, `u_step`, `u_step2` (and `v_…`) | 48 each | signed Q15.32: u + ½, Δ, ΔΔ |
//! | `valid_out` | 1 | `u`, `v` is the pixel's texel |
//! | `u`, `v` | 16 each | the texel ⌊U⌋, two's complement (not wrapped) |
//! | `u_word`, `v_word` | 48 each | U itself (signed Q15.32, +½), for the bench's format check |
//!
//! Words U, D, DD: signed Q15.32 in 48 bits, additions modulo 2^48 (U ∈ [−2^15, 2^15)
//! texels). Clocks with `valid_in` low freeze the recurrences.
//!
//! # Latency, throughput, handshake
//!
//! One pixel per clock, no stall: the texel of the pixel presented with `valid_in` in clock t
//! shows with `valid_out` in clock t + 1 (`valid_in`/`valid_out`, the span blocks' `load`).
//!
//! Latency (the block's `LATENCY`): 1 clock, valid_in to valid_out.
//!
//! # Overflow and error budget
//!
//! Modulo 2^48, exact on the words; the set-up's rounding of u, Δ, ΔΔ to 2^−32 puts the n-th
//! pixel of a line (n = 0 at the load) within 2^−33·(1 + n + n(n − 1)/2) of the f64 recurrence
//! (`golden::units::texture_quadratic::error_bound`: under 2^−9 texel on a 4096-pixel line).
//! The texel can then differ from the f64 quadratic's nearest texel only within that bound of
//! a half texel. The quadratic's own error against the perspective-correct u is the method's
//! (SPEC §15's table), not the block's.
//!
//! This file also holds two parts of `textured-pipeline`'s per-line builds, checked through
//! that pipeline's registry sets (`texture=quadratic`, `texture=bezier`): the line FIFO
//! [`LineFifo`] and [`QuadWalk`], this unit driven by the address block's walk.

use rust_hdl::prelude::*;

crate::hw_block! {
    /// One coordinate: U, D, DD and the output register.
    pub struct QuadLane(clock) {
        in { valid_in: Bit, load: Bit, start: Bits<48>, step: Bits<48>, step2: Bits<48> }
        out { word: Bits<48> }
        u_q: DFF<Bits<48>>, d_q: DFF<Bits<48>>, dd_q: DFF<Bits<48>>, out_q: DFF<Bits<48>>,
        /// U + D and D + DD, and U for this pixel.
        u_next: Signal<Local, Bits<48>>, d_next: Signal<Local, Bits<48>>,
        u_now: Signal<Local, Bits<48>>,
    }
}

impl Logic for QuadLane {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, u_q, d_q, dd_q, out_q);
        self.u_next.next = self.u_q.q.val() + self.d_q.q.val();
        self.d_next.next = self.d_q.q.val() + self.dd_q.q.val();
        self.u_now.next = self.u_next.val();
        if self.load.val() {
            self.u_now.next = self.start.val();
        }
        if self.valid_in.val() {
            self.u_q.d.next = self.u_now.val();
            self.out_q.d.next = self.u_now.val();
            self.d_q.d.next = self.d_next.val();
            if self.load.val() {
                self.d_q.d.next = self.step.val();
                self.dd_q.d.next = self.step2.val();
            }
        }
        self.word.next = self.out_q.q.val();
    }
}

crate::hw_block! {
    /// The quadratic texture-coordinate unit: a [`QuadLane`] for u and one for v.
    pub struct TextureQuadratic(clock) as "texture-quadratic" {
        summary: "per-line quadratic texel (u, v) along a raster line by second-order forward differences, two adds per pixel and coordinate (SPEC §15)",
        latency: 1 => "valid_in to valid_out, one pixel per clock",
        multipliers: 0,
        in {
            valid_in: Bit, load: Bit,
            u_start: Bits<48>, u_step: Bits<48>, u_step2: Bits<48>,
            v_start: Bits<48>, v_step: Bits<48>, v_step2: Bits<48>,
        }
        out { valid_out: Bit, u: Bits<16>, v: Bits<16>, u_word: Bits<48>, v_word: Bits<48> }
        /// 0: u, 1: v.
        pub lane: [QuadLane; 2],
        valid_q: DFF<Bit>,
    }
}

impl Logic for TextureQuadratic {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid_q);
        for i in 0..2 {
            self.lane[i].clock.next = self.clock.val();
            self.lane[i].valid_in.next = self.valid_in.val();
            self.lane[i].load.next = self.load.val();
        }
        self.lane[0].start.next = self.u_start.val();
        self.lane[0].step.next = self.u_step.val();
        self.lane[0].step2.next = self.u_step2.val();
        self.lane[1].start.next = self.v_start.val();
        self.lane[1].step.next = self.v_step.val();
        self.lane[1].step2.next = self.v_step2.val();
        self.valid_q.d.next = self.valid_in.val();
        self.valid_out.next = self.valid_q.q.val();
        self.u.next = self.lane[0].word.val().get_bits::<16>(32);
        self.v.next = self.lane[1].word.val().get_bits::<16>(32);
        self.u_word.next = self.lane[0].word.val();
        self.v_word.next = self.lane[1].word.val();
    }
}

/// Line records a [`LineFifo`] holds.
pub const LINE_FIFO: usize = 4;

crate::hw_block! {
    /// The textured pipeline's line FIFO (`textured_pipeline`'s quadratic and Bézier builds):
    /// [`LINE_FIFO`] line records in a ring, written at `wp`, read at `rp` (the head is the
    /// entry at `rp`: a pop moves `rp` and touches no record, so the consumer's decision
    /// reaches four register bits, not every word). A record is the `line_…` ports' words: u's
    /// and v's start, Δ, ΔΔ (both builds), the last pixel's index and X's Δ, ΔΔ (the Bézier
    /// build's; the quadratic one leaves them unread). `push` is taken when the FIFO is not
    /// full or a record is popped in the same clock (a push while full is dropped); `ready`:
    /// not full, `any`: not empty, both functions of the registers.
    pub struct LineFifo(clock) {
        in {
            push: Bit, pop: Bit,
            in_us: Bits<48>, in_ud: Bits<48>, in_udd: Bits<48>,
            in_vs: Bits<48>, in_vd: Bits<48>, in_vdd: Bits<48>,
            in_last: Bits<12>, in_xd: Bits<48>, in_xdd: Bits<48>,
        }
        out {
            ready: Bit, any: Bit,
            us: Bits<48>, ud: Bits<48>, udd: Bits<48>, vs: Bits<48>, vd: Bits<48>, vdd: Bits<48>,
            last: Bits<12>, xd: Bits<48>, xdd: Bits<48>,
        }
        f_us: [DFF<Bits<48>>; LINE_FIFO], f_ud: [DFF<Bits<48>>; LINE_FIFO],
        f_udd: [DFF<Bits<48>>; LINE_FIFO], f_vs: [DFF<Bits<48>>; LINE_FIFO],
        f_vd: [DFF<Bits<48>>; LINE_FIFO], f_vdd: [DFF<Bits<48>>; LINE_FIFO],
        f_last: [DFF<Bits<12>>; LINE_FIFO], f_xd: [DFF<Bits<48>>; LINE_FIFO],
        f_xdd: [DFF<Bits<48>>; LINE_FIFO],
        /// Write and read pointers, and the records held (0 … 4).
        wp: DFF<Bits<2>>, rp: DFF<Bits<2>>, count: DFF<Bits<3>>,
        go: Signal<Local, Bit>, put: Signal<Local, Bit>,
        four: Constant<Bits<3>> = Constant::new(4u64.into()),
        slot: [Constant<Bits<2>>; LINE_FIFO] = [0u64, 1, 2, 3].map(|k| Constant::new(k.into())),
    }
}

impl Logic for LineFifo {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, wp, rp, count);
        self.go.next = self.pop.val() & (self.count.q.val() != 0);
        self.put.next = self.push.val() & ((self.count.q.val() != self.four.val()) | self.go.val());
        for i in 0..4 {
            clock!(self, clock, f_us[i], f_ud[i], f_udd[i], f_vs[i], f_vd[i], f_vdd[i]);
            clock!(self, clock, f_last[i], f_xd[i], f_xdd[i]);
            self.f_us[i].d.next = self.f_us[i].q.val();
            self.f_ud[i].d.next = self.f_ud[i].q.val();
            self.f_udd[i].d.next = self.f_udd[i].q.val();
            self.f_vs[i].d.next = self.f_vs[i].q.val();
            self.f_vd[i].d.next = self.f_vd[i].q.val();
            self.f_vdd[i].d.next = self.f_vdd[i].q.val();
            self.f_last[i].d.next = self.f_last[i].q.val();
            self.f_xd[i].d.next = self.f_xd[i].q.val();
            self.f_xdd[i].d.next = self.f_xdd[i].q.val();
            if self.put.val() & (self.wp.q.val() == self.slot[i].val()) {
                self.f_us[i].d.next = self.in_us.val();
                self.f_ud[i].d.next = self.in_ud.val();
                self.f_udd[i].d.next = self.in_udd.val();
                self.f_vs[i].d.next = self.in_vs.val();
                self.f_vd[i].d.next = self.in_vd.val();
                self.f_vdd[i].d.next = self.in_vdd.val();
                self.f_last[i].d.next = self.in_last.val();
                self.f_xd[i].d.next = self.in_xd.val();
                self.f_xdd[i].d.next = self.in_xdd.val();
            }
        }
        if self.put.val() {
            self.wp.d.next = self.wp.q.val() + 1;
        }
        if self.go.val() {
            self.rp.d.next = self.rp.q.val() + 1;
        }
        if self.put.val() & !self.go.val() {
            self.count.d.next = self.count.q.val() + 1;
        } else if self.go.val() & !self.put.val() {
            self.count.d.next = self.count.q.val() - 1;
        }
        self.ready.next = self.count.q.val() != self.four.val();
        self.any.next = self.count.q.val() != 0;
        // The head: the entry at rp.
        self.us.next = self.f_us[0].q.val();
        self.ud.next = self.f_ud[0].q.val();
        self.udd.next = self.f_udd[0].q.val();
        self.vs.next = self.f_vs[0].q.val();
        self.vd.next = self.f_vd[0].q.val();
        self.vdd.next = self.f_vdd[0].q.val();
        self.last.next = self.f_last[0].q.val();
        self.xd.next = self.f_xd[0].q.val();
        self.xdd.next = self.f_xdd[0].q.val();
        for i in 1..4 {
            if self.rp.q.val() == self.slot[i].val() {
                self.us.next = self.f_us[i].q.val();
                self.ud.next = self.f_ud[i].q.val();
                self.udd.next = self.f_udd[i].q.val();
                self.vs.next = self.f_vs[i].q.val();
                self.vd.next = self.f_vd[i].q.val();
                self.vdd.next = self.f_vdd[i].q.val();
                self.last.next = self.f_last[i].q.val();
                self.xd.next = self.f_xd[i].q.val();
                self.xdd.next = self.f_xdd[i].q.val();
            }
        }
    }
}

crate::hw_block! {
    /// The quadratic unit on the address block's walk, with the per-line set-up queued beside
    /// it: the textured pipeline's `texture=quadratic` coordinate (`textured_pipeline`). Its
    /// event side is the texture-coordinate block's (`texture_coord`): `valid_in`,
    /// `row_start_in` are the event shown, `ready` says it is taken this clock, `valid_out`,
    /// `u`, `v` show the pixel's texel 2 clocks after it was taken.
    ///
    /// Line records (the [`TextureQuadratic`] words) wait in the pipeline's [`LineFifo`], one
    /// per raster line with a pixel, in the walk's order; the block sees its head (`line_any`
    /// and the words) and pops it with `pull`. A line start sets `need`; the next pixel (the
    /// line's first) loads the unit with the head record and pulls it, and `ready` is low while
    /// such a pixel is shown with the FIFO empty. Every other pixel steps the unit. `ready` is
    /// then a function of the registers and the event shown (the FIFO before the block keeps
    /// it out of the address block's `hold`).
    pub struct QuadWalk(clock) {
        in {
            valid_in: Bit, row_start_in: Bit,
            line_any: Bit, us: Bits<48>, ud: Bits<48>, udd: Bits<48>,
            vs: Bits<48>, vd: Bits<48>, vdd: Bits<48>,
        }
        out { ready: Bit, pull: Bit, valid_out: Bit, u: Bits<16>, v: Bits<16> }
        pub quad: TextureQuadratic,
        /// The next pixel is its line's first.
        need: DFF<Bit>,
        /// The output register (the texture-coordinate block's latency).
        out_v: DFF<Bit>, out_u: DFF<Bits<16>>, out_w: DFF<Bits<16>>,
        /// The pixel shown takes a line record; the pixel is taken; the record pops.
        want: Signal<Local, Bit>, pix: Signal<Local, Bit>,
    }
}

impl Logic for QuadWalk {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, need, out_v, out_u, out_w);
        self.quad.clock.next = self.clock.val();
        self.want.next = self.valid_in.val() & (self.need.q.val() | self.row_start_in.val());
        self.ready.next = !self.want.val() | self.line_any.val();
        self.pix.next = self.valid_in.val() & (!self.want.val() | self.line_any.val());
        self.pull.next = self.want.val() & self.line_any.val();
        if self.row_start_in.val() & self.ready.val() {
            self.need.d.next = true;
        }
        if self.pix.val() {
            self.need.d.next = false;
        }
        // The unit: loaded by the line's first pixel with the head record, stepped by the
        // others.
        self.quad.valid_in.next = self.pix.val();
        self.quad.load.next = self.pull.val();
        self.quad.u_start.next = self.us.val();
        self.quad.u_step.next = self.ud.val();
        self.quad.u_step2.next = self.udd.val();
        self.quad.v_start.next = self.vs.val();
        self.quad.v_step.next = self.vd.val();
        self.quad.v_step2.next = self.vdd.val();
        self.out_v.d.next = self.quad.valid_out.val();
        self.out_u.d.next = self.quad.u.val();
        self.out_w.d.next = self.quad.v.val();
        self.valid_out.next = self.out_v.q.val();
        self.u.next = self.out_u.q.val();
        self.v.next = self.out_w.q.val();
    }
}
