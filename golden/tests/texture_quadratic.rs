//! The quadratic texture coordinate (SPEC §15), golden face, against SPEC §15's measured table:
//! on a 256-pixel span carrying 256 texels, with the inner point at mid-span, the largest
//! |u error| against the exact perspective quotient for depth ratios 1.25 … 8 (the figures
//! `../shared/spec-checks/check_texture.py` printed, to their two significant digits).

use golden::units::texture_quadratic::{eval, lagrange_coeffs};

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
