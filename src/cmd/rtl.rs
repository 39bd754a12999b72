//! RTL commands: `export-verilog`, `sim`, `synth`.

use std::path::PathBuf;

use anyhow::{anyhow, bail, Context};
use rtl::export::{self, BlockKind};
use rtl::normalizer::NormalizerCoeffs;
use testbenches::blocks;

/// Coefficient sets of the normalizer.
fn coeffs(name: &str) -> anyhow::Result<NormalizerCoeffs> {
    let c = match name {
        "published" => golden::normalizer::PUBLISHED,
        "fit" => golden::normalizer::FIT,
        other => bail!("unknown coefficient set {other:?} (expected published or fit)"),
    };
    NormalizerCoeffs::new(c).map_err(|e| anyhow!("{e}"))
}

/// `NAME` or `all`.
fn blocks_arg(name: &str) -> anyhow::Result<Vec<BlockKind>> {
    if name == "all" {
        Ok(BlockKind::ALL.to_vec())
    } else {
        Ok(vec![name
            .parse::<BlockKind>()
            .map_err(|e| anyhow!("{e}, or all"))?])
    }
}

#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// Block: normalizer, normalizer-k, k-recurrence, span-normalizer, address-block,
    /// intensity-interpolator, gouraud-raster, or all.
    #[arg(long, default_value = "all")]
    pub block: String,
    /// Output directory (one `<module>.v` per block).
    #[arg(long, default_value = "target/verilog")]
    pub out: PathBuf,
    /// Normalizer coefficients: published (0.822, −2.046, 2.227) or fit (golden FIT).
    #[arg(long, default_value = "published")]
    pub coeffs: String,
}

#[derive(clap::Args, Debug)]
pub struct SimArgs {
    /// Block: normalizer, normalizer-k, k-recurrence, span-normalizer, address-block,
    /// intensity-interpolator or gouraud-raster.
    #[arg(long, default_value = "normalizer")]
    pub block: String,
    /// Random inputs to simulate: vectors (default 1000); pixels for the span blocks (1000);
    /// triangles for address-block, intensity-interpolator, gouraud-raster (default 20, 1000–2000
    /// clocks each on average).
    #[arg(long)]
    pub vectors: Option<usize>,
    /// Seed of the stimulus (default: the test runner's seed for "shadecore-sim";
    /// SHADECORE_SEED overrides that default).
    #[arg(long)]
    pub seed: Option<u64>,
    /// VCD file to write (default target/sims/<block>.vcd).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
    /// Normalizer coefficients: published or fit.
    #[arg(long, default_value = "published")]
    pub coeffs: String,
}

#[derive(clap::Args, Debug)]
pub struct SynthArgs {
    /// Block: normalizer, normalizer-k, k-recurrence, span-normalizer, address-block,
    /// intensity-interpolator, gouraud-raster, or all.
    #[arg(long, default_value = "normalizer")]
    pub block: String,
    /// Normalizer coefficients: published or fit.
    #[arg(long, default_value = "published")]
    pub coeffs: String,
    /// Skip place-and-route (no Fmax estimate).
    #[arg(long)]
    pub no_pnr: bool,
}

pub fn export(a: ExportArgs) -> anyhow::Result<()> {
    let c = coeffs(&a.coeffs)?;
    for b in blocks_arg(&a.block)? {
        let path = export::write(b, &c, &a.out).map_err(|e| anyhow!(e))?;
        println!(
            "{b}: module {} (latency {} clocks) -> {}",
            b.module_name(),
            b.latency(),
            path.display()
        );
    }
    Ok(())
}

pub fn sim(a: SimArgs) -> anyhow::Result<()> {
    let c = coeffs(&a.coeffs)?;
    let block: BlockKind = a.block.parse().map_err(|e: String| anyhow!(e))?;
    let n = a.vectors.unwrap_or(blocks::default_items(block));
    if n == 0 {
        bail!("--vectors must be at least 1");
    }
    let seed = a
        .seed
        .unwrap_or_else(|| golden::testing::seed_for("shadecore-sim"));
    let vcd = a.vcd.unwrap_or_else(|| {
        testbenches::harness::target_dir()
            .join("sims")
            .join(format!("{block}.vcd"))
    });
    if let Some(dir) = vcd.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let t = std::time::Instant::now();
    let out = blocks::sim_to_vcd(block, &c, n, seed, &vcd).map_err(|e| anyhow!(e))?;
    print!("{}", out.report);
    println!(
        "{block}: {} {} checked against the golden model every clock (latency {}), seed {seed}, {:.2?}",
        out.count,
        out.items,
        block.latency(),
        t.elapsed()
    );
    println!("VCD: {}", out.vcd.display());
    Ok(())
}

pub fn synth(a: SynthArgs) -> anyhow::Result<()> {
    let c = coeffs(&a.coeffs)?;
    for b in blocks_arg(&a.block)? {
        let (rep, fmax) = blocks::synth_block(b, &c, !a.no_pnr).map_err(|e| anyhow!(e))?;
        print!("{rep}");
        match fmax {
            Some(f) => println!(
                "{}: nextpnr-ice40 --up5k (sg48, timing shell): max clock {f:.1} MHz",
                rep.top
            ),
            None if a.no_pnr => {}
            None => println!("{}: nextpnr-ice40 not installed: no Fmax estimate", rep.top),
        }
    }
    Ok(())
}
