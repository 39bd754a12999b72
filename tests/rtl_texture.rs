//! `texture` (SPEC §14), `texture-quadratic` (§15) and `texture-bezier` (§16) through
//! `textured-pipeline` (built additive, quadratic and bezier) on the built-in scenes: the RTL image against the golden image of
//! the same method (largest channel difference, pixels differing; the bound is 1 LSB)
//! and against `texture-reference` (NMSE), every fragment the golden method draws and no
//! other; then the pipeline's rate, fragments per clock, for k = 1, 2 and 4 and for the
//! per-line builds (the RTL under Verilator; k = 4 also through the pipeline's twin, which
//! must take the same clocks), and the clocks from the first load to the first fragment.
//!
//! `cargo test --release --test rtl_texture -- --include-ignored --nocapture` prints the
//! figures `docs/measurements.md` quotes (the rates' test is full tier).

use golden::methods::Method;
use golden::render::render_textured;
use indicatif::ProgressBar;
use pipeline::lit::ShadingRegs;
use pipeline::textured::{TexJob, TexRegs, TexturedPipe};
use rtl::pipelines::textured_pipeline::TexCoord;
use shadecore::rtl_engine::{max_channel_diff, render_rtl_with, RtlBuild};
use shadecore::setup::{build, SceneArgs, Setup};

#[path = "../benches/common/texture.rs"]
mod texture_runs;
use texture_runs::{jobs_of, run, scene};

#[test]
fn texture_through_the_rtl_is_within_one_lsb_of_golden_on_every_scene() {
    for (method, name) in [
        Method::Texture,
        Method::TextureQuadratic,
        Method::TextureBezier,
    ]
    .into_iter()
    .flat_map(|m| ["sphere", "torus", "plane"].map(|n| (m, n)))
    {
        let s = scene(name);
        let rtl = render_rtl_with(&s, method, RtlBuild::default(), &ProgressBar::hidden())
            .unwrap_or_else(|e| panic!("{method} {name}: {e:#}"));
        let gold = render_textured(&s.tris, method, &s.ctx, &s.texture, s.width, s.height);
        let reference = render_textured(
            &s.tris,
            Method::TextureReference,
            &s.ctx,
            &s.texture,
            s.width,
            s.height,
        );
        assert_eq!(
            rtl.frame.fragments, gold.fragments,
            "{method} {name}: the RTL's coverage differs from golden's"
        );
        let (max, n) = max_channel_diff(&rtl.frame, &gold);
        let nmse_rtl = golden::nmse::nmse(&reference.rgb, &rtl.frame.rgb);
        let nmse_gold = golden::nmse::nmse(&reference.rgb, &gold.rgb);
        println!(
            "{method} {name}: {} fragments in {} clocks ({:.3} per clock); RTL vs golden: max \
             {max} LSB, {n} pixels differ; NMSE vs texture-reference: RTL {nmse_rtl:.3e}, golden \
             {nmse_gold:.3e}; {} pixels with other visibility",
            rtl.stats.pixels,
            rtl.stats.clocks,
            rtl.stats.pixels_per_clock(),
            rtl.visibility_mismatches
        );
        assert!(
            max <= 1,
            "{method} {name}: the RTL differs from golden by {max} LSB"
        );
        assert_eq!(
            rtl.visibility_mismatches, 0,
            "{method} {name}: visibility differs"
        );
    }
}

/// `textured-stream` (k = 4) on `jobs` with `tready` high, the register record and the texture's
/// texel records first: (fragments, clocks from the first triangle word's clock to the last
/// beat, clocks of the records before it), from the stream's twin; the RTL under Verilator
/// (through `TexturedPipe`'s stream mode) must take the same clocks in all.
fn run_stream(s: &Setup, jobs: &[TexJob]) -> (u64, u64, u64) {
    let regs = ShadingRegs::of(&s.ctx).unwrap();
    let t = TexRegs::of(&s.ctx, &s.texture).unwrap();
    let p = pipeline::textured::params("4").unwrap();
    let before = pipeline::textured::textured_register_record(&regs, &t).len()
        + pipeline::textured::texel_records(&s.texture).unwrap().len();
    let words = pipeline::textured::textured_scene_words(jobs, &regs, &t, &s.texture).unwrap();
    let run = testbenches::stream::textured_stream::run(
        &p,
        &words,
        1,
        0.0,
        testbenches::stall::StallPattern::never(),
    );
    // The clock in which the first triangle word is taken: `before` words accepted.
    let mut taken = 0;
    let start = (0..run.rows.len())
        .find(|&c| {
            let hit = taken == before && run.rows[c][1] != 0 && run.outputs[c][0] != 0;
            taken += (run.rows[c][1] != 0 && run.outputs[c][0] != 0) as usize;
            hit
        })
        .unwrap();
    let last = run.outputs.iter().rposition(|o| o[1] != 0).unwrap();
    let fragments = run.beats[0].iter().filter(|b| b.pixel).count() as u64;
    // The RTL, driven by `pipeline::axis::drive` (a word every clock it is taken), ends on its
    // last `tlast` beat: the twin's last beat, one clock later than its index.
    let mut pipe = TexturedPipe::on("4", flow::engine::Sim::fastest(), true).unwrap();
    assert_eq!(pipe.load_texture(&s.texture, &regs, &t).unwrap(), 0);
    let st = pipe
        .run(jobs, &regs, &t, u64::MAX / 8, |_| {}, |_| {})
        .unwrap();
    assert_eq!(
        (st.pixels, st.clocks),
        (fragments, last as u64 + 1),
        "the RTL's stream run differs from the twin's"
    );
    (fragments, (last + 1 - start) as u64, start as u64)
}

/// Fragments and clocks for `jobs` through the pipeline's twin with k (any k: the block's
/// model, `TexCoordModel::unbuilt`).
fn run_model(s: &Setup, jobs: &[TexJob], k: u32) -> (u64, u64) {
    use testbenches::registry::Twin;
    let regs = ShadingRegs::of(&s.ctx).unwrap();
    let t = TexRegs::of(&s.ctx, &s.texture).unwrap();
    let p = pipeline::textured::params("2").unwrap();
    let mut twin = testbenches::pipelines::textured_pipeline::TexturedTwin::with_k(&p, k);
    let (mut next, mut done, mut pixels, mut clocks) = (0, 0, 0u64, 0u64);
    while done < jobs.len() {
        let load = (twin.ready() && next < jobs.len()).then(|| &jobs[next]);
        next += load.is_some() as usize;
        let o = twin.step(&pipeline::textured::tex_row(load, &regs, &t, None, false));
        clocks += 1;
        pixels += o[1];
        done += o[8] as usize;
        assert!(clocks < 100_000_000, "the model does not finish");
    }
    (pixels, clocks)
}

#[test]
#[ignore = "full tier: the textured pipeline's and its stream top's rates on the scenes, k = 1, 2, 4 and the per-line builds (the figures of docs/measurements.md)"]
fn textured_pipeline_fragments_per_clock_on_the_scenes() {
    // One scene per thread (each runs its Verilator models one after another).
    std::thread::scope(|sc| {
        let sphere = sc.spawn(|| rates_on("sphere"));
        rates_on("plane");
        sphere.join().expect("the sphere's rates");
    });
}

fn rates_on(name: &str) {
    let s = scene(name);
    let all = jobs_of(&s, TexCoord::Additive);
    let mut by_w: Vec<(TexJob, f64)> = all.clone();
    by_w.sort_by(|a, b| a.1.total_cmp(&b.1));
    let fifth = by_w.len() / 5;
    let mut sets = vec![(
        "all",
        all.iter().map(|(j, _)| j.clone()).collect::<Vec<_>>(),
    )];
    if name == "plane" {
        sets.push((
            "nearest fifth",
            by_w[..fifth].iter().map(|(j, _)| j.clone()).collect(),
        ));
        sets.push((
            "farthest fifth",
            by_w[by_w.len() - fifth..]
                .iter()
                .map(|(j, _)| j.clone())
                .collect(),
        ));
    }
    for (label, jobs) in sets {
        let (p1, c1, first1, _) = run(&s, &jobs, "1");
        let (p2, c2, first2, _) = run(&s, &jobs, "2");
        let (p4, c4, first4, _) = run(&s, &jobs, "4");
        let (pm, cm) = run_model(&s, &jobs, 4);
        assert!(
            p1 == p2 && p2 == p4,
            "{name} {label}: the builds drew different counts"
        );
        assert_eq!(
            (pm, cm),
            (p4, c4),
            "{name} {label}: the twin's k = 4 run differs from the RTL's"
        );
        let r = |p: u64, c: u64| p as f64 / c as f64;
        println!(
            "{name} ({label}, {} triangles, {p2} fragments): fragments per clock k = 1 \
             {:.3}, k = 2 {:.3}, k = 4 {:.3}; first load to first fragment {first1} \
             clocks (k = 1), {first2} (k = 2), {first4} (k = 4)",
            jobs.len(),
            r(p1, c1),
            r(p2, c2),
            r(p4, c4)
        );
        // The block's claim: a faster k never costs clocks; the first fragment comes after
        // the pipeline's latency at the earliest.
        assert!(
            c2 <= c1 && c4 <= c2,
            "{name} {label}: a larger k took more clocks"
        );
        assert!(first2 as usize + 1 >= rtl::pipelines::textured_pipeline::TEX_EVENT_TO_FRAGMENT);
        if label == "all" {
            // The per-line builds, the same triangles with their line records (pushed
            // whenever `line_ready` is high).
            for coord in [TexCoord::Quadratic, TexCoord::Bezier] {
                let lined: Vec<TexJob> = jobs_of(&s, coord).into_iter().map(|(j, _)| j).collect();
                let (pq, cq, firstq, _) = run(&s, &lined, coord.name());
                assert_eq!(
                    pq,
                    p4,
                    "{name}: the {} build drew a different count",
                    coord.name()
                );
                println!(
                    "{name}: texture={} {:.3} fragments per clock ({cq} clocks, {} line \
                     records); first load to first fragment {firstq} clocks",
                    coord.name(),
                    r(pq, cq),
                    lined.iter().map(|j| j.lines.len()).sum::<usize>()
                );
            }
            // The AXI4-Stream top, the same jobs: set-up words one per clock.
            let (ps, cs, load) = run_stream(&s, &jobs);
            assert_eq!(ps, p4, "{name}: the stream top drew a different count");
            println!(
                "{name}: textured-stream (k = 4, tready high) {:.3} fragments per clock from \
                 the first triangle word to the last beat ({cs} clocks; textured-pipeline \
                 {:.3}, ratio {:.3}); the register and texel records before it {load} clocks",
                r(ps, cs),
                r(p4, c4),
                r(ps, cs) / r(p4, c4)
            );
        }
    }
}

/// The twin's texel weighting (`testbenches`'s only unit test, kept here so that the
/// test-support crate builds no unit-test binary of its own).
#[test]
fn texel_weights_round_and_saturate() {
    use testbenches::pipelines::textured_pipeline::texel_weight;
    // 255 · 1.0 (Q1.15) = 255.0 exactly; ½ LSB of Q8.8 rounds up.
    assert_eq!(texel_weight(255, 32768), 255 << 8);
    assert_eq!(texel_weight(1, 64), 1); // 64/128 = ½ → 1
    assert_eq!(texel_weight(1, 63), 0);
    assert_eq!(texel_weight(255, 0xFFFF), 0xFFFF);
}

/// The span texture-coordinate blocks on every line of the scenes, under the fast simulator:
/// `texture-quadratic` and `texture-bezier`, fed each line's record as the golden methods
/// compute it (`golden::shading::texture::quadratic_line`, `bezier_line`), give at every
/// pixel the texel the golden `texture-quadratic` and `texture-bezier` images are drawn with
/// (their coordinates in walk order). Not a pipeline: the blocks alone, the scenes' lines back
/// to back (a line per load; the Bézier block loads when `ready`).
#[test]
fn span_texture_blocks_give_the_golden_texels_on_the_scenes() {
    use golden::shading::texture::{bezier_line, coordinates, quadratic_line, setup, Coord};
    use rtl::core::registry::Options;
    let sim = flow::engine::Sim::fastest();
    let quad = flow::blocks::find("texture-quadratic").unwrap();
    let bez = flow::blocks::find("texture-bezier").unwrap();
    for (name, eye) in [("sphere", None), ("torus", Some(1.5)), ("plane", None)] {
        let s = build(&SceneArgs {
            scene: name.into(),
            eye,
            ..SceneArgs::default()
        })
        .unwrap();
        let (mut want_q, mut want_b) = (Vec::new(), Vec::new());
        let (mut q_rows, mut b_lines) = (Vec::new(), Vec::new());
        for t in &s.tris {
            let walk = golden::raster::walk(t);
            let Some(ts) = setup(t, &s.texture).filter(|_| t.depth_plane().is_some()) else {
                continue;
            };
            let texel = |c: &glam::DVec2| [c.x as i64, c.y as i64];
            want_q.extend(
                coordinates(t, &ts, &walk, Coord::Quadratic)
                    .iter()
                    .map(texel),
            );
            want_b.extend(coordinates(t, &ts, &walk, Coord::Bezier).iter().map(texel));
            for row in walk.rows.iter().filter(|r| r.len > 0) {
                let [u, v] = quadratic_line(&ts, row);
                for k in 0..row.len {
                    let mut r = vec![1, (k == 0) as u64];
                    if k == 0 {
                        r.extend([u.u, u.d, u.dd, v.u, v.d, v.dd]);
                    } else {
                        r.extend([0; 6]);
                    }
                    q_rows.push(r);
                }
                b_lines.push(bezier_line(&ts, row));
            }
        }
        // The quadratic block: a pixel per clock, its texel a clock later.
        q_rows.push(vec![0; 8]);
        let out = quad.simulate_on(&Options::new(), &q_rows, sim).unwrap();
        let got_q: Vec<[i64; 2]> = out
            .iter()
            .filter(|o| o[0] != 0)
            .map(|o| [o[1] as u16 as i16 as i64, o[2] as u16 as i16 as i64])
            .collect();
        // The Bézier block: a line loaded whenever `ready`, the texels as `valid_out` shows them.
        let mut model = bez.model(&Options::new(), sim).unwrap();
        let (ins, outs) = bez.ports();
        let mut o = vec![0u64; outs.len()];
        let mut got_b = Vec::with_capacity(want_b.len());
        let (mut next, mut clocks) = (0, 0u64);
        while got_b.len() < want_b.len() {
            clocks += 1;
            assert!(
                clocks < 100 * want_b.len() as u64 + 1000,
                "{name}: the Bézier block stalls"
            );
            let ready = model.peek(0) != 0;
            let mut row = vec![0u64; ins.len()];
            if ready && next < b_lines.len() {
                row[0] = 1;
                row[1..ins.len() - 1].copy_from_slice(&b_lines[next].ports());
                next += 1;
            }
            model.step(&row, &mut o).unwrap();
            if o[1] != 0 {
                got_b.push([o[2] as u16 as i16 as i64, o[3] as u16 as i16 as i64]);
            }
        }
        let differ = |got: &[[i64; 2]], want: &[[i64; 2]]| {
            assert_eq!(got.len(), want.len(), "{name}: texel count");
            got.iter().zip(want).filter(|(g, w)| g != w).count()
        };
        let (dq, db) = (differ(&got_q, &want_q), differ(&got_b, &want_b));
        println!(
            "{name} (eye {eye:?}): {} pixels on {} lines; texels differing from golden: \
             texture-quadratic {dq}, texture-bezier {db} ({clocks} clocks for the Bézier block)",
            want_q.len(),
            b_lines.len()
        );
        assert_eq!((dq, db), (0, 0), "{name}: the blocks' texels are golden's");
    }
}
