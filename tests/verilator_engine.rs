//! The Verilator engine (`render --engine rtl --sim verilator`, the exported Verilog in
//! process) gives the same frames as the rust-hdl simulation, bit for bit, with the same clock
//! counts, for every pipeline: the Gouraud pipe, the lit pipeline (two builds), the span tops,
//! the quadric unit and the cubic pipeline (both Horner variants), through the render's default
//! tops. Skips with a notice without Verilator (fails when `CI` is set).

use flow::tools::{self, Tool};
use golden::methods::Method;
use indicatif::ProgressBar;
use shadecore::rtl_engine::{render_rtl_with, RtlBuild};
use shadecore::setup::{build, SceneArgs};
use shadecore::sim::Sim;

#[test]
fn verilator_frames_equal_rust_hdl_frames() {
    if !tools::require(&[Tool::Verilator], "verilator_frames_equal_rust_hdl_frames") {
        return;
    }
    let s = build(&SceneArgs {
        size: (120, 120),
        rez: 12,
        ..SceneArgs::default()
    })
    .unwrap();
    let cases = [
        (Method::Gouraud, false),
        (Method::Subdivision, false),
        (Method::NormalizerFit, false),
        (Method::Bump, false),
        (Method::Angular, false),
        (Method::FastFit, false),
        (Method::Quadric, false),
        (Method::Cubic, false),
        (Method::Cubic, true),
    ];
    // Two methods at a time (each run is one simulation on one core).
    flow::tools::two_at_a_time(cases, |(m, pipelined)| {
        let run = |sim: Sim| {
            render_rtl_with(
                &s,
                m,
                RtlBuild {
                    horner_pipelined: pipelined,
                    sim,
                    ..RtlBuild::default()
                },
                &ProgressBar::hidden(),
            )
            .unwrap_or_else(|e| panic!("{m} ({sim:?}): {e:#}"))
        };
        let t0 = std::time::Instant::now();
        let v = run(Sim::Verilator);
        let tv = t0.elapsed();
        let t0 = std::time::Instant::now();
        let r = run(Sim::RustHdl);
        let tr = t0.elapsed();
        println!(
            "{m}{}: {} fragments, {} clocks; verilator {tv:.1?} (build cached after the first run), rust-hdl {tr:.1?}",
            if pipelined { " (pipelined Horner)" } else { "" },
            r.stats.pixels,
            r.stats.clocks
        );
        assert!(
            r.stats.pixels > 1000,
            "{m}: only {} fragments",
            r.stats.pixels
        );
        assert_eq!(v.frame.rgb, r.frame.rgb, "{m}: the frames differ");
        assert_eq!(
            v.frame.depth, r.frame.depth,
            "{m}: the depth buffers differ"
        );
        assert_eq!(
            (v.stats.clocks, v.stats.pixels),
            (r.stats.clocks, r.stats.pixels),
            "{m}: clock counts differ"
        );
    });
}

/// `raster --sim verilator` gives the address block's per-clock outputs of the rust-hdl run,
/// clock for clock, on ordinary, degenerate, one-pixel and sliver triangles.
#[test]
fn verilator_raster_equals_rust_hdl_raster() {
    use shadecore::cmd::raster::{parse_tri, walk_clocks_with, Engine};
    if !tools::require(
        &[Tool::Verilator],
        "verilator_raster_equals_rust_hdl_raster",
    ) {
        return;
    }
    for t in [
        "3,1,40,12,9,30",
        "10,10,20,10,30,10",
        "5,5,5,5,5,5",
        "0,0,4095,3,7,1",
        "100,0,0,60,200,61",
    ] {
        let tri = parse_tri(t).unwrap();
        let v = walk_clocks_with(&tri, Engine::Rtl, None, Sim::Verilator).unwrap();
        let r = walk_clocks_with(&tri, Engine::Rtl, None, Sim::RustHdl).unwrap();
        assert_eq!(v, r, "{t}: the Verilator run differs");
        println!("{t}: {} clocks identical", r.len());
    }
}

/// `raster --address four-triangle --sim verilator` gives the four-triangle block's per-clock
/// outputs of the rust-hdl run, clock for clock.
#[test]
fn verilator_four_triangle_raster_equals_rust_hdl() {
    use shadecore::cmd::raster::{four_clocks, parse_tri, Engine};
    if !tools::require(
        &[Tool::Verilator],
        "verilator_four_triangle_raster_equals_rust_hdl",
    ) {
        return;
    }
    for t in [
        "3,1,40,12,9,30",
        "10,10,20,10,30,10",
        "0,0,4095,3,7,1",
        "100,0,0,61,201,61",
    ] {
        let tri = parse_tri(t).unwrap();
        let v = four_clocks(&tri, Engine::Rtl, None, Sim::Verilator).unwrap();
        let r = four_clocks(&tri, Engine::Rtl, None, Sim::RustHdl).unwrap();
        assert_eq!(v, r, "{t}: the Verilator run differs");
        println!("{t}: {} clocks identical", r.len());
    }
}

/// The main job (`render`, every method golden and through the RTL) on a small scene writes the
/// same files on both engines: every image byte for byte, and `report.json` equal but for the
/// wall times (`seconds`). A 16×16 texture (`--texture`): the built-in 256×256 one is 65 536
/// load clocks, about a minute of rust-hdl.
#[test]
fn main_job_files_are_identical_on_both_engines() {
    if !tools::require(
        &[Tool::Verilator],
        "main_job_files_are_identical_on_both_engines",
    ) {
        return;
    }
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    let texture = tempfile::tempdir().unwrap();
    let texture = texture.path().join("checker.png");
    image::RgbImage::from_fn(16, 16, |x, y| {
        let on = (x / 2 + y / 2) % 2 == 0;
        image::Rgb([if on { 230 } else { 20 }, (x * 16) as u8, (y * 16) as u8])
    })
    .save(&texture)
    .unwrap();
    for (dir, sim) in dirs.iter().zip(["verilator", "rust-hdl"]) {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_shadecore"))
            .args([
                "render",
                "--rez",
                "8",
                "--size",
                "48x48",
                "--sim",
                sim,
                "--texture",
            ])
            .arg(&texture)
            .arg("--out")
            .arg(dir.path())
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{sim}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let list = |d: &std::path::Path| {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
            // The folder's lock (`.shadecore.lock`: the pid that held it) is no output.
            .filter(|n| !n.starts_with('.'))
            .collect();
        v.sort();
        v
    };
    let files = list(dirs[0].path());
    assert_eq!(files, list(dirs[1].path()));
    assert!(
        files.iter().filter(|f| f.ends_with("-rtl.png")).count() >= 13,
        "{files:?}"
    );
    fn without_seconds(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(m) => {
                m.remove("seconds");
                m.values_mut().for_each(without_seconds);
            }
            serde_json::Value::Array(a) => a.iter_mut().for_each(without_seconds),
            _ => {}
        }
    }
    for f in &files {
        let [a, b] = [0, 1].map(|k| std::fs::read(dirs[k].path().join(f)).unwrap());
        if f == "report.json" {
            let [mut a, mut b]: [serde_json::Value; 2] =
                [a, b].map(|t| serde_json::from_slice(&t).unwrap());
            without_seconds(&mut a);
            without_seconds(&mut b);
            assert_eq!(a, b, "report.json differs beyond the wall times");
        } else {
            assert!(a == b, "{f} differs between the engines");
        }
    }
}
