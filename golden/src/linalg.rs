//! A small dense linear solver for the set-up software (the quadric's six nodes, the Remez
//! exchange of the fitted normalizer segments).

/// Solve the N×N system `m·x = r` by Gaussian elimination with partial pivoting; `None` when
/// a pivot is below 10⁻¹² (singular for these uses).
pub fn solve<const N: usize>(mut m: [[f64; N]; N], mut r: [f64; N]) -> Option<[f64; N]> {
    for col in 0..N {
        let piv = (col..N).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
        if m[piv][col].abs() < 1e-12 {
            return None;
        }
        m.swap(col, piv);
        r.swap(col, piv);
        for row in col + 1..N {
            let f = m[row][col] / m[col][col];
            let pivot_row = m[col];
            for (dst, src) in m[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *dst -= f * src;
            }
            r[row] -= f * r[col];
        }
    }
    let mut x = [0.0; N];
    for row in (0..N).rev() {
        let s: f64 = (row + 1..N).map(|k| m[row][k] * x[k]).sum();
        x[row] = (r[row] - s) / m[row][row];
    }
    Some(x)
}
