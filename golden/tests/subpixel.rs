//! Sub-pixel vertices (SPEC §5, issue 38 item 1): the walk, the address block's set-up and its
//! cycle model on triangles whose vertices carry `SUBPIXEL_BITS` fractional bits, against a
//! reference written here in f64 from the fill convention alone (no code shared with
//! `golden::raster`), on 10 000 seeded triangles with slivers and one-pixel triangles, and
//! watertightness on shared edges.

use std::collections::{HashMap, HashSet};

use golden::raster::{edge_function_pixels_of, walk_subpixel};
use golden::seed::seed_for;
use golden::units::address_block::{
    run_model, stream_pixels, AddressBlockModel, AddressSetup, EdgeSetup,
};
use golden::units::four_triangle::{
    lane_pixels, run_on, subdivide_subpixel, FourTriangleModel, FourTriangleSetup, LANES,
    SUBPIXEL_LANE_ERR_BITS,
};
use golden::{ScreenTriangle, ScreenVertex, SubpixelTriangle, SUBPIXEL_BITS};

const F: u32 = SUBPIXEL_BITS;
const ONE: i32 = 1 << F;
const MAX: i32 = 4095 * ONE;

use golden::testing::Rng;

/// A coordinate within `r` of `c`, clamped to the address range.
fn around(rng: &mut Rng, c: i32, r: i32) -> i32 {
    (c + rng.below(2 * r + 1) - r).clamp(0, MAX)
}

/// The f64 reference: pixel (x, y) is covered when its centre (x + ½, y + ½) passes the three
/// edge functions, a centre on an edge counting only for a left edge (interior on +x) or a top
/// edge (horizontal, interior below). Coordinates are dyadic with ≤ 16 significant bits, so
/// every product here is exact in f64.
fn reference(t: &SubpixelTriangle) -> HashSet<(i32, i32)> {
    let s = 1.0 / (1u32 << t.frac) as f64;
    let mut p: Vec<(f64, f64)> =
        t.v.iter()
            .map(|&(x, y)| (x as f64 * s, y as f64 * s))
            .collect();
    let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
    if area == 0.0 {
        return HashSet::new();
    }
    if area > 0.0 {
        p.swap(1, 2); // counter-clockwise on a y-down screen: interior on +x of downward edges
    }
    let xs: Vec<f64> = p.iter().map(|q| q.0).collect();
    let ys: Vec<f64> = p.iter().map(|q| q.1).collect();
    let lo = |v: &[f64]| v.iter().cloned().fold(f64::MAX, f64::min).floor() as i32 - 1;
    let hi = |v: &[f64]| v.iter().cloned().fold(f64::MIN, f64::max).ceil() as i32 + 1;
    let mut out = HashSet::new();
    for y in lo(&ys)..=hi(&ys) {
        for x in lo(&xs)..=hi(&xs) {
            let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
            let inside = (0..3).all(|i| {
                let (a, b) = (p[i], p[(i + 1) % 3]);
                let e = (cx - a.0) * (b.1 - a.1) - (cy - a.1) * (b.0 - a.0);
                let left_or_top = b.1 > a.1 || (b.1 == a.1 && b.0 < a.0);
                e > 0.0 || (e == 0.0 && left_or_top)
            });
            if inside {
                out.insert((x, y));
            }
        }
    }
    out
}

/// Seeded triangles of every shape: general, slivers, one-pixel and sub-pixel ones, and
/// vertices on pixel centres and on horizontal lines through them (where the rule's "top"
/// half decides).
fn triangles(n: usize, name: &str) -> Vec<SubpixelTriangle> {
    let mut rng = Rng(seed_for(name) | 1);
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let c = (rng.below(MAX + 1), rng.below(MAX + 1));
        let r = match i % 5 {
            0 => 40 * ONE,
            1 => 3 * ONE,
            2 => ONE,
            3 => ONE / 2,
            _ => 300 * ONE,
        };
        let mut v = [(0, 0); 3];
        for p in v.iter_mut() {
            *p = (around(&mut rng, c.0, r), around(&mut rng, c.1, r));
        }
        match i % 7 {
            // A sliver: the third vertex close to the line through the first two.
            0 => {
                let k = rng.below(ONE + 1);
                v[2] = (
                    (v[0].0 + (v[1].0 - v[0].0) * k / ONE + rng.below(3) - 1).clamp(0, MAX),
                    (v[0].1 + (v[1].1 - v[0].1) * k / ONE + rng.below(3) - 1).clamp(0, MAX),
                );
            }
            // Vertices on pixel centres.
            1 => {
                for p in v.iter_mut() {
                    *p = ((p.0 & !(ONE - 1)) + ONE / 2, (p.1 & !(ONE - 1)) + ONE / 2);
                    *p = (p.0.min(MAX), p.1.min(MAX));
                }
            }
            // A horizontal edge through a row of centres.
            2 => {
                let y = (v[0].1 & !(ONE - 1)) + ONE / 2;
                v[0].1 = y.min(MAX);
                v[1].1 = y.min(MAX);
            }
            _ => {}
        }
        out.push(SubpixelTriangle { v, frac: F });
    }
    out
}

#[test]
fn subpixel_walks_equal_the_f64_reference_on_10000_triangles() {
    let tris = triangles(10_000, "subpixel-walk");
    let (mut covered, mut empty) = (0usize, 0usize);
    for t in &tris {
        let want = reference(t);
        let walk = walk_subpixel(t);
        let got: Vec<(i32, i32)> = walk.pixels().iter().map(|p| (p.x, p.y)).collect();
        let set: HashSet<(i32, i32)> = got.iter().cloned().collect();
        assert_eq!(set.len(), got.len(), "{t:?}: a pixel twice");
        assert_eq!(set, want, "{t:?}: walk against the f64 reference");
        let ef: HashSet<(i32, i32)> = edge_function_pixels_of(t).into_iter().collect();
        assert_eq!(
            ef, want,
            "{t:?}: integer edge functions against the f64 reference"
        );
        covered += got.len();
        empty += got.is_empty() as usize;
    }
    // The stimulus reaches both kinds.
    assert!(
        covered > 100_000 && empty > 500,
        "{covered} pixels, {empty} empty"
    );
}

#[test]
fn subpixel_setups_drive_the_block_model_through_the_walk() {
    let tris = triangles(2_000, "subpixel-model");
    let setups: Vec<AddressSetup> = tris.iter().map(AddressSetup::subpixel).collect();
    let (out, _) = run_model(AddressBlockModel::subpixel(), &setups);
    let want: Vec<(i32, i32)> = tris
        .iter()
        .flat_map(|t| walk_subpixel(t).pixels().into_iter().map(|p| (p.x, p.y)))
        .collect();
    let got: Vec<(i32, i32)> = stream_pixels(&out).iter().map(|p| (p.x, p.y)).collect();
    assert_eq!(got, want);
    // The words fit the sub-pixel block's 20-bit error ports, and some need more than 13.
    let words = setups
        .iter()
        .flat_map(|s| [s.w, s.a, s.t])
        .flat_map(|e| [e.e0, e.r, e.d]);
    let widest = words.max().unwrap();
    assert!(
        ((1 << 13)..(1 << 20)).contains(&widest),
        "widest error word {widest}"
    );
}

/// The integer set-up written from the module doc's formulas alone (rows y_top..y_bottom, the
/// switch at y_mid, e = B·D − N with D = 2Δy, N(y0) = Δy·(2x0 − 1) + Δx, B found by search),
/// independent of `raster`'s grid and DDA.
fn integer_setup(v: [(i32, i32); 3]) -> AddressSetup {
    let mut s = v;
    s.sort_by_key(|&(x, y)| (y, x));
    let [top, mid, bot] = s;
    let area = (mid.0 - top.0) as i64 * (bot.1 - top.1) as i64
        - (bot.0 - top.0) as i64 * (mid.1 - top.1) as i64;
    if area == 0 {
        return AddressSetup {
            y_top: top.1 as u32,
            ..AddressSetup::default()
        };
    }
    let edge = |u: (i32, i32), l: (i32, i32)| -> EdgeSetup {
        let (dx, dy) = ((l.0 - u.0) as i64, (l.1 - u.1) as i64);
        if dy <= 0 {
            return EdgeSetup::default();
        }
        let (d, n0) = (2 * dy, dy * (2 * u.0 as i64 - 1) + dx);
        // B: the smallest x with B·D ≥ N (the centre on or right of the edge).
        let b0 = (0..=4096i64).find(|b| b * d >= n0).unwrap();
        let f = dx.div_euclid(dy);
        EdgeSetup {
            b0: b0 as u32,
            e0: (b0 * d - n0) as u32,
            f: f as i32,
            r: (2 * dx - f * d) as u32,
            d: d as u32,
        }
    };
    let t = edge(mid, bot);
    AddressSetup {
        w: edge(top, bot),
        a: if mid.1 > top.1 { edge(top, mid) } else { t },
        t,
        y_top: top.1 as u32,
        rows: (bot.1 - top.1) as u32,
        y_switch: mid.1 as u32,
        // The working edge top→bottom is the right edge when the middle vertex is on its −x
        // side: (mid − top) × (bot − top) < 0.
        dir_neg: area < 0,
    }
}

#[test]
fn integer_vertices_give_the_integer_setup() {
    let mut rng = Rng(seed_for("subpixel-integer") | 1);
    for _ in 0..5_000 {
        let c = (rng.below(4096), rng.below(4096));
        let r = [2, 20, 400][rng.below(3) as usize];
        let v: [(i32, i32); 3] = std::array::from_fn(|_| {
            let x = (c.0 + rng.below(2 * r + 1) - r).clamp(0, 4095);
            let y = (c.1 + rng.below(2 * r + 1) - r).clamp(0, 4095);
            (x, y)
        });
        let t = ScreenTriangle {
            v: v.map(|(x, y)| ScreenVertex {
                x,
                y,
                z: 0.0,
                normal: glam::DVec3::Z,
                uv: glam::DVec2::ZERO,
                w: 1.0,
            }),
            frac: 0,
        };
        let s = SubpixelTriangle::of(&t);
        assert_eq!(AddressSetup::subpixel(&s), integer_setup(v), "{v:?}");
        assert_eq!(AddressSetup::new(&t), integer_setup(v), "{v:?}");
        // The same triangle at F fractional bits covers the same pixels.
        let fine = SubpixelTriangle {
            v: v.map(|(x, y)| (x * ONE, y * ONE)),
            frac: F,
        };
        let a: Vec<_> = walk_subpixel(&fine)
            .pixels()
            .iter()
            .map(|p| (p.x, p.y))
            .collect();
        let b: Vec<_> = walk_subpixel(&s)
            .pixels()
            .iter()
            .map(|p| (p.x, p.y))
            .collect();
        assert_eq!(a, b, "{v:?}");
    }
}

/// Fans of triangles around shared sub-pixel points: every pixel of the fan's hull is covered
/// exactly once (shared edges neither twice nor never).
#[test]
fn shared_subpixel_edges_are_covered_exactly_once() {
    let mut rng = Rng(seed_for("subpixel-fans") | 1);
    for _ in 0..300 {
        let centre = (
            around(&mut rng, 2048 * ONE, 2000 * ONE),
            around(&mut rng, 2048 * ONE, 2000 * ONE),
        );
        let r = [ONE, 4 * ONE, 30 * ONE][rng.below(3) as usize];
        // A convex polygon around the centre, by angle, each vertex off the grid.
        let n = 3 + rng.below(6) as usize;
        let mut ring: Vec<(i32, i32)> = (0..n)
            .map(|k| {
                let a = (k as f64 + 0.3 * (rng.below(100) as f64 / 100.0)) * std::f64::consts::TAU
                    / n as f64;
                let d = r as f64 * (0.6 + 0.4 * rng.below(100) as f64 / 100.0);
                (
                    (centre.0 as f64 + d * a.cos()).round() as i32,
                    (centre.1 as f64 + d * a.sin()).round() as i32,
                )
            })
            .collect();
        ring.dedup();
        let mut count: HashMap<(i32, i32), u32> = HashMap::new();
        for k in 0..ring.len() {
            let t = SubpixelTriangle {
                v: [centre, ring[k], ring[(k + 1) % ring.len()]],
                frac: F,
            };
            for p in walk_subpixel(&t).pixels() {
                *count.entry((p.x, p.y)).or_default() += 1;
            }
        }
        assert!(
            count.values().all(|&c| c == 1),
            "a pixel twice in the fan {centre:?} {ring:?}"
        );
        // Nothing missing: every centre strictly inside the ring (away from its outer edges)
        // is covered.
        for y in (centre.1 - r) / ONE..=(centre.1 + r) / ONE {
            for x in (centre.0 - r) / ONE..=(centre.0 + r) / ONE {
                let c = (x * ONE + ONE / 2, y * ONE + ONE / 2);
                let inside = (0..ring.len()).all(|k| {
                    let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
                    let e = (c.0 - a.0) as i64 * (b.1 - a.1) as i64
                        - (c.1 - a.1) as i64 * (b.0 - a.0) as i64;
                    e < 0 // the ring runs clockwise on a y-down screen... either way, see below
                }) || (0..ring.len()).all(|k| {
                    let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
                    let e = (c.0 - a.0) as i64 * (b.1 - a.1) as i64
                        - (c.1 - a.1) as i64 * (b.0 - a.0) as i64;
                    e > 0
                });
                if inside {
                    assert!(
                        count.contains_key(&(x, y)),
                        "hole at {:?} in fan {centre:?} {ring:?}",
                        (x, y)
                    );
                }
            }
        }
    }
}

/// The four-triangle block with sub-pixel parents (SPEC §7 on the finer grid): on seeded
/// parents of every shape, and on integer ones, the four sub-triangles (at one more fraction
/// bit than the parent) tile
/// the parent's pixel set exactly, each judged by the f64 reference alone; and the sub-pixel
/// block's model, loaded with the parents back to back, emits on lane k exactly the f64
/// reference's pixels of every parent's sub-triangle k, in walk order.
#[test]
fn subpixel_parents_split_into_four_that_tile_them_through_the_block_model() {
    let mut tris = triangles(3_000, "subpixel-four");
    // Tall narrow parents (over 2048 pixels high, 64 wide): their words need the 21st bit.
    let mut rng = Rng(seed_for("subpixel-four-tall") | 1);
    for _ in 0..20 {
        let x = rng.below(MAX - 64 * ONE);
        let mut p = || (x + rng.below(64 * ONE), rng.below(MAX + 1));
        let (mut a, b, mut c) = (p(), p(), p());
        a.1 %= 100 * ONE;
        c.1 = MAX - c.1 % (100 * ONE);
        tris.push(SubpixelTriangle {
            v: [a, b, c],
            frac: F,
        });
    }
    // Integer parents (half-pixel sub-triangles), judged by the same reference.
    tris.extend(
        triangles(1_000, "subpixel-four-integer")
            .iter()
            .map(|t| SubpixelTriangle {
                v: t.v.map(|(x, y)| (x >> F, y >> F)),
                frac: 0,
            }),
    );
    let mut setups = Vec::new();
    let mut lanes_want: Vec<Vec<(i32, i32)>> = vec![Vec::new(); LANES];
    let mut covered = 0usize;
    for t in &tris {
        let parent = reference(t);
        let Some(subs) = subdivide_subpixel(t) else {
            assert!(parent.is_empty(), "{t:?}: no sub-triangles but pixels");
            setups.push(FourTriangleSetup::subpixel(t));
            continue;
        };
        let mut union = HashSet::new();
        for (k, sub) in subs.iter().enumerate() {
            assert_eq!(sub.frac, t.frac + 1);
            let want = reference(sub);
            for q in &want {
                assert!(union.insert(*q), "{t:?}: pixel {q:?} twice (lane {k})");
            }
            let walk: Vec<(i32, i32)> = walk_subpixel(sub)
                .pixels()
                .iter()
                .map(|p| (p.x, p.y))
                .collect();
            assert_eq!(
                walk.iter().cloned().collect::<HashSet<_>>(),
                want,
                "{t:?} lane {k}: walk against the f64 reference"
            );
            lanes_want[k].extend(walk);
        }
        assert_eq!(union, parent, "{t:?}: the four against the parent");
        covered += parent.len();
        setups.push(FourTriangleSetup::subpixel(t));
    }
    assert!(covered > 30_000, "{covered} pixels");
    let (out, _) = run_on(FourTriangleModel::subpixel(), &setups);
    for (k, want) in lanes_want.iter().enumerate() {
        let got: Vec<(i32, i32)> = lane_pixels(&out, k).iter().map(|p| (p.x, p.y)).collect();
        let first = got.iter().zip(want).position(|(g, w)| g != w);
        assert!(
            first.is_none() && got.len() == want.len(),
            "lane {k}: the block model against the walks: {} pixels against {}, first \
             difference at {first:?}",
            got.len(),
            want.len()
        );
    }
    // The words fit the lanes' 21-bit error ports, and some need more than the 20 of the
    // single sub-pixel address block.
    let words = setups.iter().flat_map(|s| {
        [s.w, s.a, s.t]
            .into_iter()
            .flat_map(|i| [i.r, i.d])
            .chain(s.lanes.iter().flat_map(|l| [l.w_e0, l.a_e0, l.t_e0]))
    });
    let widest = words.max().unwrap();
    assert!(
        ((1 << 20)..(1 << SUBPIXEL_LANE_ERR_BITS)).contains(&widest),
        "widest error word {widest}"
    );
}
