//! `textured-stream` (the AXI4-Stream top of the textured pipeline): back-pressure keeps every
//! fragment, in order, under random and long stalls, the RTL equal to the twin every clock; a
//! texture rewritten between triangles changes only the triangles after it; the header's
//! latency; the layout's fields are the pipeline's ports. (The generic tests — twin every
//! clock, golden, the Verilog — are the registry's.)

use golden::testing::seed_for;
use golden::texture::Texture;
use pipeline::axis::{Beat, Word};
use pipeline::textured::{
    texel_records, textured_register_record, textured_scene_words, textured_triangle_record,
};
use rtl::core::registry::{BlockParams, Options};
use rtl::pipelines::textured_pipeline::{TexCoord, TexturedParams};
use rtl::stream::textured_stream::{TexturedStream, FIFO_DEPTH};
use testbenches::pipelines::textured_pipeline::bench_texture;
use testbenches::registry::find;
use testbenches::registry::Twin;
use testbenches::stall::StallPattern;
use testbenches::stream::stream_twin::LaneRun;
use testbenches::stream::textured_stream::{
    pipeline_beats, run, scene, scene_of, TexturedStreamTwin,
};

fn params() -> (TexturedParams, Options) {
    let o = Options::new();
    (TexturedParams::from_options(&o).unwrap(), o)
}

/// The beats the RTL delivers for the run's input rows (Verilator in process where installed,
/// else rust-hdl), which must equal the twin's outputs every clock; and its `error` at the end.
fn rtl_beats(run: &LaneRun<1>, o: &Options) -> (Vec<Beat>, bool) {
    let out = find("textured-stream")
        .unwrap()
        .simulate_on(o, &run.rows, flow::engine::fast_sim("textured_stream"))
        .unwrap();
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
    let seed = seed_for("textured_back_pressure_keeps_every_fragment_in_order");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let (p, o) = params();
    let (jobs, regs, t, texture) = scene(seed, 8);
    let words = textured_scene_words(&jobs, &regs, &t, &texture).unwrap();
    let reference = pipeline_beats(&p, &jobs, &regs, &t, &texture);
    let pixels = reference.iter().filter(|b| b.pixel).count();
    assert!(pixels > 500, "a scene worth stalling: {pixels} fragments");
    assert_eq!(reference.iter().filter(|b| b.last).count(), jobs.len());
    for (label, stall_p, gap) in [("random 25 %", 0.25, 0.1), ("random 90 %", 0.9, 0.0)] {
        let run = run(
            &p,
            &words,
            seed,
            gap,
            StallPattern::new(seed ^ label.len() as u64, stall_p),
        );
        let (beats, error) = rtl_beats(&run, &o);
        assert!(!error, "{label}: no protocol error");
        assert_eq!(beats.len(), reference.len(), "{label}: beat count");
        assert!(
            beats == reference,
            "{label}: beats differ from the pipeline's"
        );
        assert!(run.max_level <= FIFO_DEPTH);
        println!(
            "{label}: {} beats in {} clocks, consumer stalled {} clocks, address block held {}, FIFO at most {}",
            beats.len(),
            run.rows.len(),
            run.consumer_stalls[0],
            run.held,
            run.max_level
        );
        if stall_p > 0.5 {
            assert!(run.held > 0, "{label}: the address block was held");
        }
    }
    // Long stretches: `tready` low for 3 000 clocks, twice, after the texture is in.
    let load = words.len();
    let mut random = StallPattern::new(seed, 0.2);
    let stalls = StallPattern::from_fn(move |c| {
        let r = random.next_stalled();
        (load + 300..load + 3300).contains(&c) || (load + 4000..load + 7000).contains(&c) || r
    });
    let run = run(&p, &words, seed, 0.05, stalls);
    let (beats, error) = rtl_beats(&run, &o);
    assert!(!error && beats == reference, "long stalls: beats differ");
    assert!(run.held > 5000, "held {} clocks", run.held);
    assert!(run.max_level <= FIFO_DEPTH);
    println!(
        "long stalls: held {} clocks, FIFO at most {} of {FIFO_DEPTH}",
        run.held, run.max_level
    );
}

/// A texture rewritten between triangles (every texel) is written only after every triangle
/// before it has left the pipeline: the first triangles' fragments all read the first
/// texture, the later ones the second.
#[test]
fn a_new_texture_applies_to_the_triangles_after_it() {
    let seed = seed_for("a_new_texture_applies_to_the_triangles_after_it");
    let (p, o) = params();
    let (jobs, regs, t, first) = scene(seed, 6);
    let second: Texture = bench_texture(seed ^ 0x5eed);
    let half = jobs.len() / 2;
    let mut words: Vec<Word> = textured_scene_words(&jobs[..half], &regs, &t, &first).unwrap();
    words.extend(texel_records(&second).unwrap());
    jobs[half..]
        .iter()
        .for_each(|j| words.extend(textured_triangle_record(j)));
    let run = run(&p, &words, seed, 0.0, StallPattern::new(seed, 0.3));
    let (beats, error) = rtl_beats(&run, &o);
    assert!(!error);
    let mut want = pipeline_beats(&p, &jobs[..half], &regs, &t, &first);
    want.extend(pipeline_beats(&p, &jobs[half..], &regs, &t, &second));
    assert_eq!(beats.len(), want.len(), "beat count");
    // A beat without a pixel carries only its `tlast`.
    let same = |a: &Beat, b: &Beat| (a.pixel, a.last) == (b.pixel, b.last) && (!a.pixel || a == b);
    if let Some(i) = (0..want.len()).find(|&i| !same(&beats[i], &want[i])) {
        panic!("beat {i} is {:?}, want {:?}", beats[i], want[i]);
    }
    // The second texture changes the colours (else the test shows nothing).
    assert!(
        pipeline_beats(&p, &jobs[..half], &regs, &t, &first)
            != pipeline_beats(&p, &jobs[..half], &regs, &t, &second),
        "the two textures give the first triangles different colours"
    );
}

/// The header's latency: a triangle record's last word accepted in clock t, its first beat
/// offered in clock t + `TexturedStream::LATENCY` (banks free, the pipeline idle, `tready`
/// high, the first pixel's texel settling at once), and the register record and a texel
/// record taken a word per clock.
#[test]
fn latency_from_last_word_to_first_beat() {
    let (p, o) = params();
    let (jobs, regs, t, texture) = scene(7, 1);
    let mut rows: Vec<Vec<u64>> = Vec::new();
    for (w, last) in textured_register_record(&regs, &t) {
        rows.push(vec![w as u64, 1, last as u64, 1]);
    }
    rows.extend(std::iter::repeat_n(vec![0, 0, 0, 1], 10));
    // Sixteen texel records back to back: four clocks a texel (its three words, then the
    // clock in which `s_axis_tready` is low while the record moves to the load bank).
    // The producer follows the twin's `s_axis_tready` (the RTL is held to the twin below).
    let texels = &texel_records(&texture).unwrap()[..16 * 3];
    let mut twin = TexturedStreamTwin::new(&p);
    for r in &rows {
        twin.step(r);
    }
    let at = rows.len();
    let mut k = 0;
    while k < texels.len() {
        assert!(
            rows.len() - at < 16 * 4,
            "the texels take over four clocks each"
        );
        let row = vec![texels[k].0 as u64, 1, texels[k].1 as u64, 1];
        k += (twin.step(&row)[0] != 0) as usize;
        rows.push(row);
    }
    assert_eq!(rows.len() - at, 16 * 4 - 1, "four clocks a texel");
    rows.extend(std::iter::repeat_n(vec![0, 0, 0, 1], 10));
    for (w, last) in textured_triangle_record(&jobs[0]) {
        rows.push(vec![w as u64, 1, last as u64, 1]);
    }
    let last = rows.len() - 1;
    let latency = TexturedStream::LATENCY;
    rows.extend(std::iter::repeat_n(vec![0, 0, 0, 1], latency + 200));
    let out = find("textured-stream")
        .unwrap()
        .simulate_on(&o, &rows, flow::engine::fast_sim("textured_stream"))
        .unwrap();
    assert!(
        out[at + 16 * 4..=last]
            .iter()
            .zip(&rows[at + 16 * 4..])
            .all(|(o, r)| r[1] == 0 || o[0] != 0),
        "every triangle word accepted when shown"
    );
    let mut twin = TexturedStreamTwin::new(&p);
    let twin_out: Vec<Vec<u64>> = rows.iter().map(|r| twin.step(r)).collect();
    assert!(out == twin_out, "the RTL equals the twin");
    let first = (0..out.len()).find(|&c| out[c][1] != 0).unwrap();
    // The first event may be a line start without a pixel or a pixel needing steps: the
    // first beat comes at the latency or later, never earlier; a pixel settling at once is
    // the common case, and the seeded triangle's first pixel is one.
    assert_eq!(
        first - last,
        latency,
        "first beat {} clocks after",
        first - last
    );
}

/// The layout's textured records are `textured-pipeline`'s set-up, register, texel-write and
/// line ports: the same names and widths, in port order (between `load` and `hold`, `tex_we`
/// the texel record's strobe, `line_push` the line record's).
#[test]
fn layout_fields_are_the_pipeline_ports() {
    use rtl::stream::layout::{TEXEL, TEXTURED_LINE, TEXTURED_REGISTERS, TEXTURED_TRIANGLE};
    let (ins, _) = find("textured-pipeline").unwrap().ports();
    let ports: Vec<(String, usize)> = ins.iter().map(|p| (p.name.to_string(), p.width)).collect();
    let mut fields: Vec<(String, usize)> = TEXTURED_TRIANGLE
        .fields
        .iter()
        .chain(TEXTURED_REGISTERS.fields)
        .map(|f| (f.name.to_string(), f.bits as usize))
        .collect();
    fields.push(("tex_we".to_string(), 1));
    fields.extend(
        TEXEL
            .fields
            .iter()
            .map(|f| (f.name.to_string(), f.bits as usize)),
    );
    // Then the per-line builds' line record, its strobe `line_push`.
    fields.push(("line_push".to_string(), 1));
    fields.extend(
        TEXTURED_LINE
            .fields
            .iter()
            .map(|f| (f.name.to_string(), f.bits as usize)),
    );
    assert_eq!(ports.first().map(|p| p.0.as_str()), Some("load"));
    assert_eq!(ports.last().map(|p| p.0.as_str()), Some("hold"));
    assert_eq!(ports[1..ports.len() - 1], fields[..]);
}

/// With `m_axis_tready` always high the FIFO holds at most one beat and the address block is
/// never held.
#[test]
fn tready_high_never_holds_the_address_block() {
    let seed = seed_for("textured_tready_high_never_holds_the_address_block");
    let (p, _) = params();
    let (jobs, regs, t, texture) = scene(seed, 12);
    let words = textured_scene_words(&jobs, &regs, &t, &texture).unwrap();
    let run = run(&p, &words, seed, 0.0, StallPattern::never());
    assert_eq!(run.held, 0);
    assert!(run.max_level <= 1, "FIFO at most {}", run.max_level);
}

/// The per-line builds behind the stream top (`texture=quadratic`, `texture=bezier`): each
/// triangle's line records follow its triangle record on the set-up stream; under random
/// stalls of both streams the RTL equals the twin every clock, and the beats are
/// `textured-pipeline`'s with its line records pushed through its ports. The texels differ
/// from the additive build's on these triangles (else the line records would show nothing).
#[test]
fn per_line_builds_take_their_line_records_on_the_stream() {
    let seed = seed_for("per_line_builds_take_their_line_records_on_the_stream");
    println!("seed {seed} (SHADECORE_SEED overrides)");
    for coord in [TexCoord::Quadratic, TexCoord::Bezier] {
        let o = Options::new().with("texture", coord.name());
        let p = TexturedParams::from_options(&o).unwrap();
        let (jobs, regs, t, texture) = scene_of(seed, 6, coord);
        let lines: usize = jobs.iter().map(|j| j.lines.len()).sum();
        assert!(lines > 20, "{}: {lines} line records", coord.name());
        let words = textured_scene_words(&jobs, &regs, &t, &texture).unwrap();
        let reference = pipeline_beats(&p, &jobs, &regs, &t, &texture);
        assert_eq!(reference.iter().filter(|b| b.last).count(), jobs.len());
        let run = run(&p, &words, seed, 0.1, StallPattern::new(seed, 0.3));
        let (beats, error) = rtl_beats(&run, &o);
        assert!(!error, "{}: no protocol error", coord.name());
        // A beat without a pixel carries only its `tlast`.
        let same =
            |a: &Beat, b: &Beat| (a.pixel, a.last) == (b.pixel, b.last) && (!a.pixel || a == b);
        let n = beats.len().min(reference.len());
        if let Some(i) = (0..n).find(|&i| !same(&beats[i], &reference[i])) {
            panic!(
                "{}: beat {i} of {} ({} expected) is {:?}, want {:?}",
                coord.name(),
                beats.len(),
                reference.len(),
                beats[i],
                reference[i]
            );
        }
        assert_eq!(beats.len(), reference.len(), "{}: beat count", coord.name());
        let (additive, ..) = scene(seed, 6);
        let pa = TexturedParams::default();
        assert!(
            pipeline_beats(&pa, &additive, &regs, &t, &texture) != reference,
            "{}: the build's texels are its own",
            coord.name()
        );
        println!(
            "{}: {} line records, {} beats in {} clocks, address block held {}",
            coord.name(),
            lines,
            beats.len(),
            run.rows.len(),
            run.held
        );
    }
}
