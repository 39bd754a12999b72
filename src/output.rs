//! Image output: PNG files and a labelled side-by-side contact sheet.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// Write an RGB image as PNG, whole or not at all (`golden::files`).
pub fn save_png(path: &Path, width: u32, height: u32, rgb: &[[u8; 3]]) -> Result<()> {
    let buf: Vec<u8> = rgb.iter().flatten().copied().collect();
    save_rgb8(path, &buf, width, height)
}

/// Encode packed RGB bytes as PNG and write them whole (`golden::files`).
pub fn save_rgb8(path: &Path, buf: &[u8], width: u32, height: u32) -> Result<()> {
    let mut png = std::io::Cursor::new(Vec::new());
    image::write_buffer_with_format(
        &mut png,
        buf,
        width,
        height,
        image::ExtendedColorType::Rgb8,
        image::ImageFormat::Png,
    )
    .with_context(|| format!("encoding {}", path.display()))?;
    write_whole(path, png.get_ref())
}

/// Write `bytes` to `path` whole or not at all (`golden::files`): one-line error naming it.
pub fn write_whole(path: &Path, bytes: &[u8]) -> Result<()> {
    golden::files::write_whole(path, bytes).map_err(|e| anyhow::anyhow!(e))
}

/// The output folder of a render, owned for the run: locked against a second render, cleared
/// of the previous render's files when opened, and closed by writing `report.json` last.
///
/// A folder therefore holds either no `report.json` (a render is running, failed or was
/// killed: whatever PNGs are there are not a complete set) or one that lists every output file
/// of the folder with its size and FNV-1a hash ([`RenderDir::finish`]).
pub struct RenderDir {
    dir: PathBuf,
    /// Held (an advisory lock, released when the process ends, however it ends).
    _lock: std::fs::File,
}

/// The lock file of a render folder.
pub const LOCK_FILE: &str = ".shadecore.lock";
/// The report a render writes last.
pub const REPORT_FILE: &str = "report.json";

/// One output file as `report.json` lists it.
#[derive(serde::Serialize, serde::Deserialize, Debug, Clone, PartialEq, Eq)]
pub struct FileEntry {
    pub bytes: u64,
    /// FNV-1a, 64 bits, of the contents, in hex.
    pub fnv1a: String,
}

/// FNV-1a, 64 bits, of `bytes`, in hex.
pub fn fnv1a(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// Whether `name` is a file a render writes: `report.json`, `reference.png`, `sheet.png`, or
/// `<method>[-diff|-rtl|-rtl-diff|-golden|-rtl-vs-golden-diff].png` (the methods include
/// `texture-reference`).
pub fn is_render_output(name: &str) -> bool {
    if matches!(name, REPORT_FILE | "reference.png" | "sheet.png") {
        return true;
    }
    let Some(stem) = name.strip_suffix(".png") else {
        return false;
    };
    let method = [
        "-rtl-vs-golden-diff",
        "-rtl-diff",
        "-diff",
        "-rtl",
        "-golden",
    ]
    .iter()
    .find_map(|s| stem.strip_suffix(s))
    .unwrap_or(stem);
    golden::methods::Method::all()
        .filter(|&m| m != golden::methods::Method::Reference)
        .any(|m| m.name() == method)
}

impl RenderDir {
    /// Create (if needed) and lock `dir`, then remove the previous render's `report.json` first
    /// and its other outputs after it (files named as a render names them; other files are
    /// left alone), and temporary files a killed writer left.
    pub fn open(dir: &Path) -> Result<RenderDir> {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating output directory {}", dir.display()))?;
        let lock_path = dir.join(LOCK_FILE);
        let lock = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .with_context(|| format!("creating {}", lock_path.display()))?;
        match lock.try_lock() {
            Ok(()) => {
                // Who holds it, for a user who finds the file.
                let _ = lock.set_len(0);
                let _ = std::io::Write::write_all(
                    &mut &lock,
                    format!("{}\n", std::process::id()).as_bytes(),
                );
            }
            Err(std::fs::TryLockError::WouldBlock) => anyhow::bail!(
                "another shadecore render is writing into {} (it holds {LOCK_FILE}): wait for it or choose another --out",
                dir.display()
            ),
            Err(std::fs::TryLockError::Error(e)) => {
                return Err(e).with_context(|| format!("locking {}", lock_path.display()))
            }
        }
        let report = dir.join(REPORT_FILE);
        match std::fs::remove_file(&report) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(e).with_context(|| format!("removing {}", report.display())),
        }
        golden::files::remove_stale_temps(dir);
        for e in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
            let e = e.with_context(|| format!("reading {}", dir.display()))?;
            let name = e.file_name().to_string_lossy().into_owned();
            if is_render_output(&name) && e.file_type().is_ok_and(|t| t.is_file()) {
                std::fs::remove_file(e.path())
                    .with_context(|| format!("removing {}", e.path().display()))?;
            }
        }
        Ok(RenderDir {
            dir: dir.to_path_buf(),
            _lock: lock,
        })
    }

    /// Every render output in the folder (all written by this run: the folder was cleared
    /// when opened, under the lock) with its size and hash.
    pub fn files(&self) -> Result<BTreeMap<String, FileEntry>> {
        let mut files = BTreeMap::new();
        for e in std::fs::read_dir(&self.dir)
            .with_context(|| format!("reading {}", self.dir.display()))?
        {
            let e = e.with_context(|| format!("reading {}", self.dir.display()))?;
            let name = e.file_name().to_string_lossy().into_owned();
            if name != REPORT_FILE && is_render_output(&name) {
                let bytes = std::fs::read(e.path())
                    .with_context(|| format!("reading {}", e.path().display()))?;
                files.insert(
                    name,
                    FileEntry {
                        bytes: bytes.len() as u64,
                        fnv1a: fnv1a(&bytes),
                    },
                );
            }
        }
        Ok(files)
    }

    /// Write `report.json` (whole), the last file of the render.
    pub fn finish(self, json: &str) -> Result<()> {
        write_whole(&self.dir.join(REPORT_FILE), json.as_bytes())
    }
}

/// An RGB picture in memory.
pub struct Picture {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<[u8; 3]>,
}

const LABEL_H: u32 = 14;
const GAP: u32 = 4;

/// Largest side of a tile on the contact sheet: a larger image is shrunk by a whole factor
/// (each tile pixel the mean of a block), so a 4096² render's sheet stays small (the full
/// images are the PNGs beside it).
pub const MAX_TILE: u32 = 512;

/// Lay out `tiles` (label, image of `w`×`h`, or `None` for an empty cell) in a grid of `cols`
/// columns, each with its label above it in an 8×8 bitmap font. Images larger than
/// [`MAX_TILE`] are shrunk by the smallest whole factor that fits.
pub fn sheet(tiles: &[(String, Option<&[[u8; 3]]>)], w: u32, h: u32, cols: u32) -> Picture {
    let f = w.max(h).div_ceil(MAX_TILE).max(1);
    let (tw, th) = (w.div_ceil(f), h.div_ceil(f));
    let cols = cols.max(1).min(tiles.len().max(1) as u32);
    let rows = (tiles.len() as u32).div_ceil(cols);
    let cell_w = tw + GAP;
    let cell_h = th + LABEL_H + GAP;
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
        for y in 0..th {
            let dst = ((oy + LABEL_H + y) * width + ox) as usize;
            if f == 1 {
                let src = (y * w) as usize;
                pic.rgb[dst..dst + w as usize].copy_from_slice(&img[src..src + w as usize]);
                continue;
            }
            for x in 0..tw {
                // The mean of the f×f block (clipped at the image's edge).
                let (mut sum, mut n) = ([0u32; 3], 0u32);
                for sy in y * f..((y + 1) * f).min(h) {
                    for sx in x * f..((x + 1) * f).min(w) {
                        let p = img[(sy * w + sx) as usize];
                        for c in 0..3 {
                            sum[c] += p[c] as u32;
                        }
                        n += 1;
                    }
                }
                pic.rgb[dst + x as usize] = sum.map(|s| ((s + n / 2) / n) as u8);
            }
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

/// Progress as plain lines on stderr when stderr is not a terminal (a log, CI, `2> file`),
/// where the progress bars do not draw: every [`TICK_SECONDS`] a line with the position of
/// each bar being watched. Stops when dropped.
pub struct LogTicker {
    bars: std::sync::Arc<std::sync::Mutex<Vec<(String, indicatif::ProgressBar)>>>,
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

/// Seconds between two progress lines of a [`LogTicker`] (`SHADECORE_TICK_SECONDS` overrides
/// it, e.g. for a test).
pub const TICK_SECONDS: u64 = 5;

impl LogTicker {
    /// A ticker labelled `what` ("render"), running only when stderr is not a terminal.
    pub fn start(what: &str) -> LogTicker {
        use std::io::IsTerminal;
        use std::sync::atomic::Ordering;
        let bars: std::sync::Arc<std::sync::Mutex<Vec<(String, indicatif::ProgressBar)>>> =
            Default::default();
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let thread = (!std::io::stderr().is_terminal()).then(|| {
            let (bars, stop, what) = (bars.clone(), stop.clone(), what.to_string());
            let every = std::env::var("SHADECORE_TICK_SECONDS")
                .ok()
                .and_then(|s| s.parse::<f64>().ok())
                .filter(|s| *s > 0.0)
                .map_or(
                    std::time::Duration::from_secs(TICK_SECONDS),
                    std::time::Duration::from_secs_f64,
                );
            std::thread::spawn(move || {
                let t0 = std::time::Instant::now();
                let mut next = every;
                while !stop.load(Ordering::Relaxed) {
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    if t0.elapsed() < next {
                        continue;
                    }
                    next += every;
                    let parts: Vec<String> = bars
                        .lock()
                        .map(|b| {
                            b.iter()
                                .filter(|(_, bar)| !bar.is_finished())
                                .map(|(l, bar)| {
                                    format!("{l} {}/{}", bar.position(), bar.length().unwrap_or(0))
                                })
                                .collect()
                        })
                        .unwrap_or_default();
                    if !parts.is_empty() {
                        eprintln!(
                            "progress: {what}, {:.0} s: {}",
                            t0.elapsed().as_secs_f64(),
                            parts.join(", ")
                        );
                    }
                }
            })
        });
        LogTicker { bars, stop, thread }
    }

    /// Report `bar` as `label` in the lines (while it is not finished).
    pub fn watch(&self, label: &str, bar: &indicatif::ProgressBar) {
        if let Ok(mut b) = self.bars.lock() {
            b.push((label.to_string(), bar.clone()));
        }
    }
}

impl Drop for LogTicker {
    fn drop(&mut self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tile pixel of the sheet, `(x, y)` inside cell `i`'s image.
    fn at(p: &Picture, cols: u32, tw: u32, th: u32, i: u32, x: u32, y: u32) -> [u8; 3] {
        let ox = GAP + (i % cols) * (tw + GAP);
        let oy = GAP + (i / cols) * (th + LABEL_H + GAP);
        p.rgb[((oy + LABEL_H + y) * p.width + ox + x) as usize]
    }

    #[test]
    fn small_images_are_copied_and_large_ones_shrunk_by_block_means() {
        // 400×300: copied as they are.
        let (w, h) = (400u32, 300u32);
        let img: Vec<[u8; 3]> = (0..w * h)
            .map(|k| [(k % 251) as u8, 7, (k / w) as u8])
            .collect();
        let p = sheet(&[("a".into(), Some(&img[..])), ("b".into(), None)], w, h, 5);
        assert_eq!(
            (p.width, p.height),
            (2 * (w + GAP) + GAP, h + LABEL_H + 2 * GAP)
        );
        for (x, y) in [(0, 0), (399, 299), (123, 45)] {
            assert_eq!(at(&p, 2, w, h, 0, x, y), img[(y * w + x) as usize]);
        }
        // 1030×600: shrunk by 3 (⌈1030 / 512⌉) to 344×200; red is 90 on every third column,
        // so a full block's mean is 30, and the last column's block (x = 1029, alone) is 0
        // (1029 is a multiple of 3: 90).
        let (w, h) = (1030u32, 600u32);
        let img: Vec<[u8; 3]> = (0..w * h)
            .map(|k| [if (k % w) % 3 == 0 { 90 } else { 0 }, 200, 0])
            .collect();
        let p = sheet(&[("big".into(), Some(&img[..]))], w, h, 5);
        let (tw, th) = (344, 200);
        assert_eq!((p.width, p.height), (tw + 2 * GAP, th + LABEL_H + 2 * GAP));
        assert_eq!(at(&p, 1, tw, th, 0, 0, 0), [30, 200, 0]);
        assert_eq!(at(&p, 1, tw, th, 0, 342, 199), [30, 200, 0]);
        assert_eq!(at(&p, 1, tw, th, 0, 343, 0), [90, 200, 0]);
    }
}
