//! Subdivision raster pipe (SPEC §7 with §6): the four-triangle address block feeding one
//! intensity interpolator BVI per lane, so each of the four midpoint sub-triangles of a
//! parent is Gouraud-shaded by its own BVI, four pixels per clock (golden:
//! `golden::four_triangle` for the addresses, `golden::subdivision` for the colours).
//!
//! ```text
//!  load + set-up ─► FourTriangle ─lane K: valid,row_start,step,carry─► BVI K ─► lK_red/green/blue
//!                       └──────────── lane K: x, y, done ──► 1-clock delay ──► lK_x, lK_y, lK_done
//! ```
//!
//! Two uses, the same hardware: **Gouraud through the four-triangle block** loads every lane's
//! BVI with the parent's planes (set up for the lane's own start pixel and walk), and the
//! **`subdivision` method** loads lane K with the planes through sub-triangle K's own vertex
//! intensities (the parent's vertices and the exactly lit, normalized midpoint normals).
//!
//! Ports: the four-triangle block's set-up inputs (same names, see `four_triangle`) and each
//! lane's twelve signed Q16.16 BVI words `lK_r_start` … `lK_b_line` (see
//! `intensity_interpolator`), all sampled on the one `load` strobe, accepted when `ready`;
//! `hold`, the four-triangle block's stall (a held clock shows no event on any lane, so no BVI
//! steps and the next clock shows no pixel; each lane's pixels under holds are its pixels
//! without them with empty clocks inserted; 0 in every use without a stream top).
//! Outputs per lane K: `lK_valid`, `lK_x`, `lK_y` (12 bits), `lK_red`, `lK_green`, `lK_blue`
//! (8 bits, saturated), `lK_done` (the lane's last event of the parent); and `ready`.
//!
//! Latency: load → first pixels 4 clocks (3 + 1). Throughput: up to four pixels per clock (the
//! four-triangle block's). Overflow and error budget: the BVI's (each channel within 1 LSB of
//! its rounded plane value; the Q16.16 adders wrap, harmlessly on in-range planes).

use crate::four_triangle::FourTriangle;
use crate::intensity_interpolator::IntensityInterpolator;
use crate::primitives::Delay;
use rust_hdl::prelude::*;

crate::hw_block! {
    /// The subdivision raster pipe (see the module header).
    pub struct SubdivisionRaster(clock) as "subdivision-raster" {
        summary: "four-triangle block feeding one BVI per sub-triangle: four Gouraud pixels per clock (SPEC §6–7)",
        latency: FourTriangle::LATENCY + IntensityInterpolator::LATENCY
            => "load to the first pixels, up to four pixels per clock",
        multipliers: 0,
        in {
            load: Bit,
            w_f: Bits<12>,
            w_r: Bits<13>,
            w_d: Bits<13>,
            a_f: Bits<12>,
            a_r: Bits<13>,
            a_d: Bits<13>,
            t_f: Bits<12>,
            t_r: Bits<13>,
            t_d: Bits<13>,
            l0_w_b0: Bits<12>,
            l0_w_e0: Bits<13>,
            l0_a_b0: Bits<12>,
            l0_a_e0: Bits<13>,
            l0_a_third: Bit,
            l0_t_b0: Bits<12>,
            l0_t_e0: Bits<13>,
            l0_t_adjacent: Bit,
            l0_y_top: Bits<12>,
            l0_rows: Bits<12>,
            l0_y_switch: Bits<12>,
            l0_dir_neg: Bit,
            l1_w_b0: Bits<12>,
            l1_w_e0: Bits<13>,
            l1_a_b0: Bits<12>,
            l1_a_e0: Bits<13>,
            l1_a_third: Bit,
            l1_t_b0: Bits<12>,
            l1_t_e0: Bits<13>,
            l1_t_adjacent: Bit,
            l1_y_top: Bits<12>,
            l1_rows: Bits<12>,
            l1_y_switch: Bits<12>,
            l1_dir_neg: Bit,
            l2_w_b0: Bits<12>,
            l2_w_e0: Bits<13>,
            l2_a_b0: Bits<12>,
            l2_a_e0: Bits<13>,
            l2_a_third: Bit,
            l2_t_b0: Bits<12>,
            l2_t_e0: Bits<13>,
            l2_t_adjacent: Bit,
            l2_y_top: Bits<12>,
            l2_rows: Bits<12>,
            l2_y_switch: Bits<12>,
            l2_dir_neg: Bit,
            l3_w_b0: Bits<12>,
            l3_w_e0: Bits<13>,
            l3_a_b0: Bits<12>,
            l3_a_e0: Bits<13>,
            l3_a_third: Bit,
            l3_t_b0: Bits<12>,
            l3_t_e0: Bits<13>,
            l3_t_adjacent: Bit,
            l3_y_top: Bits<12>,
            l3_rows: Bits<12>,
            l3_y_switch: Bits<12>,
            l3_dir_neg: Bit,
            l0_r_start: Bits<32>, l0_r_short: Bits<32>, l0_r_long: Bits<32>, l0_r_line: Bits<32>,
            l0_g_start: Bits<32>, l0_g_short: Bits<32>, l0_g_long: Bits<32>, l0_g_line: Bits<32>,
            l0_b_start: Bits<32>, l0_b_short: Bits<32>, l0_b_long: Bits<32>, l0_b_line: Bits<32>,
            l1_r_start: Bits<32>, l1_r_short: Bits<32>, l1_r_long: Bits<32>, l1_r_line: Bits<32>,
            l1_g_start: Bits<32>, l1_g_short: Bits<32>, l1_g_long: Bits<32>, l1_g_line: Bits<32>,
            l1_b_start: Bits<32>, l1_b_short: Bits<32>, l1_b_long: Bits<32>, l1_b_line: Bits<32>,
            l2_r_start: Bits<32>, l2_r_short: Bits<32>, l2_r_long: Bits<32>, l2_r_line: Bits<32>,
            l2_g_start: Bits<32>, l2_g_short: Bits<32>, l2_g_long: Bits<32>, l2_g_line: Bits<32>,
            l2_b_start: Bits<32>, l2_b_short: Bits<32>, l2_b_long: Bits<32>, l2_b_line: Bits<32>,
            l3_r_start: Bits<32>, l3_r_short: Bits<32>, l3_r_long: Bits<32>, l3_r_line: Bits<32>,
            l3_g_start: Bits<32>, l3_g_short: Bits<32>, l3_g_long: Bits<32>, l3_g_line: Bits<32>,
            l3_b_start: Bits<32>, l3_b_short: Bits<32>, l3_b_long: Bits<32>, l3_b_line: Bits<32>,
            hold: Bit,
        }
        out {
            ready: Bit,
            l0_valid: Bit, l0_x: Bits<12>, l0_y: Bits<12>,
            l0_red: Bits<8>, l0_green: Bits<8>, l0_blue: Bits<8>, l0_done: Bit,
            l1_valid: Bit, l1_x: Bits<12>, l1_y: Bits<12>,
            l1_red: Bits<8>, l1_green: Bits<8>, l1_blue: Bits<8>, l1_done: Bit,
            l2_valid: Bit, l2_x: Bits<12>, l2_y: Bits<12>,
            l2_red: Bits<8>, l2_green: Bits<8>, l2_blue: Bits<8>, l2_done: Bit,
            l3_valid: Bit, l3_x: Bits<12>, l3_y: Bits<12>,
            l3_red: Bits<8>, l3_green: Bits<8>, l3_blue: Bits<8>, l3_done: Bit,
        }
        pub addr: FourTriangle,
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
        self.addr.l0_w_b0.next = self.l0_w_b0.val();
        self.addr.l0_w_e0.next = self.l0_w_e0.val();
        self.addr.l0_a_b0.next = self.l0_a_b0.val();
        self.addr.l0_a_e0.next = self.l0_a_e0.val();
        self.addr.l0_a_third.next = self.l0_a_third.val();
        self.addr.l0_t_b0.next = self.l0_t_b0.val();
        self.addr.l0_t_e0.next = self.l0_t_e0.val();
        self.addr.l0_t_adjacent.next = self.l0_t_adjacent.val();
        self.addr.l0_y_top.next = self.l0_y_top.val();
        self.addr.l0_rows.next = self.l0_rows.val();
        self.addr.l0_y_switch.next = self.l0_y_switch.val();
        self.addr.l0_dir_neg.next = self.l0_dir_neg.val();
        self.addr.l1_w_b0.next = self.l1_w_b0.val();
        self.addr.l1_w_e0.next = self.l1_w_e0.val();
        self.addr.l1_a_b0.next = self.l1_a_b0.val();
        self.addr.l1_a_e0.next = self.l1_a_e0.val();
        self.addr.l1_a_third.next = self.l1_a_third.val();
        self.addr.l1_t_b0.next = self.l1_t_b0.val();
        self.addr.l1_t_e0.next = self.l1_t_e0.val();
        self.addr.l1_t_adjacent.next = self.l1_t_adjacent.val();
        self.addr.l1_y_top.next = self.l1_y_top.val();
        self.addr.l1_rows.next = self.l1_rows.val();
        self.addr.l1_y_switch.next = self.l1_y_switch.val();
        self.addr.l1_dir_neg.next = self.l1_dir_neg.val();
        self.addr.l2_w_b0.next = self.l2_w_b0.val();
        self.addr.l2_w_e0.next = self.l2_w_e0.val();
        self.addr.l2_a_b0.next = self.l2_a_b0.val();
        self.addr.l2_a_e0.next = self.l2_a_e0.val();
        self.addr.l2_a_third.next = self.l2_a_third.val();
        self.addr.l2_t_b0.next = self.l2_t_b0.val();
        self.addr.l2_t_e0.next = self.l2_t_e0.val();
        self.addr.l2_t_adjacent.next = self.l2_t_adjacent.val();
        self.addr.l2_y_top.next = self.l2_y_top.val();
        self.addr.l2_rows.next = self.l2_rows.val();
        self.addr.l2_y_switch.next = self.l2_y_switch.val();
        self.addr.l2_dir_neg.next = self.l2_dir_neg.val();
        self.addr.l3_w_b0.next = self.l3_w_b0.val();
        self.addr.l3_w_e0.next = self.l3_w_e0.val();
        self.addr.l3_a_b0.next = self.l3_a_b0.val();
        self.addr.l3_a_e0.next = self.l3_a_e0.val();
        self.addr.l3_a_third.next = self.l3_a_third.val();
        self.addr.l3_t_b0.next = self.l3_t_b0.val();
        self.addr.l3_t_e0.next = self.l3_t_e0.val();
        self.addr.l3_t_adjacent.next = self.l3_t_adjacent.val();
        self.addr.l3_y_top.next = self.l3_y_top.val();
        self.addr.l3_rows.next = self.l3_rows.val();
        self.addr.l3_y_switch.next = self.l3_y_switch.val();
        self.addr.l3_dir_neg.next = self.l3_dir_neg.val();
        self.ready.next = self.addr.ready.val();

        // Lane 0: its BVI's shadow bank is written on the accepted load.
        self.bvi0.load.next = self.load.val() & self.addr.ready.val();
        self.bvi0.r_start.next = self.l0_r_start.val();
        self.bvi0.r_short.next = self.l0_r_short.val();
        self.bvi0.r_long.next = self.l0_r_long.val();
        self.bvi0.r_line.next = self.l0_r_line.val();
        self.bvi0.g_start.next = self.l0_g_start.val();
        self.bvi0.g_short.next = self.l0_g_short.val();
        self.bvi0.g_long.next = self.l0_g_long.val();
        self.bvi0.g_line.next = self.l0_g_line.val();
        self.bvi0.b_start.next = self.l0_b_start.val();
        self.bvi0.b_short.next = self.l0_b_short.val();
        self.bvi0.b_long.next = self.l0_b_long.val();
        self.bvi0.b_line.next = self.l0_b_line.val();
        self.bvi0.in_valid.next = self.addr.l0_valid.val();
        self.bvi0.in_row_start.next = self.addr.l0_row_start.val();
        self.bvi0.in_step.next = self.addr.l0_step.val();
        self.bvi0.in_carry.next = self.addr.l0_carry.val();
        self.x0_p1.d.next = self.addr.l0_x.val();
        self.y0_p1.d.next = self.addr.l0_y.val();
        self.done0_p1.d.next = self.addr.l0_done.val();
        self.l0_valid.next = self.bvi0.valid_out.val();
        self.l0_x.next = self.x0_p1.q.val();
        self.l0_y.next = self.y0_p1.q.val();
        self.l0_red.next = self.bvi0.red.val();
        self.l0_green.next = self.bvi0.green.val();
        self.l0_blue.next = self.bvi0.blue.val();
        self.l0_done.next = self.done0_p1.q.val();

        // Lane 1: its BVI's shadow bank is written on the accepted load.
        self.bvi1.load.next = self.load.val() & self.addr.ready.val();
        self.bvi1.r_start.next = self.l1_r_start.val();
        self.bvi1.r_short.next = self.l1_r_short.val();
        self.bvi1.r_long.next = self.l1_r_long.val();
        self.bvi1.r_line.next = self.l1_r_line.val();
        self.bvi1.g_start.next = self.l1_g_start.val();
        self.bvi1.g_short.next = self.l1_g_short.val();
        self.bvi1.g_long.next = self.l1_g_long.val();
        self.bvi1.g_line.next = self.l1_g_line.val();
        self.bvi1.b_start.next = self.l1_b_start.val();
        self.bvi1.b_short.next = self.l1_b_short.val();
        self.bvi1.b_long.next = self.l1_b_long.val();
        self.bvi1.b_line.next = self.l1_b_line.val();
        self.bvi1.in_valid.next = self.addr.l1_valid.val();
        self.bvi1.in_row_start.next = self.addr.l1_row_start.val();
        self.bvi1.in_step.next = self.addr.l1_step.val();
        self.bvi1.in_carry.next = self.addr.l1_carry.val();
        self.x1_p1.d.next = self.addr.l1_x.val();
        self.y1_p1.d.next = self.addr.l1_y.val();
        self.done1_p1.d.next = self.addr.l1_done.val();
        self.l1_valid.next = self.bvi1.valid_out.val();
        self.l1_x.next = self.x1_p1.q.val();
        self.l1_y.next = self.y1_p1.q.val();
        self.l1_red.next = self.bvi1.red.val();
        self.l1_green.next = self.bvi1.green.val();
        self.l1_blue.next = self.bvi1.blue.val();
        self.l1_done.next = self.done1_p1.q.val();

        // Lane 2: its BVI's shadow bank is written on the accepted load.
        self.bvi2.load.next = self.load.val() & self.addr.ready.val();
        self.bvi2.r_start.next = self.l2_r_start.val();
        self.bvi2.r_short.next = self.l2_r_short.val();
        self.bvi2.r_long.next = self.l2_r_long.val();
        self.bvi2.r_line.next = self.l2_r_line.val();
        self.bvi2.g_start.next = self.l2_g_start.val();
        self.bvi2.g_short.next = self.l2_g_short.val();
        self.bvi2.g_long.next = self.l2_g_long.val();
        self.bvi2.g_line.next = self.l2_g_line.val();
        self.bvi2.b_start.next = self.l2_b_start.val();
        self.bvi2.b_short.next = self.l2_b_short.val();
        self.bvi2.b_long.next = self.l2_b_long.val();
        self.bvi2.b_line.next = self.l2_b_line.val();
        self.bvi2.in_valid.next = self.addr.l2_valid.val();
        self.bvi2.in_row_start.next = self.addr.l2_row_start.val();
        self.bvi2.in_step.next = self.addr.l2_step.val();
        self.bvi2.in_carry.next = self.addr.l2_carry.val();
        self.x2_p1.d.next = self.addr.l2_x.val();
        self.y2_p1.d.next = self.addr.l2_y.val();
        self.done2_p1.d.next = self.addr.l2_done.val();
        self.l2_valid.next = self.bvi2.valid_out.val();
        self.l2_x.next = self.x2_p1.q.val();
        self.l2_y.next = self.y2_p1.q.val();
        self.l2_red.next = self.bvi2.red.val();
        self.l2_green.next = self.bvi2.green.val();
        self.l2_blue.next = self.bvi2.blue.val();
        self.l2_done.next = self.done2_p1.q.val();

        // Lane 3: its BVI's shadow bank is written on the accepted load.
        self.bvi3.load.next = self.load.val() & self.addr.ready.val();
        self.bvi3.r_start.next = self.l3_r_start.val();
        self.bvi3.r_short.next = self.l3_r_short.val();
        self.bvi3.r_long.next = self.l3_r_long.val();
        self.bvi3.r_line.next = self.l3_r_line.val();
        self.bvi3.g_start.next = self.l3_g_start.val();
        self.bvi3.g_short.next = self.l3_g_short.val();
        self.bvi3.g_long.next = self.l3_g_long.val();
        self.bvi3.g_line.next = self.l3_g_line.val();
        self.bvi3.b_start.next = self.l3_b_start.val();
        self.bvi3.b_short.next = self.l3_b_short.val();
        self.bvi3.b_long.next = self.l3_b_long.val();
        self.bvi3.b_line.next = self.l3_b_line.val();
        self.bvi3.in_valid.next = self.addr.l3_valid.val();
        self.bvi3.in_row_start.next = self.addr.l3_row_start.val();
        self.bvi3.in_step.next = self.addr.l3_step.val();
        self.bvi3.in_carry.next = self.addr.l3_carry.val();
        self.x3_p1.d.next = self.addr.l3_x.val();
        self.y3_p1.d.next = self.addr.l3_y.val();
        self.done3_p1.d.next = self.addr.l3_done.val();
        self.l3_valid.next = self.bvi3.valid_out.val();
        self.l3_x.next = self.x3_p1.q.val();
        self.l3_y.next = self.y3_p1.q.val();
        self.l3_red.next = self.bvi3.red.val();
        self.l3_green.next = self.bvi3.green.val();
        self.l3_blue.next = self.bvi3.blue.val();
        self.l3_done.next = self.done3_p1.q.val();
    }
}
