//! The normal influence operator by direct products over the non-zero inputs, for small
//! grids where an FFT convolution costs more than the sum (references.md §C3.3).
//!
//! A_IJ = k(|x_I − x_J|, |y_I − y_J|) with the tabulated kernel of the FFT operator (Love's
//! formula, even in both offsets); u = A p is summed column by column over the elements with
//! p_J ≠ 0 only, i.e. over NormCG's contact set: O(n·|C|) against the FFT's O(n log n) for the
//! padded grid. The preconditioner is the same operator as the FFT one (the convolution whose
//! spectrum is the reciprocal of A's, §C3.4), tabulated once as its impulse response (an even
//! kernel too) and applied by the same sums on the rows asked for. Products equal the FFT
//! operator's to round-off (tests/influence_operator.rs); a NormCG solve over either takes
//! the same iterations to the same solution.

use super::{FftInfluence, InfluenceOperator};
use crate::convolution::FftConvolution;
use crate::error::ContactError;
use crate::grid::Grid;
use crate::influence::circulant_kernel;
use crate::material::Material;

/// The dense-sum implementation (module documentation). Holds two nx·ny tables (A's kernel
/// and the preconditioner's) and a list of the non-zero inputs; no method allocates.
#[derive(Debug, Clone)]
pub struct DenseInfluence {
    grid: Grid,
    material: Material,
    /// k_A(dx, dy) at `dy * nx + dx` for the offsets 0 ≤ dx < nx, 0 ≤ dy < ny.
    kernel: Vec<f64>,
    /// The preconditioner's kernel in the same layout.
    inverse: Vec<f64>,
    /// Scratch: the non-zero inputs of a product as (index, value).
    nonzero: Vec<(usize, f64)>,
}

impl DenseInfluence {
    /// Tabulates A's kernel for `grid` and `material` and the preconditioner's (one FFT
    /// convolution of a unit input).
    pub fn new(grid: Grid, material: &Material) -> Result<Self, ContactError> {
        let fft = FftInfluence::new(grid, material)?;
        let grid = fft.grid;
        let (nx, ny) = (grid.nx, grid.ny);
        let table = circulant_kernel(material, &grid);
        let mut kernel = vec![0.0; nx * ny];
        for dy in 0..ny {
            kernel[dy * nx..(dy + 1) * nx].copy_from_slice(&table[dy * 2 * nx..dy * 2 * nx + nx]);
        }
        // The preconditioner's impulse response: M e_0 holds m(dx, dy) at dy·nx + dx.
        let mut unit = vec![0.0; nx * ny];
        unit[0] = 1.0;
        let mut inverse = vec![0.0; nx * ny];
        let mut conv = FftConvolution::new(nx, ny);
        conv.apply(&fft.inverse, &unit, &mut inverse);
        Ok(DenseInfluence {
            grid,
            material: *material,
            kernel,
            inverse,
            nonzero: Vec::with_capacity(nx * ny),
        })
    }
}

/// `output[rows] = K input` for the even kernel `kernel` (layout of [`DenseInfluence`]), summed
/// over the non-zero inputs listed in `nonzero`; the other rows of `output` are set to zero.
fn product(
    kernel: &[f64],
    nx: usize,
    nonzero: &[(usize, f64)],
    output: &mut [f64],
    rows: std::ops::Range<usize>,
) {
    output.fill(0.0);
    for &(j, value) in nonzero {
        let (jx, jy) = (j % nx, j / nx);
        for iy in rows.clone() {
            let k = &kernel[iy.abs_diff(jy) * nx..(iy.abs_diff(jy) + 1) * nx];
            let out = &mut output[iy * nx..(iy + 1) * nx];
            let (left, right) = out.split_at_mut(jx);
            // ix < jx: offset jx − ix, read backwards from k[jx] (left is ix = 0 .. jx).
            for (u, c) in left.iter_mut().zip(k[1..=jx].iter().rev()) {
                *u += c * value;
            }
            for (u, c) in right.iter_mut().zip(k) {
                *u += c * value;
            }
        }
    }
}

impl DenseInfluence {
    fn collect(&mut self, input: &[f64]) {
        assert_eq!(input.len(), self.grid.len(), "one value per element");
        self.nonzero.clear();
        self.nonzero.extend(
            input
                .iter()
                .enumerate()
                .filter(|(_, v)| **v != 0.0)
                .map(|(j, v)| (j, *v)),
        );
    }
}

impl InfluenceOperator for DenseInfluence {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn material(&self) -> &Material {
        &self.material
    }

    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        assert_eq!(displacement.len(), self.grid.len(), "one value per element");
        self.collect(pressure);
        let ny = self.grid.ny;
        product(
            &self.kernel,
            self.grid.nx,
            &self.nonzero,
            displacement,
            0..ny,
        );
    }

    fn add_columns(&mut self, changes: &[(usize, f64)], displacement: &mut [f64]) {
        assert_eq!(displacement.len(), self.grid.len(), "one value per element");
        let nx = self.grid.nx;
        for &(j, dp) in changes {
            let (jx, jy) = (j % nx, j / nx);
            for (iy, out) in displacement.chunks_mut(nx).enumerate() {
                let k = &self.kernel[iy.abs_diff(jy) * nx..(iy.abs_diff(jy) + 1) * nx];
                let (left, right) = out.split_at_mut(jx);
                for (u, c) in left.iter_mut().zip(k[1..=jx].iter().rev()) {
                    *u += c * dp;
                }
                for (u, c) in right.iter_mut().zip(k) {
                    *u += c * dp;
                }
            }
        }
    }

    fn precondition(&mut self, residual: &[f64], out: &mut [f64]) {
        let ny = self.grid.ny;
        self.precondition_rows(residual, out, 0..ny);
    }

    fn precondition_rows(
        &mut self,
        residual: &[f64],
        out: &mut [f64],
        rows: std::ops::Range<usize>,
    ) {
        assert_eq!(out.len(), self.grid.len(), "one value per element");
        self.collect(residual);
        product(&self.inverse, self.grid.nx, &self.nonzero, out, rows);
    }
}
