//! The coupling iteration of one step attempt (module documentation, "Time step"): the
//! Picard, quasi-Newton (Sherman–Morrison / Woodbury) and Newton iterations, the
//! extrapolated quasi-Newton start, and the floating-point floor of the contact forces.

use std::ops::Range;

use super::accept::{Accepted, StateUpdate};
use super::contact::{is_point, is_rigid};
use super::contact_eval::add_modal_load;
use super::detached::evaluate_wheel;
use super::linalg::{contact_update, dense_contact_update};
use super::step::StepFailure;
use super::{CouplingSolver, Simulation, VehicleBridgeError};

/// The quasi-Newton iteration keeps the factorisation of an articulated rake's band with its
/// folded off-span wheels while each of their contact stiffnesses is within this relative
/// change of the one factorised (`linalg::CapacitanceWork::set_fold_tolerance`): a chord
/// step for those wheels, whose error contracts by at least this factor per update.
pub(super) const FOLD_TOLERANCE: f64 = 1e-3;

impl Simulation {
    /// Checks at run time that every wheel's v stays the same within a step attempt, as the
    /// coupled step declares to the capacitance work space after each attempt's geometry
    /// (`linalg::CapacitanceWork::new_geometry`; always checked in debug builds): a panic
    /// naming the wheel if not. For tests; it costs a comparison of v per wheel and update.
    pub fn verify_declared_geometry(&mut self, on: bool) {
        self.work.cap.verify_declared_geometry(on);
    }

    /// Quasi-Newton start without a contact evaluation: every contact law is replaced by its
    /// linearisation at the end of the previous step, `F ≈ F_n + k_n (δ − δ_n)`, with the
    /// previous column forces carried along with the wheel (modal loads
    /// `I_j ≈ (F/F_n) Σ_i F_n,i w_j(x_k + ξ_i)` at the new position), and one
    /// Sherman–Morrison/Woodbury update is applied to the predictor `work.x`. The following
    /// contact evaluations correct it; with a smooth force history the first correction is then
    /// often already below the tolerance, so the step needs one contact solve instead of two.
    /// Skipped unless every wheel is in compliant contact with a known tangent.
    ///
    /// Returns whether the state is now the solution under known forces φ of point contacts
    /// (in `work.prev_force`): the first evaluation can then be compared with φ (the change
    /// test of the iteration, `Simulation::try_step`).
    fn extrapolated_start(&mut self, s: f64) -> bool {
        let m = self.scenario.bridge.n_modes();
        let live = &self.resting.live;
        let nl = live.len();
        let w = &mut self.work;
        let usable = live.iter().all(|&k| {
            !is_rigid(&self.contacts[k])
                && w.outputs[k].force > 0.0
                && w.outputs[k].stiffness > 0.0
                && w.column_force[k].iter().sum::<f64>() > 0.0
        });
        if !usable {
            return false;
        }
        let mut points = true;
        self.a_matrix.mul(&w.x, &mut w.res);
        let rows = &self.resting.live_rows;
        residual_rows(rows, &w.r, &mut w.res);
        Self::zero_held(&self.resting.held_dofs, &mut w.res);
        for (a, &k) in live.iter().enumerate() {
            let iw = self.wheel_dof[k];
            let delta = w.approach(k, iw, &w.x);
            // A point contact's law linearised at the predicted approach δ* (the predictor's,
            // corrected by its error in the last step: `Work::start_point`):
            // F ≈ F(δ*) + k(δ*)(δ − δ*), whose error ½ F'' (δ − δ*)² is far below that of the
            // tangent of the previous step, ½ F'' (δ − δ_n)², so that the first evaluation is
            // often within the tolerance of the forces the start carries, and otherwise the
            // first correction (one contact evaluation per step instead of two). Other laws
            // (a BEM solve per evaluation): F ≈ F_n + k_n (δ − δ_n).
            let point = is_point(&self.contacts[k]);
            points &= point;
            let (force, k_n) = if point {
                let rk = w.r_at_wheel[k];
                let at = w.start_point(k, delta, self.stats.steps);
                match evaluate_wheel(&mut self.contacts, w, k, at, rk, true) {
                    // The linearised law at the predictor's approach.
                    Ok(out) => (out.force + out.stiffness * (delta - at), out.stiffness),
                    Err(_) => return false,
                }
            } else {
                let (f_n, k_n) = (w.outputs[k].force, w.outputs[k].stiffness);
                (f_n + k_n * (delta - w.delta[k]), k_n)
            };
            if force <= 0.0 || k_n <= 0.0 || !k_n.is_finite() {
                return false;
            }
            // The linearised force at the linearisation point (+ ΔF of the update below).
            w.prev_force[k] = force;
            w.law.force[k] = force;
            let shapes = &w.shape_at_wheel[k];
            let cols: f64 = w.column_force[k].iter().sum();
            let scale = force / cols;
            // Only the pattern (modes and the wheel) is ever written, so the rest stays zero.
            let (gh, v) = (&mut w.g_act[k], &mut w.v_act[k]);
            let mk = w.span_modes[k];
            if mk > 0 {
                gh[..m].fill(0.0);
                // I_k at the new position, held in `gh` first.
                add_modal_load(
                    &w.shape_at_columns[k],
                    &w.column_force[k],
                    scale,
                    &mut gh[..m],
                );
            }
            // −R gets +s I_k on the modes and −s F_k on the wheel; ĝ = (−I/F, +1), exactly
            // −w(x_k) for a point contact (as in `evaluate_contacts`).
            for j in 0..mk {
                w.res[j] += s * gh[j];
                gh[j] = if point { -shapes[j] } else { -gh[j] / force };
                v[j] = -shapes[j];
            }
            w.res[iw] -= s * force;
            gh[iw] = 1.0;
            v[iw] = 1.0;
            w.compliance[a] = 1.0 / k_n;
            w.delta_tilde[a] = 0.0;
        }
        let solved = contact_update(
            &self.a_matrix,
            s,
            &w.g_act,
            &w.v_act,
            &w.pattern,
            live,
            &w.compliance[..nl],
            &w.delta_tilde[..nl],
            &mut w.res,
            &mut w.df,
            &mut w.cap,
        );
        // A singular update leaves the predictor as it is (the iteration then starts there).
        // The held rows of the update are zero (they keep their state).
        if solved.is_ok()
            && rows
                .iter()
                .all(|r| w.res[r.clone()].iter().all(|d| d.is_finite()))
        {
            add_rows(rows, &w.res, &mut w.x);
            // φ = F + ΔF, the forces the state now carries; for a wheel folded into an
            // articulated rake's kept factorisation (a chord step) the increment its solve
            // used, `fold_ratio` × ΔF (as `law_residual` records it).
            for (a, &k) in live.iter().enumerate() {
                w.prev_force[k] += w.cap.fold_ratio(a) * w.df[a];
            }
            self.record_linearised(true);
            return points;
        }
        false
    }

    /// Bounds the contact forces' floating-point floor where the bound decides the same as
    /// the floor (`true`; the force floor of the coupled step: the states, forces and iteration counts are
    /// the same bit for bit, the reported `max_force_floor` is then an upper bound), or
    /// always computes it (`false`, the default). Call before the first step.
    pub fn bound_force_floor(&mut self, bound: bool) {
        self.work.floor_bound = bound;
    }

    /// The steps whose force floor was bounded ([`Self::bound_force_floor`]).
    pub fn bounded_force_floors(&self) -> u64 {
        self.work.floor_bounded
    }

    /// The floating-point floor of the contact forces in this step, into `work.force_floor`
    /// \[N\]: the largest over the wheels of
    ///
    /// ```text
    /// F_floor,k = κ ε (|v_k|ᵀ |A⁻¹| e + |δ|_k) / (1/k_c + s |v_kᵀ A⁻¹ ĝ_k|),
    /// e_i = |r_i| + |(A x)_i| + s |G_i|,   |δ|_k = |x_w| + Σ_j |q_j w_j(x_k)| + |r(x_k)|,
    /// ```
    ///
    /// with ε the machine epsilon and κ = 32: the step residual R = A x − r − s G cannot be
    /// computed more accurately than ε e (each entry is a sum of terms of size e_i), nor the
    /// approach than ε |δ|_k, and one (quasi-)Newton force update maps such an error through the
    /// same formula as a true residual (`linalg::contact_update`, one wheel). A force change
    /// below it is round-off: for a 2.8e5 N moving mass at Δt = 2e-5 s it is 2.9e-2 N,
    /// far above ε |F| because the step matrix A ~ m/(β Δt²) is large.
    ///
    /// With the bound on ([`Simulation::bound_force_floor`]) `|A⁻¹| e` at a multibody
    /// vehicle's wheels is first bounded by its diagonal term plus the off-diagonal sum of its
    /// row of `|A⁻¹|` times the largest `e` of the vehicle's block
    /// (`BlockDiagonal::solve_abs_bound_at`, O(m) per block instead of O(m) per wheel), which
    /// bounds every wheel's floor from above. The floor enters the iteration only through `max(tol, floor)` and the
    /// stagnation test `change ≤ 16 floor` (here and in the detached solve), neither of which
    /// differs from `change ≤ tol` while 16 floor < tol: when 16 (1 + 1e-12) times the largest
    /// bound is below `tol` (the factor for the round-off of both sides, ≤ m ε ≈ 3e-14
    /// relative for m ≤ 256), the bounds are kept and every
    /// decision of the iteration is the one the exact floor gives; otherwise the exact floor
    /// is computed. Only the reported `max_force_floor` differs (a bound, not the floor).
    fn force_floor(&mut self, s: f64, tol: f64) {
        if self.work.floor_bound {
            self.floor_residual(s);
            let w = &mut self.work;
            self.a_matrix
                .solve_abs_bound_at(&mut w.floor_residual, &self.wheel_dof);
            let bound = self.wheel_floors(s, true);
            if 16.0 * (1.0 + 1e-12) * bound < tol {
                self.work.floor_bounded += 1;
                return;
            }
        }
        self.floor_residual(s);
        let w = &mut self.work;
        self.a_matrix
            .solve_abs_at(&mut w.floor_residual, &self.wheel_dof);
        self.wheel_floors(s, false);
    }

    /// `e = |A x| + |r| + s |G|` (module `resting`: zero on the held rows) into
    /// `work.floor_residual` (see [`Self::force_floor`]); A x of the current iterate is in
    /// `work.floor_ax` (the caller formed it for the residual: one product instead of two,
    /// the same values).
    fn floor_residual(&mut self, s: f64) {
        let w = &mut self.work;
        let e = &mut w.floor_residual;
        e.copy_from_slice(&w.floor_ax);
        for range in &self.resting.live_rows {
            for (ei, ri) in e[range.clone()].iter_mut().zip(&w.r[range.clone()]) {
                *ei = ei.abs() + ri.abs();
            }
        }
        let live = &self.resting.live;
        Self::zero_held(&self.resting.held_dofs, e);
        for &k in live {
            for j in 0..w.span_modes[k] {
                e[j] += s * w.modal_load[k][j].abs();
            }
            e[self.wheel_dof[k]] += s * w.outputs[k].force.abs();
        }
    }

    /// The live wheels' floors from `|A⁻¹| e` in `work.floor_residual` (at their patterns)
    /// into `work.wheel_floor`, and `work.force_floor`; returns the largest over the live
    /// wheels (see [`Self::force_floor`]). With `bounding` (the bound of
    /// [`Self::force_floor`]) a compliant wheel's denominator is its compliance alone,
    /// which bounds it from below (s |vᵀA⁻¹ĝ| ≥ 0; with Hertz contact on the benchmark
    /// span it is below 1 % of the compliance), so each floor is bounded from above without
    /// the solve of A⁻¹ĝ; a rigid wheel (compliance 0) takes the quadratic form.
    fn wheel_floors(&mut self, s: f64, bounding: bool) -> f64 {
        let w = &mut self.work;
        let e = &w.floor_residual;
        let live = &self.resting.live;
        let mut largest = 0.0f64;
        for &k in live {
            let iw = self.wheel_dof[k];
            let shapes = &w.shape_at_wheel[k];
            let approach_scale = w.x[iw].abs()
                + (0..w.span_modes[k])
                    .map(|j| (w.x[j] * shapes[j]).abs())
                    .sum::<f64>()
                + w.r_at_wheel[k].abs();
            let pattern = &w.pattern[k];
            let propagated: f64 = pattern.iter().map(|&i| w.v[k][i].abs() * e[i]).sum();
            let compliance = if is_rigid(&self.contacts[k]) || w.outputs[k].stiffness <= 0.0 {
                0.0
            } else {
                1.0 / w.outputs[k].stiffness
            };
            let den = if bounding && compliance > 0.0 {
                compliance
            } else {
                let v_ainv_g =
                    w.cap
                        .quadratic_form(&self.a_matrix, k, &w.g_hat[k], &w.v[k], pattern);
                compliance + s * v_ainv_g.abs()
            };
            w.wheel_floor[k] = if den > 0.0 && den.is_finite() {
                32.0 * f64::EPSILON * (propagated + approach_scale) / den
            } else {
                0.0
            };
            largest = largest.max(w.wheel_floor[k]);
        }
        // A held wheel keeps the floor of its last step in the iteration (its state, and with
        // it its floor, is the same to round-off; module `resting`).
        w.force_floor = w.wheel_floor.iter().fold(0.0f64, |m, &f| m.max(f));
        largest
    }

    /// One step attempt of size `dt`; on success the state is advanced.
    pub(super) fn try_step(&mut self, dt: f64) -> Result<(), StepFailure> {
        let fatal = |e: VehicleBridgeError| StepFailure {
            iterations: 0,
            change: 0.0,
            reason: e.to_string(),
            fatal: Some(e),
        };
        // The geometry at the step's end first: it decides which vehicles are held, and the
        // vehicles at rest are frozen in the stepper before it forms the step equation.
        let t_new = self.stepper.t() + dt;
        self.wheel_geometry(t_new).map_err(fatal)?;
        // Every wheel's v is now fixed until the next attempt: the mode shapes under it and
        // its own DOF (`evaluate_contacts`, `extrapolated_start`), or the rigid constraint's
        // gradient of this attempt (`rigid_setup`).
        self.work.cap.new_geometry();
        self.select_live_wheels().map_err(fatal)?;
        self.stepper
            .step_equation_into(dt, &mut self.eq)
            .map_err(|e| fatal(e.into()))?;
        self.update_a().map_err(fatal)?;
        let s = 1.0 - self.eq.alpha_f;
        // The rows of the vehicles at rest are not used (frozen: zero rows of the load).
        let w = &mut self.work;
        for range in &self.resting.moving_rows {
            let rows = w.f_ext[range.clone()]
                .iter_mut()
                .zip(&self.structure.gravity_load[range.clone()])
                .zip(&self.contact_load[range.clone()]);
            for ((f, g), c) in rows {
                *f = g + self.eq.alpha_f * c;
            }
        }
        // The moving forces at t_{n+1} (their part at t_n is in `contact_load`).
        if !self.scenario.moving_forces.is_empty() {
            self.moving_force_load(self.eq.t_new).map_err(fatal)?;
            let w = &mut self.work;
            for (f, p) in w.f_ext.iter_mut().zip(&w.moving_load) {
                *f += s * p;
            }
        }
        self.eq
            .effective_load_sparse(
                self.structure.mass_sparse.as_ref(),
                Some(self.structure.damping_sparse.as_ref()),
                &self.work.f_ext,
                &mut self.work.r,
            )
            .map_err(|e| fatal(e.into()))?;
        let c_qa = self.eq.displacement_per_acceleration;
        let a = self.stepper.a();
        for range in &self.resting.moving_rows {
            let rows = self.work.x[range.clone()]
                .iter_mut()
                .zip(&self.eq.q_pred[range.clone()])
                .zip(&a[range.clone()]);
            for ((x, q), a) in rows {
                *x = q + c_qa * a;
            }
        }
        // A held vehicle takes the predictor with zero acceleration, q̃ = q (frozen in the
        // stepper: module `resting`).
        for &i in &self.resting.resting_dofs {
            self.work.x[i] = self.eq.q_pred[i];
        }
        self.rigid_setup().map_err(fatal)?;
        self.work.law.valid = false;
        // After a start of point contacts the state carries the forces φ (`prev_force`): the
        // first evaluation's change is then |F(δ) − φ|, the residual of the contact laws.
        let started = self.scenario.coupling.solver == CouplingSolver::QuasiNewton
            && self.extrapolated_start(s);
        let tol = self.scenario.coupling.tol * self.force_scale;
        let solver = self.scenario.coupling.solver;
        let mut change = f64::INFINITY;
        let mut converged = false;
        let mut iterations = 0;
        let mut contact_iterations = 0;
        let mut growth = 0;
        // The force changes of the two previous iterations (stagnation test).
        let mut history = [f64::INFINITY; 2];
        // A rigid multiplier was clipped at zero in the last update (the state then does not
        // match the forces, so another iteration is needed).
        let mut clamped = false;
        for it in 1..=self.scenario.coupling.max_iter {
            iterations = it;
            let tangent = match solver {
                CouplingSolver::Newton => true,
                CouplingSolver::QuasiNewton => it == 1,
                CouplingSolver::Picard => false,
            };
            if let Err(e) = self.evaluate_contacts(tangent) {
                return Err(StepFailure {
                    iterations,
                    change,
                    reason: e.to_string(),
                    fatal: None,
                });
            }
            self.rigid_constraints();
            if it == 1 {
                // The force floor at the first iterate (needed by the change test below), from
                // its A x, which is also the first residual's.
                let w = &mut self.work;
                self.a_matrix.mul(&w.x, &mut w.floor_ax);
                self.force_floor(s, tol);
            }
            let w = &mut self.work;
            let live = &self.resting.live;
            contact_iterations += live.iter().map(|&k| w.outputs[k].iterations).sum::<usize>();
            if it > 1 || started {
                let mut c = 0.0f64;
                for &k in live {
                    let d = if is_rigid(&self.contacts[k]) {
                        w.last_df[k].abs()
                    } else {
                        (w.outputs[k].force - w.prev_force[k]).abs()
                    };
                    c = c.max(d);
                }
                if c > change {
                    growth += 1;
                } else {
                    growth = 0;
                }
                change = c;
                if !change.is_finite() || (growth >= 4 && change > 10.0 * self.force_scale) {
                    return Err(StepFailure {
                        iterations,
                        change,
                        reason: "the iteration diverges".to_string(),
                        fatal: None,
                    });
                }
                // Converged at the tolerance, or at the floating-point floor of the forces:
                // below the floor the change is round-off (it stagnates instead of falling), so
                // a change within the floor, or one that stopped decreasing over two iterations
                // within 16× the floor, is convergence.
                let floor = w.force_floor;
                let stagnant = change <= 16.0 * floor && history[0].min(history[1]) <= change;
                if (change <= tol.max(floor) || stagnant) && !clamped {
                    converged = true;
                    break;
                }
                history = [history[1], change];
            }
            // The laws' residual against the forces the iterate was solved with (opt-in,
            // module `law_residual`; the floor is this step's from the second iteration on).
            if !clamped && let Some(rho) = self.law_residual() {
                let w = &mut self.work;
                let limit = if it == 1 { tol } else { tol.max(w.force_floor) };
                if rho <= limit {
                    w.law.accepted += 1;
                    change = rho;
                    converged = true;
                    break;
                }
            }
            let w = &mut self.work;
            let live = &self.resting.live;
            for &k in live {
                w.prev_force[k] = w.outputs[k].force;
            }
            // Residual R = A x − r − s Σ G_k, written as −R into `res` (on the rows outside
            // the held vehicles; theirs are zero).
            if it == 1 {
                // A x of this iterate is the force floor's (above).
                w.res.copy_from_slice(&w.floor_ax);
            } else {
                self.a_matrix.mul(&w.x, &mut w.res);
            }
            residual_rows(&self.resting.live_rows, &w.r, &mut w.res);
            for &k in live {
                for j in 0..w.span_modes[k] {
                    w.res[j] += s * w.modal_load[k][j];
                }
                w.res[self.wheel_dof[k]] -= s * w.outputs[k].force;
            }
            Self::zero_held(&self.resting.held_dofs, &mut w.res);
            let live = &self.resting.live;
            let solved = match solver {
                CouplingSolver::Picard => {
                    self.a_matrix.solve_in_place(&mut w.res);
                    Ok(())
                }
                CouplingSolver::QuasiNewton | CouplingSolver::Newton => {
                    w.active.clear();
                    for &k in live {
                        let rigid = is_rigid(&self.contacts[k]);
                        let active = if rigid {
                            self.in_contact[k] && !self.rigid.released[k]
                        } else {
                            w.outputs[k].stiffness > 0.0
                        };
                        w.last_df[k] = 0.0;
                        if active {
                            let a = w.active.len();
                            w.compliance[a] = if rigid {
                                0.0
                            } else {
                                1.0 / w.outputs[k].stiffness
                            };
                            w.delta_tilde[a] = if rigid { self.rigid.residual[k] } else { 0.0 };
                            w.active.push(k);
                        }
                    }
                    let ka = w.active.len();
                    let solved = if solver == CouplingSolver::QuasiNewton {
                        contact_update(
                            &self.a_matrix,
                            s,
                            &w.g_hat,
                            &w.v,
                            &w.pattern,
                            &w.active,
                            &w.compliance[..ka],
                            &w.delta_tilde[..ka],
                            &mut w.res,
                            &mut w.df,
                            &mut w.cap,
                        )
                    } else {
                        dense_contact_update(
                            &self.a_matrix,
                            s,
                            &w.g_hat,
                            &w.v,
                            &w.active,
                            &w.compliance[..ka],
                            &w.delta_tilde[..ka],
                            &mut w.res,
                            &mut w.df,
                            &mut w.dense,
                        )
                    };
                    clamped = false;
                    for (a, &k) in w.active.iter().enumerate() {
                        if is_rigid(&self.contacts[k]) {
                            // A multiplier that would pull releases the wheel for the step
                            // (module `rigid`): it flies freely, F = 0.
                            let release = self.forces[k] + w.df[a] < 0.0;
                            clamped |= release;
                            self.rigid.released[k] |= release;
                            let f_new = if release {
                                0.0
                            } else {
                                self.forces[k] + w.df[a]
                            };
                            w.last_df[k] = f_new - self.forces[k];
                            self.forces[k] = f_new;
                        }
                    }
                    solved
                }
            };
            if let Err(singular) = solved {
                return Err(StepFailure {
                    iterations,
                    change,
                    reason: format!("{singular} in the coupled step"),
                    fatal: None,
                });
            }
            if solver != CouplingSolver::Picard {
                self.record_linearised(false);
            }
            let w = &mut self.work;
            let live = &self.resting.live;
            // The held rows of the update are zero (they keep their state).
            let rows = &self.resting.live_rows;
            add_rows(rows, &w.res, &mut w.x);
            if rows
                .iter()
                .any(|r| w.x[r.clone()].iter().any(|v| !v.is_finite()))
            {
                return Err(StepFailure {
                    iterations,
                    change,
                    reason: "non-finite state".to_string(),
                    fatal: None,
                });
            }
            // (Quasi-)Newton: when every wheel is in contact and the predicted force
            // corrections are within the tolerance, accept the corrected state with the
            // linearised forces F + ΔF (error O(ΔF²)) without another contact evaluation.
            if solver != CouplingSolver::Picard && w.active.len() == live.len() && !clamped {
                let predicted = w.df[..live.len()]
                    .iter()
                    .fold(0.0f64, |m, d| m.max(d.abs()));
                let all_positive = w
                    .active
                    .iter()
                    .enumerate()
                    .all(|(a, &k)| w.outputs[k].force + w.df[a] > 0.0);
                if predicted <= tol.max(w.force_floor) && all_positive {
                    for (a, &k) in w.active.iter().enumerate() {
                        let f_old = w.outputs[k].force;
                        let f_new = if is_rigid(&self.contacts[k]) {
                            self.forces[k]
                        } else {
                            f_old + w.df[a]
                        };
                        if f_old > 0.0 {
                            let scale = f_new / f_old;
                            w.modal_load[k].iter_mut().for_each(|l| *l *= scale);
                        } else {
                            for (l, sh) in w.modal_load[k].iter_mut().zip(&w.shape_at_wheel[k]) {
                                *l = f_new * sh;
                            }
                        }
                        w.outputs[k].force = f_new;
                        w.delta[k] = w.approach(k, self.wheel_dof[k], &w.x);
                    }
                    change = predicted;
                    converged = true;
                    break;
                }
            }
        }
        if !converged {
            return Err(StepFailure {
                iterations,
                change,
                reason: format!(
                    "no convergence in {} iterations to the target force change {:e} N (coupling.tol = {:e} × the largest static wheel load {:e} N; floating-point floor of the forces {:e} N)",
                    self.scenario.coupling.max_iter,
                    tol,
                    self.scenario.coupling.tol,
                    self.force_scale,
                    self.work.force_floor,
                ),
                fatal: None,
            });
        }
        // The vehicles off the span, each on its own (module `detached`).
        contact_iterations += self.solve_detached(s, tol)?;
        self.accept(
            StateUpdate::Finish { dt },
            Accepted {
                steps: 1,
                iterations,
                contact_iterations,
                rejected: 0,
            },
        )
        .map_err(fatal)
    }
}

/// `res ← r − res` on the rows `rows` (−R from `res` = A x).
fn residual_rows(rows: &[Range<usize>], r: &[f64], res: &mut [f64]) {
    for range in rows {
        for (y, ri) in res[range.clone()].iter_mut().zip(&r[range.clone()]) {
            *y = ri - *y;
        }
    }
}

/// `x ← x + d` on the rows `rows`.
fn add_rows(rows: &[Range<usize>], d: &[f64], x: &mut [f64]) {
    for range in rows {
        for (xi, di) in x[range.clone()].iter_mut().zip(&d[range.clone()]) {
            *xi += di;
        }
    }
}
