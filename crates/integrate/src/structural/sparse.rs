//! Sparse (compressed-row) copies of the constant structural matrices, so that the products
//! of a step cost O(nnz) instead of O(n²): a coupled vehicle–bridge model has diagonal modal
//! blocks and small vehicle blocks, a few entries per row out of n = 100–500.
//!
//! The storage is faer's [`SparseRowMat`]; the product is a plain row loop (no allocation,
//! no dispatch, which matters at these sizes).

use std::ops::Range;

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
    let n = out.len();
    sparse_mul_add_rows(a, s, x, out, std::iter::once(0..n));
}

/// `out_i += s · (A x)_i` for the rows `i` in `rows` only (the other entries of `out` are left
/// as they are): the same operations per row as [`sparse_mul_add`].
pub fn sparse_mul_add_rows(
    a: SparseRowMatRef<'_, usize, f64>,
    s: f64,
    x: &[f64],
    out: &mut [f64],
    rows: impl Iterator<Item = Range<usize>>,
) {
    for_rows(a, out, rows, |cols, vals, o| {
        *o += s * row_dot(cols, vals, x)
    });
}

/// `out_i += s1 · (A x1)_i`, then `out_i += s2 · (A x2)_i`, for the rows `i` in `rows` only:
/// the operations of [`sparse_mul_add_rows`] with (s1, x1) followed by the same with (s2, x2),
/// bit for bit, in one pass over the rows of `A`.
pub fn sparse_mul_add2_rows(
    a: SparseRowMatRef<'_, usize, f64>,
    (s1, x1): (f64, &[f64]),
    (s2, x2): (f64, &[f64]),
    out: &mut [f64],
    rows: impl Iterator<Item = Range<usize>>,
) {
    for_rows(a, out, rows, |cols, vals, o| {
        let (ax1, ax2) = (row_dot(cols, vals, x1), row_dot(cols, vals, x2));
        *o += s1 * ax1;
        *o += s2 * ax2;
    });
}

/// `f(columns, values, out_i)` for each row `i` of `a` in `rows`, with the row's column indices
/// and values.
#[inline(always)]
pub(crate) fn for_rows(
    a: SparseRowMatRef<'_, usize, f64>,
    out: &mut [f64],
    rows: impl Iterator<Item = Range<usize>>,
    mut f: impl FnMut(&[usize], &[f64], &mut f64),
) {
    let symbolic = a.symbolic();
    let (row_ptr, col_idx, val) = (symbolic.row_ptr(), symbolic.col_idx(), a.val());
    for range in rows {
        let start = range.start;
        for (i, o) in out[range].iter_mut().enumerate() {
            let (begin, end) = (row_ptr[start + i], row_ptr[start + i + 1]);
            f(&col_idx[begin..end], &val[begin..end], o);
        }
    }
}

/// One row's `Σ_j a_ij x_j`, summed in column order.
#[inline(always)]
pub(crate) fn row_dot(cols: &[usize], vals: &[f64], x: &[f64]) -> f64 {
    cols.iter().zip(vals).map(|(&j, v)| v * x[j]).sum()
}

/// The rows `0..n` outside the sorted, disjoint ranges `frozen`, as ranges in increasing order
/// (the rows a step evaluates; `StructuralStepper::freeze`).
pub fn rows_outside(n: usize, frozen: &[Range<usize>]) -> impl Iterator<Item = Range<usize>> + '_ {
    let mut start = 0;
    frozen
        .iter()
        .map(|f| (f.start, f.end))
        .chain(std::iter::once((n, n)))
        .filter_map(move |(f0, f1)| {
            let range = start..f0;
            start = f1;
            (!range.is_empty()).then_some(range)
        })
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
        // Restricted to the rows outside {1, 2} and {5}: those rows equal the full product
        // bit for bit, the others are untouched.
        let frozen = [1..3, 5..6];
        let rows: Vec<_> = rows_outside(n, &frozen).collect();
        assert_eq!(rows, vec![0..1, 3..5, 6..7]);
        let mut z = vec![0.5; n];
        sparse_mul_add_rows(sparse.as_ref(), -2.0, &x, &mut z, rows.into_iter());
        for i in 0..n {
            let expected = if frozen.iter().any(|f| f.contains(&i)) {
                0.5
            } else {
                y[i]
            };
            assert_eq!(z[i].to_bits(), expected.to_bits(), "row {i}");
        }
        // Two products in one pass: bit for bit the two products in turn.
        let x2: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut twice = vec![0.5; n];
        sparse_mul_add_rows(
            sparse.as_ref(),
            -2.0,
            &x,
            &mut twice,
            rows_outside(n, &frozen),
        );
        sparse_mul_add_rows(
            sparse.as_ref(),
            0.3,
            &x2,
            &mut twice,
            rows_outside(n, &frozen),
        );
        let mut once = vec![0.5; n];
        let rows = rows_outside(n, &frozen);
        sparse_mul_add2_rows(sparse.as_ref(), (-2.0, &x), (0.3, &x2), &mut once, rows);
        for i in 0..n {
            assert_eq!(once[i].to_bits(), twice[i].to_bits(), "row {i}");
        }
        let everything = [Range { start: 0, end: 4 }];
        assert_eq!(rows_outside(4, &everything).count(), 0);
        assert_eq!(rows_outside(4, &[]).collect::<Vec<_>>(), vec![0..4]);
    }
}
