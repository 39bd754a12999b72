//! The multiplies: signed products from rust-hdl's unsigned 16×16→32, pipelined with their
//! operand registers, and the narrow and wide variants.

use rust_hdl::prelude::*;

crate::hw_block! {
    /// Signed × unsigned 16×16 → signed 32 on one unsigned multiplier (one DSP slice):
    /// `p = ua·ub − [a<0]·(ub ≪ 16)  (mod 2³²)`, exact since the true product fits 32 bits.
    /// Formats: `a` signed Qm.n, `b` unsigned Qk.l → `p` signed Q(m+k).(n+l). Combinational.
    pub struct MulSignedUnsigned {
        in { a: Bits<16>, b: Bits<16> }
        out { p: Bits<32> }
        /// ua·ub, the unsigned product.
        raw: Signal<Local, Bits<32>>,
        /// [a<0]·(ub ≪ 16), the sign correction.
        corr: Signal<Local, Bits<32>>,
    }
}

impl Logic for MulSignedUnsigned {
    #[hdl_gen]
    fn update(&mut self) {
        self.raw.next = self.a.val() * self.b.val();
        if self.a.val().get_bit(15) {
            self.corr.next = bit_cast::<32, 16>(self.b.val()) << 16;
        } else {
            self.corr.next = 0.into();
        }
        self.p.next = self.raw.val() - self.corr.val();
    }
}

/// Latency of [`MulLow3Pipe`]: one clock less than the 16×16 multiplies beside it, so its
/// caller can shift its product and add a constant in the clock that meets theirs.
pub const MUL_LOW_LATENCY: usize = 2;

crate::hw_block! {
    /// `p = v·m` for a 24-bit two's-complement `v` (a 16- to 20-bit word, sign- or
    /// zero-extended by the caller) and a 3-bit unsigned `m`, by shift and add (no multiplier):
    /// `v` and `m` registered; `(m₀·v + m₁·2v) + m₂·4v` in 24 bits, registered; `p` is that
    /// word sign-extended to 32 bits (wiring). Exact when |v·m| < 2²³, which holds for every
    /// word of up to 20 bits (|v| ≤ 2²⁰), signed or unsigned, times m ≤ 7. It multiplies the
    /// three low bits of a 19-bit operand split into 16 + 3 (the 16 go through a multiplier),
    /// or a whole 19-bit word by another's three low bits. Latency [`MUL_LOW_LATENCY`], one
    /// product per clock. (It was 20 bits wide, enough for 16-bit words, until the
    /// normalizer's input N became 19 bits.)
    pub struct MulLow3Pipe(clock) {
        in { v: Bits<24>, m: Bits<3> }
        out { p: Bits<32> }
        v_q: DFF<Bits<24>>,
        m_q: DFF<Bits<3>>,
        t0: Signal<Local, Bits<24>>,
        t1: Signal<Local, Bits<24>>,
        t2: Signal<Local, Bits<24>>,
        p_q: DFF<Bits<24>>,
        sign8: Constant<Bits<32>> = Constant::new(0xFF00_0000u64.into()),
    }
}

impl Logic for MulLow3Pipe {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, v_q, m_q, p_q);
        self.v_q.d.next = self.v.val();
        self.m_q.d.next = self.m.val();
        self.t0.next = 0.into();
        self.t1.next = 0.into();
        self.t2.next = 0.into();
        if self.m_q.q.val().get_bit(0) {
            self.t0.next = self.v_q.q.val();
        }
        if self.m_q.q.val().get_bit(1) {
            self.t1.next = self.v_q.q.val() << 1;
        }
        if self.m_q.q.val().get_bit(2) {
            self.t2.next = self.v_q.q.val() << 2;
        }
        self.p_q.d.next = self.t0.val() + self.t1.val() + self.t2.val();
        if self.p_q.q.val().get_bit(23) {
            self.p.next = bit_cast::<32, 24>(self.p_q.q.val()) | self.sign8.val();
        } else {
            self.p.next = bit_cast::<32, 24>(self.p_q.q.val());
        }
    }
}

/// Latency of [`MulPipe`]: the operands registered beside the multiplier, then the product.
pub const MUL_LATENCY: usize = 2;
/// Latency of [`MulSignedPipe`] and [`MulSignedUnsignedPipe`]: the
/// operands registered, the unsigned product and the sign correction registered, then their
/// difference.
pub const SIGNED_MUL_LATENCY: usize = 3;

// Why the operand registers: on ECP5 a MULT18X18D sits in a fixed column; with its operands
// coming from registers placed by the logic that forms them, the route to the multiplier, the
// multiplier and the route back took over 10 ns in the pixel pipeline (94 MHz). Registers that
// feed only the multiplier are placed beside it (one copy per multiplier, even where the words
// are shared), so each clock has one long route.

crate::hw_block! {
    /// Unsigned 16×16 → 32 in two clocks: `a`, `b` registered, then `p = a·b` registered
    /// (exact). Latency [`MUL_LATENCY`], one product per clock.
    pub struct MulPipe(clock) {
        in { a: Bits<16>, b: Bits<16> }
        out { p: Bits<32> }
        a_q: DFF<Bits<16>>,
        b_q: DFF<Bits<16>>,
        p_q: DFF<Bits<32>>,
    }
}

impl Logic for MulPipe {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, a_q, b_q, p_q);
        self.a_q.d.next = self.a.val();
        self.b_q.d.next = self.b.val();
        self.p_q.d.next = self.a_q.q.val() * self.b_q.q.val();
        self.p.next = self.p_q.q.val();
    }
}

/// Latency of [`MulPipeDeep`]: the operands registered twice, the product registered twice.
pub const MUL_DEEP_LATENCY: usize = 4;

crate::hw_block! {
    /// Unsigned 16×16 → 32 in four clocks, for a multiplier that may be placed far from the
    /// logic around it: `a`, `b` registered twice, the product registered twice (exact).
    /// The register next to the multiplier on each side has it as its only neighbour there, so
    /// the placer can put it beside the multiplier's site and the long routes get a clock of
    /// their own. Latency [`MUL_DEEP_LATENCY`], one product per clock.
    pub struct MulPipeDeep(clock) {
        in { a: Bits<16>, b: Bits<16> }
        out { p: Bits<32> }
        a_q: DFF<Bits<16>>,
        b_q: DFF<Bits<16>>,
        a_q2: DFF<Bits<16>>,
        b_q2: DFF<Bits<16>>,
        p_q: DFF<Bits<32>>,
        p_q2: DFF<Bits<32>>,
    }
}

impl Logic for MulPipeDeep {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, a_q, b_q, a_q2, b_q2, p_q, p_q2);
        self.a_q.d.next = self.a.val();
        self.b_q.d.next = self.b.val();
        self.a_q2.d.next = self.a_q.q.val();
        self.b_q2.d.next = self.b_q.q.val();
        self.p_q.d.next = self.a_q2.q.val() * self.b_q2.q.val();
        self.p_q2.d.next = self.p_q.q.val();
        self.p.next = self.p_q2.q.val();
    }
}

crate::hw_block! {
    /// [`MulSignedUnsigned`] in three clocks: the operands registered; ua·ub and `[a<0]·ub`
    /// registered; `p = ua·ub − ([a<0]·ub ≪ 16)  (mod 2³²)` registered. Latency
    /// [`SIGNED_MUL_LATENCY`], one product per clock, exact.
    pub struct MulSignedUnsignedPipe(clock) {
        in { a: Bits<16>, b: Bits<16> }
        out { p: Bits<32> }
        a_q: DFF<Bits<16>>,
        b_q: DFF<Bits<16>>,
        raw: DFF<Bits<32>>,
        corr: DFF<Bits<16>>,
        corr_w: Signal<Local, Bits<32>>,
        p_q: DFF<Bits<32>>,
    }
}

impl Logic for MulSignedUnsignedPipe {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, a_q, b_q, raw, corr, p_q);
        self.a_q.d.next = self.a.val();
        self.b_q.d.next = self.b.val();
        self.raw.d.next = self.a_q.q.val() * self.b_q.q.val();
        if self.a_q.q.val().get_bit(15) {
            self.corr.d.next = self.b_q.q.val();
        } else {
            self.corr.d.next = 0.into();
        }
        self.corr_w.next = bit_cast::<32, 16>(self.corr.q.val()) << 16;
        self.p_q.d.next = self.raw.q.val() - self.corr_w.val();
        self.p.next = self.p_q.q.val();
    }
}

crate::hw_block! {
    /// Signed × signed 16×16 → signed 32 on one unsigned multiplier, in three clocks: the
    /// operands registered; ua·ub and the sum of the corrections `([a<0]·ub + [b<0]·ua) mod
    /// 2¹⁶` registered (only the high half of the product sees them); `p = ua·ub − corr ≪ 16
    /// (mod 2³²)` registered. Exact, since the true product fits 32 bits (|p| ≤ 2³⁰). Formats:
    /// signed Qm.n × signed Qk.l → signed Q(m+k).(n+l). With `b = a` it is the signed square
    /// (the corrections sum to 2·ua, i.e. `ua ≪ 17`). Latency [`SIGNED_MUL_LATENCY`], one
    /// product per clock.
    pub struct MulSignedPipe(clock) {
        in { a: Bits<16>, b: Bits<16> }
        out { p: Bits<32> }
        a_q: DFF<Bits<16>>,
        b_q: DFF<Bits<16>>,
        raw: DFF<Bits<32>>,
        corr_a: Signal<Local, Bits<16>>,
        corr_b: Signal<Local, Bits<16>>,
        corr: DFF<Bits<16>>,
        corr_w: Signal<Local, Bits<32>>,
        p_q: DFF<Bits<32>>,
    }
}

impl Logic for MulSignedPipe {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, a_q, b_q, raw, corr, p_q);
        self.a_q.d.next = self.a.val();
        self.b_q.d.next = self.b.val();
        self.raw.d.next = self.a_q.q.val() * self.b_q.q.val();
        if self.a_q.q.val().get_bit(15) {
            self.corr_a.next = self.b_q.q.val();
        } else {
            self.corr_a.next = 0.into();
        }
        if self.b_q.q.val().get_bit(15) {
            self.corr_b.next = self.a_q.q.val();
        } else {
            self.corr_b.next = 0.into();
        }
        self.corr.d.next = self.corr_a.val() + self.corr_b.val();
        self.corr_w.next = bit_cast::<32, 16>(self.corr.q.val()) << 16;
        self.p_q.d.next = self.raw.q.val() - self.corr_w.val();
        self.p.next = self.p_q.q.val();
    }
}
