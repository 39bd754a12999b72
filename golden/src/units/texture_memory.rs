//! Texture memory (the RTL block `texture-memory`), golden face: where the set-up writes a
//! texel ([`write_address`], [`texel_word`]) and the bit-exact twin of the block
//! ([`MemoryTwin`]), written from the block header's formats. The float face is
//! [`crate::texture::Texture::texel`]: the texel (u, v) of a W×H texture with GL_REPEAT.

use crate::texture::Texture;

/// Address bits of the memory: 2^16 texels.
pub const ADDRESS_BITS: u32 = 16;

/// The address the set-up writes texel (i, j) to (i from the left, j from the bottom row):
/// j·W + i with W = 2^log_w.
pub fn write_address(log_w: u32, i: u32, j: u32) -> u32 {
    (j << log_w) | i
}

/// An RGB texel as the 24-bit word (red in bits 23..16).
pub fn texel_word(rgb: [u8; 3]) -> u32 {
    (rgb[0] as u32) << 16 | (rgb[1] as u32) << 8 | rgb[2] as u32
}

/// Every write of `texture` into the memory: (address, word), row j = 0 (the bottom) first.
/// `None` when the texture does not fit (more than 2^16 texels).
pub fn load_words(texture: &Texture) -> Option<Vec<(u32, u32)>> {
    let (w, h) = (texture.width(), texture.height());
    if (w as u64) * (h as u64) > 1 << ADDRESS_BITS {
        return None;
    }
    let log_w = w.trailing_zeros();
    Some(
        (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| {
                (
                    write_address(log_w, i, j),
                    texel_word(texture.texel(i as i64, j as i64)),
                )
            })
            .collect(),
    )
}

/// The block's bit-exact twin: the memory, the output register.
#[derive(Clone, Debug)]
pub struct MemoryTwin {
    mem: Vec<u32>,
    address: u32,
    valid: [bool; 4],
    /// The RAM's read, the bank register, and the output register.
    read: u32,
    bank: u32,
    word: u32,
}

impl Default for MemoryTwin {
    fn default() -> Self {
        MemoryTwin {
            mem: vec![0; 1 << ADDRESS_BITS],
            address: 0,
            valid: [false; 4],
            read: 0,
            bank: 0,
            word: 0,
        }
    }
}

/// One clock's inputs of the block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MemoryInputs {
    pub we: bool,
    pub waddr: u32,
    pub wdata: u32,
    pub log_w: u32,
    pub log_h: u32,
    pub valid: bool,
    /// 16-bit two's-complement words.
    pub u: u32,
    pub v: u32,
}

impl MemoryTwin {
    /// (valid_out, [red, green, blue]) shown this clock.
    pub fn outputs(&self) -> (bool, [u32; 3]) {
        let w = self.word;
        (self.valid[3], [(w >> 16) & 0xFF, (w >> 8) & 0xFF, w & 0xFF])
    }

    /// The read address of (u, v): ((v & (H − 1)) << log_w | (u & (W − 1))) mod 2^16, the masks
    /// 2^log − 1 in 16 bits (a log of 16 or more gives the mask 2^16 − 1).
    pub fn address(i: &MemoryInputs) -> u32 {
        let m = 0xFFFFu32;
        let mask = |log: u32| ((1u64 << log.min(16)) as u32).wrapping_sub(1) & m;
        let row = (((i.v & mask(i.log_h)) as u64) << i.log_w) as u32 & m;
        (row | (i.u & mask(i.log_w))) & m
    }

    /// One rising edge: the output register takes the bank register, which takes the last
    /// read; the RAM reads the registered address (before this clock's write); the address
    /// register takes this clock's address; then the write.
    pub fn clock(&mut self, i: &MemoryInputs) {
        self.word = self.bank;
        self.bank = self.read;
        self.read = self.mem[self.address as usize];
        self.address = Self::address(i);
        self.valid = [i.valid, self.valid[0], self.valid[1], self.valid[2]];
        if i.we {
            self.mem[(i.waddr & 0xFFFF) as usize] = i.wdata & 0xFF_FFFF;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loaded_texture_reads_back_with_repeat() {
        let rgb = (0..8 * 4).map(|k| [k as u8, (k * 3) as u8, 7]).collect();
        let t = Texture::new(8, 4, rgb).unwrap();
        let mut m = MemoryTwin::default();
        for (a, w) in load_words(&t).unwrap() {
            m.clock(&MemoryInputs {
                we: true,
                waddr: a,
                wdata: w,
                ..Default::default()
            });
        }
        for (u, v) in [
            (0i64, 0i64),
            (7, 3),
            (-1, -1),
            (9, 5),
            (-17, 100),
            (32767, -32768),
        ] {
            let read = MemoryInputs {
                log_w: 3,
                log_h: 2,
                valid: true,
                u: (u as u32) & 0xFFFF,
                v: (v as u32) & 0xFFFF,
                ..Default::default()
            };
            m.clock(&read);
            for _ in 0..3 {
                m.clock(&MemoryInputs::default());
            }
            let want = t.texel(u, v).map(u32::from);
            assert_eq!(m.outputs(), (true, want), "({u}, {v})");
        }
        let big = Texture::new(1024, 128, vec![[0; 3]; 1024 * 128]).unwrap();
        assert!(load_words(&big).is_none());
    }
}
