//! The span pipelines (SPEC §3, §4, §0; golden: the `angular`, `fast` and `fast-fit` methods of
//! `golden::methods`): one raster line's set-up words in, lit fragments out two per clock —
//! the two span units (diffuse with L, specular with H) side by side, then the power unit and
//! the colour combine once per lane.
//!
//! ```text
//!  load + span words ─► span unit (L) ──valid, index, cos φ (lanes A, B)──┐
//!            │       └► span unit (H) ──cos γ (lanes A, B)─────────────────┤
//!            └ x0, y, dir, z0, zm, dz ─► base registers, z runs ─► Delay(U − 1) ┤
//!                                                     SpanShader: per lane PowerUnit(cos γ) + Delay(10)(cos φ)
//!                                                                 ─► ColourCombine ─► r, g, b; x, z beside
//! ```
//! Two tops: [`AngularPipeline`] (`angular-pipeline`: two cos v accumulators, U = 3) and
//! [`FastPipeline`] (`fast-pipeline`: two fast two-point units, U = 8, the 1/√(M+1) set a build
//! parameter: `inv-sqrt=chebyshev` for `fast`, `fit` for `fast-fit`). Their ports differ only in
//! the span unit's words.
//!
//! # Span front end (software)
//! The per-span set-up stays software, as the thesis has it: for each raster line of the
//! triangle walk (`golden::raster::walk`, the same line starts and lengths the address block
//! produces — `testbenches/tests/address_block.rs` proves the two equal) the exactly normalized
//! end normals, then arccos, the division and cos β (angular) or b, h, g, c, s (fast), quantized
//! to the unit's words; the depth at both ends and its step. A line whose end normal vanishes
//! loads zero words (ambient colour, as the golden method).
//!
//! # Ports (both tops)
//! | port | dir | format |
//! |---|---|---|
//! | `load` | in | a span's words this clock (taken when `ready`) |
//! | `y`, `x0` | in | the line's y and first pixel's x (12 bits) |
//! | `dir` | in | 0: pixel t is at x0 + t; 1: at x0 − t (the walk's direction) |
//! | `m` | in | pixels − 1 (12 bits) |
//! | L words, H words | in | the span unit's words for X = L and X = H (`cos_v_accumulator`, `fast_unit`) |
//! | `z0`, `zm`, `dz` | in | depth at pixel 0 and pixel m, step per pixel; signed Q16.16 pixels |
//! | `n`, `amb_r` … `spc_b` | in | material registers: exponent (10 bits), colour weights UQ8.8 |
//! | `hold` | in | 1: both span units and the depth runs stand still this clock (no pixel enters the shading, no span is taken); the stages after the units run on, so a stream top holding on its FIFO's level loses nothing |
//! | `ready` | out | the span units': a `load` now follows the current span without a gap (low while held) |
//! | `valid_a`, `x_a`, `z_a`, `red_a`, `green_a`, `blue_a` | out | lane A: pixel t = k in the span's clock k |
//! | `valid_b`, `x_b`, … `blue_b` | out | lane B: pixel m − k (when m − k > k) |
//! | `y_out` | out | the line of both lanes' pixels (`y` is taken by the input) |
//! | `done` | out | the span's last clock |
//!
//! # Latency, throughput
//! Load → first fragments: U + 54 (power 50, colour 4): 60 (angular), 68 (fast). A span of
//! m + 1 pixels takes ⌊m/2⌋ + 1 clocks and the next span's load is taken in its last clock, so
//! the pipeline adds no clock per span: two pixels per clock, one in the last clock of an
//! odd-length span (m even). A one-pixel span (m = 0) costs a whole clock for one pixel — the
//! symmetry cannot pay below two pixels; that and the per-span software set-up (one set-up per
//! ⌊m/2⌋ + 1 clocks must keep up) are the price of short spans.
//!
//! # Overflow, error budget
//! Those of the blocks: cosines, power and colours saturate; the z runs wrap like the BVI's
//! (the set-up keeps depths within ±2¹⁴). z: ≤ 2⁻¹⁷ per step from the rounded dz, ≤ 2048 steps
//! from either end: ≤ 0.0157 pixels. Colours against the golden method: the span unit's
//! bound through the power (n·cos^(n−1)·δ) and the combine's half LSB; measured ≤ 2 LSB.
//!
//! Latency (`angular-pipeline`: the block's `LATENCY`): 60 clocks, load to the first fragments, two fragments per clock.
//! Latency (`fast-pipeline`: the block's `LATENCY`): 68 clocks, load to the first fragments, two fragments per clock.

use rust_hdl::prelude::*;

use crate::core::primitives::Delay;
use crate::core::registry::{BlockParams, Options, RtlBlock};
use crate::units::colour_combine::ColourCombine;
use crate::units::cos_v_accumulator::CosVAccumulator;
use crate::units::fast_unit::{FastParams, FastUnit};
use crate::units::power_unit::{PowerParams, PowerUnit};

/// Build parameters of [`FastPipeline`]: the fast units' 1/√(M+1) set (`inv-sqrt`, as
/// `fast-unit`). The generic tests build `fit` (the `fast-fit` method) and `chebyshev`
/// (`fast`); `fast-unit` itself is tested with every set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastPipelineParams(pub FastParams);

impl BlockParams for FastPipelineParams {
    const KEYS: &'static [&'static str] = FastParams::KEYS;
    fn from_options(o: &Options) -> Result<Self, String> {
        FastParams::from_options(o).map(FastPipelineParams)
    }
    fn describe(&self) -> Option<String> {
        self.0.describe()
    }
    fn test_sets() -> Vec<Options> {
        ["fit", "chebyshev"]
            .map(|c| Options::new().with("inv-sqrt", c))
            .to_vec()
    }
}

/// Clocks from the span units' pixels to the fragments (power 50, colour 4).
pub const SHADE_LATENCY: usize = PowerUnit::LATENCY + ColourCombine::LATENCY;

/// The material registers (n, the nine colour weights).
#[macro_export]
macro_rules! material_registers {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [
                n: Bits<10>,
                amb_r: Bits<16>, amb_g: Bits<16>, amb_b: Bits<16>,
                dif_r: Bits<16>, dif_g: Bits<16>, dif_b: Bits<16>,
                spc_r: Bits<16>, spc_g: Bits<16>, spc_b: Bits<16>,
            ]
            $($then)*
        }
    };
}

/// The span's address and depth words after `load`.
#[macro_export]
macro_rules! span_base_ports {
    ($($then:tt)*) => {
        $crate::hw_bundle! {
            [y: Bits<12>, x0: Bits<12>, dir: Bit, m: Bits<12>]
            $($then)*
        }
    };
}

/// The back end both tops share: the span base (x0, y, dir, depth runs) held from the load and
/// delayed to meet the span units' pixels (`U1` = the unit's state-to-pixel latency), then per
/// lane the power unit on cos γ, cos φ delayed beside it, the colour combine. Not exported on its
/// own: its blocks are (`power-unit`, `colour-combine`), and both tops test it every clock.
#[derive(LogicBlock)]
pub struct SpanShader<const U1: usize> {
    pub clock: Signal<In, Clock>,
    /// The span's load was taken this clock (its base words are on the ports below).
    pub take: Signal<In, Bit>,
    /// The units stand still this clock (`hold`): so do the depth runs.
    pub hold: Signal<In, Bit>,
    pub x0: Signal<In, Bits<12>>,
    pub y_in: Signal<In, Bits<12>>,
    pub dir: Signal<In, Bit>,
    pub z0: Signal<In, Bits<32>>,
    pub zm: Signal<In, Bits<32>>,
    pub dz: Signal<In, Bits<32>>,
    /// The span units' lanes (L unit's flags and indices; the H unit runs the same schedule).
    pub va: Signal<In, Bit>,
    pub ta: Signal<In, Bits<12>>,
    pub cd_a: Signal<In, Bits<16>>,
    pub cs_a: Signal<In, Bits<16>>,
    pub vb: Signal<In, Bit>,
    pub tb: Signal<In, Bits<12>>,
    pub cd_b: Signal<In, Bits<16>>,
    pub cs_b: Signal<In, Bits<16>>,
    pub done_in: Signal<In, Bit>,
    pub n: Signal<In, Bits<10>>,
    /// amb r g b, dif r g b, spc r g b (UQ8.8).
    pub w: [Signal<In, Bits<16>>; 9],
    pub valid_a: Signal<Out, Bit>,
    pub x_a: Signal<Out, Bits<12>>,
    pub z_a: Signal<Out, Bits<32>>,
    pub rgb_a: [Signal<Out, Bits<8>>; 3],
    pub valid_b: Signal<Out, Bit>,
    pub x_b: Signal<Out, Bits<12>>,
    pub z_b: Signal<Out, Bits<32>>,
    pub rgb_b: [Signal<Out, Bits<8>>; 3],
    pub y: Signal<Out, Bits<12>>,
    pub done: Signal<Out, Bit>,
    // Base registers (with the units' state) and their delay to the units' pixels.
    x0_q: DFF<Bits<12>>,
    y_q: DFF<Bits<12>>,
    dir_q: DFF<Bit>,
    dz_q: DFF<Bits<32>>,
    za: DFF<Bits<32>>,
    zb: DFF<Bits<32>>,
    x0_d: Delay<Bits<12>, U1>,
    y_d: Delay<Bits<12>, U1>,
    dir_d: Delay<Bit, U1>,
    za_d: Delay<Bits<32>, U1>,
    zb_d: Delay<Bits<32>, U1>,
    // Shading per lane.
    power_a: PowerUnit,
    power_b: PowerUnit,
    cd_a_p: Delay<Bits<16>, { PowerUnit::LATENCY }>,
    cd_b_p: Delay<Bits<16>, { PowerUnit::LATENCY }>,
    colour_a: ColourCombine,
    colour_b: ColourCombine,
    xa_p: Delay<Bits<12>, SHADE_LATENCY>,
    xb_p: Delay<Bits<12>, SHADE_LATENCY>,
    za_p: Delay<Bits<32>, SHADE_LATENCY>,
    zb_p: Delay<Bits<32>, SHADE_LATENCY>,
    y_p: Delay<Bits<12>, SHADE_LATENCY>,
    last_p: Delay<Bit, SHADE_LATENCY>,
}

impl<const U1: usize> Default for SpanShader<U1> {
    fn default() -> Self {
        let power = || PowerUnit::new(&PowerParams::default());
        SpanShader {
            clock: Default::default(),
            take: Default::default(),
            hold: Default::default(),
            x0: Default::default(),
            y_in: Default::default(),
            dir: Default::default(),
            z0: Default::default(),
            zm: Default::default(),
            dz: Default::default(),
            va: Default::default(),
            ta: Default::default(),
            cd_a: Default::default(),
            cs_a: Default::default(),
            vb: Default::default(),
            tb: Default::default(),
            cd_b: Default::default(),
            cs_b: Default::default(),
            done_in: Default::default(),
            n: Default::default(),
            w: Default::default(),
            valid_a: Default::default(),
            x_a: Default::default(),
            z_a: Default::default(),
            rgb_a: Default::default(),
            valid_b: Default::default(),
            x_b: Default::default(),
            z_b: Default::default(),
            rgb_b: Default::default(),
            y: Default::default(),
            done: Default::default(),
            x0_q: Default::default(),
            y_q: Default::default(),
            dir_q: Default::default(),
            dz_q: Default::default(),
            za: Default::default(),
            zb: Default::default(),
            x0_d: Default::default(),
            y_d: Default::default(),
            dir_d: Default::default(),
            za_d: Default::default(),
            zb_d: Default::default(),
            power_a: power(),
            power_b: power(),
            cd_a_p: Default::default(),
            cd_b_p: Default::default(),
            colour_a: Default::default(),
            colour_b: Default::default(),
            xa_p: Default::default(),
            xb_p: Default::default(),
            za_p: Default::default(),
            zb_p: Default::default(),
            y_p: Default::default(),
            last_p: Default::default(),
        }
    }
}

// Lane L's colour weights are one text repeated by `seq!` (lanes `a`, `b`).
seq_macro::seq!(L in 'a'..='b' {
impl<const U1: usize> Logic for SpanShader<U1> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, x0_q, y_q, dir_q, dz_q, za, zb);
        clock!(
            self, clock, x0_d, y_d, dir_d, za_d, zb_d, power_a, power_b, cd_a_p, cd_b_p, colour_a,
            colour_b, xa_p, xb_p, za_p, zb_p, y_p, last_p
        );
        // The depth runs advance with the units' state: pixel k from the start, m − k from
        // the end (every clock but a held one; a load restarts them).
        if !self.hold.val() {
            self.za.d.next = self.za.q.val() + self.dz_q.q.val();
            self.zb.d.next = self.zb.q.val() - self.dz_q.q.val();
        }
        if self.take.val() {
            self.x0_q.d.next = self.x0.val();
            self.y_q.d.next = self.y_in.val();
            self.dir_q.d.next = self.dir.val();
            self.dz_q.d.next = self.dz.val();
            self.za.d.next = self.z0.val();
            self.zb.d.next = self.zm.val();
        }
        self.x0_d.d.next = self.x0_q.q.val();
        self.y_d.d.next = self.y_q.q.val();
        self.dir_d.d.next = self.dir_q.q.val();
        self.za_d.d.next = self.za.q.val();
        self.zb_d.d.next = self.zb.q.val();

        // Lane A.
        self.power_a.valid_in.next = self.va.val();
        self.power_a.cos_gamma.next = self.cs_a.val();
        self.power_a.n.next = self.n.val();
        self.cd_a_p.d.next = self.cd_a.val();
        self.colour_a.valid_in.next = self.power_a.valid_out.val();
        self.colour_a.cos_phi.next = self.cd_a_p.q.val();
        self.colour_a.spec.next = self.power_a.spec.val();
        // Lane B.
        self.power_b.valid_in.next = self.vb.val();
        self.power_b.cos_gamma.next = self.cs_b.val();
        self.power_b.n.next = self.n.val();
        self.cd_b_p.d.next = self.cd_b.val();
        self.colour_b.valid_in.next = self.power_b.valid_out.val();
        self.colour_b.cos_phi.next = self.cd_b_p.q.val();
        self.colour_b.spec.next = self.power_b.spec.val();
        // Weights (both lanes).
        #(
        self.colour_~L.amb_r.next = self.w[0].val();
        self.colour_~L.amb_g.next = self.w[1].val();
        self.colour_~L.amb_b.next = self.w[2].val();
        self.colour_~L.dif_r.next = self.w[3].val();
        self.colour_~L.dif_g.next = self.w[4].val();
        self.colour_~L.dif_b.next = self.w[5].val();
        self.colour_~L.spc_r.next = self.w[6].val();
        self.colour_~L.spc_g.next = self.w[7].val();
        self.colour_~L.spc_b.next = self.w[8].val();
        )*

        // Addresses: x = x0 ± index.
        if self.dir_d.q.val() {
            self.xa_p.d.next = self.x0_d.q.val() - self.ta.val();
            self.xb_p.d.next = self.x0_d.q.val() - self.tb.val();
        } else {
            self.xa_p.d.next = self.x0_d.q.val() + self.ta.val();
            self.xb_p.d.next = self.x0_d.q.val() + self.tb.val();
        }
        self.za_p.d.next = self.za_d.q.val();
        self.zb_p.d.next = self.zb_d.q.val();
        self.y_p.d.next = self.y_d.q.val();
        self.last_p.d.next = self.done_in.val();

        self.valid_a.next = self.colour_a.valid_out.val();
        self.x_a.next = self.xa_p.q.val();
        self.z_a.next = self.za_p.q.val();
        self.rgb_a[0].next = self.colour_a.red.val();
        self.rgb_a[1].next = self.colour_a.green.val();
        self.rgb_a[2].next = self.colour_a.blue.val();
        self.valid_b.next = self.colour_b.valid_out.val();
        self.x_b.next = self.xb_p.q.val();
        self.z_b.next = self.zb_p.q.val();
        self.rgb_b[0].next = self.colour_b.red.val();
        self.rgb_b[1].next = self.colour_b.green.val();
        self.rgb_b[2].next = self.colour_b.blue.val();
        self.y.next = self.y_p.q.val();
        self.done.next = self.last_p.q.val();
    }
}
});

/// Multipliers of the shared back end: two power units (exact) and two colour combines.
pub const SHADER_MULTIPLIERS: usize =
    2 * (<PowerUnit as RtlBlock>::MULTIPLIERS + <ColourCombine as RtlBlock>::MULTIPLIERS);

/// Declare a span pipeline: two span units (`unit_l` for L, `unit_h` for H) and the shared
/// back end ([`SpanShader`]). The ports are the same but for the units' own set-up words,
/// given as `unit_l`/`unit_h` port ← pipeline port pairs in port order; `lanes` names the
/// `unit_l` outputs that carry lane A's and lane B's parameter into the shader.
///
/// The whole `impl Logic` is in this macro's own text; the caller passes names only (see
/// `crate::core::declare` on hygiene).
macro_rules! span_pipeline {
    (
        $(#[$m:meta])*
        pub struct $name:ident as $block:literal {
            summary: $summary:literal,
            latency_text: $latency_text:literal,
            multipliers: $mults:expr,
            unit: $unit:ident $(= $init:expr)?,
            set_up { $($port:ident: $l:ident / $h:ident: $t:ty),* $(,)? }
            lanes: $ta:ident / $tb:ident,
        }
        $(new($arg:ident : &$pt:ty);)?
    ) => {
        crate::hw_block! {
            $(#[$m])*
            pub struct $name(clock) as $block {
                summary: $summary,
                latency: $unit::LATENCY + SHADE_LATENCY => $latency_text,
                multipliers: $mults,
                in {
                    load: Bit, span_base_ports!,
                    $($l: $t,)*
                    $($h: $t,)*
                    z0: Bits<32>, zm: Bits<32>, dz: Bits<32>,
                    material_registers!, hold: Bit,
                }
                out {
                    ready: Bit,
                    valid_a: Bit, x_a: Bits<12>, z_a: Bits<32>, red_a: Bits<8>, green_a: Bits<8>, blue_a: Bits<8>,
                    valid_b: Bit, x_b: Bits<12>, z_b: Bits<32>, red_b: Bits<8>, green_b: Bits<8>, blue_b: Bits<8>,
                    y_out: Bits<12>, done: Bit,
                }
                pub unit_l: $unit $(= $init)?,
                pub unit_h: $unit $(= $init)?,
                pub shader: SpanShader<{ $unit::LATENCY - 1 }>,
                take: Signal<Local, Bit>,
            }
            $(new($arg: &$pt);)?
        }

        impl Logic for $name {
            #[hdl_gen]
            fn update(&mut self) {
                clock!(self, clock, unit_l, unit_h, shader);
                self.take.next = self.load.val() & self.unit_l.ready.val();
                self.unit_l.hold.next = self.hold.val();
                self.unit_h.hold.next = self.hold.val();
                self.shader.hold.next = self.hold.val();
                self.unit_l.load.next = self.load.val();
                $(self.unit_l.$port.next = self.$l.val();)*
                self.unit_l.m.next = self.m.val();
                self.unit_h.load.next = self.load.val();
                $(self.unit_h.$port.next = self.$h.val();)*
                self.unit_h.m.next = self.m.val();

                self.shader.take.next = self.take.val();
                self.shader.x0.next = self.x0.val();
                self.shader.y_in.next = self.y.val();
                self.shader.dir.next = self.dir.val();
                self.shader.z0.next = self.z0.val();
                self.shader.zm.next = self.zm.val();
                self.shader.dz.next = self.dz.val();
                self.shader.va.next = self.unit_l.valid_a.val();
                self.shader.ta.next = self.unit_l.$ta.val();
                self.shader.cd_a.next = self.unit_l.cos_a.val();
                self.shader.cs_a.next = self.unit_h.cos_a.val();
                self.shader.vb.next = self.unit_l.valid_b.val();
                self.shader.tb.next = self.unit_l.$tb.val();
                self.shader.cd_b.next = self.unit_l.cos_b.val();
                self.shader.cs_b.next = self.unit_h.cos_b.val();
                self.shader.done_in.next = self.unit_l.done.val();
                self.shader.n.next = self.n.val();
                self.shader.w[0].next = self.amb_r.val();
                self.shader.w[1].next = self.amb_g.val();
                self.shader.w[2].next = self.amb_b.val();
                self.shader.w[3].next = self.dif_r.val();
                self.shader.w[4].next = self.dif_g.val();
                self.shader.w[5].next = self.dif_b.val();
                self.shader.w[6].next = self.spc_r.val();
                self.shader.w[7].next = self.spc_g.val();
                self.shader.w[8].next = self.spc_b.val();

                self.ready.next = self.unit_l.ready.val();
                self.valid_a.next = self.shader.valid_a.val();
                self.x_a.next = self.shader.x_a.val();
                self.z_a.next = self.shader.z_a.val();
                self.red_a.next = self.shader.rgb_a[0].val();
                self.green_a.next = self.shader.rgb_a[1].val();
                self.blue_a.next = self.shader.rgb_a[2].val();
                self.valid_b.next = self.shader.valid_b.val();
                self.x_b.next = self.shader.x_b.val();
                self.z_b.next = self.shader.z_b.val();
                self.red_b.next = self.shader.rgb_b[0].val();
                self.green_b.next = self.shader.rgb_b[1].val();
                self.blue_b.next = self.shader.rgb_b[2].val();
                self.y_out.next = self.shader.y.val();
                self.done.next = self.shader.done.val();
            }
        }
    };
}

span_pipeline! {
    /// The angular-interpolation span pipeline (see the module header).
    pub struct AngularPipeline as "angular-pipeline" {
        summary: "a raster line's angular set-up (ψ, Δφ, cos β for L and H) in, lit fragments out two per clock: cos v accumulators, power unit, colour combine (SPEC §4, §0)",
        latency_text: "load to the first fragments, two fragments per clock",
        multipliers: 2 * 2 + 2 * (18 + 6),
        unit: CosVAccumulator,
        set_up {
            p: lp / hp: Bits<32>, q: lq / hq: Bits<32>, d: ld / hd: Bits<32>,
            cos_beta: lcb / hcb: Bits<16>,
        }
        lanes: t / u,
    }
}

span_pipeline! {
    /// The fast two-point span pipeline (see the module header).
    pub struct FastPipeline as "fast-pipeline" {
        summary: "a raster line's fast set-up (b, h, g, c + s, 2c for L and H) in, lit fragments out two per clock: fast two-point units, power unit, colour combine (SPEC §3, §0)",
        latency_text: "load to the first fragments, two fragments per clock",
        multipliers: 2 * 4 + 2 * (18 + 6),
        unit: FastUnit = FastUnit::new(&p.0),
        set_up {
            b: lb / hb: Bits<32>, h: lh / hh: Bits<32>, g: lg / hg: Bits<32>,
            d0: ld0 / hd0: Bits<48>, dd: ldd / hdd: Bits<48>,
        }
        lanes: x_a / x_b,
    }
    new(p: &FastPipelineParams);
}
