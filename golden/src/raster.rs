//! The golden address generator (SPEC §5): the edge walk the address block reproduces, and a
//! plain bounding-box edge-function rasterizer beside it as the reference.
//!
//! # Fill convention
//!
//! - Vertices have integer screen coordinates (x right, y down, 0..=4095). Pixel (x, y) is
//!   sampled at its centre (x + ½, y + ½).
//! - A pixel belongs to a triangle when its centre is strictly inside, or exactly on a *left*
//!   edge (an edge with the interior on its +x side). Centres on a *right* edge are outside.
//!   This is the top-left rule; its "top" half never applies, because a horizontal edge lies on
//!   an integer y and centres lie on half-integers. Centres never coincide with a vertex either.
//! - Consequences: two triangles sharing an edge never both own a pixel and never both miss one
//!   (watertight tiling); a zero-area triangle owns no pixel; the last column and row of a
//!   triangle's bounding box (x = max vertex x, y = max vertex y) are never covered, so a
//!   triangle with vertices in 0..=4095 only writes pixels in 0..=4094.
//!
//! # Arithmetic
//!
//! Integer only. Coordinates are doubled so pixel centres (2x + 1, 2y + 1) are integers; an
//! edge A→B (doubled, B below A) has the edge function
//! `F(P) = (P.x − A.x)·(B.y − A.y) − (P.y − A.y)·(B.x − A.x)`, which is ≥ 0 exactly when P is on
//! or right of the edge. Its magnitude stays below 2·8190² < 2³¹ for 12-bit vertices; it is kept
//! in `i64` anyway so intermediate sums never need a width argument.
//!
//! # Sub-pixel vertices
//!
//! [`walk_subpixel`] and [`edge_function_pixels_of`] take a [`SubpixelTriangle`], whose
//! coordinates have `frac` fractional bits, in the units of a [`Grid`] (one pixel 2^max(frac, 1)
//! units, every centre an integer). The convention is the same; a centre can now lie on a
//! horizontal edge or on a vertex, and the top-left rule's "top" half applies: a centre on a
//! horizontal edge belongs to the triangle below it, and the rows of a walk are those whose
//! centres lie in [top.y, bottom.y). The integer functions are the case frac = 0.
//!
//! Each edge is tracked by a Bresenham-style DDA ([`EdgeDda`]): `c` is the smallest x whose
//! centre is on or right of the edge on the current row, `e = F(c)` its error term, kept in
//! `0..2·ΔY` (ΔY doubled). One row down subtracts `2·ΔX` from `e`; each correction of `e` by
//! `±2·ΔY` moves `c` by one pixel, which is one horizontal step of the edge.

use crate::types::{EdgeStep, Row, ScreenTriangle, StepType, SubpixelTriangle, Walk};

/// Integer point in doubled coordinates.
pub type P2 = (i64, i64);

/// Edge function of the directed edge a→b at point p (all doubled). Positive on the right of
/// a→b when a→b points down the screen (y grows), i.e. on the +x side.
fn edge_fn(a: P2, b: P2, p: P2) -> i64 {
    (p.0 - a.0) * (b.1 - a.1) - (p.1 - a.1) * (b.0 - a.0)
}

/// Ceiling of n / d for d > 0.
fn div_ceil(n: i64, d: i64) -> i64 {
    debug_assert!(d > 0);
    -((-n).div_euclid(d))
}

/// Bresenham-style tracker of one non-horizontal edge, one raster line at a time.
#[derive(Clone, Copy, Debug)]
pub struct EdgeDda {
    /// Top end of the edge (doubled coordinates).
    a: P2,
    /// ΔX, ΔY of the edge (doubled), ΔY > 0.
    dx: i64,
    dy: i64,
    /// Current raster line.
    y: i64,
    /// Smallest x whose centre is on or right of the edge on line `y`.
    c: i64,
    /// Error term: F at the centre of pixel (c, y); always in `0..pix·dy`.
    e: i64,
    /// One pixel in the DDA's units (2 for integer vertices).
    pix: i64,
}

/// The units a walk works in: vertex coordinates with `frac` fractional bits, scaled so that
/// pixel centres are integers.
///
/// With m = max(frac, 1), one pixel is 2^m units and pixel x's centre is 2^m·x + 2^(m−1); a
/// vertex coordinate v (in 2^−frac pixel) is v·2^(m−frac) units. Integer vertices (frac = 0)
/// are the doubled coordinates of the module doc.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Grid {
    /// Vertex scale 2^(m − frac): 2 for frac = 0, else 1.
    pub k: i64,
    /// One pixel, 2^m.
    pub pix: i64,
}

impl Grid {
    pub fn of(frac: u32) -> Grid {
        let m = frac.max(1);
        Grid {
            k: 1 << (m - frac),
            pix: 1 << m,
        }
    }
    /// A vertex in these units.
    pub fn point(&self, p: (i32, i32)) -> P2 {
        (p.0 as i64 * self.k, p.1 as i64 * self.k)
    }
    /// The centre of pixel (x, y).
    pub fn centre(&self, x: i64, y: i64) -> P2 {
        (self.pix * x + self.pix / 2, self.pix * y + self.pix / 2)
    }
    /// The first raster line whose centre is at or below `y` (a coordinate in 2^−frac pixel).
    pub fn row_at_or_below(&self, y: i32) -> i64 {
        div_ceil(y as i64 * self.k - self.pix / 2, self.pix)
    }
}

impl EdgeDda {
    /// Edge from `top` to `bottom` (integer screen coordinates, `top.y < bottom.y`), placed on
    /// raster line `y` (the set-up the software does once per edge).
    pub fn new(top: (i32, i32), bottom: (i32, i32), y: i32) -> EdgeDda {
        EdgeDda::new_in(Grid::of(0), top, bottom, y)
    }

    /// [`EdgeDda::new`] for vertices in the units of `g` (coordinates in 2^−frac pixel).
    pub fn new_in(g: Grid, top: (i32, i32), bottom: (i32, i32), y: i32) -> EdgeDda {
        let a = g.point(top);
        let b = g.point(bottom);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        assert!(dy > 0, "EdgeDda needs a downward edge");
        let (half, yc) = (g.pix / 2, g.centre(0, y as i64).1);
        // F(x) = (pix·x + half − a.x)·dy − (yc − a.y)·dx ≥ 0
        //   ⇔  x ≥ (dy·(a.x − half) + (yc − a.y)·dx) / (pix·dy)
        let c = div_ceil(dy * (a.0 - half) + (yc - a.1) * dx, g.pix * dy);
        let e = edge_fn(a, b, g.centre(c, y as i64));
        debug_assert!((0..g.pix * dy).contains(&e));
        EdgeDda {
            a,
            dx,
            dy,
            y: y as i64,
            c,
            e,
            pix: g.pix,
        }
    }

    /// The error term and the per-line change in the units of the hardware's words (see
    /// `units::address_block`): (e, pix·dx, pix·dy) divided by the vertex scale `g.k`.
    pub fn words(&self, g: Grid) -> (i64, i64, i64) {
        debug_assert_eq!(self.e % g.k, 0);
        (
            self.e / g.k,
            self.pix * self.dx / g.k,
            self.pix * self.dy / g.k,
        )
    }

    /// Smallest x whose centre is on or right of the edge on the current line.
    pub fn boundary(&self) -> i32 {
        self.c as i32
    }

    /// Current raster line.
    pub fn line(&self) -> i32 {
        self.y as i32
    }

    /// Moves to the next raster line; returns the signed number of horizontal pixel moves of
    /// the boundary (`c_new − c_old`), made one pixel at a time as the hardware does.
    pub fn next_line(&mut self) -> i64 {
        self.y += 1;
        self.e -= self.pix * self.dx;
        let mut moved = 0;
        while self.e < 0 {
            self.c += 1;
            self.e += self.pix * self.dy;
            moved += 1;
        }
        while self.e >= self.pix * self.dy {
            self.c -= 1;
            self.e -= self.pix * self.dy;
            moved -= 1;
        }
        debug_assert_eq!(
            self.e,
            edge_fn(
                self.a,
                (self.a.0 + self.dx, self.a.1 + self.dy),
                (
                    self.pix * self.c + self.pix / 2,
                    self.pix * self.y + self.pix / 2
                )
            )
        );
        moved
    }
}

/// Edge steps of a working-edge move by `dx` pixels: `[V]` for 0, otherwise `|dx| − 1`
/// horizontal steps and one diagonal, all in the direction of `dx`.
pub fn edge_steps(dx: i64) -> Vec<EdgeStep> {
    if dx == 0 {
        return vec![EdgeStep {
            step: StepType::Vertical,
            dx: 0,
        }];
    }
    let s = dx.signum() as i8;
    let mut v = vec![
        EdgeStep {
            step: StepType::Horizontal,
            dx: s
        };
        (dx.unsigned_abs() - 1) as usize
    ];
    v.push(EdgeStep {
        step: StepType::Diagonal,
        dx: s,
    });
    v
}

/// A triangle's vertices in walk order and the side of its working edge (walk contract in
/// `types.rs`): the single place both the walk and the address block's set-up take them from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Orientation {
    pub top: (i32, i32),
    pub mid: (i32, i32),
    pub bot: (i32, i32),
    /// The working edge top→bottom is the left edge (lines run towards +x).
    pub left: bool,
}

/// Sort by (y, x) and find the working edge's side; `None` for a zero-area triangle.
pub fn orientation(tri: &ScreenTriangle) -> Option<Orientation> {
    orientation_of(&SubpixelTriangle::of(tri))
}

/// [`orientation`] of a triangle with sub-pixel vertices (the points stay in its units).
pub fn orientation_of(tri: &SubpixelTriangle) -> Option<Orientation> {
    if tri.area2() == 0 {
        return None;
    }
    let mut v = tri.v;
    v.sort_by_key(|&(x, y)| (y, x));
    let (top, mid, bot) = (v[0], v[1], v[2]);
    // Working edge top→bottom is the left edge when the middle vertex is on its +x side.
    let g = Grid::of(tri.frac);
    let side = edge_fn(g.point(top), g.point(bot), g.point(mid));
    debug_assert!(side != 0);
    Some(Orientation {
        top,
        mid,
        bot,
        left: side > 0,
    })
}

/// The raster lines of a triangle's walk: the first one, the end (exclusive) and the line where
/// the third edge takes over, from the first line whose centre is at or below each vertex
/// (a centre on a vertex's line belongs to the edges below it: the top half of the top-left rule).
pub fn walk_rows(tri: &SubpixelTriangle, o: &Orientation) -> (i64, i64, i64) {
    let g = Grid::of(tri.frac);
    (
        g.row_at_or_below(o.top.1),
        g.row_at_or_below(o.bot.1),
        g.row_at_or_below(o.mid.1),
    )
}

/// The SPEC §5 walk of one triangle, following the walk contract in the doc of [`Row`].
///
/// The working edge (top→bottom) and the other side's current edge (top→middle, then
/// middle→bottom) are each tracked by an [`EdgeDda`]; a row's length is the distance between
/// the two boundaries. Zero-area triangles give an empty walk.
pub fn walk(tri: &ScreenTriangle) -> Walk {
    walk_subpixel(&SubpixelTriangle::of(tri))
}

/// [`walk`] of a triangle with sub-pixel vertices: the rows whose centres lie in
/// [top.y, bottom.y), each edge's boundary taken at the row's centre.
pub fn walk_subpixel(tri: &SubpixelTriangle) -> Walk {
    let Some(o) = orientation_of(tri) else {
        return Walk::default();
    };
    let Orientation {
        top,
        mid,
        bot,
        left,
    } = o;
    let (y_first, y_end, y_switch) = walk_rows(tri, &o);
    if y_end <= y_first {
        return Walk::default();
    }
    let g = Grid::of(tri.frac);
    let dir: i8 = if left { 1 } else { -1 };
    let first = y_first as i32;
    let mut working = EdgeDda::new_in(g, top, bot, first);
    let mut other = if y_switch > y_first {
        EdgeDda::new_in(g, top, mid, first)
    } else {
        EdgeDda::new_in(g, mid, bot, first)
    };
    let mut rows = Vec::with_capacity((y_end - y_first) as usize);
    for y in y_first..y_end {
        let mut steps = Vec::new();
        if y > y_first {
            steps = edge_steps(working.next_line());
            if y == y_switch {
                // The adjacent edge is done: load the third edge.
                other = EdgeDda::new_in(g, mid, bot, y as i32);
            } else {
                other.next_line();
            }
        }
        debug_assert_eq!((working.line() as i64, other.line() as i64), (y, y));
        let (x_start, len) = if left {
            // Pixels x_start..other.boundary() (right edge: strictly left of it).
            (working.boundary(), other.boundary() - working.boundary())
        } else {
            // Pixels other.boundary()..=x_start (left edge: on or right of it).
            (
                working.boundary() - 1,
                working.boundary() - other.boundary(),
            )
        };
        rows.push(Row {
            y: y as i32,
            edge_steps: steps,
            x_start,
            len: len.max(0) as u32,
            dir,
        });
    }
    Walk { rows }
}

/// Reference rasterizer: every pixel of the bounding box whose centre passes the three edge
/// functions under the fill convention of this module, in row-major order (y, then x).
pub fn edge_function_pixels(tri: &ScreenTriangle) -> Vec<(i32, i32)> {
    edge_function_pixels_of(&SubpixelTriangle::of(tri))
}

/// [`edge_function_pixels`] of a triangle with sub-pixel vertices, under the full top-left
/// rule: a centre on an edge belongs to the triangle for a left edge (interior on +x) or a top
/// edge (horizontal, interior below).
pub fn edge_function_pixels_of(tri: &SubpixelTriangle) -> Vec<(i32, i32)> {
    let g = Grid::of(tri.frac);
    let mut p: [P2; 3] = tri.v.map(|v| g.point(v));
    let area = tri.area2();
    if area == 0 {
        return Vec::new();
    }
    if area > 0 {
        p.swap(1, 2);
    }
    // Now the vertices run counter-clockwise on screen (y down): the interior is on the +x side
    // of every downward edge, i.e. edge_fn > 0 inside. On the edge itself (edge_fn == 0) the
    // pixel is inside only for a left edge (interior on +x: the edge points down, b.y > a.y) or
    // a top edge (horizontal with the interior below: the edge points to −x).
    let edges: Vec<(P2, P2, bool)> = (0..3)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 3]);
            let owns_ties = b.1 > a.1 || (b.1 == a.1 && b.0 < a.0);
            (a, b, owns_ties)
        })
        .collect();
    // Pixel range: every pixel whose centre can lie in the closed bounding box.
    let lo = |c: i64| div_ceil(c - g.pix / 2, g.pix);
    let hi = |c: i64| (c - g.pix / 2).div_euclid(g.pix);
    let xs = p.map(|v| v.0);
    let ys = p.map(|v| v.1);
    let (x0, x1) = (lo(*xs.iter().min().unwrap()), hi(*xs.iter().max().unwrap()));
    let (y0, y1) = (lo(*ys.iter().min().unwrap()), hi(*ys.iter().max().unwrap()));
    let mut out = Vec::new();
    for y in y0..=y1 {
        for x in x0..=x1 {
            let c = g.centre(x, y);
            let inside = edges.iter().all(|&(a, b, ties)| {
                let f = edge_fn(a, b, c);
                f > 0 || (f == 0 && ties)
            });
            if inside {
                out.push((x as i32, y as i32));
            }
        }
    }
    out
}
