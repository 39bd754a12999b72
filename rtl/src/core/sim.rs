//! Hand-stepped simulation of the RTL blocks: the [`Dut`] view of a block (its clock, input
//! ports and output ports as raw words), the [`Stepper`] that runs it one clock at a time, and
//! VCD output. Every block file declares its ports once with [`hw_block!`](crate::hw_block),
//! which implements [`Dut`] through [`impl_dut!`](crate::impl_dut) in the declaration's port order.
//!
//! Timing of clock `c` (what [`Stepper::step`] does): at t = 10c the clock falls and the inputs
//! change; the design settles and the outputs are sampled (what a downstream register would
//! capture at the coming edge); at t = 10c + 5 the clock rises and the design settles. So a
//! block with L register stages shows the result of input row c in output row c + L
//! (latency L), and a combinational output shows row c in row c. The generated Verilog
//! testbenches and the VCD use the same timing.
//!
//! Why not `simple_sim!`: it hands the circuit between threads on every event; stepping by hand
//! calls `update_all()` until `has_changed()` is false, exactly like rust-hdl's own
//! `Simulation::dispatch`, without the thread hand-offs. This module is the product's
//! simulation engine (the render driver uses it); the checking harness is in `testbenches`.

use std::fs::File;
use std::io::{BufWriter, Write};

use rust_hdl::prelude::*;

/// One port of a [`Dut`]: its rust-hdl field name (= its name in the exported Verilog) and width.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Port {
    pub name: &'static str,
    pub width: usize,
}

/// A rust-hdl block the harness can drive. Implemented by [`hw_block!`](crate::hw_block)
/// (through [`impl_dut!`](crate::impl_dut)).
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

/// Width of a signal's type (helper for [`impl_dut!`](crate::impl_dut)).
pub fn width_of<D: Direction, T: Synth>(_: &Signal<D, T>) -> usize {
    T::BITS
}

/// Implement [`Dut`] for a block from its field names:
/// ```text
/// impl_dut!(crate::units::normalizer::Normalizer, clock: clock,
///           inputs: [valid_in, x, y, z], outputs: [valid_out, nx, ny, nz]);
/// ```
#[macro_export]
macro_rules! impl_dut {
    ($ty:ty, clock: $clock:ident, inputs: [$($i:ident),* $(,)?], outputs: [$($o:ident),* $(,)?]) => {
        impl $crate::core::sim::Dut for $ty {
            fn inputs(&self) -> Vec<$crate::core::sim::Port> {
                vec![$($crate::core::sim::Port { name: stringify!($i), width: $crate::core::sim::width_of(&self.$i) }),*]
            }
            fn outputs(&self) -> Vec<$crate::core::sim::Port> {
                vec![$($crate::core::sim::Port { name: stringify!($o), width: $crate::core::sim::width_of(&self.$o) }),*]
            }
            fn clock_mut(&mut self) -> &mut rust_hdl::prelude::Signal<rust_hdl::prelude::In, rust_hdl::prelude::Clock> {
                &mut self.$clock
            }
            #[allow(unused_assignments)]
            fn drive(&mut self, row: &[u64]) {
                let mut k = 0;
                $( self.$i.next = $crate::core::sim::Word::from_word(row[k]); k += 1; )*
            }
            #[allow(unused_assignments)]
            fn sample(&self, row: &mut [u64]) {
                let mut k = 0;
                $( row[k] = $crate::core::sim::Word::to_word(&self.$o.val()); k += 1; )*
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
    /// Boxed: a top is hundreds of kB (the fast pipeline 390 kB), and each by-value move of it
    /// in a caller's frame would sit on a thread's stack (2 MB for test and worker threads).
    dut: Box<D>,
    cycle: u64,
    vcd: Option<VCDProbe<Box<dyn Write>>>,
    /// The writer under the probe and the first error it gave (see [`VcdSink`]).
    vcd_sink: Option<VcdSink>,
}

/// `write_vcd_*` take the writer by value; a boxed writer lets the probe live in the stepper.
type VCDProbe<W> = rust_hdl::core::vcd_probe::VCDProbe<W>;

/// The writer a VCD probe writes through. rust-hdl's probe unwraps every write
/// (`vendor/rust-hdl-core/src/vcd_probe.rs`), so a full disk or `/dev/full` would panic in
/// it: this writer never reports an error to the probe. It keeps the first error, drops every
/// later write, and the stepper returns that error from its next [`Stepper::step`] and from
/// [`Stepper::stop_vcd`].
#[derive(Clone)]
struct VcdSink {
    inner: std::rc::Rc<std::cell::RefCell<Box<dyn Write>>>,
    error: std::rc::Rc<std::cell::RefCell<Option<std::io::Error>>>,
}

impl VcdSink {
    fn new(w: Box<dyn Write>) -> Self {
        Self {
            inner: std::rc::Rc::new(std::cell::RefCell::new(w)),
            error: Default::default(),
        }
    }
    /// The first write error, as one line.
    fn failed(&self) -> Result<(), String> {
        match &*self.error.borrow() {
            Some(e) => Err(format!("writing the VCD: {e}")),
            None => Ok(()),
        }
    }
    fn keep(&self, r: std::io::Result<()>) {
        if let Err(e) = r {
            self.error.borrow_mut().get_or_insert(e);
        }
    }
}

impl Write for VcdSink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.error.borrow().is_none() {
            let r = self.inner.borrow_mut().write_all(buf);
            self.keep(r);
        }
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        if self.error.borrow().is_none() {
            let r = self.inner.borrow_mut().flush();
            self.keep(r);
        }
        Ok(())
    }
}

impl<D: Dut> Stepper<D> {
    /// Connect, check (open signals, loops) and settle `dut` with the clock low.
    pub fn new(dut: D) -> Result<Self, String> {
        Self::new_boxed(Box::new(dut))
    }

    /// [`Stepper::new`] of a DUT already on the heap.
    pub fn new_boxed(mut dut: Box<D>) -> Result<Self, String> {
        dut.connect_all();
        check_all(dut.as_ref()).map_err(|e| format!("rust-hdl check failed: {e:?}"))?;
        dut.clock_mut().next = Clock { clk: false };
        settle(dut.as_mut())?;
        Ok(Self {
            dut,
            cycle: 0,
            vcd: None,
            vcd_sink: None,
        })
    }

    /// Start writing a VCD of every signal from the current cycle on. A write error (a full
    /// disk) is returned by the next [`Stepper::step`] and by [`Stepper::stop_vcd`].
    pub fn start_vcd(&mut self, w: Box<dyn Write>) {
        let sink = VcdSink::new(w);
        self.vcd_sink = Some(sink.clone());
        let probe = write_vcd_header(Box::new(sink) as Box<dyn Write>, self.dut.as_ref());
        let mut probe = write_vcd_dump(probe, self.dut.as_ref());
        let _ = probe.timestamp(self.cycle * CLOCK_PERIOD_PS);
        self.vcd = Some(probe);
    }

    /// Stop tracing: flushes the writer and drops it; the first write error, if any.
    pub fn stop_vcd(&mut self) -> Result<(), String> {
        self.vcd = None;
        match self.vcd_sink.take() {
            Some(mut sink) => {
                let _ = sink.flush();
                sink.failed()
            }
            None => Ok(()),
        }
    }

    fn trace(&mut self, t: u64) -> Result<(), String> {
        if let Some(probe) = self.vcd.take() {
            let mut probe = probe;
            let _ = probe.timestamp(t);
            self.vcd = Some(write_vcd_change(probe, self.dut.as_ref()));
        }
        match &self.vcd_sink {
            Some(sink) => sink.failed(),
            None => Ok(()),
        }
    }

    /// One clock: apply `inputs` (clock low), settle, sample into `outputs`, raise the clock, settle.
    pub fn step(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), String> {
        let t0 = self.cycle * CLOCK_PERIOD_PS;
        self.dut.drive(inputs);
        self.dut.clock_mut().next = Clock { clk: false };
        settle(self.dut.as_mut())?;
        self.trace(t0)?;
        self.dut.sample(outputs);
        self.dut.clock_mut().next = Clock { clk: true };
        settle(self.dut.as_mut())?;
        self.trace(t0 + CLOCK_PERIOD_PS / 2)?;
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

/// A simulated block as the drivers and benches see it, whatever simulates it: rust-hdl
/// ([`Stepper`]) or the exported Verilog under Verilator in process (the `verilated` crate).
/// Rows are raw words in the port order of [`Dut::inputs`] / [`Dut::outputs`]; the timing of a
/// step is [`Stepper::step`]'s.
pub trait Model {
    /// Input ports, in row order.
    fn inputs(&self) -> &[Port];
    /// Output ports, in row order.
    fn outputs(&self) -> &[Port];
    /// One clock (see [`Stepper::step`]).
    fn step(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), String>;
    /// Output port `k` as it stands between clocks (after the last rising edge settled, before
    /// the next inputs): what a registered output such as `ready` shows the driver.
    fn peek(&self, k: usize) -> u64;
    /// Clocks stepped so far.
    fn cycle(&self) -> u64;
    /// Trace every following clock into `w` as a VCD; an error where the simulator cannot.
    fn start_vcd(&mut self, w: Box<dyn Write>) -> Result<(), String>;
    /// Stop tracing (flushes the writer); nothing when not tracing. The first write error of
    /// the trace, if any.
    fn stop_vcd(&mut self) -> Result<(), String>;
    /// Which simulator this is, for messages: `"rust-hdl"` or `"verilator"`.
    fn simulator(&self) -> &'static str;
}

/// A [`Stepper`] with its port lists, as a [`Model`].
pub struct RustHdlModel<D: Dut> {
    stepper: Stepper<D>,
    inputs: Vec<Port>,
    outputs: Vec<Port>,
}

impl<D: Dut> RustHdlModel<D> {
    /// Connect, check and settle `dut` (see [`Stepper::new`]).
    pub fn new(dut: D) -> Result<Self, String> {
        Self::from_stepper(Stepper::new(dut)?)
    }
    pub fn from_stepper(stepper: Stepper<D>) -> Result<Self, String> {
        let inputs = stepper.dut().inputs();
        let outputs = stepper.dut().outputs();
        Ok(Self {
            stepper,
            inputs,
            outputs,
        })
    }
    pub fn stepper(&self) -> &Stepper<D> {
        &self.stepper
    }
    pub fn stepper_mut(&mut self) -> &mut Stepper<D> {
        &mut self.stepper
    }
}

impl<D: Dut> Model for RustHdlModel<D> {
    fn inputs(&self) -> &[Port] {
        &self.inputs
    }
    fn outputs(&self) -> &[Port] {
        &self.outputs
    }
    fn step(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), String> {
        self.stepper.step(inputs, outputs)
    }
    fn peek(&self, k: usize) -> u64 {
        let mut row = [0u64; 64];
        let n = self.outputs.len();
        if n <= row.len() {
            self.stepper.dut().sample(&mut row[..n]);
            row[k]
        } else {
            let mut v = vec![0; n];
            self.stepper.dut().sample(&mut v);
            v[k]
        }
    }
    fn cycle(&self) -> u64 {
        self.stepper.cycle()
    }
    fn start_vcd(&mut self, w: Box<dyn Write>) -> Result<(), String> {
        self.stepper.start_vcd(w);
        Ok(())
    }
    fn stop_vcd(&mut self) -> Result<(), String> {
        self.stepper.stop_vcd()
    }
    fn simulator(&self) -> &'static str {
        "rust-hdl"
    }
}

/// Run `rows` through `model` from its current state, one output row per input row.
pub fn run_model(model: &mut dyn Model, rows: &[Vec<u64>]) -> Result<Vec<Vec<u64>>, String> {
    let n_out = model.outputs().len();
    let mut out = Vec::with_capacity(rows.len());
    for r in rows {
        let mut o = vec![0; n_out];
        model.step(r, &mut o)?;
        out.push(o);
    }
    Ok(out)
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
    // Written under a temporary name and renamed into place when whole (`golden::files`).
    golden::files::write_through(path, |temp| {
        let mut file =
            Some(File::create(temp).map_err(|e| format!("cannot create {}: {e}", path.display()))?);
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
        s.stop_vcd().map_err(|e| format!("{}: {e}", path.display()))
    })
}
