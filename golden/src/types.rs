//! Types shared by every part of the golden model: screen-space triangles as the software
//! set-up hands them to the hardware, and the rasterizer walk (SPEC §5) that the address block
//! reproduces.
//!
//! Conventions (documented once, used everywhere):
//! - Screen coordinates are integers, x to the right, y **down**, both in 0..=4095 (12-bit
//!   addresses, SPEC §0). Pixel (x, y) is sampled at its centre (x + 0.5, y + 0.5).
//! - Normals are unit vectors in view space (viewer looks down −z, so a front face has n.z > 0).
//! - Light and viewer are at infinity (directional), so L, V and H are constant over a frame.

use glam::{DVec2, DVec3};

/// Largest screen address: vertex coordinates must lie in `0..=MAX_ADDRESS` (12 bits).
pub const MAX_ADDRESS: i32 = 4095;

/// A vertex after projection: integer screen address, depth, unit view-space normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenVertex {
    pub x: i32,
    pub y: i32,
    /// Depth, smaller is nearer.
    pub z: f64,
    /// Unit normal in view space.
    pub normal: DVec3,
    /// Texture coordinates (s, t) of this corner, in texture repeats (1 is the texture's side;
    /// t up, as OBJ's `vt`); zero where the mesh has none.
    pub uv: DVec2,
    /// The projection's divisor w > 0 at this vertex (1 under the orthographic camera): 1/w,
    /// s/w and t/w are affine in screen space.
    pub w: f64,
}

impl ScreenVertex {
    /// A vertex at pixel address (x, y) with depth ½ and the normal +z: for tests and set-ups
    /// that need the position only.
    pub fn at(x: i32, y: i32) -> ScreenVertex {
        ScreenVertex {
            x,
            y,
            z: 0.5,
            normal: DVec3::Z,
            uv: DVec2::ZERO,
            w: 1.0,
        }
    }
}

/// A projected, front-facing triangle ready for rasterization.
///
/// Vertex coordinates are in units of 2^−`frac` pixel: `frac` = 0 (integer addresses, the
/// default projection) or [`SUBPIXEL_BITS`] (`render --subpixel 4`). Every function that takes
/// the triangle (planes, walks, set-ups) reads positions through [`ScreenTriangle::position`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenTriangle {
    pub v: [ScreenVertex; 3],
    /// Fraction bits of the vertex coordinates.
    pub frac: u32,
}

/// Fraction bits of the sub-pixel vertex coordinates the address block is built for: its error
/// words are sized for vertices with up to this many fractional bits (`rtl`'s
/// `SubpixelAddressBlock`; integer vertices are 0).
pub const SUBPIXEL_BITS: u32 = 4;

/// A triangle's screen positions with `frac` fractional bits: (x, y) in units of 2^−frac
/// pixel, in 0..=4095·2^frac, pixel (x, y) sampled at its centre (x + ½, y + ½). The fill
/// convention is `raster`'s (the top-left rule; at sub-pixel positions a centre can lie on a
/// horizontal edge or a vertex, where the rule's "top" half decides).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SubpixelTriangle {
    pub v: [(i32, i32); 3],
    pub frac: u32,
}

impl SubpixelTriangle {
    /// The vertex addresses of `tri`, with its fraction bits.
    pub fn of(tri: &ScreenTriangle) -> SubpixelTriangle {
        SubpixelTriangle {
            v: tri.v.map(|p| (p.x, p.y)),
            frac: tri.frac,
        }
    }
    /// Twice the signed area, in (2^−frac pixel)².
    pub fn area2(&self) -> i64 {
        let [a, b, c] = self.v.map(|(x, y)| (x as i64, y as i64));
        (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)
    }
}

/// Screen-space plane of a scalar attribute: value(px, py) = a·px + b·py + c, with (px, py)
/// the continuous screen position (pixel centre = x + 0.5, y + 0.5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub a: f64,
    pub b: f64,
    pub c: f64,
}

impl Plane {
    /// Plane through three (x, y, value) samples; `None` for a zero-area triangle.
    pub fn through(p: [(f64, f64, f64); 3]) -> Option<Plane> {
        let (x0, y0, v0) = p[0];
        let (x1, y1, v1) = p[1];
        let (x2, y2, v2) = p[2];
        let det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        if det == 0.0 {
            return None;
        }
        let a = ((v1 - v0) * (y2 - y0) - (v2 - v0) * (y1 - y0)) / det;
        let b = ((x1 - x0) * (v2 - v0) - (x2 - x0) * (v1 - v0)) / det;
        Some(Plane {
            a,
            b,
            c: v0 - a * x0 - b * y0,
        })
    }
    /// Value at the centre of pixel (x, y).
    pub fn at_pixel(&self, x: i32, y: i32) -> f64 {
        self.a * (x as f64 + 0.5) + self.b * (y as f64 + 0.5) + self.c
    }
}

/// Screen-space linear interpolation of a vector attribute (the three planes of x, y, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VecPlane {
    pub x: Plane,
    pub y: Plane,
    pub z: Plane,
}

impl VecPlane {
    pub fn at_pixel(&self, x: i32, y: i32) -> DVec3 {
        DVec3::new(
            self.x.at_pixel(x, y),
            self.y.at_pixel(x, y),
            self.z.at_pixel(x, y),
        )
    }
    /// Increment per horizontal step (+1 in x): ΔN_H of SPEC §1.
    pub fn delta_h(&self) -> DVec3 {
        DVec3::new(self.x.a, self.y.a, self.z.a)
    }
    /// Increment per vertical step (+1 in y): ΔN_V of SPEC §1.
    pub fn delta_v(&self) -> DVec3 {
        DVec3::new(self.x.b, self.y.b, self.z.b)
    }
}

impl ScreenTriangle {
    /// A triangle of addresses only (depth 0, normals +z): what the address block and the
    /// intensity interpolator see, for tests and benches.
    pub fn from_points(p: [(i32, i32); 3]) -> ScreenTriangle {
        ScreenTriangle {
            v: p.map(|(x, y)| ScreenVertex {
                x,
                y,
                z: 0.0,
                normal: glam::DVec3::Z,
                uv: DVec2::ZERO,
                w: 1.0,
            }),
            frac: 0,
        }
    }

    /// One unit of the vertex coordinates, in pixels (2^−frac).
    pub fn unit(&self) -> f64 {
        1.0 / (1u64 << self.frac) as f64
    }
    /// Vertex `i`'s screen position in pixels.
    pub fn position(&self, i: usize) -> (f64, f64) {
        let u = self.unit();
        (self.v[i].x as f64 * u, self.v[i].y as f64 * u)
    }

    fn samples(&self, f: impl Fn(&ScreenVertex) -> f64) -> [(f64, f64, f64); 3] {
        std::array::from_fn(|i| {
            let (x, y) = self.position(i);
            (x, y, f(&self.v[i]))
        })
    }
    /// Twice the signed area in (2^−frac pixel)² (positive when the vertices run clockwise on
    /// screen, y down).
    pub fn area2(&self) -> i64 {
        let [a, b, c] = self.v;
        (b.x - a.x) as i64 * (c.y - a.y) as i64 - (c.x - a.x) as i64 * (b.y - a.y) as i64
    }
    /// Plane of the depth; `None` for a zero-area triangle.
    pub fn depth_plane(&self) -> Option<Plane> {
        Plane::through(self.samples(|v| v.z))
    }
    /// Planes of the (unnormalized) linearly interpolated normal; `None` for zero area.
    pub fn normal_plane(&self) -> Option<VecPlane> {
        Some(VecPlane {
            x: Plane::through(self.samples(|v| v.normal.x))?,
            y: Plane::through(self.samples(|v| v.normal.y))?,
            z: Plane::through(self.samples(|v| v.normal.z))?,
        })
    }
    /// Plane of any per-vertex scalar (e.g. a Gouraud intensity); `None` for zero area.
    pub fn scalar_plane(&self, values: [f64; 3]) -> Option<Plane> {
        let s = self.samples(|_| 0.0);
        Plane::through([
            (s[0].0, s[0].1, values[0]),
            (s[1].0, s[1].1, values[1]),
            (s[2].0, s[2].1, values[2]),
        ])
    }
}

/// Kind of one rasterizer move (SPEC §5): along the raster line, down one line, or both.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum StepType {
    /// The first point of a triangle: reached by set-up, not by a step.
    Start,
    /// x ± 1, same line.
    Horizontal,
    /// y + 1, same x.
    Vertical,
    /// x ± 1 and y + 1.
    Diagonal,
}

impl StepType {
    /// Two-bit code used by the hardware and in CSV dumps: Start 0, H 1, V 2, D 3.
    pub fn code(self) -> u8 {
        match self {
            StepType::Start => 0,
            StepType::Horizontal => 1,
            StepType::Vertical => 2,
            StepType::Diagonal => 3,
        }
    }
}

/// One move of the working edge: its type and the x direction (−1, 0 or +1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeStep {
    pub step: StepType,
    pub dx: i8,
}

/// One raster line of a triangle as the SPEC §5 walk produces it.
///
/// **The walk contract** (golden rasterizer, address-block RTL and interpolators all follow it):
/// - Vertices are sorted by (y, x); the first is the *top*, the last the *bottom*. The
///   *working edge* is top→bottom; the other two edges (top→middle, then middle→bottom: the
///   *adjacent* and the *third* edge) lie on the other side. A zero-area triangle has no rows.
/// - Rows are `y_top ..= y_bottom − 1` (pixel centres y + 0.5 strictly between the vertices'
///   integer y), every one listed even when it holds no pixel.
/// - Fill rule: pixel-centre sampling, top-left rule. A centre exactly on a left edge is inside,
///   on a right edge outside (centres never lie on a horizontal edge: vertex y are integers).
/// - `dir` is +1 when the working edge is the left edge, −1 when it is the right edge.
/// - `x_start` depends on the working edge alone: the first pixel on its inner side, i.e. the
///   smallest x whose centre is on/right of it (left edge), or the largest x whose centre is
///   strictly left of it (right edge). `len` counts pixels from `x_start` in direction `dir`
///   whose centres are also inside the other side's edge for that row (0 if none).
///   Hence `x_start` spans −1..=4095 (13 bits signed), while emitted pixels lie in 0..=4094:
///   −1 occurs for a right working edge and 4095 for a left one, both only with `len` 0.
/// - `edge_steps` from the previous row's `x_start` to this one's, `dx = x_start − prev`:
///   `dx == 0` → `[V]`; otherwise `|dx| − 1` × `H(sign dx)` followed by one `D(sign dx)`.
///
/// The working edge is the edge that spans the triangle's full height; its point on this line is
/// `(x_start, y)`, reached from the previous line's start by `edge_steps` (empty on the first
/// line, where set-up places it). The line's pixels are `x_start + i·dir` for `i in 0..len`
/// (`len` may be 0: a line crossed by the triangle with no pixel centre inside).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    pub y: i32,
    pub edge_steps: Vec<EdgeStep>,
    pub x_start: i32,
    pub len: u32,
    /// Direction of the raster line from the working edge towards the other edges: −1 or +1.
    pub dir: i8,
}

/// The whole walk of one triangle, top to bottom.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct Walk {
    pub rows: Vec<Row>,
}

/// One emitted pixel with the step type that reached it (what the interpolators need).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct WalkPixel {
    pub x: i32,
    pub y: i32,
    /// `Start` for the triangle's first line start, the last edge step (V or D) for other line
    /// starts, `Horizontal` along a line.
    pub step: StepType,
    pub line_start: bool,
}

impl Walk {
    /// Every emitted pixel in walk order.
    pub fn pixels(&self) -> Vec<WalkPixel> {
        let mut out = Vec::new();
        for (r, row) in self.rows.iter().enumerate() {
            let start_step = if r == 0 {
                StepType::Start
            } else {
                row.edge_steps
                    .last()
                    .map(|s| s.step)
                    .unwrap_or(StepType::Vertical)
            };
            for i in 0..row.len as i32 {
                out.push(WalkPixel {
                    x: row.x_start + i * row.dir as i32,
                    y: row.y,
                    step: if i == 0 {
                        start_step
                    } else {
                        StepType::Horizontal
                    },
                    line_start: i == 0,
                });
            }
        }
        out
    }
    /// Number of emitted pixels.
    pub fn pixel_count(&self) -> usize {
        self.rows.iter().map(|r| r.len as usize).sum()
    }
}
