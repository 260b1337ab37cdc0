//! What a ball-drop run returns: the time series, the impacts, the statistics and the
//! accuracy indicators.

use super::{HertzImpact, RunPlan};

/// One recorded point of the time series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time \[s\].
    pub t: f64,
    /// Height of the lowest point \[m\].
    pub z: f64,
    /// Velocity \[m/s\].
    pub v: f64,
    /// Acceleration `F/m − g` \[m/s²\].
    pub a: f64,
    /// Approach δ = max(0, −z) \[m\].
    pub approach: f64,
    /// Contact force F \[N\].
    pub force: f64,
    /// Total energy `½ m v² + m g z + W(δ) + D` \[J\].
    pub energy: f64,
}

/// One impact.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Impact {
    /// Contact start \[s\].
    pub time: f64,
    /// Speed at contact start \[m/s\] (positive).
    pub impact_velocity: f64,
    /// Largest approach \[m\], located inside the step by the dense output.
    pub max_approach: f64,
    /// Largest contact force \[N\], located inside the step by the dense output.
    pub peak_force: f64,
    /// Contact end − start \[s\] (`None` if the run ended in contact).
    pub contact_duration: Option<f64>,
    /// Upward speed at contact end \[m/s\].
    pub rebound_velocity: Option<f64>,
    /// `rebound_velocity / impact_velocity`.
    pub restitution: Option<f64>,
}

impl Impact {
    pub(super) fn start(time: f64, speed: f64) -> Self {
        Self {
            time,
            impact_velocity: speed,
            max_approach: 0.0,
            peak_force: 0.0,
            contact_duration: None,
            rebound_velocity: None,
            restitution: None,
        }
    }
}

/// Run statistics.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RunStats {
    /// The method's name.
    pub method: &'static str,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps.
    pub rejected_steps: usize,
    /// Right-hand side / internal force evaluations.
    pub f_evals: usize,
    /// Jacobian / tangent evaluations.
    pub jacobian_evals: usize,
    /// LU factorisations.
    pub lu_decompositions: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Steps undone by the contact guard (first-order) or replaced by a landing step
    /// (structural).
    pub guard_retries: usize,
    /// Half-space solves (BEM model).
    pub contact_solves: usize,
}

/// Result of [`BallDrop::simulate`](super::BallDrop::simulate).
#[derive(Debug, Clone, PartialEq)]
pub struct BallDropResult {
    /// Time series (every step in contact, free flight every `output_interval`).
    pub samples: Vec<Sample>,
    /// Impacts in time order.
    pub impacts: Vec<Impact>,
    /// Mean restitution over the completed impacts.
    pub restitution: Option<f64>,
    /// Initial energy E₀ \[J\] (potential energy measured from the surface).
    pub initial_energy: f64,
    /// `E_ref` \[J\].
    pub energy_scale: f64,
    /// `(E(t_end) − E₀)/E_ref`.
    pub energy_drift: f64,
    /// `max |E(t) − E₀|/E_ref` over the recorded samples.
    pub energy_drift_max: Option<f64>,
    /// Integrator counters.
    pub stats: RunStats,
    /// Wall time of the integration \[s\].
    pub wall_time_s: f64,
    /// Hertz closed form for the first impact.
    pub reference: HertzImpact,
    /// Hertz constant K of `F = K δ^{3/2}` \[N/m^{3/2}\].
    pub hertz_constant: f64,
    /// Time reached \[s\] (`duration` when `completed`).
    pub final_time: f64,
    /// `false` when the observer of [`simulate_observed`](super::BallDrop::simulate_observed)
    /// stopped the run before `duration` (the series, impacts and energy end at `final_time`).
    pub completed: bool,
    /// The run's plan: contact time scale, the fixed step used in contact (refined
    /// automatically to `t_c/50` when the given one was longer), the estimated step count.
    pub plan: RunPlan,
    /// Step in contact / contact time (`None` without a contact time scale).
    pub step_ratio: Option<f64>,
    /// Accuracy warnings: `|energy_drift|` above [`ENERGY_DRIFT_LIMIT`](super::plan::ENERGY_DRIFT_LIMIT) or `step_ratio`
    /// above [`STEP_RATIO_LIMIT`](super::plan::STEP_RATIO_LIMIT); empty when neither is exceeded.
    pub accuracy_flags: Vec<String>,
}

/// Where a run is: given to the observer of
/// [`BallDrop::simulate_observed`](super::BallDrop::simulate_observed) after every accepted step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Time reached \[s\].
    pub t: f64,
    /// End time of the run (`duration`) \[s\].
    pub end: f64,
    /// Accepted steps so far.
    pub steps: usize,
}
