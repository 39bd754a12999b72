//! `verilator --lint-only -Wall` on the exported Verilog of every registered block, in every
//! parameter set the generic tests build (issue "FPGA-ready Verilog", item 4). The only
//! configuration is the waiver file `rtl/lint/verilator_waivers.vlt`, where every waiver names
//! its signals and its reason; any other warning fails the test.
//!
//! Needs Verilator: skips with a notice without it, fails when `CI` is set.

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

use flow::tools::{self, two_at_a_time, Tool};
use rtl::core::export;
use rtl::core::registry::Options;
use testbenches::registry::{self, BLOCKS};

/// The `%Warning`/`%Error` lines of `verilator --lint-only -Wall [waivers] --top-module m file`.
fn lint(dir: &Path, module: &str, file: &Path, waivers: Option<&Path>) -> Vec<String> {
    let mut cmd = Command::new("verilator");
    cmd.arg("--lint-only").arg("-Wall");
    if let Some(w) = waivers {
        cmd.arg(w);
    }
    cmd.arg("--top-module")
        .arg(module)
        .arg(file)
        .current_dir(dir);
    let out = cmd.output().expect("verilator runs (probed)");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<String> = text
        .lines()
        .filter(|l| l.starts_with("%Warning") || l.starts_with("%Error"))
        .filter(|l| !l.starts_with("%Error: Exiting due to"))
        .map(str::to_owned)
        .collect();
    assert!(
        out.status.success() || !lines.is_empty(),
        "verilator failed without a message on {}:\n{text}",
        file.display()
    );
    lines
}

#[test]
fn verilator_wall_is_clean_on_every_exported_block() {
    if !tools::require(&[Tool::Verilator], "verilator -Wall lint of every block") {
        return;
    }
    let dir = tools::unique_dir("lint").unwrap();
    let waivers = export::write_waivers(&dir).unwrap();
    let mut seen = BTreeSet::new();
    // Every distinct export, written under the module's own name in a folder of its own.
    let mut jobs = Vec::new();
    for b in BLOCKS {
        let mut sets = b.test_sets();
        sets.insert(0, Options::new());
        for (k, o) in sets.iter().enumerate() {
            let text = b.verilog(o).unwrap();
            // Parameter sets that give the same hardware give the same body (the header
            // differs only in its parameter line).
            let body: String = text.lines().filter(|l| !l.starts_with("//")).collect();
            if !seen.insert((b.name(), body)) {
                continue;
            }
            // The file name differs from the module's only by the set index: lint under the
            // module's own name, as a user's flow would see it.
            let sub = dir.join(format!("{}-set{k}", b.name()));
            std::fs::create_dir_all(&sub).unwrap();
            let named = sub.join(format!("{}.v", b.module_name()));
            std::fs::write(&named, &text).unwrap();
            jobs.push((b.name(), format!("{o:?}"), b.module_name(), sub, named));
        }
    }
    let linted = jobs.len();
    // Without the waivers on the first export until one shows the file is not vacuous (each
    // lint is a Verilator run; the waived lint below is the check).
    let unwaived = jobs
        .iter()
        .map(|(_, _, m, sub, named)| lint(sub, m, named, None).len())
        .find(|&n| n > 0)
        .unwrap_or(0);
    // The waived lint of every export, two Verilator runs at a time.
    let failures = std::sync::Mutex::new(Vec::new());
    two_at_a_time(jobs.iter(), |(name, o, m, sub, named)| {
        let w = lint(sub, m, named, Some(&waivers));
        if !w.is_empty() {
            failures.lock().unwrap().push(format!(
                "{name} ({o}): {} warning(s), first:\n  {}",
                w.len(),
                w.iter().take(5).cloned().collect::<Vec<_>>().join("\n  ")
            ));
        }
    });
    let mut failures = failures.into_inner().unwrap();
    failures.sort();
    println!(
        "verilator -Wall: {linted} distinct exports of {} blocks; {unwaived} warnings without \
         the waiver file on the first that has any, {} with it",
        BLOCKS.len(),
        failures.len()
    );
    assert!(linted >= BLOCKS.len(), "every block linted");
    assert!(unwaived > 0, "the waiver file is not vacuous");
    assert!(
        failures.is_empty(),
        "verilator -Wall is not clean:\n{}",
        failures.join("\n")
    );
}

/// The lint can fail: an unsized 32-bit literal put back into one assignment, an unused
/// signal and a truncating assignment are each reported, waiver file or not.
#[test]
fn lint_reports_width_and_unused_defects() {
    if !tools::require(&[Tool::Verilator], "verilator -Wall lint mutants") {
        return;
    }
    let dir = tools::unique_dir("lint-mutants").unwrap();
    let waivers = export::write_waivers(&dir).unwrap();
    let b = registry::find("address-block").unwrap();
    let text = b.verilog(&Options::new()).unwrap();
    let module = b.module_name();
    let anchor = "p_x$d = p_x$q + 12'h1;";
    assert!(text.contains(anchor), "anchor {anchor:?} in the export");
    let mutants = [
        (
            "unsized literal",
            "WIDTH",
            text.replacen(anchor, "p_x$d = p_x$q + 32'h1;", 1),
        ),
        (
            "unused local",
            "UNUSEDSIGNAL",
            text.replacen(
                "// Update code",
                "// Update code\n    reg [3:0] stray_word;\n    always @(*) stray_word = 4'h0;",
                1,
            ),
        ),
    ];
    let file = dir.join(format!("{module}.v"));
    std::fs::write(&file, &text).unwrap();
    assert_eq!(
        lint(&dir, &module, &file, Some(&waivers)),
        Vec::<String>::new()
    );
    for (what, rule, m) in mutants {
        assert_ne!(m, text, "{what}: mutation applied");
        std::fs::write(&file, &m).unwrap();
        let w = lint(&dir, &module, &file, Some(&waivers));
        assert!(
            w.iter().any(|l| l.contains(rule)),
            "{what}: expected a {rule} warning, got {w:?}"
        );
        println!("{what}: caught ({})", w[0]);
    }
}
