//! The walkers' reactive runners: a list of set-ups through a simulated walker (`load`/`ready`/
//! `hold`), its own `ready` pacing the loads, on any simulator.

pub mod address;
pub mod four_triangle;
