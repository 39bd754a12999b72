//! The infrastructure every block is built from: fixed-point formats, the block declaration
//! macro, simulation, the registry traits, Verilog export, and the primitives (storage,
//! rounding, multipliers). No block of its own.

pub mod declare;
pub mod export;
pub mod fixed;
pub mod primitives;
pub mod registry;
pub mod sim;
