//! The cost of a run estimated before it starts: steps × work per step, in "operations" (a
//! count of the dominant loops whose constants are calibrated so that 1e9 operations take
//! about a second of one core of the development machine in a release build; good to a small
//! factor), refused above a limit so that a mistyped step or duration is an error in a
//! second, not a run of months.
//!
//! The default limit [`MAX_WORK`] (1e16 operations, months of one core) is far above any
//! real use — a 16-car train (64 wheels, 400 m) with boundary-element contact crossing a
//! 100 m bridge at Δt = 1e-5 s is about 1.3e14, a run of a day and a half — and is raised or
//! lowered with
//! [`LoadOptions::max_work`](super::LoadOptions::max_work) (`dyncontact run --max-work`).
//!
//! Per step (n modes, a axles or wheels):
//! * `moving_load`, exact modal step: `n (10 + 30 a)` (mode shapes at every axle);
//!   a structural method adds `8 n²` (its dense n × n matrix–vector products);
//! * `vehicle_bridge`: `4 (8 N² + a c)` with `N = n + 2a` unknowns, 4 coupling iterations and
//!   `c` the contact law's cost (rigid or Hertz 200; boundary elements: 3 solves of
//!   `2 · 4e log₂(4e)` for `e` elements, `bem_solve`), × 6 with Radau5 (three stages,
//!   sub-steps);
//! * `ball_drop`: the estimated steps of its plan ([`crate::ball_drop::plan`]) × 2000, plus
//!   per estimated contact step 40 BEM solves (`BALL_SOLVES_PER_STEP`).
//!
//! A `contact` case is one solve and has no estimate here.

use super::{ConfigError, ScenarioConfig, checks};
use crate::ball_drop::ForceModel;
use crate::vehicle_bridge::ContactModel;

/// Default largest estimated work of a run \[floating-point operations\] (module
/// documentation).
pub const MAX_WORK: f64 = 1e16;

/// One step of the ball drop's integrators with the Hertz law (a Radau5 step with its Newton
/// iterations and the event functions on the dense output) \[operations\].
const BALL_STEP: f64 = 2000.0;
/// Boundary-element solves per ball-drop step in contact, counted as warm-started solves:
/// Radau5 evaluates the law ≈ 10 times per step (measured 9.4), each at a new approach and
/// about 4 times the cost of a warm-started solve (calibrated on ball_drop_bem.toml: 0.8 s).
const BALL_SOLVES_PER_STEP: f64 = 40.0;

/// One boundary-element solve on `e` elements, `2 · 4e log₂ 4e` (FFT convolutions on the
/// doubled grid; calibrated: a warm-started 32 × 32 solve of the vehicle–bridge step takes
/// ≈ 0.1 ms) \[operations\].
fn bem_solve(e: f64) -> f64 {
    2.0 * 4.0 * e * (4.0 * e).log2().max(1.0)
}

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
        ScenarioConfig::Sweep(c) => {
            let n = c.bridge.basis.n_modes() as f64;
            let length = c.bridge.basis.length();
            let mut steps = 0.0;
            let mut axle_steps = 0.0;
            for t in &c.spec.trains {
                let (span, axles) = (t.length(), t.axles(c.spec.gravity).map_or(0, |a| a.len()));
                for &v in &c.spec.speeds {
                    let s = ((length + span) / v + c.spec.free_vibration) / c.spec.dt;
                    steps += s;
                    // Axles on the span at a time: about axles × L / (L + train length).
                    axle_steps += s * axles as f64 * length / (length + span);
                }
            }
            Some(WorkEstimate {
                steps,
                per_step: n * (10.0 + 3.0 * c.spec.points.len() as f64)
                    + 20.0 * axle_steps / steps.max(1.0),
                keys: "speeds.from/to/step, trains.names, integrator.dt, bridge.modes",
            })
        }
        ScenarioConfig::VehicleBridge(v) => {
            let s = &v.scenario;
            let wheels = s.wheels.len() as f64;
            let unknowns = s.bridge.n_modes() as f64 + 2.0 * wheels;
            let contact = match s.contact {
                ContactModel::Rigid | ContactModel::Hertz => 200.0,
                ContactModel::Bem { elements, .. } => 3.0 * bem_solve((elements * elements) as f64),
                // Every evaluation sets up its patch solvers afresh (no warm start): about
                // twice the work of a warm-started solve.
                ContactModel::BemProfiles(ref p) => {
                    6.0 * bem_solve((p.elements * p.elements) as f64)
                }
            };
            let radau = match s.integrator {
                crate::vehicle_bridge::Integrator::Radau5(_) => 6.0,
                _ => 1.0,
            };
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
        ScenarioConfig::BallDrop(b) => {
            // An invalid or refused scenario is reported by the run itself.
            let plan = b.scenario.plan().ok()?;
            let contact = match b.scenario.model {
                ForceModel::Hertz => 0.0,
                ForceModel::Bem { elements, .. } => {
                    BALL_SOLVES_PER_STEP * bem_solve((elements * elements) as f64)
                }
            };
            Some(WorkEstimate {
                steps: plan.estimated_steps,
                per_step: BALL_STEP + contact * plan.contact_steps / plan.estimated_steps.max(1.0),
                keys: "duration, integrator.dt, integrator.dt_flight, initial.height, initial.velocity, contact.model, contact.elements",
            })
        }
        ScenarioConfig::Contact(_) => None,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{LoadOptions, load};
    use std::path::Path;

    fn example(name: &str) -> String {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples")
            .join(name);
        std::fs::read_to_string(path).unwrap()
    }

    fn options(max_work: Option<f64>) -> LoadOptions {
        LoadOptions {
            max_work,
            ..LoadOptions::default()
        }
    }

    /// The real use of the module documentation: 64 BEM wheels (16 four-axle cars, 400 m)
    /// crossing a 100 m bridge with 20 modes at Δt = 1e-5 s is accepted by the default limit,
    /// and its estimate is 1.67e6 steps × 7.6e7 operations ≈ 1.3e14.
    #[test]
    fn a_long_bem_train_is_accepted() {
        let base = example("vehicle_bridge_default.toml");
        let wheel = base
            .split("[[vehicle.wheels]]")
            .nth(1)
            .unwrap()
            .split("[contact]")
            .next()
            .unwrap()
            .to_string();
        let mut text = base
            .replace(&format!("[[vehicle.wheels]]{wheel}"), "")
            .replace("length = 25.0", "length = 100.0")
            .replace("dt = 2.5e-4", "dt = 1e-5")
            .replace("every = 4", "every = 100");
        for k in 0..64 {
            let w = wheel.replace(
                "position = 0.0",
                &format!("position = {}", -6.25 * k as f64),
            );
            text.push_str(&format!("\n[[vehicle.wheels]]{w}"));
        }
        let config = load(&text, Path::new("."), &options(None)).unwrap();
        let w = estimate(&config).unwrap();
        assert!(
            (w.steps - (100.0 + 6.25 * 63.0) / 30.0 / 1e-5).abs() < 2.0,
            "{w:?}"
        );
        assert!(w.total() > 1e14 && w.total() < MAX_WORK / 10.0, "{w:?}");
    }

    /// Every shipped ball-drop, moving-load and vehicle–bridge example is far below the limit
    /// and below the fuzz test's budget of 5e9 (about 5 s).
    #[test]
    fn the_examples_are_far_below_the_limit() {
        for name in [
            "ball_drop_bem.toml",
            "ball_drop_damped_ellipsoid.toml",
            "ball_drop_steel.toml",
            "moving_load_fryba.toml",
            "moving_load_two_span_train.toml",
            "vehicle_bridge_biggs.toml",
            "vehicle_bridge_braking.toml",
            "vehicle_bridge_default.toml",
            "vehicle_bridge_radau5.toml",
            "vehicle_bridge_two_span_flat.toml",
        ] {
            let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
            let config = load(&example(name), &base, &options(None)).unwrap();
            let total = estimate(&config).unwrap().total();
            eprintln!("{name}: {total:.3e} operations");
            assert!(total < 5e9, "{name}: {total:e}");
        }
    }

    /// A crawl at a tiny step is refused with the estimate and the keys that drive it; a
    /// larger `max_work` accepts it.
    #[test]
    fn an_absurd_run_is_refused_with_its_estimate() {
        let text = example("moving_load_fryba.toml")
            .replace("speed = 27.78", "speed = 0.01")
            .replace("dt = 1e-4", "dt = 1e-5")
            .replace("[output]", "[output]\nevery = 10000");
        // 2500 s / 1e-5 s = 2.5e8 steps > the 1e8-step limit: a smaller case for the work.
        let text = text.replace("speed = 0.01", "speed = 0.05");
        // 5.02e7 steps × (20 modes × 40 + 8 × 20² Newmark) = 2.0e11 operations.
        let message = match load(&text, Path::new("."), &options(Some(1e11))) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("accepted"),
        };
        assert!(
            message.contains("time steps × 4000 operations per step")
                && message.contains("integrator.dt")
                && message.contains("--max-work"),
            "{message}"
        );
        assert!(load(&text, Path::new("."), &options(None)).is_ok());
    }
}
