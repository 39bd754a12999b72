//! `shadecore-sim`, a block's testbench from the command line: its waveform, its limits and
//! its errors.

use std::process::{Command, Output};

fn sim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shadecore-sim"))
        .args(args)
        .output()
        .expect("run shadecore-sim")
}

/// Run `shadecore-sim args`, which must succeed (its stderr is the failure message).
fn sim_ok(args: &[&str]) -> Output {
    let out = sim(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// One line on stderr containing `needle`, a non-zero exit, no panic.
fn assert_clean_error(args: &[&str], needle: &str) {
    let o = sim(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{args:?} exited 0");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{args:?}: {err:?}");
    assert!(lines[0].contains(needle), "{args:?}: {err:?}");
}

#[test]
fn bad_arguments_are_one_line_errors() {
    // A simulation too large to hold (the VCD grows with the run).
    assert_clean_error(
        &["--block", "normalizer", "--vectors", "100000000"],
        "limit",
    );
    assert_clean_error(&["--block", "normaliser"], "normaliser");
    assert_clean_error(&["--block", "normalizer", "--vectors", "0"], "at least 1");
    assert_clean_error(&["--block", "normalizer", "--coeffs", "bogus"], "bogus");
    // A flag the block does not read is refused, not ignored.
    assert_clean_error(&["--block", "normalizer", "--power", "w4"], "--power");
}

/// A VCD that cannot be written (a full disk: /dev/full) is a one-line error, not a panic in
/// rust-hdl's probe; the device stays a device.
#[test]
fn an_unwritable_vcd_is_a_one_line_error() {
    if !std::path::Path::new("/dev/full").exists() {
        eprintln!("SKIPPED: no /dev/full");
        assert!(std::env::var_os("CI").is_none(), "no /dev/full under CI");
        return;
    }
    assert_clean_error(
        &[
            "--block",
            "normalizer",
            "--vectors",
            "10",
            "--vcd",
            "/dev/full",
            "--sim",
            "rust-hdl",
        ],
        "No space left",
    );
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata("/dev/full")
        .unwrap()
        .file_type()
        .is_char_device());
}

/// A closed standard output is a one-line error, not a panic (the read end is closed before
/// the command starts, so its first write fails).
#[test]
fn closed_standard_output_is_a_one_line_error() {
    let tmp = tempfile::tempdir().unwrap();
    let vcd = tmp.path().join("n.vcd");
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let o = Command::new(env!("CARGO_BIN_EXE_shadecore-sim"))
        .args(["--block", "normalizer", "--vectors", "50", "--vcd"])
        .arg(&vcd)
        .stdout(writer)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(!stderr.contains("panicked"), "{stderr}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{stderr:?}");
}

/// Values of `names` (under scope `uut`) sampled on every rising clock edge of a VCD, parsed
/// with the `vcd` crate (independent of the simulator's writer).
fn sample_vcd(path: &std::path::Path, names: &[&str]) -> Vec<Vec<u64>> {
    use vcd::{Command, Value};
    let mut parser = vcd::Parser::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let header = parser.parse_header().expect("VCD header");
    let code = |n: &str| {
        header
            .find_var(&["uut", n])
            .unwrap_or_else(|| panic!("port {n} missing from the VCD"))
            .code
    };
    let clock = code("clock");
    let codes: Vec<_> = names.iter().map(|n| code(n)).collect();
    let mut now = vec![0u64; names.len()];
    let mut samples = Vec::new();
    let mut clock_high = false;
    for cmd in parser {
        match cmd.expect("VCD body") {
            // The writer lists a rising clock before the register updates it causes, so the
            // values in force at that moment are the ones the flip-flops sample.
            Command::ChangeScalar(id, v) if id == clock => {
                let high = v == Value::V1;
                if high && !clock_high {
                    samples.push(now.clone());
                }
                clock_high = high;
            }
            Command::ChangeScalar(id, v) => {
                if let Some(k) = codes.iter().position(|c| *c == id) {
                    now[k] = (v == Value::V1) as u64;
                }
            }
            Command::ChangeVector(id, bits) => {
                if let Some(k) = codes.iter().position(|c| *c == id) {
                    now[k] = bits
                        .iter()
                        .fold(0, |acc, b| acc << 1 | (b == Value::V1) as u64);
                }
            }
            _ => {}
        }
    }
    samples
}

/// `shadecore-sim --vcd` writes a waveform a viewer can open: the ports are there, `valid`
/// travels 15 clocks (the normalizer's stated latency), one vector per clock comes out, and
/// every output vector is a unit vector to the formula's 0.36 % plus quantization.
#[test]
fn sim_writes_a_readable_normalizer_vcd() {
    let dir = tempfile::tempdir().unwrap();
    let vcd_path = dir.path().join("n.vcd");
    sim_ok(&[
        "--block",
        "normalizer",
        "--vectors",
        "200",
        "--seed",
        "11",
        "--vcd",
        vcd_path.to_str().unwrap(),
    ]);
    let s = sample_vcd(&vcd_path, &["valid_in", "valid_out", "x", "nx", "ny", "nz"]);
    let first_in = s
        .iter()
        .position(|r| r[0] == 1)
        .expect("valid_in never high");
    let first_out = s
        .iter()
        .position(|r| r[1] == 1)
        .expect("valid_out never high");
    assert_eq!(first_out - first_in, 15, "latency");
    assert_eq!(
        s.iter().filter(|r| r[1] == 1).count(),
        200,
        "one output per input vector"
    );
    // N' is signed Q2.17 (19 bits).
    let q217 = |w: u64| (((w << 45) as i64) >> 45) as f64 / 131072.0;
    for r in s.iter().filter(|r| r[1] == 1) {
        let len = (q217(r[3]).powi(2) + q217(r[4]).powi(2) + q217(r[5]).powi(2)).sqrt();
        assert!(
            (len - 1.0).abs() < 0.0036 + 3.0 * 2f64.powi(-17),
            "|N'| = {len}"
        );
    }
}
