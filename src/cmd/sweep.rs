//! `shadecore sweep`: NMSE of every shading method (the textured ones are not swept) over scene × rez × shininess × light angle, as CSV
//! and Markdown. The rez axis applies to the built-in scenes; an OBJ mesh is swept once per
//! shininess and light angle.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result};
use golden::methods::Method;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use crate::cmd::render::{compare, render_golden};
use crate::setup::{build, Lighting, SceneArgs};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Tessellations to sweep.
    #[arg(long, value_delimiter = ',', default_value = "10,20,50,100")]
    pub rez: Vec<u32>,
    /// Specular exponents to sweep.
    #[arg(long, value_delimiter = ',', default_value = "10,50,255")]
    pub shininess: Vec<u32>,
    /// Light angles (degrees) to sweep.
    #[arg(long = "light-deg", value_delimiter = ',', default_value = "30,90,150")]
    pub light_deg: Vec<f64>,
    /// `sphere`, `torus` or an .obj path; repeat the flag for a scene axis (`--scene sphere
    /// --scene mesh.obj`). The rez axis applies to the built-in scenes only.
    #[arg(long, default_value = "sphere")]
    pub scene: Vec<PathBuf>,
    /// Canvas size WxH.
    #[arg(long, default_value = "400x400", value_parser = crate::setup::parse_size)]
    pub size: (u32, u32),
    #[arg(long, value_enum, default_value = "blinn")]
    pub lighting: Lighting,
    /// Output directory for sweep.csv and sweep.md.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Adaptive subdivision before every method: 0, 1, 2 or auto (as `render --subdivide`).
    #[arg(long, default_value = "0")]
    pub subdivide: golden::shading::refine::Subdivide,
    /// Fraction bits of the vertex coordinates: 4 (the default) or 0 (as `render --subpixel`).
    #[arg(long, default_value_t = golden::SUBPIXEL_BITS, value_parser = crate::setup::parse_subpixel)]
    pub subpixel: u32,
}

pub fn run(args: Args) -> Result<()> {
    // (configuration, whether its rez means anything).
    let mut configs = Vec::new();
    for scene in &args.scene {
        let built_in = matches!(scene.to_str(), Some("sphere" | "torus"));
        let rezzes = if built_in {
            &args.rez[..]
        } else {
            &args.rez[..1]
        };
        for &rez in rezzes {
            for &shininess in &args.shininess {
                for &light_deg in &args.light_deg {
                    configs.push((
                        SceneArgs {
                            scene: scene.clone(),
                            rez,
                            shininess,
                            light_deg,
                            size: args.size,
                            lighting: args.lighting,
                            subdivide: args.subdivide,
                            subpixel: args.subpixel,
                            texture: None,
                            eye: None,
                        },
                        built_in,
                    ));
                }
            }
        }
    }
    let (configs, built_in): (Vec<SceneArgs>, Vec<bool>) = configs.into_iter().unzip();
    // Validate every configuration up front: a bad value fails before any work is done.
    let setups = configs.iter().map(build).collect::<Result<Vec<_>>>()?;
    for (c, s) in configs.iter().zip(&setups) {
        s.ensure_drawn().with_context(|| {
            format!(
                "{} shininess {} light {}°",
                c.describe(),
                c.shininess,
                c.light_deg
            )
        })?;
    }
    let methods = &Method::ALL_NON_REFERENCE[..];
    let bar = ProgressBar::new((configs.len() * (methods.len() + 1)) as u64).with_style(
        ProgressStyle::with_template("sweep [{bar:40}] {pos}/{len} images {elapsed}")
            .expect("static template")
            .progress_chars("=> "),
    );
    let rows: Vec<Vec<f64>> = setups
        .par_iter()
        .map(|setup| {
            let (reference, frames) = render_golden(setup, methods, &bar);
            frames
                .iter()
                .map(|f| compare(&reference.plain, f).nmse)
                .collect()
        })
        .collect();
    bar.finish_and_clear();

    let mut csv = String::from("scene,rez,shininess,light_deg,method,nmse,band\n");
    let mut md = String::from("| scene | rez | n | light | ");
    md += &methods
        .iter()
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(" | ");
    md += " |\n|---|---|---|---|";
    md += &"---:|".repeat(methods.len());
    md += "\n";
    for ((c, row), &built_in) in configs.iter().zip(&rows).zip(&built_in) {
        // An OBJ has no rez: empty in the CSV, — in the table.
        let rez = if built_in {
            c.rez.to_string()
        } else {
            String::new()
        };
        let scene = c.scene.display().to_string();
        write!(
            md,
            "| {} | {} | {} | {}° |",
            scene.replace('|', "\\|"),
            if built_in { rez.as_str() } else { "—" },
            c.shininess,
            c.light_deg
        )
        .unwrap();
        for (m, v) in methods.iter().zip(row) {
            let band = golden::nmse::Band::of(*v);
            writeln!(
                csv,
                "{},{},{},{},{},{:.8},{}",
                csv_field(&scene),
                rez,
                c.shininess,
                c.light_deg,
                m.name(),
                v,
                band.label()
            )
            .unwrap();
            write!(md, " {v:.2e} |").unwrap();
        }
        md += "\n";
    }
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating output directory {}", args.out.display()))?;
    crate::output::write_whole(&args.out.join("sweep.csv"), csv.as_bytes())?;
    crate::output::write_whole(&args.out.join("sweep.md"), md.as_bytes())?;
    crate::out!("{md}")?;
    crate::outln!(
        "wrote {} and {}",
        args.out.join("sweep.csv").display(),
        args.out.join("sweep.md").display()
    )?;
    Ok(())
}

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}
