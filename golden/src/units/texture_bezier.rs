//! Quadratic-Bézier texture coordinate along a raster line (SPEC §16), golden face: the control
//! point at the intersection of the tangents to u(x) at the span's ends, the curve
//! (x(t), u(t)), its forward differences in t (additions only), the set-up words of the RTL
//! block `texture-bezier` (`rtl::units::texture_bezier`) and its bit-exact integer twin
//! [`BezierTwin`].
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

/// The control point's x from the depth alone: along a line where N and D are linear in x, the
/// tangents to u = N/D at x0 and x2 meet at x1 = (x0·D2 + x2·D0)/(D0 + D2) (D0, D2 the
/// depths there), whatever N is: u and v share it, and so the block's one X lane.
pub fn control_x(d0: f64, d2: f64, x0: f64, x2: f64) -> f64 {
    (x0 * d2 + x2 * d0) / (d0 + d2)
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

/// The samples of a line of `n` pixels: t = j/m, j = 0 … m, with m = 2(n − 1) (two samples per
/// pixel step; a one-pixel line has its one sample).
pub fn samples(n: u32) -> u32 {
    2 * n.saturating_sub(1)
}

/// The sample each pixel of a line takes: pixel i (at X = i, X the distance from the line's
/// first pixel along the walk) takes sample j, found by walking j up from the previous pixel's
/// while sample j + 1 lies at least as near X = i as sample j. On a curve whose X does not
/// fall along t this is the nearest sample (a tie goes to the later one).
pub fn pick(xs: &[f64], n: u32) -> Vec<usize> {
    let mut j = 0;
    (0..n)
        .map(|i| {
            let p = i as f64;
            while j + 1 < xs.len() && (xs[j + 1] - p).abs() <= (xs[j] - p).abs() {
                j += 1;
            }
            j
        })
        .collect()
}

/// The u the block may show at pixel i (X = i) that took sample `jf` by [`pick`] on the f64
/// curve's samples `xs` (X) and `us` (u or v): the span (centre, half-width) of u over the
/// samples as near X = i as sample `jf` within `slack` (the words' deviation on both samples
/// of a comparison: 4·[`error_bound`] of the line's last sample), where the block's fixed-point
/// comparisons can pick another sample than the f64 ones.
pub fn may_show(xs: &[f64], us: &[f64], jf: usize, i: u32, slack: f64) -> (f64, f64) {
    let p = i as f64;
    let near = (xs[jf] - p).abs() + slack;
    let (mut lo, mut hi) = (jf, jf);
    while lo > 0 && (xs[lo - 1] - p).abs() <= near {
        lo -= 1;
    }
    while hi + 1 < xs.len() && (xs[hi + 1] - p).abs() <= near {
        hi += 1;
    }
    let (a, b) = us[lo..=hi]
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    ((a + b) / 2.0, (b - a) / 2.0)
}

/// The slack of [`may_show`] on a line of `n` pixels.
pub fn pick_slack(n: u32) -> f64 {
    4.0 * error_bound(samples(n) as u64) + 1e-9
}

/// Samples a window sees at once: a pixel can take the sample up to `WINDOW − 1` beyond the
/// previous pixel's in its clock; beyond that the window moves by `WINDOW` with no pixel.
pub const WINDOW: usize = 3;

/// Fraction bits of every word (signed Q15.32 in 48 bits, as `texture-quadratic`'s).
pub const FRAC_BITS: u32 = 32;
const MASK: u64 = (1 << 48) - 1;

/// `v` as a signed Q15.32 word, rounded to nearest.
pub fn word(v: f64) -> u64 {
    ((v * (1u64 << FRAC_BITS) as f64).round() as i64 as u64) & MASK
}

/// One lane's words: the value at t = 0, its first difference Δ(0) and the second difference
/// d (signed Q15.32).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaneWords {
    pub start: u64,
    pub step: u64,
    pub step2: u64,
}

/// A line's set-up record for `texture-bezier`: its last pixel index n − 1, and the words of
/// the three lanes X (the pixel distance along the walk, from 0 to n − 1), u + ½ and v + ½.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BezierLine {
    pub end_index: u32,
    pub lanes: [LaneWords; 3],
}

impl BezierLine {
    /// The record of a line of `n` pixels (1 ≤ n ≤ 4096) whose curves have the control points
    /// `x` (X: 0, X1, n − 1; its start is 0 whatever `x[0]` is), `u` and `v` (texel space): the forward differences in
    /// dt = 1/m ([`samples`]) rounded to 2^−32, u and v carrying +½ so that a word's integer
    /// part is the nearest texel.
    pub fn new(n: u32, x: [f64; 3], u: [f64; 3], v: [f64; 3]) -> BezierLine {
        assert!((1..=4096).contains(&n), "a line of {n} pixels");
        let m = samples(n);
        let lane = |p: [f64; 3], half: f64| {
            if m == 0 {
                return LaneWords {
                    start: word(p[0] + half),
                    ..LaneWords::default()
                };
            }
            let (s, d, dd) = differences(p, 1.0 / m as f64);
            LaneWords {
                start: word(s + half),
                step: word(d),
                step2: word(dd),
            }
        };
        BezierLine {
            end_index: n - 1,
            lanes: [
                LaneWords {
                    start: 0,
                    ..lane(x, 0.0)
                },
                lane(u, 0.5),
                lane(v, 0.5),
            ],
        }
    }

    /// The record as the block's input ports after `load`: end_index, X's step and step2
    /// (X starts at 0: no port), then u's and v's start, step, step2.
    pub fn ports(&self) -> Vec<u64> {
        let x = &self.lanes[0];
        let mut p = vec![self.end_index as u64, x.step, x.step2];
        for l in &self.lanes[1..] {
            p.extend([l.start, l.step, l.step2]);
        }
        p
    }

    /// The record from the ports ([`BezierLine::ports`]' order), masked to the port widths.
    pub fn from_ports(p: &[u64]) -> BezierLine {
        let l = |k: usize| LaneWords {
            start: p[3 * k] & MASK,
            step: p[1 + 3 * k] & MASK,
            step2: p[2 + 3 * k] & MASK,
        };
        BezierLine {
            end_index: (p[0] & 0xFFF) as u32,
            lanes: [
                LaneWords {
                    start: 0,
                    step: p[1] & MASK,
                    step2: p[2] & MASK,
                },
                l(1),
                l(2),
            ],
        }
    }
}

/// Largest deviation of sample j's word from the exact curve at t = j/m, given words rounded
/// to nearest: 2^−33·(1 + j + j(j − 1)/2) (start, Δ(0) and d each within 2^−33, Δ added j
/// times, d j(j − 1)/2 times): under 0.004 on a 4096-pixel line (j ≤ 8190).
pub fn error_bound(j: u64) -> f64 {
    let j = j as f64;
    (1.0 + j + j * (j - 1.0) / 2.0) / (1u64 << (FRAC_BITS + 1)) as f64
}

/// One lane of the twin: the window of samples j … j + 3, Δ after the window's last sample
/// (Δ(j + 3)), d and 3d.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WindowLane {
    pub w: [u64; 4],
    d: u64,
    dd: u64,
    dd3: u64,
}

impl WindowLane {
    /// Samples j + 4, j + 5, j + 6 from the window's last sample: w3 + Δ, w3 + 2Δ + d,
    /// w3 + 3Δ + 3d (from `base`, `d`, `dd`, `dd3`).
    fn beyond(base: u64, d: u64, dd: u64, dd3: u64) -> [u64; 3] {
        let x4 = base.wrapping_add(d) & MASK;
        let x5 = base.wrapping_add(d << 1).wrapping_add(dd) & MASK;
        let x6 = x4.wrapping_add(d << 1).wrapping_add(dd3) & MASK;
        [x4, x5, x6]
    }

    /// The window of a newly loaded line: samples 0 … 3.
    fn load(w: &LaneWords) -> WindowLane {
        let dd3 = w.step2.wrapping_add(w.step2 << 1) & MASK;
        let [x1, x2, x3] = Self::beyond(w.start, w.step, w.step2, dd3);
        WindowLane {
            w: [w.start, x1, x2, x3],
            d: w.step.wrapping_add(dd3) & MASK,
            dd: w.step2,
            dd3,
        }
    }

    /// Move the window by r ∈ {1, 2, 3} samples.
    fn advance(&mut self, r: usize) {
        let x = Self::beyond(self.w[3], self.d, self.dd, self.dd3);
        let all = [self.w[0], self.w[1], self.w[2], self.w[3], x[0], x[1], x[2]];
        self.w.copy_from_slice(&all[r..r + 4]);
        let step = [0, self.dd, (self.dd << 1) & MASK, self.dd3][r];
        self.d = self.d.wrapping_add(step) & MASK;
    }
}

/// The outputs of [`BezierTwin`] in one clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BezierOutputs {
    pub ready: bool,
    pub valid: bool,
    /// Texels: the integer part of the u + ½ and v + ½ words (16-bit two's complement).
    pub u: u64,
    pub v: u64,
    /// The pixel's index along its line, 0 … n − 1.
    pub index: u32,
    /// The line's last pixel.
    pub done: bool,
}

/// The bit-exact twin of `texture-bezier` (see that block's header): the line's first pixel
/// takes sample 0; then per clock, the window's comparisons X(j + k − 1) + X(j + k) ≤ 2i
/// (k = 1, 2, 3, sample j + k existing) give r, the number that hold in a row; r < 3 shows
/// pixel i with sample j + r and moves the window by r; r = 3 moves it by 3 with no pixel. The
/// twin loads the window on the load; the block forms it in the first pixel's clock (which
/// does not use it), the same state where it is read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BezierTwin {
    busy: bool,
    /// The line's first pixel is next: it takes sample 0.
    first: bool,
    end_index: u32,
    /// The pixel index i and the samples left after the window's first, m − j.
    i: u32,
    rem: u32,
    lanes: [WindowLane; 3],
    out: BezierOutputs,
}

impl BezierTwin {
    /// r: how many of the window's comparisons hold in a row (0 for the line's first pixel).
    fn r(&self) -> usize {
        if self.first {
            return 0;
        }
        let x = &self.lanes[0].w;
        let ni = !((self.i as u64) << (FRAC_BITS + 1)) & MASK;
        let mut r = 0;
        while r < WINDOW
            && self.rem > r as u32
            && (x[r].wrapping_add(x[r + 1]).wrapping_add(ni) >> 47) & 1 == 1
        {
            r += 1;
        }
        r
    }

    /// Whether the line's last pixel is decided this clock (with `hold` low).
    fn last_now(&self) -> bool {
        self.busy && self.r() < WINDOW && self.i == self.end_index
    }

    /// The outputs shown this clock under `hold`.
    pub fn outputs(&self, hold: bool) -> BezierOutputs {
        BezierOutputs {
            ready: !hold && (!self.busy || self.last_now()),
            ..self.out
        }
    }

    /// Whether a line is being walked.
    pub fn busy(&self) -> bool {
        self.busy
    }

    /// One rising edge: `load` (taken when `ready`), `hold`.
    pub fn clock(&mut self, load: Option<&BezierLine>, hold: bool) {
        let take = load.is_some() && self.outputs(hold).ready;
        let r = self.r();
        let step = self.busy && !hold;
        let emit = step && r < WINDOW;
        self.out = BezierOutputs {
            ready: false,
            valid: emit,
            ..self.out
        };
        if emit {
            let t = |w: u64| (w >> FRAC_BITS) & 0xFFFF;
            self.out.u = t(self.lanes[1].w[r]);
            self.out.v = t(self.lanes[2].w[r]);
            self.out.index = self.i;
            self.out.done = self.i == self.end_index;
        }
        if step && r > 0 {
            for l in &mut self.lanes {
                l.advance(r);
            }
            self.rem -= r as u32;
        }
        if emit {
            self.first = false;
            if self.i == self.end_index {
                self.busy = false;
            } else {
                self.i += 1;
            }
        }
        if let Some(line) = load.filter(|_| take) {
            for (l, w) in self.lanes.iter_mut().zip(&line.lanes) {
                *l = WindowLane::load(w);
            }
            self.busy = true;
            self.first = true;
            self.end_index = line.end_index;
            self.i = 0;
            self.rem = 2 * line.end_index;
        }
    }
}

/// Texels the textured pipeline's Bézier walk keeps (`rtl`'s `BezWalk`).
pub const TEXEL_FIFO: usize = 4;

/// The bit-exact twin of the textured pipeline's Bézier walk (`rtl`'s `BezWalk` with the
/// pipeline's line FIFO, written from their headers): up to
/// [`crate::units::texture_quadratic::LINE_FIFO`] line records, the Bézier block's twin
/// ([`BezierTwin`]) loading the head record when ready and held while two or more texels
/// wait, a [`TEXEL_FIFO`]-entry texel FIFO (a shift register: its entries keep stale words,
/// which the output stage reads), each pixel shown taking the head texel, and two registers
/// after (the taken texel, the output).
#[derive(Clone, Debug, Default)]
pub struct BezWalkTwin {
    lines: std::collections::VecDeque<BezierLine>,
    bez: BezierTwin,
    occ: [bool; TEXEL_FIFO],
    tu: [u64; TEXEL_FIFO],
    tv: [u64; TEXEL_FIFO],
    /// The taken pixel's texel (valid, u, v), then the output register.
    stage: (bool, u64, u64),
    out: (bool, u64, u64),
}

impl BezWalkTwin {
    /// `line_ready`: the line FIFO takes a record this clock.
    pub fn line_ready(&self) -> bool {
        self.lines.len() < crate::units::texture_quadratic::LINE_FIFO
    }

    /// Line records waiting.
    pub fn lines(&self) -> usize {
        self.lines.len()
    }

    /// `ready` with a pixel shown (`valid`) or not: low only for a pixel while no texel waits.
    pub fn ready(&self, valid: bool) -> bool {
        !valid || self.occ[0]
    }

    /// (valid_out, [u, v]) shown this clock.
    pub fn outputs(&self) -> (bool, [u64; 2]) {
        (self.out.0, [self.out.1, self.out.2])
    }

    /// One rising edge with a pixel shown (`valid`) or not and a record pushed or not.
    pub fn clock(&mut self, valid: bool, push: Option<&BezierLine>) {
        let hold = self.occ[1];
        let bo = self.bez.outputs(hold);
        let pull = !self.lines.is_empty() && bo.ready;
        let pix = valid && self.occ[0];
        // The texel FIFO: the pixel pops the head, the Bézier block's texel lands in the first
        // free entry after it.
        let mut kept = self.occ;
        let (mut tu, mut tv) = (self.tu, self.tv);
        if pix {
            for i in 0..TEXEL_FIFO - 1 {
                kept[i] = self.occ[i + 1];
                tu[i] = self.tu[i + 1];
                tv[i] = self.tv[i + 1];
            }
            kept[TEXEL_FIFO - 1] = false;
        }
        let mut occ = kept;
        for i in 0..TEXEL_FIFO {
            let put = bo.valid && !kept[i] && (i == 0 || kept[i - 1]);
            if put {
                occ[i] = true;
                tu[i] = bo.u;
                tv[i] = bo.v;
            }
        }
        self.out = self.stage;
        self.stage = (pix, self.tu[0], self.tv[0]);
        self.occ = occ;
        self.tu = tu;
        self.tv = tv;
        // The head record is shown as the Bézier block's load; it is taken (`pull`) when the
        // block is ready.
        let head = self.lines.front().copied();
        self.bez.clock(head.as_ref(), hold);
        if pull {
            self.lines.pop_front();
        }
        if let Some(l) = push {
            if self.lines.len() < crate::units::texture_quadratic::LINE_FIFO {
                self.lines.push_back(*l);
            }
        }
    }
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
    fn the_control_x_is_the_depth_alone() {
        let k = [0.3, 0.2, 5.0, 0.001, 0.002, 1.0];
        let (y, x0, x2) = (7.0, 10.0, 200.0);
        let d = |x: f64| k[3] * x + k[4] * y + k[5];
        let (x1, _) = control_point(k, y, x0, x2);
        assert!((control_x(d(x0), d(x2), x0, x2) - x1).abs() < 1e-9);
        // Another numerator, the same depth: the same x1.
        let kv = [-2.0, 0.7, -1.0, k[3], k[4], k[5]];
        assert!((control_point(kv, y, x0, x2).0 - x1).abs() < 1e-9);
    }

    /// The block's words, stepped by the twin's lane one sample at a time and by its moves of
    /// 2 and 3, stay within `error_bound` of the closed-form curve (an independent check of
    /// the set-up words and of the window's arithmetic).
    #[test]
    fn the_words_follow_the_curve() {
        let n = 700;
        let m = samples(n) as usize;
        let p = [0.0, 150.0, (n - 1) as f64];
        let line = BezierLine::new(n, p, [-40.0, 3.0, 900.0], [5.0, 5.0, 5.0]);
        let to_f = |w: u64| ((w << 16) as i64 >> 16) as f64 / (1u64 << FRAC_BITS) as f64;
        for moves in [[1, 1, 1], [2, 3, 1], [3, 3, 3]] {
            let mut lane = WindowLane::load(&line.lanes[0]);
            let (mut j, mut k) = (0, 0);
            while j + 3 <= m {
                for (o, w) in lane.w.iter().enumerate() {
                    let exact = bezier(p, (j + o) as f64 / m as f64);
                    let bound = error_bound((j + o) as u64) + 1e-9;
                    assert!(
                        (to_f(*w) - exact).abs() <= bound,
                        "sample {}: {} against {exact}",
                        j + o,
                        to_f(*w)
                    );
                }
                let r = moves[k % 3];
                lane.advance(r);
                j += r;
                k += 1;
            }
        }
        // u + ½ and a one-pixel line.
        let one = BezierLine::new(1, [0.0; 3], [7.25; 3], [-3.5; 3]);
        assert_eq!(one.lanes[1].start >> FRAC_BITS, 7);
        assert_eq!((one.lanes[2].start >> FRAC_BITS) & 0xFFFF, 0xFFFD);
        assert_eq!(one.end_index, 0);
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
