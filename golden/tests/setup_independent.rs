//! Independent checks of the set-up code that both the RTL's inputs and the golden expectations
//! come from (a wrong set-up would pass every testbench): the subdivision's midpoint normals
//! and planes, and the refinement's midpoint vertices, each against an f64 formula written here
//! from SPEC §7 without calling the code under test.

use glam::DVec3;
use golden::shade::ShadeContext;
use golden::shading::refine::{refine, Subdivide};
use golden::types::{ScreenTriangle, ScreenVertex};

/// |v|, written out.
fn length(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The normal at the midpoint of an edge whose end normals are `a` and `b` (SPEC §7): the sum
/// of the two unit normals, made unit again — the bisector of the two directions, whatever
/// their lengths.
fn bisector(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let (la, lb) = (length(a), length(b));
    let s = [
        a[0] / la + b[0] / lb,
        a[1] / la + b[1] / lb,
        a[2] / la + b[2] / lb,
    ];
    let ls = length(s);
    [s[0] / ls, s[1] / ls, s[2] / ls]
}

fn arr(v: DVec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

#[test]
fn midpoint_normal_is_the_bisector_of_the_two_directions() {
    use golden::shading::subdivision::midpoint_normal;
    // Known values: the bisector of x and y; of 2x and 5z (lengths must not weigh in: the
    // plain mean (2, 0, 5)/√29 would be wrong).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(close(
        arr(midpoint_normal(DVec3::X, DVec3::Y)),
        [h, h, 0.0],
        1e-15
    ));
    assert!(close(
        arr(midpoint_normal(2.0 * DVec3::X, 5.0 * DVec3::Z)),
        [h, 0.0, h],
        1e-15
    ));
    // Seeded pairs against the formula above, and the bisector's own properties: unit, at equal
    // angles to both, in their plane.
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut r = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for _ in 0..2000 {
        let a = [r(), r(), r() + 1.5];
        let b = [r() * 3.0, r() * 3.0, r() * 3.0 + 4.0];
        let got = arr(midpoint_normal(DVec3::from(a), DVec3::from(b)));
        assert!(close(got, bisector(a, b), 1e-12), "{a:?} {b:?}: {got:?}");
        let cos = |u: [f64; 3]| (u[0] * got[0] + u[1] * got[1] + u[2] * got[2]) / length(u);
        assert!((cos(a) - cos(b)).abs() < 1e-12);
        let n = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        assert!((n[0] * got[0] + n[1] * got[1] + n[2] * got[2]).abs() < 1e-9 * length(n));
    }
}

/// Every lane's three planes take, at each of the lane's vertices, the exact intensity of the
/// normal SPEC §7 puts there: a parent vertex's own, or at an edge midpoint the bisector of
/// its two ends' normals. The lane vertices are identified by their coordinates (doubled: a
/// parent vertex is 2·P, a midpoint P + Q), not by the order the set-up lists them in.
#[test]
fn subdivision_planes_take_the_midpoint_intensities_at_every_lane_vertex() {
    let n = |x: f64, y: f64| DVec3::new(x, y, 1.0).normalize();
    for (points, normals) in [
        (
            [(3, 1), (40, 7), (11, 30)],
            [n(-0.5, -0.4), n(0.6, -0.2), n(0.1, 0.7)],
        ),
        // Normals of unequal lengths and a flatter light angle.
        (
            [(100, 20), (13, 61), (70, 95)],
            [3.0 * n(0.9, 0.1), 0.5 * n(-0.3, 0.8), n(0.2, -0.9)],
        ),
    ] {
        let mut tri = ScreenTriangle::from_points(points);
        for (v, nn) in tri.v.iter_mut().zip(normals) {
            v.normal = nn;
        }
        let ctx = ShadeContext::default();
        let s = golden::shading::subdivision::setup(&tri, &ctx).expect("non-degenerate");
        let p: Vec<(i64, i64)> = tri.v.iter().map(|v| (v.x as i64, v.y as i64)).collect();
        let unit = |k: usize| {
            let v = arr(tri.v[k].normal);
            let l = length(v);
            DVec3::new(v[0] / l, v[1] / l, v[2] / l)
        };
        let mut seen = 0;
        for (lane, sub) in s.subs.iter().enumerate() {
            assert_eq!(sub.frac, 1, "integer parents: half-pixel sub-triangles");
            for &(x2, y2) in &sub.v {
                let (x2, y2) = (x2 as i64, y2 as i64);
                let normal = (0..3)
                    .find(|&i| (2 * p[i].0, 2 * p[i].1) == (x2, y2))
                    .map(unit)
                    .or_else(|| {
                        [(0, 1), (0, 2), (1, 2)]
                            .into_iter()
                            .find(|&(i, j)| (p[i].0 + p[j].0, p[i].1 + p[j].1) == (x2, y2))
                            .map(|(i, j)| {
                                DVec3::from(bisector(arr(tri.v[i].normal), arr(tri.v[j].normal)))
                            })
                    })
                    .unwrap_or_else(|| panic!("lane {lane} vertex ({x2}, {y2})/2 is neither"));
                let want = ctx.exact_intensity(normal);
                for (c, (pl, w)) in s.planes[lane].iter().zip(want).enumerate() {
                    let got = pl.a * x2 as f64 / 2.0 + pl.b * y2 as f64 / 2.0 + pl.c;
                    assert!(
                        (got - w).abs() < 1e-9,
                        "lane {lane} channel {c} at ({x2}, {y2})/2: {got} against {w}"
                    );
                }
                seen += 1;
            }
        }
        assert_eq!(seen, 12);
    }
}

/// The normal and depth the parent interpolates linearly at integer point (x, y), by
/// barycentric coordinates written out (SPEC §7: a refined vertex lies on the parent's planes).
fn parent_at(t: &ScreenTriangle, x: f64, y: f64) -> ([f64; 3], f64) {
    let [a, b, c] = t.v.map(|v| (v.x as f64, v.y as f64));
    let det = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
    let l1 = ((x - a.0) * (c.1 - a.1) - (c.0 - a.0) * (y - a.1)) / det;
    let l2 = ((b.0 - a.0) * (y - a.1) - (x - a.0) * (b.1 - a.1)) / det;
    let l0 = 1.0 - l1 - l2;
    let n = |k: usize| arr(t.v[k].normal);
    let normal = [0, 1, 2].map(|i| l0 * n(0)[i] + l1 * n(1)[i] + l2 * n(2)[i]);
    (normal, l0 * t.v[0].z + l1 * t.v[1].z + l2 * t.v[2].z)
}

/// Whether (x, y) lies in `t` (barycentric coordinates ≥ 0).
fn inside(t: &ScreenTriangle, x: f64, y: f64) -> bool {
    let [a, b, c] = t.v.map(|v| (v.x as f64, v.y as f64));
    let det = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
    let l1 = ((x - a.0) * (c.1 - a.1) - (c.0 - a.0) * (y - a.1)) / det;
    let l2 = ((b.0 - a.0) * (y - a.1) - (x - a.0) * (b.1 - a.1)) / det;
    l1 >= -1e-9 && l2 >= -1e-9 && 1.0 - l1 - l2 >= -1e-9
}

/// Refining a fan whose normals tilt outwards (its spokes are interior edges, split at every
/// level): every vertex of every child lies on its parent's planes — the parent being the
/// fan triangle that holds the child's centroid — so its normal points where the parent's
/// interpolated normal points at that address (the direction, not only the length), and its
/// depth is the parent's there.
#[test]
fn refined_vertices_keep_the_parents_normal_direction_and_depth() {
    let v = |x, y, z, n: DVec3| ScreenVertex {
        x,
        y,
        z,
        normal: n,
        uv: glam::DVec2::ZERO,
        w: 1.0,
    };
    let ring: Vec<(i32, i32)> = (0..8)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 8.0;
            (
                (50.0 + 40.0 * a.cos()).round() as i32,
                (50.0 + 40.0 * a.sin()).round() as i32,
            )
        })
        .collect();
    let n = |p: (i32, i32)| DVec3::new((p.0 - 50) as f64, (p.1 - 50) as f64, 45.0).normalize();
    let depth = |p: (i32, i32)| 0.5 + 0.002 * (p.0 + 2 * p.1) as f64;
    let c = v(
        50,
        50,
        depth((50, 50)),
        DVec3::new(0.1, -0.1, 1.0).normalize(),
    );
    let fan: Vec<ScreenTriangle> = (0..8)
        .map(|k| {
            let (p, q) = (ring[k], ring[(k + 1) % 8]);
            ScreenTriangle {
                v: [c, v(p.0, p.1, depth(p), n(p)), v(q.0, q.1, depth(q), n(q))],
                frac: 0,
            }
        })
        .collect();
    for mode in [Subdivide::Levels(1), Subdivide::Levels(2), Subdivide::Auto] {
        let kids = refine(&fan, mode);
        assert!(kids.len() > fan.len(), "{mode}: not split");
        let mut off_vertex = 0;
        for k in &kids {
            let (cx, cy) = (
                k.v.iter().map(|p| p.x as f64).sum::<f64>() / 3.0,
                k.v.iter().map(|p| p.y as f64).sum::<f64>() / 3.0,
            );
            let t = fan
                .iter()
                .find(|t| inside(t, cx, cy))
                .unwrap_or_else(|| panic!("{mode}: a child outside the fan at ({cx}, {cy})"));
            for p in &k.v {
                let (want, z) = parent_at(t, p.x as f64, p.y as f64);
                let (got, lw) = (arr(p.normal), length(want));
                let cos =
                    (got[0] * want[0] + got[1] * want[1] + got[2] * want[2]) / (length(got) * lw);
                assert!(
                    cos > 1.0 - 1e-12,
                    "{mode}: ({}, {}): normal {got:?} points away from {want:?}",
                    p.x,
                    p.y
                );
                assert!(
                    (p.z - z).abs() < 1e-12,
                    "{mode}: ({}, {}): depth {} against {z}",
                    p.x,
                    p.y,
                    p.z
                );
                off_vertex += fan
                    .iter()
                    .all(|f| f.v.iter().all(|q| (q.x, q.y) != (p.x, p.y)))
                    as usize;
            }
        }
        assert!(off_vertex > 0, "{mode}: no midpoint vertex checked");
    }
}
