//! The Verilator engine under bad conditions, through the CLI: Verilator missing (the default
//! falls back to rust-hdl with a notice; `--sim verilator` is a one-line error), two processes
//! compiling the same block at once (one builds, the other waits; one cache entry), and a
//! broken cache entry (a truncated library is rebuilt, never loaded). Each run on a cache of
//! its own (`CARGO_TARGET_DIR` in a temporary directory).

use std::process::{Command, Output};

use flow::tools::{self, Tool};

fn shadecore() -> Command {
    Command::new(env!("CARGO_BIN_EXE_shadecore"))
}

fn text(o: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&o.stdout).to_string(),
        String::from_utf8_lossy(&o.stderr).to_string(),
    )
}

#[test]
fn without_verilator_the_default_falls_back_and_the_switch_fails_in_one_line() {
    let out = tempfile::tempdir().unwrap();
    // No PATH: neither verilator nor a C++ compiler is found.
    let run = |extra: &[&str]| {
        shadecore()
            .args([
                "render", "--engine", "rtl", "--method", "gouraud", "--rez", "6",
            ])
            .args(["--size", "48x48", "--out"])
            .arg(out.path())
            .args(extra)
            .env("PATH", "")
            .output()
            .unwrap()
    };
    let fallback = run(&[]);
    let (_, err) = text(&fallback);
    assert!(fallback.status.success(), "{err}");
    assert!(
        err.contains("verilator is not installed") && err.contains("rust-hdl"),
        "no notice: {err}"
    );
    assert!(out.path().join("gouraud.png").exists());
    let forced = run(&["--sim", "verilator"]);
    let (_, err) = text(&forced);
    assert!(!forced.status.success());
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(lines[0].contains("--sim verilator") && lines[0].contains("apt-get install verilator"));
    assert!(!err.contains("panicked"));
}

/// One triangle through the address block under Verilator: its per-clock CSV on stdout.
fn raster_on_verilator(target: &std::path::Path) -> Command {
    let mut c = shadecore();
    c.args(["raster", "--tri", "3,1,40,12,9,30", "--sim", "verilator"])
        .env("CARGO_TARGET_DIR", target);
    c
}

/// The run's result: every CSV row.
fn result_lines(stdout: &str) -> Vec<String> {
    stdout.lines().map(str::to_string).collect()
}

fn entries(target: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(target.join("verilated"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| !n.ends_with(".lock"))
        .collect();
    v.sort();
    v
}

#[test]
fn two_processes_share_one_build_and_a_broken_entry_is_rebuilt() {
    if !tools::require(
        &[Tool::Verilator],
        "two_processes_share_one_build_and_a_broken_entry_is_rebuilt",
    ) {
        return;
    }
    let target = tempfile::tempdir().unwrap();
    let spawn = || {
        raster_on_verilator(target.path())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (a, b) = (spawn(), spawn());
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    for o in [&a, &b] {
        assert!(o.status.success(), "{}", text(o).1);
    }
    assert_eq!(result_lines(&text(&a).0), result_lines(&text(&b).0));
    let e = entries(target.path());
    let models: Vec<&String> = e
        .iter()
        .filter(|n| n.starts_with("address_block-"))
        .collect();
    assert_eq!(models.len(), 1, "one cache entry for the block: {e:?}");
    assert!(
        e.iter().all(|n| !n.starts_with(".tmp")),
        "a temporary directory left: {e:?}"
    );

    // Cut the library short (a new file: as a full disk or a killed copy leaves it): the next
    // run says so, rebuilds, and gives the same result.
    let lib = target
        .path()
        .join("verilated")
        .join(models[0])
        .join("lib.so");
    let whole = std::fs::read(&lib).unwrap();
    let cut = lib.with_extension("cut");
    std::fs::write(&cut, &whole[..whole.len() / 3]).unwrap();
    std::fs::rename(&cut, &lib).unwrap();
    let again = raster_on_verilator(target.path()).output().unwrap();
    let (out, err) = text(&again);
    assert!(again.status.success(), "{err}");
    assert!(
        err.contains("is broken") && err.contains("rebuilding"),
        "{err}"
    );
    assert_eq!(result_lines(&out), result_lines(&text(&a).0));
    assert_eq!(std::fs::read(&lib).unwrap().len(), whole.len());
}
