//! The Bézier block's twin (`golden::units::texture_bezier::BezierTwin`, bit-exact with the RTL
//! block `texture-bezier`) on every raster line of the sphere, the torus and `plane`, the lines
//! streamed back to back as the set-up software records them (`bezier_points`):
//!
//! - it shows every pixel of every line, in order, with `index` and `done`, and its texels are
//!   the golden `texture-bezier` method's (which runs the twin line by line: a check of that
//!   wiring);
//! - its texel is the f64 curve's nearest sample's except where the block's fixed-point
//!   comparisons may pick another sample as near the pixel centre (`may_show`): every
//!   difference lies within that, and the count is printed;
//! - the clocks it takes are the header's rate: one per pixel plus ⌊s/3⌋ for a pixel whose
//!   sample lies s samples beyond the previous pixel's, the next line's load taken in the clock
//!   of the last pixel (no clock between lines), plus the first load and the output register.
//!   The pixels per clock are printed.

use golden::raster::walk;
use golden::shading::texture::{bezier_points, coordinates, setup, Coord};
use golden::texture::Texture;
use golden::units::texture_bezier::{
    bezier, may_show, pick, pick_slack, samples, BezierLine, BezierTwin,
};
mod common;
use common::scene_tris;

/// One line: its record, the method's texels, the ranges the block may show, and the clocks
/// the header's rate gives its pixels.
struct Line {
    rec: BezierLine,
    method: Vec<[i64; 2]>,
    /// The f64 curve's nearest sample's texel.
    nearest: Vec<[i64; 2]>,
    may: Vec<[(f64, f64); 2]>,
    clocks: u64,
}

fn lines(name: &str, tex: &Texture) -> Vec<Line> {
    let mut out = Vec::new();
    for tri in scene_tris(name) {
        let wk = walk(&tri);
        if wk.pixel_count() == 0 {
            continue;
        }
        let s = setup(&tri, tex).expect("a textured triangle with an area");
        let method = coordinates(&tri, &s, &wk, Coord::Bezier);
        let mut k = 0;
        for row in wk.rows.iter().filter(|r| r.len > 0) {
            let [xp, up, vp] = bezier_points(&s, row);
            let n = row.len;
            let m = samples(n) as usize;
            let t = |j: usize| if m == 0 { 0.0 } else { j as f64 / m as f64 };
            let curve = |c: [f64; 3]| (0..=m).map(|j| bezier(c, t(j))).collect::<Vec<f64>>();
            let (xs, us, vs) = (curve(xp), curve(up), curve(vp));
            let picks = pick(&xs, n);
            let (mut prev, mut clocks) = (0, 0);
            for &j in &picks {
                clocks += 1 + ((j - prev) / 3) as u64;
                prev = j;
            }
            let slack = pick_slack(n);
            out.push(Line {
                rec: BezierLine::new(n, xp, up, vp),
                method: method[k..k + n as usize]
                    .iter()
                    .map(|p| [(p.x + 0.5).floor() as i64, (p.y + 0.5).floor() as i64])
                    .collect(),
                nearest: picks
                    .iter()
                    .map(|&j| [&us, &vs].map(|c| (c[j] + 0.5).floor() as i64))
                    .collect(),
                may: picks
                    .iter()
                    .enumerate()
                    .map(|(i, &j)| [&us, &vs].map(|c| may_show(&xs, c, j, i as u32, slack)))
                    .collect(),
                clocks,
            });
            k += n as usize;
        }
    }
    out
}

#[test]
fn the_bezier_block_shows_the_methods_texels_at_the_headers_rate() {
    let tex = Texture::builtin();
    for name in ["sphere", "torus", "plane"] {
        let lines = lines(name, tex);
        let pixels: usize = lines.iter().map(|l| l.method.len()).sum();
        let rate_clocks: u64 = 2 + lines.iter().map(|l| l.clocks).sum::<u64>();
        let mut twin = BezierTwin::default();
        let (mut next, mut line, mut pixel) = (0, 0, 0);
        let (mut clock, mut last_clock) = (0u64, 0u64);
        let (mut differ, mut beyond) = (0, Vec::new());
        while line < lines.len() {
            let o = twin.outputs(false);
            if o.valid {
                let l = &lines[line];
                assert_eq!(o.index as usize, pixel, "{name}: line {line}");
                assert_eq!(o.done, pixel + 1 == l.method.len(), "{name}: line {line}");
                let got = [o.u, o.v].map(|t| t as u16 as i16 as i64);
                assert_eq!(
                    got, l.method[pixel],
                    "{name}: line {line} pixel {pixel}: the method"
                );
                let want = l.nearest[pixel].map(|t| (t as u16 as i16) as i64);
                if got != want {
                    differ += 1;
                    for (a, (&g, &(c, h))) in got.iter().zip(&l.may[pixel]).enumerate() {
                        let b = 0.5 + h + pick_slack(l.rec.end_index + 1);
                        if (g as f64 - c).abs() > b {
                            beyond.push(format!(
                                "line {line} pixel {pixel} axis {a}: texel {g} against {c:.4} ± {b:.4}"
                            ));
                        }
                    }
                }
                pixel += 1;
                if pixel == l.method.len() {
                    line += 1;
                    pixel = 0;
                }
                last_clock = clock;
            }
            let load = (next < lines.len()).then(|| &lines[next].rec);
            if load.is_some() && o.ready {
                next += 1;
            }
            twin.clock(load, false);
            clock += 1;
            assert!(clock < 100 * rate_clocks, "{name}: the twin stalled");
        }
        let clocks = last_clock + 1;
        eprintln!(
            "{name}: {} lines, {pixels} pixels in {clocks} clocks ({:.3} pixels per clock; the header's rate gives {rate_clocks}); texels differing from the f64 curve's nearest sample's: {differ}",
            lines.len(),
            pixels as f64 / clocks as f64
        );
        assert!(beyond.is_empty(), "{name}: {}", beyond.join("\n"));
        assert_eq!(
            clocks, rate_clocks,
            "{name}: clocks against the header's rate"
        );
    }
}
