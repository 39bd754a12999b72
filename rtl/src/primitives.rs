//! Building blocks shared by the RTL blocks: a delay line, the fixed-point narrowings of
//! [`crate::fixed`] (round to nearest, saturate) and the signed multiplies built on rust-hdl's
//! unsigned 16×16→32 multiply.
//!
//! Not a block of its own (nothing here is exported alone). Each primitive states its formula,
//! the formats of its ports, its latency and its overflow behaviour:
//!
//! | primitive              | ports (in → out)         | formula / formats                                  | latency |
//! |------------------------|--------------------------|----------------------------------------------------|---------|
//! | [`Delay<T, N>`]        | `d` → `q`                | q = d delayed N clocks (N registers, reset 0)      | N       |
//! | [`SatToQ2_14`]         | `wide` (32) → `narrow` (16) | signed Q3.29 + ½ LSB → signed Q2.14: drop 15 LSBs, saturate | 0 |
//! | [`RoundToUQ1_15`]      | `wide` (32) → `narrow` (16) | unsigned Q4.28 → unsigned Q1.15: add ½ LSB (2¹²), drop 13 LSBs, saturate | 0 |
//! | [`MulSignedUnsigned`]  | `a` (16), `b` (16) → `p` (32) | `a·b = ua·ub − [a<0]·(ub ≪ 16)` mod 2³² (one multiplier) | 0 |
//! | [`MulPipe`]            | `a` (16), `b` (16) → `p` (32) | a·b unsigned, exact: operands registered, product registered | 2 |
//! | [`MulPipeDeep`]        | `a` (16), `b` (16) → `p` (32) | as [`MulPipe`] with each side registered twice (a multiplier placed far from its logic) | 4 |
//! | [`MulSignedUnsignedPipe`] | `a` (16), `b` (16) → `p` (32) | as [`MulSignedUnsigned`], pipelined: operands registered; ua·ub and the correction registered; their difference registered | 3 |
//! | [`MulSignedPipe`]      | `a` (16), `b` (16) → `p` (32) | `a·b = ua·ub − ([a<0]·ub + [b<0]·ua) ≪ 16` mod 2³², pipelined the same way; with `b = a` the signed square | 3 |
//! | [`RoundProductToUQ1_15`] | `wide` (32) → `narrow` (16) | unsigned Q2.30 → unsigned Q1.15: add ½ LSB (2¹⁴), drop 15 LSBs, saturate | 0 |
//! | [`SatToQ2_17`]         | `wide` (32) → `narrow` (19) | signed Q3.29 + ½ LSB → signed Q2.17: drop 12 LSBs, saturate | 0 |
//! | [`RoundToQ2_17`]       | `wide` (32) → `narrow` (19) | signed Q3.29 → signed Q2.17: add ½ LSB (2¹¹), then [`SatToQ2_17`] | 0 |
//! | [`SatToUQ1_18`]        | `wide` (32) → `narrow` (19) | signed Q4.28 + ½ LSB → unsigned Q1.18: drop 10 LSBs, clamp to [0, 2 − 2⁻¹⁸] | 0 |
//! | [`MulLow3Pipe`]        | `v` (24), `m` (3) → `p` (32) | v·m for a 3-bit unsigned m, by shift and add in 24 bits (no multiplier), sign-extended: the low part of a 19-bit operand split 16 + 3 | 2 |
//!
//! Rounding is to nearest with ties toward +∞ (add half an output LSB, then drop the LSBs), the
//! rule of [`crate::fixed`]. The `Sat…` narrowings take a word that already carries the half LSB
//! (folded into a constant the caller adds anyway); the `Round…` ones add it themselves. Error
//! of a narrowing: at most half an output LSB when it does not saturate. The multiplies are
//! exact (the true product fits 32 bits).
//!
//! Every intermediate is its own exactly sized signal: rust-hdl's simulator wraps each operation
//! at its operands' width, Verilog sizes an expression by its context, and only one-operation
//! assignments mean the same in both.

use rust_hdl::prelude::*;

/// `q` is `d` delayed by `N` clocks (`N` ≥ 1 registers in a chain, reset to 0). Latency `N`,
/// one value per clock. Replaces hand-unrolled `_p1 … _pN` chains; name the field after the
/// tap it gives (`x_p5: Delay<Bits<16>, 5>`).
#[derive(LogicBlock)]
pub struct Delay<T: Synth, const N: usize> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    /// `stage[i]` holds `d` of i + 1 clocks ago.
    stage: [DFF<T>; N],
}

impl<T: Synth, const N: usize> Default for Delay<T, N> {
    fn default() -> Self {
        assert!(N >= 1, "a delay line needs at least one register");
        Self {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            stage: std::array::from_fn(|_| Default::default()),
        }
    }
}

impl<T: Synth, const N: usize> Logic for Delay<T, N> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..N {
            self.stage[i].clock.next = self.clock.val();
        }
        self.stage[0].d.next = self.d.val();
        for i in 1..N {
            self.stage[i].d.next = self.stage[i - 1].q.val();
        }
        // rust-hdl resolves an array index in Verilog only from a loop variable, so the last
        // register is addressed by a one-step loop.
        for i in (N - 1)..N {
            self.q.next = self.stage[i].q.val();
        }
    }
}

/// A synchronous ROM (PROM): `data` = `contents[address]` of the previous clock edge, as FPGA
/// block RAM reads; 0 before the first edge in every simulator (rust-hdl's `SyncROM` leaves
/// the Verilog register uninitialised, which Icarus shows as `x`). Latency 1. Exported as a
/// `reg` array with an `initial` block, which Yosys maps to block RAM (iCE40: SB_RAM40_4K).
/// Every one of the 2^N addresses holds a word.
#[derive(LogicBlock)]
pub struct Prom<D: Synth, const N: usize> {
    pub address: Signal<In, Bits<N>>,
    pub clock: Signal<In, Clock>,
    pub data: Signal<Out, D>,
    // Boxed as rust-hdl's own SyncROM holds it (the derive treats `_` fields as opaque).
    #[allow(clippy::box_collection)]
    _contents: Box<std::collections::BTreeMap<Bits<N>, D>>,
}

impl<D: Synth, const N: usize> Prom<D, N> {
    /// A PROM holding `words` from address 0 on.
    pub fn new(words: impl IntoIterator<Item = D>) -> Self {
        assert!(N < 20, "a PROM of 2^{N} words is not block RAM");
        let contents: std::collections::BTreeMap<Bits<N>, D> = words
            .into_iter()
            .enumerate()
            .map(|(i, w)| (Bits::<N>::from(i as u64), w))
            .collect();
        assert!(
            contents.len() == 1 << N,
            "a PROM of 2^{N} addresses needs 2^{N} words"
        );
        Self {
            address: Signal::default(),
            clock: Signal::default(),
            data: Signal::new_with_default(D::default()),
            _contents: Box::new(contents),
        }
    }
}

impl<D: Synth, const N: usize> Logic for Prom<D, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            self.data.next = *self
                ._contents
                .get(&self.address.val())
                .unwrap_or(&D::default());
        }
    }
    fn connect(&mut self) {
        self.data.connect();
    }
    fn hdl(&self) -> Verilog {
        let init = self
            ._contents
            .iter()
            .map(|(a, w)| format!("mem[{}] = {};", a.verilog(), w.verilog()))
            .collect::<Vec<_>>()
            .join("\n");
        Verilog::Custom(format!(
            "reg[{d}:0] mem [0:{last}];\n\ninitial begin\n{init}\ndata = 0;\nend\n\n\
             always @(posedge clock) begin\n   data <= mem[address];\nend",
            d = D::BITS - 1,
            last = (1usize << N) - 1,
        ))
    }
}

/// A small RAM with synchronous write and asynchronous read (FPGA distributed RAM: ECP5
/// TRELLIS_DPR16X4 slices, Xilinx LUTRAM): `mem[write_address] ← write_data` on the rising
/// edge when `write_enable`; `read_data` = `mem[read_address]` at once (also the word written
/// at the last edge). 2^N words, 0 in the rust-hdl simulation before their first write; the
/// Verilog leaves them uninitialised, so a reader must not use a word before it is written
/// (the FIFO in `pixel_stream` gates its output with its `valid`).
#[derive(LogicBlock)]
pub struct Lutram<D: Synth, const N: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Signal<In, Bit>,
    pub write_address: Signal<In, Bits<N>>,
    pub write_data: Signal<In, D>,
    pub read_address: Signal<In, Bits<N>>,
    pub read_data: Signal<Out, D>,
    #[allow(clippy::box_collection)]
    _mem: Box<Vec<D>>,
}

impl<D: Synth, const N: usize> Default for Lutram<D, N> {
    fn default() -> Self {
        assert!(N <= 8, "a distributed RAM of 2^{N} words is too deep");
        Self {
            clock: Signal::default(),
            write_enable: Signal::default(),
            write_address: Signal::default(),
            write_data: Signal::default(),
            read_address: Signal::default(),
            read_data: Signal::new_with_default(D::default()),
            _mem: Box::new(vec![D::default(); 1 << N]),
        }
    }
}

impl<D: Synth, const N: usize> Logic for Lutram<D, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.write_enable.val() {
            let a = self.write_address.val().index();
            self._mem[a] = self.write_data.val();
        }
        self.read_data.next = self._mem[self.read_address.val().index()];
    }
    fn connect(&mut self) {
        self.read_data.connect();
    }
    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "reg [{d}:0] mem [0:{last}];\n\n\
             always @(posedge clock) begin\n   if (write_enable) mem[write_address] <= write_data;\nend\n\n\
             always @(*) read_data = mem[read_address];",
            d = D::BITS - 1,
            last = (1usize << N) - 1,
        ))
    }
}

crate::hw_block! {
    /// Signed Q3.29 → signed Q2.14, for a word that already carries the half output LSB (2¹⁴):
    /// `narrow` = bits 30..15 of `wide` when bits 31 and 30 agree (the value fits [−2, 2)),
    /// else the bound on `wide`'s side: 0x8000 (−2) or 0x7FFF (2 − 2⁻¹⁴). Combinational.
    pub struct SatToQ2_14 {
        in { wide: Bits<32> }
        out { narrow: Bits<16> }
        q2_14_min: Constant<Bits<16>> = Constant::new(0x8000.into()),
        q2_14_max: Constant<Bits<16>> = Constant::new(0x7FFF.into()),
    }
}

impl Logic for SatToQ2_14 {
    #[hdl_gen]
    fn update(&mut self) {
        if self.wide.val().get_bit(31) == self.wide.val().get_bit(30) {
            self.narrow.next = self.wide.val().get_bits::<16>(15);
        } else if self.wide.val().get_bit(31) {
            self.narrow.next = self.q2_14_min.val();
        } else {
            self.narrow.next = self.q2_14_max.val();
        }
    }
}

crate::hw_block! {
    /// Unsigned Q4.28 → unsigned Q1.15, rounded to nearest (ties toward +∞) and saturated:
    /// bits 28..13 of `wide + 2¹²`, or 0xFFFF (2 − 2⁻¹⁵) when `wide` ≥ 2 − 2⁻¹⁶ (it would
    /// round to 2.0). That test is `wide` ≥ 2 (bits 31..29) or bits 28..12 all ones — bit tests
    /// instead of a 32-bit comparator, which would sit on the normalizer's critical path.
    /// Combinational.
    pub struct RoundToUQ1_15 {
        in { wide: Bits<32> }
        out { narrow: Bits<16> }
        half_lsb: Constant<Bits<32>> = Constant::new((1u64 << 12).into()),
        uq1_15_max: Constant<Bits<16>> = Constant::new(0xFFFF.into()),
        rounded: Signal<Local, Bits<32>>,
    }
}

impl Logic for RoundToUQ1_15 {
    #[hdl_gen]
    fn update(&mut self) {
        self.rounded.next = self.wide.val() + self.half_lsb.val();
        if self.wide.val().get_bits::<3>(29).any() | self.wide.val().get_bits::<17>(12).all() {
            self.narrow.next = self.uq1_15_max.val();
        } else {
            self.narrow.next = self.rounded.val().get_bits::<16>(13);
        }
    }
}

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

crate::hw_block! {
    /// Unsigned Q2.30 → unsigned Q1.15, rounded to nearest (ties toward +∞) and saturated:
    /// `rounded = wide + 2¹⁴` (cannot wrap: a 16×16 product is ≤ (2¹⁶ − 1)²), then bits
    /// 30..15, or 0xFFFF (2 − 2⁻¹⁵) when bit 31 of `rounded` is set (the value rounds to ≥ 2).
    /// For products of two UQ1.15 words. Combinational.
    pub struct RoundProductToUQ1_15 {
        in { wide: Bits<32> }
        out { narrow: Bits<16> }
        half_lsb: Constant<Bits<32>> = Constant::new((1u64 << 14).into()),
        uq1_15_max: Constant<Bits<16>> = Constant::new(0xFFFF.into()),
        rounded: Signal<Local, Bits<32>>,
    }
}

impl Logic for RoundProductToUQ1_15 {
    #[hdl_gen]
    fn update(&mut self) {
        self.rounded.next = self.wide.val() + self.half_lsb.val();
        if self.rounded.val().get_bit(31) {
            self.narrow.next = self.uq1_15_max.val();
        } else {
            self.narrow.next = self.rounded.val().get_bits::<16>(15);
        }
    }
}

crate::hw_block! {
    /// Signed Q3.29 → signed Q2.17 (19 bits), for a word that already carries the half output
    /// LSB (2¹¹): `narrow` = bits 30..12 of `wide` when bits 31 and 30 agree (the value fits
    /// [−2, 2)), else the bound on `wide`'s side: 0x40000 (−2) or 0x3FFFF (2 − 2⁻¹⁷).
    /// Combinational.
    pub struct SatToQ2_17 {
        in { wide: Bits<32> }
        out { narrow: Bits<19> }
        q2_17_min: Constant<Bits<19>> = Constant::new(0x40000.into()),
        q2_17_max: Constant<Bits<19>> = Constant::new(0x3FFFF.into()),
    }
}

impl Logic for SatToQ2_17 {
    #[hdl_gen]
    fn update(&mut self) {
        if self.wide.val().get_bit(31) == self.wide.val().get_bit(30) {
            self.narrow.next = self.wide.val().get_bits::<19>(12);
        } else if self.wide.val().get_bit(31) {
            self.narrow.next = self.q2_17_min.val();
        } else {
            self.narrow.next = self.q2_17_max.val();
        }
    }
}

crate::hw_block! {
    /// Signed Q3.29 → signed Q2.17 (19 bits), rounded to nearest (ties toward +∞) and
    /// saturated: `rounded = wide + 2¹¹` (32-bit; wraps only for `wide` ≥ 2³¹ − 2¹¹, i.e. a
    /// value within 2⁻¹⁸ of 4, which the vector interpolator's plane values of unit normals
    /// never reach), then [`SatToQ2_17`]. Combinational.
    pub struct RoundToQ2_17 {
        in { wide: Bits<32> }
        out { narrow: Bits<19> }
        half_lsb: Constant<Bits<32>> = Constant::new((1u64 << 11).into()),
        rounded: Signal<Local, Bits<32>>,
        sat: SatToQ2_17,
    }
}

impl Logic for RoundToQ2_17 {
    #[hdl_gen]
    fn update(&mut self) {
        self.rounded.next = self.wide.val() + self.half_lsb.val();
        self.sat.wide.next = self.rounded.val();
        self.narrow.next = self.sat.narrow.val();
    }
}

crate::hw_block! {
    /// Signed Q4.28 → unsigned Q1.18 (19 bits), for a word that already carries the half output
    /// LSB (2⁹): negative → 0; ≥ 2 (bit 30 or 29 set) → 0x7FFFF (2 − 2⁻¹⁸); else bits 28..10.
    /// Combinational.
    pub struct SatToUQ1_18 {
        in { wide: Bits<32> }
        out { narrow: Bits<19> }
        uq1_18_max: Constant<Bits<19>> = Constant::new(0x7FFFF.into()),
    }
}

impl Logic for SatToUQ1_18 {
    #[hdl_gen]
    fn update(&mut self) {
        if self.wide.val().get_bit(31) {
            self.narrow.next = 0.into();
        } else if self.wide.val().get_bit(30) | self.wide.val().get_bit(29) {
            self.narrow.next = self.uq1_18_max.val();
        } else {
            self.narrow.next = self.wide.val().get_bits::<19>(10);
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::{QFormat, K_FULL, K_NARROW, NORMAL, NORMALIZED, NORM_SCALE, PRODUCT, SCALE};

    /// Settle a block's combinational logic after its inputs changed.
    fn settle<B: Block>(uut: &mut B) {
        for _ in 0..100 {
            uut.update_all();
            if !uut.has_changed() {
                return;
            }
        }
        panic!("did not settle");
    }

    /// Words covering every bit pattern class: a stride over the range plus the edges.
    fn words32() -> Vec<u32> {
        let mut w: Vec<u32> = (0..=u32::MAX).step_by(65_521).collect();
        for e in [
            0u32,
            1,
            0x7FFF_FFFF,
            0x8000_0000,
            0xFFFF_FFFF,
            0x3FFF_BFFF,
            0x3FFF_C000,
        ] {
            for d in 0..4u32 {
                w.push(e.wrapping_add(d));
                w.push(e.wrapping_sub(d));
            }
        }
        for k in 0..32 {
            w.push(1 << k);
            w.push((1u32 << k).wrapping_sub(1));
            w.push(!(1u32 << k));
        }
        w
    }

    /// f64 rounding of a raw word of `from` into `to` (ties toward +∞, saturated).
    fn reference(from: QFormat, to: QFormat, w: u32) -> u64 {
        to.quantize(from.to_f64(w as u64))
    }

    #[test]
    fn narrowings_match_the_fixed_rules() {
        let mut sat_s = SatToQ2_14::default();
        let mut round_17 = RoundToQ2_17::default();
        round_17.connect_all();
        let mut sat_u = SatToUQ1_18::default();
        let mut sat_17 = SatToQ2_17::default();
        sat_17.connect_all();
        let mut round_u = RoundToUQ1_15::default();
        let mut round_p = RoundProductToUQ1_15::default();
        round_p.connect_all();
        sat_s.connect_all();
        sat_u.connect_all();
        round_u.connect_all();
        // Signed Q4.28 (f's wide format).
        let f_wide = QFormat::signed(4, 28);
        for w in words32() {
            // The Sat… forms see the word with the half LSB already added.
            sat_s.wide.next = (w.wrapping_add(1 << 14) as u64).into();
            settle(&mut sat_s);
            if !(0x7FFF_C000..=0x7FFF_FFFF).contains(&w) {
                assert_eq!(
                    sat_s.narrow.val().to_u64(),
                    reference(PRODUCT, NORMAL, w),
                    "SatToQ2_14 {w:#x}"
                );
            }
            round_17.wide.next = (w as u64).into();
            settle(&mut round_17);
            if !(0x7FFF_F800..=0x7FFF_FFFF).contains(&w) {
                assert_eq!(
                    round_17.narrow.val().to_u64(),
                    reference(PRODUCT, NORMALIZED, w),
                    "RoundToQ2_17 {w:#x}"
                );
            }
            if (w as i32) < i32::MAX - (1 << 9) {
                sat_u.wide.next = (w.wrapping_add(1 << 9) as u64).into();
                settle(&mut sat_u);
                assert_eq!(
                    sat_u.narrow.val().to_u64(),
                    reference(f_wide, NORM_SCALE, w),
                    "SatToUQ1_18 {w:#x}"
                );
            }
            if (w as i32) < i32::MAX - (1 << 11) {
                sat_17.wide.next = (w.wrapping_add(1 << 11) as u64).into();
                settle(&mut sat_17);
                assert_eq!(
                    sat_17.narrow.val().to_u64(),
                    reference(PRODUCT, NORMALIZED, w),
                    "SatToQ2_17 {w:#x}"
                );
            }
            round_p.wide.next = (w as u64).into();
            settle(&mut round_p);
            if w <= 0xFFFE_0001 {
                assert_eq!(
                    round_p.narrow.val().to_u64(),
                    reference(QFormat::unsigned(2, 30), SCALE, w),
                    "RoundProductToUQ1_15 {w:#x}"
                );
            }
            round_u.wide.next = (w as u64).into();
            settle(&mut round_u);
            assert_eq!(
                round_u.narrow.val().to_u64(),
                reference(K_FULL, K_NARROW, w),
                "RoundToUQ1_15 {w:#x}"
            );
        }
    }

    #[test]
    fn multiplies_are_exact() {
        let mut mul = MulSignedUnsigned::default();
        mul.connect_all();
        let edges = [
            0u32, 1, 2, 0x3FFF, 0x4000, 0x7FFE, 0x7FFF, 0x8000, 0x8001, 0xC000, 0xFFFF,
        ];
        let mut words: Vec<u32> = (0..=0xFFFF).step_by(251).collect();
        words.extend(edges);
        for &a in &words {
            let sa = NORMAL.to_int(a as u64);
            for &b in &words {
                mul.a.next = (a as u64).into();
                mul.b.next = (b as u64).into();
                settle(&mut mul);
                assert_eq!(
                    mul.p.val().to_u64(),
                    PRODUCT.from_int(sa * b as i64),
                    "{a:#x}·{b:#x}"
                );
            }
        }
    }

    /// The shift-add of a 3-bit factor: v·m (exact, as a 32-bit word) of the words presented
    /// `MUL_LOW_LATENCY` clocks earlier, for every m and signed and unsigned 16-bit v, and
    /// 20-bit v at the ends of their range (|v| ≤ 2²⁰, the widest a caller gives).
    #[test]
    fn low_part_shift_add_is_exact_after_its_latency() {
        let mut low = MulLow3Pipe::default();
        low.connect_all();
        // Every 16-bit word as a signed and as an unsigned value, in the 20-bit input.
        let mut values: Vec<i64> = vec![0, 1, -1, 0x7FFF, -0x8000, 0xFFFF, 0x8000, 0x1234];
        values.extend((0..600i64).map(|i| ((i * 40503) & 0xFFFF) - (i % 2) * 0x8000));
        values.extend([
            1 << 20,
            -(1 << 20),
            (1 << 20) - 1,
            -(1 << 19),
            (1 << 19) - 1,
            0xA_BCDE,
        ]);
        values.extend((0..300i64).map(|i| ((i * 2_654_435) & 0xF_FFFF) - (i % 2) * 0x8_0000));
        let pairs: Vec<(i64, i64)> = values
            .iter()
            .flat_map(|&v| (0..8i64).map(move |m| (v, m)))
            .collect();
        for c in 0..pairs.len() + MUL_LOW_LATENCY {
            let (v, m) = pairs.get(c).copied().unwrap_or((0, 0));
            low.v.next = ((v as u64) & 0xFF_FFFF).into();
            low.m.next = (m as u64).into();
            low.clock.next = Clock { clk: false };
            settle(&mut low);
            if c >= MUL_LOW_LATENCY {
                let (v, m) = pairs[c - MUL_LOW_LATENCY];
                assert_eq!(
                    low.p.val().to_u64(),
                    ((v * m) as u64) & 0xFFFF_FFFF,
                    "{v}·{m}"
                );
            }
            low.clock.next = Clock { clk: true };
            settle(&mut low);
        }
    }

    /// The pipelined multiplies: the product of the words presented `SIGNED_MUL_LATENCY`
    /// (`MUL_LATENCY` unsigned) clocks earlier, exact, one per clock.
    #[test]
    fn pipelined_multiplies_are_exact_after_their_latency() {
        let mut m = MulSignedPipe::default();
        let mut sq = MulSignedPipe::default();
        let mut su = MulSignedUnsignedPipe::default();
        let mut mu = MulPipe::default();
        let mut md = MulPipeDeep::default();
        md.connect_all();
        m.connect_all();
        sq.connect_all();
        su.connect_all();
        mu.connect_all();
        let edges = [
            0u64, 1, 0x3FFF, 0x4000, 0x7FFF, 0x8000, 0x8001, 0xC000, 0xFFFF,
        ];
        let mut pairs: Vec<(u64, u64)> = edges
            .iter()
            .flat_map(|&a| edges.iter().map(move |&b| (a, b)))
            .collect();
        pairs.extend((0..3000u64).map(|i| ((i * 40503) & 0xFFFF, (i * 9973 + 7) & 0xFFFF)));
        let mut sent: Vec<(u64, u64)> = vec![];
        for c in 0..pairs.len() + MUL_DEEP_LATENCY {
            let (a, b) = pairs.get(c).copied().unwrap_or((0, 0));
            m.a.next = a.into();
            m.b.next = b.into();
            sq.a.next = a.into();
            sq.b.next = a.into();
            su.a.next = a.into();
            su.b.next = b.into();
            mu.a.next = a.into();
            mu.b.next = b.into();
            md.a.next = a.into();
            md.b.next = b.into();
            md.clock.next = Clock { clk: false };
            settle(&mut md);
            m.clock.next = Clock { clk: false };
            sq.clock.next = Clock { clk: false };
            su.clock.next = Clock { clk: false };
            mu.clock.next = Clock { clk: false };
            settle(&mut m);
            settle(&mut sq);
            settle(&mut su);
            settle(&mut mu);
            if c >= SIGNED_MUL_LATENCY {
                let (a, b) = sent[c - SIGNED_MUL_LATENCY];
                let want = PRODUCT.from_int(NORMAL.to_int(a) * NORMAL.to_int(b));
                assert_eq!(m.p.val().to_u64(), want, "{a:#x}·{b:#x}");
                let want = (NORMAL.to_int(a) * NORMAL.to_int(a)) as u64;
                assert_eq!(sq.p.val().to_u64(), want, "{a:#x}²");
                let want = PRODUCT.from_int(NORMAL.to_int(a) * b as i64);
                assert_eq!(su.p.val().to_u64(), want, "{a:#x}·{b:#x} unsigned b");
            }
            if c >= MUL_LATENCY {
                let (a, b) = sent[c - MUL_LATENCY];
                assert_eq!(mu.p.val().to_u64(), a * b, "unsigned {a:#x}·{b:#x}");
            }
            if c >= MUL_DEEP_LATENCY {
                let (a, b) = sent[c - MUL_DEEP_LATENCY];
                assert_eq!(md.p.val().to_u64(), a * b, "deep {a:#x}·{b:#x}");
            }
            sent.push((a, b));
            m.clock.next = Clock { clk: true };
            sq.clock.next = Clock { clk: true };
            su.clock.next = Clock { clk: true };
            mu.clock.next = Clock { clk: true };
            md.clock.next = Clock { clk: true };
            settle(&mut md);
            settle(&mut m);
            settle(&mut sq);
            settle(&mut su);
            settle(&mut mu);
        }
    }

    #[test]
    fn delay_line_delays_by_n() {
        let mut line = Delay::<Bits<16>, 3>::default();
        line.connect_all();
        let mut seen = vec![];
        for c in 0..10u32 {
            line.clock.next = Clock { clk: false };
            line.d.next = (c as u64 + 100).into();
            settle(&mut line);
            seen.push(line.q.val().to_u64());
            line.clock.next = Clock { clk: true };
            settle(&mut line);
        }
        assert_eq!(seen, [0, 0, 0, 100, 101, 102, 103, 104, 105, 106]);
    }

    #[test]
    fn primitives_export_valid_verilog() {
        let v = crate::export::raw_verilog(Delay::<Bit, 2>::default()).unwrap();
        assert!(v.contains("stage$1$q"), "{v}");
        assert!(crate::export::raw_verilog(RoundToQ2_17::default()).is_ok());
        assert!(crate::export::raw_verilog(MulSignedUnsigned::default()).is_ok());
    }
}

crate::hw_block! {
    /// Signed 32 × unsigned 16, rounded: `r = (x·p + 2¹⁴) >> 15` (arithmetic; ties up), from two
    /// 16×16 products (two DSP slices: the low half unsigned, the high half signed × unsigned)
    /// summed in 48 bits — exact, since |x·p| < 2⁴⁷. Formats: `x` signed Qm.n (32 bits), `p`
    /// unsigned Q1.15 → `r` signed Q(m+1).n (33 bits). Combinational.
    pub struct MulS32U16Round {
        in { x: Bits<32>, p: Bits<16> }
        out { r: Bits<33> }
        hi_mul: MulSignedUnsigned,
        lo: Signal<Local, Bits<32>>,
        hi48: Signal<Local, Bits<48>>,
        prod: Signal<Local, Bits<48>>,
        sign_ext: Constant<Bits<48>> = Constant::new(0xFFFF_0000_0000u64.into()),
        half: Constant<Bits<48>> = Constant::new((1u64 << 14).into()),
    }
}

impl Logic for MulS32U16Round {
    #[hdl_gen]
    fn update(&mut self) {
        self.lo.next = self.x.val().get_bits::<16>(0) * self.p.val();
        self.hi_mul.a.next = self.x.val().get_bits::<16>(16);
        self.hi_mul.b.next = self.p.val();
        if self.hi_mul.p.val().get_bit(31) {
            self.hi48.next = bit_cast::<48, 32>(self.hi_mul.p.val()) | self.sign_ext.val();
        } else {
            self.hi48.next = bit_cast::<48, 32>(self.hi_mul.p.val());
        }
        self.prod.next =
            (self.hi48.val() << 16) + bit_cast::<48, 32>(self.lo.val()) + self.half.val();
        self.r.next = self.prod.val().get_bits::<33>(15);
    }
}
