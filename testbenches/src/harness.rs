//! Cycle-by-cycle harness: drives a block through `rtl::core::sim` (the hand-stepped simulation:
//! [`Dut`], [`Stepper`], re-exported here), one input row per clock, records one output row
//! per clock, and compares every clock with the golden model.
//!
//! Layers (use the lowest one that fits):
//! 1. [`Dut`] (implemented beside each block in `rtl/src` with `rtl::impl_dut!`): a block's
//!    clock, input ports and output ports as raw words (`u64`, one per port, LSB-aligned).
//! 2. [`Stepper`]: `step(&inputs, &mut outputs)` runs one clock (timing in `rtl::core::sim`).
//! 3. [`run`] / [`run_rows`]: drive a stimulus (a row list, or a closure that may react to the
//!    previous outputs), compare with per-clock [`Expected`] values (exact words, or reals
//!    within a [`Tolerance`]), keep max and RMS error per port, and on the first mismatch
//!    return a [`Failure`] naming cycle, signal, expected, actual and seed, after writing a VCD
//!    of the run around that cycle to `target/sims/<name>.vcd`.

use std::path::PathBuf;

pub use rtl::core::fixed::QFormat;

pub use rtl::core::sim::{
    simulate_rows, width_of, write_vcd_window, Dut, Port, Stepper, Word, CLOCK_PERIOD_PS,
};

/// What the golden model says about one output port in one clock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Expected {
    /// Not checked this clock (e.g. data while `valid` is low).
    DontCare,
    /// Exact raw word (flags, counters, addresses, exact arithmetic).
    Word(u64),
    /// A real value, compared through the port's [`Compare::Fixed`] format and tolerance.
    Real(f64),
    /// A real value with its own bound on |actual − value| this clock (for a block whose
    /// error budget depends on its inputs, e.g. the power unit's on n), at most the port's
    /// tolerance; the port's RMS bound still applies over the run.
    Within(f64, f64),
}

/// Allowed error of a real-valued port; derive it from the formats (and write the derivation
/// next to the formats), never from observed results.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Bound on |actual − expected| in every checked clock.
    pub max_abs: f64,
    /// Bound on the RMS of (actual − expected) over the checked clocks (checked when there
    /// are at least [`RMS_MIN_SAMPLES`] of them).
    pub rms: f64,
}

/// The RMS bound is a statistical statement about quantization noise; it is checked only for
/// ports compared in at least this many clocks (short runs of named cases check `max_abs`).
pub const RMS_MIN_SAMPLES: u64 = 1000;

/// How an output port is compared.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Compare {
    /// Raw words must be equal (expected values are [`Expected::Word`]).
    Exact,
    /// The raw word is read in `format`; expected values are [`Expected::Real`].
    Fixed { format: QFormat, tol: Tolerance },
}

/// What [`run`] needs besides the stimulus: a name (for the VCD), the seed (for messages)
/// and how to compare each output port (same order as [`Dut::outputs`]).
#[derive(Clone, Debug)]
pub struct CheckSpec {
    pub name: String,
    pub seed: u64,
    pub compare: Vec<Compare>,
}

/// Error statistics of one output port over a run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PortStats {
    pub name: String,
    /// Clocks in which the port was checked.
    pub checked: u64,
    /// Largest |actual − expected| (0 for exact ports that passed).
    pub max_abs: f64,
    /// Cycle of the largest error.
    pub worst_cycle: u64,
    sum_sq: f64,
}

impl PortStats {
    /// RMS of (actual − expected) over the checked clocks.
    pub fn rms(&self) -> f64 {
        if self.checked == 0 {
            0.0
        } else {
            (self.sum_sq / self.checked as f64).sqrt()
        }
    }
}

/// A passed run: per-port statistics plus the rows that were driven and observed.
#[derive(Clone, Debug)]
pub struct Report {
    pub name: String,
    pub seed: u64,
    pub cycles: u64,
    pub ports: Vec<PortStats>,
    pub inputs: Vec<Vec<u64>>,
    pub outputs: Vec<Vec<u64>>,
}

impl Report {
    pub fn port(&self, name: &str) -> Option<&PortStats> {
        self.ports.iter().find(|p| p.name == name)
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "[{}] {} clocks, seed {}",
            self.name, self.cycles, self.seed
        )?;
        for p in &self.ports {
            writeln!(f, "  {p}")?;
        }
        Ok(())
    }
}

impl std::fmt::Display for PortStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:<12} checked {:>8}  max |err| {:.3e} (cycle {})  rms {:.3e}",
            self.name,
            self.checked,
            self.max_abs,
            self.worst_cycle,
            self.rms()
        )
    }
}

/// Why a run failed. `Display` gives the one-paragraph message tests panic with.
///
/// It is returned by value (once per run, so its size does not matter); `run`/`run_rows`
/// therefore allow clippy's `result_large_err`, and callers may box it.
#[derive(Clone, Debug)]
pub struct Failure {
    pub name: String,
    pub seed: u64,
    /// Cycle of the mismatch (for an RMS failure: of the port's worst error).
    pub cycle: u64,
    pub signal: String,
    pub expected: String,
    pub actual: String,
    /// The VCD written for this failure, if writing succeeded.
    pub vcd: Option<PathBuf>,
    pub detail: String,
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "[{}] mismatch at cycle {} on `{}`: expected {}, actual {} (seed {}; replay with SHADECORE_SEED={})",
            self.name, self.cycle, self.signal, self.expected, self.actual, self.seed, self.seed
        )?;
        if !self.detail.is_empty() {
            write!(f, "; {}", self.detail)?;
        }
        match &self.vcd {
            Some(p) => write!(f, "\n  VCD of the run: {}", p.display()),
            None => write!(f, "\n  (no VCD written)"),
        }
    }
}

impl std::error::Error for Failure {}

pub use flow::{file_safe, target_dir};

/// `target/sims/<name>.vcd`.
pub fn vcd_path(name: &str) -> PathBuf {
    target_dir()
        .join("sims")
        .join(format!("{}.vcd", file_safe(name)))
}

/// Clocks before a failure that its VCD shows (the whole run if shorter).
pub const VCD_WINDOW_BEFORE: u64 = 200;
/// Clocks after a failure that its VCD shows.
pub const VCD_WINDOW_AFTER: u64 = 16;

fn describe(compare: &Compare, raw: u64) -> String {
    match compare {
        Compare::Exact => format!("{raw:#x}"),
        Compare::Fixed { format, .. } => {
            format!("{:.6} (raw {raw:#x}, {format})", format.to_f64(raw))
        }
    }
}

impl CheckSpec {
    /// A failure of this run at `cycle` on `signal`.
    fn failure(
        &self,
        cycle: u64,
        signal: &str,
        expected: String,
        actual: String,
        detail: String,
    ) -> Failure {
        Failure {
            name: self.name.clone(),
            seed: self.seed,
            cycle,
            signal: signal.into(),
            expected,
            actual,
            vcd: None,
            detail,
        }
    }
}

/// Compare one port's `actual` word with `e`, updating its statistics; `Some((expected,
/// detail))` on a mismatch.
fn check_port(
    e: &Expected,
    cmp: &Compare,
    actual: u64,
    st: &mut PortStats,
    cycle: u64,
) -> Option<(String, String)> {
    match (e, cmp) {
        (Expected::DontCare, _) => None,
        (Expected::Word(w), _) => {
            st.checked += 1;
            (actual != *w).then(|| (format!("{w:#x}"), String::new()))
        }
        (Expected::Real(v) | Expected::Within(v, _), Compare::Fixed { format, tol }) => {
            let bound = match e {
                Expected::Within(_, b) => b.min(tol.max_abs),
                _ => tol.max_abs,
            };
            let err = format.to_f64(actual) - v;
            st.checked += 1;
            st.sum_sq += err * err;
            if err.abs() > st.max_abs {
                st.max_abs = err.abs();
                st.worst_cycle = cycle;
            }
            (err.abs() > bound || err.is_nan())
                .then(|| (format!("{v:.6} ± {bound:.3e}"), format!("error {err:.3e}")))
        }
        (Expected::Real(_) | Expected::Within(..), Compare::Exact) => {
            panic!(
                "port {} is compared exactly but got a real expectation",
                st.name
            )
        }
    }
}

/// After a run without per-clock mismatches: the first port whose RMS error exceeds its
/// bound (checked over at least [`RMS_MIN_SAMPLES`] clocks).
fn check_rms(spec: &CheckSpec, stats: &[PortStats]) -> Option<Failure> {
    spec.compare
        .iter()
        .zip(stats)
        .find_map(|(cmp, st)| match cmp {
            Compare::Fixed { tol, .. } if st.checked >= RMS_MIN_SAMPLES && st.rms() > tol.rms => {
                Some(spec.failure(
                    st.worst_cycle,
                    &st.name,
                    format!("RMS error ≤ {:.3e}", tol.rms),
                    format!("RMS error {:.3e} over {} clocks", st.rms(), st.checked),
                    "RMS bound exceeded; the VCD shows the worst clock".into(),
                ))
            }
            _ => None,
        })
}

/// Replay `inputs` on a fresh DUT from `make` into `target/sims/<name>.vcd` around the
/// failure's cycle, and attach the path (or why it could not be written).
fn with_vcd<D: Dut>(
    mut f: Failure,
    make: impl Fn() -> D,
    inputs: &[Vec<u64>],
    name: &str,
) -> Failure {
    let path = vcd_path(name);
    let from = f.cycle.saturating_sub(VCD_WINDOW_BEFORE);
    let to = (f.cycle + VCD_WINDOW_AFTER).min(inputs.len() as u64);
    match write_vcd_window(make(), inputs, from, to, &path) {
        Ok(()) => f.vcd = Some(path),
        Err(e) => f.detail.push_str(&format!(" (VCD not written: {e})")),
    }
    f
}

/// Drive `dut` (built by `make`, which is called again to replay a failure into a VCD) one row
/// per clock from `drive(cycle, previous_outputs)` until it returns `None`; after each clock
/// compare the outputs with `expect(cycle, inputs_of_this_clock)`.
#[allow(clippy::result_large_err)]
pub fn run<D, M, Drv, Exp>(
    make: M,
    spec: &CheckSpec,
    mut drive: Drv,
    mut expect: Exp,
) -> Result<Report, Failure>
where
    D: Dut,
    M: Fn() -> D,
    Drv: FnMut(u64, &[u64]) -> Option<Vec<u64>>,
    Exp: FnMut(u64, &[u64]) -> Vec<Expected>,
{
    let dash = || "-".to_string();
    let mut s = Stepper::new(make()).map_err(|e| spec.failure(0, "(set-up)", dash(), dash(), e))?;
    let ports = s.dut().outputs();
    assert_eq!(
        ports.len(),
        spec.compare.len(),
        "CheckSpec.compare needs one entry per output port"
    );
    let mut stats: Vec<PortStats> = ports
        .iter()
        .map(|p| PortStats {
            name: p.name.to_string(),
            ..Default::default()
        })
        .collect();
    let (mut inputs, mut outputs) = (Vec::new(), Vec::new());
    let mut out = vec![0u64; ports.len()];
    s.dut().sample(&mut out);
    let mut failure: Option<Failure> = None;
    'clocks: while let Some(row) = drive(s.cycle(), &out) {
        let c = s.cycle();
        if let Err(e) = s.step(&row, &mut out) {
            failure = Some(spec.failure(c, "(set-up)", dash(), dash(), e));
            inputs.push(row);
            break;
        }
        let exp = expect(c, &row);
        inputs.push(row);
        outputs.push(out.clone());
        for (k, (e, cmp)) in exp.iter().zip(&spec.compare).enumerate() {
            if let Some((expected, detail)) = check_port(e, cmp, out[k], &mut stats[k], c) {
                failure =
                    Some(spec.failure(c, ports[k].name, expected, describe(cmp, out[k]), detail));
                break 'clocks;
            }
        }
    }
    match failure.or_else(|| check_rms(spec, &stats)) {
        None => Ok(Report {
            name: spec.name.clone(),
            seed: spec.seed,
            cycles: s.cycle(),
            ports: stats,
            inputs,
            outputs,
        }),
        Some(f) => Err(with_vcd(f, make, &inputs, &spec.name)),
    }
}

/// Check recorded `outputs` (one row per clock, from a run of `inputs` on any simulator) against
/// `expected` under `spec`, as [`run`] checks them as the clocks go (every clock's bound, then
/// RMS), without simulating again — unless a check fails: then `make`'s design replays the
/// inputs into the failure's VCD. `expected` may be shorter than `outputs` (clocks past it are
/// not checked).
#[allow(clippy::result_large_err)]
pub fn check_recorded<D: Dut>(
    make: impl Fn() -> D,
    spec: &CheckSpec,
    inputs: &[Vec<u64>],
    outputs: &[Vec<u64>],
    expected: &[Vec<Expected>],
) -> Result<Report, Failure> {
    let ports = make().outputs();
    assert_eq!(
        ports.len(),
        spec.compare.len(),
        "CheckSpec.compare needs one entry per output port"
    );
    let mut stats: Vec<PortStats> = ports
        .iter()
        .map(|p| PortStats {
            name: p.name.to_string(),
            ..Default::default()
        })
        .collect();
    for (c, (out, exp)) in outputs.iter().zip(expected).enumerate() {
        for (k, (e, cmp)) in exp.iter().zip(&spec.compare).enumerate() {
            if let Some((want, detail)) = check_port(e, cmp, out[k], &mut stats[k], c as u64) {
                let f = spec.failure(c as u64, ports[k].name, want, describe(cmp, out[k]), detail);
                return Err(with_vcd(f, make, inputs, &spec.name));
            }
        }
    }
    if let Some(f) = check_rms(spec, &stats) {
        return Err(with_vcd(f, make, inputs, &spec.name));
    }
    Ok(Report {
        name: spec.name.clone(),
        seed: spec.seed,
        cycles: outputs.len() as u64,
        ports: stats,
        inputs: inputs.to_vec(),
        outputs: outputs.to_vec(),
    })
}

/// One batch of a streamed run ([`run_stream`]): input rows and their golden expectations.
pub struct Batch {
    pub rows: Vec<Vec<u64>>,
    pub expected: Vec<Vec<Expected>>,
}

/// What a streamed run keeps: the clock count and per-port statistics, not the rows.
#[derive(Clone, Debug)]
pub struct StreamReport {
    pub name: String,
    pub seed: u64,
    pub cycles: u64,
    pub batches: usize,
    /// Clocks with at least one valid output (a port named `valid…` or `…_valid` set).
    pub valid_clocks: u64,
    pub ports: Vec<PortStats>,
}

/// A long run in constant memory: batches of stimulus are made one at a time by
/// `next_batch(k)` and driven back to back into one simulation (no reset between them); every
/// clock the outputs are compared exactly with `twin(row)` (the bit-exact twin, stepped on the
/// same rows) and with the batch's golden expectations under `spec.compare` (after the first
/// batch: valid flags every clock, data where an output is valid); the VCD, when given, is
/// written as the clocks go. Only the per-port statistics are kept.
#[allow(clippy::result_large_err)]
pub fn run_stream<D: Dut>(
    dut: D,
    spec: &CheckSpec,
    next_batch: impl FnMut(usize) -> Option<Batch>,
    twin: &mut dyn FnMut(&[u64]) -> Vec<u64>,
    vcd: Option<Box<dyn std::io::Write>>,
    progress: impl FnMut(u64),
) -> Result<StreamReport, Failure> {
    let dash = || "-".to_string();
    use rtl::core::sim::Model as _;
    let mut s = rtl::core::sim::RustHdlModel::new(dut)
        .map_err(|e| spec.failure(0, "(set-up)", dash(), dash(), e))?;
    if let Some(w) = vcd {
        s.start_vcd(w)
            .map_err(|e| spec.failure(0, "(set-up)", dash(), dash(), e))?;
    }
    let checked = run_stream_on(&mut s, spec, next_batch, twin, progress);
    // The VCD ends with the run (up to a failing clock); a write error is the failure then.
    let cycle = s.cycle();
    s.stop_vcd()
        .map_err(|e| spec.failure(cycle, "(VCD)", dash(), dash(), e))?;
    checked
}

/// [`run_stream`] on any simulated block (rust-hdl or Verilator: `flow::engine::model`),
/// from its current state; a VCD, if any, is the caller's to start and to stop (after the
/// run, which ends at the first failing clock).
#[allow(clippy::result_large_err)]
pub fn run_stream_on(
    s: &mut dyn rtl::core::sim::Model,
    spec: &CheckSpec,
    mut next_batch: impl FnMut(usize) -> Option<Batch>,
    twin: &mut dyn FnMut(&[u64]) -> Vec<u64>,
    mut progress: impl FnMut(u64),
) -> Result<StreamReport, Failure> {
    let dash = || "-".to_string();
    let ports = s.outputs().to_vec();
    let valid_ports: Vec<usize> = ports
        .iter()
        .enumerate()
        .filter(|(_, p)| is_valid_port(p.name))
        .map(|(k, _)| k)
        .collect();
    let mut stats: Vec<PortStats> = ports
        .iter()
        .map(|p| PortStats {
            name: p.name.to_string(),
            ..Default::default()
        })
        .collect();
    let mut out = vec![0u64; ports.len()];
    let (mut batches, mut valid_clocks) = (0, 0);
    while let Some(b) = next_batch(batches) {
        batches += 1;
        for (row, exp) in b.rows.iter().zip(&b.expected) {
            let c = s.cycle();
            let want = twin(row);
            s.step(row, &mut out)
                .map_err(|e| spec.failure(c, "(set-up)", dash(), dash(), e))?;
            for k in 0..ports.len() {
                if out[k] != want[k] {
                    return Err(spec.failure(
                        c,
                        ports[k].name,
                        format!("{:#x} (twin)", want[k]),
                        format!("{:#x}", out[k]),
                        "the RTL differs from its bit-exact twin".into(),
                    ));
                }
            }
            // A batch's expectations start from the reset state; after the first batch the
            // registers hold the previous batch's last values instead, so there the golden
            // model checks the valid flags every clock and the data in clocks with a valid
            // output (the twin, stepped on the same rows, checks every port every clock).
            let data_clock =
                batches == 1 || valid_ports.iter().any(|&k| exp[k] == Expected::Word(1));
            for (k, (e, cmp)) in exp.iter().zip(&spec.compare).enumerate() {
                if !data_clock && !valid_ports.contains(&k) {
                    continue;
                }
                if let Some((expected, detail)) = check_port(e, cmp, out[k], &mut stats[k], c) {
                    return Err(spec.failure(
                        c,
                        ports[k].name,
                        expected,
                        describe(cmp, out[k]),
                        detail,
                    ));
                }
            }
            valid_clocks += valid_ports.iter().any(|&k| out[k] != 0) as u64;
        }
        progress(s.cycle());
    }
    if let Some(f) = check_rms(spec, &stats) {
        return Err(f);
    }
    Ok(StreamReport {
        name: spec.name.clone(),
        seed: spec.seed,
        cycles: s.cycle(),
        batches,
        valid_clocks,
        ports: stats,
    })
}

/// A port that flags a valid output: `valid*`, a lane's `*_valid`, or an AXI4-Stream
/// master's `m_axis_tvalid` (a two-lane top's `m_axis_a_tvalid`, `m_axis_b_tvalid`).
pub fn is_valid_port(name: &str) -> bool {
    name.starts_with("valid")
        || name.ends_with("_valid")
        || (name.starts_with("m_axis") && name.ends_with("_tvalid"))
}

/// [`run`] over a fixed list: clock `c` drives `rows[c]` and checks `expected[c]`.
#[allow(clippy::result_large_err)]
pub fn run_rows<D: Dut, M: Fn() -> D>(
    make: M,
    spec: &CheckSpec,
    rows: &[Vec<u64>],
    expected: &[Vec<Expected>],
) -> Result<Report, Failure> {
    assert_eq!(
        rows.len(),
        expected.len(),
        "one expectation row per stimulus row"
    );
    run(
        make,
        spec,
        |c, _| rows.get(c as usize).cloned(),
        |c, _| expected[c as usize].clone(),
    )
}

/// Expectations of a fixed-latency pipeline: `per_input[i]` (what input row i should produce)
/// becomes the expectation of clock `i + latency`; the first `latency` clocks expect `idle`
/// (e.g. `valid_out` = 0, data don't care). Returns one row per input row.
pub fn delay_expectations(
    per_input: &[Vec<Expected>],
    latency: usize,
    idle: &[Expected],
) -> Vec<Vec<Expected>> {
    (0..per_input.len())
        .map(|c| {
            if c < latency {
                idle.to_vec()
            } else {
                per_input[c - latency].clone()
            }
        })
        .collect()
}

/// Append `n` copies of `idle` so the last real input's result leaves the pipeline.
pub fn pad_rows(rows: &mut Vec<Vec<u64>>, idle: &[u64], n: usize) {
    rows.extend(std::iter::repeat_n(idle.to_vec(), n));
}
