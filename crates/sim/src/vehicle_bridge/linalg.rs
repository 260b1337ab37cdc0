//! Linear algebra of the coupled step (references.md §D4.2).
//!
//! The contact-free step matrix `A = c_M M + c_C C + c_K K` of the bridge modes and the vehicle
//! is block diagonal: one 1×1 block per bridge mode (mass-normalised modal equations) and one
//! 1×1 or 2×2 block per wheel (wheel mass, suspension spring–damper, body mass), so `A⁻¹v`
//! costs O(n). The contact adds a low-rank term `U Vᵀ` (one column per wheel in contact):
//!
//! * Sherman–Morrison (one column): `(A + u vᵀ)⁻¹ r = A⁻¹r − A⁻¹u (vᵀA⁻¹r)/(1 + vᵀA⁻¹u)`;
//! * Woodbury (k columns): `(A + U Vᵀ)⁻¹ r = A⁻¹r − A⁻¹U (I_k + VᵀA⁻¹U)⁻¹ VᵀA⁻¹r`, with the
//!   k × k capacitance matrix `I_k + VᵀA⁻¹U` (all wheels couple through the bridge modes).
//!
//! [`contact_update`] applies both in a force form that also admits rigid contacts;
//! [`dense_contact_update`] (an LU factorisation with partial pivoting of the bordered system)
//! is the reference. The dense solves (the k × k capacitance matrix, the bordered system) use
//! `integrate`'s [`DenseLu`] (faer's partial-pivoting LU in preallocated storage). A singular
//! block or matrix is an error ([`Singular`]), never skipped.

use integrate::DenseLu;

/// A singular or non-finite matrix met by a solve of the coupled step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("singular or non-finite {what}")]
pub struct Singular {
    /// Which matrix: `step-matrix block`, `capacitance matrix`, `bordered matrix`.
    pub what: &'static str,
}

/// A block-diagonal matrix (up to a permutation) with 1×1 and 2×2 blocks and dense blocks
/// of a multibody vehicle (any index set, at most [`MAX_DENSE_BLOCK`] indices), stored with
/// the block inverses.
#[derive(Debug, Clone, Default)]
pub struct BlockDiagonal {
    n: usize,
    /// (first index, second index or usize::MAX, inverse entries [a, b, c, d] row-major).
    blocks: Vec<(usize, usize, [f64; 4])>,
    /// The matrix entries (same layout), kept for products and dense assembly.
    entries: Vec<[f64; 4]>,
    /// Dense blocks: indices, entries and inverse (row-major m × m).
    dense: Vec<DenseBlock>,
    /// The block of each index: `Some(Small(i))` (1×1/2×2 block i) or `Some(Dense(i))`.
    owner: Vec<Option<Owner>>,
}

/// Which block an index belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Owner {
    Small(usize),
    Dense(usize),
}

/// Largest dense block (a bogie vehicle has 10 DOFs).
pub const MAX_DENSE_BLOCK: usize = 16;

#[derive(Debug, Clone, Default)]
struct DenseBlock {
    indices: Vec<usize>,
    entries: Vec<f64>,
    inverse: Vec<f64>,
}

/// Which matrix of a dense block [`BlockDiagonal::dense_apply`] applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum DensePart {
    Inverse,
    AbsInverse,
}

/// Marker for a 1×1 block.
const NONE: usize = usize::MAX;

const SINGULAR_BLOCK: Singular = Singular {
    what: "step-matrix block",
};

impl BlockDiagonal {
    /// An empty matrix of dimension `n` (every index must then be covered by a block).
    pub fn new(n: usize) -> Self {
        Self {
            n,
            blocks: Vec::with_capacity(n),
            entries: Vec::with_capacity(n),
            dense: Vec::new(),
            owner: vec![None; n],
        }
    }

    /// Removes all blocks (keeps the capacity).
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.entries.clear();
        self.dense.clear();
        self.owner.clear();
        self.owner.resize(self.n, None);
    }

    /// Adds the dense block with row-major `entries` on `indices` (m ≤ [`MAX_DENSE_BLOCK`]);
    /// its inverse by Gauss–Jordan elimination with partial pivoting. An error if it is
    /// singular or not finite (the block is then not added).
    pub fn push_dense(&mut self, indices: &[usize], entries: &[f64]) -> Result<(), Singular> {
        let m = indices.len();
        if m == 0 || m > MAX_DENSE_BLOCK || entries.len() != m * m {
            return Err(SINGULAR_BLOCK);
        }
        let mut a = entries.to_vec();
        let mut inv = vec![0.0; m * m];
        for i in 0..m {
            inv[i * m + i] = 1.0;
        }
        let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        if !(scale.is_finite() && scale > 0.0) {
            return Err(SINGULAR_BLOCK);
        }
        for col in 0..m {
            let pivot = (col..m)
                .max_by(|&r, &q| a[r * m + col].abs().total_cmp(&a[q * m + col].abs()))
                .unwrap_or(col);
            if a[pivot * m + col].abs() <= 1e-14 * scale {
                return Err(SINGULAR_BLOCK);
            }
            if pivot != col {
                for j in 0..m {
                    a.swap(pivot * m + j, col * m + j);
                    inv.swap(pivot * m + j, col * m + j);
                }
            }
            let p = a[col * m + col];
            for j in 0..m {
                a[col * m + j] /= p;
                inv[col * m + j] /= p;
            }
            for r in 0..m {
                if r != col {
                    let f = a[r * m + col];
                    if f != 0.0 {
                        for j in 0..m {
                            a[r * m + j] -= f * a[col * m + j];
                            inv[r * m + j] -= f * inv[col * m + j];
                        }
                    }
                }
            }
        }
        if inv.iter().any(|v| !v.is_finite()) {
            return Err(SINGULAR_BLOCK);
        }
        for &i in indices {
            self.owner[i] = Some(Owner::Dense(self.dense.len()));
        }
        self.dense.push(DenseBlock {
            indices: indices.to_vec(),
            entries: entries.to_vec(),
            inverse: inv,
        });
        Ok(())
    }

    /// `x ← B x` over the dense blocks (B = the inverses or their absolute values), with a
    /// stack buffer (no allocation).
    fn dense_apply(&self, x: &mut [f64], which: DensePart) {
        let mut buf = [0.0; MAX_DENSE_BLOCK];
        for b in &self.dense {
            let m = b.indices.len();
            let mat = &b.inverse;
            for (r, out) in buf.iter_mut().enumerate().take(m) {
                *out = (0..m)
                    .map(|c| {
                        let v = mat[r * m + c];
                        let v = if which == DensePart::AbsInverse {
                            v.abs()
                        } else {
                            v
                        };
                        v * x[b.indices[c]]
                    })
                    .sum();
            }
            for (r, &i) in b.indices.iter().enumerate() {
                x[i] = buf[r];
            }
        }
    }

    /// Dimension n.
    pub fn dimension(&self) -> usize {
        self.n
    }

    /// Adds the 1×1 block `a` at index `i`; an error if `a` is zero or not finite (the block
    /// is then not added).
    pub fn push1(&mut self, i: usize, a: f64) -> Result<(), Singular> {
        if a == 0.0 || !a.is_finite() {
            return Err(SINGULAR_BLOCK);
        }
        self.owner[i] = Some(Owner::Small(self.blocks.len()));
        self.blocks.push((i, NONE, [1.0 / a, 0.0, 0.0, 0.0]));
        self.entries.push([a, 0.0, 0.0, 0.0]);
        Ok(())
    }

    /// Adds the 2×2 block `[[a, b], [c, d]]` on indices (i, j); an error if it is singular or
    /// not finite (the block is then not added).
    pub fn push2(
        &mut self,
        i: usize,
        j: usize,
        a: f64,
        b: f64,
        c: f64,
        d: f64,
    ) -> Result<(), Singular> {
        let det = a * d - b * c;
        if det == 0.0 || !det.is_finite() {
            return Err(SINGULAR_BLOCK);
        }
        self.owner[i] = Some(Owner::Small(self.blocks.len()));
        self.owner[j] = Some(Owner::Small(self.blocks.len()));
        self.blocks
            .push((i, j, [d / det, -b / det, -c / det, a / det]));
        self.entries.push([a, b, c, d]);
        Ok(())
    }

    /// `x ← A⁻¹ x` in place for a sparse `x`: only the blocks that hold a non-zero of `x`
    /// are applied (the others map zeros to zeros), and `support` receives the indices of
    /// those blocks (where the result can be non-zero). Equal to [`Self::solve_in_place`].
    pub fn solve_sparse_in_place(&self, x: &mut [f64], support: &mut Vec<usize>) {
        support.clear();
        let mut buf = [0.0; MAX_DENSE_BLOCK];
        let mut last: Option<Owner> = None;
        for i in 0..x.len() {
            if x[i] == 0.0 {
                continue;
            }
            let Some(owner) = self.owner.get(i).copied().flatten() else {
                continue;
            };
            if last == Some(owner) {
                continue;
            }
            last = Some(owner);
            match owner {
                Owner::Small(b) => {
                    let (p, q, inv) = self.blocks[b];
                    if support.contains(&p) {
                        continue;
                    }
                    if q == NONE {
                        x[p] *= inv[0];
                        support.push(p);
                    } else {
                        let (xp, xq) = (x[p], x[q]);
                        x[p] = inv[0] * xp + inv[1] * xq;
                        x[q] = inv[2] * xp + inv[3] * xq;
                        support.extend([p, q]);
                    }
                }
                Owner::Dense(d) => {
                    let blk = &self.dense[d];
                    if support.contains(&blk.indices[0]) {
                        continue;
                    }
                    let m = blk.indices.len();
                    for (r, out) in buf.iter_mut().enumerate().take(m) {
                        let row = &blk.inverse[r * m..(r + 1) * m];
                        *out = row.iter().zip(&blk.indices).map(|(a, &j)| a * x[j]).sum();
                    }
                    for (r, &j) in blk.indices.iter().enumerate() {
                        x[j] = buf[r];
                    }
                    support.extend_from_slice(&blk.indices);
                }
            }
        }
    }

    /// `x ← A⁻¹ x` in place.
    pub fn solve_in_place(&self, x: &mut [f64]) {
        self.dense_apply(x, DensePart::Inverse);
        for &(i, j, inv) in &self.blocks {
            if j == NONE {
                x[i] *= inv[0];
            } else {
                let (xi, xj) = (x[i], x[j]);
                x[i] = inv[0] * xi + inv[1] * xj;
                x[j] = inv[2] * xi + inv[3] * xj;
            }
        }
    }

    /// `x ← |A⁻¹| x` in place, with the entrywise absolute value of each block's inverse (a
    /// bound on how an error vector of x's magnitudes propagates through a solve).
    pub fn solve_abs_in_place(&self, x: &mut [f64]) {
        self.dense_apply(x, DensePart::AbsInverse);
        for &(i, j, inv) in &self.blocks {
            if j == NONE {
                x[i] *= inv[0].abs();
            } else {
                let (xi, xj) = (x[i], x[j]);
                x[i] = inv[0].abs() * xi + inv[1].abs() * xj;
                x[j] = inv[2].abs() * xi + inv[3].abs() * xj;
            }
        }
    }

    /// `y = A x`.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        for b in &self.dense {
            let m = b.indices.len();
            for (r, &i) in b.indices.iter().enumerate() {
                y[i] = (0..m).map(|c| b.entries[r * m + c] * x[b.indices[c]]).sum();
            }
        }
        for (&(i, j, _), e) in self.blocks.iter().zip(&self.entries) {
            if j == NONE {
                y[i] = e[0] * x[i];
            } else {
                y[i] = e[0] * x[i] + e[1] * x[j];
                y[j] = e[2] * x[i] + e[3] * x[j];
            }
        }
    }

    /// Writes the entries of A into the upper-left n × n corner of `mat` (the rest untouched).
    pub fn write_into(&self, mat: &mut faer::MatMut<'_, f64>) {
        for b in &self.dense {
            let m = b.indices.len();
            for (r, &i) in b.indices.iter().enumerate() {
                for (c, &j) in b.indices.iter().enumerate() {
                    mat[(i, j)] = b.entries[r * m + c];
                }
            }
        }
        for (&(i, j, _), e) in self.blocks.iter().zip(&self.entries) {
            mat[(i, i)] = e[0];
            if j != NONE {
                mat[(i, j)] = e[1];
                mat[(j, i)] = e[2];
                mat[(j, j)] = e[3];
            }
        }
    }

    /// The dense matrix, row-major n × n.
    pub fn to_dense(&self) -> Vec<f64> {
        let n = self.n;
        let mut a = vec![0.0; n * n];
        for b in &self.dense {
            let m = b.indices.len();
            for (r, &i) in b.indices.iter().enumerate() {
                for (c, &j) in b.indices.iter().enumerate() {
                    a[i * n + j] = b.entries[r * m + c];
                }
            }
        }
        for (&(i, j, _), e) in self.blocks.iter().zip(&self.entries) {
            a[i * n + i] = e[0];
            if j != NONE {
                a[i * n + j] = e[1];
                a[j * n + i] = e[2];
                a[j * n + j] = e[3];
            }
        }
        a
    }
}

/// Work space of [`contact_update`] for up to `k_max` wheels: A⁻¹ĝ per wheel and one LU of
/// each capacitance-matrix size 2..=k_max (allocated once).
#[derive(Debug, Default)]
pub struct CapacitanceWork {
    ainv_g: Vec<Vec<f64>>,
    /// Where each A⁻¹ĝ can be non-zero.
    support: Vec<Vec<usize>>,
    /// `lu[k - 2]` factorises the k × k capacitance matrix.
    lu: Vec<DenseLu<f64>>,
}

impl CapacitanceWork {
    /// Work space for dimension n and up to `k_max` wheels.
    pub fn new(n: usize, k_max: usize) -> Self {
        Self {
            ainv_g: vec![vec![0.0; n]; k_max],
            support: vec![Vec::with_capacity(n); k_max],
            lu: (2..=k_max).map(DenseLu::new).collect(),
        }
    }
}

/// Work space of [`dense_contact_update`]: the LU of each bordered size n + k met so far
/// (allocated at the first use of a size) and the right-hand side.
#[derive(Debug, Default)]
pub struct DenseWork {
    lu: Vec<DenseLu<f64>>,
    rhs: Vec<f64>,
}

/// The LU storage for an `m × m` matrix among `lus` (added at the first use of a size).
fn lu_of_size(lus: &mut Vec<DenseLu<f64>>, m: usize) -> &mut DenseLu<f64> {
    let i = match lus.iter().position(|lu| lu.dim() == m) {
        Some(i) => i,
        None => {
            lus.push(DenseLu::new(m));
            lus.len() - 1
        }
    };
    &mut lus[i]
}

/// One linearised (quasi-)Newton update of the coupled step (references.md §D4.2), in the
/// capacitance form that also covers rigid contacts.
///
/// Unknowns: the state increment Δx and the force increments ΔF_c of the active wheels. The
/// generalized contact force of wheel c is `−F_c ĝ_c` with weight `s = 1 − α_f`, its approach
/// `δ_c = v_cᵀx + r_c`, and the linearised contact law `v_cᵀΔx = compliance_c ΔF_c − δ̃_c`
/// (compliance = 1/k_c; for a rigid contact compliance = 0 and δ̃ = δ, for a compliant one
/// δ̃ = 0). With `A Δx + s Ĝ ΔF = −R`:
///
/// ```text
/// (K_c⁻¹ + s VᵀA⁻¹Ĝ) ΔF = Vᵀ A⁻¹(−R) + δ̃,     Δx = A⁻¹(−R) − s A⁻¹Ĝ ΔF.
/// ```
///
/// For compliant contacts this is the Woodbury formula for `(A + s Ĝ K_c Vᵀ)⁻¹` (capacitance
/// matrix scaled by K_c⁻¹) and, for one wheel, Sherman–Morrison with the denominator
/// `1 + λ`, `λ = s k_c vᵀA⁻¹ĝ` (references.md §D4.2). On entry `x` holds −R; on exit Δx, and `df`
/// holds ΔF. An error if the capacitance matrix is singular.
pub fn contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut CapacitanceWork,
) -> Result<(), Singular> {
    let k = g_hat.len();
    a.solve_in_place(x);
    if k == 0 {
        return Ok(());
    }
    if work.ainv_g.len() < k || work.ainv_g[0].len() != x.len() {
        *work = CapacitanceWork::new(x.len(), k);
    }
    for c in 0..k {
        work.ainv_g[c].copy_from_slice(g_hat[c].as_ref());
        a.solve_sparse_in_place(&mut work.ainv_g[c], &mut work.support[c]);
    }
    // vᵀA⁻¹ĝ_c over the support of A⁻¹ĝ_c only (zero elsewhere).
    let sparse_dot = |v: &[f64], c: usize| -> f64 {
        work.support[c]
            .iter()
            .map(|&i| v[i] * work.ainv_g[c][i])
            .sum()
    };
    if k == 1 {
        // Sherman–Morrison: ΔF = (vᵀy + δ̃)/(1/k_c + s vᵀA⁻¹ĝ) = k_c(vᵀy + δ̃)/(1 + λ).
        let den = compliance[0] + s * sparse_dot(v[0].as_ref(), 0);
        if den == 0.0 || !den.is_finite() {
            return Err(SINGULAR_CAPACITANCE);
        }
        df[0] = (dot(v[0].as_ref(), x) + delta_tilde[0]) / den;
    } else {
        let lu = &mut work.lu[k - 2];
        let mut cap = lu.matrix_mut();
        for r in 0..k {
            for c in 0..k {
                let diag = if r == c { compliance[r] } else { 0.0 };
                cap[(r, c)] = diag + s * sparse_dot(v[r].as_ref(), c);
            }
            df[r] = dot(v[r].as_ref(), x) + delta_tilde[r];
        }
        if !lu.factor() {
            return Err(SINGULAR_CAPACITANCE);
        }
        lu.solve_in_place(&mut df[..k]);
    }
    for c in 0..k {
        let f = s * df[c];
        for &i in &work.support[c] {
            x[i] -= f * work.ainv_g[c][i];
        }
    }
    Ok(())
}

const SINGULAR_CAPACITANCE: Singular = Singular {
    what: "capacitance matrix",
};

/// The same update as [`contact_update`] by one dense solve of the bordered system
///
/// ```text
/// [ A    s Ĝ  ] [Δx]   [ −R ]
/// [ Vᵀ  −K_c⁻¹] [ΔF] = [ −δ̃ ]
/// ```
///
/// (the reference "full Newton" solve). Same argument conventions; `work` keeps the LU
/// storage of each size met.
pub fn dense_contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut DenseWork,
) -> Result<(), Singular> {
    let n = x.len();
    let k = g_hat.len();
    let m = n + k;
    let rhs = &mut work.rhs;
    rhs.clear();
    rhs.resize(m, 0.0);
    let lu = lu_of_size(&mut work.lu, m);
    let mut mat = lu.matrix_mut();
    mat.fill(0.0);
    a.write_into(&mut mat);
    for i in 0..n {
        for c in 0..k {
            mat[(i, n + c)] = s * g_hat[c].as_ref()[i];
        }
        rhs[i] = x[i];
    }
    for c in 0..k {
        for (j, &vj) in v[c].as_ref().iter().enumerate() {
            mat[(n + c, j)] = vj;
        }
        mat[(n + c, n + c)] = -compliance[c];
        rhs[n + c] = -delta_tilde[c];
    }
    if !lu.factor() {
        return Err(Singular {
            what: "bordered matrix",
        });
    }
    lu.solve_in_place(rhs);
    x.copy_from_slice(&rhs[..n]);
    df[..k].copy_from_slice(&rhs[n..]);
    Ok(())
}

/// The dot product.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
