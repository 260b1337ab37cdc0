//! Small dense helpers shared by the structural steppers (no allocation).

use faer::MatRef;

use crate::IntegrateError;

/// `out = A x` for a dense `A`.
pub(crate) fn mat_vec(a: MatRef<'_, f64>, x: &[f64], out: &mut [f64]) {
    for (i, o) in out.iter_mut().enumerate() {
        *o = (0..a.ncols()).map(|j| a[(i, j)] * x[j]).sum();
    }
}

/// `out += s · A x` for a dense `A`.
pub(crate) fn mat_vec_add(a: MatRef<'_, f64>, s: f64, x: &[f64], out: &mut [f64]) {
    for (i, o) in out.iter_mut().enumerate() {
        let ax: f64 = (0..a.ncols()).map(|j| a[(i, j)] * x[j]).sum();
        *o += s * ax;
    }
}

/// Maximum norm `‖x‖_∞`.
pub(crate) fn norm_inf(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Checks that `a` is `n × n` with finite entries; the error names the parameter.
pub(crate) fn check_matrix(
    name: &'static str,
    a: MatRef<'_, f64>,
    n: usize,
) -> Result<(), IntegrateError> {
    if a.nrows() != n || a.ncols() != n {
        return Err(IntegrateError::InvalidParameter {
            name,
            reason: format!("shape {}x{} (expected {n}x{n})", a.nrows(), a.ncols()),
        });
    }
    for j in 0..n {
        for i in 0..n {
            if !a[(i, j)].is_finite() {
                return Err(IntegrateError::InvalidParameter {
                    name,
                    reason: format!("entry ({i}, {j}) is {}", a[(i, j)]),
                });
            }
        }
    }
    Ok(())
}

/// Checks that `x` has length `n` and finite entries; the error names the parameter.
pub(crate) fn check_vector(name: &'static str, x: &[f64], n: usize) -> Result<(), IntegrateError> {
    if x.len() != n {
        return Err(IntegrateError::InvalidParameter {
            name,
            reason: format!("length {} (expected {n})", x.len()),
        });
    }
    if let Some(i) = x.iter().position(|v| !v.is_finite()) {
        return Err(IntegrateError::InvalidParameter {
            name,
            reason: format!("entry {i} is {}", x[i]),
        });
    }
    Ok(())
}
