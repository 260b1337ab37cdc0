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
//! the prediction: its force is not bounded by quantities the model holds. The check needs
//! the predicted displacement Σ_k a_k (A y_k)_j off C, one convolution of Σ_k a_k y_k for the
//! evaluation's fit a (kept for the model's guess of the next set at the same fit), unless no
//! element can penetrate: its distance is at least the least one, min_j e_r,j, and its gap
//! change is at most max_i |Δg_i| + Σ_k |a_k| U_k with U_k = K₁ Σ_C |y_k,e| ≥ |(A y_k)_j|
//! (K₁ the largest kernel entry off the diagonal: an element off C is at a non-zero offset
//! from every element of C), so when that sum is below the least distance the evaluation
//! needs no convolution (references.md §C8.4, "Displacements off the set").

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

/// A model that has convolved this many combinations Σ_k a_k y_k (evaluations that needed the
/// entering check) convolves the three y_k once instead, and combines them for its later
/// evaluations: a model that answers many evaluations (a wheel on a smooth span) pays three
/// convolutions, one that is replaced at the next step one or two.
const SHAPE_CONVOLUTIONS_AFTER: usize = 2;

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
    /// Scratch for A y_k, and for Σ_k a_k A y_k.
    scratch: Vec<f64>,
    /// Scratch for Σ_k a_k y_k (zero off the set).
    combination: Vec<f64>,
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
            combination: vec![0.0; n],
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
    /// The elements off C (with a finite deformed distance).
    inactive: Vec<u32>,
    /// Their grid columns.
    inactive_column: Vec<u32>,
    /// The least of their deformed distances.
    nearest: f64,
    /// Whether the responses came from the dense factor (which then holds A_CC of C).
    factored: bool,
    /// Their deformed distances e_r.
    distance: Vec<f64>,
    /// U_k ≥ max_j |(A y_k)_j| off C (module documentation; infinite without the factor's
    /// kernel table).
    bound: [f64; BASIS],
    /// The fit a whose predicted displacement Σ_k a_k (A y_k) off C is in `displaced`.
    fitted: Option<[f64; BASIS]>,
    /// That displacement (`inactive` order).
    displaced: Vec<f64>,
    /// Convolutions of combinations so far; from [`SHAPE_CONVOLUTIONS_AFTER`] on, A y_k
    /// off C of every shape (`shape_u`), and U_k their exact maximum.
    combinations: usize,
    shape_u: Option<[Vec<f64>; BASIS]>,
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
        let active: Vec<usize> = (0..n).filter(|&e| in_contact[e]).collect();
        let inactive: Vec<usize> = (0..n)
            .filter(|&e| !in_contact[e] && solution.deformed_distance[e].is_finite())
            .collect();
        let nearest = inactive
            .iter()
            .map(|&e| solution.deformed_distance[e])
            .fold(f64::INFINITY, f64::min);
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
            if !factored {
                solver.solve_on_set(
                    in_contact,
                    &responses.shapes[k],
                    &mut responses.y[k],
                    &mut responses.scratch,
                    RESPONSE_TOL,
                    max_iter,
                )?;
            }
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
        // K₁, the largest kernel entry off the diagonal (module documentation).
        let off_diagonal = match responses.factor.as_ref() {
            Some(factor) if factored => factor.kernel()[1..]
                .iter()
                .fold(0.0_f64, |m, v| m.max(v.abs())),
            _ => f64::INFINITY,
        };
        let bound = std::array::from_fn(|k| {
            off_diagonal * active.iter().map(|&e| responses.y[k][e].abs()).sum::<f64>()
        });
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
            nearest,
            displaced: vec![0.0; inactive.len()],
            inactive: inactive.iter().map(|&e| e as u32).collect(),
            factored,
            bound,
            fitted: None,
            combinations: 0,
            shape_u: None,
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
    /// `None` when an element outside the set would penetrate (or the convolution of that
    /// check fails: the full solve then reports the error).
    pub(super) fn predict(
        &mut self,
        solver: &mut NormalSolver,
        responses: &mut Responses,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        pressure: &mut [f64],
        delta_g: &mut Vec<f64>,
    ) -> Option<Prediction> {
        let nx = self.nx;
        let a = self.fit(responses, delta, column_gap, delta_g);
        // Entering elements refuse the prediction (module documentation).
        if self.may_enter(&a, delta_g) {
            self.displace(solver, responses, &a).ok()?;
            if (0..self.distance.len()).any(|j| self.penetrates(j, delta_g)) {
                return None;
            }
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

    /// Whether an element off C may penetrate under the fit `a` and the column changes
    /// `delta_g`: its gap change max_i |Δg_i| + Σ_k |a_k| U_k reaches the least distance
    /// (module documentation). A NaN answers yes.
    fn may_enter(&self, a: &[f64; BASIS], delta_g: &[f64]) -> bool {
        let reach = delta_g.iter().fold(0.0_f64, |m, g| m.max(g.abs()))
            + (0..BASIS).map(|k| a[k].abs() * self.bound[k]).sum::<f64>();
        reach.is_nan() || reach >= self.nearest
    }

    /// The predicted displacement Σ_k a_k (A y_k) off C of the fit `a` into `displaced`, by
    /// one convolution of Σ_k a_k y_k (none when it is there already), or, from the
    /// [`SHAPE_CONVOLUTIONS_AFTER`]-th on, from A y_k of every shape (three convolutions once;
    /// U_k is then their exact maximum).
    fn displace(
        &mut self,
        solver: &mut NormalSolver,
        responses: &mut Responses,
        a: &[f64; BASIS],
    ) -> Result<(), ContactError> {
        if self.fitted == Some(*a) {
            return Ok(());
        }
        self.fitted = None;
        if self.shape_u.is_none() && self.combinations >= SHAPE_CONVOLUTIONS_AFTER {
            let mut shape_u: [Vec<f64>; BASIS] = std::array::from_fn(|_| Vec::new());
            for (k, u) in shape_u.iter_mut().enumerate() {
                let y = &mut responses.combination;
                y.fill(0.0);
                for (&e, &v) in self.active.iter().zip(&self.y[k]) {
                    y[e] = v;
                }
                solver.displacement(y, &mut responses.scratch)?;
                *u = self
                    .inactive
                    .iter()
                    .map(|&e| responses.scratch[e as usize])
                    .collect();
                self.bound[k] = u.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            }
            self.shape_u = Some(shape_u);
        }
        if let Some(shape_u) = &self.shape_u {
            for (j, u) in self.displaced.iter_mut().enumerate() {
                *u = (0..BASIS).map(|k| a[k] * shape_u[k][j]).sum();
            }
        } else {
            let combination = &mut responses.combination;
            combination.fill(0.0);
            for (c, &e) in self.active.iter().enumerate() {
                combination[e] = (0..BASIS).map(|k| a[k] * self.y[k][c]).sum();
            }
            solver.displacement(combination, &mut responses.scratch)?;
            for (u, &e) in self.displaced.iter_mut().zip(&self.inactive) {
                *u = responses.scratch[e as usize];
            }
            self.combinations += 1;
        }
        self.fitted = Some(*a);
        Ok(())
    }

    /// Whether the `j`-th element off C penetrates under the displacement in `displaced`
    /// and the column changes `delta_g`: e_r − Δg_i + Σ_k a_k (A y_k)_j < 0.
    fn penetrates(&self, j: usize, delta_g: &[f64]) -> bool {
        self.distance[j] - delta_g[self.inactive_column[j] as usize] + self.displaced[j] < 0.0
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
        &mut self,
        solver: &mut NormalSolver,
        responses: &mut Responses,
        delta: f64,
        column_gap: &[f64],
        delta_g: &mut Vec<f64>,
        in_contact: &mut Vec<bool>,
    ) -> Result<(), ContactError> {
        let a = self.fit(responses, delta, column_gap, delta_g);
        in_contact.clear();
        in_contact.resize(responses.shapes[0].len(), false);
        for (j, &e) in self.active.iter().enumerate() {
            let p: f64 = self.pressure[j] + (0..BASIS).map(|k| a[k] * self.y[k][j]).sum::<f64>();
            in_contact[e] = p >= 0.0;
        }
        if self.may_enter(&a, delta_g) {
            self.displace(solver, responses, &a)?;
            for j in 0..self.distance.len() {
                if self.penetrates(j, delta_g) {
                    in_contact[self.inactive[j] as usize] = true;
                }
            }
        }
        Ok(())
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
mod tests;
