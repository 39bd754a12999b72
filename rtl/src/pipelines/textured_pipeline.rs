//! The textured pixel pipeline (SPEC §14 with §0–§2, §5, §6): the lit pixel pipeline
//! (`pixel_pipeline`, built as `normalizer-fit`) whose diffuse colour is, per pixel, the nearest
//! texel of the division-free perspective-correct texture coordinate (`texture_coord`), read
//! from the texture memory (`texture_memory`). Golden: the `texture` method
//! (`golden::shading::texture::shade` with `Coord::Additive`): the texel takes the place of the
//! material's diffuse colour in the ambient and diffuse terms, lit per pixel as `normalizer-fit`.
//! Built `texture=quadratic` or `texture=bezier`, the texel comes instead from the §15
//! quadratic unit (`texture_quadratic`) or the §16 Bézier unit (`texture_bezier`), each line's
//! from a per-line record (golden: the `texture-quadratic` and `texture-bezier` methods,
//! `Coord::Quadratic`, `Coord::Bezier`); see "The per-line builds" below.
//!
//! ```text
//!  load ─► SubpixelAddressBlock ─event─► FIFO 1 (8) ─head─► TextureCoord ─(u, v)─► TextureMemory (4) ─texel─► Delay ─► TexelWeights (3) ─amb, dif─┐
//!            ▲ hold | FIFO 1 ≥ 7          └─taken─► FIFO 2 (8) ─pop (non-pixel, or texel shown)─► the lit path of pixel-pipeline (85) ─► ColourCombine ─► x, y, z, r, g, b
//! ```
//!
//! # How the variable-rate texel meets the fixed-latency lit path
//!
//! The texture-coordinate block takes an event only while its `ready` is high, and a pixel
//! needing more than k correction steps on an axis holds it. The address block's events go
//! into a first 8-entry FIFO (the address block is held while it has 7 or more, a function of
//! registers: at most one push a clock); the texture-coordinate block is shown the FIFO's head
//! and takes it when ready, and the event taken moves into a second 8-entry FIFO. Its head
//! leaves (`pop`) when it is not a pixel (a line start without a pixel, a lone `done`) or when
//! the texture-coordinate block shows the pixel's texel (`valid_out`): the block keeps the
//! walk's order, so the texel shown is the head's. From the pop on, the event and its texel
//! travel at fixed latencies: the event through the lit path exactly as in `pixel-pipeline`
//! (the pop takes the place of the address block's event), the texel through the memory, a
//! delay line and the weight stage, so that its weights reach the colour combine with the
//! pixel's cosines. (The first FIFO keeps the block's `ready` out of the address block's
//! `hold`: that path through two sub-blocks and back made a combinational loop at the level of
//! the exported Verilog's always blocks, which the in-process Verilator model evaluated
//! differently from Icarus and rust-hdl.)
//!
//! The interpolators' shadow banks are written on the accepted load, so a load must not come
//! before the previous triangle's first event has left the FIFO: `ready` is the address
//! block's `ready` while no accepted load waits for its triangle's start to leave the FIFO
//! (`first_wait`): its first event, or the lone `done` of a triangle without pixel centres
//! (the address block shows no first event for it; `seen_first` tells such a `done` from the
//! end of a triangle that had one). The second FIFO holds at most the pending pixel, the
//! pixel being shown and the events taken between them; 8 entries have margin (the bench's
//! twin checks that no push finds either FIFO full and that no texel is shown with a
//! non-pixel at the second one's head).
//!
//! # The per-line builds
//!
//! `texture=quadratic` puts a [`QuadWalk`], `texture=bezier` a [`BezWalk`], where the
//! texture-coordinate block's outputs are read (all three are built; constants select, and
//! synthesis drops the others). The set-up software sends, beside the triangles, one line
//! record per raster line with a pixel, in the walk's order (`line_push` with the line's
//! words: u + ½, Δ, ΔΔ and v's, the words `texture-quadratic` takes,
//! `golden::shading::texture::quadratic_line`; or the `texture-bezier` record,
//! `golden::shading::texture::bezier_line`, whose u and v lanes take the same ports and whose
//! last pixel index and X lane take `line_end`, `line_x_step`, `line_x_step2`), into a
//! 4-entry line FIFO ([`LineFifo`]) that takes a push while `line_ready` is high. Quadratic:
//! the first pixel of a line loads the unit from the FIFO's head, the next ones step it, and
//! such a first pixel waits at the first event FIFO's head while no line record is there.
//! Bézier: the unit loads the head record whenever it is ready and walks the line on its own
//! into a 4-entry texel FIFO (held while two texels wait); each pixel takes the head texel,
//! and waits while none is there. The event side, the texel's latency (2 clocks from the
//! take) and everything after are the additive build's. The `tex_e0` … `tex_v_p_long` words
//! are not read in these builds; in the additive one nothing pops the line FIFO, so line
//! records pushed there only fill it (`line_ready` then falls).
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | accepted when `ready` is high: writes the address block, every shadow bank and the texture-coordinate block's shadow set-up |
//! | address set-up (`w_b0` … `dir_neg`) | in | the sub-pixel address block's (`address_block`) |
//! | `x_start` … `z_line` | in | the normal planes, signed Q3.29 (`vector_interpolator`) |
//! | `d_start d_short d_long d_line` | in | the depth plane, signed Q16.16 pixels |
//! | `tex_e0` … `tex_v_p_long` | in | the texture-coordinate block's set-up, its ports `e0` … `v_p_long` with `tex_` before each (`texture_coord`: 48-bit two's complement words, 16-bit texels) |
//! | `lx ly lz`, `hx hy hz`, `n`, `spc_r spc_g spc_b` | in | as `pixel-pipeline` (frame and material registers; the ambient and diffuse weights come from the texel) |
//! | `ka`, `kd` | in | the material's k_a and k_d, unsigned Q1.15 (registers; k·255 < 256 so every weight fits Q8.8) |
//! | `log_w`, `log_h` | in | the texture's sides, 2^log_w × 2^log_h texels (registers, `texture_memory`) |
//! | `tex_we`, `tex_waddr` (16), `tex_wdata` (24) | in | a texel write (`texture_memory`'s `we`, `waddr`, `wdata`): load the texture before the triangles that read it |
//! | `line_push`, `line_u_start line_u_step line_u_step2 line_v_start line_v_step line_v_step2` | in | the per-line builds: a line record, its words signed Q15.32 in 48 bits (`texture_quadratic`, `texture_bezier`), taken when `line_ready` is high |
//! | `line_end` (12), `line_x_step line_x_step2` (48 each) | in | `texture=bezier`: the line's last pixel index and X's Δ(0), d (`texture_bezier`'s `end_index`, `x_step`, `x_step2`) |
//! | `hold` | in | stall the address block (no event this clock); the fragment stream gets empty clocks |
//! | `ready` | out | a `load` is accepted this clock |
//! | `valid`, `x`, `y`, `z`, `red green blue`, `done` | out | as `pixel-pipeline` |
//! | `line_ready` | out | the line FIFO takes a `line_push` this clock (a function of the registers) |
//!
//! # Texel weights (`TexelWeights`)
//! amb_c = ⌊(texel_c·ka + 2⁶) / 2⁷⌋, dif_c = ⌊(texel_c·kd + 2⁶) / 2⁷⌋: UQ8.0 × UQ1.15 →
//! UQ9.15, rounded to the colour combine's UQ8.8 weight, saturated at 2¹⁶ − 1 (never reached
//! when k·255 < 256). Two clocks of multiplier (`MulPipe`, 6 multipliers), one register on the
//! rounded weight; amb waits two more clocks (the colour combine samples it two clocks after
//! dif).
//!
//! # Latency, throughput
//! Event → fragment 88 clocks when the pixel's texel settles in its first clock (the first
//! FIFO's register 1, the texture-coordinate block 2, then the lit path's 85 from the pop),
//! load → first fragment 91.
//! The per-line builds: one fragment per clock while line records arrive ahead of their lines
//! (and, Bézier, while its unit keeps one texel a clock: 1.000 on the scenes' lines).
//! The additive build: one fragment per clock while every pixel needs at most k correction steps per axis; a pixel
//! needing q steps on its worse axis costs max(1, ⌈q/k⌉) clocks, and a line start without a
//! pixel one clock, as in the texture-coordinate block. A triangle's load waits until the
//! previous triangle's first event has left the second FIFO (4 clocks after the address
//! block showed it, if it settles at once): on the default scene this costs about 0.008
//! fragments per clock.
//!
//! # Build parameters
//! `texture` (`additive`: the §14 block, the default; `quadratic`: the §15 unit on line
//! records; `bezier`: the §16 unit on line records) and, with additive, `tex-k`
//! (1 | 2 | 4: correction steps per clock; 4 by default here, where the texture-coordinate
//! block alone defaults to 2). The lit path is
//! `pixel-pipeline`'s `coeffs=fit power=exact bump=off` (the `normalizer-fit` lighting the
//! textured methods use).
//!
//! # Overflow, error budget
//! Those of the blocks. Against the golden `texture` method: the texel is the same (the block
//! is exact on the coefficients the golden method uses); built quadratic or bezier, against
//! the golden `texture-quadratic` or `texture-bezier` method, the texel is the same too (the
//! method steps the unit's bit-exact twin on the same line words); the weights add ≤ 2⁻⁹ + 255·2⁻¹⁶ each
//! to the pipeline's colour budget; the bench and the image tests measure it (≤ 2 LSB
//! required, 1 LSB asked).
//!
//! Latency (the block's `LATENCY`): 91 clocks, load to the first fragment, one fragment per clock.

use rust_hdl::prelude::*;

use crate::core::primitives::{Delay, MulPipe, MUL_LATENCY};
use crate::core::registry::{BlockParams, Options};
use crate::pipelines::pixel_pipeline::{
    PipelineParams, EVENT_REGISTER, EVENT_TO_BRZSSK, EVENT_TO_FRAGMENT, NORMAL_REGISTER,
};
use crate::units::address_block::SubpixelAddressBlock;
use crate::units::brzssk::Brzssk;
use crate::units::colour_combine::ColourCombine;
use crate::units::intensity_interpolator::IntensityChannel;
use crate::units::lighting_unit::LightingUnit;
use crate::units::power_unit::PowerUnit;
use crate::units::texture_bezier::BezWalk;
use crate::units::texture_coord::{TexCoordParams, TextureCoord};
use crate::units::texture_memory::TextureMemory;
use crate::units::texture_quadratic::{LineFifo, QuadWalk};
use crate::units::vector_interpolator::VectorInterpolator;

/// Entries of the event FIFO (the update's loops are written for 8).
pub const EVENT_FIFO: usize = 8;

/// Clocks of the texel weight stage: the multiplier, then the rounded weight's register.
pub const WEIGHT_LATENCY: usize = MUL_LATENCY + 1;

/// Clocks from the pop to the colour combine's input (where the dif weights must be).
pub const POP_TO_COLOUR: usize = EVENT_TO_FRAGMENT - ColourCombine::LATENCY;

/// The texel's delay between the memory and the weight stage.
pub const TEXEL_DELAY: usize = POP_TO_COLOUR - TextureMemory::LATENCY - WEIGHT_LATENCY;

/// Clocks from an address event to its fragment, for a pixel whose texel settles in its first
/// clock: the first FIFO's register, the texture-coordinate block's latency, then the lit path.
pub const TEX_EVENT_TO_FRAGMENT: usize = 1 + TextureCoord::LATENCY + EVENT_TO_FRAGMENT;

/// The texture coordinate a build reads its texel with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TexCoord {
    /// `texture=additive`: the §14 block (`texture_coord`).
    #[default]
    Additive,
    /// `texture=quadratic`: the §15 unit on per-line records ([`QuadWalk`]).
    Quadratic,
    /// `texture=bezier`: the §16 unit on per-line records ([`BezWalk`]).
    Bezier,
}

impl TexCoord {
    /// The option value.
    pub fn name(self) -> &'static str {
        match self {
            TexCoord::Additive => "additive",
            TexCoord::Quadratic => "quadratic",
            TexCoord::Bezier => "bezier",
        }
    }
}

/// Build parameters: the texture coordinate and, for the additive one, its k.
#[derive(Clone, Debug, PartialEq)]
pub struct TexturedParams {
    pub coord: TexCoord,
    /// The §14 block's k (1 with the per-line coordinates, where the block is built but
    /// unread).
    pub k: TexCoordParams,
    /// The lit path's build (always `coeffs=fit power=exact bump=off`).
    pub lit: PipelineParams,
}

impl TexturedParams {
    fn lit() -> PipelineParams {
        PipelineParams::from_options(
            &Options::new()
                .with("coeffs", "fit")
                .with("power", "exact")
                .with("bump", "off"),
        )
        .expect("the normalizer-fit build")
    }
}

/// The pipeline's default k: 4, the k that keeps the default scene at 0.95 fragments per
/// clock or more (0.959; k = 2 gives 0.941, see `docs/measurements.md`).
pub const DEFAULT_K: u32 = 4;

impl Default for TexturedParams {
    fn default() -> Self {
        TexturedParams {
            coord: TexCoord::Additive,
            k: TexCoordParams { k: DEFAULT_K },
            lit: Self::lit(),
        }
    }
}

impl BlockParams for TexturedParams {
    const KEYS: &'static [&'static str] = &["texture", "tex-k"];
    /// `texture=additive|quadratic|bezier` (default additive) and, with additive,
    /// `tex-k=1|2|4` (default 4, [`DEFAULT_K`]).
    fn from_options(o: &Options) -> Result<Self, String> {
        let coord = match o.get("texture") {
            None | Some("additive") => TexCoord::Additive,
            Some("quadratic") => TexCoord::Quadratic,
            Some("bezier") => TexCoord::Bezier,
            Some(other) => {
                return Err(format!(
                    "unknown texture coordinate {other:?} (expected additive, quadratic or bezier)"
                ))
            }
        };
        let per_line = coord != TexCoord::Additive;
        let k = match o.get("tex-k") {
            Some(_) if per_line => {
                return Err(format!(
                    "tex-k sets the additive block's correction steps: it does not go with \
                     texture={}",
                    coord.name()
                ))
            }
            Some(_) => TexCoordParams::from_options(o)?,
            None if per_line => TexCoordParams { k: 1 },
            None => TexCoordParams { k: DEFAULT_K },
        };
        Ok(TexturedParams {
            coord,
            k,
            lit: Self::lit(),
        })
    }
    fn describe(&self) -> Option<String> {
        Some(match self.coord {
            TexCoord::Quadratic => {
                "texture = quadratic (SPEC §15, per-line records); lit as normalizer-fit".into()
            }
            TexCoord::Bezier => {
                "texture = bezier (SPEC §16, per-line records); lit as normalizer-fit".into()
            }
            TexCoord::Additive => format!(
                "texture = additive (SPEC §14), {}; lit as normalizer-fit",
                self.k.describe().unwrap_or_default()
            ),
        })
    }
    fn test_sets() -> Vec<Options> {
        // The default build and the per-line ones: the pipeline around the texture-coordinate
        // block does not depend on k, and every k is checked in `texture-coord`'s own sets
        // (twin, golden, Verilog); `tests/rtl_texture.rs` runs the pipeline at k = 1, 2, 4.
        vec![
            Options::new(),
            Options::new().with("texture", "quadratic"),
            Options::new().with("texture", "bezier"),
        ]
    }
}

/// The texture-coordinate block's fourteen set-up words (`texture_coord`).
#[macro_export]
macro_rules! texture_setup_ports {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [
                tex_e0: Bits<48>, tex_de_line: Bits<48>, tex_de_short: Bits<48>, tex_de_long: Bits<48>,
                tex_u_u0: Bits<16>, tex_u_w0: Bits<48>, tex_u_p_line: Bits<48>, tex_u_p_short: Bits<48>, tex_u_p_long: Bits<48>,
                tex_v_u0: Bits<16>, tex_v_w0: Bits<48>, tex_v_p_line: Bits<48>, tex_v_p_short: Bits<48>, tex_v_p_long: Bits<48>,
            ]
            $($then)*
        }
    };
}

crate::hw_block! {
    /// The texel weights: amb_c = texel_c·ka, dif_c = texel_c·kd rounded to UQ8.8 (see the
    /// module header). dif after [`WEIGHT_LATENCY`] clocks, amb two clocks after that.
    pub struct TexelWeights(clock) {
        in { red: Bits<8>, green: Bits<8>, blue: Bits<8>, ka: Bits<16>, kd: Bits<16> }
        out {
            amb_r: Bits<16>, amb_g: Bits<16>, amb_b: Bits<16>,
            dif_r: Bits<16>, dif_g: Bits<16>, dif_b: Bits<16>,
        }
        /// 0..2: texel·ka, 3..5: texel·kd.
        m: [MulPipe; 6],
        /// The rounded product (bits 7.. of product + 2⁶), 25 bits so the sum cannot wrap.
        w_rnd: [Signal<Local, Bits<32>>; 6],
        wq: [DFF<Bits<16>>; 6],
        amb_late: [Delay<Bits<16>, 2>; 3],
        half: Constant<Bits<32>> = Constant::new(64u64.into()),
        top: Constant<Bits<16>> = Constant::new(0xFFFFu64.into()),
    }
}

impl Logic for TexelWeights {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..6 {
            self.m[i].clock.next = self.clock.val();
            self.wq[i].clock.next = self.clock.val();
        }
        for c in 0..3 {
            self.amb_late[c].clock.next = self.clock.val();
        }
        self.m[0].a.next = bit_cast::<16, 8>(self.red.val());
        self.m[1].a.next = bit_cast::<16, 8>(self.green.val());
        self.m[2].a.next = bit_cast::<16, 8>(self.blue.val());
        self.m[3].a.next = bit_cast::<16, 8>(self.red.val());
        self.m[4].a.next = bit_cast::<16, 8>(self.green.val());
        self.m[5].a.next = bit_cast::<16, 8>(self.blue.val());
        for c in 0..3 {
            self.m[c].b.next = self.ka.val();
            self.m[c + 3].b.next = self.kd.val();
        }
        for i in 0..6 {
            self.w_rnd[i].next = self.m[i].p.val() + self.half.val();
            if self.w_rnd[i].val().get_bits::<9>(23).any() {
                self.wq[i].d.next = self.top.val();
            } else {
                self.wq[i].d.next = self.w_rnd[i].val().get_bits::<16>(7);
            }
        }
        for c in 0..3 {
            self.amb_late[c].d.next = self.wq[c].q.val();
        }
        self.amb_r.next = self.amb_late[0].q.val();
        self.amb_g.next = self.amb_late[1].q.val();
        self.amb_b.next = self.amb_late[2].q.val();
        self.dif_r.next = self.wq[3].q.val();
        self.dif_g.next = self.wq[4].q.val();
        self.dif_b.next = self.wq[5].q.val();
    }
}

crate::hw_block! {
    /// An event FIFO of [`EVENT_FIFO`] entries (shift register: entry 0 is the head, the
    /// entries in use a prefix). `pop` is ignored when empty; the head's fields read zero then.
    /// `nearly_full`: 7 or more entries (a function of the registers).
    pub struct EventFifo(clock) {
        in {
            push: Bit, pop: Bit,
            in_valid: Bit, in_row: Bit, in_step: Bits<2>, in_carry: Bit, in_first: Bit,
            in_done: Bit, in_x: Bits<12>, in_y: Bits<12>,
        }
        out {
            any: Bit, nearly_full: Bit,
            h_valid: Bit, h_row: Bit, h_step: Bits<2>, h_carry: Bit, h_first: Bit,
            h_done: Bit, h_x: Bits<12>, h_y: Bits<12>,
        }
        occ: [DFF<Bit>; EVENT_FIFO],
        f_valid: [DFF<Bit>; EVENT_FIFO], f_row: [DFF<Bit>; EVENT_FIFO],
        f_step: [DFF<Bits<2>>; EVENT_FIFO], f_carry: [DFF<Bit>; EVENT_FIFO],
        f_first: [DFF<Bit>; EVENT_FIFO], f_done: [DFF<Bit>; EVENT_FIFO],
        f_x: [DFF<Bits<12>>; EVENT_FIFO], f_y: [DFF<Bits<12>>; EVENT_FIFO],
        /// After the pop: entry i in use (entry i + 1 moved down, or i kept).
        kept: [Signal<Local, Bit>; EVENT_FIFO],
        /// The push lands in entry i.
        put: [Signal<Local, Bit>; EVENT_FIFO],
        go: Signal<Local, Bit>,
    }
}

impl Logic for EventFifo {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..8 {
            clock!(self, clock, occ[i], f_valid[i], f_row[i], f_step[i], f_carry[i]);
            clock!(self, clock, f_first[i], f_done[i], f_x[i], f_y[i]);
        }
        self.go.next = self.pop.val() & self.occ[0].q.val();
        for i in 0..8 {
            self.kept[i].next = self.occ[i].q.val();
        }
        for i in 0..7 {
            if self.go.val() {
                self.kept[i].next = self.occ[i + 1].q.val();
            }
        }
        if self.go.val() {
            self.kept[7].next = false;
        }
        self.put[0].next = self.push.val() & !self.kept[0].val();
        for i in 1..8 {
            self.put[i].next = self.push.val() & !self.kept[i].val() & self.kept[i - 1].val();
        }
        for i in 0..8 {
            self.occ[i].d.next = self.kept[i].val() | self.put[i].val();
            self.f_valid[i].d.next = self.f_valid[i].q.val();
            self.f_row[i].d.next = self.f_row[i].q.val();
            self.f_step[i].d.next = self.f_step[i].q.val();
            self.f_carry[i].d.next = self.f_carry[i].q.val();
            self.f_first[i].d.next = self.f_first[i].q.val();
            self.f_done[i].d.next = self.f_done[i].q.val();
            self.f_x[i].d.next = self.f_x[i].q.val();
            self.f_y[i].d.next = self.f_y[i].q.val();
        }
        for i in 0..7 {
            if self.go.val() {
                self.f_valid[i].d.next = self.f_valid[i + 1].q.val();
                self.f_row[i].d.next = self.f_row[i + 1].q.val();
                self.f_step[i].d.next = self.f_step[i + 1].q.val();
                self.f_carry[i].d.next = self.f_carry[i + 1].q.val();
                self.f_first[i].d.next = self.f_first[i + 1].q.val();
                self.f_done[i].d.next = self.f_done[i + 1].q.val();
                self.f_x[i].d.next = self.f_x[i + 1].q.val();
                self.f_y[i].d.next = self.f_y[i + 1].q.val();
            }
        }
        for i in 0..8 {
            if self.put[i].val() {
                self.f_valid[i].d.next = self.in_valid.val();
                self.f_row[i].d.next = self.in_row.val();
                self.f_step[i].d.next = self.in_step.val();
                self.f_carry[i].d.next = self.in_carry.val();
                self.f_first[i].d.next = self.in_first.val();
                self.f_done[i].d.next = self.in_done.val();
                self.f_x[i].d.next = self.in_x.val();
                self.f_y[i].d.next = self.in_y.val();
            }
        }
        self.any.next = self.occ[0].q.val();
        self.nearly_full.next = self.occ[6].q.val();
        self.h_valid.next = false;
        self.h_row.next = false;
        self.h_step.next = 0.into();
        self.h_carry.next = false;
        self.h_first.next = false;
        self.h_done.next = false;
        self.h_x.next = 0.into();
        self.h_y.next = 0.into();
        if self.occ[0].q.val() {
            self.h_valid.next = self.f_valid[0].q.val();
            self.h_row.next = self.f_row[0].q.val();
            self.h_step.next = self.f_step[0].q.val();
            self.h_carry.next = self.f_carry[0].q.val();
            self.h_first.next = self.f_first[0].q.val();
            self.h_done.next = self.f_done[0].q.val();
            self.h_x.next = self.f_x[0].q.val();
            self.h_y.next = self.f_y[0].q.val();
        }
    }
}

crate::pipelines::pixel_pipeline::lit_pipeline! {
    /// The textured pixel pipeline (see the module header).
    pub struct TexturedPipeline(clock) as "textured-pipeline" {
        summary: "one triangle's set-up in, textured lit fragments out: the lit pixel pipeline whose diffuse colour is the nearest texel of the division-free perspective-correct (u, v), read from block RAM (SPEC §14, §0–§2, §5–§6)",
        latency: SubpixelAddressBlock::LATENCY + TEX_EVENT_TO_FRAGMENT
            => "load to the first fragment, one fragment per clock while every pixel needs at most k correction steps per axis",
        multipliers: 44,
        in {
            load: Bit, address_setup_ports!, normal_setup_ports!, depth_setup_ports!,
            texture_setup_ports!,
            lx: Bits<16>, ly: Bits<16>, lz: Bits<16>, hx: Bits<16>, hy: Bits<16>, hz: Bits<16>,
            n: Bits<10>, spc_r: Bits<16>, spc_g: Bits<16>, spc_b: Bits<16>,
            ka: Bits<16>, kd: Bits<16>, log_w: Bits<4>, log_h: Bits<4>,
            tex_we: Bit, tex_waddr: Bits<16>, tex_wdata: Bits<24>,
            line_push: Bit,
            line_u_start: Bits<48>, line_u_step: Bits<48>, line_u_step2: Bits<48>,
            line_v_start: Bits<48>, line_v_step: Bits<48>, line_v_step2: Bits<48>,
            line_end: Bits<12>, line_x_step: Bits<48>, line_x_step2: Bits<48>,
            hold: Bit,
        }
        more_out { line_ready: Bit, }
        fields {
            pub addr: SubpixelAddressBlock,
            pub coord: TextureCoord = TextureCoord::new(&p.k),
            pub lines: LineFifo,
            pub quad: QuadWalk,
            pub bez: BezWalk,
            pub memory: TextureMemory,
        }
        more_fields {
            pub weights: TexelWeights,
            /// The build's coordinate: `texture=quadratic` ([`QuadWalk`]), `texture=bezier`
            /// ([`BezWalk`]), else the §14 block.
            quadratic: Constant<Bit> = Constant::new(p.coord == TexCoord::Quadratic),
            bezier: Constant<Bit> = Constant::new(p.coord == TexCoord::Bezier),
            /// The coordinate block's `ready`, `valid_out`, `u`, `v`, from the build's.
            c_ready: Signal<Local, Bit>, c_valid: Signal<Local, Bit>,
            c_u: Signal<Local, Bits<16>>, c_v: Signal<Local, Bits<16>>,
            texel_r: Delay<Bits<8>, { TEXEL_DELAY }>,
            texel_g: Delay<Bits<8>, { TEXEL_DELAY }>,
            texel_b: Delay<Bits<8>, { TEXEL_DELAY }>,
            /// The address block's events before the texture-coordinate block takes them.
            pub coord_q: EventFifo,
            /// The events taken, until their texels show (a non-pixel leaves at once).
            pub lit_q: EventFifo,
            pop: Signal<Local, Bit>,
            /// An accepted load waits for its triangle's start to leave the FIFO: its first event,
            /// or, for a triangle without one (no pixel centre inside), its lone `done`.
            first_wait: DFF<Bit>,
            /// The popped stream is inside a triangle: its first event has left, its `done` not.
            seen_first: DFF<Bit>,
            start: Signal<Local, Bit>,
            gate: Signal<Local, Bit>,
            accepted: Signal<Local, Bit>,
            /// The popped event (zero when nothing pops), as `pixel-pipeline` sees the address
            /// block's.
            p_valid: Signal<Local, Bit>, p_row: Signal<Local, Bit>, p_step: Signal<Local, Bits<2>>,
            p_carry: Signal<Local, Bit>, p_first: Signal<Local, Bit>, p_done: Signal<Local, Bit>,
            p_x: Signal<Local, Bits<12>>, p_y: Signal<Local, Bits<12>>,
        }
    }
    new(p: &TexturedParams), lit: (p.lit);

    impl Logic {
        #[hdl_gen]
        fn update(&mut self) {
            front {
                {
                    clock!(
                        self, clock, addr, coord, lines, quad, bez, memory, normal, depth, n_valid_reg, light, bump,
                        x_to_bump, y_to_bump, power, colour, weights, texel_r, texel_g, texel_b,
                        cos_phi_to_colour, z_to_out, x_to_out, y_to_out, done_to_out, ev_valid,
                        ev_row_start, ev_step, ev_carry, ev_first, ld_q, first_wait, seen_first,
                        coord_q, lit_q
                    );
                    for i in 0..16 {
                        self.sw[i].clock.next = self.clock.val();
                    }
                    // The address block, held while the texture-coordinate block cannot take
                    // an event; a load only while no accepted load waits for its first event to
                    // leave the FIFO.
                    self.gate.next = !self.first_wait.q.val();
                    self.accepted.next = self.load.val() & self.addr.ready.val() & self.gate.val();
                    self.addr.load.next = self.load.val() & self.gate.val();
                    self.addr.hold.next = self.hold.val() | self.coord_q.nearly_full.val();
                }
                forward addr <- address_setup_ports!;
                {
                    // The texture-coordinate block's set-up.
                    self.coord.load.next = self.accepted.val();
                    self.coord.e0.next = self.tex_e0.val();
                    self.coord.de_line.next = self.tex_de_line.val();
                    self.coord.de_short.next = self.tex_de_short.val();
                    self.coord.de_long.next = self.tex_de_long.val();
                    self.coord.u_u0.next = self.tex_u_u0.val();
                    self.coord.u_w0.next = self.tex_u_w0.val();
                    self.coord.u_p_line.next = self.tex_u_p_line.val();
                    self.coord.u_p_short.next = self.tex_u_p_short.val();
                    self.coord.u_p_long.next = self.tex_u_p_long.val();
                    self.coord.v_u0.next = self.tex_v_u0.val();
                    self.coord.v_w0.next = self.tex_v_w0.val();
                    self.coord.v_p_line.next = self.tex_v_p_line.val();
                    self.coord.v_p_short.next = self.tex_v_p_short.val();
                    self.coord.v_p_long.next = self.tex_v_p_long.val();
                    // The first FIFO takes every event the address block shows (held while it
                    // has 7 or more: at most one push a clock); the texture-coordinate block
                    // takes its head when ready, and the event moves into the second FIFO, whose
                    // head leaves when it is not a pixel or its texel shows.
                    self.coord_q.push.next =
                        self.addr.valid.val() | self.addr.row_start.val() | self.addr.done.val();
                    self.coord_q.in_valid.next = self.addr.valid.val();
                    self.coord_q.in_row.next = self.addr.row_start.val();
                    self.coord_q.in_step.next = self.addr.step.val();
                    self.coord_q.in_carry.next = self.addr.carry.val();
                    self.coord_q.in_first.next =
                        self.addr.row_start.val() & (self.addr.step.val() == 0);
                    self.coord_q.in_done.next = self.addr.done.val();
                    self.coord_q.in_x.next = self.addr.x.val();
                    self.coord_q.in_y.next = self.addr.y.val();
                    // The build's coordinate: the §14 block, or the §15 unit on line records.
                    // The line records, for the per-line coordinates.
                    self.lines.push.next = self.line_push.val();
                    self.lines.in_us.next = self.line_u_start.val();
                    self.lines.in_ud.next = self.line_u_step.val();
                    self.lines.in_udd.next = self.line_u_step2.val();
                    self.lines.in_vs.next = self.line_v_start.val();
                    self.lines.in_vd.next = self.line_v_step.val();
                    self.lines.in_vdd.next = self.line_v_step2.val();
                    self.lines.in_last.next = self.line_end.val();
                    self.lines.in_xd.next = self.line_x_step.val();
                    self.lines.in_xdd.next = self.line_x_step2.val();
                    self.line_ready.next = self.lines.ready.val();
                    self.quad.valid_in.next = self.coord_q.h_valid.val();
                    self.quad.row_start_in.next = self.coord_q.h_row.val();
                    self.quad.line_any.next = self.lines.any.val();
                    self.quad.us.next = self.lines.us.val();
                    self.quad.ud.next = self.lines.ud.val();
                    self.quad.udd.next = self.lines.udd.val();
                    self.quad.vs.next = self.lines.vs.val();
                    self.quad.vd.next = self.lines.vd.val();
                    self.quad.vdd.next = self.lines.vdd.val();
                    self.bez.valid_in.next = self.coord_q.h_valid.val();
                    self.bez.line_any.next = self.lines.any.val();
                    self.bez.us.next = self.lines.us.val();
                    self.bez.ud.next = self.lines.ud.val();
                    self.bez.udd.next = self.lines.udd.val();
                    self.bez.vs.next = self.lines.vs.val();
                    self.bez.vd.next = self.lines.vd.val();
                    self.bez.vdd.next = self.lines.vdd.val();
                    self.bez.last.next = self.lines.last.val();
                    self.bez.xd.next = self.lines.xd.val();
                    self.bez.xdd.next = self.lines.xdd.val();
                    self.lines.pop.next = false;
                    self.c_ready.next = self.coord.ready.val();
                    self.c_valid.next = self.coord.valid_out.val();
                    self.c_u.next = self.coord.u.val();
                    self.c_v.next = self.coord.v.val();
                    if self.quadratic.val() {
                        self.lines.pop.next = self.quad.pull.val();
                        self.c_ready.next = self.quad.ready.val();
                        self.c_valid.next = self.quad.valid_out.val();
                        self.c_u.next = self.quad.u.val();
                        self.c_v.next = self.quad.v.val();
                    }
                    if self.bezier.val() {
                        self.lines.pop.next = self.bez.pull.val();
                        self.c_ready.next = self.bez.ready.val();
                        self.c_valid.next = self.bez.valid_out.val();
                        self.c_u.next = self.bez.u.val();
                        self.c_v.next = self.bez.v.val();
                    }
                    self.coord_q.pop.next = self.c_ready.val();
                    self.coord.valid_in.next = self.coord_q.h_valid.val();
                    self.coord.row_start_in.next = self.coord_q.h_row.val();
                    self.coord.step_in.next = self.coord_q.h_step.val();
                    self.coord.carry_in.next = self.coord_q.h_carry.val();
                    self.coord.x_in.next = self.coord_q.h_x.val();
                    self.coord.y_in.next = self.coord_q.h_y.val();
                    self.coord.done_in.next = self.coord_q.h_done.val();
                    self.coord.hold.next = false;
                    self.lit_q.push.next = self.c_ready.val() & self.coord_q.any.val();
                    self.lit_q.in_valid.next = self.coord_q.h_valid.val();
                    self.lit_q.in_row.next = self.coord_q.h_row.val();
                    self.lit_q.in_step.next = self.coord_q.h_step.val();
                    self.lit_q.in_carry.next = self.coord_q.h_carry.val();
                    self.lit_q.in_first.next = self.coord_q.h_first.val();
                    self.lit_q.in_done.next = self.coord_q.h_done.val();
                    self.lit_q.in_x.next = self.coord_q.h_x.val();
                    self.lit_q.in_y.next = self.coord_q.h_y.val();
                    self.pop.next = !self.lit_q.h_valid.val() | self.c_valid.val();
                    self.lit_q.pop.next = self.pop.val();
                    // The popped event (the head is zero when the FIFO is empty).
                    self.p_valid.next = false;
                    self.p_row.next = false;
                    self.p_step.next = 0.into();
                    self.p_carry.next = false;
                    self.p_first.next = false;
                    self.p_done.next = false;
                    self.p_x.next = 0.into();
                    self.p_y.next = 0.into();
                    if self.pop.val() {
                        self.p_valid.next = self.lit_q.h_valid.val();
                        self.p_row.next = self.lit_q.h_row.val();
                        self.p_step.next = self.lit_q.h_step.val();
                        self.p_carry.next = self.lit_q.h_carry.val();
                        self.p_first.next = self.lit_q.h_first.val();
                        self.p_done.next = self.lit_q.h_done.val();
                        self.p_x.next = self.lit_q.h_x.val();
                        self.p_y.next = self.lit_q.h_y.val();
                }
                    self.start.next =
                        self.p_first.val() | (self.p_done.val() & !self.seen_first.q.val());
                    self.seen_first.d.next = self.seen_first.q.val();
                    if self.p_first.val() {
                        self.seen_first.d.next = true;
                }
                    if self.p_done.val() {
                        self.seen_first.d.next = false;
                }
                    self.first_wait.d.next = self.first_wait.q.val();
                    if self.start.val() {
                        self.first_wait.d.next = false;
                }
                    if self.accepted.val() {
                        self.first_wait.d.next = true;
                }
                    // The texel: fetched at the pop, delayed, weighted.
                    self.memory.we.next = self.tex_we.val();
                    self.memory.waddr.next = self.tex_waddr.val();
                    self.memory.wdata.next = self.tex_wdata.val();
                    self.memory.log_w.next = self.log_w.val();
                    self.memory.log_h.next = self.log_h.val();
                    self.memory.valid_in.next = self.c_valid.val();
                    self.memory.u.next = self.c_u.val();
                    self.memory.v.next = self.c_v.val();
                    self.texel_r.d.next = self.memory.red.val();
                    self.texel_g.d.next = self.memory.green.val();
                    self.texel_b.d.next = self.memory.blue.val();
                    self.weights.red.next = self.texel_r.q.val();
                    self.weights.green.next = self.texel_g.q.val();
                    self.weights.blue.next = self.texel_b.q.val();
                    self.weights.ka.next = self.ka.val();
                    self.weights.kd.next = self.kd.val();
                }
            }
            event {
                before {}
                valid [self.p_valid.val()] row_start [self.p_row.val()] step [self.p_step.val()]
                carry [self.p_carry.val()] first [self.p_first.val()]
                x [self.p_x.val()] y [self.p_y.val()] done [self.p_done.val()]
            }
            amb [self.weights.amb_r.val()] [self.weights.amb_g.val()] [self.weights.amb_b.val()]
            dif [self.weights.dif_r.val()] [self.weights.dif_g.val()] [self.weights.dif_b.val()]
            ready [self.addr.ready.val() & self.gate.val()]
        }
    }
}
