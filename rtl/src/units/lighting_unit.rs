//! Lighting unit (SPEC §0 lighting with the SPEC §1 normalizer in front; golden:
//! `golden::units::lighting_unit`): the interpolated normal in, the two cosines of Blinn lighting out.
//!
//! ```text
//! N' = N·f(|N|²)                      (the normalizer, patent 63343: no division, no root)
//! cos φ = max(N'·L, 0),  cos γ = max(N'·H, 0),   H = (L + V)/|L + V|  (Blinn)
//! ```
//! Lambert lighting uses cos φ only: the set-up loads zero specular weights into the colour
//! combine, so cos γ is computed and ignored. Phong lighting (cos = R·V = 2(N'·L)(N'·V) − L·V)
//! is not built: it would need a third dot product, a multiply and a subtract per pixel for a
//! model the sources call the more expensive one; the RTL engine rejects `--lighting phong`.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `valid_in` | in | 1 = x, y, z hold a normal this clock |
//! | `x`, `y`, `z` | in | signed Q2.17 (19 bits): the interpolated (unnormalized) normal |
//! | `lx ly lz`, `hx hy hz` | in | signed Q2.14: unit L and H, registers of the top (sampled when a pixel enters D1, 5 clocks before its output; hold them while pixels are in flight) |
//! | `valid_out` | out | `valid_in` delayed by the latency |
//! | `cos_phi`, `cos_gamma` | out | unsigned Q1.15, registered |
//!
//! # Pipeline
//! ```text
//! N1..N15 the normalizer (`crate::units::normalizer::Normalizer`, coefficient set a build parameter),
//!         N' out in signed Q2.17
//! D1  p = nx·lx … nz·hz     six signed Q2.17 × Q2.14 products in Q4.28, in four clocks
//!                           [DotTerm]: N' split into its top 16 bits ⌊N'/8⌋ (signed Q2.14)
//!                           and its three low bits; ⌊N'/8⌋·u exact on a multiplier in three
//!                           clocks [MulSignedPipe: the operands; ua·ub and the sign
//!                           corrections; their difference]; beside it (low bits)·u by
//!                           shift-add [MulLow3Pipe], floored by 8 into Q4.28; the two added
//!                           in the fourth clock (|p| ≤ 2³⁰ + 2¹⁵: no wrap)
//! D2  s = Σp + 2¹²          three-operand sums, exact (|Σp| ≤ 3·2³⁰: 34 bits), + 2¹²
//!                           (half LSB), formed in two parts so no word is wider than 32 bits
//!                           (the simulator's fast width; the same 34-bit sum, split at bit 16):
//!                           lo = Σ p[15:0] + 2¹² (< 2¹⁸), hs = Σ sext(p[31:16]); hs and
//!                           lo[17:13] registered
//! D3  hi = hs + lo[17:16]    Σp + 2¹² = hi·2¹⁶ + lo[15:0]; then Q4.28 → unsigned Q1.15:
//!                           negative (hi < 0) → 0, ≥ 2 − 2⁻¹⁶ (hi ≥ 2¹³) → 0xFFFF
//!                           (2 − 2⁻¹⁵), else bits 28..13 = hi[12:0] : lo[15:13]
//! ```
//! For ECP5 timing D1's multiply takes three clocks and D2, D3 were one stage (latency 11
//! before, 72.6 MHz: the three-operand sums, the carry add and the clamp in one clock; then the
//! multiply and its sign correction in one clock, 95 MHz). D1's fourth clock came with N' at
//! Q2.17 (before: Q2.14, latency 20).
//! Latency 21 clocks (15 + 6), one pixel per clock, no stall; `valid` travels with the data.
//! 14 multipliers: the normalizer's 8 and the six of D1 (the low parts are shift-adds).
//!
//! # Overflow
//! Nothing wraps: the products are exact but for the low parts' floor, the 34-bit sums cannot
//! overflow for any input words, and the cosines saturate at 0 and 2 − 2⁻¹⁵. A
//! published-coefficient normal is up to 0.35 % long, so cos γ may exceed 1 (by design: the
//! golden model keeps that bias).
//!
//! # Error budget (vs `golden::units::lighting_unit::cosines` on the same quantized N, L, H)
//! The normalizer's per-component bound e (3.73·10⁻⁵ published, 2.65·10⁻⁵ fit on the domain,
//! `crate::units::normalizer::error_budget`) enters each dot product weighted by Σ|u_i| ≤ √3; the
//! floors of the three low-part products add < 3·2⁻²⁸, the sums are exact, the output rounding
//! adds 2⁻¹⁶: |Δcos| ≤ Σ|u_i|·e + 2⁻¹⁶ + 3·2⁻²⁸ ≤ 8.0·10⁻⁵ (published), 6.1·10⁻⁵ (fit), i.e.
//! ≤ 2.6 and 2.0 LSB of Q1.15 (`golden::units::lighting_unit::error_bound`; with 16-bit t1, f and N'
//! before: 6.5 LSB).
//!
//! Measured against the golden f64 front end (N and H unquantized, fitted set):
//! `examples/bump_precision.rs` and `docs/bump-precision.md` give each word's share. N's own
//! rounding in the vector interpolator was the largest (1.4 LSB of Q1.15 on cos γ alone at
//! Q2.14); N is now Q2.17, and K's rounding to Q1.15 and H's to Q2.14 lead.

use rust_hdl::prelude::*;

use crate::core::primitives::{Delay, MulLow3Pipe, MulSignedPipe, SIGNED_MUL_LATENCY};
use crate::units::normalizer::{Normalizer, NormalizerCoeffs};

crate::hw_block! {
    /// The lighting unit: normalizer, then N'·L and N'·H clamped to [0, 2) (see the module
    /// header).
    pub struct LightingUnit(clock) as "lighting-unit" {
        summary: "N in, cos φ = N'·L and cos γ = N'·H out (Q1.15, clamped at 0): normalizer + two dot products (SPEC §0, §1)",
        latency: Normalizer::LATENCY + DotTerm::LATENCY + 2 => "valid_in to valid_out, one pixel per clock",
        multipliers: 14,
        in {
            valid_in: Bit, x: Bits<19>, y: Bits<19>, z: Bits<19>,
            lx: Bits<16>, ly: Bits<16>, lz: Bits<16>,
            hx: Bits<16>, hy: Bits<16>, hz: Bits<16>,
        }
        out { valid_out: Bit, cos_phi: Bits<16>, cos_gamma: Bits<16> }
        // N1..N15
        pub norm: Normalizer = Normalizer::new(c),
        // D1: the six products in the order nx·lx, ny·ly, nz·lz, nx·hx, ny·hy, nz·hz.
        mul: [DotTerm; 6],
        valid_p1: Delay<Bit, { DotTerm::LATENCY }>,
        // D2: each product's high half sign-extended, the two sums in two parts, registered.
        ext: [Signal<Local, Bits<32>>; 6],
        lo_l: Signal<Local, Bits<32>>,
        lo_h: Signal<Local, Bits<32>>,
        /// lo[17:13]: the carry into the high part and the output's three low bits.
        lo_l_q: DFF<Bits<5>>,
        lo_h_q: DFF<Bits<5>>,
        hs_l: DFF<Bits<32>>,
        hs_h: DFF<Bits<32>>,
        sign_ext: Constant<Bits<32>> = Constant::new(0xFFFF_0000u64.into()),
        half_lsb: Constant<Bits<32>> = Constant::new((1u64 << 12).into()),
        valid_p2: DFF<Bit>,
        // D3: the carry into the high part, the clamp.
        hi_l: Signal<Local, Bits<32>>,
        hi_h: Signal<Local, Bits<32>>,
        cos_max: Constant<Bits<16>> = Constant::new(0xFFFF.into()),
        cos_phi_q: DFF<Bits<16>>,
        cos_gamma_q: DFF<Bits<16>>,
        valid_p3: DFF<Bit>,
    }
    new(c: &NormalizerCoeffs);
}

seq_macro::seq!(N in 0..6 {
impl Logic for LightingUnit {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            norm,
            valid_p1,
            lo_l_q,
            lo_h_q,
            hs_l,
            hs_h,
            valid_p2,
            cos_phi_q,
            cos_gamma_q,
            valid_p3
        );
        for i in 0..6 {
            self.mul[i].clock.next = self.clock.val();
        }
        self.norm.valid_in.next = self.valid_in.val();
        self.norm.x.next = self.x.val();
        self.norm.y.next = self.y.val();
        self.norm.z.next = self.z.val();
        // D1
        self.mul[0].a.next = self.norm.nx.val();
        self.mul[0].b.next = self.lx.val();
        self.mul[1].a.next = self.norm.ny.val();
        self.mul[1].b.next = self.ly.val();
        self.mul[2].a.next = self.norm.nz.val();
        self.mul[2].b.next = self.lz.val();
        self.mul[3].a.next = self.norm.nx.val();
        self.mul[3].b.next = self.hx.val();
        self.mul[4].a.next = self.norm.ny.val();
        self.mul[4].b.next = self.hy.val();
        self.mul[5].a.next = self.norm.nz.val();
        self.mul[5].b.next = self.hz.val();
        self.valid_p1.d.next = self.norm.valid_out.val();
        // D2: exact sums, split at bit 16 (see the header).
        // (rust-hdl resolves a loop index inside bit_cast arguments in neither backend: the
        // six products are one text repeated by `seq!`.)
        #(
        if self.mul[N].p.val().get_bit(31) {
            self.ext[N].next =
                bit_cast::<32, 16>(self.mul[N].p.val().get_bits::<16>(16)) | self.sign_ext.val();
        } else {
            self.ext[N].next = bit_cast::<32, 16>(self.mul[N].p.val().get_bits::<16>(16));
        }
        )*
        self.lo_l.next = bit_cast::<32, 16>(self.mul[0].p.val().get_bits::<16>(0))
            + bit_cast::<32, 16>(self.mul[1].p.val().get_bits::<16>(0))
            + bit_cast::<32, 16>(self.mul[2].p.val().get_bits::<16>(0))
            + self.half_lsb.val();
        self.hs_l.d.next = self.ext[0].val() + self.ext[1].val() + self.ext[2].val();
        self.lo_h.next = bit_cast::<32, 16>(self.mul[3].p.val().get_bits::<16>(0))
            + bit_cast::<32, 16>(self.mul[4].p.val().get_bits::<16>(0))
            + bit_cast::<32, 16>(self.mul[5].p.val().get_bits::<16>(0))
            + self.half_lsb.val();
        self.hs_h.d.next = self.ext[3].val() + self.ext[4].val() + self.ext[5].val();
        self.lo_l_q.d.next = self.lo_l.val().get_bits::<5>(13);
        self.lo_h_q.d.next = self.lo_h.val().get_bits::<5>(13);
        self.valid_p2.d.next = self.valid_p1.q.val();
        // D3
        self.hi_l.next =
            self.hs_l.q.val() + bit_cast::<32, 2>(self.lo_l_q.q.val().get_bits::<2>(3));
        self.hi_h.next =
            self.hs_h.q.val() + bit_cast::<32, 2>(self.lo_h_q.q.val().get_bits::<2>(3));
        if self.hi_l.val().get_bit(31) {
            self.cos_phi_q.d.next = 0.into();
        } else if self.hi_l.val().get_bits::<18>(13).any() {
            self.cos_phi_q.d.next = self.cos_max.val();
        } else {
            self.cos_phi_q.d.next = (bit_cast::<16, 13>(self.hi_l.val().get_bits::<13>(0)) << 3)
                | bit_cast::<16, 3>(self.lo_l_q.q.val().get_bits::<3>(0));
        }
        if self.hi_h.val().get_bit(31) {
            self.cos_gamma_q.d.next = 0.into();
        } else if self.hi_h.val().get_bits::<18>(13).any() {
            self.cos_gamma_q.d.next = self.cos_max.val();
        } else {
            self.cos_gamma_q.d.next = (bit_cast::<16, 13>(self.hi_h.val().get_bits::<13>(0)) << 3)
                | bit_cast::<16, 3>(self.lo_h_q.q.val().get_bits::<3>(0));
        }
        self.valid_p3.d.next = self.valid_p2.q.val();
        self.valid_out.next = self.valid_p3.q.val();
        self.cos_phi.next = self.cos_phi_q.q.val();
        self.cos_gamma.next = self.cos_gamma_q.q.val();
    }
}
});

crate::hw_block! {
    /// One product of D1: `p = a·b` for a normalizer component `a` (signed Q2.17, 19 bits) and
    /// a unit-vector component `b` (signed Q2.14), in Q4.28. `a` is split: its top 16 bits
    /// (Q2.14, a's floor) times b on a multiplier, exact; its three low bits times b by
    /// shift-add (units 2⁻³¹, exact), floored to Q4.28 (an arithmetic shift by 3) and added in
    /// the clock after both arrive. Error: the floor, < 2⁻²⁸. Latency [`DotTerm::LATENCY`].
    struct DotTerm(clock) {
        in { a: Bits<19>, b: Bits<16> }
        out { p: Bits<32> }
        mul: MulSignedPipe, low: MulLow3Pipe, corr: DFF<Bits<32>>, p_q: DFF<Bits<32>>,
        sign3: Constant<Bits<32>> = Constant::new(0xE000_0000u64.into()),
        sign8: Constant<Bits<24>> = Constant::new(0xFF_0000u64.into()),
        u_ext: Signal<Local, Bits<24>>, low_shift: Signal<Local, Bits<32>>,
    }
}

impl DotTerm {
    /// The multiplier's three clocks, then the sum with the low part.
    const LATENCY: usize = SIGNED_MUL_LATENCY + 1;
}

impl Logic for DotTerm {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, mul, low, corr, p_q);
        self.mul.a.next = self.a.val().get_bits::<16>(3);
        self.mul.b.next = self.b.val();
        if self.b.val().get_bit(15) {
            self.u_ext.next = bit_cast::<24, 16>(self.b.val()) | self.sign8.val();
        } else {
            self.u_ext.next = bit_cast::<24, 16>(self.b.val());
        }
        self.low.v.next = self.u_ext.val();
        self.low.m.next = self.a.val().get_bits::<3>(0);
        // |a_low·b| ≤ 7·2¹⁵: the floor by 8 fits; |a_high·b| ≤ 2³⁰: the sum cannot wrap.
        if self.low.p.val().get_bit(31) {
            self.low_shift.next = (self.low.p.val() >> 3) | self.sign3.val();
        } else {
            self.low_shift.next = self.low.p.val() >> 3;
        }
        self.corr.d.next = self.low_shift.val();
        self.p_q.d.next = self.mul.p.val() + self.corr.q.val();
        self.p.next = self.p_q.q.val();
    }
}
