//! The AXI4-Stream side of the stream tops (`pixel-stream`, `gouraud-stream`, `cubic-stream`,
//! `angular-stream`, `fast-stream`, `quadric-stream`, `subdivision-stream`), independent of
//! any method: set-up words, fragment beats read back with the one layout table
//! (`rtl::stream::layout`), and the drivers that step a top. Each method packs its own records
//! beside its job types (`lit::scene_words`, `gouraud::gouraud_words`, …).

use rtl::stream::layout::unpack_fragment;

/// One set-up word and its `tlast`.
pub type Word = (u32, bool);

/// `words` with `tlast` on the last.
pub(crate) fn with_last(words: Vec<u32>) -> Vec<Word> {
    let n = words.len();
    words
        .into_iter()
        .enumerate()
        .map(|(i, w)| (w, i + 1 == n))
        .collect()
}

/// Counters of one pipe run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PipeStats {
    /// Clocks from the first load to the clock showing the last triangle's `done`, inclusive.
    pub clocks: u64,
    pub pixels: u64,
    pub triangles: u64,
}

impl PipeStats {
    pub fn pixels_per_clock(&self) -> f64 {
        self.pixels as f64 / self.clocks.max(1) as f64
    }
}

/// `crate::lit::balanced_order` of triangles given by their address set-ups (the Gouraud jobs' too).
pub fn balanced_order_of(addrs: &[golden::units::address_block::AddressSetup]) -> Vec<usize> {
    let walk: Vec<usize> = addrs
        .iter()
        .map(|a| {
            golden::units::address_block::run(std::slice::from_ref(a))
                .0
                .len()
        })
        .collect();
    let mut by_size: Vec<usize> = (0..addrs.len()).collect();
    by_size.sort_by_key(|&i| std::cmp::Reverse(walk[i]));
    let mut order = Vec::with_capacity(addrs.len());
    let (mut lo, mut hi) = (0, by_size.len());
    while lo < hi {
        order.push(by_size[lo]);
        lo += 1;
        if lo < hi {
            hi -= 1;
            order.push(by_size[hi]);
        }
    }
    order
}

/// An error unless `model`'s first output is `name` (the register output a driver reads with
/// [`rtl::core::sim::Model::peek`] before each clock).
pub fn first_output_is(model: &dyn rtl::core::sim::Model, name: &str) -> Result<(), String> {
    match model.outputs().first() {
        Some(p) if p.name == name => Ok(()),
        other => Err(format!(
            "the driver reads {name} as output 0, which is {:?}",
            other.map(|p| p.name)
        )),
    }
}

/// One fragment beat read back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Beat {
    /// A fragment (else the beat carries only its triangle's end).
    pub pixel: bool,
    pub x: u32,
    pub y: u32,
    pub rgb: [u8; 3],
    /// Depth word (`m_axis_tuser`), signed Q16.16.
    pub z: i32,
    /// The triangle's last event.
    pub last: bool,
}

impl Beat {
    /// The beat's `m_axis_tdata` (the inverse of [`Beat::read`]'s).
    pub fn tdata(&self) -> u64 {
        rtl::stream::layout::pack_fragment(&[
            self.x as u64,
            self.y as u64,
            self.pixel as u64,
            self.rgb[0] as u64,
            self.rgb[1] as u64,
            self.rgb[2] as u64,
        ]) as u64
    }

    /// The beat of `m_axis_tdata`, `m_axis_tuser`, `m_axis_tlast`.
    pub fn read(tdata: u64, tuser: u64, tlast: bool) -> Beat {
        let f = unpack_fragment(tdata as u128);
        Beat {
            x: f[0] as u32,
            y: f[1] as u32,
            pixel: f[2] != 0,
            rgb: [f[3] as u8, f[4] as u8, f[5] as u8],
            z: tuser as u32 as i32,
            last: tlast,
        }
    }
}

/// What [`drive`] needs to know of a single-stream top (its outputs start with
/// `s_axis_tready`, a register output).
pub trait StreamTop: rtl::core::sim::Dut {
    /// Whether the fragment beat has `m_axis_tuser` (the depth) among the outputs.
    const TUSER: bool = true;
}

impl StreamTop for rtl::stream::pixel_stream::PixelStream {}

impl StreamTop for rtl::stream::gouraud_stream::GouraudStream {
    const TUSER: bool = false;
}

impl StreamTop for rtl::stream::cubic_stream::CubicStream {}

impl StreamTop for rtl::stream::textured_stream::TexturedStream {}

/// The stream tops with a fragment stream per lane (`angular-stream`, `fast-stream`,
/// `quadric-stream`: two lanes with `tuser`; `subdivision-stream`: four without), for
/// [`drive_lanes`].
pub trait LaneTop: rtl::core::sim::Dut {
    /// Its registry name.
    const NAME: &'static str;
    /// Fragment streams.
    const LANES: usize = 2;
    /// Whether each stream has `m_axis_*_tuser` (the depth).
    const TUSER: bool = true;
    /// What one record loads, for messages ("lines", "parents").
    const RECORDS: &'static str = "lines";
}

impl LaneTop for rtl::stream::angular_stream::AngularStream {
    const NAME: &'static str = "angular-stream";
}

impl LaneTop for rtl::stream::quadric_stream::QuadricStream {
    const NAME: &'static str = "quadric-stream";
}

impl LaneTop for rtl::stream::fast_stream::FastStream {
    const NAME: &'static str = "fast-stream";
}

impl LaneTop for rtl::stream::subdivision_stream::SubdivisionStream {
    const NAME: &'static str = "subdivision-stream";
    const LANES: usize = 4;
    const TUSER: bool = false;
    const RECORDS: &'static str = "parents";
}

/// [`drive`] for a top's per-lane fragment streams (every `m_axis_*_tready` high):
/// `fragment(record, beat, clock, lane)` for each beat with a pixel (record = the `tlast`s
/// seen before it on its lane), `record_done(records_done)` when every lane has seen a
/// record's `tlast`. `records` counts the load records (lines, parents; a register record at
/// the start is not one).
pub fn drive_lanes<T: LaneTop>(
    s: &mut dyn rtl::core::sim::Model,
    words: &[Word],
    records: u64,
    max_clocks: u64,
    fragment: &mut dyn FnMut(usize, Beat, u64, usize),
    record_done: &mut dyn FnMut(u64),
) -> Result<PipeStats, String> {
    first_output_is(s, "s_axis_tready")?;
    let mut st = PipeStats::default();
    // Outputs: s_axis_tready; per lane tvalid, tdata, [tuser,] tlast; error.
    let per = 3 + T::TUSER as usize;
    let mut out = vec![0u64; 2 + per * T::LANES];
    let mut ready_row = vec![0u64; 3];
    ready_row.extend(std::iter::repeat_n(1, T::LANES));
    let (mut next, mut ends) = (0, vec![0u64; T::LANES]);
    while st.triangles < records {
        if st.clocks >= max_clocks {
            return Err(format!(
                "{}: {} of {records} {} done after {max_clocks} clocks",
                T::NAME,
                st.triangles,
                T::RECORDS
            ));
        }
        // `s_axis_tready` (output 0, checked above) is a register output: settled before the
        // clock's step.
        let taken = s.peek(0) != 0;
        let mut row = ready_row.clone();
        if let Some(&(w, last)) = words.get(next) {
            row[..3].copy_from_slice(&[w as u64, 1, last as u64]);
        }
        s.step(&row, &mut out)?;
        next += (row[1] != 0 && taken) as usize;
        st.clocks += 1;
        if out[out.len() - 1] != 0 {
            return Err(format!("{} flagged a malformed set-up record", T::NAME));
        }
        for (lane, end) in ends.iter_mut().enumerate() {
            let at = 1 + per * lane;
            if out[at] == 0 {
                continue;
            }
            let tuser = if T::TUSER { out[at + 2] } else { 0 };
            let b = Beat::read(out[at + 1], tuser, out[at + per - 1] != 0);
            if b.pixel {
                st.pixels += 1;
                fragment(*end as usize, b, st.clocks - 1, lane);
            }
            *end += b.last as u64;
        }
        let done = ends.iter().copied().min().unwrap_or(0);
        while st.triangles < done {
            st.triangles += 1;
            record_done(st.triangles);
        }
    }
    s.stop_vcd()?;
    Ok(st)
}

/// Drive `words` into the stream top `s`, a word per clock while `s_axis_tready`, and take every
/// fragment beat (`m_axis_tready` high) until `records` beats with `tlast` have come:
/// `fragment(record, beat, clock)` for each beat with a pixel (record = the `tlast`s seen
/// before it), `record_done(records_done)` after each `tlast`. An error names `top` and
/// `what` the records are when `max_clocks` pass first, or when the top flags a malformed
/// record. Stops the VCD (if any) at the end.
#[allow(clippy::too_many_arguments)]
pub fn drive<T: StreamTop>(
    s: &mut dyn rtl::core::sim::Model,
    top: &str,
    what: &str,
    words: &[Word],
    records: u64,
    max_clocks: u64,
    fragment: &mut dyn FnMut(usize, Beat, u64),
    record_done: &mut dyn FnMut(u64),
) -> Result<PipeStats, String> {
    let mut ends = 0u64;
    drive_beats::<T>(s, top, what, words, records, max_clocks, &mut |b, clock| {
        if b.pixel {
            fragment(ends as usize, b, clock);
        }
        if b.last {
            ends += 1;
            record_done(ends);
        }
    })
}

/// [`drive`] reporting every beat the top delivers, `beat(beat, clock)`, fragments and
/// end-of-record beats alike (what `shadecore stream` writes).
pub fn drive_beats<T: StreamTop>(
    s: &mut dyn rtl::core::sim::Model,
    top: &str,
    what: &str,
    words: &[Word],
    records: u64,
    max_clocks: u64,
    beat: &mut dyn FnMut(Beat, u64),
) -> Result<PipeStats, String> {
    first_output_is(s, "s_axis_tready")?;
    let mut st = PipeStats::default();
    // Outputs: s_axis_tready, m_axis_tvalid, m_axis_tdata, [m_axis_tuser,] m_axis_tlast, error.
    let n_out = if T::TUSER { 6 } else { 5 };
    let mut out = vec![0u64; n_out];
    let mut next = 0;
    while st.triangles < records {
        if st.clocks >= max_clocks {
            return Err(format!(
                "{top}: {} of {records} {what} done after {max_clocks} clocks",
                st.triangles
            ));
        }
        // `s_axis_tready` (output 0, checked above) is a register output: settled before the
        // clock's step.
        let taken = s.peek(0) != 0;
        let row = match words.get(next) {
            Some(&(w, last)) => [w as u64, 1, last as u64, 1],
            None => [0, 0, 0, 1],
        };
        s.step(&row, &mut out)?;
        next += (row[1] != 0 && taken) as usize;
        st.clocks += 1;
        if out[n_out - 1] != 0 {
            return Err(format!("{top} flagged a malformed set-up record"));
        }
        if out[1] != 0 {
            let (tuser, tlast) = if T::TUSER {
                (out[3], out[4])
            } else {
                (0, out[3])
            };
            let b = Beat::read(out[2], tuser, tlast != 0);
            st.pixels += b.pixel as u64;
            st.triangles += b.last as u64;
            beat(b, st.clocks - 1);
        }
    }
    s.stop_vcd()?;
    Ok(st)
}
