//! Reuse of a boundary-element solution across evaluations: the frozen-contact-set model of
//! [`super::BemLaw`] (references.md §C8.4).
//!
//! After a full NormCG solve at the interference g_r = δ_r − h_r (h the undeformed gap per
//! element) with contact set C, pressure p_r and deformed distance e_r = h_r − δ_r + A p_r, the
//! solution of a changed problem g = g_r + Δg *on the same contact set* is linear in Δg:
//! p = p_r + A_CC⁻¹ Δg_C. Between time steps Δg varies only along the rolling direction (the
//! approach and the column corrections c(ξ_i)): Δg_i = Δδ − Δc_i per grid column i. The model
//! keeps, on C, the responses y_k = A_CC⁻¹ b_k to the gap shapes b_0 = 1, b_1 = ξ/ℓ,
//! b_2 = (ξ/ℓ)² (ℓ the grid's half-length), their displacements A y_k off C, and their column
//! sums Y_k,i = ΔA Σ_{e ∈ column i ∩ C} y_k,e. Then, by the symmetry of A,
//!
//! * F = F_r + Σ_i X_i Δg_i exactly for any column change (X_i = Y_0,i; Σ_i X_i = dF/dδ);
//! * the column forces F_i = F_{r,i} + Σ_k a_k Y_k,i + X_i ρ_i, with Δg_i = Σ_k a_k b_k(ξ_i) + ρ_i
//!   the X-weighted least-squares fit (exact for the quadratic part; the remainder ρ, whose
//!   total force Σ X_i ρ_i is exact, is attributed to its own column);
//! * the energy W = W_r + Σ_i (F_{r,i} + ½ ΔF_i) Δg_i (exact for a linear response).
//!
//! The frozen set is the exact solution of the contact problem (which is unique) as long as
//! the predicted pressure p_r + Σ a_k y_k ≥ 0 on C and the predicted distance
//! e_r − Δg + Σ a_k A y_k ≥ 0 off C. The a-posteriori estimate of the force error is
//!
//! * for an element of C whose predicted pressure is negative (it would leave the set): the
//!   force change of removing it alone, ΔA |p_e| x_e / (A_CC⁻¹)_ee ≤ ΔA |p_e| x_e A_ee (for a
//!   symmetric positive-definite matrix (A⁻¹)_ee ≥ 1/A_ee), summed and doubled for the
//!   cascade of releases (an estimate, not a bound: measured up to 1.16 × the plain sum);
//! * Σ_i |X_i ρ_i|, the force of the gap change outside the quadratic basis (its effect on the
//!   set check is not computed);
//! * Σ_C ΔA |x_e e_e|, the reference solve's own error (its residual e on C);
//! * τ Σ_i |X_i Δg_i|, the force change times the relative CG tolerance τ of the responses.
//!
//! An element outside C that the prediction makes penetrate (it would enter the set) refuses
//! the prediction: its force is not bounded by quantities the model holds.

use crate::error::ContactError;
use crate::grid::Grid;
use crate::normcg::NormalSolver;
use crate::solution::NormalSolution;

use super::set_factor::SetFactor;
use super::set_solve::{self, SetSolveWork};

/// Number of gap shapes in the basis (1, ξ, ξ²).
const BASIS: usize = 3;

/// Factor on the sum of the single-element release bounds: releasing one element lowers its
/// neighbours' pressures, and the cascade is not in the sum (a wheel sequence of 60 steps,
/// law tests, measured up to 1.16 × the plain sum).
const LEAVING_FACTOR: f64 = 2.0;

/// Elements off the contact set kept in order of distance ([`FrozenSet::build`]); the
/// others are visited only when a gap change reaches them.
const NEAREST: usize = 64;

/// Relative residual of the CG solves of the responses y_k.
const RESPONSE_TOL: f64 = 1e-5;

/// Relative error of the responses solved with the dense factor of A_CC (round-off of
/// triangular solves of order ≤ [`MAX_FACTOR_SET`] with condition number ≤ 1e3, with a
/// margin of 1e2).
const FACTOR_TOL: f64 = 1e-10;

/// Grids of at most this many elements keep the dense factor of A_CC ([`SetFactor`]; 8 MB at
/// most); larger grids solve the responses by CG.
const MAX_FACTOR_GRID: usize = 1024;

/// Contact sets larger than this solve the responses by CG (the factor's memory and the cost
/// of a new factorization, m³/3).
const MAX_FACTOR_SET: usize = 1024;

/// The responses y_k kept between models (warm starts of the next model's solves).
#[derive(Debug)]
pub(super) struct Responses {
    /// b_k per element (full grid).
    shapes: [Vec<f64>; BASIS],
    /// b_k per column.
    column_shapes: [Vec<f64>; BASIS],
    /// y_k per element (zero outside the last contact set).
    y: [Vec<f64>; BASIS],
    /// Scratch for A y_k.
    scratch: Vec<f64>,
    /// The self-influence A_ee \[m/Pa\] (equal for every element of a uniform grid).
    self_influence: f64,
    /// The dense factor of A_CC kept across set changes (grids up to [`MAX_FACTOR_GRID`]).
    pub(super) factor: Option<SetFactor>,
    /// b_k, then y_k, on the set in the factor's order (a fourth, zero, column: four lanes
    /// of AVX).
    set_block: Vec<[f64; BASIS + 1]>,
    /// Whether `y` holds the responses on the factor's set already (solved by
    /// [`Responses::solve_set`] together with the pressure).
    fresh: bool,
    /// Scratch of [`Responses::solve_set`].
    set_work: SetSolveWork,
}

impl Responses {
    pub(super) fn new(grid: &Grid, solver: &mut NormalSolver) -> Result<Self, ContactError> {
        let n = grid.len();
        let half = 0.5 * grid.nx as f64 * grid.dx;
        let shape = |k: usize, xi: f64| (xi / half).powi(k as i32);
        let shapes = std::array::from_fn(|k| {
            (0..n)
                .map(|e| shape(k, grid.x(e % grid.nx) - grid.x0))
                .collect()
        });
        let column_shapes = std::array::from_fn(|k| {
            (0..grid.nx)
                .map(|i| shape(k, grid.x(i) - grid.x0))
                .collect()
        });
        let mut unit = vec![0.0; n];
        let centre = (grid.ny / 2) * grid.nx + grid.nx / 2;
        unit[centre] = 1.0;
        let mut u = vec![0.0; n];
        solver.displacement(&unit, &mut u)?;
        let factor = if n <= MAX_FACTOR_GRID {
            // K(dx, dy) = the displacement of a unit pressure on element 0 at offset (dx, dy).
            let mut unit = vec![0.0; n];
            unit[0] = 1.0;
            let mut kernel = vec![0.0; n];
            solver.displacement(&unit, &mut kernel)?;
            Some(SetFactor::new(kernel, grid.nx))
        } else {
            None
        };
        Ok(Responses {
            shapes,
            column_shapes,
            y: std::array::from_fn(|_| vec![0.0; n]),
            scratch: u.clone(),
            self_influence: u[centre],
            factor,
            set_block: Vec::new(),
            fresh: false,
            set_work: SetSolveWork::default(),
        })
    }
}

impl Responses {
    /// The exact solution at `delta` for the gap `gap` by the factor's active-set rounds
    /// ([`set_solve`]) from the set `guess` (one flag per element); on success the responses
    /// y_k on its set come from the same pass over the factor. `None` without a factor or
    /// when the rounds fail.
    pub(super) fn solve_set(
        &mut self,
        solver: &mut NormalSolver,
        gap: &[f64],
        delta: f64,
        guess: impl FnOnce(&mut Vec<bool>),
    ) -> Result<Option<NormalSolution>, ContactError> {
        self.fresh = false;
        let Some(factor) = self.factor.as_mut() else {
            return Ok(None);
        };
        guess(&mut self.set_work.in_contact);
        let solution =
            set_solve::solve(factor, solver, gap, delta, &self.shapes, &mut self.set_work)?;
        if solution.is_some() {
            for (k, y) in self.y.iter_mut().enumerate() {
                y.fill(0.0);
                for (&e, row) in factor.members().iter().zip(&self.set_work.block) {
                    y[e] = row[k + 1];
                }
            }
            self.fresh = true;
        }
        Ok(solution)
    }

    /// y_k = A_CC⁻¹ b_k for every shape k on the factor's set (zero elsewhere), in one pass
    /// over the factor.
    fn solve_by_factor(&mut self) {
        let factor = self.factor.as_ref().expect("a factor");
        let members = factor.members();
        self.set_block.clear();
        self.set_block.extend(
            members
                .iter()
                .map(|&e| std::array::from_fn(|k| if k < BASIS { self.shapes[k][e] } else { 0.0 })),
        );
        factor.solve_block(&mut self.set_block);
        for (k, y) in self.y.iter_mut().enumerate() {
            y.fill(0.0);
            for (&e, row) in members.iter().zip(&self.set_block) {
                y[e] = row[k];
            }
        }
    }
}

/// The frozen-set model of one full solve (module documentation).
#[derive(Debug)]
pub(super) struct FrozenSet {
    delta: f64,
    column_gap: Vec<f64>,
    force: f64,
    energy: f64,
    column_force: Vec<f64>,
    active: Vec<usize>,
    pressure: Vec<f64>,
    /// y_k on C (`active` order).
    y: [Vec<f64>; BASIS],
    /// The elements off C, by increasing deformed distance.
    inactive: Vec<u32>,
    /// Their grid columns.
    inactive_column: Vec<u32>,
    /// The first `sorted` of them are the nearest, by increasing distance; the others, in
    /// no order, are at least `rest_min` away.
    sorted: usize,
    rest_min: f64,
    /// Whether the responses came from the dense factor (which then holds A_CC of C).
    factored: bool,
    /// Their deformed distances e_r.
    distance: Vec<f64>,
    /// A y_k off C (`inactive` order).
    response_u: [Vec<f64>; BASIS],
    /// max_j |(A y_k)_j| off C.
    response_u_max: [f64; BASIS],
    /// Y_k,i.
    column_response: [Vec<f64>; BASIS],
    /// Inverse of the X-weighted Gram matrix of the basis over the columns.
    gram_inverse: [[f64; BASIS]; BASIS],
    /// Column of each element.
    nx: usize,
    area: f64,
    self_influence: f64,
    patch: (f64, f64),
    /// Σ_C ΔA |x_e e_e|: the force error of the reference solve \[N\].
    reference_error: f64,
    /// Relative error of the responses ([`RESPONSE_TOL`] by CG, [`FACTOR_TOL`] by the factor).
    response_tol: f64,
}

/// A prediction of the model.
#[derive(Debug, Clone, Copy)]
pub(super) struct Prediction {
    pub force: f64,
    pub stiffness: f64,
    pub energy: f64,
    pub max_pressure: f64,
    pub patch: (f64, f64),
    /// Estimated force error \[N\] (module documentation).
    pub estimate: f64,
}

impl FrozenSet {
    /// The model of the converged `solution` at approach `delta` with the column
    /// corrections `column_gap` (empty: none) and the column forces `column_force`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn build(
        solver: &mut NormalSolver,
        responses: &mut Responses,
        solution: &NormalSolution,
        delta: f64,
        column_gap: &[f64],
        column_force: &[f64],
        energy: f64,
        max_iter: usize,
    ) -> Result<Option<Self>, ContactError> {
        let grid = solution.grid;
        let (n, nx) = (grid.len(), grid.nx);
        let area = grid.element_area();
        let in_contact = &solution.in_contact;
        let mut column_response: [Vec<f64>; BASIS] = std::array::from_fn(|_| vec![0.0; nx]);
        let mut response_u: [Vec<f64>; BASIS] = std::array::from_fn(|_| Vec::new());
        let active: Vec<usize> = (0..n).filter(|&e| in_contact[e]).collect();
        // Off C, the [`NEAREST`] nearest first by increasing distance, then the others (all
        // at least as far) unordered: an evaluation's entering check stops at the first
        // element whose distance exceeds the largest possible gap change (`predict`), and
        // visits the others only when that change reaches them.
        let mut inactive: Vec<usize> = (0..n)
            .filter(|&e| !in_contact[e] && solution.deformed_distance[e].is_finite())
            .collect();
        // A total order (ties by element), so the order does not depend on the algorithm.
        let by_distance = |a: &usize, b: &usize| {
            solution.deformed_distance[*a]
                .total_cmp(&solution.deformed_distance[*b])
                .then(a.cmp(b))
        };
        let sorted = NEAREST.min(inactive.len());
        if sorted < inactive.len() {
            inactive.select_nth_unstable_by(sorted, by_distance);
        }
        inactive[..sorted].sort_unstable_by(by_distance);
        let rest_min = inactive
            .get(sorted)
            .map_or(f64::INFINITY, |&e| solution.deformed_distance[e]);
        let factored = match responses.factor.as_mut() {
            Some(factor) if active.len() <= MAX_FACTOR_SET => {
                factor.sync(in_contact)?;
                true
            }
            _ => false,
        };
        if factored && !std::mem::take(&mut responses.fresh) {
            responses.solve_by_factor();
        }
        for k in 0..BASIS {
            if factored {
                solver.displacement(&responses.y[k], &mut responses.scratch)?;
            } else {
                solver.solve_on_set(
                    in_contact,
                    &responses.shapes[k],
                    &mut responses.y[k],
                    &mut responses.scratch,
                    RESPONSE_TOL,
                    max_iter,
                )?;
            }
            response_u[k] = inactive.iter().map(|&e| responses.scratch[e]).collect();
            for &e in &active {
                column_response[k][e % nx] += area * responses.y[k][e];
            }
        }
        // Gram matrix G_kl = Σ_i X_i b_k b_l over the columns, X_i ≥ 0 weights.
        let mut gram = [[0.0; BASIS]; BASIS];
        for i in 0..nx {
            let wgt = column_response[0][i].abs();
            for (k, row) in gram.iter_mut().enumerate() {
                for (l, g) in row.iter_mut().enumerate() {
                    *g += wgt * responses.column_shapes[k][i] * responses.column_shapes[l][i];
                }
            }
        }
        let response_u_max =
            std::array::from_fn(|k| response_u[k].iter().fold(0.0_f64, |m, u| m.max(u.abs())));
        let Some(gram_inverse) = invert3(&gram) else {
            // Fewer than three columns in contact: no model (every evaluation solves).
            return Ok(None);
        };
        // The reference's own error: its residual on C, e_C = h − δ + A p ≠ 0 within the
        // NormCG tolerance, changes the force by ΔA x_Cᵀ e_C on the frozen set.
        let reference_error = active
            .iter()
            .map(|&e| area * (responses.y[0][e] * solution.deformed_distance[e]).abs())
            .sum();
        let (a, b) = if solution.elements_in_contact > 0 {
            solution.patch_half_widths()
        } else {
            (0.0, 0.0)
        };
        Ok(Some(FrozenSet {
            delta,
            column_gap: if column_gap.is_empty() {
                vec![0.0; nx]
            } else {
                column_gap.to_vec()
            },
            force: solution.normal_force,
            energy,
            column_force: column_force.to_vec(),
            pressure: active.iter().map(|&e| solution.pressure[e]).collect(),
            y: std::array::from_fn(|k| active.iter().map(|&e| responses.y[k][e]).collect()),
            active,
            distance: inactive
                .iter()
                .map(|&e| solution.deformed_distance[e])
                .collect(),
            inactive_column: inactive.iter().map(|&e| (e % nx) as u32).collect(),
            sorted,
            rest_min,
            inactive: inactive.iter().map(|&e| e as u32).collect(),
            factored,
            response_u,
            response_u_max,
            column_response,
            gram_inverse,
            nx,
            area,
            self_influence: responses.self_influence,
            patch: (2.0 * a, 2.0 * b),
            reference_error,
            response_tol: if factored { FACTOR_TOL } else { RESPONSE_TOL },
        }))
    }

    /// Whether the model's responses came from the dense factor, which then holds A_CC of
    /// the model's set.
    pub(super) fn factored(&self) -> bool {
        self.factored
    }

    /// The force F_r of the full solve the model was built from \[N\].
    pub(super) fn reference_force(&self) -> f64 {
        self.force
    }

    /// The prediction at approach `delta` with the column corrections `column_gap`, writing
    /// the column forces to `column_force` (when not empty) and the pressure to `pressure`;
    /// `None` when an element outside the set would penetrate.
    pub(super) fn predict(
        &self,
        responses: &Responses,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        pressure: &mut [f64],
        delta_g: &mut Vec<f64>,
    ) -> Option<Prediction> {
        let nx = self.nx;
        let a = self.fit(responses, delta, column_gap, delta_g);
        // Entering elements refuse the prediction. The predicted distance of an element off
        // C is e_r − Δg_i + Σ_k a_k (A y_k)_e ≥ e_r − max_i |Δg_i| − Σ_k |a_k| max |A y_k|:
        // only the elements with e_r within that bound can penetrate (the same answer as
        // checking every element). The nearest are sorted by e_r, so their check stops at
        // the first one beyond it; the others are visited only when it reaches them.
        let reach = delta_g.iter().fold(0.0_f64, |m, g| m.max(g.abs()))
            + (0..BASIS)
                .map(|k| a[k].abs() * self.response_u_max[k])
                .sum::<f64>();
        let penetrates = |j: usize| {
            let mut predicted = self.distance[j] - delta_g[self.inactive_column[j] as usize];
            for (k, ak) in a.iter().enumerate() {
                predicted += ak * self.response_u[k][j];
            }
            predicted < 0.0
        };
        let nearest = &self.distance[..self.sorted];
        let within = nearest.partition_point(|&d| d <= reach);
        if (0..within).any(penetrates) {
            return None;
        }
        if reach >= self.rest_min
            && (self.sorted..self.distance.len())
                .any(|j| self.distance[j] <= reach && penetrates(j))
        {
            return None;
        }
        // Column forces, force, energy and the remainder term.
        let (mut force, mut energy, mut stiffness, mut remainder) = (0.0, self.energy, 0.0, 0.0);
        let mut change_size = 0.0;
        for i in 0..nx {
            let x = self.column_response[0][i];
            let fit: f64 = (0..BASIS)
                .map(|k| a[k] * responses.column_shapes[k][i])
                .sum();
            let rho = delta_g[i] - fit;
            let change: f64 = (0..BASIS)
                .map(|k| a[k] * self.column_response[k][i])
                .sum::<f64>()
                + x * rho;
            let fi = self.column_force[i] + change;
            if let Some(out) = column_force.get_mut(i) {
                *out = fi;
            }
            force += fi;
            energy += (self.column_force[i] + 0.5 * change) * delta_g[i];
            stiffness += x;
            remainder += (x * rho).abs();
            change_size += (x * delta_g[i]).abs();
        }
        // Pressure on the set, and the leaving elements.
        pressure.fill(0.0);
        let (mut leaving, mut max_pressure) = (0.0, 0.0_f64);
        for (j, &e) in self.active.iter().enumerate() {
            let mut p = self.pressure[j];
            for (k, ak) in a.iter().enumerate() {
                p += ak * self.y[k][j];
            }
            if p < 0.0 {
                leaving +=
                    LEAVING_FACTOR * self.area * (-p) * self.y[0][j].abs() * self.self_influence;
            } else {
                pressure[e] = p;
                max_pressure = max_pressure.max(p);
            }
        }
        Some(Prediction {
            force,
            stiffness,
            energy,
            max_pressure,
            patch: self.patch,
            estimate: leaving + remainder + self.reference_error + self.response_tol * change_size,
        })
    }

    /// Δg_i per column into `delta_g` and its X-weighted least-squares fit a_k on the basis.
    fn fit(
        &self,
        responses: &Responses,
        delta: f64,
        column_gap: &[f64],
        delta_g: &mut Vec<f64>,
    ) -> [f64; BASIS] {
        delta_g.clear();
        let dd = delta - self.delta;
        for i in 0..self.nx {
            let c = column_gap.get(i).copied().unwrap_or(0.0);
            delta_g.push(dd - (c - self.column_gap[i]));
        }
        let mut rhs = [0.0; BASIS];
        for (i, &g) in delta_g.iter().enumerate() {
            let wgt = self.column_response[0][i].abs();
            for (k, r) in rhs.iter_mut().enumerate() {
                *r += wgt * responses.column_shapes[k][i] * g;
            }
        }
        std::array::from_fn(|k| (0..BASIS).map(|l| self.gram_inverse[k][l] * rhs[l]).sum())
    }

    /// The model's guess of the contact set at `delta` with the column corrections
    /// `column_gap` into `in_contact` (one flag per element): the elements of C whose
    /// predicted pressure p_r + Σ a_k y_k stays ≥ 0 and the elements off C whose predicted
    /// distance e_r − Δg_i + Σ a_k (A y_k) is negative (the part of Δg outside the basis is
    /// left out: a guess, the start of the factor's active-set solve).
    pub(super) fn predicted_set(
        &self,
        responses: &Responses,
        delta: f64,
        column_gap: &[f64],
        delta_g: &mut Vec<f64>,
        in_contact: &mut Vec<bool>,
    ) {
        let a = self.fit(responses, delta, column_gap, delta_g);
        in_contact.clear();
        in_contact.resize(responses.shapes[0].len(), false);
        for (j, &e) in self.active.iter().enumerate() {
            let p: f64 = self.pressure[j] + (0..BASIS).map(|k| a[k] * self.y[k][j]).sum::<f64>();
            in_contact[e] = p >= 0.0;
        }
        for (j, &d) in self.distance.iter().enumerate() {
            let mut predicted = d - delta_g[self.inactive_column[j] as usize];
            for (k, ak) in a.iter().enumerate() {
                predicted += ak * self.response_u[k][j];
            }
            if predicted < 0.0 {
                in_contact[self.inactive[j] as usize] = true;
            }
        }
    }

    /// dF/dδ of the frozen set, Σ_i X_i \[N/m\].
    pub(super) fn stiffness(&self) -> f64 {
        self.column_response[0].iter().sum()
    }
}

/// Inverse of a symmetric positive-definite 3 × 3 matrix by cofactors; `None` when it is
/// (numerically) singular.
fn invert3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c =
        |r0: usize, r1: usize, c0: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let cof = [
        [c(1, 2, 1, 2), -c(1, 2, 0, 2), c(1, 2, 0, 1)],
        [-c(0, 2, 1, 2), c(0, 2, 0, 2), -c(0, 2, 0, 1)],
        [c(0, 1, 1, 2), -c(0, 1, 0, 2), c(0, 1, 0, 1)],
    ];
    let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    let scale = m[0][0] * m[1][1] * m[2][2];
    if !(det > 1e-10 * scale && scale > 0.0) {
        return None;
    }
    let mut inv = [[0.0; 3]; 3];
    for (r, row) in inv.iter_mut().enumerate() {
        for (col, v) in row.iter_mut().enumerate() {
            // inverse = adjugate / det, adjugate = cofactor transposed.
            *v = cof[col][r] / det;
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::{BASIS, FrozenSet, NEAREST, Responses, invert3};
    use crate::grid::Grid;
    use crate::material::Material;
    use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};

    /// The entering check of `predict` (the [`NEAREST`] nearest elements off the set in
    /// order, the others unordered) refuses exactly when visiting every element off the set
    /// finds one whose predicted distance e_r − Δg_i + Σ_k a_k (A y_k)_e is negative (the
    /// independent reference: no ordering, no reach bound). A wheel-on-rail gap on a 24 × 24
    /// grid (about 140 elements in contact, 430 off), approach changes of −3 … +5 % and tilts
    /// and curvatures of the column corrections up to 3e-6 m: both outcomes occur, and
    /// changes that reach beyond the sorted elements too.
    #[test]
    fn entering_check_equals_visiting_every_element() {
        let grid = Grid::centred(24, 24, 5e-4, 4e-4, 0.0, 0.0).unwrap();
        let material = Material::identical(210e9, 0.3).unwrap();
        let gap = grid.sample(|x, y| x * x / 0.92 + y * y / 0.6);
        let mut solver = NormalSolver::new(grid, material).unwrap();
        let options = SolverOptions {
            tol: 1e-12,
            max_iter: 2000,
            ..SolverOptions::default()
        };
        let delta = 3e-5;
        let solution = solver
            .solve(&gap, NormalLoad::Approach(delta), &options)
            .unwrap();
        let mut responses = Responses::new(&grid, &mut solver).unwrap();
        let column_force = vec![0.0; grid.nx];
        let model = FrozenSet::build(
            &mut solver,
            &mut responses,
            &solution,
            delta,
            &[],
            &column_force,
            0.0,
            2000,
        )
        .unwrap()
        .expect("a model");
        assert!(model.distance.len() > NEAREST);
        let (mut refused, mut accepted, mut far) = (0, 0, 0);
        let (mut out, mut pressure, mut delta_g) =
            (vec![0.0; grid.nx], vec![0.0; grid.len()], Vec::new());
        for step in 0..400 {
            let f = step as f64;
            let d = delta * (1.0 + 0.08 * ((0.37 * f).sin() * 0.5 + 0.125));
            let (tilt, bend) = (3e-6 * (0.71 * f).sin(), 3e-6 * (1.13 * f).cos());
            let column_gap: Vec<f64> = (0..grid.nx)
                .map(|i| {
                    let xi = (i as f64 + 0.5) / grid.nx as f64 * 2.0 - 1.0;
                    tilt * xi + bend * xi * xi
                })
                .collect();
            let predicted = model.predict(
                &responses,
                d,
                &column_gap,
                &mut out,
                &mut pressure,
                &mut delta_g,
            );
            let a = model.fit(&responses, d, &column_gap, &mut delta_g);
            let every = (0..model.distance.len()).any(|j| {
                let mut e = model.distance[j] - delta_g[model.inactive_column[j] as usize];
                for (k, ak) in a.iter().enumerate().take(BASIS) {
                    e += ak * model.response_u[k][j];
                }
                e < 0.0
            });
            assert_eq!(predicted.is_none(), every, "step {step}");
            let reach = delta_g.iter().fold(0.0_f64, |m, g| m.max(g.abs()))
                + (0..BASIS)
                    .map(|k| a[k].abs() * model.response_u_max[k])
                    .sum::<f64>();
            far += usize::from(reach >= model.rest_min);
            if every {
                refused += 1;
            } else {
                accepted += 1;
            }
        }
        assert!(
            refused > 20 && accepted > 20 && far > 20,
            "{refused} {accepted} {far}"
        );
    }

    /// The cofactor inverse times the matrix is the identity (1e-12, round-off).
    #[test]
    fn inverse_of_a_gram_matrix() {
        let m = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.25], [0.5, 0.25, 2.0]];
        let inv = invert3(&m).unwrap();
        for r in 0..3 {
            for c in 0..3 {
                let v: f64 = (0..3).map(|k| m[r][k] * inv[k][c]).sum();
                assert!((v - f64::from(u8::from(r == c))).abs() < 1e-12);
            }
        }
        assert!(invert3(&[[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).is_none());
    }
}
