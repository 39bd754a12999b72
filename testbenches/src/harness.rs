//! Cycle-by-cycle harness: steps a rust-hdl block's clock by hand, one input row per clock,
//! records one output row per clock, and compares every clock with the golden model.
//!
//! Layers (use the lowest one that fits):
//! 1. [`Dut`] (usually via [`impl_dut!`]): a block's clock, input ports and output ports as
//!    raw words (`u64`, one per port, LSB-aligned; 1-bit ports are 0/1).
//! 2. [`Stepper`]: `step(&inputs, &mut outputs)` runs one clock. Timing of clock `c`:
//!    at t = 10c the clock falls and the inputs change; the design settles and the outputs
//!    are sampled (what a downstream register would capture at the coming edge); at
//!    t = 10c + 5 the clock rises and the design settles. So a block with L register stages
//!    shows the result of input row c in output row c + L (latency L), and a combinational
//!    output shows row c in row c. The generated Verilog testbench (`crate::verilog`) and
//!    the VCD use the same timing.
//! 3. [`run`] / [`run_rows`]: drive a stimulus (a row list, or a closure that may react to the
//!    previous outputs), compare with per-clock [`Expected`] values (exact words, or reals
//!    within a [`Tolerance`]), keep max and RMS error per port, and on the first mismatch
//!    return a [`Failure`] naming cycle, signal, expected, actual and seed, after writing a VCD
//!    of the run around that cycle to `target/sims/<name>.vcd`.
//!
//! Why not `simple_sim!`: it hands the circuit between threads on every event; stepping by
//! hand calls `update_all()` until `has_changed()` is false, exactly like rust-hdl's own
//! `Simulation::dispatch`, without the thread hand-offs.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;

use rust_hdl::prelude::*;

pub use rtl::fixed::QFormat;

/// One port of a [`Dut`]: its rust-hdl field name (= its name in the exported Verilog) and width.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Port {
    pub name: &'static str,
    pub width: usize,
}

/// A rust-hdl block the harness can drive. Implement it with [`impl_dut!`].
pub trait Dut: Block {
    /// Input ports, in the order of a stimulus row (the clock is not one of them).
    fn inputs(&self) -> Vec<Port>;
    /// Output ports, in the order of an output row.
    fn outputs(&self) -> Vec<Port>;
    /// The clock input.
    fn clock_mut(&mut self) -> &mut Signal<In, Clock>;
    /// Set the inputs' `next` values from a row (one raw word per input port).
    fn drive(&mut self, row: &[u64]);
    /// Read the outputs into `row` (one raw word per output port).
    fn sample(&self, row: &mut [u64]);
}

/// A port value as a raw word. Implemented for `bool` and `Bits<N>` (N ≤ 64).
pub trait Word: Synth {
    fn from_word(v: u64) -> Self;
    fn to_word(&self) -> u64;
}

impl Word for bool {
    fn from_word(v: u64) -> Self {
        v & 1 != 0
    }
    fn to_word(&self) -> u64 {
        *self as u64
    }
}

impl<const N: usize> Word for Bits<N> {
    fn from_word(v: u64) -> Self {
        let mask = if N >= 64 { u64::MAX } else { (1u64 << N) - 1 };
        (v & mask).into()
    }
    fn to_word(&self) -> u64 {
        self.to_u64()
    }
}

/// Width of a signal's type (helper for [`impl_dut!`]).
pub fn width_of<D: Direction, T: Synth>(_: &Signal<D, T>) -> usize {
    T::BITS
}

/// Implement [`Dut`] for a block from its field names:
/// ```text
/// impl_dut!(rtl::normalizer::Normalizer, clock: clock,
///           inputs: [valid_in, x, y, z], outputs: [valid_out, nx, ny, nz]);
/// ```
#[macro_export]
macro_rules! impl_dut {
    ($ty:ty, clock: $clock:ident, inputs: [$($i:ident),* $(,)?], outputs: [$($o:ident),* $(,)?]) => {
        impl $crate::harness::Dut for $ty {
            fn inputs(&self) -> Vec<$crate::harness::Port> {
                vec![$($crate::harness::Port { name: stringify!($i), width: $crate::harness::width_of(&self.$i) }),*]
            }
            fn outputs(&self) -> Vec<$crate::harness::Port> {
                vec![$($crate::harness::Port { name: stringify!($o), width: $crate::harness::width_of(&self.$o) }),*]
            }
            fn clock_mut(&mut self) -> &mut rust_hdl::prelude::Signal<rust_hdl::prelude::In, rust_hdl::prelude::Clock> {
                &mut self.$clock
            }
            #[allow(unused_assignments)]
            fn drive(&mut self, row: &[u64]) {
                let mut k = 0;
                $( self.$i.next = $crate::harness::Word::from_word(row[k]); k += 1; )*
            }
            #[allow(unused_assignments)]
            fn sample(&self, row: &mut [u64]) {
                let mut k = 0;
                $( row[k] = $crate::harness::Word::to_word(&self.$o.val()); k += 1; )*
            }
        }
    };
}

/// Settle the combinational logic: `update_all()` until nothing changes.
fn settle<B: Block>(uut: &mut B) -> Result<(), String> {
    for _ in 0..1000 {
        uut.update_all();
        if !uut.has_changed() {
            return Ok(());
        }
    }
    Err("the design did not settle in 1000 iterations (combinational loop?)".into())
}

/// Simulated time per clock in the VCD (picoseconds, as rust-hdl's VCD timescale).
pub const CLOCK_PERIOD_PS: u64 = 10;

/// Hand-stepped simulation of a [`Dut`], optionally writing a VCD.
pub struct Stepper<D: Dut> {
    dut: D,
    cycle: u64,
    vcd: Option<VCDProbe<Box<dyn Write>>>,
}

/// `write_vcd_*` take the writer by value; a boxed writer lets the probe live in the stepper.
type VCDProbe<W> = rust_hdl::core::vcd_probe::VCDProbe<W>;

impl<D: Dut> Stepper<D> {
    /// Connect, check (open signals, loops) and settle `dut` with the clock low.
    pub fn new(mut dut: D) -> Result<Self, String> {
        dut.connect_all();
        check_all(&dut).map_err(|e| format!("rust-hdl check failed: {e:?}"))?;
        dut.clock_mut().next = Clock { clk: false };
        settle(&mut dut)?;
        Ok(Self {
            dut,
            cycle: 0,
            vcd: None,
        })
    }

    /// Start writing a VCD of every signal from the current cycle on.
    pub fn start_vcd(&mut self, w: Box<dyn Write>) {
        let probe = write_vcd_header(w, &self.dut);
        let mut probe = write_vcd_dump(probe, &self.dut);
        let _ = probe.timestamp(self.cycle * CLOCK_PERIOD_PS);
        self.vcd = Some(probe);
    }

    /// Stop tracing (flushes and drops the writer).
    pub fn stop_vcd(&mut self) {
        self.vcd = None;
    }

    fn trace(&mut self, t: u64) {
        if let Some(probe) = self.vcd.take() {
            let mut probe = probe;
            let _ = probe.timestamp(t);
            self.vcd = Some(write_vcd_change(probe, &self.dut));
        }
    }

    /// One clock: apply `inputs` (clock low), settle, sample into `outputs`, raise the clock, settle.
    pub fn step(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), String> {
        let t0 = self.cycle * CLOCK_PERIOD_PS;
        self.dut.drive(inputs);
        self.dut.clock_mut().next = Clock { clk: false };
        settle(&mut self.dut)?;
        self.trace(t0);
        self.dut.sample(outputs);
        self.dut.clock_mut().next = Clock { clk: true };
        settle(&mut self.dut)?;
        self.trace(t0 + CLOCK_PERIOD_PS / 2);
        self.cycle += 1;
        Ok(())
    }

    /// Clocks stepped so far.
    pub fn cycle(&self) -> u64 {
        self.cycle
    }
    pub fn dut(&self) -> &D {
        &self.dut
    }
    pub fn dut_mut(&mut self) -> &mut D {
        &mut self.dut
    }
}

/// Run `rows` through a fresh `dut`, returning one output row per input row.
pub fn simulate_rows<D: Dut>(dut: D, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String> {
    let mut s = Stepper::new(dut)?;
    let n_out = s.dut().outputs().len();
    let mut out = Vec::with_capacity(rows.len());
    for r in rows {
        let mut o = vec![0; n_out];
        s.step(r, &mut o)?;
        out.push(o);
    }
    Ok(out)
}

/// What the golden model says about one output port in one clock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Expected {
    /// Not checked this clock (e.g. data while `valid` is low).
    DontCare,
    /// Exact raw word (flags, counters, addresses, exact arithmetic).
    Word(u64),
    /// A real value, compared through the port's [`Compare::Fixed`] format and tolerance.
    Real(f64),
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
            writeln!(
                f,
                "  {:<12} checked {:>8}  max |err| {:.3e} (cycle {})  rms {:.3e}",
                p.name,
                p.checked,
                p.max_abs,
                p.worst_cycle,
                p.rms()
            )?;
        }
        Ok(())
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

/// The workspace's `target/` directory (`CARGO_TARGET_DIR` if set).
pub fn target_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(d);
    }
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(|p| p.join("target"))
        .unwrap_or_else(|| "target".into())
}

/// `target/sims/<name>.vcd`.
pub fn vcd_path(name: &str) -> PathBuf {
    let safe: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    target_dir().join("sims").join(format!("{safe}.vcd"))
}

/// Clocks before a failure that its VCD shows (the whole run if shorter).
pub const VCD_WINDOW_BEFORE: u64 = 200;
/// Clocks after a failure that its VCD shows.
pub const VCD_WINDOW_AFTER: u64 = 16;

/// Replay `rows` on a fresh `dut` and write a VCD of cycles [from, to) to `path`.
pub fn write_vcd_window<D: Dut>(
    dut: D,
    rows: &[Vec<u64>],
    from: u64,
    to: u64,
    path: &std::path::Path,
) -> Result<(), String> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let mut file =
        Some(File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?);
    let mut s = Stepper::new(dut)?;
    let mut out = vec![0; s.dut().outputs().len()];
    for (c, r) in rows.iter().enumerate().take(to as usize) {
        if c as u64 == from {
            if let Some(f) = file.take() {
                s.start_vcd(Box::new(BufWriter::new(f)));
            }
        }
        s.step(r, &mut out)?;
    }
    s.stop_vcd();
    Ok(())
}

fn describe(compare: &Compare, raw: u64) -> String {
    match compare {
        Compare::Exact => format!("{raw:#x}"),
        Compare::Fixed { format, .. } => {
            format!("{:.6} (raw {raw:#x}, {format})", format.to_f64(raw))
        }
    }
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
    let setup_failure = |detail: String| Failure {
        name: spec.name.clone(),
        seed: spec.seed,
        cycle: 0,
        signal: "(set-up)".into(),
        expected: "-".into(),
        actual: "-".into(),
        vcd: None,
        detail,
    };
    let mut s = Stepper::new(make()).map_err(setup_failure)?;
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
    let mut inputs = Vec::new();
    let mut outputs = Vec::new();
    let mut out = vec![0u64; ports.len()];
    s.dut().sample(&mut out);
    let mut failure: Option<Failure> = None;
    'clocks: while let Some(row) = drive(s.cycle(), &out) {
        let c = s.cycle();
        if let Err(e) = s.step(&row, &mut out) {
            failure = Some(Failure {
                cycle: c,
                ..setup_failure(e)
            });
            inputs.push(row);
            break;
        }
        let exp = expect(c, &row);
        inputs.push(row);
        outputs.push(out.clone());
        for (k, (e, cmp)) in exp.iter().zip(&spec.compare).enumerate() {
            let mismatch = match (e, cmp) {
                (Expected::DontCare, _) => None,
                (Expected::Word(w), _) => {
                    stats[k].checked += 1;
                    (out[k] != *w).then(|| (format!("{w:#x}"), String::new()))
                }
                (Expected::Real(v), Compare::Fixed { format, tol }) => {
                    let err = format.to_f64(out[k]) - v;
                    let st = &mut stats[k];
                    st.checked += 1;
                    st.sum_sq += err * err;
                    if err.abs() > st.max_abs {
                        st.max_abs = err.abs();
                        st.worst_cycle = c;
                    }
                    (err.abs() > tol.max_abs || err.is_nan()).then(|| {
                        (
                            format!("{v:.6} ± {:.3e}", tol.max_abs),
                            format!("error {err:.3e}"),
                        )
                    })
                }
                (Expected::Real(_), Compare::Exact) => {
                    panic!(
                        "port {} is compared exactly but got Expected::Real",
                        ports[k].name
                    )
                }
            };
            if let Some((expected, detail)) = mismatch {
                failure = Some(Failure {
                    name: spec.name.clone(),
                    seed: spec.seed,
                    cycle: c,
                    signal: ports[k].name.to_string(),
                    expected,
                    actual: describe(cmp, out[k]),
                    vcd: None,
                    detail,
                });
                break 'clocks;
            }
        }
    }
    if failure.is_none() {
        for (k, cmp) in spec.compare.iter().enumerate() {
            if let Compare::Fixed { tol, .. } = cmp {
                let st = &stats[k];
                if st.checked >= RMS_MIN_SAMPLES && st.rms() > tol.rms {
                    failure = Some(Failure {
                        name: spec.name.clone(),
                        seed: spec.seed,
                        cycle: st.worst_cycle,
                        signal: ports[k].name.to_string(),
                        expected: format!("RMS error ≤ {:.3e}", tol.rms),
                        actual: format!("RMS error {:.3e} over {} clocks", st.rms(), st.checked),
                        vcd: None,
                        detail: "RMS bound exceeded; the VCD shows the worst clock".into(),
                    });
                    break;
                }
            }
        }
    }
    match failure {
        None => Ok(Report {
            name: spec.name.clone(),
            seed: spec.seed,
            cycles: s.cycle(),
            ports: stats,
            inputs,
            outputs,
        }),
        Some(mut f) => {
            let path = vcd_path(&spec.name);
            let from = f.cycle.saturating_sub(VCD_WINDOW_BEFORE);
            let to = (f.cycle + VCD_WINDOW_AFTER).min(inputs.len() as u64);
            match write_vcd_window(make(), &inputs, from, to, &path) {
                Ok(()) => f.vcd = Some(path),
                Err(e) => f.detail.push_str(&format!(" (VCD not written: {e})")),
            }
            Err(f)
        }
    }
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
