//! Verilog export of the RTL blocks.
//!
//! rust-hdl names the top module `top` and every sub-module by its path (`top$scale$f`).
//! [`verilog`] renames that prefix to the block's module name ([`BlockKind::module_name`]) so the
//! files of several blocks can be read into one tool without collisions.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use rust_hdl::prelude::*;

use crate::address_block::AddressBlock;
use crate::gouraud_raster::GouraudRaster;
use crate::intensity_interpolator::IntensityInterpolator;
use crate::k_recurrence::{KRecurrence, SpanNormalizer};
use crate::normalizer::{Normalizer, NormalizerCoeffs, NormalizerK};

/// The exportable blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BlockKind {
    /// N in, N·f(|N|²) out (squarers + Horner + scaling).
    Normalizer,
    /// N and K in, N·f(K) out (the normalizer without its squarers).
    NormalizerK,
    /// K along a span by additions.
    KRecurrence,
    /// K recurrence + vector interpolation feeding NormalizerK.
    SpanNormalizer,
    /// One triangle's set-up in, its pixel addresses out, one per clock (SPEC §5).
    AddressBlock,
    /// BVI: the address block's step information in, 8-bit R, G, B per pixel out (SPEC §6).
    IntensityInterpolator,
    /// Gouraud raster pipe: address block feeding the BVI.
    GouraudRaster,
}

impl BlockKind {
    pub const ALL: [BlockKind; 7] = [
        BlockKind::Normalizer,
        BlockKind::NormalizerK,
        BlockKind::KRecurrence,
        BlockKind::SpanNormalizer,
        BlockKind::AddressBlock,
        BlockKind::IntensityInterpolator,
        BlockKind::GouraudRaster,
    ];

    /// Address block: clocks from the accepted `load` to the triangle's first event (header of
    /// `address_block`; the blocks of SPEC §5–6 have no `LATENCY` constant of their own).
    pub const ADDRESS_BLOCK_LATENCY: usize = 3;
    /// BVI: clocks from an event (`in_valid`) to its colour (`valid_out`).
    pub const INTENSITY_INTERPOLATOR_LATENCY: usize = 1;
    /// Raster pipe: clocks from the accepted `load` to the first pixel (address block + BVI).
    pub const GOURAUD_RASTER_LATENCY: usize =
        Self::ADDRESS_BLOCK_LATENCY + Self::INTENSITY_INTERPOLATOR_LATENCY;

    /// The CLI name (`--block NAME`).
    pub fn name(self) -> &'static str {
        match self {
            BlockKind::Normalizer => "normalizer",
            BlockKind::NormalizerK => "normalizer-k",
            BlockKind::KRecurrence => "k-recurrence",
            BlockKind::SpanNormalizer => "span-normalizer",
            BlockKind::AddressBlock => "address-block",
            BlockKind::IntensityInterpolator => "intensity-interpolator",
            BlockKind::GouraudRaster => "gouraud-raster",
        }
    }

    /// The Verilog name of the block's top module.
    pub fn module_name(self) -> String {
        self.name().replace('-', "_")
    }

    /// Clocks from an input to its output ([`BlockKind::latency_meaning`] says which).
    pub fn latency(self) -> usize {
        match self {
            BlockKind::Normalizer => Normalizer::LATENCY,
            BlockKind::NormalizerK => NormalizerK::LATENCY,
            BlockKind::KRecurrence => KRecurrence::LATENCY,
            BlockKind::SpanNormalizer => SpanNormalizer::LATENCY,
            BlockKind::AddressBlock => Self::ADDRESS_BLOCK_LATENCY,
            BlockKind::IntensityInterpolator => Self::INTENSITY_INTERPOLATOR_LATENCY,
            BlockKind::GouraudRaster => Self::GOURAUD_RASTER_LATENCY,
        }
    }

    /// What [`BlockKind::latency`] measures, and the block's throughput.
    pub fn latency_meaning(self) -> &'static str {
        match self {
            BlockKind::Normalizer
            | BlockKind::NormalizerK
            | BlockKind::KRecurrence
            | BlockKind::SpanNormalizer => "valid_in to valid_out, one input per clock",
            BlockKind::AddressBlock => "load to the first event, one address per clock",
            BlockKind::IntensityInterpolator => "in_valid to valid_out, one pixel per clock",
            BlockKind::GouraudRaster => "load to the first pixel, one pixel per clock",
        }
    }

    /// The block is built from the normalizer coefficients.
    pub fn uses_coeffs(self) -> bool {
        match self {
            BlockKind::Normalizer | BlockKind::NormalizerK | BlockKind::SpanNormalizer => true,
            BlockKind::KRecurrence
            | BlockKind::AddressBlock
            | BlockKind::IntensityInterpolator
            | BlockKind::GouraudRaster => false,
        }
    }

    /// Names accepted by `--block` (plus `all`).
    pub fn names() -> String {
        Self::ALL
            .iter()
            .map(|b| b.name())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl std::fmt::Display for BlockKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for BlockKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .iter()
            .copied()
            .find(|b| b.name() == s)
            .ok_or_else(|| format!("unknown block {s:?} (expected one of: {})", Self::names()))
    }
}

/// rust-hdl's Verilog of a block (module `top`), checked for open signals and loops.
pub fn raw_verilog<B: Block>(mut uut: B) -> Result<String, String> {
    uut.connect_all();
    check_all(&uut).map_err(|e| format!("rust-hdl check failed: {e:?}"))?;
    Ok(generate_verilog(&uut))
}

/// Rename the module prefix `top` (module names `top`, `top$...`) to `name`. Identifiers are
/// matched whole, so signals that merely contain `top` are untouched.
pub fn rename_top(verilog: &str, name: &str) -> String {
    let is_ident = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$';
    let mut out = String::with_capacity(verilog.len() + 1024);
    let mut ident = String::new();
    let flush = |ident: &mut String, out: &mut String| {
        if ident == "top" || ident.starts_with("top$") {
            out.push_str(name);
            out.push_str(&ident[3..]);
        } else {
            out.push_str(ident);
        }
        ident.clear();
    };
    for c in verilog.chars() {
        if is_ident(c) {
            ident.push(c);
        } else {
            flush(&mut ident, &mut out);
            out.push(c);
        }
    }
    flush(&mut ident, &mut out);
    out
}

/// Synthesizable Verilog of `block` built with `coeffs`; top module [`BlockKind::module_name`].
pub fn verilog(block: BlockKind, coeffs: &NormalizerCoeffs) -> Result<String, String> {
    let raw = match block {
        BlockKind::Normalizer => raw_verilog(Normalizer::new(coeffs))?,
        BlockKind::NormalizerK => raw_verilog(NormalizerK::new(coeffs))?,
        BlockKind::KRecurrence => raw_verilog(KRecurrence::new())?,
        BlockKind::SpanNormalizer => raw_verilog(SpanNormalizer::new(coeffs))?,
        BlockKind::AddressBlock => raw_verilog(AddressBlock::default())?,
        BlockKind::IntensityInterpolator => raw_verilog(IntensityInterpolator::default())?,
        BlockKind::GouraudRaster => raw_verilog(GouraudRaster::default())?,
    };
    let c = coeffs.requested;
    let mut header = format!(
        "// Generated by `shadecore export-verilog --block {}` from rtl/src (rust-hdl). Do not edit.\n\
         // Top module: {}. Latency {} clocks ({}).\n\
         // Ports and formats: see the block's header in rtl/src.\n",
        block.name(),
        block.module_name(),
        block.latency(),
        block.latency_meaning()
    );
    if block.uses_coeffs() {
        header.push_str(&format!(
            "// Coefficients (c2, c1, c0) = ({}, {}, {}); as quantized: {:?}\n",
            c[0],
            c[1],
            c[2],
            coeffs.quantized()
        ));
    }
    Ok(format!(
        "{header}{}",
        rename_top(&raw, &block.module_name())
    ))
}

/// Write `<dir>/<module_name>.v`; returns the path.
pub fn write(block: BlockKind, coeffs: &NormalizerCoeffs, dir: &Path) -> Result<PathBuf, String> {
    let text = verilog(block, coeffs)?;
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let path = dir.join(format!("{}.v", block.module_name()));
    std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rename_touches_module_names_only() {
        let v = "module top(a);\n top$x x(.d(top_sig));\nendmodule // top$x\nwire stop$top;";
        let r = rename_top(v, "norm");
        assert_eq!(
            r,
            "module norm(a);\n norm$x x(.d(top_sig));\nendmodule // norm$x\nwire stop$top;"
        );
    }

    #[test]
    fn block_names_round_trip() {
        for b in BlockKind::ALL {
            assert_eq!(b.name().parse::<BlockKind>(), Ok(b));
        }
        assert!("nope"
            .parse::<BlockKind>()
            .unwrap_err()
            .contains("expected one of"));
    }

    #[test]
    fn every_block_generates_verilog() {
        let c = NormalizerCoeffs::published();
        for b in BlockKind::ALL {
            let v = verilog(b, &c).unwrap();
            assert!(v.contains(&format!("module {}(", b.module_name())), "{b}");
            assert!(!v.contains("module top"), "{b}");
            // Only blocks built from the coefficients name them in their header.
            assert_eq!(v.contains("// Coefficients"), b.uses_coeffs(), "{b}");
        }
    }

    #[test]
    fn module_names_are_distinct_identifiers() {
        let names: std::collections::HashSet<String> =
            BlockKind::ALL.iter().map(|b| b.module_name()).collect();
        assert_eq!(names.len(), BlockKind::ALL.len());
        for n in &names {
            assert!(n.chars().all(|c| c.is_ascii_lowercase() || c == '_'), "{n}");
        }
        assert_eq!(BlockKind::GouraudRaster.module_name(), "gouraud_raster");
    }
}
