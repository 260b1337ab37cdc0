//! The exact solves of a response table's nodes, on two threads (issue #14).
//!
//! Each node is the exact discrete solution at its approach: the dense factor's active-set
//! solve ([`set_solve`]; references.md §C8.4, "Set changes by the factor"), started from a
//! neighbouring node's contact set, exact to round-off, or NormCG to [`NODE_TOL`] where that
//! does not converge and on grids above 1024 elements (`MAX_FACTOR_GRID`). A batch of nodes is
//! split into two contiguous halves solved by two solvers on two threads (`std::thread::scope`,
//! not rayon: the table is built inside a law's evaluation, within rayon's parallel pass over
//! the wheels, where a nested rayon job could run another wheel that waits for this very
//! table). The split is always in two, whatever the number of threads, and each half runs in
//! a fixed order on its own solver, so the table is the same on any machine.

use crate::error::ContactError;
use crate::grid::Grid;
use crate::material::Material;
use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};
use crate::solution::NormalSolution;

use super::super::reuse::grid_factor;
use super::super::set_factor::SetFactor;
use super::super::set_solve::{self, SetSolveWork};
#[cfg(doc)]
use super::NODE_TOL;
use super::{Node, Solved};

/// A node to solve: its approach and its start (a pressure whose positive elements are the
/// start set), or `None` for the previous node of the same half (zero for its first).
pub(super) type Job = (f64, Option<Vec<f64>>);

/// The exact solver of one half of the nodes (module documentation).
pub(super) struct NodeSolver {
    pub(super) solver: NormalSolver,
    factor: Option<SetFactor>,
    work: SetSolveWork,
    /// Zero gap shapes: the factor's solve carries three response lanes the table does not
    /// use.
    shapes: [Vec<f64>; 3],
    options: SolverOptions,
}

impl NodeSolver {
    pub(super) fn new(
        grid: Grid,
        material: Material,
        options: SolverOptions,
    ) -> Result<Self, ContactError> {
        let mut solver = NormalSolver::new(grid, material)?;
        let n = grid.len();
        let factor = grid_factor(&mut solver)?;
        Ok(NodeSolver {
            solver,
            factor,
            work: SetSolveWork::default(),
            shapes: std::array::from_fn(|_| vec![0.0; n]),
            options,
        })
    }

    /// The node at `delta`, started from the contact set {e : `start`\[e\] > 0} (a
    /// neighbouring node's pressure) by the factor, or from the pressure `start` by NormCG.
    fn solve(
        &mut self,
        base_gap: &[f64],
        delta: f64,
        start: &[f64],
    ) -> Result<Solved, ContactError> {
        if let Some(factor) = self.factor.as_mut() {
            self.work.in_contact.clear();
            self.work.in_contact.extend(start.iter().map(|&p| p > 0.0));
            if let Some(s) = set_solve::solve(
                factor,
                &mut self.solver,
                base_gap,
                delta,
                &self.shapes,
                &mut self.work,
            )? {
                return Ok(solved(&self.solver, s, delta));
            }
        }
        self.solver.set_initial_pressure(start)?;
        let s = self
            .solver
            .solve(base_gap, NormalLoad::Approach(delta), &self.options)?;
        Ok(solved(&self.solver, s, delta))
    }
}

/// A node with its fields from the solution `s` at approach `delta`.
fn solved(solver: &NormalSolver, s: NormalSolution, delta: f64) -> Solved {
    let grid = *solver.grid();
    let (nx, area) = (grid.nx, grid.element_area());
    let mut column_force = vec![0.0; nx];
    for (k, p) in s.pressure.iter().enumerate() {
        column_force[k % nx] += p * area;
    }
    let work: f64 = s
        .pressure
        .iter()
        .zip(&s.displacement)
        .map(|(p, u)| p * u)
        .sum();
    let patch = if s.elements_in_contact > 0 {
        let (a, b) = s.patch_half_widths();
        (2.0 * a, 2.0 * b)
    } else {
        (0.0, 0.0)
    };
    Solved {
        node: Node {
            delta,
            force: s.normal_force,
            energy: 0.5 * area * work,
            max_pressure: s.max_pressure,
            patch,
        },
        column_force,
        pressure: s.pressure,
    }
}

/// Solves `jobs` in two contiguous halves of about equal cost, the first on this thread with
/// `workers[0]`, the second on a scoped thread with `workers[1]`; the nodes in the order of
/// `jobs`. A node's cost grows with the square of the order of its factor, the number of
/// elements in contact, which grows in proportion to t = δ − `h_min` (the Hertz area ∝ δ), so
/// the halves have equal sums of t².
pub(super) fn solve_in_two(
    workers: &mut [NodeSolver; 2],
    base_gap: &[f64],
    h_min: f64,
    jobs: Vec<Job>,
) -> Result<Vec<Solved>, ContactError> {
    let cost = |job: &Job| (job.0 - h_min).max(0.0).powi(2);
    let total: f64 = jobs.iter().map(cost).sum();
    let mut sum = 0.0;
    let half = jobs
        .iter()
        .position(|job| {
            sum += cost(job);
            sum >= 0.5 * total
        })
        .map_or(jobs.len(), |i| i + 1);
    let (first, second) = jobs.split_at(half);
    let [w0, w1] = workers;
    let (a, b) = std::thread::scope(|s| {
        let other = s.spawn(|| solve_half(w1, base_gap, second));
        let mine = solve_half(w0, base_gap, first);
        (mine, other.join())
    });
    let mut solved = a?;
    match b {
        Ok(b) => solved.extend(b?),
        Err(panic) => std::panic::resume_unwind(panic),
    }
    Ok(solved)
}

/// The nodes of `jobs` in order by one solver.
fn solve_half(
    worker: &mut NodeSolver,
    base_gap: &[f64],
    jobs: &[Job],
) -> Result<Vec<Solved>, ContactError> {
    let mut solved: Vec<Solved> = Vec::with_capacity(jobs.len());
    let mut previous = vec![0.0; base_gap.len()];
    for (d, start) in jobs {
        let start = match start {
            Some(start) => start.as_slice(),
            None => {
                if let Some(last) = solved.last() {
                    previous.copy_from_slice(&last.pressure);
                }
                previous.as_slice()
            }
        };
        solved.push(worker.solve(base_gap, *d, start)?);
    }
    Ok(solved)
}
