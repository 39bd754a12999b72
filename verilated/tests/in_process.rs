//! The in-process Verilator model against rust-hdl, and its cache under abuse (a broken entry,
//! two builds of one design at once). Needs Verilator: without it each test says so on stderr
//! and returns; with `CI` set it fails.

use rtl::registry::{BlockParams, Options, RtlBlock};
use rtl::sim::{Model, RustHdlModel};

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
    let p =
        <rtl::normalizer::Normalizer as RtlBlock>::Params::from_options(&Options::new()).unwrap();
    let mut v = same_as_rust_hdl::<rtl::normalizer::Normalizer>(&p, 3000);
    assert_eq!(v.cycle(), 3000);
    // The ceiling loop runs the same clocks (it returns a hash; two fresh instances agree).
    let widths: Vec<usize> = v.inputs().iter().map(|p| p.width).collect();
    let r = rows(9, 500, &widths);
    let h1 = v.bench_rows(&r).unwrap();
    let mut w = verilated::model::<rtl::normalizer::Normalizer>(&p).unwrap();
    let mut x = verilated::model::<rtl::normalizer::Normalizer>(&p).unwrap();
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
    let p = <rtl::address_block::AddressBlock as RtlBlock>::Params::from_options(&Options::new())
        .unwrap();
    let d = verilated::design::<rtl::address_block::AddressBlock>(&p);
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
fn two_builds_at_once_agree_and_a_broken_entry_is_rebuilt() {
    if !require("two_builds_at_once_agree_and_a_broken_entry_is_rebuilt") {
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

    // Two processes at once (this test binary, twice, in children) on another new design: one
    // builds it, the other waits for the lock and loads the same entry.
    let text = (fresh_design().verilog)().unwrap();
    let v = std::env::temp_dir().join(format!("shadecore-fresh-{}.v", std::process::id()));
    std::fs::write(&v, &text).unwrap();
    let child = || {
        std::process::Command::new(std::env::current_exe().unwrap())
            .args([
                "--exact",
                "child_builds_and_steps",
                "--nocapture",
                "--ignored",
            ])
            .env("SHADECORE_CHILD_VERILOG", &v)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (a, b) = (child(), child());
    let outs = [a.wait_with_output().unwrap(), b.wait_with_output().unwrap()];
    let errs: Vec<String> = outs
        .iter()
        .map(|o| String::from_utf8_lossy(&o.stderr).to_string())
        .collect();
    for (o, e) in outs.iter().zip(&errs) {
        assert!(o.status.success(), "a child failed: {e}");
    }
    let built = errs
        .iter()
        .filter(|e| e.contains("verilated: built"))
        .count();
    assert_eq!(built, 1, "exactly one child builds: {errs:?}");

    // A broken entry (its library cut short, as a full disk or a killed copy leaves it; a new
    // file, so this process's mapping of the old one stays intact) is rebuilt by the next load.
    let module = d.module.clone();
    let dir = std::fs::read_dir(verilated::cache_dir())
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| {
            p.is_dir()
                && p.file_name()
                    .unwrap()
                    .to_string_lossy()
                    .starts_with(&format!("{module}-"))
                && std::fs::read_to_string(p.join("dut.v")).is_ok_and(|t| t == text)
        })
        .expect("the children's entry");
    let lib = dir.join("lib.so");
    let whole = std::fs::read(&lib).unwrap();
    let cut = dir.join("lib.so.cut");
    std::fs::write(&cut, &whole[..whole.len() / 3]).unwrap();
    std::fs::rename(&cut, &lib).unwrap();
    let again = child().wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(again.status.success(), "the child failed: {err}");
    assert!(
        err.contains("is broken") && err.contains("verilated: built"),
        "no rebuild: {err}"
    );
    assert_eq!(std::fs::read(&lib).unwrap().len(), whole.len());
    let _ = std::fs::remove_file(&v);
}

/// Run by the test above in child processes: build the design in `SHADECORE_CHILD_VERILOG`
/// (the address block's ports) and step it a clock.
#[test]
#[ignore = "a child of two_builds_at_once_agree_and_a_broken_entry_is_rebuilt"]
fn child_builds_and_steps() {
    let Some(path) = std::env::var_os("SHADECORE_CHILD_VERILOG") else {
        return;
    };
    let p = <rtl::address_block::AddressBlock as RtlBlock>::Params::from_options(&Options::new())
        .unwrap();
    let d = verilated::design::<rtl::address_block::AddressBlock>(&p);
    let text = std::fs::read_to_string(path).unwrap();
    let d = verilated::Design::from_verilog(
        "address-block (fresh)",
        &d.module,
        text,
        d.inputs,
        d.outputs,
    );
    let mut m =
        verilated::VModel::new(verilated::build(&d).unwrap_or_else(|e| panic!("{e}"))).unwrap();
    let mut out = vec![0; m.outputs().len()];
    m.step(&vec![0; m.inputs().len()], &mut out).unwrap();
}
