//! NormCG: the bound-constrained conjugate-gradient solver of the normal contact problem.
//!
//! Find p ≥ 0 on the grid with (references.md §C3.4; Vollebregt, J. Comput. Phys. 257A (2014) 333)
//!
//! ```text
//! e_I = h_I − δ + Σ_J A_IJ p_J = 0   and p_I ≥ 0   on the contact set C,
//! e_I > 0                            and p_I = 0   outside C,
//! ```
//!
//! i.e. minimise ½ pᵀA p + pᵀ(h − δ) subject to p ≥ 0. Each iteration is a preconditioned
//! conjugate-gradient step restricted to C, followed by a projection:
//!
//! 1. r = −e on C; z = M r masked to C, with M the operator's preconditioner (for the FFT
//!    operator the convolution whose spectrum is the reciprocal of A's, an approximate
//!    inverse of A);
//! 2. Polak–Ribière direction v = z + β v, β = max(0, zᵀ(r − r_prev)/(z_prevᵀ r_prev)),
//!    restarted (β = 0) whenever C changed;
//! 3. q = A v, α = rᵀv / vᵀq, p ← p + α v, u ← u + α q;
//! 4. projection: elements with p < 0 leave C (p = 0); elements outside C with e < 0
//!    enter C. After a projection u = A p is recomputed exactly.
//!
//! **Passes over memory.** Steps 1–3 and the update of p run over the elements of C only
//! (kept as an ascending index list); r and v are zero outside C, so the convolutions skip
//! their zero rows, and the preconditioned residual is transformed back on the rows of C
//! only ([`InfluenceOperator::precondition_rows`]). One pass over the whole grid per
//! iteration remains (`scan`): u ← u + α q outside C fused with the projection, split over
//! the rayon threads on large grids without any sum over the parts, so the result does not
//! depend on the number of threads. All sums run over C in ascending order, as the
//! whole-grid sums they replace (whose other terms are zero): the iterates are those of the
//! plain implementation.
//!
//! With a prescribed total force F the approach δ is a Lagrange multiplier for
//! ΔA Σ p = F. It is handled by deflation of the constant: δ = mean_C(h + u) makes the
//! residual mean-free, z and v are made mean-free on C so that the force is conserved by
//! every update, and the pressure is rescaled to F after a projection.
//!
//! **Stopping rule.** Stop when an iteration leaves C unchanged and
//! ‖Δp‖_rms ≤ tol · ‖p‖_rms (CONTACT's criterion, references.md §C3.7), and a final exact recomputation of
//! u confirms that no element outside C penetrates (e ≥ −tol·|δ|... see `penetration_tol`).
//! Reaching `max_iter` first returns [`ContactError::NotConverged`] with the iteration
//! count, the last relative change and the last iterate.
//!
//! **Sensitivity.** dF_n/dδ is computed from the problem linearised on the converged
//! contact set: solve A_CC x = 1_C (unit increase of the approach, contact set frozen) by
//! preconditioned CG; then dF_n/dδ = ΔA Σ x. Exact for a set that does not change under a
//! small change of δ, i.e. the one-sided derivative of the discrete problem.
//!
//! **Operator.** Every product with A, the sparse column updates and the preconditioner go
//! through [`InfluenceOperator`]: [`NormalSolver::new`] uses [`NormalInfluence`] (the FFT
//! operator [`crate::FftInfluence`], with dense sums for sparse inputs on small grids),
//! [`NormalSolver::with_operator`] any implementation (e.g. the direct O(n²) oracle
//! [`crate::DirectInfluence`]).

mod active_set;
mod options;
mod sensitivity;

use crate::error::{ContactError, positive};
use crate::grid::Grid;
use crate::material::Material;
use crate::operator::{InfluenceOperator, NormalInfluence};
use crate::solution::NormalSolution;
use active_set::{
    contact_rows, initial_force_guess, list_mean, list_mean_loaded, mean_over, remove_list_mean,
    rescale,
};
pub use options::{NormalLoad, SolverOptions};

/// Grids with at least this many elements split [`NormalSolver::scan`] over the rayon
/// threads (the FFT convolution's threshold).
const PARALLEL_THRESHOLD: usize = 128 * 128;

/// Work vectors of one solve, allocated once per solver.
#[derive(Debug)]
struct Workspace {
    p: Vec<f64>,
    u: Vec<f64>,
    r: Vec<f64>,
    r_prev: Vec<f64>,
    z: Vec<f64>,
    v: Vec<f64>,
    q: Vec<f64>,
    active: Vec<bool>,
    /// Elements clipped to p = 0 in the last update, with the pressure added to them.
    clipped: Vec<(usize, f64)>,
    /// The elements of the contact set, ascending (`active` as a list).
    list: Vec<usize>,
    /// The parts of the next `list`, one per part of the grid in [`NormalSolver::scan`].
    parts: Vec<Vec<usize>>,
}

impl Workspace {
    fn new(n: usize) -> Self {
        Workspace {
            p: vec![0.0; n],
            u: vec![0.0; n],
            r: vec![0.0; n],
            r_prev: vec![0.0; n],
            z: vec![0.0; n],
            v: vec![0.0; n],
            q: vec![0.0; n],
            active: vec![false; n],
            clipped: Vec::with_capacity(n),
            list: Vec::with_capacity(n),
            parts: {
                let count = if n >= PARALLEL_THRESHOLD {
                    rayon::current_num_threads().max(1)
                } else {
                    1
                };
                let chunk = n.div_ceil(count).max(1);
                (0..count).map(|_| Vec::with_capacity(chunk)).collect()
            },
        }
    }
}

/// State of the workspace between solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum WarmStart {
    /// Nothing usable: start from zero (or the force guess).
    Cold,
    /// `work.p` holds a starting pressure; `work.u` is stale.
    Pressure,
    /// `work.p` is the last solution and `work.u = A p` exactly: no convolution needed to start.
    Solution,
}

/// Solver of the normal contact problem on one grid and material pair, generic over the
/// influence operator `A` (default: [`NormalInfluence`], the FFT convolution with dense sums
/// for sparse inputs on small grids).
///
/// Owns the operator (for the FFT one: plans and the spectra of A_nn and of the
/// preconditioner, computed once) and all work vectors; repeated solves (time stepping)
/// allocate only their result, and start from the previous pressure when `warm_start` is set.
#[derive(Debug)]
pub struct NormalSolver<A: InfluenceOperator = NormalInfluence> {
    operator: A,
    work: Workspace,
    /// What the workspace holds for a warm start.
    warm: WarmStart,
    previous_sensitivity: Option<Vec<f64>>,
    convolutions: usize,
}

impl NormalSolver {
    /// Tabulate the influence kernel, plan the FFTs and build the preconditioner
    /// ([`NormalInfluence`]).
    pub fn new(grid: Grid, material: Material) -> Result<Self, ContactError> {
        Self::with_operator(NormalInfluence::new(grid, &material)?)
    }
}

impl<A: InfluenceOperator> NormalSolver<A> {
    /// A solver over any influence operator (its grid and material are the problem's).
    pub fn with_operator(operator: A) -> Result<Self, ContactError> {
        positive("G", operator.material().g)?;
        let n = operator.grid().len();
        Ok(NormalSolver {
            operator,
            work: Workspace::new(n),
            warm: WarmStart::Cold,
            previous_sensitivity: None,
            convolutions: 0,
        })
    }

    /// The influence operator.
    pub fn operator(&self) -> &A {
        &self.operator
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        self.operator.grid()
    }

    /// The combined material.
    pub fn material(&self) -> &Material {
        self.operator.material()
    }

    /// Number of operator products and preconditioner applications (FFT convolutions for
    /// the FFT operator) done so far (statistics for benchmarks).
    pub fn convolutions(&self) -> usize {
        self.convolutions
    }

    /// Forget the previous solution (the next solve starts cold).
    pub fn reset(&mut self) {
        self.warm = WarmStart::Cold;
        self.previous_sensitivity = None;
    }

    /// Use `pressure` as the starting iterate of the next solve.
    pub fn set_initial_pressure(&mut self, pressure: &[f64]) -> Result<(), ContactError> {
        self.check_len("pressure", pressure.len())?;
        for (w, &p) in self.work.p.iter_mut().zip(pressure) {
            *w = p.max(0.0);
        }
        self.warm = WarmStart::Pressure;
        Ok(())
    }

    /// Surface displacement u = A p for a given pressure field (one operator product).
    pub fn displacement(&mut self, pressure: &[f64], out: &mut [f64]) -> Result<(), ContactError> {
        self.check_len("pressure", pressure.len())?;
        self.check_len("displacement", out.len())?;
        self.operator.apply(pressure, out);
        self.convolutions += 1;
        Ok(())
    }

    fn check_len(&self, name: &'static str, found: usize) -> Result<(), ContactError> {
        self.grid().check_len(name, found)
    }

    /// Solve the normal contact problem for the undeformed gap `gap` (per element, \[m\];
    /// `f64::INFINITY` excludes an element) under `load`.
    pub fn solve(
        &mut self,
        gap: &[f64],
        load: NormalLoad,
        options: &SolverOptions,
    ) -> Result<NormalSolution, ContactError> {
        options.validate()?;
        self.check_len("gap", gap.len())?;
        if gap.iter().any(|h| h.is_nan() || *h == f64::NEG_INFINITY) {
            return Err(ContactError::InvalidParameter {
                name: "gap",
                value: f64::NAN,
                reason: "must be finite (or +infinity to exclude an element)",
            });
        }
        let target_force = match load {
            NormalLoad::Approach(d) => {
                crate::error::finite("approach", d)?;
                None
            }
            NormalLoad::Force(f) => {
                crate::error::finite("force", f)?;
                if f < 0.0 {
                    return Err(ContactError::InvalidParameter {
                        name: "force",
                        value: f,
                        reason: "a normal force cannot be tensile",
                    });
                }
                Some(f)
            }
        };
        if let Some(f) = target_force
            && f == 0.0
        {
            let hmin = gap.iter().copied().fold(f64::INFINITY, f64::min);
            return Ok(NormalSolution::empty(*self.grid(), gap, hmin));
        }
        let warm = if options.warm_start {
            self.warm
        } else {
            WarmStart::Cold
        };
        // The workspace is overwritten from here on: a failed solve leaves nothing to reuse.
        self.warm = WarmStart::Cold;
        let mut solution = self.iterate(gap, load, target_force, warm, options)?;
        if options.sensitivity && solution.elements_in_contact > 0 {
            let (dfn, its) = self.sensitivity(
                &solution.in_contact,
                options.sensitivity_tol,
                options.max_iter,
            )?;
            solution.dfn_dapproach = Some(dfn);
            solution.sensitivity_iterations = its;
        } else if !options.sensitivity {
            solution.dfn_dapproach = None;
        }
        // The sensitivity solve leaves work.p and work.u untouched.
        self.warm = WarmStart::Solution;
        Ok(solution)
    }

    /// The NormCG iteration (see the module documentation).
    fn iterate(
        &mut self,
        gap: &[f64],
        load: NormalLoad,
        target_force: Option<f64>,
        warm: WarmStart,
        options: &SolverOptions,
    ) -> Result<NormalSolution, ContactError> {
        let grid = *self.grid();
        let area = grid.element_area();
        let n = grid.len();
        let force_mode = target_force.is_some();
        let target_sum = target_force.map(|f| f / area);

        // Initial iterate: the workspace's pressure when warm, zero otherwise.
        let mut u_valid = warm == WarmStart::Solution;
        if warm == WarmStart::Cold {
            self.work.p.fill(0.0);
            u_valid = false;
        }
        if let Some(sum) = target_sum {
            if self.work.p.iter().sum::<f64>() <= 0.0 {
                u_valid = false;
                initial_force_guess(
                    &grid,
                    self.operator.material(),
                    gap,
                    sum * area,
                    &mut self.work.p,
                );
            }
            let s: f64 = self.work.p.iter().sum();
            if s <= 0.0 {
                return Err(ContactError::NoContact {
                    reason: "no finite gap value to carry the force",
                });
            }
            let scale = sum / s;
            self.work.p.iter_mut().for_each(|p| *p *= scale);
            // u = A p is linear in p.
            self.work.u.iter_mut().for_each(|u| *u *= scale);
        }
        if !u_valid {
            self.exact_displacement();
        }
        let mut approach = match load {
            NormalLoad::Approach(d) => d,
            NormalLoad::Force(_) => mean_over(&self.work.p, gap, &self.work.u, |p| p > 0.0),
        };
        // Initial contact set: loaded elements and penetrating ones. r and v are kept zero
        // outside the set (the inputs of the convolutions: zero rows are not transformed).
        {
            let w = &mut self.work;
            w.r.fill(0.0);
            w.v.fill(0.0);
            w.list.clear();
            for i in 0..n {
                w.active[i] = w.p[i] > 0.0 || gap[i] - approach + w.u[i] < 0.0;
                if w.active[i] {
                    w.list.push(i);
                }
            }
        }
        if self.work.list.is_empty() {
            return Ok(NormalSolution::empty(grid, gap, approach));
        }

        let mut restart = true;
        let mut rz_prev = 0.0;
        let mut change = f64::INFINITY;
        for iteration in 1..=options.max_iter {
            if force_mode {
                approach = list_mean(&self.work.list, gap, &self.work.u);
            }
            // 1. residual and preconditioned residual on C (the rows of C only).
            let w = &mut self.work;
            for &i in &w.list {
                w.r[i] = approach - gap[i] - w.u[i];
            }
            let rows = contact_rows(&w.list, grid.nx);
            self.operator
                .precondition_rows(&self.work.r, &mut self.work.z, rows);
            self.convolutions += 1;
            let w = &mut self.work;
            if force_mode {
                remove_list_mean(&mut w.z, &w.list);
            }
            // 2. Polak–Ribière direction (zᵀr and zᵀr_prev in one pass; z is read on C only).
            let (mut rz, mut rz_old) = (0.0, 0.0);
            for &i in &w.list {
                rz += w.r[i] * w.z[i];
                rz_old += w.z[i] * w.r_prev[i];
            }
            let beta = if restart || rz_prev <= 0.0 {
                0.0
            } else {
                ((rz - rz_old) / rz_prev).max(0.0)
            };
            for &i in &w.list {
                w.v[i] = w.z[i] + beta * w.v[i];
                w.r_prev[i] = w.r[i];
            }
            rz_prev = rz;
            // 3. step along v.
            self.operator.apply(&self.work.v, &mut self.work.q);
            self.convolutions += 1;
            let w = &mut self.work;
            let (mut vq, mut rv) = (0.0, 0.0);
            for &i in &w.list {
                vq += w.v[i] * w.q[i];
                rv += w.r[i] * w.v[i];
            }
            // 4. update on C (p, u, relative change, clipping), then u outside C and the
            //    projection in one pass over the grid ([`Self::scan`]).
            w.clipped.clear();
            let step = if vq <= 0.0 || rv == 0.0 {
                // No descent possible: the residual vanished (exact solution) or round-off.
                change = 0.0;
                None
            } else {
                let alpha = rv / vq;
                let (mut dp2, mut p2) = (0.0, 0.0);
                for &i in &w.list {
                    let dp = alpha * w.v[i];
                    let updated = w.p[i] + dp;
                    w.u[i] += alpha * w.q[i];
                    dp2 += dp * dp;
                    p2 += updated * updated;
                    if updated < 0.0 {
                        // Capacity n was reserved: no allocation.
                        w.clipped.push((i, -updated));
                    }
                    w.p[i] = updated.max(0.0);
                }
                change = if p2 > 0.0 {
                    (dp2 / p2).sqrt()
                } else {
                    f64::INFINITY
                };
                Some(alpha)
            };
            let changed = if self.work.clipped.is_empty() {
                if force_mode {
                    approach = list_mean_loaded(&self.work.list, &self.work.p, gap, &self.work.u);
                }
                self.scan(gap, approach, step)
            } else {
                if let Some(alpha) = step {
                    let w = &mut self.work;
                    for ((u, &q), &a) in w.u.iter_mut().zip(&w.q).zip(&w.active) {
                        if !a {
                            *u += alpha * q;
                        }
                    }
                }
                self.correct_for_clipping();
                if let Some(sum) = target_sum {
                    let scale = rescale(&mut self.work.p, &self.work.list, sum);
                    self.work.u.iter_mut().for_each(|u| *u *= scale);
                }
                if force_mode {
                    approach = list_mean_loaded(&self.work.list, &self.work.p, gap, &self.work.u);
                }
                self.scan(gap, approach, None)
            };
            restart = changed;
            if !changed && change <= options.tol {
                // Confirm on an exactly recomputed displacement.
                self.exact_displacement();
                if force_mode {
                    approach = list_mean_loaded(&self.work.list, &self.work.p, gap, &self.work.u);
                }
                if !self.scan(gap, approach, None) {
                    return Ok(self.assemble(gap, approach, iteration, change, true));
                }
                restart = true;
            }
        }
        let last = self.assemble(gap, approach, options.max_iter, change, false);
        Err(ContactError::NotConverged {
            iterations: options.max_iter,
            residual: change,
            last: Box::new(last),
        })
    }

    /// Bring u = A p up to date after the projection set the clipped elements to zero:
    /// u += A Δp with Δp the (few) added pressures, summed column by column
    /// ([`InfluenceOperator::add_columns`]) when that is clearly cheaper than a convolution
    /// (count ≤ 2 + log₂N: N multiply-adds per element against ~N log₂N for the padded FFTs),
    /// else by a full product.
    fn correct_for_clipping(&mut self) {
        let n = self.grid().len();
        let limit = 2 + (usize::BITS - n.leading_zeros()) as usize;
        if self.work.clipped.len() > limit {
            self.exact_displacement();
            return;
        }
        self.operator
            .add_columns(&self.work.clipped, &mut self.work.u);
    }

    /// u = A p from scratch (removes drift of the incremental updates).
    fn exact_displacement(&mut self) {
        self.operator.apply(&self.work.p, &mut self.work.u);
        self.convolutions += 1;
    }

    /// The pass over the grid that closes an iteration: u += α q outside the contact set C
    /// when `step` is α (on C the update is done already), then the new contact set: the
    /// elements of C with p > 0, and the elements outside C that penetrate
    /// (h − δ + u < 0). Keeps `list` (the elements of C, ascending) and r = v = 0 outside C.
    /// Returns whether the set changed. On large grids the grid is split into one part per
    /// thread; every element's result is independent of the split (no sums), so the result
    /// does not depend on the number of threads.
    fn scan(&mut self, gap: &[f64], approach: f64, step: Option<f64>) -> bool {
        let w = &mut self.work;
        let chunk = w.active.len().div_ceil(w.parts.len()).max(1);
        // A part the split leaves empty must not keep the indices of an earlier scan.
        w.parts.iter_mut().for_each(Vec::clear);
        let changed = if w.parts.len() == 1 {
            scan_part(
                0,
                ScanPart {
                    active: &mut w.active,
                    p: &w.p,
                    u: &mut w.u,
                    q: &w.q,
                    r: &mut w.r,
                    v: &mut w.v,
                    gap,
                    list: &mut w.parts[0],
                },
                approach,
                step,
            )
        } else {
            use rayon::prelude::*;
            w.active
                .par_chunks_mut(chunk)
                .zip(w.p.par_chunks(chunk))
                .zip(w.u.par_chunks_mut(chunk))
                .zip(w.q.par_chunks(chunk))
                .zip(w.r.par_chunks_mut(chunk))
                .zip(w.v.par_chunks_mut(chunk))
                .zip(gap.par_chunks(chunk))
                .zip(w.parts.par_iter_mut())
                .enumerate()
                .with_max_len(1)
                .map(|(k, (((((((active, p), u), q), r), v), gap), list))| {
                    let part = ScanPart {
                        active,
                        p,
                        u,
                        q,
                        r,
                        v,
                        gap,
                        list,
                    };
                    scan_part(k * chunk, part, approach, step)
                })
                .reduce(|| false, |a, b| a || b)
        };
        w.list.clear();
        for part in &w.parts {
            w.list.extend_from_slice(part);
        }
        changed
    }

    fn assemble(
        &self,
        gap: &[f64],
        approach: f64,
        iterations: usize,
        residual: f64,
        converged: bool,
    ) -> NormalSolution {
        let g = *self.grid();
        let w = &self.work;
        let area = g.element_area();
        let mut force_sum = 0.0;
        let (mut mx, mut my) = (0.0, 0.0);
        let mut max_pressure: f64 = 0.0;
        let mut count = 0;
        for (k, &p) in w.p.iter().enumerate() {
            if p > 0.0 {
                let (x, y) = g.centre(k);
                force_sum += p;
                mx += p * x;
                my += p * y;
                max_pressure = max_pressure.max(p);
                count += 1;
            }
        }
        let centre = if force_sum > 0.0 {
            (mx / force_sum, my / force_sum)
        } else {
            (g.x0, g.y0)
        };
        NormalSolution {
            grid: g,
            pressure: w.p.clone(),
            in_contact: w.p.iter().map(|&p| p > 0.0).collect(),
            deformed_distance: gap
                .iter()
                .zip(&w.u)
                .map(|(h, u)| h - approach + u)
                .collect(),
            displacement: w.u.clone(),
            normal_force: force_sum * area,
            approach,
            max_pressure,
            contact_area: count as f64 * area,
            elements_in_contact: count,
            centre_of_pressure: centre,
            iterations,
            residual,
            converged,
            dfn_dapproach: None,
            sensitivity_iterations: 0,
        }
    }
}

/// The slices of one part of the grid for [`NormalSolver::scan`].
struct ScanPart<'a> {
    active: &'a mut [bool],
    p: &'a [f64],
    u: &'a mut [f64],
    q: &'a [f64],
    r: &'a mut [f64],
    v: &'a mut [f64],
    gap: &'a [f64],
    /// Receives the (global) indices of the part's elements in the new contact set.
    list: &'a mut Vec<usize>,
}

/// [`NormalSolver::scan`] on the elements `first ..` of one part; returns whether the set
/// changed there.
fn scan_part(first: usize, part: ScanPart<'_>, approach: f64, step: Option<f64>) -> bool {
    let ScanPart {
        active,
        p,
        u,
        q,
        r,
        v,
        gap,
        list,
    } = part;
    list.clear();
    let mut changed = false;
    let alpha = step.unwrap_or(0.0);
    let with_step = step.is_some();
    for i in 0..active.len() {
        let was = active[i];
        let now = if was {
            p[i] > 0.0
        } else {
            if with_step {
                u[i] += alpha * q[i];
            }
            gap[i] - approach + u[i] < 0.0
        };
        if now {
            // Capacity: the part's length was reserved, no allocation.
            list.push(first + i);
        } else if was {
            r[i] = 0.0;
            v[i] = 0.0;
        }
        changed |= now != was;
        active[i] = now;
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sparse clipping correction equals a full recomputation of u = A p (both use the
    /// same kernel; the direct sum and the FFT agree to round-off, 1e-12 relative), on a small
    /// grid and on one whose column sums are split over the threads (≥ 128 × 128).
    #[test]
    fn clipping_correction_equals_recomputation() {
        for (nx, ny) in [(7, 5), (130, 129)] {
            clipping_correction_case(nx, ny);
        }
    }

    fn clipping_correction_case(nx: usize, ny: usize) {
        let grid = Grid::new(nx, ny, 1e-4, 1.5e-4, 0.0, 0.0).unwrap();
        let material = Material::from_combined(8e10, 0.3).unwrap();
        let mut solver =
            NormalSolver::with_operator(crate::FftInfluence::new(grid, &material).unwrap())
                .unwrap();
        let n = grid.len();
        for i in 0..n {
            solver.work.p[i] = 1e8 * (((i * 37 + 3) % 11) as f64 + 1.0);
        }
        solver.exact_displacement();
        // Clip three elements (corner, edge, interior) as the projection would.
        solver.work.clipped.clear();
        for &j in &[0usize, nx - 1, n / 2 + 3] {
            let dp = -solver.work.p[j];
            solver.work.p[j] = 0.0;
            solver.work.clipped.push((j, dp));
        }
        solver.correct_for_clipping();
        let corrected = solver.work.u.clone();
        solver.exact_displacement();
        let scale = solver.work.u.iter().fold(0.0_f64, |m, u| m.max(u.abs()));
        for (a, b) in corrected.iter().zip(&solver.work.u) {
            assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}");
        }
    }
}
