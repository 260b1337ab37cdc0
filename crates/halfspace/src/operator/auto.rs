//! The default normal influence operator of [`crate::NormalSolver::new`]: the FFT
//! convolution, and on small grids the dense sums of [`DenseInfluence`] for the products whose
//! input has few non-zero values (references.md §C3.3).
//!
//! Choice per product: the dense sum costs about n·m multiply-adds for m non-zero inputs on
//! n elements, the padded FFT about n·log₂(4n) times a larger constant. Measured on the
//! 2-core development machine (`examples/small_grid.rs`: Hertz spheres whose contact patch
//! covers 30, 60 and 90 % of the grid width, n = 4² … 64², both operators in the same run) the
//! two cost the same at m ≈ 25–40 non-zero inputs for n = 36 … 576, i.e. at m ≈ 3·log₂(4n):
//! the dense sum is used below that (`DENSE_FACTOR`), on grids of at most
//! [`DENSE_MAX_ELEMENTS`] elements (beyond, m ≈ 3·log₂(4n) is a negligible contact set and the
//! tables are not built). Both give the same products to round-off
//! (tests/influence_operator.rs), so the choice never changes a solution beyond round-off.

use super::{DenseInfluence, FftInfluence, InfluenceOperator};
use crate::error::ContactError;
use crate::grid::Grid;
use crate::material::Material;

/// Largest grid (elements) on which the dense sums are considered.
pub const DENSE_MAX_ELEMENTS: usize = 64 * 64;

/// Products with at most `DENSE_FACTOR · log₂(4n)` non-zero inputs use the dense sums.
const DENSE_FACTOR: f64 = 3.0;

/// The FFT operator with the dense sums for sparse inputs on small grids (module
/// documentation).
#[derive(Debug)]
pub struct NormalInfluence {
    fft: FftInfluence,
    /// The dense sums and the largest non-zero count for which they are used.
    dense: Option<(DenseInfluence, usize)>,
    /// Products done by the dense sums (statistics).
    dense_products: usize,
}

impl NormalInfluence {
    /// The FFT operator for `grid` and `material`, with the dense sums when the grid has at
    /// most [`DENSE_MAX_ELEMENTS`] elements.
    pub fn new(grid: Grid, material: &Material) -> Result<Self, ContactError> {
        let fft = FftInfluence::new(grid, material)?;
        let n = grid.len();
        let dense = if n <= DENSE_MAX_ELEMENTS {
            let limit = (DENSE_FACTOR * ((4 * n) as f64).log2()) as usize;
            Some((DenseInfluence::new(grid, material)?, limit))
        } else {
            None
        };
        Ok(NormalInfluence {
            fft,
            dense,
            dense_products: 0,
        })
    }

    /// Number of products (and preconditioner applications) done by the dense sums.
    pub fn dense_products(&self) -> usize {
        self.dense_products
    }

    /// The dense operator if `input` has few enough non-zero values.
    fn dense_for(&mut self, input: &[f64]) -> Option<&mut DenseInfluence> {
        let (dense, limit) = self.dense.as_mut()?;
        let mut count = 0;
        for &v in input {
            count += usize::from(v != 0.0);
            if count > *limit {
                return None;
            }
        }
        self.dense_products += 1;
        Some(dense)
    }
}

impl InfluenceOperator for NormalInfluence {
    fn grid(&self) -> &Grid {
        self.fft.grid()
    }

    fn material(&self) -> &Material {
        self.fft.material()
    }

    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        match self.dense_for(pressure) {
            Some(dense) => dense.apply(pressure, displacement),
            None => self.fft.apply(pressure, displacement),
        }
    }

    fn add_columns(&mut self, changes: &[(usize, f64)], displacement: &mut [f64]) {
        self.fft.add_columns(changes, displacement);
    }

    fn precondition(&mut self, residual: &[f64], out: &mut [f64]) {
        match self.dense_for(residual) {
            Some(dense) => dense.precondition(residual, out),
            None => self.fft.precondition(residual, out),
        }
    }

    fn precondition_rows(
        &mut self,
        residual: &[f64],
        out: &mut [f64],
        rows: std::ops::Range<usize>,
    ) {
        match self.dense_for(residual) {
            Some(dense) => dense.precondition_rows(residual, out, rows),
            None => self.fft.precondition_rows(residual, out, rows),
        }
    }
}
