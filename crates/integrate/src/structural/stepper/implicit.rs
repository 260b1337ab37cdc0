//! The implicit step: kinematic coefficients, the step equation, Newton's method and the
//! corrector.

use super::super::linalg::{check_vector, norm_inf};
use super::super::sparse::{for_rows, row_dot, rows_outside, sparse_mul_add_rows};
use super::super::{StepEquation, StructuralMethod, StructuralSystem};
use crate::IntegrateError;

use super::{StructuralStepper, check_step_size, finite_or_error};

/// Stopping rule of the Newton iteration on the step equation.
///
/// The iteration stops when the correction satisfies `‖Δq‖_∞ ≤ atol + rtol·‖q_{n+1}‖_∞`
/// (Newton converges quadratically, so the remaining error is far below that bound).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Maximum number of Newton iterations per step (≥ 1).
    pub max_iterations: usize,
    /// Relative tolerance `rtol` on the displacement correction (> 0).
    pub relative_tolerance: f64,
    /// Absolute tolerance `atol` on the displacement correction, in displacement units (≥ 0).
    pub absolute_tolerance: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            max_iterations: 25,
            relative_tolerance: 1e-10,
            absolute_tolerance: 1e-14,
        }
    }
}

impl NewtonOptions {
    pub(super) fn validate(&self) -> Result<(), IntegrateError> {
        let bad = |name, reason| Err(IntegrateError::InvalidParameter { name, reason });
        if self.max_iterations == 0 {
            return bad("max_iterations", "0 (must be ≥ 1)".to_string());
        }
        if !(self.relative_tolerance.is_finite() && self.relative_tolerance > 0.0) {
            return bad(
                "relative_tolerance",
                format!("{} (must be finite and > 0)", self.relative_tolerance),
            );
        }
        if !(self.absolute_tolerance.is_finite() && self.absolute_tolerance >= 0.0) {
            return bad(
                "absolute_tolerance",
                format!("{} (must be finite and ≥ 0)", self.absolute_tolerance),
            );
        }
        Ok(())
    }
}

/// Kinematic coefficients of one implicit step (module documentation of
/// [`structural`](super)): `q̃ = q_n + Δt v_n + q_a a_n`, `ṽ = v_n + v_a a_n`,
/// `q_{n+1} = q̃ + c_qa a_{n+1}`, `v_{n+1} = ṽ + c_va a_{n+1}`.
#[derive(Debug, Clone, Copy)]
struct Kinematics {
    q_a: f64,
    v_a: f64,
    c_qa: f64,
    c_va: f64,
    alpha_m: f64,
    alpha_f: f64,
    /// Step-change correction of the start acceleration, `(α_m − α_f)(Δt − Δt_prev)/Δt_prev`
    /// (0 for a constant step, for Newmark and for backward Euler).
    a_shift: f64,
}

/// The start acceleration of an entry with acceleration `a` (`a_n`), previous start
/// acceleration `a_prev` (`a*_{n−1}`) and step-change shift `shift` (`Kinematics::a_shift`). The algorithmic acceleration of HHT and
/// generalized-α approximates `q''(t_n + (α_m − α_f)Δt)` (Erlicher, Bonaventura & Bursi
/// 2002, *Comput. Mech.* 28:83–104), so after a step-size change it is moved to the new
/// shift with the slope `(a_n − a*_{n−1})/Δt_prev`, where `a*_{n−1}` is the start
/// acceleration of the previous step (so both ends carry the same shift):
/// `a*_n = a_n + (α_m − α_f)(Δt − Δt_prev)(a_n − a*_{n−1})/Δt_prev`. Without this the
/// methods drop to first order when Δt varies (measured in `tests/structural_order.rs`).
/// The extrapolation is applied only for step ratios `Δt/Δt_prev ∈ [½, 2]`: for larger
/// jumps it amplified stiff components (measured: gen-α ρ∞ = 0.5 became unstable under
/// repeated 10× changes), so such a step starts from `a_n` unchanged, which costs O(Δt)
/// in `a` at that step only.
#[inline(always)]
fn start_acceleration(a: f64, a_prev: f64, shift: f64) -> f64 {
    if shift == 0.0 {
        a
    } else {
        a + shift * (a - a_prev)
    }
}

impl StructuralStepper {
    /// The kinematic coefficients of the implicit scheme for step size `dt`.
    fn kinematics(&self, dt: f64) -> Result<Kinematics, IntegrateError> {
        if let Some(p) = self.method.alpha_parameters()
            && p.beta > 0.0
        {
            let a_shift = match self.dt_prev {
                Some(h) if h != dt && (0.5..=2.0).contains(&(dt / h)) => {
                    (p.alpha_m - p.alpha_f) * (dt - h) / h
                }
                _ => 0.0,
            };
            return Ok(Kinematics {
                q_a: dt * dt * (0.5 - p.beta),
                v_a: dt * (1.0 - p.gamma),
                c_qa: p.beta * dt * dt,
                c_va: p.gamma * dt,
                alpha_m: p.alpha_m,
                alpha_f: p.alpha_f,
                a_shift,
            });
        }
        if self.method == StructuralMethod::BackwardEuler {
            return Ok(Kinematics {
                q_a: 0.0,
                v_a: 0.0,
                c_qa: dt * dt,
                c_va: dt,
                alpha_m: 0.0,
                alpha_f: 0.0,
                a_shift: 0.0,
            });
        }
        Err(IntegrateError::InvalidParameter {
            name: "method",
            reason: format!(
                "`{}` is explicit and has no implicit step equation",
                self.method.name()
            ),
        })
    }

    /// The step equation of the step `t_n → t_n + dt` (see [`StepEquation`]). Only for the
    /// implicit methods (Newmark with β > 0, HHT, generalized-α, backward Euler).
    pub fn step_equation(&self, dt: f64) -> Result<StepEquation, IntegrateError> {
        let mut eq = StepEquation::default();
        self.step_equation_into(dt, &mut eq)?;
        Ok(eq)
    }

    /// As [`step_equation`](Self::step_equation), writing into `eq` (its vectors are reused, so
    /// no allocation after the first call).
    pub fn step_equation_into(&self, dt: f64, eq: &mut StepEquation) -> Result<(), IntegrateError> {
        check_step_size(dt)?;
        let k = self.kinematics(dt)?;
        let n = self.q.len();
        eq.t_old = self.t;
        eq.dt = dt;
        eq.t_new = self.t + dt;
        eq.t_force = eq.t_new - k.alpha_f * dt;
        eq.q_pred.resize(n, 0.0);
        eq.v_pred.resize(n, 0.0);
        eq.history_force.resize(n, 0.0);
        let mass = self.mass_sparse.as_ref();
        let (row_ptr, col_idx, mass_val) = (
            mass.symbolic().row_ptr(),
            mass.symbolic().col_idx(),
            mass.val(),
        );
        // Frozen DOFs (module `frozen`): at rest, their rows are not evaluated.
        eq.frozen_rows.clone_from(&self.frozen);
        for range in &self.frozen {
            eq.q_pred[range.clone()].copy_from_slice(&self.q[range.clone()]);
            eq.v_pred[range.clone()].fill(0.0);
            eq.history_force[range.clone()].fill(0.0);
        }
        // The predictors q̃ = q + Δt v + q_a a*, ṽ = v + v_a a* (a* the start acceleration).
        let (q, v, a, a_prev, f_int) = (&self.q, &self.v, &self.a, &self.a_prev, &self.f_int);
        let shift = k.a_shift;
        if shift == 0.0 {
            // a* = a (a constant step): the same operations over slices, M a by rows.
            for range in rows_outside(n, &self.frozen) {
                let rows = eq.q_pred[range.clone()]
                    .iter_mut()
                    .zip(&mut eq.v_pred[range.clone()])
                    .zip(&q[range.clone()])
                    .zip(&v[range.clone()])
                    .zip(&a[range.clone()]);
                for ((((qp, vp), &qi), &vi), &ai) in rows {
                    *qp = qi + dt * vi + k.q_a * ai;
                    *vp = vi + k.v_a * ai;
                }
                let history = &mut eq.history_force;
                for_rows(
                    mass,
                    history,
                    std::iter::once(range.clone()),
                    |cols, vals, h| {
                        *h = row_dot(cols, vals, a);
                    },
                );
                for (h, &f) in history[range.clone()].iter_mut().zip(&f_int[range]) {
                    *h = k.alpha_m * *h + k.alpha_f * f;
                }
            }
        } else {
            let start = |j: usize| start_acceleration(a[j], a_prev[j], shift);
            for range in rows_outside(n, &self.frozen) {
                for i in range {
                    let a0 = start(i);
                    eq.q_pred[i] = q[i] + dt * v[i] + k.q_a * a0;
                    eq.v_pred[i] = v[i] + k.v_a * a0;
                    let row = row_ptr[i]..row_ptr[i + 1];
                    let inertia: f64 = col_idx[row.clone()]
                        .iter()
                        .zip(&mass_val[row])
                        .map(|(&j, m)| m * start(j))
                        .sum();
                    eq.history_force[i] = k.alpha_m * inertia + k.alpha_f * f_int[i];
                }
            }
        }
        if let Some(c) = &self.damping_sparse {
            let rows = rows_outside(n, &self.frozen);
            sparse_mul_add_rows(c.as_ref(), k.alpha_f, &self.v, &mut eq.history_force, rows);
        }
        eq.displacement_per_acceleration = k.c_qa;
        eq.velocity_per_acceleration = k.c_va;
        eq.alpha_m = k.alpha_m;
        eq.alpha_f = k.alpha_f;
        eq.mass_coefficient = (1.0 - k.alpha_m) / k.c_qa;
        eq.damping_coefficient = (1.0 - k.alpha_f) * k.c_va / k.c_qa;
        eq.stiffness_coefficient = 1.0 - k.alpha_f;
        Ok(())
    }

    /// The corrector of an implicit step: given the solution `q_{n+1}` of the step equation
    /// for step size `dt`, sets `a_{n+1} = (q_{n+1} − q̃)/c_qa`, `v_{n+1} = ṽ + c_va a_{n+1}`,
    /// advances `t` and, for α_f ≠ 0, evaluates `f_int(q_{n+1})` (needed by the next step's
    /// history force; this is why the problem is passed).
    pub fn finish_step<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
        q_new: &[f64],
    ) -> Result<(), IntegrateError> {
        check_step_size(dt)?;
        let k = self.kinematics(dt)?;
        check_vector("q_new", q_new, self.q.len())?;
        self.check_problem(problem)?;
        self.save_old_state(dt);
        // Frozen DOFs keep their state (module `frozen`).
        // The predictors q̃ = q + Δt v + q_a a*, ṽ = v + v_a a* (a* the start acceleration).
        for range in rows_outside(q_new.len(), &self.frozen) {
            let rows = self.q[range.clone()]
                .iter_mut()
                .zip(&mut self.v[range.clone()])
                .zip(&mut self.a[range.clone()])
                .zip(&mut self.a_prev[range.clone()])
                .zip(&q_new[range]);
            for ((((q, v), a), a_prev), &qn) in rows {
                let a0 = start_acceleration(*a, *a_prev, k.a_shift);
                let q_pred = *q + dt * *v + k.q_a * a0;
                let v_pred = *v + k.v_a * a0;
                *a_prev = a0;
                *a = (qn - q_pred) / k.c_qa;
                *v = v_pred + k.c_va * *a;
                *q = qn;
            }
        }
        self.t += dt;
        self.dt_prev = Some(dt);
        if k.alpha_f != 0.0 {
            problem.internal_force(&self.q, &mut self.f_int);
            self.stats.f_evals += 1;
        }
        self.stats.steps += 1;
        Ok(())
    }

    pub(super) fn implicit_step<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
    ) -> Result<(), IntegrateError> {
        let mut eq = std::mem::take(&mut self.work.eq);
        let solved = self
            .step_equation_into(dt, &mut eq)
            .and_then(|()| self.newton_solve(problem, &eq));
        self.work.eq = eq;
        solved?;
        let q_new = std::mem::take(&mut self.work.q_iter);
        let finished = self.finish_step(problem, dt, &q_new);
        self.work.q_iter = q_new;
        finished
    }

    /// Newton's method on `R(q_{n+1}) = 0` from the guess `a_{n+1} = a_n`; the solution is
    /// left in `work.q_iter`. For a linear problem one step is exact.
    fn newton_solve<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        eq: &StepEquation,
    ) -> Result<(), IntegrateError> {
        let linear = problem.is_linear();
        problem.external_force(eq.t_force, &mut self.work.f_ext);
        for i in 0..self.q.len() {
            self.work.q_iter[i] = eq.q_pred[i] + eq.displacement_per_acceleration * self.a[i];
        }
        let mut residual_norm = f64::INFINITY;
        for _ in 0..self.newton.max_iterations {
            let w = &mut self.work;
            problem.internal_force(&w.q_iter, &mut w.f_int);
            self.stats.f_evals += 1;
            eq.residual(
                self.mass.as_ref(),
                self.damping.as_ref().map(|c| c.as_ref()),
                &w.q_iter,
                &w.f_int,
                &w.f_ext,
                &mut w.residual,
            )?;
            finite_or_error(&w.residual, eq.t_new)?;
            residual_norm = norm_inf(&w.residual);
            self.prepare_effective_matrix(problem, eq, linear)?;
            let w = &mut self.work;
            w.implicit_lu.solve_in_place(&mut w.residual);
            for (q, dq) in w.q_iter.iter_mut().zip(&w.residual) {
                *q -= dq;
            }
            finite_or_error(&w.q_iter, eq.t_new)?;
            self.stats.newton_iterations += 1;
            let tolerance = self.newton.absolute_tolerance
                + self.newton.relative_tolerance * norm_inf(&w.q_iter);
            if linear || norm_inf(&w.residual) <= tolerance {
                return Ok(());
            }
        }
        Err(IntegrateError::NewtonFailed {
            t: eq.t_new,
            iterations: self.newton.max_iterations,
            residual: residual_norm,
        })
    }

    /// Builds and factorises `K_eff` at `work.q_iter` (with `f_int(q_iter)` in `work.f_int`).
    /// For a linear problem the tangent is evaluated once and the LU reused while Δt is unchanged.
    fn prepare_effective_matrix<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        eq: &StepEquation,
        linear: bool,
    ) -> Result<(), IntegrateError> {
        let cached = self.work.implicit_lu_dt == Some(eq.dt);
        if linear && self.work.tangent_valid && cached {
            return Ok(());
        }
        if !(linear && self.work.tangent_valid) {
            self.evaluate_tangent(problem);
            self.work.tangent_valid = linear;
        }
        let w = &mut self.work;
        eq.effective_stiffness(
            self.mass.as_ref(),
            self.damping.as_ref().map(|c| c.as_ref()),
            w.tangent.as_ref(),
            w.k_eff.as_mut(),
        )?;
        w.implicit_lu_dt = None;
        w.implicit_lu.factorize(w.k_eff.as_ref(), eq.t_new)?;
        if linear {
            w.implicit_lu_dt = Some(eq.dt);
        }
        self.stats.lu_decompositions += 1;
        Ok(())
    }

    /// `K_t` at `work.q_iter` from the problem, or by forward differences
    /// `K_t e_j ≈ (f_int(q + h_j e_j) − f_int(q))/h_j`, `h_j = √ε · max(|q_j|, ‖q‖_∞, ‖q − q_n‖_∞)`.
    fn evaluate_tangent<P: StructuralSystem + ?Sized>(&mut self, problem: &mut P) {
        self.stats.jacobian_evals += 1;
        let w = &mut self.work;
        if problem.tangent_stiffness(&w.q_iter, w.tangent.as_mut()) {
            return;
        }
        let motion = w
            .q_iter
            .iter()
            .zip(&self.q)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        let scale = norm_inf(&w.q_iter).max(motion).max(f64::MIN_POSITIVE);
        w.q_fd.copy_from_slice(&w.q_iter);
        for j in 0..w.q_iter.len() {
            let q_j = w.q_iter[j];
            w.q_fd[j] = q_j + f64::EPSILON.sqrt() * q_j.abs().max(scale);
            let h = w.q_fd[j] - q_j;
            problem.internal_force(&w.q_fd, &mut w.f_fd);
            self.stats.f_evals += 1;
            for i in 0..w.f_fd.len() {
                w.tangent[(i, j)] = (w.f_fd[i] - w.f_int[i]) / h;
            }
            w.q_fd[j] = q_j;
        }
    }
}
