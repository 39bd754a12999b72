//! The quadric forward-difference unit (SPEC §8; golden: `golden::quadric_unit`): quadric
//! shading along a raster line, three colour channels, two pixels per clock, adds and shifts
//! only.
//!
//! ```text
//! I(x, y) = A·x² + B·y² + C·x·y + D·x + E·y + F        (per channel; set-up per triangle)
//! I_{k+2} = 2·I_{k+1} − I_k + 2A                        (2.5)
//! I_{k+3} = 3·I_{k+1} − 2·I_k + 6A                      (2.5) applied twice
//! ```
//! The six coefficients per channel are solved per triangle in software (the golden set-up);
//! the line's first two pixels come from the direct form (2.2) and (2.3) in the span front end
//! — the thesis notes the direct form is always needed at a line start, and with it the y terms
//! (B·y², C·y, E·y) of the line are folded into I0 and I1 there. The unit then holds the pair
//! (I_k, I_{k+1}) per channel and steps it to (I_{k+2}, I_{k+3}) each clock: pixels k and
//! k + 1 in lanes A and B. Per channel and not per lighting term: the quadric is fitted to the
//! lit intensity (the thesis' form), so there is nothing left to combine.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a line's words (taken when `ready`) |
//! | `y`, `x0`, `dir`, `m` | in | the line: y, first pixel's x, 1 = leftward (x0 − t), pixels − 1 |
//! | `r0 r1 ra`, `g0 g1 ga`, `b0 b1 ba` | in | per channel I(x0), I(x0 + d), 2A: signed Q34.30 (64 bits), LSB units |
//! | `z0`, `dz` | in | depth at pixel 0 and per pixel step, signed Q16.16 |
//! | `ready` | out | a `load` now follows the current line without a gap |
//! | `valid_a`, `x_a`, `z_a`, `red_a` … | out | lane A: pixel 2j in the line's clock j |
//! | `valid_b`, `x_b`, `z_b`, `red_b` … | out | lane B: pixel 2j + 1 (when ≤ m) |
//! | `y_out`, `last` | out | the line; its last clock |
//!
//! # Latency, throughput
//! Load → first pixels 2 clocks (state, output register). ⌊m/2⌋ + 1 clocks per line, the next
//! line's load taken in its last clock: two pixels per clock, one in the last clock of an
//! odd-length line; 0 clocks per line.
//!
//! # Overflow
//! The recurrence is exact modulo 2⁶⁴ (it must not saturate: each word feeds the next, and its
//! intermediates may wrap harmlessly); the span front end rejects a line whose intensities leave
//! ±2³¹ LSB (`golden::quadric_unit::RANGE`; the words hold ±2³³ — a quadric fitted on a sliver
//! overshoots wildly at pixel centres just outside it), so the values themselves never wrap.
//! Outputs saturate to 0..=255.
//!
//! # Error budget (vs `golden::quadric::row_kernel`, f64)
//! The words' rounding (2⁻³¹ each) grows along the line as δI0 + k·δΔ + k²/2·δ(2A): ≤ 0.004 LSB
//! at k = 4095; the output rounding ½ LSB.

use rust_hdl::prelude::*;

crate::hw_block! {
    /// A Q34.30 word (64 bits) → 8 bits: +2²⁹, drop 30, saturate to 0..=255. Combinational.
    pub struct RoundSat8Q30 {
        in { v: Bits<64> }
        out { q: Bits<8> }
        half: Constant<Bits<64>> = Constant::new((1u64 << 29).into()),
        rnd: Signal<Local, Bits<64>>,
    }
}

impl Logic for RoundSat8Q30 {
    #[hdl_gen]
    fn update(&mut self) {
        self.rnd.next = self.v.val() + self.half.val();
        if self.rnd.val().get_bit(63) {
            self.q.next = 0.into();
        } else if self.rnd.val().get_bits::<25>(38).any() {
            self.q.next = 255.into();
        } else {
            self.q.next = self.rnd.val().get_bits::<8>(30);
        }
    }
}

crate::hw_block! {
    /// The quadric forward-difference unit (see the module header).
    pub struct QuadricUnit(clock) as "quadric-unit" {
        summary: "a raster line's I(x0), I(x0 + d), 2A per channel in, quadric-shaded fragments out two per clock by forward differences, adds and shifts only (SPEC §8)",
        latency: 2 => "load to the first two pixels, two pixels per clock",
        multipliers: 0,
        in {
            load: Bit, span_base_ports!,
            r0: Bits<64>, r1: Bits<64>, ra: Bits<64>,
            g0: Bits<64>, g1: Bits<64>, ga: Bits<64>,
            b0: Bits<64>, b1: Bits<64>, ba: Bits<64>,
            z0: Bits<32>, dz: Bits<32>,
        }
        out {
            ready: Bit,
            valid_a: Bit, x_a: Bits<12>, z_a: Bits<32>, red_a: Bits<8>, green_a: Bits<8>, blue_a: Bits<8>,
            valid_b: Bit, x_b: Bits<12>, z_b: Bits<32>, red_b: Bits<8>, green_b: Bits<8>, blue_b: Bits<8>,
            y_out: Bits<12>, last: Bit,
        }
        // State.
        busy: DFF<Bit>, t_q: DFF<Bits<13>>, m_q: DFF<Bits<13>>, x0_q: DFF<Bits<12>>,
        y_q: DFF<Bits<12>>, dir_q: DFF<Bit>,
        p: [DFF<Bits<64>>; 3], q: [DFF<Bits<64>>; 3], a2: [DFF<Bits<64>>; 3],
        za: DFF<Bits<32>>, zb: DFF<Bits<32>>, dz_q: DFF<Bits<32>>,
        t2: Signal<Local, Bits<13>>, t1: Signal<Local, Bits<13>>,
        is_last: Signal<Local, Bit>, vb: Signal<Local, Bit>, rdy: Signal<Local, Bit>,
        xa: Signal<Local, Bits<12>>, xb: Signal<Local, Bits<12>>,
        sat_a: [RoundSat8Q30; 3], sat_b: [RoundSat8Q30; 3],
        // Output register.
        o_va: DFF<Bit>, o_xa: DFF<Bits<12>>, o_za: DFF<Bits<32>>, o_ca: [DFF<Bits<8>>; 3],
        o_vb: DFF<Bit>, o_xb: DFF<Bits<12>>, o_zb: DFF<Bits<32>>, o_cb: [DFF<Bits<8>>; 3],
        o_y: DFF<Bits<12>>, o_l: DFF<Bit>,
    }
}

impl Logic for QuadricUnit {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, busy, t_q, m_q, x0_q, y_q, dir_q, za, zb, dz_q);
        clock!(self, clock, o_va, o_xa, o_za, o_vb, o_xb, o_zb, o_y, o_l);
        for c in 0..3 {
            self.p[c].clock.next = self.clock.val();
            self.q[c].clock.next = self.clock.val();
            self.a2[c].clock.next = self.clock.val();
            self.p[c].d.next = self.p[c].q.val();
            self.q[c].d.next = self.q[c].q.val();
            self.a2[c].d.next = self.a2[c].q.val();
            self.o_ca[c].clock.next = self.clock.val();
            self.o_cb[c].clock.next = self.clock.val();
        }
        self.t1.next = self.t_q.q.val() + 1;
        self.t2.next = self.t_q.q.val() + 2;
        self.is_last.next = self.t2.val() > self.m_q.q.val();
        self.vb.next = self.busy.q.val() & (self.t_q.q.val() < self.m_q.q.val());
        self.rdy.next = !self.busy.q.val() | self.is_last.val();

        // Output register: both lanes, from the state.
        self.xa.next = self.x0_q.q.val() + self.t_q.q.val().get_bits::<12>(0);
        self.xb.next = self.x0_q.q.val() + self.t1.val().get_bits::<12>(0);
        if self.dir_q.q.val() {
            self.xa.next = self.x0_q.q.val() - self.t_q.q.val().get_bits::<12>(0);
            self.xb.next = self.x0_q.q.val() - self.t1.val().get_bits::<12>(0);
        }
        for c in 0..3 {
            self.sat_a[c].v.next = self.p[c].q.val();
            self.sat_b[c].v.next = self.q[c].q.val();
            self.o_ca[c].d.next = self.sat_a[c].q.val();
            self.o_cb[c].d.next = self.sat_b[c].q.val();
        }
        self.o_va.d.next = self.busy.q.val();
        self.o_xa.d.next = self.xa.val();
        self.o_za.d.next = self.za.q.val();
        self.o_vb.d.next = self.vb.val();
        self.o_xb.d.next = self.xb.val();
        self.o_zb.d.next = self.zb.q.val();
        self.o_y.d.next = self.y_q.q.val();
        self.o_l.d.next = self.busy.q.val() & self.is_last.val();

        // Step the pairs: I_{k+2} = 2·I_{k+1} − I_k + 2A, I_{k+3} = 3·I_{k+1} − 2·I_k + 6A.
        if self.busy.q.val() {
            if self.is_last.val() {
                self.busy.d.next = false;
            } else {
                for c in 0..3 {
                    self.p[c].d.next =
                        (self.q[c].q.val() << 1) - self.p[c].q.val() + self.a2[c].q.val();
                    self.q[c].d.next = (self.q[c].q.val() << 1) + self.q[c].q.val()
                        - (self.p[c].q.val() << 1)
                        + (self.a2[c].q.val() << 1)
                        + self.a2[c].q.val();
                }
                self.t_q.d.next = self.t2.val();
                self.za.d.next = self.za.q.val() + (self.dz_q.q.val() << 1);
                self.zb.d.next = self.zb.q.val() + (self.dz_q.q.val() << 1);
            }
        }
        if self.load.val() & self.rdy.val() {
            self.busy.d.next = true;
            self.t_q.d.next = 0.into();
            self.m_q.d.next = bit_cast::<13, 12>(self.m.val());
            self.x0_q.d.next = self.x0.val();
            self.y_q.d.next = self.y.val();
            self.dir_q.d.next = self.dir.val();
            self.p[0].d.next = self.r0.val();
            self.q[0].d.next = self.r1.val();
            self.a2[0].d.next = self.ra.val();
            self.p[1].d.next = self.g0.val();
            self.q[1].d.next = self.g1.val();
            self.a2[1].d.next = self.ga.val();
            self.p[2].d.next = self.b0.val();
            self.q[2].d.next = self.b1.val();
            self.a2[2].d.next = self.ba.val();
            self.za.d.next = self.z0.val();
            self.zb.d.next = self.z0.val() + self.dz.val();
            self.dz_q.d.next = self.dz.val();
        }

        self.ready.next = self.rdy.val();
        self.valid_a.next = self.o_va.q.val();
        self.x_a.next = self.o_xa.q.val();
        self.z_a.next = self.o_za.q.val();
        self.red_a.next = self.o_ca[0].q.val();
        self.green_a.next = self.o_ca[1].q.val();
        self.blue_a.next = self.o_ca[2].q.val();
        self.valid_b.next = self.o_vb.q.val();
        self.x_b.next = self.o_xb.q.val();
        self.z_b.next = self.o_zb.q.val();
        self.red_b.next = self.o_cb[0].q.val();
        self.green_b.next = self.o_cb[1].q.val();
        self.blue_b.next = self.o_cb[2].q.val();
        self.y_out.next = self.o_y.q.val();
        self.last.next = self.o_l.q.val();
    }
}
