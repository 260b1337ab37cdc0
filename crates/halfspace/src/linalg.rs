//! Small dense linear algebra shared by the solvers.

/// Dot product Σ aᵢ bᵢ.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Gaussian elimination with partial pivoting on a k × k system (k ≤ depth, tiny).
pub(crate) fn solve_dense(a: &mut [f64], b: &mut [f64], k: usize) -> Option<Vec<f64>> {
    for c in 0..k {
        let piv = (c..k).max_by(|&i, &j| a[i * k + c].abs().total_cmp(&a[j * k + c].abs()))?;
        if a[piv * k + c] == 0.0 {
            return None;
        }
        for j in 0..k {
            a.swap(c * k + j, piv * k + j);
        }
        b.swap(c, piv);
        for r in c + 1..k {
            let f = a[r * k + c] / a[c * k + c];
            for j in c..k {
                a[r * k + j] -= f * a[c * k + j];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; k];
    for c in (0..k).rev() {
        let mut v = b[c];
        for j in c + 1..k {
            v -= a[c * k + j] * x[j];
        }
        x[c] = v / a[c * k + c];
    }
    Some(x)
}
