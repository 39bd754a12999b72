//! Vector interpolator (SPEC §1, "constant increments"; golden: `golden::units::vector_interpolator`):
//! the interpolated normal N along the address block's walk, one pixel per clock, for the
//! normalizer of the lit pixel pipeline.
//!
//! # Formula
//!
//! Each component N_k is a screen-space plane a·x + b·y + c through the vertex normals'
//! component. The software set-up computes, once per triangle, the increments of SPEC §1
//! grouped the way the address block moves (`short` = f·a + b and `long` = (f + 1)·a + b for the
//! working edge's whole move into a line — the ΔN_H/ΔN_V/ΔN_D steps of that move summed —
//! and `line` = dir·a along a line), and the value at the first line start. The hardware adds
//! one of them per event, exactly as the BVI does for an intensity: the block *is* a BVI
//! ([`IntensityInterpolator`]: per component RG1–RG5, a shadow bank, the adder Sm), its words read
//! as Q3.29 instead of Q16.16, followed by a rounding stage per component to Q2.17 (19 bits;
//! Q2.14 until the lit methods' 2-LSB bound, `docs/bump-precision.md`).
//! K for the normalizer is not formed here: the pipeline squares the rounded N (the
//! normalizer's own squarers), which keeps K exact for the vector the normalizer scales.
//!
//! # Ports and formats
//!
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | write the shadow bank (with the address block's accepted load) |
//! | `x_start x_short x_long x_line`, `y_…`, `z_…` | in | signed Q3.29 words, wrapping (`golden::units::vector_interpolator::setup`) |
//! | `valid_in`, `row_start_in`, `step_in` (2), `carry_in` | in | the address block's `valid`, `row_start`, `step`, `carry` |
//! | `valid_out` | out | `valid_in` one clock later |
//! | `nx ny nz` | out | signed Q2.17 (19 bits): the running word RG4 rounded to nearest (ties toward +∞), saturated |
//!
//! Latency 1 clock (`valid_in` → `valid_out`, the BVI's; the output rounding is combinational
//! after its RG4 registers); throughput one pixel per clock; no stall. The shadow bank is
//! loaded as the BVI's (see `intensity_interpolator`): assert `load` with the address block's
//! accepted load.
//!
//! # Overflow
//!
//! Words wrap modulo 2³² on purpose (the sum of the quantized start and increments is exact
//! modulo 2³², so a sliver's giant increment wraps and unwraps without loss); only the pixel
//! values must be in range, and |N_k| ≤ 1 for interpolated unit normals (Q3.29 holds ±4). The
//! output saturates to [−2, 2 − 2⁻¹⁷] (`RoundToQ2_17`) rather than wrap.
//!
//! # Error budget
//!
//! Each quantized term is off by ≤ 2⁻³⁰; a pixel reached by n ≤ 8189 additions is within
//! n·2⁻³⁰ ≤ 7.6·10⁻⁶ (1 LSB of Q2.17) of the plane value before the output rounding, which
//! adds ≤ 2⁻¹⁸: in all ≤ n·2⁻³⁰ + 2⁻¹⁸ (`golden::units::vector_interpolator::error_bound`).

use rust_hdl::prelude::*;

use crate::core::primitives::RoundToQ2_17;
use crate::units::intensity_interpolator::IntensityInterpolator;

crate::hw_block! {
    /// The vector interpolator: the BVI's three accumulators on Q3.29 words, each rounded to
    /// Q2.17.
    pub struct VectorInterpolator(clock) as "vector-interpolator" {
        summary: "the address block's step information in, the interpolated normal N (Q2.17) per pixel out (SPEC §1)",
        latency: 1 => "valid_in to valid_out, one pixel per clock",
        multipliers: 0,
        in {
            load: Bit,
            x_start: Bits<32>, x_short: Bits<32>, x_long: Bits<32>, x_line: Bits<32>,
            y_start: Bits<32>, y_short: Bits<32>, y_long: Bits<32>, y_line: Bits<32>,
            z_start: Bits<32>, z_short: Bits<32>, z_long: Bits<32>, z_line: Bits<32>,
            valid_in: Bit, row_start_in: Bit, step_in: Bits<2>, carry_in: Bit,
        }
        out { valid_out: Bit, nx: Bits<19>, ny: Bits<19>, nz: Bits<19> }
        /// The accumulators: the BVI itself, its red, green, blue channels carrying x, y, z
        /// (its 8-bit outputs are unused and removed by synthesis).
        pub acc: IntensityInterpolator,
        /// The output rounding of each component to Q2.17.
        round: [RoundToQ2_17; 3],
    }
}

impl Logic for VectorInterpolator {
    #[hdl_gen]
    fn update(&mut self) {
        self.acc.clock.next = self.clock.val();
        self.acc.load.next = self.load.val();
        self.acc.r_start.next = self.x_start.val();
        self.acc.r_short.next = self.x_short.val();
        self.acc.r_long.next = self.x_long.val();
        self.acc.r_line.next = self.x_line.val();
        self.acc.g_start.next = self.y_start.val();
        self.acc.g_short.next = self.y_short.val();
        self.acc.g_long.next = self.y_long.val();
        self.acc.g_line.next = self.y_line.val();
        self.acc.b_start.next = self.z_start.val();
        self.acc.b_short.next = self.z_short.val();
        self.acc.b_long.next = self.z_long.val();
        self.acc.b_line.next = self.z_line.val();
        self.acc.valid_in.next = self.valid_in.val();
        self.acc.row_start_in.next = self.row_start_in.val();
        self.acc.step_in.next = self.step_in.val();
        self.acc.carry_in.next = self.carry_in.val();
        self.round[0].wide.next = self.acc.red_word.val();
        self.round[1].wide.next = self.acc.green_word.val();
        self.round[2].wide.next = self.acc.blue_word.val();
        self.valid_out.next = self.acc.valid_out.val();
        self.nx.next = self.round[0].narrow.val();
        self.ny.next = self.round[1].narrow.val();
        self.nz.next = self.round[2].narrow.val();
    }
}
