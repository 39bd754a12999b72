//! Building blocks shared by the RTL blocks: a delay line, the fixed-point narrowings of
//! [`crate::core::fixed`] (round to nearest, saturate) and the signed multiplies built on rust-hdl's
//! unsigned 16×16→32 multiply.
//!
//! Not a block of its own (nothing here is exported alone). Each primitive states its formula,
//! the formats of its ports, its latency and its overflow behaviour:
//!
//! | primitive              | ports (in → out)         | formula / formats                                  | latency |
//! |------------------------|--------------------------|----------------------------------------------------|---------|
//! | [`Delay<T, N>`]        | `d` → `q`                | q = d delayed N clocks (N registers, reset 0)      | N       |
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
//! | [`Add3`]               | `a`, `b`, `c` (48), `cin` → `sum` (48) | a + b + c + cin mod 2⁴⁸: one carry-save level (bitwise sum, majority carries shifted up with `cin` in bit 0) and one adder | 0 |
//! | [`MulLow3Pipe`]        | `v` (24), `m` (3) → `p` (32) | v·m for a 3-bit unsigned m, by shift and add in 24 bits (no multiplier), sign-extended: the low part of a 19-bit operand split 16 + 3 | 2 |
//!
//! Rounding is to nearest with ties toward +∞ (add half an output LSB, then drop the LSBs), the
//! rule of [`crate::core::fixed`]. The `Sat…` narrowings take a word that already carries the half LSB
//! (folded into a constant the caller adds anyway); the `Round…` ones add it themselves. Error
//! of a narrowing: at most half an output LSB when it does not saturate. The multiplies are
//! exact (the true product fits 32 bits).
//!
//! Every intermediate is its own exactly sized signal: rust-hdl's simulator wraps each operation
//! at its operands' width, Verilog sizes an expression by its context, and only one-operation
//! assignments mean the same in both.

mod adders;
mod multipliers;
mod rounding;
mod storage;

pub use adders::*;
pub use multipliers::*;
pub use rounding::*;
pub use storage::*;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fixed::{
        QFormat, K_FULL, K_NARROW, NORMAL, NORMALIZED, NORM_SCALE, PRODUCT, SCALE,
    };
    use rust_hdl::prelude::*;

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
        let mut round_17 = RoundToQ2_17::default();
        round_17.connect_all();
        let mut sat_u = SatToUQ1_18::default();
        let mut sat_17 = SatToQ2_17::default();
        sat_17.connect_all();
        let mut round_u = RoundToUQ1_15::default();
        let mut round_p = RoundProductToUQ1_15::default();
        round_p.connect_all();
        sat_u.connect_all();
        round_u.connect_all();
        // Signed Q4.28 (f's wide format).
        let f_wide = QFormat::signed(4, 28);
        for w in words32() {
            round_17.wide.next = (w as u64).into();
            settle(&mut round_17);
            if !(0x7FFF_F800..=0x7FFF_FFFF).contains(&w) {
                assert_eq!(
                    round_17.narrow.val().to_u64(),
                    reference(PRODUCT, NORMALIZED, w),
                    "RoundToQ2_17 {w:#x}"
                );
            }
            // The Sat… forms see the word with the half LSB already added.
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
        let v = crate::core::export::raw_verilog(Delay::<Bit, 2>::default()).unwrap();
        assert!(v.contains("stage$1$q"), "{v}");
        assert!(crate::core::export::raw_verilog(RoundToQ2_17::default()).is_ok());
        assert!(crate::core::export::raw_verilog(MulSignedUnsigned::default()).is_ok());
    }
}
