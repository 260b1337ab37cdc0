//! Longitudinal friction (traction and braking) of the wheels, weakly coupled to the vertical
//! simulation (docs/vehicle_bridge.md, "Traction (friction)"; references.md §C3.5, §3.6, §4.2).
//!
//! After every accepted vertical step of Δt \[s\] the normal problem of each wheel is known
//! (force F_n \[N\], and with the `bem` law the pressure field p_n \[Pa\] on its grid); the
//! longitudinal creep force F_x \[N\] on the wheel is then computed with one of three methods:
//!
//! * `exact`: one transient rolling step of the half-space tangential problem
//!   ([`TangentialSolver::transient_step`], CONTACT's T = 2) on the BEM grid with the wheel's
//!   pressure, the previous step's tractions and δq = V Δt (bem contact only);
//! * `fastsim`: Kalker's FASTSIM on the Hertz ellipse of the current normal force
//!   (semi-axes a along, b across the track from [`HertzPoint::at_force`]);
//! * `linear`: Kalker's linear theory F_x = −G c² C₁₁ ξ, c² = ab (references.md §C4.2), capped at
//!   |F_x| ≤ μ F_n (the theory itself is uncapped; the cap is this model's choice).
//!
//! **Sign convention** (the tangential solver's, body 1 = wheel, forces on the wheel): the
//! longitudinal creepage is the wheel's rigid slip velocity at the contact over the rolling
//! speed, ξ = (V − ωR)/V, with V > 0 the vehicle speed along +x and ω > 0 the wheel's rolling
//! angular velocity (free rolling ω = V/R). Braking (ωR < V) gives ξ > 0 and F_x < 0 (a force
//! on the wheel against the motion); driving gives ξ < 0 and F_x > 0.
//!
//! **Drive.** Either a prescribed creepage ξ, or a torque T [N m] on a wheel of polar inertia
//! I [kg m²]: I ω' = T − F_x R, started from free rolling. With the creep-force slope
//! k_ω = ∂F_x/∂ω = G c² C₁₁ R/V of the linear theory the rotation is advanced linearly
//! implicitly (Rosenbrock–Euler), ω_{n+1} = ω_n + Δt (T − F_x,n R)/(I + Δt R k_ω), stable for
//! the stiff creep time constant I V/(G c² C₁₁ R²) (≈ 1 ms) and with the exact steady state
//! T = F_x R. ξ of a step is taken from ω_n. A torque above μ F_n R spins the wheel up without
//! bound (full slip); the run reports it as saturated steps.
//!
//! **Coupling** (weak): F_x is applied to the wheel's rotational DOF only. It is NOT applied to
//! the vertical bridge model (Euler–Bernoulli vertical modes) and NOT applied as a horizontal
//! bridge load: the vehicle speed V is prescribed, and the longitudinal force history is
//! reported so that a user can apply it to a horizontal bridge model elsewhere.
//! A wheel out of contact (F_n = 0) carries no traction and its previous tractions are reset.

use halfspace::{
    Creepages, FastsimInput, Grid, Material, StepMotion, TangentialOptions, TangentialSolver,
    TangentialStrategy, creep_coefficients, fastsim, tangential_strategy,
};

use halfspace::law::{ContactModel as LawModel, HertzPoint};

use super::contact::{ContactGeometry, pressure_field};
use super::{VehicleBridgeError, WheelSample};

/// The tangential method of the traction computation (module documentation): halfspace's
/// one method enum.
pub use halfspace::TangentialMethod as TractionMethod;

/// What drives or brakes the wheels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TractionDrive {
    /// Prescribed longitudinal creepage ξ (solver convention, module documentation).
    Creepage(f64),
    /// Torque T [N m] (> 0 drives) on each wheel of polar inertia `inertia` [kg m²].
    Torque { torque: f64, inertia: f64 },
}

/// The `[traction]` settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TractionSpec {
    /// Coulomb friction coefficient μ (> 0).
    pub mu: f64,
    /// Tangential method.
    pub method: TractionMethod,
    /// Drive or brake.
    pub drive: TractionDrive,
    /// FASTSIM elements per direction (default 40).
    pub fastsim_elements: usize,
}

/// Traction of one wheel after a step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TractionSample {
    /// Longitudinal force F_x on the wheel \[N\] (> 0 forward).
    pub longitudinal_force: f64,
    /// Creepage ξ = (V − ωR)/V of the step.
    pub creepage: f64,
    /// Fraction of the contact area (elements) in adhesion (1 for uncapped linear theory,
    /// 0 when the capped linear force saturates; 0 out of contact).
    pub adhesion_fraction: f64,
    /// Wheel angular velocity ω [rad/s] after the step.
    pub angular_velocity: f64,
    /// |F_x| reached μ F_n (full slip).
    pub saturated: bool,
}

/// Run statistics of the traction.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TractionSummary {
    /// Largest |F_x| over all wheels and steps \[N\] (signed value of that step).
    pub max_longitudinal_force: f64,
    /// Mean F_x over all wheel-steps in contact \[N\].
    pub mean_longitudinal_force: f64,
    /// Wheel-steps in full slip.
    pub saturated_steps: usize,
    /// Wheel-steps in contact.
    pub contact_steps: usize,
}

/// Traction state of all wheels (module documentation).
#[derive(Debug)]
pub struct Traction {
    spec: TractionSpec,
    hertz: HertzPoint,
    material: Material,
    radius: f64,
    solvers: Vec<Option<TangentialSolver>>,
    px: Vec<Vec<f64>>,
    py: Vec<Vec<f64>>,
    omega: Vec<f64>,
    samples: Vec<TractionSample>,
    sum: f64,
    summary: TractionSummary,
}

fn bad(name: &str, value: f64, reason: &str) -> VehicleBridgeError {
    VehicleBridgeError::InvalidParameter {
        name: name.to_string(),
        value,
        reason: reason.to_string(),
    }
}

impl TractionSpec {
    /// Checks every value; errors name the `[traction]` key.
    pub fn validate(&self) -> Result<(), VehicleBridgeError> {
        if !(self.mu.is_finite() && self.mu > 0.0) {
            return Err(bad("traction.mu", self.mu, "must be positive and finite"));
        }
        if self.fastsim_elements == 0 || self.fastsim_elements > 1000 {
            return Err(bad(
                "traction.fastsim_elements",
                self.fastsim_elements as f64,
                "must be in 1..=1000",
            ));
        }
        match self.drive {
            TractionDrive::Creepage(xi) => {
                if !xi.is_finite() || xi.abs() >= 1.0 {
                    return Err(bad(
                        "traction.creepage",
                        xi,
                        "must be finite with |creepage| < 1",
                    ));
                }
            }
            TractionDrive::Torque { torque, inertia } => {
                if !torque.is_finite() {
                    return Err(bad("traction.torque", torque, "must be finite"));
                }
                if !(inertia.is_finite() && inertia > 0.0) {
                    return Err(bad(
                        "traction.wheel_inertia",
                        inertia,
                        "must be positive and finite",
                    ));
                }
            }
        }
        Ok(())
    }
}

impl Traction {
    /// Sets up the traction of `contacts.len()` wheels rolling at `speed` [m/s] (free rolling at
    /// the start). `exact` needs the `bem` contact law (its grid).
    pub(super) fn new(
        spec: TractionSpec,
        geometry: &ContactGeometry,
        contacts: &[LawModel],
        speed: f64,
    ) -> Result<Self, VehicleBridgeError> {
        spec.validate()?;
        let material = geometry.material()?;
        // Wheel and rail share E and nu (K = 0): halfspace's rule gives the sequential solve
        // (normal by the contact law, then tangential), which is what `update` does.
        if tangential_strategy(spec.method, &material) == TangentialStrategy::Coupled {
            return Err(super::error::invalid_text(
                "traction.method",
                spec.method.name(),
                "dissimilar wheel and rail materials (K != 0) need the coupled normal-tangential solve, which the traction model does not do",
            ));
        }
        let hertz = geometry.hertz()?;
        let n = contacts.len();
        let mut solvers = Vec::with_capacity(n);
        let (mut px, mut py) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for contact in contacts {
            if spec.method == TractionMethod::Exact {
                let Some((grid, _)) = pressure_field(contact) else {
                    return Err(super::error::invalid_text(
                        "traction.method",
                        "exact",
                        "`exact` needs contact.model = \"bem\" (the pressure field on a grid); use \"fastsim\" or \"linear\"",
                    ));
                };
                let grid: Grid = *grid;
                px.push(vec![0.0; grid.len()]);
                py.push(vec![0.0; grid.len()]);
                solvers.push(Some(TangentialSolver::new(grid, material)?));
            } else {
                px.push(Vec::new());
                py.push(Vec::new());
                solvers.push(None);
            }
        }
        let radius = geometry.wheel_radius;
        // Before the first step no force yet: a prescribed creepage ξ fixes the wheel's
        // rotation by its definition ξ = (V − ωR)/V, i.e. ω = V(1 − ξ)/R; a torque-driven
        // wheel starts from free rolling, ω = V/R.
        let xi0 = match spec.drive {
            TractionDrive::Creepage(xi) => xi,
            TractionDrive::Torque { .. } => 0.0,
        };
        let omega0 = speed * (1.0 - xi0) / radius;
        let start = TractionSample {
            creepage: xi0,
            angular_velocity: omega0,
            ..TractionSample::default()
        };
        Ok(Self {
            spec,
            hertz,
            material,
            radius,
            solvers,
            px,
            py,
            omega: vec![omega0; n],
            samples: vec![start; n],
            sum: 0.0,
            summary: TractionSummary::default(),
        })
    }

    /// The settings.
    pub fn spec(&self) -> &TractionSpec {
        &self.spec
    }

    /// Per-wheel traction of the last step.
    pub fn samples(&self) -> &[TractionSample] {
        &self.samples
    }

    /// Statistics so far.
    pub fn summary(&self) -> TractionSummary {
        self.summary
    }

    /// G c² C₁₁ [N] of the Hertz ellipse at normal force `fn_` [N] (0 without contact).
    fn linear_slope(&self, fn_: f64) -> Result<f64, VehicleBridgeError> {
        if fn_ <= 0.0 {
            return Ok(0.0);
        }
        let (a, b, _) = self.hertz.at_force(fn_);
        let c = creep_coefficients(a, b, self.material.nu)?;
        Ok(self.material.g * a * b * c.c11)
    }

    /// The traction of every wheel after an accepted vertical step of `dt` [s] at speed
    /// `speed` [m/s] (module documentation); updates ω in torque mode.
    pub(super) fn update(
        &mut self,
        dt: f64,
        speed: f64,
        wheels: &[WheelSample],
        contacts: &[LawModel],
    ) -> Result<(), VehicleBridgeError> {
        let mu = self.spec.mu;
        let r = self.radius;
        for k in 0..wheels.len() {
            let fn_ = wheels[k].contact.force;
            let xi = match self.spec.drive {
                // The rotation consistent with the prescribed creepage (the speed may vary).
                TractionDrive::Creepage(xi) => {
                    self.omega[k] = speed * (1.0 - xi) / r;
                    xi
                }
                TractionDrive::Torque { .. } => (speed - self.omega[k] * r) / speed,
            };
            let (fx, adhesion, saturated) = if fn_ <= 0.0 {
                if let Some(s) = self.solvers[k].as_mut() {
                    s.reset();
                    self.px[k].fill(0.0);
                    self.py[k].fill(0.0);
                }
                (0.0, 0.0, false)
            } else {
                match self.spec.method {
                    TractionMethod::Linear => {
                        let f = -self.linear_slope(fn_)? * xi;
                        let cap = mu * fn_;
                        if f.abs() >= cap {
                            (cap.copysign(f), 0.0, true)
                        } else {
                            (f, 1.0, false)
                        }
                    }
                    TractionMethod::Fastsim => {
                        let (a, b, _) = self.hertz.at_force(fn_);
                        let n = self.spec.fastsim_elements;
                        let s = fastsim(
                            &FastsimInput {
                                a,
                                b,
                                g: self.material.g,
                                nu: self.material.nu,
                                mu,
                                normal_force: fn_,
                                xi,
                                eta: 0.0,
                                phi: 0.0,
                            },
                            n,
                            n,
                        )?;
                        let total = (s.adhesion_elements + s.slip_elements).max(1);
                        (
                            s.force_x,
                            s.adhesion_elements as f64 / total as f64,
                            s.adhesion_elements == 0,
                        )
                    }
                    TractionMethod::Exact => {
                        let solver = self.solvers[k].as_mut().expect("built for exact");
                        let pressure = pressure_field(&contacts[k])
                            .map(|(_, p)| p)
                            .expect("exact needs the bem law (checked in new)");
                        let motion = StepMotion {
                            delta_q: speed * dt,
                            creepages: Creepages {
                                xi,
                                eta: 0.0,
                                phi: 0.0,
                            },
                            shift: (0.0, 0.0),
                        };
                        let s = solver.transient_step(
                            pressure,
                            mu,
                            (&self.px[k], &self.py[k]),
                            motion,
                            &TangentialOptions::default(),
                        )?;
                        self.px[k].copy_from_slice(&s.traction_x);
                        self.py[k].copy_from_slice(&s.traction_y);
                        let total = (s.adhesion_elements + s.slip_elements).max(1);
                        (
                            s.force_x,
                            s.adhesion_elements as f64 / total as f64,
                            s.adhesion_elements == 0,
                        )
                    }
                }
            };
            if let TractionDrive::Torque { torque, inertia } = self.spec.drive {
                let k_omega = self.linear_slope(fn_)? * r / speed;
                self.omega[k] += dt * (torque - fx * r) / (inertia + dt * r * k_omega);
            }
            if fn_ > 0.0 {
                self.summary.contact_steps += 1;
                self.sum += fx;
                self.summary.mean_longitudinal_force = self.sum / self.summary.contact_steps as f64;
                if saturated {
                    self.summary.saturated_steps += 1;
                }
                if fx.abs() > self.summary.max_longitudinal_force.abs() {
                    self.summary.max_longitudinal_force = fx;
                }
            }
            self.samples[k] = TractionSample {
                longitudinal_force: fx,
                creepage: xi,
                adhesion_fraction: adhesion,
                angular_velocity: self.omega[k],
                saturated,
            };
        }
        Ok(())
    }
}
