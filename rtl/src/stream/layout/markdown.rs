//! The layout tables as Markdown (`rtl/README.md`'s copy is checked against it).
//!
//! Not a block: no ports, no latency (the stream tops' headers give theirs).

use super::codec::*;
use super::tables::*;

/// The layouts as Markdown tables (`rtl/README.md`), every top.
pub fn markdown() -> String {
    let mut s = String::new();
    for top in TOPS {
        s.push_str(&format!("#### `{}` (wraps `{}`)\n\n", top.block, top.wraps));
        for r in top.records() {
            s.push_str(&format!(
                "**{}** record: header `0x{:08x}`, then {} payload words.\n\n| word | bits | field |\n|---|---|---|\n",
                r.name,
                header(&r),
                payload_words(&r)
            ));
            for pl in place(&r) {
                if pl.bits > 32 {
                    // A wide field: its low 32 bits, then the rest in the next word.
                    s.push_str(&format!(
                        "| {} | 31..0 | `{}` bits 31..0 |\n| {} | {}..0 | `{}` bits {}..32 |\n",
                        pl.word + 1,
                        pl.name,
                        pl.word + 2,
                        pl.bits - 33,
                        pl.name,
                        pl.bits - 1
                    ));
                    continue;
                }
                s.push_str(&format!(
                    "| {} | {}..{} | `{}` |\n",
                    pl.word + 1,
                    pl.offset + pl.bits - 1,
                    pl.offset,
                    pl.name
                ));
            }
            s.push('\n');
        }
        let each = |port: &str| {
            top.lanes
                .iter()
                .map(|l| format!("`{}_{port}`", StreamTop::stream(l)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let tuser = match top.tuser {
            Some(t) => format!("{}: `{}`, {} bits", each("tuser"), t.name, t.bits),
            None => "no `m_axis_tuser`".to_string(),
        };
        s.push_str(&format!(
            "**fragment** beat ({}, {FRAGMENT_BITS} bits; {tuser}; `tlast`: {}):\n\n| bits | field |\n|---|---|\n",
            each("tdata"),
            top.tlast
        ));
        for pl in FRAGMENT {
            s.push_str(&format!(
                "| {}..{} | `{}` |\n",
                pl.at() + pl.bits - 1,
                pl.at(),
                pl.name
            ));
        }
        s.push('\n');
    }
    s
}
