//! The modal-basis abstraction shared by analytic and finite-element beams.
//!
//! A modal basis represents the displacement as u(x, t) = Σ_j q_j(t) w_j(x) (references.md §D1.1,
//! §D4.4). The shapes are mass-normalised,
//! ∫ ρA w_i w_j dx (+ Σ point masses) = δ_ij, so each modal equation reads
//! q_j'' + 2ζ_j ω_j q_j' + ω_j² q_j = f_j(t) with f_j = ∫ p w_j dx.

use crate::error::BeamError;

/// Which spatial derivative of the mode shapes to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Derivative {
    /// w(x): deflection shape.
    Shape,
    /// w'(x): slope (rotation).
    Slope,
    /// w''(x): curvature; the bending moment is M = −EI w''.
    Curvature,
    /// w'''(x): the shear force is V = −(EI w'')'.
    Third,
}

/// A set of mass-normalised bending modes of a beam on [0, L].
///
/// Implemented identically by [`crate::AnalyticBeam`] and [`crate::FeModes`], so moving-load and
/// coupling code never needs to know how the modes were obtained.
pub trait ModalBasis {
    /// Number of modes in the basis (rigid-body modes included).
    fn n_modes(&self) -> usize;

    /// Span length L \[m\].
    fn length(&self) -> f64;

    /// Circular frequencies ω_j [rad/s], non-decreasing; 0 for rigid-body modes.
    fn circular_frequencies(&self) -> &[f64];

    /// Evaluate derivative `d` of every mode at `x` into `out` (length [`Self::n_modes`]).
    /// Allocation-free. Errors if `x` is outside [0, L] or `out` has the wrong length.
    fn eval_all(&self, x: f64, d: Derivative, out: &mut [f64]) -> Result<(), BeamError>;

    /// Derivative `d` of mode `j` (0-based) at `x`.
    fn mode_value(&self, j: usize, x: f64, d: Derivative) -> Result<f64, BeamError>;

    /// Bending stiffness EI(x) [N m²] at `x`.
    fn bending_stiffness(&self, x: f64) -> Result<f64, BeamError>;

    /// Modal mass of mode `j`: 1 for a mass-normalised basis.
    fn modal_mass(&self, j: usize) -> Result<f64, BeamError> {
        check_mode(j, self.n_modes())?;
        Ok(1.0)
    }

    /// Circular frequency ω_j of mode `j` [rad/s].
    fn circular_frequency(&self, j: usize) -> Result<f64, BeamError> {
        self.circular_frequencies()
            .get(j)
            .copied()
            .ok_or(BeamError::ModeIndex {
                index: j,
                n_modes: self.n_modes(),
            })
    }

    /// Mode shape w_j(x).
    fn shape(&self, j: usize, x: f64) -> Result<f64, BeamError> {
        self.mode_value(j, x, Derivative::Shape)
    }

    /// Slope w_j'(x).
    fn slope(&self, j: usize, x: f64) -> Result<f64, BeamError> {
        self.mode_value(j, x, Derivative::Slope)
    }

    /// Curvature w_j''(x).
    fn curvature(&self, j: usize, x: f64) -> Result<f64, BeamError> {
        self.mode_value(j, x, Derivative::Curvature)
    }
}

/// A shared basis is a basis (so one set of modes, computed once, can serve many runs, e.g.
/// the passages of a speed sweep with vehicle interaction).
impl<T: ModalBasis + ?Sized> ModalBasis for std::sync::Arc<T> {
    fn n_modes(&self) -> usize {
        (**self).n_modes()
    }
    fn length(&self) -> f64 {
        (**self).length()
    }
    fn circular_frequencies(&self) -> &[f64] {
        (**self).circular_frequencies()
    }
    fn eval_all(&self, x: f64, d: Derivative, out: &mut [f64]) -> Result<(), BeamError> {
        (**self).eval_all(x, d, out)
    }
    fn mode_value(&self, j: usize, x: f64, d: Derivative) -> Result<f64, BeamError> {
        (**self).mode_value(j, x, d)
    }
    fn bending_stiffness(&self, x: f64) -> Result<f64, BeamError> {
        (**self).bending_stiffness(x)
    }
    fn modal_mass(&self, j: usize) -> Result<f64, BeamError> {
        (**self).modal_mass(j)
    }
}

/// Error unless `j < n_modes`.
pub(crate) fn check_mode(j: usize, n_modes: usize) -> Result<(), BeamError> {
    if j < n_modes {
        Ok(())
    } else {
        Err(BeamError::ModeIndex { index: j, n_modes })
    }
}

/// Error unless `out.len() == expected`.
pub(crate) fn check_len(name: &'static str, got: usize, expected: usize) -> Result<(), BeamError> {
    if got == expected {
        Ok(())
    } else {
        Err(BeamError::SliceLength {
            name,
            got,
            expected,
        })
    }
}
