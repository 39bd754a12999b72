//! End-to-end tests of the RTL commands: Gouraud through the simulated hardware, and the
//! one-triangle address-block tool.

use std::collections::HashSet;
use std::process::{Command, Output};

fn shadecore(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shadecore"))
        .args(args)
        .output()
        .expect("run shadecore")
}

/// Run `shadecore args`, which must succeed (its stderr is the failure message).
fn shadecore_ok(args: &[&str]) -> Output {
    let out = shadecore(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Issue 4: the RTL Gouraud image of the default scene is within 1 LSB per channel of the
/// golden Gouraud image, with identical coverage. Checked on the PNGs the command writes.
#[test]
fn rtl_gouraud_render_within_one_lsb_of_golden() {
    let dir = tempfile::tempdir().unwrap();
    shadecore_ok(&[
        "render",
        "--engine",
        "rtl",
        "--method",
        "gouraud",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    let rtl = image::open(dir.path().join("gouraud.png"))
        .unwrap()
        .to_rgb8();
    let golden = image::open(dir.path().join("gouraud-golden.png"))
        .unwrap()
        .to_rgb8();
    assert_eq!(rtl.dimensions(), golden.dimensions());
    let mut covered = 0;
    for (a, b) in rtl.pixels().zip(golden.pixels()) {
        // Coverage must be identical: a pixel lit in one and black in the other is a
        // rasterization error, not a rounding difference.
        assert_eq!(
            a.0 == [0, 0, 0],
            b.0 == [0, 0, 0],
            "coverage differs: {a:?} vs {b:?}"
        );
        for c in 0..3 {
            assert!(a.0[c].abs_diff(b.0[c]) <= 1, "rtl {a:?} vs golden {b:?}");
        }
        covered += (b.0 != [0, 0, 0]) as usize;
    }
    assert!(covered > 100_000, "only {covered} pixels covered");
    assert!(dir.path().join("gouraud-rtl-vs-golden-diff.png").exists());
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap())
            .unwrap();
    assert_eq!(report["engine"], "rtl");
    assert!(
        report["methods"]["gouraud"]["rtl_vs_golden"]["max_abs_diff"]
            .as_u64()
            .unwrap()
            <= 1
    );
}

#[test]
fn rtl_engine_rejects_methods_it_does_not_implement() {
    let dir = tempfile::tempdir().unwrap();
    let out = shadecore(&[
        "render",
        "--engine",
        "rtl",
        "--method",
        "flat",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("gouraud") && err.contains("fast-fit") && !err.contains("panicked"),
        "{err}"
    );
}

fn dump(engine: &str, tri: &str) -> Vec<Vec<i64>> {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("clocks.csv");
    shadecore_ok(&[
        "raster",
        "--tri",
        tri,
        "--engine",
        engine,
        "--dump",
        csv.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("cycle,valid,x,y,step,line_start,done"));
    lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// The per-clock dump: RTL equals the golden cycle model, and its valid addresses are exactly
/// the triangle's pixels by an independent edge-function test written here.
#[test]
fn raster_dump_matches_golden_and_covers_the_triangle() {
    let tri = "3,1,40,12,9,30";
    let rtl = dump("rtl", tri);
    assert_eq!(rtl, dump("golden", tri));
    for (i, row) in rtl.iter().enumerate() {
        assert_eq!(row[0], i as i64, "cycle column");
    }
    assert_eq!(
        rtl.iter().filter(|r| r[6] == 1).count(),
        1,
        "exactly one done"
    );
    let got: HashSet<(i64, i64)> = rtl
        .iter()
        .filter(|r| r[1] == 1)
        .map(|r| (r[2], r[3]))
        .collect();
    assert_eq!(
        got.len(),
        rtl.iter().filter(|r| r[1] == 1).count(),
        "duplicate address"
    );
    // Independent reference: pixel centres strictly inside, or on a left edge (top-left rule;
    // this triangle has no horizontal edge). Vertices clockwise on screen (y down).
    let v = [(3i64, 1i64), (40, 12), (9, 30)];
    let mut want = HashSet::new();
    for y in 0..32 {
        for x in 0..42 {
            let (px, py) = (2 * x + 1, 2 * y + 1);
            let inside = (0..3).all(|k| {
                let (a, b) = (v[k], v[(k + 1) % 3]);
                let e = (2 * b.0 - 2 * a.0) * (py - 2 * a.1) - (2 * b.1 - 2 * a.1) * (px - 2 * a.0);
                // Edge a→b of a clockwise (y-down) triangle: interior has e > 0; on the edge,
                // inside only when it is a left edge (going up: b.y < a.y).
                e > 0 || (e == 0 && b.1 < a.1)
            });
            if inside {
                want.insert((x, y));
            }
        }
    }
    assert_eq!(got, want);
}

#[test]
fn raster_bad_triangles_are_one_line_errors() {
    for (tri, needle) in [
        ("0,0,10", "6"),
        ("0,0,10,3,4,5000", "4095"),
        ("a,0,1,1,2,2", "a"),
        ("0,0,1,1,-2,2", "-2"),
    ] {
        let out = shadecore(&["raster", "--tri", tri]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{tri} accepted");
        assert_eq!(err.lines().count(), 1, "{tri}: {err:?}");
        assert!(
            err.starts_with("error") && err.contains(needle) && !err.contains("panicked"),
            "{tri}: {err}"
        );
    }
}

/// A triangle the walk gives no pixel is not an error: the CSV (no valid clock) on standard
/// output, exit 0, and one note on standard error saying why.
#[test]
fn raster_degenerate_triangles_say_why_no_pixel() {
    for (tri, why) in [
        ("0,0,10,0,20,0", "zero area"),
        ("5,5,5,5,5,5", "zero area"),
        ("0,0,10,10,20,20", "zero area"),
        ("0,0,1,0,0,1", "area 0.5 pixels) owns no pixel centre"),
    ] {
        let out = shadecore(&["raster", "--tri", tri]);
        let err = String::from_utf8_lossy(&out.stderr);
        let csv = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{tri}: {err}");
        assert_eq!(err.lines().count(), 1, "{tri}: {err:?}");
        assert!(
            err.starts_with("note:") && err.contains(why),
            "{tri}: {err}"
        );
        assert!(
            csv.starts_with("cycle,valid")
                && csv
                    .lines()
                    .skip(1)
                    .all(|l| l.split(',').nth(1) == Some("0")),
            "{tri}: {csv}"
        );
    }
    // A triangle with pixels prints no note.
    let out = shadecore(&["raster", "--tri", "0,0,40,0,0,40"]);
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "{:?}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn export_verilog_writes_modules() {
    let dir = tempfile::tempdir().unwrap();
    shadecore_ok(&[
        "export-verilog",
        "--block",
        "all",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(dir.path().join("normalizer.v")).expect("normalizer.v");
    assert!(text.contains("module normalizer("));
    assert!(text.contains("endmodule"));
    let bad = shadecore(&[
        "export-verilog",
        "--block",
        "nonsense",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(
        !bad.status.success() && err.lines().count() == 1 && err.contains("nonsense"),
        "{err}"
    );
}

/// `export-verilog --ecp5-dsp` writes what the ECP5 flow reads: the power unit's registered
/// products as MULT18X18D instances (none left as a `*` between registers), the model beside
/// it; the default export has no vendor cell.
#[test]
fn export_verilog_ecp5_dsp_maps_products_and_writes_the_model() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let plain = shadecore_ok(&["export-verilog", "--block", "power-unit", "--out", out]);
    assert!(!String::from_utf8_lossy(&plain.stdout).contains("MULT18X18D"));
    let text = std::fs::read_to_string(dir.path().join("power_unit.v")).unwrap();
    assert!(!text.contains("MULT18X18D") && text.contains("$q * "));
    let run = shadecore_ok(&[
        "export-verilog",
        "--block",
        "power-unit",
        "--ecp5-dsp",
        "--out",
        out,
    ]);
    let said = String::from_utf8_lossy(&run.stdout);
    assert!(
        said.contains("23 products on registered MULT18X18D"),
        "{said}"
    );
    let text = std::fs::read_to_string(dir.path().join("power_unit.v")).unwrap();
    assert_eq!(text.matches("MULT18X18D #(").count(), 23);
    assert!(!text.contains("$q * "), "a product left to Yosys");
    let model = std::fs::read_to_string(dir.path().join("MULT18X18D_model.v")).unwrap();
    assert!(model.contains("module MULT18X18D("));
}

/// The README's block table is the registry's (`shadecore blocks`): adding a block without
/// updating the README fails here.
#[test]
fn readme_block_table_is_the_registry() {
    let out = shadecore(&["blocks"]);
    assert!(out.status.success());
    let table = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        table.lines().count(),
        2 + testbenches::registry::BLOCKS.len(),
        "{table}"
    );
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let begin = readme
        .find("<!-- blocks:begin -->\n")
        .expect("README marker")
        + 22;
    let end = readme.find("<!-- blocks:end -->").expect("README marker");
    assert_eq!(
        &readme[begin..end],
        table,
        "README block table differs from `shadecore blocks`: paste its output between the markers"
    );
}

/// The READMEs say what is true now: the top one a newcomer reads in ten minutes (at most 260
/// lines), and none carries a dated entry (measured figures live in `docs/`, with their date;
/// history in git).
#[test]
fn readmes_are_short_and_undated() {
    let root = env!("CARGO_MANIFEST_DIR");
    let top = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let lines = top.lines().count();
    assert!(lines <= 260, "README.md has {lines} lines (at most 260)");
    for dir in [
        "",
        "golden/",
        "rtl/",
        "pipeline/",
        "testbenches/",
        "vendor/",
    ] {
        let path = format!("{root}/{dir}README.md");
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        for (k, line) in text.lines().enumerate() {
            let dated = line.as_bytes().windows(10).any(|w| {
                w[..4].iter().all(u8::is_ascii_digit)
                    && w[4] == b'-'
                    && w[5..7].iter().all(u8::is_ascii_digit)
                    && w[7] == b'-'
                    && w[8..10].iter().all(u8::is_ascii_digit)
            });
            assert!(
                !dated,
                "{path}:{}: a dated entry in a README: {line}",
                k + 1
            );
        }
    }
}

/// `synth --pins`, `--device`, `--seed`, `--mult-regs` and `--jobs` name ECP5 placements: with
/// the iCE40 target each is a one-line error and a non-zero exit, before any tool runs.
#[test]
fn synth_ecp5_only_flags_are_one_line_errors() {
    for (args, word) in [
        (
            &["synth", "--block", "gouraud-stream", "--pins"][..],
            "--pins",
        ),
        (
            &["synth", "--block", "gouraud-stream", "--device", "25k"][..],
            "--device",
        ),
        (
            &["synth", "--block", "gouraud-stream", "--seed", "2"][..],
            "--seed",
        ),
        (
            &["synth", "--block", "power-unit", "--mult-regs", "fabric"][..],
            "--mult-regs",
        ),
        (
            &["synth", "--block", "power-unit", "--mult-regs", "dsp"][..],
            "--mult-regs",
        ),
        (
            &["synth", "--block", "power-unit", "--jobs", "2"][..],
            "--jobs",
        ),
    ] {
        let out = shadecore(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && err.trim().lines().count() == 1 && err.contains(word),
            "{args:?}: {err}"
        );
    }
}

/// The textured pipeline's build flags: `--tex-coord quadratic` or `bezier` with `--tex-k`, on a
/// block that does not read it, and an unknown coordinate are one-line errors naming what is
/// wrong.
#[test]
fn texture_coordinate_builds_refuse_what_they_cannot_build() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().to_str().unwrap();
    for (args, words) in [
        (
            &[
                "export-verilog",
                "--block",
                "textured-pipeline",
                "--tex-coord",
                "quadratic",
                "--tex-k",
                "2",
                "--out",
                out_dir,
            ][..],
            &["tex-k", "quadratic"][..],
        ),
        (
            &[
                "export-verilog",
                "--block",
                "texture-coord",
                "--tex-coord",
                "quadratic",
                "--out",
                out_dir,
            ][..],
            &["--tex-coord", "textured-pipeline"][..],
        ),
        (
            &[
                "export-verilog",
                "--block",
                "textured-pipeline",
                "--tex-coord",
                "bezier",
                "--tex-k",
                "4",
                "--out",
                out_dir,
            ][..],
            &["tex-k", "texture=bezier"][..],
        ),
        (
            &[
                "export-verilog",
                "--block",
                "textured-pipeline",
                "--tex-coord",
                "cubic",
                "--out",
                out_dir,
            ][..],
            &["cubic", "expected additive, quadratic or bezier"][..],
        ),
    ] {
        let out = shadecore(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success()
                && err.trim().lines().count() == 1
                && words.iter().all(|w| err.contains(w))
                && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
    // The per-line builds export, the pipeline and its stream top (line records on the
    // set-up stream).
    for block in ["textured-pipeline", "textured-stream"] {
        for coord in ["quadratic", "bezier"] {
            shadecore_ok(&[
                "export-verilog",
                "--block",
                block,
                "--tex-coord",
                coord,
                "--out",
                out_dir,
            ]);
        }
    }
}

/// `stream --method` with a method whose streams it does not write is a one-line error naming
/// the methods each top it writes has (and, for `quadric`, the two-lane top it does not write
/// yet); `--method gouraud` writes `gouraud-stream`'s files.
#[test]
fn stream_methods_are_the_stream_tops() {
    for method in ["quadric", "subdivision", "flat"] {
        let out = shadecore(&["stream", "--method", method, "--out", "target/never"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success()
                && err.trim().lines().count() == 1
                && err.contains(&format!("for method {method} "))
                && err.contains("gouraud-stream's for gouraud")
                && err.contains("quadric-stream")
                && err.contains("subdivision-stream"),
            "{err}"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let out = shadecore_ok(&[
        "stream",
        "--method",
        "gouraud",
        "--rez",
        "4",
        "--size",
        "32x32",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("gouraud-stream:"), "{text}");
    for f in ["setup.txt", "beats.txt", "gouraud_stream.v"] {
        assert!(dir.path().join(f).exists(), "{f}");
    }
    let setup = std::fs::read_to_string(dir.path().join("setup.txt")).unwrap();
    let words = setup.lines().filter(|l| !l.starts_with('#')).count();
    let records = setup.lines().filter(|l| l.ends_with(" 1")).count();
    assert_eq!(words, 23 * records, "23 words per Gouraud triangle record");
}

/// `stream --method texture` drives `textured-stream` (Verilator) with the register record,
/// the built-in 256×256 texture as texel records (three words each) and the sphere's
/// triangles; every beat's fragment is the golden `texture` image's pixel within 1 LSB, and the
/// fragments cover exactly the golden flat image's pixels, each once (the sphere is convex and the
/// fill rule gives every pixel to one triangle).
#[test]
fn stream_texture_drives_the_textured_top() {
    use flow::tools::{self, Tool};
    if !tools::require(&[Tool::Verilator], "stream_texture_drives_the_textured_top") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    let scene = ["--size", "48x48", "--rez", "6"];
    let out = shadecore_ok(
        &[
            &[
                "stream",
                "--method",
                "texture",
                "--sim",
                "verilator",
                "--out",
                d,
            ][..],
            &scene,
        ]
        .concat(),
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("textured-stream (texture, 256x256 texels)"),
        "{text}"
    );
    let setup = std::fs::read_to_string(dir.path().join("setup.txt")).unwrap();
    // Records as (header, words): the register record (8 words), 65 536 texel records (3
    // words), then the triangles (51 words).
    let mut records: Vec<(String, usize)> = Vec::new();
    let mut open = false;
    for l in setup.lines().filter(|l| !l.starts_with('#')) {
        if !open {
            records.push((l[..8].to_string(), 0));
        }
        records.last_mut().unwrap().1 += 1;
        open = !l.ends_with(" 1");
    }
    assert_eq!(records[0], ("00000002".to_string(), 8));
    assert!(records[1..=65536]
        .iter()
        .all(|r| *r == ("00000003".to_string(), 3)));
    assert!(records[65537..]
        .iter()
        .all(|r| *r == ("00000001".to_string(), 51)));
    let golden_dir = dir.path().join("golden");
    shadecore_ok(
        &[
            &[
                "render",
                "--engine",
                "golden",
                "--method",
                "texture,flat",
                "--out",
            ][..],
            &[golden_dir.to_str().unwrap()],
            &scene,
        ]
        .concat(),
    );
    let img = image::open(golden_dir.join("texture.png"))
        .unwrap()
        .to_rgb8();
    let beats = std::fs::read_to_string(dir.path().join("beats.txt")).unwrap();
    let mut seen = HashSet::new();
    let mut worst = 0;
    for l in beats.lines().filter(|l| !l.starts_with('#')) {
        let v: Vec<i64> = l.split(' ').map(|w| w.parse().unwrap()).collect();
        if v[2] == 0 {
            continue;
        }
        let (x, y) = (v[0] as u32, v[1] as u32);
        assert!(seen.insert((x, y)), "pixel ({x}, {y}) twice");
        let g = img.get_pixel(x, y).0;
        for c in 0..3 {
            worst = worst.max((v[3 + c] - g[c] as i64).abs());
        }
    }
    // Coverage from the flat image (a texel may be black; the flat colour is not).
    let flat = image::open(golden_dir.join("flat.png")).unwrap().to_rgb8();
    let covered: HashSet<(u32, u32)> = flat
        .enumerate_pixels()
        .filter(|p| p.2 .0 != [0, 0, 0])
        .map(|p| (p.0, p.1))
        .collect();
    assert_eq!(
        seen, covered,
        "the fragments cover the golden image's pixels"
    );
    assert!(
        worst <= 1,
        "a fragment {worst} LSB from the golden texture image"
    );
}

/// `synth --target ecp5 --jobs 2` over blocks named in a list: each block's report and table
/// row in the list's order (not the order they end in: the first takes longest), each row
/// with the LUT4 count its report printed. A block named twice is a one-line error.
#[test]
fn synth_ecp5_jobs_keep_the_list_order() {
    use flow::tools::{self, Tool};
    if !tools::require(&[Tool::Yosys], "synth_ecp5_jobs_keep_the_list_order") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("ecp5.md");
    let o = shadecore_ok(&[
        "synth",
        "--target",
        "ecp5",
        "--no-pnr",
        "--jobs",
        "2",
        "--block",
        "normalizer-k,k-recurrence,address-block",
        "--table",
        table.to_str().unwrap(),
    ]);
    let printed = String::from_utf8_lossy(&o.stdout).to_string();
    let reports: Vec<&str> = printed
        .lines()
        .filter(|l| l.contains(": Yosys synth_ecp5: "))
        .collect();
    let tops: Vec<&str> = reports
        .iter()
        .map(|l| l.split(':').next().unwrap())
        .collect();
    assert_eq!(
        tops,
        ["normalizer_k", "k_recurrence", "address_block"],
        "{printed}"
    );
    let text = std::fs::read_to_string(&table).unwrap();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .filter(|l| l.starts_with("| `"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    let names: Vec<&str> = rows.iter().map(|r| r[1]).collect();
    assert_eq!(
        names,
        ["`normalizer-k`", "`k-recurrence`", "`address-block`"],
        "{text}"
    );
    for (row, report) in rows.iter().zip(&reports) {
        assert!(
            report.contains(&format!(": {} LUT4,", row[3])),
            "{report}\n{text}"
        );
    }
    let out = shadecore(&["synth", "--block", "k-recurrence,k-recurrence", "--no-pnr"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.trim().lines().count() == 1 && err.contains("twice"),
        "{err}"
    );
}

/// `synth --table` writes the figures as a Markdown table (whole, with the command and date):
/// one row per block synthesized, its LUT4 and multiplier counts those printed.
#[test]
fn synth_table_writes_one_row_per_block() {
    use flow::tools::{self, Tool};
    if !tools::require(&[Tool::Yosys], "synth_table_writes_one_row_per_block") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("sub").join("fpga.md");
    let o = shadecore_ok(&[
        "synth",
        "--block",
        "colour-combine",
        "--no-pnr",
        "--table",
        table.to_str().unwrap(),
    ]);
    let printed = String::from_utf8_lossy(&o.stdout).to_string();
    let text = std::fs::read_to_string(&table).unwrap();
    assert!(text.contains("`shadecore synth --block colour-combine --target ice40 --no-pnr`"));
    let rows: Vec<&str> = text.lines().filter(|l| l.starts_with("| `")).collect();
    assert_eq!(rows.len(), 1, "{text}");
    let cells: Vec<&str> = rows[0].split('|').map(str::trim).collect();
    assert_eq!(cells[1], "`colour-combine`");
    let luts: u64 = cells[3].parse().unwrap();
    assert!(
        luts > 0 && printed.contains(&luts.to_string()),
        "{printed}\n{text}"
    );
    assert!(cells[5].ends_with("SB_MAC16") && cells[6] == "—");
    assert!(!dir.path().join("sub").join("fpga.md.tmp").exists());
}
