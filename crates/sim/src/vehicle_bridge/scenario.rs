//! The scenario: wheels, contact model, coupling settings, and their validation.

use beam::{ModalBasis, ModalDamping};
use integrate::structural::StructuralMethod;

use super::error::{check_non_negative, invalid, invalid_text};
use super::{ContactGeometry, Irregularity, MAX_STEPS, Radau5Spec, VehicleBridgeError};

/// Largest static sag of a body on its suspension \[m\] (a body frequency of 0.16 Hz).
pub const MAX_STATIC_SAG: f64 = 10.0;

/// One wheel (with its sprung body) of the vehicle; positions at t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelSpec {
    /// Position along the track at t = 0 \[m\] (0 = left end of the span).
    pub position: f64,
    /// Wheel (unsprung) mass m_w \[kg\], ≥ 0; 0 = a massless wheel, which needs the rigid
    /// contact and a body (module documentation).
    pub wheel_mass: f64,
    /// Sprung body mass m_b \[kg\] (0 = none).
    pub body_mass: f64,
    /// Suspension stiffness k_s \[N/m\] (> 0 when there is a body).
    pub suspension_stiffness: f64,
    /// Suspension damping c_s \[N s/m\].
    pub suspension_damping: f64,
    /// Extra constant force on the wheel P \[N\].
    pub static_load: f64,
}

impl Default for WheelSpec {
    fn default() -> Self {
        Self {
            position: 0.0,
            wheel_mass: 0.0,
            body_mass: 0.0,
            suspension_stiffness: 0.0,
            suspension_damping: 0.0,
            static_load: 0.0,
        }
    }
}

/// The contact model.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactModel {
    /// Wheel follows the rail (constraint).
    Rigid,
    /// Closed-form Hertz spring.
    Hertz,
    /// Half-space boundary elements on an `elements × elements` grid, NormCG tolerance `tol`,
    /// full solves reused across evaluations within the estimated relative force error
    /// `reuse_tol` (0: a solve at every evaluation; `halfspace::law::BemOptions::reuse_tol`).
    Bem {
        elements: usize,
        tol: f64,
        reuse_tol: f64,
    },
    /// Half-space boundary elements on real wheel and rail profiles
    /// ([`wheelrail::ProfileLaw`]; module [`profiles`](super::profiles)): every patch of the
    /// wheel solved in its contact plane at each evaluation.
    BemProfiles(super::profiles::ProfileContact),
}

/// The time integrator of the coupled system, chosen with the scenario.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// An implicit structural method of `integrate` with the coupling iteration of each step
    /// (module documentation, "Time step"; [`CouplingSpec`]).
    Structural(StructuralMethod),
    /// Radau5 on the first-order coupled system, its simplified Newton iteration being the
    /// coupling ([`radau`](super::radau)); needs compliant contact.
    Radau5(Radau5Spec),
}

impl Integrator {
    /// The scenario-file name (`newmark`, `hht`, …, `radau5`).
    pub fn name(&self) -> &'static str {
        match self {
            Self::Structural(method) => method.name(),
            Self::Radau5(_) => "radau5",
        }
    }
}

/// The coupling solver of each implicit step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CouplingSolver {
    /// Fixed-point iteration on the contact forces.
    Picard,
    /// The quasi-Newton method of references.md §D4.4 (Sherman–Morrison / Woodbury).
    QuasiNewton,
    /// The same linearisation solved with a dense matrix (reference).
    Newton,
}

impl CouplingSolver {
    /// `picard`, `quasi_newton` (or `sherman_morrison`, `woodbury`), `newton`.
    pub fn by_name(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().replace('-', "_").as_str() {
            "picard" => Some(Self::Picard),
            "quasi_newton" | "sherman_morrison" | "woodbury" => Some(Self::QuasiNewton),
            "newton" => Some(Self::Newton),
            _ => None,
        }
    }

    /// The scenario-file name.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Picard => "picard",
            Self::QuasiNewton => "quasi_newton",
            Self::Newton => "newton",
        }
    }
}

/// Settings of the coupling iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CouplingSpec {
    /// The solver.
    pub solver: CouplingSolver,
    /// Convergence when the change of every contact force between two iterations is at most
    /// `tol` × the largest static wheel load.
    pub tol: f64,
    /// Iteration limit per step.
    pub max_iter: usize,
    /// Recursive step halvings allowed for a failing step.
    pub max_halvings: usize,
}

impl Default for CouplingSpec {
    fn default() -> Self {
        Self {
            solver: CouplingSolver::QuasiNewton,
            tol: 1e-10,
            max_iter: 50,
            max_halvings: 6,
        }
    }
}

/// A complete vehicle–bridge scenario.
pub struct Scenario {
    /// The bridge modes.
    pub bridge: Box<dyn ModalBasis>,
    /// Modal damping.
    pub damping: ModalDamping,
    /// The wheels (at least one).
    pub wheels: Vec<WheelSpec>,
    /// Forces moving with the wheels without DOFs or contact (module
    /// [`moving_forces`](super::moving_forces); usually empty).
    pub moving_forces: Vec<super::MovingForce>,
    /// Vehicle speed c \[m/s\] (> 0).
    pub speed: f64,
    /// Contact model.
    pub contact: ContactModel,
    /// Contact geometry and material.
    pub geometry: ContactGeometry,
    /// Rail irregularity.
    pub irregularity: Irregularity,
    /// Time integrator (an implicit structural method, or Radau5).
    pub integrator: Integrator,
    /// Time step \[s\].
    pub dt: f64,
    /// Simulated time \[s\]; `None` = until the last wheel has left the span.
    pub duration: Option<f64>,
    /// Coupling settings.
    pub coupling: CouplingSpec,
    /// Gravity \[m/s²\].
    pub gravity: f64,
    /// Deflection and acceleration output point \[m\] (usually midspan).
    pub output_point: f64,
}

impl std::fmt::Debug for Scenario {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Scenario")
            .field("modes", &self.bridge.n_modes())
            .field("length", &self.bridge.length())
            .field("wheels", &self.wheels)
            .field("speed", &self.speed)
            .field("contact", &self.contact)
            .field("integrator", &self.integrator)
            .field("dt", &self.dt)
            .finish_non_exhaustive()
    }
}

/// Checks every scenario key (an error names the key, its value and the allowed range) and
/// tabulates a random irregularity over the track the wheels will cover; called by
/// [`Simulation::new`](super::Simulation::new) before anything is allocated.
pub(super) fn validate(scenario: &mut Scenario) -> Result<(), VehicleBridgeError> {
    let length = scenario.bridge.length();
    if scenario.wheels.is_empty() {
        return Err(invalid(
            "vehicle.wheels",
            0.0,
            "at least one wheel is needed",
        ));
    }
    if !(scenario.speed.is_finite() && scenario.speed > 0.0) {
        return Err(invalid("vehicle.speed", scenario.speed, "must be positive"));
    }
    if !(scenario.dt.is_finite() && scenario.dt > 0.0) {
        return Err(invalid("integrator.dt", scenario.dt, "must be positive"));
    }
    match scenario.integrator {
        Integrator::Structural(method) => {
            if method.is_explicit() {
                return Err(invalid_text(
                    "integrator.method",
                    method.name(),
                    "the coupled step needs an implicit method (newmark with beta > 0, hht, generalized_alpha, backward_euler, radau5)",
                ));
            }
        }
        Integrator::Radau5(spec) => {
            if scenario.contact == ContactModel::Rigid {
                return Err(invalid_text(
                    "contact.model",
                    "rigid",
                    "radau5 needs a compliant contact (hertz or bem): a rigid contact is an algebraic constraint, not an ODE",
                ));
            }
            for (name, v) in [
                ("integrator.rtol", spec.rtol),
                ("integrator.atol", spec.atol),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(invalid(name, v, "must be positive and finite"));
                }
            }
        }
    }
    if !(scenario.gravity.is_finite()) {
        return Err(invalid("gravity", scenario.gravity, "must be finite"));
    }
    if !(0.0..=length).contains(&scenario.output_point) {
        return Err(invalid(
            "output_point",
            scenario.output_point,
            "must lie on the span",
        ));
    }
    let c = scenario.coupling;
    if !(c.tol.is_finite() && c.tol > 0.0) {
        return Err(invalid("coupling.tol", c.tol, "must be positive"));
    }
    if c.max_iter == 0 {
        return Err(invalid("coupling.max_iter", 0.0, "must be at least 1"));
    }
    if let Some(d) = scenario.duration
        && !(d.is_finite() && d > 0.0)
    {
        return Err(invalid("duration", d, "must be positive"));
    }
    scenario.irregularity.validate()?;
    for (p, f) in scenario.moving_forces.iter().enumerate() {
        let key = |k: &str| format!("moving_forces[{p}].{k}");
        if !f.position.is_finite() {
            return Err(invalid(key("position"), f.position, "must be finite"));
        }
        if !f.force.is_finite() {
            return Err(invalid(key("force"), f.force, "must be finite"));
        }
    }
    {
        // The step count is checked before anything is allocated or run.
        let first = scenario.rearmost_position();
        let end = scenario
            .duration
            .unwrap_or(((length - first) / scenario.speed).max(0.0));
        let steps = end / scenario.dt;
        if steps.is_nan() || steps > MAX_STEPS {
            return Err(invalid(
                "integrator.dt",
                scenario.dt,
                &format!(
                    "the run of {end:e} s would take {steps:.3e} steps (limit {MAX_STEPS:e}); increase dt or shorten the duration"
                ),
            ));
        }
    }
    {
        // A random profile is tabulated over the track the wheels (and their contact
        // grids, < 1 m) will cover, so each evaluation is one cubic instead of a sum of
        // cosines (Irregularity::tabulated; interpolation error ≤ 2.4e-7 Σ a_k).
        let (lo, hi) = scenario
            .wheels
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), w| {
                (lo.min(w.position), hi.max(w.position))
            });
        // The run lasts until the rearmost wheel or moving force has left the span.
        let duration = scenario.duration.unwrap_or(
            ((scenario.bridge.length() - scenario.rearmost_position()) / scenario.speed).max(0.0),
        );
        scenario.irregularity = scenario
            .irregularity
            .tabulated(lo - 1.0, hi + scenario.speed * duration + 1.0);
    }
    for (k, w) in scenario.wheels.iter().enumerate() {
        let key = |f: &str| format!("vehicle.wheels[{k}].{f}");
        if !w.position.is_finite() {
            return Err(invalid(key("position"), w.position, "must be finite"));
        }
        if !(w.wheel_mass.is_finite() && w.wheel_mass >= 0.0) {
            return Err(invalid(
                key("wheel_mass"),
                w.wheel_mass,
                "must be finite and >= 0 (0 = massless wheel)",
            ));
        }
        if w.wheel_mass == 0.0 {
            // A massless wheel has no equation of motion of its own: its position must be
            // fixed by the rail (rigid constraint) and its force balance
            // F = P + k_s(z_b − z_w) + c_s(ż_b − ż_w) needs the suspension of a body.
            if scenario.contact != ContactModel::Rigid {
                return Err(invalid(
                    key("wheel_mass"),
                    0.0,
                    "a massless wheel needs contact.model = \"rigid\" (a compliant contact would leave the wheel DOF without inertia against the contact spring)",
                ));
            }
            if w.body_mass <= 0.0 {
                return Err(invalid(
                    key("wheel_mass"),
                    0.0,
                    "a massless wheel needs a sprung body (body_mass > 0); without one it is a moving force: use static_load on a light wheel",
                ));
            }
        }
        check_non_negative(key("body_mass"), w.body_mass)?;
        check_non_negative(key("suspension_stiffness"), w.suspension_stiffness)?;
        check_non_negative(key("suspension_damping"), w.suspension_damping)?;
        if !w.static_load.is_finite() {
            return Err(invalid(key("static_load"), w.static_load, "must be finite"));
        }
        if w.body_mass > 0.0 && w.suspension_stiffness <= 0.0 {
            return Err(invalid(
                key("suspension_stiffness"),
                w.suspension_stiffness,
                "must be positive when the wheel carries a body",
            ));
        }
        // The body's static sag m_b g / k_s: beyond MAX_STATIC_SAG the "suspension" does not
        // hold the body (a body frequency below 0.16 Hz), and an absurdly soft one overflows.
        if w.body_mass > 0.0
            && w.body_mass * scenario.gravity / w.suspension_stiffness > MAX_STATIC_SAG
        {
            return Err(invalid(
                key("suspension_stiffness"),
                w.suspension_stiffness,
                "too soft: the body would sag more than 10 m under its weight (body frequency below 0.16 Hz); it must be at least body_mass × 9.81 / 10 N/m",
            ));
        }
        let load = (w.wheel_mass + w.body_mass) * scenario.gravity + w.static_load;
        if load <= 0.0 {
            return Err(invalid(
                key("static_load"),
                w.static_load,
                "the total static wheel load must be positive (the wheel must press on the rail)",
            ));
        }
    }
    if c.solver == CouplingSolver::Picard && scenario.contact == ContactModel::Rigid {
        return Err(invalid_text(
            "coupling.solver",
            "picard",
            "picard needs a compliant contact (hertz or bem); a rigid contact has no force law to iterate on",
        ));
    }
    Ok(())
}

impl Scenario {
    /// The position of the rearmost wheel or moving force at t = 0 \[m\] (a run without a
    /// `duration` ends when it has left the span).
    pub fn rearmost_position(&self) -> f64 {
        self.wheels
            .iter()
            .map(|w| w.position)
            .chain(self.moving_forces.iter().map(|f| f.position))
            .fold(f64::INFINITY, f64::min)
    }
}
