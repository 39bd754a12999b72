//! A loaded model library and its instances.

use std::ffi::{c_void, CStr};
use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use rtl::core::sim::{Model, Port};

type AbiFn = unsafe extern "C" fn() -> u32;
type PortsFn = unsafe extern "C" fn() -> *const std::ffi::c_char;
type NewFn = unsafe extern "C" fn() -> *mut c_void;
type DeleteFn = unsafe extern "C" fn(*mut c_void);
type StepFn = unsafe extern "C" fn(*mut c_void, *const u64, *mut u64);
type PeekFn = unsafe extern "C" fn(*mut c_void, u32) -> u64;
type BenchFn = unsafe extern "C" fn(*mut c_void, *const u64, u64) -> u64;

/// One compiled top, loaded (`dlopen`) with its entry points resolved.
pub struct Library {
    // Keeps the code mapped for as long as an instance or a function pointer lives.
    _lib: libloading::Library,
    new: NewFn,
    delete: DeleteFn,
    step: StepFn,
    peek: PeekFn,
    bench: BenchFn,
    inputs: Vec<Port>,
    outputs: Vec<Port>,
}

fn parse_ports(side: &str) -> Result<Vec<Port>, String> {
    if side.is_empty() {
        return Ok(Vec::new());
    }
    side.split(',')
        .map(|p| {
            let (name, w) = p.split_once('/').ok_or("no width")?;
            let width = w.parse().map_err(|_| "bad width")?;
            // Names live as long as the process: a library's port names are few and loaded once.
            Ok(Port {
                name: Box::leak(name.to_string().into_boxed_str()),
                width,
            })
        })
        .collect::<Result<_, &str>>()
        .map_err(|e| format!("port list: {e}"))
}

impl Library {
    /// Load `path` and check that it states the ABI and the port list `expected`.
    pub(crate) fn open(path: &Path, expected: &str) -> Result<Library, String> {
        // SAFETY: the library is one this crate generated and compiled (its checksum was checked
        // by the caller); its initialisers are Verilator's runtime and the model's.
        let lib = unsafe { libloading::Library::new(path) }.map_err(|e| format!("dlopen: {e}"))?;
        // SAFETY: the symbols' types are those `wrapper` declares.
        unsafe {
            let sym = |name: &[u8]| -> Result<*const c_void, String> {
                lib.get::<*const c_void>(name)
                    .map(|s| *s)
                    .map_err(|e| format!("{e}"))
            };
            let abi: AbiFn = std::mem::transmute(sym(b"sc_abi\0")?);
            if abi() != crate::ABI_VERSION {
                return Err(format!(
                    "ABI {} where {} is expected",
                    abi(),
                    crate::ABI_VERSION
                ));
            }
            let ports: PortsFn = std::mem::transmute(sym(b"sc_ports\0")?);
            let stated = CStr::from_ptr(ports()).to_string_lossy().to_string();
            if stated != expected {
                return Err(format!("its ports are {stated}, not {expected}"));
            }
            let rest = stated
                .split_once(";in:")
                .map(|x| x.1)
                .ok_or("port list without inputs")?;
            let (ins, outs) = rest
                .split_once(";out:")
                .ok_or("port list without outputs")?;
            Ok(Library {
                new: std::mem::transmute::<*const c_void, NewFn>(sym(b"sc_new\0")?),
                delete: std::mem::transmute::<*const c_void, DeleteFn>(sym(b"sc_delete\0")?),
                step: std::mem::transmute::<*const c_void, StepFn>(sym(b"sc_step\0")?),
                peek: std::mem::transmute::<*const c_void, PeekFn>(sym(b"sc_peek\0")?),
                bench: std::mem::transmute::<*const c_void, BenchFn>(sym(b"sc_bench\0")?),
                inputs: parse_ports(ins)?,
                outputs: parse_ports(outs)?,
                _lib: lib,
            })
        }
    }

    pub fn inputs(&self) -> &[Port] {
        &self.inputs
    }
    pub fn outputs(&self) -> &[Port] {
        &self.outputs
    }
}

/// One instance of a Verilated top: every register at 0, the clock low, settled.
pub struct VModel {
    lib: Arc<Library>,
    handle: *mut c_void,
    cycle: u64,
}

// SAFETY: an instance owns its Verilated model and context; it is used by one thread at a time
// (every call takes `&mut self`, or `&self` for a read of one port).
unsafe impl Send for VModel {}

impl VModel {
    /// A fresh instance of `lib`.
    pub fn new(lib: Arc<Library>) -> Result<VModel, String> {
        // SAFETY: `sc_new` takes nothing and returns a heap model freed by `sc_delete`.
        let handle = unsafe { (lib.new)() };
        if handle.is_null() {
            return Err("the Verilated model could not be created".into());
        }
        Ok(VModel {
            lib,
            handle,
            cycle: 0,
        })
    }

    /// `rows` (one per clock, input port order) through the model from its current state by a C++
    /// loop over memory, without a call per clock: the speed ceiling of this model. Returns a
    /// hash of every output of every clock.
    pub fn bench_rows(&mut self, rows: &[Vec<u64>]) -> Result<u64, String> {
        let n_in = self.lib.inputs.len();
        let mut flat = Vec::with_capacity(rows.len() * n_in);
        for (c, r) in rows.iter().enumerate() {
            if r.len() != n_in {
                return Err(format!("row {c} has {} words, not {n_in}", r.len()));
            }
            flat.extend_from_slice(r);
        }
        Ok(self.bench_flat(&flat))
    }

    /// [`VModel::bench_rows`] of rows laid end to end (`flat.len()` a multiple of the input
    /// count).
    pub fn bench_flat(&mut self, flat: &[u64]) -> u64 {
        let n_in = self.lib.inputs.len().max(1);
        let n = (flat.len() / n_in) as u64;
        self.cycle += n;
        // SAFETY: `flat` holds `n` rows of `n_in` words.
        unsafe { (self.lib.bench)(self.handle, flat.as_ptr(), n) }
    }
}

impl Drop for VModel {
    fn drop(&mut self) {
        // SAFETY: `handle` came from `sc_new` of the same library, which `lib` keeps loaded.
        unsafe { (self.lib.delete)(self.handle) }
    }
}

impl Model for VModel {
    fn inputs(&self) -> &[Port] {
        &self.lib.inputs
    }
    fn outputs(&self) -> &[Port] {
        &self.lib.outputs
    }
    fn step(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), String> {
        let (n_in, n_out) = (self.lib.inputs.len(), self.lib.outputs.len());
        if inputs.len() < n_in || outputs.len() < n_out {
            return Err(format!(
                "clock {}: {} input words for {n_in} ports, room for {} of {n_out} outputs",
                self.cycle,
                inputs.len(),
                outputs.len()
            ));
        }
        // SAFETY: the lengths were checked against the ports `sc_step` reads and writes.
        unsafe { (self.lib.step)(self.handle, inputs.as_ptr(), outputs.as_mut_ptr()) };
        self.cycle += 1;
        Ok(())
    }
    fn peek(&self, k: usize) -> u64 {
        // SAFETY: `sc_peek` reads one port (0 for an index past the last).
        unsafe { (self.lib.peek)(self.handle, k as u32) }
    }
    fn cycle(&self) -> u64 {
        self.cycle
    }
    fn start_vcd(&mut self, _w: Box<dyn Write>) -> Result<(), String> {
        Err("the Verilator engine writes no VCD; use --sim rust-hdl for a waveform".into())
    }
    fn stop_vcd(&mut self) -> Result<(), String> {
        Ok(())
    }
    fn simulator(&self) -> &'static str {
        "verilator"
    }
}
