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
