//! The state and bookkeeping shared by the fixed-step methods.

use super::{
    OdeOptions, OdeSystem, check_interpolation_range, check_state, hermite_interpolate, limit_step,
};
use crate::error::IntegrateError;
use crate::ode::eval_rhs;
use crate::stats::Stats;

/// State shared by the fixed-step methods (explicit Euler, RK4, backward Euler): current and previous point with their
/// derivatives (for the cubic Hermite dense output), step and limits.
#[derive(Debug, Clone)]
pub(super) struct FixedStepState {
    pub(super) h: f64,
    pub(super) h_cap: f64,
    pub(super) max_step: f64,
    pub(super) max_steps: usize,
    pub(super) t_stop: Option<f64>,
    pub(super) t: f64,
    pub(super) t_prev: f64,
    pub(super) y: Vec<f64>,
    pub(super) y_prev: Vec<f64>,
    pub(super) f: Vec<f64>,
    pub(super) f_prev: Vec<f64>,
    pub(super) stats: Stats,
}

impl FixedStepState {
    pub(super) fn new(
        dim: usize,
        options: &OdeOptions,
        method: &str,
    ) -> Result<Self, IntegrateError> {
        options.validate()?;
        Ok(Self {
            h: options.required_fixed_step(method)?,
            h_cap: f64::INFINITY,
            max_step: options.max_step,
            max_steps: options.max_steps,
            t_stop: None,
            t: 0.0,
            t_prev: 0.0,
            y: vec![0.0; dim],
            y_prev: vec![0.0; dim],
            f: vec![0.0; dim],
            f_prev: vec![0.0; dim],
            stats: Stats::default(),
        })
    }

    pub(super) fn set_state(
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
        eval_rhs(sys, t, y, &mut self.f)?;
        self.stats.f_evals += 1;
        self.f_prev.copy_from_slice(&self.f);
        Ok(())
    }

    /// The size of the next step, after the step-count check.
    pub(super) fn next_step(&self) -> Result<f64, IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        Ok(limit_step(
            self.t,
            self.h,
            self.h_cap.min(self.max_step),
            self.t_stop,
        ))
    }

    /// Rotate current → previous; afterwards `y` and `f` are free for the new values.
    pub(super) fn begin_step(&mut self) {
        std::mem::swap(&mut self.y, &mut self.y_prev);
        std::mem::swap(&mut self.f, &mut self.f_prev);
        self.t_prev = self.t;
    }

    /// Finish a step of size `h`: evaluate `f` at the new point (reused as the first stage of
    /// the next step) and check finiteness.
    pub(super) fn end_step(
        &mut self,
        sys: &mut dyn OdeSystem,
        h: f64,
    ) -> Result<(), IntegrateError> {
        self.t = self.t_prev + h;
        if self.y.iter().any(|v| !v.is_finite()) {
            return Err(IntegrateError::NonFinite { t: self.t });
        }
        eval_rhs(sys, self.t, &self.y, &mut self.f)?;
        self.stats.f_evals += 1;
        self.stats.steps += 1;
        Ok(())
    }

    pub(super) fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), IntegrateError> {
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
}

/// Forwards the common `OdeStepper` methods to the `FixedStepState` field `state`.
macro_rules! fixed_step_accessors {
    () => {
        fn t(&self) -> f64 {
            self.state.t
        }
        fn y(&self) -> &[f64] {
            &self.state.y
        }
        fn t_prev(&self) -> f64 {
            self.state.t_prev
        }
        fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), IntegrateError> {
            self.state.interpolate(t, out)
        }
        stepper_bookkeeping!(state);
        fn set_state(
            &mut self,
            sys: &mut dyn OdeSystem,
            t: f64,
            y: &[f64],
        ) -> Result<(), IntegrateError> {
            self.state.set_state(sys, t, y)
        }
    };
}
