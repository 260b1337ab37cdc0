//! Accessors of the stepper state and the dense output over the last step.

use faer::MatRef;

use super::super::StructuralMethod;
use crate::{IntegrateError, Stats};

use super::{NewtonOptions, StructuralStepper};

impl StructuralStepper {
    /// Replaces the Newton stopping rule (validated).
    pub fn set_newton_options(&mut self, options: NewtonOptions) -> Result<(), IntegrateError> {
        options.validate()?;
        self.newton = options;
        Ok(())
    }

    /// The Newton stopping rule in use.
    pub fn newton_options(&self) -> NewtonOptions {
        self.newton
    }

    /// The method.
    pub fn method(&self) -> StructuralMethod {
        self.method
    }

    /// Number of degrees of freedom.
    pub fn dimension(&self) -> usize {
        self.q.len()
    }

    /// Current time `t_n`.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current displacement `q_n`.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// Current velocity `v_n`.
    pub fn v(&self) -> &[f64] {
        &self.v
    }

    /// Current acceleration `a_n` (the scheme's acceleration variable; for HHT and
    /// generalized-α it satisfies the balance only in the α-weighted sense).
    pub fn a(&self) -> &[f64] {
        &self.a
    }

    /// The mass matrix `M` copied from the problem.
    pub fn mass(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }

    /// The damping matrix `C` copied from the problem, if any.
    pub fn damping(&self) -> Option<MatRef<'_, f64>> {
        self.damping.as_ref().map(|c| c.as_ref())
    }

    /// Counters: steps, force evaluations (calls of `internal_force`, including those of
    /// finite-difference tangents), tangent evaluations, LU factorisations, Newton iterations.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Cubic Hermite interpolation of the displacement over the last step, from `q` and `v` at
    /// both ends: `q(θ) = h₀₀ q_n + h₁₀ Δt v_n + h₀₁ q_{n+1} + h₁₁ Δt v_{n+1}`, θ = (t − t_n)/Δt.
    pub fn dense_output(&self, t: f64, q_out: &mut [f64]) -> Result<(), IntegrateError> {
        let (theta, dt) = self.dense_theta(t, q_out.len())?;
        let (t2, t3) = (theta * theta, theta * theta * theta);
        let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
        let h10 = t3 - 2.0 * t2 + theta;
        let h01 = -2.0 * t3 + 3.0 * t2;
        let h11 = t3 - t2;
        for (i, out) in q_out.iter_mut().enumerate() {
            *out = h00 * self.q_old[i]
                + h10 * dt * self.v_old[i]
                + h01 * self.q[i]
                + h11 * dt * self.v[i];
        }
        Ok(())
    }

    /// Time derivative of the [`dense_output`](Self::dense_output) Hermite cubic.
    pub fn dense_velocity(&self, t: f64, v_out: &mut [f64]) -> Result<(), IntegrateError> {
        let (theta, dt) = self.dense_theta(t, v_out.len())?;
        let t2 = theta * theta;
        let d00 = 6.0 * t2 - 6.0 * theta;
        let d10 = 3.0 * t2 - 4.0 * theta + 1.0;
        let d11 = 3.0 * t2 - 2.0 * theta;
        for (i, out) in v_out.iter_mut().enumerate() {
            *out = (d00 * (self.q_old[i] - self.q[i])) / dt + d10 * self.v_old[i] + d11 * self.v[i];
        }
        Ok(())
    }

    /// The last step `[t_n, t_{n+1}]`, if a step was taken.
    pub fn last_step_interval(&self) -> Option<(f64, f64)> {
        self.last_step.map(|(t0, dt)| (t0, t0 + dt))
    }

    fn dense_theta(&self, t: f64, len: usize) -> Result<(f64, f64), IntegrateError> {
        if len != self.q.len() {
            return Err(IntegrateError::InvalidParameter {
                name: "out",
                reason: format!("length {len} (expected {})", self.q.len()),
            });
        }
        let Some((t0, dt)) = self.last_step else {
            return Err(IntegrateError::InvalidParameter {
                name: "t",
                reason: "no step has been taken yet".to_string(),
            });
        };
        let theta = (t - t0) / dt;
        let slack = 1e-12;
        if !(theta.is_finite() && (-slack..=1.0 + slack).contains(&theta)) {
            return Err(IntegrateError::InvalidParameter {
                name: "t",
                reason: format!("{t} outside the last step [{t0}, {}]", t0 + dt),
            });
        }
        Ok((theta, dt))
    }
}
