//! The texture-coordinate block's set-up and its bit-exact cycle twin (RTL:
//! `rtl::units::texture_coord`, block `texture-coord`). The walker of the parent module follows
//! one span; this is the block as it sits behind the address block: it follows the address
//! block's events (line starts after a short or long edge move, pixels along the line), for u
//! and v at once, and resolves up to k correction steps per clock.
//!
//! # Moves instead of x and y steps
//!
//! The address block's walk makes three kinds of move (SPEC §5): along the line (dx = dir,
//! dy = 0), a line start after a short edge move (dx = f, dy = 1) and after a long one
//! (dx = f + 1, dy = 1). A line start moves from the previous line's start, kept in a saved copy
//! of the state (as the BVI keeps RG5) and written with the settled words of the line's first
//! pixel. A line start that arrives in the clock that first pixel settles (a line of one pixel)
//! is taken, and moves one clock later, with `ready` low in between. For a move m with (dx, dy) the recurrences of SPEC §14
//! become, with ΔE_m = 2(g·dx + h·dy) and ΔL_m = dx(2a − g) + dy(2b − h):
//!
//! ```text
//!   E += ΔE_m        W += P_m         P_m = u·ΔE_m − ΔL_m   (one register per move and axis)
//!   correction by j texels:  u += j,  W += j·E,  P_m += j·ΔE_m   (every m)
//! ```
//!
//! Q = W − E is not kept: W − Q = E always, so "Q > 0" is "W − E > 0". P_m is the SPEC's
//! 2g·u register generalised to the three moves: no multiplier anywhere.
//!
//! # Words
//!
//! E, W, P_m, ΔE_m: [`WORD_BITS`]-bit two's complement, every addition modulo 2^48. A word's
//! value is exact modulo 2^48, so only the words compared must be in range: at a pixel,
//! D ∈ [1, 2^30) gives E < 2^31, and a texel within 2^15 − 4 of N/D gives |W + j·E| < 2^47 for
//! |j| ≤ 3. Accepted set-ups: D ∈ [1, 2^30) at every pixel walked, u and every pixel's nearest
//! texel in [−2^15 + 4, 2^15 − 4] ([`TexCoordSetup::check`] says which condition fails).
//! u, v: [`TEXEL_BITS`]-bit two's complement texel indices (not wrapped: the texture memory
//! takes the low bits).

use super::{nearest_texel, words_at, PctCoeffs};
use crate::units::address_block::{AddressOutputs, AddressSetup};

/// Width of E, W, P and ΔE (two's complement, modulo 2^48).
pub const WORD_BITS: u32 = 48;
/// Width of the texel coordinates u, v (two's complement).
pub const TEXEL_BITS: u32 = 16;
/// Largest D at a pixel (exclusive): E = 2D < 2^31.
pub const D_LIMIT: i128 = 1 << 30;
/// Largest |texel| and |u − N/D| the words hold (see the module doc).
pub const TEXEL_LIMIT: i64 = (1 << 15) - 4;
/// The build parameter k (correction steps resolved per clock) the block is built for.
pub const K_VALUES: [u32; 3] = [1, 2, 4];

const MASK: u64 = (1 << WORD_BITS) - 1;

/// `v` modulo 2^48, as a signed value.
pub fn wrap(v: i128) -> i64 {
    let low = (v as u64) & MASK;
    ((low << (64 - WORD_BITS)) as i64) >> (64 - WORD_BITS)
}

/// A signed word as the 48-bit port value.
pub fn word(v: i64) -> u64 {
    (v as u64) & MASK
}

/// A 48-bit port value as a signed word.
pub fn unword(w: u64) -> i64 {
    wrap(w as i128)
}

/// A texel index as the 16-bit port value, and back.
pub fn texel_word(u: i64) -> u64 {
    (u as u64) & 0xFFFF
}
pub fn unword_texel(w: u64) -> i64 {
    w as u16 as i16 as i64
}

/// One coordinate's start words: the texel u0 at the first line start, W there, and P_m.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AxisSetup {
    pub u0: i64,
    pub w0: i64,
    pub p0: [i64; 3],
}

/// The block's set-up for one triangle (computed by software): E at the first line start, the
/// three moves' ΔE, and the start words of u and v.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TexCoordSetup {
    pub e0: i64,
    pub de: [i64; 3],
    pub axes: [AxisSetup; 2],
}

/// The three moves of the walk: (dx, dy) along the line, after a short and after a long edge
/// move.
pub fn moves(f: i64, dir: i64) -> [(i64, i64); 3] {
    [(dir, 0), (f, 1), (f + 1, 1)]
}

impl TexCoordSetup {
    /// The set-up for coefficients `cu` (u = N_u/D) and `cv` (v = N_v/D), both relative to the
    /// first line start as origin (they share g, h, i), on a walk whose edge moves f or f + 1
    /// pixels per line and whose lines run towards `dir` (±1). The start texel is the nearest
    /// one where D > 0 there (one division, in software), else 0.
    pub fn new(cu: &PctCoeffs, cv: &PctCoeffs, f: i64, dir: i64) -> TexCoordSetup {
        assert!(
            (cu.g, cu.h, cu.i) == (cv.g, cv.h, cv.i),
            "u and v share the denominator D"
        );
        let mv = moves(f, dir);
        let de =
            mv.map(|(dx, dy)| wrap(2 * (cu.g as i128 * dx as i128 + cu.h as i128 * dy as i128)));
        let axis = |c: &PctCoeffs| {
            let u0 = if c.d(0, 0) > 0 {
                nearest_texel(c, 0, 0).clamp(-TEXEL_LIMIT, TEXEL_LIMIT)
            } else {
                0
            };
            let (w, _) = words_at(c, 0, 0, u0);
            let p0 = std::array::from_fn(|m| {
                let (dx, dy) = (mv[m].0 as i128, mv[m].1 as i128);
                let dl =
                    dx * (2 * c.a as i128 - c.g as i128) + dy * (2 * c.b as i128 - c.h as i128);
                wrap(u0 as i128 * 2 * (c.g as i128 * dx + c.h as i128 * dy) - dl)
            });
            AxisSetup {
                u0,
                w0: wrap(w),
                p0,
            }
        };
        TexCoordSetup {
            e0: wrap(2 * cu.d(0, 0)),
            de,
            axes: [axis(cu), axis(cv)],
        }
    }

    /// Whether the pixels `(dx, dy)` (relative to the origin) are in the block's range for
    /// these coefficients: D ∈ [1, 2^30) and the nearest texels within ±[`TEXEL_LIMIT`].
    pub fn check(cu: &PctCoeffs, cv: &PctCoeffs, pixels: &[(i64, i64)]) -> Result<(), String> {
        for &(x, y) in pixels {
            let d = cu.d(x, y);
            if !(1..D_LIMIT).contains(&d) {
                return Err(format!("D = {d} at ({x}, {y}) is outside 1..2^30"));
            }
            for (name, c) in [("u", cu), ("v", cv)] {
                let t = nearest_texel(c, x, y);
                if t.abs() > TEXEL_LIMIT {
                    return Err(format!(
                        "{name} = {t} at ({x}, {y}) is beyond ±{TEXEL_LIMIT}"
                    ));
                }
            }
        }
        Ok(())
    }

    /// The set-up ports' values in port order: e0, de_line, de_short, de_long, then per axis
    /// (u, v) u0, W0 − 1 (the block keeps W − 1, so "W > 0" is a sign bit), p_line, p_short,
    /// p_long.
    pub fn ports(&self) -> Vec<u64> {
        let mut p = vec![word(self.e0)];
        p.extend(self.de.map(word));
        for a in &self.axes {
            p.push(texel_word(a.u0));
            p.push(word(wrap(a.w0 as i128 - 1)));
            p.extend(a.p0.map(word));
        }
        p
    }

    /// The inverse of [`TexCoordSetup::ports`].
    pub fn from_ports(p: &[u64]) -> TexCoordSetup {
        let axis = |o: usize| AxisSetup {
            u0: unword_texel(p[o]),
            w0: wrap(unword(p[o + 1]) as i128 + 1),
            p0: [unword(p[o + 2]), unword(p[o + 3]), unword(p[o + 4])],
        };
        TexCoordSetup {
            e0: unword(p[0]),
            de: [unword(p[1]), unword(p[2]), unword(p[3])],
            axes: [axis(4), axis(9)],
        }
    }
}

/// Number of set-up ports ([`TexCoordSetup::ports`]).
pub const SETUP_PORTS: usize = 14;

/// The origin and walk geometry of an address block set-up: the first line start (x, y), the
/// edge's whole move f per line, and dir.
pub fn walk_geometry(a: &AddressSetup) -> ((i64, i64), i64, i64) {
    let dir = if a.dir_neg { -1 } else { 1 };
    ((a.x_start_top() as i64, a.y_top as i64), a.w.f as i64, dir)
}

/// One event of the address block as the block takes it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TexEvent {
    pub valid: bool,
    pub row_start: bool,
    pub step: u8,
    pub carry: bool,
    pub x: u32,
    pub y: u32,
    pub done: bool,
}

impl From<&AddressOutputs> for TexEvent {
    /// The address block's event as the block takes it.
    fn from(a: &AddressOutputs) -> TexEvent {
        TexEvent {
            valid: a.valid,
            row_start: a.row_start,
            step: a.step,
            carry: a.carry,
            x: a.x,
            y: a.y,
            done: a.done,
        }
    }
}

impl TexEvent {
    /// Anything to take: a pixel, a line start, or the end of a triangle.
    pub fn present(&self) -> bool {
        self.valid || self.row_start || self.done
    }
}

/// What the block shows in a clock (its registers, and `ready` from them).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TexOutputs {
    pub ready: bool,
    pub valid: bool,
    pub u: i64,
    pub v: i64,
    pub x: u32,
    pub y: u32,
    pub done: bool,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct AxisState {
    u: i64,
    w: i64,
    p: [i64; 3],
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct State {
    ax: [AxisState; 2],
    e: i64,
    e3: i64,
    z: [i64; 3],
}

/// One axis's correction this clock: j ∈ [−k, k] and whether the texel is then the nearest
/// (the comparisons of the RTL header, in the same order).
fn correction(w: i64, e: i64, e3: i64, k: u32) -> (i64, bool) {
    let pos = |v: i128| wrap(v) > 0;
    let (w, e, e3) = (w as i128, e as i128, e3 as i128);
    if k > 2 {
        // A block not built (`TexCoordModel::unbuilt`): the same comparisons for j up to k.
        let k = k as i128;
        return if !pos(w) {
            (1..=k)
                .find(|&j| pos(w + j * e))
                .map_or((k as i64, false), |j| (j as i64, true))
        } else if pos(w - e) {
            (1..=k)
                .find(|&j| !pos(w - (j + 1) * e))
                .map_or((-(k as i64), false), |j| (-(j as i64), true))
        } else {
            (0, true)
        };
    }
    if !pos(w) {
        // W ≤ 0: up.
        if pos(w + e) {
            (1, true)
        } else if k >= 2 && pos(w + 2 * e) {
            (2, true)
        } else {
            (k as i64, false)
        }
    } else if pos(w - e) {
        // Q = W − E > 0: down.
        if !pos(w - 2 * e) {
            (-1, true)
        } else if k >= 2 && !pos(w - e3) {
            (-2, true)
        } else {
            (-(k as i64), false)
        }
    } else {
        (0, true)
    }
}

/// The block's bit-exact twin (every register, from reset: all zero).
#[derive(Clone, Debug)]
pub struct TexCoordModel {
    k: u32,
    sh: TexCoordSetup,
    de: [i64; 3],
    s: State,
    r: State,
    pending: bool,
    first_px: bool,
    px: (u32, u32, bool),
    /// A line start taken in the clock its previous line's only pixel settled: its move waits
    /// a clock for the saved state (with its carry and whether it has a pixel).
    defer: Option<(bool, bool)>,
    out: TexOutputs,
    /// Correction steps taken so far (|j| summed), for the benches' statistics.
    pub steps: u64,
}

impl TexCoordModel {
    pub fn new(k: u32) -> TexCoordModel {
        assert!(K_VALUES.contains(&k), "k = {k}: built for {K_VALUES:?}");
        TexCoordModel::unbuilt(k)
    }

    /// The model with k correction steps per clock for any k ≥ 1: for k in [`K_VALUES`] the
    /// block's twin ([`TexCoordModel::new`]); for a larger k the same design with k parallel
    /// comparisons per axis, which is not built (a throughput estimate).
    pub fn unbuilt(k: u32) -> TexCoordModel {
        assert!(k >= 1, "k = 0");
        TexCoordModel {
            k,
            sh: TexCoordSetup::default(),
            de: [0; 3],
            s: State::default(),
            r: State::default(),
            pending: false,
            first_px: false,
            px: (0, 0, false),
            defer: None,
            out: TexOutputs::default(),
            steps: 0,
        }
    }

    fn corrections(&self) -> ([i64; 2], bool) {
        if !self.pending {
            return ([0, 0], true);
        }
        let c = self
            .s
            .ax
            .map(|a| correction(a.w, self.s.e, self.s.e3, self.k));
        ([c[0].0, c[1].0], c[0].1 && c[1].1)
    }

    /// `ready` without `hold`: no line start being moved, and no pixel pending or the pending
    /// one settles now.
    pub fn ready(&self) -> bool {
        self.defer.is_none() && (!self.pending || self.corrections().1)
    }

    /// The ports this clock, with `hold` low.
    pub fn outputs(&self) -> TexOutputs {
        self.outputs_held(false)
    }

    /// The ports this clock: `ready` is low under `hold`.
    pub fn outputs_held(&self, hold: bool) -> TexOutputs {
        TexOutputs {
            ready: self.ready() && !hold,
            ..self.out
        }
    }

    fn moved(&self, base: &State, m: usize) -> State {
        let e = base.z[m];
        State {
            ax: base.ax.map(|a| AxisState {
                w: wrap(a.w as i128 + a.p[m] as i128),
                ..a
            }),
            e,
            e3: wrap(3 * e as i128),
            z: std::array::from_fn(|n| wrap(base.z[n] as i128 + self.de[m] as i128)),
        }
    }

    /// One rising edge with `hold` low.
    pub fn clock(&mut self, load: Option<&TexCoordSetup>, ev: &TexEvent) {
        self.clock_held(load, ev, false);
    }

    /// One rising edge: `load` writes the shadow set-up; `ev` is taken when `ready`. Under
    /// `hold` nothing is taken or shown, and the pending pixel's corrections go on.
    pub fn clock_held(&mut self, load: Option<&TexCoordSetup>, ev: &TexEvent, hold: bool) {
        let (j, settled) = self.corrections();
        let ready = self.defer.is_none() && (!self.pending || settled) && !hold;
        let emit = self.pending && settled && !hold;
        let mut sstar = self.s;
        for (a, &j) in sstar.ax.iter_mut().zip(&j) {
            a.u = unword_texel(texel_word(a.u + j));
            a.w = wrap(a.w as i128 + j as i128 * self.s.e as i128);
            for m in 0..3 {
                a.p[m] = wrap(a.p[m] as i128 + j as i128 * self.de[m] as i128);
            }
        }
        if self.pending {
            self.steps += j[0].unsigned_abs() + j[1].unsigned_abs();
        }
        let take = ready && ev.present();
        // Registered outputs.
        self.out.valid = emit;
        if emit {
            self.out.u = sstar.ax[0].u;
            self.out.v = sstar.ax[1].u;
            self.out.x = self.px.0;
            self.out.y = self.px.1;
        }
        self.out.done = (emit && self.px.2) || (take && !ev.valid && ev.done);
        // The saved line start takes the settled state of its line's first pixel (E and Z
        // have not moved since the line start).
        let save = emit && self.first_px;
        if save {
            self.r.ax = sstar.ax;
        }
        if let Some((carry, valid)) = self.defer.take() {
            let st = self.moved(&self.r, 1 + carry as usize);
            self.s = st;
            self.r = st;
            self.pending = valid;
        } else if take {
            if ev.row_start && ev.step == 0 {
                let sh = self.sh;
                self.de = sh.de;
                let st = State {
                    ax: sh.axes.map(|a| AxisState {
                        u: a.u0,
                        w: a.w0,
                        p: a.p0,
                    }),
                    e: sh.e0,
                    e3: wrap(3 * sh.e0 as i128),
                    z: sh.de.map(|d| wrap(sh.e0 as i128 + d as i128)),
                };
                self.s = st;
                self.r = st;
            } else if ev.row_start && save {
                self.defer = Some((ev.carry, ev.valid));
                self.s = sstar;
            } else if ev.row_start {
                let st = self.moved(&self.r, 1 + ev.carry as usize);
                self.s = st;
                self.r = st;
            } else if ev.valid {
                self.s = self.moved(&sstar, 0);
            } else {
                self.s = sstar;
            }
            self.pending = ev.valid && self.defer.is_none();
            self.first_px = ev.valid && ev.row_start;
            self.px = (ev.x, ev.y, ev.done);
        } else {
            self.s = sstar;
            self.pending = self.pending && !emit;
        }
        if let Some(l) = load {
            self.sh = *l;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_wrap_at_48_bits() {
        assert_eq!(wrap(1 << 47), -(1 << 47));
        assert_eq!(wrap((1 << 47) - 1), (1 << 47) - 1);
        assert_eq!(unword(word(-5)), -5);
        assert_eq!(unword_texel(texel_word(-300)), -300);
    }

    #[test]
    fn one_step_per_clock_when_k_is_one() {
        // W ≤ 0 by 3E: three clocks of +1 at k = 1, two at k = 2 (2 then 1).
        let e = 100;
        assert_eq!(correction(-250, e, 3 * e, 1), (1, false));
        assert_eq!(correction(-250, e, 3 * e, 2), (2, false));
        assert_eq!(correction(-50, e, 3 * e, 2), (1, true));
        assert_eq!(correction(250, e, 3 * e, 2), (-2, true));
        assert_eq!(correction(350, e, 3 * e, 2), (-2, false));
        assert_eq!(correction(100, e, 3 * e, 1), (0, true));
    }
}
