//! A linear structural system `M q'' + C q' + K q = f(t)`.

use faer::{Mat, MatMut, MatRef};

use super::StructuralSystem;
use super::linalg::{check_matrix, mat_vec};
use crate::IntegrateError;

/// Linear system `M q'' + C q' + K q = f(t)` with dense constant matrices and a load closure
/// `load(t, f)` that writes `f(t)`.
pub struct LinearStructure<L> {
    mass: Mat<f64>,
    damping: Option<Mat<f64>>,
    stiffness: Mat<f64>,
    load: L,
}

impl<L: FnMut(f64, &mut [f64])> LinearStructure<L> {
    /// Builds the system after checking that `M`, `C` and `K` are square, of one size, finite,
    /// and that the diagonal of `M` is positive (a negative or zero mass is rejected), except
    /// for massless DOFs whose row and column of `M` are entirely zero (see
    /// [`StructuralStepper::new`](super::StructuralStepper::new)).
    pub fn new(
        mass: Mat<f64>,
        damping: Option<Mat<f64>>,
        stiffness: Mat<f64>,
        load: L,
    ) -> Result<Self, IntegrateError> {
        let n = mass.nrows();
        check_matrix("mass", mass.as_ref(), n)?;
        let massless = |i: usize| (0..n).all(|j| mass[(i, j)] == 0.0 && mass[(j, i)] == 0.0);
        if let Some(i) = (0..n).find(|&i| mass[(i, i)] <= 0.0 && !massless(i)) {
            return Err(IntegrateError::InvalidParameter {
                name: "mass",
                reason: format!(
                    "diagonal entry {i} is {} (must be > 0, or row and column {i} entirely 0 for a massless DOF)",
                    mass[(i, i)]
                ),
            });
        }
        if let Some(c) = &damping {
            check_matrix("damping", c.as_ref(), n)?;
        }
        check_matrix("stiffness", stiffness.as_ref(), n)?;
        Ok(Self {
            mass,
            damping,
            stiffness,
            load,
        })
    }

    /// The stiffness matrix `K`.
    pub fn stiffness(&self) -> MatRef<'_, f64> {
        self.stiffness.as_ref()
    }
}

impl<L: FnMut(f64, &mut [f64])> StructuralSystem for LinearStructure<L> {
    fn dimension(&self) -> usize {
        self.mass.nrows()
    }

    fn mass_matrix(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }

    fn damping_matrix(&self) -> Option<MatRef<'_, f64>> {
        self.damping.as_ref().map(|c| c.as_ref())
    }

    fn internal_force(&mut self, q: &[f64], f_int: &mut [f64]) {
        mat_vec(self.stiffness.as_ref(), q, f_int);
    }

    fn tangent_stiffness(&mut self, _q: &[f64], mut k: MatMut<'_, f64>) -> bool {
        k.copy_from(&self.stiffness);
        true
    }

    fn is_linear(&self) -> bool {
        true
    }

    fn external_force(&mut self, t: f64, f_ext: &mut [f64]) {
        (self.load)(t, f_ext);
    }
}
