//! Planning a ball-drop run before it starts: physical ranges of the inputs, the shortest time
//! scale (the Hertz contact duration), the automatic refinement of a fixed step that is too
//! long for it, and an up-front estimate of the step count that refuses absurd runs.
//!
//! # Contact time scale
//! `t_c = 2.9432752 (m²/(R E*² v))^{1/5}` (references.md §D1.4; `HertzImpact::contact_duration`,
//! which uses the Hertz constant `K` of the actual geometry). A ball that starts at rest on
//! the surface has no impact speed; its time scale is then the half-period `π/ω` of the
//! oscillation linearised at the largest approach under gravity,
//! `ω² = (3/2) K √δ* / m`. An impact so slow that this half-period (with the approach of a
//! ball released on the surface, `δ* = (5mg/(2K))^{2/3}`) is shorter than `t_c` ends at rest
//! on the surface: the shorter of the two is the time scale.
//!
//! # Step refinement
//! A fixed step longer than `t_c / STEPS_PER_CONTACT` is replaced by `t_c / STEPS_PER_CONTACT`
//! in contact (the structural methods keep `dt_flight` in free flight; the fixed-step
//! first-order methods take the refined step throughout). `STEPS_PER_CONTACT = 50`: the
//! second-order schemes' peak-force error scales as `(ω Δt)²` with `ω Δt ≈ π/N` over a
//! half-sine contact, which is 4e-3 at N = 50 (2.5e-2 at N = 20, too close to a 5 % claim
//! once the event location and the contact-start step are added); explicit Euler (first order)
//! stays inaccurate at any practical N and is flagged by its energy drift.

use super::{BallDrop, BallDropError, BallShape, ForceModel, HertzImpact, Integrator, invalid};

/// Fixed steps per contact duration (module documentation).
pub const STEPS_PER_CONTACT: f64 = 50.0;
/// Largest estimated step count of a run.
pub const MAX_STEPS: f64 = 2e7;
/// An adaptive run may take this many times its estimated steps (at least
/// [`MIN_STEP_BUDGET`], at most [`MAX_STEPS`]) before it is stopped with an error: the
/// estimate assumes elastic bounces, while a ball that comes to rest on the surface (damping,
/// or an L-stable method's numerical dissipation making the bounces ever shorter) stays in
/// contact with steps of `t_c/50` for the rest of the run.
pub const ADAPTIVE_STEP_FACTOR: f64 = 20.0;
/// Smallest step budget of an adaptive run.
pub const MIN_STEP_BUDGET: f64 = 1e6;
/// Largest estimated boundary-element work of a run: contact steps × elements².
pub const MAX_BEM_WORK: f64 = 1e9;
/// `|energy_drift|` above which a result is flagged (1 % of the impact energy).
pub const ENERGY_DRIFT_LIMIT: f64 = 1e-2;
/// Step / contact-time ratio above which a result is flagged (`1/STEPS_PER_CONTACT`).
pub const STEP_RATIO_LIMIT: f64 = 1.0 / STEPS_PER_CONTACT;

/// Physical ranges of the scenario's inputs (SI): `(key, min, max)`.
pub const RANGES: [(&str, f64, f64); 6] = [
    ("[ball] mass", 1e-15, 1e6),
    ("[ball] radius", 1e-7, 100.0),
    ("gravity", 0.0, 1e3),
    ("[initial] height", 0.0, 1e4),
    ("[initial] velocity", -1e3, 1e3),
    ("duration", 1e-12, 1e4),
];

/// Check `value` against its entry of [`RANGES`].
fn in_range(key: &'static str, value: f64) -> Result<(), BallDropError> {
    let (_, lo, hi) = RANGES
        .iter()
        .find(|(k, _, _)| *k == key)
        .copied()
        .unwrap_or((key, f64::NEG_INFINITY, f64::INFINITY));
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(invalid(
            key,
            value,
            &format!("must lie in [{lo:e}, {hi:e}] (SI units)"),
        ))
    }
}

/// The physical ranges of mass, radii, gravity, height, velocity and duration.
pub(super) fn check_ranges(s: &BallDrop) -> Result<(), BallDropError> {
    in_range("[ball] mass", s.mass)?;
    match s.shape {
        BallShape::Sphere { radius } => in_range("[ball] radius", radius)?,
        BallShape::Ellipsoid { radius_x, radius_y } => {
            in_range("[ball] radius", radius_x)
                .map_err(|_| invalid("[ball] radius_x", radius_x, "must lie in [1e-7, 1e2] m"))?;
            in_range("[ball] radius", radius_y)
                .map_err(|_| invalid("[ball] radius_y", radius_y, "must lie in [1e-7, 1e2] m"))?;
        }
    }
    in_range("gravity", s.gravity)?;
    in_range("[initial] height", s.height)?;
    in_range("[initial] velocity", s.velocity)?;
    in_range("duration", s.duration)
}

/// What the plan decided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunPlan {
    /// The shortest time scale `t_c` \[s\] (infinite if the ball never touches).
    pub contact_time: f64,
    /// The fixed step used in contact \[s\] (`None` for the adaptive methods).
    pub contact_step: Option<f64>,
    /// `true` if the given fixed step was longer than `t_c / STEPS_PER_CONTACT` and was
    /// refined.
    pub refined: bool,
    /// Estimated number of steps of the run.
    pub estimated_steps: f64,
    /// Estimated steps in contact (each one a contact-law evaluation per stage; a
    /// boundary-element solve with `model = "bem"`).
    pub contact_steps: f64,
}

impl RunPlan {
    /// Most steps an adaptive run may take ([`ADAPTIVE_STEP_FACTOR`]).
    pub fn step_budget(&self) -> usize {
        (ADAPTIVE_STEP_FACTOR * self.estimated_steps).clamp(MIN_STEP_BUDGET, MAX_STEPS) as usize
    }
}

impl BallDrop {
    /// The plan of the run [`BallDrop::simulate`] would make (the scenario is validated first;
    /// an absurd run is an error here too).
    pub fn plan(&self) -> Result<RunPlan, BallDropError> {
        let material = self.validate()?;
        let k = super::hertz_constant(&self.shape, &material)?;
        let reference = HertzImpact::new(self.mass, k, self.impact_speed(), self.gravity);
        plan(self, k, &reference).map(|(p, _)| p)
    }
}

/// The time scale of the contact (module documentation).
pub(super) fn contact_time(s: &BallDrop, k: f64, reference: &HertzImpact) -> f64 {
    let half_period = |d: f64| std::f64::consts::PI / (1.5 * k * d.sqrt() / s.mass).sqrt();
    let tc = reference.contact_duration;
    if tc.is_finite() && tc > 0.0 {
        // An impact far slower than the fall under gravity over the approach (a drop from a
        // height of nanometres) ends at rest on the surface: its time scale is that of a
        // ball released on the surface, δ* = (5 m g / (2K))^{2/3}, when that is shorter.
        let at_rest = (2.5 * s.mass * s.gravity / k).powf(2.0 / 3.0);
        return if at_rest > 0.0 {
            tc.min(half_period(at_rest))
        } else {
            tc
        };
    }
    let d = reference.max_approach;
    if d > 0.0 {
        half_period(d)
    } else {
        f64::INFINITY
    }
}

/// Refine the fixed step and estimate the run's cost; refuse absurd runs.
pub(super) fn plan(
    s: &BallDrop,
    k: f64,
    reference: &HertzImpact,
) -> Result<(RunPlan, Integrator), BallDropError> {
    let tc = contact_time(s, k, reference);
    let limit = tc / STEPS_PER_CONTACT;
    let mut integrator = s.integrator;
    let mut refined = false;
    let mut contact_step = None;
    match &mut integrator {
        Integrator::Ode { dt, .. } if !s.integrator.is_adaptive() => {
            if *dt > limit {
                *dt = limit;
                refined = true;
            }
            contact_step = Some(*dt);
        }
        Integrator::Structural { dt, .. } => {
            if *dt > limit {
                *dt = limit;
                refined = true;
            }
            contact_step = Some(*dt);
        }
        Integrator::Ode { .. } => {}
    }
    // Time in contact: every impact lasts about t_c; a ball thrown down or dropped returns
    // every 2 v/g. A ball at rest on the surface stays in contact throughout.
    let v = s.impact_speed();
    let impacts = if s.gravity > 0.0 && v > 0.0 {
        1.0 + s.duration / (2.0 * v / s.gravity + tc)
    } else {
        1.0
    };
    let contact_total = if v == 0.0 && s.gravity > 0.0 {
        s.duration
    } else {
        (impacts * tc).min(s.duration)
    };
    let contact_steps = match (&integrator, contact_step) {
        (_, Some(h)) => contact_total / h,
        (Integrator::Ode { guard_step, .. }, None) => {
            // Adaptive: the contact guard caps the step at h_c = t_c/50 in contact; about 50
            // more steps per impact for the approach, the rebound and the flight.
            contact_total
                / guard_step
                    .unwrap_or(limit)
                    .min(limit.max(f64::MIN_POSITIVE))
                + 50.0 * impacts
        }
        _ => 0.0,
    };
    let flight_steps = match integrator {
        Integrator::Structural { dt_flight, .. } => s.duration / dt_flight,
        Integrator::Ode { dt, .. } if !s.integrator.is_adaptive() => s.duration / dt,
        _ => 0.0,
    };
    let estimated_steps = if contact_step.is_some() && matches!(integrator, Integrator::Ode { .. })
    {
        flight_steps
    } else {
        contact_steps + flight_steps
    };
    let remedy = match integrator {
        Integrator::Ode { .. } if contact_step.is_some() => {
            "use an adaptive method (radau5) or a structural method with a longer `dt_flight`, or shorten `duration`"
        }
        Integrator::Structural { .. } => "increase `dt_flight` or shorten `duration`",
        _ => "shorten `duration`",
    };
    if estimated_steps.is_nan() || estimated_steps > MAX_STEPS {
        return Err(invalid(
            "duration",
            s.duration,
            &format!(
                "the run needs about {estimated_steps:.1e} steps (contact time {tc:.3e} s, {impacts:.1e} impacts), more than the limit {MAX_STEPS:.0e}: {remedy}"
            ),
        ));
    }
    if let ForceModel::Bem { elements, .. } = s.model {
        let work = contact_steps.min(estimated_steps) * (elements * elements) as f64;
        if work.is_nan() || work > MAX_BEM_WORK {
            return Err(invalid(
                "duration",
                s.duration,
                &format!(
                    "the BEM run needs about {:.1e} contact steps × {} elements = {work:.1e} element-solves (limit {MAX_BEM_WORK:.0e}; contact time {tc:.3e} s, {impacts:.1e} impacts): shorten `duration`, use fewer `[contact] elements`, or the Hertz model",
                    contact_steps.min(estimated_steps),
                    elements * elements
                ),
            ));
        }
    }
    Ok((
        RunPlan {
            contact_time: tc,
            contact_step,
            refined,
            estimated_steps,
            contact_steps: contact_steps.min(estimated_steps),
        },
        integrator,
    ))
}
