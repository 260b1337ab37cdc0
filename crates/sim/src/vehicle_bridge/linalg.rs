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

/// Largest dense block: a bogie vehicle has 10 DOFs, an articulated train of n bodies
/// 6n + 4 (n ≤ 42).
pub const MAX_DENSE_BLOCK: usize = 256;

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

/// `x ← B⁻¹ x` on a dense block's indices, by columns over the non-zeros of x there (a
/// wheel's vector has one non-zero in its vehicle's block: O(m) instead of O(m²)).
fn apply_dense_inverse(blk: &DenseBlock, x: &mut [f64], buf: &mut [f64; MAX_DENSE_BLOCK]) {
    let m = blk.indices.len();
    let out = &mut buf[..m];
    out.fill(0.0);
    for (c, &j) in blk.indices.iter().enumerate() {
        let xj = x[j];
        if xj != 0.0 {
            for (r, o) in out.iter_mut().enumerate() {
                *o += blk.inverse[r * m + c] * xj;
            }
        }
    }
    for (r, &j) in blk.indices.iter().enumerate() {
        x[j] = out[r];
    }
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

    /// Number of blocks (small and dense): the range of [`Self::block_of`].
    pub fn block_count(&self) -> usize {
        self.blocks.len() + self.dense.len()
    }

    /// The block holding index `i` (an id below [`Self::block_count`]), if any.
    pub fn block_of(&self, i: usize) -> Option<usize> {
        match self.owner.get(i).copied().flatten()? {
            Owner::Small(b) => Some(b),
            Owner::Dense(d) => Some(self.blocks.len() + d),
        }
    }

    /// `x ← A⁻¹ x` for an `x` that is zero outside `pattern` (and zero on the blocks it does
    /// not touch, which is kept): only the blocks holding a non-zero of `x` at a pattern index
    /// are applied. `support` receives the indices where the result can be non-zero, `blocks`
    /// the ids of the blocks applied; `mark` (one entry per block, see
    /// [`Self::block_count`]) must not hold `stamp` on entry and holds it on the applied
    /// blocks on exit. Cost O(|pattern| + the sizes of the blocks applied), independent of n.
    pub fn solve_pattern_in_place(
        &self,
        x: &mut [f64],
        pattern: &[usize],
        support: &mut Vec<usize>,
        blocks: &mut Vec<usize>,
        mark: &mut [u64],
        stamp: u64,
    ) {
        support.clear();
        blocks.clear();
        let mut buf = [0.0; MAX_DENSE_BLOCK];
        for &i in pattern {
            if x[i] == 0.0 {
                continue;
            }
            let Some(owner) = self.owner.get(i).copied().flatten() else {
                continue;
            };
            let id = match owner {
                Owner::Small(b) => b,
                Owner::Dense(d) => self.blocks.len() + d,
            };
            if mark[id] == stamp {
                continue;
            }
            mark[id] = stamp;
            blocks.push(id);
            match owner {
                Owner::Small(b) => {
                    let (p, q, inv) = self.blocks[b];
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
                    apply_dense_inverse(blk, x, &mut buf);
                    support.extend_from_slice(&blk.indices);
                }
            }
        }
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

/// Work space of [`contact_update`]: A⁻¹ĝ per wheel with its support and blocks, the
/// coupling groups, and the LU storage of each capacitance size met (allocated at its first
/// use, then reused).
#[derive(Debug, Default)]
pub struct CapacitanceWork {
    ainv_g: Vec<Vec<f64>>,
    /// Where each A⁻¹ĝ can be non-zero (all other entries of `ainv_g[c]` are zero).
    support: Vec<Vec<usize>>,
    /// The blocks of A each A⁻¹ĝ touches.
    blocks: Vec<Vec<usize>>,
    /// Per block of A: the stamp of the last solve that applied it.
    mark: Vec<u64>,
    /// Per block of A: (stamp, first wheel of this update that touched it).
    first: Vec<(u64, usize)>,
    stamp: u64,
    /// Union–find parents of the active wheels (coupling groups).
    parent: Vec<usize>,
    /// The active wheels ordered by group, and the start of each group in it.
    order: Vec<usize>,
    group_start: Vec<usize>,
    rhs: Vec<f64>,
    lu: Vec<DenseLu<f64>>,
    /// Scratch of [`Self::quadratic_form`] (kept zero between calls).
    scratch: Vec<f64>,
    scratch_support: Vec<usize>,
    scratch_blocks: Vec<usize>,
}

impl CapacitanceWork {
    /// Work space for dimension n and up to `k_max` wheels.
    pub fn new(n: usize, k_max: usize) -> Self {
        Self {
            ainv_g: vec![vec![0.0; n]; k_max],
            support: vec![Vec::new(); k_max],
            blocks: vec![Vec::new(); k_max],
            ..Self::default()
        }
    }

    /// Makes room for `k` wheels of dimension `n` and `blocks` blocks of A (allocates only
    /// when they grow).
    fn reserve(&mut self, n: usize, k: usize, blocks: usize) {
        if self.ainv_g.first().is_some_and(|a| a.len() != n) {
            self.ainv_g.clear();
            self.support.clear();
            self.blocks.clear();
        }
        while self.ainv_g.len() < k {
            self.ainv_g.push(vec![0.0; n]);
            self.support.push(Vec::new());
            self.blocks.push(Vec::new());
        }
        if self.mark.len() != blocks {
            self.mark = vec![0; blocks];
            self.first = vec![(0, 0); blocks];
            self.stamp = 0;
        }
    }

    /// `vᵀA⁻¹g` for vectors zero outside `pattern` (over the blocks g touches; no full solve).
    pub fn quadratic_form(
        &mut self,
        a: &BlockDiagonal,
        g: &[f64],
        v: &[f64],
        pattern: &[usize],
    ) -> f64 {
        let n = g.len();
        if self.scratch.len() != n {
            self.scratch = vec![0.0; n];
        }
        self.reserve(n, 0, a.block_count());
        for &i in pattern {
            self.scratch[i] = g[i];
        }
        let stamp = self.next_stamp();
        a.solve_pattern_in_place(
            &mut self.scratch,
            pattern,
            &mut self.scratch_support,
            &mut self.scratch_blocks,
            &mut self.mark,
            stamp,
        );
        let result = pattern.iter().map(|&i| v[i] * self.scratch[i]).sum();
        for &i in self.scratch_support.iter().chain(pattern) {
            self.scratch[i] = 0.0;
        }
        result
    }

    /// The next stamp (never 0, the initial mark).
    fn next_stamp(&mut self) -> u64 {
        self.stamp += 1;
        self.stamp
    }
}

fn find(parent: &mut [usize], mut a: usize) -> usize {
    while parent[a] != a {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    a
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
/// `1 + λ`, `λ = s k_c vᵀA⁻¹ĝ` (references.md §D4.2).
///
/// **Sparsity.** Wheel c's vectors ĝ_c and v_c are zero outside `pattern[c]` (the bridge modes
/// and the wheel's own DOF), so A⁻¹ĝ_c is non-zero only on the blocks of A that ĝ_c touches.
/// Two wheels are coupled (a non-zero capacitance entry) only if they touch a common block:
/// wheels on the span share the modes, wheels of one vehicle share its block. The capacitance
/// matrix is therefore block diagonal over the groups of coupled wheels (union–find over the
/// blocks), and each group is factorised on its own: a long train whose cars are mostly off the
/// span costs O(wheels), not O(wheels³).
///
/// Arguments: `active` lists the wheels taking part (indices into `g_hat`, `v`, `pattern`);
/// `compliance`, `delta_tilde` and `df` are indexed by position in `active`. On entry `x` holds
/// −R; on exit Δx, and `df` holds ΔF. An error if a capacitance matrix is singular.
#[allow(clippy::too_many_arguments)]
pub fn contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    pattern: &[impl AsRef<[usize]>],
    active: &[usize],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut CapacitanceWork,
) -> Result<(), Singular> {
    let k = active.len();
    a.solve_in_place(x);
    if k == 0 {
        return Ok(());
    }
    let n = x.len();
    work.reserve(n, k, a.block_count());
    // A⁻¹ĝ_c on the blocks ĝ_c touches (the rest of ainv_g[c] is kept zero).
    for (c, &wheel) in active.iter().enumerate() {
        for &i in &work.support[c] {
            work.ainv_g[c][i] = 0.0;
        }
        let g = g_hat[wheel].as_ref();
        let p = pattern[wheel].as_ref();
        for &i in p {
            work.ainv_g[c][i] = g[i];
        }
        let stamp = work.next_stamp();
        a.solve_pattern_in_place(
            &mut work.ainv_g[c],
            p,
            &mut work.support[c],
            &mut work.blocks[c],
            &mut work.mark,
            stamp,
        );
    }
    // Coupling groups: wheels touching a common block.
    let update = work.next_stamp();
    work.parent.clear();
    work.parent.extend(0..k);
    for c in 0..k {
        for &b in &work.blocks[c] {
            let (seen, first) = work.first[b];
            if seen == update {
                let (ra, rb) = (find(&mut work.parent, c), find(&mut work.parent, first));
                if ra != rb {
                    work.parent[ra.max(rb)] = ra.min(rb);
                }
            } else {
                work.first[b] = (update, c);
            }
        }
    }
    // Group the wheels (stable: by root, then position; roots are the smallest member).
    work.order.clear();
    work.group_start.clear();
    for c in 0..k {
        let root = find(&mut work.parent, c);
        work.parent[c] = root;
    }
    for root in 0..k {
        if work.parent[root] != root {
            continue;
        }
        work.group_start.push(work.order.len());
        for c in root..k {
            if work.parent[c] == root {
                work.order.push(c);
            }
        }
    }
    work.group_start.push(k);
    // vᵀx over the pattern (v is zero elsewhere).
    let v_dot = |c: usize, y: &[f64]| -> f64 {
        let vc = v[active[c]].as_ref();
        pattern[active[c]]
            .as_ref()
            .iter()
            .map(|&i| vc[i] * y[i])
            .sum()
    };
    for g in 0..work.group_start.len() - 1 {
        let members = &work.order[work.group_start[g]..work.group_start[g + 1]];
        let kg = members.len();
        if kg == 1 {
            // Sherman–Morrison: ΔF = (vᵀy + δ̃)/(1/k_c + s vᵀA⁻¹ĝ) = k_c(vᵀy + δ̃)/(1 + λ).
            let c = members[0];
            let den = compliance[c] + s * v_dot(c, &work.ainv_g[c]);
            if den == 0.0 || !den.is_finite() {
                return Err(SINGULAR_CAPACITANCE);
            }
            df[c] = (v_dot(c, x) + delta_tilde[c]) / den;
            continue;
        }
        let lu = lu_of_size(&mut work.lu, kg);
        let mut cap = lu.matrix_mut();
        work.rhs.clear();
        for (r, &cr) in members.iter().enumerate() {
            for (q, &cq) in members.iter().enumerate() {
                let diag = if r == q { compliance[cr] } else { 0.0 };
                cap[(r, q)] = diag + s * v_dot(cr, &work.ainv_g[cq]);
            }
            work.rhs.push(v_dot(cr, x) + delta_tilde[cr]);
        }
        if !lu.factor() {
            return Err(SINGULAR_CAPACITANCE);
        }
        lu.solve_in_place(&mut work.rhs);
        for (r, &cr) in members.iter().enumerate() {
            df[cr] = work.rhs[r];
        }
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
#[allow(clippy::too_many_arguments)]
pub fn dense_contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    active: &[usize],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut DenseWork,
) -> Result<(), Singular> {
    let n = x.len();
    let k = active.len();
    let m = n + k;
    let rhs = &mut work.rhs;
    rhs.clear();
    rhs.resize(m, 0.0);
    let lu = lu_of_size(&mut work.lu, m);
    let mut mat = lu.matrix_mut();
    mat.fill(0.0);
    a.write_into(&mut mat);
    for i in 0..n {
        for (c, &wheel) in active.iter().enumerate() {
            mat[(i, n + c)] = s * g_hat[wheel].as_ref()[i];
        }
        rhs[i] = x[i];
    }
    for (c, &wheel) in active.iter().enumerate() {
        for (j, &vj) in v[wheel].as_ref().iter().enumerate() {
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
