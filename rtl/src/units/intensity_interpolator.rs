//! Intensity interpolator BVI (SPEC §6, fig. 3.8): Gouraud intensities along the address
//! block's walk, one addition per event and colour channel (golden:
//! `golden::units::intensity_interpolator`).
//!
//! # Formula
//!
//! A channel's intensity is a screen-space plane I(x, y) = a·x + b·y + c (centre sampling). The
//! address block reports, per event, whether it starts a raster line and how far the working
//! edge moved into it (f or f + 1 pixels, see `line_interpolator`), and steps along the line
//! by `dir`. So, with per-triangle constants from the set-up software
//!
//! ```text
//!   RG1 = f·a + b          (line start after a short move)
//!   RG2 = (f + 1)·a + b    (line start after a long move)
//!   RG3 = dir·a            (next pixel on the line)
//!   RG5 = I at the first line start (+½ LSB, so truncation rounds to nearest)
//! ```
//!
//! each event needs exactly one addition `Sm = A + B`:
//!
//! | event                       | A     | B                  | writes            |
//! |-----------------------------|-------|--------------------|-------------------|
//! | first line start (step 0)   | SH5   | 0                  | RG5, RG4; RG1–3 ← SH1–3 |
//! | other line start            | RG5   | carry ? RG2 : RG1  | RG5, RG4 (if pixel) |
//! | pixel along the line        | RG4   | RG3                | RG4               |
//!
//! RG1–RG5 are the five registers of fig. 3.8 (RG4 the running intensity, RG5 the intensity
//! at the line start kept while the line is interpolated; RG1/RG2 take the place of the
//! working-edge increment because the edge moves a whole line per clock). SH1, SH2, SH3, SH5
//! are a set-up shadow bank: `load` writes them while the previous triangle is still being
//! shaded, and the first event of the next triangle copies them in, so triangles follow each
//! other without a gap. Each colour has its own [`IntensityChannel`] (`chan[0]` red, `chan[1]`
//! green, `chan[2]` blue); the address block's step information drives all three alike.
//!
//! # Formats
//!
//! Every register, the adder and the set-up ports are 32-bit two's complement **signed Q16.16**
//! ([`crate::core::fixed::INTENSITY`], the sign counted in the 16 integer bits): value =
//! word / 2^16 in 8-bit LSB units, i.e. the 0..255 scale. Additions wrap modulo
//! 2^32 on purpose: each pixel's word is the sum of the quantized start value and increments,
//! and a sum modulo 2^32 is exact modulo 2^32, so a giant increment of a sliver triangle (the
//! plane's gradient can reach millions of LSB per pixel) wraps and unwraps without loss; only
//! the pixel values themselves must be in range, and they are (convex combinations of the vertex
//! intensities, |I| < 2^15). Output: `red`, `green`, `blue` 8 bits ([`crate::core::fixed::LEVEL`],
//! unsigned Q8.0), saturating:
//! word < 0 → 0, word ≥ 256·2^16 → 255, otherwise bits 23..16 (truncation; the +½ in RG5 makes
//! it round to nearest).
//!
//! # Latency, throughput, handshake
//!
//! Inputs `valid_in`, `row_start_in`, `step_in`, `carry_in` are the address block's outputs of
//! the same name. Outputs are registers: the colour of the pixel presented in clock t appears
//! in clock t + 1 with `valid_out` (and the unsaturated words `red_word` … `blue_word`).
//! One pixel per clock. Sm is built as three adders side by side (RG4 + RG3, RG5 + RG1,
//! RG5 + RG2) and the event selects among their sums and SH5, so the event flags (and the
//! address block's `hold` in them) steer only the last multiplexer, not an adder's operands.
//! `load` writes the shadow bank in any clock: assert it together with
//! the address block's accepted load (`load & ready`). That is always safe, because the
//! address block raises `ready` only after the previous triangle's first event has been shown,
//! i.e. after the clock in which this block copied the shadow bank into RG1–RG3/RG5 (a copy and
//! a new write in the same clock are fine: the copy reads the old values).
//!
//! # Error budget
//!
//! The start value and each increment are rounded to the nearest 2^-16 (error ≤ 2^-17 each,
//! for |value·2^16| < 2^52 where f64 still holds the rounding exactly). A pixel k lines below
//! the first line start and i pixels along its line is reached by 1 + k + i ≤ 8189 additions,
//! so its word differs from (I + ½)·2^16 by at most (1 + k + i)·2^-17 ≤ 0.0625 LSB, and the
//! 8-bit output differs from round(I) (clamped) by at most 1 LSB — by exactly 0 unless I lies
//! within that bound of a half-integer.
//!
//! Latency (the block's `LATENCY`): 1 clocks, valid_in to valid_out, one pixel per clock.

use rust_hdl::prelude::*;

crate::hw_block! {
    /// One colour channel: five registers, a shadow bank, the adder Sm (three sums side by
    /// side, one selected), the saturating output.
    pub struct IntensityChannel(clock) {
        in {
            /// Write the shadow bank from the set-up ports.
            load: Bit,
            set_start: Bits<32>, set_short: Bits<32>, set_long: Bits<32>, set_line: Bits<32>,
            /// First event of a triangle (row_start with step Start).
            ev_first: Bit,
            ev_row_start: Bit, ev_carry: Bit, ev_valid: Bit,
        }
        out {
            /// The saturated 8-bit intensity of RG4.
            level: Bits<8>,
            /// RG4 itself, signed Q16.16 with the +½ bias (for blocks that need more than 8 bits).
            word: Bits<32>,
        }
        /// RG1: increment of a line start after a short edge move.
        rg1: DFF<Bits<32>>,
        /// RG2: increment of a line start after a long edge move.
        rg2: DFF<Bits<32>>,
        /// RG3: increment along the raster line.
        rg3: DFF<Bits<32>>,
        /// RG4: the running intensity (the output).
        rg4: DFF<Bits<32>>,
        /// RG5: the intensity at the current line start.
        rg5: DFF<Bits<32>>,
        /// The shadow bank: RG1, RG2, RG3 and RG5 of the next triangle.
        sh1: DFF<Bits<32>>, sh2: DFF<Bits<32>>, sh3: DFF<Bits<32>>, sh5: DFF<Bits<32>>,
        /// Sm's three possible sums, formed side by side (signed Q16.16, modulo 2^32): along
        /// the line, at a line start after a short and after a long edge move; and the one the
        /// event selects.
        s_line: Signal<Local, Bits<32>>, s_short: Signal<Local, Bits<32>>,
        s_long: Signal<Local, Bits<32>>, sum: Signal<Local, Bits<32>>,
    }
}

impl Logic for IntensityChannel {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, rg1, rg2, rg3, rg4, rg5, sh1, sh2, sh3, sh5);
        // Sm's sum for each kind of event, formed side by side from registers only; the event
        // (through the address block's `hold` gate) selects one after the carry chains, so
        // `hold` does not reach an adder (ECP5: hold_q → row_start → first → operand
        // select → carry chain → RG4 was `subdivision-stream`'s path, 10.59 ns). The same sums
        // as one adder with operand multiplexers: SH5 + 0 at the first event.
        self.s_line.next = self.rg4.q.val() + self.rg3.q.val();
        self.s_short.next = self.rg5.q.val() + self.rg1.q.val();
        self.s_long.next = self.rg5.q.val() + self.rg2.q.val();
        self.sum.next = self.s_line.val();
        if self.ev_first.val() {
            self.sum.next = self.sh5.q.val();
        } else if self.ev_row_start.val() {
            self.sum.next = self.s_short.val();
            if self.ev_carry.val() {
                self.sum.next = self.s_long.val();
            }
        }
        if self.ev_first.val() {
            self.rg1.d.next = self.sh1.q.val();
            self.rg2.d.next = self.sh2.q.val();
            self.rg3.d.next = self.sh3.q.val();
        }
        if self.ev_row_start.val() {
            self.rg5.d.next = self.sum.val();
        }
        if self.ev_valid.val() {
            self.rg4.d.next = self.sum.val();
        }
        if self.load.val() {
            self.sh1.d.next = self.set_short.val();
            self.sh2.d.next = self.set_long.val();
            self.sh3.d.next = self.set_line.val();
            self.sh5.d.next = self.set_start.val();
        }
        self.word.next = self.rg4.q.val();
        // Saturation: negative → 0, ≥ 256 → 255, else the integer part.
        self.level.next = self.rg4.q.val().get_bits::<8>(16);
        if self.rg4.q.val().get_bits::<7>(24).any() {
            self.level.next = 255.into();
        }
        if self.rg4.q.val().get_bit(31) {
            self.level.next = 0.into();
        }
    }
}

/// The BVI's twelve set-up words after `load` (signed Q16.16: start, short, long, line for
/// red, green, blue), as a port bundle (`crate::core::declare`) for the blocks that contain a BVI
/// and pass its set-up through.
#[macro_export]
macro_rules! intensity_setup_ports {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [
                r_start: Bits<32>, r_short: Bits<32>, r_long: Bits<32>, r_line: Bits<32>,
                g_start: Bits<32>, g_short: Bits<32>, g_long: Bits<32>, g_line: Bits<32>,
                b_start: Bits<32>, b_short: Bits<32>, b_long: Bits<32>, b_line: Bits<32>,
            ]
            $($then)*
        }
    };
}

crate::hw_block! {
    /// BVI: three channels sharing the address block's step information.
    pub struct IntensityInterpolator(clock) as "intensity-interpolator" {
        summary: "BVI: the address block's step information in, 8-bit R, G, B per pixel out (SPEC §6)",
        latency: 1 => "valid_in to valid_out, one pixel per clock",
        multipliers: 0,
        in { load: Bit, intensity_setup_ports!,
            valid_in: Bit, row_start_in: Bit, step_in: Bits<2>, carry_in: Bit,
        }
        out {
            valid_out: Bit, red: Bits<8>, green: Bits<8>, blue: Bits<8>,
            /// The running words RG4 (signed Q16.16, +½ LSB bias, wrapping): the value before
            /// saturation, exposed for the bench's format check and for wider consumers.
            red_word: Bits<32>,
            green_word: Bits<32>, blue_word: Bits<32>,
        }
        /// The three colour channels: 0 red, 1 green, 2 blue.
        pub chan: [IntensityChannel; 3],
        valid_p1: DFF<Bit>,
        first: Signal<Local, Bit>,
    }
}

impl Logic for IntensityInterpolator {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid_p1);
        self.first.next = self.row_start_in.val() & (self.step_in.val() == 0);
        self.valid_p1.d.next = self.valid_in.val();

        // The address block's step information drives all three channels alike.
        for i in 0..3 {
            self.chan[i].clock.next = self.clock.val();
            self.chan[i].load.next = self.load.val();
            self.chan[i].ev_first.next = self.first.val();
            self.chan[i].ev_row_start.next = self.row_start_in.val();
            self.chan[i].ev_carry.next = self.carry_in.val();
            self.chan[i].ev_valid.next = self.valid_in.val();
        }
        self.chan[0].set_start.next = self.r_start.val();
        self.chan[0].set_short.next = self.r_short.val();
        self.chan[0].set_long.next = self.r_long.val();
        self.chan[0].set_line.next = self.r_line.val();
        self.chan[1].set_start.next = self.g_start.val();
        self.chan[1].set_short.next = self.g_short.val();
        self.chan[1].set_long.next = self.g_long.val();
        self.chan[1].set_line.next = self.g_line.val();
        self.chan[2].set_start.next = self.b_start.val();
        self.chan[2].set_short.next = self.b_short.val();
        self.chan[2].set_long.next = self.b_long.val();
        self.chan[2].set_line.next = self.b_line.val();

        self.valid_out.next = self.valid_p1.q.val();
        self.red.next = self.chan[0].level.val();
        self.green.next = self.chan[1].level.val();
        self.blue.next = self.chan[2].level.val();
        self.red_word.next = self.chan[0].word.val();
        self.green_word.next = self.chan[1].word.val();
        self.blue_word.next = self.chan[2].word.val();
    }
}
