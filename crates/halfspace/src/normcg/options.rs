//! The inputs of a normal solve: the load (approach or force) and the NormCG controls (module
//! [`super`], which re-exports them).

use crate::error::{ContactError, positive};

/// The normal load: approach or total force prescribed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalLoad {
    /// Approach δ \[m\] prescribed; the force is computed.
    Approach(f64),
    /// Total normal force F_n \[N\] prescribed; the approach is computed.
    Force(f64),
}

/// Controls of the NormCG iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Relative tolerance on ‖Δp‖_rms / ‖p‖_rms (default 1e-8).
    pub tol: f64,
    /// Iteration limit (default 200).
    pub max_iter: usize,
    /// Compute dF_n/dδ after convergence (default true).
    pub sensitivity: bool,
    /// Relative residual tolerance of the sensitivity solve (default 1e-6: dF_n/dδ is a
    /// tangent for Newton-type iterations, where ~1e-6 is far below what matters; CONTACT's
    /// own sensitivities are accurate to about 1 %).
    pub sensitivity_tol: f64,
    /// Start from the previous solution of this solver when there is one (default true).
    pub warm_start: bool,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            tol: 1e-8,
            max_iter: 200,
            sensitivity: true,
            sensitivity_tol: 1e-6,
            warm_start: true,
        }
    }
}

impl SolverOptions {
    pub(super) fn validate(&self) -> Result<(), ContactError> {
        positive("tol", self.tol)?;
        positive("sensitivity_tol", self.sensitivity_tol)?;
        if self.max_iter == 0 {
            return Err(ContactError::InvalidParameter {
                name: "max_iter",
                value: 0.0,
                reason: "must be at least 1",
            });
        }
        Ok(())
    }
}
