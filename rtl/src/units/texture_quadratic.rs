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

/// Line records the [`QuadWalk`]'s FIFO holds.
pub const LINE_FIFO: usize = 4;

crate::hw_block! {
    /// The quadratic unit on the address block's walk, with the per-line set-up queued beside
    /// it: the textured pipeline's `texture=quadratic` coordinate (`textured_pipeline`). Its
    /// event side is the texture-coordinate block's (`texture_coord`): `valid_in`,
    /// `row_start_in` are the event shown, `ready` says it is taken this clock, `valid_out`,
    /// `u`, `v` show the pixel's texel 2 clocks after it was taken.
    ///
    /// Line records (`line_push` with u start, Δ, ΔΔ and v's, the [`TextureQuadratic`] words)
    /// go into a [`LINE_FIFO`]-entry FIFO (shift register, entry 0 the head; `line_ready`:
    /// not full, a function of the registers; a push while full is dropped). They come in the
    /// walk's order, one per raster line with a pixel. A line start sets `need`; the next
    /// pixel (the line's first) loads the unit with the head record and pops it, and `ready`
    /// is low while such a pixel is shown with the FIFO empty. Every other pixel steps the
    /// unit. `ready` is then a function of the registers and the event shown (the FIFO before
    /// the block keeps it out of the address block's `hold`).
    pub struct QuadWalk(clock) {
        in {
            line_push: Bit,
            line_u_start: Bits<48>, line_u_step: Bits<48>, line_u_step2: Bits<48>,
            line_v_start: Bits<48>, line_v_step: Bits<48>, line_v_step2: Bits<48>,
            valid_in: Bit, row_start_in: Bit,
        }
        out { ready: Bit, line_ready: Bit, valid_out: Bit, u: Bits<16>, v: Bits<16> }
        pub quad: TextureQuadratic,
        occ: [DFF<Bit>; LINE_FIFO],
        f_us: [DFF<Bits<48>>; LINE_FIFO], f_ud: [DFF<Bits<48>>; LINE_FIFO],
        f_udd: [DFF<Bits<48>>; LINE_FIFO], f_vs: [DFF<Bits<48>>; LINE_FIFO],
        f_vd: [DFF<Bits<48>>; LINE_FIFO], f_vdd: [DFF<Bits<48>>; LINE_FIFO],
        /// The next pixel is its line's first.
        need: DFF<Bit>,
        /// The output register (the texture-coordinate block's latency).
        out_v: DFF<Bit>, out_u: DFF<Bits<16>>, out_w: DFF<Bits<16>>,
        /// The pixel shown takes a line record; the pixel is taken; the record pops.
        want: Signal<Local, Bit>, pix: Signal<Local, Bit>, pull: Signal<Local, Bit>,
        kept: [Signal<Local, Bit>; LINE_FIFO],
        put: [Signal<Local, Bit>; LINE_FIFO],
    }
}

impl Logic for QuadWalk {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, need, out_v, out_u, out_w);
        self.quad.clock.next = self.clock.val();
        for i in 0..4 {
            clock!(self, clock, occ[i], f_us[i], f_ud[i], f_udd[i], f_vs[i], f_vd[i], f_vdd[i]);
        }
        self.want.next = self.valid_in.val() & (self.need.q.val() | self.row_start_in.val());
        self.ready.next = !self.want.val() | self.occ[0].q.val();
        self.pix.next = self.valid_in.val() & (!self.want.val() | self.occ[0].q.val());
        self.pull.next = self.want.val() & self.occ[0].q.val();
        if self.row_start_in.val() & self.ready.val() {
            self.need.d.next = true;
        }
        if self.pix.val() {
            self.need.d.next = false;
        }
        // The line FIFO: pop the head on a pull, push at the first free entry.
        for i in 0..4 {
            self.kept[i].next = self.occ[i].q.val();
        }
        for i in 0..3 {
            if self.pull.val() {
                self.kept[i].next = self.occ[i + 1].q.val();
            }
        }
        if self.pull.val() {
            self.kept[3].next = false;
        }
        self.put[0].next = self.line_push.val() & !self.kept[0].val();
        for i in 1..4 {
            self.put[i].next = self.line_push.val() & !self.kept[i].val() & self.kept[i - 1].val();
        }
        for i in 0..4 {
            self.occ[i].d.next = self.kept[i].val() | self.put[i].val();
        }
        for i in 0..4 {
            self.f_us[i].d.next = self.f_us[i].q.val();
            self.f_ud[i].d.next = self.f_ud[i].q.val();
            self.f_udd[i].d.next = self.f_udd[i].q.val();
            self.f_vs[i].d.next = self.f_vs[i].q.val();
            self.f_vd[i].d.next = self.f_vd[i].q.val();
            self.f_vdd[i].d.next = self.f_vdd[i].q.val();
        }
        for i in 0..3 {
            if self.pull.val() {
                self.f_us[i].d.next = self.f_us[i + 1].q.val();
                self.f_ud[i].d.next = self.f_ud[i + 1].q.val();
                self.f_udd[i].d.next = self.f_udd[i + 1].q.val();
                self.f_vs[i].d.next = self.f_vs[i + 1].q.val();
                self.f_vd[i].d.next = self.f_vd[i + 1].q.val();
                self.f_vdd[i].d.next = self.f_vdd[i + 1].q.val();
            }
        }
        for i in 0..4 {
            if self.put[i].val() {
                self.f_us[i].d.next = self.line_u_start.val();
                self.f_ud[i].d.next = self.line_u_step.val();
                self.f_udd[i].d.next = self.line_u_step2.val();
                self.f_vs[i].d.next = self.line_v_start.val();
                self.f_vd[i].d.next = self.line_v_step.val();
                self.f_vdd[i].d.next = self.line_v_step2.val();
            }
        }
        self.line_ready.next = !self.occ[3].q.val();
        // The unit: loaded by the line's first pixel with the head record, stepped by the
        // others.
        self.quad.valid_in.next = self.pix.val();
        self.quad.load.next = self.pull.val();
        self.quad.u_start.next = self.f_us[0].q.val();
        self.quad.u_step.next = self.f_ud[0].q.val();
        self.quad.u_step2.next = self.f_udd[0].q.val();
        self.quad.v_start.next = self.f_vs[0].q.val();
        self.quad.v_step.next = self.f_vd[0].q.val();
        self.quad.v_step2.next = self.f_vdd[0].q.val();
        self.out_v.d.next = self.quad.valid_out.val();
        self.out_u.d.next = self.quad.u.val();
        self.out_w.d.next = self.quad.v.val();
        self.valid_out.next = self.out_v.q.val();
        self.u.next = self.out_u.q.val();
        self.v.next = self.out_w.q.val();
    }
}
