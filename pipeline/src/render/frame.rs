//! From fragments to a frame: the depth test and the tie rule every family shares.

use golden::render::Frame;
use golden::types::{Plane, ScreenTriangle};

use super::Rendered;
use crate::axis::PipeStats;

/// The frame writer of the lit and span families: a z-buffer on the hardware's depth words
/// (nearer wins, ties keep the first writer), and beside it the f64 depth planes picking a
/// visible triangle per pixel as the golden renderer does, to count the pixels where the two
/// disagree.
pub struct FrameWriter {
    frame: Frame,
    golden_z: Vec<f64>,
    golden_winner: Vec<usize>,
    hw_winner: Vec<usize>,
}

impl FrameWriter {
    pub fn new(width: u32, height: u32) -> FrameWriter {
        let n = width as usize * height as usize;
        FrameWriter {
            frame: Frame::new(width, height),
            golden_z: vec![f64::INFINITY; n],
            golden_winner: vec![usize::MAX; n],
            hw_winner: vec![usize::MAX; n],
        }
    }

    /// A fragment of triangle `k` (whose f64 depth plane is `plane`) with depth word `z`.
    /// Nearer wins; at equal depth the lower `k` (the first writer in mesh order), whatever
    /// order the fragments arrive in.
    pub fn put(&mut self, k: usize, x: u32, y: u32, z: i32, rgb: [u8; 3], plane: &Plane) {
        let (w, h) = (self.frame.width, self.frame.height);
        let (xi, yi) = (x as i32, y as i32);
        let at = (x < w && y < h).then(|| y as usize * w as usize + x as usize);
        let tie_won = at.is_some_and(|i| z as f64 == self.frame.depth[i] && k < self.hw_winner[i]);
        if self.frame.put(xi, yi, z as f64, rgb) {
            self.hw_winner[y as usize * w as usize + x as usize] = k;
        } else if let (true, Some(i)) = (tie_won, at) {
            self.frame.rgb[i] = rgb;
            self.hw_winner[i] = k;
        }
        if let Some(i) = at {
            let zf = plane.at_pixel(xi, yi);
            if zf < self.golden_z[i] || (zf == self.golden_z[i] && k < self.golden_winner[i]) {
                self.golden_z[i] = zf;
                self.golden_winner[i] = k;
            }
        }
    }

    pub fn finish(self, stats: PipeStats) -> Rendered {
        let visibility_mismatches = self
            .hw_winner
            .iter()
            .zip(&self.golden_winner)
            .filter(|(a, b)| a != b)
            .count();
        Rendered {
            frame: self.frame,
            stats,
            visibility_mismatches,
        }
    }
}

/// The frame writer of the Gouraud family: depth from the f64 planes (as the golden renderer),
/// nearer wins, at equal depth the lower triangle index, whatever order the set-up order sent
/// the triangles in.
pub struct PlaneWriter {
    frame: Frame,
    winner: Vec<usize>,
}

impl PlaneWriter {
    pub fn new(width: u32, height: u32) -> PlaneWriter {
        PlaneWriter {
            frame: Frame::new(width, height),
            winner: vec![usize::MAX; width as usize * height as usize],
        }
    }

    /// A pixel of triangle `k` whose f64 depth plane is `plane`.
    pub fn put(&mut self, k: usize, x: u32, y: u32, rgb: [u8; 3], plane: &Plane) {
        let (width, height) = (self.frame.width, self.frame.height);
        let at = (x < width && y < height).then(|| y as usize * width as usize + x as usize);
        let (x, y) = (x as i32, y as i32);
        let z = plane.at_pixel(x, y);
        let tie_won = at.is_some_and(|i| z == self.frame.depth[i] && k < self.winner[i]);
        if self.frame.put(x, y, z, rgb) {
            if let Some(i) = at {
                self.winner[i] = k;
            }
        } else if let (true, Some(i)) = (tie_won, at) {
            self.frame.rgb[i] = rgb;
            self.winner[i] = k;
        }
    }

    pub fn finish(self, stats: PipeStats) -> Rendered {
        Rendered {
            frame: self.frame,
            stats,
            visibility_mismatches: 0,
        }
    }
}

/// The jobs of the triangles the golden renderer draws (those with a depth plane, i.e. non-zero
/// area, and a set-up from `job`), in order, with each one's f64 depth plane.
pub fn jobs_with_depth<J>(
    tris: &[ScreenTriangle],
    mut job: impl FnMut(&ScreenTriangle) -> Result<Option<J>, String>,
) -> Result<(Vec<J>, Vec<Plane>), String> {
    let mut jobs = Vec::with_capacity(tris.len());
    let mut depth = Vec::with_capacity(tris.len());
    for t in tris {
        let Some(d) = t.depth_plane() else { continue };
        if let Some(j) = job(t)? {
            jobs.push(j);
            depth.push(d);
        }
    }
    Ok((jobs, depth))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The frame writer's tie rule: at equal depth the lower triangle index wins, in whichever
    /// order the fragments arrive (so the set-up order cannot change an image); nearer still
    /// wins over a lower index.
    #[test]
    fn frame_writer_ties_go_to_the_lower_triangle() {
        let flat = Plane {
            a: 0.0,
            b: 0.0,
            c: 1.0,
        };
        let near = Plane { c: 0.5, ..flat };
        let stats = PipeStats::default();
        for order in [[0usize, 1, 2], [2, 1, 0], [1, 2, 0]] {
            let mut w = FrameWriter::new(4, 4);
            for &k in &order {
                let (z, plane) = if k == 2 { (100, &near) } else { (200, &flat) };
                // Pixel (1, 1): triangles 0 and 1 tie (z = 200). Pixel (2, 1): all three, and
                // triangle 2 is nearer.
                w.put(k, 1, 1, 200, [k as u8 + 1; 3], &flat);
                w.put(k, 2, 1, z, [k as u8 + 1; 3], plane);
            }
            let r = w.finish(stats);
            assert_eq!(r.frame.rgb[4 + 1], [1; 3], "tie, arrival order {order:?}");
            assert_eq!(
                r.frame.rgb[4 + 2],
                [3; 3],
                "nearer, arrival order {order:?}"
            );
            assert_eq!(r.visibility_mismatches, 0, "arrival order {order:?}");
        }
    }

    /// The plane writer's tie rule, the same: equal depth keeps the lower triangle index.
    #[test]
    fn plane_writer_ties_go_to_the_lower_triangle() {
        let flat = Plane {
            a: 0.0,
            b: 0.0,
            c: 1.0,
        };
        for order in [[0usize, 1], [1, 0]] {
            let mut w = PlaneWriter::new(2, 2);
            for &k in &order {
                w.put(k, 1, 1, [k as u8 + 1; 3], &flat);
            }
            let r = w.finish(PipeStats::default());
            assert_eq!(r.frame.rgb[2 + 1], [1; 3], "arrival order {order:?}");
        }
    }
}
