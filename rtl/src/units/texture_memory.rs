//! Texture memory (SPEC §14's texel fetch, fig. 6's БВТК store): the texture in block RAM,
//! written through a set-up port (not baked in at build time) and read at one texel per clock
//! with GL_REPEAT wrapping (golden: `golden::texture::Texture::texel`, and the bit-exact twin
//! `golden::units::texture_memory::MemoryTwin`).
//!
//! # Formula
//!
//! The texture is W×H texels, W = 2^log_w and H = 2^log_h, W·H ≤ 2^16; texel (i, j), i from
//! the left and j from the bottom row, is stored at address j·W + i
//! (`golden::units::texture_memory::write_address`). A read of the texel coordinates (u, v),
//! any integers, wraps each into its side:
//!
//! ```text
//!   address = ((v mod H) << log_w) | (u mod W)      (mod by the masks H − 1, W − 1)
//!   rgb     = memory[address]
//! ```
//!
//! # Ports
//!
//! | port | bits | format |
//! |---|---|---|
//! | `we` | 1 | write `wdata` at `waddr` this clock |
//! | `waddr` | 16 | unsigned texel address j·W + i |
//! | `wdata` | 24 | red (bits 23..16), green (15..8), blue (7..0), 8 bits each |
//! | `log_w`, `log_h` | 4 each | unsigned log2 of the sides (frame registers: hold them while reading) |
//! | `valid_in` | 1 | a texel read this clock |
//! | `u`, `v` | 16 each | the texel coordinates, two's complement (`texture-coord`'s outputs) |
//! | `valid_out` | 1 | `red`, `green`, `blue` is the texel read one clock earlier |
//! | `red`, `green`, `blue` | 8 each | the texel |
//!
//! # Latency, throughput, handshake
//!
//! One read per clock, no stall: the address of the coordinates presented in clock t is
//! registered, the four RAM banks read it in clock t + 1, their outputs are registered in
//! clock t + 2, the bank's is selected into the output register in clock t + 3, and the texel
//! shows in clock t + 4 with `valid_out` (`valid_in`/`valid_out`; the memory is read every clock, and the colour shows
//! whatever `valid_in` was). The RAM reads before it writes: a read presented in clock t sees
//! the writes of clocks up to t, not one in clock t + 1. Writes and reads may share a clock.
//!
//! Latency (the block's `LATENCY`): 4 clocks, valid_in to valid_out.
//!
//! # Overflow and error budget
//!
//! Exact: no arithmetic but the masks. Every texel reads 0 until it is written (the block
//! RAM's initial contents). The set-up keeps log_w, log_h ≤ 10 and W·H ≤ 2^16
//! (256×256, or 1024×64, …); beyond that the address is taken modulo 2^16 (the texels alias).
//! The memory holds 2^16 texels of 24 bits (1.5 Mbit: block RAM on ECP5) in four banks of 2^14.

use rust_hdl::prelude::*;

use crate::core::primitives::Bram;

crate::hw_block! {
    /// The texture memory (see the module header): the masks, the address register, four
    /// 2^14 × 24-bit block RAM banks with a register on each bank's output, the bank select and
    /// the output register.
    pub struct TextureMemory(clock) as "texture-memory" {
        summary: "the texture in block RAM: written through a set-up port, read at one texel (u, v) per clock with GL_REPEAT wrapping (SPEC §14's texel fetch)",
        latency: 4 => "valid_in to valid_out, one texel per clock",
        multipliers: 0,
        in {
            we: Bit, waddr: Bits<16>, wdata: Bits<24>,
            log_w: Bits<4>, log_h: Bits<4>,
            valid_in: Bit, u: Bits<16>, v: Bits<16>,
        }
        out { valid_out: Bit, red: Bits<8>, green: Bits<8>, blue: Bits<8> }
        /// Bank k holds the addresses with bits 15..14 = k.
        pub bank: [Bram<Bits<24>, 14>; 4],
        /// The address register (the RAM blocks' address then comes from a flip-flop), each
        /// bank's read registered (a RAM block's output goes straight to a flip-flop), the bank
        /// of the read twice, the output register and `valid_in` four times.
        address_q: DFF<Bits<16>>,
        bank_q: [DFF<Bits<24>>; 4],
        sel_q: DFF<Bits<2>>, sel2_q: DFF<Bits<2>>,
        texel_q: DFF<Bits<24>>,
        valid_q: [DFF<Bit>; 4],
        ones: Constant<Bits<16>> = Constant::new(0xFFFFu64.into()),
        /// W − 1 and H − 1 (as ¬(0xFFFF << log): each bit a function of the log's four bits,
        /// no carry chain), the address, and the write's bank.
        mask_w: Signal<Local, Bits<16>>, mask_h: Signal<Local, Bits<16>>,
        row: Signal<Local, Bits<16>>, address: Signal<Local, Bits<16>>,
        wbank: Signal<Local, Bits<2>>,
    }
}

impl Logic for TextureMemory {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, address_q, sel_q, sel2_q, texel_q);
        for k in 0..4 {
            self.bank_q[k].clock.next = self.clock.val();
            self.valid_q[k].clock.next = self.clock.val();
            self.bank[k].clock.next = self.clock.val();
            self.bank[k].read_address.next = self.address_q.q.val().get_bits::<14>(0);
            self.bank[k].write_address.next = self.waddr.val().get_bits::<14>(0);
            self.bank[k].write_data.next = self.wdata.val();
            self.bank_q[k].d.next = self.bank[k].read_data.val();
        }
        self.mask_w.next = !(self.ones.val() << self.log_w.val());
        self.mask_h.next = !(self.ones.val() << self.log_h.val());
        self.row.next = (self.v.val() & self.mask_h.val()) << self.log_w.val();
        self.address.next = self.row.val() | (self.u.val() & self.mask_w.val());
        self.address_q.d.next = self.address.val();
        self.wbank.next = self.waddr.val().get_bits::<2>(14);
        self.bank[0].write_enable.next = self.we.val() & (self.wbank.val() == 0);
        self.bank[1].write_enable.next = self.we.val() & (self.wbank.val() == 1);
        self.bank[2].write_enable.next = self.we.val() & (self.wbank.val() == 2);
        self.bank[3].write_enable.next = self.we.val() & (self.wbank.val() == 3);
        self.sel_q.d.next = self.address_q.q.val().get_bits::<2>(14);
        self.sel2_q.d.next = self.sel_q.q.val();
        self.texel_q.d.next = self.bank_q[0].q.val();
        if self.sel2_q.q.val() == 1 {
            self.texel_q.d.next = self.bank_q[1].q.val();
        }
        if self.sel2_q.q.val() == 2 {
            self.texel_q.d.next = self.bank_q[2].q.val();
        }
        if self.sel2_q.q.val() == 3 {
            self.texel_q.d.next = self.bank_q[3].q.val();
        }
        self.valid_q[0].d.next = self.valid_in.val();
        self.valid_q[1].d.next = self.valid_q[0].q.val();
        self.valid_q[2].d.next = self.valid_q[1].q.val();
        self.valid_q[3].d.next = self.valid_q[2].q.val();
        self.valid_out.next = self.valid_q[3].q.val();
        self.red.next = self.texel_q.q.val().get_bits::<8>(16);
        self.green.next = self.texel_q.q.val().get_bits::<8>(8);
        self.blue.next = self.texel_q.q.val().get_bits::<8>(0);
    }
}
