//! The sensitivity dF_n/dδ of a converged normal solution (module documentation of
//! [`super`]): preconditioned CG on the contact set.

use super::NormalSolver;
use super::active_set::{mask, masked_dot};
use crate::error::ContactError;
use crate::linalg::dot;
use crate::operator::InfluenceOperator;

impl<A: InfluenceOperator> NormalSolver<A> {
    /// dF_n/dδ from A_CC x = 1_C by preconditioned CG (see the module documentation).
    pub(super) fn sensitivity(
        &mut self,
        in_contact: &[bool],
        tol: f64,
        max_iter: usize,
    ) -> Result<(f64, usize), ContactError> {
        let n = self.grid().len();
        let area = self.grid().element_area();
        let w = &mut self.work;
        w.active.copy_from_slice(in_contact);
        // x in w.p's place would destroy the solution; use r/z/v/q and u as scratch, x in r_prev.
        let x = &mut w.r_prev;
        match &self.previous_sensitivity {
            Some(prev) if prev.len() == n => {
                x.copy_from_slice(prev);
                mask(x, &w.active);
            }
            _ => x.fill(0.0),
        }
        // r = 1 − A x on C.
        self.operator.apply(&self.work.r_prev, &mut self.work.q);
        self.convolutions += 1;
        let w = &mut self.work;
        let count = w.active.iter().filter(|&&a| a).count() as f64;
        for i in 0..n {
            w.r[i] = if w.active[i] { 1.0 - w.q[i] } else { 0.0 };
        }
        let norm0 = count.sqrt();
        // x out of the work space for the iteration (no allocation), back afterwards.
        let mut x = std::mem::take(&mut self.work.r_prev);
        let iterations = self.cg_on_set(&mut x, None, norm0, tol, max_iter);
        self.work.r_prev = x;
        let iterations = iterations?;
        let w = &self.work;
        let dfn = area * w.r_prev.iter().sum::<f64>();
        self.previous_sensitivity = Some(w.r_prev.clone());
        Ok((dfn, iterations))
    }
}

impl<A: InfluenceOperator> NormalSolver<A> {
    /// Solves A_CC y = b_C on the contact set C = `in_contact` by preconditioned CG, starting
    /// from `y` (masked to C), to ‖b_C − A_CC y‖ ≤ `tol` ‖b_C‖; `y` is zero outside C on
    /// return and `displacement` holds A y on the whole grid (accumulated by the iteration
    /// from its products, no extra product). Used by the reuse model of [`crate::law::BemLaw`] (the responses of the
    /// pressure to gap changes on a frozen contact set, references.md §C8.4). Leaves the last
    /// solution (the warm start of the next solve) untouched. Returns the CG iterations.
    pub fn solve_on_set(
        &mut self,
        in_contact: &[bool],
        rhs: &[f64],
        y: &mut [f64],
        displacement: &mut [f64],
        tol: f64,
        max_iter: usize,
    ) -> Result<usize, ContactError> {
        self.check_len("in_contact", in_contact.len())?;
        self.check_len("rhs", rhs.len())?;
        self.check_len("y", y.len())?;
        self.check_len("displacement", displacement.len())?;
        let n = in_contact.len();
        let w = &mut self.work;
        // The warm-start vectors p and u are not touched: scratch r, z, v, q and active.
        w.active.copy_from_slice(in_contact);
        mask(y, &w.active);
        self.operator.apply(y, &mut self.work.q);
        self.convolutions += 1;
        let w = &mut self.work;
        displacement.copy_from_slice(&w.q);
        let mut norm0 = 0.0;
        for i in 0..n {
            w.r[i] = if w.active[i] {
                norm0 += rhs[i] * rhs[i];
                rhs[i] - w.q[i]
            } else {
                0.0
            };
        }
        let norm0 = norm0.sqrt();
        self.cg_on_set(y, Some(displacement), norm0, tol, max_iter)
    }

    /// The preconditioned CG iteration on the contact set `work.active` shared by
    /// [`Self::sensitivity`] and [`Self::solve_on_set`]: from the residual in `work.r` (zero
    /// outside the set) of initial norm `norm0`, until ‖r‖ ≤ `tol` `norm0`; `y` += α v and,
    /// when given, `displacement` += α A v at every iteration. Returns the iterations.
    fn cg_on_set(
        &mut self,
        y: &mut [f64],
        mut displacement: Option<&mut [f64]>,
        norm0: f64,
        tol: f64,
        max_iter: usize,
    ) -> Result<usize, ContactError> {
        let n = y.len();
        let mut rz_prev = 0.0;
        let mut iterations = 0;
        loop {
            let w = &self.work;
            let rnorm = dot(&w.r, &w.r).sqrt();
            if rnorm <= tol * norm0 || norm0 == 0.0 {
                break;
            }
            if iterations >= max_iter {
                return Err(ContactError::SensitivityNotConverged {
                    iterations,
                    residual: rnorm / norm0,
                });
            }
            iterations += 1;
            self.operator.precondition(&self.work.r, &mut self.work.z);
            self.convolutions += 1;
            let w = &mut self.work;
            mask(&mut w.z, &w.active);
            let rz = dot(&w.r, &w.z);
            let beta = if rz_prev > 0.0 { rz / rz_prev } else { 0.0 };
            for i in 0..n {
                w.v[i] = w.z[i] + beta * w.v[i];
            }
            rz_prev = rz;
            self.operator.apply(&self.work.v, &mut self.work.q);
            self.convolutions += 1;
            let w = &mut self.work;
            let alpha = rz / masked_dot(&w.v, &w.q, &w.active);
            for i in 0..n {
                y[i] += alpha * w.v[i];
                if let Some(d) = displacement.as_deref_mut() {
                    d[i] += alpha * w.q[i];
                }
                if w.active[i] {
                    w.r[i] -= alpha * w.q[i];
                }
            }
        }
        Ok(iterations)
    }
}
