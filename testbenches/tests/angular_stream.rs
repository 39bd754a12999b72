//! `angular-stream` (the AXI4-Stream top of the angular span pipeline, a fragment stream per
//! lane): back-pressure on either lane keeps every fragment, in order, under random and long
//! stalls, in the rust-hdl simulation and in the exported Verilog; the fragments are
//! `angular-pipeline`'s own (its RTL stepped through its ports by the render driver); a
//! register record applies only to the lines after it; bad records are dropped with `error`;
//! with both `tready` high the pipeline is never held; the header's latency. (The generic tests
//! — twin every clock, golden, Icarus, Verilator, lint — are the registry's.)

use golden::methods::Method;
use golden::testing::seed_for;
use pipeline::lit::ShadingRegs;
use pipeline::span::{span_clock_budget, SpanJob, SpanPipe};
use pipeline::stream::{angular_record, angular_words, span_register_record, Beat, Word};
use rtl::angular_stream::{AngularStream, FIFO_DEPTH};
use rtl::registry::Options;
use testbenches::angular_stream::{drive, reference_beats, scene, stalls, AngularStreamRun};
use testbenches::registry::{differential, find};
use testbenches::stall::StallPattern;
use testbenches::verilog::Simulator;

/// Each lane's beats the RTL (rust-hdl) delivers for the run's input rows, and its `error` at
/// the end.
fn rtl_beats(run: &AngularStreamRun) -> ([Vec<Beat>; 2], bool) {
    let out = find("angular-stream")
        .unwrap()
        .simulate(&Options::new(), &run.rows)
        .unwrap();
    // The twin that made the rows (record reader, banks, registers, FIFOs, hold) agrees every
    // clock, bad records and stalls included.
    if let Some(c) = (0..out.len()).find(|&c| out[c] != run.outputs[c]) {
        panic!(
            "the RTL differs from the twin at clock {c}: {:?} against {:?}",
            out[c], run.outputs[c]
        );
    }
    let lane = |k: usize| {
        let at = 1 + 4 * k;
        out.iter()
            .zip(&run.rows)
            .filter(|(o, r)| o[at] != 0 && r[3 + k] != 0)
            .map(|(o, _)| Beat::read(o[at + 1], o[at + 2], o[at + 3] != 0))
            .collect()
    };
    ([lane(0), lane(1)], out.last().unwrap()[9] != 0)
}

/// A fragment with its line's index (the `tlast`s before it on its lane): line, x, y, z, rgb.
type Fragment = (usize, u32, u32, i32, [u8; 3]);

/// Each lane's fragments (beats with `pixel`), numbered by line; every lane has one `tlast`
/// per line.
fn fragments(beats: &[Vec<Beat>; 2], lines: usize) -> [Vec<Fragment>; 2] {
    [0, 1].map(|k| {
        let mut line = 0;
        let mut f = Vec::new();
        for b in &beats[k] {
            if b.pixel {
                f.push((line, b.x, b.y, b.z, b.rgb));
            }
            line += b.last as usize;
        }
        assert_eq!(line, lines, "lane {k}: one tlast per line");
        f
    })
}

/// `angular-pipeline`'s RTL run on `spans` with `regs` through its own ports (no stream, no
/// hold), by the render driver, as each lane's fragments.
fn pipeline_fragments(spans: &[SpanJob], regs: &ShadingRegs) -> [Vec<Fragment>; 2] {
    let mut pipe = SpanPipe::new(Method::Angular).unwrap();
    let mut lanes: [Vec<Fragment>; 2] = [Vec::new(), Vec::new()];
    pipe.run(
        spans,
        regs,
        span_clock_budget(spans),
        |f| lanes[f.lane_b as usize].push((0, f.x, f.y, f.z, f.rgb)),
        |_| {},
    )
    .unwrap();
    // Number them by line: lane A has pixels 0..=⌊m/2⌋ of a line, lane B m down to ⌊m/2⌋ + 1.
    for (k, lane) in lanes.iter_mut().enumerate() {
        let per_line = spans.iter().enumerate().flat_map(|(i, s)| {
            let (m, half) = (s.m as usize, s.m as usize / 2);
            std::iter::repeat_n(i, if k == 0 { half + 1 } else { m - half })
        });
        let lines: Vec<usize> = per_line.collect();
        assert_eq!(lines.len(), lane.len(), "lane {k}: one fragment per pixel");
        for (f, line) in lane.iter_mut().zip(lines) {
            f.0 = line;
        }
    }
    lanes
}

/// The stream's fragments are `angular-pipeline`'s (its RTL stepped through its own ports),
/// lane by lane, under independent back-pressure on the two lanes.
#[test]
fn fragments_are_the_angular_pipelines() {
    let seed = seed_for("fragments_are_the_angular_pipelines");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let (spans, regs) = scene(seed, 4);
    let run = drive(
        &angular_words(&spans, &regs),
        seed,
        0.1,
        &mut stalls(seed, 0.4),
        8,
    );
    let (beats, error) = rtl_beats(&run);
    assert!(!error, "no protocol error");
    let got = fragments(&beats, spans.len());
    let want = pipeline_fragments(&spans, &regs);
    for k in 0..2 {
        assert_eq!(got[k].len(), want[k].len(), "lane {k}: fragment count");
        if let Some(i) = (0..got[k].len()).find(|&i| got[k][i] != want[k][i]) {
            panic!(
                "lane {k}: fragment {i} is {:?}, angular-pipeline's {:?}",
                got[k][i], want[k][i]
            );
        }
    }
    println!(
        "{} + {} fragments of {} lines equal angular-pipeline's; {} clocks, consumers stalled {:?}, units held {}, FIFO at most {}",
        got[0].len(),
        got[1].len(),
        spans.len(),
        run.rows.len(),
        run.consumer_stalls,
        run.held,
        run.max_level
    );
}

#[test]
fn back_pressure_keeps_every_fragment_in_order() {
    let seed = seed_for("angular_back_pressure_keeps_every_fragment_in_order");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let (spans, regs) = scene(seed, 3);
    let words = angular_words(&spans, &regs);
    let reference = reference_beats(&words);
    assert!(
        reference[0].len() + reference[1].len() > 500,
        "a scene worth stalling: {} + {} beats",
        reference[0].len(),
        reference[1].len()
    );
    let one_lane = |p: f64| [StallPattern::new(seed, p), StallPattern::never()];
    for (label, mut pattern, gap) in [
        ("both lanes, random 25 %", stalls(seed, 0.25), 0.1),
        ("both lanes, random 60 %", stalls(seed ^ 6, 0.6), 0.3),
        ("both lanes, random 90 %", stalls(seed ^ 9, 0.9), 0.0),
        ("lane A only, random 90 %", one_lane(0.9), 0.0),
        (
            "lane B only, random 90 %",
            [StallPattern::never(), StallPattern::new(seed ^ 2, 0.9)],
            0.0,
        ),
    ] {
        let run = drive(&words, seed, gap, &mut pattern, 8);
        let (beats, error) = rtl_beats(&run);
        assert!(!error, "{label}: no protocol error");
        for k in 0..2 {
            assert_eq!(
                beats[k].len(),
                reference[k].len(),
                "{label}: lane {k} beat count"
            );
            assert!(
                beats[k] == reference[k],
                "{label}: lane {k}'s beats differ from the unstalled stream's"
            );
        }
        // The consumers are slower than the units here: the FIFO fills and they are held.
        assert!(run.held > 0, "{label}: the units were held");
        assert!(
            run.max_level <= FIFO_DEPTH,
            "{label}: FIFO {}",
            run.max_level
        );
        println!(
            "{label}: {} + {} beats in {} clocks, consumers stalled {:?}, units held {}, FIFO at most {} of {FIFO_DEPTH}",
            beats[0].len(),
            beats[1].len(),
            run.rows.len(),
            run.consumer_stalls,
            run.held,
            run.max_level
        );
    }
}

/// Long stretches: each lane's `tready` low for 1 500 clocks, at different times, on top of
/// 20 % random stalls; and the exported Verilog bit-exact with the rust-hdl simulation under
/// that pattern (Verilator).
#[test]
fn long_stalls_lose_nothing_and_the_verilog_agrees() {
    let seed = seed_for("angular_long_stalls_lose_nothing_and_the_verilog_agrees");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let (spans, regs) = scene(seed, 2);
    let words = angular_words(&spans, &regs);
    let reference = reference_beats(&words);
    let stretch = |k: u64, from: [usize; 2]| {
        let mut random = StallPattern::new(seed ^ k, 0.2);
        StallPattern::from_fn(move |c| {
            let r = random.next_stalled();
            from.iter().any(|&f| (f..f + 1500).contains(&c)) || r
        })
    };
    let mut pattern = [stretch(1, [100, 2500]), stretch(2, [900, 4200])];
    let run = drive(&words, seed, 0.05, &mut pattern, 8);
    let (beats, error) = rtl_beats(&run);
    assert!(!error);
    assert!(
        beats == reference,
        "beats differ from the unstalled stream's"
    );
    assert!(run.held > 2500, "held {} clocks", run.held);
    println!(
        "{} + {} beats in {} clocks; consumers stalled {:?}, units held {}, FIFO at most {} of {FIFO_DEPTH}",
        beats[0].len(),
        beats[1].len(),
        run.rows.len(),
        run.consumer_stalls,
        run.held,
        run.max_level
    );
    if !Simulator::Verilator.require("angular_long_stalls_lose_nothing_and_the_verilog_agrees") {
        return;
    }
    let rep = differential(
        find("angular-stream").unwrap(),
        &Options::new(),
        &run.rows,
        Simulator::Verilator,
        "angular-stream-long-stalls",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    println!(
        "Verilator bit-exact, {} clocks × {} ports",
        rep.cycles, rep.ports
    );
}

/// A register record between lines applies to the lines after it only: it waits in the load
/// bank until every line before it has left the pipeline. Each part equals `angular-pipeline`
/// run with that part's registers.
#[test]
fn registers_apply_to_the_lines_after_them() {
    let seed = seed_for("angular_registers_apply_to_the_lines_after_them");
    let (spans, regs) = scene(seed, 2);
    let half = spans.len() / 2;
    let mut other = regs;
    other.n = 7;
    other.weights = [40, 300, 900, 12_000, 200, 7_000, 65_535, 100, 30_000];
    let mut words = span_register_record(&regs);
    spans[..half]
        .iter()
        .for_each(|s| words.extend(angular_record(s)));
    words.extend(span_register_record(&other));
    spans[half..]
        .iter()
        .for_each(|s| words.extend(angular_record(s)));
    let run = drive(&words, seed, 0.0, &mut stalls(seed, 0.3), 8);
    let (beats, error) = rtl_beats(&run);
    assert!(!error);
    let got = fragments(&beats, spans.len());
    let first = pipeline_fragments(&spans[..half], &regs);
    let second = pipeline_fragments(&spans[half..], &other);
    for k in 0..2 {
        let mut want = first[k].clone();
        want.extend(second[k].iter().map(|f| (f.0 + half, f.1, f.2, f.3, f.4)));
        assert_eq!(got[k].len(), want.len(), "lane {k}: fragment count");
        if let Some(i) = (0..want.len()).find(|&i| got[k][i] != want[i]) {
            panic!(
                "lane {k}: fragment {i} is {:?}, want {:?}",
                got[k][i], want[i]
            );
        }
    }
    // The second set changes the colours (else the test shows nothing).
    let same = pipeline_fragments(&spans[half..], &regs);
    assert!(
        second[0] != same[0],
        "the two register sets give different colours"
    );
    println!(
        "{} lines with the first set, {} with the second: every fragment as angular-pipeline gives with its set",
        half,
        spans.len() - half
    );
}

/// Records of an unknown type, too short or too long are dropped whole and set `error`; the
/// records around them are unaffected.
#[test]
fn bad_records_are_dropped_with_error() {
    let seed = seed_for("angular_bad_records_are_dropped_with_error");
    let (spans, regs) = scene(seed, 1);
    let good = angular_words(&spans, &regs);
    let reference = reference_beats(&good);
    let t = angular_record(&spans[0]);
    let unknown: Vec<Word> = vec![(3, false), (0xDEAD, false), (0xBEEF, true)];
    let mut short: Vec<Word> = t[..6].to_vec();
    short.last_mut().unwrap().1 = true;
    let mut long: Vec<Word> = t.clone();
    long.last_mut().unwrap().1 = false;
    long.extend([(0x1234, false), (0x5678, true)]);
    let mut short_regs: Vec<Word> = span_register_record(&regs)[..3].to_vec();
    short_regs.last_mut().unwrap().1 = true;
    let header_only: Vec<Word> = vec![(1, true)];
    for (label, bad) in [
        ("unknown type", &unknown),
        ("short line", &short),
        ("long line", &long),
        ("short registers", &short_regs),
        ("header only", &header_only),
    ] {
        let mut words = bad.clone();
        words.extend(good.iter().copied());
        let run = drive(&words, seed, 0.0, &mut stalls(seed, 0.3), 8);
        let (beats, error) = rtl_beats(&run);
        assert!(error, "{label}: error set");
        assert!(beats == reference, "{label}: the good records' beats");
        println!(
            "{label}: dropped, error set, {} + {} beats as without it",
            beats[0].len(),
            beats[1].len()
        );
    }
    let run = drive(&good, seed, 0.0, &mut stalls(seed, 0.0), 8);
    assert!(!rtl_beats(&run).1, "no error on good records");
}

/// With both `tready` always high the units are never held and each FIFO holds at most one
/// beat; the clocks against `angular-pipeline` driven through its ports are reported (lines
/// shorter than their record are set-up bound).
#[test]
fn tready_high_never_holds_the_units() {
    let seed = seed_for("angular_tready_high_never_holds_the_units");
    let (spans, regs) = scene(seed, 4);
    let run = drive(
        &angular_words(&spans, &regs),
        seed,
        0.0,
        &mut stalls(seed, 0.0),
        8,
    );
    assert_eq!(run.held, 0, "never held");
    assert!(run.max_level <= 1, "FIFO {}", run.max_level);
    let mut pipe = SpanPipe::new(Method::Angular).unwrap();
    let st = pipe
        .run(&spans, &regs, span_clock_budget(&spans), |_| {}, |_| {})
        .unwrap();
    let short = spans
        .iter()
        .filter(|s| s.clocks() < angular_record(s).len() as u64)
        .count();
    println!(
        "{} + {} beats in {} clocks, never held; angular-pipeline through its ports {} clocks (ratio {:.3}); {short} of {} lines shorter than their 14-word record",
        run.beats[0].len(),
        run.beats[1].len(),
        run.rows.len(),
        st.clocks,
        run.rows.len() as f64 / st.clocks as f64,
        spans.len()
    );
}

/// The header's latency: a line record's last word accepted in clock t, its first beats
/// offered in clock t + `AngularStream::LATENCY` on both lanes (registers applied, both banks
/// free, the units idle, `tready` high).
#[test]
fn latency_from_last_word_to_first_beat() {
    let latency = AngularStream::LATENCY;
    let (spans, regs) = scene(7, 1);
    // A line of at least two pixels: both lanes have one in its first clock.
    let line = spans.iter().find(|s| s.m >= 1).unwrap();
    let idle = vec![0, 0, 0, 1, 1];
    let mut rows: Vec<Vec<u64>> = vec![idle.clone(); 3];
    for (w, last) in span_register_record(&regs) {
        rows.push(vec![w as u64, 1, last as u64, 1, 1]);
    }
    rows.extend(std::iter::repeat_n(idle.clone(), 4));
    for (w, last) in angular_record(line) {
        rows.push(vec![w as u64, 1, last as u64, 1, 1]);
    }
    let last = rows.len() - 1;
    rows.extend(std::iter::repeat_n(idle, latency + 10));
    let out = find("angular-stream")
        .unwrap()
        .simulate(&Options::new(), &rows)
        .unwrap();
    assert!(
        out[..=last]
            .iter()
            .zip(&rows)
            .all(|(o, r)| r[1] == 0 || o[0] != 0),
        "every word accepted when shown"
    );
    for (k, at) in [(0, 1), (1, 5)] {
        let first = (0..out.len()).find(|&c| out[c][at] != 0).unwrap();
        assert_eq!(first - last, latency, "lane {k}");
    }
    println!("last word to first beat: {latency} clocks on both lanes");
}

/// The layout's fields are `angular-pipeline`'s load and register ports: the same names and
/// widths, in port order (between `load` and `hold`).
#[test]
fn layout_fields_are_the_pipeline_ports() {
    use rtl::stream_layout::{ANGULAR_LINE, SPAN_REGISTERS};
    let (ins, _) = find("angular-pipeline").unwrap().ports();
    let ports: Vec<(String, usize)> = ins.iter().map(|p| (p.name.to_string(), p.width)).collect();
    let fields: Vec<(String, usize)> = ANGULAR_LINE
        .fields
        .iter()
        .chain(SPAN_REGISTERS.fields)
        .map(|f| (f.name.to_string(), f.bits as usize))
        .collect();
    assert_eq!(ports.first().map(|p| p.0.as_str()), Some("load"));
    assert_eq!(ports.last().map(|p| p.0.as_str()), Some("hold"));
    assert_eq!(ports[1..ports.len() - 1], fields[..]);
}
