//! The Horner unit of fig. 2.6 (SPEC §9; golden: `golden::units::horner_unit`): one colour channel of
//! cubic shading along a span.
//!
//! ```text
//! A = 8·T(I2 + 8·I4 − 3·I1 − 6·I3)   B = 256·(7·I1 − I2 + 10·I3 − 16·I4)
//! C = T(I2 + 32·I4 − 21·I1 − 12·I3)  D = 128·I1        T(v) = 64v − 16v − 4v − v = 128·v/3 (≈)
//! I(p) = ((A·p + B)·p + C)·p + D     p = t·step, step = 2²⁷/m, t = 0 … m
//! ```
//! The coefficient block is shifts and adds only (the thesis' 1/3 ≈ 1/2 − 1/8 − 1/32 − 1/128,
//! times 128: exact integers), with the project's grouping of A and C (difference numerators,
//! `golden::shading::cubic`). Two variants, a build parameter (`horner=serial|pipelined`):
//!
//! - **serial** (fig. 2.6): register RG, MX1 (A or RG into the multiplier), MX2 (B, C or D into
//!   the adder), one multiplier MUL, one adder Sm; step 0: A·p + B, step 1: RG·p + C, step 2:
//!   out ← RG·p + D. Three clocks per pixel. The MUL–Sm loop is four registers deep (OP: the
//!   operands; PR: the two 16×16 products and, beside them, the addend k·2¹⁵ + 2¹⁴ − \[x<0\]·p·2³²;
//!   PT: the 48-bit partial sum; RG), so three pixels are in the loop at once, interleaved: a
//!   free-running phase (1, 2, 0) issues the walk's next pixel's step 0 in phase 1 and the
//!   recirculated RG in phases 2 and 0, RG always holding the same pixel's previous step. This
//!   is the register placement, not a different computation: every pixel still takes its three
//!   steps through the one multiplier pair and one adder. (Until 2026-11 the loop was a single
//!   register, MUL and Sm in one clock: 44.1 MHz on ECP5; fig. 2.6's BK, which zeroed the
//!   product of an idle unit, is the item's valid bit now.)
//! - **pipelined**: three multipliers, one per Horner step, C and D travelling with their
//!   pixel; one pixel per clock. Each step is the serial loop's PR, PT and R registers
//!   without the loop (`HornerStep`, 3 clocks), after a register Q holding the issued pixel's
//!   p and its span's A..D; the result is delayed 2 clocks to the serial latency, so both
//!   variants have one latency (the build parameter changes no timing seen at the ports
//!   except the clocks per pixel). Until 2026-11-25 each step was one clock (the 32×16
//!   product and both adds): 50.3 MHz on ECP5 in `cubic-stream`, and a 10-clock pad.
//!
//! Serial MUL is two 16×16 DSP slices formed in the loop as above; each pipelined step has its
//! own two (serial 2, pipelined 6 SB_MAC16).
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a span's words (taken when `ready`) |
//! | `i1` … `i4` | in | I(0), I(1), I(1/2), I(1/4): signed Q11.5, LSB units of the 8-bit channel |
//! | `step` | in | round(2²⁷/m), UQ1.27 (28 bits; 0 for m = 0) |
//! | `m` | in | pixels − 1 (12 bits) |
//! | `hold` | in | back-pressure from a stream top: no pixel enters the datapath this clock, the walk does not move on, no span is taken (`ready` low); pixels already in it run on |
//! | `ready` | out | a `load` now is taken (idle, or the span's last pixel is being formed; low under `hold`) |
//! | `valid`, `t`, `value`, `done` | out | pixel t of the span, 8 bits (rounded, saturated 0..=255); `done` with pixel m |
//!
//! # Pipeline, latency, throughput
//! ```text
//! load   coefficient block (combinational) → A, B, C, D registers; t = 0, p accumulator = 0
//! state  p = min((acc + 2¹¹) >> 12, 1.0) (UQ1.15), advanced once per pixel
//! serial     OP → PR → PT → RG, three times round the loop per pixel, then RoundSat8 → output
//! pipelined  Q → step 1 (A·p + B) → step 2 (·p + C) → step 3 (·p + D), 3 clocks each (PR → PT → R)
//!            → RoundSat8 → 2-clock pad → output
//! ```
//! Load → first pixel 14 clocks in both variants. Serial: 3(m + 1) clocks per span, and a span
//! is taken only in phase 0 (idle: `ready` every third clock; busy: in the clock its last pixel
//! is issued, so spans follow without a gap); pipelined: m + 1 clocks per span, `ready`
//! whenever idle or on the last pixel. Serial, the output register is loaded when a pixel
//! leaves RG (phase 1) and holds between pixels.
//!
//! `hold` (0 in every use without a stream top) makes the walk stand still: pipelined, the
//! clock issues no pixel and t does not advance; serial, it matters in the issue clock (phase
//! 1): the slot carries no pixel, the register `issued` stays low and phase 0 does not move on,
//! so the same pixel is issued in the next slot (a held phase 0 only blocks a load). Nothing is
//! lost or repeated; each held slot delays the rest of the span by one slot (3 clocks serial,
//! 1 pipelined). Up to 14 clocks of pixels already issued still come out after `hold` rises.
//!
//! # Overflow
//! None can occur: |A|, |B| < 2²⁹, |C| < 2²⁷ for any sample words (units 2⁻¹²), so every
//! Horner value is below 2³¹ in magnitude (p ≤ 1) and the 32-bit words are exact. The output
//! saturates to 0..=255 (negative → 0).
//!
//! # Error budget (vs `golden::units::horner_unit::HornerWords::value`, the f64 cubic of the same
//! samples at p = t/m)
//! ½ LSB (output rounding) + 3·2⁻¹³ (product roundings) + (3|A| + 2|B| + |C|)·2⁻¹⁵ (p's error:
//! accumulated step ≤ m·2⁻²⁸, rounding to UQ1.15 2⁻¹⁶): `HornerWords::error_bound`.
//!
//! Latency (the block's `LATENCY`): 14 clocks, load to the first pixel; serial 3 clocks per pixel, pipelined 1.

use rust_hdl::prelude::*;

use crate::core::primitives::Delay;
use crate::core::registry::{BlockParams, Options};

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

/// Clocks of one pipelined Horner step ([`HornerStep`]).
pub const STEP_CLOCKS: usize = 3;
/// The pipelined variant's pad to the serial latency: from a pixel's issue to the output
/// register's input is 12 clocks in both variants; the pipelined datapath takes Q (1) and
/// three steps.
const PIPE_PAD: usize = 12 - 1 - 3 * STEP_CLOCKS;

crate::hw_block! {
    /// One Horner step of the pipelined variant, `r = ((x·p + 2¹⁴) >> 15) + k (mod 2³²)`, bit
    /// for bit as the serial loop's step, in [`STEP_CLOCKS`] clocks, the serial loop's
    /// registers without the loop: PR (the two unsigned 16×16 products x_lo·p, x_hi·p and
    /// beside them kk = k·2¹⁵ + 2¹⁴ − \[x < 0\]·p·2³², 48 bits), PT (x_hi·p·2¹⁶ + x_lo·p, mod
    /// 2⁴⁸), R ((PT + kk) >> 15). Inputs from registers; `x` signed Q-format, `p` UQ1.15,
    /// `k` and `r` signed, 32 bits. Exact mod 2³² (|x·p| < 2⁴⁷). One step per clock.
    pub struct HornerStep(clock) {
        in { x: Bits<32>, p: Bits<16>, k: Bits<32> }
        out { r: Bits<32> }
        pr_lo: DFF<Bits<32>>, pr_hi: DFF<Bits<32>>, pr_kk: DFF<Bits<48>>,
        kk_k: Signal<Local, Bits<48>>, kk_corr: Signal<Local, Bits<48>>,
        pt_s: DFF<Bits<48>>, pt_kk: DFF<Bits<48>>,
        r_q: DFF<Bits<32>>, rg_sum: Signal<Local, Bits<48>>,
        sext48: Constant<Bits<48>> = Constant::new(0xFFFF_0000_0000u64.into()),
        half48: Constant<Bits<48>> = Constant::new((1u64 << 14).into()),
    }
}

impl Logic for HornerStep {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, pr_lo, pr_hi, pr_kk, pt_s, pt_kk, r_q);
        self.pr_lo.d.next = self.x.val().get_bits::<16>(0) * self.p.val();
        self.pr_hi.d.next = self.x.val().get_bits::<16>(16) * self.p.val();
        self.kk_k.next = bit_cast::<48, 32>(self.k.val());
        if self.k.val().get_bit(31) {
            self.kk_k.next = bit_cast::<48, 32>(self.k.val()) | self.sext48.val();
        }
        self.kk_corr.next = 0.into();
        if self.x.val().get_bit(31) {
            self.kk_corr.next = bit_cast::<48, 16>(self.p.val()) << 32;
        }
        self.pr_kk.d.next = ((self.kk_k.val() << 15) | self.half48.val()) - self.kk_corr.val();
        self.pt_s.d.next =
            (bit_cast::<48, 32>(self.pr_hi.q.val()) << 16) + bit_cast::<48, 32>(self.pr_lo.q.val());
        self.pt_kk.d.next = self.pr_kk.q.val();
        self.rg_sum.next = self.pt_s.q.val() + self.pt_kk.q.val();
        self.r_q.d.next = self.rg_sum.val().get_bits::<32>(15);
        self.r.next = self.r_q.q.val();
    }
}

crate::hw_block! {
    /// The Horner unit (see the module header).
    pub struct HornerUnit(clock) as "horner-unit" {
        summary: "a span's I(0), I(1), I(1/2), I(1/4) in, the cubic I(t/m) per pixel out: shift-and-add coefficient block, Horner by fig. 2.6 (serial) or pipelined (SPEC §9)",
        latency: 14 => "load to the first pixel; serial 3 clocks per pixel, pipelined 1",
        multipliers: 2,
        in { load: Bit, i1: Bits<16>, i2: Bits<16>, i3: Bits<16>, i4: Bits<16>, step: Bits<28>, m: Bits<12>, hold: Bit }
        out { ready: Bit, valid: Bit, t: Bits<12>, value: Bits<8>, done: Bit }
        pipelined: Constant<Bit> = Constant::new(p.pipelined),
        sext: Constant<Bits<32>> = Constant::new(0xFFFF_0000u64.into()),
        p_half: Constant<Bits<29>> = Constant::new((1u64 << 11).into()),
        p_one: Constant<Bits<16>> = Constant::new(0x8000u64.into()),
        // Coefficient block.
        s: [Signal<Local, Bits<32>>; 4],
        na: Signal<Local, Bits<32>>, nb: Signal<Local, Bits<32>>, nc: Signal<Local, Bits<32>>,
        // State.
        busy: DFF<Bit>, phase: DFF<Bits<2>>, t_q: DFF<Bits<12>>, m_q: DFF<Bits<12>>,
        acc: DFF<Bits<29>>, step_q: DFF<Bits<28>>,
        kb: DFF<Bits<32>>, kd: DFF<Bits<32>>,
        /// N_a and N_c registered at load, T(·) formed after the register (the path inputs →
        /// N → T → register was 12.9 ns on ECP5 in the serial variant, 12.3 in the pipelined
        /// one); A and C are first used a clock later (an issue clock follows its load).
        na_q: DFF<Bits<32>>, nc_q: DFF<Bits<32>>,
        ta_q: Signal<Local, Bits<32>>, tc_q: Signal<Local, Bits<32>>,
        p_rnd: Signal<Local, Bits<29>>, p: Signal<Local, Bits<16>>,
        is_last: Signal<Local, Bit>, adv: Signal<Local, Bit>, rdy: Signal<Local, Bit>,
        /// Serial: the walk's pixel went into the loop in the last issue clock (phase 1), so
        /// phase 0 moves on to the next pixel; a held issue clock leaves it low and the same
        /// pixel is issued in the next slot.
        issued: DFF<Bit>,
        /// The pixel now issued goes into the datapath (busy, not held); the walk moves on.
        go: Signal<Local, Bit>, walk: Signal<Local, Bit>, fin: Signal<Local, Bit>,
        // Serial datapath (fig. 2.6, the MUL–Sm loop in four registers: OP, PR, PT, RG).
        // C and D travel with their pixel (a pixel is in the loop for 12 clocks, so up to four
        // spans of one pixel each can be in it at once).
        op_v: DFF<Bit>, op_t: DFF<Bits<12>>, op_l: DFF<Bit>, op_x: DFF<Bits<32>>,
        op_p: DFF<Bits<16>>, op_k: DFF<Bits<32>>, op_c: DFF<Bits<32>>, op_d: DFF<Bits<32>>,
        pr_v: DFF<Bit>, pr_t: DFF<Bits<12>>, pr_l: DFF<Bit>, pr_p: DFF<Bits<16>>, pr_c: DFF<Bits<32>>, pr_d: DFF<Bits<32>>,
        pr_lo: DFF<Bits<32>>, pr_hi: DFF<Bits<32>>, pr_kk: DFF<Bits<48>>,
        kk_k: Signal<Local, Bits<48>>, kk_corr: Signal<Local, Bits<48>>,
        pt_v: DFF<Bit>, pt_t: DFF<Bits<12>>, pt_l: DFF<Bit>, pt_p: DFF<Bits<16>>, pt_c: DFF<Bits<32>>, pt_d: DFF<Bits<32>>,
        pt_s: DFF<Bits<48>>, pt_kk: DFF<Bits<48>>,
        rg_v: DFF<Bit>, rg_t: DFF<Bits<12>>, rg_l: DFF<Bit>, rg_p: DFF<Bits<16>>, rg_c: DFF<Bits<32>>, rg_d: DFF<Bits<32>>,
        rg_val: DFF<Bits<32>>,
        rg_sum: Signal<Local, Bits<48>>,
        sext48: Constant<Bits<48>> = Constant::new(0xFFFF_0000_0000u64.into()),
        half48: Constant<Bits<48>> = Constant::new((1u64 << 14).into()),
        out_s: RoundSat8,
        /// The pipelined variant's outputs, padded to the serial latency.
        pd_v: Delay<Bit, PIPE_PAD>, pd_t: Delay<Bits<12>, PIPE_PAD>,
        pd_val: Delay<Bits<8>, PIPE_PAD>, pd_l: Delay<Bit, PIPE_PAD>,
        // Pipelined datapath: the issued pixel's operands registered (Q), then three Horner
        // steps of STEP_CLOCKS each; p, C, D and the pixel's tags travel beside them.
        q_v: DFF<Bit>, q_t: DFF<Bits<12>>, q_l: DFF<Bit>, q_p: DFF<Bits<16>>,
        q_a: DFF<Bits<32>>, q_b: DFF<Bits<32>>, q_c: DFF<Bits<32>>, q_d: DFF<Bits<32>>,
        step1: HornerStep, step2: HornerStep, step3: HornerStep,
        p_d1: Delay<Bits<16>, STEP_CLOCKS>, p_d2: Delay<Bits<16>, STEP_CLOCKS>,
        c_d1: Delay<Bits<32>, STEP_CLOCKS>, d_d2: Delay<Bits<32>, { 2 * STEP_CLOCKS }>,
        v_d3: Delay<Bit, { 3 * STEP_CLOCKS }>, t_d3: Delay<Bits<12>, { 3 * STEP_CLOCKS }>,
        l_d3: Delay<Bit, { 3 * STEP_CLOCKS }>,
        out_p: RoundSat8,
        // Output register.
        o_v: DFF<Bit>, o_t: DFF<Bits<12>>, o_val: DFF<Bits<8>>, o_l: DFF<Bit>,
    }
    new(p: &HornerParams);
}

impl Logic for HornerUnit {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, busy, t_q, m_q, acc, step_q, kb, kd, nc_q, na_q, o_t, o_val, issued
        );
        clock!(
            self, clock, phase, q_v, q_t, q_l, q_p, q_a, q_b, q_c, q_d, step1, step2, step3, p_d1,
            p_d2, c_d1, d_d2, v_d3, t_d3, l_d3, o_v, o_l, op_v, op_t, op_l, op_x, op_p, op_k, op_c,
            op_d, pr_v, pr_t, pr_l, pr_p, pr_c, pr_d, pr_lo, pr_hi, pr_kk, pt_v, pt_t, pt_l, pt_p,
            pt_c, pt_d, pt_s, pt_kk, rg_v, rg_t, rg_l, rg_p, rg_c, rg_d, rg_val, pd_v, pd_t,
            pd_val, pd_l
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

        // p = t·step rounded to UQ1.15, clamped at 1.0.
        self.p_rnd.next = self.acc.q.val() + self.p_half.val();
        self.p.next = self.p_rnd.val().get_bits::<16>(12);
        if self.p_rnd.val().get_bit(28) | (self.p_rnd.val().get_bits::<16>(12) > self.p_one.val()) {
            self.p.next = self.p_one.val();
        }
        self.is_last.next = self.t_q.q.val() == self.m_q.q.val();
        self.adv.next = self.pipelined.val() | (self.phase.q.val() == 0);
        // hold: no pixel enters the datapath (serial: in an issue clock, phase 1), the walk
        // does not move on, no span is taken.
        self.go.next = self.busy.q.val() & !self.hold.val();
        if self.pipelined.val() {
            self.walk.next = self.go.val();
        } else {
            self.walk.next = (self.phase.q.val() == 0) & self.busy.q.val() & self.issued.q.val();
        }
        self.fin.next = self.is_last.val() & (self.pipelined.val() | self.issued.q.val());
        self.rdy.next = self.adv.val() & !self.hold.val() & (!self.busy.q.val() | self.fin.val());
        if self.phase.q.val() == 1 {
            self.issued.d.next = self.go.val();
        }

        // T(v) = 64v − 16v − 4v − v (128·(1/2 − 1/8 − 1/32 − 1/128)·v), after the N registers.
        self.ta_q.next = (self.na_q.q.val() << 6)
            - (self.na_q.q.val() << 4)
            - (self.na_q.q.val() << 2)
            - self.na_q.q.val();
        self.tc_q.next = (self.nc_q.q.val() << 6)
            - (self.nc_q.q.val() << 4)
            - (self.nc_q.q.val() << 2)
            - self.nc_q.q.val();

        // Serial datapath. The phase runs free (1: step 0 of the walk's pixel, A·p + B;
        // 2: step 1, RG·p + C; 0: step 2, RG·p + D); RG holds the value issued four clocks
        // before, i.e. the same pixel's previous step, so three pixels are in the loop at once.
        if self.phase.q.val() == 1 {
            self.op_v.d.next = self.go.val();
            self.op_t.d.next = self.t_q.q.val();
            self.op_l.d.next = self.is_last.val();
            self.op_x.d.next = self.ta_q.val() << 3;
            self.op_p.d.next = self.p.val();
            self.op_k.d.next = self.kb.q.val();
            self.op_c.d.next = self.tc_q.val();
            self.op_d.d.next = self.kd.q.val();
        } else {
            self.op_v.d.next = self.rg_v.q.val();
            self.op_t.d.next = self.rg_t.q.val();
            self.op_l.d.next = self.rg_l.q.val();
            self.op_x.d.next = self.rg_val.q.val();
            self.op_p.d.next = self.rg_p.q.val();
            self.op_c.d.next = self.rg_c.q.val();
            self.op_d.d.next = self.rg_d.q.val();
            if self.phase.q.val() == 2 {
                self.op_k.d.next = self.rg_c.q.val();
            } else {
                self.op_k.d.next = self.rg_d.q.val();
            }
        }
        // PR: the two 16×16 products; beside them kk = k·2¹⁵ + 2¹⁴ − [x < 0]·p·2³² (48 bits).
        self.pr_v.d.next = self.op_v.q.val();
        self.pr_t.d.next = self.op_t.q.val();
        self.pr_l.d.next = self.op_l.q.val();
        self.pr_p.d.next = self.op_p.q.val();
        self.pr_c.d.next = self.op_c.q.val();
        self.pr_d.d.next = self.op_d.q.val();
        self.pr_lo.d.next = self.op_x.q.val().get_bits::<16>(0) * self.op_p.q.val();
        self.pr_hi.d.next = self.op_x.q.val().get_bits::<16>(16) * self.op_p.q.val();
        self.kk_k.next = bit_cast::<48, 32>(self.op_k.q.val());
        if self.op_k.q.val().get_bit(31) {
            self.kk_k.next = bit_cast::<48, 32>(self.op_k.q.val()) | self.sext48.val();
        }
        self.kk_corr.next = 0.into();
        if self.op_x.q.val().get_bit(31) {
            self.kk_corr.next = bit_cast::<48, 16>(self.op_p.q.val()) << 32;
        }
        self.pr_kk.d.next = ((self.kk_k.val() << 15) | self.half48.val()) - self.kk_corr.val();
        // PT: the unsigned partial product (x_hi·p·2¹⁶ + x_lo·p, mod 2⁴⁸).
        self.pt_v.d.next = self.pr_v.q.val();
        self.pt_t.d.next = self.pr_t.q.val();
        self.pt_l.d.next = self.pr_l.q.val();
        self.pt_p.d.next = self.pr_p.q.val();
        self.pt_c.d.next = self.pr_c.q.val();
        self.pt_d.d.next = self.pr_d.q.val();
        self.pt_s.d.next =
            (bit_cast::<48, 32>(self.pr_hi.q.val()) << 16) + bit_cast::<48, 32>(self.pr_lo.q.val());
        self.pt_kk.d.next = self.pr_kk.q.val();
        // RG: (x·p + 2¹⁴ + k·2¹⁵) >> 15 = mul_round(x, p) + k (mod 2³²).
        self.rg_v.d.next = self.pt_v.q.val();
        self.rg_t.d.next = self.pt_t.q.val();
        self.rg_l.d.next = self.pt_l.q.val();
        self.rg_p.d.next = self.pt_p.q.val();
        self.rg_c.d.next = self.pt_c.q.val();
        self.rg_d.d.next = self.pt_d.q.val();
        self.rg_sum.next = self.pt_s.q.val() + self.pt_kk.q.val();
        self.rg_val.d.next = self.rg_sum.val().get_bits::<32>(15);
        self.out_s.v.next = self.rg_val.q.val();

        // Pipelined datapath: Q holds the issued pixel's p, t, last and its span's A..D (the
        // span registers change at the next load); step 1 A·p + B, step 2 ·p + C, step 3
        // ·p + D, each STEP_CLOCKS deep.
        self.q_v.d.next = self.go.val();
        self.q_t.d.next = self.t_q.q.val();
        self.q_l.d.next = self.is_last.val();
        self.q_p.d.next = self.p.val();
        self.q_a.d.next = self.ta_q.val() << 3;
        self.q_b.d.next = self.kb.q.val();
        self.q_c.d.next = self.tc_q.val();
        self.q_d.d.next = self.kd.q.val();
        self.step1.x.next = self.q_a.q.val();
        self.step1.p.next = self.q_p.q.val();
        self.step1.k.next = self.q_b.q.val();
        self.p_d1.d.next = self.q_p.q.val();
        self.c_d1.d.next = self.q_c.q.val();
        self.step2.x.next = self.step1.r.val();
        self.step2.p.next = self.p_d1.q.val();
        self.step2.k.next = self.c_d1.q.val();
        self.p_d2.d.next = self.p_d1.q.val();
        self.d_d2.d.next = self.q_d.q.val();
        self.step3.x.next = self.step2.r.val();
        self.step3.p.next = self.p_d2.q.val();
        self.step3.k.next = self.d_d2.q.val();
        self.v_d3.d.next = self.q_v.q.val();
        self.t_d3.d.next = self.q_t.q.val();
        self.l_d3.d.next = self.q_l.q.val();
        self.out_p.v.next = self.step3.r.val();

        self.pd_v.d.next = self.v_d3.q.val();
        self.pd_t.d.next = self.t_d3.q.val();
        self.pd_val.d.next = self.out_p.q.val();
        self.pd_l.d.next = self.v_d3.q.val() & self.l_d3.q.val();

        // Output register (serial: loaded with a finished pixel, held otherwise).
        if self.pipelined.val() {
            self.o_v.d.next = self.pd_v.q.val();
            self.o_t.d.next = self.pd_t.q.val();
            self.o_val.d.next = self.pd_val.q.val();
            self.o_l.d.next = self.pd_l.q.val();
        } else {
            self.o_v.d.next = (self.phase.q.val() == 1) & self.rg_v.q.val();
            self.o_l.d.next = (self.phase.q.val() == 1) & self.rg_v.q.val() & self.rg_l.q.val();
            if (self.phase.q.val() == 1) & self.rg_v.q.val() {
                self.o_t.d.next = self.rg_t.q.val();
                self.o_val.d.next = self.out_s.q.val();
            }
        }

        // Walk along the span.
        if self.walk.val() {
            if self.is_last.val() {
                self.busy.d.next = false;
            } else {
                self.t_q.d.next = self.t_q.q.val() + 1;
                self.acc.d.next = self.acc.q.val() + bit_cast::<29, 28>(self.step_q.q.val());
            }
        }
        if self.phase.q.val() == 2 {
            self.phase.d.next = 0.into();
        } else {
            self.phase.d.next = self.phase.q.val() + 1;
        }
        if self.load.val() & self.rdy.val() {
            self.busy.d.next = true;
            self.t_q.d.next = 0.into();
            self.acc.d.next = 0.into();
            self.m_q.d.next = self.m.val();
            self.step_q.d.next = self.step.val();
            self.kb.d.next = self.nb.val() << 8;
            self.kd.d.next = self.s[0].val() << 7;
            self.na_q.d.next = self.na.val();
            self.nc_q.d.next = self.nc.val();
        }

        self.ready.next = self.rdy.val();
        self.valid.next = self.o_v.q.val();
        self.t.next = self.o_t.q.val();
        self.value.next = self.o_val.q.val();
        self.done.next = self.o_l.q.val();
    }
}
