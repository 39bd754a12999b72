//! The AXI4-Stream side: the word layouts (one table), the record reader and fragment FIFO,
//! and the stream tops that wrap each pipeline.

pub mod angular_stream;
pub mod cubic_stream;
pub mod fast_stream;
pub mod fragment_fifo;
pub mod gouraud_stream;
pub mod layout;
pub mod one_lane;
pub mod pixel_stream;
pub mod quadric_stream;
pub mod record_reader;
pub mod subdivision_stream;
pub mod textured_stream;
pub mod two_lane;
