//! Colour combine (SPEC §0; golden: `golden::units::colour_combine`): the two lighting terms in,
//! TrueColor out.
//!
//! ```text
//! I_c = amb_c + dif_c·cos φ + spc_c·S,   amb = I_a·k_a·D, dif = I_l·k_d·D, spc = I_l·k_s·S_col
//! ```
//! per channel c ∈ {r, g, b}, rounded to nearest and saturated to 0..255. The weights are
//! per-material registers of the top (the set-up computes them: `golden::units::colour_combine::Weights`);
//! Lambert lighting loads spc = 0.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `valid_in` | in | 1 = cos_phi, spec hold a pixel's terms |
//! | `cos_phi`, `spec` | in | unsigned Q1.15 (cos φ ≥ 0 from the lighting unit, S from the power unit) |
//! | `amb_r … amb_b`, `dif_r … dif_b`, `spc_r … spc_b` | in | unsigned Q8.8 weights, registers (hold them while pixels are in flight; dif and spc are sampled with the pixel, amb two clocks later) |
//! | `valid_out` | out | `valid_in` four clocks later |
//! | `red`, `green`, `blue` | out | 8 bits, registered |
//!
//! # Pipeline
//! ```text
//! C1 pd_c = dif_c·cos φ, ps_c = spc_c·S   UQ8.8 × UQ1.15 → UQ9.23, exact (6 multipliers),
//!    two clocks [MulPipe: the operands registered beside each multiplier, then the product]
//! C2 sum_c = amb_c·2¹⁵ + pd_c + ps_c + 2²² (half LSB), exact (< 1280·2²³), formed in two
//!    parts so no word is wider than 32 bits (the simulator's fast width; the hardware is the
//!    same 34-bit sum, split at bit 23):
//!      lo_c = pd_c[22:0] + ps_c[22:0] + amb_c[7:0]·2¹⁵ + 2²²        < 2²⁵
//!      hs_c = pd_c[31:23] + ps_c[31:23] + amb_c[15:8]                 < 2¹¹, both registered
//! C3 hi_c = hs_c + lo_c[24:23] (= ⌊sum_c / 2²³⌋)
//!    rgb_c = 255 if hi_c ≥ 256, else hi_c[7:0]
//! ```
//! Latency 4 clocks, one pixel per clock, no stall. (C1 and C2 + C3 were one clock each until
//! ECP5 timing: in the pixel pipeline the sums, the carry and the clamp in one clock ran at
//! 86 MHz; see `crate::core::primitives` for the operand registers.)
//!
//! # Overflow
//! None wraps: products and sums are exact; the result saturates at 255 ("colours that
//! saturate": a highlight on a bright material clips instead of wrapping to black).
//!
//! # Error budget (vs the f64 combine of the same words)
//! Exact until the final rounding: ≤ ½ LSB of the 8-bit output. Against the f64 combine of
//! the unquantized weights add the weight quantization, ≤ 2⁻⁹·(1 + cos φ + S) ≤ 0.01 LSB.

use rust_hdl::prelude::*;

use crate::core::primitives::{Delay, MulPipe, MUL_LATENCY};

crate::hw_block! {
    /// The colour combine (see the module header).
    pub struct ColourCombine(clock) as "colour-combine" {
        summary: "cos φ and S in, I = amb + dif·cos φ + spc·S per channel out, 8 bits saturated (SPEC §0)",
        latency: 4 => "valid_in to valid_out, one pixel per clock",
        multipliers: 6,
        in {
            valid_in: Bit, cos_phi: Bits<16>, spec: Bits<16>,
            amb_r: Bits<16>, amb_g: Bits<16>, amb_b: Bits<16>,
            dif_r: Bits<16>, dif_g: Bits<16>, dif_b: Bits<16>,
            spc_r: Bits<16>, spc_g: Bits<16>, spc_b: Bits<16>,
        }
        out { valid_out: Bit, red: Bits<8>, green: Bits<8>, blue: Bits<8> }
        // C1
        pd: [MulPipe; 3],
        ps: [MulPipe; 3],
        valid_p1: Delay<Bit, MUL_LATENCY>,
        // C2: the sum's bits 22..0 (with their carry) and 33..23, registered.
        lo: [DFF<Bits<32>>; 3],
        hs: [DFF<Bits<16>>; 3],
        half_lsb: Constant<Bits<32>> = Constant::new((1u64 << 22).into()),
        valid_p2: DFF<Bit>,
        // C3: the carry into the high part, the clamp.
        hi: [Signal<Local, Bits<16>>; 3],
        level_max: Constant<Bits<8>> = Constant::new(255.into()),
        rgb: [DFF<Bits<8>>; 3],
        valid_p3: DFF<Bit>,
    }
}

impl Logic for ColourCombine {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, valid_p1, valid_p2, valid_p3);
        for c in 0..3 {
            clock!(self, clock, lo[c], hs[c], pd[c], ps[c], rgb[c]);
        }
        // C1
        self.pd[0].a.next = self.dif_r.val();
        self.pd[1].a.next = self.dif_g.val();
        self.pd[2].a.next = self.dif_b.val();
        self.ps[0].a.next = self.spc_r.val();
        self.ps[1].a.next = self.spc_g.val();
        self.ps[2].a.next = self.spc_b.val();
        for c in 0..3 {
            self.pd[c].b.next = self.cos_phi.val();
            self.ps[c].b.next = self.spec.val();
        }
        self.valid_p1.d.next = self.valid_in.val();
        // C2 (written out per channel: rust-hdl resolves no loop index inside bit_cast).
        self.lo[0].d.next = bit_cast::<32, 23>(self.pd[0].p.val().get_bits::<23>(0))
            + bit_cast::<32, 23>(self.ps[0].p.val().get_bits::<23>(0))
            + (bit_cast::<32, 8>(self.amb_r.val().get_bits::<8>(0)) << 15)
            + self.half_lsb.val();
        self.lo[1].d.next = bit_cast::<32, 23>(self.pd[1].p.val().get_bits::<23>(0))
            + bit_cast::<32, 23>(self.ps[1].p.val().get_bits::<23>(0))
            + (bit_cast::<32, 8>(self.amb_g.val().get_bits::<8>(0)) << 15)
            + self.half_lsb.val();
        self.lo[2].d.next = bit_cast::<32, 23>(self.pd[2].p.val().get_bits::<23>(0))
            + bit_cast::<32, 23>(self.ps[2].p.val().get_bits::<23>(0))
            + (bit_cast::<32, 8>(self.amb_b.val().get_bits::<8>(0)) << 15)
            + self.half_lsb.val();
        self.hs[0].d.next = bit_cast::<16, 9>(self.pd[0].p.val().get_bits::<9>(23))
            + bit_cast::<16, 9>(self.ps[0].p.val().get_bits::<9>(23))
            + bit_cast::<16, 8>(self.amb_r.val().get_bits::<8>(8));
        self.hs[1].d.next = bit_cast::<16, 9>(self.pd[1].p.val().get_bits::<9>(23))
            + bit_cast::<16, 9>(self.ps[1].p.val().get_bits::<9>(23))
            + bit_cast::<16, 8>(self.amb_g.val().get_bits::<8>(8));
        self.hs[2].d.next = bit_cast::<16, 9>(self.pd[2].p.val().get_bits::<9>(23))
            + bit_cast::<16, 9>(self.ps[2].p.val().get_bits::<9>(23))
            + bit_cast::<16, 8>(self.amb_b.val().get_bits::<8>(8));
        self.valid_p2.d.next = self.valid_p1.q.val();
        // C3
        self.hi[0].next =
            self.hs[0].q.val() + bit_cast::<16, 2>(self.lo[0].q.val().get_bits::<2>(23));
        self.hi[1].next =
            self.hs[1].q.val() + bit_cast::<16, 2>(self.lo[1].q.val().get_bits::<2>(23));
        self.hi[2].next =
            self.hs[2].q.val() + bit_cast::<16, 2>(self.lo[2].q.val().get_bits::<2>(23));
        for c in 0..3 {
            if self.hi[c].val().get_bits::<8>(8).any() {
                self.rgb[c].d.next = self.level_max.val();
            } else {
                self.rgb[c].d.next = self.hi[c].val().get_bits::<8>(0);
            }
        }
        self.valid_p3.d.next = self.valid_p2.q.val();
        self.valid_out.next = self.valid_p3.q.val();
        self.red.next = self.rgb[0].q.val();
        self.green.next = self.rgb[1].q.val();
        self.blue.next = self.rgb[2].q.val();
    }
}
