//! `SHADECORE_RTL_FINGERPRINT`: a hash of every source the exported Verilog depends on (this
//! crate, the golden crate it takes tables and set-up from, the vendored rust-hdl-core, and
//! Cargo.lock for the rust-hdl version). The in-process Verilator cache (`verilated`) keys its
//! builds on it with the block's name and parameters, so a warm run never regenerates Verilog
//! only to find its cache entry, and any edit of the RTL's sources makes a new entry.
//!
//! Not a block: no ports, no latency.

use std::path::{Path, PathBuf};

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, out);
        } else {
            out.push(p);
        }
    }
}

fn main() {
    let here = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = here
        .parent()
        .expect("rtl/ sits in the workspace")
        .to_path_buf();
    let inputs = [
        here.join("src"),
        here.join("lint"),
        root.join("golden/src"),
        root.join("vendor/rust-hdl-core/src"),
        root.join("Cargo.lock"),
    ];
    let mut list = Vec::new();
    for i in &inputs {
        println!("cargo:rerun-if-changed={}", i.display());
        if i.is_dir() {
            files(i, &mut list);
        } else {
            list.push(i.clone());
        }
    }
    list.sort();
    // FNV-1a, 64 bits, over each file's path (relative to the workspace) and contents.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h ^= b as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for f in &list {
        eat(f
            .strip_prefix(&root)
            .unwrap_or(f)
            .to_string_lossy()
            .as_bytes());
        eat(&[0]);
        eat(&std::fs::read(f).unwrap_or_default());
        eat(&[0xff]);
    }
    println!("cargo:rustc-env=SHADECORE_RTL_FINGERPRINT={h:016x}");
}
