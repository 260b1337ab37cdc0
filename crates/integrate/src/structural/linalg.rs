//! Small dense helpers shared by the structural steppers (no allocation).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::{Mat, MatMut, MatRef, Par};

use crate::IntegrateError;

/// `out = A x` for a dense `A`.
pub(crate) fn mat_vec(a: MatRef<'_, f64>, x: &[f64], out: &mut [f64]) {
    for (i, o) in out.iter_mut().enumerate() {
        *o = (0..a.ncols()).map(|j| a[(i, j)] * x[j]).sum();
    }
}

/// `out += s · A x` for a dense `A`.
pub(crate) fn mat_vec_add(a: MatRef<'_, f64>, s: f64, x: &[f64], out: &mut [f64]) {
    for (i, o) in out.iter_mut().enumerate() {
        let ax: f64 = (0..a.ncols()).map(|j| a[(i, j)] * x[j]).sum();
        *o += s * ax;
    }
}

/// Maximum norm `‖x‖_∞`.
pub(crate) fn norm_inf(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Checks that `a` is `n × n` with finite entries; the error names the parameter.
pub(crate) fn check_matrix(
    name: &'static str,
    a: MatRef<'_, f64>,
    n: usize,
) -> Result<(), IntegrateError> {
    if a.nrows() != n || a.ncols() != n {
        return Err(IntegrateError::InvalidParameter {
            name,
            reason: format!("shape {}x{} (expected {n}x{n})", a.nrows(), a.ncols()),
        });
    }
    for j in 0..n {
        for i in 0..n {
            if !a[(i, j)].is_finite() {
                return Err(IntegrateError::InvalidParameter {
                    name,
                    reason: format!("entry ({i}, {j}) is {}", a[(i, j)]),
                });
            }
        }
    }
    Ok(())
}

/// Checks that `x` has length `n` and finite entries; the error names the parameter.
pub(crate) fn check_vector(name: &'static str, x: &[f64], n: usize) -> Result<(), IntegrateError> {
    if x.len() != n {
        return Err(IntegrateError::InvalidParameter {
            name,
            reason: format!("length {} (expected {n})", x.len()),
        });
    }
    if let Some(i) = x.iter().position(|v| !v.is_finite()) {
        return Err(IntegrateError::InvalidParameter {
            name,
            reason: format!("entry {i} is {}", x[i]),
        });
    }
    Ok(())
}

/// Dense LU factorisation with partial pivoting, `P A = L U`, with its own storage and
/// scratch memory, so refactorising and solving do not allocate (faer's low-level kernels
/// `lu_in_place` / `solve_in_place`, rust-stack.md §4.1).
pub(crate) struct DenseLu {
    /// `L` (strictly lower part, unit diagonal implied) and `U` (upper part), packed.
    factors: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    scratch: MemBuffer,
}

impl DenseLu {
    /// Storage for `n × n` matrices.
    pub(crate) fn new(n: usize) -> Self {
        let factor_req =
            factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default());
        let solve_req = solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq);
        Self {
            factors: Mat::zeros(n, n),
            perm: (0..n).collect(),
            perm_inv: (0..n).collect(),
            scratch: MemBuffer::new(factor_req.or(solve_req)),
        }
    }

    /// Factorises `a`, rejecting a numerically singular matrix: a zero or non-finite pivot,
    /// or `min |U_ii| ≤ n·ε·max |U_ii|` (`t` is reported in the error).
    pub(crate) fn factorize(&mut self, a: MatRef<'_, f64>, t: f64) -> Result<(), IntegrateError> {
        self.factors.copy_from(a);
        factor::lu_in_place(
            self.factors.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        let n = self.factors.nrows();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for i in 0..n {
            let p = self.factors[(i, i)].abs();
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if n > 0 && !(lo.is_finite() && hi.is_finite() && lo > (n as f64) * f64::EPSILON * hi) {
            return Err(IntegrateError::SingularMatrix { t });
        }
        Ok(())
    }

    /// Solves `A x = b` in place (`rhs` holds `b` on entry and `x` on exit).
    pub(crate) fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let n = rhs.len();
        let perm = PermRef::new_checked(&self.perm, &self.perm_inv, n);
        solve::solve_in_place(
            self.factors.as_ref(),
            self.factors.as_ref(),
            perm,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
    }
}
