//! The stream tops' streams (`pixel-stream`, `gouraud-stream`, `cubic-stream`,
//! `angular-stream`, `fast-stream`, `quadric-stream`, `subdivision-stream`) from the driver's
//! side: set-up
//! records packed with the one layout table (`rtl::stream_layout`), and fragment beats read
//! back with it.

use rtl::stream_layout::{
    pack, unpack_fragment, ANGULAR_LINE, CUBIC_LINE, FAST_LINE, GOURAUD_TRIANGLE, QUADRIC_LINE,
    QUADRIC_TRIANGLE, REGISTERS, SPAN_REGISTERS, SUBDIVISION_PARENT, TRIANGLE,
};

use crate::gouraud::{pipe_row, TriangleJob, PIPE_HOLD_AT};

use crate::lit::{lit_row, LitJob, ShadingRegs, REGS_AT};
use crate::span::{span_row, JobWords, SpanJob, SpanKind};

/// One set-up word and its `tlast`.
pub type Word = (u32, bool);

fn with_last(words: Vec<u32>) -> Vec<Word> {
    let n = words.len();
    words
        .into_iter()
        .enumerate()
        .map(|(i, w)| (w, i + 1 == n))
        .collect()
}

/// The triangle record of `job` (the same field values `pixel-pipeline`'s load row carries).
pub fn triangle_record(job: &LitJob) -> Vec<Word> {
    let row = lit_row(Some(job), &ShadingRegs::default());
    with_last(pack(&TRIANGLE, &row[1..REGS_AT]))
}

/// The register record of `regs`.
pub fn register_record(regs: &ShadingRegs) -> Vec<Word> {
    with_last(pack(&REGISTERS, &regs.row()))
}

/// A scene's set-up stream: the registers, then every triangle.
pub fn scene_words(jobs: &[LitJob], regs: &ShadingRegs) -> Vec<Word> {
    let mut w = register_record(regs);
    for j in jobs {
        w.extend(triangle_record(j));
    }
    w
}

/// The `gouraud-stream` record of `job` (the same field values `gouraud-raster`'s load row
/// carries).
pub fn gouraud_record(job: &TriangleJob) -> Vec<Word> {
    let row = pipe_row(Some(job));
    with_last(pack(&GOURAUD_TRIANGLE, &row[1..PIPE_HOLD_AT]))
}

/// A Gouraud scene's set-up stream: every triangle, in order.
pub fn gouraud_words(jobs: &[TriangleJob]) -> Vec<Word> {
    jobs.iter().flat_map(gouraud_record).collect()
}

/// The `subdivision-stream` record of a parent (the same field values `subdivision-raster`'s
/// load row carries).
pub fn subdivision_record(job: &crate::subdivision::SubJob) -> Vec<Word> {
    let row = crate::subdivision::pipe_row(Some(job));
    with_last(pack(
        &SUBDIVISION_PARENT,
        &row[1..crate::subdivision::PIPE_HOLD_AT],
    ))
}

/// A subdivision scene's set-up stream: every parent, in order.
pub fn subdivision_words(jobs: &[crate::subdivision::SubJob]) -> Vec<Word> {
    jobs.iter().flat_map(subdivision_record).collect()
}

/// The `cubic-stream` record of a cubic line (`span` from `crate::span::span_jobs` with a
/// cubic kind): the same field values `cubic-pipeline`'s load row carries.
pub fn cubic_record(span: &SpanJob) -> Vec<Word> {
    let kind = match span.words {
        JobWords::Cubic { pipelined, .. } => SpanKind::Cubic { pipelined },
        _ => panic!("cubic_record: not a cubic line"),
    };
    let row = span_row(kind, Some(span), &ShadingRegs::default());
    let fields = CUBIC_LINE.fields.len();
    debug_assert_eq!(row.len(), fields + 2, "load, the fields, hold");
    with_last(pack(&CUBIC_LINE, &row[1..=fields]))
}

/// A cubic scene's set-up stream: every line, in walk order.
pub fn cubic_words(spans: &[SpanJob]) -> Vec<Word> {
    spans.iter().flat_map(cubic_record).collect()
}

/// The line record of the two-lane span stream top of `kind` (`angular-stream` for
/// [`SpanKind::Angular`], `fast-stream` for [`SpanKind::Fast`]) for `span` (from
/// `crate::span::span_jobs` with that kind): the same field values the span pipeline's load row
/// carries.
pub fn span_line_record(kind: SpanKind, span: &SpanJob) -> Vec<Word> {
    let row = span_row(kind, Some(span), &ShadingRegs::default());
    if kind == SpanKind::Quadric {
        // Row: load, y, x0, dir, m, first, 18 coefficient words, z0, dz, hold. A triangle's
        // first line carries its coefficients (type 2), a later line only its base (type 1).
        let base = [row[1], row[2], row[3], row[4], row[24], row[25]];
        return with_last(if row[5] != 0 {
            let mut v = base.to_vec();
            v.extend(&row[6..24]);
            pack(&QUADRIC_TRIANGLE, &v)
        } else {
            pack(&QUADRIC_LINE, &base)
        });
    }
    let line = span_line_layout(kind);
    with_last(pack(&line, &row[1..=line.fields.len()]))
}

/// The line layout of the span stream top of `kind`.
pub fn span_line_layout(kind: SpanKind) -> rtl::stream_layout::Record {
    match kind {
        SpanKind::Angular => ANGULAR_LINE,
        SpanKind::Fast(_) => FAST_LINE,
        SpanKind::Quadric => QUADRIC_LINE,
        _ => panic!("{kind:?} has no two-lane stream top"),
    }
}

/// The span stream tops' register record of `regs` (n and the nine colour weights; L and H
/// are in each line's words).
pub fn span_register_record(regs: &ShadingRegs) -> Vec<Word> {
    let mut values = vec![regs.n];
    values.extend(regs.weights);
    with_last(pack(&SPAN_REGISTERS, &values))
}

/// A span scene's set-up stream for the stream top of `kind`: the registers (not for the
/// quadric, lit in the set-up), then every line in walk order.
pub fn span_stream_words(kind: SpanKind, spans: &[SpanJob], regs: &ShadingRegs) -> Vec<Word> {
    let mut w = if kind == SpanKind::Quadric {
        Vec::new()
    } else {
        span_register_record(regs)
    };
    for s in spans {
        w.extend(span_line_record(kind, s));
    }
    w
}

/// The order in which the driver sends `jobs` on the set-up stream (indices into `jobs`):
/// largest walk first, then smallest, then the second largest, the second smallest, and so
/// on.
///
/// Why: a triangle record is 26 words at one word per clock, so a triangle whose walk is
/// shorter than that waits for its set-up, and a mesh sends its small triangles in runs (a
/// sphere's silhouette and poles). The default scene in mesh order gives `pixel-stream` 0.885
/// fragments per clock against `pixel-pipeline`'s 0.986; more buffering cannot fix it (a model
/// of the banks with 1 000 records gives about 0.95, the stall being a run of 26-word records
/// at the front). Pairing each small triangle with a large one lets the large walk cover the
/// small one's words. The depth test's tie rule makes the order invisible in the image: the
/// frame writer keeps the nearer fragment and, at equal depth, the lower triangle index (the
/// mesh-order first writer), whatever the arrival order.
///
/// The walk length is the address block's clock count for the triangle alone
/// (`golden::address_block::run`, the cycle model), so the order is set-up software only.
/// Ties keep mesh order (a stable sort), so the order is deterministic.
pub fn balanced_order(jobs: &[LitJob]) -> Vec<usize> {
    balanced_order_of(&jobs.iter().map(|j| j.addr).collect::<Vec<_>>())
}

/// [`balanced_order`] of triangles given by their address set-ups (the Gouraud jobs' too).
pub fn balanced_order_of(addrs: &[golden::address_block::AddressSetup]) -> Vec<usize> {
    let walk: Vec<usize> = addrs
        .iter()
        .map(|a| golden::address_block::run(std::slice::from_ref(a)).0.len())
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
/// [`rtl::sim::Model::peek`] before each clock).
pub fn first_output_is(model: &dyn rtl::sim::Model, name: &str) -> Result<(), String> {
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
        rtl::stream_layout::pack_fragment(&[
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
pub trait StreamTop: rtl::sim::Dut {
    /// Whether the fragment beat has `m_axis_tuser` (the depth) among the outputs.
    const TUSER: bool = true;
}

impl StreamTop for rtl::pixel_stream::PixelStream {}

impl StreamTop for rtl::gouraud_stream::GouraudStream {
    const TUSER: bool = false;
}

impl StreamTop for rtl::cubic_stream::CubicStream {}

/// The stream tops with a fragment stream per lane (`angular-stream`, `fast-stream`,
/// `quadric-stream`: two lanes with `tuser`; `subdivision-stream`: four without), for
/// [`drive_lanes`].
pub trait LaneTop: rtl::sim::Dut {
    /// Its registry name.
    const NAME: &'static str;
    /// Fragment streams.
    const LANES: usize = 2;
    /// Whether each stream has `m_axis_*_tuser` (the depth).
    const TUSER: bool = true;
    /// What one record loads, for messages ("lines", "parents").
    const RECORDS: &'static str = "lines";
}

impl LaneTop for rtl::angular_stream::AngularStream {
    const NAME: &'static str = "angular-stream";
}

impl LaneTop for rtl::quadric_stream::QuadricStream {
    const NAME: &'static str = "quadric-stream";
}

impl LaneTop for rtl::fast_stream::FastStream {
    const NAME: &'static str = "fast-stream";
}

impl LaneTop for rtl::subdivision_stream::SubdivisionStream {
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
    s: &mut dyn rtl::sim::Model,
    words: &[Word],
    records: u64,
    max_clocks: u64,
    fragment: &mut dyn FnMut(usize, Beat, u64, usize),
    record_done: &mut dyn FnMut(u64),
) -> Result<crate::gouraud::PipeStats, String> {
    first_output_is(s, "s_axis_tready")?;
    let mut st = crate::gouraud::PipeStats::default();
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
    s.stop_vcd();
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
    s: &mut dyn rtl::sim::Model,
    top: &str,
    what: &str,
    words: &[Word],
    records: u64,
    max_clocks: u64,
    fragment: &mut dyn FnMut(usize, Beat, u64),
    record_done: &mut dyn FnMut(u64),
) -> Result<crate::gouraud::PipeStats, String> {
    first_output_is(s, "s_axis_tready")?;
    let mut st = crate::gouraud::PipeStats::default();
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
            if b.pixel {
                st.pixels += 1;
                fragment(st.triangles as usize, b, st.clocks - 1);
            }
            if b.last {
                st.triangles += 1;
                record_done(st.triangles);
            }
        }
    }
    s.stop_vcd();
    Ok(st)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtl::stream_layout::{unpack, FRAGMENT};

    #[test]
    fn records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let job = LitJob::new(&t).unwrap().unwrap();
        let rec = triangle_record(&job);
        assert_eq!(rec[0], (1, false));
        assert!(rec.last().unwrap().1);
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = lit_row(Some(&job), &ShadingRegs::default());
        assert_eq!(unpack(&TRIANGLE, &payload), row[1..REGS_AT].to_vec());
        assert_eq!(FRAGMENT[0].name, "x");
    }

    #[test]
    fn gouraud_records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let ctx = golden::shade::ShadeContext::default();
        let job = TriangleJob::gouraud(&t, &ctx).unwrap();
        let rec = gouraud_record(&job);
        assert_eq!(rec.len(), 22);
        assert_eq!(rec[0], (1, false));
        assert!(rec.last().unwrap().1);
        assert!(rec[..21].iter().all(|w| !w.1));
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = pipe_row(Some(&job));
        assert_eq!(
            unpack(&GOURAUD_TRIANGLE, &payload),
            row[1..PIPE_HOLD_AT].to_vec()
        );
        assert_eq!(gouraud_words(&[job, job]).len(), 44);
    }

    #[test]
    fn subdivision_records_carry_the_load_row() {
        let mut t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        t.v[1].normal = glam::DVec3::new(0.3, 0.1, 1.0).normalize();
        let ctx = golden::shade::ShadeContext::default();
        let job = crate::subdivision::SubJob::subdivision(&t, &ctx).unwrap();
        let rec = subdivision_record(&job);
        assert_eq!(rec.len(), 72);
        assert_eq!(rec[0], (1, false));
        assert!(rec.last().unwrap().1);
        assert!(rec[..71].iter().all(|w| !w.1));
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = crate::subdivision::pipe_row(Some(&job));
        assert_eq!(
            unpack(&SUBDIVISION_PARENT, &payload),
            row[1..crate::subdivision::PIPE_HOLD_AT].to_vec()
        );
        assert_eq!(subdivision_words(&[job, job]).len(), 144);
    }

    #[test]
    fn cubic_records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let ctx = golden::shade::ShadeContext::default();
        let kind = SpanKind::Cubic { pipelined: true };
        let spans = crate::span::span_jobs(&t, 0, kind, &ctx).unwrap();
        let rec = cubic_record(&spans[3]);
        assert_eq!(rec.len(), 12);
        assert_eq!(rec[0], (1, false));
        assert!(rec[..11].iter().all(|w| !w.1) && rec[11].1);
        let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
        let row = span_row(kind, Some(&spans[3]), &ShadingRegs::default());
        assert_eq!(
            unpack(&CUBIC_LINE, &payload),
            row[1..row.len() - 1].to_vec()
        );
        assert_eq!(cubic_words(&spans).len(), 12 * spans.len());
    }

    #[test]
    fn span_records_carry_the_load_row() {
        let t = golden::types::ScreenTriangle::from_points([(3, 1), (40, 7), (11, 30)]);
        let ctx = golden::shade::ShadeContext::default();
        let regs = ShadingRegs::of(&ctx).unwrap();
        for (kind, words) in [(SpanKind::Angular, 14), (SpanKind::Fast("fit"), 20)] {
            let spans = crate::span::span_jobs(&t, 0, kind, &ctx).unwrap();
            let rec = span_line_record(kind, &spans[3]);
            assert_eq!(rec.len(), words, "{kind:?}");
            assert_eq!(rec[0], (1, false));
            assert!(rec[..words - 1].iter().all(|w| !w.1) && rec[words - 1].1);
            let payload: Vec<u32> = rec[1..].iter().map(|w| w.0).collect();
            let row = span_row(kind, Some(&spans[3]), &regs);
            let line = span_line_layout(kind);
            let fields = line.fields.len();
            assert_eq!(unpack(&line, &payload), row[1..=fields].to_vec());
            // The register record carries the row's material registers (before `hold`).
            let r = span_register_record(&regs);
            assert_eq!(r.len(), 6);
            assert_eq!(r[0], (2, false));
            let payload: Vec<u32> = r[1..].iter().map(|w| w.0).collect();
            assert_eq!(
                unpack(&SPAN_REGISTERS, &payload),
                row[fields + 1..row.len() - 1].to_vec()
            );
            assert_eq!(
                span_stream_words(kind, &spans, &regs).len(),
                6 + words * spans.len()
            );
        }
    }

    #[test]
    fn balanced_order_alternates_large_and_small() {
        use golden::types::ScreenTriangle;
        // Walks of increasing size: triangle k spans 4k + 2 pixels each way.
        let jobs: Vec<LitJob> = (0..5)
            .map(|k| {
                let s = 4 * k + 2;
                LitJob::new(&ScreenTriangle::from_points([(0, 0), (s, 0), (0, s)]))
                    .unwrap()
                    .unwrap()
            })
            .collect();
        assert_eq!(balanced_order(&jobs), vec![4, 0, 3, 1, 2]);
        assert_eq!(balanced_order(&jobs[..0]), Vec::<usize>::new());
        assert_eq!(balanced_order(&jobs[..1]), vec![0]);
        // Equal walks keep mesh order.
        let same = vec![jobs[2]; 4];
        assert_eq!(balanced_order(&same), vec![0, 3, 1, 2]);
    }
}
