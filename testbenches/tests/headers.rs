//! What every block's header and port list must say, read from the sources and the block list:
//! - its latency, the one its `LATENCY` constant has: the `//!` header of the file declaring
//!   the block (`… as "name"`) names `LATENCY` clocks on a line about latency, and a port row
//!   saying `valid_out` is `valid_in` N clocks later says N = `LATENCY`;
//! - the one control vocabulary of `rtl/README.md` ("Shared handshake"): `valid_in`/`valid_out`
//!   for streams of items, `load`/`ready`/`hold` and `done` for walkers, `ready` with
//!   `valid_out`/`done_out` for a block after the address block that can stall it, lanes as a suffix
//!   (`_a`, `_b`, `_l0` … `_l3`), AXI4-Stream names at a stream top's boundary.

use flow::blocks::BLOCKS;

const WORDS: [&str; 21] = [
    "zero",
    "one",
    "two",
    "three",
    "four",
    "five",
    "six",
    "seven",
    "eight",
    "nine",
    "ten",
    "eleven",
    "twelve",
    "thirteen",
    "fourteen",
    "fifteen",
    "sixteen",
    "seventeen",
    "eighteen",
    "nineteen",
    "twenty",
];

/// The numbers written in `text`, as digits or as words up to twenty.
fn numbers(text: &str) -> Vec<usize> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .filter_map(|w| {
            w.parse::<usize>()
                .ok()
                .or_else(|| WORDS.iter().position(|n| n.eq_ignore_ascii_case(w)))
        })
        .collect()
}

/// The file under `rtl/src` declaring `name`, and its `//!` header.
fn header_of(name: &str) -> (String, Vec<String>) {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../rtl/src");
    let mut stack = vec![std::path::PathBuf::from(root)];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            let text = std::fs::read_to_string(&p).unwrap();
            if text.contains(&format!(" as \"{name}\" {{")) {
                let header = text
                    .lines()
                    .take_while(|l| l.starts_with("//!"))
                    .map(|l| l.trim_start_matches("//!").to_string())
                    .collect();
                return (p.display().to_string(), header);
            }
        }
    }
    panic!("no rtl source declares {name:?}");
}

#[test]
fn every_header_states_the_latency_of_its_block() {
    let mut wrong = Vec::new();
    for b in BLOCKS {
        let (file, header) = header_of(b.name());
        let latency = b.latency();
        let stated = header.iter().any(|l| {
            let lower = l.to_lowercase();
            lower.contains("latency")
                && (lower.contains(&format!("{latency} clock"))
                    || lower.contains(&format!("latency {latency}"))
                    || lower.contains(&format!("{} clock", WORDS.get(latency).unwrap_or(&"-"))))
        });
        if !stated {
            wrong.push(format!(
                "{file}: the header of {} never states its latency, {latency} clocks",
                b.name()
            ));
        }
        for l in &header {
            let lower = l.to_lowercase();
            if lower.contains("`valid_out`")
                && lower.contains("`valid_in`")
                && (lower.contains("clocks later") || lower.contains("delayed by"))
            {
                let n = numbers(l);
                if !n.is_empty() && !n.contains(&latency) {
                    wrong.push(format!(
                        "{file}: {} says {:?} ({}), its LATENCY is {latency}",
                        b.name(),
                        l.trim(),
                        n.iter()
                            .map(|n| n.to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// Lane suffixes: two-lane blocks `_a`, `_b`; four-lane blocks `_l0` … `_l3`.
const LANES: [&str; 6] = ["_a", "_b", "_l0", "_l1", "_l2", "_l3"];

/// `name` without its lane suffix.
fn base(name: &str) -> &str {
    LANES
        .iter()
        .find_map(|l| name.strip_suffix(l))
        .unwrap_or(name)
}

#[test]
fn every_block_speaks_the_one_control_vocabulary() {
    let mut wrong = Vec::new();
    for b in BLOCKS {
        let (ins, outs) = b.ports();
        let names: Vec<&str> = ins.iter().chain(&outs).map(|p| p.name).collect();
        let has = |n: &str| names.iter().any(|&p| p == n || base(p) == n);
        let mut bad = |why: String| wrong.push(format!("{}: {why}", b.name()));
        for &p in &names {
            if p.starts_with("s_axis_") || p.starts_with("m_axis_") {
                let t = p.rsplit('_').next().unwrap_or("");
                if !["tdata", "tvalid", "tready", "tlast", "tuser"].contains(&t) {
                    bad(format!("{p}: not an AXI4-Stream signal name"));
                }
                continue;
            }
            if p.starts_with("in_") {
                bad(format!(
                    "{p}: an input is marked by the suffix `_in`, not a prefix"
                ));
            }
            if base(p) == "last" || p.ends_with("_last") {
                bad(format!(
                    "{p}: a run ends in `done` (`tlast` only on AXI4-Stream)"
                ));
            }
            if p.len() > 3
                && p.as_bytes()[0] == b'l'
                && p.as_bytes()[1].is_ascii_digit()
                && p.as_bytes()[2] == b'_'
            {
                bad(format!("{p}: a lane is a suffix (`_l0`), not a prefix"));
            }
            if let Some(rest) = p.strip_prefix("valid_") {
                if !["in", "out"].contains(&rest) && !LANES.contains(&format!("_{rest}").as_str()) {
                    bad(format!(
                        "{p}: `valid_in`, `valid_out` or `valid` with a lane suffix"
                    ));
                }
            }
        }
        if has("valid_in") != has("valid_out") && !has("load") {
            bad("a stream of items carries `valid_in` and `valid_out` both".into());
        }
        if has("ready") && has("row_start_in") {
            // A block downstream of the address block that can stall it.
            for n in ["load", "hold", "valid_out", "done_out", "done_in"] {
                if !has(n) {
                    bad(format!(
                        "a stalling block after the address block (it has `ready`) needs `{n}`"
                    ));
                }
            }
        } else if has("ready") && !b.name().ends_with("-stream") {
            for n in ["load", "hold", "done"] {
                if !has(n) {
                    bad(format!("a walker (it has `ready`) needs `{n}`"));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
