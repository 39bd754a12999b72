//! Golden render driver: every front-facing triangle is walked by the golden address generator
//! (SPEC §5), shaded by one method, and depth-tested into a framebuffer.
//!
//! Depth is resolved here, in the driver, from each triangle's screen-space depth plane at the
//! pixel centre (nearer = smaller z wins; ties keep the first writer). The RTL engine resolves
//! depth the same way, so both engines see identical visibility.

use crate::methods::{shade_triangle_textured, Method};
use crate::raster;
use crate::shade::ShadeContext;
use crate::texture::Texture;
use crate::types::ScreenTriangle;

/// An 8-bit RGB framebuffer with its depth buffer and a per-pixel write counter.
#[derive(Clone, Debug)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// Row-major colours; background is black (adds nothing to NMSE's denominator).
    pub rgb: Vec<[u8; 3]>,
    pub depth: Vec<f64>,
    /// How many fragments reached each pixel (before the depth test): coverage checks use it.
    pub fragments: Vec<u32>,
}

impl Frame {
    pub fn new(width: u32, height: u32) -> Frame {
        let n = width as usize * height as usize;
        Frame {
            width,
            height,
            rgb: vec![[0, 0, 0]; n],
            depth: vec![f64::INFINITY; n],
            fragments: vec![0; n],
        }
    }

    /// Offer a fragment; off-canvas fragments are discarded. Returns whether it was written.
    pub fn put(&mut self, x: i32, y: i32, z: f64, rgb: [u8; 3]) -> bool {
        if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
            return false;
        }
        let i = y as usize * self.width as usize + x as usize;
        self.fragments[i] += 1;
        if z < self.depth[i] {
            self.depth[i] = z;
            self.rgb[i] = rgb;
            true
        } else {
            false
        }
    }

    /// Number of pixels covered by at least one fragment.
    pub fn covered(&self) -> usize {
        self.fragments.iter().filter(|&&f| f > 0).count()
    }
}

/// Render `tris` with `method` into a `width`×`height` frame (textured methods read the
/// built-in texture).
pub fn render(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    width: u32,
    height: u32,
) -> Frame {
    render_textured(tris, method, ctx, Texture::builtin(), width, height)
}

/// [`render`] with the texture the textured methods read.
pub fn render_textured(
    tris: &[ScreenTriangle],
    method: Method,
    ctx: &ShadeContext,
    texture: &Texture,
    width: u32,
    height: u32,
) -> Frame {
    let mut frame = Frame::new(width, height);
    for tri in tris {
        let Some(depth) = tri.depth_plane() else {
            continue; // zero area: no pixel centre inside
        };
        let walk = raster::walk(tri);
        shade_triangle_textured(method, tri, &walk, ctx, texture, &mut |x, y, rgb| {
            frame.put(x, y, depth.at_pixel(x, y), rgb);
        });
    }
    frame
}
