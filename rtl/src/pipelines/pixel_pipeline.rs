//! The lit pixel pipeline (SPEC §0, §1, §2, §5, §6): one triangle's set-up in, lit fragments
//! out — per-pixel normal, normalized without division or square root, Blinn-lit, the
//! specular power in hardware, TrueColor, with the fragment's depth. Golden: the `normalizer`,
//! `normalizer-fit`, `brdf-k*` and `bump` methods of `golden::methods` (which describe this
//! path), walked by `golden::raster::walk`.
//!
//! ```text
//!  load + set-up ─► SubpixelAddressBlock ─valid,row_start,step,carry─┬─► VectorInterpolator ─N─► LightingUnit ─cos φ, cos γ─► Brzssk ─cos γ'─► PowerUnit ─S─┐
//!                        │                                   │        (1)                   (11)         x, y (12) ──►  (4)   └cos φ'─► Delay(10) ─┴► ColourCombine ─► r, g, b
//!                        │                                   └─► IntensityChannel (depth z) ─► Delay(27) ──────────────────────────────────────────────────► z
//!                        └── x, y, done ─► Delay(28) ───────────────────────────────────────────────────────────────────────────────────────────────────► x, y, done
//! ```
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | accepted when `ready` is high: writes the address block and every shadow bank |
//! | address set-up (`w_b0` … `dir_neg`) | in | the sub-pixel address block's (`address_block`, 20-bit error words: vertices with 4 fraction bits, or integer ones) |
//! | `x_start` … `z_line` | in | the normal planes, signed Q3.29 words (`vector_interpolator`) |
//! | `d_start d_short d_long d_line` | in | the depth plane, signed Q16.16 words in pixels (the BVI's channel format) |
//! | `lx ly lz`, `hx hy hz` | in | unit L and H, signed Q2.14 (frame registers) |
//! | `n` | in | specular exponent, 10 bits (material register; 1..1000) |
//! | `amb_r` … `spc_b` | in | colour weights, unsigned Q8.8 (material registers, `colour_combine`) |
//! | `hold` | in | stall the address block (no event this clock; see `address_block`): the fragment stream gets empty clocks, nothing is lost or repeated |
//! | `ready` | out | the address block's: a `load` is accepted this clock |
//! | `valid` | out | a fragment this clock |
//! | `x`, `y` | out | 12-bit pixel address |
//! | `z` | out | depth, signed Q16.16 pixels (RG4 of the depth channel; smaller is nearer) |
//! | `red green blue` | out | 8 bits |
//! | `done` | out | the last event of a triangle (may come with `valid` low) |
//!
//! Frame and material registers (`lx` … `spc_b`, `n`) are plain inputs sampled as each pixel
//! passes the stage that uses them: hold them while fragments of a triangle are in flight
//! (change them only after the last `done` a set of triangles needs). `n` is carried along the
//! power unit with its pixel.
//!
//! # Latency, throughput
//! Event → fragment 85 clocks (a register on the event 1, vector interpolator 1, a register
//! on the normal 1, lighting 21, BRZSSK 7, power 50, colour 4); load → first fragment 88 (the
//! address block's 3 more). The two registers are for ECP5 timing: the interpolator's output
//! rounding feeding the normalizer's squarers was the critical path (68 MHz), and `hold`
//! gating the event into the interpolators' adders (`EVENT_REGISTER`). BRZSSK is in the path of
//! every build (passing through unless `bump=on`), so every method has the same latency. One fragment per clock along a line;
//! nothing in the pipeline stalls, so the address block is the only limit (one clock per line
//! start without pixels, as in the Gouraud pipe).
//!
//! # Build parameters
//! `coeffs` (the normalizer's set: published | fit | piecewise), `power` (exact | w4 | w8 |
//! w16) and `bump` (off | on): the `normalizer`/`normalizer-fit`/`normalizer-pw` methods are
//! `power=exact`, `brdf-kK` is `coeffs=fit power=wK`, `bump` is `coeffs=fit power=exact bump=on`.
//!
//! # Overflow, error budget
//! Those of the blocks: the normal words wrap by design (only pixel values must be in range);
//! the cosines, power and colours saturate. Depth words wrap like the BVI's: the set-up keeps
//! every vertex depth within ±2¹⁵. Against the golden method of the same name the colour is
//! within the chained budgets; the bench and the image tests measure it (≤ 2 LSB required).
//!
//! Latency (the block's `LATENCY`): 88 clocks, load to the first fragment, one fragment per clock.

use rust_hdl::prelude::*;

use crate::core::primitives::Delay;
use crate::core::registry::{BlockParams, Options, RtlBlock};
use crate::units::address_block::SubpixelAddressBlock;
use crate::units::brzssk::{Brzssk, BrzsskParams};
use crate::units::colour_combine::ColourCombine;
use crate::units::intensity_interpolator::IntensityChannel;
use crate::units::lighting_unit::LightingUnit;
use crate::units::normalizer::NormalizerCoeffs;
use crate::units::power_unit::{PowerParams, PowerUnit};
use crate::units::vector_interpolator::VectorInterpolator;

/// The register between the vector interpolator's rounded output and the lighting unit.
pub const NORMAL_REGISTER: usize = 1;

/// The register on the address block's event (valid, row start, step, carry, first) before
/// the interpolators: `hold` gates the event, so without it the hold, the gating, the
/// channels' adder select and their adders were one path (pixel-stream: 87.9 MHz on ECP5).
/// The load into the interpolators' shadow banks (and its words) is registered with it, so a
/// bank is written no earlier, relative to the copy at a triangle's first event, than without
/// the register.
pub const EVENT_REGISTER: usize = 1;

/// Clocks from an address event to its fragment.
pub const EVENT_TO_FRAGMENT: usize = EVENT_REGISTER
    + VectorInterpolator::LATENCY
    + NORMAL_REGISTER
    + LightingUnit::LATENCY
    + Brzssk::LATENCY
    + PowerUnit::LATENCY
    + ColourCombine::LATENCY;

/// Clocks from an address event to the pixel's arrival at BRZSSK (which needs its address).
pub const EVENT_TO_BRZSSK: usize =
    EVENT_REGISTER + VectorInterpolator::LATENCY + NORMAL_REGISTER + LightingUnit::LATENCY;

/// Build parameters of the pipeline: the normalizer's coefficient set and the power unit's mode.
#[derive(Clone, Debug, PartialEq)]
pub struct PipelineParams {
    pub coeffs: NormalizerCoeffs,
    pub power: PowerParams,
    /// BRZSSK perturbs (the `bump` method) or passes the cosines through.
    pub bump: BrzsskParams,
}

impl BlockParams for PipelineParams {
    const KEYS: &'static [&'static str] = &["coeffs", "power", "bump"];
    /// `coeffs` (published | fit | piecewise), `power` (exact | w4 | w8 | w16), `bump` (off |
    /// on; off by default here).
    fn from_options(o: &Options) -> Result<Self, String> {
        Ok(PipelineParams {
            coeffs: NormalizerCoeffs::from_options(o)?,
            power: PowerParams::from_options(o)?,
            bump: BrzsskParams::read(o, false)?,
        })
    }
    fn describe(&self) -> Option<String> {
        let parts: Vec<String> = [
            self.coeffs.describe(),
            self.power.describe(),
            self.bump.describe(),
        ]
        .into_iter()
        .flatten()
        .collect();
        Some(parts.join("; "))
    }
    fn test_sets() -> Vec<Options> {
        vec![
            Options::new()
                .with("coeffs", "published")
                .with("power", "exact")
                .with("bump", "off"),
            // fit is published's hardware with other constants; piecewise adds the segments.
            Options::new()
                .with("coeffs", "piecewise")
                .with("power", "w16")
                .with("bump", "on"),
        ]
    }
    fn multipliers(&self) -> Option<usize> {
        Some(
            <LightingUnit as RtlBlock>::MULTIPLIERS
                + self
                    .power
                    .multipliers()
                    .unwrap_or(<PowerUnit as RtlBlock>::MULTIPLIERS)
                + <ColourCombine as RtlBlock>::MULTIPLIERS
                + self.bump.multipliers().unwrap_or(0),
        )
    }
}

/// The depth plane's four words after `load` (signed Q16.16, the BVI channel's format).
#[macro_export]
macro_rules! depth_setup_ports {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [d_start: Bits<32>, d_short: Bits<32>, d_long: Bits<32>, d_line: Bits<32>]
            $($then)*
        }
    };
}

/// The normal planes' twelve words after `load` (signed Q3.29, `vector_interpolator`).
#[macro_export]
macro_rules! normal_setup_ports {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [
                x_start: Bits<32>, x_short: Bits<32>, x_long: Bits<32>, x_line: Bits<32>,
                y_start: Bits<32>, y_short: Bits<32>, y_long: Bits<32>, y_line: Bits<32>,
                z_start: Bits<32>, z_short: Bits<32>, z_long: Bits<32>, z_line: Bits<32>,
            ]
            $($then)*
        }
    };
}

/// The frame and material registers (L, H, n, the nine colour weights).
#[macro_export]
macro_rules! shading_registers {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [
                lx: Bits<16>, ly: Bits<16>, lz: Bits<16>,
                hx: Bits<16>, hy: Bits<16>, hz: Bits<16>,
                n: Bits<10>,
                amb_r: Bits<16>, amb_g: Bits<16>, amb_b: Bits<16>,
                dif_r: Bits<16>, dif_g: Bits<16>, dif_b: Bits<16>,
                spc_r: Bits<16>, spc_g: Bits<16>, spc_b: Bits<16>,
            ]
            $($then)*
        }
    };
}

crate::hw_block! {
    /// The lit pixel pipeline (see the module header).
    pub struct PixelPipeline(clock) as "pixel-pipeline" {
        summary: "one triangle's set-up in, lit fragments (x, y, z, r, g, b) out: address block, vector interpolator, normalizer, Blinn lighting, BRZSSK, power unit, colour combine (SPEC §0–§2, §5–§6)",
        latency: SubpixelAddressBlock::LATENCY + EVENT_TO_FRAGMENT
            => "load to the first fragment, one fragment per clock",
        multipliers: 38,
        in {
            load: Bit, address_setup_ports!, normal_setup_ports!, depth_setup_ports!,
            shading_registers!, hold: Bit,
        }
        out {
            ready: Bit, valid: Bit, x: Bits<12>, y: Bits<12>, z: Bits<32>,
            red: Bits<8>, green: Bits<8>, blue: Bits<8>, done: Bit,
        }
        pub addr: SubpixelAddressBlock,
        pub normal: VectorInterpolator,
        pub depth: IntensityChannel,
        n_reg: [Delay<Bits<19>, NORMAL_REGISTER>; 3],
        n_valid_reg: Delay<Bit, NORMAL_REGISTER>,
        pub light: LightingUnit = LightingUnit::new(&p.coeffs),
        pub bump: Brzssk = Brzssk::new(&p.bump),
        x_to_bump: Delay<Bits<12>, { EVENT_TO_BRZSSK }>,
        y_to_bump: Delay<Bits<12>, { EVENT_TO_BRZSSK }>,
        pub power: PowerUnit = PowerUnit::new(&p.power),
        pub colour: ColourCombine,
        accepted: Signal<Local, Bit>,
        first: Signal<Local, Bit>,
        ev_valid: DFF<Bit>, ev_row_start: DFF<Bit>, ev_step: DFF<Bits<2>>, ev_carry: DFF<Bit>,
        ev_first: DFF<Bit>,
        /// The accepted load and its 16 words (x, y, z planes, then depth), registered.
        ld_q: DFF<Bit>,
        sw: [DFF<Bits<32>>; 16],
        cos_phi_to_colour: Delay<Bits<16>, { PowerUnit::LATENCY }>,
        z_to_out: Delay<Bits<32>, { EVENT_TO_FRAGMENT - EVENT_REGISTER - 1 }>,
        x_to_out: Delay<Bits<12>, { EVENT_TO_FRAGMENT }>,
        y_to_out: Delay<Bits<12>, { EVENT_TO_FRAGMENT }>,
        done_to_out: Delay<Bit, { EVENT_TO_FRAGMENT }>,
    }
    new(p: &PipelineParams);
}

impl Logic for PixelPipeline {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            addr,
            normal,
            depth,
            n_valid_reg,
            light,
            bump,
            x_to_bump,
            y_to_bump,
            power,
            colour,
            cos_phi_to_colour,
            z_to_out,
            x_to_out,
            y_to_out,
            done_to_out,
            ev_valid,
            ev_row_start,
            ev_step,
            ev_carry,
            ev_first,
            ld_q
        );
        for i in 0..16 {
            self.sw[i].clock.next = self.clock.val();
        }
        self.addr.load.next = self.load.val();
        self.addr.hold.next = self.hold.val();
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
        // Every shadow bank is written on the address block's accepted load.
        self.accepted.next = self.load.val() & self.addr.ready.val();

        // Normal planes.
        self.ld_q.d.next = self.accepted.val();
        self.sw[0].d.next = self.x_start.val();
        self.sw[1].d.next = self.x_short.val();
        self.sw[2].d.next = self.x_long.val();
        self.sw[3].d.next = self.x_line.val();
        self.sw[4].d.next = self.y_start.val();
        self.sw[5].d.next = self.y_short.val();
        self.sw[6].d.next = self.y_long.val();
        self.sw[7].d.next = self.y_line.val();
        self.sw[8].d.next = self.z_start.val();
        self.sw[9].d.next = self.z_short.val();
        self.sw[10].d.next = self.z_long.val();
        self.sw[11].d.next = self.z_line.val();
        self.sw[12].d.next = self.d_start.val();
        self.sw[13].d.next = self.d_short.val();
        self.sw[14].d.next = self.d_long.val();
        self.sw[15].d.next = self.d_line.val();
        self.normal.load.next = self.ld_q.q.val();
        self.normal.x_start.next = self.sw[0].q.val();
        self.normal.x_short.next = self.sw[1].q.val();
        self.normal.x_long.next = self.sw[2].q.val();
        self.normal.x_line.next = self.sw[3].q.val();
        self.normal.y_start.next = self.sw[4].q.val();
        self.normal.y_short.next = self.sw[5].q.val();
        self.normal.y_long.next = self.sw[6].q.val();
        self.normal.y_line.next = self.sw[7].q.val();
        self.normal.z_start.next = self.sw[8].q.val();
        self.normal.z_short.next = self.sw[9].q.val();
        self.normal.z_long.next = self.sw[10].q.val();
        self.normal.z_line.next = self.sw[11].q.val();
        // The event, registered (see EVENT_REGISTER).
        self.first.next = self.addr.row_start.val() & (self.addr.step.val() == 0);
        self.ev_valid.d.next = self.addr.valid.val();
        self.ev_row_start.d.next = self.addr.row_start.val();
        self.ev_step.d.next = self.addr.step.val();
        self.ev_carry.d.next = self.addr.carry.val();
        self.ev_first.d.next = self.first.val();
        self.normal.valid_in.next = self.ev_valid.q.val();
        self.normal.row_start_in.next = self.ev_row_start.q.val();
        self.normal.step_in.next = self.ev_step.q.val();
        self.normal.carry_in.next = self.ev_carry.q.val();

        // Depth plane: one more BVI channel on the same events.
        self.depth.load.next = self.ld_q.q.val();
        self.depth.set_start.next = self.sw[12].q.val();
        self.depth.set_short.next = self.sw[13].q.val();
        self.depth.set_long.next = self.sw[14].q.val();
        self.depth.set_line.next = self.sw[15].q.val();
        self.depth.ev_first.next = self.ev_first.q.val();
        self.depth.ev_row_start.next = self.ev_row_start.q.val();
        self.depth.ev_carry.next = self.ev_carry.q.val();
        self.depth.ev_valid.next = self.ev_valid.q.val();

        // Lighting: normalizer, N'·L, N'·H.
        for k in 0..3 {
            self.n_reg[k].clock.next = self.clock.val();
        }
        self.n_reg[0].d.next = self.normal.nx.val();
        self.n_reg[1].d.next = self.normal.ny.val();
        self.n_reg[2].d.next = self.normal.nz.val();
        self.n_valid_reg.d.next = self.normal.valid_out.val();
        self.light.valid_in.next = self.n_valid_reg.q.val();
        self.light.x.next = self.n_reg[0].q.val();
        self.light.y.next = self.n_reg[1].q.val();
        self.light.z.next = self.n_reg[2].q.val();
        self.light.lx.next = self.lx.val();
        self.light.ly.next = self.ly.val();
        self.light.lz.next = self.lz.val();
        self.light.hx.next = self.hx.val();
        self.light.hy.next = self.hy.val();
        self.light.hz.next = self.hz.val();

        // BRZSSK: both cosines perturbed by the pixel's code (or passed through).
        self.x_to_bump.d.next = self.addr.x.val();
        self.y_to_bump.d.next = self.addr.y.val();
        self.bump.valid_in.next = self.light.valid_out.val();
        self.bump.cos_phi.next = self.light.cos_phi.val();
        self.bump.cos_gamma.next = self.light.cos_gamma.val();
        self.bump.x.next = self.x_to_bump.q.val();
        self.bump.y.next = self.y_to_bump.q.val();

        // Specular power; cos φ waits beside it.
        self.power.valid_in.next = self.bump.valid_out.val();
        self.power.cos_gamma.next = self.bump.cos_gamma_out.val();
        self.power.n.next = self.n.val();
        self.cos_phi_to_colour.d.next = self.bump.cos_phi_out.val();

        // Colour.
        self.colour.valid_in.next = self.power.valid_out.val();
        self.colour.cos_phi.next = self.cos_phi_to_colour.q.val();
        self.colour.spec.next = self.power.spec.val();
        self.colour.amb_r.next = self.amb_r.val();
        self.colour.amb_g.next = self.amb_g.val();
        self.colour.amb_b.next = self.amb_b.val();
        self.colour.dif_r.next = self.dif_r.val();
        self.colour.dif_g.next = self.dif_g.val();
        self.colour.dif_b.next = self.dif_b.val();
        self.colour.spc_r.next = self.spc_r.val();
        self.colour.spc_g.next = self.spc_g.val();
        self.colour.spc_b.next = self.spc_b.val();

        // The fragment's address, depth and triangle end travel beside it.
        self.z_to_out.d.next = self.depth.word.val();
        self.x_to_out.d.next = self.addr.x.val();
        self.y_to_out.d.next = self.addr.y.val();
        self.done_to_out.d.next = self.addr.done.val();

        self.ready.next = self.addr.ready.val();
        self.valid.next = self.colour.valid_out.val();
        self.x.next = self.x_to_out.q.val();
        self.y.next = self.y_to_out.q.val();
        self.z.next = self.z_to_out.q.val();
        self.red.next = self.colour.red.val();
        self.green.next = self.colour.green.val();
        self.blue.next = self.colour.blue.val();
        self.done.next = self.done_to_out.q.val();
    }
}
