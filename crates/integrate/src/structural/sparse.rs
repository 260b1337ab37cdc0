//! Sparse (compressed-row) copies of the constant structural matrices, so that the products
//! of a step cost O(nnz) instead of O(n²): a coupled vehicle–bridge model has diagonal modal
//! blocks and small vehicle blocks, a few entries per row out of n = 100–500.
//!
//! The storage is faer's [`SparseRowMat`]; the product is a plain row loop (no allocation,
//! no dispatch, which matters at these sizes).

use faer::MatRef;
use faer::sparse::{SparseRowMat, SparseRowMatRef, Triplet};

/// A compressed-row matrix (faer's `SparseRowMat` with `usize` indices).
pub type SparseMatrix = SparseRowMat<usize, f64>;

/// The non-zero entries of a dense matrix as a compressed-row matrix (exact zeros dropped;
/// the products then equal the dense ones up to the order of summation).
pub fn sparse_from_dense(a: MatRef<'_, f64>) -> SparseMatrix {
    let mut entries = Vec::new();
    for i in 0..a.nrows() {
        for j in 0..a.ncols() {
            let v = a[(i, j)];
            if v != 0.0 {
                entries.push(Triplet::new(i, j, v));
            }
        }
    }
    // Indices are in range and unique by construction, so creation cannot fail.
    SparseRowMat::try_new_from_triplets(a.nrows(), a.ncols(), &entries)
        .expect("dense entries give valid sparse indices")
}

/// `out += s · A x` for a compressed-row `A` (`x` of length ncols, `out` of length nrows).
pub fn sparse_mul_add(a: SparseRowMatRef<'_, usize, f64>, s: f64, x: &[f64], out: &mut [f64]) {
    let symbolic = a.symbolic();
    let (row_ptr, col_idx, val) = (symbolic.row_ptr(), symbolic.col_idx(), a.val());
    for (i, o) in out.iter_mut().enumerate() {
        let (start, end) = (row_ptr[i], row_ptr[i + 1]);
        let ax: f64 = col_idx[start..end]
            .iter()
            .zip(&val[start..end])
            .map(|(&j, v)| v * x[j])
            .sum();
        *o += s * ax;
    }
}

/// `out = A x` for a compressed-row `A`.
pub fn sparse_mul(a: SparseRowMatRef<'_, usize, f64>, x: &[f64], out: &mut [f64]) {
    out.fill(0.0);
    sparse_mul_add(a, 1.0, x, out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// The sparse product equals the dense one (the oracle) on a matrix with a dense block,
    /// a diagonal and empty rows.
    #[test]
    fn sparse_product_equals_dense_product() {
        let n = 7;
        let a = Mat::from_fn(n, n, |i, j| {
            if (i < 3 && j < 3) || i == j && i != 5 {
                1.0 + (3 * i + 5 * j) as f64 * 0.37
            } else {
                0.0
            }
        });
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 1.3).sin()).collect();
        let sparse = sparse_from_dense(a.as_ref());
        assert_eq!(sparse.compute_nnz(), 9 + 3);
        let mut y = vec![0.5; n];
        sparse_mul_add(sparse.as_ref(), -2.0, &x, &mut y);
        for i in 0..n {
            let dense: f64 = (0..n).map(|j| a[(i, j)] * x[j]).sum();
            assert!((y[i] - (0.5 - 2.0 * dense)).abs() <= 1e-14 * (1.0 + dense.abs()));
        }
    }
}
