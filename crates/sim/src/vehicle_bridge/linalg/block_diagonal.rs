//! The contact-free step matrix A = c_M M + c_C C + c_K K (module [`super`]): block diagonal,
//! with 1×1 modal blocks, 1×1/2×2 wheel blocks and one dense block per multibody vehicle,
//! stored with the block inverses; full, pattern and absolute-value solves and products.

use super::Singular;
use super::banded::{BandedLu, SparseRows};

mod abs;

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
    /// The position of each index of a dense block within it.
    local: Vec<usize>,
    /// Every index i below it is a 1×1 block with block id i (the bridge modes, pushed
    /// first): pattern solves take them without looking up their owner.
    unit_prefix: usize,
    /// Changes whenever the matrix does (unique across all matrices of the process), so that
    /// solves cached against it (`low_rank::CapacitanceWork`) know when they are stale.
    version: u64,
    /// Per dense block: left out of [`Self::mul`], [`Self::solve_in_place`] and
    /// [`Self::solve_abs_in_place`] (a vehicle held out of the step; kept across
    /// [`Self::clear`]).
    held: Vec<bool>,
}

/// The source of [`BlockDiagonal`] versions.
static NEXT_VERSION: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

fn next_version() -> u64 {
    NEXT_VERSION.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
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
    /// The band factorisation of a large sparse block (solves), if worth it.
    banded: Option<BandedLu>,
    /// The non-zeros of a large block (products).
    sparse: Option<SparseRows>,
    /// Σ_{c ≠ r} |B⁻¹_rc| of each row r (the bound of [`BlockDiagonal::solve_abs_bound_at`]).
    abs_off_diagonal: Vec<f64>,
}

impl DenseBlock {
    /// The block's entries of `x` gathered into the front of `xs` (returned, length m), so
    /// that each row is a dot product of two slices.
    fn gather<'a>(&self, x: &[f64], xs: &'a mut [f64]) -> &'a mut [f64] {
        let xs = &mut xs[..self.indices.len()];
        for (v, &i) in xs.iter_mut().zip(&self.indices) {
            *v = x[i];
        }
        xs
    }
}

/// The inverse of the row-major m × m `entries` by Gauss–Jordan elimination with partial
/// pivoting; `None` if it is singular or not finite.
pub(super) fn gauss_jordan_inverse(entries: &[f64], m: usize) -> Option<Vec<f64>> {
    let mut a = entries.to_vec();
    let mut inv = vec![0.0; m * m];
    for i in 0..m {
        inv[i * m + i] = 1.0;
    }
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    if !(scale.is_finite() && scale > 0.0) {
        return None;
    }
    for col in 0..m {
        let pivot = (col..m)
            .max_by(|&r, &q| a[r * m + col].abs().total_cmp(&a[q * m + col].abs()))
            .unwrap_or(col);
        if a[pivot * m + col].abs() <= 1e-14 * scale {
            return None;
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
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

/// Which matrix of a dense block [`BlockDiagonal::dense_apply`] applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum DensePart {
    Inverse,
    AbsInverse,
}

/// `x ← B⁻¹ x` on a dense block's indices, by columns over the non-zeros of x there (a
/// wheel's vector has one non-zero in its vehicle's block: O(m) instead of O(m²)).
fn apply_dense_inverse(blk: &DenseBlock, x: &mut [f64]) {
    let m = blk.indices.len();
    if m <= SMALL_DENSE_BLOCK {
        apply_dense_inverse_with(blk, x, &mut [0.0; SMALL_DENSE_BLOCK]);
    } else {
        apply_dense_inverse_with(blk, x, &mut [0.0; MAX_DENSE_BLOCK]);
    }
}

/// Dense blocks up to this size use a small stack buffer (zeroing the largest one at every
/// pattern solve would cost more than the solve of a bogie vehicle's 10 × 10 block).
const SMALL_DENSE_BLOCK: usize = 16;

fn apply_dense_inverse_with(blk: &DenseBlock, x: &mut [f64], buf: &mut [f64]) {
    let m = blk.indices.len();
    let out = &mut buf[..m];
    out.fill(0.0);
    for (c, &j) in blk.indices.iter().enumerate() {
        let xj = x[j];
        if xj != 0.0 {
            for (o, inv) in out.iter_mut().zip(blk.inverse[c..].iter().step_by(m)) {
                *o += inv * xj;
            }
        }
    }
    for (r, &j) in blk.indices.iter().enumerate() {
        x[j] = out[r];
    }
}

/// `out_r = Σ_c B_rc x_c` for the row-major m × m matrix `rows` (m = `x.len()`), or with
/// |B_rc| if `abs`: each row a sum in column order (with a fixed size for a bogie vehicle's
/// 10 × 10 block, which the compiler unrolls; the same operations in the same order).
fn rows_times(rows: &[f64], x: &[f64], out: &mut [f64], abs: bool) {
    match <&[f64; 10]>::try_from(x) {
        Ok(x) => rows_times_fixed(rows.as_chunks::<10>().0, x, out, abs),
        Err(_) => {
            for (o, row) in out.iter_mut().zip(rows.chunks_exact(x.len())) {
                *o = row_dot(row, x, abs);
            }
        }
    }
}

fn rows_times_fixed<const M: usize>(rows: &[[f64; M]], x: &[f64; M], out: &mut [f64], abs: bool) {
    for (o, row) in out.iter_mut().zip(rows) {
        *o = row_dot(row, x, abs);
    }
}

#[inline(always)]
fn row_dot(row: &[f64], x: &[f64], abs: bool) -> f64 {
    if abs {
        row.iter().zip(x).map(|(v, x)| v.abs() * x).sum()
    } else {
        row.iter().zip(x).map(|(v, x)| v * x).sum()
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
            local: vec![0; n],
            unit_prefix: 0,
            version: next_version(),
            held: Vec::new(),
        }
    }

    /// Leaves dense block `d` (the d-th pushed) out of the full products and solves, or takes
    /// it back: their entries of the vector are then not written. The matrix is unchanged
    /// (same version); pattern solves ignore the flag.
    pub fn hold_dense(&mut self, d: usize, held: bool) {
        if self.held.len() <= d {
            self.held.resize(d + 1, false);
        }
        self.held[d] = held;
    }

    /// Dense block `d` (the d-th pushed): its indices, entries and inverse (row-major m × m).
    pub fn dense_block(&self, d: usize) -> Option<(&[usize], &[f64], &[f64])> {
        let b = self.dense.get(d)?;
        Some((&b.indices, &b.entries, &b.inverse))
    }

    /// Whether dense block `d` is held out of the full products and solves.
    pub fn is_held(&self, d: usize) -> bool {
        self.held.get(d).copied().unwrap_or(false)
    }

    /// The dense blocks taking part in products and solves (a held one is skipped: its rows
    /// are left as they were; module `resting`), with their positions.
    fn live_dense(&self) -> impl Iterator<Item = (usize, &DenseBlock)> {
        self.dense
            .iter()
            .enumerate()
            .filter(|&(d, _)| !self.is_held(d))
    }

    /// The matrix's version: changes at every modification (see the field).
    pub fn version(&self) -> u64 {
        self.version
    }

    /// Removes all blocks (keeps the capacity).
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.entries.clear();
        self.dense.clear();
        self.owner.clear();
        self.owner.resize(self.n, None);
        self.unit_prefix = 0;
        self.version = next_version();
    }

    /// Adds the dense block with row-major `entries` on `indices` (m ≤ [`MAX_DENSE_BLOCK`]);
    /// its inverse by Gauss–Jordan elimination with partial pivoting. An error if it is
    /// singular or not finite (the block is then not added).
    pub fn push_dense(&mut self, indices: &[usize], entries: &[f64]) -> Result<(), Singular> {
        let m = indices.len();
        if m == 0 || m > MAX_DENSE_BLOCK || entries.len() != m * m {
            return Err(SINGULAR_BLOCK);
        }
        let inverse = gauss_jordan_inverse(entries, m).ok_or(SINGULAR_BLOCK)?;
        // A large sparse block (an articulated rake) is solved in its band and multiplied by
        // its non-zeros (module `banded`); a small one (a bogie vehicle) densely.
        let (banded, sparse) = if m > SMALL_DENSE_BLOCK {
            (
                BandedLu::new(entries, &inverse, m),
                Some(SparseRows::new(entries, m)),
            )
        } else {
            (None, None)
        };
        for (r, &i) in indices.iter().enumerate() {
            self.reowned(i);
            self.owner[i] = Some(Owner::Dense(self.dense.len()));
            self.local[i] = r;
        }
        let abs_off_diagonal = inverse
            .chunks_exact(m)
            .enumerate()
            .map(|(r, row)| {
                row.iter()
                    .enumerate()
                    .filter(|&(c, _)| c != r)
                    .map(|(_, v)| v.abs())
                    .sum()
            })
            .collect();
        self.dense.push(DenseBlock {
            indices: indices.to_vec(),
            entries: entries.to_vec(),
            inverse,
            banded,
            sparse,
            abs_off_diagonal,
        });
        self.version = next_version();
        Ok(())
    }

    /// `x ← B x` over the dense blocks (B = the inverses or their absolute values) but the
    /// `deferred` ones, with a stack buffer (no allocation).
    fn dense_apply(&self, x: &mut [f64], which: DensePart, deferred: impl Fn(usize) -> bool) {
        // The block's entries of x are gathered once, so that each row is a dot product of two
        // slices (the same products summed in the same order as entry by entry).
        self.with_scratch(|xs, buf| {
            for (_, b) in self.live_dense().filter(|&(d, _)| !deferred(d)) {
                let m = b.indices.len();
                let xs = b.gather(x, xs);
                let banded = match which {
                    DensePart::Inverse => b.banded.as_ref(),
                    DensePart::AbsInverse => None,
                };
                match (banded, which) {
                    (Some(lu), DensePart::Inverse) => {
                        lu.solve(xs, buf);
                        buf[..m].copy_from_slice(xs);
                    }
                    _ => rows_times(
                        &b.inverse,
                        xs,
                        &mut buf[..m],
                        which == DensePart::AbsInverse,
                    ),
                }
                for (r, &i) in b.indices.iter().enumerate() {
                    x[i] = buf[r];
                }
            }
        });
    }

    /// Calls `f` with two zeroed stack buffers as long as the largest dense block (a small
    /// one when every block is small: zeroing the largest size at every product would cost
    /// more than the products of bogie vehicles' 10 × 10 blocks).
    fn with_scratch(&self, f: impl FnOnce(&mut [f64], &mut [f64])) {
        if self
            .dense
            .iter()
            .all(|b| b.indices.len() <= SMALL_DENSE_BLOCK)
        {
            f(&mut [0.0; SMALL_DENSE_BLOCK], &mut [0.0; SMALL_DENSE_BLOCK]);
        } else {
            f(&mut [0.0; MAX_DENSE_BLOCK], &mut [0.0; MAX_DENSE_BLOCK]);
        }
    }

    /// For an index of a dense block with a band factorisation: (the dense block's number,
    /// the index's position in it).
    pub fn banded_block(&self, i: usize) -> Option<(usize, usize)> {
        match self.owner.get(i).copied().flatten()? {
            Owner::Dense(d) if self.dense[d].banded.is_some() => Some((d, self.local[i])),
            _ => None,
        }
    }

    /// The band factorisation of dense block d, if it has one.
    pub fn banded(&self, d: usize) -> Option<&BandedLu> {
        self.dense.get(d)?.banded.as_ref()
    }

    /// The number of dense blocks.
    pub fn dense_count(&self) -> usize {
        self.dense.len()
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
        self.reowned(i);
        if i == self.unit_prefix && self.blocks.len() == i {
            self.unit_prefix += 1;
        }
        self.owner[i] = Some(Owner::Small(self.blocks.len()));
        self.blocks.push((i, NONE, [1.0 / a, 0.0, 0.0, 0.0]));
        self.entries.push([a, 0.0, 0.0, 0.0]);
        self.version = next_version();
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
        self.reowned(i);
        self.reowned(j);
        self.owner[i] = Some(Owner::Small(self.blocks.len()));
        self.owner[j] = Some(Owner::Small(self.blocks.len()));
        self.blocks
            .push((i, j, [d / det, -b / det, -c / det, a / det]));
        self.entries.push([a, b, c, d]);
        self.version = next_version();
        Ok(())
    }

    /// Index `i` gets a new block: the run of leading 1×1 blocks (`unit_prefix`) ends before
    /// it if it was in it.
    fn reowned(&mut self, i: usize) {
        self.unit_prefix = self.unit_prefix.min(i);
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
        let apply = |_: usize, blk: &DenseBlock, x: &mut [f64]| apply_dense_inverse(blk, x);
        self.solve_pattern_with(x, pattern, support, blocks, mark, stamp, apply);
    }

    /// [`Self::solve_pattern_in_place`] except on the dense blocks d with `deferred(d)`:
    /// those are listed in `blocks` and `support` as if applied, and x is left unchanged there
    /// (the caller applies their factorisations, e.g. to many right-hand sides at once:
    /// the blocks are disjoint, so the order of their solves does not matter).
    #[allow(clippy::too_many_arguments)]
    pub fn solve_pattern_deferring(
        &self,
        x: &mut [f64],
        pattern: &[usize],
        support: &mut Vec<usize>,
        blocks: &mut Vec<usize>,
        mark: &mut [u64],
        stamp: u64,
        deferred: impl Fn(usize) -> bool,
    ) {
        let apply = |d: usize, blk: &DenseBlock, x: &mut [f64]| {
            if !deferred(d) {
                apply_dense_inverse(blk, x);
            }
        };
        self.solve_pattern_with(x, pattern, support, blocks, mark, stamp, apply);
    }

    /// The pattern solve with `dense(d, block, x)` applying dense block d's inverse.
    #[allow(clippy::too_many_arguments)]
    fn solve_pattern_with(
        &self,
        x: &mut [f64],
        pattern: &[usize],
        support: &mut Vec<usize>,
        blocks: &mut Vec<usize>,
        mark: &mut [u64],
        stamp: u64,
        dense: impl Fn(usize, &DenseBlock, &mut [f64]),
    ) {
        support.clear();
        blocks.clear();
        let unit = self.unit_prefix;
        for &i in pattern {
            if x[i] == 0.0 {
                continue;
            }
            if i < unit {
                // A leading 1×1 block, whose id is i (`unit_prefix`): as `Owner::Small` below.
                if mark[i] == stamp {
                    continue;
                }
                mark[i] = stamp;
                blocks.push(i);
                x[i] *= self.blocks[i].2[0];
                support.push(i);
                continue;
            }
            let (Some(owner), Some(id)) = (self.owner.get(i).copied().flatten(), self.block_of(i))
            else {
                continue;
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
                    dense(d, blk, x);
                    support.extend_from_slice(&blk.indices);
                }
            }
        }
    }

    /// `x ← A⁻¹ x` in place (held dense blocks: x unchanged there).
    pub fn solve_in_place(&self, x: &mut [f64]) {
        self.dense_apply(x, DensePart::Inverse, |_| false);
        self.small_solve(x);
    }

    /// [`Self::solve_in_place`] except on the dense blocks d with `deferred(d)` that are not
    /// held: x is left unchanged there (the caller applies their factorisations, e.g. with
    /// other right-hand sides at once; the blocks are disjoint, so the order of the solves
    /// does not matter).
    pub fn solve_in_place_deferring(&self, x: &mut [f64], deferred: impl Fn(usize) -> bool) {
        self.dense_apply(x, DensePart::Inverse, deferred);
        self.small_solve(x);
    }

    /// `x ← B⁻¹ x` over the 1×1 and 2×2 blocks.
    fn small_solve(&self, x: &mut [f64]) {
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

    /// `y = A x` (held dense blocks: y not written there).
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        self.with_scratch(|xs, out| {
            for (_, b) in self.live_dense() {
                let m = b.indices.len();
                let xs = b.gather(x, xs);
                match &b.sparse {
                    Some(rows) => rows.times(xs, &mut out[..m]),
                    None => rows_times(&b.entries, xs, &mut out[..m], false),
                }
                for (&i, o) in b.indices.iter().zip(&out[..m]) {
                    y[i] = *o;
                }
            }
        });
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
