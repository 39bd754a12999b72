//! The benches of `rtl::stream`: each stream top’s twin, stimulus and stalled runs.

pub mod cubic_stream;
pub mod gouraud_stream;
pub mod pixel_stream;
pub mod span_stream;
pub mod stream_twin;
pub mod subdivision_stream;
pub mod textured_stream;
