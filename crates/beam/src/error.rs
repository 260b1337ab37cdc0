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
    /// A physical quantity lies outside the range the models are meant for.
    #[error(
        "`{name}` = {value:e} {unit} lies outside the physical range [{min:e}, {max:e}] {unit}"
    )]
    OutOfRange {
        /// Name of the quantity.
        name: &'static str,
        /// The offending value.
        value: f64,
        /// Smallest accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
        /// SI unit of the quantity.
        unit: &'static str,
    },
    /// A size (modes, elements) would need more memory than allowed; checked before
    /// allocating.
    #[error(
        "`{name}` = {value} is too large: {what} needs about {bytes_required:.3e} bytes ({gib:.1} GiB; limit {limit_bytes:.1e} bytes, at most {max} allowed)",
        gib = bytes_required / 1073741824.0
    )]
    TooLarge {
        /// Name of the count.
        name: &'static str,
        /// The requested count.
        value: usize,
        /// Largest count accepted.
        max: usize,
        /// What would be allocated.
        what: &'static str,
        /// Memory the request would need \[bytes\].
        bytes_required: f64,
        /// The memory limit \[bytes\].
        limit_bytes: f64,
    },
    /// The time step of a conditionally stable (explicit) method exceeds its stability limit.
    #[error(
        "time step dt = {dt:e} s exceeds the stability limit {limit:e} s of the explicit method `{method}` (2/ω_max for central difference and Verlet; ω_max = {omega_max:e} rad/s of the highest retained mode): use dt <= {limit:e} s, fewer modes, or an implicit method (newmark, hht, generalized_alpha)"
    )]
    StepAboveStabilityLimit {
        /// The method's name.
        method: &'static str,
        /// The requested step \[s\].
        dt: f64,
        /// The largest stable step \[s\].
        limit: f64,
        /// Highest circular frequency retained \[rad/s\].
        omega_max: f64,
    },
    /// A sparse factorisation failed (a track step matrix not positive definite, or an
    /// invalid pattern).
    #[error("factorisation of the {matrix} failed: {detail}")]
    Factorisation {
        /// Which matrix.
        matrix: &'static str,
        /// What faer reported.
        detail: String,
    },
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

/// Memory allowed for one beam model or solver \[bytes\] (4 GiB).
pub const MEMORY_LIMIT_BYTES: f64 = 4.0 * 1073741824.0;
/// Largest number of modes of a basis or a modal solve.
pub const MAX_MODES: usize = 2000;
/// Largest number of finite elements.
pub const MAX_ELEMENTS: usize = 5000;
/// Physical range of the bending stiffness EI \[N m²\] (a 1 mm wire to the stiffest bridge
/// girders).
pub const BENDING_STIFFNESS_RANGE: (f64, f64) = (1e-6, 1e14);
/// Physical range of the mass per length ρA \[kg/m\].
pub const MASS_PER_LENGTH_RANGE: (f64, f64) = (1e-6, 1e7);
/// Physical range of a span or section length \[m\].
pub const LENGTH_RANGE: (f64, f64) = (1e-3, 1e4);

/// Check that `value` lies in `range` (finite, positive checked before).
pub(crate) fn in_range(
    name: &'static str,
    value: f64,
    (min, max): (f64, f64),
    unit: &'static str,
) -> Result<f64, BeamError> {
    if value >= min && value <= max {
        Ok(value)
    } else {
        Err(BeamError::OutOfRange {
            name,
            value,
            min,
            max,
            unit,
        })
    }
}

/// Check a count against its maximum and the memory `bytes_per(count)` it needs, before
/// anything is allocated.
pub(crate) fn check_size(
    name: &'static str,
    value: usize,
    max: usize,
    what: &'static str,
    bytes_per: impl Fn(usize) -> f64,
) -> Result<(), BeamError> {
    let bytes_required = bytes_per(value);
    if value > max || bytes_required > MEMORY_LIMIT_BYTES {
        return Err(BeamError::TooLarge {
            name,
            value,
            max,
            what,
            bytes_required,
            limit_bytes: MEMORY_LIMIT_BYTES,
        });
    }
    Ok(())
}
