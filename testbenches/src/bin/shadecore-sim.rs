//! `shadecore-sim`: a block's testbench from the command line — seeded stimulus through the
//! block, checked every clock against its bit-exact twin and the golden model, with a VCD of
//! the run. It lives here, not in `shadecore`, because the stimulus and the twins are test
//! support (proptest strategies), which the product CLI does not link.
//!
//! `cargo run --release -p testbenches --bin shadecore-sim -- --block normalizer --vcd n.vcd`

use std::path::PathBuf;

use anyhow::{anyhow, bail, Context};
use clap::Parser;
use flow::cli::{BuildArgs, SimArg};
use flow::engine::{self, Sim};
use testbenches::registry;

/// `println!` that returns an error instead of panicking on a closed standard output.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*)
            .map_err(|e| anyhow::anyhow!("writing to standard output: {e}"))
    }};
}

/// Simulate an RTL block on seeded random stimulus, checked every clock against its bit-exact
/// twin and the golden model, and write a VCD.
#[derive(clap::Parser, Debug)]
#[command(name = "shadecore-sim", version)]
struct Args {
    /// Block name (`shadecore blocks` lists them).
    #[arg(long, default_value = "normalizer")]
    block: String,
    /// Random items to simulate, in the block's unit (`shadecore blocks`): the block's default
    /// (vectors, pixels, spans or triangles). Longer runs go in batches of the default size
    /// through one simulation, in constant memory, with the VCD written as the clocks go; above
    /// 20 times the default a warning gives the VCD's expected size, above 1000 times the run
    /// is refused (the VCD of every signal grows with it: about 3 kB per normalizer vector).
    #[arg(long)]
    vectors: Option<usize>,
    /// Seed of the stimulus (default: the test runner's seed for "shadecore-sim";
    /// SHADECORE_SEED overrides that default).
    #[arg(long)]
    seed: Option<u64>,
    /// VCD file to write (rust-hdl only; default under rust-hdl target/sims/<block>.vcd).
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// The simulator: verilator (the exported Verilog in process, no VCD) or rust-hdl (writes
    /// the VCD). Default: verilator when it is installed, rust-hdl with --vcd.
    #[arg(long, value_enum)]
    sim: Option<SimArg>,
    #[command(flatten)]
    build: BuildArgs,
}

/// `sim` simulates at most this many times a block's default number of items (the VCD's
/// size, not memory, is the limit: the run streams).
const SIM_LIMIT_FACTOR: usize = 1000;
/// Above this many times the default, `sim` warns about the VCD's size.
const SIM_WARN_FACTOR: usize = 20;

fn sim(a: Args) -> anyhow::Result<()> {
    let block = registry::find(&a.block).map_err(|e| anyhow!(e))?;
    let as_block: &'static dyn flow::blocks::Block = block;
    let o = a
        .build
        .checked_options(&[as_block])
        .map_err(|e| anyhow!(e))?;
    let n = a.vectors.unwrap_or(block.default_items());
    if n == 0 {
        bail!("--vectors must be at least 1");
    }
    let limit = SIM_LIMIT_FACTOR * block.default_items();
    if n > limit {
        bail!(
            "--vectors {n} is above {}'s limit of {limit} {} ({SIM_LIMIT_FACTOR} × its default: the VCD of every signal grows with the run, about 3 kB per normalizer vector)",
            block.name(),
            block.items()
        );
    }
    let seed = a
        .seed
        .unwrap_or_else(|| golden::seed::seed_for("shadecore-sim"));
    let sim = match (a.sim, &a.vcd) {
        (None, Some(_)) => Sim::RustHdl,
        (Some(SimArg::Verilator), Some(_)) => {
            bail!("--vcd needs --sim rust-hdl (the Verilator run writes no waveform)")
        }
        (arg, _) => engine::resolve(arg.map(Sim::from)).map_err(|e| anyhow!(e))?,
    };
    let vcd = (sim == Sim::RustHdl).then(|| {
        a.vcd.clone().unwrap_or_else(|| {
            flow::target_dir()
                .join("sims")
                .join(format!("{}.vcd", block.name()))
        })
    });
    if let Some(dir) = vcd
        .as_ref()
        .and_then(|v| v.parent())
        .filter(|d| !d.as_os_str().is_empty())
    {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    if sim == Sim::Verilator {
        engine::prepare(
            sim,
            vec![block.design(&o).map_err(|e| anyhow!(e))?],
            &indicatif::MultiProgress::new(),
        )
        .map_err(|e| anyhow!(e))?;
    }
    if let (Some(vcd), true) = (&vcd, n > SIM_WARN_FACTOR * block.default_items()) {
        eprintln!(
            "warning: {n} {} is over {SIM_WARN_FACTOR} × {}'s default: the VCD at {} grows with every clock (about 3 kB per normalizer vector)",
            block.items(),
            block.name(),
            vcd.display()
        );
    }
    let t = std::time::Instant::now();
    let bar = indicatif::ProgressBar::new(n as u64).with_style(
        indicatif::ProgressStyle::with_template(&format!(
            "sim {} [{{bar:40}}] {{pos}}/{{len}} {} {{msg}} {{elapsed}} (eta {{eta}})",
            block.name(),
            block.items()
        ))
        .expect("static template")
        .progress_chars("=> "),
    );
    let per = block.default_items().max(1) as u64;
    let mut batches = 0u64;
    let out = block
        .sim_stream(&o, n, seed, vcd.as_deref(), sim, &mut |clocks| {
            batches += 1;
            bar.set_position((batches * per).min(n as u64));
            bar.set_message(format!("({clocks} clocks)"));
        })
        .map_err(|e| anyhow!(e));
    bar.finish_and_clear();
    let out = out?;
    outln!(
        "[{}] {} clocks in {} batch{}, seed {}",
        out.name,
        out.cycles,
        out.batches,
        if out.batches == 1 { "" } else { "es" },
        out.seed
    )?;
    for p in &out.ports {
        outln!("  {p}")?;
    }
    outln!(
        "{}: {n} {} checked every clock against the bit-exact twin and the golden model (latency {}), seed {seed}, {:.2?}",
        block.name(),
        block.items(),
        block.latency(),
        t.elapsed()
    )?;
    match &vcd {
        Some(v) => outln!("VCD: {}", v.display())?,
        None => outln!(
            "VCD: none (Verilator writes no waveform; --sim rust-hdl or --vcd PATH for one)"
        )?,
    }
    Ok(())
}

fn main() {
    flow::engine::set_thread_stack();
    verilated::set_quiet(true);
    let a = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(
                e.kind(),
                ErrorKind::DisplayHelp
                    | ErrorKind::DisplayVersion
                    | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
            ) {
                e.exit();
            }
            let text = e.render().to_string();
            eprintln!("{}", text.lines().next().unwrap_or("error: bad arguments"));
            std::process::exit(2);
        }
    };
    if let Err(e) = sim(a) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
