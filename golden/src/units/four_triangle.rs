//! Four-triangle address block (SPEC §7, figs. 3.9–3.10): the midpoint subdivision of a
//! triangle into four, the fill rule that makes the four sub-triangles tile the parent's pixel
//! set exactly, the per-triangle set-up the software loads, and a cycle-accurate model of the
//! block (`rtl/src/units/four_triangle.rs` matches [`FourTriangleModel`] bit for bit every clock).
//!
//! # Geometry
//!
//! Parent vertices sorted by (y, x): top T, middle M, bottom B (screen addresses with F
//! fraction bits: F = 0 for integer vertices, `SUBPIXEL_BITS` for sub-pixel ones). Edge
//! midpoints `m_tm`, `m_tb`, `m_mb` need one more bit, so sub-triangles are kept in **doubled
//! coordinates**, with F + 1 fraction bits ([`subdivide_subpixel`]; half-pixel units for
//! integer parents). Lanes:
//!
//! | lane | sub-triangle           | shape                        |
//! |------|------------------------|------------------------------|
//! | 0    | T, m_tm, m_tb          | half-size parent, at T       |
//! | 1    | m_tm, M, m_mb          | the same shape, at m_tm      |
//! | 2    | m_tb, m_mb, B          | the same shape, at m_tb      |
//! | 3    | m_tm, m_mb, m_tb       | the same shape turned 180°   |
//!
//! # Fill rule (SPEC §7's open point)
//!
//! Every sub-triangle is rasterized under the **same top-left rule as the single address
//! block, applied exactly to its vertices on the finer grid** (`crate::raster::Grid`): pixel
//! (x, y) is sampled at its centre, (2x + 1, 2y + 1) in half-pixel units; a centre strictly
//! inside is in; a centre on an edge is in only for a *left* edge (interior on +x) or a *top*
//! edge (horizontal, interior below). With half-integer (or finer) vertices a centre *can* lie
//! on a horizontal edge or on a vertex; the
//! rule is equivalent to moving the sample point by (ε, ε²) with ε → 0⁺, and a point that is in
//! no line of the subdivision lies in exactly one sub-triangle. Hence the four sub-triangles
//! tile the parent's pixel set ([`crate::raster::edge_function_pixels_of`]) exactly: no pixel
//! twice, none lost (tested exhaustively on small triangles here, and on seeded random parents
//! through the RTL in `testbenches/tests/four_triangle.rs`).
//!
//! Rows follow from the same rule: a sub-triangle owns the rows whose centre 2y + 1 lies in
//! [Y_top, Y_bottom) (doubled), and the other side switches to the third edge on the first row
//! whose centre is at or below the middle vertex (`Grid::row_at_or_below`).
//!
//! # Why the hardware shares increments but not error terms
//!
//! Every edge of every sub-triangle is parallel to one parent edge and half as long, so in
//! doubled units its (Δx, Δy) is the parent edge's (Δx, Δy) in pixels: the DDA words f, r and
//! D (`address_block` module doc) are **exactly the parent edge's** (the patent's CT1/CT2 holding
//! the increments shifted right by one). The boundary and error term (b0, e0) differ per lane:
//! the four shapes are translated by half-pixel offsets, and a translation by ½ changes which
//! centres a shape covers, so one walker cannot stand for three corners unless every parent
//! extent is even. The block therefore keeps one shared (f, r, D) per parent edge and one
//! (b0, e0) register pair per lane and edge, and walks all four lanes in parallel.

use crate::raster::{orientation_of, Grid};
use crate::types::{ScreenTriangle, SubpixelTriangle};
use crate::units::address_block::{AddressBlockModel, AddressOutputs, AddressSetup, EdgeSetup};

/// Number of lanes (sub-triangles) of the block.
pub const LANES: usize = 4;

/// The lane of the middle sub-triangle (turned by 180°).
pub const MIDDLE_LANE: usize = 3;

/// The four sub-triangles of a triangle with sub-pixel vertices (`frac` F), in lane order:
/// the doubled coordinates of the module doc with F + 1 fraction bits (half-pixel vertices,
/// frac 1, for an integer parent). `None` for zero area.
pub fn subdivide_subpixel(tri: &SubpixelTriangle) -> Option<[SubpixelTriangle; 4]> {
    let o = orientation_of(tri)?;
    let d = |p: (i32, i32)| (2 * p.0, 2 * p.1);
    let mid = |a: (i32, i32), b: (i32, i32)| (a.0 + b.0, a.1 + b.1);
    let (t, m, b) = (d(o.top), d(o.mid), d(o.bot));
    let (m_tm, m_tb, m_mb) = (mid(o.top, o.mid), mid(o.top, o.bot), mid(o.mid, o.bot));
    let frac = tri.frac + 1;
    Some(
        [
            [t, m_tm, m_tb],
            [m_tm, m, m_mb],
            [m_tb, m_mb, b],
            [m_tm, m_mb, m_tb],
        ]
        .map(|v| SubpixelTriangle { v, frac }),
    )
}

/// The single address block's set-up of a sub-triangle (what one lane of the block walks;
/// `frac` ≥ 1, coordinates in 2^−frac pixel): rows from the first centre at or below each
/// vertex, each edge's words from [`EdgeSetup::subpixel`] (D = 2^frac·Δy, 2^frac·Δx = f·D + r,
/// e the edge function at the boundary pixel's centre). A third edge that is never reached
/// loads no start, and a lane without rows still loads its edges' increments (the shared
/// words), unlike [`AddressSetup::subpixel`].
pub fn lane_setup(h: &SubpixelTriangle) -> AddressSetup {
    let g = Grid::of(h.frac);
    let Some(o) = orientation_of(h) else {
        let y = h.v.iter().map(|p| p.1).min().unwrap_or(0);
        return AddressSetup {
            y_top: g.row_at_or_below(y).clamp(0, 4095) as u32,
            ..AddressSetup::default()
        };
    };
    let row = |p: (i32, i32)| g.row_at_or_below(p.1);
    let (y_top, y_end, y_switch) = (row(o.top), row(o.bot), row(o.mid));
    let edge = |a: (i32, i32), b: (i32, i32), y: i64| {
        let mut e = EdgeSetup::subpixel(h.frac, a, b, y);
        e.b0 &= 0xFFF;
        e
    };
    let w = edge(o.top, o.bot, y_top);
    let mut t = edge(o.mid, o.bot, y_switch);
    if y_switch >= y_end {
        t.b0 = 0;
        t.e0 = 0;
    }
    let a = if y_switch > y_top {
        edge(o.top, o.mid, y_top)
    } else {
        t
    };
    AddressSetup {
        w,
        a,
        t,
        y_top: y_top as u32,
        rows: (y_end - y_top) as u32,
        y_switch: y_switch.rem_euclid(4096) as u32,
        dir_neg: !o.left,
    }
}

/// The increments of one edge DDA, shared by the lanes: f (12-bit word), r, D.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct EdgeIncrements {
    pub f: i32,
    pub r: u32,
    pub d: u32,
}

impl EdgeIncrements {
    fn of(e: &EdgeSetup) -> EdgeIncrements {
        EdgeIncrements {
            f: e.f,
            r: e.r,
            d: e.d,
        }
    }
    pub fn f_word(&self) -> u32 {
        (self.f as u32) & 0xFFF
    }
}

/// One lane's own set-up words: (b0, e0) of its working, other and third edge, which shared
/// increments its other and third edge use, and its rows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct LaneSetup {
    pub w_b0: u32,
    pub w_e0: u32,
    pub a_b0: u32,
    pub a_e0: u32,
    /// The other edge uses the parent's third-edge increments (else the adjacent edge's).
    pub a_third: bool,
    pub t_b0: u32,
    pub t_e0: u32,
    /// The third edge uses the parent's adjacent-edge increments (else the third edge's).
    pub t_adjacent: bool,
    pub y_top: u32,
    pub rows: u32,
    pub y_switch: u32,
    pub dir_neg: bool,
}

/// One parent triangle's set-up for the four-triangle block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FourTriangleSetup {
    /// Shared increments of the parent's working (T→B), adjacent (T→M) and third (M→B) edge.
    pub w: EdgeIncrements,
    pub a: EdgeIncrements,
    pub t: EdgeIncrements,
    pub lanes: [LaneSetup; 4],
}

impl FourTriangleSetup {
    /// The set-up of `tri` (vertices in 0..=4095 pixels): [`FourTriangleSetup::subpixel`] at
    /// the triangle's fraction bits.
    pub fn new(tri: &ScreenTriangle) -> FourTriangleSetup {
        FourTriangleSetup::subpixel(&SubpixelTriangle::of(tri))
    }

    /// The set-up of a parent with sub-pixel vertices (`frac` F, coordinates in
    /// 0..=4095·2^F): its four sub-triangles at F + 1 fraction bits ([`subdivide_subpixel`]),
    /// each lane's words from [`lane_setup`], the increments shared per parent edge (a
    /// sub-edge's Δ in 2^−(F+1) pixel is its parent edge's Δ in 2^−F pixel). A zero-area
    /// triangle loads four lanes without rows.
    pub fn subpixel(tri: &SubpixelTriangle) -> FourTriangleSetup {
        let Some(subs) = subdivide_subpixel(tri) else {
            let y = tri.v.iter().map(|p| p.1).min().unwrap_or(0);
            let y = Grid::of(tri.frac).row_at_or_below(y).clamp(0, 4095) as u32;
            let mut s = FourTriangleSetup::default();
            for l in &mut s.lanes {
                l.y_top = y;
            }
            return s;
        };
        let o = orientation_of(tri).expect("non-zero area");
        let frac = tri.frac + 1;
        let inc = |a: (i32, i32), b: (i32, i32)| {
            EdgeIncrements::of(&EdgeSetup::subpixel(
                frac,
                (0, 0),
                (b.0 - a.0, b.1 - a.1),
                0,
            ))
        };
        let (w, a, t) = (inc(o.top, o.bot), inc(o.top, o.mid), inc(o.mid, o.bot));
        let lanes = std::array::from_fn(|k| {
            let s = lane_setup(&subs[k]);
            let (si_a, si_t) = (EdgeIncrements::of(&s.a), EdgeIncrements::of(&s.t));
            assert_eq!(
                EdgeIncrements::of(&s.w),
                w,
                "lane {k}: working edge not shared"
            );
            // Where two parent edges have equal increments either choice loads the same words.
            let a_third = si_a != a;
            let t_adjacent = si_t != t;
            assert_eq!(
                si_a,
                if a_third { t } else { a },
                "lane {k}: other edge not shared"
            );
            assert_eq!(
                si_t,
                if t_adjacent { a } else { t },
                "lane {k}: third edge not shared"
            );
            LaneSetup {
                w_b0: s.w.b0,
                w_e0: s.w.e0,
                a_b0: s.a.b0,
                a_e0: s.a.e0,
                a_third,
                t_b0: s.t.b0,
                t_e0: s.t.e0,
                t_adjacent,
                y_top: s.y_top,
                rows: s.rows,
                y_switch: s.y_switch,
                dir_neg: s.dir_neg,
            }
        });
        FourTriangleSetup { w, a, t, lanes }
    }

    /// The single-block set-up lane `k` walks: its (b0, e0) with the shared increments it
    /// selects (exactly what the RTL wires into each lane's address block).
    pub fn lane(&self, k: usize) -> AddressSetup {
        let l = &self.lanes[k];
        let edge = |b0: u32, e0: u32, i: &EdgeIncrements| EdgeSetup {
            b0,
            e0,
            f: i.f,
            r: i.r,
            d: i.d,
        };
        AddressSetup {
            w: edge(l.w_b0, l.w_e0, &self.w),
            a: edge(l.a_b0, l.a_e0, if l.a_third { &self.t } else { &self.a }),
            t: edge(l.t_b0, l.t_e0, if l.t_adjacent { &self.a } else { &self.t }),
            y_top: l.y_top,
            rows: l.rows,
            y_switch: l.y_switch,
            dir_neg: l.dir_neg,
        }
    }
}

/// The block's outputs in one clock: `ready` and one address-block output bundle per lane
/// (lane k carries sub-triangle k; its `done` marks that sub-triangle's last event).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FourOutputs {
    pub ready: bool,
    pub lanes: [AddressOutputs; 4],
}

impl FourOutputs {
    /// Number of valid addresses in this clock (0..=4).
    pub fn addresses(&self) -> usize {
        self.lanes.iter().filter(|o| o.valid).count()
    }
}

/// Width of the error words of the sub-pixel four-triangle block's lanes: a sub-triangle of
/// a parent with F = [`crate::types::SUBPIXEL_BITS`] = 4 fraction bits has F + 1 = 5, so D =
/// 2^5·Δy with Δy ≤ 4095·2^4 (the parent edge's Δ in 2^−4 pixel) gives D < 4095·2^9 < 2^21.
pub const SUBPIXEL_LANE_ERR_BITS: u32 = 21;

/// Cycle-accurate model: four address-block lanes loaded together when all are ready.
#[derive(Clone, Debug, Default)]
pub struct FourTriangleModel {
    lanes: [AddressBlockModel; 4],
}

impl FourTriangleModel {
    /// The integer block (13-bit error words: integer parents only).
    pub fn new() -> Self {
        Self::default()
    }
    /// The sub-pixel block ([`SUBPIXEL_LANE_ERR_BITS`]-bit error words: parents with up to
    /// `SUBPIXEL_BITS` fraction bits, integer ones included).
    pub fn subpixel() -> Self {
        FourTriangleModel {
            lanes: std::array::from_fn(|_| {
                AddressBlockModel::with_err_bits(SUBPIXEL_LANE_ERR_BITS)
            }),
        }
    }
    pub fn ready(&self) -> bool {
        self.lanes.iter().all(|l| l.ready())
    }
    pub fn outputs(&self) -> FourOutputs {
        self.outputs_held(false)
    }
    /// The outputs with the `hold` input at `hold`: every lane's address-block outputs under
    /// it (a held clock shows no event on any lane; `ready` does not depend on it).
    pub fn outputs_held(&self, hold: bool) -> FourOutputs {
        FourOutputs {
            ready: self.ready(),
            lanes: std::array::from_fn(|k| {
                let mut o = self.lanes[k].outputs_held(hold);
                o.ready = self.ready();
                o
            }),
        }
    }
    /// One rising edge; `load` is taken only when [`Self::ready`].
    pub fn clock(&mut self, load: Option<&FourTriangleSetup>) {
        self.clock_held(load, false)
    }
    /// [`Self::clock`] with the `hold` input, which every lane's address block receives.
    pub fn clock_held(&mut self, load: Option<&FourTriangleSetup>, hold: bool) {
        let load = load.filter(|_| self.ready());
        for (k, l) in self.lanes.iter_mut().enumerate() {
            let s = load.map(|s| s.lane(k));
            l.clock_held(s.as_ref(), hold);
        }
    }
}

/// The block walking `setups` back to back, each loaded in the first clock with `ready`: per
/// clock, the outputs and the index of the set-up loaded in that clock (if any), from the
/// first load to the clock in which every lane has shown its last `done`, then `tail` more
/// clocks without a load (for the pipelines behind the block to drain).
pub fn schedule(setups: &[FourTriangleSetup], tail: usize) -> Vec<(FourOutputs, Option<usize>)> {
    schedule_on(FourTriangleModel::new(), setups, tail)
}

/// [`schedule`] on a given model (the integer or the sub-pixel block).
pub fn schedule_on(
    mut m: FourTriangleModel,
    setups: &[FourTriangleSetup],
    tail: usize,
) -> Vec<(FourOutputs, Option<usize>)> {
    let mut out = Vec::new();
    let mut dones = [0usize; 4];
    let mut next = 0;
    let mut left = tail;
    loop {
        if dones.iter().all(|&d| d >= setups.len()) {
            if left == 0 {
                break;
            }
            left -= 1;
        }
        let o = m.outputs();
        for (d, l) in dones.iter_mut().zip(&o.lanes) {
            *d += l.done as usize;
        }
        let load = (o.ready && next < setups.len()).then_some(next);
        next += load.is_some() as usize;
        out.push((o, load));
        m.clock(load.map(|k| &setups[k]));
    }
    out
}

/// Clock-by-clock outputs of the block walking `setups` back to back ([`schedule`] without a
/// tail), and the cycle of each load.
pub fn run(setups: &[FourTriangleSetup]) -> (Vec<FourOutputs>, Vec<usize>) {
    run_on(FourTriangleModel::new(), setups)
}

/// [`run`] on a given model.
pub fn run_on(
    m: FourTriangleModel,
    setups: &[FourTriangleSetup],
) -> (Vec<FourOutputs>, Vec<usize>) {
    let s = schedule_on(m, setups, 0);
    let loads = s
        .iter()
        .enumerate()
        .filter_map(|(c, (_, l))| l.map(|_| c))
        .collect();
    (s.into_iter().map(|(o, _)| o).collect(), loads)
}

/// The pixels of lane `k` in a clock stream, in emission order.
pub fn lane_pixels(out: &[FourOutputs], k: usize) -> Vec<crate::types::WalkPixel> {
    let lane: Vec<AddressOutputs> = out.iter().map(|o| o.lanes[k]).collect();
    crate::units::address_block::stream_pixels(&lane)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::{edge_function_pixels_of, walk_subpixel};
    use std::collections::HashSet;

    /// An integer parent: the four tile its pixel set; each lane's walk is its sub-triangle's
    /// edge-function set; the model emits each walk; a lane with rows whose third edge is
    /// reached loads the single block's set-up of its sub-triangle.
    fn check(p: [(i32, i32); 3]) {
        let tri = ScreenTriangle::from_points(p);
        let parent: HashSet<(i32, i32)> = edge_function_pixels_of(&SubpixelTriangle::of(&tri))
            .into_iter()
            .collect();
        let Some(subs) = subdivide_subpixel(&SubpixelTriangle::of(&tri)) else {
            assert!(parent.is_empty());
            return;
        };
        let mut union = HashSet::new();
        let setup = FourTriangleSetup::new(&tri);
        let (out, _) = run(&[setup]);
        for (k, h) in subs.iter().enumerate() {
            assert_eq!(h.frac, 1);
            let px = edge_function_pixels_of(h);
            for q in &px {
                assert!(union.insert(*q), "{p:?}: pixel {q:?} twice (lane {k})");
            }
            let w = walk_subpixel(h);
            let mut wp: Vec<_> = w.pixels().iter().map(|q| (q.x, q.y)).collect();
            wp.sort_by_key(|&(x, y)| (y, x));
            assert_eq!(wp, px, "{p:?} lane {k}: walk vs edge functions");
            assert_eq!(
                lane_pixels(&out, k),
                w.pixels(),
                "{p:?} lane {k}: model vs walk"
            );
            let single = AddressSetup::subpixel(h);
            if single.rows > 0 && single.y_switch < single.y_top + single.rows {
                assert_eq!(setup.lane(k), single, "{p:?} lane {k}: shared words");
            }
        }
        assert_eq!(union, parent, "{p:?}: union differs from the parent");
    }

    #[test]
    fn named_triangles_tile_their_parent() {
        // The address block's named triangles, an odd-sided right angle (midpoints off the
        // pixel grid) and two small general ones.
        let more = [
            [(0, 0), (11, 0), (0, 11)],
            [(1, 1), (2, 4), (5, 2)],
            [(0, 0), (3, 1), (1, 3)],
        ];
        for p in crate::units::address_block::tests::NAMED_TRIANGLES
            .into_iter()
            .chain(more)
        {
            check(p);
        }
    }

    #[test]
    fn small_triangles_exhaustively() {
        for a in 0..5 {
            for b in 0..25 {
                for c in 0..25 {
                    check([(a, 0), (b % 5, 1 + b / 5), (c % 5, c / 5)]);
                }
            }
        }
    }
}
