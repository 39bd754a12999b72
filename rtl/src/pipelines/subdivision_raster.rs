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

crate::hw_block! {
    /// The subdivision raster pipe (see the module header).
    pub struct SubdivisionRaster(clock) as "subdivision-raster" {
        summary: "four-triangle block feeding one BVI per sub-triangle: four Gouraud pixels per clock (SPEC §6–7)",
        latency: SubpixelFourTriangle::LATENCY + IntensityInterpolator::LATENCY
            => "load to the first pixels, up to four pixels per clock",
        multipliers: 0,
        in {
            load: Bit,
            w_f: Bits<12>,
            w_r: Bits<21>,
            w_d: Bits<21>,
            a_f: Bits<12>,
            a_r: Bits<21>,
            a_d: Bits<21>,
            t_f: Bits<12>,
            t_r: Bits<21>,
            t_d: Bits<21>,
            w_b0_l0: Bits<12>,
            w_e0_l0: Bits<21>,
            a_b0_l0: Bits<12>,
            a_e0_l0: Bits<21>,
            a_third_l0: Bit,
            t_b0_l0: Bits<12>,
            t_e0_l0: Bits<21>,
            t_adjacent_l0: Bit,
            y_top_l0: Bits<12>,
            rows_l0: Bits<12>,
            y_switch_l0: Bits<12>,
            dir_neg_l0: Bit,
            w_b0_l1: Bits<12>,
            w_e0_l1: Bits<21>,
            a_b0_l1: Bits<12>,
            a_e0_l1: Bits<21>,
            a_third_l1: Bit,
            t_b0_l1: Bits<12>,
            t_e0_l1: Bits<21>,
            t_adjacent_l1: Bit,
            y_top_l1: Bits<12>,
            rows_l1: Bits<12>,
            y_switch_l1: Bits<12>,
            dir_neg_l1: Bit,
            w_b0_l2: Bits<12>,
            w_e0_l2: Bits<21>,
            a_b0_l2: Bits<12>,
            a_e0_l2: Bits<21>,
            a_third_l2: Bit,
            t_b0_l2: Bits<12>,
            t_e0_l2: Bits<21>,
            t_adjacent_l2: Bit,
            y_top_l2: Bits<12>,
            rows_l2: Bits<12>,
            y_switch_l2: Bits<12>,
            dir_neg_l2: Bit,
            w_b0_l3: Bits<12>,
            w_e0_l3: Bits<21>,
            a_b0_l3: Bits<12>,
            a_e0_l3: Bits<21>,
            a_third_l3: Bit,
            t_b0_l3: Bits<12>,
            t_e0_l3: Bits<21>,
            t_adjacent_l3: Bit,
            y_top_l3: Bits<12>,
            rows_l3: Bits<12>,
            y_switch_l3: Bits<12>,
            dir_neg_l3: Bit,
            r_start_l0: Bits<32>, r_short_l0: Bits<32>, r_long_l0: Bits<32>, r_line_l0: Bits<32>,
            g_start_l0: Bits<32>, g_short_l0: Bits<32>, g_long_l0: Bits<32>, g_line_l0: Bits<32>,
            b_start_l0: Bits<32>, b_short_l0: Bits<32>, b_long_l0: Bits<32>, b_line_l0: Bits<32>,
            r_start_l1: Bits<32>, r_short_l1: Bits<32>, r_long_l1: Bits<32>, r_line_l1: Bits<32>,
            g_start_l1: Bits<32>, g_short_l1: Bits<32>, g_long_l1: Bits<32>, g_line_l1: Bits<32>,
            b_start_l1: Bits<32>, b_short_l1: Bits<32>, b_long_l1: Bits<32>, b_line_l1: Bits<32>,
            r_start_l2: Bits<32>, r_short_l2: Bits<32>, r_long_l2: Bits<32>, r_line_l2: Bits<32>,
            g_start_l2: Bits<32>, g_short_l2: Bits<32>, g_long_l2: Bits<32>, g_line_l2: Bits<32>,
            b_start_l2: Bits<32>, b_short_l2: Bits<32>, b_long_l2: Bits<32>, b_line_l2: Bits<32>,
            r_start_l3: Bits<32>, r_short_l3: Bits<32>, r_long_l3: Bits<32>, r_line_l3: Bits<32>,
            g_start_l3: Bits<32>, g_short_l3: Bits<32>, g_long_l3: Bits<32>, g_line_l3: Bits<32>,
            b_start_l3: Bits<32>, b_short_l3: Bits<32>, b_long_l3: Bits<32>, b_line_l3: Bits<32>,
            hold: Bit,
        }
        out {
            ready: Bit,
            valid_l0: Bit, x_l0: Bits<12>, y_l0: Bits<12>,
            red_l0: Bits<8>, green_l0: Bits<8>, blue_l0: Bits<8>, done_l0: Bit,
            valid_l1: Bit, x_l1: Bits<12>, y_l1: Bits<12>,
            red_l1: Bits<8>, green_l1: Bits<8>, blue_l1: Bits<8>, done_l1: Bit,
            valid_l2: Bit, x_l2: Bits<12>, y_l2: Bits<12>,
            red_l2: Bits<8>, green_l2: Bits<8>, blue_l2: Bits<8>, done_l2: Bit,
            valid_l3: Bit, x_l3: Bits<12>, y_l3: Bits<12>,
            red_l3: Bits<8>, green_l3: Bits<8>, blue_l3: Bits<8>, done_l3: Bit,
        }
        pub addr: SubpixelFourTriangle,
        pub bvi0: IntensityInterpolator,
        pub bvi1: IntensityInterpolator,
        pub bvi2: IntensityInterpolator,
        pub bvi3: IntensityInterpolator,
        x0_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        y0_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        done0_p1: Delay<Bit, { IntensityInterpolator::LATENCY }>,
        x1_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        y1_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        done1_p1: Delay<Bit, { IntensityInterpolator::LATENCY }>,
        x2_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        y2_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        done2_p1: Delay<Bit, { IntensityInterpolator::LATENCY }>,
        x3_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        y3_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        done3_p1: Delay<Bit, { IntensityInterpolator::LATENCY }>,
    }
}

impl Logic for SubdivisionRaster {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self, clock, addr, bvi0, bvi1, bvi2, bvi3, x0_p1, y0_p1, done0_p1, x1_p1, y1_p1,
            done1_p1, x2_p1, y2_p1, done2_p1, x3_p1, y3_p1, done3_p1
        );
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
        self.addr.w_b0_l0.next = self.w_b0_l0.val();
        self.addr.w_e0_l0.next = self.w_e0_l0.val();
        self.addr.a_b0_l0.next = self.a_b0_l0.val();
        self.addr.a_e0_l0.next = self.a_e0_l0.val();
        self.addr.a_third_l0.next = self.a_third_l0.val();
        self.addr.t_b0_l0.next = self.t_b0_l0.val();
        self.addr.t_e0_l0.next = self.t_e0_l0.val();
        self.addr.t_adjacent_l0.next = self.t_adjacent_l0.val();
        self.addr.y_top_l0.next = self.y_top_l0.val();
        self.addr.rows_l0.next = self.rows_l0.val();
        self.addr.y_switch_l0.next = self.y_switch_l0.val();
        self.addr.dir_neg_l0.next = self.dir_neg_l0.val();
        self.addr.w_b0_l1.next = self.w_b0_l1.val();
        self.addr.w_e0_l1.next = self.w_e0_l1.val();
        self.addr.a_b0_l1.next = self.a_b0_l1.val();
        self.addr.a_e0_l1.next = self.a_e0_l1.val();
        self.addr.a_third_l1.next = self.a_third_l1.val();
        self.addr.t_b0_l1.next = self.t_b0_l1.val();
        self.addr.t_e0_l1.next = self.t_e0_l1.val();
        self.addr.t_adjacent_l1.next = self.t_adjacent_l1.val();
        self.addr.y_top_l1.next = self.y_top_l1.val();
        self.addr.rows_l1.next = self.rows_l1.val();
        self.addr.y_switch_l1.next = self.y_switch_l1.val();
        self.addr.dir_neg_l1.next = self.dir_neg_l1.val();
        self.addr.w_b0_l2.next = self.w_b0_l2.val();
        self.addr.w_e0_l2.next = self.w_e0_l2.val();
        self.addr.a_b0_l2.next = self.a_b0_l2.val();
        self.addr.a_e0_l2.next = self.a_e0_l2.val();
        self.addr.a_third_l2.next = self.a_third_l2.val();
        self.addr.t_b0_l2.next = self.t_b0_l2.val();
        self.addr.t_e0_l2.next = self.t_e0_l2.val();
        self.addr.t_adjacent_l2.next = self.t_adjacent_l2.val();
        self.addr.y_top_l2.next = self.y_top_l2.val();
        self.addr.rows_l2.next = self.rows_l2.val();
        self.addr.y_switch_l2.next = self.y_switch_l2.val();
        self.addr.dir_neg_l2.next = self.dir_neg_l2.val();
        self.addr.w_b0_l3.next = self.w_b0_l3.val();
        self.addr.w_e0_l3.next = self.w_e0_l3.val();
        self.addr.a_b0_l3.next = self.a_b0_l3.val();
        self.addr.a_e0_l3.next = self.a_e0_l3.val();
        self.addr.a_third_l3.next = self.a_third_l3.val();
        self.addr.t_b0_l3.next = self.t_b0_l3.val();
        self.addr.t_e0_l3.next = self.t_e0_l3.val();
        self.addr.t_adjacent_l3.next = self.t_adjacent_l3.val();
        self.addr.y_top_l3.next = self.y_top_l3.val();
        self.addr.rows_l3.next = self.rows_l3.val();
        self.addr.y_switch_l3.next = self.y_switch_l3.val();
        self.addr.dir_neg_l3.next = self.dir_neg_l3.val();
        self.ready.next = self.addr.ready.val();

        // Lane 0: its BVI's shadow bank is written on the accepted load.
        self.bvi0.load.next = self.load.val() & self.addr.ready.val();
        self.bvi0.r_start.next = self.r_start_l0.val();
        self.bvi0.r_short.next = self.r_short_l0.val();
        self.bvi0.r_long.next = self.r_long_l0.val();
        self.bvi0.r_line.next = self.r_line_l0.val();
        self.bvi0.g_start.next = self.g_start_l0.val();
        self.bvi0.g_short.next = self.g_short_l0.val();
        self.bvi0.g_long.next = self.g_long_l0.val();
        self.bvi0.g_line.next = self.g_line_l0.val();
        self.bvi0.b_start.next = self.b_start_l0.val();
        self.bvi0.b_short.next = self.b_short_l0.val();
        self.bvi0.b_long.next = self.b_long_l0.val();
        self.bvi0.b_line.next = self.b_line_l0.val();
        self.bvi0.valid_in.next = self.addr.valid_l0.val();
        self.bvi0.row_start_in.next = self.addr.row_start_l0.val();
        self.bvi0.step_in.next = self.addr.step_l0.val();
        self.bvi0.carry_in.next = self.addr.carry_l0.val();
        self.x0_p1.d.next = self.addr.x_l0.val();
        self.y0_p1.d.next = self.addr.y_l0.val();
        self.done0_p1.d.next = self.addr.done_l0.val();
        self.valid_l0.next = self.bvi0.valid_out.val();
        self.x_l0.next = self.x0_p1.q.val();
        self.y_l0.next = self.y0_p1.q.val();
        self.red_l0.next = self.bvi0.red.val();
        self.green_l0.next = self.bvi0.green.val();
        self.blue_l0.next = self.bvi0.blue.val();
        self.done_l0.next = self.done0_p1.q.val();

        // Lane 1: its BVI's shadow bank is written on the accepted load.
        self.bvi1.load.next = self.load.val() & self.addr.ready.val();
        self.bvi1.r_start.next = self.r_start_l1.val();
        self.bvi1.r_short.next = self.r_short_l1.val();
        self.bvi1.r_long.next = self.r_long_l1.val();
        self.bvi1.r_line.next = self.r_line_l1.val();
        self.bvi1.g_start.next = self.g_start_l1.val();
        self.bvi1.g_short.next = self.g_short_l1.val();
        self.bvi1.g_long.next = self.g_long_l1.val();
        self.bvi1.g_line.next = self.g_line_l1.val();
        self.bvi1.b_start.next = self.b_start_l1.val();
        self.bvi1.b_short.next = self.b_short_l1.val();
        self.bvi1.b_long.next = self.b_long_l1.val();
        self.bvi1.b_line.next = self.b_line_l1.val();
        self.bvi1.valid_in.next = self.addr.valid_l1.val();
        self.bvi1.row_start_in.next = self.addr.row_start_l1.val();
        self.bvi1.step_in.next = self.addr.step_l1.val();
        self.bvi1.carry_in.next = self.addr.carry_l1.val();
        self.x1_p1.d.next = self.addr.x_l1.val();
        self.y1_p1.d.next = self.addr.y_l1.val();
        self.done1_p1.d.next = self.addr.done_l1.val();
        self.valid_l1.next = self.bvi1.valid_out.val();
        self.x_l1.next = self.x1_p1.q.val();
        self.y_l1.next = self.y1_p1.q.val();
        self.red_l1.next = self.bvi1.red.val();
        self.green_l1.next = self.bvi1.green.val();
        self.blue_l1.next = self.bvi1.blue.val();
        self.done_l1.next = self.done1_p1.q.val();

        // Lane 2: its BVI's shadow bank is written on the accepted load.
        self.bvi2.load.next = self.load.val() & self.addr.ready.val();
        self.bvi2.r_start.next = self.r_start_l2.val();
        self.bvi2.r_short.next = self.r_short_l2.val();
        self.bvi2.r_long.next = self.r_long_l2.val();
        self.bvi2.r_line.next = self.r_line_l2.val();
        self.bvi2.g_start.next = self.g_start_l2.val();
        self.bvi2.g_short.next = self.g_short_l2.val();
        self.bvi2.g_long.next = self.g_long_l2.val();
        self.bvi2.g_line.next = self.g_line_l2.val();
        self.bvi2.b_start.next = self.b_start_l2.val();
        self.bvi2.b_short.next = self.b_short_l2.val();
        self.bvi2.b_long.next = self.b_long_l2.val();
        self.bvi2.b_line.next = self.b_line_l2.val();
        self.bvi2.valid_in.next = self.addr.valid_l2.val();
        self.bvi2.row_start_in.next = self.addr.row_start_l2.val();
        self.bvi2.step_in.next = self.addr.step_l2.val();
        self.bvi2.carry_in.next = self.addr.carry_l2.val();
        self.x2_p1.d.next = self.addr.x_l2.val();
        self.y2_p1.d.next = self.addr.y_l2.val();
        self.done2_p1.d.next = self.addr.done_l2.val();
        self.valid_l2.next = self.bvi2.valid_out.val();
        self.x_l2.next = self.x2_p1.q.val();
        self.y_l2.next = self.y2_p1.q.val();
        self.red_l2.next = self.bvi2.red.val();
        self.green_l2.next = self.bvi2.green.val();
        self.blue_l2.next = self.bvi2.blue.val();
        self.done_l2.next = self.done2_p1.q.val();

        // Lane 3: its BVI's shadow bank is written on the accepted load.
        self.bvi3.load.next = self.load.val() & self.addr.ready.val();
        self.bvi3.r_start.next = self.r_start_l3.val();
        self.bvi3.r_short.next = self.r_short_l3.val();
        self.bvi3.r_long.next = self.r_long_l3.val();
        self.bvi3.r_line.next = self.r_line_l3.val();
        self.bvi3.g_start.next = self.g_start_l3.val();
        self.bvi3.g_short.next = self.g_short_l3.val();
        self.bvi3.g_long.next = self.g_long_l3.val();
        self.bvi3.g_line.next = self.g_line_l3.val();
        self.bvi3.b_start.next = self.b_start_l3.val();
        self.bvi3.b_short.next = self.b_short_l3.val();
        self.bvi3.b_long.next = self.b_long_l3.val();
        self.bvi3.b_line.next = self.b_line_l3.val();
        self.bvi3.valid_in.next = self.addr.valid_l3.val();
        self.bvi3.row_start_in.next = self.addr.row_start_l3.val();
        self.bvi3.step_in.next = self.addr.step_l3.val();
        self.bvi3.carry_in.next = self.addr.carry_l3.val();
        self.x3_p1.d.next = self.addr.x_l3.val();
        self.y3_p1.d.next = self.addr.y_l3.val();
        self.done3_p1.d.next = self.addr.done_l3.val();
        self.valid_l3.next = self.bvi3.valid_out.val();
        self.x_l3.next = self.x3_p1.q.val();
        self.y_l3.next = self.y3_p1.q.val();
        self.red_l3.next = self.bvi3.red.val();
        self.green_l3.next = self.bvi3.green.val();
        self.blue_l3.next = self.bvi3.blue.val();
        self.done_l3.next = self.done3_p1.q.val();
    }
}
