//! Gouraud raster pipe: the address block (SPEC §5) feeding the intensity interpolator BVI
//! (SPEC §6) — the hardware that turns one triangle's set-up into shaded pixels
//! (golden: `golden::units::address_block` + `golden::units::intensity_interpolator`, i.e. `golden::shading::gouraud`
//! sampled along `golden::raster::walk`).
//!
//! ```text
//!  load + set-up ─► SubpixelAddressBlock ─valid,row_start,step,carry─► IntensityInterpolator ─► rgb
//!                        └────────────── x, y, done ──► 1-clock delay ─────────────────► x, y, done
//! ```
//!
//! Ports: the sub-pixel address block's set-up inputs (same names, see `address_block`; 20-bit
//! error words, so vertices with 4 fraction bits or integer ones) and the BVI's
//! twelve signed Q16.16 set-up words (`r_start` … `b_line`, see `intensity_interpolator`), all
//! sampled on the one `load` strobe, which is accepted when `ready` is high, and `hold` (the
//! address block's: no event in a clock with `hold` high, none lost; `gouraud-stream` holds
//! the walk while its fragment FIFO fills; 0 for a free-running pipe). Outputs:
//! `valid`, `x`, `y` (12 bits), `red`, `green`, `blue` (8 bits, saturated), `done` (last event
//! of a triangle), `ready`. Every output is a register or a function of registers. The set-up
//! ports are the children's own port bundles (`address_setup_ports!`,
//! `intensity_setup_ports!`, see `crate::core::declare`), so their names and widths are written
//! once; rust-hdl exports a top's ports only from its own signal fields, so they are fields
//! here too, forwarded one by one in `update()` (type-checked against the children's ports).
//! `x`, `y`, `done` wait `IntensityInterpolator::LATENCY` clocks (`Delay`) to meet their colour.
//!
//! Latency: load → first pixel 4 clocks (3 in the address block, 1 in the BVI). Throughput:
//! one pixel per clock along a line, no extra clock per line start, one clock per raster line
//! without pixels. Overflow and error budget: those of the two blocks (addresses exact;
//! intensities within 1 LSB of the rounded plane value).

use crate::core::primitives::Delay;
use crate::units::address_block::SubpixelAddressBlock;
use crate::units::intensity_interpolator::IntensityInterpolator;
use rust_hdl::prelude::*;

crate::hw_block! {
    /// The Gouraud raster pipe: address block + BVI (see the module header).
    pub struct GouraudRaster(clock) as "gouraud-raster" {
        summary: "Gouraud raster pipe: address block feeding the BVI (SPEC §5–6)",
        latency: SubpixelAddressBlock::LATENCY + IntensityInterpolator::LATENCY
            => "load to the first pixel, one pixel per clock",
        multipliers: 0,
        in { load: Bit, address_setup_ports!, intensity_setup_ports!, hold: Bit }
        out {
            ready: Bit, valid: Bit, x: Bits<12>, y: Bits<12>,
            red: Bits<8>, green: Bits<8>, blue: Bits<8>, done: Bit,
        }
        pub addr: SubpixelAddressBlock,
        pub bvi: IntensityInterpolator,
        // The address block's x, y, done, delayed to meet the BVI's colour of the same pixel.
        x_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        y_p1: Delay<Bits<12>, { IntensityInterpolator::LATENCY }>,
        done_p1: Delay<Bit, { IntensityInterpolator::LATENCY }>,
    }
}

crate::hdl_update! {
    impl Logic for GouraudRaster {
        #[hdl_gen]
        fn update(&mut self) {
            {
                clock!(self, clock, addr, bvi, x_p1, y_p1, done_p1);
                self.addr.load.next = self.load.val();
                self.addr.hold.next = self.hold.val();
            }
            forward addr <- address_setup_ports!;
            {
                // The BVI's shadow bank is written on the same accepted load as the address
                // block.
                self.bvi.load.next = self.load.val() & self.addr.ready.val();
            }
            forward bvi <- intensity_setup_ports!;
            {
                self.bvi.valid_in.next = self.addr.valid.val();
                self.bvi.row_start_in.next = self.addr.row_start.val();
                self.bvi.step_in.next = self.addr.step.val();
                self.bvi.carry_in.next = self.addr.carry.val();

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
    }
}
