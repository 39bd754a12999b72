//! `shadecore stream`: a scene as the `pixel-stream` top's AXI4-Stream set-up words, with the
//! fragment beats the rust-hdl simulation of that top delivers for them and its Verilog — what
//! an external testbench (the cocotb test in `testbenches/cocotb/`) drives and checks.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{anyhow, bail, Context, Result};
use pipeline::lit::{method_options, LitJob, ShadingRegs};
use pipeline::stream::{scene_words, Beat};
use rtl::pixel_pipeline::PipelineParams;
use rtl::registry::BlockParams;
use testbenches::pixel_stream::drive;
use testbenches::stall::StallPattern;

use crate::setup::SceneArgs;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The lit method whose `pixel-stream` build runs: normalizer, normalizer-fit, brdf-k4,
    /// brdf-k8, brdf-k16 or bump.
    #[arg(long, default_value = "normalizer-fit")]
    pub method: String,
    /// The order the triangles are sent in: balanced (large and small walks alternately, as
    /// `render` sends them) or mesh.
    #[arg(long, value_enum, default_value = "balanced")]
    pub setup_order: crate::rtl_engine::SetupOrder,
    /// Output directory: setup.txt, beats.txt, pixel_stream.v.
    #[arg(long, default_value = "target/stream")]
    pub out: PathBuf,
}

pub fn run(a: Args) -> Result<()> {
    let method = crate::cmd::render::parse_methods(std::slice::from_ref(&a.method))?[0];
    let Some(o) = method_options(method) else {
        bail!(
            "method {} is not built by pixel-stream (it has normalizer, normalizer-fit, brdf-k4, brdf-k8, brdf-k16, bump)",
            a.method
        );
    };
    let s = crate::setup::build(&a.scene)?;
    let regs = ShadingRegs::of(&s.ctx).map_err(|e| anyhow!(e))?;
    let mut jobs = Vec::new();
    for (i, t) in s.tris.iter().enumerate() {
        if let Some(j) = LitJob::new(t).map_err(|e| anyhow!("triangle {i}: {e}"))? {
            jobs.push(j);
        }
    }
    let jobs: Vec<LitJob> = a.setup_order.of(&jobs).iter().map(|&i| jobs[i]).collect();
    let p = PipelineParams::from_options(&o).map_err(|e| anyhow!(e))?;
    let words = scene_words(&jobs, &regs);
    // The producer and consumer never pause here: the rows are the twin's; the beats are the
    // rust-hdl simulation's, which must agree with the twin's clock for clock.
    let run = drive(&p, &words, 1, 0.0, &mut StallPattern::never(), 8);
    let b = testbenches::registry::find("pixel-stream").map_err(|e| anyhow!(e))?;
    let out = b.simulate(&o, &run.rows).map_err(|e| anyhow!(e))?;
    if out != run.outputs {
        bail!("the rust-hdl simulation of pixel-stream disagrees with its twin");
    }
    let beats: Vec<Beat> = out
        .iter()
        .filter(|r| r[1] != 0)
        .map(|r| Beat::read(r[2], r[3], r[4] != 0))
        .collect();

    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    let mut setup = format!(
        "# pixel-stream set-up words ({:?} order): hex word, tlast\n",
        a.setup_order
    )
    .to_lowercase();
    for (w, last) in &words {
        setup.push_str(&format!("{w:08x} {}\n", *last as u8));
    }
    let mut text =
        String::from("# pixel-stream fragment beats: x y pixel red green blue z tlast\n");
    for bt in &beats {
        text.push_str(&format!(
            "{} {} {} {} {} {} {} {}\n",
            bt.x, bt.y, bt.pixel as u8, bt.rgb[0], bt.rgb[1], bt.rgb[2], bt.z, bt.last as u8
        ));
    }
    let verilog = b.verilog(&o).map_err(|e| anyhow!(e))?;
    for (name, body) in [
        ("setup.txt", setup.as_str()),
        ("beats.txt", text.as_str()),
        ("pixel_stream.v", verilog.as_str()),
    ] {
        let path = a.out.join(name);
        std::fs::File::create(&path)
            .and_then(|mut f| f.write_all(body.as_bytes()))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    crate::outln!(
        "pixel-stream ({}): {} triangles, {} set-up words, {} beats ({} fragments) in {} clocks -> {}",
        a.method,
        jobs.len(),
        words.len(),
        beats.len(),
        beats.iter().filter(|b| b.pixel).count(),
        run.rows.len(),
        a.out.display()
    )?;
    Ok(())
}
