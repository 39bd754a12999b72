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
//!   feeding [`NormalizerK`] in place of the three squarers. **Latency 2 + 7 = 9 clocks.**
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
//! [`SpanNormalizer`] ports: `valid_in`, `load`, `k0`, `alpha`, `beta` as above, plus
//! `x0`, `y0`, `z0` (signed Q2.14, N₀, taken with `load`) and `dx`, `dy`, `dz` (signed Q2.14,
//! Δ, taken with `load`); outputs `valid_out`, `nx`, `ny`, `nz` (signed Q2.14) as the
//! normalizer's. Error budget: the normalizer's (`crate::normalizer::error_budget`).

use rust_hdl::prelude::*;

use crate::fixed::{K_ALPHA, K_FULL};
use crate::normalizer::{NormalizerCoeffs, NormalizerK};

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

/// The K recurrence alone. Latency [`KRecurrence::LATENCY`].
#[derive(LogicBlock)]
pub struct KRecurrence {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub load: Signal<In, Bit>,
    pub k0: Signal<In, Bits<32>>,
    pub alpha: Signal<In, Bits<32>>,
    pub beta: Signal<In, Bits<32>>,
    pub valid_out: Signal<Out, Bit>,
    pub k: Signal<Out, Bits<32>>,
    // Stage 1: input registers (2α and 2β are wiring).
    valid_p1: DFF<Bit>,
    load_p1: DFF<Bit>,
    k0_p1: DFF<Bits<32>>,
    alpha2_p1: DFF<Bits<32>>,
    beta_p1: DFF<Bits<32>>,
    // Stage 2: recurrence state (value for the next pixel) and the output register.
    k_next: DFF<Bits<32>>,
    beta_i: DFF<Bits<32>>,
    alpha2: DFF<Bits<32>>,
    beta2: DFF<Bits<32>>,
    k_out: DFF<Bits<32>>,
    valid_p2: DFF<Bit>,
    // This pixel's K, β_i, 2α, 2β: the loaded values on a load, else the state.
    k_cur: Signal<Local, Bits<32>>,
    beta_cur: Signal<Local, Bits<32>>,
    alpha2_cur: Signal<Local, Bits<32>>,
    beta2_cur: Signal<Local, Bits<32>>,
}

impl KRecurrence {
    /// Clocks from `valid_in` to `valid_out`.
    pub const LATENCY: usize = 2;

    pub fn new() -> Self {
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            load: Default::default(),
            k0: Default::default(),
            alpha: Default::default(),
            beta: Default::default(),
            valid_out: Default::default(),
            k: Default::default(),
            valid_p1: Default::default(),
            load_p1: Default::default(),
            k0_p1: Default::default(),
            alpha2_p1: Default::default(),
            beta_p1: Default::default(),
            k_next: Default::default(),
            beta_i: Default::default(),
            alpha2: Default::default(),
            beta2: Default::default(),
            k_out: Default::default(),
            valid_p2: Default::default(),
            k_cur: Default::default(),
            beta_cur: Default::default(),
            alpha2_cur: Default::default(),
            beta2_cur: Default::default(),
        }
    }
}

impl Default for KRecurrence {
    fn default() -> Self {
        Self::new()
    }
}

impl Logic for KRecurrence {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
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
        // Hold while no pixel is requested.
        self.k_next.d.next = self.k_next.q.val();
        self.beta_i.d.next = self.beta_i.q.val();
        self.alpha2.d.next = self.alpha2.q.val();
        self.beta2.d.next = self.beta2.q.val();
        self.k_out.d.next = self.k_out.q.val();
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

/// K recurrence + vector interpolation feeding the normalizer's back end.
/// Latency [`SpanNormalizer::LATENCY`].
#[derive(LogicBlock)]
pub struct SpanNormalizer {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub load: Signal<In, Bit>,
    pub x0: Signal<In, Bits<16>>,
    pub y0: Signal<In, Bits<16>>,
    pub z0: Signal<In, Bits<16>>,
    pub dx: Signal<In, Bits<16>>,
    pub dy: Signal<In, Bits<16>>,
    pub dz: Signal<In, Bits<16>>,
    pub k0: Signal<In, Bits<32>>,
    pub alpha: Signal<In, Bits<32>>,
    pub beta: Signal<In, Bits<32>>,
    pub valid_out: Signal<Out, Bit>,
    pub nx: Signal<Out, Bits<16>>,
    pub ny: Signal<Out, Bits<16>>,
    pub nz: Signal<Out, Bits<16>>,
    krec: KRecurrence,
    scale: NormalizerK,
    // Vector interpolation, aligned with KRecurrence's two stages.
    valid_p1: DFF<Bit>,
    load_p1: DFF<Bit>,
    x0_p1: DFF<Bits<16>>,
    y0_p1: DFF<Bits<16>>,
    z0_p1: DFF<Bits<16>>,
    dx_p1: DFF<Bits<16>>,
    dy_p1: DFF<Bits<16>>,
    dz_p1: DFF<Bits<16>>,
    x_next: DFF<Bits<16>>,
    y_next: DFF<Bits<16>>,
    z_next: DFF<Bits<16>>,
    dx_hold: DFF<Bits<16>>,
    dy_hold: DFF<Bits<16>>,
    dz_hold: DFF<Bits<16>>,
    x_out: DFF<Bits<16>>,
    y_out: DFF<Bits<16>>,
    z_out: DFF<Bits<16>>,
    x_cur: Signal<Local, Bits<16>>,
    y_cur: Signal<Local, Bits<16>>,
    z_cur: Signal<Local, Bits<16>>,
    dx_cur: Signal<Local, Bits<16>>,
    dy_cur: Signal<Local, Bits<16>>,
    dz_cur: Signal<Local, Bits<16>>,
}

impl SpanNormalizer {
    /// Clocks from `valid_in` to `valid_out`.
    pub const LATENCY: usize = KRecurrence::LATENCY + NormalizerK::LATENCY;

    pub fn new(c: &NormalizerCoeffs) -> Self {
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            load: Default::default(),
            x0: Default::default(),
            y0: Default::default(),
            z0: Default::default(),
            dx: Default::default(),
            dy: Default::default(),
            dz: Default::default(),
            k0: Default::default(),
            alpha: Default::default(),
            beta: Default::default(),
            valid_out: Default::default(),
            nx: Default::default(),
            ny: Default::default(),
            nz: Default::default(),
            krec: KRecurrence::new(),
            scale: NormalizerK::new(c),
            valid_p1: Default::default(),
            load_p1: Default::default(),
            x0_p1: Default::default(),
            y0_p1: Default::default(),
            z0_p1: Default::default(),
            dx_p1: Default::default(),
            dy_p1: Default::default(),
            dz_p1: Default::default(),
            x_next: Default::default(),
            y_next: Default::default(),
            z_next: Default::default(),
            dx_hold: Default::default(),
            dy_hold: Default::default(),
            dz_hold: Default::default(),
            x_out: Default::default(),
            y_out: Default::default(),
            z_out: Default::default(),
            x_cur: Default::default(),
            y_cur: Default::default(),
            z_cur: Default::default(),
            dx_cur: Default::default(),
            dy_cur: Default::default(),
            dz_cur: Default::default(),
        }
    }
}

impl Logic for SpanNormalizer {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self, clock, krec, scale, valid_p1, load_p1, x0_p1, y0_p1, z0_p1, dx_p1, dy_p1, dz_p1,
            x_next, y_next, z_next, dx_hold, dy_hold, dz_hold, x_out, y_out, z_out
        );
        self.krec.valid_in.next = self.valid_in.val();
        self.krec.load.next = self.load.val();
        self.krec.k0.next = self.k0.val();
        self.krec.alpha.next = self.alpha.val();
        self.krec.beta.next = self.beta.val();

        self.valid_p1.d.next = self.valid_in.val();
        self.load_p1.d.next = self.load.val() & self.valid_in.val();
        self.x0_p1.d.next = self.x0.val();
        self.y0_p1.d.next = self.y0.val();
        self.z0_p1.d.next = self.z0.val();
        self.dx_p1.d.next = self.dx.val();
        self.dy_p1.d.next = self.dy.val();
        self.dz_p1.d.next = self.dz.val();
        if self.load_p1.q.val() {
            self.x_cur.next = self.x0_p1.q.val();
            self.y_cur.next = self.y0_p1.q.val();
            self.z_cur.next = self.z0_p1.q.val();
            self.dx_cur.next = self.dx_p1.q.val();
            self.dy_cur.next = self.dy_p1.q.val();
            self.dz_cur.next = self.dz_p1.q.val();
        } else {
            self.x_cur.next = self.x_next.q.val();
            self.y_cur.next = self.y_next.q.val();
            self.z_cur.next = self.z_next.q.val();
            self.dx_cur.next = self.dx_hold.q.val();
            self.dy_cur.next = self.dy_hold.q.val();
            self.dz_cur.next = self.dz_hold.q.val();
        }
        self.x_next.d.next = self.x_next.q.val();
        self.y_next.d.next = self.y_next.q.val();
        self.z_next.d.next = self.z_next.q.val();
        self.dx_hold.d.next = self.dx_hold.q.val();
        self.dy_hold.d.next = self.dy_hold.q.val();
        self.dz_hold.d.next = self.dz_hold.q.val();
        self.x_out.d.next = self.x_out.q.val();
        self.y_out.d.next = self.y_out.q.val();
        self.z_out.d.next = self.z_out.q.val();
        if self.valid_p1.q.val() {
            // N_{i+1} = N_i + Δ (Q2.14, the caller keeps N_i representable).
            self.x_out.d.next = self.x_cur.val();
            self.y_out.d.next = self.y_cur.val();
            self.z_out.d.next = self.z_cur.val();
            self.x_next.d.next = self.x_cur.val() + self.dx_cur.val();
            self.y_next.d.next = self.y_cur.val() + self.dy_cur.val();
            self.z_next.d.next = self.z_cur.val() + self.dz_cur.val();
            self.dx_hold.d.next = self.dx_cur.val();
            self.dy_hold.d.next = self.dy_cur.val();
            self.dz_hold.d.next = self.dz_cur.val();
        }

        self.scale.valid_in.next = self.krec.valid_out.val();
        self.scale.k.next = self.krec.k.val();
        self.scale.x.next = self.x_out.q.val();
        self.scale.y.next = self.y_out.q.val();
        self.scale.z.next = self.z_out.q.val();
        self.valid_out.next = self.scale.valid_out.val();
        self.nx.next = self.scale.nx.val();
        self.ny.next = self.scale.ny.val();
        self.nz.next = self.scale.nz.val();
    }
}
