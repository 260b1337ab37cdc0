//! Variable-order (1–5), variable-step BDF in backward-difference form with quasi-constant
//! step size: the formulation of Shampine & Reichelt's `ode15s` (SIAM J. Sci. Comput. 18, 1997)
//! as also used by scipy's `BDF`, here with the NDF coefficients κ = 0, i.e. the classical BDF.
//!
//! * History: the backward differences `D_j = ∇^j y_n` (j = 0..k) on a grid of spacing `h`.
//!   A step change by the factor `ρ` rescales them as `D ← (R(ρ) U)ᵀ D` (interpolating polynomial
//!   re-evaluated on the new grid).
//! * Step `k`: predictor `y⁽⁰⁾ = Σ_{j≤k} D_j`; corrector `(I − c J) Δ = c f(t, y) − ψ − d`
//!   with `c = h/α_k`, `α_k = γ_k = Σ_{j=1}^{k} 1/j`, `ψ = Σ_{j=1}^{k} γ_j D_j / α_k`,
//!   `d = y − y⁽⁰⁾` (simplified Newton, at most 4 iterations, Jacobian refreshed only on failure).
//! * Local error `‖d‖/(k + 1)`; step ratio `0.9 · err^{−1/(k+1)}` with a Newton-effort safety
//!   factor; order k ± 1 chosen after k + 1 steps of equal size from the error estimates
//!   `∇^k y/k` and `∇^{k+2} y/(k + 2)`.
//! * Dense output: the interpolating polynomial `y_n + Σ_j D_j Π_{m<j} (t − t_n + m h)/((m+1) h)`.
//!
//! Fixed-step mode (`options.fixed_step = Some(h)`, order `options.order`) keeps h and k
//! constant; its first k steps are classic RK4 steps of size h (each made of 4 sub-steps of
//! h/4, local error O(h⁵)), which supply the k starting values without lowering the order.

use super::explicit::rk4_step;
use super::linalg::evaluate_jacobian;
use super::{
    OdeOptions, OdeStepper, OdeSystem, check_interpolation_range, check_state, limit_step, rms_norm,
};
use crate::error::IntegrateError;
use crate::lu::DenseLu;
use crate::ode::eval_rhs;
use crate::stats::Stats;
use faer::Mat;

const MAX_ORDER: usize = 5;
const NEWTON_MAXITER: usize = 4;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;

/// `γ_k = Σ_{j=1}^{k} 1/j` (γ₀ = 0): with κ = 0 also `α_k`.
fn gamma(k: usize) -> f64 {
    (1..=k).map(|j| 1.0 / j as f64).sum()
}

/// Error constant of BDF-k in this form, `1/(k + 1)`.
fn error_const(k: usize) -> f64 {
    1.0 / (k + 1) as f64
}

/// `R(ρ)` of Shampine–Reichelt: `R_ij = Π_{m=1}^{i} (m − 1 − ρ j)/m` (row 0 = 1), size (k+1)².
#[allow(clippy::needless_range_loop)]
fn compute_r(order: usize, factor: f64, out: &mut [[f64; MAX_ORDER + 1]; MAX_ORDER + 1]) {
    for j in 0..=order {
        out[0][j] = 1.0;
    }
    for i in 1..=order {
        out[i][0] = 0.0;
        for j in 1..=order {
            out[i][j] = out[i - 1][j] * ((i as f64 - 1.0 - factor * j as f64) / i as f64);
        }
    }
}

/// Variable-order BDF stepper (see the module documentation).
#[derive(Debug)]
pub struct Bdf {
    rtol: f64,
    atol: f64,
    newton_tol: f64,
    max_order: usize,
    fixed_step: Option<f64>,
    initial_step: Option<f64>,
    max_step: f64,
    max_steps: usize,
    h_cap: f64,
    t_stop: Option<f64>,
    t: f64,
    t_prev: f64,
    h_abs: f64,
    order: usize,
    n_equal_steps: usize,
    /// Starting steps still to take in fixed-step mode.
    starter_steps_left: usize,
    d: Vec<Vec<f64>>,
    d_tmp: Vec<Vec<f64>>,
    y_predict: Vec<f64>,
    y_new: Vec<f64>,
    psi: Vec<f64>,
    corr: Vec<f64>,
    dy: Vec<f64>,
    f: Vec<f64>,
    scale: Vec<f64>,
    work: Vec<Vec<f64>>,
    jac: Mat<f64>,
    lu: DenseLu<f64>,
    lu_valid: bool,
    stats: Stats,
}

impl Bdf {
    /// `options.order` is the maximum order (adaptive) or the order (fixed step), default 5.
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        options.validate()?;
        let max_order = options.order.unwrap_or(MAX_ORDER);
        if !(1..=MAX_ORDER).contains(&max_order) {
            return Err(super::invalid(
                "order",
                format!("BDF order must be in 1..=5, got {max_order}"),
            ));
        }
        let newton_tol = (10.0 * f64::EPSILON / options.rtol).max(0.03f64.min(options.rtol.sqrt()));
        let v = || vec![0.0; dim];
        Ok(Self {
            rtol: options.rtol,
            atol: options.atol,
            newton_tol,
            max_order,
            fixed_step: options.fixed_step,
            initial_step: options.initial_step,
            max_step: options.max_step,
            max_steps: options.max_steps,
            h_cap: f64::INFINITY,
            t_stop: None,
            t: 0.0,
            t_prev: 0.0,
            h_abs: 0.0,
            order: 1,
            n_equal_steps: 0,
            starter_steps_left: 0,
            d: (0..MAX_ORDER + 3).map(|_| v()).collect(),
            d_tmp: (0..MAX_ORDER + 2).map(|_| v()).collect(),
            y_predict: v(),
            y_new: v(),
            psi: v(),
            corr: v(),
            dy: v(),
            f: v(),
            scale: v(),
            work: (0..5).map(|_| v()).collect(),
            jac: Mat::zeros(dim, dim),
            lu: DenseLu::new(dim),
            lu_valid: false,
            stats: Stats::default(),
        })
    }

    /// Current order k.
    pub fn order(&self) -> usize {
        self.order
    }

    fn h_limit(&self) -> f64 {
        self.h_cap.min(self.max_step)
    }

    /// Rescale the differences for a step change `h → factor·h`: `D ← (R(factor) U)ᵀ D`.
    fn change_d(&mut self, factor: f64) {
        let k = self.order;
        let mut r = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
        let mut u = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
        compute_r(k, factor, &mut r);
        compute_r(k, 1.0, &mut u);
        let mut ru = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
        for i in 0..=k {
            for j in 0..=k {
                ru[i][j] = (0..=k).map(|m| r[i][m] * u[m][j]).sum();
            }
        }
        for (j, row) in self.d_tmp.iter_mut().enumerate().take(k + 1) {
            row.fill(0.0);
            for (m, ru_row) in ru.iter().enumerate().take(k + 1) {
                let c = ru_row[j];
                for (x, dm) in row.iter_mut().zip(&self.d[m]) {
                    *x += c * dm;
                }
            }
        }
        for j in 0..=k {
            std::mem::swap(&mut self.d[j], &mut self.d_tmp[j]);
        }
        self.n_equal_steps = 0;
        self.lu_valid = false;
    }

    /// scipy's `select_initial_step` for order 1: `h = min(100 h₀, (0.01/max(‖f‖, ‖f'‖))^{1/2})`.
    fn initial_step_size(&mut self, sys: &mut dyn OdeSystem) -> Result<f64, IntegrateError> {
        let n = self.f.len();
        for i in 0..n {
            self.scale[i] = self.atol + self.rtol * self.d[0][i].abs();
        }
        let d0 = rms_norm(&self.d[0], &self.scale);
        let d1 = rms_norm(&self.f, &self.scale);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        for i in 0..n {
            self.work[0][i] = self.d[0][i] + h0 * self.f[i];
        }
        let (a, b) = self.work.split_at_mut(1);
        eval_rhs(sys, self.t + h0, &a[0], &mut b[0])?;
        self.stats.f_evals += 1;
        for i in 0..n {
            self.work[2][i] = self.work[1][i] - self.f[i];
        }
        let d2 = rms_norm(&self.work[2], &self.scale) / h0;
        let h1 = if d1 <= 1e-15 && d2 <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).sqrt()
        };
        Ok((100.0 * h0).min(h1).min(self.h_limit()))
    }

    fn compute_jacobian(&mut self, sys: &mut dyn OdeSystem, t: f64) -> Result<(), IntegrateError> {
        eval_rhs(sys, t, &self.y_predict, &mut self.f)?;
        self.stats.f_evals += 1;
        let (a, b) = self.work.split_at_mut(1);
        evaluate_jacobian(
            sys,
            t,
            &self.y_predict,
            &self.f,
            &mut a[0],
            &mut b[0],
            &mut self.jac,
        )?;
        self.stats.jacobian_evals += 1;
        Ok(())
    }

    fn factor_iteration_matrix(&mut self, c: f64) -> bool {
        let n = self.f.len();
        {
            let mut m = self.lu.matrix_mut();
            for j in 0..n {
                for i in 0..n {
                    m[(i, j)] = -c * self.jac[(i, j)];
                }
                m[(j, j)] += 1.0;
            }
        }
        self.stats.lu_decompositions += 1;
        self.lu_valid = self.lu.factor();
        self.lu_valid
    }

    /// Simplified Newton on `y − c f(t, y) − ψ_… = 0` from the predictor (scipy's
    /// `solve_bdf_system`): stop when `rate/(1 − rate)·‖Δ‖ < tol`, give up when the rate is
    /// ≥ 1 or the predicted final increment is too large. Returns (converged, iterations).
    fn solve_corrector(
        &mut self,
        sys: &mut dyn OdeSystem,
        t_new: f64,
        c: f64,
    ) -> Result<(bool, usize), IntegrateError> {
        let n = self.f.len();
        self.corr.fill(0.0);
        self.y_new.copy_from_slice(&self.y_predict);
        let mut dy_norm_old: Option<f64> = None;
        let mut iterations = 0;
        for k in 0..NEWTON_MAXITER {
            iterations = k + 1;
            eval_rhs(sys, t_new, &self.y_new, &mut self.f)?;
            self.stats.f_evals += 1;
            self.stats.newton_iterations += 1;
            if self.f.iter().any(|v| !v.is_finite()) {
                return Ok((false, iterations));
            }
            for i in 0..n {
                self.dy[i] = c * self.f[i] - self.psi[i] - self.corr[i];
            }
            self.lu.solve_in_place(&mut self.dy);
            let dy_norm = rms_norm(&self.dy, &self.scale);
            let rate = dy_norm_old.map(|old| dy_norm / old);
            if let Some(r) = rate
                && (r >= 1.0
                    || r.powi((NEWTON_MAXITER - k) as i32) / (1.0 - r) * dy_norm > self.newton_tol)
            {
                return Ok((false, iterations));
            }
            for i in 0..n {
                self.y_new[i] += self.dy[i];
                self.corr[i] += self.dy[i];
            }
            if dy_norm == 0.0 || rate.is_some_and(|r| r / (1.0 - r) * dy_norm < self.newton_tol) {
                return Ok((true, iterations));
            }
            if !dy_norm.is_finite() {
                return Ok((false, iterations));
            }
            dy_norm_old = Some(dy_norm);
        }
        Ok((false, iterations))
    }

    /// Predictor, ψ and scale for the current order and step.
    fn predict(&mut self) {
        let k = self.order;
        let alpha = gamma(k);
        for i in 0..self.f.len() {
            let mut yp = 0.0;
            let mut psi = 0.0;
            for j in 0..=k {
                yp += self.d[j][i];
                if j >= 1 {
                    psi += gamma(j) * self.d[j][i];
                }
            }
            self.y_predict[i] = yp;
            self.psi[i] = psi / alpha;
            self.scale[i] = self.atol + self.rtol * yp.abs();
        }
    }

    /// Update the differences after an accepted step with correction `d`.
    fn update_differences(&mut self) {
        let k = self.order;
        for i in 0..self.f.len() {
            self.d[k + 2][i] = self.corr[i] - self.d[k + 1][i];
            self.d[k + 1][i] = self.corr[i];
        }
        for j in (0..=k).rev() {
            let (lo, hi) = self.d.split_at_mut(j + 1);
            for (a, b) in lo[j].iter_mut().zip(&hi[0]) {
                *a += b;
            }
        }
    }

    /// Order and step selection after k + 1 equal steps (scipy/ode15s rule).
    fn select_order_and_step(&mut self, error_norm: f64, safety: f64) {
        let k = self.order;
        let n = self.f.len();
        let norm_of = |row: &[f64], c: f64, scale: &[f64]| {
            (row.iter()
                .zip(scale)
                .map(|(v, s)| (c * v / s).powi(2))
                .sum::<f64>()
                / n.max(1) as f64)
                .sqrt()
        };
        let error_m = if k > 1 {
            norm_of(&self.d[k], error_const(k - 1), &self.scale)
        } else {
            f64::INFINITY
        };
        let error_p = if k < self.max_order {
            norm_of(&self.d[k + 2], error_const(k + 1), &self.scale)
        } else {
            f64::INFINITY
        };
        let norms = [error_m, error_norm, error_p];
        // Step ratios for orders k − 1, k, k + 1 (exponents 1/k, 1/(k+1), 1/(k+2)); the first
        // maximum wins.
        let mut best = (0usize, f64::NEG_INFINITY);
        for (idx, e) in norms.iter().enumerate() {
            let factor = if *e == 0.0 {
                f64::INFINITY
            } else {
                e.powf(-1.0 / (k + idx) as f64)
            };
            if factor > best.1 {
                best = (idx, factor);
            }
        }
        self.order = (k + best.0) - 1;
        let factor = (safety * best.1).min(MAX_FACTOR);
        self.h_abs *= factor;
        self.change_d(factor);
    }

    /// One classic RK4 starting step of size h (4 sub-steps of h/4) in fixed-step mode; rebuilds
    /// the differences from the stored points so that the dense output is their interpolant.
    /// `d_tmp[j]` holds the point `y(t − j h)`.
    fn starter_step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        let h = self.h_abs;
        let n = self.f.len();
        let sub = h / 4.0;
        let taken = self.max_order - self.starter_steps_left;
        for j in (0..=taken).rev() {
            let (lo, hi) = self.d_tmp.split_at_mut(j + 1);
            hi[0].copy_from_slice(&lo[j]);
        }
        let mut ts = self.t;
        self.y_new.copy_from_slice(&self.d_tmp[1]);
        for _ in 0..4 {
            eval_rhs(sys, ts, &self.y_new, &mut self.f)?;
            let [w0, w1, w2, w3, w4] = &mut self.work[..] else {
                unreachable!("five work vectors")
            };
            rk4_step(sys, ts, sub, &self.y_new, &self.f, [w0, w1, w2, w3], w4)?;
            self.y_new.copy_from_slice(w4);
            ts += sub;
        }
        self.stats.f_evals += 16;
        self.d_tmp[0].copy_from_slice(&self.y_new);
        self.t_prev = self.t;
        self.t += h;
        self.starter_steps_left -= 1;
        let points = taken + 1;
        for j in 0..=points {
            self.d[j].copy_from_slice(&self.d_tmp[j]);
        }
        // Repeated differencing: afterwards d[j] = ∇^j y at the newest point.
        for level in 1..=points {
            for j in (level..=points).rev() {
                for i in 0..n {
                    self.d[j][i] = self.d[j - 1][i] - self.d[j][i];
                }
            }
        }
        self.order = points;
        for row in &mut self.d[points + 1..] {
            row.fill(0.0);
        }
        self.stats.steps += 1;
        Ok(())
    }
}

impl OdeStepper for Bdf {
    fn name(&self) -> &'static str {
        "bdf"
    }

    fn set_state(
        &mut self,
        sys: &mut dyn OdeSystem,
        t: f64,
        y: &[f64],
    ) -> Result<(), IntegrateError> {
        check_state(sys, self.f.len(), t, y)?;
        self.t = t;
        self.t_prev = t;
        for row in &mut self.d {
            row.fill(0.0);
        }
        self.d[0].copy_from_slice(y);
        eval_rhs(sys, t, y, &mut self.f)?;
        self.stats.f_evals += 1;
        self.order = 1;
        self.n_equal_steps = 0;
        self.lu_valid = false;
        if let Some(h) = self.fixed_step {
            self.h_abs = h;
            self.starter_steps_left = self.max_order;
            self.d_tmp[0].copy_from_slice(y);
            self.order = 0;
        } else {
            self.h_abs = match self.initial_step {
                Some(h) => h.min(self.h_limit()),
                None => self.initial_step_size(sys)?,
            };
            for i in 0..y.len() {
                self.d[1][i] = self.h_abs * self.f[i];
            }
        }
        // Jacobian at the initial point (scipy evaluates it once at the start).
        self.y_predict.copy_from_slice(y);
        self.compute_jacobian(sys, t)?;
        Ok(())
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        if self.starter_steps_left > 0 {
            self.starter_step(sys)?;
            if self.starter_steps_left == 0 {
                self.order = self.max_order;
                // d[order + 1] is unknown after the start; it only feeds the order selection,
                // which fixed-step mode does not use.
            }
            return Ok(());
        }
        let min_step = 10.0 * (self.t.abs() * f64::EPSILON).max(f64::MIN_POSITIVE);
        let mut current_jac = false;
        loop {
            let h_lim = limit_step(self.t, self.h_abs, self.h_limit(), self.t_stop);
            if h_lim != self.h_abs {
                let factor = h_lim / self.h_abs;
                self.h_abs = h_lim;
                self.change_d(factor);
            }
            if self.h_abs < min_step || !self.h_abs.is_finite() {
                return Err(IntegrateError::StepSizeTooSmall {
                    t: self.t,
                    h: self.h_abs,
                });
            }
            let t_new = self.t + self.h_abs;
            self.predict();
            let c = self.h_abs / gamma(self.order);
            let (converged, iterations) = loop {
                if !self.lu_valid && !self.factor_iteration_matrix(c) {
                    if current_jac {
                        break (false, 0);
                    }
                    self.compute_jacobian(sys, t_new)?;
                    current_jac = true;
                    continue;
                }
                let (ok, it) = self.solve_corrector(sys, t_new, c)?;
                if ok || current_jac {
                    break (ok, it);
                }
                self.compute_jacobian(sys, t_new)?;
                self.lu_valid = false;
                current_jac = true;
            };
            if !converged {
                if self.fixed_step.is_some() {
                    return Err(IntegrateError::NewtonFailed {
                        t: self.t,
                        iterations,
                        residual: f64::NAN,
                    });
                }
                self.stats.rejected_steps += 1;
                self.h_abs *= 0.5;
                self.change_d(0.5);
                continue;
            }
            let safety =
                0.9 * (2 * NEWTON_MAXITER + 1) as f64 / (2 * NEWTON_MAXITER + iterations) as f64;
            for i in 0..self.f.len() {
                self.scale[i] = self.atol + self.rtol * self.y_new[i].abs();
            }
            let error_norm = error_const(self.order) * rms_norm(&self.corr, &self.scale);
            if self.fixed_step.is_none() && error_norm > 1.0 {
                self.stats.rejected_steps += 1;
                let factor =
                    MIN_FACTOR.max(safety * error_norm.powf(-1.0 / (self.order + 1) as f64));
                self.h_abs *= factor;
                self.change_d(factor);
                continue;
            }
            // Accepted.
            self.n_equal_steps += 1;
            self.t_prev = self.t;
            self.t = t_new;
            self.stats.steps += 1;
            self.update_differences();
            if self.fixed_step.is_none() && self.n_equal_steps > self.order {
                self.select_order_and_step(error_norm, safety);
            }
            return Ok(());
        }
    }

    fn t(&self) -> f64 {
        self.t
    }

    fn y(&self) -> &[f64] {
        &self.d[0]
    }

    fn t_prev(&self) -> f64 {
        self.t_prev
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), IntegrateError> {
        check_interpolation_range(t, self.t_prev, self.t)?;
        out.copy_from_slice(&self.d[0]);
        let h = self.h_abs;
        let mut p = 1.0;
        for j in 0..self.order {
            let t_shift = self.t - h * j as f64;
            p *= (t - t_shift) / (h * (j + 1) as f64);
            for (o, dj) in out.iter_mut().zip(&self.d[j + 1]) {
                *o += dj * p;
            }
        }
        Ok(())
    }

    stepper_bookkeeping!();
}
