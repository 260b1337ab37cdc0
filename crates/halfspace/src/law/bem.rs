//! The boundary-element (half-space) contact law: NormCG at prescribed approach.

use std::sync::Arc;

use super::response_table::SharedTable;
use super::reuse::{FrozenSet, Responses};
use super::{ContactLaw, LawOutput, check_columns};
use crate::error::{ContactError, positive};
use crate::gap::{GapShape, auto_grid};
use crate::grid::Grid;
use crate::material::Material;
use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};

/// When `evaluate(…, tangent = false)` runs the sensitivity solve for dF/dδ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentPolicy {
    /// Only when asked; otherwise the previous tangent (0 before the first) is returned.
    Requested,
    /// When asked, or when there is no previous tangent yet (quasi-Newton iterations that
    /// reuse the tangent of a step's first evaluation).
    RequestedOrMissing,
}

/// Settings of a [`BemLaw`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BemOptions {
    /// NormCG settings (`sensitivity` is set per call from the tangent policy).
    pub solver: SolverOptions,
    /// When the tangent is computed.
    pub tangent: TangentPolicy,
    /// Return the previous result without a solve when δ and the column corrections are
    /// unchanged (and a tangent is there if one is asked for).
    pub memoize: bool,
    /// Return zero without a solve when δ ≤ min h (no element can touch). Without it only
    /// δ ≤ 0 returns zero at once; for 0 < δ ≤ min h the solver runs (and its warm start
    /// restarts from the zero pressure).
    pub skip_separated: bool,
    /// Reuse of a full solve across evaluations (references.md §C8.4): an evaluation whose
    /// estimated force error on the frozen contact set of the last full solve is at most
    /// `reuse_tol` × that solve's force is answered by the model without a solve; 0 (the
    /// default) solves every evaluation. With reuse on the tangent is always fresh (the
    /// frozen set's dF/dδ).
    pub reuse_tol: f64,
}

impl Default for BemOptions {
    /// NormCG tolerance 1e-8, 500 iterations, tangent when asked, memoized, separated
    /// states skipped.
    fn default() -> Self {
        BemOptions {
            solver: SolverOptions {
                max_iter: 500,
                ..SolverOptions::default()
            },
            tangent: TangentPolicy::Requested,
            memoize: true,
            skip_separated: true,
            reuse_tol: 0.0,
        }
    }
}

/// The half-space contact law (references.md §C3.3): on a fixed grid with the undeformed gap
/// h_e = h₀(x_e, y_e) + c(ξ_i) (the law's base gap plus the caller's column correction of the
/// element's column i), NormCG solves for the pressure p ≥ 0 at the prescribed approach δ,
/// warm-started from the previous call.
///
/// * F = ΔA Σ p_e; k = dF/dδ from the solver's linearised sensitivity solve on the contact set;
/// * W = ½ ΔA Σ p_e u_e (Clapeyron), u = A p. For a fixed gap this equals ∫₀^δ F dδ' exactly for
///   the discrete problem: by the envelope theorem on min_{p ≥ 0} ½ pᵀA p − Σ p_e(δ − h_e),
///   d(½ΔA pᵀA p)/dδ = ΔA Σ p_e = F.
#[derive(Debug)]
pub struct BemLaw {
    solver: NormalSolver,
    options: BemOptions,
    grid: Grid,
    base_gap: Vec<f64>,
    /// min over each grid column of the base gap.
    base_column_min: Vec<f64>,
    gap: Vec<f64>,
    pressure: Vec<f64>,
    columns: Vec<f64>,
    last_column_gap: Vec<f64>,
    last: Option<(f64, LawOutput)>,
    last_stiffness: Option<f64>,
    column_force: Vec<f64>,
    solves: usize,
    reuse: Option<Reuse>,
    /// The response table F(δ) of the base gap shared with identical laws (reuse only).
    table: Option<Arc<SharedTable>>,
    /// Consecutive evaluations without column corrections (the table is used from
    /// [`TABLE_STREAK`] on).
    table_streak: usize,
}

/// Consecutive evaluations without column corrections after which a law uses (and if need
/// be builds) its shared response table: a wheel that meets a smooth rail only now and then
/// does not pay for a table. Counted per law, so whether an evaluation is answered by the
/// table does not depend on the order in which laws run (thread count).
pub const TABLE_STREAK: usize = 16;

/// The reuse state of a [`BemLaw`] (references.md §C8.4).
#[derive(Debug)]
struct Reuse {
    responses: Responses,
    model: Option<FrozenSet>,
    delta_g: Vec<f64>,
    /// The model's guess of the set (scratch).
    guess: Vec<bool>,
    stats: ReuseStats,
}

/// Counts of the reuse of full solves by a [`BemLaw`] (references.md §C8.4).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ReuseStats {
    /// Full NormCG solves (including the static start).
    pub full_solves: usize,
    /// Exact solves by active-set updates of the dense factor of the last model's set
    /// (references.md §C8.4), instead of a NormCG solve.
    pub factor_solves: usize,
    /// Evaluations answered by the frozen-set model without a solve.
    pub reused: usize,
    /// Largest estimated force error of a reused evaluation, relative to the force of the
    /// full solve its model was built from.
    pub max_estimate: f64,
    /// The estimate of the last evaluation in the same measure (0 when it solved).
    pub last_estimate: f64,
    /// Evaluations answered by the shared response table F(δ) (no column corrections;
    /// [`BemLaw::share_table`]); their estimates are in `max_estimate` too.
    pub table_answers: usize,
}

impl BemLaw {
    /// A law on `grid` with the base gap `base_gap` \[m\] (one value per element, x fastest).
    pub fn new(
        grid: Grid,
        material: Material,
        base_gap: Vec<f64>,
        options: BemOptions,
    ) -> Result<Self, ContactError> {
        if base_gap.len() != grid.len() {
            return Err(ContactError::SizeMismatch {
                name: "base_gap",
                expected: grid.len(),
                found: base_gap.len(),
            });
        }
        positive("tol", options.solver.tol)?;
        positive("sensitivity_tol", options.solver.sensitivity_tol)?;
        if !(options.reuse_tol.is_finite() && options.reuse_tol >= 0.0) {
            return Err(ContactError::InvalidParameter {
                name: "reuse_tol",
                value: options.reuse_tol,
                reason: "must be finite and non-negative (0: no reuse)",
            });
        }
        let mut solver = NormalSolver::new(grid, material)?;
        let reuse = if options.reuse_tol > 0.0 {
            Some(Reuse {
                responses: Responses::new(&grid, &mut solver)?,
                model: None,
                delta_g: Vec::with_capacity(grid.nx),
                guess: Vec::new(),
                stats: ReuseStats::default(),
            })
        } else {
            None
        };
        let n = grid.len();
        let mut base_column_min = vec![f64::INFINITY; grid.nx];
        for (k, &h) in base_gap.iter().enumerate() {
            let column = &mut base_column_min[k % grid.nx];
            *column = column.min(h);
        }
        Ok(Self {
            solver,
            options,
            grid,
            base_column_min,
            gap: base_gap.clone(),
            base_gap,
            pressure: vec![0.0; n],
            columns: (0..grid.nx).map(|ix| grid.x(ix)).collect(),
            last_column_gap: Vec::with_capacity(grid.nx),
            last: None,
            last_stiffness: None,
            column_force: vec![0.0; grid.nx],
            solves: 0,
            reuse,
            table: None,
            table_streak: 0,
        })
    }

    /// A law for a point-contact `shape` on the automatic `elements × elements` grid sized for
    /// `max_load` ([`auto_grid`]), with the sampled gap of the shape.
    pub fn from_shape(
        shape: &GapShape,
        material: Material,
        max_load: NormalLoad,
        elements: usize,
        options: BemOptions,
    ) -> Result<Self, ContactError> {
        let grid = auto_grid(shape, &material, max_load, elements)?;
        let gap = shape.sample(&grid)?;
        Self::new(grid, material, gap, options)
    }

    /// A wheel (rolling radius R_w) on a rail head (transverse radius R_r) on an n × n grid
    /// centred on the wheel with half-widths 1.25 × the Hertz semi-axes at `max_force` \[N\]:
    /// h(ξ, y) = R_w − √(R_w² − ξ²) + R_r − √(R_r² − y²) (exact circles).
    pub fn wheel_on_rail(
        wheel_radius: f64,
        rail_profile_radius: f64,
        material: Material,
        n: usize,
        max_force: f64,
        options: BemOptions,
    ) -> Result<Self, ContactError> {
        let (rw, rr) = (
            positive("wheel_radius", wheel_radius)?,
            positive("rail_profile_radius", rail_profile_radius)?,
        );
        let hertz =
            crate::hertz::Hertz::elliptic(0.5 / rw, 0.5 / rr, material.e_star, max_force.max(1.0))?;
        let (hx, hy) = (1.25 * hertz.a, 1.25 * hertz.b);
        if n == 0 {
            return Err(ContactError::InvalidParameter {
                name: "n",
                value: 0.0,
                reason: "the grid needs at least one element per direction",
            });
        }
        let grid = Grid::centred(n, n, 2.0 * hx / n as f64, 2.0 * hy / n as f64, 0.0, 0.0)?;
        let gap =
            grid.sample(|x, y| (rw - (rw * rw - x * x).sqrt()) + (rr - (rr * rr - y * y).sqrt()));
        Self::new(grid, material, gap, options)
    }

    /// Answers evaluations without column corrections (δ only: a wheel on a flat, rigid,
    /// smooth track) from `table`, built on first use from this law's grid, material and base
    /// gap (`response_table` module); every law sharing it must have the same. Only with
    /// reuse on (`reuse_tol` > 0, which should be the table's tolerance): `reuse_tol = 0`
    /// keeps solving every evaluation.
    pub fn share_table(&mut self, table: Arc<SharedTable>) {
        if self.reuse.is_some() {
            self.table = Some(table);
        }
    }

    /// The shared response table, if one is attached.
    pub fn table(&self) -> Option<&Arc<SharedTable>> {
        self.table.as_ref()
    }

    /// The grid (x along the rolling direction, centred on the contact point).
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The base gap h₀ \[m\] per element.
    pub fn base_gap(&self) -> &[f64] {
        &self.base_gap
    }

    /// Number of NormCG solves so far.
    pub fn solves(&self) -> usize {
        self.solves
    }

    /// Number of FFT convolutions so far.
    pub fn convolutions(&self) -> usize {
        self.solver.convolutions()
    }

    /// The settings.
    pub fn options(&self) -> &BemOptions {
        &self.options
    }

    /// The undeformed gap h_e = h₀_e + c(ξ_i) of every element, for a full solve.
    fn set_gap(&mut self, column_gap: &[f64]) {
        let nx = self.grid.nx;
        if column_gap.is_empty() {
            self.gap.copy_from_slice(&self.base_gap);
        } else {
            for (k, (g, b)) in self.gap.iter_mut().zip(&self.base_gap).enumerate() {
                *g = b + column_gap[k % nx];
            }
        }
    }

    /// min_e h_e = min_i (min over column i of h₀ + c(ξ_i)), from the base gap's column
    /// minima (O(nx): a reused evaluation never forms the gap of every element).
    fn min_gap(&self, column_gap: &[f64]) -> f64 {
        if column_gap.is_empty() {
            return self
                .base_column_min
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min);
        }
        self.base_column_min
            .iter()
            .zip(column_gap)
            .map(|(b, c)| b + c)
            .fold(f64::INFINITY, f64::min)
    }

    fn memo_hit(&self, delta: f64, column_gap: &[f64], tangent: bool) -> Option<LawOutput> {
        if !self.options.memoize {
            return None;
        }
        let (d, out) = self.last?;
        let same_gap = column_gap == self.last_column_gap.as_slice()
            || (column_gap.is_empty() && self.last_column_gap.iter().all(|c| *c == 0.0));
        (d == delta && same_gap && (!tangent || out.tangent_fresh)).then_some(out)
    }
}

impl BemLaw {
    /// The shared table's answer when one is attached, the column corrections are all zero
    /// and δ lies in an interval the table uses (`response_table` module).
    fn try_table(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
    ) -> Option<LawOutput> {
        let shared = self.table.as_ref()?;
        if column_gap.iter().any(|&c| c != 0.0) {
            self.table_streak = 0;
            return None;
        }
        self.table_streak += 1;
        if self.table_streak < TABLE_STREAK {
            return None;
        }
        let material = *self.solver.material();
        let table = shared.get(self.grid, material, &self.base_gap)?;
        let a = table.answer(delta, &mut self.column_force, &mut self.pressure)?;
        self.reuse.as_mut()?.stats.table_answers += 1;
        let fields = (a.force, a.stiffness, a.energy, a.max_pressure, a.patch);
        Some(self.answered(column_force, a.estimate, fields))
    }

    /// Records an evaluation answered without a solve (by the frozen-set model or the
    /// response table) with the relative `estimate` of its force error, whose column forces
    /// are in `self.column_force`: the statistics, the caller's column forces and the tangent;
    /// returns its output from `(force, stiffness, energy, max_pressure, patch)`.
    fn answered(
        &mut self,
        column_force: &mut [f64],
        estimate: f64,
        (force, stiffness, energy, max_pressure, patch): (f64, f64, f64, f64, (f64, f64)),
    ) -> LawOutput {
        if let Some(reuse) = self.reuse.as_mut() {
            reuse.stats.last_estimate = estimate;
            reuse.stats.max_estimate = reuse.stats.max_estimate.max(estimate);
        }
        column_force.copy_from_slice(&self.column_force[..column_force.len()]);
        self.last_stiffness = Some(stiffness);
        LawOutput {
            force,
            stiffness,
            tangent_fresh: true,
            energy,
            patch_length: patch.0,
            patch_width: patch.1,
            max_pressure,
            iterations: 0,
        }
    }

    /// The frozen-set model's answer when reuse is on, a model exists and its estimate is
    /// within `reuse_tol` (references.md §C8.4).
    fn try_reuse(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
    ) -> Option<LawOutput> {
        let tol = self.options.reuse_tol;
        let reuse = self.reuse.as_mut()?;
        reuse.stats.last_estimate = 0.0;
        let model = reuse.model.as_mut()?;
        let prediction = model.predict(
            &mut self.solver,
            &mut reuse.responses,
            delta,
            column_gap,
            &mut self.column_force,
            &mut self.pressure,
            &mut reuse.delta_g,
        )?;
        let reference = model.reference_force();
        // A NaN estimate fails the comparison and solves.
        let within = prediction.estimate <= tol * reference;
        if !within || prediction.force <= 0.0 {
            return None;
        }
        reuse.stats.reused += 1;
        let p = prediction;
        let fields = (p.force, p.stiffness, p.energy, p.max_pressure, p.patch);
        Some(self.answered(column_force, p.estimate / reference, fields))
    }

    /// With reuse on and a model built with the dense factor, the exact solution at `delta`
    /// (for the gap in `self.gap`, with the column corrections `column_gap`) by active-set
    /// updates of the factor from the model's guess of the set
    /// ([`set_solve`]); `None` otherwise or when that iteration fails (the model is then
    /// dropped: the factor has left its set).
    fn factor_solve(
        &mut self,
        delta: f64,
        column_gap: &[f64],
    ) -> Result<Option<crate::solution::NormalSolution>, ContactError> {
        let Some(reuse) = self.reuse.as_mut() else {
            return Ok(None);
        };
        let Some(model) = reuse.model.as_mut().filter(|m| m.factored()) else {
            return Ok(None);
        };
        let delta_g = &mut reuse.delta_g;
        let responses = &mut reuse.responses;
        // The model's guess needs the responses read-only; it fills the flags first.
        let mut guess = std::mem::take(&mut reuse.guess);
        model.predicted_set(
            &mut self.solver,
            responses,
            delta,
            column_gap,
            delta_g,
            &mut guess,
        )?;
        let solution = responses.solve_set(&mut self.solver, &self.gap, delta, |set| {
            std::mem::swap(set, &mut guess)
        })?;
        reuse.guess = guess;
        match solution {
            Some(_) => reuse.stats.factor_solves += 1,
            None => reuse.model = None,
        }
        Ok(solution)
    }

    /// With reuse on, the frozen-set model of the full `solution`; returns its dF/dδ.
    fn rebuild_model(
        &mut self,
        solution: &crate::solution::NormalSolution,
        delta: f64,
        column_gap: &[f64],
        energy: f64,
    ) -> Result<Option<f64>, ContactError> {
        let Some(reuse) = self.reuse.as_mut() else {
            return Ok(None);
        };
        reuse.model = None;
        if solution.elements_in_contact == 0 {
            return Ok(None);
        }
        let model = FrozenSet::build(
            &mut self.solver,
            &mut reuse.responses,
            solution,
            delta,
            column_gap,
            &self.column_force,
            energy,
            self.options.solver.max_iter,
        )?;
        let stiffness = model.as_ref().map(|m| m.stiffness());
        reuse.model = model;
        if let Some(k) = stiffness {
            self.last_stiffness = Some(k);
        }
        Ok(stiffness)
    }
}

impl ContactLaw for BemLaw {
    fn name(&self) -> &'static str {
        "bem"
    }

    fn columns(&self) -> &[f64] {
        &self.columns
    }

    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        tangent: bool,
    ) -> Result<LawOutput, ContactError> {
        check_columns(self.grid.nx, column_gap, column_force)?;
        crate::error::finite("approach", delta)?;
        if let Some(out) = self.memo_hit(delta, column_gap, tangent) {
            column_force.copy_from_slice(&self.column_force[..column_force.len()]);
            return Ok(out);
        }
        let min_gap = self.min_gap(column_gap);
        self.last_column_gap.clear();
        self.last_column_gap.extend_from_slice(column_gap);
        let separated = if self.options.skip_separated {
            min_gap
        } else {
            0.0
        };
        if delta <= separated {
            self.pressure.fill(0.0);
            self.column_force.fill(0.0);
            column_force.fill(0.0);
            let out = LawOutput {
                tangent_fresh: true,
                ..LawOutput::default()
            };
            self.last = Some((delta, out));
            return Ok(out);
        }
        if let Some(out) = self.try_table(delta, column_gap, column_force) {
            self.last = Some((delta, out));
            return Ok(out);
        }
        if let Some(out) = self.try_reuse(delta, column_gap, column_force) {
            self.last = Some((delta, out));
            return Ok(out);
        }
        self.set_gap(column_gap);
        let reusing = self.reuse.is_some();
        if self.reuse.as_ref().is_some_and(|r| r.model.is_some()) {
            // Start from the latest reused pressure (closer than the last full solve's).
            self.solver.set_initial_pressure(&self.pressure)?;
        }
        let sensitivity = !reusing
            && match self.options.tangent {
                TangentPolicy::Requested => tangent,
                TangentPolicy::RequestedOrMissing => {
                    tangent || self.last_stiffness.is_none_or(|k| k <= 0.0)
                }
            };
        let options = SolverOptions {
            sensitivity,
            ..self.options.solver
        };
        let solution = match self.factor_solve(delta, column_gap)? {
            Some(solution) => solution,
            None => {
                let solution =
                    self.solver
                        .solve(&self.gap, NormalLoad::Approach(delta), &options)?;
                self.solves += 1;
                solution
            }
        };
        let (stiffness, tangent_fresh) = match solution.dfn_dapproach {
            Some(k) if sensitivity => {
                self.last_stiffness = Some(k);
                (k, true)
            }
            _ => (self.last_stiffness.unwrap_or(0.0), false),
        };
        let area = self.grid.element_area();
        let nx = self.grid.nx;
        self.column_force.fill(0.0);
        for (k, p) in solution.pressure.iter().enumerate() {
            self.column_force[k % nx] += p * area;
        }
        column_force.copy_from_slice(&self.column_force[..column_force.len()]);
        let work: f64 = solution
            .pressure
            .iter()
            .zip(&solution.displacement)
            .map(|(p, u)| p * u)
            .sum();
        let (a, b) = if solution.elements_in_contact > 0 {
            solution.patch_half_widths()
        } else {
            (0.0, 0.0)
        };
        self.pressure.copy_from_slice(&solution.pressure);
        let energy = 0.5 * area * work;
        let (stiffness, tangent_fresh) =
            match self.rebuild_model(&solution, delta, column_gap, energy)? {
                Some(k) => (k, true),
                None => (stiffness, tangent_fresh),
            };
        let out = LawOutput {
            force: solution.normal_force,
            stiffness,
            tangent_fresh,
            energy,
            patch_length: 2.0 * a,
            patch_width: 2.0 * b,
            max_pressure: solution.max_pressure,
            iterations: solution.iterations,
        };
        self.last = Some((delta, out));
        Ok(out)
    }

    /// NormCG at prescribed force on the base gap (no column corrections), with the
    /// settings' `solver` options as given (including their `sensitivity`).
    fn static_approach(&mut self, force: f64) -> Result<f64, ContactError> {
        self.gap.copy_from_slice(&self.base_gap);
        self.last = None;
        if let Some(reuse) = self.reuse.as_mut() {
            reuse.model = None;
        }
        let solution =
            self.solver
                .solve(&self.gap, NormalLoad::Force(force), &self.options.solver)?;
        self.solves += 1;
        self.pressure.copy_from_slice(&solution.pressure);
        Ok(solution.approach)
    }

    fn reuse_stats(&self) -> Option<ReuseStats> {
        Some(ReuseStats {
            full_solves: self.solves,
            ..self.reuse.as_ref().map(|r| r.stats).unwrap_or_default()
        })
    }

    fn pressure_field(&self) -> Option<(&Grid, &[f64])> {
        Some((&self.grid, &self.pressure))
    }

    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        out.clear();
        let (nx, iy) = (self.grid.nx, self.grid.ny / 2);
        for ix in 0..nx {
            out.push((self.grid.x(ix), self.pressure[iy * nx + ix]));
        }
    }
}
