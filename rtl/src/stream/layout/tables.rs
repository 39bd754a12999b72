//! The tables: every record of every stream top, field by field, the fragment beat, and the
//! tops themselves.
//!
//! Not a block: no ports, no latency (the stream tops' headers give theirs).

/// One field of a record: a port of `pixel-pipeline` (name, width in bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    pub name: &'static str,
    pub bits: u32,
}

pub(super) const fn f(name: &'static str, bits: u32) -> Field {
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

/// A triangle record's fields: the sub-pixel address block's set-up (`address_setup_ports!` in
/// `rtl::units::address_block`: three edges' b0, e0, f, r, d, then the walk's rows), then for
/// each named quantity its plane's four signed Q16.16 words (start, short, long, line). One list
/// for every record that loads an address block and a bilinear interpolator.
macro_rules! triangle_fields {
    ($($plane:literal),* $(; $($more:expr),* $(,)?)?) => {
        [
            f("w_b0", 12), f("w_e0", 20), f("w_f", 12), f("w_r", 20), f("w_d", 20),
            f("a_b0", 12), f("a_e0", 20), f("a_f", 12), f("a_r", 20), f("a_d", 20),
            f("t_b0", 12), f("t_e0", 20), f("t_f", 12), f("t_r", 20), f("t_d", 20),
            f("y_top", 12), f("rows", 12), f("y_switch", 12), f("dir_neg", 1),
            $(
                f(concat!($plane, "_start"), 32),
                f(concat!($plane, "_short"), 32),
                f(concat!($plane, "_long"), 32),
                f(concat!($plane, "_line"), 32),
            )*
            $($($more,)*)?
        ]
    };
}

/// A triangle: the address block's set-up, the normal planes and the depth plane (loaded into
/// the pipeline when its address block is ready; the next record streams in meanwhile).
pub const TRIANGLE: Record = Record {
    name: "triangle",
    code: 1,
    fields: &triangle_fields!("x", "y", "z", "d"),
};

/// A register record's fields: the frame (L, H: signed Q1.15), the exponent n, then the
/// material's words the pipeline takes.
macro_rules! register_fields {
    ($($more:expr),* $(,)?) => {
        [
            f("lx", 16), f("ly", 16), f("lz", 16), f("hx", 16), f("hy", 16), f("hz", 16),
            f("n", 10), $($more),*
        ]
    };
}

/// The frame and material registers (L, H, n, the colour weights). Applied when every
/// triangle loaded before it has left the pipeline, so no fragment mixes two sets.
pub const REGISTERS: Record = Record {
    name: "registers",
    code: 2,
    fields: &register_fields![
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
    fields: &triangle_fields!("r", "g", "b"),
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
    /// A texel record (type 3), where the top has a texture memory: one write, applied when
    /// every load before it has left (as a register record), `tex_we` high for that clock.
    pub texels: Option<Record>,
    /// A line record (type 4), where the wrapped top takes per-line records beside its
    /// triangles: pushed into the top's line FIFO (`line_push`) when it has room
    /// (`line_ready`), in stream order (`textured-stream`'s per-line builds).
    pub lines: Option<Record>,
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
    /// The generated core of the top (`rtl/build.rs` writes it from these tables): the
    /// record banks, the field selects into the wrapped top, the fragment packing.
    pub core: Core,
}

/// What the generated core of a stream top wraps, and which of the wrapped top's control ports
/// it passes to the hand-written top around it (the record reader, the FIFOs and the output
/// registers stay hand-written there).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Core {
    /// The core's type name (`PixelStreamCore`).
    pub name: &'static str,
    /// The wrapped top's type, as the top's module names it.
    pub pipe: &'static str,
    /// Its parameter type, when it is built from one (the core is then `new(p: &P)`).
    pub params: Option<&'static str>,
    /// Inputs of the wrapped top the outer top drives (the fragment side's `hold`), with their
    /// types; `load` and `first` are the core's own.
    pub inputs: &'static [(&'static str, &'static str)],
    /// Outputs of the wrapped top the outer top reads, with their types.
    pub outputs: &'static [(&'static str, &'static str)],
}

/// The control ports a span top passes through (`angular-stream`, `fast-stream`).
const SPAN_OUTPUTS: &[(&str, &str)] = &[
    ("done", "Bit"),
    ("valid_a", "Bit"),
    ("valid_b", "Bit"),
    ("z_a", "Bits<32>"),
    ("z_b", "Bits<32>"),
];

impl StreamTop {
    /// The record types, triangle first.
    pub fn records(&self) -> Vec<Record> {
        std::iter::once(self.triangle)
            .chain(self.registers)
            .chain(self.full)
            .chain(self.texels)
            .chain(self.lines)
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
        format!("{field}{lane}")
    }

    /// The fragment stream's port prefix of `lane`: `m_axis` (one lane), `m_axis_a`, ….
    pub fn stream(lane: &str) -> String {
        format!("m_axis{lane}")
    }
}

/// The lit pixel pipeline's stream top.
pub const PIXEL_STREAM: StreamTop = StreamTop {
    block: "pixel-stream",
    file: "stream/pixel_stream.rs",
    wraps: "pixel-pipeline",
    triangle: TRIANGLE,
    registers: Some(REGISTERS),
    full: None,
    texels: None,
    lines: None,
    tuser: Some(TUSER),
    ports: &[],
    tlast: "the triangle's last event",
    lanes: &[""],
    core: Core {
        name: "PixelStreamCore",
        pipe: "PixelPipeline",
        params: Some("PipelineParams"),
        inputs: &[("hold", "Bit")],
        outputs: &[("done", "Bit"), ("valid", "Bit"), ("z", "Bits<32>")],
    },
};

/// A textured triangle (`textured-stream`): a [`TRIANGLE`]'s fields, then the
/// texture-coordinate block's set-up (`texture_setup_ports!` in
/// `rtl::pipelines::textured_pipeline`: 48-bit two's complement words, 16-bit texels).
pub const TEXTURED_TRIANGLE: Record = Record {
    name: "textured triangle",
    code: 1,
    fields: &triangle_fields!(
        "x", "y", "z", "d";
        f("tex_e0", 48), f("tex_de_line", 48), f("tex_de_short", 48), f("tex_de_long", 48),
        f("tex_u_u0", 16), f("tex_u_w0", 48), f("tex_u_p_line", 48), f("tex_u_p_short", 48),
        f("tex_u_p_long", 48),
        f("tex_v_u0", 16), f("tex_v_w0", 48), f("tex_v_p_line", 48), f("tex_v_p_short", 48),
        f("tex_v_p_long", 48),
    ),
};

/// The textured pipeline's frame and material registers: L, H, n, the specular colour, k_a
/// and k_d (unsigned Q1.15: the texel gives the ambient and diffuse colours) and the texture's
/// sides (log₂). Applied as [`REGISTERS`] are.
pub const TEXTURED_REGISTERS: Record = Record {
    name: "textured registers",
    code: 2,
    fields: &register_fields![
        f("spc_r", 16),
        f("spc_g", 16),
        f("spc_b", 16),
        f("ka", 16),
        f("kd", 16),
        f("log_w", 4),
        f("log_h", 4),
    ],
};

/// One texel written into the texture memory (`texture_memory`'s `waddr`, `wdata`: the
/// address v·2^log_w + u, the colour 0xRRGGBB). Applied when every triangle loaded before it
/// has left, so a texture is never rewritten under a triangle that reads it.
pub const TEXEL: Record = Record {
    name: "texel",
    code: 3,
    fields: &[f("tex_waddr", 16), f("tex_wdata", 24)],
};

/// A raster line's record for the textured pipeline's per-line builds (`texture=quadratic`,
/// `texture=bezier`): its `line_…` ports, the words signed Q15.32 in 48 bits (u + ½, Δ, ΔΔ
/// and v's; the Bézier build's last pixel index and X's Δ(0), d). One per raster line with a
/// pixel, in the walk's order, after its triangle's record.
pub const TEXTURED_LINE: Record = Record {
    name: "textured line",
    code: 4,
    fields: &[
        f("line_u_start", 48),
        f("line_u_step", 48),
        f("line_u_step2", 48),
        f("line_v_start", 48),
        f("line_v_step", 48),
        f("line_v_step2", 48),
        f("line_end", 12),
        f("line_x_step", 48),
        f("line_x_step2", 48),
    ],
};

/// The textured pixel pipeline's stream top.
pub const TEXTURED_STREAM: StreamTop = StreamTop {
    block: "textured-stream",
    file: "stream/textured_stream.rs",
    wraps: "textured-pipeline",
    triangle: TEXTURED_TRIANGLE,
    registers: Some(TEXTURED_REGISTERS),
    texels: Some(TEXEL),
    lines: Some(TEXTURED_LINE),
    core: Core {
        name: "TexturedStreamCore",
        pipe: "TexturedPipeline",
        params: Some("TexturedStreamParams"),
        ..PIXEL_STREAM.core
    },
    ..PIXEL_STREAM
};

/// The Gouraud raster pipe's stream top.
pub const GOURAUD_STREAM: StreamTop = StreamTop {
    block: "gouraud-stream",
    file: "stream/gouraud_stream.rs",
    wraps: "gouraud-raster",
    triangle: GOURAUD_TRIANGLE,
    registers: None,
    full: None,
    texels: None,
    lines: None,
    tuser: None,
    ports: &[],
    tlast: "the triangle's last event",
    lanes: &[""],
    core: Core {
        name: "GouraudStreamCore",
        pipe: "GouraudRaster",
        params: None,
        inputs: &[("hold", "Bit")],
        outputs: &[("done", "Bit"), ("valid", "Bit")],
    },
};

/// The cubic span pipeline's stream top: one record per raster line.
pub const CUBIC_STREAM: StreamTop = StreamTop {
    block: "cubic-stream",
    file: "stream/cubic_stream.rs",
    wraps: "cubic-pipeline",
    triangle: CUBIC_LINE,
    registers: None,
    full: None,
    texels: None,
    lines: None,
    tuser: Some(TUSER),
    ports: &[("y", "y_out")],
    tlast: "the line's last pixel",
    lanes: &[""],
    core: Core {
        name: "CubicStreamCore",
        pipe: "CubicPipeline",
        params: Some("CubicParams"),
        inputs: &[("hold", "Bit")],
        outputs: &[("done", "Bit"), ("valid", "Bit"), ("z", "Bits<32>")],
    },
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
    file: "stream/angular_stream.rs",
    wraps: "angular-pipeline",
    triangle: ANGULAR_LINE,
    registers: Some(SPAN_REGISTERS),
    full: None,
    texels: None,
    lines: None,
    tuser: Some(TUSER),
    ports: &[("y", "y_out")],
    tlast: "the line's last clock, on both lanes (a lane without a pixel then sends a beat with `pixel` = 0)",
    lanes: &["_a", "_b"],
    core: Core {
        name: "AngularStreamCore",
        pipe: "AngularPipeline",
        params: None,
        inputs: &[("hold", "Bit")],
        outputs: SPAN_OUTPUTS,
    },
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
    file: "stream/fast_stream.rs",
    wraps: "fast-pipeline",
    triangle: FAST_LINE,
    core: Core {
        name: "FastStreamCore",
        pipe: "FastPipeline",
        params: Some("FastPipelineParams"),
        ..ANGULAR_STREAM.core
    },
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
    file: "stream/quadric_stream.rs",
    wraps: "quadric-unit",
    triangle: QUADRIC_LINE,
    registers: None,
    full: Some(QUADRIC_TRIANGLE),
    texels: None,
    lines: None,
    core: Core {
        name: "QuadricStreamCore",
        pipe: "QuadricUnit",
        params: None,
        inputs: &[("hold", "Bit")],
        outputs: SPAN_OUTPUTS,
    },
    ..ANGULAR_STREAM
};

/// The fields of [`SUBDIVISION_PARENT`]: `subdivision-raster`'s set-up ports in port order
/// (the shared edge increments, each lane's walk, each lane's twelve BVI words).
macro_rules! subdivision_fields {
    ($($l:literal),*) => {
        &[
            f("w_f", 12), f("w_r", 21), f("w_d", 21),
            f("a_f", 12), f("a_r", 21), f("a_d", 21),
            f("t_f", 12), f("t_r", 21), f("t_d", 21),
            $(
                f(concat!("w_b0_l", $l), 12), f(concat!("w_e0_l", $l), 21),
                f(concat!("a_b0_l", $l), 12), f(concat!("a_e0_l", $l), 21),
                f(concat!("a_third_l", $l), 1),
                f(concat!("t_b0_l", $l), 12), f(concat!("t_e0_l", $l), 21),
                f(concat!("t_adjacent_l", $l), 1),
                f(concat!("y_top_l", $l), 12), f(concat!("rows_l", $l), 12),
                f(concat!("y_switch_l", $l), 12), f(concat!("dir_neg_l", $l), 1),
            )*
            $(
                f(concat!("r_start_l", $l), 32), f(concat!("r_short_l", $l), 32),
                f(concat!("r_long_l", $l), 32), f(concat!("r_line_l", $l), 32),
                f(concat!("g_start_l", $l), 32), f(concat!("g_short_l", $l), 32),
                f(concat!("g_long_l", $l), 32), f(concat!("g_line_l", $l), 32),
                f(concat!("b_start_l", $l), 32), f(concat!("b_short_l", $l), 32),
                f(concat!("b_long_l", $l), 32), f(concat!("b_line_l", $l), 32),
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
    file: "stream/subdivision_stream.rs",
    wraps: "subdivision-raster",
    triangle: SUBDIVISION_PARENT,
    registers: None,
    full: None,
    texels: None,
    lines: None,
    tuser: None,
    ports: &[],
    tlast:
        "the lane's last event of the parent (a beat with `pixel` = 0 when that event has no pixel)",
    lanes: &["_l0", "_l1", "_l2", "_l3"],
    core: Core {
        name: "SubdivisionStreamCore",
        pipe: "SubdivisionRaster",
        params: None,
        inputs: &[("hold", "Bit")],
        outputs: &[
            ("done_l0", "Bit"),
            ("done_l1", "Bit"),
            ("done_l2", "Bit"),
            ("done_l3", "Bit"),
            ("valid_l0", "Bit"),
            ("valid_l1", "Bit"),
            ("valid_l2", "Bit"),
            ("valid_l3", "Bit"),
        ],
    },
};

/// Every stream top.
pub const TOPS: [StreamTop; 8] = [
    PIXEL_STREAM,
    TEXTURED_STREAM,
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

/// `m_axis_tuser`: the fragment's depth `z` (signed Q16.16 pixels, as `pixel-pipeline`'s
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
