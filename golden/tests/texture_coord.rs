//! The additive perspective-correct texture coordinate (SPEC §14), golden face: on 300 seeded
//! spans of the kind SPEC §14 measured (8–400 pixels, depth ratio 0.2–5 between the ends,
//! textures of 64, 256 and 1024 texels, starts anywhere on the row), the integer model's texel
//! is the nearest texel of the exact quotient of its coefficients at every pixel; its W and Q
//! equal their definitions at every pixel; its correction steps are exactly the texels crossed;
//! and a y step keeps the words exact as well. The f64 quotient is compared too, with its ties
//! counted.

use golden::seed::seed_for;
use golden::units::texture_coord::{
    clocks_for, exact_u, nearest_texel, walk_span, words_at, PctCoeffs, PctWalker,
};

use golden::testing::Rng;

struct Span {
    c: PctCoeffs,
    x0: i64,
    y: i64,
    len: u32,
}

/// A span whose texture coordinate runs from s0 to s1 texels (of a p-texel texture) while D
/// changes by the depth ratio r between its ends; integer coefficients at a 2^12 scale of D.
fn span(rng: &mut Rng) -> Span {
    let len = 8 + (rng.next_u64() % 393) as u32;
    let p = [64.0, 256.0, 1024.0][(rng.next_u64() % 3) as usize];
    let r = (rng.range(0.2f64.ln(), 5.0f64.ln())).exp();
    let (s0, s1) = (rng.range(0.0, p), rng.range(0.0, p));
    let x0 = (rng.next_u64() % 3000) as i64;
    let y = (rng.next_u64() % 2000) as i64;
    let d0 = rng.range(1024.0, 65536.0);
    let d1 = d0 * r;
    let l = len as f64;
    // D(x) = g·(x − x0) + d0, N(x) = a·(x − x0) + n0, folded into c and i; a small y term that
    // the row's constant y absorbs.
    let g = ((d1 - d0) / l).round() as i64;
    let (n0, n1) = (s0 * d0, s1 * d1);
    let a = ((n1 - n0) / l).round() as i64;
    let (b, h) = (
        (rng.next_u64() % 41) as i64 - 20,
        (rng.next_u64() % 5) as i64 - 2,
    );
    let c = PctCoeffs {
        a,
        b,
        c: n0.round() as i64 - a * x0 - b * y,
        g,
        h,
        i: d0.round() as i64 - g * x0 - h * y,
    };
    Span { c, x0, y, len }
}

#[test]
fn every_pixel_is_the_nearest_texel_of_the_exact_quotient() {
    let mut rng = Rng(seed_for("texture-coord-spans") | 1);
    let (mut pixels, mut steps, mut max_steps, mut f64_ties) = (0u64, 0u64, 0u32, 0u64);
    let mut clocks = [0u64; 3];
    for n in 0..300 {
        let s = span(&mut rng);
        // Start from the exact texel at the first pixel (the one division per span) on even
        // spans, and from a wrong guess (texel 0) on odd ones: the corrections must reach it.
        let u0 = if n % 2 == 0 {
            nearest_texel(&s.c, s.x0, s.y)
        } else {
            0
        };
        let walk = walk_span(&s.c, s.x0, s.y, s.len, u0);
        assert_eq!(walk.len(), s.len as usize);
        let mut prev = u0;
        for t in &walk {
            let want = nearest_texel(&s.c, t.x, s.y);
            assert_eq!(t.u, want, "span {n} pixel {}: texel", t.x);
            // Each step moves one texel: the steps are the texels crossed since the last pixel.
            assert_eq!(
                t.steps as i64,
                (t.u - prev).abs(),
                "span {n} pixel {}: steps",
                t.x
            );
            prev = t.u;
            let f = exact_u(&s.c, t.x, s.y);
            if (f + 0.5).floor() as i64 != want {
                // Only where N/D is within f64 rounding of a half-texel tie.
                assert!(
                    ((f + 0.5) - (f + 0.5).round()).abs() < 1e-6,
                    "span {n}: f64 {f}"
                );
                f64_ties += 1;
            }
            pixels += 1;
            if n % 2 == 0 {
                steps += t.steps as u64;
                max_steps = max_steps.max(t.steps);
                for (c, k) in clocks.iter_mut().zip([1, 2, 4]) {
                    *c += clocks_for(t.steps, k) as u64;
                }
            }
        }
    }
    let started = pixels / 2;
    println!(
        "{pixels} pixels; spans started on their exact texel: {:.3} steps per pixel (max {max_steps}), \
         clocks per pixel for k = 1, 2, 4: {:.3}, {:.3}, {:.3}; f64 ties {f64_ties}",
        steps as f64 / started as f64,
        clocks[0] as f64 / started as f64,
        clocks[1] as f64 / started as f64,
        clocks[2] as f64 / started as f64,
    );
    assert!(pixels > 50_000, "{pixels} pixels");
    // More steps per clock never costs clocks, and a pixel never takes less than one.
    assert!(clocks[0] >= clocks[1] && clocks[1] >= clocks[2] && clocks[2] >= started / 2);
}

#[test]
fn the_words_stay_their_definitions_along_x_and_y() {
    let mut rng = Rng(seed_for("texture-coord-words") | 1);
    for n in 0..60 {
        let s = span(&mut rng);
        let u0 = nearest_texel(&s.c, s.x0, s.y);
        let mut wk = PctWalker::start(&s.c, s.x0, s.y, u0);
        // A serpentine of x and y steps, settling at every pixel.
        for k in 0..(s.len.min(120)) {
            if k % 7 == 6 {
                wk.step_y();
            } else {
                wk.step_x();
            }
            if s.c.d(wk.x, wk.y) <= 0 {
                break;
            }
            wk.settle();
            let (w, q) = words_at(&s.c, wk.x, wk.y, wk.u);
            assert_eq!((wk.w, wk.q), (w, q), "walk {n} at ({}, {})", wk.x, wk.y);
            assert_eq!(wk.e, 2 * s.c.d(wk.x, wk.y));
            assert_eq!(wk.gu, 2 * s.c.g as i128 * wk.u as i128);
            assert_eq!(wk.hu, 2 * s.c.h as i128 * wk.u as i128);
            assert_eq!(wk.u, nearest_texel(&s.c, wk.x, wk.y));
        }
    }
}
