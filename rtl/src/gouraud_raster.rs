//! Gouraud raster pipe: the address block (SPEC §5) feeding the intensity interpolator BVI
//! (SPEC §6) — the hardware that turns one triangle's set-up into shaded pixels
//! (golden: `golden::address_block` + `golden::intensity_interpolator`, i.e. `golden::gouraud`
//! sampled along `golden::raster::walk`).
//!
//! ```text
//!  load + set-up ─► AddressBlock ─valid,row_start,step,carry─► IntensityInterpolator ─► rgb
//!                        └────────────── x, y, done ──► 1-clock delay ─────────────────► x, y, done
//! ```
//!
//! Ports: the address block's set-up inputs (same names, see `address_block`) and the BVI's
//! twelve signed Q16.16 set-up words (`r_start` … `b_line`, see `intensity_interpolator`), all
//! sampled on the one `load` strobe, which is accepted when `ready` is high. Outputs:
//! `valid`, `x`, `y` (12 bits), `red`, `green`, `blue` (8 bits, saturated), `done` (last event
//! of a triangle), `ready`. Every output is a register or a function of registers. The set-up
//! ports are declared again here, not bundled, because rust-hdl exports a top's ports only from
//! its own signal fields and would name an interface's members `bundle$field`; the forwarding
//! assignments are type-checked against the children's ports, so the widths cannot drift.
//! `x`, `y`, `done` wait `IntensityInterpolator::LATENCY` clocks (`Delay`) to meet their colour.
//!
//! Latency: load → first pixel 4 clocks (3 in the address block, 1 in the BVI). Throughput:
//! one pixel per clock along a line, no extra clock per line start, one clock per raster line
//! without pixels. Overflow and error budget: those of the two blocks (addresses exact;
//! intensities within 1 LSB of the rounded plane value).

use crate::address_block::AddressBlock;
use crate::intensity_interpolator::IntensityInterpolator;
use crate::primitives::Delay;
use crate::registry::{NoParams, RtlBlock};
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct GouraudRaster {
    pub clock: Signal<In, Clock>,
    pub load: Signal<In, Bit>,
    pub w_b0: Signal<In, Bits<12>>,
    pub w_e0: Signal<In, Bits<13>>,
    pub w_f: Signal<In, Bits<12>>,
    pub w_r: Signal<In, Bits<13>>,
    pub w_d: Signal<In, Bits<13>>,
    pub a_b0: Signal<In, Bits<12>>,
    pub a_e0: Signal<In, Bits<13>>,
    pub a_f: Signal<In, Bits<12>>,
    pub a_r: Signal<In, Bits<13>>,
    pub a_d: Signal<In, Bits<13>>,
    pub t_b0: Signal<In, Bits<12>>,
    pub t_e0: Signal<In, Bits<13>>,
    pub t_f: Signal<In, Bits<12>>,
    pub t_r: Signal<In, Bits<13>>,
    pub t_d: Signal<In, Bits<13>>,
    pub y_top: Signal<In, Bits<12>>,
    pub rows: Signal<In, Bits<12>>,
    pub y_switch: Signal<In, Bits<12>>,
    pub dir_neg: Signal<In, Bit>,
    pub r_start: Signal<In, Bits<32>>,
    pub r_short: Signal<In, Bits<32>>,
    pub r_long: Signal<In, Bits<32>>,
    pub r_line: Signal<In, Bits<32>>,
    pub g_start: Signal<In, Bits<32>>,
    pub g_short: Signal<In, Bits<32>>,
    pub g_long: Signal<In, Bits<32>>,
    pub g_line: Signal<In, Bits<32>>,
    pub b_start: Signal<In, Bits<32>>,
    pub b_short: Signal<In, Bits<32>>,
    pub b_long: Signal<In, Bits<32>>,
    pub b_line: Signal<In, Bits<32>>,

    pub ready: Signal<Out, Bit>,
    pub valid: Signal<Out, Bit>,
    pub x: Signal<Out, Bits<12>>,
    pub y: Signal<Out, Bits<12>>,
    pub red: Signal<Out, Bits<8>>,
    pub green: Signal<Out, Bits<8>>,
    pub blue: Signal<Out, Bits<8>>,
    pub done: Signal<Out, Bit>,

    pub addr: AddressBlock,
    pub bvi: IntensityInterpolator,
    // The address block's x, y, done, delayed to meet the BVI's colour of the same pixel.
    x_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
    y_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
    done_p1: Delay<Bit, { IntensityInterpolator::LATENCY }>,
}

crate::impl_dut!(GouraudRaster, clock: clock,
    inputs: [load, w_b0, w_e0, w_f, w_r, w_d, a_b0, a_e0, a_f, a_r, a_d,
             t_b0, t_e0, t_f, t_r, t_d, y_top, rows, y_switch, dir_neg,
             r_start, r_short, r_long, r_line, g_start, g_short, g_long, g_line,
             b_start, b_short, b_long, b_line],
    outputs: [ready, valid, x, y, red, green, blue, done]);

impl GouraudRaster {
    /// Clocks from the accepted `load` to the first pixel (address block + BVI).
    pub const LATENCY: usize = AddressBlock::LATENCY + IntensityInterpolator::LATENCY;
}

impl RtlBlock for GouraudRaster {
    type Params = NoParams;
    const NAME: &'static str = "gouraud-raster";
    const SUMMARY: &'static str = "Gouraud raster pipe: address block feeding the BVI (SPEC §5–6)";
    const LATENCY: usize = GouraudRaster::LATENCY;
    const LATENCY_MEANING: &'static str = "load to the first pixel, one pixel per clock";
    const MULTIPLIERS: usize = 0;
    fn build(_: &NoParams) -> Self {
        GouraudRaster::default()
    }
}

impl Logic for GouraudRaster {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, x_p1, y_p1, done_p1);
        self.addr.clock.next = self.clock.val();
        self.addr.load.next = self.load.val();
        self.addr.w_b0.next = self.w_b0.val();
        self.addr.w_e0.next = self.w_e0.val();
        self.addr.w_f.next = self.w_f.val();
        self.addr.w_r.next = self.w_r.val();
        self.addr.w_d.next = self.w_d.val();
        self.addr.a_b0.next = self.a_b0.val();
        self.addr.a_e0.next = self.a_e0.val();
        self.addr.a_f.next = self.a_f.val();
        self.addr.a_r.next = self.a_r.val();
        self.addr.a_d.next = self.a_d.val();
        self.addr.t_b0.next = self.t_b0.val();
        self.addr.t_e0.next = self.t_e0.val();
        self.addr.t_f.next = self.t_f.val();
        self.addr.t_r.next = self.t_r.val();
        self.addr.t_d.next = self.t_d.val();
        self.addr.y_top.next = self.y_top.val();
        self.addr.rows.next = self.rows.val();
        self.addr.y_switch.next = self.y_switch.val();
        self.addr.dir_neg.next = self.dir_neg.val();

        // The BVI's shadow bank is written on the same accepted load as the address block.
        self.bvi.clock.next = self.clock.val();
        self.bvi.load.next = self.load.val() & self.addr.ready.val();
        self.bvi.r_start.next = self.r_start.val();
        self.bvi.r_short.next = self.r_short.val();
        self.bvi.r_long.next = self.r_long.val();
        self.bvi.r_line.next = self.r_line.val();
        self.bvi.g_start.next = self.g_start.val();
        self.bvi.g_short.next = self.g_short.val();
        self.bvi.g_long.next = self.g_long.val();
        self.bvi.g_line.next = self.g_line.val();
        self.bvi.b_start.next = self.b_start.val();
        self.bvi.b_short.next = self.b_short.val();
        self.bvi.b_long.next = self.b_long.val();
        self.bvi.b_line.next = self.b_line.val();
        self.bvi.in_valid.next = self.addr.valid.val();
        self.bvi.in_row_start.next = self.addr.row_start.val();
        self.bvi.in_step.next = self.addr.step.val();
        self.bvi.in_carry.next = self.addr.carry.val();

        self.x_p1.d.next = self.addr.x.val();
        self.y_p1.d.next = self.addr.y.val();
        self.done_p1.d.next = self.addr.done.val();

        self.ready.next = self.addr.ready.val();
        self.valid.next = self.bvi.valid_out.val();
        self.x.next = self.x_p1.q.val();
        self.y.next = self.y_p1.q.val();
        self.red.next = self.bvi.red.val();
        self.green.next = self.bvi.green.val();
        self.blue.next = self.bvi.blue.val();
        self.done.next = self.done_p1.q.val();
    }
}
