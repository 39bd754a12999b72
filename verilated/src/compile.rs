//! Building a [`Design`] into `lib.so`, and the cache that keeps the builds.
//!
//! A cache entry is a directory `target/verilated/<module>-<hash>/` holding `lib.so` and
//! `lib.sum` (its size and FNV-1a hash). `<hash>` covers the design's key, the Verilator and C++
//! compiler versions, the flags and the wrapper's ABI version. Built in a temporary directory
//! beside it and renamed into place, so an entry is whole or absent; a load checks `lib.sum`, the
//! ABI version and the port list, and a broken entry is removed and built again (with a notice on
//! stderr). Builds of one key are serialised by an advisory lock on `<entry>.lock`. A new build
//! of a registered block removes the entries of the same block and parameters made from older
//! RTL sources.

use std::fmt::Write as _;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use rtl::core::sim::Port;

use crate::model::Library;
use crate::Design;

use crate::ABI_VERSION;

/// C++ optimisation of the model's evaluation code and of its construction code (Verilator's own
/// makefile uses `-Os` and none). `-O1` is a compromise for the cold build, which a test run
/// from a clean clone pays (its speed in process: docs/measurements/sim-speed.md); other levels
/// were not measured.
const OPT_FAST: &str = "-O1";
const OPT_SLOW: &str = "-O0";
/// Verilator's `--output-split-cfuncs` (see `compile_into`); part of a model's cache key.
const SPLIT_CFUNCS: &str = "250";

/// FNV-1a, 64 bits.
pub(crate) fn fnv(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// The installed Verilator and C++ compiler.
#[derive(Clone, Debug)]
pub struct Toolchain {
    /// `verilator --getenv VERILATOR_ROOT`: its `include/` has the runtime sources.
    pub root: PathBuf,
    /// The C++ compiler (`$CXX`, else `g++`).
    pub cxx: String,
    /// First lines of `verilator --version` and `<cxx> --version`.
    pub versions: String,
}

fn first_line(cmd: &str, args: &[&str]) -> Result<String, String> {
    let out = Command::new(cmd)
        .args(args)
        .output()
        .map_err(|e| format!("cannot run {cmd}: {e}"))?;
    if !out.status.success() {
        return Err(format!("{cmd} {} failed ({})", args.join(" "), out.status));
    }
    Ok(String::from_utf8_lossy(&out.stdout)
        .lines()
        .next()
        .unwrap_or("")
        .trim()
        .to_string())
}

/// Verilator and a C++ compiler, probed once per process; the error says what is missing and
/// how to install it.
pub fn toolchain() -> Result<&'static Toolchain, String> {
    static TOOLS: OnceLock<Result<Toolchain, String>> = OnceLock::new();
    TOOLS
        .get_or_init(|| {
            let v = first_line("verilator", &["--version"])
                .map_err(|_| "verilator is not installed (apt-get install verilator)".to_string())?;
            let root = first_line("verilator", &["--getenv", "VERILATOR_ROOT"])?;
            let cxx = std::env::var("CXX").unwrap_or_else(|_| "g++".into());
            let c = first_line(&cxx, &["--version"]).map_err(|_| {
                format!("{cxx}, the C++ compiler Verilator's models need, is not installed (apt-get install g++)")
            })?;
            let root = PathBuf::from(root);
            if !root.join("include/verilated.cpp").exists() {
                return Err(format!(
                    "Verilator's runtime sources are not in {}/include",
                    root.display()
                ));
            }
            Ok(Toolchain {
                root,
                cxx,
                versions: format!("{v} / {c}"),
            })
        })
        .as_ref()
        .map_err(Clone::clone)
}

/// `target/verilated/` (`$CARGO_TARGET_DIR/verilated/` when that is set).
pub fn cache_dir() -> PathBuf {
    let target = match std::env::var_os("CARGO_TARGET_DIR") {
        Some(d) => PathBuf::from(d),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .map(|p| p.join("target"))
            .unwrap_or_else(|| "target".into()),
    };
    target.join("verilated")
}

fn safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The port list a library states (`sc_ports()`), checked on every load.
pub(crate) fn port_list(inputs: &[Port], outputs: &[Port]) -> String {
    let side = |ps: &[Port]| {
        ps.iter()
            .map(|p| format!("{}/{}", p.name, p.width))
            .collect::<Vec<_>>()
            .join(",")
    };
    format!("v{ABI_VERSION};in:{};out:{}", side(inputs), side(outputs))
}

fn c_type(width: usize) -> &'static str {
    match width {
        0..=8 => "CData",
        9..=16 => "SData",
        17..=32 => "IData",
        _ => "QData",
    }
}

fn mask(width: usize) -> String {
    if width >= 64 {
        "~0ULL".into()
    } else {
        format!("0x{:x}ULL", (1u64 << width) - 1)
    }
}

/// The C++ of the C ABI around the Verilated model `Vdut` of a top with these ports:
/// `sc_abi`, `sc_ports`, `sc_new`, `sc_delete`, `sc_step` (one clock with the harness's
/// timing), `sc_peek` (one output between clocks), and `sc_bench` (the same clocks driven from
/// memory by a C++ loop: the ceiling the in-process stepping is measured against).
pub fn wrapper(inputs: &[Port], outputs: &[Port]) -> Result<String, String> {
    for p in inputs.iter().chain(outputs) {
        if p.width == 0 || p.width > 64 {
            return Err(format!(
                "port {} is {} bits wide: the in-process model carries 1 to 64",
                p.name, p.width
            ));
        }
        if p.name == "clock" {
            return Err("the clock is not a data port".into());
        }
    }
    let mut set_inputs = String::new();
    for (k, p) in inputs.iter().enumerate() {
        let _ = writeln!(
            set_inputs,
            "    t.{n} = ({ty})(in[{k}] & {m});",
            n = p.name,
            ty = c_type(p.width),
            m = mask(p.width)
        );
    }
    let mut get_outputs = String::new();
    let mut peek_cases = String::new();
    let mut fold_outputs = String::new();
    for (k, p) in outputs.iter().enumerate() {
        let _ = writeln!(get_outputs, "    out[{k}] = (uint64_t)t.{};", p.name);
        let _ = writeln!(peek_cases, "    case {k}: return (uint64_t)t.{};", p.name);
        let _ = writeln!(
            fold_outputs,
            "        sum = sum * 0x100000001b3ULL ^ (uint64_t)t.{};",
            p.name
        );
    }
    let n_in = inputs.len();
    let ports = port_list(inputs, outputs);
    Ok(format!(
        r#"// Generated by shadecore's `verilated` crate: the C ABI of one Verilated top. Do not edit.
#include "Vdut.h"
#include "verilated.h"
#include <cstdint>

#define SC_API extern "C" __attribute__((visibility("default")))

namespace {{
struct Model {{
    VerilatedContext ctx;
    Vdut top;
    Model() : top(&ctx, "dut") {{}}
}};

inline void apply(Vdut& t, const uint64_t* in) {{
{set_inputs}}}
}}  // namespace

SC_API uint32_t sc_abi() {{ return {ABI_VERSION}; }}

SC_API const char* sc_ports() {{ return "{ports}"; }}

SC_API void* sc_new() {{
    Model* m = new Model;
    m->top.clock = 0;
    m->top.eval();
    return m;
}}

SC_API void sc_delete(void* p) {{
    Model* m = static_cast<Model*>(p);
    m->top.final();
    delete m;
}}

// One clock: the inputs with the clock low, settle, sample, the rising edge, settle.
SC_API void sc_step(void* p, const uint64_t* in, uint64_t* out) {{
    Vdut& t = static_cast<Model*>(p)->top;
    apply(t, in);
    t.clock = 0;
    t.eval();
{get_outputs}    t.clock = 1;
    t.eval();
}}

SC_API uint64_t sc_peek(void* p, uint32_t k) {{
    Vdut& t = static_cast<Model*>(p)->top;
    switch (k) {{
{peek_cases}    default: return 0;
    }}
}}

// `n` rows of {n_in} words from memory through the same clocks; returns a hash of every output
// of every clock (so the compiler cannot drop the sampling).
SC_API uint64_t sc_bench(void* p, const uint64_t* rows, uint64_t n) {{
    Vdut& t = static_cast<Model*>(p)->top;
    uint64_t sum = 0xcbf29ce484222325ULL;
    for (uint64_t c = 0; c < n; ++c) {{
        apply(t, rows + c * {n_in});
        t.clock = 0;
        t.eval();
{fold_outputs}        t.clock = 1;
        t.eval();
    }}
    return sum;
}}
"#
    ))
}

/// Key of `design` with the toolchain: the entry's directory name.
fn entry_name(design: &Design, tools: &Toolchain) -> String {
    let all = format!(
        "{}\n{}\n{}\n{OPT_FAST} {OPT_SLOW} split {SPLIT_CFUNCS}\nabi {ABI_VERSION}\n{}",
        design.key,
        tools.versions,
        design.module,
        port_list(&design.inputs, &design.outputs)
    );
    format!("{}-{:016x}", safe(&design.module), fnv(all.as_bytes()))
}

fn run(dir: &Path, program: &str, args: &[String], what: &str) -> Result<(), String> {
    let out = Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .map_err(|e| format!("cannot run {program}: {e}"))?;
    if out.status.success() {
        return Ok(());
    }
    let mut text = String::from_utf8_lossy(&out.stdout).to_string();
    text += &String::from_utf8_lossy(&out.stderr);
    let tail: Vec<&str> = text.lines().rev().take(20).collect();
    let tail: Vec<&str> = tail.into_iter().rev().collect();
    let _ = std::fs::write(dir.join(format!("{what}.log")), &text);
    Err(format!(
        "{what} failed ({}) in {}:\n{}",
        out.status,
        dir.display(),
        tail.join("\n")
    ))
}

static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

static QUIET: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Run `program` in `dir` once per job at the same time, a thread each: `flags` then the job's
/// arguments; `what` names the job in an error. The first error (in `jobs`' order) is returned
/// once every job has ended.
fn run_all(
    dir: &Path,
    program: &str,
    flags: &[String],
    jobs: &[(String, Vec<String>)],
) -> Result<(), String> {
    std::thread::scope(|s| {
        let workers: Vec<_> = jobs
            .iter()
            .map(|(what, rest)| {
                s.spawn(move || {
                    let mut args = flags.to_vec();
                    args.extend(rest.iter().cloned());
                    run(dir, program, &args, what)
                })
            })
            .collect();
        workers
            .into_iter()
            .map(|w| {
                w.join()
                    .unwrap_or_else(|_| Err("a compile thread panicked".into()))
            })
            .collect::<Result<Vec<()>, String>>()
    })?;
    Ok(())
}

/// Whether [`build`] says on stderr what it built and how long it took (it does by default; a
/// caller that shows its own progress turns it off).
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// A fresh temporary directory in `cache` (same file system as the entries, for the rename).
/// Temporary directories over an hour old (a build killed midway) are removed first.
fn temp_dir(cache: &Path, tag: &str) -> Result<PathBuf, String> {
    if let Ok(entries) = std::fs::read_dir(cache) {
        for e in entries.flatten() {
            let old = e
                .metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age.as_secs() > 3600);
            if old && e.file_name().to_string_lossy().starts_with(".tmp-") {
                let _ = std::fs::remove_dir_all(e.path());
            }
        }
    }
    let n = TMP_COUNTER.fetch_add(1, Ordering::SeqCst);
    let d = cache.join(format!(".tmp-{tag}-{}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).map_err(|e| format!("cannot create {}: {e}", d.display()))?;
    Ok(d)
}

fn cxx_flags(tools: &Toolchain) -> Vec<String> {
    let inc = tools.root.join("include");
    [
        "-std=gnu++17",
        "-fPIC",
        "-fvisibility=hidden",
        "-fvisibility-inlines-hidden",
        "-faligned-new",
        "-fcf-protection=none",
        "-w",
        "-DVM_COVERAGE=0",
        "-DVM_SC=0",
        "-DVM_TRACE=0",
        "-DVM_TRACE_FST=0",
        "-DVM_TRACE_VCD=0",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([
        format!("-I{}", inc.display()),
        format!("-I{}", inc.join("vltstd").display()),
    ])
    .collect()
}

/// Take the advisory lock of `path` (created if missing), waiting for whoever holds it.
fn lock(path: &Path) -> Result<File, String> {
    let f = File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)
        .map_err(|e| format!("cannot open the lock {}: {e}", path.display()))?;
    if f.try_lock().is_err() {
        eprintln!(
            "verilated: waiting for another build of {} to finish",
            path.display()
        );
        f.lock()
            .map_err(|e| format!("cannot lock {}: {e}", path.display()))?;
    }
    Ok(f)
}

/// The Verilator runtime (`verilated.cpp`, `verilated_threads.cpp`) compiled once per toolchain
/// into `target/verilated/runtime-<hash>/` and linked into every model, beside a precompiled
/// `verilated.h` for each optimisation level the models use.
struct Runtime {
    /// The runtime's objects.
    objects: Vec<PathBuf>,
    dir: PathBuf,
}

/// The header every generated file includes first, precompiled.
const PCH: &str = "sc_pch.h";

impl Runtime {
    /// `-include` of the precompiled `verilated.h` built at `opt`. Every generated file and the
    /// wrapper include `verilated.h`, whose parse is most of a small unit's compile time (on
    /// `pixel-stream`: 5.1 s of compiler time for its two units without it, 3.3 s with it). A
    /// header GCC cannot use is read as text, with the same result.
    fn include_pch(&self, opt: &str) -> [String; 2] {
        [
            "-include".into(),
            self.dir
                .join(format!("pch{opt}"))
                .join(PCH)
                .display()
                .to_string(),
        ]
    }
}

fn runtime(cache: &Path, tools: &Toolchain) -> Result<Runtime, String> {
    const UNITS: [&str; 2] = ["verilated", "verilated_threads"];
    let name = format!(
        "runtime-{:016x}",
        fnv(format!(
            "{}\n{OPT_FAST}\n{OPT_SLOW}\npch {PCH}\nabi {ABI_VERSION}",
            tools.versions
        )
        .as_bytes())
    );
    let dir = cache.join(&name);
    let objects: Vec<PathBuf> = UNITS.iter().map(|u| dir.join(format!("{u}.o"))).collect();
    let headers: Vec<PathBuf> = [OPT_FAST, OPT_SLOW]
        .iter()
        .map(|o| dir.join(format!("pch{o}")).join(format!("{PCH}.gch")))
        .collect();
    let whole = || objects.iter().chain(&headers).all(|o| o.exists());
    let done = || Runtime {
        objects: objects.clone(),
        dir: dir.clone(),
    };
    if whole() {
        return Ok(done());
    }
    let _guard = lock(&cache.join(format!("{name}.lock")))?;
    if whole() {
        return Ok(done());
    }
    let tmp = temp_dir(cache, "runtime")?;
    let flags = cxx_flags(tools);
    // (what, compiler arguments after the flags)
    let mut jobs: Vec<(String, Vec<String>)> = UNITS
        .iter()
        .map(|u| {
            let src = tools.root.join("include").join(format!("{u}.cpp"));
            (
                format!("compiling {u}.cpp"),
                vec![
                    OPT_FAST.to_string(),
                    "-c".into(),
                    src.display().to_string(),
                    "-o".into(),
                    format!("{u}.o"),
                ],
            )
        })
        .collect();
    for opt in [OPT_FAST, OPT_SLOW] {
        let sub = tmp.join(format!("pch{opt}"));
        std::fs::create_dir_all(&sub)
            .map_err(|e| format!("cannot create {}: {e}", sub.display()))?;
        std::fs::write(sub.join(PCH), "#include \"verilated.h\"\n")
            .map_err(|e| format!("cannot write {}: {e}", sub.join(PCH).display()))?;
        jobs.push((
            format!("precompiling verilated.h at {opt}"),
            vec![
                opt.to_string(),
                "-x".into(),
                "c++-header".into(),
                format!("pch{opt}/{PCH}"),
                "-o".into(),
                format!("pch{opt}/{PCH}.gch"),
            ],
        ));
    }
    run_all(&tmp, &tools.cxx, &flags, &jobs)?;
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::rename(&tmp, &dir)
        .map_err(|e| format!("cannot move the runtime into {}: {e}", dir.display()))?;
    Ok(done())
}

/// Compile `design` into `<tmp>/lib.so`.
fn compile_into(
    tmp: &Path,
    design: &Design,
    tools: &Toolchain,
    cache: &Path,
) -> Result<(), String> {
    let verilog = (design.verilog)()?;
    let write = |name: &str, text: &str| {
        std::fs::write(tmp.join(name), text)
            .map_err(|e| format!("cannot write {}: {e}", tmp.join(name).display()))
    };
    write("dut.v", &verilog)?;
    write("key.txt", &design.key)?;
    write("wrapper.cpp", &wrapper(&design.inputs, &design.outputs)?)?;
    let args: Vec<String> = [
        "--cc",
        "dut.v",
        "--top-module",
        &design.module,
        "--prefix",
        "Vdut",
        "--Mdir",
        "obj",
        "-O3",
        // Evaluation code in functions of at most about 250 statements: the compiler's time
        // grows faster than linearly with a function's size. On `pixel-stream` (2026-11-28,
        // this crate's bench `sim_speed`, two runs each): `g++ -O1` of the evaluation unit
        // 3.3 s unsplit, 1.1 s split; the model's build 7.3 s -> 5.6 s; clocks/s in process
        // about a fifth lower (330-411x rust-hdl split, 455-515x unsplit). A test run builds
        // some sixty models and steps most for well under a second, so the build wins.
        "--output-split-cfuncs",
        SPLIT_CFUNCS,
        "-Wno-fatal",
        "-Wno-lint",
        "-Wno-style",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    run(tmp, "verilator", &args, "verilator")?;
    let runtime = runtime(cache, tools)?;
    let mut sources: Vec<PathBuf> = std::fs::read_dir(tmp.join("obj"))
        .map_err(|e| format!("cannot list {}: {e}", tmp.join("obj").display()))?
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "cpp"))
        .collect();
    sources.push(tmp.join("wrapper.cpp"));
    sources.sort();
    // Two translation units, as Verilator's own makefile builds `__ALL.cpp` without parallel
    // builds: each generated file re-parses `verilated.h` (about 1.2 s of a compiler's time),
    // so one unit per group costs less than half the compiler time of one per file. The
    // construction and symbol tables run once: no optimisation (as Verilator's makefile treats
    // its `__Slow` and `__Syms` files); the evaluation code and the wrapper at `OPT_FAST`.
    let slow = |p: &PathBuf| {
        p.file_name()
            .map(|f| f.to_string_lossy().to_string())
            .is_some_and(|f| f.contains("__Slow") || f.contains("__Syms"))
    };
    let mut units = Vec::new();
    for (name, opt, group) in [
        (
            "unit_fast.cpp",
            OPT_FAST,
            sources.iter().filter(|p| !slow(p)).collect::<Vec<_>>(),
        ),
        (
            "unit_slow.cpp",
            OPT_SLOW,
            sources.iter().filter(|p| slow(p)).collect::<Vec<_>>(),
        ),
    ] {
        if group.is_empty() {
            continue;
        }
        // Relative to the unit (`obj/…` and `wrapper.cpp`: names Verilator and this crate
        // chose), so that no character of the cache's path reaches the C++ source.
        let text: String = group
            .iter()
            .map(|p| {
                let rel = p.strip_prefix(tmp).unwrap_or(p);
                format!("#include \"{}\"\n", rel.display())
            })
            .collect();
        write(name, &text)?;
        units.push((tmp.join(name), opt));
    }
    let flags = cxx_flags(tools);
    let objects: Vec<PathBuf> = units.iter().map(|(s, _)| s.with_extension("o")).collect();
    let jobs: Vec<(String, Vec<String>)> = units
        .iter()
        .zip(&objects)
        .map(|((src, opt), obj)| {
            let file = src.file_name().map(|f| f.to_string_lossy().to_string());
            let mut args: Vec<String> = runtime.include_pch(opt).into();
            args.extend([
                opt.to_string(),
                format!("-I{}", tmp.join("obj").display()),
                "-c".into(),
                src.display().to_string(),
                "-o".into(),
                obj.display().to_string(),
            ]);
            (format!("compiling {}", file.unwrap_or_default()), args)
        })
        .collect();
    run_all(tmp, &tools.cxx, &flags, &jobs)?;
    let mut link: Vec<String> = vec![
        "-shared".into(),
        "-Wl,-Bsymbolic".into(),
        "-o".into(),
        "lib.so".into(),
    ];
    link.extend(objects.iter().map(|o| o.display().to_string()));
    link.extend(runtime.objects.iter().map(|o| o.display().to_string()));
    link.extend(["-pthread".into(), "-latomic".into()]);
    run(tmp, &tools.cxx, &link, "linking lib.so")?;
    let lib = std::fs::read(tmp.join("lib.so")).map_err(|e| format!("cannot read lib.so: {e}"))?;
    write("lib.sum", &format!("{} {:016x}\n", lib.len(), fnv(&lib)))?;
    // The objects and generated C++ are megabytes; the entry keeps the library, its sum and the
    // Verilog it was made from.
    let _ = std::fs::remove_dir_all(tmp.join("obj"));
    let _ = std::fs::remove_file(tmp.join("wrapper.o"));
    Ok(())
}

/// Why the entry in `dir` cannot serve (`None`: it is whole).
fn broken(dir: &Path) -> Option<String> {
    let sum = match std::fs::read_to_string(dir.join("lib.sum")) {
        Ok(s) => s,
        Err(e) => return Some(format!("no lib.sum ({e})")),
    };
    let lib = match std::fs::read(dir.join("lib.so")) {
        Ok(b) => b,
        Err(e) => return Some(format!("no lib.so ({e})")),
    };
    let want = format!("{} {:016x}", lib.len(), fnv(&lib));
    (sum.trim() != want).then(|| {
        format!(
            "lib.so does not match lib.sum (found {want}, recorded {})",
            sum.trim()
        )
    })
}

/// Remove the entries `design` supersedes: the same block and parameters built from other RTL
/// sources (a key `block:NAME|PARAMS|FINGERPRINT` equal but for its last field), so that editing
/// the RTL does not grow the cache by a build of every block each time. A process still using
/// a removed library keeps its mapping; one about to load it builds it again.
fn evict_superseded(cache: &Path, design: &Design, keep: &str) {
    let Some((stem, _)) = design.key.rsplit_once('|') else {
        return;
    };
    if !design.key.starts_with("block:") {
        return;
    }
    let prefix = format!("{}-", safe(&design.module));
    let Ok(entries) = std::fs::read_dir(cache) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if name == keep || !name.starts_with(&prefix) || name.ends_with(".lock") {
            continue;
        }
        let Ok(key) = std::fs::read_to_string(e.path().join("key.txt")) else {
            continue;
        };
        if key.rsplit_once('|').is_some_and(|(s, _)| s == stem) && key != design.key {
            let _ = std::fs::remove_dir_all(e.path());
            let _ = std::fs::remove_file(cache.join(format!("{name}.lock")));
        }
    }
}

/// Libraries already loaded by this process, by entry name.
fn loaded() -> &'static Mutex<std::collections::HashMap<String, Arc<Library>>> {
    static LOADED: OnceLock<Mutex<std::collections::HashMap<String, Arc<Library>>>> =
        OnceLock::new();
    LOADED.get_or_init(Default::default)
}

/// The library of `design`: loaded from the cache, or built first (Verilator, then the C++
/// compiler; a large top takes tens of seconds). A broken entry is rebuilt.
pub fn build(design: &Design) -> Result<Arc<Library>, String> {
    let tools = toolchain()?;
    let name = entry_name(design, tools);
    if let Some(l) = loaded().lock().expect("loaded").get(&name) {
        return Ok(l.clone());
    }
    let cache = cache_dir();
    std::fs::create_dir_all(&cache)
        .map_err(|e| format!("cannot create {}: {e}", cache.display()))?;
    let dir = cache.join(&name);
    let expected = port_list(&design.inputs, &design.outputs);
    let _guard = lock(&cache.join(format!("{name}.lock")))?;
    // Another thread of this process may have loaded it while this one waited.
    if let Some(l) = loaded().lock().expect("loaded").get(&name) {
        return Ok(l.clone());
    }
    for attempt in 0..2 {
        if dir.exists() {
            let why = match broken(&dir) {
                None => match Library::open(&dir.join("lib.so"), &expected) {
                    Ok(l) => {
                        let l = Arc::new(l);
                        loaded()
                            .lock()
                            .expect("loaded")
                            .insert(name.clone(), l.clone());
                        return Ok(l);
                    }
                    Err(e) => e,
                },
                Some(why) => why,
            };
            if attempt > 0 {
                return Err(format!(
                    "the Verilator build of {} in {} does not load: {why}",
                    design.name,
                    dir.display()
                ));
            }
            eprintln!(
                "verilated: the cache entry {} is broken ({why}); rebuilding it",
                dir.display()
            );
            std::fs::remove_dir_all(&dir)
                .map_err(|e| format!("cannot remove {}: {e}", dir.display()))?;
        }
        let tmp = temp_dir(&cache, &safe(&design.module))?;
        let t = std::time::Instant::now();
        if let Err(e) = compile_into(&tmp, design, tools, &cache) {
            return Err(format!("Verilator build of {}: {e}", design.name));
        }
        std::fs::rename(&tmp, &dir)
            .map_err(|e| format!("cannot move the build into {}: {e}", dir.display()))?;
        evict_superseded(&cache, design, &name);
        if !QUIET.load(Ordering::Relaxed) {
            eprintln!(
                "verilated: built {} in {:.1} s",
                design.name,
                t.elapsed().as_secs_f64()
            );
        }
    }
    unreachable!("the second attempt returns")
}
