//! The stream tops' generated cores: for each top, one whole Rust file written by
//! `rtl/build.rs` into `OUT_DIR` ([`core_file`]): a block holding the record banks, the field
//! selects into the wrapped top, the register fields and the fragment packing, all from the
//! tables. The hand-written top around it (record reader, FIFOs, output registers) includes it
//! (`include!(concat!(env!("OUT_DIR"), "/<file>"))`).
//!
//! Not a block: no ports, no latency (the stream tops' headers give theirs; a core adds none:
//! it is combinational but for its banks, as the regions it replaces were).

use super::tables::*;

/// The file name of `top`'s generated core under `OUT_DIR` (`pixel_stream_core.rs`).
pub fn core_file_name(top: &StreamTop) -> String {
    format!("{}_core.rs", top.block.replace('-', "_"))
}

/// The whole generated core of `top`: a `hw_block!` (clock, the set-up stream and the wrapped
/// top's `hold` in; `s_axis_tready`, `error`, the wrapped top's outputs the fragment side reads
/// and the fragment beats out) and its `update`: the record reader, the load bank's handshake
/// (a load record loads when the wrapped top is `ready`; a register record applies when every
/// load before it has left, `done` counted, and a texel record is written then with `tex_we`;
/// a second load record loads with `first`; a line record goes into the wrapped top's line
/// FIFO when `line_ready`), the
/// word banks, the field selects and the fragment packing.
pub fn core_file(top: &StreamTop) -> String {
    let (decl, up) = generated_rtl(top);
    let c = &top.core;
    let second = top.registers.or(top.full).or(top.texels);
    let mut ins = vec![
        "s_axis_tdata: Bits<32>".to_string(),
        "s_axis_tvalid: Bit".into(),
        "s_axis_tlast: Bit".into(),
    ];
    ins.extend(c.inputs.iter().map(|(n, t)| format!("{n}: {t}")));
    let mut outs = vec!["s_axis_tready: Bit".to_string(), "error: Bit".into()];
    outs.extend(c.outputs.iter().map(|(n, t)| format!("{n}: {t}")));
    outs.extend(
        top.lanes
            .iter()
            .map(|l| format!("beat{l}: Bits<{FRAGMENT_BITS}>")),
    );
    let pipe_init = match c.params {
        Some(_) => format!(" = {}::new(p)", c.pipe),
        None => String::new(),
    };
    let ctor = match c.params {
        Some(p) => format!("    new(p: &{p});\n"),
        None => String::new(),
    };
    // The set-up side's state.
    let mut fields = format!(
        "        /// The record reader (`record_reader`).
        rd: RecordReader,
        /// A complete record waits in the load bank (`pend_b`){}.
        pend_b: DFF<Bit>,{}
        transfer: Signal<Local, Bit>, load_taken: Signal<Local, Bit>,
        /// The word the reader takes, and which payload word it is (+ 1).
        in_word: Signal<Local, Bits<32>>, take_word: Signal<Local, Bit>,
        word_index: Signal<Local, Bits<INDEX_BITS>>,
        /// The payload words of record types 1 … 4 (0: no such type).
        len1: Constant<Bits<INDEX_BITS>> = Constant::new({}u64.into()),
        len2: Constant<Bits<INDEX_BITS>> = Constant::new({}u64.into()),
        len3: Constant<Bits<INDEX_BITS>> = Constant::new({}u64.into()),
        len4: Constant<Bits<INDEX_BITS>> = Constant::new({}u64.into()),
",
        if second.is_some() {
            ", of type `type_b`"
        } else {
            ""
        },
        if second.is_some() {
            " type_b: DFF<Bits<4>>,"
        } else {
            ""
        },
        payload_words(&top.triangle),
        top.registers.or(top.full).map_or(0, |r| payload_words(&r)),
        top.texels.map_or(0, |r| payload_words(&r)),
        top.lines.map_or(0, |r| payload_words(&r)),
    );
    if top.registers.is_some() {
        fields.push_str(
            "        /// Loads whose `done` has not left the wrapped top; registers apply at 0.
        outstanding: DFF<Bits<16>>, apply_regs: Signal<Local, Bit>,
",
        );
    }
    assert!(
        top.texels.is_none() || top.registers.is_some(),
        "{}: a texel record drains as the register record does",
        top.block
    );
    assert!(
        top.lines.is_none() || top.registers.is_some(),
        "{}: a line record comes with a register record",
        top.block
    );
    if top.lines.is_some() {
        fields.push_str(
            "        /// A line record goes into the wrapped top's line FIFO this clock.
        push_line: Signal<Local, Bit>,
",
        );
    }
    if top.texels.is_some() {
        fields.push_str(
            "        /// A texel record is written this clock (every load before it has left).
        apply_texel: Signal<Local, Bit>,
",
        );
    }
    let mut setup = format!(
        "        dff_setup!(self, clock, pend_b{});
        // The record reader takes a word while no complete record waits in the receive bank,
        // and names the payload word it is.
        self.rd.head.next = self.s_axis_tdata.val().get_bits::<4>(0);
        self.rd.tvalid.next = self.s_axis_tvalid.val();
        self.rd.tlast.next = self.s_axis_tlast.val();
        self.rd.len1.next = self.len1.val();
        self.rd.len2.next = self.len2.val();
        self.rd.len3.next = self.len3.val();
        self.rd.len4.next = self.len4.val();
        self.s_axis_tready.next = self.rd.tready.val();
        self.in_word.next = self.s_axis_tdata.val();
        self.take_word.next = self.rd.take_word.val();
        self.word_index.next = self.rd.index.val();
        self.error.next = self.rd.error.val();
        // A complete record moves to the load bank when that is free, and the receive bank
        // takes the next record.
        self.transfer.next = self.rd.pending.val() & !self.pend_b.q.val();
        self.rd.take_record.next = self.transfer.val();
        if self.transfer.val() {{
            self.pend_b.d.next = true;{}
        }}
",
        if second.is_some() { ", type_b" } else { "" },
        if second.is_some() {
            "\n            self.type_b.d.next = self.rd.rec_type.val();"
        } else {
            ""
        },
    );
    if top.registers.is_some() {
        setup.push_str(
            "        // A load record (type 1) loads when the wrapped top is ready; a register record
        // (type 2) applies when every load before it has left.
        dff_setup!(self, clock, outstanding);
        self.pipe.load.next = self.pend_b.q.val() & (self.type_b.q.val() == 1);
        self.load_taken.next =
            self.pend_b.q.val() & (self.type_b.q.val() == 1) & self.pipe.ready.val();
        self.apply_regs.next =
            self.pend_b.q.val() & (self.type_b.q.val() == 2) & (self.outstanding.q.val() == 0);
        if self.load_taken.val() | self.apply_regs.val() {
            self.pend_b.d.next = false;
        }
        if self.load_taken.val() & !self.pipe.done.val() {
            self.outstanding.d.next = self.outstanding.q.val() + 1;
        } else if !self.load_taken.val() & self.pipe.done.val() {
            self.outstanding.d.next = self.outstanding.q.val() - 1;
        }
",
        );
        if top.texels.is_some() {
            setup.push_str(
                "        // A texel record (type 3) is written when every load before it has left.
        self.apply_texel.next =
            self.pend_b.q.val() & (self.type_b.q.val() == 3) & (self.outstanding.q.val() == 0);
        if self.apply_texel.val() {
            self.pend_b.d.next = false;
        }
        self.pipe.tex_we.next = self.apply_texel.val();
",
            );
        }
        if top.lines.is_some() {
            setup.push_str(
                "        // A line record (type 4) goes into the wrapped top's line FIFO when that has room,
        // in stream order (after its triangle's load).
        self.push_line.next =
            self.pend_b.q.val() & (self.type_b.q.val() == 4) & self.pipe.line_ready.val();
        if self.push_line.val() {
            self.pend_b.d.next = false;
        }
        self.pipe.line_push.next = self.push_line.val();
",
            );
        }
    } else {
        setup.push_str(
            "        // Either record type loads when the wrapped top is ready.
        self.pipe.load.next = self.pend_b.q.val();
        self.load_taken.next = self.pend_b.q.val() & self.pipe.ready.val();
        if self.load_taken.val() {
            self.pend_b.d.next = false;
        }
",
        );
        if top.full.is_some() {
            setup.push_str(
                "        // The second record type loads with `first`.
        self.pipe.first.next = self.type_b.q.val() == 2;
",
            );
        }
    }
    let mut pass = String::new();
    for (n, _) in c.inputs {
        pass.push_str(&format!("        self.pipe.{n}.next = self.{n}.val();\n"));
    }
    for (n, _) in c.outputs {
        pass.push_str(&format!("        self.{n}.next = self.pipe.{n}.val();\n"));
    }
    format!(
        "// Generated by rtl/build.rs from rtl::stream::layout ({block}): do not edit; change the
// tables (rtl/src/stream/layout/tables.rs) or the generator (codegen.rs) instead.

crate::hw_block! {{
    /// `{block}`'s generated core: the record reader and the load bank's handshake, the
    /// receive and load banks of its set-up records, the field selects into `{wraps}`
    /// (`pipe`), the register fields, and the fragment beats.
    pub struct {name}(clock) {{
        in {{ {ins} }}
        out {{ {outs} }}
        pub pipe: {pipe}{pipe_init},
{fields}{decl}    }}
{ctor}}}

impl Logic for {name} {{
    #[hdl_gen]
    fn update(&mut self) {{
        clock!(self, clock, pipe, rd);
{setup}        // The wrapped top's ports the fragment side drives and reads.
{pass}{up}    }}
}}
",
        block = top.block,
        wraps = top.wraps,
        name = c.name,
        ins = ins.join(", "),
        outs = outs.join(", "),
        pipe = c.pipe,
    )
}

/// The two parts of `top`'s core: (field declarations inside its `hw_block!`, statements
/// inside its `update`).
fn generated_rtl(top: &StreamTop) -> (String, String) {
    let n = top.bank_words();
    let no_regs = Record {
        name: "",
        code: 0,
        fields: &[],
    };
    let regs_rec = top.registers.unwrap_or(no_regs);
    let mut decl = String::new();
    decl.push_str("        // The receive bank (payload words of the record being received).\n");
    for k in 0..n {
        decl.push_str(&format!("        sw{k}: DFF<Bits<32>>,\n"));
    }
    decl.push_str("        // The load bank (the complete record waiting for the pipeline).\n");
    for k in 0..n {
        decl.push_str(&format!("        lw{k}: DFF<Bits<32>>,\n"));
    }
    if top.registers.is_some() {
        decl.push_str("        // The active frame and material registers.\n");
    }
    for fl in regs_rec.fields {
        decl.push_str(&format!("        r_{}: DFF<Bits<{}>>,\n", fl.name, fl.bits));
    }
    let mut up = String::new();
    let banks = (0..n)
        .map(|k| format!("sw{k}"))
        .chain((0..n).map(|k| format!("lw{k}")));
    let regs = regs_rec.fields.iter().map(|fl| format!("r_{}", fl.name));
    // Short enough lists that rustfmt leaves each call on one line.
    for (names, per_call) in [(banks.collect::<Vec<_>>(), 9), (regs.collect(), 6)] {
        for chunk in names.chunks(per_call) {
            up.push_str(&format!(
                "        dff_setup!(self, clock, {});\n",
                chunk.join(", ")
            ));
        }
    }
    up.push_str("        // Payload word k is the (k + 1)-th word of a record.\n");
    for k in 0..n {
        up.push_str(&format!(
            "        if self.take_word.val() & (self.word_index.val() == {}) {{\n            self.sw{k}.d.next = self.in_word.val();\n        }}\n",
            k + 1
        ));
    }
    up.push_str("        // A complete record moves to the load bank when that is free.\n");
    up.push_str("        if self.transfer.val() {\n");
    for k in 0..n {
        up.push_str(&format!(
            "            self.lw{k}.d.next = self.sw{k}.q.val();\n"
        ));
    }
    up.push_str("        }\n");
    up.push_str("        // Triangle fields: the pipeline's set-up ports.\n");
    for pl in place(&top.triangle) {
        up.push_str(&format!(
            "        self.pipe.{}.next = {};\n",
            pl.name,
            select(&pl)
        ));
    }
    if let Some(full) = top.full {
        let line = place(&top.triangle);
        let placed = place(&full);
        assert_eq!(
            placed[..line.len()],
            line[..],
            "{}: the line's fields lead, in the same places",
            full.name
        );
        up.push_str(&format!(
            "        // The {} record's further fields (loaded with `first`).\n",
            full.name
        ));
        for pl in &placed[line.len()..] {
            up.push_str(&format!(
                "        self.pipe.{}.next = {};\n",
                pl.name,
                select(pl)
            ));
        }
    }
    // Records applied through a strobe: each field straight from the load bank.
    for (rec, strobe) in [
        (top.texels, "written with `tex_we`"),
        (top.lines, "pushed with `line_push`"),
    ] {
        let Some(rec) = rec else { continue };
        up.push_str(&format!(
            "        // The {} record's fields ({strobe}).\n",
            rec.name
        ));
        for pl in place(&rec) {
            up.push_str(&format!(
                "        self.pipe.{}.next = {};\n",
                pl.name,
                select(&pl)
            ));
        }
    }
    if top.registers.is_some() {
        up.push_str("        // Register fields: applied into the active registers.\n");
        up.push_str("        if self.apply_regs.val() {\n");
        for pl in place(&regs_rec) {
            up.push_str(&format!(
                "            self.r_{}.d.next = {};\n",
                pl.name,
                select(&pl)
            ));
        }
        up.push_str("        }\n");
    }
    for fl in regs_rec.fields {
        up.push_str(&format!(
            "        self.pipe.{0}.next = self.r_{0}.q.val();\n",
            fl.name
        ));
    }
    for pl in FRAGMENT.iter().filter(|pl| pl.bits == 1) {
        decl.push_str(&format!(
            "        frag_{}_bit: Constant<Bits<{FRAGMENT_BITS}>> = Constant::new((1u64 << {}).into()),\n",
            pl.name,
            pl.at()
        ));
    }
    for lane in top.lanes {
        let valid = top.port("pixel", lane);
        up.push_str(&format!(
            "        // The fragment beat{} (`pixel` is the pipeline's `{valid}`).\n",
            if lane.is_empty() {
                String::new()
            } else {
                format!(" of lane {}", &lane[1..].to_uppercase())
            }
        ));
        let terms: Vec<String> = FRAGMENT
            .iter()
            .filter(|pl| pl.bits > 1)
            .map(|pl| {
                let wide = format!(
                    "bit_cast::<{FRAGMENT_BITS}, {}>(self.pipe.{}.val())",
                    pl.bits,
                    top.port(pl.name, lane)
                );
                if pl.at() == 0 {
                    wide
                } else {
                    format!("({wide} << {})", pl.at())
                }
            })
            .collect();
        up.push_str(&format!(
            "        self.beat{lane}_data.next = {};\n        self.beat{lane}.next = self.beat{lane}_data.val();\n",
            terms.join("\n            | ")
        ));
        for pl in FRAGMENT.iter().filter(|pl| pl.bits == 1) {
            let src = top.port(pl.name, lane);
            up.push_str(&format!(
                "        if self.pipe.{src}.val() {{\n            self.beat{lane}.next = self.beat{lane}_data.val() | self.frag_{}_bit.val();\n        }}\n",
                pl.name
            ));
        }
        decl.push_str(&format!(
            "        beat{lane}_data: Signal<Local, Bits<{FRAGMENT_BITS}>>,\n"
        ));
    }
    (decl, up)
}

/// The hardware's select of a placed field from its load-bank word.
fn select(pl: &Placed) -> String {
    if pl.bits > 32 {
        // Low 32 bits from the first word, the rest from the next word's low bits.
        let (b, hi) = (pl.bits, pl.bits - 32);
        let high = if hi == 32 {
            format!("self.lw{}.q.val()", pl.word + 1)
        } else {
            format!("self.lw{}.q.val().get_bits::<{hi}>(0)", pl.word + 1)
        };
        // Broken as rustfmt breaks it (the line is too long for one).
        format!(
            "bit_cast::<{b}, 32>(self.lw{}.q.val())\n            | (bit_cast::<{b}, {hi}>({high}) << 32)",
            pl.word
        )
    } else if pl.bits == 32 {
        format!("self.lw{}.q.val()", pl.word)
    } else if pl.bits == 1 {
        format!("self.lw{}.q.val().get_bit({})", pl.word, pl.offset)
    } else {
        format!(
            "self.lw{}.q.val().get_bits::<{}>({})",
            pl.word, pl.bits, pl.offset
        )
    }
}
