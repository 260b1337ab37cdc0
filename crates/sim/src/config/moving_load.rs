//! `kind = "moving_load"`: a force or a train of axle forces crossing the bridge at constant
//! speed (modal superposition; Frýba's problem, references.md §D1.1). Schema: docs/bridge.md.

use beam::{Axle, ModalIntegrator, MovingLoadSettings, MovingLoads};
use serde::Deserialize;

use super::ConfigError;
use super::bridge::{Bridge, BridgeSpec};
use super::checks::{self, ranges};
use super::integrator::StructuralParameters;

/// Default time step \[s\]: the exact modal step integrates piecewise-linear forcing exactly,
/// so the step only sets how finely the load path is sampled (0.1 mm at 1 m/s … 10 cm at
/// 1000 m/s is far below any span).
pub const DEFAULT_DT: f64 = 1e-4;
/// Default free vibration after the last axle has left: three periods of mode 1, at most this
/// long \[s\].
pub const DEFAULT_FREE_VIBRATION_MAX: f64 = 5.0;
/// Default number of recorded samples of the whole run (sets `output.every`).
pub const DEFAULT_SAMPLES: f64 = 20_000.0;

/// The scenario file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MovingLoadFile {
    /// `"moving_load"`.
    pub kind: String,
    /// The bridge.
    pub bridge: BridgeSpec,
    /// The moving load(s) ...
    pub load: Option<LoadSpec>,
    /// ... or a train (`[train]` with `speed`; each vehicle's static axle loads).
    pub train: Option<super::train::TrainTable>,
    /// Time integration.
    pub integrator: Option<IntegratorSpec>,
    /// Outputs.
    pub output: Option<OutputSpec>,
}

/// `[load]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// One force \[N\] ...
    pub force: Option<f64>,
    /// ... or axles [[offset behind the first axle (m), force (N)], ...].
    pub axles: Option<Vec<[f64; 2]>>,
    /// Speed \[m/s\].
    pub speed: f64,
}

/// `[integrator]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    /// "exact" (default: exact modal step for piecewise-linear forcing) or a structural method:
    /// newmark, hht, generalized_alpha, backward_euler, verlet, leapfrog, central_difference, ...
    pub method: Option<String>,
    /// Time step \[s\] (default [`DEFAULT_DT`]).
    pub dt: Option<f64>,
    /// Newmark β.
    pub beta: Option<f64>,
    /// Newmark γ.
    pub gamma: Option<f64>,
    /// HHT α.
    pub alpha: Option<f64>,
    /// Generalized-α ρ∞.
    pub rho_inf: Option<f64>,
}

/// `[output]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Extra response points \[m\] (midspan is always the first).
    pub points: Option<Vec<f64>>,
    /// Free vibration simulated after the last axle leaves \[s\].
    pub free_vibration: Option<f64>,
    /// Record every n-th step (default: about [`DEFAULT_SAMPLES`] samples in all).
    pub every: Option<usize>,
}

/// A validated moving-load scenario.
pub struct MovingLoadConfig {
    /// The bridge.
    pub bridge: Bridge,
    /// The axle train.
    pub loads: MovingLoads,
    /// The integrator's name as given (`exact` or a structural method).
    pub integrator_name: String,
    /// Step, free-vibration time, output interval and integrator.
    pub settings: MovingLoadSettings,
    /// Response points \[m\]: midspan first.
    pub points: Vec<f64>,
}

fn integrator(
    spec: Option<&IntegratorSpec>,
) -> Result<(ModalIntegrator, String, f64), ConfigError> {
    let dt = spec.and_then(|s| s.dt).unwrap_or(DEFAULT_DT);
    if !dt.is_finite() || dt <= 0.0 {
        bail!("[integrator] `dt` = {dt}: must be a positive number of seconds");
    }
    ranges::TIME_STEP.check("integrator.dt", dt)?;
    let name = spec
        .and_then(|s| s.method.clone())
        .unwrap_or_else(|| "exact".into());
    let params = StructuralParameters {
        beta: spec.and_then(|s| s.beta),
        gamma: spec.and_then(|s| s.gamma),
        alpha: spec.and_then(|s| s.alpha),
        rho_inf: spec.and_then(|s| s.rho_inf),
    };
    if name == "exact" {
        if let Some((key, _)) = params.list()?.first() {
            bail!("[integrator] `{key}` does not apply to method = \"exact\"");
        }
        return Ok((ModalIntegrator::ExactPiecewiseLinear, name, dt));
    }
    let method = params.method(&name, &["exact"])?;
    Ok((ModalIntegrator::Structural(method), name, dt))
}

fn loads(spec: &LoadSpec) -> Result<MovingLoads, ConfigError> {
    let axles = match (spec.force, &spec.axles) {
        (Some(f), None) => {
            ranges::FORCE.check("load.force", f)?;
            vec![Axle {
                offset: 0.0,
                force: f,
            }]
        }
        (None, Some(list)) => {
            checks::count("load.axles", list.len(), 1, super::checks::MAX_WHEELS)?;
            list.iter()
                .enumerate()
                .map(|(k, [offset, force])| {
                    ranges::POSITION.check(&format!("load.axles[{k}][0]"), *offset)?;
                    ranges::FORCE.check(&format!("load.axles[{k}][1]"), *force)?;
                    Ok(Axle {
                        offset: *offset,
                        force: *force,
                    })
                })
                .collect::<Result<_, ConfigError>>()?
        }
        (Some(_), Some(_)) => bail!("[load]: give either `force` or `axles`, not both"),
        (None, None) => bail!("[load]: missing `force` [N] (or `axles`)"),
    };
    let loads = MovingLoads::train(axles, spec.speed).map_err(|e| invalid!("[load] {e}"))?;
    ranges::SPEED.check("load.speed", spec.speed)?;
    Ok(loads)
}

/// The axle loads of a `[train]` (each vehicle's statics), at `train.speed`.
fn train_loads(table: &super::train::TrainTable) -> Result<MovingLoads, ConfigError> {
    let train = super::train::build(table, "train")?;
    let speed = table
        .speed
        .ok_or_else(|| invalid!("[train]: missing `speed` [m/s]"))?;
    ranges::SPEED.check("train.speed", speed)?;
    if table.position.is_some() {
        bail!("[train] `position` does not apply to moving_load (the first axle enters at t = 0)");
    }
    let axles = train
        .axles(crate::vehicle_bridge::GRAVITY)
        .map_err(|e| invalid!("[train] {e}"))?
        .into_iter()
        .map(|a| Axle {
            offset: a.offset,
            force: a.load,
        })
        .collect();
    MovingLoads::train(axles, speed).map_err(|e| invalid!("[train] {e}"))
}

/// Validate a parsed file.
pub fn build(file: MovingLoadFile) -> Result<MovingLoadConfig, ConfigError> {
    if file.kind != "moving_load" {
        bail!("`kind` = \"{}\" is not a moving-load scenario", file.kind);
    }
    let bridge = file.bridge.build()?;
    let loads = match (&file.load, &file.train) {
        (Some(load), None) => loads(load)?,
        (None, Some(train)) => train_loads(train)?,
        (Some(_), Some(_)) => bail!("give either [load] or [train], not both"),
        (None, None) => bail!("missing [load] (a force or axles) or [train]"),
    };
    let (modal_integrator, integrator_name, dt) = integrator(file.integrator.as_ref())?;
    let length = bridge.basis.length();
    let omega1 = bridge
        .basis
        .circular_frequencies()
        .iter()
        .copied()
        .find(|w| *w > 0.0)
        .unwrap_or(1.0);
    let output = file.output.as_ref();
    let free = match output.and_then(|o| o.free_vibration) {
        Some(f) => checks::Range::closed(0.0, 1e6, "s").check("output.free_vibration", f)?,
        None => (3.0 * 2.0 * std::f64::consts::PI / omega1).min(DEFAULT_FREE_VIBRATION_MAX),
    };
    // "Midspan": L/2, or the longest span's midspan where L/2 is a support; without
    // `points`, a continuous bridge reports the midspan of every other span too.
    let mut points = vec![bridge.default_output_point().0];
    if output.and_then(|o| o.points.as_ref()).is_none() {
        points.extend(bridge.other_span_midpoints(points[0]));
    }
    if let Some(extra) = output.and_then(|o| o.points.as_deref()) {
        let extra = checks::points_on_span(extra, 0, length)?;
        points.extend(extra);
    }
    let total_steps = ((loads.exit_time(length) + free) / dt).ceil().max(1.0);
    checks::steps(
        "the passage (bridge.length / load.speed) plus output.free_vibration at integrator.dt",
        total_steps,
    )?;
    let every = match output.and_then(|o| o.every) {
        Some(0) => bail!("[output] `every` = 0: must be at least 1"),
        Some(e) => e,
        None => ((total_steps / DEFAULT_SAMPLES).ceil() as usize).max(1),
    };
    let rows = total_steps / every as f64 + 2.0;
    checks::output_rows("the run with output.every", rows)?;
    checks::memory(
        "the recorded time series (output.every, output.points)",
        rows * points.len() as f64,
        6.0 * 8.0,
    )?;
    let settings = MovingLoadSettings {
        dt,
        free_vibration_time: free,
        output_every: every,
        integrator: modal_integrator,
    };
    Ok(MovingLoadConfig {
        bridge,
        loads,
        integrator_name,
        settings,
        points,
    })
}
