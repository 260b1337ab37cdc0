//! Radau5 for the coupled vehicle–bridge step ([`Simulation::set_radau5`]).
//!
//! The coupled system (bridge modes and vehicle DOFs, with the contact forces) is written as
//! the first-order ODE `y = [x, ẋ]`,
//!
//! ```text
//! ẋ = v,   M v̇ = f_g − C v − K x + Σ_k G_k(x, t),   G_k = (+I_k on the modes, −F_k on wheel k)
//! ```
//!
//! (the structure of the module documentation; the mass matrix is diagonal), and advanced by
//! the 3-stage Radau IIA method of order 5 of the `integrate` crate ([`integrate::ode::Radau5`],
//! Hairer & Wanner, *Solving ODEs II*, §IV.8), adaptive with the tolerances `rtol`/`atol` and
//! stopped exactly on every output time t_n = n Δt (`set_stop_time`, steps capped at Δt). The
//! contact force is part of the right-hand side, so the coupling iteration is Radau5's own
//! simplified Newton iteration with the Jacobian
//!
//! ```text
//! J = [[0, I], [−M⁻¹(K + Σ_k k_c,k ĝ_k v_kᵀ), −M⁻¹C]]
//! ```
//!
//! (k_c = dF/dδ from the contact law, ĝ_k and v_k as in the quasi-Newton coupling: the pressure
//! shape is lagged in the Jacobian only, which affects Newton's convergence, not the result).
//! A compliant contact is needed (`hertz` or `bem`): a rigid contact (or a massless wheel) is
//! a differential-algebraic constraint, not an ODE. Loss of contact needs no special handling:
//! F(δ) = C_H δ₊^{3/2} is continuously differentiable, and the adaptive step control resolves
//! the flight and the landing. After every output step the structural stepper that holds the
//! reported state is restarted at (x, ẋ) with the acceleration M⁻¹(f_g − C v − K x + Σ G_k), so
//! the accessors of [`Simulation`] report the Radau5 state.

use faer::MatMut;
use integrate::ode::{OdeOptions, OdeStepper, OdeSystem, Radau5};

use super::contact::is_rigid;
use super::{LawOutput, Simulation, VehicleBridgeError, invalid};

/// Tolerances of the Radau5 path (local error test `|e_i| ≤ atol + rtol |y_i|`, on
/// displacements \[m\] and modal coordinates [m √kg] and their rates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Radau5Spec {
    /// Relative tolerance (> 0).
    pub rtol: f64,
    /// Absolute tolerance (> 0).
    pub atol: f64,
}

impl Default for Radau5Spec {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol: 1e-9,
        }
    }
}

/// The Radau5 state of a run.
pub(super) struct RadauPath {
    stepper: Radau5,
    y: Vec<f64>,
    /// First contact-law error met inside the right-hand side (which cannot return it).
    error: Option<VehicleBridgeError>,
}

/// The coupled system, borrowing the simulation during one Radau5 step.
struct Coupled<'a> {
    sim: &'a mut Simulation,
    error: &'a mut Option<VehicleBridgeError>,
}

impl Coupled<'_> {
    /// Contact forces at (t, x): fills the simulation's work space (outputs, modal loads, ĝ, v).
    fn contacts(&mut self, t: f64, x: &[f64], tangent: bool) -> bool {
        let sim = &mut *self.sim;
        sim.work.x.copy_from_slice(x);
        let r = sim
            .wheel_geometry(t)
            .and_then(|()| sim.evaluate_contacts(tangent));
        match r {
            Ok(()) => true,
            Err(e) => {
                if self.error.is_none() {
                    *self.error = Some(e);
                }
                false
            }
        }
    }
}

impl OdeSystem for Coupled<'_> {
    fn dim(&self) -> usize {
        2 * self.sim.work.x.len()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = y.len() / 2;
        let (x, v) = y.split_at(n);
        if !self.contacts(t, x, false) {
            dydt.fill(f64::NAN);
            return;
        }
        let sim = &*self.sim;
        let st = &sim.structure;
        let m = sim.scenario.bridge.n_modes();
        dydt[..n].copy_from_slice(v);
        for i in 0..n {
            let mut f = st.gravity_load[i];
            for j in 0..n {
                f -= st.stiffness[(i, j)] * x[j] + st.damping[(i, j)] * v[j];
            }
            dydt[n + i] = f;
        }
        for (k, &iw) in sim.wheel_dof.iter().enumerate() {
            for j in 0..m {
                dydt[n + j] += sim.work.modal_load[k][j];
            }
            dydt[n + iw] -= sim.work.outputs[k].force;
        }
        for i in 0..n {
            dydt[n + i] /= st.mass[(i, i)];
        }
    }

    fn jacobian(&mut self, t: f64, y: &[f64], mut jac: MatMut<'_, f64>) -> bool {
        let n = y.len() / 2;
        if !self.contacts(t, &y[..n], true) {
            return false;
        }
        let sim = &*self.sim;
        let st = &sim.structure;
        jac.fill(0.0);
        for i in 0..n {
            jac[(i, n + i)] = 1.0;
            let inv_m = 1.0 / st.mass[(i, i)];
            for j in 0..n {
                jac[(n + i, j)] = -st.stiffness[(i, j)] * inv_m;
                jac[(n + i, n + j)] = -st.damping[(i, j)] * inv_m;
            }
        }
        for k in 0..sim.contacts.len() {
            let kc = sim.work.outputs[k].stiffness;
            if kc == 0.0 {
                continue;
            }
            let (gh, vk) = (&sim.work.g_hat[k], &sim.work.v[k]);
            for i in 0..n {
                if gh[i] == 0.0 {
                    continue;
                }
                let s = kc * gh[i] / st.mass[(i, i)];
                for j in 0..n {
                    jac[(n + i, j)] -= s * vk[j];
                }
            }
        }
        true
    }
}

impl Simulation {
    /// Switches the time integration to Radau5 (module [`radau`](self)); the scenario's
    /// structural `method` is then unused. Call before the first step. Errors: a rigid contact
    /// (`contact.model`), non-positive or non-finite tolerances (`integrator.rtol`,
    /// `integrator.atol`).
    pub fn set_radau5(&mut self, spec: Radau5Spec) -> Result<(), VehicleBridgeError> {
        if self.contacts.iter().any(is_rigid) {
            return Err(invalid(
                "contact.model",
                f64::NAN,
                "radau5 needs a compliant contact (hertz or bem): a rigid contact is an algebraic constraint, not an ODE",
            ));
        }
        for (name, v) in [
            ("integrator.rtol", spec.rtol),
            ("integrator.atol", spec.atol),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(name, v, "must be positive and finite"));
            }
        }
        let n = self.work.x.len();
        let options = OdeOptions {
            max_step: self.scenario.dt,
            max_steps: usize::MAX,
            ..OdeOptions::adaptive(spec.rtol, spec.atol)
        };
        let mut stepper = Radau5::new(2 * n, &options)?;
        let mut y = self.stepper.q().to_vec();
        y.extend_from_slice(self.stepper.v());
        let t = self.stepper.t();
        let mut error = None;
        let r = stepper.set_state(
            &mut Coupled {
                sim: self,
                error: &mut error,
            },
            t,
            &y,
        );
        if let Some(e) = error {
            return Err(e);
        }
        r?;
        self.radau = Some(RadauPath {
            stepper,
            y,
            error: None,
        });
        Ok(())
    }

    /// `true` when the run uses Radau5.
    pub fn uses_radau5(&self) -> bool {
        self.radau.is_some()
    }

    /// One output step of size `dt` by Radau5 (adaptive sub-steps ending exactly on t + dt).
    pub(super) fn radau_step(&mut self, dt: f64) -> Result<(), VehicleBridgeError> {
        let Some(mut path) = self.radau.take() else {
            return Ok(());
        };
        let result = self.radau_advance(&mut path, dt);
        self.radau = Some(path);
        result
    }

    fn radau_advance(&mut self, path: &mut RadauPath, dt: f64) -> Result<(), VehicleBridgeError> {
        let t_end = self.stepper.t() + dt;
        path.stepper.set_stop_time(Some(t_end));
        path.stepper.set_max_step(dt);
        let before = path.stepper.stats();
        let mut error = path.error.take();
        while path.stepper.t() < t_end {
            let r = path.stepper.step(&mut Coupled {
                sim: self,
                error: &mut error,
            });
            if let Some(e) = error.take() {
                return Err(e);
            }
            if let Err(e) = r {
                return Err(VehicleBridgeError::CouplingFailed {
                    solver: "radau5",
                    t: path.stepper.t(),
                    dt,
                    halvings: 0,
                    iterations: 0,
                    change: f64::NAN,
                    reason: e.to_string(),
                });
            }
        }
        let after = path.stepper.stats();
        path.y.copy_from_slice(path.stepper.y());
        let n = self.work.x.len();
        let (x, v) = path.y.split_at(n);
        // Contact state at the output time (the tangent as well, for the report).
        let mut error = None;
        let ok = Coupled {
            sim: self,
            error: &mut error,
        }
        .contacts(t_end, x, true);
        if !ok {
            return Err(error.unwrap_or_else(|| invalid("contact", f64::NAN, "contact failed")));
        }
        let m = self.scenario.bridge.n_modes();
        let nw = self.contacts.len();
        self.contact_load.fill(0.0);
        for k in 0..nw {
            for j in 0..m {
                self.contact_load[j] += self.work.modal_load[k][j];
            }
            self.contact_load[self.wheel_dof[k]] = -self.work.outputs[k].force;
        }
        self.structure
            .contact_load
            .copy_from_slice(&self.contact_load);
        self.stepper
            .restart(&mut self.structure, t_end, x, v)
            .map_err(VehicleBridgeError::from)?;
        let steps = after.steps - before.steps;
        let newton = after.newton_iterations - before.newton_iterations;
        self.stats.steps += steps;
        self.stats.iterations += newton;
        self.stats.max_iterations = self.stats.max_iterations.max(newton);
        self.stats.failed_steps += after.rejected_steps - before.rejected_steps;
        let contact_iterations: usize = self.work.outputs.iter().map(|o| o.iterations).sum();
        self.stats.contact_iterations += contact_iterations;
        let q = self.stepper.q();
        let a = self.stepper.a();
        for k in 0..nw {
            let iw = self.wheel_dof[k];
            let contact = self.work.outputs[k];
            let touching = contact.force > 0.0;
            if self.in_contact[k] && !touching {
                self.loss_events += 1;
                self.wheel_loss_events[k] += 1;
            }
            self.in_contact[k] = touching;
            self.forces[k] = contact.force;
            let sample = &mut self.samples[k];
            sample.wheel_displacement = q[iw];
            sample.wheel_acceleration = a[iw];
            sample.body_displacement = self.body_dof[k].map_or(q[iw], |ib| q[ib]);
            sample.body_acceleration = self.body_dof[k].map_or(0.0, |ib| a[ib]);
            sample.approach = self.work.delta[k];
            sample.contact = LawOutput {
                iterations: contact_iterations,
                ..contact
            };
        }
        Ok(())
    }
}
