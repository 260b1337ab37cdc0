//! summary.json of a ball-drop run (docs/ball_drop.md lists the keys). Typed, so that a
//! non-finite number is written as `null` and listed under `"non_finite"` by
//! [`crate::output::json_text`] instead of vanishing silently.

use serde::Serialize;
use sim::ball_drop::{BallDropResult, ForceModel, HertzImpact, Impact, Integrator, RunStats};
use sim::config::ball_drop::BallDropConfig;

/// The whole summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    pub kind: &'static str,
    /// False when the run stopped early (interrupted): the outputs then end at `time_reached`
    /// and timeseries.csv is named timeseries.partial.csv.
    pub completed: bool,
    /// Simulated time reached \[s\] (the duration when `completed`).
    pub time_reached: f64,
    /// Why the run stopped early (absent when `completed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_by: Option<String>,
    pub mass: f64,
    pub hertz_constant: f64,
    pub contact: Contact,
    /// The Hertz impact at the first impact speed.
    pub closed_form: HertzImpact,
    pub impacts: Vec<Impact>,
    pub restitution: Option<f64>,
    pub initial_energy: f64,
    pub energy_drift: f64,
    pub energy_drift_max: Option<f64>,
    pub accuracy: Accuracy,
    pub integrator: IntegratorJson,
    pub final_time: f64,
    pub samples: usize,
    pub wall_time_s: f64,
}

/// `contact`.
#[derive(Debug, Serialize)]
pub struct Contact {
    pub model: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tol: Option<f64>,
    pub damping: f64,
}

/// `accuracy`: the run's own accuracy indicators.
#[derive(Debug, Serialize)]
pub struct Accuracy {
    pub contact_time: f64,
    pub contact_step: Option<f64>,
    pub step_refined: bool,
    pub step_ratio: Option<f64>,
    pub estimated_steps: f64,
    pub energy_drift_limit: f64,
    pub step_ratio_limit: f64,
    pub flags: Vec<String>,
}

/// `integrator`: the method, its settings and its counters.
#[derive(Debug, Serialize)]
pub struct IntegratorJson {
    /// The settings of the method's kind (absent for the others; `null`: not given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rtol: Option<Option<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub atol: Option<Option<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt: Option<Option<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt_flight: Option<Option<f64>>,
    /// The method's name and counters.
    #[serde(flatten)]
    pub stats: RunStats,
}

/// The summary of run `r` of scenario `p`.
pub fn summary(p: &BallDropConfig, r: &BallDropResult) -> Summary {
    let sc = &p.scenario;
    let st = &r.stats;
    let (rtol, atol, dt) = p.settings;
    let (rtol, atol, dt, dt_flight) = match sc.integrator {
        Integrator::Ode { .. } if sc.integrator.is_adaptive() => {
            (Some(rtol), Some(atol), None, None)
        }
        Integrator::Ode { .. } => (None, None, Some(dt), None),
        Integrator::Structural { dt, dt_flight, .. } => {
            (None, None, Some(Some(dt)), Some(Some(dt_flight)))
        }
    };
    let contact = match sc.model {
        ForceModel::Hertz => Contact {
            model: "hertz",
            elements: None,
            tol: None,
            damping: sc.damping,
        },
        ForceModel::Bem { elements, tol } => Contact {
            model: "bem",
            elements: Some(elements),
            tol: Some(tol),
            damping: sc.damping,
        },
    };
    Summary {
        kind: "ball_drop",
        completed: r.completed,
        time_reached: r.final_time,
        stopped_by: (!r.completed).then(|| "interrupt (SIGINT or SIGTERM)".to_string()),
        mass: sc.mass,
        hertz_constant: r.hertz_constant,
        contact,
        closed_form: r.reference,
        impacts: r.impacts.clone(),
        restitution: r.restitution,
        initial_energy: r.initial_energy,
        energy_drift: r.energy_drift,
        energy_drift_max: r.energy_drift_max,
        accuracy: Accuracy {
            contact_time: r.plan.contact_time,
            contact_step: r.plan.contact_step,
            step_refined: r.plan.refined,
            step_ratio: r.step_ratio,
            estimated_steps: r.plan.estimated_steps,
            energy_drift_limit: sim::ball_drop::plan::ENERGY_DRIFT_LIMIT,
            step_ratio_limit: sim::ball_drop::plan::STEP_RATIO_LIMIT,
            flags: r.accuracy_flags.clone(),
        },
        integrator: IntegratorJson {
            rtol,
            atol,
            dt,
            dt_flight,
            stats: st.clone(),
        },
        final_time: r.final_time,
        samples: r.samples.len(),
        wall_time_s: r.wall_time_s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sim::config::ScenarioConfig;

    /// A NaN or infinite result is written as `null` and listed under `non_finite`; a finite
    /// run lists nothing.
    #[test]
    fn non_finite_values_are_null_and_listed() {
        let text = include_str!("../../../examples/ball_drop_steel.toml");
        let options = sim::config::LoadOptions::default();
        let Ok(ScenarioConfig::BallDrop(p)) =
            sim::config::load(text, std::path::Path::new("."), &options)
        else {
            panic!("the example is a ball drop")
        };
        let mut r = p.scenario.simulate(false).unwrap();
        let clean = crate::output::json_text(&summary(&p, &r)).unwrap();
        assert!(!clean.contains("non_finite"), "{clean}");
        r.energy_drift = f64::NAN;
        r.impacts[0].peak_force = f64::INFINITY;
        let text = crate::output::json_text(&summary(&p, &r)).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(v["energy_drift"].is_null() && v["impacts"][0]["peak_force"].is_null());
        assert_eq!(
            v["non_finite"]["fields"],
            serde_json::json!(["energy_drift", "impacts[0].peak_force"])
        );
        assert!(!text.contains(": NaN") && !text.contains(": inf"));
    }
}
