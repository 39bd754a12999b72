//! Bench of the Bézier texture-coordinate unit (`rtl::units::texture_bezier`) against the f64
//! Bézier of each line (`golden::units::texture_bezier`) and its bit-exact twin.
//!
//! # Stimulus
//!
//! Seeded perspective lines: 1 to 300 pixels (a seeded tenth up to 3000), a depth ratio up to 8
//! between the ends (so samples crowd towards one end), texel coordinates up to ±2000; the
//! control points as the set-up software takes them (x1 from the depth, `control_x`; u1, v1 on
//! the tangent at the first pixel). Each line is loaded as soon as the block is `ready`, or
//! after a seeded gap of idle clocks; `hold` is high in a seeded tenth of the clocks. Every
//! tenth line has a constant depth (the samples evenly spaced, every pixel on a sample).
//! Edge rows: random words and flags on every input.
//!
//! # Tolerances (from the formats)
//!
//! - `ready`, `valid_out`: the cycle model's (exact); `index` and `done`: the pixel's place in
//!   its line, counted here (exact).
//! - `u`, `v`: the f64 curve's samples at t = j/m that lie as near the pixel centre as the
//!   nearest one, within 4·`error_bound(m)` (the words' deviation, on both samples of a
//!   comparison: `may_show`); the texel within ½ + `error_bound(m)` + 10^−6 (the f64 arithmetic) of
//!   the span of their u (or v).

use golden::testing::Rng;
use golden::units::texture_bezier::{
    bezier, control_x, error_bound, may_show, pick, pick_slack, samples, BezierLine, BezierOutputs,
    BezierTwin,
};
use rtl::core::fixed::QFormat;
use rtl::core::registry::NoParams;
use rtl::units::texture_bezier::TextureBezier;

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};

/// One line: its record, and per pixel the (centre, half-width) of the u and v the block may
/// show.
struct Line {
    rec: BezierLine,
    expect: Vec<[(f64, f64); 2]>,
}

/// The control points of a coordinate N/D along X ∈ [0, n − 1] (N = nn[0] + nn[1]·X,
/// D = dd[0] + dd[1]·X) at the control x `x1`: the ends and the tangent at X = 0 there.
fn points(nn: [f64; 2], dd: [f64; 2], last: f64, x1: f64) -> [f64; 3] {
    let u = |x: f64| (nn[0] + nn[1] * x) / (dd[0] + dd[1] * x);
    let slope = (nn[1] * dd[0] - nn[0] * dd[1]) / (dd[0] * dd[0]);
    [u(0.0), u(0.0) + slope * x1, u(last)]
}

fn line(rng: &mut Rng, flat: bool) -> Line {
    let len = if rng.below(10) == 0 { 3000 } else { 300 };
    let n = 1 + rng.below(len) as u32;
    let last = (n - 1) as f64;
    let r = if flat {
        1.0
    } else {
        (rng.unit() * 8f64.ln()).exp()
    };
    let (q0, q1) = if rng.below(2) == 0 {
        (1.0, 1.0 / r)
    } else {
        (1.0 / r, 1.0)
    };
    let span = last.max(1.0);
    let dd = [q0, (q1 - q0) / span];
    let x1 = control_x(q0, q1, 0.0, last);
    let mut axis = || {
        let (s0, s1) = ((rng.unit() - 0.5) * 4000.0, (rng.unit() - 0.5) * 4000.0);
        points([s0 * q0, (s1 * q1 - s0 * q0) / span], dd, last, x1)
    };
    let (up, vp) = (axis(), axis());
    let xp = [0.0, x1, last];
    let rec = BezierLine::new(n, xp, up, vp);
    let m = samples(n) as usize;
    let t = |j: usize| if m == 0 { 0.0 } else { j as f64 / m as f64 };
    let curve = |c: [f64; 3]| (0..=m).map(|j| bezier(c, t(j))).collect::<Vec<f64>>();
    let (xs, us, vs) = (curve(xp), curve(up), curve(vp));
    let slack = pick_slack(n);
    let expect = pick(&xs, n)
        .into_iter()
        .enumerate()
        .map(|(i, jf)| [&us, &vs].map(|c| may_show(&xs, c, jf, i as u32, slack)))
        .collect();
    Line { rec, expect }
}

/// One input row: `load` and the record, then `hold`.
fn row(load: Option<&BezierLine>, hold: bool) -> Vec<u64> {
    let mut r = vec![load.is_some() as u64];
    r.extend(load.map_or(vec![0; 9], |l| l.ports()));
    r.push(hold as u64);
    r
}

fn out_row(o: &BezierOutputs) -> Vec<u64> {
    vec![
        o.ready as u64,
        o.valid as u64,
        o.u,
        o.v,
        o.index as u64,
        o.done as u64,
    ]
}

const TEXEL: QFormat = QFormat::signed(16, 0);

impl Bench for TextureBezier {
    const ITEMS: &'static str = "lines";
    const DEFAULT_ITEMS: usize = 30;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let mut rng = Rng::new(seed | 1);
        let lines: Vec<Line> = (0..n).map(|k| line(&mut rng, k % 10 == 9)).collect();
        let mut twin = BezierTwin::default();
        let (mut rows, mut expected) = (Vec::new(), Vec::new());
        let (mut next, mut gap) = (0, 0);
        // The line and pixel of each pixel shown, counted in order.
        let (mut shown_line, mut shown_pixel) = (0usize, 0usize);
        let mut idle = 0;
        let mut worst = 0.0f64;
        while idle < 4 {
            let hold = rng.below(10) == 0;
            let o = twin.outputs(hold);
            let mut e = vec![
                Expected::Word(o.ready as u64),
                Expected::Word(o.valid as u64),
            ];
            if o.valid {
                let l = &lines[shown_line];
                let [(cu, hu), (cv, hv)] = l.expect[shown_pixel];
                let b = 0.5 + error_bound(samples(l.rec.end_index + 1) as u64) + 1e-6;
                worst = worst.max(hu + b).max(hv + b);
                let last = shown_pixel == l.expect.len() - 1;
                e.extend([
                    Expected::Within(cu, hu + b),
                    Expected::Within(cv, hv + b),
                    Expected::Word(shown_pixel as u64),
                    Expected::Word(last as u64),
                ]);
                if last {
                    shown_line += 1;
                    shown_pixel = 0;
                } else {
                    shown_pixel += 1;
                }
            } else {
                e.extend([Expected::DontCare; 4]);
            }
            expected.push(e);
            let load = if next < lines.len() && gap == 0 {
                Some(&lines[next].rec)
            } else {
                None
            };
            if gap > 0 {
                gap -= 1;
            }
            if load.is_some() && o.ready {
                next += 1;
                gap = if rng.below(5) == 0 { rng.below(4) } else { 0 };
            }
            rows.push(row(load, hold));
            twin.clock(load, hold);
            let busy = next < lines.len() || twin.busy() || o.valid;
            idle = if busy { 0 } else { idle + 1 };
        }
        assert_eq!(shown_line, lines.len(), "every line's pixels shown");
        let texel = Compare::Fixed {
            format: TEXEL,
            tol: Tolerance {
                max_abs: worst,
                rms: worst,
            },
        };
        let mut compare = vec![Compare::Exact; 6];
        compare[2] = texel;
        compare[3] = texel;
        Stimulus {
            rows,
            expected,
            compare,
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(BezierRows(BezierTwin::default()))
    }
    /// Random words and flags on every input (set-ups in and out of the block's range).
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let mut rng = Rng::new(seed ^ 0xbe2 | 1);
        (0..400)
            .map(|_| {
                let mut r = vec![(rng.below(3) == 0) as u64, rng.below(64) as u64];
                r.extend((0..8).map(|_| rng.next_u64() & ((1 << 48) - 1)));
                r.push((rng.below(5) == 0) as u64);
                r
            })
            .collect()
    }
}

/// The twin on input rows.
struct BezierRows(BezierTwin);

impl Twin for BezierRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let hold = r[10] & 1 != 0;
        let o = out_row(&self.0.outputs(hold));
        let load = (r[0] & 1 != 0).then(|| BezierLine::from_ports(&r[1..10]));
        self.0.clock(load.as_ref(), hold);
        o
    }
}
