//! Hostile and careless inputs (issue "Hostile inputs and whole files"): each test is one of
//! its eleven reproduced defects. `.ci/hostile-inputs` runs the wider corpus against the
//! built binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The binary under test: this build's, or `SHADECORE_BIN` (e.g. an earlier build, to see
/// these tests fail on the defects they were written for).
fn bin() -> String {
    std::env::var("SHADECORE_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_shadecore").into())
}

/// Run shadecore with `args` in `dir`, killed after `limit` (a hang is a failure).
fn run_in(dir: &Path, args: &[&str], limit: Duration) -> Output {
    run_env(dir, args, &[], limit)
}

fn run_env(dir: &Path, args: &[&str], env: &[(&str, &str)], limit: Duration) -> Output {
    let mut child = Command::new(bin())
        .args(args)
        .envs(env.iter().copied())
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run shadecore");
    let t0 = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > limit {
            child.kill().unwrap();
            let out = child.wait_with_output().unwrap();
            panic!(
                "{args:?} still running after {limit:?} (a hang): {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// The lines of stderr that are not blank.
fn err_lines(out: &Output) -> Vec<String> {
    String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(str::to_string)
        .collect()
}

/// `out` is a one-line error (exit 1 or 2, no panic) mentioning every one of `needles`.
fn assert_one_line_error(out: &Output, what: &str, needles: &[&str]) {
    let lines = err_lines(out);
    assert!(
        matches!(out.status.code(), Some(1) | Some(2)),
        "{what}: exit {:?}, stderr {lines:?}",
        out.status
    );
    assert_eq!(lines.len(), 1, "{what}: expected one line, got {lines:?}");
    assert!(lines[0].starts_with("error:"), "{what}: {lines:?}");
    for n in needles {
        assert!(
            lines[0].to_lowercase().contains(&n.to_lowercase()),
            "{what}: {:?} does not mention {n:?}",
            lines[0]
        );
    }
}

fn assert_ok(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "{what}: exit {:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A tetrahedron with its vertices scaled by `scale`, then `extra` lines.
fn tetrahedron(scale: f64, extra: &str) -> String {
    let v = [
        [0.0, 0.0, 1.0],
        [1.0, 0.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, -1.0],
    ];
    let mut s = String::new();
    for p in v {
        s += &format!(
            "v {:e} {:e} {:e}\n",
            p[0] * scale,
            p[1] * scale,
            p[2] * scale
        );
    }
    s + "f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n" + extra
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const MINUTE: Duration = Duration::from_secs(60);

/// Item 1: `mtllib` opens nothing: neither /dev/zero (which grew without bound) nor a named
/// pipe (which hung `render`, `sweep` and `stream`).
#[test]
fn mtllib_opens_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(
        d,
        "zero.obj",
        &tetrahedron(1.0, "mtllib /dev/zero\nusemtl a\n"),
    );
    let fifo = d.join("fifo.mtl");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success());
    assert!(made, "mkfifo failed");
    write(d, "fifo.obj", &tetrahedron(1.0, "mtllib fifo.mtl\n"));
    for scene in ["zero.obj", "fifo.obj"] {
        let size = ["--size", "64x48"];
        for args in [
            vec![
                "render", "--engine", "golden", "--scene", scene, "--out", "r",
            ],
            vec![
                "sweep",
                "--rez",
                "10",
                "--shininess",
                "10",
                "--light-deg",
                "90",
            ],
            vec![
                "stream", "--sim", "rust-hdl", "--scene", scene, "--out", "s",
            ],
        ] {
            let mut args = args;
            if args[0] == "sweep" {
                args.extend(["--scene", scene, "--out", "w"]);
            }
            args.extend(size);
            let out = run_in(d, &args, MINUTE);
            assert_ok(&out, &format!("{args:?}"));
        }
    }
}

/// Item 2: a VCD that cannot be written is a one-line error, not a panic in rust-hdl's probe.
#[test]
fn vcd_write_errors_are_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    if !Path::new("/dev/full").exists() {
        eprintln!("SKIPPED: no /dev/full");
        assert!(std::env::var_os("CI").is_none(), "no /dev/full under CI");
        return;
    }
    for address in ["single", "four-triangle"] {
        let out = run_in(
            tmp.path(),
            &[
                "raster",
                "--tri",
                "3,1,40,12,9,30",
                "--address",
                address,
                "--vcd",
                "/dev/full",
            ],
            MINUTE,
        );
        assert_one_line_error(&out, "raster --vcd /dev/full", &["VCD", "no space"]);
    }
    // /dev/full is still the device (a rename into place would have replaced it).
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata("/dev/full")
        .unwrap()
        .file_type()
        .is_char_device());
}

/// Item 3: the error of one method among several names that method and its cause.
#[test]
fn an_error_names_its_method_and_cause() {
    let tmp = tempfile::tempdir().unwrap();
    let out = run_in(
        tmp.path(),
        &[
            "render",
            "--lighting",
            "phong",
            "--method",
            "gouraud,flat,bump,normalizer",
            "--sim",
            "rust-hdl",
            "--size",
            "64x48",
            "--out",
            "o",
        ],
        MINUTE,
    );
    assert_one_line_error(&out, "phong through the lit pipeline", &["phong"]);
    let line = &err_lines(&out)[0];
    assert!(
        line.contains("method bump") || line.contains("method normalizer"),
        "{line}"
    );
    assert!(!line.contains("another method"), "{line}");
}

/// Item 4: empty work is an error in `sweep` and `stream`, as in `render` (a 2×1 canvas with
/// integer vertices: the sphere covers no pixel centre).
#[test]
fn empty_work_is_an_error_everywhere() {
    let tmp = tempfile::tempdir().unwrap();
    for args in [
        vec![
            "sweep",
            "--subpixel",
            "0",
            "--size",
            "2x1",
            "--rez",
            "10",
            "--shininess",
            "10",
            "--light-deg",
            "90",
        ],
        vec![
            "stream",
            "--subpixel",
            "0",
            "--size",
            "2x1",
            "--sim",
            "rust-hdl",
        ],
        vec![
            "render",
            "--subpixel",
            "0",
            "--size",
            "2x1",
            "--engine",
            "golden",
        ],
    ] {
        let out = run_in(tmp.path(), &args, MINUTE);
        assert_one_line_error(&out, &format!("{args:?}"), &["nothing to draw"]);
    }
}

/// The names of the files in `dir` (hidden ones included).
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Item 5: a file-size limit (a full disk) leaves no truncated output and no temporary file;
/// the file it would have replaced keeps its old contents.
#[test]
fn a_full_disk_leaves_no_truncated_file() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    std::fs::create_dir(d.join("v")).unwrap();
    std::fs::write(d.join("v/normalizer.v"), "// an earlier export\n").unwrap();
    // bash: a 16 KiB limit on every file written, SIGXFSZ ignored so a write fails with EFBIG
    // (what a full disk gives, ENOSPC) instead of killing the process.
    let out = Command::new("bash")
        .arg("-c")
        .arg(format!(
            "ulimit -f 16; trap '' XFSZ; exec {} export-verilog --block normalizer --out v",
            bin()
        ))
        .current_dir(d)
        .output()
        .unwrap();
    assert_one_line_error(&out, "export onto a full disk", &["normalizer.v"]);
    assert_eq!(names(&d.join("v")), ["normalizer.v"]);
    assert_eq!(
        std::fs::read_to_string(d.join("v/normalizer.v")).unwrap(),
        "// an earlier export\n"
    );
    // The same for a render: no PNG cut short, no report.
    let out = Command::new("bash")
        .arg("-c")
        .arg(format!(
            "ulimit -f 16; trap '' XFSZ; exec {} render --engine golden --size 256x256 --out r",
            bin()
        ))
        .current_dir(d)
        .output()
        .unwrap();
    assert_one_line_error(&out, "render onto a full disk", &["png"]);
    for n in names(&d.join("r")) {
        assert!(!n.starts_with(".shadecore-tmp-"), "temporary left: {n}");
        assert_ne!(n, "report.json");
        if n.ends_with(".png") {
            let bytes = std::fs::read(d.join("r").join(&n)).unwrap();
            assert!(image::load_from_memory(&bytes).is_ok(), "{n} is cut short");
        }
    }
}

/// The files `report.json` of `dir` lists must be the folder's render outputs exactly, each
/// with the listed size and hash. `None` when there is no report.
fn report_agrees(dir: &Path) -> Option<Result<usize, String>> {
    let text = std::fs::read_to_string(dir.join("report.json")).ok()?;
    let check = || -> Result<usize, String> {
        let v: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
        let files = v["files"].as_object().ok_or("no files in report.json")?;
        for (name, f) in files {
            let bytes = std::fs::read(dir.join(name)).map_err(|e| format!("{name}: {e}"))?;
            if f["bytes"] != bytes.len() as u64 || f["fnv1a"] != shadecore::output::fnv1a(&bytes) {
                return Err(format!("{name} differs from report.json"));
            }
        }
        for n in names(dir) {
            if n.ends_with(".png") && !files.contains_key(&n) {
                return Err(format!("{n} is not in report.json"));
            }
        }
        Ok(files.len())
    };
    Some(check())
}

/// Item 5: a render into a folder holding an earlier render replaces it whole (the earlier
/// methods' files go), and a render killed at random points (SIGTERM, 20 tries) never leaves
/// a `report.json` that disagrees with the folder's PNGs.
#[test]
fn renders_killed_at_random_never_leave_a_disagreeing_report() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let all = [
        "render", "--engine", "golden", "--size", "160x120", "--out", "o",
    ];
    let t0 = Instant::now();
    assert_ok(&run_in(d, &all, MINUTE), "first render");
    let whole = t0.elapsed();
    // The reference, texture-reference and 19 methods (15 shading, 4 textured), 19 difference
    // images, the sheet.
    assert_eq!(report_agrees(&d.join("o")), Some(Ok(41)));
    // A smaller render into the same folder: the earlier methods' files go.
    let two = [&all[..], &["--method", "flat,gouraud"]].concat();
    assert_ok(&run_in(d, &two, MINUTE), "second render");
    assert_eq!(report_agrees(&d.join("o")), Some(Ok(6)));
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut reports = 0;
    for _ in 0..20 {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let at = whole.mul_f64((seed % 1000) as f64 / 1000.0 * 1.2);
        let mut child = Command::new(bin())
            .args(all)
            .current_dir(d)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(at);
        sigterm(child.id());
        child.wait().unwrap();
        if let Some(r) = report_agrees(&d.join("o")) {
            r.unwrap_or_else(|e| panic!("killed after {at:?}: {e}"));
            reports += 1;
        }
    }
    println!("{reports} of 20 killed renders had finished their report");
}

/// SIGTERM to `pid` through kill(1) (no libc dependency).
fn sigterm(pid: u32) {
    let _ = Command::new("kill")
        .args(["-TERM", &pid.to_string()])
        .status();
}

/// Item 5: two renders into one folder do not mix their files: the second is refused while
/// the first runs.
#[test]
fn two_renders_do_not_share_a_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    // A render of several seconds (two methods on rust-hdl at 800×600).
    let long = [
        "render",
        "--engine",
        "rtl",
        "--sim",
        "rust-hdl",
        "--method",
        "gouraud,subdivision",
        "--size",
        "800x600",
        "--out",
        "o",
    ];
    let mut first = Command::new(bin())
        .args(long)
        .current_dir(d)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // The first has made its folder (and, when it locks, taken the lock first).
    let t0 = Instant::now();
    while !d.join("o").exists() && t0.elapsed() < MINUTE {
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(Duration::from_millis(200));
    let second = run_in(
        d,
        &[
            "render", "--engine", "golden", "--size", "64x48", "--out", "o",
        ],
        MINUTE,
    );
    let still_running = first.try_wait().unwrap().is_none();
    assert!(first.wait().unwrap().success());
    assert!(
        still_running,
        "the first render ended before the second did: no overlap to check"
    );
    assert_one_line_error(
        &second,
        "a second render into the folder",
        &["another shadecore render"],
    );
    // The folder holds the first render alone (two methods, both engines' files).
    assert!(report_agrees(&d.join("o")).is_some_and(|r| r.is_ok()));
}

/// Item 6: an unknown value, or a flag without effect in the chosen combination, is a
/// one-line error naming the flag.
#[test]
fn options_without_effect_or_value_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let cases: &[(&[&str], &[&str])] = &[
        (
            &[
                "export-verilog",
                "--block",
                "normalizer",
                "--power",
                "bogus",
            ],
            &["--power"],
        ),
        (
            &[
                "export-verilog",
                "--block",
                "power-unit",
                "--power",
                "bogus",
            ],
            &["--power", "bogus"],
        ),
        (
            &[
                "export-verilog",
                "--block",
                "fast-unit",
                "--inv-sqrt",
                "bogus",
            ],
            &["--inv-sqrt"],
        ),
        (
            &["export-verilog", "--block", "brzssk", "--bump", "maybe"],
            &["--bump"],
        ),
        (
            &["export-verilog", "--block", "horner-unit", "--horner", "x"],
            &["--horner"],
        ),
        (
            &[
                "export-verilog",
                "--block",
                "normalizer",
                "--horner",
                "pipelined",
            ],
            &["--horner"],
        ),
        (
            &["synth", "--block", "normalizer", "--power", "w4"],
            &["--power"],
        ),
        (
            &["render", "--engine", "golden", "--sim", "verilator"],
            &["--sim"],
        ),
        (
            &["render", "--engine", "golden", "--lit-top", "stream"],
            &["--lit-top"],
        ),
        (
            &["render", "--engine", "golden", "--address", "four-triangle"],
            &["--address"],
        ),
        (
            &["render", "--engine", "golden", "--horner", "pipelined"],
            &["--horner"],
        ),
        (
            &[
                "render",
                "--method",
                "flat,gouraud",
                "--horner",
                "pipelined",
            ],
            &["--horner"],
        ),
        (
            &["render", "--method", "normalizer", "--address", "single"],
            &["--address"],
        ),
        (
            &[
                "raster",
                "--tri",
                "3,1,40,12,9,30",
                "--engine",
                "golden",
                "--sim",
                "verilator",
            ],
            &["--sim"],
        ),
        (
            &["synth", "--target", "ecp5", "--no-pnr", "--pins"],
            &["--pins"],
        ),
        (&["raster"], &["--tri"]),
    ];
    for (args, needles) in cases {
        let out = run_in(d, args, MINUTE);
        assert_one_line_error(&out, &format!("{args:?}"), needles);
    }
    assert!(!d.join("out").exists() && !d.join("target").exists());
}

/// Item 7: `--no-pnr` is honoured for ECP5: Yosys only, no nextpnr (a stand-in that fails
/// and records any call proves it is not run).
#[test]
fn no_pnr_skips_place_and_route_on_ecp5() {
    if !flow::tools::available(flow::tools::Tool::Yosys) {
        flow::tools::skip(
            "no_pnr_skips_place_and_route_on_ecp5",
            "yosys is not installed",
        );
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let called = d.join("called");
    let fake = write(
        d,
        "nextpnr",
        &format!("#!/bin/sh\necho \"$@\" >> {}\nexit 1\n", called.display()),
    );
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let out = run_env(
        d,
        &[
            "synth",
            "--target",
            "ecp5",
            "--block",
            "k-recurrence",
            "--no-pnr",
        ],
        &[("SHADECORE_NEXTPNR_ECP5", fake.to_str().unwrap())],
        Duration::from_secs(300),
    );
    assert_ok(&out, "synth --target ecp5 --no-pnr");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("place and route skipped (--no-pnr)"),
        "{stdout}"
    );
    let calls = std::fs::read_to_string(&called).unwrap_or_default();
    assert!(
        calls.lines().all(|l| l.trim() == "--version"),
        "nextpnr ran: {calls}"
    );
}

/// Item 8: depth takes the camera fit, so a mesh at a scale of 20 000 renders through the RTL
/// as through the golden model.
#[test]
fn a_large_scale_mesh_renders_through_the_rtl() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    for (name, scale) in [("big.obj", 20000.0), ("far.obj", 1e12)] {
        write(d, name, &tetrahedron(scale, ""));
        let out = run_in(
            d,
            &[
                "render",
                "--engine",
                "rtl",
                "--sim",
                "rust-hdl",
                "--method",
                "gouraud,normalizer",
                "--scene",
                name,
                "--size",
                "64x48",
                "--out",
                "o",
            ],
            MINUTE,
        );
        assert_ok(&out, name);
    }
}

/// Item 9: coordinates are read as f64: a finite 1e308 is reported as that value and the
/// range it breaks; a mesh at 1e-300 says why it cannot be drawn.
#[test]
fn coordinates_are_f64_with_a_stated_range() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(
        d,
        "huge.obj",
        &format!("v 1e308 0 0\n{}", &tetrahedron(1.0, "")[..]),
    );
    write(d, "tiny.obj", &tetrahedron(1e-300, ""));
    write(d, "fine.obj", &tetrahedron(1e-20, ""));
    let run = |scene: &str| {
        run_in(
            d,
            &[
                "render", "--engine", "golden", "--scene", scene, "--size", "64x48", "--out", "o",
            ],
            MINUTE,
        )
    };
    assert_one_line_error(&run("huge.obj"), "1e308", &["1e308", "1e30", "vertex 0"]);
    assert_one_line_error(
        &run("tiny.obj"),
        "1e-300",
        &["extent", "too small", "scale"],
    );
    // Small but distinct in f64: drawn.
    assert_ok(&run("fine.obj"), "1e-20");
}

/// Item 10: a file whose faces would not fit the memory budget is refused up front, the
/// budget in the error (2 000 000 identical faces took 1.76 GB; the cap allows a 256 MiB
/// file of 29 GB).
#[test]
fn faces_beyond_the_memory_budget_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let n = golden::scene::MAX_TRIANGLES + 1;
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    text.reserve(n as usize * 8);
    for _ in 0..n {
        text.push_str("f 1 2 3\n");
    }
    write(d, "many.obj", &text);
    let t0 = Instant::now();
    let out = run_in(
        d,
        &[
            "render", "--engine", "golden", "--scene", "many.obj", "--size", "64x48", "--out", "o",
        ],
        MINUTE,
    );
    assert_one_line_error(
        &out,
        "too many faces",
        &[&n.to_string(), "2048 MiB", "budget"],
    );
    assert!(t0.elapsed() < Duration::from_secs(20), "{:?}", t0.elapsed());
    // Quads count as two triangles each.
    let quads = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n".to_string()
        + &"f 1 2 3 4\n".repeat((golden::scene::MAX_TRIANGLES / 2 + 1) as usize);
    write(d, "quads.obj", &quads);
    let out = run_in(
        d,
        &[
            "render",
            "--engine",
            "golden",
            "--scene",
            "quads.obj",
            "--size",
            "64x48",
            "--out",
            "o",
        ],
        MINUTE,
    );
    assert_one_line_error(&out, "too many quads", &["triangles", "budget"]);
    // The span methods' per-line set-up has its own cap, named with the budget.
    let lines = pipeline::span::SPAN_BUDGET_BYTES / pipeline::span::BYTES_PER_SPAN_LINE;
    // 64×48: the triangle spans about 33 lines.
    let faces = lines / 30 + 1;
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n".to_string() + &"f 1 2 3\n".repeat(faces as usize);
    write(d, "lines.obj", &text);
    let out = run_in(
        d,
        &[
            "render",
            "--engine",
            "rtl",
            "--sim",
            "rust-hdl",
            "--method",
            "angular",
            "--scene",
            "lines.obj",
            "--size",
            "64x48",
            "--out",
            "o",
        ],
        MINUTE,
    );
    assert_one_line_error(
        &out,
        "too many span lines",
        &["method angular", "raster lines", "MiB memory budget"],
    );
}

/// Item 11: without a terminal, a long render prints a progress line every few seconds on
/// stderr; the help says how long a 4096² render takes.
#[test]
fn progress_shows_without_a_terminal() {
    let tmp = tempfile::tempdir().unwrap();
    let out = run_env(
        tmp.path(),
        &[
            "render", "--method", "gouraud", "--sim", "rust-hdl", "--size", "128x96", "--out", "o",
        ],
        &[("SHADECORE_TICK_SECONDS", "0.1")],
        MINUTE,
    );
    assert_ok(&out, "render");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("progress: render"))
        .collect();
    assert!(
        lines.len() >= 2 && lines.iter().all(|l| l.contains("rtl gouraud")),
        "{stderr}"
    );
    let help = Command::new(bin())
        .args(["render", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("4096x4096"), "{help}");
}
