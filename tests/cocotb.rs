//! The cocotb tests of the exported stream tops `pixel-stream`, `gouraud-stream`,
//! `cubic-stream` and `textured-stream` (testbenches/cocotb/): `shadecore stream` writes a
//! small scene's set-up words, the simulation's fragment beats and the Verilog; cocotb with
//! cocotbext-axi drives the Verilog under Icarus with random gaps on the set-up stream and
//! random back-pressure (long stretches included) on the fragment stream, and requires the
//! same beats in the same order. The same test fails on the Verilog with one operator flipped
//! (shown for two per top; for `textured-stream` tried once, not run in CI).
//!
//! Needs Icarus and a Python with cocotb, cocotb_tools and cocotbext-axi (`.ci/run` installs
//! them into `.venv/`; `SHADECORE_PYTHON` names another): skips with a notice without them,
//! fails when `CI` is set.

use std::path::Path;
use std::process::Command;

use flow::tools::{self, Tool};

fn cocotb(python: &Path, dir: &Path, verilog: &Path, build: &str, top: &str) -> (bool, String) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("testbenches/cocotb/run.py");
    let out = Command::new(python)
        .arg(&script)
        .arg(dir)
        .arg(verilog)
        .arg(dir.join(build))
        .arg(top)
        .env("SHADECORE_SEED", "20261123")
        .output()
        .expect("python runs (probed)");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

fn tail(text: &str, n: usize) -> String {
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

#[test]
#[ignore = "full tier: cocotb under Icarus"]
fn cocotb_drives_the_exported_pixel_stream_with_back_pressure() {
    if !tools::require(&[Tool::Iverilog, Tool::Vvp], "cocotb test of pixel-stream") {
        return;
    }
    let Some(python) = tools::cocotb_python() else {
        tools::skip(
            "cocotb test of pixel-stream",
            "no Python with cocotb, cocotb_tools and cocotbext-axi (pip install cocotb cocotbext-axi; .ci/run installs them into .venv/)",
        );
        return;
    };
    let dir = tools::unique_dir("cocotb-pixel-stream").unwrap();
    let st = Command::new(env!("CARGO_BIN_EXE_shadecore"))
        .args(["stream", "--rez", "6", "--size", "48x48", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    println!("{}", String::from_utf8_lossy(&st.stdout).trim());
    let verilog = dir.join("pixel_stream.v");
    let (ok, text) = cocotb(&python, &dir, &verilog, "build-good", "pixel_stream");
    assert!(
        ok,
        "cocotb test failed on the exported Verilog:\n{}",
        tail(&text, 30)
    );
    let summary = text
        .lines()
        .find(|l| l.contains("beats equal"))
        .unwrap_or("")
        .trim()
        .to_string();
    println!("cocotb (Icarus): {summary}");

    let good = std::fs::read_to_string(&verilog).unwrap();
    for (what, from, to) in [
        (
            "FIFO read pointer: + 1 → + 2",
            "rd_ptr$d = rd_ptr$q + 7'b1;",
            "rd_ptr$d = rd_ptr$q + 7'b10;",
        ),
        (
            "red channel rounding: + half LSB → − half LSB",
            "amb_r[(0)+:(8)]} << 32'hf) + half_lsb;",
            "amb_r[(0)+:(8)]} << 32'hf) - half_lsb;",
        ),
    ] {
        assert_eq!(
            good.matches(from).count(),
            1,
            "{what}: anchor {from:?} once"
        );
        let path = dir.join(format!("mutant-{}.v", what.len()));
        std::fs::write(&path, good.replacen(from, to, 1)).unwrap();
        let (ok, text) = cocotb(
            &python,
            &dir,
            &path,
            &format!("build-{}", what.len()),
            "pixel_stream",
        );
        assert!(!ok, "{what}: the cocotb test passed on the broken Verilog");
        let why = text
            .lines()
            .find(|l| l.contains("Error:") || l.contains("beat "))
            .unwrap_or("failed")
            .trim()
            .to_string();
        println!("mutant {what}: caught ({why})");
    }
}

/// The cocotb test on the stream top `top` (`shadecore stream --method <method> <extra>`): the
/// exported Verilog under random gaps and back-pressure delivers the rust-hdl simulation's
/// beats, and fails with each of `mutants` (what, anchor found once, replacement).
fn drive_stream_top(method: &str, extra: &[&str], top: &str, mutants: &[(&str, &str, &str)]) {
    let what_test = format!("cocotb test of {}", top.replace('_', "-"));
    if !tools::require(&[Tool::Iverilog, Tool::Vvp], &what_test) {
        return;
    }
    let Some(python) = tools::cocotb_python() else {
        tools::skip(
            &what_test,
            "no Python with cocotb, cocotb_tools and cocotbext-axi (pip install cocotb cocotbext-axi; .ci/run installs them into .venv/)",
        );
        return;
    };
    let dir = tools::unique_dir(&format!("cocotb-{top}")).unwrap();
    let st = Command::new(env!("CARGO_BIN_EXE_shadecore"))
        .args(["stream", "--method", method])
        .args(extra)
        .args(["--rez", "6", "--size", "48x48", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    println!("{}", String::from_utf8_lossy(&st.stdout).trim());
    let verilog = dir.join(format!("{top}.v"));
    let (ok, text) = cocotb(&python, &dir, &verilog, "build-good", top);
    assert!(
        ok,
        "cocotb test failed on the exported Verilog:\n{}",
        tail(&text, 30)
    );
    let summary = text
        .lines()
        .find(|l| l.contains("beats equal"))
        .unwrap_or("")
        .trim()
        .to_string();
    println!("cocotb (Icarus): {summary}");
    let good = std::fs::read_to_string(&verilog).unwrap();
    for (k, (what, from, to)) in mutants.iter().enumerate() {
        assert_eq!(
            good.matches(from).count(),
            1,
            "{what}: anchor {from:?} once"
        );
        let path = dir.join(format!("mutant-{k}.v"));
        std::fs::write(&path, good.replacen(from, to, 1)).unwrap();
        let (ok, text) = cocotb(&python, &dir, &path, &format!("build-{k}"), top);
        assert!(!ok, "{what}: the cocotb test passed on the broken Verilog");
        let why = text
            .lines()
            .find(|l| l.contains("Error:") || l.contains("beat "))
            .unwrap_or("failed")
            .trim()
            .to_string();
        println!("mutant {what}: caught ({why})");
    }
}

/// The same cocotb test on `gouraud-stream` (`shadecore stream --method gouraud`), two
/// operators flipped.
#[test]
#[ignore = "full tier: cocotb under Icarus"]
fn cocotb_drives_the_exported_gouraud_stream_with_back_pressure() {
    drive_stream_top(
        "gouraud",
        &[],
        "gouraud_stream",
        &[
            (
                "FIFO read pointer: + 1 → + 2",
                "rd_ptr$d = rd_ptr$q + 4'h1;",
                "rd_ptr$d = rd_ptr$q + 4'h2;",
            ),
            (
                "address block x step: + 1 → + 2",
                "p_x$d = p_x$q + 12'h1;",
                "p_x$d = p_x$q + 12'h2;",
            ),
        ],
    );
}

/// The same cocotb test on `cubic-stream` (`shadecore stream --method cubic`, both Horner
/// variants), two operators flipped in the serial build.
#[test]
#[ignore = "full tier: cocotb under Icarus"]
fn cocotb_drives_the_exported_cubic_stream_with_back_pressure() {
    drive_stream_top(
        "cubic",
        &["--horner", "serial"],
        "cubic_stream",
        &[
            (
                "FIFO read pointer: + 1 → + 2",
                "rd_ptr$d = rd_ptr$q + 5'b1;",
                "rd_ptr$d = rd_ptr$q + 5'b10;",
            ),
            (
                "depth run: + dz → − dz",
                "o_z$d = o_z$q + dz_d$q;",
                "o_z$d = o_z$q - dz_d$q;",
            ),
        ],
    );
    drive_stream_top("cubic", &["--horner", "pipelined"], "cubic_stream", &[]);
}

/// The same cocotb test on `textured-stream` (`shadecore stream --method texture`, an 8×8
/// texture so the texel records stay short under Icarus): the texture's texel records, then
/// the triangles. No mutant is run here, to keep CI within its time: the same harness fails
/// on two flipped operators per top above, and on this top with its texel write strobe tied
/// low (`pipe$tex_we = 1'b0;`, tried once when the test was written).
#[test]
#[ignore = "full tier: cocotb under Icarus"]
fn cocotb_drives_the_exported_textured_stream_with_back_pressure() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("texture.png");
    let texels: Vec<u8> = (0..8 * 8 * 3).map(|k| (k * 37 % 251) as u8).collect();
    image::RgbImage::from_raw(8, 8, texels)
        .unwrap()
        .save(&png)
        .unwrap();
    drive_stream_top(
        "texture",
        &["--texture", png.to_str().unwrap()],
        "textured_stream",
        &[],
    );
}
