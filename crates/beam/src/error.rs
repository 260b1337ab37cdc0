//! Errors of the beam crate. Every variant carries the numbers that explain the failure.

use thiserror::Error;

/// Failure of a beam computation (invalid input or a failed factorisation).
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum BeamError {
    /// A scalar parameter is non-finite or outside its valid range.
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Name of the parameter as it appears in the API.
        name: &'static str,
        /// The offending value.
        value: f64,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// A position lies outside the span `[0, length]`.
    #[error("position `{name}` = {x} lies outside the span [0, {length}]")]
    OutsideSpan {
        /// Name of the position parameter.
        name: &'static str,
        /// The offending position.
        x: f64,
        /// Span length.
        length: f64,
    },
    /// A count (number of modes, elements, quadrature points) is invalid.
    #[error("invalid count `{name}` = {value}: {reason}")]
    InvalidCount {
        /// Name of the count.
        name: &'static str,
        /// The offending count.
        value: usize,
        /// What the count must satisfy.
        reason: &'static str,
    },
    /// A mode index is not below the number of modes.
    #[error("mode index {index} out of range (basis has {n_modes} modes)")]
    ModeIndex {
        /// Requested (0-based) mode index.
        index: usize,
        /// Number of modes in the basis.
        n_modes: usize,
    },
    /// An output slice has the wrong length.
    #[error("slice `{name}` has length {got}, expected {expected}")]
    SliceLength {
        /// Name of the slice argument.
        name: &'static str,
        /// Actual length.
        got: usize,
        /// Required length.
        expected: usize,
    },
    /// The bracketed root search of a characteristic equation failed.
    #[error("root {n} of the characteristic equation not bracketed in [{lo}, {hi}]")]
    RootNotBracketed {
        /// Mode number (1-based, elastic modes).
        n: usize,
        /// Lower end of the bracket.
        lo: f64,
        /// Upper end of the bracket.
        hi: f64,
    },
    /// The mass matrix was not positive definite (Cholesky pivot index).
    #[error("mass matrix not positive definite (Cholesky pivot {pivot})")]
    MassNotPositiveDefinite {
        /// Index of the failing pivot.
        pivot: usize,
    },
    /// The stiffness matrix is singular in a static solve (constraints missing).
    #[error(
        "stiffness matrix singular or indefinite (pivot {pivot}); the beam needs supports for a static solve"
    )]
    StiffnessSingular {
        /// Index of the failing pivot.
        pivot: usize,
    },
    /// The symmetric eigen-solver did not converge.
    #[error("symmetric eigen-solver did not converge (matrix size {size})")]
    EigenNoConvergence {
        /// Size of the eigenproblem.
        size: usize,
    },
    /// A structural time integrator of the `integrate` crate failed.
    #[error("time integrator failed: {0}")]
    Integrator(#[from] integrate::IntegrateError),
    /// More modes were requested than the discrete model has degrees of freedom.
    #[error(
        "requested {requested} modes but the model has only {available} free degrees of freedom"
    )]
    TooManyModes {
        /// Requested number of modes.
        requested: usize,
        /// Number of free DOFs.
        available: usize,
    },
}

/// Check that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, BeamError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(BeamError::InvalidParameter {
            name,
            value,
            reason: "must be finite and > 0",
        })
    }
}

/// Check that `value` is finite and non-negative.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64, BeamError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(BeamError::InvalidParameter {
            name,
            value,
            reason: "must be finite and >= 0",
        })
    }
}

/// Check that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, BeamError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(BeamError::InvalidParameter {
            name,
            value,
            reason: "must be finite",
        })
    }
}

/// Check that `x` is finite and inside `[0, length]`.
pub(crate) fn inside_span(name: &'static str, x: f64, length: f64) -> Result<f64, BeamError> {
    if x.is_finite() && (0.0..=length).contains(&x) {
        Ok(x)
    } else {
        Err(BeamError::OutsideSpan { name, x, length })
    }
}
