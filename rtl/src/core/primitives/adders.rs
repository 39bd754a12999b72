//! Adder primitives: a three-operand sum through one carry-save level and one carry chain.
//!
//! [`Add3`]: formula sum = a + b + c + cin mod 2^48 (no SPEC section: arithmetic for the
//! recurrences of SPEC §14 and §16). Ports: `a`, `b`, `c` 48-bit words (any two's complement
//! or unsigned reading), `cin` 1 bit, `sum` 48 bits. Latency 0 (combinational), throughput one
//! sum per clock, no handshake. Overflow: wraps modulo 2^48, exactly as the chained adds it
//! replaces. Error budget: exact.

use rust_hdl::prelude::*;

crate::hw_block! {
    /// a + b + c (+1 with `cin`) modulo 2^48 through one carry-save stage and one adder: a
    /// three-operand sum in a recurrence costs one carry chain (the texture-coordinate block's
    /// pixel loop, the Bézier unit's candidates).
    pub struct Add3 {
        in { a: Bits<48>, b: Bits<48>, c: Bits<48>, cin: Bit }
        out { sum: Bits<48> }
        /// The carry-save pair: bitwise sum and majority carries (shifted up, `cin` in bit 0).
        half: Signal<Local, Bits<48>>, carries: Signal<Local, Bits<48>>,
    }
}

impl Logic for Add3 {
    #[hdl_gen]
    fn update(&mut self) {
        self.half.next = self.a.val() ^ self.b.val() ^ self.c.val();
        self.carries.next = ((self.a.val() & self.b.val())
            | (self.a.val() & self.c.val())
            | (self.b.val() & self.c.val()))
            << 1;
        if self.cin.val() {
            self.carries.next = (((self.a.val() & self.b.val())
                | (self.a.val() & self.c.val())
                | (self.b.val() & self.c.val()))
                << 1)
                | 1;
        }
        self.sum.next = self.half.val() + self.carries.val();
    }
}
