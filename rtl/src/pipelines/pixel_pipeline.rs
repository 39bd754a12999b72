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

/// The lit pipeline's one text: the struct of `pixel-pipeline` or `textured-pipeline` and its
/// `update`, whose lit path (the shadow words, the vector interpolator, the depth channel,
/// lighting, BRZSSK, the power unit, the colour combine and the fragment's delays) is written
/// here once. A caller gives the fields and statements before the lit path (its event
/// source), the event the lit path takes, the ambient and diffuse weights, and `ready`.
/// `#[hdl_gen]`, `self` and the parameter's name come from the caller, so that its statements,
/// these and the functions `#[hdl_gen]` adds have one hygiene; the exported Verilog is the
/// text written out in each block.
macro_rules! lit_pipeline {
    (
        $(#[$sm:meta])*
        pub struct $name:ident(clock) as $export:literal {
            summary: $summary:literal,
            latency: $lat:expr => $lm:literal,
            multipliers: $mul:expr,
            in { $($ins:tt)* }
            $(more_out { $($mo:tt)* })?
            fields { $($front_f:tt)* }
            more_fields { $($mid_f:tt)* }
        }
        new($p:ident: &$pt:ty), lit: ($($lit:tt)*);

        impl Logic {
            $hdl_pound:tt $hdl_attr:tt
            fn update(&mut $s:ident) {
                front { $($front:tt)* }
                event {
                    before { $($before:tt)* }
                    valid [$($ev_v:tt)*] row_start [$($ev_r:tt)*] step [$($ev_s:tt)*]
                    carry [$($ev_c:tt)*] first [$($ev_f:tt)*]
                    x [$($ev_x:tt)*] y [$($ev_y:tt)*] done [$($ev_d:tt)*]
                }
                amb [$($ar:tt)*] [$($ag:tt)*] [$($ab:tt)*]
                dif [$($dr:tt)*] [$($dg:tt)*] [$($db:tt)*]
                ready [$($ready:tt)*]
            }
        }
    ) => {
        crate::hw_block! {
            $(#[$sm])*
            pub struct $name(clock) as $export {
                summary: $summary,
                latency: $lat => $lm,
                multipliers: $mul,
                in { $($ins)* }
                out {
                    ready: Bit, valid: Bit, x: Bits<12>, y: Bits<12>, z: Bits<32>,
                    red: Bits<8>, green: Bits<8>, blue: Bits<8>, done: Bit,
                    $($($mo)*)?
                }
                $($front_f)*
                pub normal: VectorInterpolator,
                pub depth: IntensityChannel,
                n_reg: [Delay<Bits<19>, NORMAL_REGISTER>; 3],
                n_valid_reg: Delay<Bit, NORMAL_REGISTER>,
                pub light: LightingUnit = LightingUnit::new(&$($lit)*.coeffs),
                pub bump: Brzssk = Brzssk::new(&$($lit)*.bump),
                x_to_bump: Delay<Bits<12>, { EVENT_TO_BRZSSK }>,
                y_to_bump: Delay<Bits<12>, { EVENT_TO_BRZSSK }>,
                pub power: PowerUnit = PowerUnit::new(&$($lit)*.power),
                pub colour: ColourCombine,
                $($mid_f)*
                ev_valid: DFF<Bit>, ev_row_start: DFF<Bit>, ev_step: DFF<Bits<2>>,
                ev_carry: DFF<Bit>, ev_first: DFF<Bit>,
                /// The accepted load and its 16 words (x, y, z planes, then depth), registered.
                ld_q: DFF<Bit>,
                sw: [DFF<Bits<32>>; 16],
                cos_phi_to_colour: Delay<Bits<16>, { PowerUnit::LATENCY }>,
                z_to_out: Delay<Bits<32>, { EVENT_TO_FRAGMENT - EVENT_REGISTER - 1 }>,
                x_to_out: Delay<Bits<12>, { EVENT_TO_FRAGMENT }>,
                y_to_out: Delay<Bits<12>, { EVENT_TO_FRAGMENT }>,
                done_to_out: Delay<Bit, { EVENT_TO_FRAGMENT }>,
            }
            new($p: &$pt);
        }

        crate::hdl_update! {
            impl Logic for $name {
                $hdl_pound $hdl_attr
                fn update(&mut $s) {
                    $($front)*
                    {
                        // Normal planes.
                        $s.ld_q.d.next = $s.accepted.val();
                        $s.sw[0].d.next = $s.x_start.val();
                        $s.sw[1].d.next = $s.x_short.val();
                        $s.sw[2].d.next = $s.x_long.val();
                        $s.sw[3].d.next = $s.x_line.val();
                        $s.sw[4].d.next = $s.y_start.val();
                        $s.sw[5].d.next = $s.y_short.val();
                        $s.sw[6].d.next = $s.y_long.val();
                        $s.sw[7].d.next = $s.y_line.val();
                        $s.sw[8].d.next = $s.z_start.val();
                        $s.sw[9].d.next = $s.z_short.val();
                        $s.sw[10].d.next = $s.z_long.val();
                        $s.sw[11].d.next = $s.z_line.val();
                        $s.sw[12].d.next = $s.d_start.val();
                        $s.sw[13].d.next = $s.d_short.val();
                        $s.sw[14].d.next = $s.d_long.val();
                        $s.sw[15].d.next = $s.d_line.val();
                        $s.normal.load.next = $s.ld_q.q.val();
                        $s.normal.x_start.next = $s.sw[0].q.val();
                        $s.normal.x_short.next = $s.sw[1].q.val();
                        $s.normal.x_long.next = $s.sw[2].q.val();
                        $s.normal.x_line.next = $s.sw[3].q.val();
                        $s.normal.y_start.next = $s.sw[4].q.val();
                        $s.normal.y_short.next = $s.sw[5].q.val();
                        $s.normal.y_long.next = $s.sw[6].q.val();
                        $s.normal.y_line.next = $s.sw[7].q.val();
                        $s.normal.z_start.next = $s.sw[8].q.val();
                        $s.normal.z_short.next = $s.sw[9].q.val();
                        $s.normal.z_long.next = $s.sw[10].q.val();
                        $s.normal.z_line.next = $s.sw[11].q.val();
                        // The event, registered (see EVENT_REGISTER).
                        $($before)*
                        $s.ev_valid.d.next = $($ev_v)*;
                        $s.ev_row_start.d.next = $($ev_r)*;
                        $s.ev_step.d.next = $($ev_s)*;
                        $s.ev_carry.d.next = $($ev_c)*;
                        $s.ev_first.d.next = $($ev_f)*;
                        $s.normal.valid_in.next = $s.ev_valid.q.val();
                        $s.normal.row_start_in.next = $s.ev_row_start.q.val();
                        $s.normal.step_in.next = $s.ev_step.q.val();
                        $s.normal.carry_in.next = $s.ev_carry.q.val();

                        // Depth plane: one more BVI channel on the same events.
                        $s.depth.load.next = $s.ld_q.q.val();
                        $s.depth.set_start.next = $s.sw[12].q.val();
                        $s.depth.set_short.next = $s.sw[13].q.val();
                        $s.depth.set_long.next = $s.sw[14].q.val();
                        $s.depth.set_line.next = $s.sw[15].q.val();
                        $s.depth.ev_first.next = $s.ev_first.q.val();
                        $s.depth.ev_row_start.next = $s.ev_row_start.q.val();
                        $s.depth.ev_carry.next = $s.ev_carry.q.val();
                        $s.depth.ev_valid.next = $s.ev_valid.q.val();

                        // Lighting: normalizer, N'·L, N'·H.
                        for k in 0..3 {
                            $s.n_reg[k].clock.next = $s.clock.val();
                        }
                        $s.n_reg[0].d.next = $s.normal.nx.val();
                        $s.n_reg[1].d.next = $s.normal.ny.val();
                        $s.n_reg[2].d.next = $s.normal.nz.val();
                        $s.n_valid_reg.d.next = $s.normal.valid_out.val();
                        $s.light.valid_in.next = $s.n_valid_reg.q.val();
                        $s.light.x.next = $s.n_reg[0].q.val();
                        $s.light.y.next = $s.n_reg[1].q.val();
                        $s.light.z.next = $s.n_reg[2].q.val();
                        $s.light.lx.next = $s.lx.val();
                        $s.light.ly.next = $s.ly.val();
                        $s.light.lz.next = $s.lz.val();
                        $s.light.hx.next = $s.hx.val();
                        $s.light.hy.next = $s.hy.val();
                        $s.light.hz.next = $s.hz.val();

                        // BRZSSK: both cosines perturbed by the pixel's code (or passed through).
                        $s.x_to_bump.d.next = $($ev_x)*;
                        $s.y_to_bump.d.next = $($ev_y)*;
                        $s.bump.valid_in.next = $s.light.valid_out.val();
                        $s.bump.cos_phi.next = $s.light.cos_phi.val();
                        $s.bump.cos_gamma.next = $s.light.cos_gamma.val();
                        $s.bump.x.next = $s.x_to_bump.q.val();
                        $s.bump.y.next = $s.y_to_bump.q.val();

                        // Specular power; cos φ waits beside it.
                        $s.power.valid_in.next = $s.bump.valid_out.val();
                        $s.power.cos_gamma.next = $s.bump.cos_gamma_out.val();
                        $s.power.n.next = $s.n.val();
                        $s.cos_phi_to_colour.d.next = $s.bump.cos_phi_out.val();

                        // Colour.
                        $s.colour.valid_in.next = $s.power.valid_out.val();
                        $s.colour.cos_phi.next = $s.cos_phi_to_colour.q.val();
                        $s.colour.spec.next = $s.power.spec.val();
                        $s.colour.amb_r.next = $($ar)*;
                        $s.colour.amb_g.next = $($ag)*;
                        $s.colour.amb_b.next = $($ab)*;
                        $s.colour.dif_r.next = $($dr)*;
                        $s.colour.dif_g.next = $($dg)*;
                        $s.colour.dif_b.next = $($db)*;
                        $s.colour.spc_r.next = $s.spc_r.val();
                        $s.colour.spc_g.next = $s.spc_g.val();
                        $s.colour.spc_b.next = $s.spc_b.val();

                        // The fragment's address, depth and triangle end travel beside it.
                        $s.z_to_out.d.next = $s.depth.word.val();
                        $s.x_to_out.d.next = $($ev_x)*;
                        $s.y_to_out.d.next = $($ev_y)*;
                        $s.done_to_out.d.next = $($ev_d)*;

                        $s.ready.next = $($ready)*;
                        $s.valid.next = $s.colour.valid_out.val();
                        $s.x.next = $s.x_to_out.q.val();
                        $s.y.next = $s.y_to_out.q.val();
                        $s.z.next = $s.z_to_out.q.val();
                        $s.red.next = $s.colour.red.val();
                        $s.green.next = $s.colour.green.val();
                        $s.blue.next = $s.colour.blue.val();
                        $s.done.next = $s.done_to_out.q.val();
                    }
                }
            }
        }
    };
}
pub(crate) use lit_pipeline;

lit_pipeline! {
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
        fields { pub addr: SubpixelAddressBlock, }
        more_fields { accepted: Signal<Local, Bit>, first: Signal<Local, Bit>, }
    }
    new(p: &PipelineParams), lit: (p);

    impl Logic {
        #[hdl_gen]
        fn update(&mut self) {
            front {
                {
                    clock!(
                        self, clock, addr, normal, depth, n_valid_reg, light, bump, x_to_bump,
                        y_to_bump, power, colour, cos_phi_to_colour, z_to_out, x_to_out, y_to_out,
                        done_to_out, ev_valid, ev_row_start, ev_step, ev_carry, ev_first, ld_q
                    );
                    for i in 0..16 {
                        self.sw[i].clock.next = self.clock.val();
                    }
                    self.addr.load.next = self.load.val();
                    self.addr.hold.next = self.hold.val();
                }
                forward addr <- address_setup_ports!;
                {
                    // Every shadow bank is written on the address block's accepted load.
                    self.accepted.next = self.load.val() & self.addr.ready.val();
                }
            }
            event {
                before {
                    self.first.next = self.addr.row_start.val() & (self.addr.step.val() == 0);
                }
                valid [self.addr.valid.val()] row_start [self.addr.row_start.val()]
                step [self.addr.step.val()] carry [self.addr.carry.val()]
                first [self.first.val()]
                x [self.addr.x.val()] y [self.addr.y.val()] done [self.addr.done.val()]
            }
            amb [self.amb_r.val()] [self.amb_g.val()] [self.amb_b.val()]
            dif [self.dif_r.val()] [self.dif_g.val()] [self.dif_b.val()]
            ready [self.addr.ready.val()]
        }
    }
}
