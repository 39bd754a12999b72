//! The schedule shared by the span units' benches (`cos_v_accumulator`, `fast_unit`): spans
//! loaded back to back in the clock `ready` rises, each occupying a known number of clocks, and
//! in every clock of a span up to two pixels — (index, golden value) per lane — shown
//! `latency` clocks later, beside `ready` and `done`. Output order: ready, (valid, index,
//! value) for lanes A and B, last.

use glam::DVec3;
use proptest::strategy::{Strategy, ValueTree};

use crate::harness::Expected;
use golden::testing::seeded_runner;

/// The unit vector at height `z` and azimuth `phi`.
fn unit(z: f64, phi: f64) -> DVec3 {
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// `n` seeded random spans for the span units' benches: unit end normals N_a, N_b in the upper
/// hemisphere at most 90° apart, a unit X anywhere, m in 0..=60 — as (N_a, N_b, X, m).
pub fn random_span_vectors(seed: u64, n: usize) -> Vec<(DVec3, DVec3, DVec3, u32)> {
    let mut r = seeded_runner(seed);
    let st = (
        (0.0..=1.0f64, 0.0..std::f64::consts::TAU),
        (0.0..=1.0f64, 0.0..std::f64::consts::TAU),
        (-1.0..=1.0f64, 0.0..std::f64::consts::TAU),
        0u32..=60,
    );
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let ((z1, p1), (z2, p2), (z3, p3), m) =
            st.new_tree(&mut r).expect("no rejection").current();
        let (na, nb, x) = (unit(z1, p1), unit(z2, p2), unit(z3, p3));
        if na.dot(nb) >= 0.0 {
            out.push((na, nb, x, m));
        }
    }
    out
}

/// One lane's expectation: its (index, value) this clock, or nothing.
pub type Lane = Option<(u64, f64)>;

/// Rows and per-clock expectations for `n` spans: `clocks(i)` clocks each, loaded by
/// `load_row(Some(i))` (idle rows `load_row(None)`), showing `lanes(i, k)` in their clock `k`
/// `latency` clocks later.
pub fn span_run(
    n: usize,
    clocks: impl Fn(usize) -> usize,
    load_row: impl Fn(Option<usize>) -> Vec<u64>,
    latency: usize,
    lanes: impl Fn(usize, usize) -> [Lane; 2],
) -> (Vec<Vec<u64>>, Vec<Vec<Expected>>) {
    let mut rows = vec![load_row((n > 0).then_some(0))];
    let mut state: Vec<Option<(usize, usize)>> = vec![None];
    for i in 0..n {
        let len = clocks(i);
        for k in 0..len {
            state.push(Some((i, k)));
            let next = (k == len - 1 && i + 1 < n).then_some(i + 1);
            rows.push(load_row(next));
        }
    }
    for _ in 0..=latency {
        rows.push(load_row(None));
        state.push(None);
    }
    let expected = (0..rows.len())
        .map(|c| {
            let ready = state[c].is_none_or(|(i, k)| k + 1 == clocks(i));
            let mut e = vec![Expected::Word(ready as u64)];
            let shown = c.checked_sub(latency).and_then(|s| state[s]);
            let lane = |l: Lane| match l {
                Some((t, v)) => [Expected::Word(1), Expected::Word(t), Expected::Real(v)],
                None => [Expected::Word(0), Expected::DontCare, Expected::DontCare],
            };
            let [a, b] = shown.map_or([None, None], |(i, k)| lanes(i, k));
            e.extend(lane(a));
            e.extend(lane(b));
            e.push(Expected::Word(
                shown.is_some_and(|(i, k)| k + 1 == clocks(i)) as u64,
            ));
            e
        })
        .collect();
    (rows, expected)
}
