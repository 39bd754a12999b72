//! Address block (SPEC §5): the per-triangle set-up the software loads into it, and a
//! cycle-accurate model of its register transfers — which pixel address (or none) appears at
//! each clock.
//!
//! The pixel *set and order* are defined by [`crate::raster::walk`] (the walk contract in the
//! doc of [`crate::types::Row`]); this module adds the *timing*: the RTL block in
//! `rtl/src/units/address_block.rs` must match [`AddressBlockModel`] bit for bit every clock, and the
//! pixels it emits must equal the walk's. The set-up uses the same integer edge geometry as the
//! walk (the boundary of each edge comes from [`crate::raster::EdgeDda`]).
//!
//! # Edge DDA in quotient/remainder form
//!
//! For an edge from (x0, y0) down to (x1, y1), Δx = x1 − x0, Δy = y1 − y0 > 0, the boundary on
//! raster line y (the smallest x whose centre is on or right of the edge) is
//! `B(y) = ⌈N(y) / D⌉` with `D = 2Δy`, `N(y) = Δy·(2x0 − 1) + (2(y − y0) + 1)·Δx`.
//! One line down adds `2Δx = f·D + r` to N, with `f = ⌊Δx/Δy⌋`, `r ∈ 0..D`. Keeping the error
//! `e = B·D − N ∈ 0..D`, one line down is
//!
//! ```text
//!   carry = e < r;   B += f + carry;   e = e − r + (carry ? D : 0)
//! ```
//!
//! i.e. a Bresenham DDA whose run of horizontal steps per line (f or f + 1 of them, the last
//! one diagonal) is taken in a single clock. The set-up software does the one division per edge
//! (`f`, `r`); the hardware only adds and compares. Ranges for 12-bit vertices: B ∈ 0..=4095 on
//! every raster line the edge is used for, D ≤ 8190 and e, r < D (13 bits), f ∈ −4095..=4095
//! (only needed modulo 4096, because B + f + carry lands in 0..=4095 again).
//!
//! **Sub-pixel vertices** ([`AddressSetup::subpixel`]: coordinates in 2^−frac pixel, m =
//! max(frac, 1)): the same recurrence with D = 2^m·Δy, 2^m·Δx = f·D + r and e the edge function
//! at the boundary pixel's centre, all in 2^−frac pixel; rows are those whose centres lie in
//! [top.y, bottom.y). For frac = `SUBPIXEL_BITS` = 4, D < 2^20 ([`SUBPIXEL_ERR_BITS`]); B, f and
//! the rows keep their ranges.
//!
//! # Rows
//!
//! Vertices sorted by (y, x): top T, middle M, bottom Bt. Working edge T→Bt, adjacent edge T→M,
//! third edge M→Bt. Rows y_top..y_bottom−1. With `dir = +1` (working edge on the left) a row
//! starts at `x_start = B_w` and holds `B_o − B_w` pixels; with `dir = −1` it starts at
//! `B_w − 1` and holds `B_w − B_o` pixels (going left). The other edge switches from the
//! adjacent to the third edge on the row y_mid.
//!
//! # Timing (what [`AddressBlockModel`] models)
//!
//! Three register stages:
//!
//! ```text
//!  load ─► E: edge stage ──row record──► RGr/start registers ──► P: CTx, CTy, CTr ──► outputs
//!          two line interpolators        (one-row buffer)          one event per clock
//!          + length (step-increment)
//! ```
//!
//! - **E** computes one row record per clock (x_start, y, length RGr, step type and carry of
//!   the working edge's move into the row) and advances both edge DDAs, whenever the buffer is
//!   empty or being emptied in the same clock.
//! - **P** shows one *event* per clock: a pixel (the line's first pixel when it takes a row
//!   record, then CTx ± 1 while CTr counts down), or — for a row with no pixel — one clock with
//!   `valid = 0` and `row_start = 1` (the intensity interpolators still advance their line-start
//!   value there). It takes the next record in the clock after the row's last event, so a line
//!   start costs no extra clock; an empty row costs one.
//! - A triangle with no rows (zero area) still produces one event: `valid = 0`, `done = 1`.
//! - `ready` is high when a new triangle may be loaded: E has produced all rows of the current
//!   one and P has taken its first record. The next triangle's rows then follow the current
//!   one's without a gap once the walk is longer than the two-clock load latency.
//!
//! Latency: load in clock t → first event in clock t + 3 (E fires in t + 1, P takes the record
//! in t + 2).

use crate::raster::{EdgeDda, Grid};
use crate::types::{ScreenTriangle, StepType, SubpixelTriangle};

/// Set-up of one edge's DDA, placed on the edge's first raster line (its upper vertex's y).
/// All zero for an edge that is never used (horizontal).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub struct EdgeSetup {
    /// Boundary B on the first raster line, 0..=4095 (12 bits).
    pub b0: u32,
    /// Error term e = B·D − N on the first line, 0..D (13 bits; 20 with sub-pixel vertices).
    pub e0: u32,
    /// Whole part of the move per line, ⌊Δx/Δy⌋, −4095..=4095 (loaded modulo 4096).
    pub f: i32,
    /// Remainder of 2Δx by D, 0..D (13 bits; sub-pixel: of 2^m·Δx, 20 bits).
    pub r: u32,
    /// D = 2Δy, 2..=8190 (13 bits; sub-pixel: 2^m·Δy with Δy in 2^−frac pixel, < 2^20).
    pub d: u32,
}

impl EdgeSetup {
    /// The DDA of the edge `upper`→`lower` with sub-pixel vertices (coordinates in 2^−frac
    /// pixel, upper.y < lower.y), placed on raster line `y`: with m = max(frac, 1),
    /// D = 2^m·Δy, 2^m·Δx = f·D + r and e the edge function at the boundary pixel's centre,
    /// all in 2^−frac pixel (so the integer set-up is the case frac = 0, D = 2Δy).
    pub fn subpixel(frac: u32, upper: (i32, i32), lower: (i32, i32), y: i64) -> EdgeSetup {
        let (dx, dy) = ((lower.0 - upper.0) as i64, (lower.1 - upper.1) as i64);
        if dy <= 0 {
            return EdgeSetup::default();
        }
        let g = Grid::of(frac);
        let dda = EdgeDda::new_in(g, upper, lower, y as i32);
        let (e0, step, d) = dda.words(g);
        let f = dx.div_euclid(dy);
        let r = step - f * d;
        debug_assert!((0..d).contains(&e0) && (0..d).contains(&r));
        EdgeSetup {
            b0: dda.boundary() as u32,
            e0: e0 as u32,
            f: f as i32,
            r: r as u32,
            d: d as u32,
        }
    }

    /// `f` as the 12-bit two's-complement word the hardware loads.
    pub fn f_word(&self) -> u32 {
        (self.f as u32) & 0xFFF
    }
}

/// One triangle's set-up for the address block (integer only; computed by software).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub struct AddressSetup {
    /// Working edge top→bottom.
    pub w: EdgeSetup,
    /// The other side's edge on the first row: top→middle, or middle→bottom for a flat top.
    pub a: EdgeSetup,
    /// The third edge middle→bottom, loaded when the walk reaches `y_switch`.
    pub t: EdgeSetup,
    /// First raster line (the top vertex's y).
    pub y_top: u32,
    /// Number of raster lines, y_bottom − y_top (0 for a zero-area triangle), 0..=4095.
    pub rows: u32,
    /// Raster line where the third edge takes over (y_mid; never reached for a flat bottom).
    pub y_switch: u32,
    /// The working edge is the right edge: lines run towards −x.
    pub dir_neg: bool,
}

impl AddressSetup {
    /// The set-up of `tri` (vertex coordinates must be in 0..=4095 pixels): [`AddressSetup::subpixel`]
    /// at the triangle's fraction bits (integer vertices are frac = 0, the words of the
    /// module doc: D = 2Δy, N(y) = Δy·(2x0 − 1) + (2(y − y0) + 1)·Δx).
    pub fn new(tri: &ScreenTriangle) -> AddressSetup {
        AddressSetup::subpixel(&SubpixelTriangle::of(tri))
    }

    /// The set-up of a triangle with sub-pixel vertices (`raster::walk_subpixel`'s rows and
    /// edges; coordinates in 0..=4095·2^frac). A triangle whose rows hold no pixel centre
    /// (zero area, or too thin between two centres) has no rows.
    pub fn subpixel(tri: &SubpixelTriangle) -> AddressSetup {
        let o = crate::raster::orientation_of(tri);
        let rows = o.map(|o| crate::raster::walk_rows(tri, &o));
        let (Some(o), Some((y_first, y_end, y_switch))) = (o, rows) else {
            let y_top = tri.v.iter().map(|p| p.1).min().unwrap_or(0);
            let y_top = Grid::of(tri.frac).row_at_or_below(y_top).clamp(0, 4095);
            return AddressSetup {
                y_top: y_top as u32,
                ..AddressSetup::default()
            };
        };
        if y_end <= y_first {
            return AddressSetup {
                y_top: y_first.clamp(0, 4095) as u32,
                ..AddressSetup::default()
            };
        }
        let f = tri.frac;
        let (top, mid, bot) = (o.top, o.mid, o.bot);
        let w = EdgeSetup::subpixel(f, top, bot, y_first);
        let t = EdgeSetup::subpixel(f, mid, bot, y_switch);
        let a = if y_switch > y_first {
            EdgeSetup::subpixel(f, top, mid, y_first)
        } else {
            EdgeSetup::subpixel(f, mid, bot, y_first)
        };
        AddressSetup {
            w,
            a,
            t,
            y_top: y_first as u32,
            rows: (y_end - y_first) as u32,
            y_switch: y_switch as u32,
            dir_neg: !o.left,
        }
    }

    /// The x of the first row's start (the first pixel when that row is not empty).
    pub fn x_start_top(&self) -> i32 {
        self.w.b0 as i32 - self.dir_neg as i32
    }
}

/// A row record as the edge stage hands it to the row counter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct RowRecord {
    /// False for the single record of a zero-row triangle.
    is_row: bool,
    x: u32,
    y: u32,
    len: u32,
    step: u8,
    carry: bool,
    dir_neg: bool,
    first: bool,
    last: bool,
}

/// One edge DDA's registers (a line interpolator).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Dda {
    b: u32,
    e: u32,
    f: u32,
    r: u32,
    d: u32,
    /// Step type code and carry of the last move (Start after a load).
    step: u8,
    carry: bool,
    /// e is kept modulo 2^ERR_BITS (the width of the error words).
    mask: u32,
}

/// Width of the error words e, r, D of the integer address block (D ≤ 2·4095).
pub const ERR_BITS: u32 = 13;
/// Width of the error words of the sub-pixel address block: D = 2^m·Δy with Δy ≤ 4095·2^frac
/// and m = frac = [`crate::types::SUBPIXEL_BITS`] = 4 gives D < 4095·2^8 < 2^20.
pub const SUBPIXEL_ERR_BITS: u32 = 20;

impl Dda {
    fn load(s: &EdgeSetup, err_bits: u32) -> Dda {
        Dda {
            mask: (1 << err_bits) - 1,
            b: s.b0,
            e: s.e0,
            f: s.f_word(),
            r: s.r,
            d: s.d,
            step: StepType::Start.code(),
            carry: false,
        }
    }
    fn advance(&mut self) {
        let carry = self.e < self.r;
        let mv = (self.f + carry as u32) & 0xFFF;
        self.b = (self.b + mv) & 0xFFF;
        self.e = (self
            .e
            .wrapping_sub(self.r)
            .wrapping_add(if carry { self.d } else { 0 }))
            & self.mask;
        self.step = if mv == 0 {
            StepType::Vertical.code()
        } else {
            StepType::Diagonal.code()
        };
        self.carry = carry;
    }
}

/// The block's outputs in one clock (what the RTL's output ports show).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub struct AddressOutputs {
    /// A new triangle may be loaded in this clock.
    pub ready: bool,
    /// A pixel address is present.
    pub valid: bool,
    pub x: u32,
    pub y: u32,
    /// StepType code of the pixel (Start/V/D at a line start, H along the line); for an empty
    /// row's event the working edge's move into that row.
    pub step: u8,
    /// First pixel of a raster line.
    pub line_start: bool,
    /// First event of a raster line, empty or not (the intensity interpolators' edge advance).
    pub row_start: bool,
    /// The working edge's move into this row was the long one (f + 1); valid with `row_start`.
    pub carry: bool,
    /// Last event of the triangle.
    pub done: bool,
}

/// Cycle-accurate model of the address block's registers (see the module doc).
#[derive(Clone, Debug, Default)]
pub struct AddressBlockModel {
    /// The width of the error words; 0 for [`ERR_BITS`].
    err_bits: u32,
    // Edge stage.
    e_busy: bool,
    e_rows_left: u32,
    e_y: u32,
    e_first: bool,
    e_dir_neg: bool,
    y_switch: u32,
    wait_first: bool,
    w: Dda,
    o: Dda,
    t: EdgeSetup,
    // Row buffer (RGr and the start registers).
    nb_valid: bool,
    nb: RowRecord,
    // Row counter stage.
    p_busy: bool,
    p_pix: bool,
    p_x: u32,
    p_y: u32,
    p_ctr: u32,
    p_step: u8,
    p_line_start: bool,
    p_row_start: bool,
    p_carry: bool,
    p_last: bool,
    p_dir_neg: bool,
}

impl AddressBlockModel {
    /// The integer address block (13-bit error words).
    pub fn new() -> Self {
        Self::default()
    }

    /// The sub-pixel address block (20-bit error words).
    pub fn subpixel() -> Self {
        Self::with_err_bits(SUBPIXEL_ERR_BITS)
    }

    /// The block with `bits`-bit error words (the four-triangle block's sub-pixel lanes:
    /// [`crate::units::four_triangle::SUBPIXEL_LANE_ERR_BITS`]).
    pub fn with_err_bits(bits: u32) -> Self {
        AddressBlockModel {
            err_bits: bits,
            ..Self::default()
        }
    }

    fn err_bits(&self) -> u32 {
        if self.err_bits == 0 {
            ERR_BITS
        } else {
            self.err_bits
        }
    }

    /// `ready` in the current clock.
    pub fn ready(&self) -> bool {
        !self.e_busy && !self.wait_first
    }

    /// The outputs during the current clock (they depend on registers only).
    pub fn outputs(&self) -> AddressOutputs {
        self.outputs_held(false)
    }

    /// The outputs during the current clock with the `hold` input at `hold`: a held clock
    /// shows no event (the pending one is shown in the next clock without `hold`).
    pub fn outputs_held(&self, hold: bool) -> AddressOutputs {
        let busy = self.p_busy && !hold;
        AddressOutputs {
            ready: self.ready(),
            valid: busy && self.p_pix,
            x: if busy { self.p_x } else { 0 },
            y: if busy { self.p_y } else { 0 },
            step: if busy { self.p_step } else { 0 },
            line_start: busy && self.p_line_start,
            row_start: busy && self.p_row_start,
            carry: busy && self.p_carry,
            done: busy && self.p_last && !(self.p_pix && self.p_ctr != 0),
        }
    }

    /// One rising clock edge. `load` is sampled only when [`Self::ready`] is high (otherwise
    /// ignored, as the hardware does).
    pub fn clock(&mut self, load: Option<&AddressSetup>) {
        self.clock_held(load, false)
    }

    /// [`Self::clock`] with the `hold` input: while held the row counter stage keeps its event
    /// and takes no record; the edge stage may still fill an empty buffer, and a load is
    /// accepted as usual.
    pub fn clock_held(&mut self, load: Option<&AddressSetup>, hold: bool) {
        let p_more = self.p_busy && self.p_pix && self.p_ctr != 0;
        let nb_take = self.nb_valid && !p_more && !hold;
        let e_fire = self.e_busy && (!self.nb_valid || nb_take);
        let load = load.filter(|_| self.ready());

        // Row counter stage (reads the buffer before E overwrites it).
        let nb = self.nb;
        if hold {
            // P keeps its event.
        } else if p_more {
            self.p_x = if self.p_dir_neg {
                self.p_x.wrapping_sub(1)
            } else {
                self.p_x + 1
            } & 0xFFF;
            self.p_ctr -= 1;
            self.p_step = StepType::Horizontal.code();
            self.p_line_start = false;
            self.p_row_start = false;
        } else if nb_take {
            self.p_busy = true;
            self.p_pix = nb.is_row && nb.len != 0;
            self.p_x = nb.x;
            self.p_y = nb.y;
            self.p_ctr = nb.len.saturating_sub(1);
            self.p_step = nb.step;
            self.p_line_start = self.p_pix;
            self.p_row_start = nb.is_row;
            self.p_carry = nb.carry;
            self.p_last = nb.last;
            self.p_dir_neg = nb.dir_neg;
            if nb.first {
                self.wait_first = false;
            }
        } else {
            self.p_busy = false;
        }

        // Edge stage and buffer.
        if e_fire {
            let rec = if self.e_rows_left == 0 {
                self.e_busy = false;
                RowRecord {
                    is_row: false,
                    first: true,
                    last: true,
                    dir_neg: self.e_dir_neg,
                    ..RowRecord::default()
                }
            } else {
                let (x, len) = if self.e_dir_neg {
                    (
                        (self.w.b.wrapping_sub(1)) & 0xFFF,
                        self.w.b.wrapping_sub(self.o.b) & 0xFFF,
                    )
                } else {
                    (self.w.b, self.o.b.wrapping_sub(self.w.b) & 0xFFF)
                };
                let rec = RowRecord {
                    is_row: true,
                    x,
                    y: self.e_y,
                    len,
                    step: self.w.step,
                    carry: self.w.carry,
                    dir_neg: self.e_dir_neg,
                    first: self.e_first,
                    last: self.e_rows_left == 1,
                };
                self.w.advance();
                if (self.e_y + 1) & 0xFFF == self.y_switch {
                    self.o = Dda::load(&self.t, self.err_bits());
                } else {
                    self.o.advance();
                }
                self.e_y = (self.e_y + 1) & 0xFFF;
                self.e_rows_left -= 1;
                self.e_first = false;
                if self.e_rows_left == 0 {
                    self.e_busy = false;
                }
                rec
            };
            self.nb = rec;
            self.nb_valid = true;
        } else if nb_take {
            self.nb_valid = false;
        }

        if let Some(s) = load {
            self.e_busy = true;
            self.e_rows_left = s.rows;
            self.e_y = s.y_top;
            self.e_first = true;
            self.e_dir_neg = s.dir_neg;
            self.y_switch = s.y_switch;
            self.wait_first = true;
            self.w = Dda::load(&s.w, self.err_bits());
            self.o = Dda::load(&s.a, self.err_bits());
            self.t = s.t;
        }
    }
}

/// Clock-by-clock outputs of the block walking `setups` one after another, each loaded in the
/// first clock where `ready` is high. Returns the outputs of every clock from the first load
/// (cycle 0) to the clock showing the last triangle's `done`, inclusive, and the cycle at which
/// each triangle was loaded.
pub fn run(setups: &[AddressSetup]) -> (Vec<AddressOutputs>, Vec<usize>) {
    run_model(AddressBlockModel::new(), setups)
}

/// [`run`] on a given build of the block (integer or [`AddressBlockModel::subpixel`]).
pub fn run_model(
    mut m: AddressBlockModel,
    setups: &[AddressSetup],
) -> (Vec<AddressOutputs>, Vec<usize>) {
    let mut out = Vec::new();
    let mut loads = Vec::with_capacity(setups.len());
    let mut next = 0;
    let mut dones = 0;
    while dones < setups.len() {
        let o = m.outputs();
        out.push(o);
        dones += o.done as usize;
        let load = if next < setups.len() && o.ready {
            loads.push(out.len() - 1);
            next += 1;
            Some(&setups[next - 1])
        } else {
            None
        };
        m.clock(load);
        if dones == setups.len() {
            break;
        }
    }
    (out, loads)
}

/// The pixels of a clock stream in emission order, as walk pixels.
pub fn stream_pixels(out: &[AddressOutputs]) -> Vec<crate::types::WalkPixel> {
    out.iter()
        .filter(|o| o.valid)
        .map(|o| crate::types::WalkPixel {
            x: o.x as i32,
            y: o.y as i32,
            step: match o.step {
                0 => StepType::Start,
                1 => StepType::Horizontal,
                2 => StepType::Vertical,
                _ => StepType::Diagonal,
            },
            line_start: o.line_start,
        })
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::raster::walk;
    use crate::types::StepType;

    fn tri(p: [(i32, i32); 3]) -> ScreenTriangle {
        ScreenTriangle::from_points(p)
    }

    fn check(p: [(i32, i32); 3]) {
        let t = tri(p);
        let s = AddressSetup::new(&t);
        let (out, loads) = run(&[s]);
        assert_eq!(loads, vec![0]);
        assert_eq!(stream_pixels(&out), walk(&t).pixels(), "{p:?}");
        assert_eq!(out.iter().filter(|o| o.done).count(), 1);
        assert!(out.last().unwrap().done);
        // One event per row (at least), no bubble after the load latency.
        let rows = walk(&t).rows;
        let events: usize = rows
            .iter()
            .map(|r| r.len.max(1) as usize)
            .sum::<usize>()
            .max(1);
        assert_eq!(out.len(), 3 + events, "{p:?}");
        // Row-start events carry the working edge's move; check V/D against the walk.
        let starts: Vec<_> = out.iter().filter(|o| o.row_start).collect();
        assert_eq!(starts.len(), rows.len());
        for (o, r) in starts.iter().zip(&rows) {
            let expect = r.edge_steps.last().map_or(StepType::Start, |s| s.step);
            assert_eq!(o.step, expect.code(), "{p:?} row {}", r.y);
            assert_eq!(o.y, r.y as u32);
        }
    }

    /// Named triangles for the walkers' tests (this block's and the four-triangle block's):
    /// right angles either way, a general one in both windings, slivers across the whole
    /// screen, the smallest, a zero-area line and a point.
    pub(crate) const NAMED_TRIANGLES: [[(i32, i32); 3]; 10] = [
        [(0, 0), (10, 0), (0, 10)],
        [(0, 0), (10, 0), (10, 10)],
        [(5, 0), (0, 10), (10, 10)],
        [(3, 1), (40, 7), (11, 30)],
        [(40, 1), (3, 7), (11, 30)],
        [(0, 0), (4095, 1), (0, 2)],
        [(4095, 0), (0, 4095), (4095, 4095)],
        [(0, 0), (1, 0), (0, 1)],
        [(0, 0), (1, 1), (2, 2)],
        [(7, 7), (7, 7), (7, 7)],
    ];

    #[test]
    fn named_triangles_follow_the_walk() {
        for p in NAMED_TRIANGLES {
            check(p);
        }
    }

    #[test]
    fn back_to_back_triangles_have_no_gap_when_long_enough() {
        // The first triangle ends with long rows, so the second's load latency is hidden.
        let ts = [
            tri([(0, 0), (0, 50), (50, 50)]),
            tri([(50, 0), (50, 50), (0, 0)]),
        ];
        let setups: Vec<_> = ts.iter().map(AddressSetup::new).collect();
        let (out, _) = run(&setups);
        let events: usize = ts
            .iter()
            .flat_map(|t| walk(t).rows)
            .map(|r| r.len.max(1) as usize)
            .sum();
        assert_eq!(out.len(), 3 + events);
        let mut expect: Vec<_> = walk(&ts[0]).pixels();
        expect.extend(walk(&ts[1]).pixels());
        assert_eq!(stream_pixels(&out), expect);
    }
}
