//! Image quality metric of the thesis (SPEC §0, thesis §4.3):
//! NMSE = Σ((R−r)² + (G−g)² + (B−b)²) / Σ(R² + G² + B²) over 8-bit RGB, against the reference
//! (R, G, B), with the thesis' four bands.

use serde::Serialize;

/// The thesis' verdict bands for an NMSE value. Serialized as its [`Band::label`], the words
/// the printed table uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Band {
    /// NMSE ≤ 0.0001: the images look identical.
    Identical,
    /// (0.0001, 0.00025]: small differences.
    Small,
    /// (0.00025, 0.001]: noticeably different.
    Noticeable,
    /// > 0.001: entirely different.
    Different,
}

impl Band {
    pub fn of(nmse: f64) -> Band {
        if nmse <= 0.0001 {
            Band::Identical
        } else if nmse <= 0.00025 {
            Band::Small
        } else if nmse <= 0.001 {
            Band::Noticeable
        } else {
            Band::Different
        }
    }
    pub fn label(self) -> &'static str {
        match self {
            Band::Identical => "identical",
            Band::Small => "small differences",
            Band::Noticeable => "noticeably different",
            Band::Different => "entirely different",
        }
    }
}

impl Serialize for Band {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.label())
    }
}

/// NMSE of `test` against `reference` (same length). An all-black reference gives `NaN` unless
/// the test image is also all black (then 0).
pub fn nmse(reference: &[[u8; 3]], test: &[[u8; 3]]) -> f64 {
    assert_eq!(
        reference.len(),
        test.len(),
        "NMSE of images of different sizes"
    );
    let (mut num, mut den) = (0u64, 0u64);
    for (r, t) in reference.iter().zip(test) {
        for c in 0..3 {
            let d = r[c] as i64 - t[c] as i64;
            num += (d * d) as u64;
            den += r[c] as u64 * r[c] as u64;
        }
    }
    match (num, den) {
        (0, _) => 0.0,
        (_, 0) => f64::NAN,
        _ => num as f64 / den as f64,
    }
}

/// Largest per-channel absolute difference.
pub fn max_abs_diff(reference: &[[u8; 3]], test: &[[u8; 3]]) -> u8 {
    reference
        .iter()
        .zip(test)
        .flat_map(|(r, t)| (0..3).map(move |c| r[c].abs_diff(t[c])))
        .max()
        .unwrap_or(0)
}

/// Heat map of the per-pixel error: black where equal, then blue → green → yellow → red as the
/// largest channel difference grows to `full_scale` (and beyond, saturated red).
pub fn diff_heatmap(reference: &[[u8; 3]], test: &[[u8; 3]], full_scale: u8) -> Vec<[u8; 3]> {
    let full = full_scale.max(1) as f64;
    reference
        .iter()
        .zip(test)
        .map(|(r, t)| {
            let d = (0..3).map(|c| r[c].abs_diff(t[c])).max().unwrap_or(0);
            if d == 0 {
                return [0, 0, 0];
            }
            heat((d as f64 / full).min(1.0))
        })
        .collect()
}

/// Colour ramp for u in (0, 1]: dark blue → cyan → green → yellow → red.
fn heat(u: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [0.0, 0.0, 160.0],
        [0.0, 200.0, 255.0],
        [0.0, 220.0, 0.0],
        [255.0, 255.0, 0.0],
        [255.0, 0.0, 0.0],
    ];
    let x = u * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let mut out = [0u8; 3];
    for c in 0..3 {
        out[c] = (STOPS[i][c] + (STOPS[i + 1][c] - STOPS[i][c]) * f).round() as u8;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nmse_by_hand() {
        // reference energy 3·100² + 3·200² = 150 000; error (10² + 0 + 0) + (0 + 20² + 0) = 500
        let r = [[100, 100, 100], [200, 200, 200]];
        let t = [[110, 100, 100], [200, 180, 200]];
        assert!((nmse(&r, &t) - 500.0 / 150_000.0).abs() < 1e-15);
        assert_eq!(nmse(&r, &r), 0.0);
    }

    /// Coloured pixels, so that a mix-up of channels or of the two images changes the value.
    #[test]
    fn nmse_by_hand_on_coloured_pixels() {
        let r = [[200, 100, 50], [10, 40, 160]];
        let t = [[190, 103, 50], [10, 40, 168]];
        // error: (200−190)² + (100−103)² + (50−50)² + (10−10)² + (40−40)² + (160−168)²
        //      = 100 + 9 + 0 + 0 + 0 + 64 = 173
        // reference energy: 200² + 100² + 50² + 10² + 40² + 160²
        //      = 40 000 + 10 000 + 2 500 + 100 + 1 600 + 25 600 = 79 800
        // NMSE = 173/79 800 (both sums exact in u64, one rounding in the division).
        assert_eq!(nmse(&r, &t), 173.0 / 79_800.0);
        // Against the test image's energy instead: 190² + 103² + 50² + 10² + 40² + 168²
        //      = 36 100 + 10 609 + 2 500 + 100 + 1 600 + 28 224 = 79 133.
        assert_eq!(nmse(&t, &r), 173.0 / 79_133.0);
        // Channel c compared with channel c + 1 would give, for the first pixel alone,
        // (200−103)² + (100−50)² + (50−190)² = 9 409 + 2 500 + 19 600 = 31 509 > 173.
        assert_eq!(max_abs_diff(&r, &t), 10);
    }

    #[test]
    fn bands_at_their_edges() {
        assert_eq!(Band::of(0.0001), Band::Identical);
        assert_eq!(Band::of(0.000_100_1), Band::Small);
        assert_eq!(Band::of(0.00025), Band::Small);
        assert_eq!(Band::of(0.000_250_1), Band::Noticeable);
        assert_eq!(Band::of(0.001), Band::Noticeable);
        assert_eq!(Band::of(0.0011), Band::Different);
    }

    #[test]
    fn heatmap_black_only_where_equal() {
        let r = [[10, 10, 10], [10, 10, 10], [10, 10, 10]];
        let t = [[10, 10, 10], [11, 10, 10], [200, 10, 10]];
        let h = diff_heatmap(&r, &t, 16);
        assert_eq!(h[0], [0, 0, 0]);
        assert_ne!(h[1], [0, 0, 0]);
        assert_eq!(h[2], [255, 0, 0]);
    }
}
