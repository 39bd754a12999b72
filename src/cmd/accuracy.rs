//! `shadecore accuracy`: each approximation's maximum error over its stated domain, measured by
//! `golden::accuracy`, printed beside the sources' claims; `--json` prints the same report as
//! JSON, `--plots DIR` writes PNG plots of the error curves.
//!
//! The plots are drawn with `plotters` (lines, grid, frame) into an in-memory RGB buffer; their
//! text is drawn with the 8×8 bitmap font `font8x8`, so no font file is needed on the machine.

use anyhow::{Context, Result};
use golden::accuracy::{self, Entry, Metric, Plot, Report};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print the report as JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write PNG plots of the error curves into this directory (created if missing).
    #[arg(long, value_name = "DIR")]
    pub plots: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<()> {
    let report = accuracy::report();
    if a.json {
        crate::outln!("{}", serde_json::to_string_pretty(&report)?)?;
    } else {
        crate::out!("{}", table(&report))?;
    }
    if let Some(dir) = &a.plots {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        for p in accuracy::plots() {
            let path = dir.join(format!("{}.png", p.id));
            plot_png(&p, &path)?;
            eprintln!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// A figure in the units its metric reads best in.
pub fn format_value(metric: Metric, v: f64) -> String {
    match metric {
        Metric::MaxRelative | Metric::Relative => format!("{:+.4}%", 100.0 * v),
        Metric::MaxAbsolute => format!("{v:+.5}"),
        Metric::Ratio => format!("{v:.2}x"),
        Metric::Value => format!("{v:+.6}"),
    }
}

fn claim_text(e: &Entry) -> String {
    match e.claim {
        None => "-".into(),
        Some(c) => match e.metric {
            Metric::MaxRelative | Metric::Relative => format!("{:.3}%", 100.0 * c),
            Metric::Ratio => format!("{c:.0}x"),
            _ => format!("{c}"),
        },
    }
}

/// The report as a fixed-width text table: measured beside claim (ids are in the JSON).
pub fn table(r: &Report) -> String {
    let rows: Vec<[String; 4]> = r
        .entries
        .iter()
        .map(|e| {
            [
                e.what.clone(),
                e.domain.clone(),
                format_value(e.metric, e.measured),
                claim_text(e),
            ]
        })
        .collect();
    let head = ["approximation", "domain", "measured", "claimed"];
    let w: Vec<usize> = (0..4)
        .map(|i| {
            rows.iter()
                .map(|r| r[i].chars().count())
                .chain([head[i].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: [&str; 4]| {
        let mut s = String::new();
        for (i, c) in cells.iter().enumerate() {
            let pad = " ".repeat(w[i].saturating_sub(c.chars().count()));
            if i >= 2 {
                s.push_str(&pad);
                s.push_str(c);
            } else {
                s.push_str(c);
                s.push_str(&pad);
            }
            s.push_str(if i < 3 { "  " } else { "\n" });
        }
        s
    };
    let mut out = line(head);
    let dashes: Vec<String> = w.iter().map(|&n| "-".repeat(n)).collect();
    out.push_str(&line([&dashes[0], &dashes[1], &dashes[2], &dashes[3]]));
    for r in &rows {
        out.push_str(&line([&r[0], &r[1], &r[2], &r[3]]));
    }
    out.push_str(
        "\nRelative errors in percent; W and Schlick: absolute error against cos^n (peak = 1);\n\
         centre: cos^n >= 1/2, fall-off: cos^n < 1/2. Claims from the sources (seed 000/001).\n",
    );
    out
}

// ------------------------------------------------------------------------------------ plots

const W: u32 = 960;
const H: u32 = 600;
const LEFT: u32 = 100;
const RIGHT: u32 = 190;
const TOP: u32 = 50;
const BOTTOM: u32 = 60;

const PALETTE: [RGBColor; 5] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

/// "Nice" tick positions covering [lo, hi].
fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = (hi - lo).max(1e-300);
    let raw = span / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| span / s <= 7.0)
        .unwrap_or(mag * 10.0);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

fn tick_label(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// Draw `text` with the 8×8 bitmap font scaled by `scale`, top-left at (x, y).
fn draw_text(buf: &mut [u8], x: i32, y: i32, text: &str, scale: i32, rgb: [u8; 3]) {
    use font8x8::UnicodeFonts;
    for (k, ch) in text.chars().enumerate() {
        let glyph = font8x8::BASIC_FONTS
            .get(ch)
            .or_else(|| font8x8::BASIC_FONTS.get('?'));
        let Some(glyph) = glyph else { continue };
        for (gy, bits) in glyph.iter().enumerate() {
            for gx in 0..8 {
                if bits & (1 << gx) == 0 {
                    continue;
                }
                for sy in 0..scale {
                    for sx in 0..scale {
                        let px = x + (k as i32 * 8 + gx) * scale + sx;
                        let py = y + gy as i32 * scale + sy;
                        if px >= 0 && py >= 0 && (px as u32) < W && (py as u32) < H {
                            let i = 3 * (py as usize * W as usize + px as usize);
                            buf[i..i + 3].copy_from_slice(&rgb);
                        }
                    }
                }
            }
        }
    }
}

/// Text width in pixels at `scale`.
fn text_w(text: &str, scale: i32) -> i32 {
    text.chars().count() as i32 * 8 * scale
}

/// Render one error plot to a PNG file.
pub fn plot_png(p: &Plot, path: &Path) -> Result<()> {
    let mut buf = vec![255u8; (W * H * 3) as usize];
    let pts = p.series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !(x0.is_finite() && x1 > x0 && y0.is_finite() && y1.is_finite()) {
        anyhow::bail!("plot {} has no finite data", p.id);
    }
    let pad = ((y1 - y0) * 0.06).max(1e-12);
    let (y0, y1) = (y0 - pad, y1 + pad);
    let (xt, yt) = (ticks(x0, x1), ticks(y0, y1));
    let mut labels: Vec<(i32, i32, String, bool)> = Vec::new(); // (x, y, text, is_y_axis)
    {
        let root = BitMapBackend::with_buffer(&mut buf, (W, H)).into_drawing_area();
        let area = root.margin(TOP, BOTTOM, LEFT, RIGHT);
        let mut chart = ChartBuilder::on(&area).build_cartesian_2d(x0..x1, y0..y1)?;
        let grid = RGBColor(225, 225, 225);
        for &x in &xt {
            chart.draw_series(LineSeries::new([(x, y0), (x, y1)], grid))?;
            let (px, py) = chart.backend_coord(&(x, y0));
            labels.push((
                px,
                py + 8,
                tick_label(x, xt.get(1).map_or(1.0, |b| b - xt[0])),
                false,
            ));
        }
        for &y in &yt {
            chart.draw_series(LineSeries::new([(x0, y), (x1, y)], grid))?;
            let (px, py) = chart.backend_coord(&(x0, y));
            labels.push((
                px - 6,
                py - 4,
                tick_label(y, yt.get(1).map_or(1.0, |b| b - yt[0])),
                true,
            ));
        }
        if y0 < 0.0 && y1 > 0.0 {
            chart.draw_series(LineSeries::new(
                [(x0, 0.0), (x1, 0.0)],
                RGBColor(120, 120, 120),
            ))?;
        }
        for (i, s) in p.series.iter().enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            chart.draw_series(LineSeries::new(s.points.iter().copied(), c.stroke_width(2)))?;
        }
        let (fx0, fy0) = chart.backend_coord(&(x0, y1));
        let (fx1, fy1) = chart.backend_coord(&(x1, y0));
        root.draw(&Rectangle::new([(fx0, fy0), (fx1, fy1)], BLACK))?;
        for (i, _) in p.series.iter().enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            let (lx, ly) = (fx1 + 16, fy0 + 10 + 24 * i as i32);
            root.draw(&Rectangle::new(
                [(lx, ly + 6), (lx + 24, ly + 9)],
                c.filled(),
            ))?;
        }
        root.present()?;
    }
    let ink = [20, 20, 20];
    for (x, y, t, is_y) in labels {
        if is_y {
            draw_text(&mut buf, x - text_w(&t, 1), y, &t, 1, ink);
        } else {
            draw_text(&mut buf, x - text_w(&t, 1) / 2, y, &t, 1, ink);
        }
    }
    let plot_right = (W - RIGHT) as i32;
    for (i, s) in p.series.iter().enumerate() {
        draw_text(
            &mut buf,
            plot_right + 46,
            TOP as i32 + 12 + 24 * i as i32,
            &s.name,
            1,
            ink,
        );
    }
    let mid = (LEFT + (W - LEFT - RIGHT) / 2) as i32;
    draw_text(
        &mut buf,
        mid - text_w(&p.title, 2) / 2,
        14,
        &p.title,
        2,
        ink,
    );
    draw_text(
        &mut buf,
        mid - text_w(&p.x_label, 1) / 2,
        (H - BOTTOM) as i32 + 30,
        &p.x_label,
        1,
        ink,
    );
    draw_text(&mut buf, 8, TOP as i32 - 16, &p.y_label, 1, ink);
    crate::output::save_rgb8(path, &buf, W, H)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_lists_every_entry_with_its_claim() {
        let r = accuracy::report();
        let t = table(&r);
        for e in &r.entries {
            assert!(t.contains(&e.what), "missing {}", e.id);
        }
        // Measured beside claimed, e.g. the normalizer's 0.3509% against 0.360%.
        let line = t.lines().find(|l| l.contains("0.822K²")).unwrap();
        assert!(
            line.contains("+0.3509%") && line.trim_end().ends_with("0.360%"),
            "{line}"
        );
    }

    #[test]
    fn json_round_trips_the_figures() {
        let r = accuracy::report();
        let v: serde_json::Value =
            serde_json::from_str(&serde_json::to_string(&r).unwrap()).unwrap();
        let entries = v["entries"].as_array().unwrap();
        assert_eq!(entries.len(), r.entries.len());
        let e = entries
            .iter()
            .find(|e| e["id"] == "inv-sqrt-shift-add")
            .unwrap();
        assert_eq!(
            e["measured"].as_f64().unwrap(),
            r.get("inv-sqrt-shift-add").unwrap().measured
        );
        assert_eq!(e["claim"].as_f64().unwrap(), 0.0051);
    }

    #[test]
    fn plots_render_curves_and_text() {
        let dir = tempfile::tempdir().unwrap();
        for p in accuracy::plots() {
            let path = dir.path().join(format!("{}.png", p.id));
            plot_png(&p, &path).unwrap();
            let img = image::open(&path).unwrap().to_rgb8();
            assert_eq!(img.dimensions(), (W, H));
            // Every series colour appears (curves were drawn), and so does the text ink.
            for (i, _) in p.series.iter().enumerate() {
                let c = PALETTE[i % PALETTE.len()];
                assert!(
                    img.pixels().any(|px| px.0 == [c.0, c.1, c.2]),
                    "{}: series {i} not drawn",
                    p.id
                );
            }
            assert!(
                img.pixels().filter(|px| px.0 == [20, 20, 20]).count() > 500,
                "{}: no text",
                p.id
            );
        }
    }

    #[test]
    fn ticks_are_nice_and_cover_the_range() {
        let t = ticks(0.0, 1.0);
        let want = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0];
        assert_eq!(t.len(), want.len(), "{t:?}");
        assert!(
            t.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12),
            "{t:?}"
        );
        let t = ticks(-0.83, 0.82);
        assert!(t.len() >= 3 && t.len() <= 8, "{t:?}");
        assert!(t.iter().all(|v| (-0.83..=0.82).contains(v)));
    }
}
