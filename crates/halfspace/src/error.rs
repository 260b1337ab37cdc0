//! Errors of the half-space contact solver.

use thiserror::Error;

use crate::solution::NormalSolution;

/// Failure of a contact computation. Invalid-input variants name the offending parameter.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum ContactError {
    /// A parameter is out of its physical or numerical range.
    #[error("invalid `{name}` = {value}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    /// Array sizes do not match the grid.
    #[error("`{name}` has {found} values, the grid has {expected} elements")]
    SizeMismatch {
        name: &'static str,
        expected: usize,
        found: usize,
    },
    /// A grid too large for the solvers, refused before anything is allocated.
    #[error(
        "grid of {nx} x {ny} = {elements} elements is too large (limits: {per_direction} per direction, {total} in total); the solvers would need about {memory_gib:.1} GiB",
        elements = *nx as u128 * *ny as u128,
        per_direction = crate::grid::MAX_ELEMENTS_PER_DIRECTION,
        total = crate::grid::MAX_ELEMENTS
    )]
    GridTooLarge {
        nx: usize,
        ny: usize,
        memory_gib: f64,
    },
    /// Both bodies are rigid: the contact problem has no elastic solution.
    #[error("both bodies are rigid: at least one must be elastic")]
    BothRigid,
    /// No element of the potential contact area comes into contact.
    #[error("no contact: the prescribed load gives no element in contact ({reason})")]
    NoContact { reason: &'static str },
    /// The iterative solver stopped at its iteration limit. The last iterate is kept so a
    /// caller can inspect or report it, but it must not be used as an answer.
    #[error("NormCG did not converge in {iterations} iterations (relative change {residual:e})")]
    NotConverged {
        iterations: usize,
        residual: f64,
        last: Box<NormalSolution>,
    },
    /// The linearised solve for dF_n/dδ stopped at its iteration limit.
    #[error(
        "sensitivity solve did not converge in {iterations} iterations (relative residual {residual:e})"
    )]
    SensitivityNotConverged { iterations: usize, residual: f64 },
    /// The tangential Gauss–Seidel iteration stopped at its sweep limit.
    #[error(
        "tangential solver did not converge in {iterations} sweeps (relative change {residual:e})"
    )]
    TangentialNotConverged { iterations: usize, residual: f64 },
    /// Newton's method for prescribed tangential forces stopped at its iteration limit.
    #[error(
        "Newton iteration on the creepages/shift did not converge in {iterations} iterations (force error {residual:e} N)"
    )]
    NewtonNotConverged { iterations: usize, residual: f64 },
    /// The normal–tangential outer loop (K ≠ 0) stopped at its iteration limit.
    #[error(
        "normal-tangential outer loop did not converge in {iterations} iterations (relative change {residual:e})"
    )]
    CoupledNotConverged { iterations: usize, residual: f64 },
    /// A prescribed tangential force cannot be carried by friction.
    #[error("tangential force {force:e} N reaches the friction limit mu*Fn = {limit:e} N")]
    ForceExceedsFriction { force: f64, limit: f64 },
    /// The FFT operator reported an internal inconsistency (should not happen).
    #[error("FFT failure: {0}")]
    Fft(String),
}

/// Check that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, ContactError> {
    if !value.is_finite() {
        return Err(ContactError::InvalidParameter {
            name,
            value,
            reason: "must be a finite number",
        });
    }
    if value <= 0.0 {
        return Err(ContactError::InvalidParameter {
            name,
            value,
            reason: "must be positive",
        });
    }
    Ok(value)
}

/// Check that `value` is finite and lies in [lo, hi]; `reason` states the range.
pub(crate) fn in_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    reason: &'static str,
) -> Result<f64, ContactError> {
    if !(value.is_finite() && (lo..=hi).contains(&value)) {
        return Err(ContactError::InvalidParameter {
            name,
            value,
            reason,
        });
    }
    Ok(value)
}

/// Check that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, ContactError> {
    if !value.is_finite() {
        return Err(ContactError::InvalidParameter {
            name,
            value,
            reason: "must be a finite number",
        });
    }
    Ok(value)
}
