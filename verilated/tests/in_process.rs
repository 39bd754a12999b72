//! The in-process Verilator model against rust-hdl, and its cache under abuse (a broken entry,
//! two builds of one design at once). Needs Verilator: without it each test says so on stderr
//! and returns; with `CI` set it fails.

use rtl::core::registry::{BlockParams, Options, RtlBlock};
use rtl::core::sim::{Model, RustHdlModel};

fn require(test: &str) -> bool {
    match verilated::toolchain() {
        Ok(_) => true,
        Err(e) if std::env::var_os("CI").is_some_and(|v| !v.is_empty()) => {
            panic!("{test}: {e} (CI is set, so this is a failure)")
        }
        Err(e) => {
            eprintln!("SKIPPED {test}: {e} (set CI=1 to make this a failure)");
            false
        }
    }
}

/// xorshift64*: seeded rows without a dependency.
fn rows(seed: u64, n: usize, widths: &[usize]) -> Vec<Vec<u64>> {
    let mut s = seed | 1;
    let mut next = move || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        s.wrapping_mul(0x2545_f491_4f6c_dd1d)
    };
    (0..n)
        .map(|_| {
            widths
                .iter()
                .map(|&w| next() & if w >= 64 { u64::MAX } else { (1 << w) - 1 })
                .collect()
        })
        .collect()
}

fn same_as_rust_hdl<B: RtlBlock>(p: &B::Params, n: usize) -> verilated::VModel {
    let mut v = verilated::model::<B>(p).unwrap_or_else(|e| panic!("{e}"));
    let mut r = RustHdlModel::new(B::build(p)).unwrap();
    let widths: Vec<usize> = r.inputs().iter().map(|p| p.width).collect();
    assert_eq!(v.inputs(), r.inputs());
    assert_eq!(v.outputs(), r.outputs());
    let n_out = r.outputs().len();
    let (mut a, mut b) = (vec![0; n_out], vec![0; n_out]);
    for (c, row) in rows(7, n, &widths).iter().enumerate() {
        for k in 0..n_out {
            assert_eq!(
                v.peek(k),
                r.peek(k),
                "{} peek {k} before clock {c}",
                B::NAME
            );
        }
        v.step(row, &mut a).unwrap();
        r.step(row, &mut b).unwrap();
        assert_eq!(a, b, "{}: clock {c}, row {row:?}", B::NAME);
    }
    v
}

#[test]
fn normalizer_equals_rust_hdl_every_clock() {
    if !require("normalizer_equals_rust_hdl_every_clock") {
        return;
    }
    let p = <rtl::units::normalizer::Normalizer as RtlBlock>::Params::from_options(&Options::new())
        .unwrap();
    let mut v = same_as_rust_hdl::<rtl::units::normalizer::Normalizer>(&p, 3000);
    assert_eq!(v.cycle(), 3000);
    // The ceiling loop runs the same clocks (it returns a hash; two fresh instances agree).
    let widths: Vec<usize> = v.inputs().iter().map(|p| p.width).collect();
    let r = rows(9, 500, &widths);
    let h1 = v.bench_rows(&r).unwrap();
    let mut w = verilated::model::<rtl::units::normalizer::Normalizer>(&p).unwrap();
    let mut x = verilated::model::<rtl::units::normalizer::Normalizer>(&p).unwrap();
    let (h2, h3) = (w.bench_rows(&r).unwrap(), x.bench_rows(&r).unwrap());
    assert_eq!(h2, h3);
    assert_ne!(
        h1, h2,
        "a model 3000 clocks on has other registers (the K pipeline)"
    );
    assert!(v.start_vcd(Box::new(std::io::sink())).is_err());
}

/// A design only this run knows (a comment with the process id and time in its Verilog), so
/// the cache has no entry for it.
fn fresh_design() -> verilated::Design {
    let p = <rtl::units::address_block::AddressBlock as RtlBlock>::Params::from_options(
        &Options::new(),
    )
    .unwrap();
    let d = verilated::design::<rtl::units::address_block::AddressBlock>(&p);
    let text = (d.verilog)().unwrap();
    let stamp = format!(
        "// fresh {} {:?}\n",
        std::process::id(),
        std::time::SystemTime::now()
    );
    verilated::Design::from_verilog(
        "address-block (fresh)",
        &d.module,
        stamp + &text,
        d.inputs,
        d.outputs,
    )
}

#[test]
fn two_threads_building_one_design_share_one_build() {
    if !require("two_threads_building_one_design_share_one_build") {
        return;
    }
    // Two threads build one new design at once: one builds, the other waits and loads it.
    let d = fresh_design();
    let libs: Vec<_> = std::thread::scope(|s| {
        let a = s.spawn(|| verilated::build(&d));
        let b = s.spawn(|| verilated::build(&d));
        [a.join().unwrap(), b.join().unwrap()]
    })
    .into_iter()
    .map(|r| r.unwrap_or_else(|e| panic!("{e}")))
    .collect();
    assert!(std::sync::Arc::ptr_eq(&libs[0], &libs[1]));

    // The entry of this run's design is of no use to a later run: remove it (and its lock).
    let stamp = format!("// fresh {} ", std::process::id());
    for e in std::fs::read_dir(verilated::cache_dir()).unwrap().flatten() {
        let p = e.path();
        if std::fs::read_to_string(p.join("dut.v")).is_ok_and(|t| t.starts_with(&stamp)) {
            std::fs::remove_dir_all(&p).unwrap();
            let _ = std::fs::remove_file(p.with_extension("lock"));
        }
    }
    // Two processes at once and a broken entry: tests/engine_errors.rs (through the CLI, on a
    // cache of its own).
}

/// A build of a registered block made from newer RTL sources removes the entry of the same
/// block and parameters made from older ones (the cache does not grow with every RTL edit);
/// other entries stay.
#[test]
fn a_newer_build_of_a_block_supersedes_the_older_one() {
    if !require("a_newer_build_of_a_block_supersedes_the_older_one") {
        return;
    }
    let fresh = fresh_design();
    // Not starting with the other test's stamp (that test removes what it stamped).
    let text = format!("// eviction test\n{}", (fresh.verilog)().unwrap());
    // Two "generations" of one block and parameters (keys equal but for the fingerprint), and a
    // third design with other parameters.
    let tag = format!("evict{}", std::process::id());
    let make = |key: String| verilated::Design {
        name: format!("eviction test {key}"),
        key,
        module: fresh.module.clone(),
        inputs: fresh.inputs.clone(),
        outputs: fresh.outputs.clone(),
        verilog: Box::new({
            let t = text.clone();
            move || Ok(t.clone())
        }),
    };
    let old = make(format!("block:{tag}|P1|old"));
    let other = make(format!("block:{tag}|P2|old"));
    let new = make(format!("block:{tag}|P1|new"));
    let dir_of = |key: &str| {
        std::fs::read_dir(verilated::cache_dir())
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .find(|p| std::fs::read_to_string(p.join("key.txt")).is_ok_and(|k| k == key))
    };
    verilated::build(&old).unwrap();
    verilated::build(&other).unwrap();
    let old_dir = dir_of(&old.key).expect("the old entry");
    verilated::build(&new).unwrap();
    assert!(!old_dir.exists(), "the superseded entry is still there");
    assert!(dir_of(&new.key).is_some() && dir_of(&other.key).is_some());
    for d in [&new, &other] {
        let p = dir_of(&d.key).unwrap();
        std::fs::remove_dir_all(&p).unwrap();
        let _ = std::fs::remove_file(p.with_extension("lock"));
    }
}
