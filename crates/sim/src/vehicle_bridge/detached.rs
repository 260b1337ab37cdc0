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
//! wheel of the train has, so the two agree to the coupling tolerance or the forces'
//! floating-point floor (the test
//! `train_resting_vehicles::detached_vehicles_equal_the_coupled_step`).
//!
//! The iteration runs on the four wheels only. After any update the state is the block's
//! solution under the forces φ of that update, `x = x₀ − P φ` with `x₀ = B⁻¹ r` and
//! `P = s B⁻¹ Eᵀ`, so the wheels' displacements are `z = z₀ − S φ` (`S = E P`, the
//! capacitance matrix without the compliances) and the update above becomes
//!
//! ```text
//! (K_c⁻¹ + S) ΔF = z₀ − z − S F,   φ = F + ΔF,   z ← z₀ − S φ
//! ```
//!
//! (`E B⁻¹(−R) = z₀ − z − S F`): one 10 × 10 product per step for x₀, a 4 × 4 solve per
//! update, and `x` formed once at the end.
//!
//! It applies to bogie vehicles ([`MAX_DOFS`] DOFs, [`MAX_WHEELS`] wheels: fixed-size kernels)
//! with compliant contacts (Hertz, or BEM, whose column forces load no mode off the span),
//! under the conditions of module `resting`.

use halfspace::law::{ContactModel as LawModel, LawOutput};

use super::contact::{is_point, wheel_error};
use super::linalg::small_solve_in_place;
use super::step::StepFailure;
use super::vehicles::VehicleDofs;
use super::{Simulation, Work};

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

/// The vehicle's own DOFs (body and bogies); its wheels' DOFs follow them.
const OWN: usize = MAX_DOFS - MAX_WHEELS;

/// `M x` for the rows `m`, or `|M| x` if `abs` (fixed size: the compiler unrolls it).
#[inline]
fn apply(m: &[[f64; MAX_DOFS]], x: &[f64; MAX_DOFS], abs: bool) -> [f64; MAX_DOFS] {
    std::array::from_fn(|l| row_times(&m[l], x, abs))
}

/// `m_l · x`, or `|m_l| · x` if `abs`.
#[inline]
fn row_times(row: &[f64; MAX_DOFS], x: &[f64; MAX_DOFS], abs: bool) -> f64 {
    if abs {
        row.iter().zip(x).map(|(a, x)| a.abs() * x).sum()
    } else {
        row.iter().zip(x).map(|(a, x)| a * x).sum()
    }
}

/// A detached vehicle's step reduced to its wheels (module documentation): `x₀ = B⁻¹ r`,
/// `P = s B⁻¹ Eᵀ` and `S = E P`, so that `x = x₀ − P φ` and `z = z₀ − S φ` for contact forces φ.
struct Reduced {
    /// `x₀ = B⁻¹ r`, the step's solution without contact forces.
    x0: [f64; MAX_DOFS],
    /// `P = s B⁻¹ Eᵀ`: row `l` holds DOF `l`'s response to each wheel's force.
    p: [[f64; MAX_WHEELS]; MAX_DOFS],
    /// `S = s E B⁻¹ Eᵀ`, the wheels' rows of P.
    s: [[f64; MAX_WHEELS]; MAX_WHEELS],
    /// `z₀ = E x₀`.
    z0: [f64; MAX_WHEELS],
}

impl Reduced {
    /// The reduction for the block's inverse `inverse`, the step load `r` and the weight `s`.
    fn new(inverse: &[[f64; MAX_DOFS]], r: &[f64; MAX_DOFS], s: f64) -> Self {
        let x0 = apply(inverse, r, false);
        let p: [[f64; MAX_WHEELS]; MAX_DOFS] =
            std::array::from_fn(|l| std::array::from_fn(|c| s * inverse[l][OWN + c]));
        let s: [[f64; MAX_WHEELS]; MAX_WHEELS] = std::array::from_fn(|c| p[OWN + c]);
        let z0 = std::array::from_fn(|c| x0[OWN + c]);
        Self { x0, p, s, z0 }
    }

    /// The wheel displacements under the forces `phi`, `z = z₀ − S φ`.
    #[inline]
    fn wheels(&self, phi: &[f64; MAX_WHEELS]) -> [f64; MAX_WHEELS] {
        std::array::from_fn(|c| self.z0[c] - dot(&self.s[c], phi))
    }

    /// The whole state under the forces `phi`, `x = x₀ − P φ`.
    fn state(&self, phi: &[f64; MAX_WHEELS]) -> [f64; MAX_DOFS] {
        std::array::from_fn(|l| self.x0[l] - dot(&self.p[l], phi))
    }

    /// Solves `(diag(compliance) + S) d = rhs` on the wheels `active` (the others get
    /// `d = 0`: a wheel out of contact has no tangent); `None` if singular or not finite.
    fn solve(
        &self,
        compliance: &[f64; MAX_WHEELS],
        active: &[bool; MAX_WHEELS],
        rhs: &[f64; MAX_WHEELS],
    ) -> Option<[f64; MAX_WHEELS]> {
        if active.iter().all(|&a| a)
            && let Some(d) = ldlt_solve(&self.s, compliance, rhs)
        {
            return Some(d);
        }
        let mut index = [0; MAX_WHEELS];
        let mut na = 0;
        for c in (0..MAX_WHEELS).filter(|&c| active[c]) {
            index[na] = c;
            na += 1;
        }
        let mut cap = [0.0; MAX_WHEELS * MAX_WHEELS];
        let mut d = [0.0; MAX_WHEELS];
        for (a, &ca) in index[..na].iter().enumerate() {
            for (b, &cb) in index[..na].iter().enumerate() {
                cap[a * na + b] = self.s[ca][cb];
            }
            cap[a * na + a] += compliance[ca];
            d[a] = rhs[ca];
        }
        if na > 0 && !small_solve_in_place(&mut cap[..na * na], &mut d[..na]) {
            return None;
        }
        let mut out = [0.0; MAX_WHEELS];
        for (a, &c) in index[..na].iter().enumerate() {
            out[c] = d[a];
        }
        out.iter().all(|v| v.is_finite()).then_some(out)
    }
}

/// Solves `(diag(c) + S) d = rhs` by `L D Lᵀ` without pivoting, from the lower triangle:
/// the capacitance matrix of compliant contacts is symmetric positive definite (S = s E B⁻¹ Eᵀ
/// with B = c_M M + c_C C + c_K K symmetric positive definite, c > 0). `None` if a pivot is not
/// positive and finite (the caller then takes the pivoted solve).
fn ldlt_solve(
    s: &[[f64; MAX_WHEELS]; MAX_WHEELS],
    c: &[f64; MAX_WHEELS],
    rhs: &[f64; MAX_WHEELS],
) -> Option<[f64; MAX_WHEELS]> {
    // L below the diagonal, D on it.
    let mut f = [[0.0; MAX_WHEELS]; MAX_WHEELS];
    for i in 0..MAX_WHEELS {
        for j in 0..i {
            let mut v = s[i][j];
            for k in 0..j {
                v -= f[i][k] * f[j][k] * f[k][k];
            }
            f[i][j] = v / f[j][j];
        }
        let mut d = s[i][i] + c[i];
        for k in 0..i {
            d -= f[i][k] * f[i][k] * f[k][k];
        }
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        f[i][i] = d;
    }
    let mut y = *rhs;
    for i in 0..MAX_WHEELS {
        for k in 0..i {
            y[i] -= f[i][k] * y[k];
        }
    }
    for (i, yi) in y.iter_mut().enumerate() {
        *yi /= f[i][i];
    }
    for i in (0..MAX_WHEELS).rev() {
        for k in i + 1..MAX_WHEELS {
            y[i] -= f[k][i] * y[k];
        }
    }
    y.iter().all(|v| v.is_finite()).then_some(y)
}

/// `a · b` over the wheels.
#[inline]
fn dot(a: &[f64; MAX_WHEELS], b: &[f64; MAX_WHEELS]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
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

/// The contact law of wheel `k` (a point contact) at the approach `delta`, with the rail
/// height `rk` under it, into `w.outputs[k]` and `w.delta[k]` (the tangent if `tangent`): the
/// one place where the detached solve (and the extrapolated start of the coupled step, for a
/// point contact) evaluates a contact.
pub(super) fn evaluate_wheel(
    contacts: &mut [LawModel],
    w: &mut Work,
    k: usize,
    delta: f64,
    rk: f64,
    tangent: bool,
) -> Result<LawOutput, String> {
    w.delta[k] = delta;
    for (gap, rc) in w.column_gap[k].iter_mut().zip(&w.r_at_columns[k]) {
        *gap = -(rc - rk);
    }
    let LawModel::Law(law) = &mut contacts[k] else {
        return Err("not a compliant contact".to_string());
    };
    let out = law
        .evaluate(delta, &w.column_gap[k], &mut w.column_force[k], tangent)
        .map_err(|e| wheel_error(k)(e).to_string())?;
    w.outputs[k] = out;
    Ok(out)
}

/// The floating-point floor (`Simulation::force_floor`) of a detached vehicle's forces at its
/// state `x` (wheels from `k0`, forces `forces`, block `entries` and `inverse`, step load `r`)
/// into `w.wheel_floor` and `w.force_floor`; returns the new `w.force_floor`.
#[allow(clippy::too_many_arguments)]
fn detached_floor(
    w: &mut Work,
    k0: usize,
    entries: &[[f64; MAX_DOFS]],
    inverse: &[[f64; MAX_DOFS]],
    x: &[f64; MAX_DOFS],
    r: &[f64; MAX_DOFS],
    rk: &[f64; MAX_WHEELS],
    forces: &[f64; MAX_WHEELS],
    s: f64,
) -> f64 {
    let mut e = apply(entries, x, false);
    for (ei, rl) in e.iter_mut().zip(r) {
        *ei = ei.abs() + rl.abs();
    }
    for c in 0..MAX_WHEELS {
        e[OWN + c] += s * forces[c].abs();
    }
    let mut floor = w.force_floor;
    for c in 0..MAX_WHEELS {
        let (k, l) = (k0 + c, OWN + c);
        let stiffness = w.outputs[k].stiffness;
        let compliance = if stiffness > 0.0 {
            1.0 / stiffness
        } else {
            0.0
        };
        let den = compliance + s * inverse[l][l].abs();
        let propagated = row_times(&inverse[l], &e, true);
        w.wheel_floor[k] = if den > 0.0 && den.is_finite() {
            32.0 * f64::EPSILON * (propagated + x[l].abs() + rk[c].abs()) / den
        } else {
            0.0
        };
        floor = floor.max(w.wheel_floor[k]);
    }
    w.force_floor = floor;
    floor
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

    /// The quasi-Newton step of detached vehicle `v` (its block of A is the v-th dense block),
    /// on its wheels (`Reduced`, module documentation).
    fn solve_detached_vehicle(&mut self, v: usize, s: f64, tol: f64) -> Result<usize, StepFailure> {
        let k0 = self.vehicles[v].first_wheel;
        let Some((indices, entries, inverse)) = self.a_matrix.dense_block(v) else {
            return Err(failure(0, 0.0, "no step-matrix block".to_string()));
        };
        let (entries, inverse) = (entries.as_chunks().0, inverse.as_chunks().0);
        if indices.len() != MAX_DOFS || entries.len() != MAX_DOFS || inverse.len() != MAX_DOFS {
            return Err(failure(0, 0.0, "not a bogie vehicle's block".to_string()));
        }
        let w = &self.work;
        let x_pred: [f64; MAX_DOFS] = std::array::from_fn(|l| w.x[indices[l]]);
        let r: [f64; MAX_DOFS] = std::array::from_fn(|l| w.r[indices[l]]);
        let rk: [f64; MAX_WHEELS] = std::array::from_fn(|c| w.r_at_wheel[k0 + c]);
        let red = Reduced::new(inverse, &r, s);
        // The wheels' displacements and the forces φ with z = z₀ − S φ (None: the predictor).
        let mut z: [f64; MAX_WHEELS] = std::array::from_fn(|c| x_pred[OWN + c]);
        let mut phi: Option<[f64; MAX_WHEELS]> = None;
        let mut contact_iterations = 0;
        // Extrapolated start (as `Simulation::extrapolated_start`, on this vehicle): the
        // linearised laws F = F_n + k_n (z + r − δ_n) with z = z₀ − S F, i.e.
        // (K_n⁻¹ + S) F = K_n⁻¹ F_n + z₀ + r − δ_n; for point contacts (F_n, k_n, δ_n) are
        // the law at the predicted approach instead of at the end of the previous step.
        let wheels = k0..k0 + MAX_WHEELS;
        let point = wheels.clone().all(|k| is_point(&self.contacts[k]));
        let usable = wheels.clone().all(|k| {
            w.outputs[k].force > 0.0
                && w.outputs[k].stiffness > 0.0
                && w.column_force[k].iter().sum::<f64>() > 0.0
        });
        if usable {
            let mut compliance = [0.0; MAX_WHEELS];
            let mut rhs = [0.0; MAX_WHEELS];
            let mut positive = true;
            for c in 0..MAX_WHEELS {
                let k = k0 + c;
                // A point contact's law linearised at the predicted approach δ̃ = z̃ + r, as
                // in `Simulation::extrapolated_start`: F ≈ F(δ̃) + k(δ̃)(δ − δ̃).
                let (f_n, k_n, delta_n) = if point {
                    let delta = self.work.start_point(k, z[c] + rk[c], self.stats.steps);
                    let Ok(out) =
                        evaluate_wheel(&mut self.contacts, &mut self.work, k, delta, rk[c], true)
                    else {
                        // The iteration's first evaluation reports the error.
                        positive = false;
                        break;
                    };
                    contact_iterations += out.iterations;
                    (out.force, out.stiffness, delta)
                } else {
                    let w = &self.work;
                    (w.outputs[k].force, w.outputs[k].stiffness, w.delta[k])
                };
                positive &= f_n + k_n * (z[c] + rk[c] - delta_n) > 0.0 && k_n > 0.0;
                compliance[c] = 1.0 / k_n;
                rhs[c] = compliance[c] * f_n + red.z0[c] + rk[c] - delta_n;
            }
            if positive && let Some(f) = red.solve(&compliance, &[true; MAX_WHEELS], &rhs) {
                z = red.wheels(&f);
                phi = Some(f);
            }
        }
        let mut change = f64::INFINITY;
        let mut history = [f64::INFINITY; 2];
        let mut growth = 0;
        let mut floor = self.work.force_floor;
        // After a start of point contacts the state carries the forces φ: the first
        // evaluation's change is |F(δ) − φ|, the residual of the contact laws.
        let started = point && phi.is_some();
        let mut prev = phi.unwrap_or([0.0; MAX_WHEELS]);
        for it in 1..=self.scenario.coupling.max_iter {
            // The contact laws at the iterate (the tangent at the first evaluation).
            let mut forces = [0.0; MAX_WHEELS];
            let mut compliance = [0.0; MAX_WHEELS];
            let mut active = [false; MAX_WHEELS];
            for c in 0..MAX_WHEELS {
                let delta = z[c] + rk[c];
                let out = evaluate_wheel(
                    &mut self.contacts,
                    &mut self.work,
                    k0 + c,
                    delta,
                    rk[c],
                    it == 1,
                )
                .map_err(|reason| failure(it, change, reason))?;
                contact_iterations += out.iterations;
                forces[c] = out.force;
                active[c] = out.stiffness > 0.0;
                compliance[c] = if active[c] { 1.0 / out.stiffness } else { 0.0 };
            }
            if it == 1 {
                let x = phi.as_ref().map_or(x_pred, |phi| red.state(phi));
                floor = detached_floor(
                    &mut self.work,
                    k0,
                    entries,
                    inverse,
                    &x,
                    &r,
                    &rk,
                    &forces,
                    s,
                );
            }
            if let Some(phi) = &phi
                && (it > 1 || started)
            {
                let c = (0..MAX_WHEELS).fold(0.0f64, |m, c| m.max((forces[c] - prev[c]).abs()));
                growth = if c > change { growth + 1 } else { 0 };
                change = c;
                if !change.is_finite() || (growth >= 4 && change > 10.0 * self.force_scale) {
                    return Err(failure(it, change, "the iteration diverges".to_string()));
                }
                let stagnant = change <= 16.0 * floor && history[0].min(history[1]) <= change;
                if change <= tol.max(floor) || stagnant {
                    return Ok(self.finish_detached(v, &red.state(phi), contact_iterations));
                }
                history = [history[1], change];
            }
            prev = forces;
            // The Woodbury update in the wheels: (K_c⁻¹ + S) ΔF = E B⁻¹(−R) = z₀ − z − S F.
            let rhs: [f64; MAX_WHEELS] =
                std::array::from_fn(|c| red.z0[c] - z[c] - dot(&red.s[c], &forces));
            let Some(df) = red.solve(&compliance, &active, &rhs) else {
                return Err(failure(
                    it,
                    change,
                    "singular or non-finite capacitance matrix in the detached step".to_string(),
                ));
            };
            let next: [f64; MAX_WHEELS] = std::array::from_fn(|c| forces[c] + df[c]);
            z = red.wheels(&next);
            phi = Some(next);
            if z.iter().any(|v| !v.is_finite()) {
                return Err(failure(it, change, "non-finite state".to_string()));
            }
            // Every wheel in contact and the predicted corrections within the tolerance: the
            // corrected state with the linearised forces.
            let predicted = df.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            if active.iter().all(|&a| a)
                && predicted <= tol.max(floor)
                && next.iter().all(|&f| f > 0.0)
            {
                let w = &mut self.work;
                for c in 0..MAX_WHEELS {
                    w.outputs[k0 + c].force = next[c];
                    w.delta[k0 + c] = z[c] + rk[c];
                }
                return Ok(self.finish_detached(v, &red.state(&next), contact_iterations));
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

    /// Writes the converged state of detached vehicle `v` into the step's state; returns
    /// `contact_iterations`.
    fn finish_detached(
        &mut self,
        v: usize,
        x: &[f64; MAX_DOFS],
        contact_iterations: usize,
    ) -> usize {
        for (l, &i) in self.vehicles[v].dofs.iter().enumerate() {
            self.work.x[i] = x[l];
        }
        contact_iterations
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `L D Lᵀ` solve of a capacitance matrix equals the pivoted elimination
    /// (`small_solve_in_place`, the general path) to round-off, and refuses an indefinite one.
    #[test]
    fn ldlt_solve_equals_the_pivoted_solve() {
        // S = G Gᵀ (symmetric positive semi-definite) with entries of very different size, as
        // s E B⁻¹ Eᵀ of a vehicle (1e-12 m/N), and Hertz compliances (1e-9 m/N).
        let g = [
            [1.0, 0.2, -0.3, 0.1],
            [0.4, 2.0, 0.1, -0.2],
            [-0.1, 0.3, 0.7, 0.05],
            [0.2, -0.4, 0.6, 1.5],
        ];
        let s: [[f64; 4]; 4] = std::array::from_fn(|i| {
            std::array::from_fn(|j| 1e-12 * (0..4).map(|k| g[i][k] * g[j][k]).sum::<f64>())
        });
        let c = [6.1e-10, 7.3e-10, 5.2e-10, 6.6e-10];
        let rhs = [1e-4, -2e-5, 3.3e-5, 7e-6];
        let d = ldlt_solve(&s, &c, &rhs).unwrap();
        let mut a: Vec<f64> = (0..16)
            .map(|e| s[e / 4][e % 4] + if e / 4 == e % 4 { c[e / 4] } else { 0.0 })
            .collect();
        let mut b = rhs.to_vec();
        assert!(small_solve_in_place(&mut a, &mut b));
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (x, y) in d.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-13 * scale, "{x:e} vs {y:e}");
        }
        // A negative compliance makes it indefinite: no L D Lᵀ without pivoting.
        assert!(ldlt_solve(&s, &[-1.0, 1e-9, 1e-9, 1e-9], &rhs).is_none());
    }
}
