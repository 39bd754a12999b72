//! `shadecore` command-line interface.

use clap::{Parser, Subcommand};
use shadecore::cmd;

#[derive(Parser)]
#[command(
    name = "shadecore",
    version,
    about = "Accelerated shading hardware (VNTU patents) as rust-hdl RTL with an f64 golden model"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene with the reference and the accelerated methods; write PNGs, diffs, NMSE report.
    #[command(
        long_about = "Render a scene with the reference and the accelerated methods; write PNGs, diffs, NMSE report.\n\n\
Time and memory grow with the canvas. Measured on a 2-core AMD EPYC (2026-11-27), every method, \
Verilator models already built (building them first adds about a minute): a 4096x4096 render takes \
51 s and 2.6 GB with --engine both, 10 s and 1.2 GB with --engine golden (2048x2048: 12 s and 0.75 GB; \
the default 400x400: 0.7 s); with --sim rust-hdl the RTL images take about 400 times longer \
(hours). Without a terminal, progress is a line on stderr every 5 s."
    )]
    Render(cmd::render::Args),
    /// Measure each approximation's maximum error over its domain beside the sources' claims.
    Accuracy(cmd::accuracy::Args),
    /// NMSE of every shading method (not the textured ones) over a grid of tessellations, exponents and light angles.
    Sweep(cmd::sweep::Args),
    /// Write synthesizable Verilog of RTL blocks.
    ExportVerilog(cmd::rtl::ExportArgs),
    /// Moved to `shadecore-sim` (the testbenches crate): says how to run it.
    #[command(hide = true, disable_help_flag = true)]
    Sim {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Synthesize a block with Yosys and print cell counts.
    Synth(cmd::rtl::SynthArgs),
    /// Walk one triangle through the address block (RTL or golden) and dump one row per clock.
    Raster(cmd::raster::Args),
    /// List the registered RTL blocks (the table in the README) as Markdown.
    Blocks,
    /// Write a scene as a stream top's AXI4-Stream set-up words (pixel-stream, or gouraud-stream for gouraud), the beats its simulation delivers, and its Verilog.
    Stream(cmd::stream::Args),
}

fn main() {
    flow::engine::set_thread_stack();
    // Model builds show as progress bars (`shadecore::sim::prepare`), not as lines on stderr.
    verilated::set_quiet(true);
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion)
                || matches!(
                    e.kind(),
                    ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
                )
            {
                e.exit();
            }
            // Bad arguments: one line naming the problem (clap's first line, with the next
            // one when the first ends in a colon: "…were not provided:" and the argument),
            // exit code 2.
            let text = e.render().to_string();
            let mut lines = text.lines().filter(|l| !l.trim().is_empty());
            let first = lines.next().unwrap_or("error: bad arguments");
            match (first.ends_with(':'), lines.next()) {
                (true, Some(next)) => eprintln!("{first} {}", next.trim()),
                _ => eprintln!("{first}"),
            }
            std::process::exit(2);
        }
    };
    let result = match cli.command {
        Command::Render(a) => cmd::render::run(a),
        Command::Accuracy(a) => cmd::accuracy::run(a),
        Command::Sweep(a) => cmd::sweep::run(a),
        Command::ExportVerilog(a) => cmd::rtl::export(a),
        Command::Sim { args } => Err(anyhow::anyhow!(
            "`sim` checks a block against its testbench, which lives in the testbenches crate: run `cargo run --release -p testbenches --bin shadecore-sim --{}`",
            args.iter().map(|a| format!(" {a}")).collect::<String>()
        )),
        Command::Synth(a) => cmd::rtl::synth(a),
        Command::Raster(a) => cmd::raster::run(a),
        Command::Blocks => cmd::rtl::blocks(),
        Command::Stream(a) => cmd::stream::run(a),
    };
    if let Err(e) = result {
        // One line, no backtrace: the chain of causes joined by ": ".
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
