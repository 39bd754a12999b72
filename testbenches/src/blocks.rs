//! Per-block glue for the CLI (`shadecore sim`, `synth`, `bench`) and the tests: port lists,
//! seeded stimulus of N items with golden expectations, a checked run, and its VCD.

use std::path::{Path, PathBuf};

use rtl::export::BlockKind;
use rtl::k_recurrence::{KRecurrence, SpanNormalizer};
use rtl::normalizer::{Normalizer, NormalizerCoeffs, NormalizerK};

use crate::harness::{self, CheckSpec, Compare, Dut, Expected, Failure, Port, Report};
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

/// `n` items of seeded random stimulus for `block` (domain vectors, or span pixels).
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
