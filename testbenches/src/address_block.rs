//! Cycle-by-cycle bench of the address block (`rtl::address_block`) against its cycle-accurate
//! golden model (`golden::address_block`) and the golden walk (`golden::raster`).
//!
//! Both sides are driven the same way: a list of triangles, each loaded in the first clock
//! where the block's own `ready` output is high. The RTL decides its timing; the model predicts
//! it; every output is compared every clock.

use golden::address_block::{AddressBlockModel, AddressOutputs, AddressSetup};
use proptest::prelude::*;
use rtl::address_block::AddressBlock;
use rust_hdl::prelude::*;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Settle combinational logic (panics on a combinational loop, which is a design bug).
pub fn settle<B: Block>(uut: &mut B) {
    assert!(simulate(uut, 100), "circuit did not settle");
}

/// A freshly connected and settled address block.
pub fn new_address_block() -> AddressBlock {
    let mut uut = AddressBlock::default();
    uut.connect_all();
    settle(&mut uut);
    uut
}

/// Drive the load port with `s` (or deassert it).
pub fn apply_load(uut: &mut AddressBlock, s: Option<&AddressSetup>) {
    uut.load.next = s.is_some();
    let z = AddressSetup::default();
    let s = s.unwrap_or(&z);
    let edge = |e: &golden::address_block::EdgeSetup| {
        (
            Bits::<12>::from(e.b0 as u64),
            Bits::<13>::from(e.e0 as u64),
            Bits::<12>::from(e.f_word() as u64),
            Bits::<13>::from(e.r as u64),
            Bits::<13>::from(e.d as u64),
        )
    };
    (
        uut.w_b0.next,
        uut.w_e0.next,
        uut.w_f.next,
        uut.w_r.next,
        uut.w_d.next,
    ) = edge(&s.w);
    (
        uut.a_b0.next,
        uut.a_e0.next,
        uut.a_f.next,
        uut.a_r.next,
        uut.a_d.next,
    ) = edge(&s.a);
    (
        uut.t_b0.next,
        uut.t_e0.next,
        uut.t_f.next,
        uut.t_r.next,
        uut.t_d.next,
    ) = edge(&s.t);
    uut.y_top.next = (s.y_top as u64).into();
    uut.rows.next = (s.rows as u64).into();
    uut.y_switch.next = (s.y_switch as u64).into();
    uut.dir_neg.next = s.dir_neg;
}

/// The block's outputs in the current clock.
pub fn read_outputs(uut: &AddressBlock) -> AddressOutputs {
    AddressOutputs {
        ready: uut.ready.val(),
        valid: uut.valid.val(),
        x: uut.x.val().index() as u32,
        y: uut.y.val().index() as u32,
        step: uut.step.val().index() as u8,
        line_start: uut.line_start.val(),
        row_start: uut.row_start.val(),
        carry: uut.carry.val(),
        done: uut.done.val(),
    }
}

/// One full clock period: rising edge, then falling edge, settling after each.
pub fn clock_address_block(uut: &mut AddressBlock) {
    uut.clock.next = true.into();
    settle(uut);
    uut.clock.next = false.into();
    settle(uut);
}

/// Walk `setups` through the RTL, loading each as soon as `ready` is high; stop after the last
/// triangle's `done` or after `max_clocks`. With `vcd`, every half clock is traced (10 time
/// units per half period; rising edges at 20·cycle + 10).
pub fn run_rtl(
    setups: &[AddressSetup],
    max_clocks: usize,
    vcd: Option<&mut dyn Write>,
) -> Vec<AddressOutputs> {
    let mut uut = new_address_block();
    let mut probe = vcd.map(|w| {
        let p = write_vcd_header(w, &uut);
        write_vcd_dump(p, &uut)
    });
    let mut out = Vec::new();
    let (mut next, mut dones) = (0, 0);
    while dones < setups.len() && out.len() < max_clocks {
        let load = (uut.ready.val() && next < setups.len()).then(|| &setups[next]);
        next += load.is_some() as usize;
        apply_load(&mut uut, load);
        settle(&mut uut);
        let o = read_outputs(&uut);
        dones += o.done as usize;
        out.push(o);
        if dones == setups.len() {
            break;
        }
        let t = 20 * (out.len() as u64 - 1);
        uut.clock.next = true.into();
        settle(&mut uut);
        probe = probe.map(|mut p| {
            p.timestamp(t + 10).ok();
            write_vcd_change(p, &uut)
        });
        uut.clock.next = false.into();
        settle(&mut uut);
        probe = probe.map(|mut p| {
            p.timestamp(t + 20).ok();
            write_vcd_change(p, &uut)
        });
    }
    out
}

/// The golden model's prediction for the same stimulus (see [`run_rtl`]).
pub fn run_model(setups: &[AddressSetup], max_clocks: usize) -> Vec<AddressOutputs> {
    let mut m = AddressBlockModel::new();
    let mut out = Vec::new();
    let (mut next, mut dones) = (0, 0);
    while dones < setups.len() && out.len() < max_clocks {
        let o = m.outputs();
        let load = (o.ready && next < setups.len()).then(|| &setups[next]);
        next += load.is_some() as usize;
        dones += o.done as usize;
        out.push(o);
        if dones == setups.len() {
            break;
        }
        m.clock(load);
    }
    out
}

/// Path of a waveform written for a failing run: `target/sims/<name>.vcd` in the workspace.
pub fn sims_path(name: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf();
    let dir = root.join("target").join("sims");
    std::fs::create_dir_all(&dir).ok();
    dir.join(format!("{name}.vcd"))
}

/// First clock where `got` differs from `expected`: (cycle, field, expected, actual).
pub fn first_mismatch(
    expected: &[AddressOutputs],
    got: &[AddressOutputs],
) -> Option<(usize, &'static str, String, String)> {
    for (c, (e, g)) in expected.iter().zip(got).enumerate() {
        let fields: [(&str, u64, u64); 9] = [
            ("ready", e.ready as u64, g.ready as u64),
            ("valid", e.valid as u64, g.valid as u64),
            ("x", e.x as u64, g.x as u64),
            ("y", e.y as u64, g.y as u64),
            ("step", e.step as u64, g.step as u64),
            ("line_start", e.line_start as u64, g.line_start as u64),
            ("row_start", e.row_start as u64, g.row_start as u64),
            ("carry", e.carry as u64, g.carry as u64),
            ("done", e.done as u64, g.done as u64),
        ];
        if let Some((n, a, b)) = fields.iter().find(|(_, a, b)| a != b) {
            return Some((c, n, a.to_string(), b.to_string()));
        }
    }
    if expected.len() != got.len() {
        let c = expected.len().min(got.len());
        return Some((
            c,
            "length",
            expected.len().to_string(),
            got.len().to_string(),
        ));
    }
    None
}

/// Run RTL and model on `setups` and compare every clock. On a mismatch, re-run the RTL with
/// a VCD under `target/sims/<name>.vcd` and return a one-paragraph report.
pub fn check_against_model(
    name: &str,
    seed: Option<u64>,
    setups: &[AddressSetup],
) -> Result<Vec<AddressOutputs>, String> {
    let expected = run_model(setups, 1 << 28);
    let max = expected.len() + 16;
    let got = run_rtl(setups, max, None);
    match first_mismatch(&expected, &got) {
        None => Ok(got),
        Some((cycle, field, e, g)) => {
            let path = sims_path(name);
            let mut f = std::fs::File::create(&path).map_err(|e| e.to_string())?;
            run_rtl(setups, cycle + 4, Some(&mut f));
            Err(format!(
                "{name}: cycle {cycle}: {field} expected {e}, got {g} (seed {seed:?}); \
                 triangles {setups:?}; waveform {}",
                path.display()
            ))
        }
    }
}

/// Random triangles from several families: general small ones, axis-aligned edges, one-pixel
/// ones, degenerate ones, long slivers up to the full 4095 extent.
pub fn triangle_strategy() -> impl Strategy<Value = [(i32, i32); 3]> {
    let pt = |max: i32| (0..=max, 0..=max);
    prop_oneof![
        // General, small box.
        4 => [pt(40), pt(40), pt(40)],
        // General, medium box.
        2 => [pt(200), pt(200), pt(200)],
        // Horizontal and vertical edges.
        1 => (pt(100), 1..60i32, 1..60i32, any::<bool>()).prop_map(|((x, y), w, h, flip)| {
            if flip { [(x, y), (x + w, y), (x, y + h)] } else { [(x + w, y), (x + w, y + h), (x, y + h)] }
        }),
        // Tiny: one pixel or nothing.
        1 => (pt(4093), 0..3usize).prop_map(|((x, y), k)| {
            [[(x, y), (x + 1, y), (x, y + 1)], [(x, y), (x + 1, y + 1), (x, y + 1)], [(x + 1, y), (x + 1, y + 1), (x, y + 1)]][k]
        }),
        // Degenerate: collinear.
        1 => (pt(2000), -40..40i32, -40..40i32, 0..4i32, 0..4i32).prop_map(|((x, y), dx, dy, k, m)| {
            let p = |t: i32| ((x + 2000 + t * dx).clamp(0, 4095), (y + t * dy).clamp(0, 4095));
            [p(0), p(k), p(k + m)]
        }),
        // Long slivers spanning up to the full address range.
        1 => (pt(4095), pt(4095), -3..=3i32, -3..=3i32).prop_map(|(a, b, ox, oy)| {
            [a, b, ((b.0 + ox).clamp(0, 4095), (b.1 + oy).clamp(0, 4095))]
        }),
    ]
}
