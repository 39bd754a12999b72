//! The Horner unit of fig. 2.6 (SPEC §9; golden: `golden::horner_unit`): one colour channel of
//! cubic shading along a span.
//!
//! ```text
//! A = 8·T(I2 + 8·I4 − 3·I1 − 6·I3)   B = 256·(7·I1 − I2 + 10·I3 − 16·I4)
//! C = T(I2 + 32·I4 − 21·I1 − 12·I3)  D = 128·I1        T(v) = 64v − 16v − 4v − v = 128·v/3 (≈)
//! I(p) = ((A·p + B)·p + C)·p + D     p = t·step, step = 2²⁷/m, t = 0 … m
//! ```
//! The coefficient block is shifts and adds only (the thesis' 1/3 ≈ 1/2 − 1/8 − 1/32 − 1/128,
//! times 128: exact integers), with the project's grouping of A and C (difference numerators,
//! `golden::cubic`). Two variants, a build parameter (`horner=serial|pipelined`):
//!
//! - **serial** (fig. 2.6): register RG, MX1 (A or RG into the multiplier), MX2 (B, C or D into
//!   the adder), one multiplier MUL, one adder Sm, and BK in front of the adder; phase 0:
//!   RG ← A·p + B, phase 1: RG ← RG·p + C, phase 2: out ← RG·p + D. Three clocks per pixel.
//!   BK passes the product while a span is in the unit and zeroes it otherwise (the idle adder
//!   then only passes a coefficient; the SPEC names BK without saying when it zeroes).
//! - **pipelined**: three multipliers, one per Horner step, C and D travelling with their
//!   pixel; one pixel per clock.
//!
//! MUL is a signed 32 × UQ1.15 multiplier, `MulS32U16Round`: two 16×16 DSP slices (so serial 2,
//! pipelined 6 SB_MAC16).
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a span's words (taken when `ready`) |
//! | `i1` … `i4` | in | I(0), I(1), I(1/2), I(1/4): signed Q11.5, LSB units of the 8-bit channel |
//! | `step` | in | round(2²⁷/m), UQ1.27 (28 bits; 0 for m = 0) |
//! | `m` | in | pixels − 1 (12 bits) |
//! | `ready` | out | a `load` now is taken (idle, or the span's last pixel is being formed) |
//! | `valid`, `t`, `value`, `last` | out | pixel t of the span, 8 bits (rounded, saturated 0..=255); `last` with pixel m |
//!
//! # Pipeline, latency, throughput
//! ```text
//! load   coefficient block (combinational) → A, B, C, D registers; t = 0, p accumulator = 0
//! state  p = min((acc + 2¹¹) >> 12, 1.0) (UQ1.15); serial: phases 0, 1, 2; pipelined: stage 1
//!        (A·p + B), stage 2 (·p + C), output (·p + D)
//! ```
//! Load → first pixel 4 clocks in both variants (state → pixel 3). Serial: 3(m + 1) clocks per
//! span; pipelined: m + 1. The next span's load is taken in the clock forming the last pixel, so
//! spans follow without a gap.
//!
//! # Overflow
//! None can occur: |A|, |B| < 2²⁹, |C| < 2²⁷ for any sample words (units 2⁻¹²), so every
//! Horner value is below 2³¹ in magnitude (p ≤ 1) and the 32-bit words are exact. The output
//! saturates to 0..=255 (negative → 0).
//!
//! # Error budget (vs `golden::horner_unit::HornerWords::value`, the f64 cubic of the same
//! samples at p = t/m)
//! ½ LSB (output rounding) + 3·2⁻¹³ (product roundings) + (3|A| + 2|B| + |C|)·2⁻¹⁵ (p's error:
//! accumulated step ≤ m·2⁻²⁸, rounding to UQ1.15 2⁻¹⁶): `HornerWords::error_bound`.

use rust_hdl::prelude::*;

use crate::primitives::MulS32U16Round;
use crate::registry::{BlockParams, Options};

/// The variant (`horner=serial|pipelined`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct HornerParams {
    pub pipelined: bool,
}

impl BlockParams for HornerParams {
    const KEYS: &'static [&'static str] = &["horner"];
    /// `horner=serial` (default: fig. 2.6, one multiplier, three clocks per pixel) or
    /// `pipelined` (three multipliers, one pixel per clock).
    fn from_options(o: &Options) -> Result<Self, String> {
        match o.get("horner").unwrap_or("serial") {
            "serial" => Ok(HornerParams { pipelined: false }),
            "pipelined" => Ok(HornerParams { pipelined: true }),
            other => Err(format!(
                "unknown Horner variant {other:?} (expected serial or pipelined)"
            )),
        }
    }
    fn describe(&self) -> Option<String> {
        Some(
            if self.pipelined {
                "Horner pipelined (3 multipliers, 1 pixel per clock)"
            } else {
                "Horner serial, fig. 2.6 (1 multiplier, 3 clocks per pixel)"
            }
            .into(),
        )
    }
    fn test_sets() -> Vec<Options> {
        ["serial", "pipelined"]
            .map(|v| Options::new().with("horner", v))
            .to_vec()
    }
    /// MUL is two 16×16 slices: serial 2, pipelined 6.
    fn multipliers(&self) -> Option<usize> {
        Some(if self.pipelined { 6 } else { 2 })
    }
}

crate::hw_block! {
    /// A Horner value (signed, units 2⁻¹², |v| < 2³⁰) → 8 bits: +2¹¹, drop 12, saturate to
    /// 0..=255. Combinational.
    pub struct RoundSat8 {
        in { v: Bits<32> }
        out { q: Bits<8> }
        half: Constant<Bits<32>> = Constant::new((1u64 << 11).into()),
        rnd: Signal<Local, Bits<32>>,
    }
}

impl Logic for RoundSat8 {
    #[hdl_gen]
    fn update(&mut self) {
        self.rnd.next = self.v.val() + self.half.val();
        if self.rnd.val().get_bit(31) {
            self.q.next = 0.into();
        } else if self.rnd.val().get_bits::<11>(20).any() {
            self.q.next = 255.into();
        } else {
            self.q.next = self.rnd.val().get_bits::<8>(12);
        }
    }
}

crate::hw_block! {
    /// The Horner unit (see the module header).
    pub struct HornerUnit(clock) as "horner-unit" {
        summary: "a span's I(0), I(1), I(1/2), I(1/4) in, the cubic I(t/m) per pixel out: shift-and-add coefficient block, Horner by fig. 2.6 (serial) or pipelined (SPEC §9)",
        latency: 4 => "load to the first pixel; serial 3 clocks per pixel, pipelined 1",
        multipliers: 2,
        in { load: Bit, i1: Bits<16>, i2: Bits<16>, i3: Bits<16>, i4: Bits<16>, step: Bits<28>, m: Bits<12> }
        out { ready: Bit, valid: Bit, t: Bits<12>, value: Bits<8>, last: Bit }
        pipelined: Constant<Bit> = Constant::new(p.pipelined),
        sext: Constant<Bits<32>> = Constant::new(0xFFFF_0000u64.into()),
        p_half: Constant<Bits<29>> = Constant::new((1u64 << 11).into()),
        p_one: Constant<Bits<16>> = Constant::new(0x8000u64.into()),
        // Coefficient block.
        s: [Signal<Local, Bits<32>>; 4],
        na: Signal<Local, Bits<32>>, nb: Signal<Local, Bits<32>>, nc: Signal<Local, Bits<32>>,
        ta: Signal<Local, Bits<32>>, tc: Signal<Local, Bits<32>>,
        // State.
        busy: DFF<Bit>, phase: DFF<Bits<2>>, t_q: DFF<Bits<12>>, m_q: DFF<Bits<12>>,
        acc: DFF<Bits<29>>, step_q: DFF<Bits<28>>,
        ka: DFF<Bits<32>>, kb: DFF<Bits<32>>, kc: DFF<Bits<32>>, kd: DFF<Bits<32>>,
        rg: DFF<Bits<32>>,
        p_rnd: Signal<Local, Bits<29>>, p: Signal<Local, Bits<16>>,
        is_last: Signal<Local, Bit>, adv: Signal<Local, Bit>, rdy: Signal<Local, Bit>,
        // Serial datapath (fig. 2.6).
        mx1: Signal<Local, Bits<32>>, mx2: Signal<Local, Bits<32>>,
        mul: MulS32U16Round, bk: Signal<Local, Bits<32>>, sm: Signal<Local, Bits<32>>,
        out_s: RoundSat8,
        // Pipelined datapath.
        mul1: MulS32U16Round, mul2: MulS32U16Round, mul3: MulS32U16Round,
        s1_v: DFF<Bit>, s1_t: DFF<Bits<12>>, s1_l: DFF<Bit>, s1_p: DFF<Bits<16>>,
        s1_x: DFF<Bits<32>>, s1_c: DFF<Bits<32>>, s1_d: DFF<Bits<32>>,
        s2_v: DFF<Bit>, s2_t: DFF<Bits<12>>, s2_l: DFF<Bit>, s2_p: DFF<Bits<16>>,
        s2_x: DFF<Bits<32>>, s2_d: DFF<Bits<32>>,
        x3: Signal<Local, Bits<32>>, out_p: RoundSat8,
        // Output register.
        o_v: DFF<Bit>, o_t: DFF<Bits<12>>, o_val: DFF<Bits<8>>, o_l: DFF<Bit>,
    }
    new(p: &HornerParams);
}

impl Logic for HornerUnit {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, busy, phase, t_q, m_q, acc, step_q, ka, kb, kc, kd, rg);
        clock!(
            self, clock, s1_v, s1_t, s1_l, s1_p, s1_x, s1_c, s1_d, s2_v, s2_t, s2_l, s2_p, s2_x,
            s2_d, o_v, o_t, o_val, o_l
        );

        // Coefficient block: the samples sign-extended, then shifts and adds.
        self.s[0].next = bit_cast::<32, 16>(self.i1.val());
        if self.i1.val().get_bit(15) {
            self.s[0].next = bit_cast::<32, 16>(self.i1.val()) | self.sext.val();
        }
        self.s[1].next = bit_cast::<32, 16>(self.i2.val());
        if self.i2.val().get_bit(15) {
            self.s[1].next = bit_cast::<32, 16>(self.i2.val()) | self.sext.val();
        }
        self.s[2].next = bit_cast::<32, 16>(self.i3.val());
        if self.i3.val().get_bit(15) {
            self.s[2].next = bit_cast::<32, 16>(self.i3.val()) | self.sext.val();
        }
        self.s[3].next = bit_cast::<32, 16>(self.i4.val());
        if self.i4.val().get_bit(15) {
            self.s[3].next = bit_cast::<32, 16>(self.i4.val()) | self.sext.val();
        }
        // N_a = I2 + 8·I4 − 3·I1 − 6·I3
        self.na.next = self.s[1].val() + (self.s[3].val() << 3)
            - ((self.s[0].val() << 1) + self.s[0].val())
            - ((self.s[2].val() << 2) + (self.s[2].val() << 1));
        // N_b = 7·I1 − I2 + 10·I3 − 16·I4
        self.nb.next = ((self.s[0].val() << 3) - self.s[0].val()) - self.s[1].val()
            + ((self.s[2].val() << 3) + (self.s[2].val() << 1))
            - (self.s[3].val() << 4);
        // N_c = I2 + 32·I4 − 21·I1 − 12·I3
        self.nc.next = self.s[1].val() + (self.s[3].val() << 5)
            - ((self.s[0].val() << 4) + (self.s[0].val() << 2) + self.s[0].val())
            - ((self.s[2].val() << 3) + (self.s[2].val() << 2));
        // T(v) = 64v − 16v − 4v − v (128·(1/2 − 1/8 − 1/32 − 1/128)·v)
        self.ta.next =
            (self.na.val() << 6) - (self.na.val() << 4) - (self.na.val() << 2) - self.na.val();
        self.tc.next =
            (self.nc.val() << 6) - (self.nc.val() << 4) - (self.nc.val() << 2) - self.nc.val();

        // p = t·step rounded to UQ1.15, clamped at 1.0.
        self.p_rnd.next = self.acc.q.val() + self.p_half.val();
        self.p.next = self.p_rnd.val().get_bits::<16>(12);
        if self.p_rnd.val().get_bit(28) | (self.p_rnd.val().get_bits::<16>(12) > self.p_one.val()) {
            self.p.next = self.p_one.val();
        }
        self.is_last.next = self.t_q.q.val() == self.m_q.q.val();
        self.adv.next = self.pipelined.val() | (self.phase.q.val() == 2);
        self.rdy.next = !self.busy.q.val() | (self.adv.val() & self.is_last.val());

        // Serial datapath: MX1, MUL, BK, MX2, Sm.
        self.mx1.next = self.rg.q.val();
        if self.phase.q.val() == 0 {
            self.mx1.next = self.ka.q.val();
        }
        self.mx2.next = self.kd.q.val();
        if self.phase.q.val() == 0 {
            self.mx2.next = self.kb.q.val();
        } else if self.phase.q.val() == 1 {
            self.mx2.next = self.kc.q.val();
        }
        self.mul.x.next = self.mx1.val();
        self.mul.p.next = self.p.val();
        self.bk.next = 0.into();
        if self.busy.q.val() {
            self.bk.next = self.mul.r.val().get_bits::<32>(0);
        }
        self.sm.next = self.bk.val() + self.mx2.val();
        if self.phase.q.val() != 2 {
            self.rg.d.next = self.sm.val();
        }
        self.out_s.v.next = self.sm.val();

        // Pipelined datapath.
        self.mul1.x.next = self.ka.q.val();
        self.mul1.p.next = self.p.val();
        self.s1_v.d.next = self.busy.q.val();
        self.s1_t.d.next = self.t_q.q.val();
        self.s1_l.d.next = self.is_last.val();
        self.s1_p.d.next = self.p.val();
        self.s1_x.d.next = self.mul1.r.val().get_bits::<32>(0) + self.kb.q.val();
        self.s1_c.d.next = self.kc.q.val();
        self.s1_d.d.next = self.kd.q.val();
        self.mul2.x.next = self.s1_x.q.val();
        self.mul2.p.next = self.s1_p.q.val();
        self.s2_v.d.next = self.s1_v.q.val();
        self.s2_t.d.next = self.s1_t.q.val();
        self.s2_l.d.next = self.s1_l.q.val();
        self.s2_p.d.next = self.s1_p.q.val();
        self.s2_x.d.next = self.mul2.r.val().get_bits::<32>(0) + self.s1_c.q.val();
        self.s2_d.d.next = self.s1_d.q.val();
        self.mul3.x.next = self.s2_x.q.val();
        self.mul3.p.next = self.s2_p.q.val();
        self.x3.next = self.mul3.r.val().get_bits::<32>(0) + self.s2_d.q.val();
        self.out_p.v.next = self.x3.val();

        // Output register.
        if self.pipelined.val() {
            self.o_v.d.next = self.s2_v.q.val();
            self.o_t.d.next = self.s2_t.q.val();
            self.o_val.d.next = self.out_p.q.val();
            self.o_l.d.next = self.s2_v.q.val() & self.s2_l.q.val();
        } else {
            self.o_v.d.next = self.busy.q.val() & (self.phase.q.val() == 2);
            self.o_t.d.next = self.t_q.q.val();
            self.o_val.d.next = self.out_s.q.val();
            self.o_l.d.next = self.busy.q.val() & (self.phase.q.val() == 2) & self.is_last.val();
        }

        // Walk along the span.
        if self.busy.q.val() & self.adv.val() {
            if self.is_last.val() {
                self.busy.d.next = false;
            } else {
                self.t_q.d.next = self.t_q.q.val() + 1;
                self.acc.d.next = self.acc.q.val() + bit_cast::<29, 28>(self.step_q.q.val());
            }
        }
        if self.busy.q.val() & !self.pipelined.val() {
            if self.phase.q.val() == 2 {
                self.phase.d.next = 0.into();
            } else {
                self.phase.d.next = self.phase.q.val() + 1;
            }
        }
        if self.load.val() & self.rdy.val() {
            self.busy.d.next = true;
            self.phase.d.next = 0.into();
            self.t_q.d.next = 0.into();
            self.acc.d.next = 0.into();
            self.m_q.d.next = self.m.val();
            self.step_q.d.next = self.step.val();
            self.ka.d.next = self.ta.val() << 3;
            self.kb.d.next = self.nb.val() << 8;
            self.kc.d.next = self.tc.val();
            self.kd.d.next = self.s[0].val() << 7;
        }

        self.ready.next = self.rdy.val();
        self.valid.next = self.o_v.q.val();
        self.t.next = self.o_t.q.val();
        self.value.next = self.o_val.q.val();
        self.last.next = self.o_l.q.val();
    }
}
