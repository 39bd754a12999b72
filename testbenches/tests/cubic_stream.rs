//! `cubic-stream` (the AXI4-Stream top of the cubic span pipeline), both Horner variants:
//! back-pressure keeps every fragment, in order, under random and long stalls, in the rust-hdl
//! simulation and in the exported Verilog; the fragments are `cubic-pipeline`'s own (its RTL
//! stepped through its ports by the render driver); bad records are dropped with `error`; with
//! `m_axis_tready` always high the pipeline is never held. (The generic tests — twin every
//! clock, golden, Icarus, Verilator, lint — are the registry's.)

use flow::blocks::differential;
use flow::verilog::Simulator;
use golden::methods::Method;
use golden::testing::seed_for;
use pipeline::axis::{Beat, Word};
use pipeline::lit::ShadingRegs;
use pipeline::span::{cubic_record, cubic_words};
use pipeline::span::{span_clock_budget, SpanJob, SpanPipe};
use rtl::core::registry::Options;
use rtl::pipelines::cubic_pipeline::CubicParams;
use rtl::units::horner_unit::HornerParams;
use testbenches::registry::find;
use testbenches::stall::StallPattern;
use testbenches::stream::cubic_stream::{drive, load_row, reference_beats, scene, CubicStreamRun};

const VARIANTS: [(&str, bool); 2] = [("serial", false), ("pipelined", true)];

fn params(pipelined: bool) -> CubicParams {
    CubicParams(HornerParams { pipelined })
}

fn options(pipelined: bool) -> Options {
    Options::new().with("horner", if pipelined { "pipelined" } else { "serial" })
}

/// The beats the RTL (rust-hdl) delivers for the run's input rows, and its `error` at the end.
fn rtl_beats(pipelined: bool, run: &CubicStreamRun) -> (Vec<Beat>, bool) {
    let b = find("cubic-stream").unwrap();
    let out = b
        .simulate_on(
            &options(pipelined),
            &run.rows,
            flow::engine::fast_sim("cubic_stream"),
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
        .map(|(o, _)| Beat::read(o[2], o[3], o[4] != 0))
        .collect();
    (beats, out.last().unwrap()[5] != 0)
}

/// A fragment with its line's index (the number of line ends before it): line, x, y, z, rgb.
type Fragment = (usize, u32, u32, i32, [u8; 3]);

fn fragments(beats: &[Beat]) -> Vec<Fragment> {
    let mut line = 0;
    beats
        .iter()
        .map(|b| {
            assert!(b.pixel, "every cubic-stream beat is a fragment");
            let f = (line, b.x, b.y, b.z, b.rgb);
            line += b.last as usize;
            f
        })
        .collect()
}

/// `cubic-pipeline`'s RTL run on `spans` through its own ports (no stream, no hold), by the
/// render driver, as fragments.
fn pipeline_fragments(pipelined: bool, spans: &[SpanJob]) -> Vec<Fragment> {
    let mut pipe = SpanPipe::with_horner(Method::Cubic, pipelined).unwrap();
    let mut out = Vec::new();
    let st = pipe
        .run(
            spans,
            &ShadingRegs::default(),
            span_clock_budget(spans),
            |f| out.push((f.x, f.y, f.z, f.rgb)),
            |_| {},
        )
        .unwrap();
    assert_eq!(st.triangles, spans.len() as u64);
    // Pixels come in span order: number them by the spans' pixel counts.
    let lines = spans
        .iter()
        .enumerate()
        .flat_map(|(i, s)| std::iter::repeat_n(i, s.m as usize + 1));
    assert_eq!(
        spans.iter().map(|s| s.m as usize + 1).sum::<usize>(),
        out.len(),
        "one fragment per span pixel"
    );
    lines
        .zip(out)
        .map(|(i, (x, y, z, rgb))| (i, x, y, z, rgb))
        .collect()
}

/// The stream's fragments are `cubic-pipeline`'s (its RTL stepped through its own ports), under
/// back-pressure, for both Horner variants.
#[test]
fn fragments_are_the_cubic_pipelines() {
    let seed = seed_for("fragments_are_the_cubic_pipelines");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    for (label, pipelined) in VARIANTS {
        let p = params(pipelined);
        let spans = scene(&p, seed, 4);
        let mut stalls = StallPattern::new(seed, 0.4);
        let run = drive(&p, &cubic_words(&spans), seed, 0.1, &mut stalls, 8);
        let (beats, error) = rtl_beats(pipelined, &run);
        assert!(!error, "{label}: no protocol error");
        let got = fragments(&beats);
        let want = pipeline_fragments(pipelined, &spans);
        assert_eq!(got.len(), want.len(), "{label}: fragment count");
        if let Some(k) = (0..got.len()).find(|&k| got[k] != want[k]) {
            panic!(
                "{label}: fragment {k} is {:?}, cubic-pipeline's {:?}",
                got[k], want[k]
            );
        }
        assert_eq!(
            beats.iter().filter(|b| b.last).count(),
            spans.len(),
            "{label}: one tlast per line"
        );
        println!(
            "{label}: {} fragments of {} lines equal cubic-pipeline's; {} clocks, consumer stalled {}, units held {}, FIFO at most {}",
            got.len(),
            spans.len(),
            run.rows.len(),
            run.consumer_stalls,
            run.held,
            run.max_level
        );
    }
}

#[test]
fn back_pressure_keeps_every_fragment_in_order() {
    let seed = seed_for("cubic_back_pressure_keeps_every_fragment_in_order");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    for (variant, pipelined) in VARIANTS {
        let p = params(pipelined);
        let spans = scene(&p, seed, 3);
        let words = cubic_words(&spans);
        let reference = reference_beats(&p, &spans);
        assert!(
            reference.len() > 500,
            "a scene worth stalling: {} fragments",
            reference.len()
        );
        for (label, stall_p, gap) in [
            ("random 25 %", 0.25, 0.1),
            ("random 60 %", 0.6, 0.3),
            ("random 90 %", 0.9, 0.0),
        ] {
            let mut stalls = StallPattern::new(seed ^ label.len() as u64, stall_p);
            let run = drive(&p, &words, seed, gap, &mut stalls, 8);
            let (beats, error) = rtl_beats(pipelined, &run);
            assert!(!error, "{variant} {label}: no protocol error");
            assert_eq!(
                beats.len(),
                reference.len(),
                "{variant} {label}: beat count"
            );
            assert!(
                beats == reference,
                "{variant} {label}: beats differ from the unstalled stream's"
            );
            // Where the consumer is slower than the units, the FIFO fills and they are held.
            if stall_p >= 0.6 || pipelined {
                assert!(run.held > 0, "{variant} {label}: the units were held");
            }
            println!(
                "{variant} {label}: {} beats in {} clocks, consumer stalled {} clocks, units held {}, FIFO at most {}",
                beats.len(),
                run.rows.len(),
                run.consumer_stalls,
                run.held,
                run.max_level
            );
        }
    }
}

/// Long stretches: `tready` low for 1 500 clocks, twice, on top of 20 % random stalls; and the
/// exported Verilog bit-exact with the rust-hdl simulation under that pattern (Verilator).
#[test]
fn long_stalls_lose_nothing_and_the_verilog_agrees() {
    let seed = seed_for("cubic_long_stalls_lose_nothing_and_the_verilog_agrees");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    for (variant, pipelined) in VARIANTS {
        let p = params(pipelined);
        let spans = scene(&p, seed, 2);
        let reference = reference_beats(&p, &spans);
        let mut random = StallPattern::new(seed, 0.2);
        let mut stalls = StallPattern::from_fn(move |c| {
            let r = random.next_stalled();
            (100..1600).contains(&c) || (2500..4000).contains(&c) || r
        });
        let run = drive(&p, &cubic_words(&spans), seed, 0.05, &mut stalls, 8);
        let (beats, error) = rtl_beats(pipelined, &run);
        assert!(!error);
        assert!(
            beats == reference,
            "{variant}: beats differ from the unstalled stream's"
        );
        assert!(run.held > 2500, "{variant}: held {} clocks", run.held);
        println!(
            "{variant}: {} beats in {} clocks; consumer stalled {}, units held {}, FIFO at most {} of {}",
            beats.len(),
            run.rows.len(),
            run.consumer_stalls,
            run.held,
            run.max_level,
            rtl::stream::cubic_stream::FIFO_DEPTH
        );
        if !Simulator::Verilator.require("cubic_long_stalls_lose_nothing_and_the_verilog_agrees") {
            return;
        }
        let rep = differential(
            find("cubic-stream").unwrap(),
            &options(pipelined),
            &run.rows,
            Simulator::Verilator,
            &format!("cubic-stream-long-stalls-{variant}"),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        println!(
            "{variant}: Verilator bit-exact, {} clocks × {} ports",
            rep.cycles, rep.ports
        );
    }
}

/// Records of an unknown type, too short or too long are dropped whole and set `error`; the
/// records around them are unaffected.
#[test]
fn bad_records_are_dropped_with_error() {
    let seed = seed_for("cubic_bad_records_are_dropped_with_error");
    let p = params(true);
    let spans = scene(&p, seed, 1);
    let good = cubic_words(&spans);
    let reference = reference_beats(&p, &spans);
    let t = cubic_record(&spans[0]);
    let unknown: Vec<Word> = vec![(2, false), (0xDEAD, false), (0xBEEF, true)];
    let mut short: Vec<Word> = t[..6].to_vec();
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
        let run = drive(&p, &words, seed, 0.0, &mut StallPattern::new(seed, 0.3), 8);
        let (beats, error) = rtl_beats(true, &run);
        assert!(error, "{label}: error set");
        assert!(beats == reference, "{label}: the good records' beats");
        println!(
            "{label}: dropped, error set, {} beats as without it",
            beats.len()
        );
    }
    let run = drive(&p, &good, seed, 0.0, &mut StallPattern::never(), 8);
    assert!(!rtl_beats(true, &run).1, "no error on good records");
}

/// With `m_axis_tready` always high the units are never held and the FIFO holds at most one
/// beat; the clocks against `cubic-pipeline` driven through its ports are reported (lines
/// shorter than a record are set-up bound).
#[test]
fn tready_high_never_holds_the_units() {
    let seed = seed_for("tready_high_never_holds_the_units");
    for (variant, pipelined) in VARIANTS {
        let p = params(pipelined);
        let spans = scene(&p, seed, 4);
        let run = drive(
            &p,
            &cubic_words(&spans),
            seed,
            0.0,
            &mut StallPattern::never(),
            8,
        );
        assert_eq!(run.held, 0, "{variant}: never held");
        assert!(run.max_level <= 1, "{variant}: FIFO {}", run.max_level);
        let mut pipe = SpanPipe::with_horner(Method::Cubic, pipelined).unwrap();
        let st = pipe
            .run(
                &spans,
                &ShadingRegs::default(),
                span_clock_budget(&spans),
                |_| {},
                |_| {},
            )
            .unwrap();
        let short = spans
            .iter()
            .filter(|s| s.clocks() < cubic_record(s).len() as u64)
            .count();
        println!(
            "{variant}: {} beats in {} clocks, never held; cubic-pipeline through its ports {} clocks (ratio {:.3}); {short} of {} lines shorter than their 12-word record",
            run.beats.len(),
            run.rows.len(),
            st.clocks,
            run.rows.len() as f64 / st.clocks as f64,
            spans.len()
        );
    }
}

/// The header's latency: a line record's last word accepted in clock t, its first beat offered
/// in clock t + `CubicStream::LATENCY` with the pipelined units, up to 2 clocks later with the
/// serial ones (both banks free, the units idle, `tready` high).
#[test]
fn latency_from_last_word_to_first_beat() {
    let latency = rtl::stream::cubic_stream::CubicStream::LATENCY;
    for (variant, pipelined) in VARIANTS {
        let p = params(pipelined);
        let spans = scene(&p, 7, 1);
        let mut seen = Vec::new();
        // Starting in each clock of the serial units' three-clock slot.
        for lead in 5..8 {
            let mut rows: Vec<Vec<u64>> = vec![vec![0, 0, 0, 1]; lead];
            for (w, last) in cubic_record(&spans[0]) {
                rows.push(vec![w as u64, 1, last as u64, 1]);
            }
            let last = rows.len() - 1;
            rows.extend(std::iter::repeat_n(vec![0, 0, 0, 1], latency + 10));
            let out = find("cubic-stream")
                .unwrap()
                .simulate_on(
                    &options(pipelined),
                    &rows,
                    flow::engine::fast_sim("cubic_stream"),
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
            seen.push(first - last);
        }
        println!("{variant}: last word to first beat {seen:?} clocks");
        if pipelined {
            assert!(seen.iter().all(|&l| l == latency), "{variant}: {seen:?}");
        } else {
            assert!(
                seen.iter().all(|&l| (latency..=latency + 2).contains(&l)),
                "{variant}: {seen:?}"
            );
            assert!(seen.contains(&latency), "{variant}: {seen:?}");
        }
    }
}

/// The layout's fields are `cubic-pipeline`'s load ports: the same names and widths, in port
/// order (between `load` and `hold`), and a record carries the driver's load row.
#[test]
fn layout_fields_are_the_pipeline_ports() {
    use rtl::stream::layout::{unpack, CUBIC_LINE};
    let (ins, _) = find("cubic-pipeline").unwrap().ports();
    let ports: Vec<(String, usize)> = ins.iter().map(|p| (p.name.to_string(), p.width)).collect();
    let fields: Vec<(String, usize)> = CUBIC_LINE
        .fields
        .iter()
        .map(|f| (f.name.to_string(), f.bits as usize))
        .collect();
    assert_eq!(ports.first().map(|p| p.0.as_str()), Some("load"));
    assert_eq!(ports.last().map(|p| p.0.as_str()), Some("hold"));
    assert_eq!(ports[1..ports.len() - 1], fields[..]);
    let p = params(false);
    let spans = scene(&p, 3, 1);
    let rec = cubic_record(&spans[1]);
    let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
    let row = load_row(&p, &spans[1]);
    assert_eq!(unpack(&CUBIC_LINE, &payload), row[1..row.len() - 1]);
}
