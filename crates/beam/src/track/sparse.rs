//! Symmetric sparse matrices assembled from entries, their combinations and the sparse
//! Cholesky factorisation of faer (fill-reducing ordering, symbolic analysis once).

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{MatMut, Side};

use crate::error::BeamError;

/// A symmetric matrix as merged (row, column, value) entries of both triangles, sorted by
/// column then row, duplicates summed.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct SymmetricEntries {
    n: usize,
    raw: Vec<(usize, usize, f64)>,
}

impl SymmetricEntries {
    pub(crate) fn new(n: usize) -> Self {
        Self { n, raw: Vec::new() }
    }

    /// A\[i, j\] += v and A\[j, i\] += v (once on the diagonal).
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        if v == 0.0 {
            return;
        }
        self.raw.push((i, j, v));
        if i != j {
            self.raw.push((j, i, v));
        }
    }

    /// Sort by (column, row) and sum duplicates.
    pub(crate) fn compress(&mut self) {
        self.raw.sort_by_key(|&(i, j, _)| (j, i));
        let mut out: Vec<(usize, usize, f64)> = Vec::with_capacity(self.raw.len());
        for &(i, j, v) in &self.raw {
            match out.last_mut() {
                Some(last) if last.0 == i && last.1 == j => last.2 += v,
                _ => out.push((i, j, v)),
            }
        }
        self.raw = out;
    }

    pub(crate) fn entries(&self) -> &[(usize, usize, f64)] {
        &self.raw
    }

    /// y += s A x.
    pub(crate) fn mul_add(&self, s: f64, x: &[f64], y: &mut [f64]) {
        for &(i, j, v) in &self.raw {
            y[i] += s * v * x[j];
        }
    }

    /// A\[i, j\] (summing duplicates; for tests).
    #[cfg(test)]
    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        self.raw
            .iter()
            .filter(|e| e.0 == i && e.1 == j)
            .map(|e| e.2)
            .sum()
    }
}

/// The merged entries of Σ c_k A_k.
pub(crate) fn combine(parts: &[(f64, &SymmetricEntries)]) -> Vec<Triplet<usize, usize, f64>> {
    let mut all = SymmetricEntries::new(parts.first().map_or(0, |p| p.1.n));
    for &(c, a) in parts {
        if c != 0.0 {
            all.raw.extend(a.raw.iter().map(|&(i, j, v)| (i, j, c * v)));
        }
    }
    all.compress();
    all.raw
        .iter()
        .map(|&(i, j, v)| Triplet::new(i, j, v))
        .collect()
}

/// A sparse symmetric positive-definite matrix factorised once as LLᵀ (faer's supernodal or
/// simplicial sparse Cholesky with an AMD ordering); each solve is two triangular sweeps.
#[derive(Debug, Clone)]
pub struct SparseCholesky {
    n: usize,
    llt: Llt<usize, f64>,
}

impl SparseCholesky {
    /// Factorise Σ c_k A_k; `what` names the matrix in the error.
    pub(crate) fn factorise(
        n: usize,
        parts: &[(f64, &SymmetricEntries)],
        what: &'static str,
    ) -> Result<Self, BeamError> {
        let entries = combine(parts);
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &entries).map_err(|e| {
            BeamError::Factorisation {
                matrix: what,
                detail: format!("{e:?}"),
            }
        })?;
        let symbolic = SymbolicLlt::try_new(a.symbolic(), Side::Lower).map_err(|e| {
            BeamError::Factorisation {
                matrix: what,
                detail: format!("{e:?}"),
            }
        })?;
        let llt = Llt::try_new_with_symbolic(symbolic, a.as_ref(), Side::Lower).map_err(|e| {
            BeamError::Factorisation {
                matrix: what,
                detail: format!("not positive definite ({e:?})"),
            }
        })?;
        Ok(Self { n, llt })
    }

    /// Dimension.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Solve A x = r in place (`r` has length n).
    pub fn solve_in_place(&self, r: &mut [f64]) {
        let n = self.n;
        self.llt
            .solve_in_place(MatMut::from_column_major_slice_mut(r, n, 1));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Factorise a tridiagonal SPD matrix (the 1-D Laplacian plus 0.5 I) plus an arrow row, and
    /// check the residual of a solve against the entry-wise product (1e-12: well conditioned).
    #[test]
    fn cholesky_solves_arrow_matrix() {
        let n = 40;
        let mut a = SymmetricEntries::new(n);
        for i in 0..n - 1 {
            a.add(i, i, 2.5);
            if i + 1 < n - 1 {
                a.add(i, i + 1, -1.0);
            }
            a.add(i, n - 1, 0.1);
        }
        a.add(n - 1, n - 1, 10.0);
        a.compress();
        assert_eq!(a.get(3, 4), -1.0);
        let f = SparseCholesky::factorise(n, &[(1.0, &a)], "test").unwrap();
        let r: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = r.clone();
        f.solve_in_place(&mut x);
        let mut ax = vec![0.0; n];
        a.mul_add(1.0, &x, &mut ax);
        for i in 0..n {
            assert!((ax[i] - r[i]).abs() < 1e-12);
        }
        let mut neg = SymmetricEntries::new(1);
        neg.add(0, 0, -1.0);
        neg.compress();
        assert!(SparseCholesky::factorise(1, &[(1.0, &neg)], "neg").is_err());
    }
}
