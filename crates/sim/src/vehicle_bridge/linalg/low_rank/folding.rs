//! Folding of the compliant off-span wheels into an articulated rake's band
//! ([`contact_update`](super::contact_update), "Folding"): the factorisation of each changed
//! block, reused while A and the folded wheels' diagonal additions are the same bit for bit,
//! and the solves of the step's right-hand side and of the wheels that touch a folded block,
//! all right-hand sides of a block in one pass over its band
//! ([`BandedLu::solve_interleaved`]).
//!
//! A wheel's solve on a folded block is kept ([`FoldColumn`]) and taken again while the
//! block's factorisation and the wheel's ĝ on it are the same: the quasi-Newton start of a
//! step meets the factorisation of the previous step's last update, whose wheel solves are
//! then at hand. With a fold tolerance ([`CapacitanceWork::set_fold_tolerance`]) the
//! factorisation also stands while the folded stiffnesses change by less than it (a chord
//! step for those wheels), and so do the kept solves.
//!
//! Both are the operations of the wheel-by-wheel path on the same inputs: a reused
//! factorisation is the one the refactorisation would compute (same matrix, same
//! operations), and the batched solve does each right-hand side's operations in the same
//! order; the results are identical bit for bit (the interleaved substitutions against
//! [`BandedLu::solve`] in `banded`'s unit tests, the update against the dense bordered solve in
//! `tests/vehicle_bridge_banded.rs`).

use super::super::banded::{BandedLu, MANY};
use super::{BlockDiagonal, CapacitanceWork, SolveKey};

impl CapacitanceWork {
    /// Folds the compliant wheels of `active` that are off the span (ĝ and v on the wheel's
    /// DOF only) and belong to a banded block of A into that block
    /// ([`contact_update`](super::contact_update), "Folding"): marks them in `folded` and
    /// factorises each block changed (unless its factorisation from the same A and the same
    /// additions is at hand). False (nothing
    /// folded) if there are none, or if a changed block is singular (the capacitance form
    /// then takes every wheel, as without folding).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn fold_off_span(
        &mut self,
        a: &BlockDiagonal,
        s: f64,
        g_hat: &[impl AsRef<[f64]>],
        v: &[impl AsRef<[f64]>],
        pattern: &[impl AsRef<[usize]>],
        active: &[usize],
        compliance: &[f64],
    ) -> bool {
        let nd = a.dense_count();
        self.fold_gen.resize(nd, 0);
        self.fold_add.resize_with(nd, Vec::new);
        self.fold_lu.resize_with(nd, BandedLu::default);
        self.fold_key.resize_with(nd, Default::default);
        self.fold_used.clear();
        self.fold_used.resize(nd, false);
        for add in &mut self.fold_add {
            add.clear();
        }
        self.folded.clear();
        self.folded.resize(active.len(), false);
        self.fold_slot.clear();
        self.fold_slot.resize(active.len(), (0, 0));
        let mut any = false;
        for (c, &wheel) in active.iter().enumerate() {
            let &[i] = pattern[wheel].as_ref() else {
                continue;
            };
            let Some((d, r)) = a.banded_block(i) else {
                continue;
            };
            if compliance[c] > 0.0 {
                let value = s * g_hat[wheel].as_ref()[i] * v[wheel].as_ref()[i] / compliance[c];
                self.fold_slot[c] = (d, self.fold_add[d].len());
                self.fold_add[d].push((r, value));
                self.fold_used[d] = true;
                self.folded[c] = true;
                any = true;
            }
        }
        for d in 0..nd {
            if !self.fold_used[d] {
                continue;
            }
            let (version, key) = &self.fold_key[d];
            let tolerance = self.fold_tolerance;
            let same = *version == a.version()
                && key.len() == self.fold_add[d].len()
                && key
                    .iter()
                    .zip(&self.fold_add[d])
                    .all(|(&(rk, bits), &(r, value))| {
                        rk == r && (bits == value.to_bits() || within(value, bits, tolerance))
                    });
            if same {
                self.fold_reused += 1;
                continue;
            }
            let base = a.banded(d).expect("a folded block is banded");
            self.fold_gens += 1;
            self.fold_gen[d] = self.fold_gens;
            if !base.refactor_with_diagonal(&self.fold_add[d], &mut self.fold_lu[d]) {
                self.fold_key[d].0 = 0;
                self.fold_gen[d] = 0;
                self.fold_used.fill(false);
                self.folded.fill(false);
                return false;
            }
            let key = &mut self.fold_key[d];
            key.0 = a.version();
            key.1.clear();
            key.1.extend(
                self.fold_add[d]
                    .iter()
                    .map(|&(r, value)| (r, value.to_bits())),
            );
        }
        if any {
            self.folds += self.folded.iter().filter(|&&f| f).count() as u64;
        }
        any
    }

    /// Whether `pattern` touches a block changed by folding.
    pub(super) fn touches_fold(&self, a: &BlockDiagonal, pattern: &[usize]) -> bool {
        pattern.iter().any(|&i| {
            a.banded_block(i)
                .is_some_and(|(d, _)| self.fold_used.get(d).copied().unwrap_or(false))
        })
    }

    /// A_c⁻¹ĝ of the wheels in `batch` into their `ainv_g`, A_c being A with the folded
    /// wheels (not kept for reuse: A_c changes with the contact stiffnesses), and the
    /// folded blocks' part of `x ← A_c⁻¹ x` (x solved elsewhere already,
    /// [`BlockDiagonal::solve_in_place_deferring`]): each wheel's pattern solve without the
    /// folded blocks, then per folded block x and the wheels that touch it solved together
    /// ([`BandedLu::solve_interleaved`]). The same result,
    /// bit for bit, as solving x and the wheels one by one.
    pub(super) fn solve_wheels_folded(
        &mut self,
        a: &BlockDiagonal,
        g_hat: &[impl AsRef<[f64]>],
        pattern: &[impl AsRef<[usize]>],
        x: &mut [f64],
    ) {
        for b in 0..self.batch.len() {
            let wheel = self.batch[b];
            let (g, p) = (g_hat[wheel].as_ref(), pattern[wheel].as_ref());
            self.start_wheel(wheel, g, p);
            let used = &self.fold_used;
            a.solve_pattern_deferring(
                &mut self.ainv_g[wheel],
                p,
                &mut self.support[wheel],
                &mut self.blocks[wheel],
                &mut self.mark,
                self.stamp,
                |d| used[d],
            );
            self.key[wheel] = SolveKey::default();
        }
        for d in 0..self.fold_used.len() {
            if self.fold_used[d] {
                self.solve_block_many(a, d, g_hat, pattern, x);
            }
        }
    }

    /// Folded block d's factorisation applied to the entries on it of `x` (unless the block
    /// is held: a full solve leaves it) and of every wheel of `batch` whose pattern solve
    /// deferred it: a wheel whose [`FoldColumn`] holds the solve of the same ĝ with the same
    /// factorisation takes it from there, the others are solved and kept.
    fn solve_block_many(
        &mut self,
        a: &BlockDiagonal,
        d: usize,
        g_hat: &[impl AsRef<[f64]>],
        pattern: &[impl AsRef<[usize]>],
        x: &mut [f64],
    ) {
        let Some((indices, _, _)) = a.dense_block(d) else {
            return;
        };
        let Some(id) = indices.first().and_then(|&i| a.block_of(i)) else {
            return;
        };
        // The right-hand sides: x (usize::MAX) unless the block is held, and the wheels that
        // deferred it; gathered straight into band order, up to MANY at a time.
        self.rows.clear();
        if !a.is_held(d) {
            self.rows.push(usize::MAX);
        }
        let generation = self.fold_gen[d];
        for &wheel in &self.batch {
            if !self.blocks[wheel].contains(&id) {
                continue;
            }
            let (g, p) = (g_hat[wheel].as_ref(), pattern[wheel].as_ref());
            let column = &self.fold_column[wheel];
            if column.matches(a, d, generation, g, p) {
                // The kept solve of the same right-hand side by the same factorisation.
                let x = &mut self.ainv_g[wheel];
                for (&i, &value) in indices.iter().zip(&column.values) {
                    x[i] = value;
                }
                self.column_reused += 1;
            } else {
                self.rows.push(wheel);
            }
        }
        let lu = &self.fold_lu[d];
        let m = indices.len();
        self.many_buf.resize(MANY * m, 0.0);
        for group in self.rows.chunks(MANY) {
            let g = group.len();
            let y = &mut self.many_buf[..g * m];
            for (r, &row) in group.iter().enumerate() {
                let src: &[f64] = if row == usize::MAX {
                    x
                } else {
                    &self.ainv_g[row]
                };
                for (k, &o) in lu.order().iter().enumerate() {
                    y[k * g + r] = src[indices[o]];
                }
            }
            lu.solve_interleaved(y, g);
            for (r, &row) in group.iter().enumerate() {
                let dst: &mut [f64] = if row == usize::MAX {
                    x
                } else {
                    &mut self.ainv_g[row]
                };
                for (k, &o) in lu.order().iter().enumerate() {
                    dst[indices[o]] = y[k * g + r];
                }
            }
        }
        for &wheel in &self.rows {
            if wheel != usize::MAX {
                let (g, p) = (g_hat[wheel].as_ref(), pattern[wheel].as_ref());
                let solved = &self.ainv_g[wheel];
                self.fold_column[wheel].set(a, d, generation, g, p, indices, solved);
            }
        }
    }

    /// Lets the factorisation of a folded block stand while every folded wheel's diagonal
    /// addition s k_c (its contact stiffness) is within `relative` of the one factorised
    /// (0, the default: only bit for bit the same). With `relative` > 0 the update is no
    /// longer the exact linearisation but a quasi-Newton step whose Jacobian is off by at
    /// most that relative amount in the off-span wheels' stiffnesses: the iteration
    /// converges to the same solution, each update contracting the error by a factor
    /// ≲ `relative` instead of quadratically (the chord method, Kelley 1995 ch. 5;
    /// references.md §D4.2). Negative or non-finite values count as 0.
    pub fn set_fold_tolerance(&mut self, relative: f64) {
        self.fold_tolerance = if relative.is_finite() && relative > 0.0 {
            relative
        } else {
            0.0
        };
    }

    /// The solves of wheel columns on folded blocks that were reused (statistics).
    pub fn column_reuse_count(&self) -> u64 {
        self.column_reused
    }

    /// The factorisations of folded blocks reused from an earlier update with the same A and
    /// the same folded wheels' stiffnesses (statistics).
    pub fn fold_reuse_count(&self) -> u64 {
        self.fold_reused
    }
}

/// Whether `value` is within `tolerance` (relative) of the value with bits `bits`.
impl CapacitanceWork {
    /// For the wheel at position `c` of the last update's `active`: the ratio of the diagonal
    /// addition its block was factorised with to its own, s g v / compliance (1 unless the
    /// wheel was folded into a factorisation kept within the fold tolerance). The state of
    /// that update holds the step equation with the folded wheel's force increment
    /// `ratio × df[c]` (the chord's stiffness), not `df[c]` (its own tangent's).
    pub fn fold_ratio(&self, c: usize) -> f64 {
        if !self.folded.get(c).copied().unwrap_or(false) {
            return 1.0;
        }
        let (d, at) = self.fold_slot[c];
        let used = f64::from_bits(self.fold_key[d].1[at].1);
        used / self.fold_add[d][at].1
    }
}

fn within(value: f64, bits: u64, tolerance: f64) -> bool {
    let stored = f64::from_bits(bits);
    tolerance > 0.0 && (value - stored).abs() <= tolerance * stored.abs()
}

/// A wheel's A_c⁻¹ĝ on a folded block (block positions in block order), kept with what it was
/// solved from: the block, the generation of its factorisation and ĝ's entries on the block
/// (index and bits). A kept column is the one the solve would give (the same right-hand side
/// through the same factorisation: [`BandedLu::solve_interleaved`] treats every right-hand
/// side alike, bit for bit).
#[derive(Debug, Default, Clone)]
pub(super) struct FoldColumn {
    block: usize,
    generation: u64,
    input: Vec<(usize, u64)>,
    values: Vec<f64>,
}

impl FoldColumn {
    /// Whether this is the solve of ĝ (`g` on `pattern`) on block d with factorisation
    /// `generation` (never for generation 0).
    fn matches(
        &self,
        a: &BlockDiagonal,
        d: usize,
        generation: u64,
        g: &[f64],
        pattern: &[usize],
    ) -> bool {
        if generation == 0 || self.generation != generation || self.block != d {
            return false;
        }
        let mut stored = self.input.iter();
        for &i in pattern {
            if a.banded_block(i).is_some_and(|(b, _)| b == d) {
                match stored.next() {
                    Some(&(si, bits)) if si == i && bits == g[i].to_bits() => {}
                    _ => return false,
                }
            }
        }
        stored.next().is_none()
    }

    /// Keeps `solved`'s entries on block d (indices `indices`) as the solve of ĝ.
    #[allow(clippy::too_many_arguments)]
    fn set(
        &mut self,
        a: &BlockDiagonal,
        d: usize,
        generation: u64,
        g: &[f64],
        pattern: &[usize],
        indices: &[usize],
        solved: &[f64],
    ) {
        self.block = d;
        self.generation = generation;
        self.input.clear();
        self.input.extend(
            pattern
                .iter()
                .filter(|&&i| a.banded_block(i).is_some_and(|(b, _)| b == d))
                .map(|&i| (i, g[i].to_bits())),
        );
        self.values.clear();
        self.values.extend(indices.iter().map(|&i| solved[i]));
    }
}
