//! Simulated clocks per second of `pixel-stream` (normalizer-fit) on the default scene (sphere
//! rez 50, 400×400, light 90°, the triangles in the render's balanced order, every `tready`
//! high), measured in one run on three simulators of the same hardware:
//!
//! 1. **in process**: the exported Verilog verilated into a shared library (`verilated`),
//!    stepped a clock per call by the same driver the render uses (`pipeline::axis::drive`);
//! 2. **rust-hdl**: the same driver over rust-hdl's simulation;
//! 3. **ceiling**: the same compiled model driven from memory by a C++ loop (no call per
//!    clock), on the input rows the in-process run recorded.
//!
//! The three runs must agree: the in-process and rust-hdl runs deliver the same fragments in
//! the same clocks, and the ceiling loop's hash of every output of every clock equals the
//! in-process run's. Run with `cargo bench --bench sim_speed`; it prints the table and writes
//! it, with the date and the machine, to `docs/measurements/sim-speed.md`.
//! `SHADECORE_BENCH_RUST_HDL_TRIANGLES=N` runs rust-hdl on the first N triangles only (default
//! all: about half a minute).

mod common;
use std::time::Instant;

use flow::engine::{model, Sim};
use golden::methods::Method;
use pipeline::lit::{lit_clock_budget, method_options, LitJob, ShadingRegs};
use rtl::core::registry::BlockParams;
use rtl::core::sim::{Model, Port};
use rtl::pipelines::pixel_pipeline::PipelineParams;
use rtl::stream::pixel_stream::PixelStream;

/// A model that records every input row it is stepped with, and hashes every output.
struct Recorder {
    inner: Box<dyn Model>,
    rows: Vec<u64>,
    hash: u64,
}

impl Model for Recorder {
    fn inputs(&self) -> &[Port] {
        self.inner.inputs()
    }
    fn outputs(&self) -> &[Port] {
        self.inner.outputs()
    }
    fn step(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), String> {
        self.rows.extend_from_slice(inputs);
        self.inner.step(inputs, outputs)?;
        for &o in outputs.iter() {
            self.hash = self.hash.wrapping_mul(0x100000001b3) ^ o;
        }
        Ok(())
    }
    fn peek(&self, k: usize) -> u64 {
        self.inner.peek(k)
    }
    fn cycle(&self) -> u64 {
        self.inner.cycle()
    }
    fn start_vcd(&mut self, w: Box<dyn std::io::Write>) -> Result<(), String> {
        self.inner.start_vcd(w)
    }
    fn stop_vcd(&mut self) -> Result<(), String> {
        Ok(())
    }
    fn simulator(&self) -> &'static str {
        self.inner.simulator()
    }
}

fn scene() -> (Vec<LitJob>, ShadingRegs) {
    let (tris, ctx) = common::default_scene();
    let jobs: Vec<LitJob> = tris
        .iter()
        .filter_map(|t| LitJob::new(t).unwrap())
        .collect();
    let order = pipeline::lit::balanced_order(&jobs);
    (
        order.iter().map(|&i| jobs[i]).collect(),
        ShadingRegs::of(&ctx).unwrap(),
    )
}

/// A fragment as the bench records it: (triangle, x, y, colour, clock).
type Fragment = (usize, u32, u32, [u8; 3], u64);

/// (clocks, fragments, seconds, recorder) of `jobs` through `pixel-stream` on `inner`.
fn drive(
    inner: Box<dyn Model>,
    jobs: &[LitJob],
    regs: &ShadingRegs,
) -> (u64, Vec<Fragment>, f64, Recorder) {
    let mut rec = Recorder {
        inner,
        rows: Vec::new(),
        hash: 0xcbf29ce484222325,
    };
    let words = pipeline::lit::scene_words(jobs, regs);
    let mut frags = Vec::new();
    let t = Instant::now();
    let st = pipeline::axis::drive::<PixelStream>(
        &mut rec,
        "pixel-stream",
        "triangles",
        &words,
        jobs.len() as u64,
        lit_clock_budget(jobs) + 64 * jobs.len() as u64,
        &mut |job, b, clock| frags.push((job, b.x, b.y, b.rgb, clock)),
        &mut |_| {},
    )
    .unwrap();
    (st.clocks, frags, t.elapsed().as_secs_f64(), rec)
}

fn main() {
    if let Err(e) = verilated::toolchain() {
        eprintln!("SKIPPED sim_speed: {e}");
        if std::env::var_os("CI").is_some() {
            std::process::exit(1);
        }
        return;
    }
    let p = PipelineParams::from_options(&method_options(Method::NormalizerFit).unwrap()).unwrap();
    let (jobs, regs) = scene();
    // Compile (or load) before timing.
    drop(model::<PixelStream>(&p, Sim::Verilator).unwrap());

    let (clocks, frags, t_in, rec) = drive(
        model::<PixelStream>(&p, Sim::Verilator).unwrap(),
        &jobs,
        &regs,
    );
    let in_process = clocks as f64 / t_in;

    let mut ceiling_model = verilated::model::<PixelStream>(&p).unwrap();
    let t = Instant::now();
    let hash = ceiling_model.bench_flat(&rec.rows);
    let t_ceiling = t.elapsed().as_secs_f64();
    let ceiling = clocks as f64 / t_ceiling;
    assert_eq!(
        hash, rec.hash,
        "the C++ loop's outputs differ from the in-process run's"
    );

    let n_rust: usize = std::env::var("SHADECORE_BENCH_RUST_HDL_TRIANGLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(jobs.len())
        .min(jobs.len());
    let (rc, rfrags, t_rust, _) = drive(
        model::<PixelStream>(&p, Sim::RustHdl).unwrap(),
        &jobs[..n_rust],
        &regs,
    );
    let rust = rc as f64 / t_rust;
    if n_rust == jobs.len() {
        assert_eq!(
            rfrags, frags,
            "rust-hdl and Verilator deliver other fragments"
        );
    }

    let (date, machine) = flow::tools::stamp();
    let table = format!(
        "# Simulation speed\n\n\
         Written by `cargo bench --bench sim_speed` on {date}, {machine}, one core per simulator.\n\
         `pixel-stream` built for normalizer-fit, the default scene (sphere rez 50, 400×400, \
         light 90°, {n} triangles in the balanced order, every `tready` high): {clocks} clocks, \
         {f} fragments. The three runs agree (same fragments in the same clocks; the C++ loop's \
         hash of every output of every clock equals the in-process run's).\n\n\
         | simulator | clocks | seconds | clocks/s | vs rust-hdl | vs ceiling |\n\
         |---|---:|---:|---:|---:|---:|\n\
         | Verilator in process (a call per clock, the render's driver) | {clocks} | {t_in:.3} | {in_process:.0} | {r1:.0}× | {c1:.2} |\n\
         | Verilator from memory, C++ loop (ceiling) | {clocks} | {t_ceiling:.3} | {ceiling:.0} | {r2:.0}× | 1.00 |\n\
         | rust-hdl (the render's driver) | {rc} | {t_rust:.2} | {rust:.0} | 1× | {c3:.4} |\n",
        n = jobs.len(),
        f = frags.len(),
        r1 = in_process / rust,
        r2 = ceiling / rust,
        c1 = in_process / ceiling,
        c3 = rust / ceiling,
    );
    print!("{table}");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("docs/measurements");
    let _ = std::fs::create_dir_all(&dir);
    let tmp = dir.join(".sim-speed.md.tmp");
    if std::fs::write(&tmp, &table)
        .and_then(|_| std::fs::rename(&tmp, dir.join("sim-speed.md")))
        .is_err()
    {
        eprintln!("could not write docs/measurements/sim-speed.md");
    }
}
