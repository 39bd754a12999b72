//! Subdivision raster pipe (SPEC §7 with §6): the four-triangle address block feeding one
//! intensity interpolator BVI per lane, so each of the four midpoint sub-triangles of a
//! parent is Gouraud-shaded by its own BVI, four pixels per clock (golden:
//! `golden::units::four_triangle` for the addresses, `golden::shading::subdivision` for the colours).
//!
//! ```text
//!  load + set-up ─► SubpixelFourTriangle ─lane K: valid,row_start,step,carry─► BVI K ─► red_lK/green/blue
//!                       └──────────── lane K: x, y, done ──► 1-clock delay ──► x_lK, y_lK, done_lK
//! ```
//!
//! Two uses, the same hardware: **Gouraud through the four-triangle block** loads every lane's
//! BVI with the parent's planes (set up for the lane's own start pixel and walk), and the
//! **`subdivision` method** loads lane K with the planes through sub-triangle K's own vertex
//! intensities (the parent's vertices and the exactly lit, normalized midpoint normals).
//!
//! Ports: the sub-pixel four-triangle block's set-up inputs (`four-triangle-subpixel`: same
//! names, error words of 21 bits, see `four_triangle`; parents with integer or
//! `SUBPIXEL_BITS` = 4 fractional bits) and each
//! lane's twelve signed Q16.16 BVI words `r_start_lK` … `b_line_lK` (see
//! `intensity_interpolator`), all sampled on the one `load` strobe, accepted when `ready`;
//! `hold`, the four-triangle block's stall (a held clock shows no event on any lane, so no BVI
//! steps and the next clock shows no pixel; each lane's pixels under holds are its pixels
//! without them with empty clocks inserted; 0 in every use without a stream top).
//! Outputs per lane K: `valid_lK`, `x_lK`, `y_lK` (12 bits), `red_lK`, `green_lK`, `blue_lK`
//! (8 bits, saturated), `done_lK` (the lane's last event of the parent); and `ready`.
//!
//! Latency: load → first pixels 4 clocks (3 + 1). Throughput: up to four pixels per clock (the
//! four-triangle block's). Overflow and error budget: the BVI's (each channel within 1 LSB of
//! its rounded plane value; the Q16.16 adders wrap, harmlessly on in-range planes).

use crate::core::primitives::Delay;
use crate::units::four_triangle::SubpixelFourTriangle;
use crate::units::intensity_interpolator::IntensityInterpolator;
use rust_hdl::prelude::*;

// The four lanes are one text repeated by `seq!` (lane `L`: `bviL`, the delays `x_p1_lL`,
// `y_p1_lL`, `done_p1_lL`, ports ending in `_lL`), as in `four_triangle`.
seq_macro::seq!(L in 0..4 {
crate::hw_block! {
    /// The subdivision raster pipe (see the module header).
    pub struct SubdivisionRaster(clock) as "subdivision-raster" {
        summary: "four-triangle block feeding one BVI per sub-triangle: four Gouraud pixels per clock (SPEC §6–7)",
        latency: SubpixelFourTriangle::LATENCY + IntensityInterpolator::LATENCY
            => "load to the first pixels, up to four pixels per clock",
        multipliers: 0,
        in {
            load: Bit,
            w_f: Bits<12>, w_r: Bits<21>, w_d: Bits<21>,
            a_f: Bits<12>, a_r: Bits<21>, a_d: Bits<21>,
            t_f: Bits<12>, t_r: Bits<21>, t_d: Bits<21>,
            #(
            w_b0_l~L: Bits<12>, w_e0_l~L: Bits<21>, a_b0_l~L: Bits<12>, a_e0_l~L: Bits<21>,
            a_third_l~L: Bit, t_b0_l~L: Bits<12>, t_e0_l~L: Bits<21>, t_adjacent_l~L: Bit,
            y_top_l~L: Bits<12>, rows_l~L: Bits<12>, y_switch_l~L: Bits<12>, dir_neg_l~L: Bit,
            )*
            #(
            r_start_l~L: Bits<32>, r_short_l~L: Bits<32>, r_long_l~L: Bits<32>, r_line_l~L: Bits<32>,
            g_start_l~L: Bits<32>, g_short_l~L: Bits<32>, g_long_l~L: Bits<32>, g_line_l~L: Bits<32>,
            b_start_l~L: Bits<32>, b_short_l~L: Bits<32>, b_long_l~L: Bits<32>, b_line_l~L: Bits<32>,
            )*
            hold: Bit,
        }
        out {
            ready: Bit,
            #(
            valid_l~L: Bit, x_l~L: Bits<12>, y_l~L: Bits<12>,
            red_l~L: Bits<8>, green_l~L: Bits<8>, blue_l~L: Bits<8>, done_l~L: Bit,
            )*
        }
        pub addr: SubpixelFourTriangle,
        #(
        pub bvi~L: IntensityInterpolator,
        )*
        #(
        x_p1_l~L: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        y_p1_l~L: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        done_p1_l~L: Delay<Bit, { IntensityInterpolator::LATENCY }>,
        )*
    }
}

impl Logic for SubdivisionRaster {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, addr #(, bvi~L)* #(, x_p1_l~L, y_p1_l~L, done_p1_l~L)*);
        self.addr.load.next = self.load.val();
        self.addr.hold.next = self.hold.val();
        self.addr.w_f.next = self.w_f.val();
        self.addr.w_r.next = self.w_r.val();
        self.addr.w_d.next = self.w_d.val();
        self.addr.a_f.next = self.a_f.val();
        self.addr.a_r.next = self.a_r.val();
        self.addr.a_d.next = self.a_d.val();
        self.addr.t_f.next = self.t_f.val();
        self.addr.t_r.next = self.t_r.val();
        self.addr.t_d.next = self.t_d.val();
        #(
        self.addr.w_b0_l~L.next = self.w_b0_l~L.val();
        self.addr.w_e0_l~L.next = self.w_e0_l~L.val();
        self.addr.a_b0_l~L.next = self.a_b0_l~L.val();
        self.addr.a_e0_l~L.next = self.a_e0_l~L.val();
        self.addr.a_third_l~L.next = self.a_third_l~L.val();
        self.addr.t_b0_l~L.next = self.t_b0_l~L.val();
        self.addr.t_e0_l~L.next = self.t_e0_l~L.val();
        self.addr.t_adjacent_l~L.next = self.t_adjacent_l~L.val();
        self.addr.y_top_l~L.next = self.y_top_l~L.val();
        self.addr.rows_l~L.next = self.rows_l~L.val();
        self.addr.y_switch_l~L.next = self.y_switch_l~L.val();
        self.addr.dir_neg_l~L.next = self.dir_neg_l~L.val();
        )*
        self.ready.next = self.addr.ready.val();
        #(
        // Lane L: its BVI's shadow bank is written on the accepted load.
        self.bvi~L.load.next = self.load.val() & self.addr.ready.val();
        self.bvi~L.r_start.next = self.r_start_l~L.val();
        self.bvi~L.r_short.next = self.r_short_l~L.val();
        self.bvi~L.r_long.next = self.r_long_l~L.val();
        self.bvi~L.r_line.next = self.r_line_l~L.val();
        self.bvi~L.g_start.next = self.g_start_l~L.val();
        self.bvi~L.g_short.next = self.g_short_l~L.val();
        self.bvi~L.g_long.next = self.g_long_l~L.val();
        self.bvi~L.g_line.next = self.g_line_l~L.val();
        self.bvi~L.b_start.next = self.b_start_l~L.val();
        self.bvi~L.b_short.next = self.b_short_l~L.val();
        self.bvi~L.b_long.next = self.b_long_l~L.val();
        self.bvi~L.b_line.next = self.b_line_l~L.val();
        self.bvi~L.valid_in.next = self.addr.valid_l~L.val();
        self.bvi~L.row_start_in.next = self.addr.row_start_l~L.val();
        self.bvi~L.step_in.next = self.addr.step_l~L.val();
        self.bvi~L.carry_in.next = self.addr.carry_l~L.val();
        self.x_p1_l~L.d.next = self.addr.x_l~L.val();
        self.y_p1_l~L.d.next = self.addr.y_l~L.val();
        self.done_p1_l~L.d.next = self.addr.done_l~L.val();
        self.valid_l~L.next = self.bvi~L.valid_out.val();
        self.x_l~L.next = self.x_p1_l~L.q.val();
        self.y_l~L.next = self.y_p1_l~L.q.val();
        self.red_l~L.next = self.bvi~L.red.val();
        self.green_l~L.next = self.bvi~L.green.val();
        self.blue_l~L.next = self.bvi~L.blue.val();
        self.done_l~L.next = self.done_p1_l~L.q.val();
        )*
    }
}
});
