//! The cubic span pipeline (SPEC §9, §0; golden: the `cubic` method of `golden::methods`): one
//! raster line's four samples per colour channel in, lit fragments out — three Horner units
//! (R, G, B) side by side, the line's base and depth beside them.
//!
//! ```text
//!  load + samples ─► HornerUnit (R) ─valid, t, red──┐
//!             │   └► HornerUnit (G) ─green──────────┤
//!             │   └► HornerUnit (B) ─blue───────────┼─► output register: x = x0 ± t, z run, r, g, b
//!             └ x0, y, dir, z0, dz ─► base registers ─► Delay(3) ┘
//! ```
//! The per-line set-up is software, as the thesis has it: for each raster line of the walk the
//! exactly lit intensities at p = 0, 1, ½, ¼ (`golden::shading::cubic::span_samples`), quantized to the
//! unit's Q11.5 sample words, and round(2²⁷/m). The coefficients A..D are formed in hardware
//! (each unit's shift-and-add block). The Horner variant is a build parameter
//! (`horner=serial|pipelined`), the same for the three units.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a line's words (taken when `ready`) |
//! | `y`, `x0`, `dir`, `m` | in | the line: y, first pixel's x, 1 = leftward (x0 − t), pixels − 1 |
//! | `step` | in | round(2²⁷/m), UQ1.27 (28 bits) |
//! | `r1` … `r4`, `g1` … `g4`, `b1` … `b4` | in | I(0), I(1), I(½), I(¼) per channel, signed Q11.5 |
//! | `z0`, `dz` | in | depth at pixel 0 and per pixel step, signed Q16.16 pixels |
//! | `hold` | in | back-pressure from a stream top, to the three units: no pixel enters them this clock, the walk does not move on, no line is taken (see `horner_unit`); pixels already issued run on |
//! | `ready` | out | the units': a `load` now follows the current line without a gap |
//! | `valid`, `x`, `z`, `red`, `green`, `blue` | out | one fragment |
//! | `y_out`, `done` | out | its line; the line's last pixel |
//!
//! # Latency, throughput
//! Load → first fragment 15 clocks (the units' 14, the output register 1; 5 before the serial
//! unit's MUL–Sm loop was split into four registers). Serial: 3 clocks per pixel, and an idle
//! pipeline takes a line every third clock (the units' free-running phase); pipelined: one
//! pixel per clock. Lines follow without a gap (0 clocks per line).
//!
//! Under `hold` (0 in every use without a stream top) the depth run needs no freezing: it
//! advances on the units' output pixels, which come in order whatever the holds; a line's base
//! is taken only with the line (`ready` is low under `hold`), at least as late as without holds
//! after its previous line's last pixel, so the delayed base still meets its first pixel.
//!
//! # Overflow, error budget
//! The units': nothing wraps, the colours saturate. Depth: the z run adds dz per pixel from z0
//! (≤ 4095 additions, ≤ 2⁻¹⁷ each: ≤ 0.032 pixels), wrapping like the BVI's (the set-up
//! keeps depths within ±2¹⁴). Colours against the golden `cubic`: the units' bound
//! (`golden::units::horner_unit::HornerWords::error_bound`) plus the sample words' rounding (2⁻⁶ LSB
//! each, through the cubic's weights).
//!
//! Latency (the block's `LATENCY`): 15 clocks, load to the first fragment; serial 3 clocks per pixel, pipelined 1.

use rust_hdl::prelude::*;

use crate::core::primitives::Delay;
use crate::core::registry::{BlockParams, Options, RtlBlock};
use crate::units::horner_unit::{HornerParams, HornerUnit};

/// Build parameters of [`CubicPipeline`]: the three units' Horner variant (`horner`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct CubicParams(pub HornerParams);

impl BlockParams for CubicParams {
    const KEYS: &'static [&'static str] = HornerParams::KEYS;
    fn from_options(o: &Options) -> Result<Self, String> {
        HornerParams::from_options(o).map(CubicParams)
    }
    fn describe(&self) -> Option<String> {
        self.0.describe()
    }
    fn test_sets() -> Vec<Options> {
        HornerParams::test_sets()
    }
    /// Three units: serial 6, pipelined 18.
    fn multipliers(&self) -> Option<usize> {
        self.0.multipliers().map(|m| 3 * m)
    }
}

/// Clocks from a load to the base registers' delayed copy meeting the units' first pixel.
const BASE_DELAY: usize = <HornerUnit as RtlBlock>::LATENCY - 1;

crate::hw_block! {
    /// The cubic span pipeline (see the module header).
    pub struct CubicPipeline(clock) as "cubic-pipeline" {
        summary: "a raster line's four samples per channel in, cubic-shaded fragments out: three Horner units (fig. 2.6 serial, or pipelined), depth run (SPEC §9, §0)",
        latency: <HornerUnit as RtlBlock>::LATENCY + 1
            => "load to the first fragment; serial 3 clocks per pixel, pipelined 1",
        multipliers: 6,
        in {
            load: Bit, span_base_ports!, step: Bits<28>,
            r1: Bits<16>, r2: Bits<16>, r3: Bits<16>, r4: Bits<16>,
            g1: Bits<16>, g2: Bits<16>, g3: Bits<16>, g4: Bits<16>,
            b1: Bits<16>, b2: Bits<16>, b3: Bits<16>, b4: Bits<16>,
            z0: Bits<32>, dz: Bits<32>, hold: Bit,
        }
        out {
            ready: Bit, valid: Bit, x: Bits<12>, z: Bits<32>,
            red: Bits<8>, green: Bits<8>, blue: Bits<8>, y_out: Bits<12>, done: Bit,
        }
        pub unit_r: HornerUnit = HornerUnit::new(&p.0),
        pub unit_g: HornerUnit = HornerUnit::new(&p.0),
        pub unit_b: HornerUnit = HornerUnit::new(&p.0),
        take: Signal<Local, Bit>,
        x0_q: DFF<Bits<12>>, y_q: DFF<Bits<12>>, dir_q: DFF<Bit>, z0_q: DFF<Bits<32>>, dz_q: DFF<Bits<32>>,
        x0_d: Delay<Bits<12>, BASE_DELAY>, y_d: Delay<Bits<12>, BASE_DELAY>, dir_d: Delay<Bit, BASE_DELAY>,
        z0_d: Delay<Bits<32>, BASE_DELAY>, dz_d: Delay<Bits<32>, BASE_DELAY>,
        o_v: DFF<Bit>, o_x: DFF<Bits<12>>, o_z: DFF<Bits<32>>, o_r: DFF<Bits<8>>, o_g: DFF<Bits<8>>,
        o_b: DFF<Bits<8>>, o_y: DFF<Bits<12>>, o_l: DFF<Bit>,
    }
    new(p: &CubicParams);
}

impl Logic for CubicPipeline {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, x0_q, y_q, dir_q, z0_q, dz_q, o_z);
        clock!(
            self, clock, unit_r, unit_g, unit_b, x0_d, y_d, dir_d, z0_d, dz_d, o_v, o_x, o_r, o_g,
            o_b, o_y, o_l
        );
        self.take.next = self.load.val() & self.unit_r.ready.val();
        self.unit_r.load.next = self.load.val();
        self.unit_r.i1.next = self.r1.val();
        self.unit_r.i2.next = self.r2.val();
        self.unit_r.i3.next = self.r3.val();
        self.unit_r.i4.next = self.r4.val();
        self.unit_r.step.next = self.step.val();
        self.unit_r.m.next = self.m.val();
        self.unit_r.hold.next = self.hold.val();
        self.unit_g.load.next = self.load.val();
        self.unit_g.i1.next = self.g1.val();
        self.unit_g.i2.next = self.g2.val();
        self.unit_g.i3.next = self.g3.val();
        self.unit_g.i4.next = self.g4.val();
        self.unit_g.step.next = self.step.val();
        self.unit_g.m.next = self.m.val();
        self.unit_g.hold.next = self.hold.val();
        self.unit_b.load.next = self.load.val();
        self.unit_b.i1.next = self.b1.val();
        self.unit_b.i2.next = self.b2.val();
        self.unit_b.i3.next = self.b3.val();
        self.unit_b.i4.next = self.b4.val();
        self.unit_b.step.next = self.step.val();
        self.unit_b.m.next = self.m.val();
        self.unit_b.hold.next = self.hold.val();

        // The line's base, held from its load, delayed to meet its first pixel.
        if self.take.val() {
            self.x0_q.d.next = self.x0.val();
            self.y_q.d.next = self.y.val();
            self.dir_q.d.next = self.dir.val();
            self.z0_q.d.next = self.z0.val();
            self.dz_q.d.next = self.dz.val();
        }
        self.x0_d.d.next = self.x0_q.q.val();
        self.y_d.d.next = self.y_q.q.val();
        self.dir_d.d.next = self.dir_q.q.val();
        self.z0_d.d.next = self.z0_q.q.val();
        self.dz_d.d.next = self.dz_q.q.val();

        // Output register: x = x0 ± t; z from z0 by dz per pixel (pixels come in order).
        self.o_v.d.next = self.unit_r.valid.val();
        if self.dir_d.q.val() {
            self.o_x.d.next = self.x0_d.q.val() - self.unit_r.t.val();
        } else {
            self.o_x.d.next = self.x0_d.q.val() + self.unit_r.t.val();
        }
        if self.unit_r.valid.val() {
            if self.unit_r.t.val() == 0 {
                self.o_z.d.next = self.z0_d.q.val();
            } else {
                self.o_z.d.next = self.o_z.q.val() + self.dz_d.q.val();
            }
        }
        self.o_r.d.next = self.unit_r.value.val();
        self.o_g.d.next = self.unit_g.value.val();
        self.o_b.d.next = self.unit_b.value.val();
        self.o_y.d.next = self.y_d.q.val();
        self.o_l.d.next = self.unit_r.done.val();

        self.ready.next = self.unit_r.ready.val();
        self.valid.next = self.o_v.q.val();
        self.x.next = self.o_x.q.val();
        self.z.next = self.o_z.q.val();
        self.red.next = self.o_r.q.val();
        self.green.next = self.o_g.q.val();
        self.blue.next = self.o_b.q.val();
        self.y_out.next = self.o_y.q.val();
        self.done.next = self.o_l.q.val();
    }
}
