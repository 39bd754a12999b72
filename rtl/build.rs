//! `SHADECORE_RTL_FINGERPRINT`: a hash of every source the exported Verilog depends on (this
//! crate, the golden crate it takes tables and set-up from, the vendored rust-hdl-core, and
//! Cargo.lock for the rust-hdl version). The in-process Verilator cache (`verilated`) keys its
//! builds on it with the block's name and parameters, so a warm run never regenerates Verilog
//! only to find its cache entry, and any edit of the RTL's sources makes a new entry.
//!
//!
//! Also writes the stream tops' generated cores into `OUT_DIR` (one file per top,
//! `rtl::stream::layout::core_file`), from the same tables the driver packs records with.
//!
//! Not a block: no ports, no latency.

use std::path::{Path, PathBuf};

// The layout tables and the code generator, shared with the crate (`rtl::stream::layout`).
#[allow(dead_code)]
#[path = "src/stream/layout/codegen.rs"]
mod codegen;
#[allow(dead_code)]
#[path = "src/stream/layout/tables.rs"]
mod tables;

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

    let out = PathBuf::from(std::env::var("OUT_DIR").expect("set by cargo"));
    for top in &tables::TOPS {
        let path = out.join(codegen::core_file_name(top));
        let text = codegen::core_file(top);
        // Rewritten only when it changes, so an unchanged core does not rebuild the crate.
        if std::fs::read_to_string(&path).ok().as_deref() != Some(text.as_str()) {
            std::fs::write(&path, text)
                .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        }
    }
}
