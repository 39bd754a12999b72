//! Per-block glue for the CLI (`shadecore sim`, `synth`, `bench`) and the tests: port lists,
//! seeded stimulus of N items with golden expectations, a checked run, and its VCD.
//!
//! Items are domain vectors (normalizers), span pixels (span blocks) or triangles (address
//! block, BVI, raster pipe: the address bench's families, see
//! [`crate::address_block::triangle_strategy`], with random vertex intensities).

use std::path::{Path, PathBuf};

use glam::DVec3;
use golden::address_block::{AddressBlockModel, AddressOutputs, AddressSetup};
use golden::intensity_interpolator::{additions, error_bound, interpolate};
use golden::raster::walk;
use golden::shade::to_u8;
use golden::types::{Plane, ScreenTriangle, ScreenVertex};
use proptest::test_runner::TestRunner;
use rtl::address_block::AddressBlock;
use rtl::export::BlockKind;
use rtl::gouraud_raster::GouraudRaster;
use rtl::intensity_interpolator::IntensityInterpolator;
use rtl::k_recurrence::{KRecurrence, SpanNormalizer};
use rtl::normalizer::{Normalizer, NormalizerCoeffs, NormalizerK};

use crate::address_block::{self as ab, triangle_strategy};
use crate::harness::{self, CheckSpec, Compare, Dut, Expected, Failure, Port, Report, Tolerance};
use crate::intensity_interpolator::{
    bvi_rows, pipe_rows, GoldenPixel, TriangleJob, INTENSITY, LEVEL,
};
use crate::k_recurrence::{
    krec_rows, random_gaps, schedule, span_budget, span_rows, span_strategy, Span,
};
use crate::normalizer::{self as nb, Slot};
use crate::synth::{self, SynthReport};
use crate::tools::{self, Tool};

/// Input and output ports of `block` (in the harness's row order).
pub fn ports(block: BlockKind, c: &NormalizerCoeffs) -> (Vec<Port>, Vec<Port>) {
    fn p<D: Dut>(d: D) -> (Vec<Port>, Vec<Port>) {
        (d.inputs(), d.outputs())
    }
    match block {
        BlockKind::Normalizer => p(Normalizer::new(c)),
        BlockKind::NormalizerK => p(NormalizerK::new(c)),
        BlockKind::KRecurrence => p(KRecurrence::new()),
        BlockKind::SpanNormalizer => p(SpanNormalizer::new(c)),
        BlockKind::AddressBlock => p(AddressBlock::default()),
        BlockKind::IntensityInterpolator => p(IntensityInterpolator::default()),
        BlockKind::GouraudRaster => p(GouraudRaster::default()),
    }
}

/// Items `shadecore sim` simulates by default: 1000 vectors or span pixels, 20 triangles (a
/// random triangle takes 1000–2000 clocks on average, and the whole run goes into the VCD).
pub fn default_items(block: BlockKind) -> usize {
    match block {
        BlockKind::Normalizer
        | BlockKind::NormalizerK
        | BlockKind::KRecurrence
        | BlockKind::SpanNormalizer => 1000,
        BlockKind::AddressBlock | BlockKind::IntensityInterpolator | BlockKind::GouraudRaster => 20,
    }
}

/// A seeded stimulus for `block` with golden expectations and how to compare them.
pub struct Stimulus {
    pub rows: Vec<Vec<u64>>,
    pub expected: Vec<Vec<Expected>>,
    pub compare: Vec<Compare>,
    /// What one item is ("vectors", "pixels").
    pub items: &'static str,
    pub count: usize,
}

fn spans_for(
    runner: &mut proptest::test_runner::TestRunner,
    pixels: usize,
) -> (Vec<Span>, Vec<crate::k_recurrence::Clock>) {
    use proptest::strategy::{Strategy, ValueTree};
    let st = span_strategy(64);
    let mut spans = Vec::new();
    let mut total = 0;
    while total < pixels {
        let mut s = st.new_tree(runner).expect("no rejection").current();
        s.len = s.len.min(pixels - total);
        total += s.len;
        spans.push(s);
    }
    let gaps = random_gaps(runner, total);
    let sched = schedule(&spans, &gaps);
    (spans, sched)
}

/// `n` seeded random triangles ([`triangle_strategy`]) with random vertex intensities
/// (−40..320 per channel, so both saturation ends are reached): the raster jobs, and the golden
/// f64 value and addition count of every pixel in stream order. The same seed gives the same
/// triangles for the address block, the BVI and the pipe.
pub fn triangle_jobs(r: &mut TestRunner, n: usize) -> (Vec<TriangleJob>, Vec<GoldenPixel>) {
    use proptest::prelude::*;
    use proptest::strategy::ValueTree;
    let st = (
        triangle_strategy(),
        prop::array::uniform3(prop::array::uniform3(-40.0..320.0f64)),
    );
    let mut jobs = Vec::with_capacity(n);
    let mut golden = Vec::new();
    for _ in 0..n {
        let (p, v) = st.new_tree(r).expect("no rejection").current();
        let t = ScreenTriangle {
            v: p.map(|(x, y)| ScreenVertex {
                x,
                y,
                z: 0.0,
                normal: DVec3::Z,
            }),
        };
        // A zero-area triangle has no plane; the hardware still walks it (no pixel).
        let planes: [Plane; 3] = std::array::from_fn(|c| {
            t.scalar_plane([v[0][c], v[1][c], v[2][c]])
                .unwrap_or(Plane {
                    a: 0.0,
                    b: 0.0,
                    c: 0.0,
                })
        });
        let w = walk(&t);
        let per: [Vec<f64>; 3] = std::array::from_fn(|c| interpolate(&w, &planes[c]));
        for (k, adds) in additions(&w).into_iter().enumerate() {
            golden.push(([per[0][k], per[1][k], per[2][k]], adds));
        }
        jobs.push(TriangleJob::new(&t, &planes));
    }
    (jobs, golden)
}

/// The BVI's word tolerance for `golden` (`crate::intensity_interpolator` module doc): the
/// run's largest per-pixel bound, and its RMS.
fn word_tolerance(golden: &[GoldenPixel]) -> Tolerance {
    let bounds: Vec<f64> = golden.iter().map(|g| error_bound(g.1) + 1e-6).collect();
    Tolerance {
        max_abs: bounds.iter().copied().fold(0.0, f64::max).max(1e-6),
        rms: (bounds.iter().map(|b| b * b).sum::<f64>() / bounds.len().max(1) as f64)
            .sqrt()
            .max(1e-6),
    }
}

/// 8-bit outputs: within 1 LSB of the rounded, clamped golden value.
const LEVEL_1LSB: Compare = Compare::Fixed {
    format: LEVEL,
    tol: Tolerance {
        max_abs: 1.0,
        rms: 1.0,
    },
};

/// Expected colours of one output clock: the next golden pixel when `valid`, else don't care.
fn colour_expectations(
    valid: bool,
    golden: &mut std::slice::Iter<'_, GoldenPixel>,
    words: bool,
) -> Vec<Expected> {
    let n = if words { 6 } else { 3 };
    if !valid {
        return vec![Expected::DontCare; n];
    }
    let (v, _) = golden
        .next()
        .expect("golden pixels and address stream disagree");
    let mut e: Vec<Expected> = v.map(|x| Expected::Real(to_u8(x) as f64)).to_vec();
    if words {
        // RG4 carries the +½ LSB rounding bias.
        e.extend(v.map(|x| Expected::Real(x + 0.5)));
    }
    e
}

/// Rows, expectations and comparisons of a triangle block's run.
type TriangleRun = (Vec<Vec<u64>>, Vec<Vec<Expected>>, Vec<Compare>);

/// Address block: the cycle model paces the loads and predicts every port exactly.
fn address_run(jobs: &[TriangleJob]) -> TriangleRun {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let st = ab::stimulus(&setups);
    let expected = st
        .expected
        .iter()
        .map(|o| ab::outputs_row(o).into_iter().map(Expected::Word).collect())
        .collect();
    (st.rows, expected, vec![Compare::Exact; 9])
}

/// BVI, driven by the golden address block's stream: the colour of event c in clock c + L.
fn bvi_run(jobs: &[TriangleJob], golden: &[GoldenPixel]) -> TriangleRun {
    let lat = BlockKind::IntensityInterpolator.latency();
    let (rows, stream) = bvi_rows(jobs);
    let mut g = golden.iter();
    let expected: Vec<Vec<Expected>> = (0..rows.len())
        .map(|c| {
            let valid = c >= lat && stream[c - lat].valid;
            let mut e = vec![Expected::Word(valid as u64)];
            e.extend(colour_expectations(valid, &mut g, true));
            e
        })
        .collect();
    assert!(g.next().is_none(), "golden pixels left over");
    let word = Compare::Fixed {
        format: INTENSITY,
        tol: word_tolerance(golden),
    };
    let compare = vec![
        Compare::Exact,
        LEVEL_1LSB,
        LEVEL_1LSB,
        LEVEL_1LSB,
        word,
        word,
        word,
    ];
    (rows, expected, compare)
}

/// Raster pipe: the address block's cycle model, loaded in the clocks [`pipe_rows`] loads; the
/// pipe shows `ready` as is and the address stream one BVI latency later, with its colours.
fn pipe_run(jobs: &[TriangleJob], golden: &[GoldenPixel]) -> TriangleRun {
    let setups: Vec<AddressSetup> = jobs.iter().map(|j| j.addr).collect();
    let rows = pipe_rows(jobs);
    let delay = BlockKind::GouraudRaster.latency() - BlockKind::AddressBlock.latency();
    let mut m = AddressBlockModel::new();
    let mut addr: Vec<AddressOutputs> = Vec::with_capacity(rows.len());
    let mut next = 0;
    for row in &rows {
        let o = m.outputs();
        let load = (row[0] != 0).then(|| &setups[next]);
        next += load.is_some() as usize;
        addr.push(o);
        m.clock(load);
    }
    let mut g = golden.iter();
    let expected: Vec<Vec<Expected>> = (0..rows.len())
        .map(|c| {
            let d = match c.checked_sub(delay) {
                Some(k) => addr[k],
                None => AddressOutputs::default(),
            };
            let w = |v: u32| Expected::Word(v as u64);
            let mut e = vec![w(addr[c].ready as u32), w(d.valid as u32), w(d.x), w(d.y)];
            e.extend(colour_expectations(d.valid, &mut g, false));
            e.push(w(d.done as u32));
            e
        })
        .collect();
    assert!(g.next().is_none(), "golden pixels left over");
    let compare = vec![
        Compare::Exact,
        Compare::Exact,
        Compare::Exact,
        Compare::Exact,
        LEVEL_1LSB,
        LEVEL_1LSB,
        LEVEL_1LSB,
        Compare::Exact,
    ];
    (rows, expected, compare)
}

fn triangle_stimulus((rows, expected, compare): TriangleRun, n: usize) -> Stimulus {
    Stimulus {
        rows,
        expected,
        compare,
        items: "triangles",
        count: n,
    }
}

/// `n` items of seeded random stimulus for `block` (domain vectors, span pixels, or triangles).
pub fn stimulus(block: BlockKind, c: &NormalizerCoeffs, n: usize, seed: u64) -> Stimulus {
    let mut r = nb::seeded_runner(seed);
    match block {
        BlockKind::Normalizer | BlockKind::NormalizerK => {
            let vectors = nb::domain_vectors(&mut r, n);
            let slots: Vec<Slot> = vectors
                .iter()
                .map(|v| Slot::Vector(nb::quantize(*v)))
                .collect();
            let lat = block.latency();
            let mut rows = nb::stimulus_rows(&slots, lat);
            let expected = nb::expectations(&rows, lat, c.requested);
            if block == BlockKind::NormalizerK {
                for row in &mut rows {
                    let i = [row[1], row[2], row[3]].map(|w| rtl::fixed::NORMAL.to_int(w));
                    row.push((i[0] * i[0] + i[1] * i[1] + i[2] * i[2]) as u64);
                }
            }
            let b = nb::domain_budget(c);
            Stimulus {
                rows,
                expected,
                compare: nb::check_spec("", 0, &b).compare,
                items: "vectors",
                count: n,
            }
        }
        BlockKind::KRecurrence => {
            let (spans, sched) = spans_for(&mut r, n);
            let (rows, expected) = krec_rows(&spans, &sched);
            Stimulus {
                rows,
                expected,
                compare: vec![Compare::Exact, Compare::Exact],
                items: "pixels",
                count: n,
            }
        }
        BlockKind::SpanNormalizer => {
            let (spans, sched) = spans_for(&mut r, n);
            let (rows, expected) = span_rows(&spans, &sched, c.requested);
            let b = span_budget(&spans, c);
            Stimulus {
                rows,
                expected,
                compare: nb::check_spec("", 0, &b).compare,
                items: "pixels",
                count: n,
            }
        }
        BlockKind::AddressBlock => {
            let (jobs, _) = triangle_jobs(&mut r, n);
            triangle_stimulus(address_run(&jobs), n)
        }
        BlockKind::IntensityInterpolator => {
            let (jobs, golden) = triangle_jobs(&mut r, n);
            triangle_stimulus(bvi_run(&jobs, &golden), n)
        }
        BlockKind::GouraudRaster => {
            let (jobs, golden) = triangle_jobs(&mut r, n);
            triangle_stimulus(pipe_run(&jobs, &golden), n)
        }
    }
}

/// Run `stim` through `block`, checking every clock against the golden model.
#[allow(clippy::result_large_err)] // harness::Failure, returned once per run
pub fn run_checked(
    block: BlockKind,
    c: &NormalizerCoeffs,
    stim: &Stimulus,
    name: &str,
    seed: u64,
) -> Result<Report, Failure> {
    let spec = CheckSpec {
        name: name.into(),
        seed,
        compare: stim.compare.clone(),
    };
    let (rows, exp) = (&stim.rows, &stim.expected);
    match block {
        BlockKind::Normalizer => harness::run_rows(|| Normalizer::new(c), &spec, rows, exp),
        BlockKind::NormalizerK => harness::run_rows(|| NormalizerK::new(c), &spec, rows, exp),
        BlockKind::KRecurrence => harness::run_rows(KRecurrence::new, &spec, rows, exp),
        BlockKind::SpanNormalizer => harness::run_rows(|| SpanNormalizer::new(c), &spec, rows, exp),
        BlockKind::AddressBlock => harness::run_rows(AddressBlock::default, &spec, rows, exp),
        BlockKind::IntensityInterpolator => {
            harness::run_rows(IntensityInterpolator::default, &spec, rows, exp)
        }
        BlockKind::GouraudRaster => harness::run_rows(GouraudRaster::default, &spec, rows, exp),
    }
}

/// Replay `rows` through `block` writing a VCD of the whole run (every signal) to `path`.
pub fn write_vcd(
    block: BlockKind,
    c: &NormalizerCoeffs,
    rows: &[Vec<u64>],
    path: &Path,
) -> Result<(), String> {
    let n = rows.len() as u64;
    match block {
        BlockKind::Normalizer => harness::write_vcd_window(Normalizer::new(c), rows, 0, n, path),
        BlockKind::NormalizerK => harness::write_vcd_window(NormalizerK::new(c), rows, 0, n, path),
        BlockKind::KRecurrence => harness::write_vcd_window(KRecurrence::new(), rows, 0, n, path),
        BlockKind::SpanNormalizer => {
            harness::write_vcd_window(SpanNormalizer::new(c), rows, 0, n, path)
        }
        BlockKind::AddressBlock => {
            harness::write_vcd_window(AddressBlock::default(), rows, 0, n, path)
        }
        BlockKind::IntensityInterpolator => {
            harness::write_vcd_window(IntensityInterpolator::default(), rows, 0, n, path)
        }
        BlockKind::GouraudRaster => {
            harness::write_vcd_window(GouraudRaster::default(), rows, 0, n, path)
        }
    }
}

/// Outcome of [`sim_to_vcd`].
pub struct SimOutcome {
    pub report: Report,
    pub vcd: PathBuf,
    pub items: &'static str,
    pub count: usize,
}

/// `shadecore sim`: `n` seeded items through `block`, checked against the golden model every
/// clock, then replayed into a VCD at `vcd`. A check failure is returned as the error (its
/// own VCD is under `target/sims/`).
pub fn sim_to_vcd(
    block: BlockKind,
    c: &NormalizerCoeffs,
    n: usize,
    seed: u64,
    vcd: &Path,
) -> Result<SimOutcome, String> {
    let stim = stimulus(block, c, n, seed);
    let report =
        run_checked(block, c, &stim, &format!("sim-{block}"), seed).map_err(|f| f.to_string())?;
    write_vcd(block, c, &report.inputs, vcd)?;
    Ok(SimOutcome {
        report,
        vcd: vcd.to_path_buf(),
        items: stim.items,
        count: stim.count,
    })
}

/// `shadecore synth`: Yosys cell counts, and the nextpnr UP5K Fmax when `pnr` and
/// nextpnr-ice40 is installed (`None` otherwise).
pub fn synth_block(
    block: BlockKind,
    c: &NormalizerCoeffs,
    pnr: bool,
) -> Result<(SynthReport, Option<f64>), String> {
    if !tools::available(Tool::Yosys) {
        return Err("yosys is not installed (apt-get install yosys)".into());
    }
    let v = rtl::export::verilog(block, c)?;
    let module = block.module_name();
    let rep = synth::check_and_synth(&v, &module, &format!("synth-{block}"))?;
    let fmax = if pnr && tools::available(Tool::NextpnrIce40) {
        let (i, o) = ports(block, c);
        Some(synth::fmax_ice40_up5k(
            &v,
            &module,
            &i,
            &o,
            &format!("pnr-{block}"),
        )?)
    } else {
        None
    };
    Ok((rep, fmax))
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRIANGLE_BLOCKS: [BlockKind; 3] = [
        BlockKind::AddressBlock,
        BlockKind::IntensityInterpolator,
        BlockKind::GouraudRaster,
    ];

    /// The latencies the registry states are what the RTL does: one fixed triangle, loaded in
    /// clock 0; its first row has pixels.
    #[test]
    fn triangle_block_latencies_match_the_rtl() {
        let t = ScreenTriangle {
            v: [(3, 1), (40, 7), (11, 30)].map(|(x, y)| ScreenVertex {
                x,
                y,
                z: 0.0,
                normal: DVec3::Z,
            }),
        };
        let ramp = |c: f64| Plane { a: 1.0, b: 2.0, c };
        let job = TriangleJob::new(&t, &[ramp(10.0), ramp(20.0), ramp(30.0)]);
        let first = |outs: &[Vec<u64>], k: usize| outs.iter().position(|o| o[k] != 0);

        let (rows, _, _) = address_run(&[job]);
        assert_eq!(rows[0][0], 1, "loaded in clock 0");
        let outs = harness::simulate_rows(AddressBlock::default(), &rows).unwrap();
        // Outputs: ready, valid, x, y, step, line_start, row_start, carry, done.
        assert_eq!(first(&outs, 6), Some(BlockKind::AddressBlock.latency()));
        assert_eq!(first(&outs, 1), Some(BlockKind::AddressBlock.latency()));

        let rows = pipe_rows(&[job]);
        assert_eq!(rows[0][0], 1, "loaded in clock 0");
        let outs = harness::simulate_rows(GouraudRaster::default(), &rows).unwrap();
        assert_eq!(first(&outs, 1), Some(BlockKind::GouraudRaster.latency()));

        // BVI: valid_out is in_valid (input 13) delayed by the latency, every clock.
        let (rows, _) = bvi_rows(&[job]);
        let outs = harness::simulate_rows(IntensityInterpolator::default(), &rows).unwrap();
        let lat = BlockKind::IntensityInterpolator.latency();
        assert!(rows.iter().any(|r| r[13] != 0));
        for c in lat..rows.len() {
            assert_eq!(outs[c][0], rows[c - lat][13], "clock {c}");
        }
    }

    /// `shadecore sim` on the triangle blocks: a checked run and a VCD; and the check can fail
    /// (one expected address / colour altered).
    #[test]
    fn triangle_blocks_simulate_and_the_check_can_fail() {
        let c = NormalizerCoeffs::published();
        let seed = golden::testing::seed_for("blocks_triangle_sim");
        println!("[blocks_triangle_sim] seed {seed}");
        for b in TRIANGLE_BLOCKS {
            let vcd = harness::target_dir()
                .join("sims")
                .join(format!("test-blocks-{b}.vcd"));
            let out = sim_to_vcd(b, &c, 6, seed, &vcd).unwrap_or_else(|e| panic!("{b}: {e}"));
            let (ins, outs) = ports(b, &c);
            // The VCD declares every port with its width (tests/waveform.rs reads values back).
            let vars = crate::vcd_check::variables(&vcd).unwrap();
            for p in ins.iter().chain(&outs) {
                let full = format!("uut.{}", p.name);
                assert!(
                    vars.iter()
                        .any(|(n, w)| *n == full && *w as usize == p.width),
                    "{b}: {full} ({} bits) missing from the VCD",
                    p.width
                );
            }
            let valid = outs
                .iter()
                .position(|p| p.name.starts_with("valid"))
                .unwrap();
            let pixels = out.report.outputs.iter().filter(|o| o[valid] != 0).count();
            assert!(pixels > 0, "{b}: no pixel in {} clocks", out.report.cycles);

            // Alter the expectation of the first valid pixel: x + 1 (address block, pipe)
            // or red + 2 LSB (BVI); the run must fail there.
            let mut stim = stimulus(b, &c, 6, seed);
            let clock = stim
                .expected
                .iter()
                .position(|e| e[valid] == Expected::Word(1))
                .unwrap();
            let port = if b == BlockKind::IntensityInterpolator {
                1
            } else {
                2
            };
            stim.expected[clock][port] = match stim.expected[clock][port] {
                Expected::Word(w) => Expected::Word(w + 1),
                Expected::Real(v) => Expected::Real(v + 2.0),
                Expected::DontCare => panic!("{b}: pixel not checked"),
            };
            let f = run_checked(b, &c, &stim, &format!("blocks-mutant-{b}"), seed)
                .expect_err("an altered expectation must fail");
            assert_eq!(f.cycle as usize, clock, "{b}");
            assert_eq!(f.signal, outs[port].name, "{b}");
        }
    }
}
