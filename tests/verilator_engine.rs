//! The Verilator engine (`render --engine rtl --sim verilator`, the exported Verilog in
//! process) gives the same frames as the rust-hdl simulation, bit for bit, with the same clock
//! counts, for every pipeline: the Gouraud pipe, the lit pipeline (two builds), the span tops,
//! the quadric unit and the cubic pipeline (both Horner variants), through the render's default
//! tops. Skips with a notice without Verilator (fails when `CI` is set).

use golden::methods::Method;
use indicatif::ProgressBar;
use shadecore::rtl_engine::{render_rtl_with, RtlBuild};
use shadecore::setup::{build, SceneArgs};
use shadecore::sim::Sim;
use testbenches::tools::{self, Tool};

#[test]
fn verilator_frames_equal_rust_hdl_frames() {
    if !tools::require(&[Tool::Verilator], "verilator_frames_equal_rust_hdl_frames") {
        return;
    }
    let s = build(&SceneArgs {
        size: (120, 120),
        rez: 12,
        ..SceneArgs::default()
    })
    .unwrap();
    let cases = [
        (Method::Gouraud, false),
        (Method::Subdivision, false),
        (Method::NormalizerFit, false),
        (Method::Bump, false),
        (Method::Angular, false),
        (Method::FastFit, false),
        (Method::Quadric, false),
        (Method::Cubic, false),
        (Method::Cubic, true),
    ];
    for (m, pipelined) in cases {
        let run = |sim: Sim| {
            render_rtl_with(
                &s.tris,
                m,
                &s.ctx,
                s.width,
                s.height,
                &ProgressBar::hidden(),
                RtlBuild {
                    horner_pipelined: pipelined,
                    sim,
                    ..RtlBuild::default()
                },
            )
            .unwrap_or_else(|e| panic!("{m} ({sim:?}): {e:#}"))
        };
        let t0 = std::time::Instant::now();
        let v = run(Sim::Verilator);
        let tv = t0.elapsed();
        let t0 = std::time::Instant::now();
        let r = run(Sim::RustHdl);
        let tr = t0.elapsed();
        println!(
            "{m}{}: {} fragments, {} clocks; verilator {tv:.1?} (build cached after the first run), rust-hdl {tr:.1?}",
            if pipelined { " (pipelined Horner)" } else { "" },
            r.stats.pixels,
            r.stats.clocks
        );
        assert!(
            r.stats.pixels > 1000,
            "{m}: only {} fragments",
            r.stats.pixels
        );
        assert_eq!(v.frame.rgb, r.frame.rgb, "{m}: the frames differ");
        assert_eq!(
            v.frame.depth, r.frame.depth,
            "{m}: the depth buffers differ"
        );
        assert_eq!(
            (v.stats.clocks, v.stats.pixels),
            (r.stats.clocks, r.stats.pixels),
            "{m}: clock counts differ"
        );
    }
}

/// `raster --sim verilator` gives the address block's per-clock outputs of the rust-hdl run,
/// clock for clock, on ordinary, degenerate, one-pixel and sliver triangles.
#[test]
fn verilator_raster_equals_rust_hdl_raster() {
    use shadecore::cmd::raster::{parse_tri, walk_clocks_with, Engine};
    if !tools::require(
        &[Tool::Verilator],
        "verilator_raster_equals_rust_hdl_raster",
    ) {
        return;
    }
    for t in [
        "3,1,40,12,9,30",
        "10,10,20,10,30,10",
        "5,5,5,5,5,5",
        "0,0,4095,3,7,1",
        "100,0,0,60,200,61",
    ] {
        let tri = parse_tri(t).unwrap();
        let v = walk_clocks_with(&tri, Engine::Rtl, None, Sim::Verilator).unwrap();
        let r = walk_clocks_with(&tri, Engine::Rtl, None, Sim::RustHdl).unwrap();
        assert_eq!(v, r, "{t}: the Verilator run differs");
        println!("{t}: {} clocks identical", r.len());
    }
}

/// `raster --address four-triangle --sim verilator` gives the four-triangle block's per-clock
/// outputs of the rust-hdl run, clock for clock.
#[test]
fn verilator_four_triangle_raster_equals_rust_hdl() {
    use shadecore::cmd::raster::{four_clocks, parse_tri, Engine};
    if !tools::require(
        &[Tool::Verilator],
        "verilator_four_triangle_raster_equals_rust_hdl",
    ) {
        return;
    }
    for t in [
        "3,1,40,12,9,30",
        "10,10,20,10,30,10",
        "0,0,4095,3,7,1",
        "100,0,0,61,201,61",
    ] {
        let tri = parse_tri(t).unwrap();
        let v = four_clocks(&tri, Engine::Rtl, None, Sim::Verilator).unwrap();
        let r = four_clocks(&tri, Engine::Rtl, None, Sim::RustHdl).unwrap();
        assert_eq!(v, r, "{t}: the Verilator run differs");
        println!("{t}: {} clocks identical", r.len());
    }
}
