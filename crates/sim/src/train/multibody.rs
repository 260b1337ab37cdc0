//! What the multibody vehicles (bogie vehicle, articulated train) share: their matrices and
//! the assembly of spring–damper pairs, e = gᵀq adding k g gᵀ to K and c g gᵀ to C.

use faer::Mat;

/// Mass (diagonal), stiffness and damping matrices of a contact-free multibody vehicle: the
/// body and bogie DOFs first (`own_dofs` of them), then one DOF per wheelset in running order.
#[derive(Debug, Clone)]
pub struct VehicleMatrices {
    /// Diagonal of M (masses on z DOFs, pitch inertias on θ DOFs, wheelset masses).
    pub mass: Vec<f64>,
    /// K (symmetric).
    pub stiffness: Mat<f64>,
    /// C (symmetric).
    pub damping: Mat<f64>,
    /// Number of body and bogie DOFs (the wheelsets follow).
    pub own_dofs: usize,
}

impl VehicleMatrices {
    /// Total number of DOFs.
    pub fn dofs(&self) -> usize {
        self.mass.len()
    }

    /// Number of wheelsets.
    pub fn wheelsets(&self) -> usize {
        self.mass.len() - self.own_dofs
    }
}

/// Accumulates spring–damper pairs into K and C.
pub(crate) struct SpringAssembler {
    stiffness: Mat<f64>,
    damping: Mat<f64>,
}

impl SpringAssembler {
    pub(crate) fn new(dofs: usize) -> Self {
        Self {
            stiffness: Mat::zeros(dofs, dofs),
            damping: Mat::zeros(dofs, dofs),
        }
    }

    /// Adds a spring k and damper c whose elongation is e = Σ g_i q_i (`g` as (DOF, g_i)).
    pub(crate) fn add(&mut self, g: &[(usize, f64)], k: f64, c: f64) {
        for &(i, gi) in g {
            for &(j, gj) in g {
                self.stiffness[(i, j)] += k * gi * gj;
                self.damping[(i, j)] += c * gi * gj;
            }
        }
    }

    /// (K, C).
    pub(crate) fn finish(self) -> (Mat<f64>, Mat<f64>) {
        (self.stiffness, self.damping)
    }
}
