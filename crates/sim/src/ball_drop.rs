//! A rigid or elastic ball dropped on an elastic half-space (references.md §D1.4,
//! references.md §C4.10).
//!
//! # Model
//! One degree of freedom: `z` \[m\] is the height of the ball's lowest point above the surface
//! (upward positive), `v = z'` \[m/s\]. The approach is `δ = max(0, −z)` and
//!
//! ```text
//! m z'' = F(δ, δ') − m g,        F = max(0, F_el(δ) + c δ')  for δ > 0,  F = 0 otherwise,
//! ```
//!
//! with the elastic law `F_el` either Hertz's closed form `K δ^{3/2}` (`K = (4/3)E*√R` for a
//! sphere, the elliptic Hertz solution for an ellipsoid; Johnson 1985 §11.4, references.md §C4.1)
//! or the boundary-element half-space solver at prescribed approach ([`ContactForce::bem`]),
//! and optional linear surface damping `c` \[N·s/m\]. `1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂`
//! (a rigid ball has `1/E₁ = 0`).
//!
//! # Integrators
//! * first-order methods of [`integrate::ode`] (euler, rk4, dopri5, backward_euler, radau5,
//!   bdf, adams) on `y = (z, v, D)`, where `D' = (F − F_el)·δ'` accumulates the dissipated
//!   energy. Contact start (`z` falling through 0, guarded by [`integrate::ode::events`]' contact
//!   guard with `h_c = T_c/50` so that no bounce is stepped over), maximum approach (`v` rising
//!   through 0), peak force (`dF/dt` falling through 0, with damping) and contact end are
//!   events located on the methods' dense output;
//! * structural methods of [`integrate::structural`] (verlet, leapfrog, newmark, hht,
//!   generalized_alpha) on `m z'' + f_int(z) = −m g` with `f_int(z) = −F_el(−z)` and its
//!   tangent; fixed step `dt` in contact and `dt_flight` in free flight (a flight step that
//!   ends below the surface is undone and replaced by a step that lands on the crossing of the
//!   free-flight parabola, which these schemes integrate exactly). Events are
//!   located by root finding on the dense output. These schemes take no velocity-dependent
//!   force, so damping requires a first-order method.
//!
//! # Energy
//! `E = ½ m v² + m g z + W(δ) + D` with `W = ∫₀^δ F_el dδ'` (`(2/5) K δ^{5/2}` for Hertz,
//! Clapeyron's `½ ΔA Σ p u` for the BEM solution). `energy_drift = (E(t_end) − E₀)/E_ref` with
//! `E_ref = ½ m v_impact²`, `v_impact² = v₀² + 2 g h` (the kinetic energy at the first impact),
//! or `m g R` when that is zero, or 1 J when both are.
//!
//! Units are SI throughout.

mod first_order;
mod force;
mod hertz_impact;
pub mod plan;
mod result;
mod second_order;

use std::ops::ControlFlow;
use std::time::Instant;

pub use force::{ContactForce, ElasticForce, hertz_constant};
use halfspace::{Body, ContactError, Material};
pub use hertz_impact::{CONTACT_TIME_FACTOR, HertzImpact};
use integrate::{IntegrateError, Method, StructuralMethod};
pub use plan::RunPlan;
pub use result::{BallDropResult, Impact, Progress, RunStats, Sample};
use thiserror::Error;

/// Failure of a ball-drop simulation. `key` names the scenario-file key at fault.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum BallDropError {
    /// A parameter is out of range.
    #[error("invalid `{key}` = {value}: {reason}")]
    InvalidParameter {
        key: &'static str,
        value: f64,
        reason: String,
    },
    /// A material or geometry rejected by the contact crate.
    #[error("`{key}`: {source}")]
    Material {
        key: &'static str,
        #[source]
        source: ContactError,
    },
    /// The boundary-element solve failed inside the time integration.
    #[error("boundary-element contact solve failed at approach δ = {approach:e} m: {source}")]
    ContactSolve {
        approach: f64,
        #[source]
        source: ContactError,
    },
    /// The time integrator failed.
    #[error("time integration failed: {0}")]
    Integration(#[from] IntegrateError),
}

fn invalid(key: &'static str, value: f64, reason: &str) -> BallDropError {
    BallDropError::InvalidParameter {
        key,
        value,
        reason: reason.to_string(),
    }
}

/// Geometry of the ball near its lowest point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BallShape {
    /// A sphere of radius `radius` \[m\].
    Sphere { radius: f64 },
    /// A body with principal radii of curvature `radius_x`, `radius_y` \[m\] at its lowest
    /// point (Hertz's elliptic contact).
    Ellipsoid { radius_x: f64, radius_y: f64 },
}

/// The elastic force law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ForceModel {
    /// `F = K δ^{3/2}`.
    Hertz,
    /// The half-space solver on `elements × elements` elements, NormCG tolerance `tol`.
    Bem { elements: usize, tol: f64 },
}

/// The time integrator and its settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// A method of [`integrate::ode`]. euler, rk4 and backward_euler take fixed steps `dt` \[s\];
    /// dopri5, radau5, bdf and adams are adaptive with `rtol`, `atol` \[m, m/s, J\].
    Ode {
        method: Method,
        rtol: f64,
        atol: f64,
        dt: f64,
        /// Contact-guard step `h_c` \[s\] (default: `T_c/50` from the Hertz contact time at the
        /// first impact speed; for the fixed-step methods always `dt`).
        guard_step: Option<f64>,
        /// Largest step of an adaptive method \[s\] (default unbounded).
        max_step: Option<f64>,
    },
    /// A method of [`integrate::structural`] with the step `dt` \[s\] in contact and
    /// `dt_flight` \[s\] in free flight.
    Structural {
        method: StructuralMethod,
        dt: f64,
        dt_flight: f64,
    },
}

/// Settings from which [`Integrator::from_name`] builds an integrator.
#[derive(Debug, Clone, PartialEq)]
pub struct IntegratorSettings {
    /// Relative tolerance of adaptive methods (default 1e-8).
    pub rtol: f64,
    /// Absolute tolerance of adaptive methods (default 1e-12).
    pub atol: f64,
    /// Fixed step \[s\] (default 1e-6).
    pub dt: f64,
    /// Free-flight step of the structural methods \[s\] (default `dt`).
    pub dt_flight: Option<f64>,
    /// Contact-guard step of the first-order methods \[s\].
    pub guard_step: Option<f64>,
    /// Largest step of adaptive methods \[s\].
    pub max_step: Option<f64>,
    /// Structural method parameters (`alpha`, `rho_inf`, `beta`, `gamma`).
    pub parameters: Vec<(&'static str, f64)>,
}

impl Default for IntegratorSettings {
    fn default() -> Self {
        Self {
            rtol: 1e-8,
            atol: 1e-12,
            dt: 1e-6,
            dt_flight: None,
            guard_step: None,
            max_step: None,
            parameters: Vec::new(),
        }
    }
}

/// Names accepted by [`Integrator::from_name`].
pub const METHOD_NAMES: [&str; 12] = [
    "euler",
    "rk4",
    "dopri5",
    "backward_euler",
    "radau5",
    "bdf",
    "adams",
    "verlet",
    "leapfrog",
    "newmark",
    "hht",
    "generalized_alpha",
];

impl Integrator {
    /// Build from a method name (one of [`METHOD_NAMES`]; the structural aliases of
    /// [`StructuralMethod::by_name`] are accepted too) and its settings.
    pub fn from_name(name: &str, s: &IntegratorSettings) -> Result<Self, BallDropError> {
        if let Ok(method) = Method::from_name(name) {
            if let Some((p, v)) = s.parameters.first() {
                return Err(invalid(
                    "[integrator] parameters",
                    *v,
                    &format!("`{p}` is a parameter of the structural methods, not of `{name}`"),
                ));
            }
            if s.dt_flight.is_some() {
                return Err(invalid(
                    "[integrator] dt_flight",
                    s.dt_flight.unwrap_or(f64::NAN),
                    "only the structural methods (verlet, leapfrog, newmark, hht, generalized_alpha) take `dt_flight`",
                ));
            }
            return Ok(Integrator::Ode {
                method,
                rtol: s.rtol,
                atol: s.atol,
                dt: s.dt,
                guard_step: s.guard_step,
                max_step: s.max_step,
            });
        }
        let method = StructuralMethod::by_name(name, &s.parameters).map_err(|e| {
            BallDropError::InvalidParameter {
                key: "[integrator] method",
                value: f64::NAN,
                reason: format!("{e} (known methods: {})", METHOD_NAMES.join(", ")),
            }
        })?;
        if s.guard_step.is_some() || s.max_step.is_some() {
            return Err(invalid(
                "[integrator] guard_step/max_step",
                s.guard_step.or(s.max_step).unwrap_or(f64::NAN),
                "only the first-order methods take `guard_step` and `max_step`; the structural methods use `dt` and `dt_flight`",
            ));
        }
        Ok(Integrator::Structural {
            method,
            dt: s.dt,
            dt_flight: s.dt_flight.unwrap_or(s.dt),
        })
    }

    /// The method's name.
    pub fn name(&self) -> &'static str {
        match self {
            Integrator::Ode { method, .. } => method.name(),
            Integrator::Structural { method, .. } => match method {
                StructuralMethod::Newmark { beta, .. } if *beta == 0.0 => "central_difference",
                m => m.name(),
            },
        }
    }

    /// `true` for the adaptive first-order methods (dopri5, radau5, bdf, adams).
    pub fn is_adaptive(&self) -> bool {
        matches!(
            self,
            Integrator::Ode {
                method: Method::Dopri5 | Method::Radau5 | Method::Bdf | Method::Adams,
                ..
            }
        )
    }
}

/// A ball-drop scenario (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct BallDrop {
    /// Ball mass m \[kg\].
    pub mass: f64,
    /// Ball geometry at its lowest point.
    pub shape: BallShape,
    /// The ball's material (rigid or elastic).
    pub ball: Body,
    /// The half-space's material.
    pub surface: Body,
    /// Gravitational acceleration g \[m/s²\] (default 9.81).
    pub gravity: f64,
    /// Initial height h ≥ 0 of the lowest point above the surface \[m\].
    pub height: f64,
    /// Initial velocity v₀ \[m/s\], upward positive.
    pub velocity: f64,
    /// Simulated time \[s\].
    pub duration: f64,
    /// Elastic force law.
    pub model: ForceModel,
    /// Linear surface damping c ≥ 0 \[N·s/m\].
    pub damping: f64,
    /// Time integrator.
    pub integrator: Integrator,
    /// Spacing of the recorded free-flight samples \[s\] (every step in contact is recorded);
    /// default `duration / 2000`.
    pub output_interval: Option<f64>,
}

impl BallDrop {
    /// The reference steel ball (references.md §C4.10): R = 10 mm, ρ = 7850 kg/m³, rigid, on steel (E = 210 GPa,
    /// ν = 0.3), dropped from 0.1 m at rest, g = 9.81, 1 s, Hertz, Radau5 at rtol 1e-8.
    pub fn steel_ball() -> Self {
        let radius = 0.01;
        Self {
            mass: sphere_mass(radius, 7850.0),
            shape: BallShape::Sphere { radius },
            ball: Body::Rigid,
            surface: Body::Elastic { e: 210e9, nu: 0.3 },
            gravity: 9.81,
            height: 0.1,
            velocity: 0.0,
            duration: 1.0,
            model: ForceModel::Hertz,
            damping: 0.0,
            integrator: Integrator::Ode {
                method: Method::Radau5,
                rtol: 1e-8,
                atol: 1e-12,
                dt: 1e-6,
                guard_step: None,
                max_step: None,
            },
            output_interval: None,
        }
    }

    /// Check every parameter; the error names the scenario key.
    pub fn validate(&self) -> Result<Material, BallDropError> {
        positive("[ball] mass", self.mass)?;
        match self.shape {
            BallShape::Sphere { radius } => positive("[ball] radius", radius)?,
            BallShape::Ellipsoid { radius_x, radius_y } => {
                positive("[ball] radius_x", radius_x)?;
                positive("[ball] radius_y", radius_y)?;
            }
        }
        if !(self.gravity.is_finite() && self.gravity >= 0.0) {
            return Err(invalid("gravity", self.gravity, "must be finite and >= 0"));
        }
        if !(self.height.is_finite() && self.height >= 0.0) {
            return Err(invalid(
                "[initial] height",
                self.height,
                "must be finite and >= 0 (the ball starts on or above the surface)",
            ));
        }
        if !self.velocity.is_finite() {
            return Err(invalid(
                "[initial] velocity",
                self.velocity,
                "must be finite",
            ));
        }
        positive("duration", self.duration)?;
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(invalid(
                "[contact] damping",
                self.damping,
                "must be finite and >= 0",
            ));
        }
        if let ForceModel::Bem { elements, tol } = self.model {
            if !(4..=1024).contains(&elements) {
                return Err(invalid(
                    "[contact] elements",
                    elements as f64,
                    "must lie in 4..=1024",
                ));
            }
            positive("[contact] tol", tol)?;
        }
        if let Some(dt) = self.output_interval {
            positive("[output] interval", dt)?;
        }
        match self.integrator {
            Integrator::Ode {
                rtol,
                atol,
                dt,
                guard_step,
                max_step,
                ..
            } => {
                positive("[integrator] rtol", rtol)?;
                if !(atol.is_finite() && (atol > 0.0 || !self.integrator.is_adaptive())) {
                    return Err(invalid(
                        "[integrator] atol",
                        atol,
                        "must be finite and > 0 (the dissipated energy starts at 0: the step control needs an absolute error scale)",
                    ));
                }
                positive("[integrator] dt", dt)?;
                if let Some(h) = guard_step {
                    positive("[integrator] guard_step", h)?;
                }
                if let Some(h) = max_step {
                    positive("[integrator] max_step", h)?;
                }
                if !self.integrator.is_adaptive() {
                    max_step_count("[integrator] dt", self.duration, dt)?;
                }
            }
            Integrator::Structural { dt, dt_flight, .. } => {
                positive("[integrator] dt", dt)?;
                positive("[integrator] dt_flight", dt_flight)?;
                if dt_flight < dt {
                    return Err(invalid(
                        "[integrator] dt_flight",
                        dt_flight,
                        "must be >= dt",
                    ));
                }
                max_step_count("[integrator] dt_flight", self.duration, dt_flight)?;
                if self.damping > 0.0 {
                    return Err(invalid(
                        "[contact] damping",
                        self.damping,
                        "the structural methods take no velocity-dependent contact force; use a first-order method (e.g. radau5) with damping",
                    ));
                }
            }
        }
        plan::check_ranges(self)?;
        let check = |key, body: Body| -> Result<(), BallDropError> {
            if let Body::Elastic { e, nu } = body {
                Body::elastic(e, nu).map_err(|source| BallDropError::Material { key, source })?;
            }
            Ok(())
        };
        check("[ball]", self.ball)?;
        check("[surface]", self.surface)?;
        Material::combine(self.ball, self.surface).map_err(|source| BallDropError::Material {
            key: "[ball]/[surface]",
            source,
        })
    }

    /// `true` if the ball starts at the surface and is pressed into it at once (height 0 and
    /// moving down, or at rest under gravity): the first impact starts at t = 0 with the
    /// speed `−v₀`.
    pub fn starts_in_contact(&self) -> bool {
        self.height == 0.0 && (self.velocity < 0.0 || (self.velocity == 0.0 && self.gravity > 0.0))
    }

    /// Speed at the first impact, `√(v₀² + 2 g h)` for a ball moving down or at rest
    /// (a ball thrown upward returns with the same speed) \[m/s\].
    pub fn impact_speed(&self) -> f64 {
        (self.velocity * self.velocity + 2.0 * self.gravity * self.height).sqrt()
    }

    /// The energy scale `E_ref` of `energy_drift` (module documentation) \[J\].
    pub fn energy_scale(&self) -> f64 {
        let kinetic = 0.5 * self.mass * self.impact_speed().powi(2);
        let r = match self.shape {
            BallShape::Sphere { radius } => radius,
            BallShape::Ellipsoid { radius_x, radius_y } => radius_x.min(radius_y),
        };
        if kinetic > 0.0 {
            kinetic
        } else if self.gravity > 0.0 {
            self.mass * self.gravity * r
        } else {
            1.0
        }
    }

    /// Run the simulation. With `record_series = false` only the events, the final state and
    /// the statistics are kept (benchmarks).
    pub fn simulate(&self, record_series: bool) -> Result<BallDropResult, BallDropError> {
        self.simulate_observed(record_series, &mut |_| ControlFlow::Continue(()))
    }

    /// [`simulate`](Self::simulate) with an `observer` called after every accepted step short
    /// of the end; `ControlFlow::Break` stops the run there and returns what is complete with
    /// `completed = false` (an interrupt, a wall-clock budget).
    pub fn simulate_observed(
        &self,
        record_series: bool,
        observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
    ) -> Result<BallDropResult, BallDropError> {
        let material = self.validate()?;
        let k = hertz_constant(&self.shape, &material)?;
        let reference = HertzImpact::new(self.mass, k, self.impact_speed(), self.gravity);
        let model = match self.model {
            ForceModel::Hertz => ContactForce::hertz(&self.shape, &material, self.damping)?,
            ForceModel::Bem { elements, tol } => {
                // The largest patch: the Hertz approach at the first impact from the energy
                // balance (the later impacts are no faster), or the static approach under m g.
                let approach = reference
                    .max_approach
                    .max((self.mass * self.gravity / k).powf(2.0 / 3.0));
                if approach.is_nan() || approach <= 0.0 {
                    return Err(invalid(
                        "[initial] velocity",
                        self.velocity,
                        "the BEM model needs an impact (a non-zero impact speed or gravity) to size its grid",
                    ));
                }
                ContactForce::bem(&self.shape, material, approach, elements, tol, self.damping)?
            }
        };
        let interval = self.output_interval.unwrap_or(self.duration / 2000.0);
        let (run_plan, integrator) = plan::plan(self, k, &reference)?;
        let planned = BallDrop {
            integrator,
            ..self.clone()
        };
        let start = Instant::now();
        let mut run = match planned.integrator {
            Integrator::Ode { .. } => {
                let recording = (interval, record_series, run_plan.step_budget());
                first_order::run(&planned, model, &reference, recording, observer)?
            }
            Integrator::Structural { .. } => {
                second_order::run(&planned, model, (interval, record_series), observer)?
            }
        };
        let wall_time_s = start.elapsed().as_secs_f64();
        let scale = self.energy_scale();
        let e0 = 0.5 * self.mass * self.velocity * self.velocity
            + self.mass * self.gravity * self.height;
        let energy_drift = (run.final_energy - e0) / scale;
        let energy_drift_max = if record_series && !run.samples.is_empty() {
            Some(
                run.samples
                    .iter()
                    .map(|s| ((s.energy - e0) / scale).abs())
                    .fold(0.0, f64::max),
            )
        } else {
            None
        };
        for imp in &mut run.impacts {
            imp.restitution = imp
                .rebound_velocity
                .map(|vr| vr / imp.impact_velocity)
                .filter(|e| e.is_finite());
        }
        let complete: Vec<f64> = run.impacts.iter().filter_map(|i| i.restitution).collect();
        let restitution = if complete.is_empty() {
            None
        } else {
            Some(complete.iter().sum::<f64>() / complete.len() as f64)
        };
        let step_ratio = step_ratio(&planned, &run_plan);
        let mut accuracy_flags = Vec::new();
        if energy_drift.is_nan() || energy_drift.abs() > plan::ENERGY_DRIFT_LIMIT {
            accuracy_flags.push(format!(
                "energy drift {energy_drift:.3e} exceeds {:.0e} of the impact energy",
                plan::ENERGY_DRIFT_LIMIT
            ));
        }
        if let Some(r) = step_ratio.filter(|r| *r > plan::STEP_RATIO_LIMIT) {
            accuracy_flags.push(format!(
                "step / contact time {r:.3e} exceeds {:.0e} (contact time {:.3e} s)",
                plan::STEP_RATIO_LIMIT,
                run_plan.contact_time
            ));
        }
        Ok(BallDropResult {
            samples: run.samples,
            impacts: run.impacts,
            restitution,
            initial_energy: e0,
            energy_scale: scale,
            energy_drift,
            energy_drift_max,
            stats: run.stats,
            wall_time_s,
            reference,
            hertz_constant: k,
            final_time: run.final_time,
            completed: run.completed,
            plan: run_plan,
            step_ratio,
            accuracy_flags,
        })
    }
}

/// The step in contact over the contact time: the fixed step, or for the adaptive methods
/// the contact guard's cap (`None` when there is no contact time scale).
fn step_ratio(planned: &BallDrop, run_plan: &RunPlan) -> Option<f64> {
    let tc = run_plan.contact_time;
    if !(tc.is_finite() && tc > 0.0) {
        return None;
    }
    let h = match (run_plan.contact_step, planned.integrator) {
        (Some(h), _) => h,
        (None, Integrator::Ode { guard_step, .. }) => guard_step.unwrap_or(tc / 50.0),
        (None, Integrator::Structural { dt, .. }) => dt,
    };
    Some(h / tc)
}

/// Mass of a sphere of radius `r` \[m\] and density `rho` \[kg/m³\]: `(4/3)π r³ ρ`.
pub fn sphere_mass(r: f64, rho: f64) -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * r.powi(3) * rho
}

fn positive(key: &'static str, v: f64) -> Result<(), BallDropError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(key, v, "must be finite and > 0"))
    }
}

/// Refuse runs of more than 1e9 steps (a mistyped step size).
fn max_step_count(key: &'static str, duration: f64, dt: f64) -> Result<(), BallDropError> {
    if duration / dt > 1e9 {
        return Err(invalid(
            key,
            dt,
            &format!("{:.1e} steps over the duration; at most 1e9", duration / dt),
        ));
    }
    Ok(())
}

/// What a driver returns.
struct RunOutput {
    samples: Vec<Sample>,
    impacts: Vec<Impact>,
    final_energy: f64,
    final_time: f64,
    /// `false` when the observer stopped the run.
    completed: bool,
    stats: RunStats,
}
