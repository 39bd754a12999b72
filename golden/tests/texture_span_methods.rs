//! The quadratic (SPEC §15) and quadratic-Bézier (SPEC §16) texture coordinates, golden faces,
//! against SPEC §15's and §16's measured tables: on a 256-pixel span carrying 256 texels, the
//! largest |u error| against the exact perspective quotient for depth ratios 1.25 … 8 (the
//! figures `../shared/spec-checks/check_texture.py` printed, to their two significant digits),
//! the quadratic through the ends and mid-span, the Bézier with the tangents' intersection as
//! control point; and the ratio of the two.

use golden::units::texture_bezier::{bezier, control_point};
use golden::units::texture_quadratic::{eval, lagrange_coeffs};

/// Largest |Bézier u − exact u at the Bézier's x| over t ∈ [0, 1] (200 001 samples).
fn bezier_error(r: f64) -> f64 {
    let l = 256.0;
    let (a, c, g, i) = ((256.0 / r) / l, 0.0, (1.0 / r - 1.0) / l, 1.0);
    let k = [a, 0.0, c, g, 0.0, i];
    let exact = |x: f64| (a * x + c) / (g * x + i);
    let (x1, u1) = control_point(k, 0.0, 0.0, l);
    (0..=200_000)
        .map(|s| {
            let t = s as f64 / 200_000.0;
            let x = bezier([0.0, x1, l], t);
            (bezier([exact(0.0), u1, exact(l)], t) - exact(x)).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_bezier_errs_as_spec_16_measured() {
    for (r, spec, ratio) in [
        (1.25, 0.044, 14.7),
        (1.5, 0.26, 8.5),
        (2.0, 1.3, 5.4),
        (3.0, 4.8, 3.7),
        (4.0, 9.0, 3.2),
        (8.0, 25.0, 2.4),
    ] {
        let (e, q) = (bezier_error(r), max_error(r));
        eprintln!(
            "depth ratio {r}: Bézier max |u error| {e:.3} texel (SPEC §16: {spec}), quadratic {q:.3}, ratio {:.2} (SPEC: {ratio})",
            q / e
        );
        assert!(
            (e - spec).abs() <= 0.05 * spec,
            "depth ratio {r}: Bézier {e:.4}, SPEC {spec}"
        );
        assert!(
            (q / e - ratio).abs() <= 0.05 * ratio,
            "depth ratio {r}: ratio {:.2}, SPEC {ratio}",
            q / e
        );
    }
}

/// Largest |quadratic − exact| over x ∈ [0, 256] (4001 samples) for depth ratio `r`.
fn max_error(r: f64) -> f64 {
    let l = 256.0;
    let (w0, w2, u2) = (1.0, r, 256.0);
    let (a, c) = ((u2 / w2) / l, 0.0);
    let (g, i) = ((1.0 / w2 - 1.0 / w0) / l, 1.0 / w0);
    let exact = |x: f64| (a * x + c) / (g * x + i);
    let q = lagrange_coeffs([0.0, l / 2.0, l], [exact(0.0), exact(l / 2.0), exact(l)]);
    (0..=4000)
        .map(|k| {
            let x = l * k as f64 / 4000.0;
            (eval(&q, x) - exact(x)).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_quadratic_errs_as_spec_15_measured() {
    for (r, spec) in [
        (1.25, 0.65),
        (1.5, 2.2),
        (2.0, 6.8),
        (4.0, 28.0),
        (8.0, 61.0),
    ] {
        let e = max_error(r);
        eprintln!("depth ratio {r}: max |u error| {e:.3} texel (SPEC §15: {spec})");
        assert!(
            (e - spec).abs() <= 0.05 * spec,
            "depth ratio {r}: {e:.3} texel, SPEC §15 measured {spec}"
        );
    }
}
