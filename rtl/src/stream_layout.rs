//! Word layouts of the AXI4-Stream tops (`pixel-stream`, `gouraud-stream`, `cubic-stream`,
//! `angular-stream`, `fast-stream`, `quadric-stream`, `subdivision-stream`), defined once.
//!
//! The set-up stream (`s_axis_*`, 32-bit words) carries *records*: a header word, then the
//! record's fields packed LSB first into 32-bit words (a field of up to 32 bits never
//! straddles two words; a wider one takes a word and the next one's low bits), `tlast` on the
//! record's last word. The fragment stream (`m_axis_*`, 64-bit `tdata` and the
//! fragment's 32-bit depth on `tuser`) carries one fragment, or one triangle end, per beat; a
//! two-lane top (`angular-stream`, `fast-stream`, `quadric-stream`) has one such stream per
//! lane (`m_axis_a_*`, `m_axis_b_*`), `subdivision-stream` one per sub-triangle lane
//! (`m_axis_l0_*` … `m_axis_l3_*`, without `tuser`).
//!
//! Everything that reads or writes these words comes from the tables here:
//! - the driver packs records with [`pack`] (`pipeline::stream`), and reads fragments with
//!   [`unpack_fragment`];
//! - each top's field selects and fragment packing (`rtl/src/pixel_stream.rs`,
//!   `rtl/src/gouraud_stream.rs`, `rtl/src/cubic_stream.rs`, `rtl/src/angular_stream.rs`,
//!   `rtl/src/fast_stream.rs`, `rtl/src/quadric_stream.rs`, `rtl/src/subdivision_stream.rs`)
//!   are generated from the same tables
//!   by [`generated_rtl`]; the tests `*_rtl_is_generated` fail if a file's generated regions
//!   differ from what the tables give (set `SHADECORE_REGENERATE=1` to rewrite them);
//! - `rtl/README.md`'s layout table is printed by [`markdown`] (checked by a test as well).
//!
//! Field names and widths are the wrapped top's input ports (`pixel-pipeline`'s,
//! `gouraud-raster`'s, `cubic-pipeline`'s, `angular-pipeline`'s, `fast-pipeline`'s,
//! `quadric-unit`'s, `subdivision-raster`'s), in its port order — the quadric's by name —
//! (checked against its port list by `testbenches/tests/pixel_stream.rs`, `gouraud_stream.rs`,
//! `cubic_stream.rs`, `span_stream.rs` and `subdivision_stream.rs`).
//!
//! Not a block: no ports, no latency (the hardware that reads these words is the stream tops',
//! whose headers give them).

/// One field of a record: a port of `pixel-pipeline` (name, width in bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    pub name: &'static str,
    pub bits: u32,
}

const fn f(name: &'static str, bits: u32) -> Field {
    Field { name, bits }
}

/// A record type of the set-up stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Record {
    pub name: &'static str,
    /// Header word: bits 3..0 hold this code; the other bits are zero.
    pub code: u32,
    pub fields: &'static [Field],
}

/// A triangle: the address block's set-up, the normal planes and the depth plane (loaded into
/// the pipeline when its address block is ready; the next record streams in meanwhile).
pub const TRIANGLE: Record = Record {
    name: "triangle",
    code: 1,
    fields: &[
        f("w_b0", 12),
        f("w_e0", 13),
        f("w_f", 12),
        f("w_r", 13),
        f("w_d", 13),
        f("a_b0", 12),
        f("a_e0", 13),
        f("a_f", 12),
        f("a_r", 13),
        f("a_d", 13),
        f("t_b0", 12),
        f("t_e0", 13),
        f("t_f", 12),
        f("t_r", 13),
        f("t_d", 13),
        f("y_top", 12),
        f("rows", 12),
        f("y_switch", 12),
        f("dir_neg", 1),
        f("x_start", 32),
        f("x_short", 32),
        f("x_long", 32),
        f("x_line", 32),
        f("y_start", 32),
        f("y_short", 32),
        f("y_long", 32),
        f("y_line", 32),
        f("z_start", 32),
        f("z_short", 32),
        f("z_long", 32),
        f("z_line", 32),
        f("d_start", 32),
        f("d_short", 32),
        f("d_long", 32),
        f("d_line", 32),
    ],
};

/// The frame and material registers (L, H, n, the colour weights). Applied when every
/// triangle loaded before it has left the pipeline, so no fragment mixes two sets.
pub const REGISTERS: Record = Record {
    name: "registers",
    code: 2,
    fields: &[
        f("lx", 16),
        f("ly", 16),
        f("lz", 16),
        f("hx", 16),
        f("hy", 16),
        f("hz", 16),
        f("n", 10),
        f("amb_r", 16),
        f("amb_g", 16),
        f("amb_b", 16),
        f("dif_r", 16),
        f("dif_g", 16),
        f("dif_b", 16),
        f("spc_r", 16),
        f("spc_g", 16),
        f("spc_b", 16),
    ],
};

/// Both record types of `pixel-stream`.
pub const RECORDS: [Record; 2] = [TRIANGLE, REGISTERS];

/// A Gouraud triangle (`gouraud-stream`): the address block's set-up and the BVI's twelve
/// signed Q16.16 words (`gouraud-raster`'s set-up ports).
pub const GOURAUD_TRIANGLE: Record = Record {
    name: "gouraud triangle",
    code: 1,
    fields: &[
        f("w_b0", 12),
        f("w_e0", 13),
        f("w_f", 12),
        f("w_r", 13),
        f("w_d", 13),
        f("a_b0", 12),
        f("a_e0", 13),
        f("a_f", 12),
        f("a_r", 13),
        f("a_d", 13),
        f("t_b0", 12),
        f("t_e0", 13),
        f("t_f", 12),
        f("t_r", 13),
        f("t_d", 13),
        f("y_top", 12),
        f("rows", 12),
        f("y_switch", 12),
        f("dir_neg", 1),
        f("r_start", 32),
        f("r_short", 32),
        f("r_long", 32),
        f("r_line", 32),
        f("g_start", 32),
        f("g_short", 32),
        f("g_long", 32),
        f("g_line", 32),
        f("b_start", 32),
        f("b_short", 32),
        f("b_long", 32),
        f("b_line", 32),
    ],
};

/// A raster line of the cubic method (`cubic-stream`): `cubic-pipeline`'s load ports — the
/// line's base (y, first pixel's x, direction, pixels − 1), round(2²⁷/m), the four Q11.5
/// samples per channel, the depth at pixel 0 and per pixel.
pub const CUBIC_LINE: Record = Record {
    name: "cubic line",
    code: 1,
    fields: &[
        f("y", 12),
        f("x0", 12),
        f("dir", 1),
        f("m", 12),
        f("step", 28),
        f("r1", 16),
        f("r2", 16),
        f("r3", 16),
        f("r4", 16),
        f("g1", 16),
        f("g2", 16),
        f("g3", 16),
        f("g4", 16),
        f("b1", 16),
        f("b2", 16),
        f("b3", 16),
        f("b4", 16),
        f("z0", 32),
        f("dz", 32),
    ],
};

/// An AXI4-Stream top: the record that loads a triangle (or a line), the register record if it has one,
/// the fragment beat's sideband. The fragment beat is [`FRAGMENT`] for every top.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StreamTop {
    /// The block's registry name.
    pub block: &'static str,
    /// Its source file under `rtl/src`.
    pub file: &'static str,
    /// The wrapped top's registry name.
    pub wraps: &'static str,
    pub triangle: Record,
    pub registers: Option<Record>,
    /// A second load record (type 2), where the top has one: `triangle`'s fields in the same
    /// places, then more of the wrapped top's load ports; a record of this type loads with
    /// `first` = 1 (`quadric-stream`: a triangle's first line and its coefficients).
    pub full: Option<Record>,
    /// `m_axis_tuser`, when the top has one.
    pub tuser: Option<Field>,
    /// The wrapped top's output port for a fragment field, where it is not the field's name
    /// and lane suffix (`pixel` is `valid` and the lane's suffix unless given here).
    pub ports: &'static [(&'static str, &'static str)],
    /// What `m_axis_tlast` marks.
    pub tlast: &'static str,
    /// The fragment lanes: `&[""]` for one stream (`m_axis_*`, the wrapped top's `x`, `red`,
    /// …); `&["_a", "_b"]` for a two-lane top, one stream per lane (`m_axis_a_*` fed from the
    /// wrapped top's `x_a`, `red_a`, …, `m_axis_b_*` from `x_b`, …). A field in `ports` is the
    /// same port for every lane (the line's `y`).
    pub lanes: &'static [&'static str],
    /// The wrapped top names a lane's ports with a prefix instead: lane `_l0`'s `x` is `l0_x`
    /// (`subdivision-raster`'s four lanes); the streams are still `m_axis_l0_*`, ….
    pub lane_prefix: bool,
}

impl StreamTop {
    /// The record types, triangle first.
    pub fn records(&self) -> Vec<Record> {
        std::iter::once(self.triangle)
            .chain(self.registers)
            .chain(self.full)
            .collect()
    }

    /// The most payload words of any record (the hardware's word bank).
    pub fn bank_words(&self) -> usize {
        self.records().iter().map(payload_words).max().unwrap_or(0)
    }

    /// The wrapped top's output port that fragment field `field` of lane `lane` (a suffix
    /// from [`StreamTop::lanes`]) comes from.
    pub fn port(&self, field: &'static str, lane: &str) -> String {
        let field = match self.ports.iter().find(|(f, _)| *f == field) {
            Some((_, p)) => return p.to_string(),
            None if field == "pixel" => "valid",
            None => field,
        };
        if self.lane_prefix && !lane.is_empty() {
            format!("{}_{field}", &lane[1..])
        } else {
            format!("{field}{lane}")
        }
    }

    /// The fragment stream's port prefix of `lane`: `m_axis` (one lane), `m_axis_a`, ….
    pub fn stream(lane: &str) -> String {
        format!("m_axis{lane}")
    }
}

/// The lit pixel pipeline's stream top.
pub const PIXEL_STREAM: StreamTop = StreamTop {
    block: "pixel-stream",
    file: "pixel_stream.rs",
    wraps: "pixel-pipeline",
    triangle: TRIANGLE,
    registers: Some(REGISTERS),
    full: None,
    tuser: Some(TUSER),
    ports: &[],
    tlast: "the triangle's last event",
    lanes: &[""],
    lane_prefix: false,
};

/// The Gouraud raster pipe's stream top.
pub const GOURAUD_STREAM: StreamTop = StreamTop {
    block: "gouraud-stream",
    file: "gouraud_stream.rs",
    wraps: "gouraud-raster",
    triangle: GOURAUD_TRIANGLE,
    registers: None,
    full: None,
    tuser: None,
    ports: &[],
    tlast: "the triangle's last event",
    lanes: &[""],
    lane_prefix: false,
};

/// The cubic span pipeline's stream top: one record per raster line.
pub const CUBIC_STREAM: StreamTop = StreamTop {
    block: "cubic-stream",
    file: "cubic_stream.rs",
    wraps: "cubic-pipeline",
    triangle: CUBIC_LINE,
    registers: None,
    full: None,
    tuser: Some(TUSER),
    ports: &[("y", "y_out")],
    tlast: "the line's last pixel",
    lanes: &[""],
    lane_prefix: false,
};

/// A raster line of the angular method (`angular-stream`): `angular-pipeline`'s load ports —
/// the line's base (y, first pixel's x, direction, pixels − 1), the cos v accumulator's words
/// for L and for H (p, q, d, cos β), the depth at pixel 0, at pixel m and per pixel.
pub const ANGULAR_LINE: Record = Record {
    name: "angular line",
    code: 1,
    fields: &[
        f("y", 12),
        f("x0", 12),
        f("dir", 1),
        f("m", 12),
        f("lp", 32),
        f("lq", 32),
        f("ld", 32),
        f("lcb", 16),
        f("hp", 32),
        f("hq", 32),
        f("hd", 32),
        f("hcb", 16),
        f("z0", 32),
        f("zm", 32),
        f("dz", 32),
    ],
};

/// The material registers of a span pipeline (`angular-stream`): n and the nine colour
/// weights (L and H are in each line's words). Applied when every line loaded before it has
/// left the pipeline.
pub const SPAN_REGISTERS: Record = Record {
    name: "span registers",
    code: 2,
    fields: &[
        f("n", 10),
        f("amb_r", 16),
        f("amb_g", 16),
        f("amb_b", 16),
        f("dif_r", 16),
        f("dif_g", 16),
        f("dif_b", 16),
        f("spc_r", 16),
        f("spc_g", 16),
        f("spc_b", 16),
    ],
};

/// The angular span pipeline's stream top: one record per raster line, two fragment streams
/// (lane A: pixel k of the line in its clock k; lane B: pixel m − k).
pub const ANGULAR_STREAM: StreamTop = StreamTop {
    block: "angular-stream",
    file: "angular_stream.rs",
    wraps: "angular-pipeline",
    triangle: ANGULAR_LINE,
    registers: Some(SPAN_REGISTERS),
    full: None,
    tuser: Some(TUSER),
    ports: &[("y", "y_out")],
    tlast: "the line's last clock, on both lanes (a lane without a pixel then sends a beat with `pixel` = 0)",
    lanes: &["_a", "_b"],
    lane_prefix: false,
};

/// A raster line of the fast methods (`fast-stream`): `fast-pipeline`'s load ports — the
/// line's base, the fast unit's words for L and for H (b, h, g; the 48-bit d0 and dd, each over
/// two words), the depth at pixel 0, at pixel m and per pixel.
pub const FAST_LINE: Record = Record {
    name: "fast line",
    code: 1,
    fields: &[
        f("y", 12),
        f("x0", 12),
        f("dir", 1),
        f("m", 12),
        f("lb", 32),
        f("lh", 32),
        f("lg", 32),
        f("ld0", 48),
        f("ldd", 48),
        f("hb", 32),
        f("hh", 32),
        f("hg", 32),
        f("hd0", 48),
        f("hdd", 48),
        f("z0", 32),
        f("zm", 32),
        f("dz", 32),
    ],
};

/// The fast span pipeline's stream top: as `angular-stream`, with the fast unit's words.
pub const FAST_STREAM: StreamTop = StreamTop {
    block: "fast-stream",
    file: "fast_stream.rs",
    wraps: "fast-pipeline",
    triangle: FAST_LINE,
    ..ANGULAR_STREAM
};

/// A raster line of the quadric method (`quadric-stream`) after a triangle's first: the line's
/// base and its depth at pixel 0 and per pixel (the tracker reaches its start from the line
/// before).
pub const QUADRIC_LINE: Record = Record {
    name: "quadric line",
    code: 1,
    fields: &[
        f("y", 12),
        f("x0", 12),
        f("dir", 1),
        f("m", 12),
        f("z0", 32),
        f("dz", 32),
    ],
};

/// A triangle's first line (`quadric-stream`): the line's fields, then per channel I, Dx, Dy
/// at its first pixel, 2A, 2B, C (signed Q34.30, 64 bits, each two words).
pub const QUADRIC_TRIANGLE: Record = Record {
    name: "quadric triangle",
    code: 2,
    fields: &[
        f("y", 12),
        f("x0", 12),
        f("dir", 1),
        f("m", 12),
        f("z0", 32),
        f("dz", 32),
        f("ri", 64),
        f("rdx", 64),
        f("rdy", 64),
        f("ra", 64),
        f("rb", 64),
        f("rc", 64),
        f("gi", 64),
        f("gdx", 64),
        f("gdy", 64),
        f("ga", 64),
        f("gb", 64),
        f("gc", 64),
        f("bi", 64),
        f("bdx", 64),
        f("bdy", 64),
        f("ba", 64),
        f("bb", 64),
        f("bc", 64),
    ],
};

/// The quadric unit's stream top: a 4-word record per line, a 40-word one for a triangle's
/// first line (its coefficients), two fragment streams.
pub const QUADRIC_STREAM: StreamTop = StreamTop {
    block: "quadric-stream",
    file: "quadric_stream.rs",
    wraps: "quadric-unit",
    triangle: QUADRIC_LINE,
    registers: None,
    full: Some(QUADRIC_TRIANGLE),
    ..ANGULAR_STREAM
};

/// The fields of [`SUBDIVISION_PARENT`]: `subdivision-raster`'s set-up ports in port order
/// (the shared edge increments, each lane's walk, each lane's twelve BVI words).
macro_rules! subdivision_fields {
    ($($l:literal),*) => {
        &[
            f("w_f", 12), f("w_r", 13), f("w_d", 13),
            f("a_f", 12), f("a_r", 13), f("a_d", 13),
            f("t_f", 12), f("t_r", 13), f("t_d", 13),
            $(
                f(concat!("l", $l, "_w_b0"), 12), f(concat!("l", $l, "_w_e0"), 13),
                f(concat!("l", $l, "_a_b0"), 12), f(concat!("l", $l, "_a_e0"), 13),
                f(concat!("l", $l, "_a_third"), 1),
                f(concat!("l", $l, "_t_b0"), 12), f(concat!("l", $l, "_t_e0"), 13),
                f(concat!("l", $l, "_t_adjacent"), 1),
                f(concat!("l", $l, "_y_top"), 12), f(concat!("l", $l, "_rows"), 12),
                f(concat!("l", $l, "_y_switch"), 12), f(concat!("l", $l, "_dir_neg"), 1),
            )*
            $(
                f(concat!("l", $l, "_r_start"), 32), f(concat!("l", $l, "_r_short"), 32),
                f(concat!("l", $l, "_r_long"), 32), f(concat!("l", $l, "_r_line"), 32),
                f(concat!("l", $l, "_g_start"), 32), f(concat!("l", $l, "_g_short"), 32),
                f(concat!("l", $l, "_g_long"), 32), f(concat!("l", $l, "_g_line"), 32),
                f(concat!("l", $l, "_b_start"), 32), f(concat!("l", $l, "_b_short"), 32),
                f(concat!("l", $l, "_b_long"), 32), f(concat!("l", $l, "_b_line"), 32),
            )*
        ]
    };
}

/// A parent triangle of the subdivision raster pipe (`subdivision-stream`): the four-triangle
/// block's set-up (the shared increments, then per lane its walk) and each lane's twelve
/// signed Q16.16 BVI words (`subdivision-raster`'s set-up ports).
pub const SUBDIVISION_PARENT: Record = Record {
    name: "subdivision parent",
    code: 1,
    fields: subdivision_fields!("0", "1", "2", "3"),
};

/// The subdivision raster pipe's stream top: one record per parent, a fragment stream per
/// lane (sub-triangle K's pixels on `m_axis_lK_*`).
pub const SUBDIVISION_STREAM: StreamTop = StreamTop {
    block: "subdivision-stream",
    file: "subdivision_stream.rs",
    wraps: "subdivision-raster",
    triangle: SUBDIVISION_PARENT,
    registers: None,
    full: None,
    tuser: None,
    ports: &[],
    tlast:
        "the lane's last event of the parent (a beat with `pixel` = 0 when that event has no pixel)",
    lanes: &["_l0", "_l1", "_l2", "_l3"],
    lane_prefix: true,
};

/// Every stream top.
pub const TOPS: [StreamTop; 7] = [
    PIXEL_STREAM,
    GOURAUD_STREAM,
    CUBIC_STREAM,
    ANGULAR_STREAM,
    FAST_STREAM,
    QUADRIC_STREAM,
    SUBDIVISION_STREAM,
];

/// A fragment beat (`m_axis_tdata`, 64 bits); `tlast` marks a triangle's last event. A beat
/// with `pixel` = 0 carries only that end (a triangle whose last event had no pixel). The
/// depth travels on `m_axis_tuser` (AXI4-Stream's per-beat sideband), see [`TUSER`]: the
/// project's simulation rows hold ports of up to 64 bits.
pub const FRAGMENT: &[Placed] = &[
    p("x", 12, 0),
    p("y", 12, 12),
    p("pixel", 1, 24),
    p("red", 8, 32),
    p("green", 8, 40),
    p("blue", 8, 48),
];

/// Width of `m_axis_tdata`.
pub const FRAGMENT_BITS: u32 = 64;

/// `m_axis_tuser`: the fragment's depth `z` (signed Q16.16 model units, as `pixel-pipeline`'s
/// `z` port), 32 bits.
pub const TUSER: Field = Field {
    name: "z",
    bits: 32,
};

const fn p(name: &'static str, bits: u32, at: u32) -> Placed {
    Placed {
        name,
        bits,
        word: (at / 32) as usize,
        offset: at % 32,
    }
}

/// A field's place: word index within the payload (0 = the word after the header) and bit
/// offset within the word (for [`FRAGMENT`]: 32-bit lane and offset).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placed {
    pub name: &'static str,
    pub bits: u32,
    pub word: usize,
    pub offset: u32,
}

impl Placed {
    /// The last word the field has bits in (`word` unless it is wider than 32 bits).
    pub fn last_word(&self) -> usize {
        self.word + (self.offset + self.bits - 1) as usize / 32
    }

    /// Bit position in a multi-word beat.
    pub fn at(&self) -> u32 {
        self.word as u32 * 32 + self.offset
    }
}

/// The fields of `r` placed LSB first, a field never straddling a word; a field wider than 32
/// bits (up to 64) starts a word and takes the next one's low bits for the rest (its low 32
/// bits in the first word).
pub fn place(r: &Record) -> Vec<Placed> {
    let (mut word, mut used) = (0usize, 0u32);
    r.fields
        .iter()
        .map(|fl| {
            assert!(
                (1..=64).contains(&fl.bits),
                "{}: a field has 1 to 64 bits",
                fl.name
            );
            if used + fl.bits > 32 && used > 0 {
                word += 1;
                used = 0;
            }
            let pl = Placed {
                name: fl.name,
                bits: fl.bits,
                word,
                offset: used,
            };
            if fl.bits > 32 {
                word += 1;
                used = fl.bits - 32;
            } else {
                used += fl.bits;
            }
            pl
        })
        .collect()
}

/// Payload words of `r` (without the header).
pub fn payload_words(r: &Record) -> usize {
    place(r).last().map_or(0, |p| p.last_word() + 1)
}

/// The most payload words of any `pixel-stream` record (its word bank).
pub fn bank_words() -> usize {
    PIXEL_STREAM.bank_words()
}

/// The header word of `r`.
pub fn header(r: &Record) -> u32 {
    r.code
}

/// A record's words: header, then `values` (one per field, in field order; only the field's
/// low bits are kept) packed. `tlast` goes with the last word.
pub fn pack(r: &Record, values: &[u64]) -> Vec<u32> {
    assert_eq!(
        values.len(),
        r.fields.len(),
        "{}: one value per field",
        r.name
    );
    let placed = place(r);
    let mut words = vec![0u32; 1 + payload_words(r)];
    words[0] = header(r);
    for (pl, v) in placed.iter().zip(values) {
        let v = *v & mask64(pl.bits);
        words[1 + pl.word] |= (v << pl.offset) as u32;
        if pl.bits > 32 {
            words[2 + pl.word] |= (v >> 32) as u32;
        }
    }
    words
}

/// The low `bits` bits set.
fn mask64(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// The inverse of [`pack`] for the payload (without the header).
pub fn unpack(r: &Record, payload: &[u32]) -> Vec<u64> {
    place(r)
        .iter()
        .map(|pl| {
            let mut v = (payload[pl.word] as u64) >> pl.offset;
            if pl.bits > 32 {
                v |= (payload[pl.word + 1] as u64) << 32;
            }
            v & mask64(pl.bits)
        })
        .collect()
}

/// A fragment beat's fields, in [`FRAGMENT`] order.
pub fn unpack_fragment(beat: u128) -> Vec<u64> {
    FRAGMENT
        .iter()
        .map(|pl| ((beat >> pl.at()) & ((1u128 << pl.bits) - 1)) as u64)
        .collect()
}

/// A fragment beat from field values in [`FRAGMENT`] order.
pub fn pack_fragment(values: &[u64]) -> u128 {
    FRAGMENT
        .iter()
        .zip(values)
        .map(|(pl, v)| ((*v as u128) & ((1u128 << pl.bits) - 1)) << pl.at())
        .fold(0, |a, b| a | b)
}

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

/// Marker lines around the generated regions of a stream top's source.
pub const BEGIN: &str = "// BEGIN GENERATED by rtl::stream_layout::generated_rtl";
pub const END: &str = "// END GENERATED";

/// The two generated regions of `top`'s source (`rtl/src/<file>`): (declarations inside the
/// block's `hw_block!`, statements inside its `update`).
pub fn generated_rtl(top: &StreamTop) -> (String, String) {
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

/// `text` (a stream top's source) with its two generated regions replaced by what
/// [`generated_rtl`] gives for `top`.
pub fn with_generated(text: &str, top: &StreamTop) -> String {
    let (decl, up) = generated_rtl(top);
    let mut out = String::new();
    let mut rest = text;
    for body in [&decl, &up] {
        let b = rest.find(BEGIN).expect("BEGIN marker");
        let line_end = b + rest[b..].find('\n').unwrap() + 1;
        let e = line_end + rest[line_end..].find(END).expect("END marker");
        let indent_start = rest[..e].rfind('\n').unwrap() + 1;
        out.push_str(&rest[..line_end]);
        out.push_str(body);
        out.push_str(&rest[indent_start..e]);
        rest = &rest[e..];
    }
    out.push_str(rest);
    out
}

/// Check `top`'s source file against the tables: `Err` naming the file when its generated
/// regions differ (white space aside) (with `SHADECORE_REGENERATE` set, the file is rewritten instead).
pub fn check_generated(top: &StreamTop) -> Result<(), String> {
    let path = format!("{}/src/{}", env!("CARGO_MANIFEST_DIR"), top.file);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{path}: {e}"))?;
    let out = with_generated(&text, top);
    // Compared without white space: rustfmt may break a generated line differently (run
    // `cargo fmt` after regenerating).
    let squash = |t: &str| t.split_whitespace().collect::<String>();
    if squash(&out) == squash(&text) {
        Ok(())
    } else if std::env::var_os("SHADECORE_REGENERATE").is_some() {
        std::fs::write(&path, &out).map_err(|e| format!("{path}: {e}"))
    } else {
        Err(format!(
            "rtl/src/{} is not what rtl::stream_layout generates: run with SHADECORE_REGENERATE=1",
            top.file
        ))
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_pack_and_unpack() {
        for r in TOPS.iter().flat_map(|t| t.records()) {
            let values: Vec<u64> = r
                .fields
                .iter()
                .enumerate()
                .map(|(i, fl)| 0x9E37_79B9_7F4A_7C15u64.rotate_left(i as u32 * 7) & mask64(fl.bits))
                .collect();
            let words = pack(&r, &values);
            assert_eq!(words[0], r.code);
            assert_eq!(unpack(&r, &words[1..]), values);
        }
        assert_eq!(payload_words(&TRIANGLE), 25);
        assert_eq!(payload_words(&REGISTERS), 8);
        assert_eq!(payload_words(&GOURAUD_TRIANGLE), 21);
        assert_eq!(payload_words(&CUBIC_LINE), 11);
        assert_eq!(payload_words(&ANGULAR_LINE), 13);
        assert_eq!(payload_words(&SPAN_REGISTERS), 5);
        assert_eq!(payload_words(&FAST_LINE), 19);
        assert_eq!(payload_words(&QUADRIC_LINE), 4);
        assert_eq!(payload_words(&QUADRIC_TRIANGLE), 40);
        assert_eq!(payload_words(&SUBDIVISION_PARENT), 71);
    }

    /// Every record's payload fits the record reader's word count.
    #[test]
    fn records_fit_the_readers_count() {
        for top in TOPS {
            assert!(
                top.bank_words() < 1 << crate::record_reader::INDEX_BITS,
                "{}: {} words",
                top.block,
                top.bank_words()
            );
        }
    }

    /// A lane-prefixed top takes lane K's fragment fields from the wrapped top's `lK_*` ports.
    #[test]
    fn lane_prefixed_ports() {
        let t = SUBDIVISION_STREAM;
        assert_eq!(t.port("x", "_l2"), "l2_x");
        assert_eq!(t.port("pixel", "_l0"), "l0_valid");
        assert_eq!(StreamTop::stream("_l3"), "m_axis_l3");
        assert_eq!(ANGULAR_STREAM.port("pixel", "_b"), "valid_b");
        assert_eq!(ANGULAR_STREAM.port("y", "_b"), "y_out");
    }

    /// A field wider than 32 bits starts a word and ends in the next one's low bits, where
    /// the next field may follow; 64 bits take two whole words.
    #[test]
    fn wide_fields_take_two_words() {
        const R: Record = Record {
            name: "wide",
            code: 1,
            fields: &[f("a", 5), f("w", 48), f("b", 16), f("c", 64), f("d", 1)],
        };
        let at: Vec<(usize, u32, usize)> = place(&R)
            .iter()
            .map(|p| (p.word, p.offset, p.last_word()))
            .collect();
        assert_eq!(at, [(0, 0, 0), (1, 0, 2), (2, 16, 2), (3, 0, 4), (5, 0, 5)]);
        let v = [0x1F, 0xABCD_1234_5678, 0xBEEF, u64::MAX - 5, 1];
        let words = pack(&R, &v);
        assert_eq!(words[2..5], [0x1234_5678, 0xBEEF_ABCD, 0xFFFF_FFFA]);
        assert_eq!(unpack(&R, &words[1..]), v);
    }

    #[test]
    fn fragment_fields_do_not_overlap() {
        let mut used = 0u128;
        for pl in FRAGMENT {
            let m = ((1u128 << pl.bits) - 1) << pl.at();
            assert_eq!(used & m, 0, "{} overlaps", pl.name);
            assert!(pl.at() + pl.bits <= FRAGMENT_BITS);
            used |= m;
        }
        let v = [0xABC, 0x123, 1, 0x12, 0x34, 0x56];
        assert_eq!(unpack_fragment(pack_fragment(&v)), v);
    }
}
