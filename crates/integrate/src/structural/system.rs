//! The second-order problem `M q'' + C q' + f_int(q) = f_ext(t)`.

use faer::{MatMut, MatRef};

/// A structural system `M q'' + C q' + f_int(q) = f_ext(t)` with constant `M` and `C`.
///
/// Evaluation takes `&mut self`, so a system may keep caches or count calls.
/// Loads that depend on the configuration (a contact force, a nonlinear spring) belong in
/// [`internal_force`](Self::internal_force) (with their tangent), or are handled by an outside
/// solver through [`StepEquation`](super::StepEquation).
pub trait StructuralSystem {
    /// Number of degrees of freedom `n`.
    fn dimension(&self) -> usize;

    /// The constant mass matrix `M` (`n × n`, nonsingular). It is read once, when a
    /// stepper is created.
    fn mass_matrix(&self) -> MatRef<'_, f64>;

    /// The constant damping matrix `C` (`n × n`), or `None` for an undamped system. Read once,
    /// when a stepper is created.
    fn damping_matrix(&self) -> Option<MatRef<'_, f64>> {
        None
    }

    /// Writes the internal (restoring) force `f_int(q)` into `f_int`.
    fn internal_force(&mut self, q: &[f64], f_int: &mut [f64]);

    /// Writes the tangent stiffness `K_t = ∂f_int/∂q` at `q` into `k` (every entry) and returns
    /// `true`, or returns `false` if no analytic tangent is available; the stepper then uses
    /// forward finite differences of [`internal_force`](Self::internal_force).
    fn tangent_stiffness(&mut self, _q: &[f64], _k: MatMut<'_, f64>) -> bool {
        false
    }

    /// `true` if `f_int(q) = K q` with a constant `K`. The stepper then evaluates the tangent
    /// once, factorises the effective matrix once per step size and takes one Newton step.
    fn is_linear(&self) -> bool {
        false
    }

    /// Writes the external load `f_ext(t)` into `f_ext`.
    fn external_force(&mut self, t: f64, f_ext: &mut [f64]);
}

/// A mutable reference to a system is a system (so adapters can borrow a problem).
impl<T: StructuralSystem + ?Sized> StructuralSystem for &mut T {
    fn dimension(&self) -> usize {
        (**self).dimension()
    }
    fn mass_matrix(&self) -> MatRef<'_, f64> {
        (**self).mass_matrix()
    }
    fn damping_matrix(&self) -> Option<MatRef<'_, f64>> {
        (**self).damping_matrix()
    }
    fn internal_force(&mut self, q: &[f64], f_int: &mut [f64]) {
        (**self).internal_force(q, f_int)
    }
    fn tangent_stiffness(&mut self, q: &[f64], k: MatMut<'_, f64>) -> bool {
        (**self).tangent_stiffness(q, k)
    }
    fn is_linear(&self) -> bool {
        (**self).is_linear()
    }
    fn external_force(&mut self, t: f64, f_ext: &mut [f64]) {
        (**self).external_force(t, f_ext)
    }
}
