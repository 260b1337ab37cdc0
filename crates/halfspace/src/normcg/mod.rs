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
//! through [`InfluenceOperator`]: [`NormalSolver::new`] uses [`FftInfluence`],
//! [`NormalSolver::with_operator`] any implementation (e.g. the direct O(n²) oracle
//! [`crate::DirectInfluence`]).

mod active_set;
mod sensitivity;

use crate::error::{ContactError, positive};
use crate::grid::Grid;
use crate::material::Material;
use crate::operator::{FftInfluence, InfluenceOperator};
use crate::solution::NormalSolution;
use active_set::{active_mean, initial_force_guess, mask, mean_over, remove_active_mean, rescale};

/// The normal load: approach or total force prescribed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalLoad {
    /// Approach δ \[m\] prescribed; the force is computed.
    Approach(f64),
    /// Total normal force F_n \[N\] prescribed; the approach is computed.
    Force(f64),
}

/// Controls of the NormCG iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Relative tolerance on ‖Δp‖_rms / ‖p‖_rms (default 1e-8).
    pub tol: f64,
    /// Iteration limit (default 200).
    pub max_iter: usize,
    /// Compute dF_n/dδ after convergence (default true).
    pub sensitivity: bool,
    /// Relative residual tolerance of the sensitivity solve (default 1e-6: dF_n/dδ is a
    /// tangent for Newton-type iterations, where ~1e-6 is far below what matters; CONTACT's
    /// own sensitivities are accurate to about 1 %).
    pub sensitivity_tol: f64,
    /// Start from the previous solution of this solver when there is one (default true).
    pub warm_start: bool,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            tol: 1e-8,
            max_iter: 200,
            sensitivity: true,
            sensitivity_tol: 1e-6,
            warm_start: true,
        }
    }
}

impl SolverOptions {
    fn validate(&self) -> Result<(), ContactError> {
        positive("tol", self.tol)?;
        positive("sensitivity_tol", self.sensitivity_tol)?;
        if self.max_iter == 0 {
            return Err(ContactError::InvalidParameter {
                name: "max_iter",
                value: 0.0,
                reason: "must be at least 1",
            });
        }
        Ok(())
    }
}

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
/// influence operator `A` (default: the FFT convolution [`FftInfluence`]).
///
/// Owns the operator (for the FFT one: plans and the spectra of A_nn and of the
/// preconditioner, computed once) and all work vectors; repeated solves (time stepping)
/// allocate only their result, and start from the previous pressure when `warm_start` is set.
#[derive(Debug)]
pub struct NormalSolver<A: InfluenceOperator = FftInfluence> {
    operator: A,
    work: Workspace,
    /// What the workspace holds for a warm start.
    warm: WarmStart,
    previous_sensitivity: Option<Vec<f64>>,
    convolutions: usize,
}

impl NormalSolver {
    /// Tabulate the influence kernel, plan the FFTs and build the preconditioner.
    pub fn new(grid: Grid, material: Material) -> Result<Self, ContactError> {
        Self::with_operator(FftInfluence::new(grid, &material)?)
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
        // Initial contact set: loaded elements and penetrating ones.
        {
            let w = &mut self.work;
            for i in 0..n {
                w.active[i] = w.p[i] > 0.0 || gap[i] - approach + w.u[i] < 0.0;
            }
        }
        if !self.work.active.iter().any(|&a| a) {
            return Ok(NormalSolution::empty(grid, gap, approach));
        }

        let mut restart = true;
        let mut rz_prev = 0.0;
        let mut change = f64::INFINITY;
        for iteration in 1..=options.max_iter {
            if force_mode {
                approach = active_mean(&self.work.active, gap, &self.work.u);
            }
            // 1. residual and preconditioned residual on C.
            {
                let w = &mut self.work;
                for (((r, &a), &h), &u) in w.r.iter_mut().zip(&w.active).zip(gap).zip(&w.u) {
                    *r = if a { approach - h - u } else { 0.0 };
                }
            }
            self.operator.precondition(&self.work.r, &mut self.work.z);
            self.convolutions += 1;
            let w = &mut self.work;
            mask(&mut w.z, &w.active);
            if force_mode {
                remove_active_mean(&mut w.z, &w.active);
            }
            // 2. Polak–Ribière direction (zᵀr and zᵀr_prev in one pass).
            let (mut rz, mut rz_old) = (0.0, 0.0);
            for ((&r, &z), &rp) in w.r.iter().zip(&w.z).zip(&w.r_prev) {
                rz += r * z;
                rz_old += z * rp;
            }
            let beta = if restart || rz_prev <= 0.0 {
                0.0
            } else {
                ((rz - rz_old) / rz_prev).max(0.0)
            };
            for ((v, &z), &a) in w.v.iter_mut().zip(&w.z).zip(&w.active) {
                *v = if a { z + beta * *v } else { 0.0 };
            }
            w.r_prev.copy_from_slice(&w.r);
            rz_prev = rz;
            // 3. step along v.
            self.operator.apply(&self.work.v, &mut self.work.q);
            self.convolutions += 1;
            let w = &mut self.work;
            let (mut vq, mut rv) = (0.0, 0.0);
            for (((&v, &q), &a), &r) in w.v.iter().zip(&w.q).zip(&w.active).zip(&w.r) {
                if a {
                    vq += v * q;
                }
                rv += r * v;
            }
            // 4. update, relative change and projection in one pass.
            w.clipped.clear();
            if vq <= 0.0 || rv == 0.0 {
                // No descent possible: the residual vanished (exact solution) or round-off.
                change = 0.0;
            } else {
                let alpha = rv / vq;
                let (mut dp2, mut p2) = (0.0, 0.0);
                for (i, (((p, u), &v), &q)) in
                    w.p.iter_mut()
                        .zip(w.u.iter_mut())
                        .zip(&w.v)
                        .zip(&w.q)
                        .enumerate()
                {
                    let dp = alpha * v;
                    let updated = *p + dp;
                    *u += alpha * q;
                    dp2 += dp * dp;
                    p2 += updated * updated;
                    if updated < 0.0 {
                        // Capacity n was reserved: no allocation.
                        w.clipped.push((i, -updated));
                    }
                    *p = updated.max(0.0);
                }
                change = if p2 > 0.0 {
                    (dp2 / p2).sqrt()
                } else {
                    f64::INFINITY
                };
            }
            if !self.work.clipped.is_empty() {
                self.correct_for_clipping();
                if let Some(sum) = target_sum {
                    let scale = rescale(&mut self.work.p, sum);
                    self.work.u.iter_mut().for_each(|u| *u *= scale);
                }
            }
            if force_mode {
                approach = mean_over(&self.work.p, gap, &self.work.u, |p| p > 0.0);
            }
            let changed = self.update_active_set(gap, approach);
            restart = changed;
            if !changed && change <= options.tol {
                // Confirm on an exactly recomputed displacement.
                self.exact_displacement();
                if force_mode {
                    approach = mean_over(&self.work.p, gap, &self.work.u, |p| p > 0.0);
                }
                if !self.update_active_set(gap, approach) {
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

    /// New contact set: elements with p > 0, and elements outside the set that penetrate.
    /// Returns whether the set changed.
    fn update_active_set(&mut self, gap: &[f64], approach: f64) -> bool {
        let w = &mut self.work;
        let mut changed = false;
        for (((a, &p), &h), &u) in w.active.iter_mut().zip(&w.p).zip(gap).zip(&w.u) {
            let now = p > 0.0 || (h - approach + u < 0.0 && !*a);
            changed |= now != *a;
            *a = now;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The sparse clipping correction equals a full recomputation of u = A p (both use the
    /// same kernel; the direct sum and the FFT agree to round-off, 1e-12 relative).
    #[test]
    fn clipping_correction_equals_recomputation() {
        let grid = Grid::new(7, 5, 1e-4, 1.5e-4, 0.0, 0.0).unwrap();
        let material = Material::from_combined(8e10, 0.3).unwrap();
        let mut solver = NormalSolver::new(grid, material).unwrap();
        let n = grid.len();
        for i in 0..n {
            solver.work.p[i] = 1e8 * (((i * 37 + 3) % 11) as f64 + 1.0);
        }
        solver.exact_displacement();
        // Clip three elements (corner, edge, interior) as the projection would.
        solver.work.clipped.clear();
        for &j in &[0usize, 6, 17] {
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
