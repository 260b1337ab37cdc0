//! A structural system seen as a first-order system, so the methods of [`crate::ode`]
//! (RK4, DOPRI5, Radau5, BDF, …) can integrate it.

use faer::{Mat, MatMut};

use super::StructuralSystem;
use super::linalg::{check_matrix, mat_vec_add};
use crate::IntegrateError;
use crate::lu::DenseLu;
use crate::ode::OdeSystem;

/// `M q'' + C q' + f_int(q) = f_ext(t)` written as `y' = F(t, y)` with `y = [q, v]`:
///
/// ```text
/// q' = v,    v' = M⁻¹ (f_ext(t) − C v − f_int(q))
/// ∂F/∂y = [[0, I], [−M⁻¹ K_t, −M⁻¹ C]]
/// ```
///
/// `M` is factorised once, when the adapter is built. The Jacobian is analytic when the
/// problem provides its tangent stiffness, otherwise the first-order method's finite
/// differences are requested.
pub struct FirstOrderForm<P> {
    problem: P,
    mass_lu: DenseLu<f64>,
    damping: Option<Mat<f64>>,
    force: Vec<f64>,
    load: Vec<f64>,
    tangent: Mat<f64>,
    column: Vec<f64>,
}

impl<P: StructuralSystem> FirstOrderForm<P> {
    /// Wraps `problem`, checking and factorising its mass matrix (an error names `mass` or
    /// `damping`, or reports a singular `M` at t = 0).
    pub fn new(problem: P) -> Result<Self, IntegrateError> {
        let n = problem.dimension();
        let mass = problem.mass_matrix();
        check_matrix("mass", mass, n)?;
        if let Some(i) = (0..n).find(|&i| mass[(i, i)] <= 0.0) {
            return Err(IntegrateError::InvalidParameter {
                name: "mass",
                reason: format!("diagonal entry {i} is {} (must be > 0)", mass[(i, i)]),
            });
        }
        let mut mass_lu = DenseLu::new(n);
        mass_lu.factorize(mass, 0.0)?;
        let damping = problem.damping_matrix().map(|c| c.to_owned());
        if let Some(c) = &damping {
            check_matrix("damping", c.as_ref(), n)?;
        }
        Ok(Self {
            problem,
            mass_lu,
            damping,
            force: vec![0.0; n],
            load: vec![0.0; n],
            tangent: Mat::zeros(n, n),
            column: vec![0.0; n],
        })
    }

    /// The wrapped structural problem.
    pub fn problem(&self) -> &P {
        &self.problem
    }

    /// The wrapped structural problem, mutably.
    pub fn problem_mut(&mut self) -> &mut P {
        &mut self.problem
    }

    /// Unwraps the structural problem.
    pub fn into_inner(self) -> P {
        self.problem
    }

    /// Number of structural degrees of freedom `n` (the first-order dimension is `2n`).
    fn n(&self) -> usize {
        self.force.len()
    }
}

impl<P: StructuralSystem> OdeSystem for FirstOrderForm<P> {
    fn dim(&self) -> usize {
        2 * self.n()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = self.n();
        let (q, v) = y.split_at(n);
        let (dq, dv) = dydt.split_at_mut(n);
        dq.copy_from_slice(v);
        self.problem.internal_force(q, &mut self.force);
        self.problem.external_force(t, &mut self.load);
        for ((a, f_ext), f_int) in dv.iter_mut().zip(&self.load).zip(&self.force) {
            *a = f_ext - f_int;
        }
        if let Some(c) = &self.damping {
            mat_vec_add(c.as_ref(), -1.0, v, dv);
        }
        self.mass_lu.solve_in_place(dv);
    }

    fn jacobian(&mut self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) -> bool {
        let n = self.n();
        if !self
            .problem
            .tangent_stiffness(&y[..n], self.tangent.as_mut())
        {
            return false;
        }
        jac.fill(0.0);
        for j in 0..n {
            jac[(j, n + j)] = 1.0;
            // Column j of −M⁻¹K_t and of −M⁻¹C.
            for (block, matrix) in [(0, Some(&self.tangent)), (n, self.damping.as_ref())] {
                let Some(matrix) = matrix else { continue };
                for (i, c) in self.column.iter_mut().enumerate() {
                    *c = -matrix[(i, j)];
                }
                self.mass_lu.solve_in_place(&mut self.column);
                for (i, &c) in self.column.iter().enumerate() {
                    jac[(n + i, block + j)] = c;
                }
            }
        }
        true
    }
}
