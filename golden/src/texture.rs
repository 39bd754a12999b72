//! Texture images and how a texture coordinate picks a texel.
//!
//! - A [`Texture`] is RGB8 with power-of-two sides up to [`MAX_TEXTURE_SIDE`] (the hardware's
//!   texel address is the coordinate's low bits, and GL_REPEAT is free).
//! - Texture coordinates (s, t) are in texture repeats, t up (OBJ's `vt`): (0, 0) is the
//!   image's bottom-left corner, (1, 1) its top-right.
//! - **Texel space** (what the set-up hands the texture-coordinate hardware): u = s·W − ½,
//!   v = t·H − ½, so texel centres sit at integers ([`Texture::texel_space`]).
//! - **Texel-centre rule**: a point picks its nearest texel centre, (⌊u + ½⌋, ⌊v + ½⌋); a tie
//!   goes up. In (s, t) that is texel ⌊s·W⌋, the texel whose square [i/W, (i + 1)/W) holds s:
//!   OpenGL's GL_NEAREST.
//! - **GL_REPEAT**: texel (i, j) reads column i mod W and row j mod H counted from the bottom
//!   ([`Texture::texel`]), for any integers.

use glam::DVec2;
use std::sync::OnceLock;

/// Largest texture side (texels).
pub const MAX_TEXTURE_SIDE: u32 = 1024;

/// A texture that cannot be used: one-line messages.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TextureError {
    #[error(
        "texture {width}x{height}: each side must be a power of two from 1 to {MAX_TEXTURE_SIDE}"
    )]
    Side { width: u32, height: u32 },
    #[error("texture {width}x{height}: {got} texels given, {want} expected")]
    Size {
        width: u32,
        height: u32,
        got: usize,
        want: usize,
    },
}

/// An RGB8 texture, rows stored top row first (as an image file holds them).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Texture {
    width: u32,
    height: u32,
    rgb: Vec<[u8; 3]>,
}

impl Texture {
    /// A texture of `width`×`height` texels, `rgb` row-major from the top row.
    pub fn new(width: u32, height: u32, rgb: Vec<[u8; 3]>) -> Result<Texture, TextureError> {
        let side_ok = |n: u32| n.is_power_of_two() && n <= MAX_TEXTURE_SIDE;
        if !side_ok(width) || !side_ok(height) {
            return Err(TextureError::Side { width, height });
        }
        let want = width as usize * height as usize;
        if rgb.len() != want {
            return Err(TextureError::Size {
                width,
                height,
                got: rgb.len(),
                want,
            });
        }
        Ok(Texture { width, height, rgb })
    }

    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    /// The texels, row-major from the top row.
    pub fn rgb(&self) -> &[[u8; 3]] {
        &self.rgb
    }

    /// Texel (i, j), i from the left, j from the bottom, wrapped (GL_REPEAT).
    pub fn texel(&self, i: i64, j: i64) -> [u8; 3] {
        let (w, h) = (self.width as i64, self.height as i64);
        let (c, r) = (i.rem_euclid(w), j.rem_euclid(h));
        self.rgb[((h - 1 - r) * w + c) as usize]
    }

    /// Texel-space coordinates of (s, t): (s·W − ½, t·H − ½).
    pub fn texel_space(&self, st: DVec2) -> DVec2 {
        DVec2::new(
            st.x * self.width as f64 - 0.5,
            st.y * self.height as f64 - 0.5,
        )
    }

    /// The nearest texel of a texel-space point (⌊u + ½⌋, ⌊v + ½⌋), wrapped. Non-finite or
    /// huge coordinates saturate and wrap; they never panic.
    pub fn nearest(&self, uv: DVec2) -> [u8; 3] {
        self.texel((uv.x + 0.5).floor() as i64, (uv.y + 0.5).floor() as i64)
    }

    /// The built-in texture: 256×256, a checkerboard of 8-texel squares (light and dark grey)
    /// under a coloured grid, a red column and a blue row every 32 texels (two texels wide),
    /// yellow where they cross. Fine enough that a texel off shows as a broken edge, coloured
    /// so that an error along s and one along t look different.
    pub fn checker() -> Texture {
        let n = 256usize;
        let rgb = (0..n * n)
            .map(|k| {
                let (c, r) = (k % n, n - 1 - k / n); // column, row from the bottom
                let (col_line, row_line) = (c % 32 < 2, r % 32 < 2);
                match (col_line, row_line) {
                    (true, true) => [235, 200, 40],
                    (true, false) => [210, 50, 45],
                    (false, true) => [45, 90, 215],
                    _ if (c / 8 + r / 8) % 2 == 0 => [215, 215, 205],
                    _ => [95, 100, 105],
                }
            })
            .collect();
        Texture::new(n as u32, n as u32, rgb).expect("256×256 is a valid texture")
    }

    /// The built-in texture ([`Texture::checker`]), made once.
    pub fn builtin() -> &'static Texture {
        static BUILTIN: OnceLock<Texture> = OnceLock::new();
        BUILTIN.get_or_init(Texture::checker)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_must_be_powers_of_two_up_to_1024() {
        for (w, h) in [(0, 4), (3, 4), (4, 2048), (1024, 1000)] {
            let e = Texture::new(w, h, vec![[0; 3]; (w * h) as usize]).unwrap_err();
            assert_eq!(
                e,
                TextureError::Side {
                    width: w,
                    height: h
                }
            );
        }
        assert!(Texture::new(1, 1024, vec![[0; 3]; 1024]).is_ok());
        assert!(matches!(
            Texture::new(2, 2, vec![[0; 3]; 3]),
            Err(TextureError::Size {
                got: 3,
                want: 4,
                ..
            })
        ));
    }

    #[test]
    fn the_texel_centre_rule_and_repeat() {
        // 4×2 texture, texel value = (column, row from the bottom, 0).
        let rgb = (0..8)
            .map(|k| [(k % 4) as u8, (1 - k / 4) as u8, 0])
            .collect();
        let t = Texture::new(4, 2, rgb).unwrap();
        assert_eq!(t.texel(0, 0), [0, 0, 0]);
        assert_eq!(t.texel(3, 1), [3, 1, 0]);
        assert_eq!(t.texel(-1, -1), [3, 1, 0]);
        assert_eq!(t.texel(5, 2), [1, 0, 0]);
        // s in [i/W, (i+1)/W) picks column i; t likewise from the bottom.
        for (s, col) in [
            (0.0, 0),
            (0.2499, 0),
            (0.25, 1),
            (0.99, 3),
            (1.0, 0),
            (-0.01, 3),
        ] {
            assert_eq!(
                t.nearest(t.texel_space(DVec2::new(s, 0.1)))[0],
                col,
                "s = {s}"
            );
        }
        for (tt, row) in [(0.0, 0), (0.4999, 0), (0.5, 1), (0.99, 1)] {
            assert_eq!(
                t.nearest(t.texel_space(DVec2::new(0.1, tt)))[1],
                row,
                "t = {tt}"
            );
        }
        // Non-finite input does not panic.
        let _ = t.nearest(DVec2::new(f64::NAN, f64::INFINITY));
        let _ = t.nearest(DVec2::new(-1e300, 1e300));
    }

    #[test]
    fn the_builtin_checker_has_its_grid() {
        let t = Texture::builtin();
        assert_eq!((t.width(), t.height()), (256, 256));
        assert_eq!(t.texel(0, 5), [210, 50, 45]);
        assert_eq!(t.texel(5, 33), [45, 90, 215]);
        assert_eq!(t.texel(32, 32), [235, 200, 40]);
        assert_ne!(t.texel(4, 4), t.texel(12, 4));
        assert_eq!(t.texel(4, 4), t.texel(12, 12));
    }
}
