//! Image output: PNG files and a labelled side-by-side contact sheet.

use std::path::Path;

use anyhow::{Context, Result};

/// Write an RGB image as PNG.
pub fn save_png(path: &Path, width: u32, height: u32, rgb: &[[u8; 3]]) -> Result<()> {
    let buf: Vec<u8> = rgb.iter().flatten().copied().collect();
    image::save_buffer(path, &buf, width, height, image::ExtendedColorType::Rgb8)
        .with_context(|| format!("writing {}", path.display()))
}

/// An RGB picture in memory.
pub struct Picture {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<[u8; 3]>,
}

const LABEL_H: u32 = 14;
const GAP: u32 = 4;

/// Lay out `tiles` (label, image of `w`×`h`, or `None` for an empty cell) in a grid of `cols`
/// columns, each with its label above it in an 8×8 bitmap font.
pub fn sheet(tiles: &[(String, Option<&[[u8; 3]]>)], w: u32, h: u32, cols: u32) -> Picture {
    let cols = cols.max(1).min(tiles.len().max(1) as u32);
    let rows = (tiles.len() as u32).div_ceil(cols);
    let cell_w = w + GAP;
    let cell_h = h + LABEL_H + GAP;
    let width = cols * cell_w + GAP;
    let height = rows * cell_h + GAP;
    let mut pic = Picture {
        width,
        height,
        rgb: vec![[24, 24, 24]; (width * height) as usize],
    };
    for (i, (label, img)) in tiles.iter().enumerate() {
        let ox = GAP + (i as u32 % cols) * cell_w;
        let oy = GAP + (i as u32 / cols) * cell_h;
        draw_text(&mut pic, ox, oy + 3, label, [230, 230, 230]);
        let Some(img) = img else { continue };
        for y in 0..h {
            let src = (y * w) as usize;
            let dst = ((oy + LABEL_H + y) * width + ox) as usize;
            pic.rgb[dst..dst + w as usize].copy_from_slice(&img[src..src + w as usize]);
        }
    }
    pic
}

fn draw_text(pic: &mut Picture, x0: u32, y0: u32, text: &str, colour: [u8; 3]) {
    use font8x8::UnicodeFonts;
    for (k, ch) in text.chars().enumerate() {
        let Some(glyph) = font8x8::BASIC_FONTS.get(ch) else {
            continue;
        };
        for (gy, bits) in glyph.iter().enumerate() {
            for gx in 0..8u32 {
                if bits & (1 << gx) != 0 {
                    let (x, y) = (x0 + k as u32 * 8 + gx, y0 + gy as u32);
                    if x < pic.width && y < pic.height {
                        pic.rgb[(y * pic.width + x) as usize] = colour;
                    }
                }
            }
        }
    }
}

/// `println!` that returns an error instead of panicking when standard output is closed (a
/// pipe whose reader has gone: `shadecore render | true`): `outln!(...)?` gives the one-line
/// "writing to standard output: Broken pipe" and a non-zero exit.
#[macro_export]
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*)
            .map_err(|e| anyhow::anyhow!("writing to standard output: {e}"))
    }};
}

/// `print!` as [`outln!`].
#[macro_export]
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        write!(std::io::stdout().lock(), $($arg)*)
            .map_err(|e| anyhow::anyhow!("writing to standard output: {e}"))
    }};
}
