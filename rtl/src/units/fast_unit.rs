//! The fast two-point unit (SPEC §3, thesis §3.1; golden: `golden::units::fast_unit`): along a span,
//! N̂_x·X = p_x/√q_x two pixels per step without a division or a root.
//!
//! ```text
//! p_x = b + g·x (left pixel x),  p = h − g·x (mirror pixel m − x),  q_x = M_x + 1 = q_{m−x}
//! M_{x+1} = M_x + Δ_x,  Δ_{x+1} = Δ_x + 2c,  Δ₀ = c + s        (second-order recurrence)
//! 1/√q ≈ f(M) = (c2·M + c1)·M + c0                               (Horner; coefficients a build
//!                                                                 parameter: published
//!                                                                 Chebyshev, shift-add, fitted)
//! ```
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a span's words (taken when `ready`) |
//! | `b`, `h`, `g` | in | signed Q2.30 |
//! | `d0` (= c + s), `dd` (= 2c) | in | signed Q2.46 (48 bits) |
//! | `m` | in | span length − 1, 12 bits |
//! | `hold` | in | 1: the step stands still this clock — no pixel enters the pipeline, no span is taken (`ready` low); nothing is lost (a stream top's back-pressure) |
//! | `ready` | out | no step after this clock and no `hold`: a `load` now follows without a gap |
//! | `valid_a`, `x_a`, `cos_a` | out | left pixel: index, cos (unsigned Q1.15, clamped at 0) |
//! | `valid_b`, `x_b`, `cos_b` | out | mirror pixel m − x (not when it is the left pixel itself) |
//! | `done` | out | the span's last step |
//!
//! # Pipeline
//! ```text
//! S0  state x, p_l, p_r (32), M, Δ, 2c (48), rem = m − 2x (14-bit two's complement, −2 at
//!     the end); active = busy & rem ≥ 0, another step follows when rem ≥ 2 (sign and bit
//!     tests of a register, not compares: for ECP5 timing)
//! S1  M → Q1.15 (round, saturate), p_l, p_r → Q2.14 (round, saturate)
//! S2  |c2|·M                UQ1.15 × signed Q1.15 → Q2.30, exact, 3 clocks [MulSignedUnsignedPipe]
//! S3  t1 = c1 + |c2|·M      Q2.30 → Q2.14, rounded
//! S4  t1·M                  Q2.14 × Q1.15 → Q3.29, exact, 3 clocks         [MulSignedPipe]
//! S5  f = c0 + t1·M         Q3.29 → UQ1.15, rounded, clamped to [0, 2)
//! S6  p_l·f, p_r·f          signed Q2.14 × UQ1.15 → Q3.29, exact (2), 3 clocks [MulSignedUnsignedPipe]
//! S7  cos = round → UQ1.15, clamped to [0, 2)
//! ```
//! Each product takes three clocks (operands, raw product and sign correction, difference
//! registered apart): for ECP5 timing, a multiplier and its correction in one clock ran at
//! 92 MHz (see `crate::core::primitives`).
//! Latency: state → pixels 13 clocks, load → first pixels 14. Throughput: two pixels per clock
//! (one in the middle step of an even m); a span takes ⌊m/2⌋ + 1 clocks and the next follows
//! at once. 4 multipliers (c2 > 0 required: every published and fitted set has it).
//!
//! # Overflow
//! The recurrences wrap modulo 2³² / 2⁴⁸ (exact; in-domain values stay far inside); M, p and
//! the outputs saturate.
//!
//! # Error budget (vs `golden::units::fast_unit::FastWords::values` of the same words)
//! `golden::units::fast_unit::error_bound`: ≤ 2.0·10⁻⁴ for the published Chebyshev set on the domain
//! M ∈ [−0.5, 0], |p| ≤ 1.
//!
//! Latency (the block's `LATENCY`): 14 clocks, load to the first pixels, two pixels per clock.

use golden::units::normalizer::Coeffs;
use rust_hdl::prelude::*;

use crate::core::primitives::{MulSignedPipe, MulSignedUnsignedPipe, SIGNED_MUL_LATENCY};

/// Clocks from the state (S0) to the pixels: S1, three products, S3, S5, S7.
const STATE_TO_PIXELS: usize = 4 + 3 * SIGNED_MUL_LATENCY;
/// M's delay line (to S4's multiplier) and p's (to S6's).
const MM_LEN: usize = SIGNED_MUL_LATENCY + 2;
const P16_LEN: usize = 2 * SIGNED_MUL_LATENCY + 3;
// `#[hdl_gen]` takes only literal indices and loop bounds: `update` writes these lengths out.
const _: () = assert!(STATE_TO_PIXELS == 13 && MM_LEN == 5 && P16_LEN == 9);
use crate::core::registry::{BlockParams, Options};

/// The 1/√(M + 1) coefficient set, as (c2, c1, c0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastParams {
    pub name: &'static str,
    pub coeffs: Coeffs,
}

impl BlockParams for FastParams {
    const KEYS: &'static [&'static str] = &["inv-sqrt"];
    /// `inv-sqrt=chebyshev` (default, the published 1.003 − 0.403M + 0.82M²), `shift-add`
    /// (1 − l·M + 2l·M²) or `fit` (exact in value and slope at M = 0).
    fn from_options(o: &Options) -> Result<Self, String> {
        let (name, coeffs) = match o.get("inv-sqrt").unwrap_or("chebyshev") {
            "chebyshev" => ("chebyshev", golden::shading::fast::CHEBYSHEV),
            "shift-add" => ("shift-add", golden::shading::fast::SHIFT_ADD),
            "fit" => ("fit", golden::shading::fast::FIT),
            other => {
                return Err(format!(
                    "unknown 1/sqrt(M+1) set {other:?} (expected chebyshev, shift-add or fit)"
                ))
            }
        };
        Ok(FastParams { name, coeffs })
    }
    fn describe(&self) -> Option<String> {
        Some(format!("1/sqrt(M+1) set {} = {:?}", self.name, self.coeffs))
    }
    fn test_sets() -> Vec<Options> {
        ["chebyshev", "shift-add", "fit"]
            .map(|c| Options::new().with("inv-sqrt", c))
            .to_vec()
    }
}

fn word(v: i64, bits: u32) -> u64 {
    (v as u64) & ((1u64 << bits) - 1)
}

crate::hw_block! {
    /// The fast two-point unit (see the module header).
    pub struct FastUnit(clock) as "fast-unit" {
        summary: "a span's b, h, g, c + s, 2c in, p/√q for pixel x and its mirror m − x out, two pixels per clock (SPEC §3)",
        latency: STATE_TO_PIXELS + 1 => "load to the first pixels, two pixels per clock",
        multipliers: 4,
        in {
            load: Bit, b: Bits<32>, h: Bits<32>, g: Bits<32>, d0: Bits<48>, dd: Bits<48>,
            m: Bits<12>, hold: Bit,
        }
        out {
            ready: Bit,
            valid_a: Bit, x_a: Bits<12>, cos_a: Bits<16>,
            valid_b: Bit, x_b: Bits<12>, cos_b: Bits<16>,
            done: Bit,
        }
        c2: Constant<Bits<16>> = Constant::new(word(golden::units::fast_unit::twin::coefficient_words(p.coeffs).0, 16).into()),
        c1: Constant<Bits<32>> = Constant::new(word(golden::units::fast_unit::twin::coefficient_words(p.coeffs).1, 32).into()),
        c0: Constant<Bits<32>> = Constant::new(word(golden::units::fast_unit::twin::coefficient_words(p.coeffs).2, 32).into()),
        // S0
        busy: DFF<Bit>, x: DFF<Bits<12>>, m_q: DFF<Bits<12>>,
        pl: DFF<Bits<32>>, pr: DFF<Bits<32>>, g_q: DFF<Bits<32>>,
        big_m: DFF<Bits<48>>, delta: DFF<Bits<48>>, dd_q: DFF<Bits<48>>,
        rem: DFF<Bits<14>>,
        act: Signal<Local, Bit>, more: Signal<Local, Bit>,
        /// The step is taken this clock (active and not held).
        go: Signal<Local, Bit>,
        // S1 narrowings (one extra bit so the rounding add cannot wrap)
        m49: Signal<Local, Bits<49>>, pl33: Signal<Local, Bits<33>>, pr33: Signal<Local, Bits<33>>,
        sx49: Constant<Bits<49>> = Constant::new((1u64 << 48).into()),
        sx33: Constant<Bits<33>> = Constant::new((1u64 << 32).into()),
        half31: Constant<Bits<49>> = Constant::new((1u64 << 30).into()),
        half16: Constant<Bits<33>> = Constant::new((1u64 << 15).into()),
        vl: [DFF<Bit>; STATE_TO_PIXELS], vr: [DFF<Bit>; STATE_TO_PIXELS],
        xl: [DFF<Bits<12>>; STATE_TO_PIXELS], xr: [DFF<Bits<12>>; STATE_TO_PIXELS],
        lst: [DFF<Bit>; STATE_TO_PIXELS],
        mm: [DFF<Bits<16>>; MM_LEN],
        p16l: [DFF<Bits<16>>; P16_LEN],
        p16r: [DFF<Bits<16>>; P16_LEN],
        // S2..S7
        mul_c2m: MulSignedUnsignedPipe,
        t1_sum: Signal<Local, Bits<32>>, t1_rnd: Signal<Local, Bits<32>>, t1: DFF<Bits<16>>,
        half_t1: Constant<Bits<32>> = Constant::new((1u64 << 15).into()),
        mul_t1m: MulSignedPipe,
        f_sum: Signal<Local, Bits<32>>, f_rnd: Signal<Local, Bits<32>>, f: DFF<Bits<16>>,
        half14: Constant<Bits<32>> = Constant::new((1u64 << 13).into()),
        mul_l: MulSignedUnsignedPipe, mul_r: MulSignedUnsignedPipe,
        out_l_rnd: Signal<Local, Bits<32>>, out_r_rnd: Signal<Local, Bits<32>>,
        cos_lq: DFF<Bits<16>>, cos_rq: DFF<Bits<16>>,
    }
    new(p: &FastParams);
}

impl Logic for FastUnit {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, busy, x, m_q, pl, pr, g_q, big_m, delta, dd_q, rem);
        clock!(self, clock, mul_c2m, t1, mul_t1m, f, mul_l, mul_r, cos_lq, cos_rq);
        for i in 0..13 {
            clock!(self, clock, vl[i], vr[i], xl[i], xr[i], lst[i]);
        }
        for i in 0..5 {
            self.mm[i].clock.next = self.clock.val();
        }
        for i in 0..9 {
            clock!(self, clock, p16l[i], p16r[i]);
        }
        // S0: the step of this clock, and whether another follows.
        self.act.next = self.busy.q.val() & !self.rem.q.val().get_bit(13);
        self.more.next = self.act.val() & self.rem.q.val().get_bits::<12>(1).any();
        // `hold`: the step stands still and emits nothing this clock, no span is taken.
        self.ready.next = !self.more.val() & !self.hold.val();
        self.go.next = self.act.val() & !self.hold.val();
        if self.go.val() {
            self.pl.d.next = self.pl.q.val() + self.g_q.q.val();
            self.pr.d.next = self.pr.q.val() - self.g_q.q.val();
            self.big_m.d.next = self.big_m.q.val() + self.delta.q.val();
            self.delta.d.next = self.delta.q.val() + self.dd_q.q.val();
            self.x.d.next = self.x.q.val() + 1;
            self.rem.d.next = self.rem.q.val() - 2;
        } else if !self.act.val() {
            self.busy.d.next = false;
        }
        if self.load.val() & self.ready.val() {
            self.busy.d.next = true;
            self.x.d.next = 0.into();
            self.m_q.d.next = self.m.val();
            self.rem.d.next = bit_cast::<14, 12>(self.m.val());
            self.pl.d.next = self.b.val();
            self.pr.d.next = self.h.val();
            self.g_q.d.next = self.g.val();
            self.big_m.d.next = 0.into();
            self.delta.d.next = self.d0.val();
            self.dd_q.d.next = self.dd.val();
        }
        // S1: flags and indices; M → Q1.15 and p → Q2.14, rounded, saturated.
        self.vl[0].d.next = self.go.val();
        self.vr[0].d.next = self.go.val() & self.rem.q.val().any();
        self.xl[0].d.next = self.x.q.val();
        self.xr[0].d.next = self.m_q.q.val() - self.x.q.val();
        self.lst[0].d.next = self.go.val() & !self.more.val();
        for i in 1..13 {
            self.vl[i].d.next = self.vl[i - 1].q.val();
            self.vr[i].d.next = self.vr[i - 1].q.val();
            self.xl[i].d.next = self.xl[i - 1].q.val();
            self.xr[i].d.next = self.xr[i - 1].q.val();
            self.lst[i].d.next = self.lst[i - 1].q.val();
        }
        if self.big_m.q.val().get_bit(47) {
            self.m49.next =
                (bit_cast::<49, 48>(self.big_m.q.val()) | self.sx49.val()) + self.half31.val();
        } else {
            self.m49.next = bit_cast::<49, 48>(self.big_m.q.val()) + self.half31.val();
        }
        if self.m49.val().get_bit(48) == self.m49.val().get_bit(46) {
            if self.m49.val().get_bit(48) == self.m49.val().get_bit(47) {
                self.mm[0].d.next = self.m49.val().get_bits::<16>(31);
            } else if self.m49.val().get_bit(48) {
                self.mm[0].d.next = 0x8000.into();
            } else {
                self.mm[0].d.next = 0x7FFF.into();
            }
        } else if self.m49.val().get_bit(48) {
            self.mm[0].d.next = 0x8000.into();
        } else {
            self.mm[0].d.next = 0x7FFF.into();
        }
        if self.pl.q.val().get_bit(31) {
            self.pl33.next =
                (bit_cast::<33, 32>(self.pl.q.val()) | self.sx33.val()) + self.half16.val();
        } else {
            self.pl33.next = bit_cast::<33, 32>(self.pl.q.val()) + self.half16.val();
        }
        if self.pr.q.val().get_bit(31) {
            self.pr33.next =
                (bit_cast::<33, 32>(self.pr.q.val()) | self.sx33.val()) + self.half16.val();
        } else {
            self.pr33.next = bit_cast::<33, 32>(self.pr.q.val()) + self.half16.val();
        }
        if self.pl33.val().get_bit(32) == self.pl33.val().get_bit(31) {
            self.p16l[0].d.next = self.pl33.val().get_bits::<16>(16);
        } else if self.pl33.val().get_bit(32) {
            self.p16l[0].d.next = 0x8000.into();
        } else {
            self.p16l[0].d.next = 0x7FFF.into();
        }
        if self.pr33.val().get_bit(32) == self.pr33.val().get_bit(31) {
            self.p16r[0].d.next = self.pr33.val().get_bits::<16>(16);
        } else if self.pr33.val().get_bit(32) {
            self.p16r[0].d.next = 0x8000.into();
        } else {
            self.p16r[0].d.next = 0x7FFF.into();
        }
        for i in 1..9 {
            self.p16l[i].d.next = self.p16l[i - 1].q.val();
            self.p16r[i].d.next = self.p16r[i - 1].q.val();
        }
        for i in 1..5 {
            self.mm[i].d.next = self.mm[i - 1].q.val();
        }
        // S2: |c2|·M.
        self.mul_c2m.a.next = self.mm[0].q.val();
        self.mul_c2m.b.next = self.c2.val();
        // S3: t1 = round(c1 + |c2|·M) to Q2.14.
        self.t1_sum.next = self.c1.val() + self.mul_c2m.p.val();
        self.t1_rnd.next = self.t1_sum.val() + self.half_t1.val();
        self.t1.d.next = self.t1_rnd.val().get_bits::<16>(16);
        // S4: t1·M.
        self.mul_t1m.a.next = self.t1.q.val();
        self.mul_t1m.b.next = self.mm[4].q.val();
        // S5: f = c0 + t1·M, to UQ1.15, clamped to [0, 2).
        self.f_sum.next = self.c0.val() + self.mul_t1m.p.val();
        self.f_rnd.next = self.f_sum.val() + self.half14.val();
        if self.f_rnd.val().get_bit(31) {
            self.f.d.next = 0.into();
        } else if self.f_rnd.val().get_bit(30) {
            self.f.d.next = 0xFFFF.into();
        } else {
            self.f.d.next = self.f_rnd.val().get_bits::<16>(14);
        }
        // S6: p·f for both pixels.
        self.mul_l.a.next = self.p16l[8].q.val();
        self.mul_l.b.next = self.f.q.val();
        self.mul_r.a.next = self.p16r[8].q.val();
        self.mul_r.b.next = self.f.q.val();
        // S7: round to UQ1.15, clamped to [0, 2).
        self.out_l_rnd.next = self.mul_l.p.val() + self.half14.val();
        self.out_r_rnd.next = self.mul_r.p.val() + self.half14.val();
        if self.out_l_rnd.val().get_bit(31) {
            self.cos_lq.d.next = 0.into();
        } else if self.out_l_rnd.val().get_bit(30) {
            self.cos_lq.d.next = 0xFFFF.into();
        } else {
            self.cos_lq.d.next = self.out_l_rnd.val().get_bits::<16>(14);
        }
        if self.out_r_rnd.val().get_bit(31) {
            self.cos_rq.d.next = 0.into();
        } else if self.out_r_rnd.val().get_bit(30) {
            self.cos_rq.d.next = 0xFFFF.into();
        } else {
            self.cos_rq.d.next = self.out_r_rnd.val().get_bits::<16>(14);
        }
        self.valid_a.next = self.vl[12].q.val();
        self.x_a.next = self.xl[12].q.val();
        self.cos_a.next = self.cos_lq.q.val();
        self.valid_b.next = self.vr[12].q.val();
        self.x_b.next = self.xr[12].q.val();
        self.cos_b.next = self.cos_rq.q.val();
        self.done.next = self.lst[12].q.val();
    }
}
