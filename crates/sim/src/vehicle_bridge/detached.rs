//! Vehicles off the span solved on their own (issue #10, performance).
//!
//! While none of a bogie vehicle's wheels is on the span, every mode shape under it is zero:
//! its wheels' vectors ĝ and v are the unit vectors of their own DOFs, and the coupled step
//! (module documentation, "Time step") splits exactly into the bridge with the vehicles on it,
//! and one 10-DOF system with four contacts per vehicle off the span. Such a vehicle is held
//! out of the coupled iteration (module `resting`) and solved here with the same quasi-Newton
//! iteration in its own small dense work space: the block B of the step matrix A and its
//! inverse (`linalg::BlockDiagonal::dense_block`), the extrapolated start
//! `F ≈ F_n + k_n (δ − δ_n)`, the contact law with its tangent at the first evaluation, the
//! Woodbury update
//!
//! ```text
//! (K_c⁻¹ + s E B⁻¹ Eᵀ) ΔF = E B⁻¹(−R),   Δx = B⁻¹(−R) − s B⁻¹ Eᵀ ΔF
//! ```
//!
//! (E picks the wheel DOFs: the capacitance matrix is the wheels' rows and columns of B⁻¹,
//! references.md §D4.2), the force floor of `Simulation::force_floor` and the same convergence
//! and acceptance tests. It is the general step's algebra on the vehicle's block; what differs
//! is that the vehicle iterates until its own forces have converged instead of until every
//! wheel of the train has, so the two agree to the coupling tolerance (the test
//! `train_resting_vehicles::detached_vehicles_equal_the_coupled_step`), and it costs a few
//! 10 × 10 products instead of the general per-wheel patterns, supports and groups.
//!
//! It applies to bogie vehicles ([`MAX_DOFS`] DOFs, [`MAX_WHEELS`] wheels: fixed-size kernels)
//! with compliant contacts (Hertz, or BEM, whose column forces load no mode off the span),
//! under the conditions of module `resting`.

use halfspace::law::ContactModel as LawModel;

use super::Simulation;
use super::contact::wheel_error;
use super::linalg::small_solve_in_place;
use super::step::StepFailure;
use super::vehicles::VehicleDofs;

/// The DOFs of a vehicle solved on its own (a bogie vehicle).
pub(super) const MAX_DOFS: usize = 10;
/// Its wheels (their DOFs follow the own DOFs).
pub(super) const MAX_WHEELS: usize = 4;

/// Whether vehicle `veh` can be solved on its own when off the span: a bogie vehicle, every
/// wheel in compliant contact (a point contact, or a BEM patch: off the span its column
/// forces load no mode, so only the wheel's total force enters).
pub(super) fn applies(veh: &VehicleDofs, contacts: &[LawModel]) -> bool {
    let wheels = veh.dofs.len() - veh.own().len();
    veh.dofs.len() == MAX_DOFS
        && wheels == MAX_WHEELS
        && (veh.first_wheel..veh.first_wheel + wheels)
            .all(|k| matches!(contacts[k], LawModel::Law(_)))
}

/// A vehicle's block of the step matrix: entries and inverse, row-major.
struct Block<'a> {
    entries: &'a [[f64; MAX_DOFS]],
    inverse: &'a [[f64; MAX_DOFS]],
}

/// `M x` for the rows `m`, or `|M| x` if `abs` (fixed size: the compiler unrolls it).
#[inline]
fn apply(m: &[[f64; MAX_DOFS]], x: &[f64; MAX_DOFS], abs: bool) -> [f64; MAX_DOFS] {
    let mut out = [0.0; MAX_DOFS];
    for (o, row) in out.iter_mut().zip(m) {
        *o = if abs {
            row.iter().zip(x).map(|(a, x)| a.abs() * x).sum()
        } else {
            row.iter().zip(x).map(|(a, x)| a * x).sum()
        };
    }
    out
}

impl Block<'_> {
    /// `(B⁻¹)_ij`.
    #[inline]
    fn inv(&self, i: usize, j: usize) -> f64 {
        self.inverse[i][j]
    }

    /// One linearised update (the Woodbury formula of the module documentation) for the
    /// residual `−R` in `res`: the wheels `active` (local DOF indices) with compliances
    /// `compliance`; returns `(Δx, ΔF)`, or `None` if the capacitance matrix is singular.
    fn update(
        &self,
        s: f64,
        res: &[f64; MAX_DOFS],
        active: &[usize],
        compliance: &[f64],
    ) -> Option<([f64; MAX_DOFS], [f64; MAX_WHEELS])> {
        let mut dx = apply(self.inverse, res, false);
        let na = active.len();
        let mut cap = [0.0; MAX_WHEELS * MAX_WHEELS];
        let mut df = [0.0; MAX_WHEELS];
        for (a, &wa) in active.iter().enumerate() {
            for (b, &wb) in active.iter().enumerate() {
                let diag = if a == b { compliance[a] } else { 0.0 };
                cap[a * na + b] = diag + s * self.inv(wa, wb);
            }
            df[a] = dx[wa];
        }
        if na > 0 && !small_solve_in_place(&mut cap[..na * na], &mut df[..na]) {
            return None;
        }
        for (a, &wa) in active.iter().enumerate() {
            let f = s * df[a];
            for (x, row) in dx.iter_mut().zip(self.inverse) {
                *x -= f * row[wa];
            }
        }
        Some((dx, df))
    }
}

/// A failed detached solve (the step is retried as two half steps, as for the coupled one).
fn failure(iterations: usize, change: f64, reason: String) -> StepFailure {
    StepFailure {
        iterations,
        change,
        reason,
        fatal: None,
    }
}

impl Simulation {
    /// Solves the step of every detached vehicle (module documentation) after the coupled
    /// iteration; returns the contact-solver iterations.
    pub(super) fn solve_detached(&mut self, s: f64, tol: f64) -> Result<usize, StepFailure> {
        let mut contact_iterations = 0;
        for i in 0..self.resting.detached.len() {
            let v = self.resting.detached[i];
            contact_iterations += self.solve_detached_vehicle(v, s, tol)?;
        }
        Ok(contact_iterations)
    }

    /// The quasi-Newton step of detached vehicle `v` (its block of A is the v-th dense block).
    fn solve_detached_vehicle(&mut self, v: usize, s: f64, tol: f64) -> Result<usize, StepFailure> {
        let veh = &self.vehicles[v];
        let own = veh.own().len();
        let nwh = veh.dofs.len() - own;
        let k0 = veh.first_wheel;
        let Some((indices, entries, inverse)) = self.a_matrix.dense_block(v) else {
            return Err(failure(0, 0.0, "no step-matrix block".to_string()));
        };
        let (entries, inverse) = (entries.as_chunks().0, inverse.as_chunks().0);
        if indices.len() != MAX_DOFS || entries.len() != MAX_DOFS || inverse.len() != MAX_DOFS {
            return Err(failure(0, 0.0, "not a bogie vehicle's block".to_string()));
        }
        let b = Block { entries, inverse };
        let w = &mut self.work;
        let mut x = [0.0; MAX_DOFS];
        let mut r = [0.0; MAX_DOFS];
        for (l, &i) in indices.iter().enumerate() {
            x[l] = w.x[i];
            r[l] = w.r[i];
        }
        let rk: [f64; MAX_WHEELS] =
            std::array::from_fn(|c| if c < nwh { w.r_at_wheel[k0 + c] } else { 0.0 });
        // −R = r − B x − s Σ F_c e_c (the wheels' DOFs follow the own DOFs).
        let residual = |x: &[f64; MAX_DOFS], forces: &[f64]| {
            let mut res = apply(b.entries, x, false);
            for (l, v) in res.iter_mut().enumerate() {
                *v = r[l] - *v;
            }
            for (c, f) in forces.iter().enumerate() {
                res[own + c] -= s * f;
            }
            res
        };
        let wheel_dofs: [usize; MAX_WHEELS] = std::array::from_fn(|c| own + c);
        let wheel_dofs = &wheel_dofs[..nwh];
        // Extrapolated start (as `Simulation::extrapolated_start`, on this vehicle).
        let usable = (k0..k0 + nwh).all(|k| {
            w.outputs[k].force > 0.0
                && w.outputs[k].stiffness > 0.0
                && w.column_force[k].iter().sum::<f64>() > 0.0
        });
        if usable {
            let mut forces = [0.0; MAX_WHEELS];
            let mut compliance = [0.0; MAX_WHEELS];
            let mut positive = true;
            for c in 0..nwh {
                let k = k0 + c;
                let (f_n, k_n) = (w.outputs[k].force, w.outputs[k].stiffness);
                forces[c] = f_n + k_n * (x[own + c] + rk[c] - w.delta[k]);
                compliance[c] = 1.0 / k_n;
                positive &= forces[c] > 0.0;
            }
            if positive {
                let res = residual(&x, &forces[..nwh]);
                if let Some((dx, _)) = b.update(s, &res, wheel_dofs, &compliance[..nwh])
                    && dx.iter().all(|d| d.is_finite())
                {
                    for (xl, d) in x.iter_mut().zip(&dx) {
                        *xl += d;
                    }
                }
            }
        }
        let mut change = f64::INFINITY;
        let mut history = [f64::INFINITY; 2];
        let mut growth = 0;
        let mut floor = w.force_floor;
        let mut prev = [0.0; MAX_WHEELS];
        let mut contact_iterations = 0;
        for it in 1..=self.scenario.coupling.max_iter {
            // The contact laws at the iterate (the tangent at the first evaluation).
            let mut forces = [0.0; MAX_WHEELS];
            for c in 0..nwh {
                let k = k0 + c;
                let delta = x[own + c] + rk[c];
                w.delta[k] = delta;
                for (gap, rc) in w.column_gap[k].iter_mut().zip(&w.r_at_columns[k]) {
                    *gap = -(rc - rk[c]);
                }
                let LawModel::Law(law) = &mut self.contacts[k] else {
                    return Err(failure(it, change, "not a compliant contact".to_string()));
                };
                let out = law
                    .evaluate(delta, &w.column_gap[k], &mut w.column_force[k], it == 1)
                    .map_err(|e| failure(it, change, wheel_error(k)(e).to_string()))?;
                contact_iterations += out.iterations;
                w.outputs[k] = out;
                forces[c] = out.force;
            }
            if it > 1 {
                let c = (0..nwh).fold(0.0f64, |m, c| m.max((forces[c] - prev[c]).abs()));
                growth = if c > change { growth + 1 } else { 0 };
                change = c;
                if !change.is_finite() || (growth >= 4 && change > 10.0 * self.force_scale) {
                    return Err(failure(it, change, "the iteration diverges".to_string()));
                }
                let stagnant = change <= 16.0 * floor && history[0].min(history[1]) <= change;
                if change <= tol.max(floor) || stagnant {
                    return self.finish_detached(v, &x, contact_iterations);
                }
                history = [history[1], change];
            }
            prev = forces;
            let res = residual(&x, &forces[..nwh]);
            let mut active = [0; MAX_WHEELS];
            let mut compliance = [0.0; MAX_WHEELS];
            let mut na = 0;
            for c in 0..nwh {
                let stiffness = w.outputs[k0 + c].stiffness;
                if stiffness > 0.0 {
                    active[na] = own + c;
                    compliance[na] = 1.0 / stiffness;
                    na += 1;
                }
            }
            if it == 1 {
                // The floating-point floor (`Simulation::force_floor`) of this vehicle's forces.
                let mut e = apply(b.entries, &x, false);
                for (l, ei) in e.iter_mut().enumerate() {
                    *ei = ei.abs() + r[l].abs();
                }
                for c in 0..nwh {
                    e[own + c] += s * forces[c].abs();
                }
                let e = apply(b.inverse, &e, true);
                for c in 0..nwh {
                    let (k, l) = (k0 + c, own + c);
                    let stiffness = w.outputs[k].stiffness;
                    let compliance = if stiffness > 0.0 {
                        1.0 / stiffness
                    } else {
                        0.0
                    };
                    let den = compliance + s * b.inv(l, l).abs();
                    w.wheel_floor[k] = if den > 0.0 && den.is_finite() {
                        32.0 * f64::EPSILON * (e[l] + x[l].abs() + rk[c].abs()) / den
                    } else {
                        0.0
                    };
                    floor = floor.max(w.wheel_floor[k]);
                }
                w.force_floor = floor;
            }
            let Some((dx, df)) = b.update(s, &res, &active[..na], &compliance[..na]) else {
                return Err(failure(
                    it,
                    change,
                    "singular or non-finite capacitance matrix in the detached step".to_string(),
                ));
            };
            for (xl, d) in x.iter_mut().zip(&dx) {
                *xl += d;
            }
            if x.iter().any(|v| !v.is_finite()) {
                return Err(failure(it, change, "non-finite state".to_string()));
            }
            // Every wheel in contact and the predicted corrections within the tolerance: the
            // corrected state with the linearised forces.
            let predicted = df[..na].iter().fold(0.0f64, |m, d| m.max(d.abs()));
            let all_positive = (0..na).all(|a| forces[active[a] - own] + df[a] > 0.0);
            if na == nwh && predicted <= tol.max(floor) && all_positive {
                for a in 0..na {
                    let c = active[a] - own;
                    let k = k0 + c;
                    w.outputs[k].force = forces[c] + df[a];
                    w.delta[k] = x[own + c] + rk[c];
                }
                return self.finish_detached(v, &x, contact_iterations);
            }
        }
        Err(failure(
            self.scenario.coupling.max_iter,
            change,
            format!(
                "no convergence of a vehicle off the span in {} iterations to the target force change {tol:e} N",
                self.scenario.coupling.max_iter
            ),
        ))
    }

    /// Writes the converged state of detached vehicle `v` into the step's state.
    fn finish_detached(
        &mut self,
        v: usize,
        x: &[f64; MAX_DOFS],
        contact_iterations: usize,
    ) -> Result<usize, StepFailure> {
        for (l, &i) in self.vehicles[v].dofs.iter().enumerate() {
            self.work.x[i] = x[l];
        }
        Ok(contact_iterations)
    }
}
