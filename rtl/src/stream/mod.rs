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

/// A one-stream top's header states its figures as its constants give them: the FIFO's depth
/// (`N-entry FIFO`), the hold threshold (`more than N beats`), its latency (`clock t + N`) and
/// the wrapped top's (`N clocks through` and its name), and each of `more`. `text` is the
/// file; its `//!` lines are read as one line, spaces folded.
#[cfg(test)]
pub(crate) fn assert_header_states<Top: crate::core::registry::RtlBlock>(
    text: &str,
    fifo: (usize, usize),
    wraps: (&str, usize),
    more: &[String],
) {
    let text = text
        .replace("//!", " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let figures = [
        format!("{}-entry FIFO", fifo.0),
        format!("more than {} beats", fifo.1),
        format!("clock t + {}", Top::LATENCY),
        format!("{} clocks through `{}`", wraps.1, wraps.0),
    ];
    for want in figures.iter().chain(more) {
        assert!(text.contains(want.as_str()), "header lacks {want:?}");
    }
}
