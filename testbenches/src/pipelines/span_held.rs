//! Held runs of the span tops (`angular-pipeline`, `fast-pipeline`, `quadric-unit`,
//! `cubic-pipeline`): lines driven into each top's twin under a stall pattern, the rows every
//! clock (the RTL must equal the twin on them; `tests/span_hold.rs`).

use golden::shade::ShadeContext;
use golden::types::ScreenTriangle;
use pipeline::lit::ShadingRegs;
use pipeline::span::{span_jobs, span_row, SpanJob, SpanKind};
use rtl::core::registry::NoParams;

use crate::pipelines::span_pipeline::SpanPipelineTwin;
use crate::registry::{Bench, Twin};

/// A run of a span top (`angular-pipeline`, `fast-pipeline`, `quadric-unit`, `cubic-pipeline`) under
/// `hold`: the input rows (each line loaded as soon as `ready` takes it, `hold` from the
/// pattern in every clock), the lines, pixels and held clocks.
pub struct HeldRun {
    pub rows: Vec<Vec<u64>>,
    pub lines: usize,
    pub pixels: usize,
    pub held: usize,
}

/// Drive the lines of `tris` (default context, `kind`'s front end) into its top, `hold` (the
/// row's last input) from `stalls` every clock: the next line is presented with `load` high
/// until a clock whose `ready` (the twin's, which the RTL must equal every clock) takes it;
/// the run ends 4 clocks after the last pixel shows.
pub fn held_run(
    kind: SpanKind,
    tris: &[ScreenTriangle],
    stalls: &mut crate::stall::StallPattern,
) -> HeldRun {
    let ctx = ShadeContext::default();
    let regs = ShadingRegs::of(&ctx).expect("default context fits");
    let jobs: Vec<SpanJob> = tris
        .iter()
        .enumerate()
        .flat_map(|(i, t)| span_jobs(t, i, kind, &ctx).expect("in range"))
        .collect();
    let pixels: usize = jobs.iter().map(|j| j.m as usize + 1).sum();
    let mut twin: Box<dyn Twin> = match kind {
        SpanKind::Quadric => <rtl::units::quadric_unit::QuadricUnit as Bench>::twin(&NoParams),
        SpanKind::Angular | SpanKind::Fast(_) => Box::new(SpanPipelineTwin::new(kind)),
        SpanKind::Cubic { pipelined } => {
            Box::new(crate::pipelines::cubic_pipeline::CubicPipelineTwin::new(
                &rtl::pipelines::cubic_pipeline::CubicParams(
                    rtl::units::horner_unit::HornerParams { pipelined },
                ),
            ))
        }
    };
    let (lanes, _, _) = pipeline::span::output_columns(kind);
    let (mut rows, mut next, mut shown, mut held, mut after) = (Vec::new(), 0, 0, 0, 0);
    while after < 4 {
        let hold = stalls.next_stalled();
        let mut row = span_row(kind, jobs.get(next), &regs);
        *row.last_mut().expect("a row") = hold as u64;
        held += hold as usize;
        let out = twin.step(&row);
        if out[0] != 0 && next < jobs.len() {
            next += 1;
        }
        shown += lanes.iter().map(|&k| out[k] as usize).sum::<usize>();
        if shown == pixels && next == jobs.len() {
            after += 1;
        }
        rows.push(row);
        assert!(rows.len() < 50 * pixels + 10_000, "the run does not end");
    }
    HeldRun {
        rows,
        lines: jobs.len(),
        pixels,
        held,
    }
}
