//! `hold` on the four-triangle block and the subdivision raster pipe (the back-pressure a
//! stream top gives them): under random holds (30 %, in stretches) and two long ones the RTL
//! equals its twin every clock, a held clock shows no event (four-triangle) and the next clock
//! no pixel (subdivision, one BVI clock later), and each lane shows exactly the events or
//! pixels of the unheld run, in the same order. (The generic tests — twin, Icarus, Verilator,
//! lint — are the registry's; both blocks' edge rows hold in a quarter of their clocks.)

use golden::testing::seed_for;
use golden::units::address_block::AddressOutputs;
use golden::units::four_triangle::{FourTriangleSetup, LANES};
use pipeline::subdivision::{pipe_row, SubJob, OUTPUTS, PIPE_HOLD_AT};
use rtl::core::registry::{NoParams, Options};
use rtl::pipelines::subdivision_raster::SubdivisionRaster;
use testbenches::pipelines::subdivision_raster::random_jobs;
use testbenches::registry::{find, Bench};
use testbenches::stall::StallPattern;
use testbenches::units::four_triangle::{random_triangles, run_reactive_held, HOLD_AT};

/// Random holds (probability 0.3) plus the clocks 2..40 and 300..900.
fn stalls(seed: u64) -> impl FnMut(usize) -> bool {
    let mut random = StallPattern::new(seed, 0.3);
    move |c| {
        let r = random.next_stalled();
        (2..40).contains(&c) || (300..900).contains(&c) || r
    }
}

#[test]
fn four_triangle_hold_keeps_every_event_and_matches_the_twin() {
    let test = "four_triangle_hold_keeps_every_event_and_matches_the_twin";
    let seed = seed_for(test);
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let setups: Vec<FourTriangleSetup> = random_triangles(seed, 30)
        .iter()
        .map(FourTriangleSetup::new)
        .collect();
    let (free_rows, free) = run_reactive_held(&setups, 1_000_000, None, |_| false).unwrap();
    let (rows, out) = run_reactive_held(&setups, 1_000_000, None, stalls(seed)).unwrap();
    let held_at = |c: usize| rows[c][HOLD_AT] != 0;
    let held = (0..rows.len()).filter(|&c| held_at(c)).count();
    assert!(held > 800, "held {held} clocks");
    find("four-triangle")
        .unwrap()
        .run_twin(&Options::new(), &rows, "four-triangle-hold", seed)
        .unwrap_or_else(|f| panic!("{f}"));
    let quiet = AddressOutputs::default();
    for (c, o) in out.iter().enumerate() {
        if held_at(c) {
            for (k, l) in o.lanes.iter().enumerate() {
                let mut l = *l;
                l.ready = false;
                assert_eq!(l, quiet, "clock {c}, lane {k}: an event shown while held");
            }
        }
    }
    // Each lane's events (every clock whose outputs are not all quiet), in order.
    let events =
        |out: &[golden::units::four_triangle::FourOutputs], k: usize| -> Vec<AddressOutputs> {
            out.iter()
                .map(|o| AddressOutputs {
                    ready: false,
                    ..o.lanes[k]
                })
                .filter(|l| *l != quiet)
                .collect()
        };
    let mut total = 0;
    for k in 0..LANES {
        let (a, b) = (events(&free, k), events(&out, k));
        assert!(!a.is_empty(), "lane {k} shows events");
        assert!(
            a == b,
            "lane {k}: the held run's events differ from the unheld run's"
        );
        total += a.len();
    }
    println!(
        "four-triangle: {} parents, {total} lane events: {} clocks unheld, {} with {held} held",
        setups.len(),
        free_rows.len(),
        rows.len()
    );
    assert!(rows.len() > free_rows.len() + 600);
}

/// A pixel of one lane: x, y, r, g, b, done.
type LanePixel = [u64; 6];

/// Drive `jobs` into the subdivision pipe, each parent presented until the twin's `ready`
/// (which the RTL must equal every clock) takes it, `hold(clock)` on the stall input; the run
/// ends 4 clocks after every lane's last `done`. Returns the rows and the held clocks.
fn sub_rows(jobs: &[SubJob], mut hold: impl FnMut(usize) -> bool) -> (Vec<Vec<u64>>, usize) {
    let mut twin = <SubdivisionRaster as Bench>::twin(&NoParams);
    let (mut rows, mut next, mut dones, mut after, mut held) =
        (Vec::new(), 0, [0usize; LANES], 0, 0);
    while after < 4 {
        let mut row = pipe_row(jobs.get(next));
        let h = hold(rows.len());
        row[PIPE_HOLD_AT] = h as u64;
        held += h as usize;
        let o = twin.step(&row);
        if o[0] != 0 && next < jobs.len() {
            next += 1;
        }
        for (k, d) in dones.iter_mut().enumerate() {
            *d += o[7 + 7 * k] as usize;
        }
        if next == jobs.len() && dones.iter().all(|&d| d == jobs.len()) {
            after += 1;
        }
        rows.push(row);
        assert!(rows.len() < 2_000_000, "the run does not end");
    }
    (rows, held)
}

#[test]
fn subdivision_hold_keeps_every_pixel_and_matches_the_twin() {
    let test = "subdivision_hold_keeps_every_pixel_and_matches_the_twin";
    let seed = seed_for(test);
    println!("seed {seed} (SHADECORE_SEED overrides)");
    let jobs: Vec<SubJob> = random_jobs(seed, 16).into_iter().map(|j| j.0).collect();
    let o = Options::new();
    let entry = find("subdivision-raster").unwrap();
    let lanes = |rows: &[Vec<u64>]| -> Vec<Vec<LanePixel>> {
        let out = entry
            .simulate_on(&o, rows, flow::engine::fast_sim("four_hold"))
            .unwrap();
        let mut px = vec![Vec::new(); LANES];
        for (c, r) in out.iter().enumerate() {
            assert_eq!(r.len(), OUTPUTS);
            for (k, lane) in px.iter_mut().enumerate() {
                let b = 1 + 7 * k;
                if c > 0 && rows[c - 1][PIPE_HOLD_AT] != 0 {
                    assert_eq!(r[b], 0, "clock {c}, lane {k}: a pixel after a held clock");
                }
                if r[b] != 0 {
                    lane.push([r[b + 1], r[b + 2], r[b + 3], r[b + 4], r[b + 5], r[b + 6]]);
                }
            }
        }
        px
    };
    let (free_rows, _) = sub_rows(&jobs, |_| false);
    let reference = lanes(&free_rows);
    let (rows, held) = sub_rows(&jobs, stalls(seed));
    assert!(held > 800, "held {held} clocks");
    entry
        .run_twin(&o, &rows, "subdivision-raster-hold", seed)
        .unwrap_or_else(|f| panic!("{f}"));
    let pixels = lanes(&rows);
    for k in 0..LANES {
        assert!(!reference[k].is_empty(), "lane {k} shows pixels");
        assert!(
            pixels[k] == reference[k],
            "lane {k}: the held run's pixels differ from the unheld run's"
        );
    }
    println!(
        "subdivision-raster: {} parents, {} pixels: {} clocks unheld, {} with {held} held",
        jobs.len(),
        reference.iter().map(Vec::len).sum::<usize>(),
        free_rows.len(),
        rows.len()
    );
    assert!(rows.len() > free_rows.len() + 600);
}
