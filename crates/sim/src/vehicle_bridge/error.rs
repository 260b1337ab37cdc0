//! The error type of the vehicle–bridge simulation and the parameter-check helpers.

use beam::BeamError;
use halfspace::ContactError;
use integrate::IntegrateError;

/// Errors of the vehicle–bridge simulation.
#[derive(Debug, thiserror::Error)]
pub enum VehicleBridgeError {
    /// A parameter is out of range; `name` is the scenario key.
    #[error("invalid `{name}` = {value}: {reason}")]
    InvalidParameter {
        name: String,
        value: f64,
        reason: String,
    },
    /// A choice (a method or model name) is not allowed here; `name` is the scenario key.
    #[error("invalid `{name}` = \"{value}\": {reason}")]
    InvalidChoice {
        name: String,
        value: String,
        reason: String,
    },
    /// The beam (modal basis) failed.
    #[error("bridge: {0}")]
    Beam(#[from] BeamError),
    /// The time integrator failed.
    #[error("integrator: {0}")]
    Integrate(#[from] IntegrateError),
    /// The half-space contact solver failed.
    #[error("contact solver: {0}")]
    Contact(#[from] ContactError),
    /// The wheel–rail profiles or their rigid contact geometry failed.
    #[error("wheel–rail profiles: {0}")]
    Profiles(#[from] wheelrail::WheelRailError),
    /// The contact law of wheel `wheel` (0-based) failed during a step.
    #[error("contact law of wheel {wheel}: {source}")]
    WheelContact {
        wheel: usize,
        #[source]
        source: ContactError,
    },
    /// The contact-free step matrix A has a singular (or non-finite) block at `dof`.
    #[error("singular step matrix at DOF {dof}: {reason}")]
    SingularStepMatrix { dof: usize, reason: String },
    /// The coupling iteration of a step failed even after step reduction.
    #[error(
        "coupling ({solver}) failed at t = {t:.6} s with step {dt:e} s after {halvings} step halvings: {reason} ({})",
        iteration_note(*change, *iterations)
    )]
    CouplingFailed {
        solver: &'static str,
        t: f64,
        dt: f64,
        halvings: usize,
        iterations: usize,
        change: f64,
        reason: String,
    },
}

/// The iterations of a failed coupling solve, with the last force change where the solver
/// measures one (the track's patch and rigid solvers do not: no "NaN N" in the message).
fn iteration_note(change: f64, iterations: usize) -> String {
    if change.is_finite() {
        format!("last force change {change:e} N after {iterations} iterations")
    } else {
        format!("after {iterations} iterations")
    }
}

/// The error of an out-of-range scenario key `name` with its `value` and the allowed range.
pub(crate) fn invalid(name: impl Into<String>, value: f64, reason: &str) -> VehicleBridgeError {
    VehicleBridgeError::InvalidParameter {
        name: name.into(),
        value,
        reason: reason.to_string(),
    }
}

/// The error of a scenario key `name` whose text `value` (a method or model name) is not
/// allowed, with the reason.
pub(crate) fn invalid_text(name: &str, value: &str, reason: &str) -> VehicleBridgeError {
    VehicleBridgeError::InvalidChoice {
        name: name.to_string(),
        value: value.to_string(),
        reason: reason.to_string(),
    }
}

/// Checks that the scenario key `name` is finite and ≥ 0.
pub(super) fn check_non_negative(name: String, v: f64) -> Result<(), VehicleBridgeError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(invalid(name, v, "must be finite and >= 0"))
    }
}

#[cfg(test)]
mod tests {
    use super::VehicleBridgeError;

    fn failed(change: f64) -> String {
        VehicleBridgeError::CouplingFailed {
            solver: "track_patch_newton",
            t: 0.05,
            dt: 1e-4,
            halvings: 0,
            iterations: 2,
            change,
            reason: "no decrease of the residual".into(),
        }
        .to_string()
    }

    /// A solver without a force change (the track's patch and rigid solvers) prints none, and
    /// never "NaN N"; a measured change is printed as before.
    #[test]
    fn coupling_failure_names_a_measured_change_only() {
        let without = failed(f64::NAN);
        assert!(!without.contains("NaN"), "{without}");
        assert!(without.ends_with("(after 2 iterations)"), "{without}");
        let with = failed(8.08e-2);
        assert!(
            with.ends_with("(last force change 8.08e-2 N after 2 iterations)"),
            "{with}"
        );
    }
}
