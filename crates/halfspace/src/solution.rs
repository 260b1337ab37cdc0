//! Results of a normal contact computation.

use crate::grid::Grid;

/// The solution of the normal contact problem on a grid. SI units.
#[derive(Debug, Clone)]
pub struct NormalSolution {
    /// The grid the fields live on.
    pub grid: Grid,
    /// Pressure p_n per element \[Pa\] (≥ 0; compression positive).
    pub pressure: Vec<f64>,
    /// Contact set: true where p_n > 0.
    pub in_contact: Vec<bool>,
    /// Deformed distance e = h − δ + u_n per element \[m\] (0 in contact, > 0 outside).
    pub deformed_distance: Vec<f64>,
    /// Normal surface displacement difference u_n = Σ A p \[m\].
    pub displacement: Vec<f64>,
    /// Total normal force F_n = ΔA Σ p \[N\].
    pub normal_force: f64,
    /// Approach δ of the two bodies \[m\].
    pub approach: f64,
    /// Largest element pressure \[Pa\].
    pub max_pressure: f64,
    /// Contact area ΔA · (elements in contact) \[m²\].
    pub contact_area: f64,
    /// Number of elements in contact.
    pub elements_in_contact: usize,
    /// Centre of pressure (x, y) \[m\] (the grid origin if there is no contact).
    pub centre_of_pressure: (f64, f64),
    /// NormCG iterations used.
    pub iterations: usize,
    /// Final convergence measure ‖Δp‖_rms / ‖p‖_rms of the last iteration (CONTACT's criterion).
    pub residual: f64,
    /// Whether the stopping rule was met (false only inside a `NotConverged` error).
    pub converged: bool,
    /// Sensitivity dF_n/dδ [N/m] from the problem linearised on the contact set, if computed.
    pub dfn_dapproach: Option<f64>,
    /// Iterations of the sensitivity solve (0 if not computed).
    pub sensitivity_iterations: usize,
}

impl NormalSolution {
    /// A solution with no contact (δ below the smallest gap).
    pub(crate) fn empty(grid: Grid, gap: &[f64], approach: f64) -> Self {
        let n = grid.len();
        NormalSolution {
            grid,
            pressure: vec![0.0; n],
            in_contact: vec![false; n],
            deformed_distance: gap.iter().map(|h| h - approach).collect(),
            displacement: vec![0.0; n],
            normal_force: 0.0,
            approach,
            max_pressure: 0.0,
            contact_area: 0.0,
            elements_in_contact: 0,
            centre_of_pressure: (grid.x0, grid.y0),
            iterations: 0,
            residual: 0.0,
            converged: true,
            dfn_dapproach: Some(0.0),
            sensitivity_iterations: 0,
        }
    }

    /// Semi-axes of the contact patch estimated from its extent: half the number of
    /// contact elements along x (at the row through the centre of pressure) times dx, and
    /// likewise along y. Used for reporting and for comparisons with Hertz.
    pub fn patch_half_widths(&self) -> (f64, f64) {
        let g = &self.grid;
        let mut cols = vec![false; g.nx];
        let mut rows = vec![false; g.ny];
        for (k, &c) in self.in_contact.iter().enumerate() {
            if c {
                cols[k % g.nx] = true;
                rows[k / g.nx] = true;
            }
        }
        let nxc = cols.iter().filter(|&&c| c).count();
        let nyc = rows.iter().filter(|&&c| c).count();
        (0.5 * nxc as f64 * g.dx, 0.5 * nyc as f64 * g.dy)
    }
}
