//! The cos v accumulator (SPEC §4, thesis fig. 3.6; golden: `golden::units::cos_v_accumulator`):
//! angular interpolation along a span, two pixels per clock.
//!
//! ```text
//! cos v(t) = cos β · cos(ψ − t·Δφ)        t = 0 … m
//! ```
//! Two accumulating adders in subtract mode run from both ends of the span at once: run A
//! holds ψ − t·Δφ for t = 0 … h − 1, run B holds (m·Δφ − ψ) − (m − u)·Δφ = u·Δφ − ψ for
//! u = m … h, h = ⌈(m + 1)/2⌉ (the set-up loads q = m·d − p from the same quantized words). Each
//! run addresses its own copy of the cos PROM (block RAM has one read port) with |argument| —
//! when the argument borrows past the symmetry point E it keeps going on the other side, cos
//! being even: the fig. 3.6 reload with φ − ψ in another form — and one multiplier forms
//! cos β·PROM. So every span of two or more pixels goes at two pixels per clock. (Splitting at
//! E instead, as the thesis words it, gives two per clock only when E lies inside the span: on
//! the default scene 0 of 17 199 spans for H and 222 for L — `benches/rtl_span.rs` measured
//! that design at 1.00 pixels/clock.) Per-span set-up (arccos, the division,
//! cos β) is software: `golden::shading::angular::span_setup`, quantized by
//! `golden::units::cos_v_accumulator::SpanWords`.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a span's words this clock (taken when `ready`) |
//! | `p` | in | ψ, binary angle (2³² a turn: π is 2³¹) |
//! | `q` | in | m·Δφ − ψ, binary angle |
//! | `d` | in | Δφ ∈ [0, π], binary angle |
//! | `cos_beta` | in | unsigned Q1.15 |
//! | `m` | in | span length − 1, 12 bits |
//! | `hold` | in | 1: the runs stand still this clock — no pixel enters the pipeline, no span is taken (`ready` low); nothing is lost (a stream top's back-pressure) |
//! | `ready` | out | no pixel after this clock and no `hold`: a `load` now starts the next span without a gap |
//! | `valid_a`, `t`, `cos_a` | out | run A's pixel: index (12 bits) and cos v (unsigned Q1.15) |
//! | `valid_b`, `u`, `cos_b` | out | run B's pixel |
//! | `done` | out | the span's last pixel(s) |
//!
//! # Pipeline
//! ```text
//! S0  state: arg_a, arg_b (32 bits), t (13), u (12), h = (m + 2) >> 1, busy flags, d, cos β;
//!     A active = busy & t < h; B active = busy & u ≥ h — kept as the counts ra = h − t and
//!     rb = u − h (14-bit two's complement, loaded with the span and stepped with the runs),
//!     so the tests are sign and bit tests of registers, not compares (ECP5 timing: the
//!     compares, the next-span decision and the argument load in one clock ran at 97 MHz);
//!     address = (|arg| + 2¹⁸) bits 29..19 (|arg|: the two's complement negation when bit
//!     31 is set, the angle folded to [0, π]), "top" (read 0) when bits 31..30 ≠ 0
//! S1  PROM[address] (synchronous, one copy per run), flags, indices, cos β carried
//! S2  the PROM word registered (a block RAM's output is 5.6 ns from the clock on ECP5)
//! S3  cos β · PROM                        UQ1.15 × UQ1.15 → UQ2.30, exact, two clocks [MulPipe]
//! S4  cos = top ? 0 : round(product)      + 2¹⁴, drop 15, saturate
//! ```
//! S2, S3's second clock and S4 are there for ECP5 timing: the PROM word, the multiplier and
//! the rounding in one clock ran at 62 MHz (latency 3 before).
//! Latency: load → first pixels 6 clocks; results 5 clocks after their state. Throughput: two
//! pixels per clock (one in the last clock of an odd-length span); a span takes ⌈(m + 1)/2⌉
//! clocks and the next one follows at once (`ready` rises in the last clock), so the per-span
//! overhead is zero clocks in the block.
//! 2 multipliers, 2 × 2048 × 16 PROM (2 × 8 iCE40 block RAMs).
//!
//! # Overflow
//! None: arguments are binary angles, exact integers modulo 2³², and wrap as angles do (a span
//! whose end normals are nearly opposite takes its argument past a half turn, where the fold
//! gives the true cosine); folded arguments ≥ π/2 − π/8192 read 0 (cos ≤ 3.9·10⁻⁴ there,
//! negative from π/2 on, clamped); outputs saturate.
//!
//! # Error budget (vs `golden::units::cos_v_accumulator::cos_v` of the same words)
//! The address rounding moves the argument by ≤ π/8192 (cos by ≤ π/8192·|sin|), the PROM word
//! and the product roundings add 2⁻¹⁶ each: ≤ π/8192 + 2⁻¹⁵ = 4.1·10⁻⁴.

use rust_hdl::prelude::*;

use crate::core::primitives::{Delay, MulPipe, Prom, RoundProductToUQ1_15, MUL_LATENCY};

fn cos_prom() -> Prom<Bits<16>, 11> {
    Prom::new(
        golden::units::cos_v_accumulator::prom()
            .into_iter()
            .map(Bits::<16>::from),
    )
}

crate::hw_block! {
    /// The cos v accumulator (see the module header).
    pub struct CosVAccumulator(clock) as "cos-v-accumulator" {
        summary: "a span's ψ, Δφ, cos β in, cos v = cos β·cos(ψ − tΔφ) out from both ends, two pixels per clock (SPEC §4)",
        latency: 6 => "load to the first pixels, up to two pixels per clock",
        multipliers: 2,
        in { load: Bit, p: Bits<32>, q: Bits<32>, d: Bits<32>, cos_beta: Bits<16>, m: Bits<12>, hold: Bit }
        out {
            ready: Bit,
            valid_a: Bit, t: Bits<12>, cos_a: Bits<16>,
            valid_b: Bit, u: Bits<12>, cos_b: Bits<16>,
            done: Bit,
        }
        // S0
        busy_a: DFF<Bit>, busy_b: DFF<Bit>,
        arg_a: DFF<Bits<32>>, arg_b: DFF<Bits<32>>,
        t_q: DFF<Bits<13>>, u_q: DFF<Bits<12>>,
        d_q: DFF<Bits<32>>, cb: DFF<Bits<16>>,
        // h = ⌈(m + 1)/2⌉: run A takes t < h, run B u ≥ h (as ra, rb below).
        m_plus2: Signal<Local, Bits<13>>,
        /// h − t and u − h, two's complement.
        ra: DFF<Bits<14>>, rb: DFF<Bits<14>>,
        h_new: Signal<Local, Bits<14>>,
        t_plus1: Signal<Local, Bits<13>>,
        act_a: Signal<Local, Bit>, act_b: Signal<Local, Bit>,
        /// The runs emit this clock (active and not held).
        go_a: Signal<Local, Bit>, go_b: Signal<Local, Bit>,
        next_a: Signal<Local, Bits<32>>, next_b: Signal<Local, Bits<32>>,
        more: Signal<Local, Bit>,
        mag_a: Signal<Local, Bits<32>>, mag_b: Signal<Local, Bits<32>>,
        rnd_a: Signal<Local, Bits<32>>, rnd_b: Signal<Local, Bits<32>>,
        half_step: Constant<Bits<32>> = Constant::new((1u64 << 18).into()),
        zero: Constant<Bits<32>> = Constant::new(0.into()),
        // S1
        prom_a: Prom<Bits<16>, 11> = cos_prom(),
        prom_b: Prom<Bits<16>, 11> = cos_prom(),
        valid1: [DFF<Bit>; 2], idx1: [DFF<Bits<12>>; 2], top1: [DFF<Bit>; 2],
        cb1: DFF<Bits<16>>, last1: DFF<Bit>,
        // S2: the PROM words and cos β registered; S3 the products; the flags carried.
        word2: [DFF<Bits<16>>; 2], cb2: DFF<Bits<16>>,
        prod: [MulPipe; 2],
        valid_d: [Delay<Bit, { 1 + MUL_LATENCY }>; 2],
        idx_d: [Delay<Bits<12>, { 1 + MUL_LATENCY }>; 2],
        top_d: [Delay<Bit, { 1 + MUL_LATENCY }>; 2],
        last_d: Delay<Bit, { 1 + MUL_LATENCY }>,
        // S4
        mul: [RoundProductToUQ1_15; 2],
        valid2: [DFF<Bit>; 2], idx2: [DFF<Bits<12>>; 2], cos2: [DFF<Bits<16>>; 2],
        last2: DFF<Bit>,
    }
}

impl Logic for CosVAccumulator {
    #[hdl_gen]
    fn update(&mut self) {
        // State registers hold unless assigned (dff_setup!: d = q), the rest load every clock.
        dff_setup!(self, clock, busy_a, busy_b, arg_a, arg_b, t_q, u_q, d_q, cb, ra, rb);
        clock!(self, clock, prom_a, prom_b, cb1, last1, last2, cb2, last_d);
        for k in 0..2 {
            clock!(
                self, clock, word2[k], prod[k], valid_d[k], idx_d[k], top_d[k], valid1[k], idx1[k],
                top1[k], valid2[k], idx2[k], cos2[k]
            );
        }
        // S0: which runs emit this clock, and whether any emits after it.
        self.m_plus2.next = bit_cast::<13, 12>(self.m.val()) + 2;
        self.h_new.next = bit_cast::<14, 13>(self.m_plus2.val() >> 1);
        self.t_plus1.next = self.t_q.q.val() + 1;
        self.act_a.next =
            self.busy_a.q.val() & !self.ra.q.val().get_bit(13) & self.ra.q.val().any();
        self.act_b.next = self.busy_b.q.val() & !self.rb.q.val().get_bit(13);
        self.next_a.next = self.arg_a.q.val() - self.d_q.q.val();
        self.next_b.next = self.arg_b.q.val() - self.d_q.q.val();
        self.more.next = (self.act_a.val() & self.ra.q.val().get_bits::<13>(1).any())
            | (self.act_b.val() & self.rb.q.val().any());
        // `hold`: the runs stand still and emit nothing this clock, no span is taken.
        self.ready.next = !self.more.val() & !self.hold.val();
        self.go_a.next = self.act_a.val() & !self.hold.val();
        self.go_b.next = self.act_b.val() & !self.hold.val();
        // The runs advance, or stop for good.
        if self.go_a.val() {
            self.arg_a.d.next = self.next_a.val();
            self.t_q.d.next = self.t_plus1.val();
            self.ra.d.next = self.ra.q.val() - 1;
        } else if !self.act_a.val() {
            self.busy_a.d.next = false;
        }
        if self.go_b.val() {
            self.arg_b.d.next = self.next_b.val();
            self.rb.d.next = self.rb.q.val() - 1;
            if self.u_q.q.val().any() {
                self.u_q.d.next = self.u_q.q.val() - 1;
            } else {
                self.busy_b.d.next = false;
            }
        } else if !self.act_b.val() {
            self.busy_b.d.next = false;
        }
        if self.load.val() & self.ready.val() {
            self.busy_a.d.next = true;
            self.busy_b.d.next = true;
            self.arg_a.d.next = self.p.val();
            self.arg_b.d.next = self.q.val();
            self.t_q.d.next = 0.into();
            self.u_q.d.next = self.m.val();
            self.ra.d.next = self.h_new.val();
            self.rb.d.next = bit_cast::<14, 12>(self.m.val()) - self.h_new.val();
            self.d_q.d.next = self.d.val();
            self.cb.d.next = self.cos_beta.val();
        }
        // PROM addresses: the argument folded to [0, π] (cos is even and 2π-periodic, and a
        // turn is 2³²: the two's complement negation folds), rounded to the step π/4096.
        if self.arg_a.q.val().get_bit(31) {
            self.mag_a.next = self.zero.val() - self.arg_a.q.val();
        } else {
            self.mag_a.next = self.arg_a.q.val();
        }
        if self.arg_b.q.val().get_bit(31) {
            self.mag_b.next = self.zero.val() - self.arg_b.q.val();
        } else {
            self.mag_b.next = self.arg_b.q.val();
        }
        self.rnd_a.next = self.mag_a.val() + self.half_step.val();
        self.rnd_b.next = self.mag_b.val() + self.half_step.val();
        self.prom_a.address.next = self.rnd_a.val().get_bits::<11>(19);
        self.prom_b.address.next = self.rnd_b.val().get_bits::<11>(19);
        // S1
        self.valid1[0].d.next = self.go_a.val();
        self.valid1[1].d.next = self.go_b.val();
        self.idx1[0].d.next = self.t_q.q.val().get_bits::<12>(0);
        self.idx1[1].d.next = self.u_q.q.val();
        self.top1[0].d.next = self.rnd_a.val().get_bits::<2>(30).any();
        self.top1[1].d.next = self.rnd_b.val().get_bits::<2>(30).any();
        self.cb1.d.next = self.cb.q.val();
        self.last1.d.next = (self.go_a.val() | self.go_b.val()) & !self.more.val();
        // S2, S3
        self.word2[0].d.next = self.prom_a.data.val();
        self.word2[1].d.next = self.prom_b.data.val();
        self.cb2.d.next = self.cb1.q.val();
        for k in 0..2 {
            self.prod[k].a.next = self.cb2.q.val();
            self.prod[k].b.next = self.word2[k].q.val();
            self.valid_d[k].d.next = self.valid1[k].q.val();
            self.idx_d[k].d.next = self.idx1[k].q.val();
            self.top_d[k].d.next = self.top1[k].q.val();
        }
        self.last_d.d.next = self.last1.q.val();
        // S4
        for k in 0..2 {
            self.mul[k].wide.next = self.prod[k].p.val();
            self.valid2[k].d.next = self.valid_d[k].q.val();
            self.idx2[k].d.next = self.idx_d[k].q.val();
            if self.top_d[k].q.val() {
                self.cos2[k].d.next = 0.into();
            } else {
                self.cos2[k].d.next = self.mul[k].narrow.val();
            }
        }
        self.last2.d.next = self.last_d.q.val();
        self.valid_a.next = self.valid2[0].q.val();
        self.t.next = self.idx2[0].q.val();
        self.cos_a.next = self.cos2[0].q.val();
        self.valid_b.next = self.valid2[1].q.val();
        self.u.next = self.idx2[1].q.val();
        self.cos_b.next = self.cos2[1].q.val();
        self.done.next = self.last2.q.val();
    }
}
