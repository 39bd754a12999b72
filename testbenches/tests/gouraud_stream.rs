//! `gouraud-stream` (the AXI4-Stream top of the Gouraud raster pipe): back-pressure keeps every
//! fragment, in order, under random and long stalls, in the rust-hdl simulation and in the
//! exported Verilog; the fragments are `gouraud-raster`'s own (its RTL stepped without a
//! stream) and the golden planes' (addresses exact, colours within 1 LSB); bad records are
//! dropped with `error`; with `m_axis_tready` always high the address block is never held.
//! (The generic tests — twin every clock, golden, Icarus, Verilator, lint — are the registry's.)

use flow::blocks::differential;
use flow::verilog::Simulator;
use golden::shade::to_u8;
use golden::testing::seed_for;
use pipeline::axis::{Beat, Word};
use pipeline::gouraud::{gouraud_record, gouraud_words};
use pipeline::gouraud::{Pipe, TriangleJob};
use rtl::core::registry::Options;
use testbenches::registry::find;
use testbenches::stall::StallPattern;
use testbenches::stream::gouraud_stream::{drive, reference_beats, scene, GouraudStreamRun};

/// The beats the RTL (rust-hdl) delivers for the run's input rows, and its `error` at the end.
fn rtl_beats(run: &GouraudStreamRun) -> (Vec<Beat>, bool) {
    let b = find("gouraud-stream").unwrap();
    let out = b
        .simulate_on(
            &Options::new(),
            &run.rows,
            flow::engine::fast_sim("gouraud_stream"),
        )
        .unwrap();
    // The twin that made the rows (record reader, banks, FIFO, hold) agrees every clock,
    // bad records and stalls included.
    if let Some(c) = (0..out.len()).find(|&c| out[c] != run.outputs[c]) {
        panic!(
            "the RTL differs from the twin at clock {c}: {:?} against {:?}",
            out[c], run.outputs[c]
        );
    }
    let beats = out
        .iter()
        .zip(&run.rows)
        .filter(|(o, r)| o[1] != 0 && r[3] != 0)
        .map(|(o, _)| Beat::read(o[2], 0, o[3] != 0))
        .collect();
    (beats, out.last().unwrap()[4] != 0)
}

/// A fragment with its triangle's index (the number of triangle ends before it).
type Fragment = (usize, u32, u32, [u8; 3]);

/// The fragments of a beat stream.
fn fragments(beats: &[Beat]) -> Vec<Fragment> {
    let mut tri = 0;
    let mut out = Vec::new();
    for b in beats {
        if b.pixel {
            out.push((tri, b.x, b.y, b.rgb));
        }
        tri += b.last as usize;
    }
    out
}

/// `gouraud-raster`'s RTL run on `jobs` through its own ports (no stream, no hold), as
/// fragments (the render driver's `Pipe`).
fn raster_fragments(jobs: &[TriangleJob]) -> Vec<Fragment> {
    let mut pipe = Pipe::new().unwrap();
    let mut out = Vec::new();
    let st = pipe
        .run(
            jobs,
            pipeline::gouraud::clock_budget(jobs),
            |k, x, y, rgb| out.push((k, x, y, rgb)),
            |_| {},
        )
        .unwrap();
    assert_eq!(st.triangles, jobs.len() as u64);
    out
}

/// The stream's fragments are `gouraud-raster`'s (its RTL stepped through its own ports) and
/// the golden planes' (colours within 1 LSB of the f64 value rounded, as the raster's bench
/// requires), under back-pressure.
#[test]
fn fragments_are_the_raster_pipes_and_the_golden_planes() {
    let seed = seed_for("fragments_are_the_raster_pipes_and_the_golden_planes");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let (jobs, golden) = scene(seed, 12);
    let mut stalls = StallPattern::new(seed, 0.4);
    let run = drive(&gouraud_words(&jobs), seed, 0.1, &mut stalls, 8);
    let (beats, error) = rtl_beats(&run);
    assert!(!error);
    let got = fragments(&beats);
    let want = raster_fragments(&jobs);
    assert_eq!(got.len(), want.len(), "fragment count");
    assert!(got == want, "fragments differ from gouraud-raster's");
    assert_eq!(got.len(), golden.len(), "one fragment per golden pixel");
    let mut worst = 0i32;
    for ((_, x, y, rgb), (v, _)) in got.iter().zip(&golden) {
        for c in 0..3 {
            let d = (rgb[c] as i32 - to_u8(v[c]) as i32).abs();
            assert!(
                d <= 1,
                "({x}, {y}) channel {c}: {} against golden {}",
                rgb[c],
                v[c]
            );
            worst = worst.max(d);
        }
    }
    println!(
        "{} fragments of {} triangles equal gouraud-raster's; max {worst} LSB from the golden planes",
        got.len(),
        jobs.len()
    );
}

#[test]
fn back_pressure_keeps_every_fragment_in_order() {
    let seed = seed_for("back_pressure_keeps_every_fragment_in_order");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let (jobs, _) = scene(seed, 12);
    let words = gouraud_words(&jobs);
    let reference = reference_beats(&jobs);
    let pixels = reference.iter().filter(|b| b.pixel).count();
    assert!(pixels > 500, "a scene worth stalling: {pixels} fragments");
    assert_eq!(reference.iter().filter(|b| b.last).count(), jobs.len());
    for (label, stall_p, gap) in [
        ("random 25 %", 0.25, 0.1),
        ("random 60 %", 0.6, 0.3),
        ("random 90 %", 0.9, 0.0),
    ] {
        let mut stalls = StallPattern::new(seed ^ label.len() as u64, stall_p);
        let run = drive(&words, seed, gap, &mut stalls, 8);
        let (beats, error) = rtl_beats(&run);
        assert!(!error, "{label}: no protocol error");
        assert_eq!(beats.len(), reference.len(), "{label}: beat count");
        assert!(
            beats == reference,
            "{label}: beats differ from the unstalled pipe's"
        );
        assert!(run.held > 0, "{label}: the address block was held");
        println!(
            "{label}: {} beats in {} clocks, consumer stalled {} clocks, address block held {}",
            beats.len(),
            run.rows.len(),
            run.consumer_stalls,
            run.held
        );
    }
}

/// Long stretches: `tready` low for 3 000 clocks in the middle of a triangle, twice, and the
/// exported Verilog bit-exact with the rust-hdl simulation under that pattern (Verilator, in process).
#[test]
fn long_stalls_lose_nothing_and_the_verilog_agrees() {
    let seed = seed_for("long_stalls_lose_nothing_and_the_verilog_agrees");
    let (jobs, _) = scene(seed, 6);
    let words = gouraud_words(&jobs);
    let reference = reference_beats(&jobs);
    let mut random = StallPattern::new(seed, 0.2);
    let mut stalls = StallPattern::from_fn(move |c| {
        let r = random.next_stalled();
        (100..3100).contains(&c) || (4000..7000).contains(&c) || r
    });
    let run = drive(&words, seed, 0.05, &mut stalls, 8);
    let (beats, error) = rtl_beats(&run);
    assert!(!error);
    assert!(beats == reference, "beats differ from the unstalled pipe's");
    assert!(run.held > 5000, "held {} clocks", run.held);
    println!(
        "{} beats in {} clocks; consumer stalled {}, address block held {}",
        beats.len(),
        run.rows.len(),
        run.consumer_stalls,
        run.held
    );
    if !Simulator::Verilator.require("long_stalls_lose_nothing_and_the_verilog_agrees") {
        return;
    }
    let b = find("gouraud-stream").unwrap();
    let rep = differential(
        b,
        &Options::new(),
        &run.rows,
        Simulator::Verilator,
        "gouraud-stream-long-stalls",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    println!(
        "Verilator bit-exact: {} clocks × {} ports",
        rep.cycles, rep.ports
    );
}

/// Records of an unknown type, too short or too long are dropped whole and set `error`; the
/// records around them are unaffected.
#[test]
fn bad_records_are_dropped_with_error() {
    let seed = seed_for("bad_records_are_dropped_with_error");
    let (jobs, _) = scene(seed, 2);
    let good = gouraud_words(&jobs);
    let reference = reference_beats(&jobs);
    let t = gouraud_record(&jobs[0]);
    let unknown: Vec<Word> = vec![(2, false), (0xDEAD, false), (0xBEEF, true)];
    let mut short: Vec<Word> = t[..10].to_vec();
    short.last_mut().unwrap().1 = true;
    let mut long: Vec<Word> = t.clone();
    long.last_mut().unwrap().1 = false;
    long.extend([(0x1234, false), (0x5678, true)]);
    // Longer by a whole well-formed record: dropped with the rest, not taken.
    let mut long_record: Vec<Word> = t.clone();
    long_record.last_mut().unwrap().1 = false;
    long_record.extend(t.iter().copied());
    let header_only: Vec<Word> = vec![(1, true)];
    for (label, bad) in [
        ("unknown type", &unknown),
        ("short", &short),
        ("long", &long),
        ("long by a whole record", &long_record),
        ("header only", &header_only),
    ] {
        let mut words = bad.clone();
        words.extend(good.iter().copied());
        let run = drive(&words, seed, 0.0, &mut StallPattern::new(seed, 0.3), 8);
        let (beats, error) = rtl_beats(&run);
        assert!(error, "{label}: error set");
        assert!(beats == reference, "{label}: the good records' beats");
        println!(
            "{label}: dropped, error set, {} beats as without it",
            beats.len()
        );
    }
    let run = drive(&good, seed, 0.0, &mut StallPattern::never(), 8);
    assert!(!rtl_beats(&run).1, "no error on good records");
}

/// With `m_axis_tready` always high the address block is never held, and the stream takes as
/// many clocks per fragment as the raster pipe alone where the walks outlast the set-up.
#[test]
fn tready_high_never_holds_the_address_block() {
    let seed = seed_for("tready_high_never_holds_the_address_block");
    let (jobs, _) = scene(seed, 30);
    let run = drive(
        &gouraud_words(&jobs),
        seed,
        0.0,
        &mut StallPattern::never(),
        8,
    );
    assert_eq!(run.held, 0);
    println!(
        "{} beats in {} clocks, never held",
        run.beats.len(),
        run.rows.len()
    );
}

/// The header's latency: a triangle record's last word accepted in clock t, its first beat
/// offered in clock t + `GouraudStream::LATENCY` (both banks free, the address block idle,
/// `tready` high).
#[test]
fn latency_from_last_word_to_first_beat() {
    // A triangle with a pixel on its first row.
    let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
    let job = TriangleJob::gouraud(&t, &golden::shade::ShadeContext::default()).unwrap();
    let mut rows: Vec<Vec<u64>> = vec![vec![0, 0, 0, 1]; 5];
    for (w, last) in gouraud_record(&job) {
        rows.push(vec![w as u64, 1, last as u64, 1]);
    }
    let last = rows.len() - 1;
    let latency = rtl::stream::gouraud_stream::GouraudStream::LATENCY;
    rows.extend(std::iter::repeat_n(vec![0, 0, 0, 1], latency + 10));
    let out = find("gouraud-stream")
        .unwrap()
        .simulate_on(
            &Options::new(),
            &rows,
            flow::engine::fast_sim("gouraud_stream"),
        )
        .unwrap();
    assert!(
        out[..=last]
            .iter()
            .zip(&rows)
            .all(|(o, r)| r[1] == 0 || o[0] != 0),
        "every word accepted when shown"
    );
    let first = (0..out.len()).find(|&c| out[c][1] != 0).unwrap();
    assert_eq!(first - last, latency);
    assert!(
        Beat::read(out[first][2], 0, false).pixel,
        "the first beat is a fragment"
    );
}

/// The layout's fields are `gouraud-raster`'s set-up ports: the same names and widths, in
/// port order (between `load` and `hold`).
#[test]
fn layout_fields_are_the_raster_ports() {
    use rtl::stream::layout::GOURAUD_TRIANGLE;
    let (ins, _) = find("gouraud-raster").unwrap().ports();
    let ports: Vec<(String, usize)> = ins.iter().map(|p| (p.name.to_string(), p.width)).collect();
    let fields: Vec<(String, usize)> = GOURAUD_TRIANGLE
        .fields
        .iter()
        .map(|f| (f.name.to_string(), f.bits as usize))
        .collect();
    assert_eq!(ports.first().map(|p| p.0.as_str()), Some("load"));
    assert_eq!(ports.last().map(|p| p.0.as_str()), Some("hold"));
    assert_eq!(ports[1..ports.len() - 1], fields[..]);
}

/// The measurement, as a test: on the LFE5U-25F in its CABGA256 package (197 user
/// I/O), `gouraud-raster` with its flat set-up ports does not place (more pins than the
/// package has), while `gouraud-stream` places and routes on its own pins and keeps ≥ 100 MHz.
#[test]
#[ignore = "full tier: nextpnr-ecp5 on a package's pins"]
fn the_stream_top_places_on_its_own_pins_and_the_flat_top_does_not() {
    use flow::synth::{ecp5_on_pins, require_ecp5, ECP5_PARTS};
    let what = "the_stream_top_places_on_its_own_pins_and_the_flat_top_does_not";
    if !require_ecp5(what) {
        return;
    }
    let part = ECP5_PARTS[0];
    assert_eq!(part.package, "CABGA256");
    let o = Options::new();
    let mut seen = Vec::new();
    for name in ["gouraud-raster", "gouraud-stream"] {
        let b = find(name).unwrap();
        let r = ecp5_on_pins(
            &b.verilog(&o).unwrap(),
            &b.module_name(),
            &b.ports(),
            part,
            &format!("pins-{name}"),
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        println!(
            "{name}: {} pins on {} ({}): {}",
            r.pins,
            part.name,
            part.package,
            match (&r.fmax, &r.unplaced) {
                (Some(f), _) => format!("placed and routed, {f:.1} MHz"),
                (None, Some(why)) => format!("not placed: {why}"),
                _ => "?".into(),
            }
        );
        seen.push(r);
    }
    let (flat, stream) = (&seen[0], &seen[1]);
    assert!(flat.pins > 197, "gouraud-raster: {} pins", flat.pins);
    // Refused before nextpnr: more pins than the package's user I/O (nextpnr-ecp5 itself ran
    // out of the die's I/O sites: "no BELs remaining to implement cell type 'TRELLIS_IO'").
    assert!(
        flat.unplaced
            .as_deref()
            .is_some_and(|w| w.contains("727 pins, but the CABGA256 package has 197 user I/O")),
        "gouraud-raster should not fit the package's I/O: {:?}",
        flat.unplaced
    );
    assert_eq!(stream.pins, 104, "gouraud-stream's pins");
    let mhz = stream
        .fmax
        .unwrap_or_else(|| panic!("gouraud-stream did not place: {:?}", stream.unplaced));
    assert!(mhz >= 100.0, "gouraud-stream on its pins: {mhz} MHz");
}
