//! shadecore library glue: scene set-up, the render driver, image output, and CLI commands.

pub mod cmd;
pub mod output;
pub mod rtl_engine;
pub mod setup;
pub mod sim;
