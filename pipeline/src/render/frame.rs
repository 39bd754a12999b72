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
    /// The f64 plane's depth of the fragment the hardware shows.
    hw_golden_z: Vec<f64>,
}

impl FrameWriter {
    pub fn new(width: u32, height: u32) -> FrameWriter {
        let n = width as usize * height as usize;
        FrameWriter {
            frame: Frame::new(width, height),
            golden_z: vec![f64::INFINITY; n],
            golden_winner: vec![usize::MAX; n],
            hw_winner: vec![usize::MAX; n],
            hw_golden_z: vec![f64::INFINITY; n],
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
        let zf = plane.at_pixel(xi, yi);
        if self.frame.put(xi, yi, z as f64, rgb) {
            let i = y as usize * w as usize + x as usize;
            self.hw_winner[i] = k;
            self.hw_golden_z[i] = zf;
        } else if let (true, Some(i)) = (tie_won, at) {
            self.frame.rgb[i] = rgb;
            self.hw_winner[i] = k;
            self.hw_golden_z[i] = zf;
        }
        if let Some(i) = at {
            if zf < self.golden_z[i] || (zf == self.golden_z[i] && k < self.golden_winner[i]) {
                self.golden_z[i] = zf;
                self.golden_winner[i] = k;
            }
        }
    }

    pub fn finish(self, stats: PipeStats) -> Rendered {
        let (mut visibility_mismatches, mut visibility_depth_gap) = (0, 0f64);
        for i in 0..self.hw_winner.len() {
            if self.hw_winner[i] != self.golden_winner[i] {
                visibility_mismatches += 1;
                visibility_depth_gap =
                    visibility_depth_gap.max(self.hw_golden_z[i] - self.golden_z[i]);
            }
        }
        Rendered {
            frame: self.frame,
            stats,
            visibility_mismatches,
            visibility_depth_gap,
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
            visibility_depth_gap: 0.0,
        }
    }
}

/// The jobs of the triangles the golden renderer draws (those with a depth plane, i.e. non-zero
/// area, and a set-up from `job`), in order, with each one's f64 depth plane. `job` sees every
/// triangle, drawn or not; its error is returned naming the triangle (`triangle i: …`).
pub fn jobs_with_depth<J>(
    tris: &[ScreenTriangle],
    mut job: impl FnMut(&ScreenTriangle) -> Result<Option<J>, String>,
) -> Result<(Vec<J>, Vec<Plane>), String> {
    let mut jobs = Vec::with_capacity(tris.len());
    let mut depth = Vec::with_capacity(tris.len());
    for (i, t) in tris.iter().enumerate() {
        let j = job(t).map_err(|e| format!("triangle {i}: {e}"))?;
        if let (Some(d), Some(j)) = (t.depth_plane(), j) {
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

    /// A pixel where the depth words tie but the f64 planes differ by rounding noise counts as
    /// a visibility mismatch whose depth gap is that noise; a pixel where the depth words put
    /// the farther surface in front reports the planes' whole gap.
    #[test]
    fn visibility_mismatches_report_the_surfaces_depth_gap() {
        let plane = |c: f64| Plane { a: 0.0, b: 0.0, c };
        // Pixel (0, 0): equal words, triangle 1's plane 1e-12 nearer: the golden pick is 1,
        // the hardware's (tie → lower index) 0.
        let mut w = FrameWriter::new(2, 1);
        w.put(0, 0, 0, 500, [1; 3], &plane(10.0));
        w.put(1, 0, 0, 500, [2; 3], &plane(10.0 - 1e-12));
        let r = w.finish(PipeStats::default());
        assert_eq!(r.visibility_mismatches, 1);
        assert!(
            (r.visibility_depth_gap - 1e-12).abs() < 1e-14,
            "{}",
            r.visibility_depth_gap
        );
        // Pixel (1, 0): the words put triangle 0 in front although its plane is 0.25 farther.
        let mut w = FrameWriter::new(2, 1);
        w.put(0, 1, 0, 400, [1; 3], &plane(5.25));
        w.put(1, 1, 0, 600, [2; 3], &plane(5.0));
        let r = w.finish(PipeStats::default());
        assert_eq!(r.visibility_mismatches, 1);
        assert_eq!(r.visibility_depth_gap, 0.25);
        // Agreement: no mismatch, no gap.
        let mut w = FrameWriter::new(2, 1);
        w.put(0, 1, 0, 600, [1; 3], &plane(5.25));
        w.put(1, 1, 0, 400, [2; 3], &plane(5.0));
        let r = w.finish(PipeStats::default());
        assert_eq!((r.visibility_mismatches, r.visibility_depth_gap), (0, 0.0));
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
