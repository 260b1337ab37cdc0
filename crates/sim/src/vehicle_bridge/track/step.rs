//! One step of the track-coupled system (module documentation of [`super`], "Time step"), the
//! contact forces by Newton's method on the capacitance system, and the samples.

use halfspace::law::{ContactModel as LawModel, LawOutput};
use integrate::DenseLu;
use integrate::structural::sparse::sparse_mul_add;

use super::super::contact::wheel_error;
use super::super::{Simulation, VehicleBridgeError, WheelSample};
use super::TrackLayer;
use super::moving::add_moving_loads;

/// Newton's method on `F_k = F_law,k(δ₀_k − (S F)_k)` (S: the k × k capacitance matrix,
/// row-major): the Jacobian of `G(F) = F − F_law(δ₀ − S F)` is `I + diag(k_c) S`. Each
/// iteration is damped (halved up to 30 times) until max |G| decreases. Returns the iterations;
/// `forces` holds the start on entry and the solution on exit, `outputs` the law outputs at it.
/// `work` holds the iteration's vectors, sized for the k wheels by [`NewtonWork::resize`].
#[allow(clippy::too_many_arguments)]
fn contact_forces(
    contacts: &mut [LawModel],
    delta0: &[f64],
    cap: &[f64],
    forces: &mut [f64],
    outputs: &mut [LawOutput],
    tol: f64,
    max_iter: usize,
    work: &mut NewtonWork,
) -> Result<(usize, f64), VehicleBridgeError> {
    let k = delta0.len();
    let NewtonWork {
        g,
        step,
        trial,
        g_trial,
        out_trial,
        lu,
        law_iterations,
        ..
    } = work;
    *law_iterations = 0;
    let mut cf = [0.0];
    let mut eval =
        |f: &[f64], g: &mut [f64], out: &mut [LawOutput]| -> Result<f64, VehicleBridgeError> {
            let mut worst = 0.0f64;
            for c in 0..k {
                let delta = delta0[c] - (0..k).map(|j| cap[c * k + j] * f[j]).sum::<f64>();
                let LawModel::Law(law) = &mut contacts[c] else {
                    unreachable!("the track couples compliant laws only (checked at set-up)")
                };
                out[c] = law
                    .evaluate(delta, &[0.0], &mut cf, true)
                    .map_err(wheel_error(c))?;
                *law_iterations += out[c].iterations;
                g[c] = f[c] - out[c].force;
                worst = worst.max(g[c].abs());
            }
            Ok(worst)
        };
    let mut residual = eval(forces, g, outputs)?;
    let mut change = f64::INFINITY;
    for it in 1..=max_iter {
        // (I + diag(k_c) S) ΔF = −G (one contact: a division).
        if k == 1 {
            step[0] = -g[0] / (1.0 + outputs[0].stiffness * cap[0]);
        } else {
            {
                let mut m = lu.matrix_mut();
                for r in 0..k {
                    for c in 0..k {
                        let id = if r == c { 1.0 } else { 0.0 };
                        m[(r, c)] = id + outputs[r].stiffness * cap[r * k + c];
                    }
                }
            }
            if !lu.factor() {
                return Err(failure(it, change, "singular capacitance Jacobian"));
            }
            for c in 0..k {
                step[c] = -g[c];
            }
            lu.solve_in_place(step);
        }
        let mut scale = 1.0;
        let mut accepted = false;
        for _ in 0..30 {
            for c in 0..k {
                trial[c] = (forces[c] + scale * step[c]).max(0.0);
            }
            let r_trial = eval(trial, g_trial, out_trial)?;
            if r_trial < residual || r_trial <= tol {
                change = (0..k)
                    .map(|c| (trial[c] - forces[c]).abs())
                    .fold(0.0, f64::max);
                forces.copy_from_slice(trial);
                g.copy_from_slice(g_trial);
                outputs.copy_from_slice(out_trial);
                residual = r_trial;
                accepted = true;
                break;
            }
            scale *= 0.5;
        }
        if residual <= tol || (accepted && change <= tol) {
            return Ok((it, change));
        }
        if !accepted {
            // No decrease in 30 halvings: at the floating-point floor of G.
            return if residual <= 1e3 * tol {
                Ok((it, change))
            } else {
                Err(failure(it, change, "no decrease of the residual"))
            };
        }
    }
    Err(failure(
        max_iter,
        change,
        &format!("no convergence in {max_iter} iterations (residual {residual:e} N)"),
    ))
}

/// The vectors of a step's contact solve, sized for the wheels once (module [`super`]).
#[derive(Debug)]
pub(super) struct NewtonWork {
    g: Vec<f64>,
    step: Vec<f64>,
    trial: Vec<f64>,
    g_trial: Vec<f64>,
    out_trial: Vec<LawOutput>,
    /// The LU storage of the k × k capacitance Jacobian.
    lu: DenseLu<f64>,
    /// Predicted approaches δ₀, the capacitance matrix S (row-major) and the forces.
    delta0: Vec<f64>,
    cap: Vec<f64>,
    forces: Vec<f64>,
    /// The contact solver's iterations over the law evaluations of the last solve (the
    /// profile law's half-space solves; 0 for the closed-form Hertz law).
    law_iterations: usize,
}

impl NewtonWork {
    /// Work space for `k` wheels.
    pub(super) fn new(k: usize) -> Self {
        Self {
            g: vec![0.0; k],
            step: vec![0.0; k],
            trial: vec![0.0; k],
            g_trial: vec![0.0; k],
            out_trial: vec![LawOutput::default(); k],
            lu: DenseLu::new(k),
            delta0: vec![0.0; k],
            cap: vec![0.0; k * k],
            forces: vec![0.0; k],
            law_iterations: 0,
        }
    }

    /// Sizes the iteration vectors for `k` wheels (allocates only if k changed).
    fn resize(&mut self, k: usize) {
        // The step takes δ₀, S and F out while it uses them: a failed step leaves them empty.
        if self.g.len() != k
            || self.delta0.len() != k
            || self.cap.len() != k * k
            || self.forces.len() != k
        {
            *self = Self::new(k);
        }
    }
}

fn failure(iterations: usize, change: f64, reason: &str) -> VehicleBridgeError {
    VehicleBridgeError::CouplingFailed {
        solver: "track_capacitance_newton",
        t: f64::NAN,
        dt: f64::NAN,
        halvings: 0,
        iterations,
        change,
        reason: reason.to_string(),
    }
}

impl Simulation {
    /// One step of Δt of the track-coupled system (module documentation of [`super`]).
    pub(in super::super) fn track_step(&mut self, dt: f64) -> Result<(), VehicleBridgeError> {
        let mut layer = self.track.take().expect("called with a track");
        let result = self.track_advance(&mut layer, dt, 0);
        self.track = Some(layer);
        result?;
        self.track_samples()
    }

    /// Advances by `dt`, retrying an attempt whose contact solve failed as two half steps up
    /// to `coupling.max_halvings` times (as without the track, module `step`). A failed
    /// attempt leaves the state of the step before it: the track's state is written only
    /// after the contact solve.
    fn track_advance(
        &mut self,
        l: &mut TrackLayer,
        dt: f64,
        depth: usize,
    ) -> Result<(), VehicleBridgeError> {
        l.use_step_size(dt)?;
        match self.track_step_with(l, dt) {
            Err(VehicleBridgeError::CouplingFailed {
                solver,
                t,
                iterations,
                change,
                reason,
                ..
            }) => {
                self.stats.failed_steps += 1;
                if depth >= self.scenario.coupling.max_halvings {
                    return Err(VehicleBridgeError::CouplingFailed {
                        solver,
                        t,
                        dt,
                        halvings: depth,
                        iterations,
                        change,
                        reason,
                    });
                }
                self.track_advance(l, 0.5 * dt, depth + 1)?;
                self.track_advance(l, 0.5 * dt, depth + 1)
            }
            other => other,
        }
    }

    fn track_step_with(&mut self, l: &mut TrackLayer, dt: f64) -> Result<(), VehicleBridgeError> {
        debug_assert_eq!(dt, l.dt, "the factor of this dt is in place");
        let p = l.params;
        let (beta, gamma, am, af) = (p.beta, p.gamma, p.alpha_m, p.alpha_f);
        let s = 1.0 - af;
        let c_qa = beta * dt * dt;
        let c_va = gamma * dt;
        let (cm, cc) = ((1.0 - am) / c_qa, s * c_va / c_qa);
        let n = l.q.len();
        // Predictors q̃, ṽ and the vectors multiplied by M (c_M q̃ − α_m a) and by C
        // (c_C q̃ − s ṽ − α_f v), in one pass.
        {
            let (q, v, a) = (&l.q[..n], &l.v[..n], &l.a[..n]);
            let (qp, vp) = (&mut l.q_pred[..n], &mut l.v_pred[..n]);
            let (tm, tc) = (&mut l.tmp[..n], &mut l.tmp_c[..n]);
            let (c_a, c_v) = (dt * dt * (0.5 - beta), (1.0 - gamma) * dt);
            for i in 0..n {
                let q_pred = q[i] + dt * v[i] + c_a * a[i];
                let v_pred = v[i] + c_v * a[i];
                qp[i] = q_pred;
                vp[i] = v_pred;
                tm[i] = cm * q_pred - am * a[i];
                tc[i] = cc * q_pred - s * v_pred - af * v[i];
            }
        }
        // r = f − h + M(c_M q̃) + C(c_C q̃ − s ṽ), f = gravity + α_f × the old contact load,
        // h = α_m M a + α_f (C v + K q).
        l.r.copy_from_slice(&l.gravity);
        let nw = self.scenario.wheels.len();
        if let Some(patch) = &l.patch {
            patch.add_old_load(af, &mut l.r);
        } else {
            for k in 0..nw {
                let f_old = af * l.forces[k];
                if f_old != 0.0 {
                    let pt = &l.points[k];
                    for a in 0..4 {
                        l.r[pt.dofs[a]] += f_old * pt.weights[a];
                    }
                    l.r[l.offset + self.wheel_dof[k]] -= f_old;
                }
            }
        }
        let t_new = self.t() + dt;
        add_moving_loads(&l.track, &self.scenario, self.t(), af, &mut l.r)?;
        add_moving_loads(&l.track, &self.scenario, t_new, s, &mut l.r)?;
        sparse_mul_add(l.mass.as_ref(), 1.0, &l.tmp, &mut l.r);
        sparse_mul_add(l.damping.as_ref(), 1.0, &l.tmp_c, &mut l.r);
        if af != 0.0 {
            sparse_mul_add(l.stiffness.as_ref(), -af, &l.q, &mut l.r);
        }
        // z = L⁻¹P r; the contact forces; z ← z − s L⁻¹P Σ_k F_k v_k.
        l.factor.forward(&mut l.r);
        let solved = if l.patch.is_some() {
            self.patch_contact(l, t_new)
        } else {
            self.point_contact(l, t_new)
        };
        let iterations = solved.map_err(|e| match e {
            VehicleBridgeError::CouplingFailed {
                solver,
                iterations,
                change,
                reason,
                ..
            } => VehicleBridgeError::CouplingFailed {
                solver,
                t: self.t(),
                dt,
                halvings: 0,
                iterations,
                change,
                reason,
            },
            other => other,
        })?;
        l.factor.backward(&mut l.r);
        {
            let inv_cqa = 1.0 / c_qa;
            let (x, qp, vp) = (&l.r[..n], &l.q_pred[..n], &l.v_pred[..n]);
            let (q, v, a) = (&mut l.q[..n], &mut l.v[..n], &mut l.a[..n]);
            for i in 0..n {
                let a_new = (x[i] - qp[i]) * inv_cqa;
                v[i] = vp[i] + c_va * a_new;
                a[i] = a_new;
                q[i] = x[i];
            }
        }
        // The simulation's DOFs to its stepper (which holds the reported state).
        let o = l.offset;
        self.stepper.restart_with_acceleration(
            &mut self.structure,
            t_new,
            &l.q[o..],
            &l.v[o..],
            &l.a[o..],
        )?;
        let stats = &mut self.stats;
        stats.steps += 1;
        stats.iterations += iterations;
        stats.max_iterations = stats.max_iterations.max(iterations);
        for k in 0..nw {
            let touching = l.forces[k] > 0.0;
            if self.in_contact[k] && !touching {
                self.loss_events += 1;
                self.wheel_loss_events[k] += 1;
            }
            self.in_contact[k] = touching;
            self.forces[k] = l.forces[k];
        }
        Ok(())
    }

    /// The point contacts' forces of a step (Hertz, the profile law, the rigid constraint):
    /// y_k = L⁻¹P v_k (v_k = e_k − b_k), δ₀ and S, the forces, and z ← z − s Σ_k F_k y_k in
    /// `l.r`. Returns the iterations.
    fn point_contact(
        &mut self,
        l: &mut TrackLayer,
        t_new: f64,
    ) -> Result<usize, VehicleBridgeError> {
        let s = 1.0 - l.params.alpha_f;
        let nw = self.scenario.wheels.len();
        l.newton.resize(nw);
        let mut delta0 = std::mem::take(&mut l.newton.delta0);
        let mut cap = std::mem::take(&mut l.newton.cap);
        let mut forces = std::mem::take(&mut l.newton.forces);
        for k in 0..nw {
            let x = self.scenario.wheels[k].position + self.scenario.speed * t_new;
            let pt = l.rail_point(x)?;
            let iw = l.offset + self.wheel_dof[k];
            let v: [(usize, f64); 5] = [
                (iw, 1.0),
                (pt.dofs[0], -pt.weights[0]),
                (pt.dofs[1], -pt.weights[1]),
                (pt.dofs[2], -pt.weights[2]),
                (pt.dofs[3], -pt.weights[3]),
            ];
            l.factor
                .forward_sparse_reach(&v, &mut l.y[k], &mut l.reach[k]);
            l.next_points[k] = pt;
            self.work.r_at_wheel[k] = self.scenario.irregularity.height(x);
            delta0[k] = dot_on(l.reach[k].nodes(), &l.y[k], &l.r) + self.work.r_at_wheel[k];
        }
        for j in 0..nw {
            for k in 0..=j {
                let c = s * dot_on(l.reach[j].nodes(), &l.y[j], &l.y[k]);
                cap[j * nw + k] = c;
                cap[k * nw + j] = c;
            }
        }
        let tol = self.scenario.coupling.tol * self.force_scale;
        forces.copy_from_slice(&l.forces);
        let solved = if let Some(rigid) = l.rigid.as_mut() {
            rigid.forces(&delta0, &cap, &mut forces, &mut self.work.outputs, tol)
        } else {
            contact_forces(
                &mut self.contacts,
                &delta0,
                &cap,
                &mut forces,
                &mut self.work.outputs,
                tol,
                self.scenario.coupling.max_iter,
                &mut l.newton,
            )
            .map(|(iterations, _change)| iterations)
        };
        self.stats.contact_iterations += l.newton.law_iterations;
        let iterations = solved?;
        l.points.copy_from_slice(&l.next_points);
        for k in 0..nw {
            let f = s * forces[k];
            for &i in l.reach[k].nodes() {
                l.r[i] -= f * l.y[k][i];
            }
            self.work.delta[k] =
                delta0[k] - (0..nw).map(|j| cap[k * nw + j] * forces[j]).sum::<f64>();
        }
        l.forces.copy_from_slice(&forces);
        // The step's vectors back into the work space (no allocation in the next step).
        l.newton.delta0 = delta0;
        l.newton.cap = cap;
        l.newton.forces = forces;
        Ok(iterations)
    }

    /// The wheel samples and the track sample at the current state (and the running maxima).
    pub(super) fn track_samples(&mut self) -> Result<(), VehicleBridgeError> {
        let t = self.t();
        let layer = self.track.as_mut().expect("called with a track");
        let q = self.stepper.q();
        let a = self.stepper.a();
        let nw = self.scenario.wheels.len();
        for k in 0..nw {
            let x = self.scenario.wheels[k].position + self.scenario.speed * t;
            let pt = layer.rail_point(x)?;
            let rail = pt.value(&layer.q);
            let iw = self.wheel_dof[k];
            let r = self.scenario.irregularity.height(x);
            let delta = q[iw] - rail + r;
            // The law's output of the last step (of the static start at t = 0).
            let contact = self.work.outputs[k];
            let body = self.wheel_vehicle[k]
                .map(|v| self.vehicles[v].body_over(k - self.vehicles[v].first_wheel))
                .or(self.body_dof[k]);
            self.samples[k] = WheelSample {
                position: x,
                wheel_displacement: q[iw],
                body_displacement: body.map_or(q[iw], |ib| q[ib]),
                body_acceleration: body.map_or(0.0, |ib| a[ib]),
                wheel_acceleration: a[iw],
                approach: delta,
                contact,
            };
            layer.sample.rail_displacement[k] = rail;
            layer.maxima.rail_displacement = layer.maxima.rail_displacement.max(rail);
        }
        // The most loaded sleeper: the largest pad force k (u_rail − u_below) + c (v_rail − v_below).
        let track = &layer.track;
        let (mut best, mut best_force) = (0, f64::NEG_INFINITY);
        for (i, sl) in track.sleepers().iter().enumerate() {
            let pad = sl.stack.springs()[0];
            let rail = track.rail_dof(sl.node);
            let (u_below, v_below) = match sl.body_dofs.first() {
                Some(&b) => (layer.q[b], layer.v[b]),
                None => (
                    track.foundation_displacement(i, &layer.q),
                    track.foundation_displacement(i, &layer.v),
                ),
            };
            let f =
                pad.stiffness * (layer.q[rail] - u_below) + pad.damping * (layer.v[rail] - v_below);
            if f > best_force {
                best_force = f;
                best = i;
            }
        }
        let chain = track.chain_forces(best, &layer.q, &layer.v);
        let sample = &mut layer.sample;
        sample.loaded_sleeper = track.sleepers()[best].x - track.layout().approach();
        sample.pad_force = chain[0];
        sample.ballast_force = chain.get(1).copied().unwrap_or(chain[0]);
        let rail_out = track
            .rail_displacement(layer.output_x, &layer.q)
            .map_err(super::track_key)?;
        let bridge_out: f64 = self
            .output_shapes
            .iter()
            .enumerate()
            .map(|(j, s)| s * q[j])
            .sum();
        sample.rail_bridge_relative = rail_out - bridge_out;
        let mx = &mut layer.maxima;
        mx.pad_force = mx.pad_force.max(sample.pad_force);
        mx.ballast_force = mx.ballast_force.max(sample.ballast_force);
        mx.rail_bridge_relative = mx
            .rail_bridge_relative
            .max(sample.rail_bridge_relative.abs());
        Ok(())
    }
}

/// aᵀb with four partial sums (independent chains of additions), over the entries from the
/// first non-zero of `a` on (y = L⁻¹Pv is zero before the first non-zero of Pv).
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let start = a.iter().position(|&x| x != 0.0).unwrap_or(a.len());
    let (a, b) = (&a[start..], &b[start.min(b.len())..]);
    let n = a.len().min(b.len());
    let mut acc = [0.0f64; 4];
    let chunks = n / 4;
    for c in 0..chunks {
        for (j, s) in acc.iter_mut().enumerate() {
            *s += a[4 * c + j] * b[4 * c + j];
        }
    }
    let mut total = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for i in 4 * chunks..n {
        total += a[i] * b[i];
    }
    total
}

/// [`dot`] for an `a` that is zero outside `nodes` (increasing; y = L⁻¹Pv is zero off the
/// reach of its sweep), summed over `nodes` only but as [`dot`] sums over all entries from the
/// first non-zero of `a` on: entry i goes to partial sum (i − start) mod 4 within the whole
/// blocks of four, the rest is added in order after. The skipped entries contribute exact
/// zeros, so the sum is [`dot`]'s, bit for bit.
fn dot_on(nodes: &[usize], a: &[f64], b: &[f64]) -> f64 {
    let Some(first) = nodes.iter().position(|&i| a[i] != 0.0) else {
        return 0.0;
    };
    let nodes = &nodes[first..];
    let start = nodes[0];
    let n = (a.len() - start).min(b.len().saturating_sub(start));
    let body_end = start + 4 * (n / 4);
    let split = nodes.partition_point(|&i| i < body_end);
    let mut acc = [0.0f64; 4];
    for &i in &nodes[..split] {
        acc[(i - start) % 4] += a[i] * b[i];
    }
    let mut total = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for &i in &nodes[split..] {
        if i < start + n {
            total += a[i] * b[i];
        }
    }
    total
}
