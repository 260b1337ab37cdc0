//! The entrywise absolute inverse |A⁻¹| of a [`BlockDiagonal`] applied to a vector of
//! magnitudes: how an error vector propagates through a solve (the force floor of the
//! coupled step, `vehicle_bridge::coupling`), exactly or bounded.

use super::{BlockDiagonal, DensePart, NONE, Owner, row_dot};

impl BlockDiagonal {
    /// `x ← |A⁻¹| x` in place, with the entrywise absolute value of each block's inverse (a
    /// bound on how an error vector of x's magnitudes propagates through a solve).
    pub fn solve_abs_in_place(&self, x: &mut [f64]) {
        self.dense_apply(x, DensePart::AbsInverse, |_| false);
        self.small_abs(x);
    }

    /// [`Self::solve_abs_in_place`] where only the entries at the indices `rows` and outside
    /// the dense blocks are wanted: a dense block's other entries are left as they were (the
    /// wanted ones are the same sums in the same order, bit for bit). The force floor needs
    /// `|A⁻¹| e` at the wheels only, a third of an articulated rake's rows.
    pub fn solve_abs_at(&self, x: &mut [f64], rows: &[usize]) {
        self.with_scratch(|xs, out| {
            for (d, b) in self.live_dense() {
                let m = b.indices.len();
                let xs = b.gather(x, xs);
                // The wanted rows of this block, computed from its entries of x before any
                // is overwritten.
                let mut count = 0;
                for &i in rows {
                    if self.owner.get(i).copied().flatten() == Some(Owner::Dense(d)) {
                        let r = self.local[i];
                        out[count] = row_dot(&b.inverse[r * m..(r + 1) * m], xs, true);
                        count += 1;
                    }
                }
                let wanted = rows
                    .iter()
                    .filter(|&&i| self.owner.get(i).copied().flatten() == Some(Owner::Dense(d)));
                for (&i, o) in wanted.zip(&out[..count]) {
                    x[i] = *o;
                }
            }
        });
        self.small_abs(x);
    }

    /// An upper bound of [`Self::solve_abs_at`] for `x ≥ 0` at the indices `rows` of the dense
    /// blocks: the diagonal term exactly and the others bounded by the largest entry,
    ///
    /// ```text
    /// (|B⁻¹| x)_r = |B⁻¹_rr| x_r + Σ_{c≠r} |B⁻¹_rc| x_c ≤ |B⁻¹_rr| x_r + (Σ_{c≠r} |B⁻¹_rc|) max_c x_c,
    /// ```
    ///
    /// the off-diagonal sums of `|B⁻¹|` kept with the block: O(m) per block instead of O(m)
    /// per wanted row (exact arithmetic; both sides carry a relative round-off of at most m ε).
    /// A step matrix A = c_M M + … of a small step is dominated by its mass diagonal, so its
    /// inverse is too, and the bound is close. Entries outside the dense blocks are `|B⁻¹| x`
    /// as in [`Self::solve_abs_in_place`]; the other entries of the dense blocks are left as
    /// they were.
    pub fn solve_abs_bound_at(&self, x: &mut [f64], rows: &[usize]) {
        for (d, b) in self.live_dense() {
            let m = b.indices.len();
            let largest = b.indices.iter().fold(0.0f64, |l, &i| l.max(x[i]));
            for &i in rows {
                if self.owner.get(i).copied().flatten() == Some(Owner::Dense(d)) {
                    let r = self.local[i];
                    x[i] = b.inverse[r * m + r].abs() * x[i] + b.abs_off_diagonal[r] * largest;
                }
            }
        }
        self.small_abs(x);
    }

    /// `x ← |B⁻¹| x` over the 1×1 and 2×2 blocks.
    fn small_abs(&self, x: &mut [f64]) {
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
}
