//! The quadric forward-difference unit (SPEC §8; golden: `golden::quadric_unit`): quadric
//! shading by adds and shifts only — a 2-D difference tracker that moves from line start to
//! line start with the y terms, and a line generator giving two pixels per clock — for three
//! colour channels.
//!
//! ```text
//! I(x, y) = A·x² + B·y² + C·x·y + D·x + E·y + F        per channel, solved per triangle (software)
//! tracker at a line start:  I, Dx = I(x+1) − I(x), Dy = I(y+1) − I(y)
//!   y-step  I += Dy   Dy += 2B   Dx += C               (the y terms)
//!   x-step  I += Dx   Dx += 2A   Dy += C               (and −1, ±2: shifts and adds)
//! line generator (2.5):  (I_k, I_{k+1}) → (2·I_{k+1} − I_k + 2A, 3·I_{k+1} − 2·I_k + 6A)
//! ```
//! Set-up per triangle (software, the golden set-up code): the six coefficients, then I, Dx, Dy
//! at the first line's first pixel by the direct forms (2.2), (2.3) — once per triangle — and
//! 2A, 2B, C; loaded with the triangle's first line (`first`). Every later line start is reached
//! by the tracker: one y-step at the line's load, then x-steps of up to two pixels per clock to
//! the line's x0 (the walk's line start, from the address block's edge walk). The tracker works
//! on the next line while the generator emits the current one; the hand-over takes the
//! tracker's I and its first difference in the line's direction (I + Dx rightward,
//! I − Dx + 2A leftward) as the generator's pair. Per channel and not per lighting term: the
//! quadric is fitted to the lit intensity (the thesis' form), so nothing is left to combine.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a line (taken when `ready`) |
//! | `y`, `x0`, `dir`, `m` | in | the line: y, first pixel's x, 1 = leftward (x0 − t), pixels − 1 |
//! | `first` | in | the triangle's first line: the words below are loaded into the tracker |
//! | `ri rdx rdy ra rb rc`, `g…`, `b…` | in | per channel I, Dx, Dy at that line's first pixel, 2A, 2B, C: signed Q34.30 (64 bits), LSB units |
//! | `z0`, `dz` | in | depth at the line's pixel 0 and per pixel step, signed Q16.16 |
//! | `hold` | in | 1: the generator stands still this clock (no step, no hand-over, so a tracker waiting to hand over keeps `ready` low) and the next clock's outputs carry no pixel; nothing is lost or repeated — the pixels come one clock per clock without `hold` (a stream top's back-pressure) |
//! | `ready` | out | the tracker takes a line this clock |
//! | `valid_a`, `x_a`, `z_a`, `red_a` … | out | lane A: pixel 2j in the line's clock j |
//! | `valid_b`, `x_b`, `z_b`, `red_b` … | out | lane B: pixel 2j + 1 (when ≤ m) |
//! | `y_out`, `last` | out | the line; its last clock |
//!
//! # Latency, throughput
//! A line is taken in the clock the tracker hands its previous line over (or when idle), reaches
//! its start after ⌈|Δx0|/2⌉ clocks of x-steps (the y-step rides on the load), and is handed to
//! the generator when that finishes its line: per line max(⌊m/2⌋ + 1, 1 + ⌈|Δx0|/2⌉) clocks,
//! two pixels per clock on lines longer than their start's move. Load → first pixels of a
//! triangle's first line: 3 clocks (load, hand-over, output register). Each clock with `hold`
//! high delays everything the generator has yet to show by one clock; the tracker still moves
//! to its line's start meanwhile.
//!
//! Timing: the decisions come from registers: the distance to the line start (lx0 − tx) is
//! a register, and three flags (zero, negative, two or more pixels) of it, as are ty = ly, the
//! generator's last clock and the hand-over, so no compare precedes the 576 word multiplexers
//! they steer. Each flag's next value is formed per case (a load, an x-step, a y-step, the
//! generator's step or hand-over) and the control only selects; after an x-step the flags
//! follow from compares on the distance register (a 1-pixel step reaches the start, a 2-pixel
//! one leaves d ∓ 2), without a carry chain. Every three-operand add is one carry-save level
//! (full adders bit by bit; a subtraction's +1 in the carry word's free bit 0) and one carry
//! chain: the x-step of I is a single such add, I + T1 + T2 with the terms (Dx, 2·Dx + 2A,
//! −Dx + 2A, −2·Dx + 3·2A) selected by the registered flags, so the word multiplexer after the
//! chain chooses only among the x-step, the y-step and the load; Dx and Dy, two-operand, form
//! their four outcomes in parallel and select after the chain. The generator keeps the pair's
//! difference e = q − p and 3·2A as registers, so p' = q + e + 2A and q' = q + 2e + 3·2A are
//! three-operand adds too (they were 3q − 2p + 3·2A, a five-operand sum).
//! ECP5: 55.7 MHz (operands selected before two chained 64-bit adds) → 88.1 (registered flags;
//! 11 566 LUT4; path: the +2 x-step's I + 2·Dx + 2A, two carry chains) → 93.6 MHz (placer seeds
//! 2, 3: 92.0, 90.1; 11 013 LUT4; with `hold`: 97.5, seeds 2, 3: 92.4, 91.8, 11 080 LUT4);
//! what is left is routing — 6.6 ns of the 10.68 ns path
//! f_neg → term selects → carry chain → I: the flag's fan-out to the 3 × 192 term selects, and
//! from the chain to I's word multiplexer.
//! Tried on this netlist and not kept (placer seed 1, the exported Verilog edited by hand; the
//! first, second and fourth repeat probes of an earlier session, README: 91.5–96.7, 87.9 (in
//! RTL) and 97.2 MHz then — placement alone moves these figures by several MHz):
//! - each channel with its own copy of the step flags (one inverted, one ANDed with `tbusy`:
//!   Yosys merges identical flip-flops): 96.5 MHz, the path moved to tdx → xi_k → carry chain;
//! - the x-step's four outcomes of I formed in parallel and selected after the chains, as for
//!   Dx: 83.2 MHz (I's word multiplexer became three LUT levels);
//! - `synth_ecp5 -abc9`: 96.2 MHz, 9 985 LUT4 (against 11 080; two per carry cell);
//! - I's x-step without its carry chain (an XOR, to find the next path): 92.8 MHz, on the
//!   load's y compare → f_yat → f_hand;
//! - the tracker's I in carry-save form (two words; the x- and y-steps without a carry chain,
//!   the hand-over resolving it): 90.2 MHz, 13 139 LUT4; the path moved to Dx, 11.09 ns:
//!   tdx → dx_m1's carry chain → four LUT levels of tdx's select;
//! - x-steps of one pixel only (the two-pixel flag tied to 0, which would change the
//!   tracker's timing): 97.7 MHz, 9 051 LUT4, on neg → xi_s (one LUT level) → carry chain →
//!   ti, 10.24 ns (4.16 of it logic).
//!
//! So several kinds of path (I's step, Dx's step, the load's flags) sit between 10.2 and
//! 11.1 ns, 6–8 ns of it routing; moving one brings up the next. A 64-bit carry chain is
//! 2.3 ns of each: what would be left is to split the words' adds at bit 32 with the carry
//! between the halves registered, and to resolve a word only where it leaves the tracker.
//!
//! # Overflow
//! Every update is an exact integer add modulo 2⁶⁴ (nothing may saturate: each word feeds the
//! next; intermediates may wrap harmlessly, the values equal the exact quadric of the words
//! modulo 2⁶⁴); the span front end rejects a line whose intensities or coefficients leave ±2³¹
//! LSB (`golden::quadric_unit::RANGE`; the words hold ±2³³ — a quadric fitted on a sliver
//! overshoots wildly at pixel centres just outside it), so the values themselves never wrap.
//! Outputs saturate to 0..=255.
//!
//! # Error budget (vs `golden::quadric::row_kernel`, f64)
//! The words' rounding (2⁻³¹ each) grows with the walk as a quadratic in the distance: ≤ 1.5·N²·2⁻³¹
//! for a triangle N pixels across (≤ 0.012 LSB at N = 4096); the output rounding ½ LSB.

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
        summary: "a triangle's I, Dx, Dy, 2A, 2B, C per channel and its raster lines in, quadric-shaded fragments out two per clock: a 2-D difference tracker over the line starts and a line generator, adds and shifts only (SPEC §8)",
        latency: 3 => "load of a triangle's first line to its first two pixels, two pixels per clock along a line",
        multipliers: 0,
        in {
            load: Bit, span_base_ports!, first: Bit,
            ri: Bits<64>, rdx: Bits<64>, rdy: Bits<64>, ra: Bits<64>, rb: Bits<64>, rc: Bits<64>,
            gi: Bits<64>, gdx: Bits<64>, gdy: Bits<64>, ga: Bits<64>, gb: Bits<64>, gc: Bits<64>,
            bi: Bits<64>, bdx: Bits<64>, bdy: Bits<64>, ba: Bits<64>, bb: Bits<64>, bc: Bits<64>,
            z0: Bits<32>, dz: Bits<32>, hold: Bit,
        }
        out {
            ready: Bit,
            valid_a: Bit, x_a: Bits<12>, z_a: Bits<32>, red_a: Bits<8>, green_a: Bits<8>, blue_a: Bits<8>,
            valid_b: Bit, x_b: Bits<12>, z_b: Bits<32>, red_b: Bits<8>, green_b: Bits<8>, blue_b: Bits<8>,
            y_out: Bits<12>, last: Bit,
        }
        // Tracker: position, the line it holds, (I, Dx, Dy, 2A, 2B, C) per channel.
        tbusy: DFF<Bit>, tx: DFF<Bits<12>>, ty: DFF<Bits<12>>,
        ly: DFF<Bits<12>>, lx0: DFF<Bits<12>>, ldir: DFF<Bit>, lm: DFF<Bits<12>>,
        lz0: DFF<Bits<32>>, ldz: DFF<Bits<32>>,
        ti: [DFF<Bits<64>>; 3], tdx: [DFF<Bits<64>>; 3], tdy: [DFF<Bits<64>>; 3],
        ta2: [DFF<Bits<64>>; 3], tb2: [DFF<Bits<64>>; 3], tc: [DFF<Bits<64>>; 3],
        w_i: [Signal<Local, Bits<64>>; 3], w_dx: [Signal<Local, Bits<64>>; 3], w_dy: [Signal<Local, Bits<64>>; 3],
        w_a2: [Signal<Local, Bits<64>>; 3], w_b2: [Signal<Local, Bits<64>>; 3], w_c: [Signal<Local, Bits<64>>; 3],
        /// The tracker's decisions from registers: flags of the distance to the line start
        /// (zero, negative, two or more pixels; `diff` is a load's distance x0 − tx), of
        /// ty = ly and of the generator's last clock — no compare precedes the 576 word
        /// multiplexers they steer.
        diff: Signal<Local, Bits<13>>, neg: Signal<Local, Bit>, big: Signal<Local, Bit>,
        f_zero: DFF<Bit>, f_neg: DFF<Bit>, f_big: DFF<Bit>, f_yat: DFF<Bit>, f_glast: DFF<Bit>,
        /// The hand-over (tracker at its line's start, generator free), also a flag.
        f_hand: DFF<Bit>,
        /// The distance to the line start, lx0 − tx (13 bits), as a register: the flags' next
        /// values after an x-step come from compares on it, without a carry chain.
        tdist: DFF<Bits<13>>, nxt: Signal<Local, Bits<13>>, d_step: Signal<Local, Bits<13>>,
        ty1: Signal<Local, Bits<12>>, t4: Signal<Local, Bits<13>>,
        n_zero: Signal<Local, Bit>, n_neg: Signal<Local, Bit>, n_big: Signal<Local, Bit>,
        a_zero: Signal<Local, Bit>, a_neg: Signal<Local, Bit>, a_big: Signal<Local, Bit>,
        /// 3·2A, registered with 2A (the −2 x-step's term).
        ta3: [DFF<Bits<64>>; 3],
        /// The x-step of I as one add: its terms are selected by the registered flags
        /// (direction, size) before one carry-save level and one carry chain, and the word
        /// multiplexer after the chain chooses only among the x-step, the y-step and the load
        /// (−x = !x + 1, the +1 entering as the carry word's free bit 0). Dx and Dy, two-operand,
        /// form their four outcomes (±1, ±2 pixels) from registers; the flags select after the
        /// chains (`xdx`, `xdy`).
        xt1: [Signal<Local, Bits<64>>; 3], xt2: [Signal<Local, Bits<64>>; 3],
        xi_s: [Signal<Local, Bits<64>>; 3], xi_k: [Signal<Local, Bits<64>>; 3], xi: [Signal<Local, Bits<64>>; 3],
        dx_p1: [Signal<Local, Bits<64>>; 3], dx_p2: [Signal<Local, Bits<64>>; 3],
        dx_m1: [Signal<Local, Bits<64>>; 3], dx_m2: [Signal<Local, Bits<64>>; 3],
        dy_p1: [Signal<Local, Bits<64>>; 3], dy_p2: [Signal<Local, Bits<64>>; 3],
        dy_m1: [Signal<Local, Bits<64>>; 3], dy_m2: [Signal<Local, Bits<64>>; 3],
        xdx: [Signal<Local, Bits<64>>; 3], xdy: [Signal<Local, Bits<64>>; 3],
        /// The hand-over's first difference along the line: I + Dx (rightward), I − Dx + 2A
        /// (leftward, carry-save as above).
        i_p1: [Signal<Local, Bits<64>>; 3], i_m1: [Signal<Local, Bits<64>>; 3],
        cs_m1: [Signal<Local, Bits<64>>; 3], ck_m1: [Signal<Local, Bits<64>>; 3], n_dx: [Signal<Local, Bits<64>>; 3],
        step: Signal<Local, Bits<12>>,
        /// `handover`: the hand-over happens this clock (`f_hand` and no `hold`).
        handover: Signal<Local, Bit>, can_take: Signal<Local, Bit>, gstep: Signal<Local, Bit>,
        accept: Signal<Local, Bit>, y_move: Signal<Local, Bit>, x_move: Signal<Local, Bit>,
        // Generator: the line being emitted.
        gbusy: DFF<Bit>, t_q: DFF<Bits<13>>, gm: DFF<Bits<13>>, gx0: DFF<Bits<12>>,
        gy: DFF<Bits<12>>, gdir: DFF<Bit>, gdz: DFF<Bits<32>>,
        p: [DFF<Bits<64>>; 3], q: [DFF<Bits<64>>; 3], ga2: [DFF<Bits<64>>; 3],
        /// The pair's difference e = q − p and 3·2A: the pair's step as three-operand adds,
        /// each one carry-save level and one carry chain (p' = q + e + 2A,
        /// q' = q + 2e + 3·2A, e' = e + 2·2A).
        ge: [DFF<Bits<64>>; 3], ga3: [DFF<Bits<64>>; 3],
        gp_s: [Signal<Local, Bits<64>>; 3], gp_k: [Signal<Local, Bits<64>>; 3],
        gq_s: [Signal<Local, Bits<64>>; 3], gq_k: [Signal<Local, Bits<64>>; 3], ge2: [Signal<Local, Bits<64>>; 3],
        za: DFF<Bits<32>>, zb: DFF<Bits<32>>,
        t2: Signal<Local, Bits<13>>, t1: Signal<Local, Bits<13>>,
        glast: Signal<Local, Bit>, vb: Signal<Local, Bit>,
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
        dff_setup!(
            self, clock, tbusy, tx, ty, ly, lx0, ldir, lm, lz0, ldz, gbusy, t_q, gm, gx0, gy, gdir,
            gdz, za, zb, f_zero, f_neg, f_big, f_yat, f_glast, f_hand, tdist
        );
        clock!(self, clock, o_va, o_xa, o_za, o_vb, o_xb, o_zb, o_y, o_l);
        for c in 0..3 {
            self.ti[c].clock.next = self.clock.val();
            self.tdx[c].clock.next = self.clock.val();
            self.tdy[c].clock.next = self.clock.val();
            self.ta2[c].clock.next = self.clock.val();
            self.tb2[c].clock.next = self.clock.val();
            self.tc[c].clock.next = self.clock.val();
            self.ta3[c].clock.next = self.clock.val();
            self.ta3[c].d.next = self.ta3[c].q.val();
            self.ti[c].d.next = self.ti[c].q.val();
            self.tdx[c].d.next = self.tdx[c].q.val();
            self.tdy[c].d.next = self.tdy[c].q.val();
            self.ta2[c].d.next = self.ta2[c].q.val();
            self.tb2[c].d.next = self.tb2[c].q.val();
            self.tc[c].d.next = self.tc[c].q.val();
            self.p[c].clock.next = self.clock.val();
            self.q[c].clock.next = self.clock.val();
            self.ga2[c].clock.next = self.clock.val();
            self.p[c].d.next = self.p[c].q.val();
            self.q[c].d.next = self.q[c].q.val();
            self.ga2[c].d.next = self.ga2[c].q.val();
            self.ge[c].clock.next = self.clock.val();
            self.ga3[c].clock.next = self.clock.val();
            self.ge[c].d.next = self.ge[c].q.val();
            self.ga3[c].d.next = self.ga3[c].q.val();
            self.o_ca[c].clock.next = self.clock.val();
            self.o_cb[c].clock.next = self.clock.val();
        }
        // The load's words per channel.
        self.w_i[0].next = self.ri.val();
        self.w_dx[0].next = self.rdx.val();
        self.w_dy[0].next = self.rdy.val();
        self.w_a2[0].next = self.ra.val();
        self.w_b2[0].next = self.rb.val();
        self.w_c[0].next = self.rc.val();
        self.w_i[1].next = self.gi.val();
        self.w_dx[1].next = self.gdx.val();
        self.w_dy[1].next = self.gdy.val();
        self.w_a2[1].next = self.ga.val();
        self.w_b2[1].next = self.gb.val();
        self.w_c[1].next = self.gc.val();
        self.w_i[2].next = self.bi.val();
        self.w_dx[2].next = self.bdx.val();
        self.w_dy[2].next = self.bdy.val();
        self.w_a2[2].next = self.ba.val();
        self.w_b2[2].next = self.bb.val();
        self.w_c[2].next = self.bc.val();

        // Generator status.
        self.t1.next = self.t_q.q.val() + 1;
        self.t2.next = self.t_q.q.val() + 2;
        self.glast.next = self.f_glast.q.val();
        self.vb.next = self.gbusy.q.val() & (self.t_q.q.val() < self.gm.q.val());

        // Tracker status and moves.
        // `hold` stops the generator (no step, no hand-over) and empties the outputs of the
        // next clock; the tracker's moves do not depend on it (it has none left once `f_hand`
        // is set), so they use `f_hand` itself.
        self.handover.next = self.f_hand.q.val() & !self.hold.val();
        self.gstep.next = self.gbusy.q.val() & !self.hold.val();
        self.can_take.next = !self.tbusy.q.val() | self.handover.val();
        self.accept.next = self.load.val() & self.can_take.val();
        self.y_move.next = self.tbusy.q.val() & !self.f_hand.q.val() & !self.f_yat.q.val();
        self.x_move.next =
            self.tbusy.q.val() & !self.f_hand.q.val() & self.f_yat.q.val() & !self.f_zero.q.val();
        self.neg.next = self.f_neg.q.val();
        self.big.next = self.f_big.q.val();
        self.step.next = 1.into();
        if self.big.val() {
            self.step.next = 2.into();
        }
        for c in 0..3 {
            // The hand-over's pair: I + Dx, I − Dx + 2A.
            self.i_p1[c].next = self.ti[c].q.val() + self.tdx[c].q.val();
            self.n_dx[c].next = !self.tdx[c].q.val();
            self.cs_m1[c].next = self.ti[c].q.val() ^ self.n_dx[c].val() ^ self.ta2[c].q.val();
            self.ck_m1[c].next = (((self.ti[c].q.val() & self.n_dx[c].val())
                | (self.ti[c].q.val() & self.ta2[c].q.val())
                | (self.n_dx[c].val() & self.ta2[c].q.val()))
                << 1)
                | 1;
            self.i_m1[c].next = self.cs_m1[c].val() + self.ck_m1[c].val();
            // The x-step's terms: I + (Dx | 2·Dx + 2A | −Dx + 2A | −2·Dx + 3·2A),
            // Dx ± 2A·step, Dy ± C·step.
            if self.neg.val() {
                if self.big.val() {
                    self.xt1[c].next = !(self.tdx[c].q.val() << 1);
                    self.xt2[c].next = self.ta3[c].q.val();
                } else {
                    self.xt1[c].next = !self.tdx[c].q.val();
                    self.xt2[c].next = self.ta2[c].q.val();
                }
            } else if self.big.val() {
                self.xt1[c].next = self.tdx[c].q.val() << 1;
                self.xt2[c].next = self.ta2[c].q.val();
            } else {
                self.xt1[c].next = self.tdx[c].q.val();
                self.xt2[c].next = 0.into();
            }
            self.xi_s[c].next = self.ti[c].q.val() ^ self.xt1[c].val() ^ self.xt2[c].val();
            self.xi_k[c].next = ((self.ti[c].q.val() & self.xt1[c].val())
                | (self.ti[c].q.val() & self.xt2[c].val())
                | (self.xt1[c].val() & self.xt2[c].val()))
                << 1;
            if self.neg.val() {
                self.xi_k[c].next = (((self.ti[c].q.val() & self.xt1[c].val())
                    | (self.ti[c].q.val() & self.xt2[c].val())
                    | (self.xt1[c].val() & self.xt2[c].val()))
                    << 1)
                    | 1;
            }
            self.xi[c].next = self.xi_s[c].val() + self.xi_k[c].val();
            // Dx ± 2A·step, Dy ± C·step: two-operand adds from registers, the flags selecting
            // after the carry chains.
            self.dx_p1[c].next = self.tdx[c].q.val() + self.ta2[c].q.val();
            self.dx_p2[c].next = self.tdx[c].q.val() + (self.ta2[c].q.val() << 1);
            self.dx_m1[c].next = self.tdx[c].q.val() - self.ta2[c].q.val();
            self.dx_m2[c].next = self.tdx[c].q.val() - (self.ta2[c].q.val() << 1);
            self.dy_p1[c].next = self.tdy[c].q.val() + self.tc[c].q.val();
            self.dy_p2[c].next = self.tdy[c].q.val() + (self.tc[c].q.val() << 1);
            self.dy_m1[c].next = self.tdy[c].q.val() - self.tc[c].q.val();
            self.dy_m2[c].next = self.tdy[c].q.val() - (self.tc[c].q.val() << 1);
            if self.neg.val() {
                if self.big.val() {
                    self.xdx[c].next = self.dx_m2[c].val();
                    self.xdy[c].next = self.dy_m2[c].val();
                } else {
                    self.xdx[c].next = self.dx_m1[c].val();
                    self.xdy[c].next = self.dy_m1[c].val();
                }
            } else if self.big.val() {
                self.xdx[c].next = self.dx_p2[c].val();
                self.xdy[c].next = self.dy_p2[c].val();
            } else {
                self.xdx[c].next = self.dx_p1[c].val();
                self.xdy[c].next = self.dy_p1[c].val();
            }
        }
        if self.y_move.val()
            | (self.accept.val() & !self.first.val() & (self.ty.q.val() != self.y.val()))
        {
            self.ty.d.next = self.ty.q.val() + 1;
            for c in 0..3 {
                self.ti[c].d.next = self.ti[c].q.val() + self.tdy[c].q.val();
                self.tdy[c].d.next = self.tdy[c].q.val() + self.tb2[c].q.val();
                self.tdx[c].d.next = self.tdx[c].q.val() + self.tc[c].q.val();
            }
        }
        if self.x_move.val() {
            self.tx.d.next = self.tx.q.val() + self.step.val();
            if self.neg.val() {
                self.tx.d.next = self.tx.q.val() - self.step.val();
            }
            for c in 0..3 {
                self.ti[c].d.next = self.xi[c].val();
                self.tdx[c].d.next = self.xdx[c].val();
                self.tdy[c].d.next = self.xdy[c].val();
            }
        }
        if self.handover.val() {
            self.tbusy.d.next = false;
        }
        if self.accept.val() {
            self.tbusy.d.next = true;
            self.ly.d.next = self.y.val();
            self.lx0.d.next = self.x0.val();
            self.ldir.d.next = self.dir.val();
            self.lm.d.next = self.m.val();
            self.lz0.d.next = self.z0.val();
            self.ldz.d.next = self.dz.val();
            if self.first.val() {
                self.tx.d.next = self.x0.val();
                self.ty.d.next = self.y.val();
                for c in 0..3 {
                    self.ti[c].d.next = self.w_i[c].val();
                    self.tdx[c].d.next = self.w_dx[c].val();
                    self.tdy[c].d.next = self.w_dy[c].val();
                    self.ta2[c].d.next = self.w_a2[c].val();
                    self.ta3[c].d.next = (self.w_a2[c].val() << 1) + self.w_a2[c].val();
                    self.tb2[c].d.next = self.w_b2[c].val();
                    self.tc[c].d.next = self.w_c[c].val();
                }
            }
        }

        // Output register: both lanes, from the generator's state.
        self.xa.next = self.gx0.q.val() + self.t_q.q.val().get_bits::<12>(0);
        self.xb.next = self.gx0.q.val() + self.t1.val().get_bits::<12>(0);
        if self.gdir.q.val() {
            self.xa.next = self.gx0.q.val() - self.t_q.q.val().get_bits::<12>(0);
            self.xb.next = self.gx0.q.val() - self.t1.val().get_bits::<12>(0);
        }
        for c in 0..3 {
            self.sat_a[c].v.next = self.p[c].q.val();
            self.sat_b[c].v.next = self.q[c].q.val();
            self.o_ca[c].d.next = self.sat_a[c].q.val();
            self.o_cb[c].d.next = self.sat_b[c].q.val();
        }
        self.o_va.d.next = self.gstep.val();
        self.o_xa.d.next = self.xa.val();
        self.o_za.d.next = self.za.q.val();
        self.o_vb.d.next = self.vb.val() & !self.hold.val();
        self.o_xb.d.next = self.xb.val();
        self.o_zb.d.next = self.zb.q.val();
        self.o_y.d.next = self.gy.q.val();
        self.o_l.d.next = self.gstep.val() & self.glast.val();

        // Generator: the pair's step, p' = q + e + 2A, q' = q + 2e + 3·2A (carry-save, then
        // one carry chain each), computed every clock and taken while the line runs.
        for c in 0..3 {
            self.ge2[c].next = self.ge[c].q.val() << 1;
            self.gp_s[c].next = self.q[c].q.val() ^ self.ge[c].q.val() ^ self.ga2[c].q.val();
            self.gp_k[c].next = ((self.q[c].q.val() & self.ge[c].q.val())
                | (self.q[c].q.val() & self.ga2[c].q.val())
                | (self.ge[c].q.val() & self.ga2[c].q.val()))
                << 1;
            self.gq_s[c].next = self.q[c].q.val() ^ self.ge2[c].val() ^ self.ga3[c].q.val();
            self.gq_k[c].next = ((self.q[c].q.val() & self.ge2[c].val())
                | (self.q[c].q.val() & self.ga3[c].q.val())
                | (self.ge2[c].val() & self.ga3[c].q.val()))
                << 1;
        }
        // Generator: step the pairs, or take the tracker's line.
        if self.gstep.val() {
            if self.glast.val() {
                self.gbusy.d.next = false;
            } else {
                for c in 0..3 {
                    self.p[c].d.next = self.gp_s[c].val() + self.gp_k[c].val();
                    self.q[c].d.next = self.gq_s[c].val() + self.gq_k[c].val();
                    self.ge[c].d.next = self.ge[c].q.val() + (self.ga2[c].q.val() << 1);
                }
                self.t_q.d.next = self.t2.val();
                self.za.d.next = self.za.q.val() + (self.gdz.q.val() << 1);
                self.zb.d.next = self.zb.q.val() + (self.gdz.q.val() << 1);
            }
        }
        if self.handover.val() {
            self.gbusy.d.next = true;
            self.t_q.d.next = 0.into();
            self.gm.d.next = bit_cast::<13, 12>(self.lm.q.val());
            self.gx0.d.next = self.lx0.q.val();
            self.gy.d.next = self.ly.q.val();
            self.gdir.d.next = self.ldir.q.val();
            self.gdz.d.next = self.ldz.q.val();
            self.za.d.next = self.lz0.q.val();
            self.zb.d.next = self.lz0.q.val() + self.ldz.q.val();
            for c in 0..3 {
                self.p[c].d.next = self.ti[c].q.val();
                self.ga2[c].d.next = self.ta2[c].q.val();
                self.ga3[c].d.next = self.ta3[c].q.val();
                if self.ldir.q.val() {
                    self.q[c].d.next = self.i_m1[c].val();
                    self.ge[c].d.next = self.ta2[c].q.val() - self.tdx[c].q.val();
                } else {
                    self.q[c].d.next = self.i_p1[c].val();
                    self.ge[c].d.next = self.tdx[c].q.val();
                }
            }
        }

        self.ready.next = self.can_take.val();
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
        // The decision flags of the next clock, each from the case that sets the registers it
        // tests (a load, an x-step, a y-step, the generator's step or hand-over), formed in
        // parallel from registers and inputs; the control only selects. Last in `update`: the
        // hand-over flag reads the others' next values.
        // x-step: tx moves by the step towards lx0 (distance + step when negative). The flags
        // of the distance after it, from the distance before: a 1-pixel step reaches the line
        // start; a 2-pixel one leaves d − 2 (d ≥ 2) or d + 2 (d ≤ −2).
        self.d_step.next = 0x1FFF.into();
        if self.f_neg.q.val() & self.f_big.q.val() {
            self.d_step.next = 2.into();
        } else if self.f_neg.q.val() {
            self.d_step.next = 1.into();
        } else if self.f_big.q.val() {
            self.d_step.next = 0x1FFE.into();
        }
        self.nxt.next = self.tdist.q.val() + self.d_step.val();
        self.n_zero.next = true;
        self.n_neg.next = false;
        self.n_big.next = false;
        if self.f_big.q.val() {
            if self.f_neg.q.val() {
                self.n_zero.next = self.tdist.q.val() == 0x1FFE;
                self.n_neg.next = self.tdist.q.val() != 0x1FFE;
                self.n_big.next = (self.tdist.q.val() != 0x1FFE) & (self.tdist.q.val() != 0x1FFD);
            } else {
                self.n_zero.next = self.tdist.q.val() == 2;
                self.n_big.next = self.tdist.q.val().get_bits::<10>(2).any();
            }
        }
        // A later line's load: lx0 = x0, tx stays.
        self.diff.next = bit_cast::<13, 12>(self.x0.val()) - bit_cast::<13, 12>(self.tx.q.val());
        self.a_zero.next = self.diff.val() == 0;
        self.a_neg.next = self.diff.val().get_bit(12);
        self.a_big.next = self.diff.val().get_bits::<11>(1).any();
        if self.diff.val().get_bit(12) {
            self.a_big.next = self.diff.val() != 0x1FFF;
        }
        self.ty1.next = self.ty.q.val() + 1;
        self.t4.next = self.t_q.q.val() + 4;
        if self.accept.val() {
            if self.first.val() {
                self.f_zero.d.next = true;
                self.f_neg.d.next = false;
                self.f_big.d.next = false;
                self.f_yat.d.next = true;
            } else {
                self.f_zero.d.next = self.a_zero.val();
                self.f_neg.d.next = self.a_neg.val();
                self.f_big.d.next = self.a_big.val();
                self.f_yat.d.next =
                    (self.ty.q.val() == self.y.val()) | (self.ty1.val() == self.y.val());
            }
        }
        if self.accept.val() {
            self.tdist.d.next = self.diff.val();
            if self.first.val() {
                self.tdist.d.next = 0.into();
            }
        }
        if self.x_move.val() {
            self.tdist.d.next = self.nxt.val();
            self.f_zero.d.next = self.n_zero.val();
            self.f_neg.d.next = self.n_neg.val();
            self.f_big.d.next = self.n_big.val();
        }
        if self.y_move.val() {
            self.f_yat.d.next = self.ty1.val() == self.ly.q.val();
        }
        if self.gstep.val() & !self.glast.val() {
            self.f_glast.d.next = self.t4.val() > self.gm.q.val();
        }
        if self.handover.val() {
            self.f_glast.d.next = bit_cast::<13, 12>(self.lm.q.val()) < 2;
        }
        self.f_hand.d.next = self.tbusy.d.val()
            & self.f_yat.d.val()
            & self.f_zero.d.val()
            & (!self.gbusy.d.val() | self.f_glast.d.val());
    }
}
