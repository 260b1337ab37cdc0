//! Finite-element Euler–Bernoulli beam: Hermite cubic elements (2 DOF per node: w, θ = w').
//!
//! Piecewise-constant sections EI(x), ρA(x); pinned or clamped supports anywhere along the span
//! (continuous multi-span bridges); elastic bearings (translational and rotational springs);
//! point masses with optional rotary inertia. Element matrices (Przemieniecki 1968; Cook et al.,
//! *Concepts and Applications of FEA*, §2.5 and §11.3), element length h, DOFs (w₁, θ₁, w₂, θ₂):
//!
//! K_e = EI/h³ [[12, 6h, −12, 6h], [6h, 4h², −6h, 2h²], [−12, −6h, 12, −6h], [6h, 2h², −6h, 4h²]]
//! M_e = ρA h/420 [[156, 22h, 54, −13h], [22h, 4h², 13h, −3h²], [54, 13h, 156, −22h], [−13h, −3h², −22h, 4h²]]
//!
//! (consistent mass). Modes solve K φ = ω² M φ by a Cholesky reduction to a standard dense
//! symmetric eigenproblem (faer): M = LLᵀ, (L⁻¹ K L⁻ᵀ) y = ω² y, φ = L⁻ᵀ y, also through the SVD
//! of the square root G L⁻ᵀ (K = GᵀG), which keeps the lowest modes accurate on fine meshes; the
//! default is a banded subspace iteration whose Rayleigh–Ritz step uses the same Cholesky /
//! square-root reduction on the subspace (see [`EigenReduction`]); φᵀ M φ = I (mass-normalised
//! including point masses). Between nodes the shapes are interpolated with the
//! Hermite shape functions and their derivatives. Eigenvalue error is O(h⁴) for smooth modes.

mod eigen;
mod model;
pub(crate) mod shape;
mod subspace;
mod supports;

pub use eigen::EigenReduction;
pub use model::Section;
pub use shape::{FeModes, StaticDeflection};
pub use supports::{PointMass, PointSupport, SupportKind};

use crate::banded::SymmetricBand;
use shape::Mesh;

/// The assembled finite-element beam.
#[derive(Debug, Clone, PartialEq)]
pub struct FeBeam {
    mesh: Mesh,
    /// Global DOF → free DOF index (None if constrained).
    free_index: Vec<Option<usize>>,
    /// Stiffness K on the free DOFs (banded, half-bandwidth 3).
    stiffness: SymmetricBand,
    /// Consistent mass M (plus point masses) on the free DOFs (banded).
    mass: SymmetricBand,
    /// Spectral shift σ of [`EigenReduction::ShiftedStiffness`].
    shift: f64,
    /// Free DOF index and stiffness of every elastic bearing spring.
    springs: Vec<(usize, f64)>,
}

impl FeBeam {
    /// Node positions.
    pub fn nodes(&self) -> &[f64] {
        &self.mesh.nodes
    }

    /// Number of unconstrained DOFs.
    pub fn n_free_dofs(&self) -> usize {
        self.stiffness.n()
    }
}
