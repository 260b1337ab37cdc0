//! Symmetric sparse matrices assembled from entries, their combinations and the sparse
//! Cholesky factorisation of faer (fill-reducing ordering, symbolic analysis once).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    LltRef, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, MatMut, Par, Side};

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

    /// A compressed-row copy (allocation-free products in a time loop).
    pub(crate) fn to_rows(&self) -> integrate::structural::sparse::SparseMatrix {
        let t: Vec<Triplet<usize, usize, f64>> = self
            .raw
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        // Indices are in range and merged by construction.
        faer::sparse::SparseRowMat::try_new_from_triplets(self.n, self.n, &t)
            .expect("merged entries are valid")
    }

    /// y += s A x.
    #[cfg(test)]
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

/// A sparse symmetric positive-definite matrix factorised once as LLᵀ (faer's simplicial or
/// supernodal sparse Cholesky with an AMD ordering); each solve is two triangular sweeps in a
/// workspace allocated once (no allocation per solve).
pub struct SparseCholesky {
    n: usize,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    work: MemBuffer,
}

impl std::fmt::Debug for SparseCholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseCholesky")
            .field("n", &self.n)
            .field("factor_entries", &self.values.len())
            .finish()
    }
}

impl SparseCholesky {
    /// Factorise Σ c_k A_k; `what` names the matrix in the error.
    pub(crate) fn factorise(
        n: usize,
        parts: &[(f64, &SymmetricEntries)],
        what: &'static str,
    ) -> Result<Self, BeamError> {
        let fail = |detail: String| BeamError::Factorisation {
            matrix: what,
            detail,
        };
        let entries = combine(parts);
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &entries)
            .map_err(|e| fail(format!("{e:?}")))?;
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(|e| fail(format!("{e:?}")))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let mut scratch = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
        )
        .map_err(|e| fail(format!("{e:?}")))?;
        symbolic
            .factorize_numeric_llt::<f64>(
                &mut values,
                a.as_ref(),
                Side::Lower,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut scratch),
                Default::default(),
            )
            .map_err(|e| fail(format!("not positive definite ({e:?})")))?;
        let work = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
            .map_err(|e| fail(format!("{e:?}")))?;
        Ok(Self {
            n,
            symbolic,
            values,
            work,
        })
    }

    /// Dimension.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Number of stored entries of the factor L.
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }

    /// Solve A x = r in place (`r` has length n).
    pub fn solve_in_place(&mut self, r: &mut [f64]) {
        let n = self.n;
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(r, n, 1),
            Par::Seq,
            MemStack::new(&mut self.work),
        );
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
        let mut f = SparseCholesky::factorise(n, &[(1.0, &a)], "test").unwrap();
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
