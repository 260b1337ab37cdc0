//! Backward (implicit) Euler, `y_{n+1} = y_n + h f(t_{n+1}, y_{n+1})`, fixed step, solved by
//! Newton's method with the Jacobian evaluated once per step at `(t_n, y_n)`
//! (Hairer–Wanner II, §IV.3; L-stable, order 1).

use super::linalg::evaluate_jacobian;
use super::{
    OdeOptions, OdeStepper, OdeSystem, check_interpolation_range, check_state, hermite_interpolate,
    limit_step, rms_norm,
};
use crate::error::IntegrateError;
use crate::lu::DenseLu;
use crate::stats::Stats;
use faer::Mat;

const MAX_NEWTON: usize = 10;

/// Backward Euler stepper (see the module documentation). The Newton iteration stops when the
/// scaled increment `‖Δ‖/(atol + rtol|y|)` is below `max(10ε/rtol, min(0.03, √rtol))` and, once
/// a contraction rate `r` is known, `r/(1 − r)‖Δ‖` is below the same bound.
#[derive(Debug)]
pub struct BackwardEuler {
    rtol: f64,
    atol: f64,
    newton_tol: f64,
    h: f64,
    h_cap: f64,
    max_step: f64,
    max_steps: usize,
    t_stop: Option<f64>,
    t: f64,
    t_prev: f64,
    y: Vec<f64>,
    y_prev: Vec<f64>,
    f: Vec<f64>,
    f_prev: Vec<f64>,
    residual: Vec<f64>,
    scale: Vec<f64>,
    work: [Vec<f64>; 2],
    jac: Mat<f64>,
    lu: DenseLu<f64>,
    stats: Stats,
}

impl BackwardEuler {
    /// Needs `options.fixed_step`; `rtol`/`atol` set the Newton stopping test.
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        options.validate()?;
        let v = || vec![0.0; dim];
        Ok(Self {
            rtol: options.rtol,
            atol: options.atol,
            newton_tol: (10.0 * f64::EPSILON / options.rtol).max(0.03f64.min(options.rtol.sqrt())),
            h: options.required_fixed_step("backward_euler")?,
            h_cap: f64::INFINITY,
            max_step: options.max_step,
            max_steps: options.max_steps,
            t_stop: None,
            t: 0.0,
            t_prev: 0.0,
            y: v(),
            y_prev: v(),
            f: v(),
            f_prev: v(),
            residual: v(),
            scale: v(),
            work: [v(), v()],
            jac: Mat::zeros(dim, dim),
            lu: DenseLu::new(dim),
            stats: Stats::default(),
        })
    }

    /// Factorise `I − h J` at `(t_n, y_n)`.
    fn prepare_newton_matrix(
        &mut self,
        sys: &mut dyn OdeSystem,
        h: f64,
    ) -> Result<(), IntegrateError> {
        let n = self.y.len();
        let [w0, w1] = &mut self.work;
        evaluate_jacobian(
            sys,
            self.t_prev,
            &self.y_prev,
            &self.f_prev,
            w0,
            w1,
            &mut self.jac,
        );
        self.stats.jacobian_evals += 1;
        {
            let mut m = self.lu.matrix_mut();
            for j in 0..n {
                for i in 0..n {
                    m[(i, j)] = -h * self.jac[(i, j)];
                }
                m[(j, j)] += 1.0;
            }
        }
        self.stats.lu_decompositions += 1;
        if self.lu.factor() {
            Ok(())
        } else {
            Err(IntegrateError::SingularMatrix { t: self.t_prev })
        }
    }
}

impl OdeStepper for BackwardEuler {
    fn name(&self) -> &'static str {
        "backward_euler"
    }

    fn set_state(
        &mut self,
        sys: &mut dyn OdeSystem,
        t: f64,
        y: &[f64],
    ) -> Result<(), IntegrateError> {
        check_state(sys, self.y.len(), t, y)?;
        self.t = t;
        self.t_prev = t;
        self.y.copy_from_slice(y);
        self.y_prev.copy_from_slice(y);
        sys.rhs(t, y, &mut self.f);
        self.stats.f_evals += 1;
        self.f_prev.copy_from_slice(&self.f);
        Ok(())
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        let h = limit_step(self.t, self.h, self.h_cap.min(self.max_step), self.t_stop);
        std::mem::swap(&mut self.y, &mut self.y_prev);
        std::mem::swap(&mut self.f, &mut self.f_prev);
        self.t_prev = self.t;
        let t_new = self.t_prev + h;
        self.prepare_newton_matrix(sys, h)?;
        let n = self.y.len();
        // Explicit Euler predictor.
        for i in 0..n {
            self.y[i] = self.y_prev[i] + h * self.f_prev[i];
            self.scale[i] = self.atol + self.rtol * self.y_prev[i].abs();
        }
        let mut norm_old: Option<f64> = None;
        let mut converged = false;
        let mut norm = f64::INFINITY;
        for _ in 0..MAX_NEWTON {
            sys.rhs(t_new, &self.y, &mut self.f);
            self.stats.f_evals += 1;
            self.stats.newton_iterations += 1;
            // Newton: (I − hJ) Δ = −(y − y_n − h f(t_{n+1}, y)).
            for i in 0..n {
                self.residual[i] = self.y_prev[i] + h * self.f[i] - self.y[i];
            }
            self.lu.solve_in_place(&mut self.residual);
            for i in 0..n {
                self.y[i] += self.residual[i];
            }
            norm = rms_norm(&self.residual, &self.scale);
            if !norm.is_finite() {
                break;
            }
            let rate = norm_old.map(|old| norm / old);
            let small = match rate {
                Some(r) if r < 1.0 => r / (1.0 - r) * norm < self.newton_tol,
                Some(_) => false,
                None => norm < 1e-3 * self.newton_tol,
            };
            if norm == 0.0 || small {
                converged = true;
                break;
            }
            norm_old = Some(norm);
        }
        if !converged {
            return Err(IntegrateError::NewtonFailed {
                t: self.t_prev,
                iterations: MAX_NEWTON,
                residual: norm,
            });
        }
        self.t = t_new;
        sys.rhs(self.t, &self.y, &mut self.f);
        self.stats.f_evals += 1;
        self.stats.steps += 1;
        Ok(())
    }

    fn t(&self) -> f64 {
        self.t
    }

    fn y(&self) -> &[f64] {
        &self.y
    }

    fn t_prev(&self) -> f64 {
        self.t_prev
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), IntegrateError> {
        check_interpolation_range(t, self.t_prev, self.t)?;
        hermite_interpolate(
            t,
            self.t_prev,
            self.t - self.t_prev,
            (&self.y_prev, &self.f_prev),
            (&self.y, &self.f),
            out,
        );
        Ok(())
    }

    stepper_bookkeeping!();
}
