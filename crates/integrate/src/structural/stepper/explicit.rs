//! The explicit steps: Störmer–Verlet, leapfrog and explicit Newmark.

use super::super::StructuralSystem;
use super::super::sparse::sparse_mul_add;
use crate::IntegrateError;

use super::{StructuralStepper, finite_or_error};

impl StructuralStepper {
    /// Störmer–Verlet (`implicit_damping = true`) or leapfrog (`false`), see
    /// [`StructuralMethod::StormerVerlet`] and [`StructuralMethod::Leapfrog`].
    pub(super) fn kick_drift_kick<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
        implicit_damping: bool,
    ) -> Result<(), IntegrateError> {
        let t_new = self.t + dt;
        let w = &mut self.work;
        for (i, half) in w.half.iter_mut().enumerate() {
            *half = self.v[i] + 0.5 * dt * self.a[i];
            w.q_iter[i] = self.q[i] + dt * *half;
        }
        let c = if implicit_damping { 0.5 * dt } else { 0.0 };
        self.explicit_acceleration(problem, t_new, c)?;
        self.save_old_state(dt);
        for i in 0..self.q.len() {
            self.q[i] = self.work.q_iter[i];
            self.a[i] = self.work.residual[i];
            self.v[i] = self.work.half[i] + 0.5 * dt * self.a[i];
        }
        self.f_int.copy_from_slice(&self.work.f_int);
        self.t = t_new;
        self.stats.steps += 1;
        Ok(())
    }

    /// Explicit Newmark (β = 0): `q_{n+1} = q_n + Δt v_n + ½Δt² a_n`,
    /// `(M + γΔt C) a_{n+1} = f_ext(t_{n+1}) − f_int(q_{n+1}) − C ṽ`,
    /// `v_{n+1} = ṽ + γΔt a_{n+1}` with `ṽ = v_n + (1 − γ)Δt a_n` (Newmark 1959).
    pub(super) fn explicit_newmark<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
        gamma: f64,
    ) -> Result<(), IntegrateError> {
        let t_new = self.t + dt;
        for i in 0..self.q.len() {
            self.work.q_iter[i] = self.q[i] + dt * self.v[i] + 0.5 * dt * dt * self.a[i];
            self.work.half[i] = self.v[i] + (1.0 - gamma) * dt * self.a[i];
        }
        self.explicit_acceleration(problem, t_new, gamma * dt)?;
        self.save_old_state(dt);
        for i in 0..self.q.len() {
            self.q[i] = self.work.q_iter[i];
            self.a[i] = self.work.residual[i];
            self.v[i] = self.work.half[i] + gamma * dt * self.a[i];
        }
        self.f_int.copy_from_slice(&self.work.f_int);
        self.t = t_new;
        self.stats.steps += 1;
        Ok(())
    }

    /// Solves `(M + c C) a = f_ext(t) − f_int(q) − C v` with `q = work.q_iter`,
    /// `v = work.half`; the result is left in `work.residual`, `f_int(q)` in `work.f_int`.
    fn explicit_acceleration<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        t: f64,
        c: f64,
    ) -> Result<(), IntegrateError> {
        let w = &mut self.work;
        problem.external_force(t, &mut w.f_ext);
        problem.internal_force(&w.q_iter, &mut w.f_int);
        self.stats.f_evals += 1;
        for i in 0..w.residual.len() {
            w.residual[i] = w.f_ext[i] - w.f_int[i];
        }
        let (Some(damping), Some(damping_sparse)) = (&self.damping, &self.damping_sparse) else {
            self.mass_lu.solve_in_place(&mut w.residual);
            return finite_or_error(&w.residual, t);
        };
        sparse_mul_add(damping_sparse.as_ref(), -1.0, &w.half, &mut w.residual);
        if c == 0.0 {
            self.mass_lu.solve_in_place(&mut w.residual);
            return finite_or_error(&w.residual, t);
        }
        if w.explicit_lu_c != Some(c) {
            let n = self.q.len();
            for j in 0..n {
                for i in 0..n {
                    w.k_eff[(i, j)] = self.mass[(i, j)] + c * damping[(i, j)];
                }
            }
            w.explicit_lu_c = None;
            w.explicit_lu.factorize(w.k_eff.as_ref(), t)?;
            w.explicit_lu_c = Some(c);
            self.stats.lu_decompositions += 1;
        }
        w.explicit_lu.solve_in_place(&mut w.residual);
        finite_or_error(&w.residual, t)
    }
}
