//! Every block's header states its latency, and states the one its `LATENCY` constant has: the
//! `//!` header of the file declaring the block (`… as "name"`) must name `LATENCY` clocks on a
//! line about latency, and a port row saying `valid_out` is `valid_in` N clocks later must say
//! N = `LATENCY`. A header left behind by a re-timed block fails here.

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
