//! Errors of the integrators. Variants carry the numbers that explain the failure.

use std::error::Error as StdError;
use std::fmt;
use std::sync::Arc;

use thiserror::Error;

/// An error raised by a caller's callback (a right-hand side, a Jacobian), carried through the
/// integrator unchanged. Recover the caller's own type with [`CallbackError::downcast_ref`].
///
/// The error is shared (`Arc`) so that [`IntegrateError`] stays `Clone`; two
/// `CallbackError`s compare equal when they hold the same error object.
#[derive(Clone)]
pub struct CallbackError(Arc<dyn StdError + Send + Sync + 'static>);

impl CallbackError {
    /// Wrap the caller's error.
    pub fn new<E: StdError + Send + Sync + 'static>(error: E) -> Self {
        Self(Arc::new(error))
    }

    /// The caller's error as its own type `E`, if it is one.
    pub fn downcast_ref<E: StdError + 'static>(&self) -> Option<&E> {
        self.0.downcast_ref::<E>()
    }

    /// The caller's error as a trait object.
    pub fn get(&self) -> &(dyn StdError + Send + Sync + 'static) {
        &*self.0
    }
}

impl fmt::Debug for CallbackError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&*self.0, f)
    }
}

impl fmt::Display for CallbackError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&*self.0, f)
    }
}

impl PartialEq for CallbackError {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

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
    /// A callback of the caller (right-hand side, Jacobian) failed; its error is carried
    /// unchanged in `error` (recover it with [`CallbackError::downcast_ref`] or
    /// [`IntegrateError::callback_error`]).
    #[error("callback failed at t = {t}: {error}")]
    Callback { t: f64, error: CallbackError },
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

impl IntegrateError {
    /// The caller's error of type `E` if this is a [`IntegrateError::Callback`] holding one.
    pub fn callback_error<E: StdError + 'static>(&self) -> Option<&E> {
        match self {
            IntegrateError::Callback { error, .. } => error.downcast_ref::<E>(),
            _ => None,
        }
    }
}
