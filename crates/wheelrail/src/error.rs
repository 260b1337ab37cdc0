//! Errors of the wheel–rail geometry.

use thiserror::Error;

/// Failure of a profile or contact-geometry computation. Input variants name the offending
/// parameter, its value and the allowed range.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum WheelRailError {
    /// A parameter is outside its allowed range.
    #[error("invalid `{name}` = {value}: {allowed}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        allowed: &'static str,
    },
    /// A profile definition is inconsistent (segments not ordered or not joined).
    #[error("invalid profile: {0}")]
    InvalidProfile(String),
    /// The wheel and rail profiles do not overlap laterally at this wheelset position.
    #[error(
        "no contact candidate: wheel and rail profiles do not overlap laterally at lateral shift {lateral_shift} m"
    )]
    NoOverlap { lateral_shift: f64 },
    /// An iteration (roll angle, vertical force) did not converge.
    #[error("{what} did not converge in {iterations} iterations (residual {residual:e})")]
    NotConverged {
        what: &'static str,
        iterations: usize,
        residual: f64,
    },
    /// The half-space solver failed on a patch.
    #[error("contact patch {patch}: {source}")]
    Contact {
        patch: usize,
        #[source]
        source: halfspace::ContactError,
    },
}
/// `Ok` when `value` is finite and within [`lo`, `hi`].
pub(crate) fn in_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    allowed: &'static str,
) -> Result<(), WheelRailError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(WheelRailError::InvalidParameter {
            name,
            value,
            allowed,
        })
    }
}
