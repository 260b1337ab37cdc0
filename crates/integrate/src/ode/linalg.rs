//! Finite-difference Jacobians of the implicit methods (their LU factorisation is
//! [`crate::lu::DenseLu`]).

use super::{OdeSystem, eval_rhs};
use crate::IntegrateError;
use faer::{Mat, MatMut};

/// Forward-difference Jacobian `J[:, j] ≈ (f(t, y + δ_j e_j) − f(t, y)) / δ_j` with the
/// increment `δ_j = √ε · max(|y_j|, 10⁻⁵)` (ε the machine epsilon): the truncation error
/// O(δ) and the cancellation error O(ε/δ) balance at δ ≈ √ε relative to the magnitude of y_j;
/// the floor 10⁻⁵ (RADAU5's) serves components that pass through zero. `f0 = f(t, y)` is given;
/// `y_work` and `f_work` are scratch vectors of length n. Costs n evaluations of `f`.
pub fn finite_difference_jacobian(
    sys: &mut dyn OdeSystem,
    t: f64,
    y: &[f64],
    f0: &[f64],
    y_work: &mut [f64],
    f_work: &mut [f64],
    mut jac: MatMut<'_, f64>,
) {
    y_work.copy_from_slice(y);
    for j in 0..y.len() {
        let delta = f64::EPSILON.sqrt() * y[j].abs().max(1e-5);
        y_work[j] = y[j] + delta;
        sys.rhs(t, y_work, f_work);
        for i in 0..y.len() {
            jac[(i, j)] = (f_work[i] - f0[i]) / delta;
        }
        y_work[j] = y[j];
    }
}

/// As [`finite_difference_jacobian`], evaluating `f` through [`OdeSystem::try_rhs`] so that a
/// callback error stops the evaluation.
fn try_finite_difference_jacobian(
    sys: &mut dyn OdeSystem,
    t: f64,
    y: &[f64],
    f0: &[f64],
    y_work: &mut [f64],
    f_work: &mut [f64],
    mut jac: MatMut<'_, f64>,
) -> Result<(), IntegrateError> {
    y_work.copy_from_slice(y);
    for j in 0..y.len() {
        let delta = f64::EPSILON.sqrt() * y[j].abs().max(1e-5);
        y_work[j] = y[j] + delta;
        eval_rhs(sys, t, y_work, f_work)?;
        for i in 0..y.len() {
            jac[(i, j)] = (f_work[i] - f0[i]) / delta;
        }
        y_work[j] = y[j];
    }
    Ok(())
}

/// Evaluate the Jacobian (analytic if the system provides one, finite differences otherwise).
/// Returns the number of right-hand-side evaluations spent (0 for an analytic Jacobian); a
/// callback error of the system is returned as [`IntegrateError::Callback`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_jacobian(
    sys: &mut dyn OdeSystem,
    t: f64,
    y: &[f64],
    f0: &[f64],
    y_work: &mut [f64],
    f_work: &mut [f64],
    jac: &mut Mat<f64>,
) -> Result<usize, IntegrateError> {
    let analytic = sys
        .try_jacobian(t, y, jac.as_mut())
        .map_err(|error| IntegrateError::Callback { t, error })?;
    if analytic {
        Ok(0)
    } else {
        try_finite_difference_jacobian(sys, t, y, f0, y_work, f_work, jac.as_mut())?;
        Ok(y.len())
    }
}
