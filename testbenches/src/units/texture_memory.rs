//! Bench of the texture memory (`rtl::units::texture_memory`) against the golden texture's
//! texel lookup (`golden::texture::Texture::texel`, GL_REPEAT) and the bit-exact twin
//! (`golden::units::texture_memory::MemoryTwin`).
//!
//! # Stimulus
//!
//! Seeded textures of random power-of-two sides and random texels:
//! - W·H up to 2^10 texels, written whole through the set-up port as the set-up software writes
//!   them (`load_words`);
//! - every eighth texture W·H = 2^16 (the whole address range, all four banks), 2048 random
//!   texels of it written (`write_address`, `texel_word`).
//!
//! A random read address beside every write (the memory reads every clock; `valid_in` low).
//! Then 300 reads of written texels at random repeats: any 16-bit (u, v) words ≡ (i, j), so
//! negative coordinates and wrapping on both sides; a seeded tenth of the clocks without a
//! read. The next texture overwrites the last. Edge rows: random words on every input, `log_w` and `log_h`
//! up to 15.
//!
//! # Tolerances (from the formats)
//!
//! Exact: the texel read is the golden texture's texel (u mod W, v mod H); `valid_out` exact.
//! Reads beside a write (the previous texture's texels, partly overwritten) are the twin's
//! alone.

use golden::texture::Texture;
use golden::units::texture_memory::{
    load_words, texel_word, write_address, MemoryInputs, MemoryTwin,
};
use rtl::core::registry::NoParams;
use rtl::units::texture_memory::TextureMemory;

use crate::harness::{Compare, Expected};
use crate::registry::{Bench, Stimulus, Twin};
use golden::testing::Rng;

/// One input row in port order: we, waddr, wdata, log_w, log_h, valid_in, u, v.
fn row(i: &MemoryInputs) -> Vec<u64> {
    [
        i.we as u32,
        i.waddr,
        i.wdata,
        i.log_w,
        i.log_h,
        i.valid as u32,
        i.u,
        i.v,
    ]
    .map(u64::from)
    .to_vec()
}

/// The 16-bit word of an integer texel coordinate, and back (sign-extended).
fn word(c: i64) -> u32 {
    (c as u32) & 0xFFFF
}
fn signed(w: u32) -> i64 {
    w as u16 as i16 as i64
}

const QUIET: [Expected; 4] = [
    Expected::Word(0),
    Expected::DontCare,
    Expected::DontCare,
    Expected::DontCare,
];

impl Bench for TextureMemory {
    const ITEMS: &'static str = "textures";
    const DEFAULT_ITEMS: usize = 8;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let mut rng = Rng::new(seed | 1);
        // Latency 4: the outputs of the first four clocks are the reset's.
        let (mut rows, mut expected) = (Vec::new(), vec![QUIET.to_vec(); 4]);
        for item in 0..n {
            // Every eighth texture fills the whole memory's address range (W·H = 2^16, all four
            // banks) but is written sparsely; the others are written whole.
            let sparse = item % 8 == 7;
            let bits = if sparse { 16 } else { 10 };
            let log_w = if sparse {
                6 + rng.below(5) as u32
            } else {
                rng.below(bits + 1) as u32
            };
            let log_h = if sparse {
                16 - log_w
            } else {
                rng.below(bits - log_w as i32 + 1) as u32
            };
            let (w, h) = (1u32 << log_w, 1u32 << log_h);
            let texel = |rng: &mut Rng| {
                let x = rng.next_u64();
                [x as u8, (x >> 8) as u8, (x >> 16) as u8]
            };
            // The texels written (i, j from the bottom), and the texture they make (unwritten
            // texels 0 there; only written ones are read back).
            let mut rgb = vec![[0u8; 3]; (w * h) as usize];
            let mut written: Vec<(u32, u32)> = Vec::new();
            let mut writes: Vec<(u32, u32)> = Vec::new();
            if sparse {
                for _ in 0..2048 {
                    let (i, j) = (rng.below(w as i32) as u32, rng.below(h as i32) as u32);
                    let c = texel(&mut rng);
                    rgb[((h - 1 - j) * w + i) as usize] = c;
                    written.push((i, j));
                    writes.push((write_address(log_w, i, j), texel_word(c)));
                }
            } else {
                for c in rgb.iter_mut() {
                    *c = texel(&mut rng);
                }
            }
            let t = Texture::new(w, h, rgb).expect("power-of-two sides up to 1024");
            if !sparse {
                writes = load_words(&t).expect("at most 2^16 texels");
                written = (0..h).flat_map(|j| (0..w).map(move |i| (i, j))).collect();
            }
            for (a, d) in writes {
                // The memory reads every clock: a random address beside the write, its texel
                // the previous texture's, partly overwritten (the twin's alone).
                rows.push(row(&MemoryInputs {
                    we: true,
                    waddr: a,
                    wdata: d,
                    log_w,
                    log_h,
                    valid: false,
                    u: rng.next_u64() as u32 & 0xFFFF,
                    v: rng.next_u64() as u32 & 0xFFFF,
                }));
                expected.push(QUIET.to_vec());
            }
            let mut reads = 0;
            while reads < 300 {
                if rng.below(10) == 0 {
                    rows.push(row(&MemoryInputs {
                        log_w,
                        log_h,
                        ..Default::default()
                    }));
                    expected.push(QUIET.to_vec());
                    continue;
                }
                // A written texel at any of its repeats (W and H divide 2^16, so every 16-bit
                // word ≡ i mod W is one).
                let (i, j) = written[rng.below(written.len() as i32) as usize];
                let u = i.wrapping_add(w.wrapping_mul(rng.next_u64() as u32)) & 0xFFFF;
                let v = j.wrapping_add(h.wrapping_mul(rng.next_u64() as u32)) & 0xFFFF;
                rows.push(row(&MemoryInputs {
                    log_w,
                    log_h,
                    valid: true,
                    u,
                    v,
                    ..Default::default()
                }));
                let texel = t.texel(signed(u), signed(v));
                let mut e = vec![Expected::Word(1)];
                e.extend(texel.map(|c| Expected::Word(c as u64)));
                expected.push(e);
                reads += 1;
            }
        }
        // The last read shows four clocks after it.
        for _ in 0..4 {
            rows.push(row(&MemoryInputs::default()));
        }
        expected.extend([QUIET.to_vec(), QUIET.to_vec(), QUIET.to_vec()]);
        expected.truncate(rows.len());
        Stimulus {
            rows,
            expected,
            compare: vec![Compare::Exact; 4],
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(MemoryRows(MemoryTwin::default()))
    }
    /// Random words on every input.
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let mut rng = Rng::new(seed ^ 0x7e4 | 1);
        (0..300)
            .map(|_| {
                let r = |bits: u32, rng: &mut Rng| (rng.next_u64() & ((1 << bits) - 1)) as u32;
                row(&MemoryInputs {
                    we: rng.below(2) == 0,
                    waddr: r(16, &mut rng),
                    wdata: r(24, &mut rng),
                    log_w: r(4, &mut rng),
                    log_h: r(4, &mut rng),
                    valid: rng.below(2) == 0,
                    u: word(rng.next_u64() as i64),
                    v: word(rng.next_u64() as i64),
                })
            })
            .collect()
    }
}

/// The twin on input rows.
struct MemoryRows(MemoryTwin);

impl Twin for MemoryRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (valid, rgb) = self.0.outputs();
        let w = |k: usize| r[k] as u32;
        self.0.clock(&MemoryInputs {
            we: r[0] & 1 != 0,
            waddr: w(1),
            wdata: w(2),
            log_w: w(3),
            log_h: w(4),
            valid: r[5] & 1 != 0,
            u: w(6),
            v: w(7),
        });
        let mut out = vec![valid as u64];
        out.extend(rgb.map(u64::from));
        out
    }
}
