//! The influence operator u = A p of the normal problem, behind one trait with a fast and
//! a slow implementation (references.md §C3.3).
//!
//! A_IJ is Love's displacement at the centre of element I under a unit pressure on element J
//! ([`crate::influence::normal_influence`]); it depends on the offset of the two elements
//! only, so the product is a discrete convolution.
//!
//! * [`FftInfluence`]: the zero-padded FFT convolution with the tabulated circulant kernel,
//!   O(n log n) (the path of [`crate::NormalSolver`]);
//! * [`DirectInfluence`]: the O(n²) sum straight from Love's formula, with no table and no
//!   FFT: the first-class slow oracle (as RustFFT's `Dft` is for its FFTs), for tests and
//!   for checking the fast path on new grids.
//!
//! The solvers still hold their own FFT convolution; making NormCG and the tangential sweeps
//! generic over this trait is not done yet.

use crate::convolution::{FftConvolution, KernelSpectrum};
use crate::error::ContactError;
use crate::grid::Grid;
use crate::influence::{circulant_kernel, normal_influence};
use crate::material::Material;

/// u = A p on a grid: `pressure` \[Pa\] in, normal displacement difference \[m\] out, both
/// with one value per element (x fastest).
pub trait InfluenceOperator {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;

    /// `displacement = A pressure`. Panics if a slice does not have one value per element.
    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]);
}

/// The FFT implementation (module documentation). Plans and the kernel spectrum are made
/// once; [`InfluenceOperator::apply`] does not allocate.
#[derive(Debug)]
pub struct FftInfluence {
    grid: Grid,
    conv: FftConvolution,
    spectrum: KernelSpectrum,
}

impl FftInfluence {
    /// Tabulates A's kernel for `grid` and `material` and plans the FFTs.
    pub fn new(grid: Grid, material: &Material) -> Result<Self, ContactError> {
        let grid = Grid::new(grid.nx, grid.ny, grid.dx, grid.dy, grid.x0, grid.y0)?;
        let conv = FftConvolution::new(grid.nx, grid.ny);
        let spectrum = conv.kernel_spectrum(&circulant_kernel(material, &grid));
        Ok(Self {
            grid,
            conv,
            spectrum,
        })
    }
}

impl InfluenceOperator for FftInfluence {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        self.conv.apply(&self.spectrum, pressure, displacement);
    }
}

/// The direct O(n²) sum u_I = Σ_J A(x_I − x_J, y_I − y_J) p_J with every coefficient
/// evaluated from Love's formula (module documentation).
#[derive(Debug, Clone)]
pub struct DirectInfluence {
    grid: Grid,
    material: Material,
}

impl DirectInfluence {
    /// The oracle on `grid` for `material`.
    pub fn new(grid: Grid, material: Material) -> Result<Self, ContactError> {
        let grid = Grid::new(grid.nx, grid.ny, grid.dx, grid.dy, grid.x0, grid.y0)?;
        Ok(Self { grid, material })
    }

    /// One value u_I of A p (O(n)), for spot checks on grids too large for the full product.
    pub fn displacement_at(&self, index: usize, pressure: &[f64]) -> f64 {
        let g = &self.grid;
        assert_eq!(pressure.len(), g.len(), "one pressure per element");
        let (xi, yi) = g.centre(index);
        pressure
            .iter()
            .enumerate()
            .map(|(j, p)| {
                let (xj, yj) = g.centre(j);
                normal_influence(&self.material, xi - xj, yi - yj, g.dx, g.dy) * p
            })
            .sum()
    }
}

impl InfluenceOperator for DirectInfluence {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        assert_eq!(displacement.len(), self.grid.len(), "one value per element");
        for (i, u) in displacement.iter_mut().enumerate() {
            *u = self.displacement_at(i, pressure);
        }
    }
}
