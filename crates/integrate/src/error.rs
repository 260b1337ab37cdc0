//! Errors of the integrators. Variants carry the numbers that explain the failure.

use thiserror::Error;

/// Failure of a time integrator.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum IntegrateError {
    /// A parameter of the method or the problem is out of its valid range.
    #[error("invalid parameter `{name}`: {reason}")]
    InvalidParameter { name: &'static str, reason: String },
    /// The adaptive step size fell below the smallest allowed value.
    #[error("step size {h:e} too small at t = {t}")]
    StepSizeTooSmall { t: f64, h: f64 },
    /// The Newton iteration of an implicit step did not converge.
    #[error(
        "Newton iteration did not converge at t = {t} after {iterations} iterations (residual {residual:e})"
    )]
    NewtonFailed {
        t: f64,
        iterations: usize,
        residual: f64,
    },
    /// A linear system of an implicit method was singular.
    #[error("singular iteration matrix at t = {t}")]
    SingularMatrix { t: f64 },
    /// The right-hand side or the state became non-finite.
    #[error("non-finite state at t = {t}")]
    NonFinite { t: f64 },
    /// Too many steps were taken.
    #[error("maximum number of steps ({max_steps}) reached at t = {t}")]
    TooManySteps { t: f64, max_steps: usize },
    /// A state vector or system has the wrong number of components.
    #[error("dimension mismatch: expected {expected} components, found {found}")]
    DimensionMismatch { expected: usize, found: usize },
    /// Dense output was requested outside the last accepted step.
    #[error("interpolation at t = {t} outside the last step [{t_start}, {t_end}]")]
    OutsideLastStep { t: f64, t_start: f64, t_end: f64 },
    /// The event root finder did not bracket or converge.
    #[error(
        "event {index} could not be located in [{t_start}, {t_end}] after {iterations} iterations"
    )]
    EventLocation {
        index: usize,
        t_start: f64,
        t_end: f64,
        iterations: usize,
    },
}
