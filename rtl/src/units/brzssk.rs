//! BRZSSK, the block computing the perturbed specular colour component (SPEC §2, Ukrainian
//! patent 60139; golden: `golden::units::brzssk`): the bump effect by perturbing the reflectance
//! function instead of the normal.
//!
//! ```text
//! cos(γ ± dγ) = cos γ·cos dγ ∓ sin γ·sin dγ        cos(φ ± dγ) the same way from cos φ
//! ```
//! No trigonometric unit: PROMs supply sin γ for cos γ (and sin φ for cos φ), the perturbation
//! code for the pixel address (the procedural map of `golden::shading::bump`, period 16 pixels, so the
//! code ROM is addressed by the address modulo 16), and cos dγ, sin dγ for the code's
//! magnitude; the trigger TG holds the code's sign and selects add or subtract. Two multipliers
//! per cosine (Mul1–Mul4 of the patent). The power and the colour follow in the power unit and
//! the colour combine (the patent's output path).
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `valid_in` | in | 1 = the cosines hold a pixel |
//! | `cos_phi`, `cos_gamma` | in | unsigned Q1.15, ≥ 0 (the lighting unit's) |
//! | `x`, `y` | in | the pixel's 12-bit address (bits 3..0 address the code ROM) |
//! | `valid_out` | out | `valid_in` seven clocks later |
//! | `cos_phi_out`, `cos_gamma_out` | out | unsigned Q1.15, registered |
//!
//! # Pipeline (PROMs are synchronous: a read takes the clock edge, as block RAM does)
//! ```text
//! B1  sφ = SINφ[round(cos φ·2¹⁰)] (cos φ ≥ 1 − 2⁻¹¹: 0), code = CODE[y₃..₀ x₃..₀] (sign,
//!     8-bit magnitude), (s, d) = SINγ[cos γ bits 14..4] (cos γ ≥ 1: 0), frac = bits 3..0
//! B2  the PROM words registered; DG read at the code's magnitude, TG = sign
//! B3  sγ = s − (d·frac + 8) >> 4 (shift-add); cd, sd = DG word (Q1.15 each), registered
//! B4  pφ = cos φ·cd, qφ = sφ·sd, pγ = cos γ·cd, qγ = sγ·sd   UQ1.15² → UQ2.30, exact (4 multipliers),
//!     two clocks [MulPipe: the operands registered beside each multiplier, then the product]
//! B5  TG ? p + q : max(p − q, 0)
//! B6  + 2¹⁴, drop 15 bits, saturate at 0xFFFF
//! ```
//! B2, B5, B4's second clock and the registered DG word are there for ECP5 timing (before:
//! latency 4, 64 MHz):
//! a block RAM's output takes 5.6 ns from the clock, so none feeds logic or a multiplier in the
//! same clock, and the add/subtract and the rounding carry chains take a clock each.
//! PROM sizes: SINγ 2048 × 27 (s in Q1.15 and the step `d = s[a] − s[a+1]` ≤ 1024 to the next
//! word, linearly interpolated by the 4 bits below the address: sin γ is steep near cos γ = 1
//! and the power after it would turn a bare PROM step into a ring), SINφ 1024 × 16 (rounded
//! address, no interpolation: no power follows the diffuse term), CODE 256 × 9, DG 256 × 32.
//! The word of cos = 1 (sin = 0) is a registered flag, not a PROM address.
//! Latency 7 clocks, one pixel per clock, no stall. Build parameter `bump` (on | off): off
//! passes the cosines through the same seven registers (the pixel pipeline keeps one latency
//! for every method; synthesis removes the unused PROMs and multipliers).
//!
//! # Overflow
//! Out-of-domain inputs saturate, as the PROMs' addresses do: a cosine ≥ 1 − 2^-(A+1) reads
//! sin = 0 (the last word); sums stay below 2³²; outputs saturate at 2 − 2⁻¹⁵ and clamp at 0.
//!
//! # Error budget (vs `golden::units::brzssk::brzssk` of the same input words)
//! The PROM contents, addressing and interpolation are the golden's, bit for bit (checked for
//! every cosine word in `golden::units::brzssk`); the products are exact; the one rounding adds
//! ≤ 2⁻¹⁶. The golden evaluates the same words in f64: |Δ| ≤ 2⁻¹⁶.
//! (Against the angle sum cos(γ ± dγ) of the exact angles, the PROM steps add
//! sin|dγ|·2^(−A/2), see `golden/tests/methods.rs`.)

use rust_hdl::prelude::*;

use crate::core::primitives::{Delay, MulPipe, Prom, MUL_LATENCY};
use crate::core::registry::{BlockParams, Options};

/// Build parameters: whether the block perturbs (bump method) or passes through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BrzsskParams {
    pub enable: bool,
}

impl Default for BrzsskParams {
    fn default() -> Self {
        BrzsskParams { enable: true }
    }
}

impl BrzsskParams {
    /// Read `bump=on|off`, with the given default.
    pub fn read(o: &Options, default: bool) -> Result<Self, String> {
        let enable = match o.get("bump") {
            None => default,
            Some("on") => true,
            Some("off") => false,
            Some(other) => {
                return Err(format!(
                    "unknown bump setting {other:?} (expected on or off)"
                ))
            }
        };
        Ok(BrzsskParams { enable })
    }
}

impl BlockParams for BrzsskParams {
    const KEYS: &'static [&'static str] = &["bump"];
    /// `bump=on` (default for the block alone) or `bump=off` (pass-through).
    fn from_options(o: &Options) -> Result<Self, String> {
        Self::read(o, true)
    }
    fn describe(&self) -> Option<String> {
        Some(format!("Bump {}", if self.enable { "on" } else { "off" }))
    }
    fn multipliers(&self) -> Option<usize> {
        Some(if self.enable { 4 } else { 0 })
    }
}

/// A PROM of the first 2^N of `words`.
fn rom<const D: usize, const N: usize>(words: Vec<u64>) -> Prom<Bits<D>, N> {
    Prom::new(words.into_iter().take(1 << N).map(Bits::<D>::from))
}

crate::hw_block! {
    /// BRZSSK (see the module header).
    pub struct Brzssk(clock) as "brzssk" {
        summary: "cos φ, cos γ and the pixel address in, cos(φ ± dγ), cos(γ ± dγ) out: PROMs, trigger TG, four multipliers, add/subtract (SPEC §2)",
        latency: 7 => "valid_in to valid_out, one pixel per clock",
        multipliers: 4,
        in { valid_in: Bit, cos_phi: Bits<16>, cos_gamma: Bits<16>, x: Bits<12>, y: Bits<12> }
        out { valid_out: Bit, cos_phi_out: Bits<16>, cos_gamma_out: Bits<16> }
        enable: Constant<Bit> = Constant::new(p.enable),
        // B1: PROM reads and the inputs carried along.
        // The PROMs hold addresses 0 .. 2^A − 1; address 2^A (cos ≥ 1 − 2^-(A+1), sin = 0)
        // is the registered `top` flag instead, which keeps SINγ at 16 block RAMs, not 32.
        sin_phi_rom: Prom<Bits<16>, 10> = rom(golden::units::brzssk::sin_rom(golden::shading::bump::SIN_PHI_ADDR_BITS)),
        sin_gamma_rom: Prom<Bits<27>, 11> = rom(golden::units::brzssk::sin_rom_interp(golden::shading::bump::SIN_ADDR_BITS)),
        code_rom: Prom<Bits<9>, 8> = rom(golden::units::brzssk::code_rom()),
        addr_phi: Signal<Local, Bits<10>>,
        top_p1: [DFF<Bit>; 2],
        /// The 4 interpolation bits of cos γ, and the shift-add d·frac (no multiplier).
        frac_p1: DFF<Bits<4>>,
        s_word: Signal<Local, Bits<16>>,
        d_word: Signal<Local, Bits<16>>,
        d_frac: [Signal<Local, Bits<16>>; 4],
        d_prod: Signal<Local, Bits<16>>,
        d_rnd: Signal<Local, Bits<16>>,
        rnd_phi: Signal<Local, Bits<16>>,
        code_addr: Signal<Local, Bits<8>>,
        cos_p1: [DFF<Bits<16>>; 2],
        valid_p1: DFF<Bit>,
        // B2: the PROM words registered, the dγ PROM read.
        dg_rom: Prom<Bits<32>, 8> = rom(golden::units::brzssk::dgamma_rom()),
        sg_p2: DFF<Bits<27>>,
        frac_p2: DFF<Bits<4>>,
        top_p2: DFF<Bit>,
        tg: DFF<Bit>,
        sin_p2: DFF<Bits<16>>,
        cos_p2: [DFF<Bits<16>>; 2],
        valid_p2: DFF<Bit>,
        // B3: the interpolated sin γ, the DG word registered.
        sin_p3: [DFF<Bits<16>>; 2],
        cos_d: DFF<Bits<16>>,
        sin_d: DFF<Bits<16>>,
        tg_p3: DFF<Bit>,
        cos_p3: [DFF<Bits<16>>; 2],
        valid_p3: DFF<Bit>,
        // B4 (two clocks)
        prod: [MulPipe; 4],
        tg_p4: Delay<Bit, MUL_LATENCY>,
        cos_p4: [Delay<Bits<16>, MUL_LATENCY>; 2],
        valid_p4: Delay<Bit, MUL_LATENCY>,
        // B5
        sum: [DFF<Bits<32>>; 2],
        cos_p5: [DFF<Bits<16>>; 2],
        valid_p5: DFF<Bit>,
        // B6
        sum_rnd: [Signal<Local, Bits<32>>; 2],
        half_lsb: Constant<Bits<32>> = Constant::new((1u64 << 14).into()),
        out: [DFF<Bits<16>>; 2],
        valid_p6: DFF<Bit>,
    }
    new(p: &BrzsskParams);
}

impl Logic for Brzssk {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            sin_phi_rom,
            sin_gamma_rom,
            code_rom,
            valid_p1,
            dg_rom,
            sg_p2,
            frac_p2,
            top_p2,
            tg,
            sin_p2,
            valid_p2,
            cos_d,
            sin_d,
            tg_p3,
            valid_p3,
            tg_p4,
            valid_p4,
            valid_p5,
            valid_p6
        );
        self.frac_p1.clock.next = self.clock.val();
        for k in 0..2 {
            clock!(
                self, clock, top_p1[k], cos_p1[k], cos_p2[k], sin_p3[k], cos_p3[k], cos_p4[k],
                sum[k], cos_p5[k], out[k]
            );
        }
        for k in 0..4 {
            self.prod[k].clock.next = self.clock.val();
        }
        // B1: PROM addresses — cos rounded to 10 / 12 fraction bits, clamped at 1.
        self.rnd_phi.next = self.cos_phi.val() + 16;
        self.addr_phi.next = self.rnd_phi.val().get_bits::<10>(5);
        self.top_p1[0].d.next = self.cos_phi.val() >= 0x7FF0;
        // SINγ: address = cos γ truncated to 11 bits, the next 4 bits interpolate.
        self.sin_gamma_rom.address.next = self.cos_gamma.val().get_bits::<11>(4);
        self.frac_p1.d.next = self.cos_gamma.val().get_bits::<4>(0);
        self.top_p1[1].d.next = self.cos_gamma.val().get_bit(15);
        self.sin_phi_rom.address.next = self.addr_phi.val();
        self.code_addr.next = (bit_cast::<8, 4>(self.y.val().get_bits::<4>(0)) << 4)
            | bit_cast::<8, 4>(self.x.val().get_bits::<4>(0));
        self.code_rom.address.next = self.code_addr.val();
        self.cos_p1[0].d.next = self.cos_phi.val();
        self.cos_p1[1].d.next = self.cos_gamma.val();
        self.valid_p1.d.next = self.valid_in.val();
        // B2: the PROM words registered; the dγ PROM, the trigger TG.
        self.dg_rom.address.next = self.code_rom.data.val().get_bits::<8>(0);
        self.tg.d.next = self.code_rom.data.val().get_bit(8);
        if self.top_p1[0].q.val() {
            self.sin_p2.d.next = 0.into();
        } else {
            self.sin_p2.d.next = self.sin_phi_rom.data.val();
        }
        self.sg_p2.d.next = self.sin_gamma_rom.data.val();
        self.frac_p2.d.next = self.frac_p1.q.val();
        self.top_p2.d.next = self.top_p1[1].q.val();
        self.cos_p2[0].d.next = self.cos_p1[0].q.val();
        self.cos_p2[1].d.next = self.cos_p1[1].q.val();
        self.valid_p2.d.next = self.valid_p1.q.val();
        // B3: sin γ = s − round(d·frac / 16), d·frac by four shifted adds (d ≤ 1024,
        // frac ≤ 15); the DG word registered.
        self.s_word.next = self.sg_p2.q.val().get_bits::<16>(11);
        self.d_word.next = bit_cast::<16, 11>(self.sg_p2.q.val().get_bits::<11>(0));
        self.d_frac[0].next = 0.into();
        self.d_frac[1].next = 0.into();
        self.d_frac[2].next = 0.into();
        self.d_frac[3].next = 0.into();
        if self.frac_p2.q.val().get_bit(0) {
            self.d_frac[0].next = self.d_word.val();
        }
        if self.frac_p2.q.val().get_bit(1) {
            self.d_frac[1].next = self.d_word.val() << 1;
        }
        if self.frac_p2.q.val().get_bit(2) {
            self.d_frac[2].next = self.d_word.val() << 2;
        }
        if self.frac_p2.q.val().get_bit(3) {
            self.d_frac[3].next = self.d_word.val() << 3;
        }
        self.d_prod.next = self.d_frac[0].val()
            + self.d_frac[1].val()
            + self.d_frac[2].val()
            + self.d_frac[3].val();
        self.d_rnd.next = self.d_prod.val() + 8;
        self.sin_p3[0].d.next = self.sin_p2.q.val();
        if self.top_p2.q.val() {
            self.sin_p3[1].d.next = 0.into();
        } else {
            self.sin_p3[1].d.next = self.s_word.val() - (self.d_rnd.val() >> 4);
        }
        self.cos_d.d.next = self.dg_rom.data.val().get_bits::<16>(16);
        self.sin_d.d.next = self.dg_rom.data.val().get_bits::<16>(0);
        self.tg_p3.d.next = self.tg.q.val();
        self.cos_p3[0].d.next = self.cos_p2[0].q.val();
        self.cos_p3[1].d.next = self.cos_p2[1].q.val();
        self.valid_p3.d.next = self.valid_p2.q.val();
        // B4: Mul1–Mul4.
        self.prod[0].a.next = self.cos_p3[0].q.val();
        self.prod[0].b.next = self.cos_d.q.val();
        self.prod[1].a.next = self.sin_p3[0].q.val();
        self.prod[1].b.next = self.sin_d.q.val();
        self.prod[2].a.next = self.cos_p3[1].q.val();
        self.prod[2].b.next = self.cos_d.q.val();
        self.prod[3].a.next = self.sin_p3[1].q.val();
        self.prod[3].b.next = self.sin_d.q.val();
        self.tg_p4.d.next = self.tg_p3.q.val();
        self.cos_p4[0].d.next = self.cos_p3[0].q.val();
        self.cos_p4[1].d.next = self.cos_p3[1].q.val();
        self.valid_p4.d.next = self.valid_p3.q.val();
        // B5: add (dγ < 0) or subtract (clamped at 0).
        if self.tg_p4.q.val() {
            self.sum[0].d.next = self.prod[0].p.val() + self.prod[1].p.val();
            self.sum[1].d.next = self.prod[2].p.val() + self.prod[3].p.val();
        } else {
            self.sum[0].d.next = self.prod[0].p.val() - self.prod[1].p.val();
            self.sum[1].d.next = self.prod[2].p.val() - self.prod[3].p.val();
            if self.prod[1].p.val() > self.prod[0].p.val() {
                self.sum[0].d.next = 0.into();
            }
            if self.prod[3].p.val() > self.prod[2].p.val() {
                self.sum[1].d.next = 0.into();
            }
        }
        self.cos_p5[0].d.next = self.cos_p4[0].q.val();
        self.cos_p5[1].d.next = self.cos_p4[1].q.val();
        self.valid_p5.d.next = self.valid_p4.q.val();
        // B6: round, saturate.
        for k in 0..2 {
            self.sum_rnd[k].next = self.sum[k].q.val() + self.half_lsb.val();
            if !self.enable.val() {
                self.out[k].d.next = self.cos_p5[k].q.val();
            } else if self.sum_rnd[k].val().get_bit(31) {
                self.out[k].d.next = 0xFFFF.into();
            } else {
                self.out[k].d.next = self.sum_rnd[k].val().get_bits::<16>(15);
            }
        }
        self.valid_p6.d.next = self.valid_p5.q.val();
        self.valid_out.next = self.valid_p6.q.val();
        self.cos_phi_out.next = self.out[0].q.val();
        self.cos_gamma_out.next = self.out[1].q.val();
    }
}
