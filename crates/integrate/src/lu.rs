//! Dense LU factorisation `P A = L U` into preallocated storage, shared by the implicit
//! first-order methods (real and complex, Radau5) and the structural steppers: faer's
//! partial-pivoting kernels with an explicit workspace, so refactorising and solving do not
//! allocate (references.md §R4.1).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::traits::ComplexField;
use faer::{Mat, MatMut, MatRef, Par, c64};

use crate::IntegrateError;

/// Scalars the implicit methods factorise: real (`f64`) and complex (`c64`, Radau5).
pub trait LuScalar: ComplexField + Copy {
    /// Modulus, used to detect a singular pivot.
    fn modulus(self) -> f64;
}

impl LuScalar for f64 {
    fn modulus(self) -> f64 {
        self.abs()
    }
}

impl LuScalar for c64 {
    fn modulus(self) -> f64 {
        self.norm()
    }
}

/// An `n × n` LU factorisation `P A = L U` whose matrix, permutation and workspace are
/// allocated once; `factor` and `solve` do not allocate. Also used by `sim` for the dense
/// solves of the vehicle–bridge coupling.
pub struct DenseLu<T: LuScalar> {
    lu: Mat<T>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    workspace: MemBuffer,
}

impl<T: LuScalar> std::fmt::Debug for DenseLu<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DenseLu")
            .field("dim", &self.lu.nrows())
            .finish()
    }
}

impl<T: LuScalar> DenseLu<T> {
    /// Storage and workspace for an `n × n` matrix.
    pub fn new(n: usize) -> Self {
        let req = factor::lu_in_place_scratch::<usize, T>(n, n, Par::Seq, Default::default())
            .or(solve::solve_in_place_scratch::<usize, T>(n, 1, Par::Seq));
        Self {
            lu: Mat::zeros(n, n),
            perm: vec![0; n],
            perm_inv: vec![0; n],
            workspace: MemBuffer::new(req),
        }
    }

    /// The dimension n.
    pub fn dim(&self) -> usize {
        self.lu.nrows()
    }

    /// The matrix to be factorised; fill it, then call [`Self::factor`].
    pub fn matrix_mut(&mut self) -> MatMut<'_, T> {
        self.lu.as_mut()
    }

    /// Factorise in place. Returns `false` when a pivot is zero or non-finite (singular matrix).
    pub fn factor(&mut self) -> bool {
        let n = self.lu.nrows();
        let _ = factor::lu_in_place(
            self.lu.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            MemStack::new(&mut self.workspace),
            Default::default(),
        );
        (0..n).all(|i| {
            let p = self.lu[(i, i)].modulus();
            p > 0.0 && p.is_finite()
        })
    }

    /// Overwrite `rhs` with `A⁻¹ rhs`.
    pub fn solve_in_place(&mut self, rhs: &mut [T]) {
        let n = self.lu.nrows();
        let perm = PermRef::new_checked(&self.perm, &self.perm_inv, n);
        solve::solve_in_place(
            self.lu.as_ref(),
            self.lu.as_ref(),
            perm,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            Par::Seq,
            MemStack::new(&mut self.workspace),
        );
    }
}

impl<T: LuScalar> DenseLu<T> {
    /// Copy `a` and factorise it, rejecting a numerically singular matrix: a zero or
    /// non-finite pivot, or `min |U_ii| ≤ n·ε·max |U_ii|` (`t` is reported in the error).
    pub fn factorize(&mut self, a: MatRef<'_, T>, t: f64) -> Result<(), IntegrateError> {
        self.lu.copy_from(a);
        self.factor();
        let n = self.lu.nrows();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for i in 0..n {
            let p = self.lu[(i, i)].modulus();
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if n > 0 && !(lo.is_finite() && hi.is_finite() && lo > (n as f64) * f64::EPSILON * hi) {
            return Err(IntegrateError::SingularMatrix { t });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3×3 system with known solution, real and complex: residual at round-off level
    /// (tolerance 1e-13: condition number of the matrix is below 10).
    #[test]
    fn lu_solves_real_and_complex_systems() {
        let a = [[4.0, 1.0, 0.5], [1.0, 3.0, -1.0], [0.5, -1.0, 5.0]];
        let x = [1.0, -2.0, 0.25];
        let mut lu = DenseLu::<f64>::new(3);
        let mut b = [0.0; 3];
        for i in 0..3 {
            for j in 0..3 {
                lu.matrix_mut()[(i, j)] = a[i][j];
                b[i] += a[i][j] * x[j];
            }
        }
        assert!(lu.factor());
        lu.solve_in_place(&mut b);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-13);
        }
        let shift = c64::new(0.5, 2.0);
        let mut luc = DenseLu::<c64>::new(3);
        let xc = [c64::new(1.0, 1.0), c64::new(0.0, -1.0), c64::new(2.0, 0.5)];
        let mut bc = [c64::new(0.0, 0.0); 3];
        for i in 0..3 {
            for j in 0..3 {
                let aij = c64::new(a[i][j], 0.0) + if i == j { shift } else { c64::new(0.0, 0.0) };
                luc.matrix_mut()[(i, j)] = aij;
                bc[i] += aij * xc[j];
            }
        }
        assert!(luc.factor());
        luc.solve_in_place(&mut bc);
        for i in 0..3 {
            assert!((bc[i] - xc[i]).norm() < 1e-13);
        }
    }

    #[test]
    fn singular_matrix_is_reported() {
        let mut lu = DenseLu::<f64>::new(2);
        lu.matrix_mut()[(0, 0)] = 1.0;
        lu.matrix_mut()[(0, 1)] = 2.0;
        lu.matrix_mut()[(1, 0)] = 2.0;
        lu.matrix_mut()[(1, 1)] = 4.0;
        assert!(!lu.factor());
    }
}
