//! Render drivers: the software side that feeds triangles through the simulated hardware
//! (`rtl`, stepped by `rtl::core::sim::Stepper`) into a frame, and the input-row layouts of the
//! blocks' set-up ports, shared by the drivers, the benches and the CLI.
//!
//! - [`gouraud`]: the Gouraud raster pipe (address block + BVI): per-triangle set-up words
//!   ([`gouraud::TriangleJob`]), the row layouts, and [`gouraud::Pipe`], which runs a list of
//!   jobs to fragments.

//! - [`lit`]: the lit pixel pipeline (`rtl::pipelines::pixel_pipeline`): [`lit::LitJob`] set-up,
//!   [`lit::ShadingRegs`], and [`lit::LitPipe`], which runs jobs to fragments with depth.
//! - The simulator switch is `flow::engine` ([`flow::engine::Sim`]: rust-hdl or Verilator in
//!   process), the one place a driver's top is made.
//! - [`textured`]: the textured pixel pipeline (`rtl::pipelines::textured_pipeline`):
//!   [`textured::TexJob`] (the lit set-up and the texture-coordinate block's), the texture
//!   written into the memory, [`textured::TexturedPipe`].
//! - [`span`]: the span pipelines (`rtl::pipelines::span_pipeline`, angular and fast): the span front end
//!   ([`span::span_jobs`], one set-up per raster line) and [`span::SpanPipe`], two fragments
//!   per clock.

pub mod axis;
pub mod gouraud;
pub mod lit;
pub mod render;
pub mod span;
pub mod subdivision;
pub mod textured;
pub mod walkers;
