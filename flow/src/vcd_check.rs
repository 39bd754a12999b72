//! Reading a VCD back with an independent parser (the `vcd` crate; rust-hdl writes with its
//! own copy of an older version): which signals it declares, and their values at given times.

use std::collections::HashMap;
use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use vcd::{Command, IdCode, Parser, ScopeItem, Value};

/// Full dotted names (`uut.nx`, `uut.scale.f.q`, …) and widths of every variable in the file.
pub fn variables(path: &Path) -> Result<Vec<(String, u32)>, String> {
    let f = File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    let mut p = Parser::new(BufReader::new(f));
    let header = p
        .parse_header()
        .map_err(|e| format!("{}: bad VCD header: {e}", path.display()))?;
    fn walk(items: &[ScopeItem], prefix: &str, out: &mut Vec<(String, u32)>) {
        for it in items {
            match it {
                ScopeItem::Scope(s) => walk(&s.items, &format!("{prefix}{}.", s.identifier), out),
                ScopeItem::Var(v) => out.push((format!("{prefix}{}", v.reference), v.size)),
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    walk(&header.items, "", &mut out);
    Ok(out)
}

fn word(bits: impl IntoIterator<Item = Value>) -> Option<u64> {
    let mut w = 0u64;
    for b in bits {
        w = (w << 1)
            | match b {
                Value::V0 => 0,
                Value::V1 => 1,
                _ => return None,
            };
    }
    Some(w)
}

/// Values of the variables `path_in_file` (each a scope path plus name, e.g.
/// `["uut", "nx"]`) at each time of `times` (ascending): the value after every change
/// stamped at or before that time. `x`/`z` bits are an error.
pub fn sample(path: &Path, signals: &[Vec<&str>], times: &[u64]) -> Result<Vec<Vec<u64>>, String> {
    let f = File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    let mut p = Parser::new(BufReader::new(f));
    let header = p
        .parse_header()
        .map_err(|e| format!("{}: bad VCD header: {e}", path.display()))?;
    let mut codes: Vec<IdCode> = Vec::new();
    for s in signals {
        let v = header
            .find_var(s)
            .ok_or_else(|| format!("{}: no variable {}", path.display(), s.join(".")))?;
        codes.push(v.code);
    }
    let index: HashMap<IdCode, Vec<usize>> =
        codes
            .iter()
            .enumerate()
            .fold(HashMap::new(), |mut m, (k, c)| {
                m.entry(*c).or_default().push(k);
                m
            });
    let mut current: Vec<Option<u64>> = vec![None; codes.len()];
    let mut out = Vec::with_capacity(times.len());
    let mut next = 0;
    let snapshot = |current: &[Option<u64>], t: u64| -> Result<Vec<u64>, String> {
        current
            .iter()
            .enumerate()
            .map(|(k, v)| {
                v.ok_or_else(|| format!("{} undefined or x/z at time {t}", signals[k].join(".")))
            })
            .collect()
    };
    for cmd in p {
        let cmd = cmd.map_err(|e| format!("{}: {e}", path.display()))?;
        match cmd {
            Command::Timestamp(t) => {
                while next < times.len() && times[next] < t {
                    out.push(snapshot(&current, times[next])?);
                    next += 1;
                }
            }
            Command::ChangeScalar(id, v) => {
                if let Some(ks) = index.get(&id) {
                    for &k in ks {
                        current[k] = word([v]);
                    }
                }
            }
            Command::ChangeVector(id, v) => {
                if let Some(ks) = index.get(&id) {
                    for &k in ks {
                        current[k] = word(&v);
                    }
                }
            }
            _ => {}
        }
    }
    while next < times.len() {
        out.push(snapshot(&current, times[next])?);
        next += 1;
    }
    Ok(out)
}
