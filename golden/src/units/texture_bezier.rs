//! Quadratic-Bézier texture coordinate along a raster line (SPEC §16), golden face: the control
//! point at the intersection of the tangents to u(x) at the span's ends, the curve
//! (x(t), u(t)), and its forward differences in t (additions only). No RTL block yet.
//!
//! # Formula (SPEC §16)
//!
//! On line y, with B = h·y + i, A = a·B − g·(b·y + c), C0 = (g·x0 + B)², C2 = (g·x2 + B)²:
//!
//! ```text
//!   x1 = [(u0 − u2)·C0·C2 − A·(x0·C2 − x2·C0)] / [A·(C0 − C2)]
//!   u1 = u0 + (A/C0)·(x1 − x0)                       (du/dx = A/(g·x + B)²)
//!   x(t) = (1 − t)²x0 + 2t(1 − t)x1 + t²x2,   u(t) likewise,   t ∈ [0, 1]
//!   x(t + dt) = x(t) + Δx,  Δx += dₓ;  Δx(0) = 2dt(x1 − x0) + dt²Sₓ,  dₓ = 2dt²Sₓ,
//!   Sₓ = x0 − 2x1 + x2   (and the same for u)
//! ```
//!
//! Where the depth does not change along the line (g = 0, or C0 = C2) u(x) is linear and the
//! control point is the span's middle.

/// The control point (x1, u1) of the line from x0 to x2 for u = (a·x + b·y + c)/(g·x + h·y + i).
pub fn control_point(k: [f64; 6], y: f64, x0: f64, x2: f64) -> (f64, f64) {
    let [a, b, c, g, h, i] = k;
    let bb = h * y + i;
    let aa = a * bb - g * (b * y + c);
    let u = |x: f64| (a * x + b * y + c) / (g * x + bb);
    let (u0, u2) = (u(x0), u(x2));
    let (c0, c2) = ((g * x0 + bb).powi(2), (g * x2 + bb).powi(2));
    let den = aa * (c0 - c2);
    if den.abs() <= 1e-12 * (aa.abs() * c0.max(c2)).max(f64::MIN_POSITIVE) {
        let xm = (x0 + x2) / 2.0;
        return (xm, (u0 + u2) / 2.0);
    }
    let x1 = ((u0 - u2) * c0 * c2 - aa * (x0 * c2 - x2 * c0)) / den;
    (x1, u0 + aa / c0 * (x1 - x0))
}

/// The quadratic Bézier through p0, p1 (control), p2 at t.
pub fn bezier(p: [f64; 3], t: f64) -> f64 {
    let s = 1.0 - t;
    s * s * p[0] + 2.0 * t * s * p[1] + t * t * p[2]
}

/// Forward differences of a quadratic Bézier in steps dt: (start, Δ(0), d).
pub fn differences(p: [f64; 3], dt: f64) -> (f64, f64, f64) {
    let s = p[0] - 2.0 * p[1] + p[2];
    (
        p[0],
        2.0 * dt * (p[1] - p[0]) + dt * dt * s,
        2.0 * dt * dt * s,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forward_differences_reach_the_end_exactly() {
        let p = [3.0, 40.0, 100.0];
        let n = 64;
        let (mut x, mut d, dd) = differences(p, 1.0 / n as f64);
        for k in 0..n {
            assert!((x - bezier(p, k as f64 / n as f64)).abs() < 1e-9);
            x += d;
            d += dd;
        }
        assert!((x - p[2]).abs() < 1e-9);
    }

    #[test]
    fn the_control_point_is_where_the_tangents_meet() {
        let k = [0.3, 0.2, 5.0, 0.001, 0.002, 1.0];
        let (y, x0, x2) = (7.0, 10.0, 200.0);
        let (x1, u1) = control_point(k, y, x0, x2);
        let u = |x: f64| (k[0] * x + k[1] * y + k[2]) / (k[3] * x + k[4] * y + k[5]);
        let slope = |x: f64| (u(x + 1e-4) - u(x - 1e-4)) / 2e-4;
        // u1 lies on both tangents.
        assert!((u(x0) + slope(x0) * (x1 - x0) - u1).abs() < 1e-6);
        assert!((u(x2) + slope(x2) * (x1 - x2) - u1).abs() < 1e-6);
    }
}
