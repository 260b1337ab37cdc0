//! Test fixtures shared by the `sim` integration tests (`mod support;` in each test file):
//! reading scenario texts and the examples, running a sweep's passages, building a
//! vehicle–bridge simulation with its vehicles (and its track), the exact moving-load response
//! of a `kind = "moving_load"` text, the closed-form static influence line of a simply
//! supported span, and the relative difference of two time histories.
// Each test crate uses a subset of these helpers.
#![allow(dead_code)]

use std::path::Path;

use sim::config::sweep::SweepConfig;
use sim::config::{self, LoadOptions, ScenarioConfig};
use sim::sweep::{Passage, Shard, run};
use sim::vehicle_bridge::Simulation;

/// A scenario text read with the default options (relative paths from `.`).
pub fn load(text: &str) -> Result<ScenarioConfig, String> {
    config::load(text, Path::new("."), &LoadOptions::default()).map_err(|e| e.to_string())
}

/// A `kind = "sweep"` text read as its configuration (panics on an error or another kind).
pub fn sweep_config(text: &str) -> SweepConfig {
    match load(text) {
        Ok(ScenarioConfig::Sweep(c)) => *c,
        Ok(_) => panic!("not a sweep"),
        Err(e) => panic!("{e}"),
    }
}

/// Every passage of a sweep, in one shard, never interrupted.
pub fn passages(c: &SweepConfig) -> Vec<Passage> {
    run(
        c.bridge.basis.as_ref(),
        &c.bridge.damping,
        &c.spec,
        Shard::ALL,
        &|| true,
    )
    .unwrap()
}

/// The text of `examples/NAME` of the repository.
pub fn example(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    std::fs::read_to_string(path).unwrap()
}

/// A `kind = "vehicle_bridge"` text as a simulation with its vehicles, and its track when it
/// has one (panics on an error).
pub fn simulation(text: &str) -> Simulation {
    match load(text).unwrap_or_else(|e| panic!("{e}")) {
        ScenarioConfig::VehicleBridge(mut v) => {
            let parts = v.take_parts();
            Simulation::with_parts(v.scenario, parts).unwrap()
        }
        _ => panic!("not vehicle_bridge"),
    }
}

/// The exact modal moving-load response (`beam::simulate_moving_loads`) of a
/// `kind = "moving_load"` text at step `dt` for `duration` s at the output `points` \[m\].
pub fn moving_load_response(
    text: &str,
    dt: f64,
    duration: f64,
    points: &[f64],
) -> beam::MovingLoadResponse {
    let m = match load(text).unwrap_or_else(|e| panic!("{e}")) {
        ScenarioConfig::MovingLoad(m) => *m,
        _ => panic!("not moving_load"),
    };
    let settings = beam::MovingLoadSettings::new(dt, duration);
    beam::simulate_moving_loads(
        m.bridge.basis.as_ref(),
        &m.bridge.damping,
        &m.loads,
        &settings,
        points,
    )
    .unwrap()
}

/// Midspan deflection of a simply supported span (length `l`, bending stiffness `ei`) under
/// a force `p` at `a` (closed form, Maxwell–Betti: P a (3L² − 4a²)/(48 EI) for a ≤ L/2;
/// references.md §D1.1); 0 off the span.
pub fn midspan_influence(l: f64, ei: f64, a: f64, p: f64) -> f64 {
    if !(0.0..=l).contains(&a) {
        return 0.0;
    }
    let a = a.min(l - a);
    p * a * (3.0 * l * l - 4.0 * a * a) / (48.0 * ei)
}

/// Largest difference of two histories relative to the largest magnitude of the reference `b`
/// (time histories: one row per step).
pub fn relative_difference(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .flatten()
        .zip(b.iter().flatten())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}
