//! Bench of the quadratic texture-coordinate unit (`rtl::units::texture_quadratic`) against the
//! f64 quadratic of each line (`golden::units::texture_quadratic`) and its bit-exact twin.
//!
//! # Stimulus
//!
//! Seeded perspective lines: 1 to 300 pixels (every fourth up to 3000), stepping +x or −x, a
//! depth ratio up to 8 between the ends and texel coordinates up to ±2000; the quadratic
//! through the exact u at both ends and the middle pixel, as the set-up software fits it.
//! A seeded tenth of the clocks carry no pixel (the recurrences must freeze). Edge rows: random
//! words on every input.
//!
//! # Tolerances (from the formats)
//!
//! - `u_word`, `v_word` (signed Q15.32 with +½): the n-th pixel of its line within
//!   `error_bound(n)` of the f64 quadratic + ½, plus the f64 arithmetic's own error bound
//!   (`f64_slack`), each pixel its own bound (`Expected::Within`).
//! - `u`, `v`: within ½ texel plus that bound of the f64 quadratic (the texel is the word's
//!   integer part).
//! - `valid_out`: exact.

use golden::units::texture_quadratic::{
    differences, error_bound, eval, f64_slack, lagrange_coeffs, QuadTwin, QuadWords,
};
use rtl::core::fixed::QFormat;
use rtl::core::registry::NoParams;
use rtl::units::texture_quadratic::TextureQuadratic;

use crate::harness::{Compare, Expected, Tolerance};
use crate::registry::{Bench, Stimulus, Twin};
use golden::testing::Rng;

/// One line: its set-up words and, per pixel, the f64 quadratic of u and v and the f64
/// arithmetic's own error bound there (`f64_slack`, the larger of the two axes).
struct Line {
    words: [QuadWords; 2],
    values: Vec<[f64; 2]>,
    slack: Vec<f64>,
}

fn line(rng: &mut Rng) -> Line {
    let len = if rng.below(4) == 0 { 3000 } else { 300 };
    let n = 1 + rng.below(len) as usize;
    let x0 = rng.below(4096 - n as i32) as f64;
    let dir = if rng.below(2) == 0 { 1.0 } else { -1.0 };
    let xs = if dir > 0.0 { x0 } else { x0 + n as f64 - 1.0 };
    let xe = xs + dir * (n as f64 - 1.0);
    // 1/w linear in x between the ends; s/w likewise.
    let r = (rng.unit() * 8f64.ln()).exp();
    let (q0, q1) = (1.0, 1.0 / r);
    let mut axis = || {
        let (s0, s1) = ((rng.unit() - 0.5) * 4000.0, (rng.unit() - 0.5) * 4000.0);
        let exact = |x: f64| {
            let t = if n > 1 { (x - xs) / (xe - xs) } else { 0.0 };
            let q = q0 + (q1 - q0) * t;
            (s0 * q0 + (s1 * q1 - s0 * q0) * t) / q
        };
        let xm = ((xs + xe) / 2.0).round();
        let a = if n >= 3 {
            lagrange_coeffs([xs, xm, xe], [exact(xs), exact(xm), exact(xe)])
        } else {
            // Too short for three points: the line through its ends (A1 = 0).
            let d = if n > 1 {
                (exact(xe) - exact(xs)) / (xe - xs)
            } else {
                0.0
            };
            [0.0, d, exact(xs) - d * xs]
        };
        let w = QuadWords::of(differences(&a, xs, dir));
        let x = |k: usize| xs + dir * k as f64;
        let v: Vec<f64> = (0..n).map(|k| eval(&a, x(k))).collect();
        let sl: Vec<f64> = (0..n).map(|k| f64_slack(&a, xs, x(k), k as u64)).collect();
        (w, v, sl)
    };
    let (wu, vu, su) = axis();
    let (wv, vv, sv) = axis();
    Line {
        words: [wu, wv],
        values: vu.into_iter().zip(vv).map(|(a, b)| [a, b]).collect(),
        slack: su.into_iter().zip(sv).map(|(a, b)| a.max(b)).collect(),
    }
}

/// One input row: valid_in, load, then the six words.
fn row(valid: bool, load: Option<&[QuadWords; 2]>) -> Vec<u64> {
    let mut r = vec![valid as u64, load.is_some() as u64];
    for w in load.map_or([QuadWords::default(); 2], |w| *w) {
        r.extend([w.u, w.d, w.dd]);
    }
    r
}

const WORD: QFormat = QFormat::signed(16, 32);
const TEXEL: QFormat = QFormat::signed(16, 0);

impl Bench for TextureQuadratic {
    const ITEMS: &'static str = "lines";
    const DEFAULT_ITEMS: usize = 30;
    fn stimulus(_: &NoParams, n: usize, seed: u64) -> Stimulus {
        let mut rng = Rng::new(seed | 1);
        let lines: Vec<Line> = (0..n).map(|_| line(&mut rng)).collect();
        let (mut rows, mut expected) = (Vec::new(), vec![vec![Expected::Word(0)]]);
        expected[0].extend([Expected::DontCare; 4]);
        let mut worst = 0.0f64;
        for l in &lines {
            let mut k = 0;
            while k < l.values.len() {
                if rng.below(10) == 0 {
                    rows.push(row(false, None));
                    expected.push(vec![Expected::Word(0)]);
                    expected.last_mut().unwrap().extend([Expected::DontCare; 4]);
                    continue;
                }
                rows.push(row(true, (k == 0).then_some(&l.words)));
                let b = error_bound(k as u64) + l.slack[k];
                worst = worst.max(b);
                let v = l.values[k];
                expected.push(vec![
                    Expected::Word(1),
                    Expected::Within(v[0], 0.5 + b),
                    Expected::Within(v[1], 0.5 + b),
                    Expected::Within(v[0] + 0.5, b),
                    Expected::Within(v[1] + 0.5, b),
                ]);
                k += 1;
            }
        }
        // The last pixel shows one clock after it.
        rows.push(row(false, None));
        expected.truncate(rows.len());
        let tol = |max_abs: f64| Tolerance {
            max_abs,
            rms: max_abs,
        };
        let texel = Compare::Fixed {
            format: TEXEL,
            tol: tol(0.5 + worst),
        };
        let word = Compare::Fixed {
            format: WORD,
            tol: tol(worst.max(1e-12)),
        };
        Stimulus {
            rows,
            expected,
            compare: vec![Compare::Exact, texel, texel, word, word],
        }
    }
    fn twin(_: &NoParams) -> Box<dyn Twin> {
        Box::new(QuadRows(QuadTwin::default()))
    }
    /// Random words and flags on every input.
    fn edge_rows(_: &NoParams, seed: u64) -> Vec<Vec<u64>> {
        let mut rng = Rng::new(seed ^ 0x5ad | 1);
        (0..300)
            .map(|_| {
                let mut r = vec![rng.below(2) as u64, (rng.below(4) == 0) as u64];
                r.extend((0..6).map(|_| rng.next_u64() & ((1 << 48) - 1)));
                r
            })
            .collect()
    }
}

/// The twin on input rows.
struct QuadRows(QuadTwin);

impl Twin for QuadRows {
    fn step(&mut self, r: &[u64]) -> Vec<u64> {
        let (valid, texels, words) = self.0.outputs();
        let load = (r[1] & 1 != 0).then(|| {
            [0, 1].map(|k| QuadWords {
                u: r[2 + 3 * k],
                d: r[3 + 3 * k],
                dd: r[4 + 3 * k],
            })
        });
        self.0.clock(r[0] & 1 != 0, load.as_ref());
        vec![valid as u64, texels[0], texels[1], words[0], words[1]]
    }
}
