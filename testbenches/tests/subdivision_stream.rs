//! `subdivision-stream` (the AXI4-Stream top of the subdivision raster pipe): back-pressure on
//! any of the four lanes keeps every fragment, in order, under random and long stalls, in the
//! rust-hdl simulation and in the exported Verilog; the fragments are `subdivision-raster`'s
//! own (its RTL stepped through its ports by the render driver) and the golden sub-triangle
//! planes' (addresses exact, colours within 1 LSB); bad records are dropped with `error`; with
//! every `tready` high the four-triangle block is never held; the header's latency. (The
//! generic tests — twin every clock, golden, Icarus, Verilator, lint — are the registry's.)

use flow::blocks::differential;
use flow::verilog::Simulator;
use golden::shade::to_u8;
use golden::testing::seed_for;
use golden::units::four_triangle::LANES;
use pipeline::axis::{Beat, Word};
use pipeline::subdivision::{clock_budget, SubJob, SubPipe};
use pipeline::subdivision::{subdivision_record, subdivision_words};
use rtl::core::registry::Options;
use rtl::stream::fragment_fifo::FIFO_DEPTH;
use testbenches::registry::find;
use testbenches::stall::StallPattern;
use testbenches::stream::subdivision_stream::{
    drive, reference_beats, scene, stalls, SubdivisionStreamRun, INPUTS, OUTPUTS,
};

/// Each lane's beats the RTL (rust-hdl) delivers for the run's input rows, and its `error` at
/// the end.
fn rtl_beats(run: &SubdivisionStreamRun) -> ([Vec<Beat>; LANES], bool) {
    let out = find("subdivision-stream")
        .unwrap()
        .simulate_on(
            &Options::new(),
            &run.rows,
            flow::engine::fast_sim("subdivision_stream"),
        )
        .unwrap();
    // The twin that made the rows (record reader, banks, FIFOs, hold) agrees every clock, bad
    // records and stalls included.
    if let Some(c) = (0..out.len()).find(|&c| out[c] != run.outputs[c]) {
        panic!(
            "the RTL differs from the twin at clock {c}: {:?} against {:?}",
            out[c], run.outputs[c]
        );
    }
    let lane = |k: usize| {
        let at = 1 + 3 * k;
        out.iter()
            .zip(&run.rows)
            .filter(|(o, r)| o[at] != 0 && r[3 + k] != 0)
            .map(|(o, _)| Beat::read(o[at + 1], 0, o[at + 2] != 0))
            .collect()
    };
    (
        std::array::from_fn(lane),
        out.last().unwrap()[OUTPUTS - 1] != 0,
    )
}

/// A fragment: its parent's index (the `tlast`s before it on its lane), lane, x, y, rgb.
type Fragment = (usize, usize, u32, u32, [u8; 3]);

/// Every lane's fragments (beats with `pixel`), numbered by parent; every lane has one `tlast`
/// per parent.
fn fragments(beats: &[Vec<Beat>; LANES], parents: usize) -> Vec<Fragment> {
    let mut f = Vec::new();
    for (k, lane) in beats.iter().enumerate() {
        let mut parent = 0;
        for b in lane {
            if b.pixel {
                f.push((parent, k, b.x, b.y, b.rgb));
            }
            parent += b.last as usize;
        }
        assert_eq!(parent, parents, "lane {k}: one tlast per parent");
    }
    f
}

/// The stream's fragments are `subdivision-raster`'s (its RTL stepped through its own ports by
/// the render driver) and the golden sub-triangle planes' (colours within 1 LSB of the f64
/// value rounded, the raster pipe's bench's bound), under independent back-pressure on the
/// four lanes.
#[test]
fn fragments_are_the_raster_pipes_and_the_golden_planes() {
    let seed = seed_for("subdivision_fragments_are_the_raster_pipes_and_the_golden_planes");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let scene = scene(seed, 10);
    let jobs: Vec<SubJob> = scene.iter().map(|j| j.0).collect();
    let run = drive(
        &subdivision_words(&jobs),
        seed,
        0.1,
        &mut stalls(seed, 0.4),
        8,
    );
    let (beats, error) = rtl_beats(&run);
    assert!(!error);
    let got = fragments(&beats, jobs.len());
    // The pipe through its ports (the render driver does not say which lane a pixel came
    // from: compare (parent, x, y, rgb) as sorted lists).
    let mut want = Vec::new();
    let st = SubPipe::new()
        .unwrap()
        .run(
            &jobs,
            clock_budget(&jobs),
            |k, x, y, rgb| want.push((k, x, y, rgb)),
            |_| {},
        )
        .unwrap();
    assert_eq!(st.triangles, jobs.len() as u64);
    let mut ours: Vec<_> = got.iter().map(|f| (f.0, f.2, f.3, f.4)).collect();
    ours.sort_unstable();
    want.sort_unstable();
    assert!(want.len() > 500, "a scene worth stalling: {}", want.len());
    assert_eq!(ours.len(), want.len(), "fragment count");
    assert!(ours == want, "fragments differ from subdivision-raster's");
    // Golden: lane K's pixel is on sub-triangle K's plane.
    let mut worst = 0i32;
    for &(parent, k, x, y, rgb) in &got {
        let s = scene[parent]
            .1
            .as_ref()
            .expect("pixels of a zero-area parent");
        for (c, (&got, plane)) in rgb.iter().zip(&s.planes[k]).enumerate() {
            let v = to_u8(plane.at_pixel(x as i32, y as i32)) as i32;
            let d = (got as i32 - v).abs();
            assert!(
                d <= 1,
                "({x}, {y}) lane {k} channel {c}: {got} against golden {v}"
            );
            worst = worst.max(d);
        }
    }
    println!(
        "{} fragments of {} parents equal subdivision-raster's; max {worst} LSB from the golden planes; {} clocks, block held {}",
        got.len(),
        jobs.len(),
        run.rows.len(),
        run.held
    );
}

#[test]
fn back_pressure_keeps_every_fragment_in_order() {
    let seed = seed_for("subdivision_back_pressure_keeps_every_fragment_in_order");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let jobs: Vec<SubJob> = scene(seed, 10).into_iter().map(|j| j.0).collect();
    let words = subdivision_words(&jobs);
    let reference = reference_beats(&words);
    for (k, lane) in reference.iter().enumerate() {
        assert_eq!(
            lane.iter().filter(|b| b.last).count(),
            jobs.len(),
            "lane {k}"
        );
    }
    for (label, stall_p, gap) in [
        ("random 25 %", 0.25, 0.1),
        ("random 60 %", 0.6, 0.3),
        ("random 90 %", 0.9, 0.0),
    ] {
        let run = drive(
            &words,
            seed,
            gap,
            &mut stalls(seed ^ label.len() as u64, stall_p),
            8,
        );
        let (beats, error) = rtl_beats(&run);
        assert!(!error, "{label}: no protocol error");
        assert!(
            beats == reference,
            "{label}: beats differ from the unstalled stream's"
        );
        assert!(run.held > 0, "{label}: the four-triangle block was held");
        println!(
            "{label}: {:?} beats in {} clocks, consumers stalled {:?}, block held {}, FIFO at most {} of {FIFO_DEPTH}",
            beats.each_ref().map(Vec::len),
            run.rows.len(),
            run.consumer_stalls,
            run.held,
            run.max_level
        );
    }
}

/// Long stretches: one lane's `tready` low for 1 500 clocks at a time, each lane at different
/// times, and the exported Verilog bit-exact with the rust-hdl simulation under that pattern
/// (Verilator).
#[test]
fn long_stalls_lose_nothing_and_the_verilog_agrees() {
    let seed = seed_for("subdivision_long_stalls_lose_nothing_and_the_verilog_agrees");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let jobs: Vec<SubJob> = scene(seed, 6).into_iter().map(|j| j.0).collect();
    let words = subdivision_words(&jobs);
    let reference = reference_beats(&words);
    let mut pattern: [StallPattern; LANES] = std::array::from_fn(|k| {
        let mut random = StallPattern::new(seed ^ k as u64, 0.2);
        let from = 100 + 700 * k;
        StallPattern::from_fn(move |c| (from..from + 1500).contains(&c) || random.next_stalled())
    });
    let run = drive(&words, seed, 0.05, &mut pattern, 8);
    let (beats, error) = rtl_beats(&run);
    assert!(!error);
    assert!(
        beats == reference,
        "beats differ from the unstalled stream's"
    );
    assert!(run.held > 1000, "held {} clocks", run.held);
    println!(
        "{:?} beats in {} clocks; consumers stalled {:?}, block held {}, FIFO at most {} of {FIFO_DEPTH}",
        beats.each_ref().map(Vec::len),
        run.rows.len(),
        run.consumer_stalls,
        run.held,
        run.max_level
    );
    if !Simulator::Verilator.require("subdivision_long_stalls_lose_nothing_and_the_verilog_agrees")
    {
        return;
    }
    let rep = differential(
        find("subdivision-stream").unwrap(),
        &Options::new(),
        &run.rows,
        Simulator::Verilator,
        "subdivision-stream-long-stalls",
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
    let seed = seed_for("subdivision_bad_records_are_dropped_with_error");
    let jobs: Vec<SubJob> = scene(seed, 2).into_iter().map(|j| j.0).collect();
    let good = subdivision_words(&jobs);
    let reference = reference_beats(&good);
    let t = subdivision_record(&jobs[0]);
    let unknown: Vec<Word> = vec![(2, false), (0xDEAD, false), (0xBEEF, true)];
    let mut short: Vec<Word> = t[..40].to_vec();
    short.last_mut().unwrap().1 = true;
    let mut long: Vec<Word> = t.clone();
    long.last_mut().unwrap().1 = false;
    long.extend([(0x1234, false), (0x5678, true)]);
    // Three records' words under one `tlast` (215 payload words, more than the reader's 7-bit
    // count holds): dropped from its 72nd payload word up to that `tlast`, none taken.
    let mut longer: Vec<Word> = Vec::new();
    for k in 0..3 {
        longer.extend(t.iter().map(|&(w, last)| (w, last && k == 2)));
    }
    for (label, bad) in [
        ("unknown type", &unknown),
        ("short", &short),
        ("long", &long),
        ("three records long", &longer),
    ] {
        let mut words = bad.clone();
        words.extend(good.iter().copied());
        let run = drive(&words, seed, 0.0, &mut stalls(seed, 0.3), 8);
        let (beats, error) = rtl_beats(&run);
        assert!(error, "{label}: error set");
        assert!(beats == reference, "{label}: the good records' beats");
        println!("{label}: dropped, error set, beats as without it");
    }
    let run = drive(&good, seed, 0.0, &mut stalls(seed, 0.0), 8);
    assert!(!rtl_beats(&run).1, "no error on good records");
}

/// With every `m_axis_lK_tready` high the four-triangle block is never held.
#[test]
fn tready_high_never_holds_the_block() {
    let seed = seed_for("subdivision_tready_high_never_holds_the_block");
    let jobs: Vec<SubJob> = scene(seed, 20).into_iter().map(|j| j.0).collect();
    let run = drive(
        &subdivision_words(&jobs),
        seed,
        0.0,
        &mut std::array::from_fn(|_| StallPattern::never()),
        8,
    );
    assert_eq!(run.held, 0);
    assert!(run.max_level <= 1, "FIFO level {}", run.max_level);
    println!(
        "{:?} beats in {} clocks, never held",
        run.beats.each_ref().map(Vec::len),
        run.rows.len()
    );
}

/// The header's latency: a parent record's last word accepted in clock t, its first beat on
/// every lane with a pixel on its first row offered in clock t + `LATENCY` (both banks free,
/// the block idle, `tready` high).
#[test]
fn latency_from_last_word_to_first_beat() {
    let mut t = golden::types::ScreenTriangle::from_points([(3, 1), (60, 9), (14, 50)]);
    t.v[1].normal = glam::DVec3::new(0.3, 0.1, 1.0).normalize();
    let job = SubJob::subdivision(&t, &golden::shade::ShadeContext::default()).unwrap();
    let idle: Vec<u64> = [0, 0, 0].into_iter().chain([1; LANES]).collect();
    assert_eq!(idle.len(), INPUTS);
    let mut rows = vec![idle.clone(); 5];
    for (w, last) in subdivision_record(&job) {
        let mut r = idle.clone();
        r[..3].copy_from_slice(&[w as u64, 1, last as u64]);
        rows.push(r);
    }
    let last = rows.len() - 1;
    let latency = rtl::stream::subdivision_stream::SubdivisionStream::LATENCY;
    rows.extend(std::iter::repeat_n(idle, latency + 10));
    let out = find("subdivision-stream")
        .unwrap()
        .simulate_on(
            &Options::new(),
            &rows,
            flow::engine::fast_sim("subdivision_stream"),
        )
        .unwrap();
    assert!(
        out[..=last]
            .iter()
            .zip(&rows)
            .all(|(o, r)| r[1] == 0 || o[0] != 0),
        "every word accepted when shown"
    );
    let first = (0..out.len())
        .find(|&c| (0..LANES).any(|k| out[c][1 + 3 * k] != 0))
        .unwrap();
    assert_eq!(first - last, latency);
    println!("last word to first beat: {latency} clocks");
}

/// The layout's fields are `subdivision-raster`'s set-up ports: the same names and widths, in
/// port order (between `load` and `hold`).
#[test]
fn layout_fields_are_the_raster_ports() {
    use rtl::stream::layout::SUBDIVISION_PARENT;
    let (ins, _) = find("subdivision-raster").unwrap().ports();
    let ports: Vec<(String, usize)> = ins.iter().map(|p| (p.name.to_string(), p.width)).collect();
    let fields: Vec<(String, usize)> = SUBDIVISION_PARENT
        .fields
        .iter()
        .map(|f| (f.name.to_string(), f.bits as usize))
        .collect();
    assert_eq!(ports.first().map(|p| p.0.as_str()), Some("load"));
    assert_eq!(ports.last().map(|p| p.0.as_str()), Some("hold"));
    assert_eq!(ports[1..ports.len() - 1], fields[..]);
}
