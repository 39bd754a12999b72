//! `pixel-stream` (the AXI4-Stream top): back-pressure keeps every fragment, in order, under
//! random and long stalls, in the rust-hdl simulation and in the exported Verilog; bad records
//! are dropped with `error`; with `m_axis_tready` always high the address block is never held.
//! (The generic tests — twin every clock, golden, Icarus, Verilator, lint — are the registry's.)

use flow::blocks::differential;
use flow::verilog::Simulator;
use golden::testing::seed_for;
use pipeline::axis::{Beat, Word};
use pipeline::lit::{register_record, scene_words, triangle_record};
use rtl::core::registry::{BlockParams, Options};
use rtl::pipelines::pixel_pipeline::PipelineParams;
use testbenches::registry::find;
use testbenches::stall::StallPattern;
use testbenches::stream::pixel_stream::{drive, reference_beats, scene, StreamRun};

fn params() -> (PipelineParams, Options) {
    let o = Options::new();
    (PipelineParams::from_options(&o).unwrap(), o)
}

/// The beats the RTL (rust-hdl) delivers for the run's input rows, and its `error` at the end.
fn rtl_beats(run: &StreamRun, o: &Options) -> (Vec<Beat>, bool) {
    let b = find("pixel-stream").unwrap();
    let out = b
        .simulate_on(o, &run.rows, flow::engine::fast_sim("pixel_stream"))
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
        .map(|(o, _)| Beat::read(o[2], o[3], o[4] != 0))
        .collect();
    (beats, out.last().unwrap()[5] != 0)
}

#[test]
fn back_pressure_keeps_every_fragment_in_order() {
    let seed = seed_for("back_pressure_keeps_every_fragment_in_order");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let (p, o) = params();
    let (jobs, regs) = scene(seed, 10);
    let words = scene_words(&jobs, &regs);
    let reference = reference_beats(&p, &jobs, &regs);
    let pixels = reference.iter().filter(|b| b.pixel).count();
    assert!(pixels > 500, "a scene worth stalling: {pixels} fragments");
    assert_eq!(reference.iter().filter(|b| b.last).count(), jobs.len());
    for (label, stall_p, gap) in [
        ("random 25 %", 0.25, 0.1),
        ("random 60 %", 0.6, 0.3),
        ("random 90 %", 0.9, 0.0),
    ] {
        let mut stalls = StallPattern::new(seed ^ label.len() as u64, stall_p);
        let run = drive(&p, &words, seed, gap, &mut stalls, 8);
        let (beats, error) = rtl_beats(&run, &o);
        assert!(!error, "{label}: no protocol error");
        assert_eq!(beats.len(), reference.len(), "{label}: beat count");
        assert!(
            beats == reference,
            "{label}: beats differ from the unstalled pipeline's"
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

/// A register record between triangles applies to the triangles after it only: it waits in
/// the load bank until every triangle before it has left the pipeline (its `done` counted),
/// so none of the first triangles' fragments takes the second set's colours.
#[test]
fn registers_apply_to_the_triangles_after_them() {
    let seed = seed_for("pixel_registers_apply_to_the_triangles_after_them");
    let (p, o) = params();
    let (jobs, regs) = scene(seed, 6);
    let half = jobs.len() / 2;
    let mut other = regs;
    other.n = 7;
    other.weights = [40, 300, 900, 12_000, 200, 7_000, 65_535, 100, 30_000];
    let mut words = register_record(&regs);
    jobs[..half]
        .iter()
        .for_each(|j| words.extend(triangle_record(j)));
    words.extend(register_record(&other));
    jobs[half..]
        .iter()
        .for_each(|j| words.extend(triangle_record(j)));
    let mut stalls = StallPattern::new(seed, 0.3);
    let run = drive(&p, &words, seed, 0.0, &mut stalls, 8);
    let (beats, error) = rtl_beats(&run, &o);
    assert!(!error);
    let mut want = reference_beats(&p, &jobs[..half], &regs);
    want.extend(reference_beats(&p, &jobs[half..], &other));
    assert_eq!(beats.len(), want.len(), "beat count");
    // A beat without a pixel carries only its `tlast` (its other fields are whatever the
    // pipeline's outputs hold then, which depends on what ran before).
    let same = |a: &Beat, b: &Beat| (a.pixel, a.last) == (b.pixel, b.last) && (!a.pixel || a == b);
    if let Some(i) = (0..want.len()).find(|&i| !same(&beats[i], &want[i])) {
        panic!("beat {i} is {:?}, want {:?}", beats[i], want[i]);
    }
    // The second set changes the colours (else the test shows nothing).
    assert!(
        reference_beats(&p, &jobs[half..], &regs) != reference_beats(&p, &jobs[half..], &other),
        "the two register sets give different colours"
    );
}

/// Long stretches: `tready` low for 3 000 clocks in the middle of a triangle, twice, and the
/// exported Verilog bit-exact with the rust-hdl simulation under that pattern (Verilator, in process).
#[test]
fn long_stalls_lose_nothing_and_the_verilog_agrees() {
    let seed = seed_for("long_stalls_lose_nothing_and_the_verilog_agrees");
    let (p, o) = params();
    let (jobs, regs) = scene(seed, 4);
    let words = scene_words(&jobs, &regs);
    let reference = reference_beats(&p, &jobs, &regs);
    // tready low over clocks 100..3100 and 4000..7000, and in a random 20 % besides.
    let mut random = StallPattern::new(seed, 0.2);
    let mut stalls = StallPattern::from_fn(move |c| {
        let r = random.next_stalled();
        (100..3100).contains(&c) || (4000..7000).contains(&c) || r
    });
    let run = drive(&p, &words, seed, 0.05, &mut stalls, 8);
    let (beats, error) = rtl_beats(&run, &o);
    assert!(!error);
    assert!(
        beats == reference,
        "beats differ from the unstalled pipeline's"
    );
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
    let b = find("pixel-stream").unwrap();
    let rep = differential(
        b,
        &o,
        &run.rows,
        Simulator::Verilator,
        "pixel-stream-long-stalls",
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
    let (p, o) = params();
    let (jobs, regs) = scene(seed, 2);
    let good: Vec<Word> = {
        let mut w = register_record(&regs);
        w.extend(triangle_record(&jobs[0]));
        w.extend(triangle_record(&jobs[1]));
        w
    };
    let reference = drive(&p, &good, seed, 0.0, &mut StallPattern::never(), 40).beats;
    let t = triangle_record(&jobs[0]);
    let mut unknown: Vec<Word> = vec![(3, false), (0xDEAD, false), (0xBEEF, true)];
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
        ("unknown type", &mut unknown),
        ("short", &mut short),
        ("long", &mut long),
        ("long by a whole record", &mut long_record),
        ("header only", &mut header_only.clone()),
    ] {
        let mut words = register_record(&regs);
        words.extend(bad.iter().copied());
        words.extend(triangle_record(&jobs[0]));
        words.extend(triangle_record(&jobs[1]));
        let run = drive(&p, &words, seed, 0.0, &mut StallPattern::new(seed, 0.3), 8);
        let (beats, error) = rtl_beats(&run, &o);
        assert!(error, "{label}: error set");
        assert!(beats == reference, "{label}: the good records' beats");
        println!(
            "{label}: dropped, error set, {} beats as without it",
            beats.len()
        );
    }
    let run = drive(&p, &good, seed, 0.0, &mut StallPattern::never(), 8);
    assert!(!rtl_beats(&run, &o).1, "no error on good records");
}

/// With `m_axis_tready` always high the address block is never held and every clock takes a
/// beat as soon as it is offered.
#[test]
fn tready_high_never_holds_the_address_block() {
    let seed = seed_for("tready_high_never_holds_the_address_block");
    let (p, _) = params();
    let (jobs, regs) = scene(seed, 30);
    let run = drive(
        &p,
        &scene_words(&jobs, &regs),
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
/// offered in clock t + `PixelStream::LATENCY` (both banks free, the address block idle,
/// `tready` high).
#[test]
fn latency_from_last_word_to_first_beat() {
    let (_, o) = params();
    let (jobs, regs) = scene(7, 1);
    let mut rows: Vec<Vec<u64>> = Vec::new();
    for (w, last) in register_record(&regs) {
        rows.push(vec![w as u64, 1, last as u64, 1]);
    }
    rows.extend(std::iter::repeat_n(vec![0, 0, 0, 1], 10));
    for (w, last) in triangle_record(&jobs[0]) {
        rows.push(vec![w as u64, 1, last as u64, 1]);
    }
    let last = rows.len() - 1;
    let latency = rtl::stream::pixel_stream::PixelStream::LATENCY;
    rows.extend(std::iter::repeat_n(vec![0, 0, 0, 1], latency + 10));
    let out = find("pixel-stream")
        .unwrap()
        .simulate_on(&o, &rows, flow::engine::fast_sim("pixel_stream"))
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
}

/// `rtl/README.md` shows the layout the table gives (`rtl::stream::layout::markdown`).
#[test]
fn readme_shows_the_generated_layout() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../rtl/README.md")).unwrap();
    assert!(
        readme.contains(&rtl::stream::layout::markdown()),
        "rtl/README.md's stream layout differs from rtl::stream::layout::markdown(): paste it\n{}",
        rtl::stream::layout::markdown()
    );
}

/// The layout table's fields are `pixel-pipeline`'s set-up and register ports: the same names
/// and widths, in port order (between `load` and `hold`).
#[test]
fn layout_fields_are_the_pipeline_ports() {
    use rtl::stream::layout::{REGISTERS, TRIANGLE};
    let (ins, _) = find("pixel-pipeline").unwrap().ports();
    let ports: Vec<(String, usize)> = ins.iter().map(|p| (p.name.to_string(), p.width)).collect();
    let fields: Vec<(String, usize)> = TRIANGLE
        .fields
        .iter()
        .chain(REGISTERS.fields)
        .map(|f| (f.name.to_string(), f.bits as usize))
        .collect();
    assert_eq!(ports.first().map(|p| p.0.as_str()), Some("load"));
    assert_eq!(ports.last().map(|p| p.0.as_str()), Some("hold"));
    assert_eq!(ports[1..ports.len() - 1], fields[..]);
}
