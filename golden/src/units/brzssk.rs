//! BRZSSK, the perturbed-specular block (SPEC §2, patent 60139), the golden of
//! `rtl/src/units/brzssk.rs`: cos(γ ± dγ) = cos γ·cos dγ ∓ sin γ·sin dγ and the diffuse cos(φ ± dγ)
//! the same way, from PROM words only (`crate::shading::bump`: sin from cos, cos dγ and sin dγ from the
//! perturbation code, the code from the procedural map at the pixel address modulo 16).
//! Input and output cosines unsigned Q1.15, clamped at 0.

use crate::shading::bump::{self, BumpMap, Code, SinProm};

/// Largest cosine the output holds (2 − 2⁻¹⁵).
pub const COS_MAX: f64 = 2.0 - 1.0 / 32768.0;

/// The f64 block: (cos(φ ± dγ), cos(γ ± dγ)) at pixel (x, y), each clamped to [0, COS_MAX].
pub fn brzssk(cos_phi: f64, cos_gamma: f64, x: i32, y: i32) -> (f64, f64) {
    let map = BumpMap::default();
    let (phi, gamma) = bump::default_proms();
    let code = map.code(x & 15, y & 15);
    let clamp = |v: f64| v.clamp(0.0, COS_MAX);
    (
        clamp(bump::perturb(cos_phi, code, &map, &phi)),
        clamp(bump::perturb(cos_gamma, code, &map, &gamma)),
    )
}

/// The code ROM: 256 words `negative << 8 | magnitude`, addressed by `(y mod 16) << 4 | x mod 16`.
pub fn code_rom() -> Vec<u64> {
    let map = BumpMap::default();
    (0..256)
        .map(|i| {
            let c = map.code(i & 15, i >> 4);
            ((c.negative as u64) << 8) | c.magnitude as u64
        })
        .collect()
}

/// The dγ PROM: 256 words `cos dγ << 16 | sin |dγ|` (Q1.15 each), addressed by the magnitude.
pub fn dgamma_rom() -> Vec<u64> {
    let map = BumpMap::default();
    (0..256u32)
        .map(|m| {
            let (c, s) = map.prom(Code {
                negative: false,
                magnitude: m,
            });
            (((c * 32768.0) as u64) << 16) | (s * 32768.0) as u64
        })
        .collect()
}

/// A sin PROM of `addr_bits` fraction bits: 2^addr_bits + 1 Q1.15 words.
pub fn sin_rom(addr_bits: u32) -> Vec<u64> {
    let p = SinProm {
        addr_bits,
        interp_bits: 0,
    };
    (0..=(1i64 << addr_bits))
        .map(|a| (p.word(a) * 32768.0) as u64)
        .collect()
}

/// Bits of the interpolated PROM's difference field (the largest step, at cos γ = 1, is
/// 1024 LSB for 11 address bits).
pub const SIN_DELTA_BITS: u32 = 11;

/// The interpolated sin PROM: 2^addr_bits words `s[a] << 11 | (s[a] − s[a+1])`.
pub fn sin_rom_interp(addr_bits: u32) -> Vec<u64> {
    let s = sin_rom(addr_bits);
    (0..1usize << addr_bits)
        .map(|a| {
            let d = s[a] - s[a + 1];
            assert!(
                d < 1 << SIN_DELTA_BITS,
                "PROM step {d} exceeds the difference field"
            );
            (s[a] << SIN_DELTA_BITS) | d
        })
        .collect()
}

/// The PROM address of a Q1.15 cosine word: round to `addr_bits` fraction bits, clamp at 1.
pub fn sin_address(w: u64, addr_bits: u32) -> u64 {
    let shift = 15 - addr_bits;
    let half = 1u64 << (shift - 1);
    if w >= 0x8000 - half {
        1 << addr_bits
    } else {
        (w + half) >> shift
    }
}

/// Bit-exact integer twin of `rtl/src/units/brzssk.rs`, from its header:
///
/// ```text
/// B1  sφ = SINφ[addr(cos φ)], sγ = SINγ-interpolated(cos γ), code = CODE[y₄ x₄]
/// B2  (cd, sd) = DG[code.magnitude], TG = code.sign                        (PROM read)
/// B3  the same words one register on (the RTL interpolates sγ here: a pure function of
///     the B1 words, so the twin does it at B1)
/// B4  pφ = cos φ·cd, qφ = sφ·sd, pγ = cos γ·cd, qγ = sγ·sd     (UQ2.30, exact; two clocks)
/// B5  sum = TG ? p + q : max(p − q, 0)
/// B6  out = rnd(sum)                                  rnd: + 2¹⁴, drop 15, saturate 0xFFFF
/// ```
/// With `enable` false the cosines pass through the same seven registers unchanged.
pub mod twin {
    use super::{code_rom, dgamma_rom, sin_address, sin_rom, sin_rom_interp, SIN_DELTA_BITS};
    use crate::shading::bump::{SIN_ADDR_BITS, SIN_INTERP_BITS, SIN_PHI_ADDR_BITS};

    fn rnd(p: u64) -> u64 {
        ((p + (1 << 14)) >> 15).min(0xFFFF)
    }

    #[derive(Clone, Debug, Default)]
    struct Regs {
        valid: [bool; 7],
        /// (cos φ, cos γ) at B1 .. B6.
        cos: [[u64; 2]; 6],
        sin: [u64; 2],
        code: u64,
        sin2: [u64; 2],
        dg: u64,
        tg: bool,
        sin3: [u64; 2],
        dg3: u64,
        tg3: bool,
        /// B4's first register (the products one clock early), then B4's.
        prod_a: [u64; 4],
        tg4_a: bool,
        prod: [u64; 4],
        tg4: bool,
        sum: [u64; 2],
        out: [u64; 2],
    }

    #[derive(Clone, Debug)]
    pub struct BrzsskTwin {
        enable: bool,
        sin_phi: Vec<u64>,
        sin_gamma: Vec<u64>,
        code: Vec<u64>,
        dg: Vec<u64>,
        r: Regs,
    }

    impl BrzsskTwin {
        pub fn new(enable: bool) -> Self {
            BrzsskTwin {
                enable,
                sin_phi: sin_rom(SIN_PHI_ADDR_BITS),
                sin_gamma: sin_rom_interp(SIN_ADDR_BITS),
                code: code_rom(),
                dg: dgamma_rom(),
                r: Regs::default(),
            }
        }
        /// The interpolated sin γ of a Q1.15 cosine word (0 from cos γ = 1 on).
        pub fn sin_gamma_word(&self, w: u64) -> u64 {
            self.sin_gamma_interp(w)
        }
        fn sin_gamma_interp(&self, w: u64) -> u64 {
            if w >= 0x8000 {
                return 0;
            }
            let f = SIN_INTERP_BITS;
            let word = self.sin_gamma[(w >> f) as usize];
            let (s, d) = (word >> SIN_DELTA_BITS, word & ((1 << SIN_DELTA_BITS) - 1));
            s - ((d * (w & ((1 << f) - 1)) + (1 << (f - 1))) >> f)
        }
        /// (valid_out, cos φ', cos γ') shown this clock.
        pub fn outputs(&self) -> (bool, u64, u64) {
            (self.r.valid[6], self.r.out[0], self.r.out[1])
        }
        /// One rising edge.
        pub fn clock(&mut self, valid_in: bool, cos_phi: u64, cos_gamma: u64, x: u64, y: u64) {
            let s = self.r.clone();
            let sin_b1 = [
                self.sin_phi[sin_address(cos_phi, SIN_PHI_ADDR_BITS) as usize],
                self.sin_gamma_interp(cos_gamma),
            ];
            let code = self.code[(((y & 15) << 4) | (x & 15)) as usize];
            let dg = self.dg[(s.code & 0xFF) as usize];
            let n = &mut self.r;
            // B6
            n.out = if self.enable {
                s.sum.map(rnd)
            } else {
                s.cos[5]
            };
            // B5
            n.sum = std::array::from_fn(|k| {
                let (p, q) = (s.prod[2 * k], s.prod[2 * k + 1]);
                if s.tg4 {
                    p + q
                } else {
                    p.saturating_sub(q)
                }
            });
            // B4 (two clocks)
            n.prod = s.prod_a;
            n.tg4 = s.tg4_a;
            let (cd, sd) = (s.dg3 >> 16, s.dg3 & 0xFFFF);
            n.prod_a = [
                s.cos[2][0] * cd,
                s.sin3[0] * sd,
                s.cos[2][1] * cd,
                s.sin3[1] * sd,
            ];
            n.tg4_a = s.tg3;
            // B3
            n.sin3 = s.sin2;
            n.dg3 = s.dg;
            n.tg3 = s.tg;
            // B2
            n.dg = dg;
            n.tg = s.code >> 8 != 0;
            n.sin2 = s.sin;
            // B1
            n.sin = sin_b1;
            n.code = code;
            n.cos = [
                [cos_phi, cos_gamma],
                s.cos[0],
                s.cos[1],
                s.cos[2],
                s.cos[3],
                s.cos[4],
            ];
            n.valid = [
                valid_in, s.valid[0], s.valid[1], s.valid[2], s.valid[3], s.valid[4], s.valid[5],
            ];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_and_addresses() {
        assert_eq!(sin_address(0x8000, 12), 4096);
        assert_eq!(sin_address(0x7FFC, 12), 4096);
        assert_eq!(sin_address(0x7FFB, 12), 4095);
        assert_eq!(sin_address(0xFFFF, 10), 1024);
        assert_eq!(sin_address(15, 10), 0);
        assert_eq!(sin_address(16, 10), 1);
        let s = sin_rom(12);
        assert_eq!((s.len(), s[0], s[4096]), (4097, 0x8000, 0));
        let d = dgamma_rom();
        assert_eq!(d[0], 0x8000 << 16, "dγ = 0: cos 1, sin 0");
        assert!(code_rom().iter().all(|&c| c < 512));
    }

    /// Every cosine word: the twin's interpolated PROM read equals the f64 SinProm's.
    #[test]
    fn interpolated_prom_matches_the_golden_sin() {
        let (_, gamma) = bump::default_proms();
        let t = twin::BrzsskTwin::new(true);
        for w in 0..=0xFFFFu64 {
            let want = gamma.sin(w as f64 / 32768.0);
            assert_eq!(t.sin_gamma_word(w) as f64 / 32768.0, want, "word {w:#x}");
        }
        // Monotone and continuous across the PROM's steps: no jump larger than the largest
        // slope allows (the last interval: 1024 LSB over 16 words).
        let mut prev = t.sin_gamma_word(0);
        for w in 1..0x8000u64 {
            let s = t.sin_gamma_word(w);
            assert!(s <= prev && prev - s <= 64, "word {w:#x}: {prev} → {s}");
            prev = s;
        }
    }
}
