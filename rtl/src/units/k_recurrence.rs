//! K along a raster line by additions only (SPEC §1, "simplified radicand" block).
//!
//! ```text
//! K_{i+1} = K_i + 2α + β_i,   β_{i+1} = β_i + 2β,   β_0 = β
//! α = N₀·Δ (once per raster line),  β = Δ·Δ (once per triangle),  K_0 = N₀·N₀
//! ```
//! Two tops:
//! - [`KRecurrence`]: K_0, α, β in (from the per-line set-up, [`span_setup`]), K_i out, one
//!   per pixel. **Latency 2 clocks.**
//! - [`SpanNormalizer`]: the same recurrence beside the vector interpolation N_{i+1} = N_i + Δ,
//!   feeding [`NormalizerK`] in place of the three squarers. **Latency 2 + 11 = 13 clocks.**
//!
//! # Exactness
//! N₀ and Δ are integers in units of the Q2.14 LSB (N_i = N₀ + i·Δ exactly, the vector
//! interpolator adds Δ in the same format), so K_i = |N_i|² is an integer in Q4.28 units and
//! α, β, K_0 are exact integers ([`span_setup`] computes them in i64). All sums are 32-bit
//! wrap-around: every true K_i is in [0, 3·2³⁰] ⊂ [0, 2³²), so the wrapped K_i equals the exact
//! integer even when the intermediate differences 2α + β_i are negative or wrap. The block's K is
//! therefore **bit-identical** to squaring the same quantized vector (Normalizer's S1+S2), and
//! SpanNormalizer's output is bit-identical to Normalizer's on the same N_i.
//!
//! # Ports of [`KRecurrence`]
//! | port        | dir | format                                                       |
//! |-------------|-----|--------------------------------------------------------------|
//! | `valid_in`  | in  | 1 = emit one K for one pixel this clock                      |
//! | `load`      | in  | with `valid_in`: this pixel is pixel 0 of a new line; take `k0`, `alpha`, `beta` (ignored without `valid_in`) |
//! | `k0`        | in  | unsigned Q4.28: K_0 = N₀·N₀                                  |
//! | `alpha`     | in  | signed Q4.28 (two's complement): α = N₀·Δ                    |
//! | `beta`      | in  | unsigned Q4.28: β = Δ·Δ                                      |
//! | `valid_out` | out | `valid_in` delayed 2 clocks                                  |
//! | `k`         | out | unsigned Q4.28: K_i, exact; holds while `valid_out` is low   |
//!
//! Handshake: one pixel per clock while `valid_in` is high; gaps (valid low) freeze the
//! recurrence, so the address block can pause between pixels. `load` restarts it.
//! ```text
//! clock     : 0     1     2     3     4     5
//! valid_in  : 1     1     0     1     ...
//! load      : 1     0     0     0
//! valid_out :             1     1     0     1
//! k         :             K_0   K_1   K_1   K_2
//! ```
//! Overflow: none possible for a line whose vectors stay representable (the caller's
//! guarantee; true for interpolation between unit normals). Error: none (exact).
//!
//! [`SpanNormalizer`] runs one two-stage interpolator per component (`ComponentStep`, built
//! like [`KRecurrence`]: input registers, then state and output register) so that N_i and K_i
//! reach [`NormalizerK`] in the same clock. Its ports: `valid_in`, `load`, `k0`, `alpha`,
//! `beta` as above, plus `x0`, `y0`, `z0` (signed Q2.14, N₀, taken with `load`) and `dx`,
//! `dy`, `dz` (signed Q2.14, Δ, taken with `load`); outputs `valid_out`, `nx`, `ny`, `nz`
//! (signed Q2.17) as the normalizer's. N_i enters [`NormalizerK`] as signed Q2.17 (its input
//! format since N left the vector interpolator at Q2.17): the Q2.14 word with three zero LSBs,
//! for which the squarers' K is exact too. Error budget: the normalizer's
//! (`crate::units::normalizer::error_budget`).

use rust_hdl::prelude::*;

use crate::core::fixed::{K_ALPHA, K_FULL};
use crate::units::normalizer::{NormalizerCoeffs, NormalizerK};

/// Per-line set-up values of the recurrence, as raw words for the block's ports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpanSetup {
    /// K_0 = N₀·N₀, unsigned Q4.28.
    pub k0: u64,
    /// α = N₀·Δ, signed Q4.28 (two's complement in 32 bits).
    pub alpha: u64,
    /// β = Δ·Δ, unsigned Q4.28.
    pub beta: u64,
}

/// The software set-up of a line (SPEC §1: α once per line, β once per triangle), exact.
/// `n0` and `delta` are raw Q2.14 integers (Δ in units of the Q2.14 LSB).
pub fn span_setup(n0: [i64; 3], delta: [i64; 3]) -> SpanSetup {
    let dot = |a: [i64; 3], b: [i64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    SpanSetup {
        k0: K_FULL.from_int(dot(n0, n0)),
        alpha: K_ALPHA.from_int(dot(n0, delta)),
        beta: K_FULL.from_int(dot(delta, delta)),
    }
}

crate::hw_block! {
    /// The K recurrence alone. Latency [`KRecurrence::LATENCY`].
    pub struct KRecurrence(clock) as "k-recurrence" {
        summary: "K along a span by additions: K_0, α, β in, K_i out (SPEC §1)",
        latency: 2 => "valid_in to valid_out, one input per clock",
        multipliers: 0,
        in { valid_in: Bit, load: Bit, k0: Bits<32>, alpha: Bits<32>, beta: Bits<32> }
        out { valid_out: Bit, k: Bits<32> }
        // Stage 1: input registers (2α and 2β are wiring).
        valid_p1: DFF<Bit>, load_p1: DFF<Bit>,
        k0_p1: DFF<Bits<32>>, alpha2_p1: DFF<Bits<32>>, beta_p1: DFF<Bits<32>>,
        // Stage 2: recurrence state (value for the next pixel) and the output register.
        k_next: DFF<Bits<32>>, beta_i: DFF<Bits<32>>, alpha2: DFF<Bits<32>>, beta2: DFF<Bits<32>>,
        k_out: DFF<Bits<32>>, valid_p2: DFF<Bit>,
        // This pixel's K, β_i, 2α, 2β: the loaded values on a load, else the state.
        k_cur: Signal<Local, Bits<32>>, beta_cur: Signal<Local, Bits<32>>,
        alpha2_cur: Signal<Local, Bits<32>>, beta2_cur: Signal<Local, Bits<32>>,
    }
    new();
}

impl Logic for KRecurrence {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, valid_p1, load_p1, k0_p1, alpha2_p1, beta_p1, k_next, beta_i, alpha2,
            beta2, k_out, valid_p2
        );
        self.valid_p1.d.next = self.valid_in.val();
        self.load_p1.d.next = self.load.val() & self.valid_in.val();
        self.k0_p1.d.next = self.k0.val();
        self.alpha2_p1.d.next = self.alpha.val() << 1;
        self.beta_p1.d.next = self.beta.val();

        if self.load_p1.q.val() {
            self.k_cur.next = self.k0_p1.q.val();
            self.beta_cur.next = self.beta_p1.q.val();
            self.alpha2_cur.next = self.alpha2_p1.q.val();
            self.beta2_cur.next = self.beta_p1.q.val() << 1;
        } else {
            self.k_cur.next = self.k_next.q.val();
            self.beta_cur.next = self.beta_i.q.val();
            self.alpha2_cur.next = self.alpha2.q.val();
            self.beta2_cur.next = self.beta2.q.val();
        }
        // dff_setup! holds every register while no pixel is requested.
        if self.valid_p1.q.val() {
            self.k_out.d.next = self.k_cur.val();
            // K_{i+1} = K_i + 2α + β_i ; β_{i+1} = β_i + 2β  (mod 2³², exact, see header)
            self.k_next.d.next = self.k_cur.val() + self.alpha2_cur.val() + self.beta_cur.val();
            self.beta_i.d.next = self.beta_cur.val() + self.beta2_cur.val();
            self.alpha2.d.next = self.alpha2_cur.val();
            self.beta2.d.next = self.beta2_cur.val();
        }
        self.valid_p2.d.next = self.valid_p1.q.val();
        self.valid_out.next = self.valid_p2.q.val();
        self.k.next = self.k_out.q.val();
    }
}

crate::hw_block! {
    /// K recurrence + vector interpolation feeding the normalizer's back end.
    /// Latency [`SpanNormalizer::LATENCY`].
    pub struct SpanNormalizer(clock) as "span-normalizer" {
        summary: "K recurrence + vector interpolator feeding the normalizer back end (SPEC §1)",
        latency: KRecurrence::LATENCY + NormalizerK::LATENCY
            => "valid_in to valid_out, one input per clock",
        multipliers: 5,
        in { valid_in: Bit, load: Bit,
            x0: Bits<16>, y0: Bits<16>, z0: Bits<16>, dx: Bits<16>, dy: Bits<16>, dz: Bits<16>,
            k0: Bits<32>, alpha: Bits<32>, beta: Bits<32>,
        }
        out { valid_out: Bit, nx: Bits<19>, ny: Bits<19>, nz: Bits<19> }
        krec: KRecurrence,
        // Vector interpolation N_{i+1} = N_i + Δ, one component each, aligned with `krec`.
        step_x: ComponentStep, step_y: ComponentStep, step_z: ComponentStep,
        scale: NormalizerK = NormalizerK::new(c),
    }
    new(c: &NormalizerCoeffs);
}

impl Logic for SpanNormalizer {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, krec, step_x, step_y, step_z, scale);
        self.krec.valid_in.next = self.valid_in.val();
        self.krec.load.next = self.load.val();
        self.krec.k0.next = self.k0.val();
        self.krec.alpha.next = self.alpha.val();
        self.krec.beta.next = self.beta.val();

        self.step_x.valid_in.next = self.valid_in.val();
        self.step_y.valid_in.next = self.valid_in.val();
        self.step_z.valid_in.next = self.valid_in.val();
        self.step_x.load.next = self.load.val();
        self.step_y.load.next = self.load.val();
        self.step_z.load.next = self.load.val();
        self.step_x.n0.next = self.x0.val();
        self.step_y.n0.next = self.y0.val();
        self.step_z.n0.next = self.z0.val();
        self.step_x.delta.next = self.dx.val();
        self.step_y.delta.next = self.dy.val();
        self.step_z.delta.next = self.dz.val();

        self.scale.valid_in.next = self.krec.valid_out.val();
        self.scale.k.next = self.krec.k.val();
        self.scale.x.next = self.step_x.n.val();
        self.scale.y.next = self.step_y.n.val();
        self.scale.z.next = self.step_z.n.val();
        self.valid_out.next = self.scale.valid_out.val();
        self.nx.next = self.scale.nx.val();
        self.ny.next = self.scale.ny.val();
        self.nz.next = self.scale.nz.val();
    }
}

crate::hw_block! {
    /// One component of [`SpanNormalizer`]'s vector interpolation, `N_{i+1} = N_i + Δ` (signed
    /// Q2.14, modulo 2¹⁶; the caller keeps N_i representable), in [`KRecurrence`]'s two stages:
    /// input registers, then the recurrence state and the output register. `load` (with
    /// `valid_in`) takes `n0` and `delta`; clocks with `valid_in` low freeze it. `n` is N_i,
    /// [`KRecurrence::LATENCY`] clocks after its `valid_in`, beside K_i, in the normalizer's
    /// input format: signed Q2.17, the Q2.14 word with three zero LSBs (wiring).
    struct ComponentStep(clock) {
        in { valid_in: Bit, load: Bit, n0: Bits<16>, delta: Bits<16> }
        out { n: Bits<19> }
        // Stage 1: input registers.
        valid_p1: DFF<Bit>, load_p1: DFF<Bit>, n0_p1: DFF<Bits<16>>, delta_p1: DFF<Bits<16>>,
        // Stage 2: recurrence state (value for the next pixel) and the output register.
        n_next: DFF<Bits<16>>, delta_hold: DFF<Bits<16>>, n_out: DFF<Bits<16>>,
        // This pixel's N and Δ: the loaded values on a load, else the state.
        n_cur: Signal<Local, Bits<16>>, delta_cur: Signal<Local, Bits<16>>,
        n_ext: Signal<Local, Bits<19>>,
    }
}

impl Logic for ComponentStep {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid_p1, load_p1, n0_p1, delta_p1, n_next, delta_hold, n_out);
        self.valid_p1.d.next = self.valid_in.val();
        self.load_p1.d.next = self.load.val() & self.valid_in.val();
        self.n0_p1.d.next = self.n0.val();
        self.delta_p1.d.next = self.delta.val();
        if self.load_p1.q.val() {
            self.n_cur.next = self.n0_p1.q.val();
            self.delta_cur.next = self.delta_p1.q.val();
        } else {
            self.n_cur.next = self.n_next.q.val();
            self.delta_cur.next = self.delta_hold.q.val();
        }
        // dff_setup! holds every register while no pixel is requested.
        if self.valid_p1.q.val() {
            self.n_out.d.next = self.n_cur.val();
            self.n_next.d.next = self.n_cur.val() + self.delta_cur.val();
            self.delta_hold.d.next = self.delta_cur.val();
        }
        self.n_ext.next = bit_cast::<19, 16>(self.n_out.q.val());
        self.n.next = self.n_ext.val() << 3;
    }
}
