//! Linear algebra of the coupled step (references.md §D4.2).
//!
//! The contact-free step matrix `A = c_M M + c_C C + c_K K` of the bridge modes and the vehicle
//! is block diagonal: one 1×1 block per bridge mode (mass-normalised modal equations) and one
//! 1×1 or 2×2 block per wheel (wheel mass, suspension spring–damper, body mass), so `A⁻¹v`
//! costs O(n). The contact adds a low-rank term `U Vᵀ` (one column per wheel in contact):
//!
//! * Sherman–Morrison (one column): `(A + u vᵀ)⁻¹ r = A⁻¹r − A⁻¹u (vᵀA⁻¹r)/(1 + vᵀA⁻¹u)`;
//! * Woodbury (k columns): `(A + U Vᵀ)⁻¹ r = A⁻¹r − A⁻¹U (I_k + VᵀA⁻¹U)⁻¹ VᵀA⁻¹r`, with the
//!   k × k capacitance matrix `I_k + VᵀA⁻¹U` (all wheels couple through the bridge modes).
//!
//! [`contact_update`] applies both in a force form that also admits rigid contacts;
//! [`dense_contact_update`] (an LU factorisation with partial pivoting of the bordered system)
//! is the reference. The dense solves (the k × k capacitance matrix, the bordered system) use
//! `integrate`'s [`integrate::DenseLu`] (faer's partial-pivoting LU in preallocated storage). A singular
//! block or matrix is an error ([`Singular`]), never skipped.
//!
//! * [`block_diagonal`]: the step matrix A and its solves;
//! * [`banded`]: the band factorisation and sparse rows of a large multibody block;
//! * [`low_rank`]: the contact update and its dense reference.

pub mod banded;
pub mod block_diagonal;
pub mod low_rank;

pub use block_diagonal::{BlockDiagonal, MAX_DENSE_BLOCK};
pub use low_rank::{
    CapacitanceWork, DenseWork, contact_update, dense_contact_update, small_solve_in_place,
};

/// A singular or non-finite matrix met by a solve of the coupled step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("singular or non-finite {what}")]
pub struct Singular {
    /// Which matrix: `step-matrix block`, `capacitance matrix`, `bordered matrix`.
    pub what: &'static str,
}

/// The dot product.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
