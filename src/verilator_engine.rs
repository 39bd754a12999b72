//! The Verilator engine (`render --engine rtl --sim verilator`): the same exported Verilog the
//! tests prove bit-exact against the rust-hdl simulation, compiled once per block and parameter
//! set (cached under `target/verilator-engine/`), run on the whole input stream of a render, and
//! replayed through the same drivers (`pipeline::replay`).
//!
//! The input stream is scheduled before the run: the lit and Gouraud pipes load a triangle when
//! the address block's `ready` is high, which its cycle model (`golden::address_block`, through
//! `testbenches::address_block::stimulus`) predicts; the span tops take a line in the last clock
//! of the previous one (⌊m/2⌋ + 1 clocks for two pixels per clock, m + 1 or 3(m + 1) for the
//! Horner units), the quadric unit as `pipeline::span::quadric_timing` says. The replay then
//! requires the driver — deciding from the hardware's own `ready` — to feed exactly those rows,
//! so a wrong schedule is an error, never a different frame.

use std::hash::{Hash, Hasher};
use std::path::PathBuf;

use anyhow::{anyhow, bail, Context, Result};
use golden::address_block::AddressSetup;
use pipeline::gouraud::{pipe_row, TriangleJob};
use pipeline::lit::{lit_row, LitJob, ShadingRegs};
use pipeline::replay::Replay;
use pipeline::span::{quadric_timing, span_row, SpanJob, SpanKind};
use rtl::registry::Options;
use testbenches::tools::{self, Tool};
use testbenches::verilog::{self, Compiled, Simulator};

/// Which simulator runs the hardware.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Sim {
    /// rust-hdl's simulation, stepped by hand (no external tool).
    #[default]
    RustHdl,
    /// The exported Verilog under Verilator (compiled once per block, cached under target/).
    Verilator,
}

/// Compile `block` (built with `options`) for Verilator, or reuse the cached build.
fn compiled(block: &str, options: &Options) -> Result<Compiled> {
    if !tools::available(Tool::Verilator) {
        bail!("--sim verilator needs verilator (apt-get install verilator)");
    }
    let entry = testbenches::registry::find(block).map_err(|e| anyhow!(e))?;
    let text = entry.verilog(options).map_err(|e| anyhow!(e))?;
    let (ins, outs) = entry.ports();
    let module = entry.module_name();
    let mut h = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut h);
    verilog::testbench(&module, &ins, &outs).hash(&mut h);
    let cache = testbenches::harness::target_dir()
        .join("verilator-engine")
        .join(format!("{module}-{:016x}", h.finish()));
    let exe = cache.join("obj_dir").join("tb");
    if !exe.exists() {
        let c = verilog::compile(
            Simulator::Verilator,
            &text,
            &module,
            &ins,
            &outs,
            &format!("verilator-engine-{block}"),
        )
        .map_err(|e| anyhow!("Verilator build of {block}: {e}"))?;
        std::fs::create_dir_all(cache.parent().expect("has a parent"))?;
        // Another render may have cached it meanwhile: either copy serves.
        if std::fs::rename(&c.dir, &cache).is_err() && !exe.exists() {
            bail!("cannot cache the Verilator build in {}", cache.display());
        }
    }
    // Each run gets its own directory (stimulus and outputs), linking the cached executable.
    let run = tools::unique_dir(&format!("verilator-run-{block}")).map_err(|e| anyhow!(e))?;
    std::fs::create_dir_all(run.join("obj_dir"))?;
    std::os::unix::fs::symlink(&exe, run.join("obj_dir").join("tb"))
        .with_context(|| format!("linking {} into {}", exe.display(), run.display()))?;
    Ok(Compiled {
        simulator: Simulator::Verilator,
        dir: run,
        compile_time: std::time::Duration::ZERO,
    })
}

/// Run `rows` through `block` under Verilator: the recorded run.
fn record(block: &str, options: &Options, rows: Vec<Vec<u64>>) -> Result<Replay> {
    let c = compiled(block, options)?;
    let run = c
        .run(&rows)
        .map_err(|e| anyhow!("Verilator run of {block}: {e}"))?;
    let outputs = run
        .rows
        .iter()
        .enumerate()
        .map(|(clock, r)| {
            r.iter()
                .map(|w| {
                    u64::from_str_radix(w, 16).map_err(|_| {
                        anyhow!("Verilator run of {block}: clock {clock} shows {w:?}, not a number")
                    })
                })
                .collect::<Result<Vec<u64>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    let _ = std::fs::remove_dir_all(&run.dir);
    Replay::new(rows, outputs).map_err(|e| anyhow!(e))
}

/// Load clocks of triangles into the address block (its cycle model), and the clocks it takes
/// to show the last `done`.
fn address_schedule(setups: &[AddressSetup]) -> (Vec<usize>, usize) {
    let st = testbenches::address_block::stimulus(setups);
    (st.loads, st.rows.len())
}

/// The lit pipeline built with `options` on `jobs`, under Verilator.
pub fn lit_replay(options: &Options, jobs: &[LitJob], regs: &ShadingRegs) -> Result<Replay> {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let (loads, n) = address_schedule(&setups);
    let n = n + rtl::pixel_pipeline::EVENT_TO_FRAGMENT + 2;
    let mut rows = vec![lit_row(None, regs); n];
    for (k, &c) in loads.iter().enumerate() {
        rows[c] = lit_row(Some(&jobs[k]), regs);
    }
    record("pixel-pipeline", options, rows)
}

/// The Gouraud raster pipe on `jobs`, under Verilator.
pub fn gouraud_replay(jobs: &[TriangleJob]) -> Result<Replay> {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let (loads, n) = address_schedule(&setups);
    let mut rows = vec![pipe_row(None); n + 4];
    for (k, &c) in loads.iter().enumerate() {
        rows[c] = pipe_row(Some(&jobs[k]));
    }
    record("gouraud-raster", &Options::new(), rows)
}

/// The subdivision raster pipe on `jobs`, under Verilator (loads where the four-triangle
/// block's cycle model is ready, as the rust-hdl run loads them).
pub fn subdivision_replay(jobs: &[pipeline::subdivision::SubJob]) -> Result<Replay> {
    use pipeline::subdivision::pipe_row;
    let setups: Vec<_> = jobs.iter().map(|j| j.addr).collect();
    let rows = golden::four_triangle::schedule(&setups, 4)
        .into_iter()
        .map(|(_, load)| pipe_row(load.map(|k| &jobs[k])))
        .collect();
    record("subdivision-raster", &Options::new(), rows)
}

/// The span top for `kind` on `spans`, under Verilator.
pub fn span_replay(kind: SpanKind, spans: &[SpanJob], regs: &ShadingRegs) -> Result<Replay> {
    let takes: Vec<u64> = match kind {
        SpanKind::Quadric => quadric_timing(spans).into_iter().map(|(t, _)| t).collect(),
        _ => spans
            .iter()
            .scan(0u64, |at, s| {
                let t = *at;
                *at += s.clocks();
                Some(t)
            })
            .collect(),
    };
    let (block, o) = match kind {
        SpanKind::Angular => ("angular-pipeline", Options::new()),
        SpanKind::Fast(set) => ("fast-pipeline", Options::new().with("inv-sqrt", set)),
        SpanKind::Cubic { pipelined } => (
            "cubic-pipeline",
            Options::new().with("horner", if pipelined { "pipelined" } else { "serial" }),
        ),
        SpanKind::Quadric => ("quadric-unit", Options::new()),
    };
    // Past the last line's last fragment: its take (quadric: its hand-over), its clocks, the
    // block's latency and a margin.
    let latency = testbenches::registry::find(block).map_or(64, |b| b.latency()) as u64;
    let last_start = match kind {
        SpanKind::Quadric => quadric_timing(spans).last().map_or(0, |&(_, h)| h),
        _ => takes.last().copied().unwrap_or(0),
    };
    let end = last_start + spans.last().map_or(0, |s| s.clocks()) + latency + 12;
    let n = end as usize;
    let mut rows = vec![span_row(kind, None, regs); n];
    for (s, &t) in spans.iter().zip(&takes) {
        rows[t as usize] = span_row(kind, Some(s), regs);
    }
    record(block, &o, rows)
}

/// The address block walking `setups` under Verilator: its outputs per clock, through the same
/// reactive loop as `testbenches::address_block::run_reactive` (a load whenever `ready` is high),
/// checked against the scheduled rows by the replay.
pub fn address_outputs(
    setups: &[AddressSetup],
) -> Result<Vec<golden::address_block::AddressOutputs>> {
    use testbenches::address_block::{row_outputs, stimulus};
    let st = stimulus(setups);
    let mut replay = record("address-block", &Options::new(), st.rows.clone())?;
    let mut out = Vec::with_capacity(st.rows.len());
    let mut row = vec![0u64; 9];
    let (mut next, mut dones) = (0, 0);
    while dones < setups.len() {
        let load = (replay.ready() && next < setups.len()).then(|| &setups[next]);
        next += load.is_some() as usize;
        replay
            .step(
                &testbenches::address_block::address_row(load, false),
                &mut row,
            )
            .map_err(|e| anyhow!(e))?;
        let o = row_outputs(&row);
        dones += o.done as usize;
        out.push(o);
    }
    Ok(out)
}

/// The four-triangle block walking `setups` under Verilator: its outputs per clock, through the
/// same reactive loop as `testbenches::four_triangle::run_reactive`.
pub fn four_triangle_outputs(
    setups: &[golden::four_triangle::FourTriangleSetup],
) -> Result<Vec<golden::four_triangle::FourOutputs>> {
    use testbenches::four_triangle::{row_outputs, stimulus, OUTPUTS};
    let (rows, _) = stimulus(setups);
    let mut replay = record("four-triangle", &Options::new(), rows.clone())?;
    let mut out = Vec::with_capacity(rows.len());
    let mut row = vec![0u64; OUTPUTS];
    let (mut next, mut dones) = (0, [0usize; 4]);
    while dones.iter().any(|&d| d < setups.len()) {
        let load = (replay.ready() && next < setups.len()).then(|| &setups[next]);
        next += load.is_some() as usize;
        replay
            .step(&testbenches::four_triangle::four_row(load, false), &mut row)
            .map_err(|e| anyhow!(e))?;
        let o = row_outputs(&row);
        for (d, l) in dones.iter_mut().zip(&o.lanes) {
            *d += l.done as usize;
        }
        out.push(o);
    }
    Ok(out)
}

/// Where the engine caches its builds.
pub fn cache_dir() -> PathBuf {
    testbenches::harness::target_dir().join("verilator-engine")
}
