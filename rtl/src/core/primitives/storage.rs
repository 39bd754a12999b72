//! Storage primitives: the delay line, the PROM (synchronous read, as block RAM) and the LUT RAM.

use rust_hdl::prelude::*;

/// `q` is `d` delayed by `N` clocks (`N` ≥ 1 registers in a chain, reset to 0). Latency `N`,
/// one value per clock. Replaces hand-unrolled `_p1 … _pN` chains; name the field after the
/// tap it gives (`x_p5: Delay<Bits<16>, 5>`).
#[derive(LogicBlock)]
pub struct Delay<T: Synth, const N: usize> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    /// `stage[i]` holds `d` of i + 1 clocks ago.
    stage: [DFF<T>; N],
}

impl<T: Synth, const N: usize> Default for Delay<T, N> {
    fn default() -> Self {
        assert!(N >= 1, "a delay line needs at least one register");
        Self {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            stage: std::array::from_fn(|_| Default::default()),
        }
    }
}

impl<T: Synth, const N: usize> Logic for Delay<T, N> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..N {
            self.stage[i].clock.next = self.clock.val();
        }
        self.stage[0].d.next = self.d.val();
        for i in 1..N {
            self.stage[i].d.next = self.stage[i - 1].q.val();
        }
        // rust-hdl resolves an array index in Verilog only from a loop variable, so the last
        // register is addressed by a one-step loop.
        for i in (N - 1)..N {
            self.q.next = self.stage[i].q.val();
        }
    }
}

/// A synchronous ROM (PROM): `data` = `contents[address]` of the previous clock edge, as FPGA
/// block RAM reads; 0 before the first edge in every simulator (rust-hdl's `SyncROM` leaves
/// the Verilog register uninitialised, which Icarus shows as `x`). Latency 1. Exported as a
/// `reg` array with an `initial` block, which Yosys maps to block RAM (iCE40: SB_RAM40_4K).
/// Every one of the 2^N addresses holds a word.
#[derive(LogicBlock)]
pub struct Prom<D: Synth, const N: usize> {
    pub address: Signal<In, Bits<N>>,
    pub clock: Signal<In, Clock>,
    pub data: Signal<Out, D>,
    // Boxed as rust-hdl's own SyncROM holds it (the derive treats `_` fields as opaque).
    #[allow(clippy::box_collection)]
    _contents: Box<std::collections::BTreeMap<Bits<N>, D>>,
}

impl<D: Synth, const N: usize> Prom<D, N> {
    /// A PROM holding `words` from address 0 on.
    pub fn new(words: impl IntoIterator<Item = D>) -> Self {
        assert!(N < 20, "a PROM of 2^{N} words is not block RAM");
        let contents: std::collections::BTreeMap<Bits<N>, D> = words
            .into_iter()
            .enumerate()
            .map(|(i, w)| (Bits::<N>::from(i as u64), w))
            .collect();
        assert!(
            contents.len() == 1 << N,
            "a PROM of 2^{N} addresses needs 2^{N} words"
        );
        Self {
            address: Signal::default(),
            clock: Signal::default(),
            data: Signal::new_with_default(D::default()),
            _contents: Box::new(contents),
        }
    }
}

impl<D: Synth, const N: usize> Logic for Prom<D, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            self.data.next = *self
                ._contents
                .get(&self.address.val())
                .unwrap_or(&D::default());
        }
    }
    fn connect(&mut self) {
        self.data.connect();
    }
    fn hdl(&self) -> Verilog {
        let init = self
            ._contents
            .iter()
            .map(|(a, w)| format!("mem[{}] = {};", a.verilog(), w.verilog()))
            .collect::<Vec<_>>()
            .join("\n");
        Verilog::Custom(format!(
            "reg[{d}:0] mem [0:{last}];\n\ninitial begin\n{init}\ndata = 0;\nend\n\n\
             always @(posedge clock) begin\n   data <= mem[address];\nend",
            d = D::BITS - 1,
            last = (1usize << N) - 1,
        ))
    }
}

/// The ports and the simulation store of a RAM with one write and one read port, and its
/// `Default` (every word 0), for [`Lutram`] and [`Bram`], which differ in how they read.
macro_rules! ram_ports {
    ($(#[$m:meta])* $name:ident, $max:expr, $what:literal) => {
        $(#[$m])*
        #[derive(LogicBlock)]
        pub struct $name<D: Synth, const N: usize> {
            pub clock: Signal<In, Clock>,
            pub write_enable: Signal<In, Bit>,
            pub write_address: Signal<In, Bits<N>>,
            pub write_data: Signal<In, D>,
            pub read_address: Signal<In, Bits<N>>,
            pub read_data: Signal<Out, D>,
            #[allow(clippy::box_collection)]
            _mem: Box<Vec<D>>,
        }

        impl<D: Synth, const N: usize> Default for $name<D, N> {
            fn default() -> Self {
                assert!(N <= $max, "a {} of 2^{N} words is too deep", $what);
                Self {
                    clock: Signal::default(),
                    write_enable: Signal::default(),
                    write_address: Signal::default(),
                    write_data: Signal::default(),
                    read_address: Signal::default(),
                    read_data: Signal::new_with_default(D::default()),
                    _mem: Box::new(vec![D::default(); 1 << N]),
                }
            }
        }
    };
}

ram_ports!(
    /// A small RAM with synchronous write and asynchronous read (FPGA distributed RAM: ECP5
    /// TRELLIS_DPR16X4 slices, Xilinx LUTRAM): `mem[write_address] ← write_data` on the rising
    /// edge when `write_enable`; `read_data` = `mem[read_address]` at once (also the word written
    /// at the last edge). 2^N words, 0 in the rust-hdl simulation before their first write; the
    /// Verilog leaves them uninitialised, so a reader must not use a word before it is written
    /// (the FIFO in `pixel_stream` gates its output with its `valid`).
    Lutram,
    8,
    "distributed RAM"
);

impl<D: Synth, const N: usize> Logic for Lutram<D, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.write_enable.val() {
            let a = self.write_address.val().index();
            self._mem[a] = self.write_data.val();
        }
        self.read_data.next = self._mem[self.read_address.val().index()];
    }
    fn connect(&mut self) {
        self.read_data.connect();
    }
    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "reg [{d}:0] mem [0:{last}];\n\n\
             always @(posedge clock) begin\n   if (write_enable) mem[write_address] <= write_data;\nend\n\n\
             always @(*) read_data = mem[read_address];",
            d = D::BITS - 1,
            last = (1usize << N) - 1,
        ))
    }
}

ram_ports!(
    /// A block RAM: synchronous write and synchronous read (`read_data` = `mem[read_address]` of
    /// the previous rising edge, read before that edge's write: FPGA block RAM in read-first mode).
    /// 2^N words, every one 0 before its first write in every simulator and on the FPGA: the
    /// Verilog zeroes the array in an `initial` loop for the simulators (rust-hdl's `RAM` leaves it
    /// uninitialised, which Icarus shows as `x`). The loop is left out under `SYNTHESIS` (Yosys
    /// defines it; unrolling 2^14 writes took Yosys' `proc` minutes): the FPGA's block RAM starts
    /// at 0 without it (ECP5 DP16KD and iCE40 SB_RAM40_4K initial contents default to 0).
    Bram,
    19,
    "block RAM"
);

impl<D: Synth, const N: usize> Logic for Bram<D, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            self.read_data.next = self._mem[self.read_address.val().index()];
            if self.write_enable.val() {
                let a = self.write_address.val().index();
                self._mem[a] = self.write_data.val();
            }
        }
    }
    fn connect(&mut self) {
        self.read_data.connect();
    }
    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "reg [{d}:0] mem [0:{last}];\ninteger i;\n\n\
             `ifndef SYNTHESIS\ninitial begin\n   for (i = 0; i <= {last}; i = i + 1) mem[i] = 0;\n   read_data = 0;\nend\n`endif\n\n\
             always @(posedge clock) begin\n   read_data <= mem[read_address];\n   if (write_enable) mem[write_address] <= write_data;\nend",
            d = D::BITS - 1,
            last = (1usize << N) - 1,
        ))
    }
}
