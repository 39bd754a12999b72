//! Seeded stall patterns for back-pressure tests: a consumer's `tready` low, or an address
//! block's `hold` high, in random clocks and in long stretches.

/// SplitMix64: a small seeded generator (the patterns must be reproducible from the seed).
#[derive(Clone, Debug)]
pub struct SplitMix(u64);

impl SplitMix {
    pub fn new(seed: u64) -> Self {
        SplitMix(seed ^ 0x5DEE_CE66_D1CE_4E5B)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A stall pattern: `stalled(clock)` for clocks 0, 1, 2, … in order. Each clock is stalled
/// with probability `p`; with probability 1/400 a clock starts a long stretch of 40–300
/// stalled clocks.
pub struct StallPattern {
    /// A fixed pattern instead of the random one.
    fixed: Option<Box<dyn FnMut(usize) -> bool>>,
    rng: SplitMix,
    p: f64,
    stretch: u32,
    /// Stalled clocks so far.
    pub stalled: usize,
    /// Clocks asked so far.
    pub clocks: usize,
}

impl StallPattern {
    pub fn new(seed: u64, p: f64) -> Self {
        StallPattern {
            fixed: None,
            rng: SplitMix::new(seed),
            p,
            stretch: 0,
            stalled: 0,
            clocks: 0,
        }
    }

    /// The pattern `f(clock)`.
    pub fn from_fn(f: impl FnMut(usize) -> bool + 'static) -> Self {
        StallPattern {
            fixed: Some(Box::new(f)),
            ..Self::new(0, 0.0)
        }
    }

    /// Never stalls.
    pub fn never() -> Self {
        Self::new(0, 0.0)
    }

    /// Whether the next clock is stalled.
    pub fn next_stalled(&mut self) -> bool {
        self.clocks += 1;
        if let Some(f) = self.fixed.as_mut() {
            let s = f(self.clocks - 1);
            self.stalled += s as usize;
            return s;
        }
        if self.p <= 0.0 {
            return false;
        }
        let s = if self.stretch > 0 {
            self.stretch -= 1;
            true
        } else if self.rng.unit() < 1.0 / 400.0 {
            self.stretch = 40 + (self.rng.next_u64() % 261) as u32 - 1;
            true
        } else {
            self.rng.unit() < self.p
        };
        self.stalled += s as usize;
        s
    }
}
