//! External EDA tools (yosys, iverilog/vvp, verilator, nextpnr-ice40): detection, the
//! skip-or-fail policy every tool test uses, unique work directories, and running a command
//! with a readable error.
//!
//! Policy ([`require`]): a test that needs a missing tool prints a `SKIPPED` notice and returns
//! early — unless the environment variable `CI` is set, in which case it fails.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::OnceLock;

/// A tool some test or command needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Tool {
    Yosys,
    Iverilog,
    Vvp,
    Verilator,
    NextpnrIce40,
}

impl Tool {
    /// Executable name.
    pub fn program(self) -> &'static str {
        match self {
            Tool::Yosys => "yosys",
            Tool::Iverilog => "iverilog",
            Tool::Vvp => "vvp",
            Tool::Verilator => "verilator",
            Tool::NextpnrIce40 => "nextpnr-ice40",
        }
    }

    fn probe_args(self) -> &'static [&'static str] {
        match self {
            Tool::Yosys => &["-V"],
            Tool::Iverilog => &["-V"],
            Tool::Vvp => &["-V"],
            Tool::Verilator => &["--version"],
            Tool::NextpnrIce40 => &["--version"],
        }
    }

    fn index(self) -> usize {
        self as usize
    }
}

static AVAILABLE: [OnceLock<bool>; 5] = [
    OnceLock::new(),
    OnceLock::new(),
    OnceLock::new(),
    OnceLock::new(),
    OnceLock::new(),
];

/// Whether `tool` runs here (probed once per process).
pub fn available(tool: Tool) -> bool {
    *AVAILABLE[tool.index()].get_or_init(|| {
        Command::new(tool.program())
            .args(tool.probe_args())
            .output()
            .map(|o| o.status.success() || !o.stdout.is_empty())
            .unwrap_or(false)
    })
}

/// Whether `CI` is set (then missing tools are failures).
pub fn in_ci() -> bool {
    std::env::var_os("CI").is_some_and(|v| !v.is_empty())
}

/// The skip-or-fail policy for a test named `what` that needs `tools`: returns `true` when all
/// are installed; otherwise prints a notice and returns `false` (skip), or panics when `CI` is
/// set.
pub fn require(tools: &[Tool], what: &str) -> bool {
    let missing: Vec<&str> = tools
        .iter()
        .filter(|t| !available(**t))
        .map(|t| t.program())
        .collect();
    if missing.is_empty() {
        return true;
    }
    let list = missing.join(", ");
    if in_ci() {
        panic!("{what}: required tool(s) not installed: {list} (CI is set, so this is a failure)");
    }
    // Written to the process's stderr directly: libtest captures `eprintln!` of passing tests,
    // and a skip must stay visible.
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED {what}: tool(s) not installed: {list} (set CI=1 to make this a failure)"
    );
    false
}

/// A visible skip of `what` because of `why`: written to the process's stderr directly (libtest
/// hides the output of passing tests, `println!` and `eprintln!` alike); a panic when `CI` is
/// set, so a skipped check never looks like a pass there.
pub fn skip(what: &str, why: &str) {
    if in_ci() {
        panic!("{what}: {why} (CI is set, so this is a failure)");
    }
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED {what}: {why} (set CI=1 to make this a failure)"
    );
}

/// `(date, machine)` for a measured figure's line: the UTC minute (`date -u`) and the CPU's
/// model name with the core count, e.g. `("2026-11-28 18:56 UTC", "AMD EPYC, 2 cores")`.
pub fn stamp() -> (String, String) {
    let date = Command::new("date")
        .args(["-u", "+%Y-%m-%d %H:%M UTC"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    (date, format!("{cpu}, {cores} cores"))
}

static DIR_COUNTER: AtomicU64 = AtomicU64::new(0);

/// A fresh directory `target/tool-runs/<tag>-<pid>-<n>` (unique per process and call, so
/// parallel tests never share files).
pub fn unique_dir(tag: &str) -> Result<PathBuf, String> {
    let n = DIR_COUNTER.fetch_add(1, Ordering::SeqCst);
    let safe = crate::file_safe(tag);
    let dir = crate::target_dir()
        .join("tool-runs")
        .join(format!("{safe}-{}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    Ok(dir)
}

fn tail(s: &[u8], lines: usize) -> String {
    let text = String::from_utf8_lossy(s);
    let v: Vec<&str> = text.lines().collect();
    v[v.len().saturating_sub(lines)..].join("\n")
}

/// Run `program args…` in `dir`; an error (missing program, non-zero exit) becomes a message
/// with the command and the last lines of its output. Full output goes to `dir/<log>.log`.
pub fn run_in(dir: &Path, program: &str, args: &[&str], log: &str) -> Result<Output, String> {
    let out = Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .map_err(|e| format!("cannot run {program}: {e}"))?;
    let mut text = out.stdout.clone();
    text.extend_from_slice(&out.stderr);
    let _ = std::fs::write(dir.join(format!("{log}.log")), &text);
    if !out.status.success() {
        return Err(format!(
            "{program} {} failed ({}) in {}:\n{}\n{}",
            args.join(" "),
            out.status,
            dir.display(),
            tail(&out.stdout, 15),
            tail(&out.stderr, 15)
        ));
    }
    Ok(out)
}

/// A Python with cocotb, its runner (`cocotb_tools`) and cocotbext-axi: `SHADECORE_PYTHON`,
/// else `.venv/bin/python` at the workspace root (`.ci/run` installs them there), else
/// `python3` on the PATH. `None` when none imports them.
pub fn cocotb_python() -> Option<PathBuf> {
    static FOUND: OnceLock<Option<PathBuf>> = OnceLock::new();
    FOUND
        .get_or_init(|| {
            let venv = crate::target_dir()
                .parent()
                .map(|root| root.join(".venv/bin/python"));
            std::env::var_os("SHADECORE_PYTHON")
                .map(PathBuf::from)
                .into_iter()
                .chain(venv)
                .chain([PathBuf::from("python3")])
                .find(|p| {
                    Command::new(p)
                        .args(["-c", "import cocotb, cocotb_tools.runner, cocotbext.axi"])
                        .output()
                        .is_ok_and(|o| o.status.success())
                })
        })
        .clone()
}

/// `f` on every item, two at a time (the machines this project targets have two cores, and
/// each job here is one tool process or one simulation): two threads take the items in order
/// from one queue. A panic in `f` ends its thread and reaches the caller when both are done;
/// the other thread goes on with the queue.
pub fn two_at_a_time<T: Send>(items: impl IntoIterator<Item = T>, f: impl Fn(T) + Sync) {
    let queue = std::sync::Mutex::new(items.into_iter().collect::<Vec<T>>().into_iter());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| loop {
                // The guard is dropped before `f` runs, so a panicking job poisons nothing.
                let next = queue.lock().unwrap_or_else(|e| e.into_inner()).next();
                let Some(item) = next else { break };
                f(item);
            });
        }
    });
}

#[cfg(test)]
mod tests {
    use super::two_at_a_time;
    use std::sync::atomic::{AtomicU64, Ordering};

    #[test]
    fn two_at_a_time_runs_every_item_once_and_passes_a_panic_on() {
        let sum = AtomicU64::new(0);
        two_at_a_time(1..=100u64, |k| {
            sum.fetch_add(1 << (k % 60), Ordering::SeqCst);
        });
        let want: u64 = (1..=100u64).map(|k| 1 << (k % 60)).sum();
        assert_eq!(sum.load(Ordering::SeqCst), want);
        let ran = AtomicU64::new(0);
        let r = std::panic::catch_unwind(|| {
            two_at_a_time(0..10, |k| {
                ran.fetch_add(1, Ordering::SeqCst);
                assert!(k != 3, "job 3 fails");
            })
        });
        assert!(r.is_err(), "the panic reaches the caller");
        assert_eq!(ran.load(Ordering::SeqCst), 10, "the other jobs still ran");
    }
}
