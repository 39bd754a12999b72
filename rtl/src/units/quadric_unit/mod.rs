//! The quadric forward-difference unit (SPEC §8; golden: `golden::units::quadric_unit`): quadric
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
//! | `hold` | in | 1: the generator stands still this clock (no step, no hand-over, so a tracker waiting to hand over keeps `ready` low) and the outputs two clocks later carry no pixel; nothing is lost or repeated — the pixels come one clock per clock without `hold` (a stream top's back-pressure) |
//! | `ready` | out | the tracker takes a line this clock |
//! | `valid_a`, `x_a`, `z_a`, `red_a` … | out | lane A: pixel 2j in the line's clock j |
//! | `valid_b`, `x_b`, `z_b`, `red_b` … | out | lane B: pixel 2j + 1 (when ≤ m) |
//! | `y_out`, `done` | out | the line; its last clock |
//!
//! # Latency, throughput
//! A line is taken in the clock the tracker hands its previous line over (or when idle), reaches
//! its start after ⌈|Δx0|/2⌉ clocks of x-steps (the y-step rides on the load), and is handed to
//! the generator when that finishes its line: per line max(⌊m/2⌋ + 1, 1 + ⌈|Δx0|/2⌉) clocks,
//! two pixels per clock on lines longer than their start's move. Load → first pixels of a
//! triangle's first line: 4 clocks (load, hand-over, output register, the colours' rounding
//! from the words' high halves, which run a clock behind). Each clock with `hold`
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
//! So several kinds of path (I's step, Dx's step, the load's flags) sat between 10.2 and
//! 11.1 ns, 6–8 ns of it routing; moving one brought up the next, and a 64-bit carry chain
//! was 2.3 ns of each.
//!
//! **Split words** (what closed it): every 64-bit word of the tracker and the generator is
//! kept as two 32-bit halves in two copies of one block (`QuadricHalf`): the low half steps
//! with this clock's control; the high half steps a clock later with the same control
//! delayed a register, the load's high words registered, and the low half's 29 crossing bits
//! per channel (`cross`: each add's carry out of bit 31, each carry-save carry word's and
//! each one-place shift's bit 31) registered. So each high half holds the word's high half of
//! the clock before, and no carry chain is longer than 32 bits (each add a + b + carry in,
//! one chain; its carry out is bit 31 of a·b + (a ⊕ b)·¬sum). A word is resolved only where
//! it leaves the unit: the colours are rounded from the high half and the low half's bits
//! 28..31 (plus the rounding constant, registered) of the clock before — one clock more
//! latency (3 → 4), the same values and the same `ready`, hand-over and pixel order in every
//! clock (the twin's outputs are delayed one clock, nothing else changed). ECP5 (LFE5U-25F):
//! 97.5 → **109.1 MHz** (placer seeds 2, 3: 111.2, 109.2), 11 080 → 9 837 LUT4, 2 652 → 3 444
//! FF; path 9.17 ns, ta2 → 2·2A → its complement → Dx − 2·2A's chain → Dx (the low half's
//! −2 x-step of Dx). `quadric-stream`: 88.7 → 104.6 MHz (seeds 2, 3: 108.5, 108.1).
//! A first build formed each add 34 bits wide, (a·2 + 1) + (b·2 + carry in), which placed at
//! 113.6 MHz but simulated 4.4 times slower than the 64-bit unit had (rust-hdl keeps vectors
//! wider than 32 bits as big integers); with 32-bit adds and the carry in as a third, 1-bit
//! operand (Yosys maps it to the chain's carry in) the simulation is as fast as before.
//!
//! # Overflow
//! Every update is an exact integer add modulo 2⁶⁴, made of two 32-bit adds with the carry
//! between them registered (the high half's carry out is dropped; nothing may saturate: each word feeds the
//! next; intermediates may wrap harmlessly, the values equal the exact quadric of the words
//! modulo 2⁶⁴); the span front end rejects a line whose intensities or coefficients leave ±2³¹
//! LSB (`golden::units::quadric_unit::RANGE`; the words hold ±2³³ — a quadric fitted on a sliver
//! overshoots wildly at pixel centres just outside it), so the values themselves never wrap.
//! Outputs saturate to 0..=255.
//!
//! # Error budget (vs `golden::shading::quadric::row_kernel`, f64)
//! The words' rounding (2⁻³¹ each) grows with the walk as a quadratic in the distance: ≤ 1.5·N²·2⁻³¹
//! for a triangle N pixels across (≤ 0.012 LSB at N = 4096); the output rounding ½ LSB.
//!
//! Latency (the block's `LATENCY`): 4 clocks, load of a triangle's first line to its first two pixels, two pixels per clock along a line.

mod half;
mod rounding;

pub use half::{cross, QuadricHalf};
pub use rounding::{RoundLo, RoundSat8Split};

use rust_hdl::prelude::*;

crate::hw_block! {
    /// The quadric forward-difference unit (see the module header).
    pub struct QuadricUnit(clock) as "quadric-unit" {
        summary: "a triangle's I, Dx, Dy, 2A, 2B, C per channel and its raster lines in, quadric-shaded fragments out two per clock: a 2-D difference tracker over the line starts and a line generator, adds and shifts only (SPEC §8)",
        latency: 4 => "load of a triangle's first line to its first two pixels, two pixels per clock along a line",
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
            y_out: Bits<12>, done: Bit,
        }
        // Tracker: position and the line it holds (its words are in the halves).
        tbusy: DFF<Bit>, tx: DFF<Bits<12>>, ty: DFF<Bits<12>>,
        ly: DFF<Bits<12>>, lx0: DFF<Bits<12>>, ldir: DFF<Bit>, lm: DFF<Bits<12>>,
        lz0: DFF<Bits<32>>, ldz: DFF<Bits<32>>,
        /// The words' low halves (this clock's control) and high halves (the control and the
        /// low halves' carries of the clock before: each word's high half is one clock behind).
        half_lo: QuadricHalf, half_hi: QuadricHalf,
        /// The control of the low half, delayed a clock for the high half.
        d_ystep: DFF<Bit>, d_xstep: DFF<Bit>, d_neg: DFF<Bit>, d_big: DFF<Bit>,
        d_ld: DFF<Bit>, d_hand: DFF<Bit>, d_hdir: DFF<Bit>, d_gadv: DFF<Bit>,
        /// The load's high halves, a clock later (channel-major: I, Dx, Dy, 2A, 2B, C).
        whi: [DFF<Bits<32>>; 18],
        /// The low halves' carries (`cross`), registered for the high halves.
        carry: [DFF<Bits<29>>; 3],
        /// Bits 28..31 of the generator's p and q plus the rounding constant (`RoundLo`), a
        /// clock later: the output rounding's low part, its carry into the high half's add.
        plo: [DFF<Bits<5>>; 3], qlo: [DFF<Bits<5>>; 3],
        rlo_a: [RoundLo; 3], rlo_b: [RoundLo; 3],
        cin_k: Constant<Bits<29>> = Constant::new(cross::LOW.into()),
        cin_kn: Constant<Bits<29>> = Constant::new((cross::LOW | (1 << cross::XIK)).into()),
        cin_lo: Signal<Local, Bits<29>>,
        ystep: Signal<Local, Bit>, ld: Signal<Local, Bit>, gadv: Signal<Local, Bit>,
        /// The tracker's decisions from registers: flags of the distance to the line start
        /// (zero, negative, two or more pixels; `diff` is a load's distance x0 − tx), of
        /// ty = ly and of the generator's last clock — no compare precedes the word
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
        step: Signal<Local, Bits<12>>,
        /// `handover`: the hand-over happens this clock (`f_hand` and no `hold`).
        handover: Signal<Local, Bit>, can_take: Signal<Local, Bit>, gstep: Signal<Local, Bit>,
        accept: Signal<Local, Bit>, y_move: Signal<Local, Bit>, x_move: Signal<Local, Bit>,
        // Generator: the line being emitted (its words are in the halves).
        gbusy: DFF<Bit>, t_q: DFF<Bits<13>>, gm: DFF<Bits<13>>, gx0: DFF<Bits<12>>,
        gy: DFF<Bits<12>>, gdir: DFF<Bit>, gdz: DFF<Bits<32>>,
        za: DFF<Bits<32>>, zb: DFF<Bits<32>>,
        t2: Signal<Local, Bits<13>>, t1: Signal<Local, Bits<13>>,
        glast: Signal<Local, Bit>, vb: Signal<Local, Bit>,
        xa: Signal<Local, Bits<12>>, xb: Signal<Local, Bits<12>>,
        sat_a: [RoundSat8Split; 3], sat_b: [RoundSat8Split; 3],
        // Output registers: the generator's clock registered (`o_*`), then once more beside
        // the colours, which are rounded a clock later from the high halves (`s_*`, `o_c*`).
        o_va: DFF<Bit>, o_xa: DFF<Bits<12>>, o_za: DFF<Bits<32>>,
        o_vb: DFF<Bit>, o_xb: DFF<Bits<12>>, o_zb: DFF<Bits<32>>,
        o_y: DFF<Bits<12>>, o_l: DFF<Bit>,
        s_va: DFF<Bit>, s_xa: DFF<Bits<12>>, s_za: DFF<Bits<32>>, o_ca: [DFF<Bits<8>>; 3],
        s_vb: DFF<Bit>, s_xb: DFF<Bits<12>>, s_zb: DFF<Bits<32>>, o_cb: [DFF<Bits<8>>; 3],
        s_y: DFF<Bits<12>>, s_l: DFF<Bit>,
    }
}

impl Logic for QuadricUnit {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, tbusy, tx, ty, ly, lx0, ldir, lm, lz0, ldz, gbusy, t_q, gm, gx0, gy, gdir,
            gdz, za, zb, f_zero, f_neg, f_big, f_yat, f_glast, f_hand, tdist
        );
        clock!(
            self, clock, o_va, o_xa, o_za, o_vb, o_xb, o_zb, o_y, o_l, s_va, s_xa, s_za, s_vb,
            s_xb, s_zb, s_y, s_l, d_ystep, d_xstep, d_neg, d_big, d_ld, d_hand, d_hdir, d_gadv
        );
        self.half_lo.clock.next = self.clock.val();
        self.half_hi.clock.next = self.clock.val();
        for k in 0..18 {
            self.whi[k].clock.next = self.clock.val();
        }
        for c in 0..3 {
            clock!(self, clock, carry[c], plo[c], qlo[c], o_ca[c], o_cb[c]);
        }

        // Generator status.
        self.t1.next = self.t_q.q.val() + 1;
        self.t2.next = self.t_q.q.val() + 2;
        self.glast.next = self.f_glast.q.val();
        self.vb.next = self.gbusy.q.val() & (self.t_q.q.val() < self.gm.q.val());

        // Tracker status and moves.
        // `hold` stops the generator (no step, no hand-over) and empties the outputs two
        // clocks later; the tracker's moves do not depend on it (it has none left once
        // `f_hand` is set), so they use `f_hand` itself.
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
        self.ystep.next = self.y_move.val()
            | (self.accept.val() & !self.first.val() & (self.ty.q.val() != self.y.val()));
        self.ld.next = self.accept.val() & self.first.val();
        self.gadv.next = self.gstep.val() & !self.glast.val();

        // The words: low halves now, high halves a clock later.
        self.cin_lo.next = self.cin_k.val();
        if self.neg.val() {
            self.cin_lo.next = self.cin_kn.val();
        }
        self.half_lo.ystep.next = self.ystep.val();
        self.half_lo.xstep.next = self.x_move.val();
        self.half_lo.neg.next = self.neg.val();
        self.half_lo.big.next = self.big.val();
        self.half_lo.ld.next = self.ld.val();
        self.half_lo.hand.next = self.handover.val();
        self.half_lo.hdir.next = self.ldir.q.val();
        self.half_lo.gadv.next = self.gadv.val();
        self.d_ystep.d.next = self.ystep.val();
        self.d_xstep.d.next = self.x_move.val();
        self.d_neg.d.next = self.neg.val();
        self.d_big.d.next = self.big.val();
        self.d_ld.d.next = self.ld.val();
        self.d_hand.d.next = self.handover.val();
        self.d_hdir.d.next = self.ldir.q.val();
        self.d_gadv.d.next = self.gadv.val();
        self.half_hi.ystep.next = self.d_ystep.q.val();
        self.half_hi.xstep.next = self.d_xstep.q.val();
        self.half_hi.neg.next = self.d_neg.q.val();
        self.half_hi.big.next = self.d_big.q.val();
        self.half_hi.ld.next = self.d_ld.q.val();
        self.half_hi.hand.next = self.d_hand.q.val();
        self.half_hi.hdir.next = self.d_hdir.q.val();
        self.half_hi.gadv.next = self.d_gadv.q.val();
        self.half_lo.ri.next = self.ri.val().get_bits::<32>(0);
        self.half_lo.rdx.next = self.rdx.val().get_bits::<32>(0);
        self.half_lo.rdy.next = self.rdy.val().get_bits::<32>(0);
        self.half_lo.ra.next = self.ra.val().get_bits::<32>(0);
        self.half_lo.rb.next = self.rb.val().get_bits::<32>(0);
        self.half_lo.rc.next = self.rc.val().get_bits::<32>(0);
        self.half_lo.gi.next = self.gi.val().get_bits::<32>(0);
        self.half_lo.gdx.next = self.gdx.val().get_bits::<32>(0);
        self.half_lo.gdy.next = self.gdy.val().get_bits::<32>(0);
        self.half_lo.ga.next = self.ga.val().get_bits::<32>(0);
        self.half_lo.gb.next = self.gb.val().get_bits::<32>(0);
        self.half_lo.gc.next = self.gc.val().get_bits::<32>(0);
        self.half_lo.bi.next = self.bi.val().get_bits::<32>(0);
        self.half_lo.bdx.next = self.bdx.val().get_bits::<32>(0);
        self.half_lo.bdy.next = self.bdy.val().get_bits::<32>(0);
        self.half_lo.ba.next = self.ba.val().get_bits::<32>(0);
        self.half_lo.bb.next = self.bb.val().get_bits::<32>(0);
        self.half_lo.bc.next = self.bc.val().get_bits::<32>(0);
        self.whi[0].d.next = self.ri.val().get_bits::<32>(32);
        self.whi[1].d.next = self.rdx.val().get_bits::<32>(32);
        self.whi[2].d.next = self.rdy.val().get_bits::<32>(32);
        self.whi[3].d.next = self.ra.val().get_bits::<32>(32);
        self.whi[4].d.next = self.rb.val().get_bits::<32>(32);
        self.whi[5].d.next = self.rc.val().get_bits::<32>(32);
        self.whi[6].d.next = self.gi.val().get_bits::<32>(32);
        self.whi[7].d.next = self.gdx.val().get_bits::<32>(32);
        self.whi[8].d.next = self.gdy.val().get_bits::<32>(32);
        self.whi[9].d.next = self.ga.val().get_bits::<32>(32);
        self.whi[10].d.next = self.gb.val().get_bits::<32>(32);
        self.whi[11].d.next = self.gc.val().get_bits::<32>(32);
        self.whi[12].d.next = self.bi.val().get_bits::<32>(32);
        self.whi[13].d.next = self.bdx.val().get_bits::<32>(32);
        self.whi[14].d.next = self.bdy.val().get_bits::<32>(32);
        self.whi[15].d.next = self.ba.val().get_bits::<32>(32);
        self.whi[16].d.next = self.bb.val().get_bits::<32>(32);
        self.whi[17].d.next = self.bc.val().get_bits::<32>(32);
        self.half_hi.ri.next = self.whi[0].q.val();
        self.half_hi.rdx.next = self.whi[1].q.val();
        self.half_hi.rdy.next = self.whi[2].q.val();
        self.half_hi.ra.next = self.whi[3].q.val();
        self.half_hi.rb.next = self.whi[4].q.val();
        self.half_hi.rc.next = self.whi[5].q.val();
        self.half_hi.gi.next = self.whi[6].q.val();
        self.half_hi.gdx.next = self.whi[7].q.val();
        self.half_hi.gdy.next = self.whi[8].q.val();
        self.half_hi.ga.next = self.whi[9].q.val();
        self.half_hi.gb.next = self.whi[10].q.val();
        self.half_hi.gc.next = self.whi[11].q.val();
        self.half_hi.bi.next = self.whi[12].q.val();
        self.half_hi.bdx.next = self.whi[13].q.val();
        self.half_hi.bdy.next = self.whi[14].q.val();
        self.half_hi.ba.next = self.whi[15].q.val();
        self.half_hi.bb.next = self.whi[16].q.val();
        self.half_hi.bc.next = self.whi[17].q.val();
        self.half_lo.cin_r.next = self.cin_lo.val();
        self.carry[0].d.next = self.half_lo.cout_r.val();
        self.half_hi.cin_r.next = self.carry[0].q.val();
        self.rlo_a[0].lo4.next = self.half_lo.p_r.val().get_bits::<4>(28);
        self.plo[0].d.next = self.rlo_a[0].lsum.val();
        self.rlo_b[0].lo4.next = self.half_lo.q_r.val().get_bits::<4>(28);
        self.qlo[0].d.next = self.rlo_b[0].lsum.val();
        self.sat_a[0].hi.next = self.half_hi.p_r.val();
        self.sat_a[0].lsum.next = self.plo[0].q.val();
        self.sat_b[0].hi.next = self.half_hi.q_r.val();
        self.sat_b[0].lsum.next = self.qlo[0].q.val();
        self.half_lo.cin_g.next = self.cin_lo.val();
        self.carry[1].d.next = self.half_lo.cout_g.val();
        self.half_hi.cin_g.next = self.carry[1].q.val();
        self.rlo_a[1].lo4.next = self.half_lo.p_g.val().get_bits::<4>(28);
        self.plo[1].d.next = self.rlo_a[1].lsum.val();
        self.rlo_b[1].lo4.next = self.half_lo.q_g.val().get_bits::<4>(28);
        self.qlo[1].d.next = self.rlo_b[1].lsum.val();
        self.sat_a[1].hi.next = self.half_hi.p_g.val();
        self.sat_a[1].lsum.next = self.plo[1].q.val();
        self.sat_b[1].hi.next = self.half_hi.q_g.val();
        self.sat_b[1].lsum.next = self.qlo[1].q.val();
        self.half_lo.cin_b.next = self.cin_lo.val();
        self.carry[2].d.next = self.half_lo.cout_b.val();
        self.half_hi.cin_b.next = self.carry[2].q.val();
        self.rlo_a[2].lo4.next = self.half_lo.p_b.val().get_bits::<4>(28);
        self.plo[2].d.next = self.rlo_a[2].lsum.val();
        self.rlo_b[2].lo4.next = self.half_lo.q_b.val().get_bits::<4>(28);
        self.qlo[2].d.next = self.rlo_b[2].lsum.val();
        self.sat_a[2].hi.next = self.half_hi.p_b.val();
        self.sat_a[2].lsum.next = self.plo[2].q.val();
        self.sat_b[2].hi.next = self.half_hi.q_b.val();
        self.sat_b[2].lsum.next = self.qlo[2].q.val();

        if self.ystep.val() {
            self.ty.d.next = self.ty.q.val() + 1;
        }
        if self.x_move.val() {
            self.tx.d.next = self.tx.q.val() + self.step.val();
            if self.neg.val() {
                self.tx.d.next = self.tx.q.val() - self.step.val();
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
            }
        }

        // Output registers: both lanes, from the generator's state; the colours a clock later.
        self.xa.next = self.gx0.q.val() + self.t_q.q.val().get_bits::<12>(0);
        self.xb.next = self.gx0.q.val() + self.t1.val().get_bits::<12>(0);
        if self.gdir.q.val() {
            self.xa.next = self.gx0.q.val() - self.t_q.q.val().get_bits::<12>(0);
            self.xb.next = self.gx0.q.val() - self.t1.val().get_bits::<12>(0);
        }
        for c in 0..3 {
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
        self.s_va.d.next = self.o_va.q.val();
        self.s_xa.d.next = self.o_xa.q.val();
        self.s_za.d.next = self.o_za.q.val();
        self.s_vb.d.next = self.o_vb.q.val();
        self.s_xb.d.next = self.o_xb.q.val();
        self.s_zb.d.next = self.o_zb.q.val();
        self.s_y.d.next = self.o_y.q.val();
        self.s_l.d.next = self.o_l.q.val();

        // Generator: step along the line, or take the tracker's line.
        if self.gstep.val() {
            if self.glast.val() {
                self.gbusy.d.next = false;
            } else {
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
        }

        self.ready.next = self.can_take.val();
        self.valid_a.next = self.s_va.q.val();
        self.x_a.next = self.s_xa.q.val();
        self.z_a.next = self.s_za.q.val();
        self.red_a.next = self.o_ca[0].q.val();
        self.green_a.next = self.o_ca[1].q.val();
        self.blue_a.next = self.o_ca[2].q.val();
        self.valid_b.next = self.s_vb.q.val();
        self.x_b.next = self.s_xb.q.val();
        self.z_b.next = self.s_zb.q.val();
        self.red_b.next = self.o_cb[0].q.val();
        self.green_b.next = self.o_cb[1].q.val();
        self.blue_b.next = self.o_cb[2].q.val();
        self.y_out.next = self.s_y.q.val();
        self.done.next = self.s_l.q.val();
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
