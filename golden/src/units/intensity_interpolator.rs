//! Intensity interpolator BVI (SPEC §6): the f64 golden of the per-pixel accumulation, and the
//! per-triangle set-up values the RTL block (`rtl/src/units/intensity_interpolator.rs`) loads.
//!
//! A channel's Gouraud intensity is a screen-space [`Plane`] (see `golden::shading::gouraud`). The golden
//! BVI follows the walk exactly as SPEC §6 describes: the intensity at the first line start is
//! sampled from the plane, every working-edge step adds its increment (ΔI_H = a per horizontal
//! step in its direction, ΔI_V = b per vertical step, ΔI_D = ±a + b per diagonal step), and
//! every pixel along a line adds dir·a. The RTL adds the same increments, grouped per line
//! (`short`/`long`: the whole move of the working edge into a line) and quantized to signed Q16.16.

use crate::types::{Plane, StepType, Walk};
use crate::units::address_block::{AddressOutputs, AddressSetup};

/// Fraction bits of the hardware's intensity words (signed Q16.16, 8-bit LSB units).
pub const FRAC_BITS: u32 = 16;

/// One channel's set-up in LSB units (the 0..255 scale), before quantization.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChannelSetup {
    /// Intensity at the centre of the first line's start pixel (x_start, y_top).
    pub start: f64,
    /// Line-start increment after a short working-edge move (f pixels): f·a + b.
    pub short: f64,
    /// Line-start increment after a long move (f + 1 pixels): (f + 1)·a + b.
    pub long: f64,
    /// Increment along a line: dir·a.
    pub line: f64,
}

/// The four 32-bit words a channel loads: start (with the +½ LSB rounding bias), short,
/// long, line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ChannelWords {
    pub start: u32,
    pub short: u32,
    pub long: u32,
    pub line: u32,
}

/// Round `v` (LSB units) to the nearest signed Q16.16 word (ties toward +∞, as everywhere in
/// `rtl::core::fixed`), modulo 2^32 (the hardware's adders wrap; the RTL header says why that is
/// harmless).
pub fn quantize(v: f64) -> u32 {
    let scaled = (v * (1u64 << FRAC_BITS) as f64 + 0.5).floor();
    // i128 holds any finite f64 we can meet here (|v| < 2^60 for 12-bit geometry).
    (scaled as i128).rem_euclid(1i128 << 32) as u32
}

/// The intensity (LSB units) a word stands for, without the rounding bias.
pub fn word_value(word: u32) -> f64 {
    word as i32 as f64 / (1u64 << FRAC_BITS) as f64
}

/// The hardware's output function of a running word: saturate to 0..=255, drop the fraction.
pub fn saturate(word: u32) -> u8 {
    let v = word as i32;
    if v < 0 {
        0
    } else if v >= 256 << FRAC_BITS {
        255
    } else {
        (v >> FRAC_BITS) as u8
    }
}

impl ChannelSetup {
    /// Set-up of `plane` for the walk described by `addr`.
    pub fn new(plane: &Plane, addr: &AddressSetup) -> ChannelSetup {
        let f = addr.w.f as f64;
        let dir = if addr.dir_neg { -1.0 } else { 1.0 };
        ChannelSetup {
            start: plane.at_pixel(addr.x_start_top(), addr.y_top as i32),
            short: f * plane.a + plane.b,
            long: (f + 1.0) * plane.a + plane.b,
            line: dir * plane.a,
        }
    }

    /// Quantized words; `start` carries +½ LSB so the hardware's truncation rounds to nearest.
    pub fn words(&self) -> ChannelWords {
        ChannelWords {
            start: quantize(self.start + 0.5),
            short: quantize(self.short),
            long: quantize(self.long),
            line: quantize(self.line),
        }
    }
}

/// Set-up of the three channels' planes.
pub fn setup(planes: &[Plane; 3], addr: &AddressSetup) -> [ChannelSetup; 3] {
    planes.map(|p| ChannelSetup::new(&p, addr))
}

/// The golden BVI: the f64 intensity of every pixel of `walk` (in `Walk::pixels` order),
/// accumulated along the walk's steps from the plane's value at the first line start.
pub fn interpolate(walk: &Walk, plane: &Plane) -> Vec<f64> {
    let mut out = Vec::with_capacity(walk.pixel_count());
    let Some(first) = walk.rows.first() else {
        return out;
    };
    let mut edge = plane.at_pixel(first.x_start, first.y);
    for row in &walk.rows {
        for s in &row.edge_steps {
            let h = s.dx as f64 * plane.a;
            edge += match s.step {
                StepType::Horizontal => h,
                StepType::Vertical => plane.b,
                StepType::Diagonal => h + plane.b,
                StepType::Start => 0.0,
            };
        }
        let mut i = edge;
        for k in 0..row.len {
            if k > 0 {
                i += row.dir as f64 * plane.a;
            }
            out.push(i);
        }
    }
    out
}

/// The bound on |word/2^16 − (I + ½)| the format guarantees for a pixel reached by `adds`
/// additions (1 for the first line start, plus one per line below it and per pixel along
/// its line): each quantized term is off by at most 2^-17.
pub fn error_bound(adds: u32) -> f64 {
    adds as f64 / (1u64 << (FRAC_BITS + 1)) as f64
}

/// Number of additions behind each pixel of `walk` (see [`error_bound`]).
pub fn additions(walk: &Walk) -> Vec<u32> {
    let mut out = Vec::with_capacity(walk.pixel_count());
    for (k, row) in walk.rows.iter().enumerate() {
        for i in 0..row.len {
            out.push(1 + k as u32 + i);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::walk;
    use crate::types::ScreenTriangle;

    fn tri(p: [(i32, i32); 3]) -> ScreenTriangle {
        ScreenTriangle::from_points(p)
    }

    #[test]
    fn following_the_walk_reproduces_the_plane() {
        for p in [
            [(3, 1), (40, 7), (11, 30)],
            [(40, 1), (3, 7), (11, 30)],
            [(0, 0), (300, 2), (5, 9)],
        ] {
            let t = tri(p);
            let plane = t.scalar_plane([10.0, 250.0, 77.7]).unwrap();
            let w = walk(&t);
            let got = interpolate(&w, &plane);
            for (px, v) in w.pixels().iter().zip(&got) {
                assert!(
                    (v - plane.at_pixel(px.x, px.y)).abs() < 1e-9,
                    "{p:?} {px:?}"
                );
            }
        }
    }

    #[test]
    fn quantize_wraps_and_rounds() {
        assert_eq!(quantize(1.0), 1 << 16);
        assert_eq!(quantize(-1.0), (-(1i32 << 16)) as u32);
        assert_eq!(quantize(0.5 / 65536.0), 1);
        assert_eq!(quantize(65536.0), 0); // 2^32 wraps to 0
        assert_eq!(saturate(quantize(-0.1)), 0);
        assert_eq!(saturate(quantize(300.0)), 255);
        assert_eq!(saturate(quantize(254.99)), 254);
    }
}

/// Bit-exact twin of one BVI channel (`rtl/src/units/intensity_interpolator.rs`), written from the
/// SPEC §6 register transfers: RG1–RG5, the shadow bank SH1–SH3, SH5, one wrap-around adder.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ChannelTwin {
    rg: [u32; 5],
    sh: ChannelWords,
}

impl ChannelTwin {
    /// RG4, the running word.
    pub fn word(&self) -> u32 {
        self.rg[3]
    }

    /// One rising edge for the event (`first`, `row_start`, `carry`, `valid`), writing the
    /// shadow bank from `load` if present.
    pub fn clock(
        &mut self,
        load: Option<&ChannelWords>,
        first: bool,
        row_start: bool,
        carry: bool,
        valid: bool,
    ) {
        let [rg1, rg2, rg3, rg4, rg5] = self.rg;
        let sum = if first {
            self.sh.start
        } else if row_start {
            rg5.wrapping_add(if carry { rg2 } else { rg1 })
        } else {
            rg4.wrapping_add(rg3)
        };
        if first {
            self.rg[0] = self.sh.short;
            self.rg[1] = self.sh.long;
            self.rg[2] = self.sh.line;
        }
        if row_start {
            self.rg[4] = sum;
        }
        if valid {
            self.rg[3] = sum;
        }
        if let Some(w) = load {
            self.sh = *w;
        }
    }
}

/// Bit-exact twin of the whole BVI: three [`ChannelTwin`]s sharing the address block's event,
/// and `valid` delayed one clock (latency 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BviTwin {
    pub channels: [ChannelTwin; 3],
    valid_p1: bool,
}

impl BviTwin {
    /// (valid_out, saturated levels, running words) shown this clock.
    pub fn outputs(&self) -> (bool, [u8; 3], [u32; 3]) {
        let w = self.channels.map(|c| c.word());
        (self.valid_p1, w.map(saturate), w)
    }

    /// One rising edge: the address block's event `ev` (its `valid`, `row_start`, `step`
    /// code and `carry`) and, with `load`, the next triangle's words.
    pub fn clock(&mut self, load: Option<&[ChannelWords; 3]>, ev: &AddressOutputs) {
        let first = ev.row_start && ev.step == 0;
        for (k, ch) in self.channels.iter_mut().enumerate() {
            ch.clock(load.map(|w| &w[k]), first, ev.row_start, ev.carry, ev.valid);
        }
        self.valid_p1 = ev.valid;
    }
}
