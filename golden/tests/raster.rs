//! The golden address generator (SPEC §5) against the plain edge-function rasterizer, the walk
//! contract of `types::Row`, and watertightness on tiled rectangles and culled spheres.

use std::cell::Cell;
use std::collections::HashSet;

use glam::DVec3;
use golden::raster::{edge_function_pixels, walk};
use golden::scene::{project, screen_addresses, uv_sphere, Camera};
use golden::testing::{quaternion, runner, split_vertices};
use golden::{EdgeStep, Row, ScreenTriangle, ScreenVertex, StepType, Walk};
use proptest::prelude::*;

type V = (i32, i32);

fn tri(v: [V; 3]) -> ScreenTriangle {
    ScreenTriangle {
        v: v.map(|(x, y)| ScreenVertex {
            x,
            y,
            z: 0.0,
            normal: DVec3::Z,
            uv: glam::DVec2::ZERO,
            w: 1.0,
        }),
        frac: 0,
    }
}

fn sorted_pixels(w: &Walk) -> Vec<(i32, i32)> {
    let mut p: Vec<_> = w.pixels().iter().map(|p| (p.x, p.y)).collect();
    p.sort_by_key(|&(x, y)| (y, x));
    p
}

/// Sign of (centre of pixel (x, y)) relative to the line top→bot (top.y < bot.y), computed
/// directly from the definition: (x + ½) − x_edge(y + ½), scaled by 2·(bot.y − top.y) > 0.
fn centre_vs_edge(top: V, bot: V, x: i32, y: i32) -> i64 {
    let (dx, dy) = ((bot.0 - top.0) as i64, (bot.1 - top.1) as i64);
    let lhs = (2 * x as i64 + 1) * dy;
    let rhs = 2 * top.0 as i64 * dy + dx * (2 * (y - top.1) as i64 + 1);
    (lhs - rhs).signum()
}

/// Checks one triangle's walk against the reference and every clause of the walk contract.
/// Returns Err with a description of the first violation.
fn check_walk(v: [V; 3]) -> Result<(), String> {
    let t = tri(v);
    let w = walk(&t);
    let reference = edge_function_pixels(&t);
    let got = sorted_pixels(&w);
    if got != reference {
        let g: HashSet<_> = got.iter().collect();
        let r: HashSet<_> = reference.iter().collect();
        let extra: Vec<_> = g.difference(&r).take(5).collect();
        let missing: Vec<_> = r.difference(&g).take(5).collect();
        return Err(format!(
            "{v:?}: walk has {} pixels, reference {}; extra {extra:?}, missing {missing:?}",
            got.len(),
            reference.len()
        ));
    }
    let unique: HashSet<_> = got.iter().collect();
    if unique.len() != got.len() {
        return Err(format!("{v:?}: duplicate pixels in the walk"));
    }
    if w.pixel_count() != got.len() {
        return Err(format!("{v:?}: pixel_count disagrees with pixels()"));
    }

    let mut s = v;
    s.sort_by_key(|&(x, y)| (y, x));
    let (top, mid, bot) = (s[0], s[1], s[2]);
    if t.area2() == 0 {
        return if w.rows.is_empty() {
            Ok(())
        } else {
            Err(format!("{v:?}: zero area, rows"))
        };
    }
    let ys: Vec<i32> = w.rows.iter().map(|r| r.y).collect();
    if ys != (top.1..bot.1).collect::<Vec<_>>() {
        return Err(format!("{v:?}: rows {ys:?}, want {}..{}", top.1, bot.1));
    }
    // The middle vertex is on the +x side of the working edge → working edge is the left edge.
    let cross = (mid.0 - top.0) as i64 * (bot.1 - top.1) as i64
        - (bot.0 - top.0) as i64 * (mid.1 - top.1) as i64;
    let want_dir: i8 = if cross > 0 { 1 } else { -1 };
    let mut prev: Option<&Row> = None;
    for r in &w.rows {
        if r.dir != want_dir {
            return Err(format!("{v:?}: row {} dir {} want {want_dir}", r.y, r.dir));
        }
        if !(-1..=4095).contains(&r.x_start) || (r.len > 0 && !(0..=4094).contains(&r.x_start)) {
            return Err(format!(
                "{v:?}: row {} x_start {} len {}",
                r.y, r.x_start, r.len
            ));
        }
        // x_start from the working edge alone.
        let ok = if r.dir == 1 {
            centre_vs_edge(top, bot, r.x_start, r.y) >= 0
                && centre_vs_edge(top, bot, r.x_start - 1, r.y) < 0
        } else {
            centre_vs_edge(top, bot, r.x_start, r.y) < 0
                && centre_vs_edge(top, bot, r.x_start + 1, r.y) >= 0
        };
        if !ok {
            return Err(format!(
                "{v:?}: row {} x_start {} not at the working edge",
                r.y, r.x_start
            ));
        }
        match prev {
            None => {
                if !r.edge_steps.is_empty() {
                    return Err(format!("{v:?}: first row has edge steps"));
                }
            }
            Some(p) => {
                let dx = r.x_start - p.x_start;
                check_steps(&r.edge_steps, dx).map_err(|e| format!("{v:?}: row {}: {e}", r.y))?;
            }
        }
        prev = Some(r);
    }
    // Line starts carry the step that reached them.
    for p in w.pixels().iter().filter(|p| p.line_start) {
        let r = w.rows.iter().position(|r| r.y == p.y).unwrap();
        let want = if r == 0 {
            StepType::Start
        } else {
            w.rows[r].edge_steps.last().unwrap().step
        };
        if p.step != want {
            return Err(format!(
                "{v:?}: line start at row {} has step {:?}",
                p.y, p.step
            ));
        }
    }
    Ok(())
}

/// `dx == 0` → `[V]`; otherwise `|dx| − 1` × H(sign) then D(sign).
fn check_steps(steps: &[EdgeStep], dx: i32) -> Result<(), String> {
    if dx == 0 {
        return if steps
            == [EdgeStep {
                step: StepType::Vertical,
                dx: 0,
            }] {
            Ok(())
        } else {
            Err(format!("x_start unchanged but steps {steps:?}"))
        };
    }
    let s = dx.signum() as i8;
    if steps.len() != dx.unsigned_abs() as usize {
        return Err(format!("x_start moved by {dx} in {} steps", steps.len()));
    }
    let (last, body) = steps.split_last().unwrap();
    if *last
        != (EdgeStep {
            step: StepType::Diagonal,
            dx: s,
        })
    {
        return Err(format!("last step {last:?}, want D({s})"));
    }
    if let Some(b) = body.iter().find(|b| {
        **b != (EdgeStep {
            step: StepType::Horizontal,
            dx: s,
        })
    }) {
        return Err(format!("step {b:?} before the diagonal, want H({s})"));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Generators.

const MAX: i32 = 4095;

/// A point within `size` of a random origin, all inside 0..=4095.
fn cluster(size: i32) -> impl Strategy<Value = [V; 3]> {
    (
        0..=MAX - size,
        0..=MAX - size,
        prop::array::uniform3((0..=size, 0..=size)),
    )
        .prop_map(|(ox, oy, d)| d.map(|(x, y)| (ox + x, oy + y)))
}

fn point() -> impl Strategy<Value = V> {
    (0..=MAX, 0..=MAX)
}

fn triangles() -> impl Strategy<Value = [V; 3]> {
    prop_oneof![
        // Tiny: mostly one-pixel, empty and degenerate triangles.
        4 => cluster(2),
        4 => cluster(6),
        4 => cluster(40),
        3 => cluster(400),
        // Repeated vertices.
        1 => (point(), point(), 0..3usize).prop_map(|(a, b, k)| [a, b, [a, b, a][k]]),
        1 => (cluster(30), 0..3usize).prop_map(|(t, k)| { let mut t = t; t[k] = t[(k + 1) % 3]; t }),
        // Collinear: a, a + i·d, a + j·d.
        2 => (0..=MAX, 0..=MAX, -300..=300i32, -300..=300i32, -13..=13i32, -13..=13i32)
            .prop_filter_map("collinear points off the screen", |(x, y, dx, dy, i, j)| {
                let p = |k: i32| (x + k * dx, y + k * dy);
                let t = [p(0), p(i), p(j)];
                t.iter().all(|&(x, y)| (0..=MAX).contains(&x) && (0..=MAX).contains(&y)).then_some(t)
            }),
        // A horizontal edge (flat top or flat bottom), a vertical edge, both.
        2 => (cluster(200), 0..3usize).prop_map(|(mut t, k)| { t[(k + 1) % 3].1 = t[k].1; t }),
        2 => (cluster(200), 0..3usize).prop_map(|(mut t, k)| { t[(k + 1) % 3].0 = t[k].0; t }),
        1 => (cluster(200), 0..3usize).prop_map(|(mut t, k)| {
            t[(k + 1) % 3].1 = t[k].1;
            t[(k + 2) % 3].0 = t[k].0;
            t
        }),
        // One-pixel right triangles in every orientation: (x, y), (x ± 1, y), (x, y ± 1).
        2 => (1..MAX, 1..MAX, prop::sample::select(vec![-1, 1]), prop::sample::select(vec![-1, 1]), any::<bool>())
            .prop_map(|(x, y, sx, sy, swap)| {
                if swap { [(x, y), (x, y + sy), (x + sx, y)] } else { [(x, y), (x + sx, y), (x, y + sy)] }
            }),
        // Long slivers: a far edge and a third vertex within a few pixels of it.
        3 => (point(), point(), 0..=1000i32, -3..=3i32, -3..=3i32).prop_map(|(a, b, t, ox, oy)| {
            let c = (
                (a.0 + (b.0 - a.0) * t / 1000 + ox).clamp(0, MAX),
                (a.1 + (b.1 - a.1) * t / 1000 + oy).clamp(0, MAX),
            );
            [a, b, c]
        }),
        // 4095 wide (short) and 4095 tall (narrow); the reference scans the bounding box.
        2 => (0..=64i32, 0..=MAX - 64, 0..=MAX, 0..=64i32, 0..=64i32).prop_map(|(h, y0, xc, ya, yb)| {
            [(0, y0 + ya.min(h)), (MAX, y0 + yb.min(h)), (xc, y0 + h)]
        }),
        2 => (0..=64i32, 0..=MAX - 64, 0..=MAX, 0..=64i32, 0..=64i32).prop_map(|(w, x0, yc, xa, xb)| {
            [(x0 + xa.min(w), 0), (x0 + xb.min(w), MAX), (x0 + w, yc)]
        }),
    ]
}

/// Every vertex order: the walk must not depend on it. k < 3: rotation by k, (k, k+1, k+2);
/// k ≥ 3: the reversed orders (−k, −k−1, −k−2), all mod 3.
fn any_order(t: [V; 3]) -> impl Strategy<Value = [V; 3]> {
    (0..6usize).prop_map(move |k| {
        let (k, sign) = (k as i32, if k < 3 { 1 } else { -1 });
        [0, 1, 2].map(|i| t[(sign * (k + i)).rem_euclid(3) as usize])
    })
}

#[test]
fn walk_equals_edge_function_rasterizer_and_obeys_contract() {
    let mut r = runner(
        "walk_equals_edge_function_rasterizer_and_obeys_contract",
        4000,
    );
    let degenerate = Cell::new(0);
    let empty_nondegenerate = Cell::new(0);
    let horizontal = Cell::new(0);
    let vertical = Cell::new(0);
    let one_pixel = Cell::new(0);
    let wide = Cell::new(0);
    let long_rows = Cell::new(0);
    let both_dirs = Cell::new([0, 0]);
    let result = r.run(&triangles().prop_flat_map(any_order), |v| {
        let t = tri(v);
        let n = edge_function_pixels(&t).len();
        let bump = |c: &Cell<i32>| c.set(c.get() + 1);
        match (t.area2() == 0, n) {
            (true, _) => bump(&degenerate),
            (false, 0) => bump(&empty_nondegenerate),
            (false, 1) => bump(&one_pixel),
            _ => {}
        }
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            if a != b && a.1 == b.1 {
                bump(&horizontal);
            }
            if a != b && a.0 == b.0 {
                bump(&vertical);
            }
        }
        let xs = v.map(|p| p.0);
        if xs.iter().max().unwrap() - xs.iter().min().unwrap() == MAX {
            bump(&wide);
        }
        let w = walk(&t);
        if let Some(r) = w.rows.first() {
            let mut d = both_dirs.get();
            d[(r.dir == 1) as usize] += 1;
            both_dirs.set(d);
        }
        if w.rows.iter().any(|r| r.edge_steps.len() > 20) {
            bump(&long_rows);
        }
        check_walk(v).map_err(TestCaseError::fail)
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    println!(
        "degenerate {}, empty {}, one-pixel {}, horizontal {}, vertical {}, 4095-wide {}, \
         rows with > 20 edge steps {}, dir −1/+1 {:?}",
        degenerate.get(),
        empty_nondegenerate.get(),
        one_pixel.get(),
        horizontal.get(),
        vertical.get(),
        wide.get(),
        long_rows.get(),
        both_dirs.get()
    );
    // The generator must keep producing the cases it exists for.
    for (name, c) in [
        ("degenerate", &degenerate),
        ("empty non-degenerate", &empty_nondegenerate),
        ("one-pixel", &one_pixel),
        ("horizontal edge", &horizontal),
        ("vertical edge", &vertical),
        ("4095-wide", &wide),
        ("x-major working edge", &long_rows),
    ] {
        assert!(c.get() >= 40, "only {} {name} cases", c.get());
    }
    assert!(
        both_dirs.get().iter().all(|&n| n >= 500),
        "{:?}",
        both_dirs.get()
    );
}

// ---------------------------------------------------------------------------------------------
// Named edge cases, expected walks derived by hand from the fill convention.

fn row(y: i32, steps: &[(StepType, i8)], x_start: i32, len: u32, dir: i8) -> Row {
    Row {
        y,
        edge_steps: steps
            .iter()
            .map(|&(step, dx)| EdgeStep { step, dx })
            .collect(),
        x_start,
        len,
        dir,
    }
}

use StepType::{Diagonal as D, Horizontal as H, Vertical as Vt};

/// Rows 0..n as a hand derivation gives them: row y starts at `x_start(y)` with `len(y)` pixels
/// in direction `dir`; the working edge takes no step on row 0 and `step(y)` on every later row.
fn expected_rows(
    n: i32,
    dir: i8,
    step: impl Fn(i32) -> (StepType, i8),
    x_start: impl Fn(i32) -> i32,
    len: impl Fn(i32) -> u32,
) -> Vec<Row> {
    (0..n)
        .map(|y| {
            let later = [step(y)];
            let steps: &[(StepType, i8)] = if y == 0 { &[] } else { &later };
            row(y, steps, x_start(y), len(y), dir)
        })
        .collect()
}

/// The walk of `v` has exactly the rows `want`, compared row by row (a failure names the row).
fn assert_walk_rows(v: [V; 3], want: &[Row]) -> Walk {
    let w = walk(&tri(v));
    assert_eq!(w.rows.len(), want.len(), "{v:?}: number of rows");
    for (got, want) in w.rows.iter().zip(want) {
        assert_eq!(got, want, "{v:?}: row {}", want.y);
    }
    w
}

/// The steps of a steep working edge one pixel wide that crosses a pixel column at row 2048:
/// vertical, and one diagonal step there.
fn turn_at_2048(y: i32) -> (StepType, i8) {
    if y == 2048 {
        (D, 1)
    } else {
        (Vt, 0)
    }
}

#[test]
fn degenerate_triangles_have_no_rows() {
    for v in golden::testing::named_with_prefix("degenerate_") {
        assert_eq!(walk(&tri(v)), Walk::default(), "{v:?}");
        assert!(edge_function_pixels(&tri(v)).is_empty(), "{v:?}");
    }
}

#[test]
fn unit_square_halves_share_the_diagonal_pixel_exactly_once() {
    // The centre (½, ½) lies on the diagonal (0,0)–(1,1). In the lower-left half the diagonal is
    // a right edge (pixel outside); in the upper-right half it is a left edge (inside).
    let lower_left = [(0, 0), (1, 1), (0, 1)];
    let upper_right = [(0, 0), (1, 0), (1, 1)];
    assert_eq!(sorted_pixels(&walk(&tri(lower_left))), vec![]);
    assert_eq!(sorted_pixels(&walk(&tri(upper_right))), vec![(0, 0)]);
    // Lower-left: top (0,0), middle (0,1), bottom (1,1): working edge is the diagonal, the
    // middle vertex is left of it → right working edge; x_start = largest x with centre strictly
    // left of x_edge(½) = ½ → −1; other edge x = 0 → len 0.
    assert_eq!(walk(&tri(lower_left)).rows, vec![row(0, &[], -1, 0, -1)]);
    // Upper-right: top (0,0), middle (1,0), bottom (1,1): left working edge; x_start 0, len 1.
    assert_eq!(walk(&tri(upper_right)).rows, vec![row(0, &[], 0, 1, 1)]);
}

#[test]
fn right_triangle_left_vertical_working_edge() {
    // (0,0),(4,0),(0,4): hypotenuse x + y = 4 is a right edge: x + ½ < 4 − (y + ½) → x < 3 − y.
    let want = expected_rows(4, 1, |_| (Vt, 0), |_| 0, |y| (3 - y) as u32);
    assert_walk_rows([(0, 0), (4, 0), (0, 4)], &want);
}

#[test]
fn flat_top_diagonal_working_edge_steps_diagonally() {
    // (0,0),(4,0),(4,4): working edge (0,0)→(4,4) is left (x_start = y), third edge x = 4 is
    // right (x ≤ 3): pixels y..=3.
    let want = expected_rows(4, 1, |_| (D, 1), |y| y, |y| (4 - y) as u32);
    assert_walk_rows([(4, 4), (0, 0), (4, 0)], &want);
}

#[test]
fn flat_bottom_right_vertical_working_edge() {
    // (4,0),(4,4),(0,4): working edge x = 4 is the right edge (x_start 3, dir −1); the adjacent
    // edge (4,0)→(0,4) is left: x + ½ ≥ 3½ − y → x ≥ 3 − y: pixels 3 down to 3 − y.
    let want = expected_rows(4, -1, |_| (Vt, 0), |_| 3, |y| (y + 1) as u32);
    assert_walk_rows([(0, 4), (4, 4), (4, 0)], &want);
}

#[test]
fn x_major_working_edge_takes_horizontal_steps_then_a_diagonal() {
    // (0,0),(10,2),(0,2): working edge (0,0)→(10,2), x_edge = 5·(y + ½); middle (0,2) is left
    // of it → right working edge. Row 0: x_edge 2.5 → x_start 1, pixels 1, 0. Row 1: x_edge 7.5
    // → x_start 6 (centre 7.5 is on the edge: outside), pixels 6..=0.
    let w = walk(&tri([(0, 0), (10, 2), (0, 2)]));
    assert_eq!(
        w.rows,
        vec![
            row(0, &[], 1, 2, -1),
            row(1, &[(H, 1), (H, 1), (H, 1), (H, 1), (D, 1)], 6, 7, -1),
        ]
    );
}

#[test]
fn full_width_one_row_triangle() {
    // (0,0),(4095,0),(0,1): one row, hypotenuse at x_edge = 4095·½ = 2047.5 is a right edge, so
    // centres x + ½ < 2047.5 → x ≤ 2046: 2047 pixels.
    let w = walk(&tri([(4095, 0), (0, 1), (0, 0)]));
    assert_eq!(w.rows, vec![row(0, &[], 0, 2047, 1)]);
}

#[test]
fn full_height_one_column_triangle() {
    // (0,0),(1,4095),(0,4095): the working edge (0,0)→(1,4095) has x_edge = (y + ½)/4095 < 1,
    // middle (0,4095) is left → right working edge. The pixel x = 0 is inside where
    // ½ < x_edge, i.e. y + ½ > 2047.5 → y ≥ 2048: 2047 pixels, x_start 0 there, −1 above.
    let inside = |y: i32| y >= 2048;
    let want = expected_rows(
        4095,
        -1,
        turn_at_2048,
        |y| if inside(y) { 0 } else { -1 },
        |y| inside(y) as u32,
    );
    let w = assert_walk_rows([(0, 0), (1, 4095), (0, 4095)], &want);
    assert_eq!(w.pixel_count(), 2047);
}

#[test]
fn x_start_reaches_4095_on_a_left_working_edge() {
    // (4094,0),(4095,10),(4095,4095): working edge (4094,0)→(4095,4095) with x_edge =
    // 4094 + (y + ½)/4095; the middle vertex is right of it → left working edge, x_start =
    // ceil(x_edge − ½): 4094 for y ≤ 2047, 4095 from y = 2048. The other side is x = 4095 (right
    // edge, centre 4094.5 inside) below y = 10 and the adjacent edge x = 4094 + (y + ½)/10 above,
    // which holds 4094.5 from y = 5.
    let want = expected_rows(
        4095,
        1,
        turn_at_2048,
        |y| if y <= 2047 { 4094 } else { 4095 },
        |y| (5..=2047).contains(&y) as u32,
    );
    let w = assert_walk_rows([(4095, 4095), (4094, 0), (4095, 10)], &want);
    assert_eq!(w.pixel_count(), 2043);
}

#[test]
fn max_extent_square_splits_into_two_triangles_without_overlap_or_hole() {
    // Both diagonals of the full 12-bit square: 4095 × 4095 pixels, each written once.
    for diag in [false, true] {
        let (a, b, c, d) = ((0, 0), (4095, 0), (4095, 4095), (0, 4095));
        let tris = if diag {
            [[a, b, c], [a, c, d]]
        } else {
            [[a, b, d], [b, c, d]]
        };
        let mut count = vec![0u8; 4096 * 4096];
        for t in tris {
            for p in walk(&tri(t)).pixels() {
                count[p.y as usize * 4096 + p.x as usize] += 1;
            }
        }
        for y in 0..4096 {
            for x in 0..4096 {
                let want = (x < 4095 && y < 4095) as u8;
                assert_eq!(
                    count[y * 4096 + x],
                    want,
                    "pixel ({x}, {y}), diagonal {diag}"
                );
            }
        }
    }
}

#[test]
fn corner_vertices_at_address_limits() {
    // Triangles up to the whole 4096² range: half of them on a second thread.
    let cases = golden::testing::named_with_prefix("corner_");
    let (a, b) = cases.split_at(cases.len() / 2);
    std::thread::scope(|s| {
        let other = s.spawn(|| a.iter().for_each(|v| check_walk(*v).unwrap()));
        b.iter().for_each(|v| check_walk(*v).unwrap());
        other.join().unwrap();
    });
}

// ---------------------------------------------------------------------------------------------
// Tiling: random triangulations of a rectangle.

/// A grid of `nx`×`ny` cells of `sx`×`sy` pixels at (x0, y0); interior vertices jittered by
/// less than a quarter cell (so every cell stays strictly convex and either diagonal splits it
/// into two properly oriented triangles), boundary vertices jittered along the boundary only.
#[derive(Clone, Debug)]
struct Grid {
    x0: i32,
    y0: i32,
    nx: usize,
    ny: usize,
    sx: i32,
    sy: i32,
    jitter: Vec<(i32, i32)>,
    diagonals: Vec<bool>,
    rotations: Vec<usize>,
}

fn grid() -> impl Strategy<Value = Grid> {
    let spacing = prop_oneof![1..=3i32, 4..=24i32, 24..=200i32];
    (1..=8usize, 1..=8usize, spacing.clone(), spacing)
        .prop_flat_map(|(nx, ny, sx, sy)| {
            let n = (nx + 1) * (ny + 1);
            let (jx, jy) = ((sx - 1) / 4, (sy - 1) / 4);
            let (w, h) = (nx as i32 * sx, ny as i32 * sy);
            (
                0..=MAX - w,
                0..=MAX - h,
                Just((nx, ny, sx, sy)),
                prop::collection::vec((-jx..=jx, -jy..=jy), n),
                prop::collection::vec(any::<bool>(), nx * ny * 2),
                prop::collection::vec(0..3usize, nx * ny * 2),
            )
        })
        .prop_map(|(x0, y0, (nx, ny, sx, sy), jitter, d, r)| Grid {
            x0,
            y0,
            nx,
            ny,
            sx,
            sy,
            jitter,
            diagonals: d,
            rotations: r,
        })
}

impl Grid {
    fn vertex(&self, i: usize, j: usize) -> V {
        let (mut jx, mut jy) = self.jitter[j * (self.nx + 1) + i];
        if i == 0 || i == self.nx {
            jx = 0;
        }
        if j == 0 || j == self.ny {
            jy = 0;
        }
        (
            self.x0 + i as i32 * self.sx + jx,
            self.y0 + j as i32 * self.sy + jy,
        )
    }

    /// Triangles as the renderer sees them after culling: clockwise on screen (area2 > 0),
    /// starting at a random vertex.
    fn triangles(&self) -> Vec<[V; 3]> {
        let mut out = Vec::new();
        for j in 0..self.ny {
            for i in 0..self.nx {
                let k = j * self.nx + i;
                let (a, b) = (self.vertex(i, j), self.vertex(i + 1, j));
                let (c, d) = (self.vertex(i + 1, j + 1), self.vertex(i, j + 1));
                let pair = if self.diagonals[k] {
                    [[a, b, c], [a, c, d]]
                } else {
                    [[a, b, d], [b, c, d]]
                };
                for (h, t) in pair.into_iter().enumerate() {
                    let area = tri(t).area2();
                    assert!(area > 0, "generator made a non-convex cell: {t:?}");
                    let r = self.rotations[2 * k + h];
                    out.push([t[r], t[(r + 1) % 3], t[(r + 2) % 3]]);
                }
            }
        }
        out
    }
}

#[test]
fn tiled_rectangles_are_covered_exactly_once() {
    let mut r = runner("tiled_rectangles_are_covered_exactly_once", 600);
    let (pixels, triangles) = (Cell::new(0usize), Cell::new(0usize));
    let result = r.run(&grid(), |g| {
        let (w, h) = (g.nx as i32 * g.sx, g.ny as i32 * g.sy);
        pixels.set(pixels.get() + (w * h) as usize);
        triangles.set(triangles.get() + 2 * g.nx * g.ny);
        // Count over the rectangle plus a 2-pixel border, to catch pixels written outside.
        let (bx, by) = (g.x0 - 2, g.y0 - 2);
        let (cw, ch) = ((w + 4) as usize, (h + 4) as usize);
        let mut count = vec![0u8; cw * ch];
        for t in g.triangles() {
            for p in walk(&tri(t)).pixels() {
                let (x, y) = ((p.x - bx) as usize, (p.y - by) as usize);
                prop_assert!(
                    x < cw && y < ch,
                    "pixel ({}, {}) far outside the rectangle",
                    p.x,
                    p.y
                );
                count[y * cw + x] += 1;
            }
        }
        for y in 0..ch {
            for x in 0..cw {
                let (px, py) = (bx + x as i32, by + y as i32);
                let inside = (g.x0..g.x0 + w).contains(&px) && (g.y0..g.y0 + h).contains(&py);
                let n = count[y * cw + x];
                prop_assert_eq!(
                    n,
                    inside as u8,
                    "pixel ({}, {}) written {} times",
                    px,
                    py,
                    n
                );
            }
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    println!(
        "{} triangles tiling {} pixels",
        triangles.get(),
        pixels.get()
    );
}

// ---------------------------------------------------------------------------------------------
// Back-face-culled spheres.

/// Convex hull (counter-clockwise on screen, y down, collinear points dropped) by the monotone
/// chain.
fn hull(mut p: Vec<V>) -> Vec<V> {
    p.sort();
    p.dedup();
    let cross = |o: V, a: V, b: V| {
        (a.0 - o.0) as i64 * (b.1 - o.1) as i64 - (a.1 - o.1) as i64 * (b.0 - o.0) as i64
    };
    let mut lower: Vec<V> = Vec::new();
    for &q in &p {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], q) <= 0 {
            lower.pop();
        }
        lower.push(q);
    }
    let mut upper: Vec<V> = Vec::new();
    for &q in p.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], q) <= 0 {
            upper.pop();
        }
        upper.push(q);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// Signed distance in pixels from the centre of pixel (x, y) to the boundary of the convex
/// polygon `poly` (positive inside).
fn inset_distance(poly: &[V], x: i32, y: i32) -> f64 {
    let n = poly.len();
    let area: i64 = (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            a.0 as i64 * b.1 as i64 - b.0 as i64 * a.1 as i64
        })
        .sum();
    let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
    (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            let (ex, ey) = ((b.0 - a.0) as f64, (b.1 - a.1) as f64);
            let cross = ex * (cy - a.1 as f64) - ey * (cx - a.0 as f64);
            cross * area.signum() as f64 / ex.hypot(ey)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Back-face-culled UV spheres at random rotations, rez and canvas sizes, with shared vertices or
/// with every triangle's vertices split (as some OBJ exporters write them): every pixel inside
/// the silhouette is written exactly once.
///
/// Why this can hold. The rounded projection of the closed sphere is a closed surface mapped
/// piecewise-linearly to the plane, so at any point the number of front-facing (positive-area)
/// triangles covering it equals the number of back-facing ones (degree 0). The fill convention
/// is the same as sampling at a point nudged by an infinitesimal (+x, +y²) from the pixel centre,
/// so the identity holds pixel by pixel. Plain rounding of the vertices can reverse sub-pixel-thin
/// triangles (at the rim, and in the slivers around the poles); the surface then folds and front
/// faces overlap. `scene::screen_addresses` finds every pixel the drawn faces would cover twice
/// and mends the faces that fold there. Checked here, each can fail:
/// - front coverage (the walk of the kept faces) equals back coverage (the edge-function
///   reference on the culled faces, same addresses) at every pixel;
/// - no pixel is written more than once;
/// - no hole: every unwritten pixel connects (4-neighbours, through unwritten pixels) to the
///   outside of the canvas, every pixel more than 1.5 px inside the convex hull of the addresses
///   is written (rounding notches the rim by up to ~1.4 px), and none outside it is;
/// - where plain rounding writes no pixel twice, the addresses are exactly the rounded ones;
/// - plain rounding *would* write pixels twice in a good share of the cases (so the repair is
///   exercised; the count and the repair's moves are printed).
#[test]
fn culled_spheres_are_written_exactly_once() {
    let mut r = runner("culled_spheres_are_written_exactly_once", 240);
    let rez = prop::sample::select(vec![3u32, 4, 5, 8, 13, 25, 50, 100]);
    let size = prop_oneof![8..=40u32, 40..=400u32];
    let folding_cases = Cell::new(0);
    let plain_double_writes = Cell::new(0usize);
    let moved = Cell::new(0usize);
    let vertices = Cell::new(0usize);
    let largest_move = Cell::new(0.0f64);
    let largest_move_big = Cell::new(0.0f64);
    let result = r.run(
        &(rez, quaternion(), size.clone(), size, any::<bool>()),
        |(rez, q, w, h, split)| {
            let mesh = uv_sphere(rez).unwrap();
            let mesh = if split { split_vertices(&mesh) } else { mesh };
            let cam = Camera::fit(&mesh, w, h, q);
            let front = project(&mesh, &cam, w, h).unwrap();
            prop_assert!(!front.is_empty());
            let idx = |x: i32, y: i32| (y as u32 * w + x as u32) as usize;
            let mut count = vec![0u8; (w * h) as usize];
            for t in &front {
                prop_assert!(t.area2() > 0);
                for p in walk(t).pixels() {
                    prop_assert!(p.x >= 0 && p.y >= 0 && (p.x as u32) < w && (p.y as u32) < h);
                    count[idx(p.x, p.y)] += 1;
                }
            }
            let exact: Vec<_> = mesh.positions.iter().map(|&p| cam.screen(p)).collect();
            let addr = screen_addresses(&mesh, &cam);
            let verts: Vec<V> = addr.iter().map(|a| (a.x as i32, a.y as i32)).collect();
            let rounded: Vec<V> = exact
                .iter()
                .map(|s| (s.x.round() as i32, s.y.round() as i32))
                .collect();
            for (k, (a, s)) in addr.iter().zip(&exact).enumerate() {
                prop_assert!(a.x.fract() == 0.0 && a.y.fract() == 0.0, "vertex {}", k);
                let d = a.distance(s.truncate());
                if verts[k] != rounded[k] {
                    moved.set(moved.get() + 1);
                }
                largest_move.set(largest_move.get().max(d));
                if w.min(h) >= 100 {
                    largest_move_big.set(largest_move_big.get().max(d));
                }
            }
            vertices.set(vertices.get() + verts.len());
            // Plain rounding, for comparison: how many pixels would its front faces write twice?
            let mut plain = vec![0u8; (w * h) as usize];
            for t in &mesh.triangles {
                let st = tri([t[0], t[2], t[1]].map(|i| rounded[i as usize]));
                if st.area2() > 0 {
                    for (x, y) in edge_function_pixels(&st) {
                        if x >= 0 && y >= 0 && (x as u32) < w && (y as u32) < h {
                            plain[idx(x, y)] += 1;
                        }
                    }
                }
            }
            let plain_doubles = plain.iter().filter(|&&n| n > 1).count();
            if plain_doubles > 0 {
                folding_cases.set(folding_cases.get() + 1);
                plain_double_writes.set(plain_double_writes.get() + plain_doubles);
            } else {
                prop_assert!(
                    verts == rounded,
                    "plain rounding writes no pixel twice, yet the repair moved vertices"
                );
            }
            let mut back = vec![0u8; (w * h) as usize];
            let mut n_back = 0;
            for t in &mesh.triangles {
                let st = tri(t.map(|i| verts[i as usize]));
                // Back faces wind clockwise as seen: area2 > 0 in the mesh's order.
                if st.area2() > 0 {
                    n_back += 1;
                    for (x, y) in edge_function_pixels(&st) {
                        back[idx(x, y)] += 1;
                    }
                }
            }
            prop_assert!(n_back > 0);
            let outline = hull(verts);
            for y in 0..h as i32 {
                for x in 0..w as i32 {
                    let (n, b) = (count[idx(x, y)], back[idx(x, y)]);
                    let at = format!("pixel ({x}, {y}), rez {rez}, {w}x{h}");
                    prop_assert_eq!(n, b, "{}: front {} back {}", at, n, b);
                    prop_assert!(n <= 1, "{} written {} times", at, n);
                    let d = inset_distance(&outline, x, y);
                    prop_assert!(
                        d < 1.5 || n == 1,
                        "{}: hole {} px inside the outline",
                        at,
                        d
                    );
                    prop_assert!(d >= 0.0 || n == 0, "{}: written outside the outline", at);
                }
            }
            // Unwritten pixels not reachable from outside the canvas are holes.
            let mut outside = vec![false; (w * h) as usize];
            let mut stack: Vec<V> = Vec::new();
            for x in 0..w as i32 {
                stack.push((x, 0));
                stack.push((x, h as i32 - 1));
            }
            for y in 0..h as i32 {
                stack.push((0, y));
                stack.push((w as i32 - 1, y));
            }
            while let Some((x, y)) = stack.pop() {
                if x < 0 || y < 0 || x >= w as i32 || y >= h as i32 {
                    continue;
                }
                let i = idx(x, y);
                if outside[i] || count[i] != 0 {
                    continue;
                }
                outside[i] = true;
                stack.extend([(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)]);
            }
            for y in 0..h as i32 {
                for x in 0..w as i32 {
                    let i = idx(x, y);
                    prop_assert!(
                        count[i] == 1 || outside[i],
                        "hole at ({}, {}), rez {}, {}x{}",
                        x,
                        y,
                        rez,
                        w,
                        h
                    );
                }
            }
            Ok(())
        },
    );
    if let Err(e) = result {
        panic!("{e}");
    }
    println!(
        "240 cases written exactly once; plain rounding would have written {} pixels twice, in \
         {} of them; the repair moved {} of {} vertices, at most {:.2} px from the continuous \
         position ({:.2} px on canvases of at least 100 px)",
        plain_double_writes.get(),
        folding_cases.get(),
        moved.get(),
        vertices.get(),
        largest_move.get(),
        largest_move_big.get()
    );
    assert!(
        folding_cases.get() >= 40,
        "too few cases where plain rounding writes a pixel twice ({}): the repair is barely \
         exercised",
        folding_cases.get()
    );
}

/// The shared named cases parse, have unique names, stay inside 12-bit addresses, and give
/// intensities for every triangle where they give any.
#[test]
fn named_triangles_are_well_formed() {
    let cases = golden::testing::named_triangles();
    let names: std::collections::HashSet<&str> = cases.iter().map(|c| c.name).collect();
    assert_eq!(names.len(), cases.len(), "duplicate names");
    assert!(cases.len() >= 40, "{} cases", cases.len());
    for c in &cases {
        assert!(c
            .tris
            .iter()
            .flatten()
            .all(|&(x, y)| (0..=4095).contains(&x) && (0..=4095).contains(&y)));
        assert!(
            c.values.as_ref().is_none_or(|v| v.len() == c.tris.len()),
            "{}",
            c.name
        );
    }
    assert_eq!(golden::testing::named_with_prefix("corner_").len(), 7);
    assert_eq!(golden::testing::named_with_prefix("degenerate_").len(), 9);
}
