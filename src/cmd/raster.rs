//! `shadecore raster`: walk one triangle through the address block (SPEC §5) — the rust-hdl
//! RTL or its cycle-accurate golden model — and write one CSV row per clock:
//! `cycle,valid,x,y,step,line_start,done` (step: 0 Start, 1 H, 2 V, 3 D; cycle 0 is the
//! clock in which the set-up is loaded; the last row is the clock showing `done`).
//!
//! With `--address four-triangle` the four-triangle block (SPEC §7) walks the triangle's four
//! midpoint sub-triangles at once: one CSV row per clock with the same six columns per lane,
//! `valid0,x0,y0,step0,line_start0,done0, … ,done3` (lane K = sub-triangle K: 0 the corner at
//! the top vertex, 1 at the top–middle midpoint, 2 at the top–bottom midpoint, 3 the middle
//! one); the last row is the clock in which every lane has shown its `done`.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use golden::types::{ScreenTriangle, ScreenVertex, MAX_ADDRESS};
use golden::units::address_block::{AddressOutputs, AddressSetup};

/// Which implementation walks the triangle.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// The rust-hdl address block, simulated clock by clock.
    Rtl,
    /// The cycle-accurate golden model (`golden::units::address_block`).
    Golden,
}

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The triangle's vertices as six integers X0,Y0,X1,Y1,X2,Y2, each in 0..=4095.
    #[arg(long, allow_hyphen_values = true)]
    pub tri: String,
    /// Implementation to run.
    #[arg(long, value_enum, default_value = "rtl")]
    pub engine: Engine,
    /// Write the per-clock CSV here instead of standard output.
    #[arg(long)]
    pub dump: Option<PathBuf>,
    /// Write a waveform (VCD) of the RTL run here (RTL engine under rust-hdl only).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
    /// With `--engine rtl`: the simulator — verilator (the exported Verilog in process) or
    /// rust-hdl (the same CSV, clock for clock). Default: verilator when it is installed, and
    /// rust-hdl with `--vcd` (only rust-hdl writes a waveform).
    #[arg(long, value_enum)]
    pub sim: Option<crate::sim::SimArg>,
    /// The address block: single (SPEC §5, one address per clock) or four-triangle (SPEC §7,
    /// the four midpoint sub-triangles, up to four addresses per clock).
    #[arg(long, value_enum, default_value = "single")]
    pub address: RasterAddress,
}

/// `raster --address`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RasterAddress {
    Single,
    FourTriangle,
}

/// The per-clock outputs of the four-triangle block walking `tri` with `engine`.
pub fn four_clocks(
    tri: &ScreenTriangle,
    engine: Engine,
    vcd: Option<&std::path::Path>,
    sim: crate::sim::Sim,
) -> Result<Vec<golden::units::four_triangle::FourOutputs>> {
    use golden::units::four_triangle::FourTriangleSetup;
    let setup = FourTriangleSetup::new(tri);
    if vcd.is_some() && (engine == Engine::Golden || sim == crate::sim::Sim::Verilator) {
        bail!("--vcd needs --engine rtl --sim rust-hdl (only that run writes a waveform)");
    }
    match (engine, sim) {
        (Engine::Golden, _) => Ok(golden::units::four_triangle::run(&[setup]).0),
        (Engine::Rtl, crate::sim::Sim::Verilator) => {
            let budget = four_budget(&setup);
            pipeline::walkers::four_triangle::run_reactive_on(
                crate::sim::Sim::Verilator,
                &[setup],
                budget,
            )
            .map_err(|e| anyhow::anyhow!("RTL simulation: {e}"))
        }
        (Engine::Rtl, crate::sim::Sim::RustHdl) => {
            let budget = four_budget(&setup);
            with_vcd(vcd, |trace| {
                pipeline::walkers::four_triangle::run_reactive(&[setup], budget, trace)
            })
        }
    }
}

/// Every row of the tallest lane at full width plus latency: a hung block stops instead of
/// spinning.
fn four_budget(setup: &golden::units::four_triangle::FourTriangleSetup) -> usize {
    let rows = setup
        .lanes
        .iter()
        .map(|l| l.rows as usize)
        .max()
        .unwrap_or(0);
    16 + (rows + 1) * (MAX_ADDRESS as usize + 2)
}

/// The CSV text of a four-triangle run.
pub fn four_csv(out: &[golden::units::four_triangle::FourOutputs]) -> String {
    let mut s = String::from("cycle");
    for k in 0..4 {
        s.push_str(&format!(
            ",valid{k},x{k},y{k},step{k},line_start{k},done{k}"
        ));
    }
    s.push('\n');
    for (c, o) in out.iter().enumerate() {
        s.push_str(&c.to_string());
        for l in &o.lanes {
            s.push_str(&format!(
                ",{},{},{},{},{},{}",
                l.valid as u8, l.x, l.y, l.step, l.line_start as u8, l.done as u8
            ));
        }
        s.push('\n');
    }
    s
}

/// Parse `X0,Y0,X1,Y1,X2,Y2` into a triangle (depth 0, normal +z: only addresses matter here).
pub fn parse_tri(s: &str) -> Result<ScreenTriangle> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 6 {
        bail!(
            "--tri {s:?}: expected 6 comma-separated integers X0,Y0,X1,Y1,X2,Y2, got {}",
            parts.len()
        );
    }
    let mut c = [0i32; 6];
    for (k, p) in parts.iter().enumerate() {
        let v: i64 = p
            .parse()
            .map_err(|_| anyhow::anyhow!("--tri {s:?}: {p:?} is not an integer"))?;
        if !(0..=MAX_ADDRESS as i64).contains(&v) {
            bail!("--tri {s:?}: {v} is outside the 12-bit address range 0..={MAX_ADDRESS}");
        }
        c[k] = v as i32;
    }
    let v = |i: usize| ScreenVertex {
        x: c[2 * i],
        y: c[2 * i + 1],
        z: 0.0,
        normal: glam::DVec3::Z,
        uv: glam::DVec2::ZERO,
        w: 1.0,
    };
    Ok(ScreenTriangle {
        v: [v(0), v(1), v(2)],
        frac: 0,
    })
}

/// The per-clock outputs of walking `tri` with `engine` (optionally tracing the RTL to `vcd`).
pub fn walk_clocks(
    tri: &ScreenTriangle,
    engine: Engine,
    vcd: Option<&std::path::Path>,
) -> Result<Vec<AddressOutputs>> {
    walk_clocks_with(tri, engine, vcd, crate::sim::Sim::RustHdl)
}

/// [`walk_clocks`] with the RTL under the simulator `sim`.
pub fn walk_clocks_with(
    tri: &ScreenTriangle,
    engine: Engine,
    vcd: Option<&std::path::Path>,
    sim: crate::sim::Sim,
) -> Result<Vec<AddressOutputs>> {
    let setup = AddressSetup::new(tri);
    if engine == Engine::Rtl && sim == crate::sim::Sim::Verilator {
        if vcd.is_some() {
            bail!("--vcd needs --sim rust-hdl (the Verilator run writes no waveform)");
        }
        let budget = 16 + (setup.rows as usize + 1) * (MAX_ADDRESS as usize + 2);
        return pipeline::walkers::address::run_reactive_on(
            crate::sim::Sim::Verilator,
            &[setup],
            budget,
        )
        .map_err(|e| anyhow::anyhow!("RTL simulation: {e}"));
    }
    match engine {
        Engine::Golden => {
            if vcd.is_some() {
                bail!("--vcd needs --engine rtl (the golden model has no waveform)");
            }
            Ok(pipeline::walkers::address::run_model(&[setup]))
        }
        Engine::Rtl => {
            // Every row at full width plus latency: a hung block stops instead of spinning.
            let budget = 16 + (setup.rows as usize + 1) * (MAX_ADDRESS as usize + 2);
            with_vcd(vcd, |trace| {
                pipeline::walkers::address::run_reactive(&[setup], budget, trace)
            })
        }
    }
}

/// Run `sim` with a VCD trace into `vcd` (written whole: `golden::files::write_through`) or
/// without one.
fn with_vcd<T>(
    vcd: Option<&std::path::Path>,
    sim: impl FnOnce(Option<Box<dyn Write>>) -> Result<T, String>,
) -> Result<T> {
    let run = |trace| sim(trace).map_err(|e| format!("RTL simulation: {e}"));
    match vcd {
        None => run(None),
        Some(p) => golden::files::write_through(p, |temp| {
            let f = std::fs::File::create(temp)
                .map_err(|e| format!("cannot create {}: {e}", p.display()))?;
            run(Some(Box::new(std::io::BufWriter::new(f))))
        }),
    }
    .map_err(|e| anyhow::anyhow!(e))
}

/// Why a walk of `tri` emitted no pixel, in one line: zero area (collinear or repeated
/// vertices), or no pixel centre it owns under the fill rule (`golden::raster`: inside, or on
/// a left edge).
pub fn no_pixel_reason(tri: &ScreenTriangle) -> String {
    let [a, b, c] = tri.v;
    let area2 = (b.x - a.x) as i64 * (c.y - a.y) as i64 - (c.x - a.x) as i64 * (b.y - a.y) as i64;
    if area2 == 0 {
        "the triangle has zero area (its vertices are collinear or repeated): the walk emits no pixel".into()
    } else {
        format!(
            "the triangle (area {:.1} pixels) owns no pixel centre (none inside it or on a left edge): the walk emits no pixel",
            area2.abs() as f64 / 2.0
        )
    }
}

/// The CSV text of a run.
pub fn csv(out: &[AddressOutputs]) -> String {
    let mut s = String::from("cycle,valid,x,y,step,line_start,done\n");
    for (c, o) in out.iter().enumerate() {
        s.push_str(&format!(
            "{c},{},{},{},{},{},{}\n",
            o.valid as u8, o.x, o.y, o.step, o.line_start as u8, o.done as u8
        ));
    }
    s
}

pub fn run(a: Args) -> Result<()> {
    let tri = parse_tri(&a.tri)?;
    if a.engine == Engine::Golden && a.sim.is_some() {
        bail!("--sim has no effect with --engine golden (it chooses how the RTL is simulated: use --engine rtl)");
    }
    let sim = match (a.sim, &a.vcd, a.engine) {
        (None, Some(_), _) | (_, _, Engine::Golden) => crate::sim::Sim::RustHdl,
        (arg, _, _) => crate::sim::resolve(arg)?,
    };
    if sim == crate::sim::Sim::Verilator {
        let d = match a.address {
            RasterAddress::Single => {
                verilated::design::<rtl::units::address_block::AddressBlock>(&Default::default())
            }
            RasterAddress::FourTriangle => {
                verilated::design::<rtl::units::four_triangle::FourTriangle>(&Default::default())
            }
        };
        crate::sim::prepare(sim, vec![d], &indicatif::MultiProgress::new())?;
    }
    let (text, clocks, pixels, rows) = match a.address {
        RasterAddress::Single => {
            let out = walk_clocks_with(&tri, a.engine, a.vcd.as_deref(), sim)?;
            let pixels = out.iter().filter(|o| o.valid).count();
            let rows = out.iter().filter(|o| o.row_start).count();
            (csv(&out), out.len(), pixels, rows)
        }
        RasterAddress::FourTriangle => {
            let out = four_clocks(&tri, a.engine, a.vcd.as_deref(), sim)?;
            let pixels = out.iter().map(|o| o.addresses()).sum();
            let rows = out
                .iter()
                .map(|o| o.lanes.iter().filter(|l| l.row_start).count())
                .sum();
            (four_csv(&out), out.len(), pixels, rows)
        }
    };
    if pixels == 0 {
        // Not an error (the hardware walks it and emits nothing), but a dump of zeros alone
        // would leave the user guessing why.
        eprintln!("note: {}", no_pixel_reason(&tri));
    }
    match &a.dump {
        Some(p) => {
            crate::output::write_whole(p, text.as_bytes())?;
            crate::outln!(
                "{}: {clocks} clocks, {pixels} pixels on {rows} raster lines{} ({:.3} pixels/clock); CSV in {}{}",
                match a.engine {
                    Engine::Rtl => "rtl",
                    Engine::Golden => "golden",
                },
                if a.address == RasterAddress::FourTriangle { " of four sub-triangles" } else { "" },
                pixels as f64 / clocks as f64,
                p.display(),
                a.vcd.as_ref().map_or(String::new(), |v| format!(", waveform in {}", v.display()))
            )?;
        }
        None => {
            std::io::stdout()
                .write_all(text.as_bytes())
                .context("writing to standard output")?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_triangles_are_one_line_errors() {
        for (s, what) in [
            ("1,2,3,4,5", "expected 6"),
            ("1,2,3,4,5,6,7", "expected 6"),
            ("1,2,3,x,5,6", "not an integer"),
            ("1,2,3,4.5,5,6", "not an integer"),
            ("1,2,3,4096,5,6", "outside"),
            ("1,-2,3,4,5,6", "outside"),
        ] {
            let e = format!("{:#}", parse_tri(s).unwrap_err());
            assert!(e.contains(what) && !e.contains('\n'), "{s}: {e}");
        }
        assert!(parse_tri(" 0, 0 ,4095,0,0,4095").is_ok());
    }

    #[test]
    fn four_triangle_rtl_and_golden_agree_and_cover_the_parent() {
        let t = parse_tri("3,1,40,7,11,30").unwrap();
        let sim = crate::sim::Sim::RustHdl;
        let r = four_clocks(&t, Engine::Rtl, None, sim).unwrap();
        let g = four_clocks(&t, Engine::Golden, None, sim).unwrap();
        assert_eq!(r, g);
        let text = four_csv(&r);
        assert_eq!(text.lines().count(), r.len() + 1);
        assert_eq!(text.lines().next().unwrap().split(',').count(), 25);
        let pixels: usize = r.iter().map(|o| o.addresses()).sum();
        assert_eq!(pixels, golden::raster::edge_function_pixels(&t).len());
    }

    #[test]
    fn rtl_and_golden_agree_and_csv_has_one_row_per_clock() {
        let t = parse_tri("3,1,40,7,11,30").unwrap();
        let r = walk_clocks(&t, Engine::Rtl, None).unwrap();
        let g = walk_clocks(&t, Engine::Golden, None).unwrap();
        assert_eq!(r, g);
        let text = csv(&r);
        assert_eq!(text.lines().count(), r.len() + 1);
        assert!(
            text.lines().last().unwrap().ends_with(",1"),
            "last row shows done"
        );
    }
}
