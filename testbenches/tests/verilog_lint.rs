//! `verilator --lint-only -Wall` on the exported Verilog of every registered block, in every
//! parameter set the generic tests build (issue "FPGA-ready Verilog", item 4): each structure
//! once in the everyday tier, the exports differing from a linted one in constants only in the
//! full tier. The only
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

/// `text` with the value of every sized literal (`12'h1f` → `12'h#`) masked: two exports alike
/// under it are the same netlist with other constants (coefficient sets), which Verilator's
/// lint rules (widths, unused and undriven bits, structure) see alike.
fn structure(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        out.push(c);
        if c == '\'' && chars.peek().is_some_and(|b| "hdbo".contains(*b)) {
            out.push(chars.next().unwrap());
            out.push('#');
            while chars
                .peek()
                .is_some_and(|d| d.is_ascii_hexdigit() || "_xz".contains(*d))
            {
                chars.next();
            }
        }
    }
    out
}

/// Which exports a lint test runs on.
#[derive(Clone, Copy, PartialEq)]
enum Which {
    /// The first export of each structure ([`structure`]): the everyday tier.
    Structures,
    /// Every other distinct export (the same structure with other constants): the full tier.
    Rest,
}

/// The waived `verilator --lint-only -Wall` of the exports `which` selects (every registered
/// block in every parameter set the generic tests build), two at a time; fails on any warning.
fn lint_exports(which: Which) {
    let dir = tools::unique_dir("lint").unwrap();
    let waivers = export::write_waivers(&dir).unwrap();
    let mut seen = BTreeSet::new();
    let mut shapes = BTreeSet::new();
    // Every distinct export, written under the module's own name in a folder of its own.
    let mut jobs = Vec::new();
    let mut distinct = 0;
    for b in BLOCKS {
        let mut sets = b.test_sets();
        sets.insert(0, Options::new());
        for (k, o) in sets.iter().enumerate() {
            let text = b.verilog(o).unwrap();
            // Parameter sets that give the same hardware give the same body (the header
            // differs only in its parameter line).
            let body: String = text.lines().filter(|l| !l.starts_with("//")).collect();
            let shape = structure(&body);
            if !seen.insert((b.name(), body)) {
                continue;
            }
            distinct += 1;
            let first_of_shape = shapes.insert((b.name(), shape));
            if first_of_shape != (which == Which::Structures) {
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
    let unwaived = if which == Which::Structures {
        jobs.iter()
            .map(|(_, _, m, sub, named)| lint(sub, m, named, None).len())
            .find(|&n| n > 0)
            .unwrap_or(0)
    } else {
        1
    };
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
        "verilator -Wall: {linted} of {distinct} distinct exports ({} structures) of {} blocks; \
         {unwaived} warnings without the waiver file on the first that has any, {} with it",
        shapes.len(),
        BLOCKS.len(),
        failures.len()
    );
    match which {
        Which::Structures => {
            assert!(linted >= BLOCKS.len(), "every block linted");
            assert!(unwaived > 0, "the waiver file is not vacuous");
        }
        Which::Rest => assert!(linted > 0, "some exports differ in constants only"),
    }
    assert!(
        failures.is_empty(),
        "verilator -Wall is not clean:\n{}",
        failures.join("\n")
    );
}

#[test]
fn verilator_wall_is_clean_on_every_block_structure() {
    if !tools::require(&[Tool::Verilator], "verilator -Wall lint of every block") {
        return;
    }
    lint_exports(Which::Structures);
}

/// Full tier: the exports the everyday lint leaves out (the same netlist as one it lints, with
/// other constants).
#[test]
#[ignore = "full tier: exports differing from a linted one in constants only"]
fn verilator_wall_is_clean_on_every_other_export() {
    if !tools::require(&[Tool::Verilator], "verilator -Wall lint of every export") {
        return;
    }
    lint_exports(Which::Rest);
}

/// The structure mask keeps widths and masks values only.
#[test]
fn structure_masks_values_not_widths() {
    assert_eq!(structure("a = 12'h1f_a + 4'b10;"), "a = 12'h# + 4'b#;");
    assert_ne!(structure("a = 12'h1;"), structure("a = 13'h1;"));
    assert_eq!(structure("x <= y'h;"), "x <= y'h#;");
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
