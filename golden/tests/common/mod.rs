//! Stimulus shared by the golden crate's integration tests.

/// xorshift64*: seeded stimulus without a dependency (seed it with `seed_for(name) | 1`).
pub struct Rng(pub u64);

#[allow(dead_code)] // each test file uses its own part
impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in 0..n.
    pub fn below(&mut self, n: i32) -> i32 {
        (self.next() % n as u64) as i32
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }
}
