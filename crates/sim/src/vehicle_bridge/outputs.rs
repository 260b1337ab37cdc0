//! What a simulation reports: per-wheel samples, coupling statistics, the state and the
//! bridge response (deflection, output point), and the run helpers.

use halfspace::law::{ContactModel as LawModel, LawOutput};

use super::{RunSummary, Scenario, Simulation, StepInfo, VehicleBridgeError, run, traction};

/// Per-wheel state reported at a time.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WheelSample {
    /// Position x_k \[m\].
    pub position: f64,
    /// Wheel displacement z_w \[m\] (down).
    pub wheel_displacement: f64,
    /// Body displacement z_b \[m\] (down; equal to z_w without a body).
    pub body_displacement: f64,
    /// Body acceleration \[m/s²\] (0 without a body).
    pub body_acceleration: f64,
    /// Wheel acceleration \[m/s²\].
    pub wheel_acceleration: f64,
    /// Approach δ \[m\].
    pub approach: f64,
    /// Contact force and patch (for the rigid constraint only the force, the multiplier).
    pub contact: LawOutput,
}

/// Coupling statistics of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolverStats {
    /// Accepted steps (including the halves of reduced steps).
    pub steps: usize,
    /// Total coupling iterations (contact evaluations).
    pub iterations: usize,
    /// Most iterations in one step.
    pub max_iterations: usize,
    /// Total contact-solver iterations (NormCG).
    pub contact_iterations: usize,
    /// Step attempts that failed and were retried with half the step.
    pub failed_steps: usize,
    /// Largest floating-point floor of the contact forces met in a step \[N\] (the
    /// convergence test's floor; module documentation of the coupling).
    pub max_force_floor: f64,
}

impl Simulation {
    /// The scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// Current time \[s\].
    pub fn t(&self) -> f64 {
        self.stepper.t()
    }

    /// Total simulated time of a [`run`](Self::run) \[s\].
    pub fn end_time(&self) -> f64 {
        self.scenario.duration.unwrap_or_else(|| {
            let first = self.scenario.rearmost_position();
            ((self.scenario.bridge.length() - first) / self.scenario.speed).max(0.0)
        })
    }

    /// The state vector (modes first, then per wheel: wheel DOF, body DOF if any).
    pub fn state(&self) -> &[f64] {
        self.stepper.q()
    }

    /// The velocity vector.
    pub fn velocity(&self) -> &[f64] {
        self.stepper.v()
    }

    /// The acceleration vector.
    pub fn acceleration(&self) -> &[f64] {
        self.stepper.a()
    }

    /// Per-wheel samples at the current time.
    pub fn wheels(&self) -> &[WheelSample] {
        &self.samples
    }

    /// Static wheel loads W_k = (m_w + m_b) g + P \[N\].
    pub fn static_loads(&self) -> &[f64] {
        &self.static_loads
    }

    /// Coupling statistics so far.
    pub fn stats(&self) -> SolverStats {
        self.stats
    }

    /// Number of transitions from contact to loss of contact (over all wheels).
    pub fn loss_of_contact_events(&self) -> usize {
        self.loss_events
    }

    /// Bridge deflection w(x) \[m\] at the current time (0 off the span).
    pub fn deflection_at(&self, x: f64) -> Result<f64, VehicleBridgeError> {
        let m = self.scenario.bridge.n_modes();
        if !(0.0..=self.scenario.bridge.length()).contains(&x) {
            return Ok(0.0);
        }
        let mut w = 0.0;
        for j in 0..m {
            w += self.stepper.q()[j] * self.scenario.bridge.shape(j, x)?;
        }
        Ok(w)
    }

    /// Deflection, velocity and acceleration of the bridge at the output point.
    pub fn output_point_response(&self) -> (f64, f64, f64) {
        let m = self.scenario.bridge.n_modes();
        let s = &self.output_shapes;
        let d = (0..m).map(|j| self.stepper.q()[j] * s[j]).sum();
        let v = (0..m).map(|j| self.stepper.v()[j] * s[j]).sum();
        let a = (0..m).map(|j| self.stepper.a()[j] * s[j]).sum();
        (d, v, a)
    }

    /// Quasi-static deflection at the output point under the static wheel loads at their
    /// current positions, `Σ_k W_k Σ_j w_j(x_out) w_j(x_k)/(m_j ω_j²)` \[m\] (same modal basis;
    /// `None` if the basis has a rigid-body mode, ω_j = 0).
    pub fn quasi_static_output_deflection(&self) -> Result<Option<f64>, VehicleBridgeError> {
        let Some(weights) = self.quasi_static_weights.as_deref() else {
            return Ok(None);
        };
        let basis = &*self.scenario.bridge;
        let length = basis.length();
        // Σ_j w_j(x_out) w_j(x)/(m_j ω_j²) at x on the span (one `sin_cos` on a sine basis).
        let influence = |x: f64| -> Result<f64, VehicleBridgeError> {
            if let Some(amplitudes) = self.sine.as_deref() {
                return Ok(beam::sine_shape_dot(amplitudes, length, x, weights));
            }
            let mut sum = 0.0;
            for (j, c) in weights.iter().enumerate() {
                sum += c * basis.shape(j, x)?;
            }
            Ok(sum)
        };
        let mut total = 0.0;
        for (sample, load) in self.samples.iter().zip(&self.static_loads) {
            if (0.0..=length).contains(&sample.position) {
                total += load * influence(sample.position)?;
            }
        }
        for f in &self.scenario.moving_forces {
            let x = f.position + self.scenario.speed * self.t();
            if (0.0..=length).contains(&x) {
                total += f.force * influence(x)?;
            }
        }
        Ok(Some(total))
    }

    /// The quasi-static deflection at the output point under the heaviest static load (a
    /// wheel's or a moving force's) standing at the output point,
    /// `W_max Σ_j w_j(x_out)²/(m_j ω_j²)` \[m\]: the scale below which the quasi-static
    /// deflection of a run is too small for a dynamic amplification (`None` as for
    /// [`Self::quasi_static_output_deflection`]).
    pub fn quasi_static_reference_deflection(&self) -> Option<f64> {
        let weights = self.quasi_static_weights.as_deref()?;
        let heaviest = self
            .static_loads
            .iter()
            .copied()
            .chain(self.scenario.moving_forces.iter().map(|f| f.force))
            .fold(0.0_f64, |m, w| m.max(w.abs()));
        let influence: f64 = weights
            .iter()
            .zip(&self.output_shapes)
            .map(|(c, w)| c * w)
            .sum();
        Some(heaviest * influence)
    }

    /// The weights `w_j(x_out)/(m_j ω_j²)` of [`Self::quasi_static_output_deflection`]
    /// (`None` if the basis has a rigid-body mode, ω_j = 0).
    pub(super) fn quasi_static_weights(
        basis: &dyn beam::ModalBasis,
        output_shapes: &[f64],
    ) -> Result<Option<Vec<f64>>, VehicleBridgeError> {
        let omegas = basis.circular_frequencies();
        if omegas.iter().any(|&w| w <= 0.0) {
            return Ok(None);
        }
        let mut weights = Vec::with_capacity(omegas.len());
        for (j, (&o, &w)) in omegas.iter().zip(output_shapes).enumerate() {
            weights.push(w / (basis.modal_mass(j)? * o * o));
        }
        Ok(Some(weights))
    }

    /// The centreline pressure of wheel `k`'s last contact evaluation (ξ \[m\], p \[Pa\]).
    pub fn centreline_pressure(&self, k: usize, out: &mut Vec<(f64, f64)>) {
        match &self.contacts[k] {
            LawModel::Law(law) => law.centreline_pressure(out),
            LawModel::Rigid(_) => out.clear(),
        }
    }

    /// Switches on longitudinal friction (module [`traction`]; weak coupling after every
    /// step). Call before the first step; `exact` needs the `bem` contact law.
    pub fn set_traction(&mut self, spec: traction::TractionSpec) -> Result<(), VehicleBridgeError> {
        if matches!(self.scenario.contact, super::ContactModel::BemProfiles(_)) {
            return Err(super::error::invalid_text(
                "traction",
                spec.method.name(),
                "not available with real profiles (contact.profiles): the creep forces need the Hertz geometry of contact.wheel_radius and contact.rail_profile_radius",
            ));
        }
        self.traction = Some(traction::Traction::new(
            spec,
            &self.scenario.geometry,
            &self.contacts,
            self.scenario.speed,
        )?);
        Ok(())
    }

    /// The traction state (`None` without `set_traction`).
    pub fn traction(&self) -> Option<&traction::Traction> {
        self.traction.as_ref()
    }

    /// Steps to the end time, calling `progress` after every step (the run driver
    /// [`run::run`] with an observer that never stops the run).
    pub fn run(
        &mut self,
        mut progress: impl FnMut(&Self),
    ) -> Result<RunSummary, VehicleBridgeError> {
        let mut observer = |sim: &Self, _: StepInfo| {
            progress(sim);
            std::ops::ControlFlow::Continue(())
        };
        run::run(self, &mut observer).map_err(|f| f.error)
    }

    /// Steps of the scenario's Δt to [`end_time`](Self::end_time): `⌈T/Δt − 10⁻⁹⌉`.
    pub fn planned_steps(&self) -> usize {
        let steps = (self.end_time() / self.scenario.dt - 1e-9).ceil().max(0.0);
        steps as usize
    }

    /// Position of wheel `k` at the current time, `x_k(t) = x_k0 + c t` \[m\].
    pub fn wheel_position(&self, k: usize) -> f64 {
        self.scenario.wheels[k].position + self.scenario.speed * self.t()
    }

    /// The step-size indicators of the scenario (module [`run`]): Δt times the highest
    /// retained bridge frequency f_max = ω_max/2π, and Δt times the largest contact frequency
    /// `f_c = √(k_c/m_w)/2π` of a wheel on its contact spring at the static load (`None` for
    /// the rigid contact or massless wheels, which have no contact mode).
    pub fn step_indicators(&self) -> (f64, Option<f64>) {
        let dt = self.scenario.dt;
        let two_pi = 2.0 * std::f64::consts::PI;
        let omega_max = self
            .scenario
            .bridge
            .circular_frequencies()
            .iter()
            .fold(0.0f64, |m, &w| m.max(w));
        let contact = self
            .scenario
            .wheels
            .iter()
            .zip(&self.static_contact_stiffness)
            .filter(|(w, k)| w.wheel_mass > 0.0 && **k > 0.0)
            .map(|(w, &k)| dt * (k / w.wheel_mass).sqrt() / two_pi)
            .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))));
        (dt * omega_max / two_pi, contact)
    }

    /// Loss-of-contact events per wheel (their sum is
    /// [`loss_of_contact_events`](Self::loss_of_contact_events)).
    pub fn wheel_loss_of_contact_events(&self) -> &[usize] {
        &self.wheel_loss_events
    }
}
