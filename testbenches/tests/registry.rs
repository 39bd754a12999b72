//! Generic tests over every block in the registry (`testbenches::registry::BLOCKS`): a block
//! that is registered gets all of them without a line of its own.
//!
//! - its bit-exact twin equals the RTL (its exported Verilog under Verilator, itself equal to
//!   the rust-hdl simulation on the first quarter of the clocks) on every port in every clock
//!   (seeded stimulus plus the block's edge rows), and the golden f64 model agrees within the
//!   format-derived bound;
//! - Yosys synthesizes it cleanly with the registry's multiplier count of SB_MAC16;
//! - its exported Verilog is bit-exact with the rust-hdl simulation under Icarus (the first
//!   parameter set) and Verilator;
//! - each parameter set it reads (`coeffs=published|fit`) builds and passes the above.
//!
//! Tests needing a tool skip with a notice when it is missing, and fail when `CI` is set.
//! `SHADECORE_SEED` replays or varies the seeds.

use flow::blocks::differential;
use flow::synth::check_and_map_ice40_dsp;
use flow::tools::{self, two_at_a_time, Tool};
use flow::verilog::Simulator;
use golden::testing::seed_for;
use rtl::core::registry::Options;
use testbenches::registry::{self, test_rows, Entry, BLOCKS};

/// Items of stimulus per block in the generic tests (triangles take 1000–2000 clocks each).
fn items(b: &dyn Entry) -> usize {
    match b.items() {
        // The AXI4-Stream tops: the pipeline inside each is a registered block, checked on its
        // own; the top adds the record packing and the handshake.
        "triangles" if b.name().ends_with("-stream") => 4,
        "triangles" => 12,
        // A span of up to 61 pixels takes up to 61 clocks; a line of up to 3 000 pixels (the
        // line units' benches) up to 3 000.
        "spans" | "lines" => 200,
        // A texture of up to 1 024 texels is written whole (every eighth spans the whole
        // memory, written sparsely) and read back: up to ~2 000 clocks each.
        "textures" => 40,
        _ => 3000,
    }
}

/// Every parameter set a block is tested with.
fn option_sets(b: &dyn Entry) -> Vec<Options> {
    b.test_sets()
}

/// The block's name and the values of the options it reads (`normalizer-fit`).
fn label(b: &dyn Entry, o: &Options) -> String {
    std::iter::once(b.name())
        .chain(b.param_keys().iter().filter_map(|k| o.get(k)))
        .collect::<Vec<_>>()
        .join("-")
}

/// Every registered block with every parameter set, and a label naming both.
/// `SHADECORE_BLOCK=name[,name…]` narrows the run to those blocks (for working on one block;
/// the full suite runs them all).
fn variants() -> Vec<(&'static dyn Entry, Options, String)> {
    let only: Option<Vec<String>> = std::env::var("SHADECORE_BLOCK")
        .ok()
        .map(|s| s.split(',').map(str::to_string).collect());
    if let Some(o) = &only {
        // Straight to stderr (libtest captures `eprintln!` of passing tests): a narrowed run
        // must never look like the whole registry passing.
        use std::io::Write;
        assert!(
            !tools::in_ci(),
            "SHADECORE_BLOCK={} narrows the registry tests to those blocks; CI must run them all",
            o.join(",")
        );
        let _ = writeln!(
            std::io::stderr(),
            "NARROWED: SHADECORE_BLOCK={} — the registry tests check only these blocks",
            o.join(",")
        );
    }
    BLOCKS
        .iter()
        .filter(|b| {
            only.as_ref()
                .is_none_or(|o| o.iter().any(|n| n == b.name()))
        })
        .flat_map(|b| {
            option_sets(*b)
                .into_iter()
                .map(|o| (*b, o.clone(), label(*b, &o)))
        })
        .collect()
}

/// The clocks of a variant's rows that rust-hdl runs when the Verilog under Verilator carries
/// the twin and golden checks: a quarter, at least 1 000 (all of them when fewer).
fn rust_hdl_clocks(rows: usize) -> usize {
    rows.div_ceil(4).max(1000).min(rows)
}

/// Every block and option set on its seeded stimulus then its edge rows, checked every clock
/// three ways: against the bit-exact twin (every port, exactly), against the golden model on
/// the stimulus's clocks (within the format-derived bounds, then RMS), and the exported Verilog
/// against the rust-hdl simulation. With Verilator (in process) the Verilog runs every row and
/// carries the twin and golden checks, and rust-hdl runs the first quarter of the rows
/// (`rust_hdl_clocks`), which must equal the Verilog's outputs every port every clock; the full
/// tier's Icarus test compares the two on the rows' edge rows too. Without Verilator, rust-hdl
/// runs every row and carries the twin and golden checks. A failure replays rust-hdl into a
/// VCD. Two blocks at a time.
#[test]
fn every_block_equals_its_twin_golden_and_verilog_every_clock() {
    let verilator = tools::require(
        &[Tool::Verilator],
        "every_block_equals_its_twin_golden_and_verilog_every_clock (the Verilog third)",
    );
    two_at_a_time(variants(), |(b, o, label)| {
        let name = format!("twin-{label}");
        let seed = seed_for(&name);
        let stim = b.stimulus(&o, items(b), seed).unwrap();
        let mut rows = stim.rows.clone();
        rows.extend(b.edge_rows(&o, seed).unwrap());
        assert!(rows.len() > 100);
        let (outputs, verilog) = if verilator {
            let v = b
                .simulate_on(&o, &rows, flow::engine::Sim::Verilator)
                .unwrap_or_else(|e| panic!("{label}: {e}"));
            let k = rust_hdl_clocks(rows.len());
            let r = b
                .simulate(&o, &rows[..k])
                .unwrap_or_else(|e| panic!("{label}: {e}"));
            flow::verilog::compare_outputs(&b.ports().1, &r, &v[..k]).unwrap_or_else(|e| {
                panic!(
                    "{label}: the Verilog under Verilator differs from rust-hdl: {e} (seed {seed})"
                )
            });
            (
                v,
                format!(
                    "; the Verilog under Verilator, equal to rust-hdl on the first {k} clocks, \
                             carries the checks"
                ),
            )
        } else {
            let rep = b
                .run_twin(&o, &rows, &name, seed)
                .unwrap_or_else(|f| panic!("{f}"));
            (rep.outputs, String::new())
        };
        let rep = b
            .check_twin(&o, &rows, &outputs, &name, seed)
            .unwrap_or_else(|f| panic!("{f}"));
        assert_eq!(rep.cycles as usize, rows.len());
        let golden = b
            .check_golden(&o, &stim, &outputs, &format!("golden-{label}"), seed)
            .unwrap_or_else(|f| panic!("{f}"));
        // Something was actually compared: the valid flag (output 0 or 1) every clock.
        assert!(golden
            .ports
            .iter()
            .all(|p| p.checked > 0 || p.name.contains("word")));
        println!(
            "[{name}] seed {seed}: {} clocks × {} ports bit-exact with the twin{verilog}\n{golden}",
            rep.cycles,
            rep.ports.len()
        );
    });
}

#[test]
fn registry_names_are_unique_and_lookups_fail_clearly() {
    let names: std::collections::HashSet<&str> = BLOCKS.iter().map(|b| b.name()).collect();
    assert_eq!(names.len(), BLOCKS.len());
    for b in BLOCKS {
        assert_eq!(registry::find(b.name()).unwrap().name(), b.name());
        assert!(b
            .module_name()
            .chars()
            .all(|c| c.is_ascii_lowercase() || c == '_'));
        let v = b.verilog(&Options::new()).unwrap();
        assert!(
            v.contains(&format!("module {}(", b.module_name())),
            "{}",
            b.name()
        );
        assert!(!v.contains("module top"), "{}", b.name());
        // Only blocks built from coefficients name them in their header.
        assert_eq!(
            v.contains("// Coefficients"),
            b.param_keys().contains(&"coeffs"),
            "{}",
            b.name()
        );
    }
    assert!(registry::find("nope")
        .err()
        .unwrap()
        .contains("expected one of"));
    assert_eq!(flow::blocks::select("all").unwrap().len(), BLOCKS.len());
    let o = Options::new().with("coeffs", "nope");
    let e = registry::find("normalizer")
        .unwrap()
        .check_options(&o)
        .unwrap_err();
    assert!(e.contains("unknown coefficient set"), "{e}");
}

#[test]
#[ignore = "full tier: Yosys over every block"]
fn yosys_checks_every_block_and_packs_its_multipliers() {
    if !tools::require(
        &[Tool::Yosys],
        "yosys_checks_every_block_and_packs_its_multipliers",
    ) {
        return;
    }
    // Every block and option set: the latch and `check -assert` checks on the elaborated
    // design, then `synth_ice40 -dsp` up to its multiplier packing, whose SB_MAC16 count must
    // be the declared one. The LUT mapping after it (two thirds of a whole map's time on a
    // large top) packs no multiplier and is left to `shadecore synth --block all` and to the iCE40 smoke
    // place-and-route below. Two Yosys runs at a time (one core each); each run has its own
    // directory, and every variant is checked even when one fails.
    //
    // A pipeline top wrapped whole by a stream top is synthesized inside it (its logic is the
    // stream's submodule, so synthesizing it alone would repeat that work);
    // here its declared multipliers must equal the stream's for every option set the stream
    // builds, and its Verilog must be part of the stream's (the stream has more modules); an
    // option set the stream refuses (`textured-pipeline`'s per-line builds) is synthesized on
    // its own. `shadecore synth --block` still synthesizes each on its own.
    let all = variants();
    let names: Vec<&str> = all.iter().map(|(b, _, _)| b.name()).collect();
    let mut skipped = Vec::new();
    let mut alone: Vec<(&str, Options)> = Vec::new();
    for (inner, outer) in registry::INSIDE_STREAM {
        if !(names.contains(&inner) && names.contains(&outer)) {
            continue;
        }
        let (i, s) = (
            registry::find(inner).unwrap(),
            registry::find(outer).unwrap(),
        );
        for o in i.test_sets() {
            if s.verilog(&o).is_err() {
                alone.push((inner, o));
                continue;
            }
            assert_eq!(
                i.multipliers_with(&o).unwrap(),
                s.multipliers_with(&o).unwrap(),
                "{inner} inside {outer}: multipliers for {o:?}"
            );
            let modules = |v: String| v.matches("\nmodule ").count();
            assert!(
                modules(s.verilog(&o).unwrap()) > modules(i.verilog(&o).unwrap()),
                "{outer} holds {inner}"
            );
        }
        skipped.push(inner);
    }
    println!("synthesized inside their stream tops: {skipped:?}, except the option sets {alone:?}");
    // The longest Verilog first, so that the two runners end together.
    let mut jobs: Vec<_> = all
        .into_iter()
        .filter(|(b, o, _)| {
            !skipped.contains(&b.name()) || alone.iter().any(|(n, a)| *n == b.name() && a == o)
        })
        .map(|(b, o, label)| {
            let v = b.verilog(&o).unwrap();
            (b, o, label, v)
        })
        .collect();
    jobs.sort_by_key(|j| std::cmp::Reverse(j.3.len()));
    let failures = std::sync::Mutex::new(Vec::<String>::new());
    two_at_a_time(jobs, |(b, o, label, v)| {
        let tag = format!("yosys-{label}");
        let fail = match check_and_map_ice40_dsp(&v, &b.module_name(), &tag) {
            Err(e) => Some(format!("{}: {e}", b.name())),
            Ok(rep) => {
                print!("{rep}");
                let want = b.multipliers_with(&o).unwrap() as u64;
                if rep.mac16() != want {
                    Some(format!(
                        "{label}: {} multipliers mapped to SB_MAC16, {want} declared",
                        rep.mac16()
                    ))
                } else if rep.ice40_total <= rep.mac16() {
                    Some(format!("{label}: empty netlist?"))
                } else {
                    None
                }
            }
        };
        failures.lock().unwrap().extend(fail);
    });
    let failures = failures.into_inner().unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Items of stimulus per block under each simulator: Verilator takes the generic tests' full
/// count; Icarus, an interpreter (17 min for the full count over every block on one core,
/// against Verilator's 9), a fifth of it. Both runs end with the block's edge rows, and the
/// seeds differ, so Icarus still sees its own stimulus every clock.
fn verilog_items(b: &dyn Entry, sim: Simulator) -> usize {
    match sim {
        Simulator::Verilator => items(b),
        Simulator::Icarus => (items(b) / 5).max(3),
    }
}

/// The Verilog of each block's first option set under `sim`, bit-exact with rust-hdl on its own
/// seeded rows. The everyday tier runs every option set under Verilator; a construct that only
/// another set has is checked under Verilator alone.
fn verilog_bit_exact(sim: Simulator, test: &str) {
    if !tools::require(sim.tools(), test) {
        return;
    }
    let mut seen = std::collections::HashSet::new();
    let firsts: Vec<_> = variants()
        .into_iter()
        .filter(|(b, _, _)| seen.insert(b.name()))
        .collect();
    // A pipeline top whose stream top wraps it whole and runs here with the same option set:
    // the stream's run simulates the pipeline's Verilog as its submodule (under Verilator the
    // everyday tier runs both).
    let names: Vec<&str> = firsts.iter().map(|(b, _, _)| b.name()).collect();
    let (inside, firsts): (Vec<_>, Vec<_>) = firsts.into_iter().partition(|(b, o, _)| {
        registry::wrapped_by_tested_stream(b.name(), o).is_some_and(|outer| {
            names.contains(&outer) && registry::find(outer).unwrap().test_sets().first() == Some(o)
        })
    });
    println!(
        "run inside their stream tops: {:?}",
        inside.iter().map(|(_, _, l)| l).collect::<Vec<_>>()
    );
    // Two blocks at a time (a simulator process each); every block runs even when one fails.
    let failures = std::sync::Mutex::new(Vec::<String>::new());
    two_at_a_time(firsts, |(b, o, label)| {
        let name = format!("{test}-{label}");
        let seed = seed_for(&name);
        let rows = test_rows(b, &o, verilog_items(b, sim), seed).unwrap();
        match differential(b, &o, &rows, sim, &name) {
            Ok(rep) => println!(
                "[{name}] {:?}: bit-exact over {} clocks × {} ports",
                sim, rep.cycles, rep.ports
            ),
            Err(e) => failures
                .lock()
                .unwrap()
                .push(format!("{label}: {e} (seed {seed})")),
        }
    });
    let failures = failures.into_inner().unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
#[ignore = "full tier: Icarus over every block (its first option set)"]
fn every_block_verilog_is_bit_exact_under_icarus() {
    verilog_bit_exact(Simulator::Icarus, "icarus_bit_exact");
}

/// The latencies the registry states are what the RTL does: one fixed triangle, loaded in
/// clock 0; its first row has pixels.
#[test]
fn triangle_block_latencies_match_the_rtl() {
    use golden::types::{Plane, ScreenTriangle};
    use pipeline::gouraud::{pipe_row, TriangleJob};
    use rtl::core::sim::simulate_rows;
    use rtl::pipelines::gouraud_raster::GouraudRaster;
    use rtl::units::address_block::AddressBlock;
    use rtl::units::intensity_interpolator::IntensityInterpolator;
    use testbenches::units::address_block::address_run;
    use testbenches::units::intensity_interpolator::{bvi_rows, pipe_rows};
    let t = ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
    let ramp = |c: f64| Plane { a: 1.0, b: 2.0, c };
    let job = TriangleJob::new(&t, &[ramp(10.0), ramp(20.0), ramp(30.0)]);
    let first = |outs: &[Vec<u64>], k: usize| outs.iter().position(|o| o[k] != 0);
    let lat = |name: &str| registry::find(name).unwrap().latency();

    let (rows, _, _) = address_run(&[job]);
    assert_eq!(rows[0][0], 1, "loaded in clock 0");
    let outs = simulate_rows(AddressBlock::default(), &rows).unwrap();
    // Outputs: ready, valid, x, y, step, line_start, row_start, carry, done.
    assert_eq!(first(&outs, 6), Some(lat("address-block")));
    assert_eq!(first(&outs, 1), Some(lat("address-block")));

    let rows = pipe_rows(&[job]);
    assert_eq!(rows[0], pipe_row(Some(&job)), "loaded in clock 0");
    let outs = simulate_rows(GouraudRaster::default(), &rows).unwrap();
    assert_eq!(first(&outs, 1), Some(lat("gouraud-raster")));

    // BVI: valid_out is the event's valid (input 13) delayed by the latency, every clock.
    let (rows, _) = bvi_rows(&[job]);
    let outs = simulate_rows(IntensityInterpolator::default(), &rows).unwrap();
    let l = lat("intensity-interpolator");
    assert!(rows.iter().any(|r| r[13] != 0));
    for c in l..rows.len() {
        assert_eq!(outs[c][0], rows[c - l][13], "clock {c}");
    }
}

/// `shadecore-sim` on every block: a checked run and a VCD declaring every port with its
/// width; and the check can fail (the first valid clock's expectation altered: a word + 1, or
/// a real + 2 LSB of its format).
#[test]
fn every_block_simulates_and_the_check_can_fail() {
    let seed = seed_for("blocks_sim");
    println!("[blocks_sim] seed {seed}");
    // Two blocks at a time.
    two_at_a_time(BLOCKS.iter(), |b| {
        simulates_and_fails(*b, seed);
    });
}

/// `every_block_simulates_and_the_check_can_fail` for one block.
fn simulates_and_fails(b: &dyn Entry, seed: u64) {
    use testbenches::harness::{target_dir, Expected};
    use testbenches::registry::sim_stimulus_to_vcd;
    let o = Options::new();
    // Enough for valid outputs (the first valid clock is the one altered below); the long
    // runs are the twin and golden tests'. The run stops 64 clocks after the first clock the
    // golden model expects valid: a whole item of a stream top is thousands of clocks, run
    // three times here (twin, VCD, the failure's replay).
    let n = if b.items() == "triangles" { 1 } else { 2 };
    let mut stim = b.stimulus(&o, n, seed).unwrap();
    let (ins, outs) = b.ports();
    let valid = outs
        .iter()
        // A lane's flag (`l0_valid`) where the block has lanes.
        .position(|p| testbenches::harness::is_valid_port(p.name))
        .unwrap();
    let first = stim
        .expected
        .iter()
        .position(|e| e[valid] == Expected::Word(1))
        .unwrap_or_else(|| panic!("{}: no valid clock expected", b.name()));
    let cut = (first + 64).min(stim.rows.len());
    stim.rows.truncate(cut);
    stim.expected.truncate(cut);
    let vcd = target_dir()
        .join("sims")
        .join(format!("test-blocks-{}.vcd", b.name()));
    let out = sim_stimulus_to_vcd(b, &o, &stim, seed, &vcd)
        .unwrap_or_else(|e| panic!("{}: {e}", b.name()));
    let vars = flow::vcd_check::variables(&vcd).unwrap();
    for p in ins.iter().chain(&outs) {
        let full = format!("uut.{}", p.name);
        assert!(
            vars.iter()
                .any(|(n, w)| *n == full && *w as usize == p.width),
            "{}: {full} ({} bits) missing from the VCD",
            b.name(),
            p.width
        );
    }
    let pixels = out.report.outputs.iter().filter(|o| o[valid] != 0).count();
    assert!(
        pixels > 0,
        "{}: nothing valid in {} clocks",
        b.name(),
        out.report.cycles
    );

    // Alter the expectation of the first checked data port in the first valid clock.
    let clock = first;
    let port = (0..outs.len())
        .find(|&k| {
            k != valid
                && stim.expected[clock][k] != Expected::DontCare
                && !outs[k].name.contains("ready")
        })
        .unwrap();
    // Beyond the clock's tolerance (the port's, or the clock's own bound) by two LSBs (at
    // least 10⁻³).
    let (tol, margin) = match stim.compare[port] {
        testbenches::harness::Compare::Fixed { format, tol } => {
            (tol.max_abs, 2.0 * format.lsb().max(1e-3))
        }
        testbenches::harness::Compare::Exact => (0.0, 1.0),
    };
    stim.expected[clock][port] = match stim.expected[clock][port] {
        Expected::Word(w) => Expected::Word(w + 1),
        Expected::Real(v) => Expected::Real(v + tol + margin),
        Expected::Within(v, b) => Expected::Within(v + b.min(tol) + margin, b),
        Expected::DontCare => unreachable!(),
    };
    let f = b
        .check_golden(
            &o,
            &stim,
            &out.report.outputs,
            &format!("blocks-mutant-{}", b.name()),
            seed,
        )
        .expect_err("an altered expectation must fail");
    assert_eq!(f.cycle as usize, clock, "{}", b.name());
    assert_eq!(f.signal, outs[port].name, "{}", b.name());
}

/// `shadecore-sim` streams: 2 × default + 1 items go in three batches back to back through
/// one simulation (no reset between them), checked every clock against the twin and the
/// golden model, the VCD written as the clocks go; only per-port statistics are kept.
#[test]
fn every_block_streams_batches_back_to_back() {
    use testbenches::harness::target_dir;
    let seed = seed_for("blocks_stream");
    println!("[blocks_stream] seed {seed}");
    for b in BLOCKS {
        let n = 2 * b.default_items() + 1;
        // The VCD of every signal is large (the pixel pipeline's three batches: about 600 MB):
        // written for two small blocks, and removed after.
        let vcd = ["normalizer", "address-block"]
            .contains(&b.name())
            .then(|| {
                let dir = target_dir().join("sims");
                std::fs::create_dir_all(&dir).unwrap();
                dir.join(format!("test-stream-{}.vcd", b.name()))
            });
        let mut seen = 0;
        let r = b
            .sim_stream(
                &Options::new(),
                n,
                seed,
                vcd.as_deref(),
                // The VCD needs rust-hdl; the other blocks' three batches run in process.
                if vcd.is_some() {
                    flow::engine::Sim::RustHdl
                } else {
                    flow::engine::fast_sim("every_block_streams_batches_back_to_back")
                },
                &mut |_| seen += 1,
            )
            .unwrap_or_else(|e| panic!("{}: {e}", b.name()));
        assert_eq!((r.batches, seen), (3, 3), "{}", b.name());
        assert!(r.valid_clocks > 0, "{}: nothing valid", b.name());
        let size = vcd.as_ref().map(|v| {
            let size = std::fs::metadata(v).unwrap().len();
            assert!(size > 100_000, "{}: VCD of {size} bytes", b.name());
            let _ = std::fs::remove_file(v);
            size
        });
        println!(
            "{}: {n} {} in {} clocks, {} valid{}",
            b.name(),
            b.items(),
            r.cycles,
            r.valid_clocks,
            size.map_or(String::new(), |s| format!("; VCD {} kB", s / 1024))
        );
    }
}

/// One smoke place-and-route on ECP5: the normalizer through Yosys `synth_ecp5` and
/// nextpnr-ecp5 on the LFE5U-25F, placed, timed (a critical path that matches the Fmax) and its
/// multipliers mapped to MULT18X18D. Every block's figures come from `shadecore synth --block
/// all --target ecp5`, not from tests.
#[test]
#[ignore = "full tier: nextpnr-ecp5"]
fn ecp5_smoke_place_and_route() {
    use flow::synth::require_ecp5;
    if !require_ecp5("ecp5_smoke_place_and_route") {
        return;
    }
    ecp5_runs(
        std::iter::once(("normalizer", Options::new(), "", false)),
        "25k",
    );
}

/// One smoke place-and-route on iCE40: the normalizer through Yosys `synth_ice40 -dsp` and
/// nextpnr-ice40 on the UP5K: it fits, its multipliers are SB_MAC16, and it routes with an
/// Fmax in a plausible range. Every block's figures come from `shadecore synth --block all`.
#[test]
#[ignore = "full tier: Yosys and nextpnr-ice40"]
fn ice40_smoke_place_and_route() {
    if !tools::require(
        &[Tool::Yosys, Tool::NextpnrIce40],
        "ice40_smoke_place_and_route",
    ) {
        return;
    }
    let b = registry::find("normalizer").unwrap();
    let (rep, placement) = flow::blocks::synth_block(b, &Options::new(), true).unwrap();
    println!("{rep}\n{placement:?}");
    assert_eq!(rep.mac16() as usize, b.multipliers());
    match placement {
        flow::blocks::Placement::Fmax(mhz) => assert!(mhz > 10.0 && mhz < 300.0, "{mhz} MHz"),
        other => panic!("the normalizer did not place on the UP5K: {other:?}"),
    }
}

/// Places and times each (block, options, label suffix, held to 100 MHz) on `part`, the
/// smallest die that holds it, and checks the report.
fn ecp5_runs<'a>(runs: impl Iterator<Item = (&'a str, Options, &'a str, bool)>, part: &str) {
    use flow::synth::ecp5;
    for (name, o, variant, held) in runs {
        let b = registry::find(name).unwrap();
        let v = b.verilog(&o).unwrap();
        let label = format!("{name}{variant}");
        let r = ecp5(
            &v,
            &b.module_name(),
            &b.ports(),
            None,
            &format!("test-ecp5-{label}"),
        )
        .unwrap_or_else(|e| panic!("{label}: {e}"));
        println!("{label}: {r}");
        assert_eq!(r.part.device, part, "{label}: not on the smallest part");
        let mhz = r
            .fmax
            .unwrap_or_else(|| panic!("{label}: not placed: {:?}", r.unplaced));
        assert!(mhz > 20.0 && mhz < 500.0, "{label}: {mhz} MHz");
        if held {
            assert!(
                mhz >= 100.0,
                "{label}: {mhz} MHz, below the 100 MHz bar: {r}"
            );
        }
        let path = r.critical.as_ref().expect("critical path parsed");
        assert!(
            !path.signals.is_empty() && (path.ns - 1000.0 / mhz).abs() < 0.2,
            "{label}: critical path {path} vs {mhz} MHz"
        );
        assert!(r.luts() > 50, "{label}: {} LUT4", r.luts());
        if part == "45k" {
            // Every multiplier placed has its registers inside (the mapping reached them all).
            assert!(
                r.dsp_mapped as u64 >= r.mult18(),
                "{label}: {} products mapped for {} MULT18X18D",
                r.dsp_mapped,
                r.mult18()
            );
        }
        assert_eq!(
            r.mult18() as usize,
            b.multipliers_with(&o).unwrap(),
            "{label}: 16×16 products map to MULT18X18D"
        );
    }
}
