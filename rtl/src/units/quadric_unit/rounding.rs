//! The quadric unit's output rounding, split across the word halves: the low part's carry
//! (`RoundLo`) and the high part with saturation to 8 bits (`RoundSat8Split`).
//!
//! Not exported alone. Formats: `RoundLo` takes bits 28..31 of a Q34.30 word and gives a 5-bit
//! sum; `RoundSat8Split` takes the high half (Q34.30 bits 32..63) and that registered sum and gives
//! an 8-bit level. Latency 0: both are combinational (the unit registers around them), one word
//! per clock; the error budget is the unit's (its header).

use rust_hdl::prelude::*;

crate::hw_block! {
    /// The rounding's low part: bits 28..31 of a Q34.30 word (`lo4`) + `half` (2: the
    /// rounding constant +2²⁹ in units of bit 28, a quarter of the output LSB, so that a
    /// quarter-LSB error in it is a change of the constant), 5 bits. Combinational; registered
    /// after it, so its carry (bit 4) enters the high half's add from a register.
    pub struct RoundLo {
        in { lo4: Bits<4> }
        out { lsum: Bits<5> }
        half: Constant<Bits<5>> = Constant::new(2u64.into()),
    }
}

impl Logic for RoundLo {
    #[hdl_gen]
    fn update(&mut self) {
        self.lsum.next = bit_cast::<5, 4>(self.lo4.val()) + self.half.val();
    }
}

crate::hw_block! {
    /// The rounding's high part: a Q34.30 word's bits 32..63 (`hi`) plus the carry of
    /// [`RoundLo`]'s sum (`lsum`, registered), dropping 30 bits and saturating to 0..=255.
    /// Combinational.
    pub struct RoundSat8Split {
        in { hi: Bits<32>, lsum: Bits<5> }
        out { q: Bits<8> }
        hsum: Signal<Local, Bits<32>>,
    }
}

impl Logic for RoundSat8Split {
    #[hdl_gen]
    fn update(&mut self) {
        self.hsum.next = self.hi.val() + bit_cast::<32, 1>(self.lsum.val().get_bits::<1>(4));
        if self.hsum.val().get_bit(31) {
            self.q.next = 0.into();
        } else if self.hsum.val().get_bits::<25>(6).any() {
            self.q.next = 255.into();
        } else {
            self.q.next = (bit_cast::<8, 6>(self.hsum.val().get_bits::<6>(0)) << 2)
                | bit_cast::<8, 2>(self.lsum.val().get_bits::<2>(2));
        }
    }
}
