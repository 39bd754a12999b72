//! Bench of the texture-coordinate block (`rtl::units::texture_coord`) against the exact
//! quotient of its coefficients and its bit-exact twin
//! (`golden::units::texture_coord::block::TexCoordModel`).
//!
//! # Stimulus
//!
//! Seeded perspective triangles (depth ratio up to 8 between vertices; texel spread from 0.3
//! to 20 texels per pixel, so both magnification and minification beyond k steps), walked by
//! the golden address block whose `hold` is the block's `ready` (the system the block is built
//! for), each triangle's set-up loaded with the address block's accepted load once the previous
//! triangle's first event has been taken; `hold` high in a seeded tenth of the clocks. Every fifth triangle is affine with N/D on half
//! texels at many pixels (the tie rule). Edge rows: random words and events on every input,
//! in and out of the block's domain, for the twin.
//!
//! # Tolerances (from the formats)
//!
//! - `ready`, `valid_out`, `done_out`: the cycle model's (exact).
//! - `u`, `v`: within ½ texel of N/D in f64 (a nearest texel, signed Q16.0). That they are the
//!   nearest texel exactly is checked by `golden/tests/texture_block.rs` (the twin against a
//!   division) and here by the twin every clock.
//! - `x`, `y`: the address block's pixel, in walk order (exact).

use golden::raster;
use golden::types::{ScreenTriangle, ScreenVertex};
use golden::units::address_block::{AddressBlockModel, AddressSetup};
use golden::units::texture_coord::block::{
    texel_word, walk_geometry, TexCoordModel, TexCoordSetup, TexEvent, TexOutputs, SETUP_PORTS,
};
use golden::units::texture_coord::{exact_u, tie_coeffs, PctCoeffs, PctPlanes};
use rtl::core::fixed::QFormat;
use rtl::units::texture_coord::{TexCoordParams, TextureCoord};

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use golden::testing::Rng;

/// One triangle of the stimulus.
pub struct TexTriangle {
    pub addr: AddressSetup,
    pub setup: TexCoordSetup,
    pub cu: PctCoeffs,
    pub cv: PctCoeffs,
    pub origin: (i64, i64),
}

/// `n` seeded triangles in the block's range (see the module doc).
pub fn tex_triangles(seed: u64, n: usize) -> Vec<TexTriangle> {
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    while out.len() < n {
        let size = [3, 12, 40, 120][rng.below(4) as usize];
        let (x0, y0) = (rng.below(3900), rng.below(3900));
        let v = [0; 3].map(|_| (x0 + rng.below(size), y0 + rng.below(size)));
        let tri = ScreenTriangle {
            v: v.map(|(x, y)| ScreenVertex::at(x, y)),
            frac: 0,
        };
        let addr = AddressSetup::new(&tri);
        let ratio: f64 = [1.2, 2.0, 8.0][rng.below(3) as usize];
        let w = [0; 3].map(|_| (rng.unit() * ratio.ln()).exp());
        let spread = [0.3, 1.0, 4.0, 20.0][rng.below(4) as usize] * size as f64;
        let st = [0; 3].map(|_| ((rng.unit() - 0.5) * spread, (rng.unit() - 0.5) * spread));
        let Some(planes) = PctPlanes::new(v.map(|(x, y)| (x as f64, y as f64)), w, st) else {
            continue;
        };
        let (origin, f, dir) = walk_geometry(&addr);
        let vmax = w.iter().map(|w| 1.0 / w).fold(0.0, f64::max);
        let (mut cu, mut cv) = planes.coeffs(origin, vmax, (1u64 << 29) as f64);
        if out.len() % 5 == 4 {
            // Ties: u = x/2 − y/4 and v = 3y/4 + x/2 exactly (D constant), so N/D lands on
            // half texels at many pixels and the tie rule (up) decides.
            (cu, cv) = tie_coeffs();
        }
        let rel: Vec<(i64, i64)> = raster::walk(&tri)
            .pixels()
            .iter()
            .map(|p| (p.x as i64 - origin.0, p.y as i64 - origin.1))
            .collect();
        if TexCoordSetup::check(&cu, &cv, &rel).is_err() {
            continue;
        }
        let setup = TexCoordSetup::new(&cu, &cv, f, dir);
        out.push(TexTriangle {
            addr,
            setup,
            cu,
            cv,
            origin,
        });
    }
    out
}

/// One input row: `load` and the set-up words, then the event, then `hold`.
pub fn tex_row(load: Option<&TexCoordSetup>, ev: &TexEvent, hold: bool) -> Vec<u64> {
    let mut r = vec![load.is_some() as u64];
    r.extend(load.map_or(vec![0; SETUP_PORTS], |s| s.ports()));
    r.extend([
        ev.valid as u64,
        ev.row_start as u64,
        ev.step as u64,
        ev.carry as u64,
        ev.x as u64,
        ev.y as u64,
        ev.done as u64,
        hold as u64,
    ]);
    r
}

fn row_event(r: &[u64]) -> TexEvent {
    let e = &r[1 + SETUP_PORTS..];
    TexEvent {
        valid: e[0] & 1 != 0,
        row_start: e[1] & 1 != 0,
        step: (e[2] & 3) as u8,
        carry: e[3] & 1 != 0,
        x: (e[4] & 0xFFF) as u32,
        y: (e[5] & 0xFFF) as u32,
        done: e[6] & 1 != 0,
    }
}

fn out_row(o: &TexOutputs) -> Vec<u64> {
    vec![
        o.ready as u64,
        o.valid as u64,
        texel_word(o.u),
        texel_word(o.v),
        o.x as u64,
        o.y as u64,
        o.done as u64,
    ]
}

/// The twin on input rows.
pub struct TexRows(pub TexCoordModel);

impl Twin for TexRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[1 + SETUP_PORTS + 7] & 1 != 0;
        let o = out_row(&self.0.outputs_held(hold));
        let load = (r[0] & 1 != 0).then(|| TexCoordSetup::from_ports(&r[1..1 + SETUP_PORTS]));
        self.0.clock_held(load.as_ref(), &row_event(r), hold);
        o
    }
}

/// The system run: the golden address block held by the cycle model's `ready`. Returns the
/// input rows, and per clock the model's outputs and the triangle of the pixel shown.
/// `hold` is high in a seeded tenth of the clocks (the consumer's back-pressure).
pub fn tex_system(
    tris: &[TexTriangle],
    k: u32,
    seed: u64,
) -> (Vec<Vec<u64>>, Vec<(TexOutputs, usize)>) {
    let mut rng = Rng::new(seed ^ 0x401d);
    let mut addr = AddressBlockModel::subpixel();
    let mut tex = TexCoordModel::new(k);
    let (mut rows, mut outs) = (Vec::new(), Vec::new());
    let (mut next_load, mut first_taken) = (0, true);
    // The triangle of each pixel taken, in order, and of each pixel shown.
    let mut owners = std::collections::VecDeque::new();
    let mut current = 0usize;
    let mut idle = 0;
    while idle < 4 {
        let stall = rng.below(10) == 0;
        let o = tex.outputs_held(stall);
        let owner = if o.valid {
            owners
                .pop_front()
                .expect("a pixel shown that was never taken")
        } else {
            usize::MAX
        };
        outs.push((o, owner));
        let hold = !o.ready;
        let a = addr.outputs_held(hold);
        let ev = TexEvent::from(&a);
        if o.ready && ev.row_start && ev.step == 0 {
            first_taken = true;
            current = next_load - 1;
        }
        if o.ready && ev.valid {
            owners.push_back(current);
        }
        let load = (next_load < tris.len() && addr.ready() && first_taken).then(|| {
            first_taken = false;
            next_load += 1;
            &tris[next_load - 1].setup
        });
        let row = tex_row(load, &ev, stall);
        tex.clock_held(load, &ev, stall);
        addr.clock_held(load.map(|_| &tris[next_load - 1].addr), hold);
        rows.push(row);
        let busy = next_load < tris.len() || !addr.ready() || ev.present() || !o.ready;
        idle = if busy { 0 } else { idle + 1 };
    }
    (rows, outs)
}

/// Texel coordinates: signed Q16.0, within ½ of N/D.
const TEXEL: Compare = Compare::Fixed {
    format: QFormat::signed(16, 0),
    tol: Tolerance {
        max_abs: 0.5,
        rms: 0.5,
    },
};

impl Bench for TextureCoord {
    const ITEMS: &'static str = "triangles";
    const DEFAULT_ITEMS: usize = 40;
    fn stimulus(p: &TexCoordParams, n: usize, seed: u64) -> Stimulus {
        let tris = tex_triangles(seed, n);
        let (rows, outs) = tex_system(&tris, p.k, seed);
        let expected = outs
            .iter()
            .map(|(o, t)| {
                let w = |v: u64| Expected::Word(v);
                let (u, v) = if o.valid {
                    let t = &tris[*t];
                    let (rx, ry) = (o.x as i64 - t.origin.0, o.y as i64 - t.origin.1);
                    (
                        Expected::Real(exact_u(&t.cu, rx, ry)),
                        Expected::Real(exact_u(&t.cv, rx, ry)),
                    )
                } else {
                    (Expected::DontCare, Expected::DontCare)
                };
                let xy = |v: u32| {
                    if o.valid {
                        w(v as u64)
                    } else {
                        Expected::DontCare
                    }
                };
                vec![
                    w(o.ready as u64),
                    w(o.valid as u64),
                    u,
                    v,
                    xy(o.x),
                    xy(o.y),
                    w(o.done as u64),
                ]
            })
            .collect();
        let mut compare = vec![Compare::Exact; 7];
        compare[2] = TEXEL;
        compare[3] = TEXEL;
        Stimulus {
            rows,
            expected,
            compare,
        }
    }
    fn twin(p: &TexCoordParams) -> Box<dyn Twin> {
        Box::new(TexRows(TexCoordModel::new(p.k)))
    }
    /// Random words on every input: set-ups out of range, events in any order.
    fn edge_rows(_p: &TexCoordParams, seed: u64) -> Vec<Vec<u64>> {
        let mut rng = Rng::new(seed ^ 0x7E7);
        (0..400)
            .map(|_| {
                let mut r = vec![(rng.below(8) == 0) as u64];
                for k in 0..SETUP_PORTS {
                    let bits = if k == 4 || k == 9 { 16 } else { 48 };
                    r.push(rng.next_u64() & ((1 << bits) - 1));
                }
                let small = rng.below(4) != 0;
                r.extend([
                    rng.below(2) as u64,
                    (rng.below(3) == 0) as u64,
                    rng.below(4) as u64,
                    rng.below(2) as u64,
                    rng.below(4096) as u64,
                    rng.below(4096) as u64,
                    (rng.below(6) == 0) as u64,
                    (rng.below(5) == 0) as u64,
                ]);
                if small {
                    // Small words: the texels move within a few steps.
                    for k in [1, 5, 10] {
                        r[1 + k] = texel_word(rng.below(50) as i64 - 25) & 0xFFFF_FFFF_FFFF;
                    }
                    r[1] = rng.below(1000) as u64 + 1;
                }
                r
            })
            .collect()
    }
}
