//! The summary of a ball-drop run (the CLI's summary.json, the Python package's `run`;
//! docs/ball_drop.md lists the keys) and the columns of its time series. Typed, so that a
//! non-finite number is written as `null` (and listed by the CLI) instead of vanishing.

use serde::Serialize;

use crate::ball_drop::{
    BallDropResult, ForceModel, HertzImpact, Impact, Integrator, RunStats, Sample,
};
use crate::config::ball_drop::BallDropConfig;

/// The columns of a ball drop's time series (SI units: s, m, m/s, m/s², m, N, J).
pub const COLUMNS: [&str; 7] = [
    "t_s",
    "z_m",
    "v_m_s",
    "a_m_s2",
    "approach_m",
    "force_n",
    "energy_j",
];

/// The values of one sample in the order of [`COLUMNS`].
pub fn row(s: &Sample) -> [f64; 7] {
    [s.t, s.z, s.v, s.a, s.approach, s.force, s.energy]
}

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
            energy_drift_limit: crate::ball_drop::plan::ENERGY_DRIFT_LIMIT,
            step_ratio_limit: crate::ball_drop::plan::STEP_RATIO_LIMIT,
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
