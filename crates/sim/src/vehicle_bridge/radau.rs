//! Radau5 for the coupled vehicle–bridge step ([`Integrator::Radau5`](super::Integrator::Radau5)).
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
//! the flight and the landing. A contact-law error inside the right-hand side or the Jacobian
//! stops the step through `integrate`'s fallible right-hand side ([`OdeSystem::try_rhs`],
//! carried as [`integrate::IntegrateError::Callback`]). Every output step is accepted as the
//! structural path's steps are (`accept.rs`): the structural stepper that holds the reported
//! state is restarted at (x, ẋ) with the acceleration M⁻¹(f_g − C v − K x + Σ G_k), so the
//! accessors of [`Simulation`] report the Radau5 state.

use faer::MatMut;
use integrate::CallbackError;
use integrate::ode::{OdeOptions, OdeStepper, OdeSystem, Radau5};

use super::accept::{Accepted, StateUpdate};
use super::{Simulation, VehicleBridgeError};

/// Tolerances of the Radau5 path (local error test `|e_i| ≤ atol + rtol |y_i|`, on
/// displacements \[m\] and modal coordinates \[m √kg\] and their rates).
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
}

/// The coupled system, borrowing the simulation during one Radau5 step.
struct Coupled<'a> {
    sim: &'a mut Simulation,
}

impl Coupled<'_> {
    /// Contact forces at (t, x): fills the simulation's work space (outputs, modal loads, ĝ, v).
    fn contacts(&mut self, t: f64, x: &[f64], tangent: bool) -> Result<(), VehicleBridgeError> {
        let sim = &mut *self.sim;
        sim.work.x.copy_from_slice(x);
        sim.wheel_geometry(t)?;
        sim.evaluate_contacts(tangent)
    }
}

impl OdeSystem for Coupled<'_> {
    fn dim(&self) -> usize {
        2 * self.sim.work.x.len()
    }

    /// Not called: the methods evaluate [`OdeSystem::try_rhs`].
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        if self.try_rhs(t, y, dydt).is_err() {
            dydt.fill(f64::NAN);
        }
    }

    fn try_rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) -> Result<(), CallbackError> {
        let n = y.len() / 2;
        let (x, v) = y.split_at(n);
        self.contacts(t, x, false).map_err(CallbackError::new)?;
        if !self.sim.scenario.moving_forces.is_empty() {
            self.sim.moving_force_load(t).map_err(CallbackError::new)?;
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
        if !sim.scenario.moving_forces.is_empty() {
            for j in 0..m {
                dydt[n + j] += sim.work.moving_load[j];
            }
        }
        for i in 0..n {
            dydt[n + i] /= st.mass[(i, i)];
        }
        Ok(())
    }

    fn try_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        mut jac: MatMut<'_, f64>,
    ) -> Result<bool, CallbackError> {
        let n = y.len() / 2;
        self.contacts(t, &y[..n], true)
            .map_err(CallbackError::new)?;
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
        Ok(true)
    }

    /// Not called: the methods evaluate [`OdeSystem::try_jacobian`].
    fn jacobian(&mut self, t: f64, y: &[f64], jac: MatMut<'_, f64>) -> bool {
        self.try_jacobian(t, y, jac).unwrap_or(false)
    }
}

/// A Radau5 failure: the contact law's own error when the right-hand side failed, else the
/// integrator's error as a coupling failure at `t`.
fn radau_error(e: integrate::IntegrateError, t: f64, dt: f64) -> VehicleBridgeError {
    if e.callback_error::<VehicleBridgeError>().is_some() {
        return VehicleBridgeError::Integrate(e);
    }
    VehicleBridgeError::CouplingFailed {
        solver: "radau5",
        t,
        dt,
        halvings: 0,
        iterations: 0,
        change: f64::NAN,
        reason: e.to_string(),
    }
}

impl Simulation {
    /// Sets up the Radau5 path at the start state (module [`radau`](self)); called by
    /// [`Simulation::new`] for [`Integrator::Radau5`](super::Integrator::Radau5) (the scenario
    /// check has rejected rigid contact and bad tolerances).
    pub(super) fn start_radau5(&mut self, spec: Radau5Spec) -> Result<(), VehicleBridgeError> {
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
        stepper
            .set_state(&mut Coupled { sim: self }, t, &y)
            .map_err(|e| radau_error(e, t, self.scenario.dt))?;
        self.radau = Some(RadauPath { stepper, y });
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
        while path.stepper.t() < t_end {
            path.stepper
                .step(&mut Coupled { sim: self })
                .map_err(|e| radau_error(e, path.stepper.t(), dt))?;
        }
        let after = path.stepper.stats();
        path.y.copy_from_slice(path.stepper.y());
        let n = self.work.x.len();
        let (x, v) = path.y.split_at(n);
        // Contact state at the output time (the tangent as well, for the report).
        Coupled { sim: self }.contacts(t_end, x, true)?;
        let newton = after.newton_iterations - before.newton_iterations;
        let contact_iterations = self.work.outputs.iter().map(|o| o.iterations).sum();
        self.accept(
            StateUpdate::Restart { t: t_end, x, v },
            Accepted {
                steps: after.steps - before.steps,
                iterations: newton,
                contact_iterations,
                rejected: after.rejected_steps - before.rejected_steps,
            },
        )
    }
}
