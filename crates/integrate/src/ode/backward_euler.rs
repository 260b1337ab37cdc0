//! Backward (implicit) Euler, `y_{n+1} = y_n + h f(t_{n+1}, y_{n+1})`, fixed step, solved by
//! Newton's method with the Jacobian evaluated once per step at `(t_n, y_n)`
//! (Hairer–Wanner II, §IV.3; L-stable, order 1).

use super::fixed_step::FixedStepState;
use super::linalg::evaluate_jacobian;
use super::{OdeOptions, OdeStepper, OdeSystem, rms_norm};
use crate::error::IntegrateError;
use crate::lu::DenseLu;
use crate::ode::eval_rhs;
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
    state: FixedStepState,
    residual: Vec<f64>,
    scale: Vec<f64>,
    work: [Vec<f64>; 2],
    jac: Mat<f64>,
    lu: DenseLu<f64>,
}

impl BackwardEuler {
    /// Needs `options.fixed_step`; `rtol`/`atol` set the Newton stopping test.
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        let state = FixedStepState::new(dim, options, "backward_euler")?;
        let v = || vec![0.0; dim];
        Ok(Self {
            rtol: options.rtol,
            atol: options.atol,
            newton_tol: (10.0 * f64::EPSILON / options.rtol).max(0.03f64.min(options.rtol.sqrt())),
            state,
            residual: v(),
            scale: v(),
            work: [v(), v()],
            jac: Mat::zeros(dim, dim),
            lu: DenseLu::new(dim),
        })
    }

    /// Factorise `I − h J` at `(t_n, y_n)`.
    fn prepare_newton_matrix(
        &mut self,
        sys: &mut dyn OdeSystem,
        h: f64,
    ) -> Result<(), IntegrateError> {
        let n = self.state.y.len();
        let [w0, w1] = &mut self.work;
        evaluate_jacobian(
            sys,
            self.state.t_prev,
            &self.state.y_prev,
            &self.state.f_prev,
            w0,
            w1,
            &mut self.jac,
        )?;
        self.state.stats.jacobian_evals += 1;
        {
            let mut m = self.lu.matrix_mut();
            for j in 0..n {
                for i in 0..n {
                    m[(i, j)] = -h * self.jac[(i, j)];
                }
                m[(j, j)] += 1.0;
            }
        }
        self.state.stats.lu_decompositions += 1;
        if self.lu.factor() {
            Ok(())
        } else {
            Err(IntegrateError::SingularMatrix {
                t: self.state.t_prev,
            })
        }
    }
}

impl OdeStepper for BackwardEuler {
    fn name(&self) -> &'static str {
        "backward_euler"
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        let h = self.state.next_step()?;
        self.state.begin_step();
        let t_new = self.state.t_prev + h;
        self.prepare_newton_matrix(sys, h)?;
        let s = &mut self.state;
        let n = s.y.len();
        // Explicit Euler predictor.
        for i in 0..n {
            s.y[i] = s.y_prev[i] + h * s.f_prev[i];
            self.scale[i] = self.atol + self.rtol * s.y_prev[i].abs();
        }
        let mut norm_old: Option<f64> = None;
        let mut converged = false;
        let mut norm = f64::INFINITY;
        for _ in 0..MAX_NEWTON {
            eval_rhs(sys, t_new, &s.y, &mut s.f)?;
            s.stats.f_evals += 1;
            s.stats.newton_iterations += 1;
            // Newton: (I − hJ) Δ = −(y − y_n − h f(t_{n+1}, y)).
            for i in 0..n {
                self.residual[i] = s.y_prev[i] + h * s.f[i] - s.y[i];
            }
            self.lu.solve_in_place(&mut self.residual);
            for i in 0..n {
                s.y[i] += self.residual[i];
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
                t: s.t_prev,
                iterations: MAX_NEWTON,
                residual: norm,
            });
        }
        s.end_step(sys, h)
    }

    fixed_step_accessors!();
}
