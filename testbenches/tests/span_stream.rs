//! The two-lane span stream tops, `angular-stream` and `fast-stream` (`inv-sqrt=fit`; the
//! registry's tests build `chebyshev` too): back-pressure on either lane keeps every fragment,
//! in order, under random and long stalls, in the rust-hdl simulation and in the exported
//! Verilog; the fragments are the wrapped span pipeline's own (its RTL stepped through its
//! ports by the render driver); a register record applies only to the lines after it; bad
//! records are dropped with `error`; with both `tready` high the pipeline is never held; the
//! header's latency. (The generic tests — twin every clock, golden, Icarus, Verilator, lint —
//! are the registry's.)

use flow::blocks::differential;
use flow::verilog::Simulator;
use golden::methods::Method;
use golden::testing::seed_for;
use pipeline::axis::{Beat, Word};
use pipeline::lit::ShadingRegs;
use pipeline::span::{span_clock_budget, SpanJob, SpanKind, SpanPipe};
use pipeline::span::{span_line_record, span_register_record, span_stream_words};
use rtl::core::registry::{Options, RtlBlock};
use rtl::stream::fragment_fifo::FIFO_DEPTH;
use testbenches::registry::find;
use testbenches::registry::Entry;
use testbenches::stall::StallPattern;
use testbenches::stream::span_stream::{drive, reference_beats, scene, stalls, SpanStreamRun};

/// A two-lane stream top under test: its registry name, build options, span kind, the wrapped
/// pipeline's method and latency.
struct Top {
    block: &'static str,
    options: Options,
    kind: SpanKind,
    method: Method,
    latency: usize,
}

fn tops() -> [Top; 3] {
    [
        Top {
            block: "angular-stream",
            options: Options::new(),
            kind: SpanKind::Angular,
            method: Method::Angular,
            latency: <rtl::stream::angular_stream::AngularStream as RtlBlock>::LATENCY,
        },
        Top {
            block: "fast-stream",
            options: Options::new().with("inv-sqrt", "fit"),
            kind: SpanKind::Fast("fit"),
            method: Method::FastFit,
            latency: <rtl::stream::fast_stream::FastStream as RtlBlock>::LATENCY,
        },
        Top {
            block: "quadric-stream",
            options: Options::new(),
            kind: SpanKind::Quadric,
            method: Method::Quadric,
            latency: <rtl::stream::quadric_stream::QuadricStream as RtlBlock>::LATENCY,
        },
    ]
}

impl Top {
    fn entry(&self) -> &'static dyn Entry {
        find(self.block).unwrap()
    }
    fn words(&self, spans: &[SpanJob], regs: &ShadingRegs) -> Vec<Word> {
        span_stream_words(self.kind, spans, regs)
    }
}

/// Each lane's beats the RTL (rust-hdl) delivers for the run's input rows, and its `error` at
/// the end.
fn rtl_beats(top: &Top, run: &SpanStreamRun) -> ([Vec<Beat>; 2], bool) {
    let out = top
        .entry()
        .simulate_on(
            &top.options,
            &run.rows,
            flow::engine::fast_sim("span_stream"),
        )
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

/// The span pipeline's RTL run on `spans` with `regs` through its own ports (no stream, no
/// hold), by the render driver, as each lane's fragments.
fn pipeline_fragments(top: &Top, spans: &[SpanJob], regs: &ShadingRegs) -> [Vec<Fragment>; 2] {
    let mut pipe = SpanPipe::new(top.method).unwrap();
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

/// The stream's fragments are the span pipeline's (its RTL stepped through its own ports),
/// lane by lane, under independent back-pressure on the two lanes.
#[test]
fn fragments_are_the_span_pipelines() {
    let seed = seed_for("fragments_are_the_span_pipelines");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    for top in tops() {
        let (spans, regs) = scene(top.kind, seed, 4);
        let run = drive(
            top.kind,
            &top.words(&spans, &regs),
            seed,
            0.1,
            &mut stalls(seed, 0.4),
            8,
        );
        let (beats, error) = rtl_beats(&top, &run);
        assert!(!error, "{}: no protocol error", top.block);
        let got = fragments(&beats, spans.len());
        let want = pipeline_fragments(&top, &spans, &regs);
        for k in 0..2 {
            assert_eq!(
                got[k].len(),
                want[k].len(),
                "{} lane {k}: fragment count",
                top.block
            );
            if let Some(i) = (0..got[k].len()).find(|&i| got[k][i] != want[k][i]) {
                panic!(
                    "{} lane {k}: fragment {i} is {:?}, the pipeline's {:?}",
                    top.block, got[k][i], want[k][i]
                );
            }
        }
        println!(
            "{}: {} + {} fragments of {} lines equal the pipeline's; {} clocks, consumers stalled {:?}, units held {}, FIFO at most {}",
            top.block,
            got[0].len(),
            got[1].len(),
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
    let seed = seed_for("span_back_pressure_keeps_every_fragment_in_order");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    for top in tops() {
        let (spans, regs) = scene(top.kind, seed, 3);
        let words = top.words(&spans, &regs);
        let reference = reference_beats(top.kind, &words);
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
            let label = format!("{} {label}", top.block);
            let run = drive(top.kind, &words, seed, gap, &mut pattern, 8);
            let (beats, error) = rtl_beats(&top, &run);
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
}

/// Long stretches: each lane's `tready` low for 1 500 clocks, at different times, on top of
/// 20 % random stalls; and the exported Verilog bit-exact with the rust-hdl simulation under
/// that pattern (Verilator).
#[test]
fn long_stalls_lose_nothing_and_the_verilog_agrees() {
    let seed = seed_for("span_long_stalls_lose_nothing_and_the_verilog_agrees");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    for top in tops() {
        let (spans, regs) = scene(top.kind, seed, 2);
        let words = top.words(&spans, &regs);
        let reference = reference_beats(top.kind, &words);
        let stretch = |k: u64, from: [usize; 2]| {
            let mut random = StallPattern::new(seed ^ k, 0.2);
            StallPattern::from_fn(move |c| {
                let r = random.next_stalled();
                from.iter().any(|&f| (f..f + 1500).contains(&c)) || r
            })
        };
        let mut pattern = [stretch(1, [100, 2500]), stretch(2, [900, 4200])];
        let run = drive(top.kind, &words, seed, 0.05, &mut pattern, 8);
        let (beats, error) = rtl_beats(&top, &run);
        assert!(!error);
        assert!(
            beats == reference,
            "{}: beats differ from the unstalled stream's",
            top.block
        );
        // Lane A's first stretch alone holds the units from when its FIFO has filled (at most
        // 128 beats after clock 100) to clock 1 600, while lines remain.
        assert!(
            run.rows.len() > 1600 && run.held > 1200,
            "{}: held {} clocks",
            top.block,
            run.held
        );
        println!(
            "{}: {} + {} beats in {} clocks; consumers stalled {:?}, units held {}, FIFO at most {} of {FIFO_DEPTH}",
            top.block,
            beats[0].len(),
            beats[1].len(),
            run.rows.len(),
            run.consumer_stalls,
            run.held,
            run.max_level
        );
        if !Simulator::Verilator.require("span_long_stalls_lose_nothing_and_the_verilog_agrees") {
            return;
        }
        let rep = differential(
            top.entry(),
            &top.options,
            &run.rows,
            Simulator::Verilator,
            &format!("{}-long-stalls", top.block),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        println!(
            "{}: Verilator bit-exact, {} clocks × {} ports",
            top.block, rep.cycles, rep.ports
        );
    }
}

/// A register record between lines applies to the lines after it only: it waits in the load
/// bank until every line before it has left the pipeline. Each part equals the span pipeline
/// run with that part's registers.
#[test]
fn registers_apply_to_the_lines_after_them() {
    let seed = seed_for("span_registers_apply_to_the_lines_after_them");
    // The quadric is lit in the set-up: `quadric-stream` has no registers.
    for top in tops().into_iter().filter(|t| t.kind != SpanKind::Quadric) {
        let (spans, regs) = scene(top.kind, seed, 2);
        let half = spans.len() / 2;
        let mut other = regs;
        other.n = 7;
        other.weights = [40, 300, 900, 12_000, 200, 7_000, 65_535, 100, 30_000];
        let mut words = span_register_record(&regs);
        let line = |s: &SpanJob| span_line_record(top.kind, s);
        spans[..half].iter().for_each(|s| words.extend(line(s)));
        words.extend(span_register_record(&other));
        spans[half..].iter().for_each(|s| words.extend(line(s)));
        let run = drive(top.kind, &words, seed, 0.0, &mut stalls(seed, 0.3), 8);
        let (beats, error) = rtl_beats(&top, &run);
        assert!(!error);
        let got = fragments(&beats, spans.len());
        let first = pipeline_fragments(&top, &spans[..half], &regs);
        let second = pipeline_fragments(&top, &spans[half..], &other);
        for k in 0..2 {
            let mut want = first[k].clone();
            want.extend(second[k].iter().map(|f| (f.0 + half, f.1, f.2, f.3, f.4)));
            assert_eq!(
                got[k].len(),
                want.len(),
                "{} lane {k}: fragment count",
                top.block
            );
            if let Some(i) = (0..want.len()).find(|&i| got[k][i] != want[i]) {
                panic!(
                    "{} lane {k}: fragment {i} is {:?}, want {:?}",
                    top.block, got[k][i], want[i]
                );
            }
        }
        // The second set changes the colours (else the test shows nothing).
        let same = pipeline_fragments(&top, &spans[half..], &regs);
        assert!(
            second[0] != same[0],
            "{}: the two register sets give different colours",
            top.block
        );
        println!(
            "{}: {half} lines with the first set, {} with the second: every fragment as the pipeline gives with its set",
            top.block,
            spans.len() - half
        );
    }
}

/// Records of an unknown type, too short or too long are dropped whole and set `error`; the
/// records around them are unaffected.
#[test]
fn bad_records_are_dropped_with_error() {
    let seed = seed_for("span_bad_records_are_dropped_with_error");
    for top in tops() {
        let (spans, regs) = scene(top.kind, seed, 1);
        let good = top.words(&spans, &regs);
        let reference = reference_beats(top.kind, &good);
        let t = span_line_record(top.kind, &spans[0]);
        let unknown: Vec<Word> = vec![(3, false), (0xDEAD, false), (0xBEEF, true)];
        let mut short: Vec<Word> = t[..6].to_vec();
        short.last_mut().unwrap().1 = true;
        let mut long: Vec<Word> = t.clone();
        long.last_mut().unwrap().1 = false;
        long.extend([(0x1234, false), (0x5678, true)]);
        // The second record type: the registers, or the quadric triangle's first line (the
        // scene's first record).
        let second = match top.kind {
            SpanKind::Quadric => span_line_record(top.kind, &spans[0]),
            _ => span_register_record(&regs),
        };
        assert_eq!(second[0].0, 2);
        let mut short_regs: Vec<Word> = second[..3].to_vec();
        short_regs.last_mut().unwrap().1 = true;
        let header_only: Vec<Word> = vec![(1, true)];
        for (label, bad) in [
            ("unknown type", &unknown),
            ("short line", &short),
            ("long line", &long),
            ("short record of type 2", &short_regs),
            ("header only", &header_only),
        ] {
            let mut words = bad.clone();
            words.extend(good.iter().copied());
            let run = drive(top.kind, &words, seed, 0.0, &mut stalls(seed, 0.3), 8);
            let (beats, error) = rtl_beats(&top, &run);
            assert!(error, "{} {label}: error set", top.block);
            assert!(
                beats == reference,
                "{} {label}: the good records' beats",
                top.block
            );
            println!(
                "{} {label}: dropped, error set, {} + {} beats as without it",
                top.block,
                beats[0].len(),
                beats[1].len()
            );
        }
        let run = drive(top.kind, &good, seed, 0.0, &mut stalls(seed, 0.0), 8);
        assert!(
            !rtl_beats(&top, &run).1,
            "{}: no error on good records",
            top.block
        );
    }
}

/// With both `tready` always high the units are never held and each FIFO holds at most one
/// beat; the clocks against the span pipeline driven through its ports are reported (lines
/// shorter than their record are set-up bound).
#[test]
fn tready_high_never_holds_the_units() {
    let seed = seed_for("span_tready_high_never_holds_the_units");
    for top in tops() {
        let (spans, regs) = scene(top.kind, seed, 4);
        let run = drive(
            top.kind,
            &top.words(&spans, &regs),
            seed,
            0.0,
            &mut stalls(seed, 0.0),
            8,
        );
        assert_eq!(run.held, 0, "{}: never held", top.block);
        assert!(run.max_level <= 1, "{}: FIFO {}", top.block, run.max_level);
        let mut pipe = SpanPipe::new(top.method).unwrap();
        let st = pipe
            .run(&spans, &regs, span_clock_budget(&spans), |_| {}, |_| {})
            .unwrap();
        let short = spans
            .iter()
            .filter(|s| s.clocks() < span_line_record(top.kind, s).len() as u64)
            .count();
        println!(
            "{}: {} + {} beats in {} clocks, never held; the pipeline through its ports {} clocks (ratio {:.3}); {short} of {} lines take fewer clocks than their record's words",
            top.block,
            run.beats[0].len(),
            run.beats[1].len(),
            run.rows.len(),
            st.clocks,
            st.clocks as f64 / run.rows.len() as f64,
            spans.len()
        );
    }
}

/// The header's latency: a line record's last word accepted in clock t, its first beats
/// offered in clock t + the top's `LATENCY` on both lanes (registers applied, both banks free,
/// the units idle, `tready` high).
#[test]
fn latency_from_last_word_to_first_beat() {
    for top in tops() {
        let (spans, regs) = scene(top.kind, 7, 1);
        // A line of at least two pixels: both lanes have one in its first clock. The quadric's
        // a triangle's first line (the tracker starts there: no move before its pixels).
        let line = spans
            .iter()
            .find(|s| {
                s.m >= 1
                    && (top.kind != SpanKind::Quadric || span_line_record(top.kind, s)[0].0 == 2)
            })
            .unwrap();
        let idle = vec![0, 0, 0, 1, 1];
        let mut rows: Vec<Vec<u64>> = vec![idle.clone(); 3];
        if top.kind != SpanKind::Quadric {
            for (w, last) in span_register_record(&regs) {
                rows.push(vec![w as u64, 1, last as u64, 1, 1]);
            }
        }
        rows.extend(std::iter::repeat_n(idle.clone(), 4));
        for (w, last) in span_line_record(top.kind, line) {
            rows.push(vec![w as u64, 1, last as u64, 1, 1]);
        }
        let last = rows.len() - 1;
        rows.extend(std::iter::repeat_n(idle, top.latency + 10));
        let out = top
            .entry()
            .simulate_on(&top.options, &rows, flow::engine::fast_sim("span_stream"))
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
            assert_eq!(first - last, top.latency, "{} lane {k}", top.block);
        }
        println!(
            "{}: last word to first beat {} clocks on both lanes",
            top.block, top.latency
        );
    }
}

/// The layouts' fields are the span pipelines' load and register ports: the same names and
/// widths, in port order (between `load` and `hold`).
#[test]
fn layout_fields_are_the_pipeline_ports() {
    use rtl::stream::layout::{ANGULAR_STREAM, FAST_STREAM};
    for layout in [ANGULAR_STREAM, FAST_STREAM] {
        let (ins, _) = find(layout.wraps).unwrap().ports();
        let ports: Vec<(String, usize)> =
            ins.iter().map(|p| (p.name.to_string(), p.width)).collect();
        let fields: Vec<(String, usize)> = layout
            .triangle
            .fields
            .iter()
            .chain(layout.registers.unwrap().fields)
            .map(|f| (f.name.to_string(), f.bits as usize))
            .collect();
        assert_eq!(ports.first().map(|p| p.0.as_str()), Some("load"));
        assert_eq!(ports.last().map(|p| p.0.as_str()), Some("hold"));
        assert_eq!(ports[1..ports.len() - 1], fields[..], "{}", layout.block);
    }
}

/// `quadric-stream`'s layout covers `quadric-unit`'s load ports: the line record's fields, then
/// the triangle record's further ones, are its ports other than `load`, `first` (the record
/// type) and `hold`, the same names and widths.
#[test]
fn quadric_layout_fields_are_the_unit_ports() {
    use rtl::stream::layout::QUADRIC_STREAM;
    let (ins, _) = find("quadric-unit").unwrap().ports();
    let mut ports: Vec<(String, usize)> = ins
        .iter()
        .filter(|p| !["load", "first", "hold"].contains(&p.name))
        .map(|p| (p.name.to_string(), p.width))
        .collect();
    let mut fields: Vec<(String, usize)> = QUADRIC_STREAM
        .full
        .unwrap()
        .fields
        .iter()
        .map(|f| (f.name.to_string(), f.bits as usize))
        .collect();
    assert_eq!(ins.len(), fields.len() + 3);
    ports.sort();
    fields.sort();
    assert_eq!(ports, fields);
    // The line record is the triangle record's head.
    let line = QUADRIC_STREAM.triangle.fields;
    assert_eq!(line, &QUADRIC_STREAM.full.unwrap().fields[..line.len()]);
}
