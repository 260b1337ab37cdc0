//! Symmetric sparse matrices assembled from entries, their combinations and the sparse
//! Cholesky factorisation of faer (fill-reducing ordering, symbolic analysis once).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
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

/// A sparse symmetric positive-definite matrix factorised once as PᵀLLᵀP (faer's simplicial
/// sparse Cholesky with an AMD ordering P). Besides the full solve it offers the two triangular
/// halves: with y = L⁻¹P b and z = L⁻¹P r, bᵀA⁻¹r = yᵀz and bᵀA⁻¹b = yᵀy, and A⁻¹(r + F b)
/// = PᵀL⁻ᵀ(z + F y). With the AMD ordering L⁻¹Pb of a track fills in from the contact's
/// position to the end of the ordering, so this split costs about as much as a second solve
/// (measured in `bench beam`); with a nested-dissection ordering
/// ([`Self::factorise_entries`]) it is non-zero only on the elimination-tree paths from b's
/// entries, which [`Self::forward_sparse_reach`] sweeps alone. No allocation per solve.
pub struct SparseCholesky {
    n: usize,
    /// Forward permutation: (P r)\[i\] = r\[perm\[i\]\]; `None` = identity.
    perm: Option<Vec<usize>>,
    /// Inverse permutation (position of DOF j in the permuted order).
    inverse: Vec<usize>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    /// 1 / L\[j, j\] (a product instead of a division on the sweeps' critical path).
    inv_diag: Vec<f64>,
    /// Elimination tree: the parent of column j is the row of its first sub-diagonal entry
    /// (`usize::MAX` for a root).
    parent: Vec<usize>,
    /// The strictly lower part of L by rows (columns increasing): `row_cols[row_ptr[i]..]`,
    /// `row_values[..]`, for the full forward sweep in gather form.
    row_ptr: Vec<usize>,
    row_cols: Vec<usize>,
    row_values: Vec<f64>,
    work: Vec<f64>,
    /// faer's symbolic factor and solve workspace (the full solve).
    symbolic: SymbolicCholesky<usize>,
    stack: MemBuffer,
}

/// The columns reached by a sparse forward sweep ([`SparseCholesky::forward_sparse_reach`]):
/// the non-zero pattern of L⁻¹Pb, in increasing order, and the marks of the tree walk.
#[derive(Debug, Clone)]
pub struct SparseReach {
    nodes: Vec<usize>,
    mark: Vec<u32>,
    stamp: u32,
}

impl SparseReach {
    /// The columns (permuted order) where the last sweep's result may be non-zero, increasing.
    pub fn nodes(&self) -> &[usize] {
        &self.nodes
    }
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
        Self::factorise_with(n, combine(parts), None, what)
    }

    /// Factorise the symmetric positive-definite n × n matrix given by `entries` (row, column,
    /// value; both triangles, duplicates summed), with the fill-reducing ordering `ordering`
    /// (`ordering[i]` = the DOF eliminated i-th; a permutation of 0..n) or AMD when `None`.
    /// `what` names the matrix in the error. Used by couplings that add their own DOFs to a
    /// track (`sim::vehicle_bridge::track`).
    pub fn factorise_entries(
        n: usize,
        entries: &[(usize, usize, f64)],
        ordering: Option<&[usize]>,
        what: &'static str,
    ) -> Result<Self, BeamError> {
        let mut all = SymmetricEntries::new(n);
        for &(i, j, v) in entries {
            if i >= n || j >= n || !v.is_finite() {
                return Err(BeamError::Factorisation {
                    matrix: what,
                    detail: format!(
                        "entry ({i}, {j}) = {v} outside the {n} x {n} matrix or not finite"
                    ),
                });
            }
            all.raw.push((i, j, v));
        }
        all.compress();
        let triplets = all
            .raw
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        Self::factorise_with(n, triplets, ordering, what)
    }

    fn factorise_with(
        n: usize,
        entries: Vec<Triplet<usize, usize, f64>>,
        ordering: Option<&[usize]>,
        what: &'static str,
    ) -> Result<Self, BeamError> {
        let fail = |detail: String| BeamError::Factorisation {
            matrix: what,
            detail,
        };
        let inverse_order: Vec<usize>;
        let order = match ordering {
            Some(fwd) => {
                if fwd.len() != n {
                    return Err(fail(format!(
                        "ordering of length {} (expected {n})",
                        fwd.len()
                    )));
                }
                let mut inv = vec![usize::MAX; n];
                for (i, &p) in fwd.iter().enumerate() {
                    if p >= n || inv[p] != usize::MAX {
                        return Err(fail("the ordering is not a permutation".into()));
                    }
                    inv[p] = i;
                }
                inverse_order = inv;
                SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(fwd, &inverse_order, n))
            }
            None => SymmetricOrdering::Amd,
        };
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &entries)
            .map_err(|e| fail(format!("{e:?}")))?;
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SIMPLICIAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(a.symbolic(), Side::Lower, order, params)
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
        let SymbolicCholeskyRaw::Simplicial(simplicial) = symbolic.raw() else {
            return Err(fail("the simplicial factorisation was not selected".into()));
        };
        let col_ptr: Vec<usize> = simplicial.col_ptr().to_vec();
        let row_idx: Vec<usize> = simplicial.row_idx().to_vec();
        // Each column of L starts with its diagonal entry (rows sorted, lower triangle).
        for (j, &start) in col_ptr.iter().take(n).enumerate() {
            if row_idx.get(start) != Some(&j) {
                return Err(fail(format!(
                    "column {j} of L does not start on the diagonal"
                )));
            }
        }
        let perm: Option<Vec<usize>> = symbolic.perm().map(|p| p.arrays().0.to_vec());
        let stack = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
            .map_err(|e| fail(format!("{e:?}")))?;
        let mut inverse = vec![0; n];
        for i in 0..n {
            inverse[perm.as_ref().map_or(i, |p| p[i])] = i;
        }
        let inv_diag = (0..n).map(|j| 1.0 / values[col_ptr[j]]).collect();
        let parent = (0..n)
            .map(|j| {
                if col_ptr[j + 1] > col_ptr[j] + 1 {
                    row_idx[col_ptr[j] + 1]
                } else {
                    usize::MAX
                }
            })
            .collect();
        // L by rows: counting sort of the strictly lower entries (columns visited in order, so
        // each row's columns come out increasing).
        let mut row_ptr = vec![0usize; n + 1];
        for j in 0..n {
            for &i in &row_idx[col_ptr[j] + 1..col_ptr[j + 1]] {
                row_ptr[i + 1] += 1;
            }
        }
        for i in 0..n {
            row_ptr[i + 1] += row_ptr[i];
        }
        let mut fill = row_ptr.clone();
        let mut row_cols = vec![0usize; row_ptr[n]];
        let mut row_values = vec![0.0; row_ptr[n]];
        for j in 0..n {
            for k in col_ptr[j] + 1..col_ptr[j + 1] {
                let i = row_idx[k];
                row_cols[fill[i]] = j;
                row_values[fill[i]] = values[k];
                fill[i] += 1;
            }
        }
        Ok(Self {
            n,
            perm,
            inverse,
            col_ptr,
            row_idx,
            values,
            inv_diag,
            parent,
            row_ptr,
            row_cols,
            row_values,
            work: vec![0.0; n],
            symbolic,
            stack,
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

    /// L⁻¹ applied in place to a vector already in the permuted order, from column `start`
    /// (the entries before `start` must be zero).
    fn lower_solve(&self, x: &mut [f64], start: usize) {
        for j in start..self.n {
            self.eliminate_column(x, j);
        }
    }

    /// Column j of the forward sweep: x\[j\] ← x\[j\] / L\[j, j\], then x\[i\] −= L\[i, j\] x\[j\]
    /// below the diagonal (skipped when x\[j\] = 0).
    #[inline]
    fn eliminate_column(&self, x: &mut [f64], j: usize) {
        let (a, b) = (self.col_ptr[j], self.col_ptr[j + 1]);
        let xj = x[j] * self.inv_diag[j];
        x[j] = xj;
        if xj != 0.0 {
            for (&i, &l) in self.row_idx[a + 1..b].iter().zip(&self.values[a + 1..b]) {
                x[i] -= l * xj;
            }
        }
    }

    /// r ← L⁻¹ P r (the forward half of a solve; the result is in the permuted order), row
    /// by row: x\[i\] = (b\[i\] − Σ_{j<i} L\[i, j\] x\[j\]) / L\[i, i\] with j increasing, the
    /// subtractions of the column sweep in the same order (one accumulator per row, no
    /// scattered stores).
    pub fn forward(&mut self, r: &mut [f64]) {
        if let Some(p) = &self.perm {
            for (w, &pi) in self.work.iter_mut().zip(p) {
                *w = r[pi];
            }
            r.copy_from_slice(&self.work);
        }
        for (i, (ends, inv)) in self.row_ptr.windows(2).zip(&self.inv_diag).enumerate() {
            let (a, b) = (ends[0], ends[1]);
            let mut acc = r[i];
            for (&j, &l) in self.row_cols[a..b].iter().zip(&self.row_values[a..b]) {
                acc -= l * r[j];
            }
            r[i] = acc * inv;
        }
    }

    /// out ← L⁻¹ P b for a sparse b given as (DOF, value) pairs (`out` has length n); the sweep
    /// starts at the first non-zero of P b.
    pub fn forward_sparse(&self, b: &[(usize, f64)], out: &mut [f64]) {
        out.fill(0.0);
        let mut start = self.n;
        for &(i, v) in b {
            let k = self.inverse[i];
            out[k] += v;
            start = start.min(k);
        }
        self.lower_solve(out, start);
    }

    /// A work space for [`Self::forward_sparse_reach`] (sized for this factor).
    pub fn new_reach(&self) -> SparseReach {
        SparseReach {
            nodes: Vec::new(),
            mark: vec![0; self.n],
            stamp: 0,
        }
    }

    /// [`Self::forward_sparse`] restricted to the reach of b: out ← L⁻¹ P b, sweeping only the
    /// columns on the paths of the elimination tree from the non-zeros of P b to the root (the
    /// only entries of L⁻¹Pb that can be non-zero; Gilbert & Peierls), which `reach` lists
    /// afterwards in increasing order. `out` must be zero except at the entries `reach` listed
    /// on entry (the previous call's result with the same `out`): those are cleared first. The
    /// same operations in the same order as [`Self::forward_sparse`] on those columns (the
    /// others hold exact zeros there), so the result is identical.
    pub fn forward_sparse_reach(
        &self,
        b: &[(usize, f64)],
        out: &mut [f64],
        reach: &mut SparseReach,
    ) {
        for &i in &reach.nodes {
            out[i] = 0.0;
        }
        reach.nodes.clear();
        reach.stamp = reach.stamp.wrapping_add(1);
        if reach.stamp == 0 {
            reach.mark.fill(0);
            reach.stamp = 1;
        }
        for &(i, v) in b {
            let mut j = self.inverse[i];
            out[j] += v;
            while j != usize::MAX && reach.mark[j] != reach.stamp {
                reach.mark[j] = reach.stamp;
                reach.nodes.push(j);
                j = self.parent[j];
            }
        }
        reach.nodes.sort_unstable();
        for &j in &reach.nodes {
            self.eliminate_column(out, j);
        }
    }

    /// z ← Pᵀ L⁻ᵀ z (the backward half of a solve).
    pub fn backward(&mut self, z: &mut [f64]) {
        for (j, (ends, inv)) in self
            .col_ptr
            .windows(2)
            .zip(&self.inv_diag)
            .enumerate()
            .rev()
        {
            let (a, b) = (ends[0] + 1, ends[1]);
            let mut s = z[j];
            for (&i, &l) in self.row_idx[a..b].iter().zip(&self.values[a..b]) {
                s -= l * z[i];
            }
            z[j] = s * inv;
        }
        if let Some(p) = &self.perm {
            for (i, &pi) in p.iter().enumerate() {
                self.work[pi] = z[i];
            }
            z.copy_from_slice(&self.work);
        }
    }

    /// Solve A x = r in place (`r` has length n; faer's simplicial solve, equal to
    /// [`Self::forward`] then [`Self::backward`] up to rounding).
    pub fn solve_in_place(&mut self, r: &mut [f64]) {
        let n = self.n;
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(r, n, 1),
            Par::Seq,
            MemStack::new(&mut self.stack),
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
        // The halves: bᵀA⁻¹r = (L⁻¹Pb)ᵀ(L⁻¹Pr) with a sparse b, against the full solve.
        let b = [(7usize, 1.5), (30usize, -0.5)];
        let mut y = vec![0.0; n];
        f.forward_sparse(&b, &mut y);
        let mut z = r.clone();
        f.forward(&mut z);
        let split: f64 = y.iter().zip(&z).map(|(a, b)| a * b).sum();
        let full = 1.5 * x[7] - 0.5 * x[30];
        assert!(
            (split - full).abs() < 1e-12 * full.abs().max(1.0),
            "{split} {full}"
        );
        // The reach-restricted sweep: identical to the full one, twice in a row on one vector.
        let mut reach = f.new_reach();
        let mut y2 = vec![0.0; n];
        for b in [
            [(30usize, 2.0), (12usize, -1.0)],
            [(7usize, 1.5), (30usize, -0.5)],
        ] {
            f.forward_sparse(&b, &mut y);
            f.forward_sparse_reach(&b, &mut y2, &mut reach);
            assert_eq!(y, y2);
            assert!(reach.nodes().windows(2).all(|w| w[0] < w[1]));
            assert!(reach.nodes().len() < n);
        }
        let mut fb = r.clone();
        f.forward(&mut fb);
        f.backward(&mut fb);
        for i in 0..n {
            assert!((fb[i] - x[i]).abs() < 1e-12 * x[i].abs().max(1.0));
        }
        let mut neg = SymmetricEntries::new(1);
        neg.add(0, 0, -1.0);
        neg.compress();
        assert!(SparseCholesky::factorise(1, &[(1.0, &neg)], "neg").is_err());
    }
}
