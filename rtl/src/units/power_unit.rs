//! Power unit (SPEC §2, the output path of BRZSSK; golden: `golden::units::power_unit`): the
//! specular value S from cos γ, one pixel per clock.
//!
//! ```text
//! exact:  S = cos^n γ                         square-and-multiply over the bits of n ≤ 1023
//! W:      S = W(n, γ) = [1 − a·(1 − cos γ)]^k, 0 where the bracket is negative,
//!         a = (n+1)·(1/4 − 1/16 + 1/64 − 1/256)  k = 4   (= 51·(n+1)·2⁻⁸)
//!           = (n+1)·(1/8 − 1/64 + 1/512)         k = 8   (= 57·(n+1)·2⁻⁹)
//!           = (n+1)·(1/16 − 1/256)               k = 16  (= 15·(n+1)·2⁻⁸)
//! ```
//! The mode is a build parameter (`power=exact|w4|w8|w16`): the `normalizer` methods need the
//! exact power, `brdf-kK` uses W with k. Both datapaths are described; the mode constant
//! selects the output and synthesis removes the other one.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `valid_in` | in | 1 = cos_gamma holds a pixel's cosine |
//! | `cos_gamma` | in | unsigned Q1.15, [0, 2): ≥ 0 from the lighting unit, may exceed 1 (published normalizer) |
//! | `n` | in | specular exponent, 10 bits; travels with its pixel (a new material may follow in-flight pixels) |
//! | `valid_out` | out | `valid_in` delayed 50 clocks |
//! | `spec` | out | S, unsigned Q1.15, saturated at 0xFFFF (2 − 2⁻¹⁵) |
//!
//! # Pipeline (every product UQ1.15 × UQ1.15 → UQ2.30, exact: in the exact mode in four
//! clocks [MulPipeDeep: the operands registered twice, the product registered twice], in W in
//! two [MulPipe: the operands registered, then the product]; then rnd: + 2¹⁴, drop 15 bits,
//! saturate at 0xFFFF [RoundProductToUQ1_15] in the next clock)
//! ```text
//! exact  E0a    acc = n₀ ? c : 1.0 (0x8000),  sq = c²   (4 clocks)         1 squarer
//!        E0b    pw = rnd(sq)
//!        Eja    prod = n_j ? acc·pw : 0,  sq = pw²      (4 clocks)  j = 1..8   2 multipliers each
//!        Ejb    acc = n_j ? rnd(prod) : acc,  pw = rnd(sq)
//!        E9a    prod = n₉ ? acc·pw : 0                  (4 clocks)         1 multiplier
//!        E9b    acc = n₉ ? rnd(prod) : acc
//!        → 18 multipliers, latency 10 · 5 = 50
//! W      W1  a = slope word by shifts and adds of n + 1 (16 bits, exact: ≤ 57·1024 < 2¹⁶),
//!            t = |c − 1| (UQ1.15), above = c > 1, zero = c = 0
//!        W2  p = a·t                        UQ8.8 (UQ7.9 for k = 8) × UQ1.15, exact, 32 bits,
//!            two clocks [MulPipe]
//!        W3a sum = 0 if zero; 1 + p if above; max(1 − p, 0) otherwise (in p's units, 32 bits,
//!            cannot wrap), registered
//!        W3b b = round sum to UQ1.15 (+ half LSB, drop 8 or 9 bits), saturate
//!        W4..W7  a, a': sq = b² [MulPipe]; b: b = rnd(sq) in the first log2 k stages (2, 3,
//!                4), passed through in the rest
//!        then 33 delay registers to latency 50
//!        → 1 + log2 k multipliers (3, 4, 5)
//! ```
//! The product is registered before its rounding for ECP5 timing: a multiply, the rounding
//! carry chain and the selection in one clock (the layout before, latency 10) ran at 91 MHz;
//! the operand registers beside each multiplier are for the pixel pipeline, where the route
//! to a multiplier and back took over 10 ns (see `crate::core::primitives`). The operands of Eja's
//! acc·pw are 0 when n_j is 0 (the product is then not used, so S is the same in every
//! clock): otherwise Yosys merges the operand registers with the acc delay register and with
//! the squarer's operand register that hold the same words, and the merged register, placed
//! between its sinks, left 4.6 ns of route to the multiplier in the fast pipeline (83 MHz).
//! With one register on each side the fast pipeline (56 multipliers on the LFE5U-45F, spread
//! over its DSP columns) still had a 3.7 ns route in and a 2.6 ns route out around the
//! multiplier's 3.9 ns (93 MHz): the exact chain's multipliers have two registers on each
//! side (MulPipeDeep), so each long route has a clock of its own. W keeps MulPipe (its five
//! multipliers were never on the critical path).
//! cos γ = 0 gives 0 in both modes for n ≥ 1 (W: the `zero` flag, as `golden::shading::brdf::w_kernel`).
//! n = 0 gives 1.0 (cos⁰) in the exact mode and [1 − a·(1 − c)]^k with a = 1/(k+1) in W;
//! n = 1001..1023 computes as written. The set-up rejects n outside 1..1000.
//!
//! Latency 50 clocks in every mode, one pixel per clock, no stall; `valid` travels with the
//! data. The patent's multiplexed single-multiplier arrangement (one multiplier reused over
//! several clocks per pixel) is not built: the pipeline must take one pixel per clock.
//!
//! # Overflow
//! Nothing wraps: products are exact, W3's sum is below 2³², and every narrowing saturates at
//! 2 − 2⁻¹⁵. An S that should be ≥ 2 (cos γ > 1 from the published normalizer with a large n)
//! is clipped there: with a specular weight ≥ 128 the colour is 255 either way; with a darker
//! specular colour the clipped pixel is darker than the f64 model's.
//!
//! # Error budget (vs the f64 `golden::units::power_unit::power` of the same input word)
//! Each rounding adds ≤ 2⁻¹⁶; an error in a value later squared j times grows ≈ 2^j near
//! c = 1 (less below it). `golden::units::power_unit::error_bound` propagates it along the chain of
//! the actual input (first order plus the squared terms). Its maximum over c ∈ [0.92, 1]:
//! n = 1: 0 (no rounding), n = 50: 7.6·10⁻⁴, n = 256: 3.9·10⁻³, n = 1000: 1.5·10⁻² (3.9 LSB of
//! an 8-bit colour at full specular weight — the exact power needs wider words for n near
//! 1000); W over c ∈ [0, 1], n ∈ {1, 50, 256, 1000}: 1.1·10⁻⁴ (k = 4), 2.3·10⁻⁴ (k = 8),
//! 4.7·10⁻⁴ (k = 16); above c = 1 the bracket exceeds 1 and the bound grows with it.
//! The input's own quantization (≤ 2⁻¹⁶) moves cos^n by n·2⁻¹⁶·cos^(n−1): that is the lighting
//! unit's budget, not this block's.

use golden::units::power_unit::PowerMode;
use rust_hdl::prelude::*;

use crate::core::primitives::{Delay, MulPipe, MulPipeDeep, RoundProductToUQ1_15, MUL_LATENCY};
use crate::core::registry::{BlockParams, Options};

/// Build parameters: which specular value the unit computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PowerParams {
    pub mode: PowerMode,
}

impl Default for PowerParams {
    fn default() -> Self {
        PowerParams {
            mode: PowerMode::Exact,
        }
    }
}

impl PowerParams {
    /// The k of W, `None` for the exact power.
    pub fn k(&self) -> Option<u32> {
        self.mode.k()
    }
    fn name(&self) -> String {
        match self.mode {
            PowerMode::Exact => "exact".into(),
            PowerMode::W(k) => format!("w{k}"),
        }
    }
}

impl BlockParams for PowerParams {
    const KEYS: &'static [&'static str] = &["power"];
    /// `power=exact` (default: cos^n γ) or `power=w4|w8|w16` (W(n, γ) with that k).
    fn from_options(o: &Options) -> Result<Self, String> {
        let mode = match o.get("power").unwrap_or("exact") {
            "exact" => PowerMode::Exact,
            "w4" => PowerMode::W(4),
            "w8" => PowerMode::W(8),
            "w16" => PowerMode::W(16),
            other => {
                return Err(format!(
                    "unsupported power mode {other:?} (expected exact, w4, w8 or w16: W(n, γ) has shift-add divisions for k = 4, 8, 16 only)"
                ))
            }
        };
        Ok(PowerParams { mode })
    }
    fn describe(&self) -> Option<String> {
        Some(format!("Power mode {}", self.name()))
    }
    fn test_sets() -> Vec<Options> {
        ["exact", "w4", "w8", "w16"]
            .map(|m| Options::new().with("power", m))
            .to_vec()
    }
    fn multipliers(&self) -> Option<usize> {
        Some(match self.mode {
            PowerMode::Exact => 18,
            PowerMode::W(k) => 1 + k.trailing_zeros() as usize,
        })
    }
}

/// Fraction bits of the W slope word (9 for k = 8, else 8; 8 in the exact mode, unused).
fn slope_frac(p: &PowerParams) -> u32 {
    p.mode
        .k()
        .map_or(8, |k| golden::units::power_unit::slope_word(k, 0).1)
}

fn bit(b: bool) -> Constant<Bit> {
    Constant::new(b)
}

crate::hw_block! {
    /// The power unit (see the module header).
    pub struct PowerUnit(clock) as "power-unit" {
        summary: "cos γ and n in, S = cos^n γ (square-and-multiply) or W(n, γ) for k = 4, 8, 16 out, Q1.15 (SPEC §2)",
        latency: 50 => "valid_in to valid_out in every mode, one pixel per clock",
        multipliers: 18,
        in { valid_in: Bit, cos_gamma: Bits<16>, n: Bits<10> }
        out { valid_out: Bit, spec: Bits<16> }
        // Mode constants.
        w_mode: Constant<Bit> = bit(p.mode != PowerMode::Exact),
        k8: Constant<Bit> = bit(p.mode == PowerMode::W(8)),
        k16: Constant<Bit> = bit(p.mode == PowerMode::W(16)),
        sq_on: [Constant<Bit>; 4] = std::array::from_fn(|i| bit(p.mode.k().is_some_and(|k| (i as u32) < k.trailing_zeros()))),
        one: Constant<Bits<16>> = Constant::new(0x8000.into()),
        // Exact path: stage 3j is Eja, 3j + 1 Eja', 3j + 2 Ejb (j = 0..9).
        e_valid: [DFF<Bit>; 50] = std::array::from_fn(|_| Default::default()),
        e_n: [DFF<Bits<10>>; 49] = std::array::from_fn(|_| Default::default()),
        e_acc: [DFF<Bits<16>>; 50] = std::array::from_fn(|_| Default::default()),
        e_pw: [DFF<Bits<16>>; 9],
        /// E1..E9's acc·pw (index j − 1), E0..E8's squares, exact.
        e_prod: [MulPipeDeep; 9],
        e_sq: [MulPipeDeep; 9],
        e_rnd_prod: [RoundProductToUQ1_15; 9],
        e_rnd_sq: [RoundProductToUQ1_15; 9],
        // W path: W1..W7 and the padding.
        m1: Signal<Local, Bits<16>>,
        a4: Signal<Local, Bits<16>>, a8: Signal<Local, Bits<16>>, a16: Signal<Local, Bits<16>>,
        w_a: DFF<Bits<16>>, w_t: DFF<Bits<16>>, w_above: DFF<Bit>, w_zero: DFF<Bit>,
        w_valid1: DFF<Bit>,
        w_p: MulPipe, w_above2: Delay<Bit, MUL_LATENCY>, w_zero2: Delay<Bit, MUL_LATENCY>,
        w_valid2: Delay<Bit, MUL_LATENCY>,
        /// 1.0 and half an output LSB in p's units (2^-(15+f), f = 9 for k = 8, else 8).
        w_one: Constant<Bits<32>> = Constant::new((1u64 << (15 + slope_frac(p))).into()),
        w_half: Constant<Bits<32>> = Constant::new((1u64 << (slope_frac(p) - 1)).into()),
        w_sum: Signal<Local, Bits<32>>,
        /// W3a: the bracket registered (splits W3's compare, subtract and rounding: the path
        /// that limited Fmax to 22 MHz).
        w_sum_q: DFF<Bits<32>>, w_valid3: DFF<Bit>,
        w_rnd: Signal<Local, Bits<32>>,
        w_b: [DFF<Bits<16>>; 5],
        w_valid: [DFF<Bit>; 5],
        /// W4a..W7a: the square, and the word it squares carried beside it.
        w_sq: [MulPipe; 4],
        w_bp: [Delay<Bits<16>, MUL_LATENCY>; 4],
        w_valid_a: [Delay<Bit, MUL_LATENCY>; 4],
        w_rnd_sq: [RoundProductToUQ1_15; 4],
        w_spec_pad: Delay<Bits<16>, 33>,
        w_valid_pad: Delay<Bit, 33>,
    }
    new(p: &PowerParams);
}

impl Logic for PowerUnit {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            w_a,
            w_t,
            w_above,
            w_zero,
            w_valid1,
            w_p,
            w_above2,
            w_zero2,
            w_valid2,
            w_sum_q,
            w_valid3,
            w_spec_pad,
            w_valid_pad
        );
        for j in 0..50 {
            clock!(self, clock, e_valid[j], e_acc[j]);
        }
        for j in 0..49 {
            self.e_n[j].clock.next = self.clock.val();
        }
        for j in 0..9 {
            clock!(self, clock, e_pw[j], e_prod[j], e_sq[j]);
        }
        for i in 0..5 {
            clock!(self, clock, w_b[i], w_valid[i]);
        }
        for i in 0..4 {
            clock!(self, clock, w_sq[i], w_bp[i], w_valid_a[i]);
        }
        // ---- exact: E0a (the square's operands enter MulPipeDeep with stage 0)
        self.e_valid[0].d.next = self.valid_in.val();
        self.e_n[0].d.next = self.n.val();
        if self.n.val().get_bit(0) {
            self.e_acc[0].d.next = self.cos_gamma.val();
        } else {
            self.e_acc[0].d.next = self.one.val();
        }
        self.e_sq[0].a.next = self.cos_gamma.val();
        self.e_sq[0].b.next = self.cos_gamma.val();
        for k in 1..4 {
            self.e_valid[k].d.next = self.e_valid[k - 1].q.val();
            self.e_n[k].d.next = self.e_n[k - 1].q.val();
            self.e_acc[k].d.next = self.e_acc[k - 1].q.val();
        }
        // E0b
        self.e_valid[4].d.next = self.e_valid[3].q.val();
        self.e_n[4].d.next = self.e_n[3].q.val();
        self.e_acc[4].d.next = self.e_acc[3].q.val();
        self.e_rnd_sq[0].wide.next = self.e_sq[0].p.val();
        self.e_pw[0].d.next = self.e_rnd_sq[0].narrow.val();
        // E1..E8: stage 5j is Eja (the operands enter with it), 5j + 1..5j + 3 the products'
        // clocks, 5j + 4 Ejb.
        for j in 1..9 {
            // Eja
            self.e_valid[5 * j].d.next = self.e_valid[5 * j - 1].q.val();
            self.e_n[5 * j].d.next = self.e_n[5 * j - 1].q.val();
            self.e_acc[5 * j].d.next = self.e_acc[5 * j - 1].q.val();
            if self.e_n[5 * j - 1].q.val().get_bit(j) {
                self.e_prod[j - 1].a.next = self.e_acc[5 * j - 1].q.val();
                self.e_prod[j - 1].b.next = self.e_pw[j - 1].q.val();
            } else {
                self.e_prod[j - 1].a.next = 0.into();
                self.e_prod[j - 1].b.next = 0.into();
            }
            self.e_sq[j].a.next = self.e_pw[j - 1].q.val();
            self.e_sq[j].b.next = self.e_pw[j - 1].q.val();
            for k in 1..4 {
                self.e_valid[5 * j + k].d.next = self.e_valid[5 * j + k - 1].q.val();
                self.e_n[5 * j + k].d.next = self.e_n[5 * j + k - 1].q.val();
                self.e_acc[5 * j + k].d.next = self.e_acc[5 * j + k - 1].q.val();
            }
            // Ejb
            self.e_valid[5 * j + 4].d.next = self.e_valid[5 * j + 3].q.val();
            self.e_n[5 * j + 4].d.next = self.e_n[5 * j + 3].q.val();
            self.e_rnd_prod[j - 1].wide.next = self.e_prod[j - 1].p.val();
            if self.e_n[5 * j + 3].q.val().get_bit(j) {
                self.e_acc[5 * j + 4].d.next = self.e_rnd_prod[j - 1].narrow.val();
            } else {
                self.e_acc[5 * j + 4].d.next = self.e_acc[5 * j + 3].q.val();
            }
            self.e_rnd_sq[j].wide.next = self.e_sq[j].p.val();
            self.e_pw[j].d.next = self.e_rnd_sq[j].narrow.val();
        }
        // E9a (operands enter with stage 45)
        self.e_valid[45].d.next = self.e_valid[44].q.val();
        self.e_n[45].d.next = self.e_n[44].q.val();
        self.e_acc[45].d.next = self.e_acc[44].q.val();
        if self.e_n[44].q.val().get_bit(9) {
            self.e_prod[8].a.next = self.e_acc[44].q.val();
            self.e_prod[8].b.next = self.e_pw[8].q.val();
        } else {
            self.e_prod[8].a.next = 0.into();
            self.e_prod[8].b.next = 0.into();
        }
        for k in 46..49 {
            self.e_valid[k].d.next = self.e_valid[k - 1].q.val();
            self.e_n[k].d.next = self.e_n[k - 1].q.val();
            self.e_acc[k].d.next = self.e_acc[k - 1].q.val();
        }
        // E9b
        self.e_valid[49].d.next = self.e_valid[48].q.val();
        self.e_rnd_prod[8].wide.next = self.e_prod[8].p.val();
        if self.e_n[48].q.val().get_bit(9) {
            self.e_acc[49].d.next = self.e_rnd_prod[8].narrow.val();
        } else {
            self.e_acc[49].d.next = self.e_acc[48].q.val();
        }
        // ---- W: W1 — a = (n+1)·C_k by shifts and adds (m1 = n + 1 ≤ 1024).
        self.m1.next = bit_cast::<16, 10>(self.n.val()) + 1;
        self.a4.next =
            (self.m1.val() << 5) + (self.m1.val() << 4) + (self.m1.val() << 1) + self.m1.val();
        self.a8.next =
            (self.m1.val() << 5) + (self.m1.val() << 4) + (self.m1.val() << 3) + self.m1.val();
        self.a16.next = (self.m1.val() << 4) - self.m1.val();
        if self.k16.val() {
            self.w_a.d.next = self.a16.val();
        } else if self.k8.val() {
            self.w_a.d.next = self.a8.val();
        } else {
            self.w_a.d.next = self.a4.val();
        }
        if self.cos_gamma.val() > self.one.val() {
            self.w_t.d.next = self.cos_gamma.val() - self.one.val();
            self.w_above.d.next = true;
        } else {
            self.w_t.d.next = self.one.val() - self.cos_gamma.val();
            self.w_above.d.next = false;
        }
        self.w_zero.d.next = self.cos_gamma.val() == 0;
        self.w_valid1.d.next = self.valid_in.val();
        // W2: p = a·t, exact, two clocks.
        self.w_p.a.next = self.w_a.q.val();
        self.w_p.b.next = self.w_t.q.val();
        self.w_above2.d.next = self.w_above.q.val();
        self.w_zero2.d.next = self.w_zero.q.val();
        self.w_valid2.d.next = self.w_valid1.q.val();
        // W3: the bracket 1 ± p in p's units (2^-(15+f)), clamped at 0, rounded to UQ1.15.
        if self.w_zero2.q.val() {
            self.w_sum.next = 0.into();
        } else if self.w_above2.q.val() {
            self.w_sum.next = self.w_one.val() + self.w_p.p.val();
        } else if self.w_p.p.val() > self.w_one.val() {
            self.w_sum.next = 0.into();
        } else {
            self.w_sum.next = self.w_one.val() - self.w_p.p.val();
        }
        self.w_sum_q.d.next = self.w_sum.val();
        self.w_valid3.d.next = self.w_valid2.q.val();
        // W3b: round to UQ1.15, saturate.
        self.w_rnd.next = self.w_sum_q.q.val() + self.w_half.val();
        if self.k8.val() {
            if self.w_rnd.val().get_bits::<7>(25).any() {
                self.w_b[0].d.next = 0xFFFF.into();
            } else {
                self.w_b[0].d.next = self.w_rnd.val().get_bits::<16>(9);
            }
        } else if self.w_rnd.val().get_bits::<8>(24).any() {
            self.w_b[0].d.next = 0xFFFF.into();
        } else {
            self.w_b[0].d.next = self.w_rnd.val().get_bits::<16>(8);
        }
        self.w_valid[0].d.next = self.w_valid3.q.val();
        // W4..W7: stage i squares b_i (when the mode's k needs it) into b_(i+1): Wia the
        // square, with b_i carried beside it; Wib the rounding and the choice.
        for i in 0..4 {
            self.w_sq[i].a.next = self.w_b[i].q.val();
            self.w_sq[i].b.next = self.w_b[i].q.val();
            self.w_bp[i].d.next = self.w_b[i].q.val();
            self.w_valid_a[i].d.next = self.w_valid[i].q.val();
            self.w_rnd_sq[i].wide.next = self.w_sq[i].p.val();
            if self.sq_on[i].val() {
                self.w_b[i + 1].d.next = self.w_rnd_sq[i].narrow.val();
            } else {
                self.w_b[i + 1].d.next = self.w_bp[i].q.val();
            }
            self.w_valid[i + 1].d.next = self.w_valid_a[i].q.val();
        }
        self.w_spec_pad.d.next = self.w_b[4].q.val();
        self.w_valid_pad.d.next = self.w_valid[4].q.val();
        // Output: the mode constant selects the datapath.
        if self.w_mode.val() {
            self.valid_out.next = self.w_valid_pad.q.val();
            self.spec.next = self.w_spec_pad.q.val();
        } else {
            self.valid_out.next = self.e_valid[49].q.val();
            self.spec.next = self.e_acc[49].q.val();
        }
    }
}
