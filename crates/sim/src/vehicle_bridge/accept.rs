//! Acceptance of a step, the same for both integrators: the generalized contact force of the
//! accepted state, the hand-over of the state to the structural stepper that holds it, the
//! statistics, the loss-of-contact events and the per-wheel samples.

use halfspace::law::LawOutput;

use super::contact::is_rigid;
use super::{Simulation, VehicleBridgeError};

/// How the accepted state reaches the structural stepper.
pub(super) enum StateUpdate<'a> {
    /// The structural method finishes its step of size `dt` from the converged state `work.x`.
    Finish { dt: f64 },
    /// Radau5: the stepper restarts at time `t` with displacements `x` and velocities `v`.
    Restart { t: f64, x: &'a [f64], v: &'a [f64] },
}

/// The counts of an accepted step.
pub(super) struct Accepted {
    /// Integrator steps taken (1 for a structural step; Radau5's sub-steps).
    pub(super) steps: usize,
    /// Coupling iterations (Radau5: its Newton iterations).
    pub(super) iterations: usize,
    /// Contact-solver iterations.
    pub(super) contact_iterations: usize,
    /// Rejected sub-steps (Radau5's step control; a structural step's retries are counted
    /// where they happen).
    pub(super) rejected: usize,
}

impl Simulation {
    /// Accepts the step whose contact state is in the work space (`outputs`, `modal_load`,
    /// `delta`): the generalized contact force at t_{n+1} (modes +Σ_k I_k, wheel k −F_k) into
    /// `contact_load` and the structure's load, the state update, the statistics, the
    /// loss-of-contact events and the samples.
    pub(super) fn accept(
        &mut self,
        update: StateUpdate<'_>,
        counts: Accepted,
    ) -> Result<(), VehicleBridgeError> {
        let nw = self.contacts.len();
        let w = &self.work;
        self.contact_load.fill(0.0);
        for k in 0..nw {
            for j in 0..w.span_modes[k] {
                self.contact_load[j] += w.modal_load[k][j];
            }
            self.contact_load[self.wheel_dof[k]] = -w.outputs[k].force;
        }
        if !self.scenario.moving_forces.is_empty() {
            let t = match update {
                StateUpdate::Finish { .. } => self.eq.t_new,
                StateUpdate::Restart { t, .. } => t,
            };
            self.moving_force_load(t)?;
            for (l, p) in self.contact_load.iter_mut().zip(&self.work.moving_load) {
                *l += p;
            }
        }
        self.structure
            .contact_load
            .copy_from_slice(&self.contact_load);
        match update {
            StateUpdate::Finish { dt } => {
                let x = std::mem::take(&mut self.work.x);
                let finished = self.stepper.finish_step(&mut self.structure, dt, &x);
                self.work.x = x;
                finished?;
                // Rigid wheels back onto the rail, landings and kinks (module `rigid`).
                self.rigid_finish(dt)?;
            }
            StateUpdate::Restart { t, x, v } => {
                self.stepper.restart(&mut self.structure, t, x, v)?;
            }
        }
        let stats = &mut self.stats;
        stats.steps += counts.steps;
        stats.iterations += counts.iterations;
        stats.max_iterations = stats.max_iterations.max(counts.iterations);
        stats.contact_iterations += counts.contact_iterations;
        stats.failed_steps += counts.rejected;
        stats.max_force_floor = stats.max_force_floor.max(self.work.force_floor);
        let q = self.stepper.q();
        let a = self.stepper.a();
        for k in 0..nw {
            // A wheel held at rest since its last sample: its state, approach and contact
            // output are unchanged (module `resting`), so is its sample but for the count.
            let at_rest = self.wheel_at_rest(k);
            if at_rest && self.resting.sampled_at_rest.get(k) == Some(&true) {
                self.samples[k].contact.iterations = counts.contact_iterations;
                continue;
            }
            if let Some(sampled) = self.resting.sampled_at_rest.get_mut(k) {
                *sampled = at_rest;
            }
            let iw = self.wheel_dof[k];
            let contact = self.work.outputs[k];
            let rigid = is_rigid(&self.contacts[k]);
            // A rigid wheel is in contact while it is held on the rail (module `rigid`).
            let touching = if rigid {
                self.rigid.attached[k]
            } else {
                contact.force > 0.0
            };
            if self.in_contact[k] && !touching {
                self.loss_events += 1;
                self.wheel_loss_events[k] += 1;
            }
            self.in_contact[k] = touching;
            self.forces[k] = if rigid && !touching {
                0.0
            } else {
                contact.force
            };
            let sample = &mut self.samples[k];
            sample.wheel_displacement = q[iw];
            sample.wheel_acceleration = a[iw];
            // A wheelset of a multibody vehicle reports its car body.
            let body = self.wheel_vehicle[k]
                .map(|v| self.vehicles[v].body_over(k - self.vehicles[v].first_wheel))
                .or(self.body_dof[k]);
            sample.body_displacement = body.map_or(q[iw], |ib| q[ib]);
            sample.body_acceleration = body.map_or(0.0, |ib| a[ib]);
            sample.approach = self.work.delta[k];
            sample.contact = LawOutput {
                iterations: counts.contact_iterations,
                ..contact
            };
        }
        Ok(())
    }
}
