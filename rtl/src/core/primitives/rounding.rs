//! The fixed-point narrowings: round to nearest (ties up) and saturate, combinational.
//!
//! Formats and rules: the table in `primitives` (this folder's `mod.rs`). Latency 0: every
//! narrowing here is combinational, one word per clock; error at most half an output LSB when it
//! does not saturate.

use rust_hdl::prelude::*;

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
