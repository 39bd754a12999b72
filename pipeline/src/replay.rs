//! A recorded run of a block — its input rows and the output rows another simulator (the
//! exported Verilog under Verilator) produced for them — replayed clock by clock through the
//! same drivers that step the rust-hdl simulation (`lit::LitPipe`, `span::SpanPipe`,
//! `gouraud::Pipe`). The driver decides its loads from `ready` as always; every row it wants to
//! feed must equal the recorded one, so a schedule that differs from the hardware's own `ready`
//! is an error, not a silently wrong frame.

/// Input and output rows of one run; `ready` is output port 0.
#[derive(Clone, Debug)]
pub struct Replay {
    inputs: Vec<Vec<u64>>,
    outputs: Vec<Vec<u64>>,
    clock: usize,
}

impl Replay {
    /// A replay of `outputs` (one row per clock) recorded for `inputs`.
    pub fn new(inputs: Vec<Vec<u64>>, outputs: Vec<Vec<u64>>) -> Result<Replay, String> {
        if inputs.len() != outputs.len() {
            return Err(format!(
                "replay: {} input rows but {} output rows",
                inputs.len(),
                outputs.len()
            ));
        }
        Ok(Replay {
            inputs,
            outputs,
            clock: 0,
        })
    }

    /// `ready` (output port 0) in the current clock; false past the recording.
    pub fn ready(&self) -> bool {
        self.outputs
            .get(self.clock)
            .is_some_and(|o| o.first().is_some_and(|&r| r != 0))
    }

    /// The current clock's outputs for `inputs`, which must be the recorded row.
    pub fn step(&mut self, inputs: &[u64], outputs: &mut [u64]) -> Result<(), String> {
        let c = self.clock;
        let Some(rec) = self.inputs.get(c) else {
            return Err(format!("replay: the recording ends after {c} clocks"));
        };
        if rec.as_slice() != inputs {
            return Err(format!(
                "replay: clock {c}: the driver feeds a row other than the recorded one (the schedule disagrees with the hardware's ready)"
            ));
        }
        let out = &self.outputs[c];
        if out.len() > outputs.len() {
            return Err(format!(
                "replay: clock {c}: {} output words recorded, room for {}",
                out.len(),
                outputs.len()
            ));
        }
        outputs[..out.len()].copy_from_slice(out);
        self.clock += 1;
        Ok(())
    }
}
