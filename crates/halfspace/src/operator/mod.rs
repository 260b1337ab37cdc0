//! The influence operators of the half-space, behind traits with a fast and a slow
//! implementation (references.md §C3.3).
//!
//! **Normal problem.** A_IJ is Love's displacement at the centre of element I under a unit
//! pressure on element J ([`crate::influence::normal_influence`]); it depends on the offset
//! of the two elements only, so the product u = A p is a discrete convolution.
//!
//! * [`FftInfluence`]: the zero-padded FFT convolution with the tabulated circulant kernel,
//!   O(n log n);
//! * [`DenseInfluence`]: the sums over the non-zero inputs with the same tabulated kernel,
//!   O(n·m) for m non-zero inputs: faster on small grids with small contact sets;
//! * [`NormalInfluence`]: the default operator of [`crate::NormalSolver`]: per product the
//!   FFT or, on small grids and for few non-zero inputs, the dense sums (measured cross-over);
//! * [`DirectInfluence`]: the O(n²) sum straight from Love's formula; its products use no
//!   table and no FFT (only its preconditioner is the FFT one, see below): the first-class
//!   slow oracle (as RustFFT's `Dft` is for its FFTs), for tests and for checking the fast
//!   path on new grids.
//!
//! **Tangential problem.** The tangential solver needs a family of kernels (A_xx, A_xy,
//! A_yy, the coupling A_xn, A_yn, each also with shifted observation points for rolling):
//! [`TangentialInfluenceOperator`] in [`tangential`], again with an FFT and a direct
//! implementation.
//!
//! NormCG ([`crate::normcg`]) and the tangential sweeps ([`crate::tangential`]) are generic
//! over these traits (monomorphised: no dynamic dispatch in the inner loops); their public
//! constructors `new` use the FFT operators, `with_operator` takes any implementation. A
//! solve with the direct operators follows the same iterates as one with the FFT operators
//! up to round-off (both use the same FFT preconditioner, which only steers the iteration),
//! so the two solutions agree to ~1e-12 (tests/operator_solvers.rs).

pub mod auto;
pub mod dense;
pub mod tangential;

use crate::convolution::{FftConvolution, KernelSpectrum};
use crate::error::{ContactError, positive};
use crate::grid::Grid;
use crate::influence::{circulant_kernel, normal_influence};
use crate::material::Material;

pub use auto::NormalInfluence;
pub use dense::DenseInfluence;
pub use tangential::{
    DirectTangentialInfluence, FftTangentialInfluence, TangentialInfluenceOperator,
    TangentialKernel, Update,
};

/// u = A p on a grid: `pressure` \[Pa\] in, normal displacement difference \[m\] out, both
/// with one value per element (x fastest), plus what NormCG needs besides the product.
pub trait InfluenceOperator {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;

    /// The combined material whose influence coefficients the operator holds.
    fn material(&self) -> &Material;

    /// `displacement = A pressure`. Panics if a slice does not have one value per element.
    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]);

    /// `displacement += Σ_j Δp_j A e_j` for the few `(j, Δp_j)` in `changes`: the columns of
    /// A for a sparse pressure change (O(n) per column).
    fn add_columns(&mut self, changes: &[(usize, f64)], displacement: &mut [f64]);

    /// `out = M residual` with M ≈ A⁻¹ symmetric positive definite (NormCG's preconditioner;
    /// it changes the number of iterations, never the solution).
    fn precondition(&mut self, residual: &[f64], out: &mut [f64]);

    /// [`Self::precondition`] where only the grid rows `rows` of `out` are needed (row iy
    /// holds the elements `iy·nx .. (iy + 1)·nx`; NormCG passes the rows of the contact set):
    /// those rows equal [`Self::precondition`]'s, the others are set to zero. The default
    /// computes the whole product.
    fn precondition_rows(
        &mut self,
        residual: &[f64],
        out: &mut [f64],
        rows: std::ops::Range<usize>,
    ) {
        self.precondition(residual, out);
        let nx = self.grid().nx;
        out[..rows.start * nx].fill(0.0);
        out[rows.end * nx..].fill(0.0);
    }
}

/// The FFT implementation (module documentation). Plans, the kernel table and the spectra of
/// A and of the preconditioner are made once; no method allocates.
#[derive(Debug)]
pub struct FftInfluence {
    grid: Grid,
    material: Material,
    conv: FftConvolution,
    spectrum: KernelSpectrum,
    /// The influence kernel in circulant order (for exact sparse column updates).
    kernel: Vec<f64>,
    /// Vollebregt's FFT preconditioner: the convolution whose spectrum is the reciprocal of
    /// A's (references.md §C3.4).
    inverse: KernelSpectrum,
}

impl FftInfluence {
    /// Tabulates A's kernel for `grid` and `material`, plans the FFTs and builds the
    /// preconditioner.
    pub fn new(grid: Grid, material: &Material) -> Result<Self, ContactError> {
        let grid = Grid::new(grid.nx, grid.ny, grid.dx, grid.dy, grid.x0, grid.y0)?;
        positive("G", material.g)?;
        let conv = FftConvolution::new(grid.nx, grid.ny);
        let kernel = circulant_kernel(material, &grid);
        let spectrum = conv.kernel_spectrum(&kernel);
        let inverse = spectrum
            .reciprocal(conv.normalisation())
            .ok_or_else(|| ContactError::Fft("influence spectrum has a zero coefficient".into()))?;
        Ok(Self {
            grid,
            material: *material,
            conv,
            spectrum,
            kernel,
            inverse,
        })
    }
}

impl InfluenceOperator for FftInfluence {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn material(&self) -> &Material {
        &self.material
    }

    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        self.conv.apply(&self.spectrum, pressure, displacement);
    }

    /// Reads the columns from the circulant kernel table: contiguous rows, no allocation. On
    /// large grids the rows are split over the rayon threads; every element receives the
    /// columns in the order of `changes` whatever the split, so the result does not depend
    /// on the number of threads.
    fn add_columns(&mut self, changes: &[(usize, f64)], displacement: &mut [f64]) {
        let (nx, ny) = (self.grid.nx, self.grid.ny);
        assert_eq!(displacement.len(), nx * ny, "one value per element");
        let kernel = &self.kernel;
        let rows_of = |first: usize, u_rows: &mut [f64]| {
            for &(j, dp) in changes {
                add_column(kernel, (nx, ny), j, dp, first, u_rows);
            }
        };
        if nx * ny >= PARALLEL_ELEMENTS {
            use rayon::prelude::*;
            let rows = ny.div_ceil(rayon::current_num_threads().max(1));
            displacement
                .par_chunks_mut(rows * nx)
                .enumerate()
                .with_max_len(1)
                .for_each(|(k, u_rows)| rows_of(k * rows, u_rows));
        } else {
            rows_of(0, displacement);
        }
    }

    fn precondition(&mut self, residual: &[f64], out: &mut [f64]) {
        self.conv.apply(&self.inverse, residual, out);
    }

    /// Skips the last (inverse) row transforms of the rows not needed.
    fn precondition_rows(
        &mut self,
        residual: &[f64],
        out: &mut [f64],
        rows: std::ops::Range<usize>,
    ) {
        self.conv.apply_rows(&self.inverse, residual, out, rows);
    }
}

/// Grids with at least this many elements split [`FftInfluence::add_columns`] over the rayon
/// threads.
const PARALLEL_ELEMENTS: usize = 128 * 128;

/// `u_rows += dp · A e_j` on the grid rows `first ..` held by `u_rows`, with A's circulant
/// kernel table on the `2nx × 2ny` embedding.
fn add_column(
    kernel: &[f64],
    (nx, ny): (usize, usize),
    j: usize,
    dp: f64,
    first: usize,
    u_rows: &mut [f64],
) {
    let (mx, my) = (2 * nx, 2 * ny);
    let (jx, jy) = (j % nx, j / nx);
    for (r, u_row) in u_rows.chunks_mut(nx).enumerate() {
        let iy = first + r;
        let dj = (iy + my - jy) % my;
        let row = &kernel[dj * mx..(dj + 1) * mx];
        // Offsets ix − jx < 0 wrap to the end of the circulant row.
        let (left, right) = u_row.split_at_mut(jx);
        for (u, k) in left.iter_mut().zip(&row[mx - jx..]) {
            *u += k * dp;
        }
        for (u, k) in right.iter_mut().zip(row) {
            *u += k * dp;
        }
    }
}

/// The direct O(n²) sum u_I = Σ_J A(x_I − x_J, y_I − y_J) p_J with every coefficient
/// evaluated from Love's formula (module documentation). Its preconditioner is the FFT one
/// of [`FftInfluence`], so that solves with either operator take the same path.
#[derive(Debug)]
pub struct DirectInfluence {
    grid: Grid,
    material: Material,
    /// Used only for [`InfluenceOperator::precondition`].
    preconditioner: FftInfluence,
}

impl DirectInfluence {
    /// The oracle on `grid` for `material`.
    pub fn new(grid: Grid, material: Material) -> Result<Self, ContactError> {
        let preconditioner = FftInfluence::new(grid, &material)?;
        Ok(Self {
            grid: preconditioner.grid,
            material,
            preconditioner,
        })
    }

    /// A_IJ from Love's formula.
    fn coefficient(&self, i: usize, j: usize) -> f64 {
        let g = &self.grid;
        let ((xi, yi), (xj, yj)) = (g.centre(i), g.centre(j));
        normal_influence(&self.material, xi - xj, yi - yj, g.dx, g.dy)
    }

    /// One value u_I of A p (O(n)), for spot checks on grids too large for the full product.
    pub fn displacement_at(&self, index: usize, pressure: &[f64]) -> f64 {
        assert_eq!(pressure.len(), self.grid.len(), "one pressure per element");
        pressure
            .iter()
            .enumerate()
            .map(|(j, p)| self.coefficient(index, j) * p)
            .sum()
    }
}

impl InfluenceOperator for DirectInfluence {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn material(&self) -> &Material {
        &self.material
    }

    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        assert_eq!(displacement.len(), self.grid.len(), "one value per element");
        for (i, u) in displacement.iter_mut().enumerate() {
            *u = self.displacement_at(i, pressure);
        }
    }

    fn add_columns(&mut self, changes: &[(usize, f64)], displacement: &mut [f64]) {
        assert_eq!(displacement.len(), self.grid.len(), "one value per element");
        for &(j, dp) in changes {
            for (i, u) in displacement.iter_mut().enumerate() {
                *u += self.coefficient(i, j) * dp;
            }
        }
    }

    fn precondition(&mut self, residual: &[f64], out: &mut [f64]) {
        self.preconditioner.precondition(residual, out);
    }

    fn precondition_rows(
        &mut self,
        residual: &[f64],
        out: &mut [f64],
        rows: std::ops::Range<usize>,
    ) {
        self.preconditioner.precondition_rows(residual, out, rows);
    }
}
