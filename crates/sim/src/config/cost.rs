//! The cost of a run estimated before it starts: steps × work per step, in floating-point
//! operations (a rough count of the dominant loops, good to a small factor), refused above a
//! limit so that a mistyped step or duration is an error in a second, not a run of days.
//!
//! The default limit [`MAX_WORK`] (1e15 operations, about a day of a single core) is far above
//! any real use — a 16-car train (64 wheels) with boundary-element contact crossing a 100 m
//! bridge at Δt = 1e-5 s is about 3e14 — and is raised or lowered with
//! [`LoadOptions::max_work`](super::LoadOptions::max_work) (`dyncontact run --max-work`).
//!
//! Per step (n modes, a axles or wheels):
//! * `moving_load`, exact modal step: `n (10 + 30 a)` (mode shapes at every axle);
//!   a structural method adds `8 n²` (its dense n × n matrix–vector products);
//! * `vehicle_bridge`: `4 (8 N² + a c)` with `N = n + 2a` unknowns, 4 coupling iterations and
//!   `c` the contact law's cost (rigid or Hertz 200; boundary elements: an FFT convolution on
//!   the doubled grid per CG iteration, 20 iterations, 3 solves: `60 · 4 e log₂(4 e) · 5` for
//!   `e` elements), × 6 with Radau5 (three stages, sub-steps);
//! * `ball_drop` and `contact` runs are planned by their own models (the ball drop's step
//!   estimate, [`crate::ball_drop::plan`]) and have no estimate here.

use super::{ConfigError, ScenarioConfig, checks};
use crate::vehicle_bridge::ContactModel;

/// Default largest estimated work of a run \[floating-point operations\] (module
/// documentation).
pub const MAX_WORK: f64 = 1e15;

/// The estimated work of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct WorkEstimate {
    /// Time steps.
    pub steps: f64,
    /// Operations per step.
    pub per_step: f64,
    /// The keys that set the steps and the work per step (for the message).
    pub keys: &'static str,
}

impl WorkEstimate {
    /// Steps × work per step.
    pub fn total(&self) -> f64 {
        self.steps * self.per_step
    }
}

/// The estimate of `config` (`None` for the kinds planned elsewhere).
pub fn estimate(config: &ScenarioConfig) -> Option<WorkEstimate> {
    match config {
        ScenarioConfig::MovingLoad(m) => {
            let n = m.bridge.basis.n_modes() as f64;
            let axles = m.loads.axles().len() as f64;
            let exit = m.loads.exit_time(m.bridge.basis.length());
            let steps = ((exit + m.settings.free_vibration_time) / m.settings.dt).ceil();
            let structural = match m.settings.integrator {
                beam::ModalIntegrator::ExactPiecewiseLinear => 0.0,
                beam::ModalIntegrator::Structural(_) => 8.0 * n * n,
            };
            Some(WorkEstimate {
                steps,
                per_step: n * (10.0 + 30.0 * axles) + structural,
                keys: "integrator.dt, bridge.length / load.speed, output.free_vibration, bridge.modes, load.axles, integrator.method",
            })
        }
        ScenarioConfig::VehicleBridge(v) => {
            let s = &v.scenario;
            let wheels = s.wheels.len() as f64;
            let unknowns = s.bridge.n_modes() as f64 + 2.0 * wheels;
            let contact = match s.contact {
                ContactModel::Rigid | ContactModel::Hertz => 200.0,
                ContactModel::Bem { elements, .. } => {
                    let e = (elements * elements) as f64;
                    60.0 * 4.0 * e * (4.0 * e).log2().max(1.0) * 5.0
                }
            };
            let radau = if v.radau5.is_some() { 6.0 } else { 1.0 };
            let end = s.duration.unwrap_or_else(|| {
                let first = s
                    .wheels
                    .iter()
                    .map(|w| w.position)
                    .fold(f64::INFINITY, f64::min);
                ((s.bridge.length() - first) / s.speed).max(0.0)
            });
            Some(WorkEstimate {
                steps: (end / s.dt).ceil(),
                per_step: radau * 4.0 * (8.0 * unknowns * unknowns + wheels * contact),
                keys: "integrator.dt, integrator.duration (or bridge.length / vehicle.speed), bridge.modes, vehicle.wheels, contact.model, contact.grid, integrator.method",
            })
        }
        ScenarioConfig::BallDrop(_) | ScenarioConfig::Contact(_) => None,
    }
}

/// Refuse a run whose estimated work exceeds `limit` (the error states the estimate and the
/// keys that drive it).
pub fn check(config: &ScenarioConfig, limit: f64) -> Result<(), ConfigError> {
    let Some(w) = estimate(config) else {
        return Ok(());
    };
    let total = w.total();
    if total.is_finite() && total <= limit {
        return Ok(());
    }
    Err(ConfigError::TooLarge(format!(
        "the run needs about {} time steps × {} operations per step = {} operations, more than the limit {} (set by {}); enlarge the step or shorten the run, use fewer modes, wheels or contact elements, or raise the limit with --max-work",
        checks::number(w.steps),
        checks::number(w.per_step),
        checks::number(total),
        checks::number(limit),
        w.keys
    )))
}
