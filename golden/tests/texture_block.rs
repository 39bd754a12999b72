//! The texture-coordinate block's set-up and cycle twin (`golden::units::texture_coord::block`),
//! behind the address block's cycle model with the block's `ready` as the address block's
//! `hold`: on seeded perspective triangles, every pixel the twin emits is the address block's
//! next pixel, and its (u, v) is the nearest texel of the exact quotients of the integer
//! coefficients, computed here by division and not through the set-up's words (the set-up's
//! independent check). Against the f64 planes the coefficients were rounded from, a texel may
//! differ only where the exact u lies within the coefficients' rounding of a texel boundary;
//! the count is printed. Every fifth triangle is affine with N/D on half texels at many
//! pixels (the tie rule: up). Clocks per pixel are measured for k = 1 and 2.

use golden::raster;
use golden::seed::seed_for;
use golden::types::{ScreenTriangle, ScreenVertex};
use golden::units::address_block::{AddressBlockModel, AddressSetup};
use golden::units::texture_coord::block::{walk_geometry, TexCoordModel, TexCoordSetup, TexEvent};
use golden::units::texture_coord::{nearest_texel, tie_coeffs, PctCoeffs, PctPlanes};

use golden::testing::Rng;

struct Tri {
    addr: AddressSetup,
    setup: TexCoordSetup,
    cu: PctCoeffs,
    cv: PctCoeffs,
    /// The f64 planes the coefficients were rounded from (none for the tie triangles).
    planes: Option<PctPlanes>,
    origin: (i64, i64),
    /// The walk's pixels, from the address block alone.
    pixels: Vec<(u32, u32)>,
}

/// Seeded triangles: small and medium boxes and slivers, depth ratio up to `ratio` between
/// vertices, texel coordinates spanning up to `span` texels per pixel of the box. Out-of-range ones are dropped
/// (counted).
fn triangles(seed: u64, n: usize, ratio: f64, span: f64) -> (Vec<Tri>, usize) {
    let mut rng = Rng(seed | 1);
    let (mut out, mut dropped) = (Vec::new(), 0);
    while out.len() < n {
        let size = [12, 60, 300][rng.below(3) as usize];
        let (x0, y0) = (rng.below(3000), rng.below(3000));
        let v = [0; 3].map(|_| (x0 + rng.below(size), y0 + rng.below(size)));
        let tri = ScreenTriangle {
            v: v.map(|(x, y)| ScreenVertex::at(x, y)),
            frac: 0,
        };
        let addr = AddressSetup::new(&tri);
        let w = [0; 3].map(|_| rng.range(0.0, ratio.ln()).exp());
        let r = span * size as f64;
        let st = [0; 3].map(|_| (rng.range(-r, r), rng.range(-r, r)));
        let p = v.map(|(x, y)| (x as f64, y as f64));
        let Some(planes) = PctPlanes::new(p, w, st) else {
            continue;
        };
        let (origin, f, dir) = walk_geometry(&addr);
        let vmax = w.iter().map(|w| 1.0 / w).fold(0.0, f64::max);
        let (mut cu, mut cv) = planes.coeffs(origin, vmax, (1u64 << 29) as f64);
        let mut planes = Some(planes);
        if out.len() % 5 == 4 {
            planes = None;
            // Ties: u = x/2 − y/4, v = 3y/4 + x/2 exactly, on half texels at many pixels.
            (cu, cv) = tie_coeffs();
        }
        let pixels: Vec<(u32, u32)> = raster::walk(&tri)
            .pixels()
            .iter()
            .map(|p| (p.x as u32, p.y as u32))
            .collect();
        let rel: Vec<(i64, i64)> = pixels
            .iter()
            .map(|&(x, y)| (x as i64 - origin.0, y as i64 - origin.1))
            .collect();
        if TexCoordSetup::check(&cu, &cv, &rel).is_err() {
            dropped += 1;
            continue;
        }
        let setup = TexCoordSetup::new(&cu, &cv, f, dir);
        out.push(Tri {
            addr,
            setup,
            cu,
            cv,
            planes,
            origin,
            pixels,
        });
    }
    (out, dropped)
}

struct Run {
    clocks: u64,
    pixels: u64,
    steps: u64,
    /// Texels differing from the f64 planes' nearest texel, and the largest ratio of such an
    /// exact u's distance from the texel boundary to the coefficients' rounding bound there.
    f64_diffs: u64,
    f64_worst_tie: f64,
}

/// The address block and the twin as one system, `ready` holding the address block.
fn run(tris: &[Tri], k: u32) -> Run {
    let mut addr = AddressBlockModel::new();
    let mut tex = TexCoordModel::new(k);
    let want: Vec<(usize, u32, u32)> = tris
        .iter()
        .enumerate()
        .flat_map(|(i, t)| t.pixels.iter().map(move |&(x, y)| (i, x, y)))
        .collect();
    let (mut next_load, mut got, mut clocks) = (0, 0, 0u64);
    // A triangle's shadow set-up may be written once the previous one's first event is taken.
    let mut first_taken = true;
    let (mut f64_diffs, mut worst) = (0, 0.0f64);
    while got < want.len() {
        clocks += 1;
        assert!(clocks < 50_000_000, "no progress");
        let o = tex.outputs();
        if o.valid {
            let (i, x, y) = want[got];
            assert_eq!((o.x, o.y), (x, y), "pixel {got} out of order");
            let t = &tris[i];
            let (rx, ry) = (x as i64 - t.origin.0, y as i64 - t.origin.1);
            let nu = nearest_texel(&t.cu, rx, ry);
            let nv = nearest_texel(&t.cv, rx, ry);
            assert_eq!(
                (o.u, o.v),
                (nu, nv),
                "triangle {i} pixel ({x}, {y}): twin's texel is not the nearest of the quotient"
            );
            if let Some(planes) = &t.planes {
                let (eu, ev) = planes.exact(x as i64, y as i64);
                // Rounding a, b, c, g, h, i moves N and D by at most ½(1 + |x| + |y|) each (x, y
                // relative to the origin), so the quotient by at most that·(1 + |u|)/(D − that).
                let eps = 0.5 * (1.0 + rx.abs() as f64 + ry.abs() as f64);
                let d = t.cu.d(rx, ry) as f64;
                for (e, n) in [(eu, nu), (ev, nv)] {
                    if (e + 0.5).floor() as i64 != n {
                        f64_diffs += 1;
                        let bound = eps * (1.0 + e.abs()) / (d - eps);
                        worst = worst.max(((e + 0.5) - (e + 0.5).round()).abs() / bound);
                    }
                }
            }
            got += 1;
        }
        let hold = !o.ready;
        let a = addr.outputs_held(hold);
        let ev = TexEvent::from(&a);
        if o.ready && ev.row_start && ev.step == 0 {
            first_taken = true;
        }
        let load = (next_load < tris.len() && addr.ready() && first_taken).then(|| {
            first_taken = false;
            next_load += 1;
            &tris[next_load - 1]
        });
        tex.clock(load.map(|t| &t.setup), &ev);
        addr.clock_held(load.map(|t| &t.addr), hold);
    }
    Run {
        clocks,
        pixels: want.len() as u64,
        steps: tex.steps,
        f64_diffs,
        f64_worst_tie: worst,
    }
}

#[test]
fn the_block_emits_the_nearest_texel_of_every_pixel() {
    // Texels per pixel up to about `span`: magnified, about one, and minified.
    for (ratio, span) in [(1.5f64, 0.3), (4.0, 1.0), (8.0, 4.0)] {
        let (tris, dropped) = triangles(
            seed_for("texture_block") ^ ratio.to_bits(),
            120,
            ratio,
            span,
        );
        for k in [1, 2] {
            let r = run(&tris, k);
            eprintln!(
                "depth ratio ≤ {ratio}, texel coordinates within ±{span}·(box size), k = {k}: {} pixels, {:.3} clocks/pixel, \
                 {:.3} steps/pixel (u and v); {} texels differ from the f64 planes' (the \
                 farthest from a tie at {:.3} of the rounding bound); {dropped} triangles out of \
                 range dropped",
                r.pixels,
                r.clocks as f64 / r.pixels as f64,
                r.steps as f64 / r.pixels as f64,
                r.f64_diffs,
                r.f64_worst_tie,
            );
            assert!(
                r.f64_worst_tie <= 1.0,
                "a texel differs from the f64 planes' beyond the coefficients' rounding"
            );
        }
    }
}
