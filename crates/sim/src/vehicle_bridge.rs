//! Wheels over a modal bridge with local contact, coupled at every time step (the founding
//! talk's central result; references.md §D1.1–1.3, §2.2–2.5, §4.2–4.3).
//!
//! # Model (SI units; displacements positive downwards)
//! * Bridge: a mass-normalised modal basis ([`beam::ModalBasis`], analytic or FE),
//!   `q_j'' + c_j q_j' + ω_j² q_j = Σ_k I_jk`, with the modal damping `c_j` of
//!   [`beam::ModalDamping`] and the modal loads of wheel k `I_jk = Σ_i F_ki w_j(x_k + ξ_i)`
//!   (the seed's ∫ p w_j dx, with F_ki the force carried by grid column i of the contact);
//!   deflection `w(x, t) = Σ_j q_j(t) w_j(x)`, zero off the span (rigid approach track).
//! * Wheel k at `x_k(t) = x_k0 + c t` with mass m_w, a sprung body m_b on a spring–damper
//!   (k_s, c_s), and a constant extra load P:
//!   `m_w z_w'' = m_w g + P − F_k + k_s(z_b − z_w) + c_s(ż_b − ż_w)`,
//!   `m_b z_b'' = m_b g − k_s(z_b − z_w) − c_s(ż_b − ż_w)`.
//! * A massless wheel (m_w = 0; rigid contact and a body required) is the classic sprung mass
//!   of Biggs and Yang–Yau (references.md §D1.3): its row is the force balance
//!   `F = P + k_s(z_b − z_w) + c_s(ż_b − ż_w)` and the constraint z_w = w(x_k) − r(x_k) fixes
//!   its position, so the body rides on a spring–damper whose lower end follows the rail. The
//!   wheel DOF stays in the state vector without inertia: the step matrix A keeps it
//!   non-singular through the suspension terms (c_C c_s + c_K k_s), and the contact multiplier
//!   F closes the row. In loss of contact (F = 0) the row becomes the first-order suspension
//!   balance `P + k_s(z_b − z_w) + c_s(ż_b − ż_w) = 0` (the massless wheel hangs on the body).
//! * Contact: the approach `δ_k = z_w − w(x_k) + r(x_k)` (r: rail irregularity, positive up)
//!   and `F_k = F(δ_k)` by a [`ContactLaw`]: `rigid` (δ_k = 0 while F_k > 0, a Lagrange
//!   multiplier: the wheel follows the rail, which is the moving-mass model of references.md
//!   §D1.2 with all its inertia and convective terms), `hertz`, or `bem`. Loss of contact
//!   (F = 0) and re-contact are handled by every law.
//!
//! # Time step (references.md §D4.2)
//! The contact-free system `M x'' + C x' + K x = f` (bridge modes and vehicle DOFs; gravity in
//! f) is advanced by an implicit [`StructuralMethod`] of the `integrate` crate through its
//! [`StepEquation`]: with `A = c_M M + c_C C + c_K K` and the step load `r`
//! ([`StepEquation::effective_load`], which takes the old contact force with weight α_f), the
//! step solves
//!
//! ```text
//! R(x) = A x − r − s Σ_k G_k(x) = 0,   s = 1 − α_f,   G_k = (+I_k on the modes, −F_k on wheel k)
//! ```
//!
//! for `x = q_{n+1}` and hands it to [`StructuralStepper::finish_step`]. Writing
//! `G_k = −F_k ĝ_k` (ĝ_k: −I_k/F_k on the modes, +1 on the wheel) and `δ_k = v_kᵀx + r_k`
//! (v_k: −w_j(x_k) on the modes, +1 on the wheel), the solvers ([`CouplingSolver`]) are
//! * `picard`: `x ← A⁻¹(r + s Σ G_k(x))` (contact force lagged); its error map is
//!   `e ← −λ e` with `λ = s k_c vᵀA⁻¹ĝ` (= k_c c_Δt), so it converges iff λ < 1;
//! * `quasi_newton` (the seed): the forces are linearised in the approach only (the pressure
//!   shape ĝ_k is lagged), `J = A + s Σ_k k_c ĝ_k v_kᵀ`, solved by Sherman–Morrison (one wheel,
//!   denominator 1 + λ) or Woodbury (k wheels, k × k capacitance matrix) in O(n) per
//!   iteration ([`linalg::contact_update`]);
//! * `newton`: the same linearisation solved densely ([`linalg::dense_contact_update`]), the
//!   reference.
//!
//! A rigid contact enters all of them as a zero compliance (an exact constraint); Picard needs
//! compliant contacts. The quasi-Newton iteration starts from the predictor corrected by the
//! previous step's contact linearisation (`F ≈ F_n + k_n(δ − δ_n)`, column forces carried with
//! the wheel), computes the BEM tangent at the first contact evaluation of a step only, and
//! accepts the corrected state with the linearised forces once every predicted force
//! correction is within the tolerance; in a smooth run most steps need one contact solve. A step whose iteration fails (no convergence in `max_iter`, divergence,
//! a contact-solver failure) is retried as two half steps, recursively up to `max_halvings`
//! times; every retry is counted in [`SolverStats::failed_steps`], and a step that still fails
//! is an error.
//!
//! # Start
//! Every wheel starts in static equilibrium on an undeformed rail: F_k = W_k =
//! (m_w + m_b) g + P, z_w = δ_static − r(x_k0), z_b = z_w + m_b g/k_s, moving with the rail
//! under it (ż_w = ż_b = −c r'(x_k0)); the bridge starts at rest and undeflected (wheels
//! normally start off the span, x_k0 ≤ 0).

mod contact;
pub mod irregularity;
pub mod linalg;
pub mod radau;
pub mod run;
pub mod traction;

use beam::{BeamError, Derivative, ModalBasis, ModalDamping};
use faer::{Mat, MatRef};
use halfspace::ContactError;
use integrate::IntegrateError;
use integrate::structural::{StepEquation, StructuralMethod, StructuralStepper, StructuralSystem};

pub use contact::{BemLaw, ContactGeometry, ContactLaw, ContactOutput, HertzLaw, RigidLaw};
pub use irregularity::{Irregularity, RandomProfile, TrackSpectrum};
use linalg::{BlockDiagonal, CapacitanceWork, contact_update, dense_contact_update};
pub use radau::Radau5Spec;
pub use run::{
    Accuracy, Extremum, NoObserver, Range, RunFailure, RunObserver, RunSummary, StepInfo,
    WheelSummary,
};

/// Standard gravity [m/s²].
pub const GRAVITY: f64 = 9.81;

/// Most steps of Δt a run may plan (checked by [`Simulation::new`] before anything is
/// allocated; about a day of wall time for the cheapest scenarios).
pub const MAX_STEPS: f64 = 1e8;

/// Errors of the vehicle–bridge simulation.
#[derive(Debug, thiserror::Error)]
pub enum VehicleBridgeError {
    /// A parameter is out of range; `name` is the scenario key.
    #[error("invalid `{name}` = {value}: {reason}")]
    InvalidParameter {
        name: String,
        value: f64,
        reason: String,
    },
    /// The beam (modal basis) failed.
    #[error("bridge: {0}")]
    Beam(#[from] BeamError),
    /// The time integrator failed.
    #[error("integrator: {0}")]
    Integrate(#[from] IntegrateError),
    /// The half-space contact solver failed.
    #[error("contact solver: {0}")]
    Contact(#[from] ContactError),
    /// The contact-free step matrix A has a singular (or non-finite) block at `dof`.
    #[error("singular step matrix at DOF {dof}: {reason}")]
    SingularStepMatrix { dof: usize, reason: String },
    /// The coupling iteration of a step failed even after step reduction.
    #[error(
        "coupling ({solver}) failed at t = {t:.6} s with step {dt:e} s after {halvings} step halvings: {reason} (last force change {change:e} N after {iterations} iterations)"
    )]
    CouplingFailed {
        solver: &'static str,
        t: f64,
        dt: f64,
        halvings: usize,
        iterations: usize,
        change: f64,
        reason: String,
    },
}

fn invalid(name: impl Into<String>, value: f64, reason: &str) -> VehicleBridgeError {
    VehicleBridgeError::InvalidParameter {
        name: name.into(),
        value,
        reason: reason.to_string(),
    }
}

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
    /// Suspension stiffness k_s [N/m] (> 0 when there is a body).
    pub suspension_stiffness: f64,
    /// Suspension damping c_s [N s/m].
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactModel {
    /// Wheel follows the rail (constraint).
    Rigid,
    /// Closed-form Hertz spring.
    Hertz,
    /// Half-space boundary elements on an `elements × elements` grid, NormCG tolerance `tol`.
    Bem { elements: usize, tol: f64 },
}

/// The coupling solver of each implicit step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CouplingSolver {
    /// Fixed-point iteration on the contact forces.
    Picard,
    /// The seed's quasi-Newton method (Sherman–Morrison / Woodbury).
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
    /// Vehicle speed c [m/s] (> 0).
    pub speed: f64,
    /// Contact model.
    pub contact: ContactModel,
    /// Contact geometry and material.
    pub geometry: ContactGeometry,
    /// Rail irregularity.
    pub irregularity: Irregularity,
    /// Time integrator (implicit).
    pub method: StructuralMethod,
    /// Time step \[s\].
    pub dt: f64,
    /// Simulated time \[s\]; `None` = until the last wheel has left the span.
    pub duration: Option<f64>,
    /// Coupling settings.
    pub coupling: CouplingSpec,
    /// Gravity [m/s²].
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
            .field("method", &self.method)
            .field("dt", &self.dt)
            .finish_non_exhaustive()
    }
}

/// Per-wheel state reported at a time.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WheelSample {
    /// Position x_k \[m\].
    pub position: f64,
    /// Wheel displacement z_w \[m\] (down).
    pub wheel_displacement: f64,
    /// Body displacement z_b \[m\] (down; equal to z_w without a body).
    pub body_displacement: f64,
    /// Body acceleration [m/s²] (0 without a body).
    pub body_acceleration: f64,
    /// Wheel acceleration [m/s²].
    pub wheel_acceleration: f64,
    /// Approach δ \[m\].
    pub approach: f64,
    /// Contact force and patch.
    pub contact: ContactOutput,
}

/// Coupling statistics of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolverStats {
    /// Accepted steps (including the halves of reduced steps).
    pub steps: usize,
    /// Total coupling iterations (contact evaluations).
    pub iterations: usize,
    /// Most iterations in one step.
    pub max_iterations: usize,
    /// Total contact-solver iterations (NormCG).
    pub contact_iterations: usize,
    /// Step attempts that failed and were retried with half the step.
    pub failed_steps: usize,
    /// Largest floating-point floor of the contact forces met in a step \[N\] (the
    /// convergence test's floor; module documentation of the coupling).
    pub max_force_floor: f64,
}

/// The simulation: state, stepper and work space.
pub struct Simulation {
    scenario: Scenario,
    laws: Vec<Box<dyn ContactLaw>>,
    structure: Structure,
    stepper: StructuralStepper,
    eq: StepEquation,
    /// Index of each wheel's DOF and of its body's DOF (if any).
    wheel_dof: Vec<usize>,
    body_dof: Vec<Option<usize>>,
    /// Static wheel loads W_k [N] and the force scale of the tolerance.
    static_loads: Vec<f64>,
    force_scale: f64,
    /// Generalized contact force of the last accepted step (modes +I, wheels −F).
    contact_load: Vec<f64>,
    /// Rigid multipliers / last forces.
    forces: Vec<f64>,
    samples: Vec<WheelSample>,
    /// Work space.
    work: Work,
    a_matrix: BlockDiagonal,
    a_coefficients: (f64, f64, f64),
    stats: SolverStats,
    output_shapes: Vec<f64>,
    loss_events: usize,
    /// Loss-of-contact events per wheel.
    wheel_loss_events: Vec<usize>,
    /// Contact tangent dF/dδ at the static load per wheel [N/m] (0 for the rigid contact).
    static_contact_stiffness: Vec<f64>,
    in_contact: Vec<bool>,
    /// Longitudinal friction (`None` = frictionless; see [`traction`]).
    traction: Option<traction::Traction>,
    /// The Radau5 path (`None` = the structural method of the scenario; see [`radau`]).
    radau: Option<radau::RadauPath>,
}

#[derive(Debug, Default)]
struct Work {
    x: Vec<f64>,
    r: Vec<f64>,
    res: Vec<f64>,
    f_ext: Vec<f64>,
    /// Per wheel: mode shapes at the wheel (m), at the columns (ncol × m), irregularity at the
    /// columns (ncol), column gaps and forces, ĝ and v vectors (n).
    shape_at_wheel: Vec<Vec<f64>>,
    shape_at_columns: Vec<Vec<f64>>,
    r_at_wheel: Vec<f64>,
    r_at_columns: Vec<Vec<f64>>,
    column_gap: Vec<Vec<f64>>,
    column_force: Vec<Vec<f64>>,
    modal_load: Vec<Vec<f64>>,
    g_hat: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    g_act: Vec<Vec<f64>>,
    v_act: Vec<Vec<f64>>,
    outputs: Vec<ContactOutput>,
    delta: Vec<f64>,
    prev_force: Vec<f64>,
    last_df: Vec<f64>,
    active: Vec<usize>,
    compliance: Vec<f64>,
    delta_tilde: Vec<f64>,
    df: Vec<f64>,
    cap: CapacitanceWork,
    dense: Vec<f64>,
    /// Round-off bound of the step residual and its image under |A⁻¹| (n), and the contact
    /// forces' floating-point floor per wheel (see `Simulation::force_floor`).
    floor_residual: Vec<f64>,
    floor_ainv_g: Vec<f64>,
    force_floor: f64,
}

impl Work {
    /// Bridge deflection under wheel k, `w(x_k) = Σ_j q_j w_j(x_k)` \[m\], at the state `x`
    /// (mode shapes of the last [`Simulation::wheel_geometry`]).
    fn deflection_under(&self, k: usize, x: &[f64]) -> f64 {
        let shapes = &self.shape_at_wheel[k];
        (0..shapes.len()).map(|j| x[j] * shapes[j]).sum()
    }

    /// The approach of wheel k, `δ_k = z_w − w(x_k) + r(x_k)` \[m\] (module documentation),
    /// at the state `x`; `iw` is the wheel's DOF. The one place δ is computed.
    fn approach(&self, k: usize, iw: usize, x: &[f64]) -> f64 {
        x[iw] - self.deflection_under(k, x) + self.r_at_wheel[k]
    }
}

/// The contact-free linear structure (bridge modes and vehicle), for the stepper.
struct Structure {
    mass: Mat<f64>,
    damping: Mat<f64>,
    stiffness: Mat<f64>,
    gravity_load: Vec<f64>,
    /// Contact load added to the external force (used for the consistent start acceleration).
    contact_load: Vec<f64>,
}

impl StructuralSystem for Structure {
    fn dimension(&self) -> usize {
        self.gravity_load.len()
    }
    fn mass_matrix(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }
    fn damping_matrix(&self) -> Option<MatRef<'_, f64>> {
        Some(self.damping.as_ref())
    }
    fn internal_force(&mut self, q: &[f64], f_int: &mut [f64]) {
        let n = q.len();
        for (i, f) in f_int.iter_mut().enumerate() {
            *f = (0..n).map(|j| self.stiffness[(i, j)] * q[j]).sum();
        }
    }
    fn tangent_stiffness(&mut self, _q: &[f64], mut k: faer::MatMut<'_, f64>) -> bool {
        k.copy_from(self.stiffness.as_ref());
        true
    }
    fn is_linear(&self) -> bool {
        true
    }
    fn external_force(&mut self, _t: f64, f_ext: &mut [f64]) {
        for ((f, g), c) in f_ext
            .iter_mut()
            .zip(&self.gravity_load)
            .zip(&self.contact_load)
        {
            *f = g + c;
        }
    }
}

/// Why one step attempt failed.
#[derive(Debug)]
struct StepFailure {
    iterations: usize,
    change: f64,
    reason: String,
    fatal: Option<VehicleBridgeError>,
}

fn check_non_negative(name: String, v: f64) -> Result<(), VehicleBridgeError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(invalid(name, v, "must be finite and >= 0"))
    }
}

impl Simulation {
    /// Validates the scenario and sets up the static start (module documentation).
    pub fn new(mut scenario: Scenario) -> Result<Self, VehicleBridgeError> {
        let m = scenario.bridge.n_modes();
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
        if scenario.method.is_explicit() {
            return Err(invalid(
                "integrator.method",
                f64::NAN,
                "the coupled step needs an implicit method (newmark with beta > 0, hht, generalized_alpha, backward_euler)",
            ));
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
        {
            // The step count is checked before anything is allocated or run.
            let first = scenario
                .wheels
                .iter()
                .map(|w| w.position)
                .fold(f64::INFINITY, f64::min);
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
            let duration = scenario
                .duration
                .unwrap_or((scenario.bridge.length() - lo) / scenario.speed);
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
            return Err(invalid(
                "coupling.solver",
                f64::NAN,
                "picard needs a compliant contact (hertz or bem); a rigid contact has no force law to iterate on",
            ));
        }

        // DOF layout and matrices.
        let mut n = m;
        let mut wheel_dof = Vec::new();
        let mut body_dof = Vec::new();
        for w in &scenario.wheels {
            wheel_dof.push(n);
            n += 1;
            if w.body_mass > 0.0 {
                body_dof.push(Some(n));
                n += 1;
            } else {
                body_dof.push(None);
            }
        }
        let omegas = scenario.bridge.circular_frequencies().to_vec();
        let modal_c = scenario.damping.velocity_coefficients(&omegas)?;
        let mut mass = Mat::<f64>::zeros(n, n);
        let mut damping = Mat::<f64>::zeros(n, n);
        let mut stiffness = Mat::<f64>::zeros(n, n);
        let mut gravity_load = vec![0.0; n];
        for j in 0..m {
            let mj = scenario.bridge.modal_mass(j)?;
            mass[(j, j)] = mj;
            damping[(j, j)] = mj * modal_c[j];
            stiffness[(j, j)] = mj * omegas[j] * omegas[j];
        }
        let g = scenario.gravity;
        let mut static_loads = Vec::new();
        for (k, w) in scenario.wheels.iter().enumerate() {
            let iw = wheel_dof[k];
            mass[(iw, iw)] = w.wheel_mass;
            gravity_load[iw] = w.wheel_mass * g + w.static_load;
            if let Some(ib) = body_dof[k] {
                mass[(ib, ib)] = w.body_mass;
                gravity_load[ib] = w.body_mass * g;
                for (mat, v) in [
                    (&mut damping, w.suspension_damping),
                    (&mut stiffness, w.suspension_stiffness),
                ] {
                    mat[(iw, iw)] += v;
                    mat[(ib, ib)] += v;
                    mat[(iw, ib)] -= v;
                    mat[(ib, iw)] -= v;
                }
            }
            static_loads.push((w.wheel_mass + w.body_mass) * g + w.static_load);
        }
        let force_scale = static_loads.iter().copied().fold(0.0, f64::max);

        // Contact laws.
        let mut laws: Vec<Box<dyn ContactLaw>> = Vec::new();
        for &load in &static_loads {
            laws.push(match scenario.contact {
                ContactModel::Rigid => Box::new(RigidLaw::default()),
                ContactModel::Hertz => Box::new(HertzLaw::new(&scenario.geometry)?),
                ContactModel::Bem { elements, tol } => {
                    Box::new(BemLaw::new(&scenario.geometry, elements, 2.5 * load, tol)?)
                }
            });
        }

        // Static start.
        let mut q0 = vec![0.0; n];
        let mut forces = Vec::new();
        let mut contact_load = vec![0.0; n];
        for (k, w) in scenario.wheels.iter().enumerate() {
            let delta = laws[k].static_approach(static_loads[k])?;
            let zw = delta - scenario.irregularity.height(w.position);
            q0[wheel_dof[k]] = zw;
            if let Some(ib) = body_dof[k] {
                q0[ib] = zw + w.body_mass * g / w.suspension_stiffness;
            }
            forces.push(static_loads[k]);
            contact_load[wheel_dof[k]] = -static_loads[k];
            if (0.0..=length).contains(&w.position) {
                for j in 0..m {
                    contact_load[j] += static_loads[k] * scenario.bridge.shape(j, w.position)?;
                }
            }
        }
        let mut structure = Structure {
            mass,
            damping,
            stiffness,
            gravity_load,
            contact_load: contact_load.clone(),
        };
        // The wheel and body start moving with the rail under them: ż = −c r'(x_k0) keeps
        // δ̇ = ż_w + c r' = 0 (r' by a central difference, h = 1e-6 m).
        let mut v0 = vec![0.0; n];
        for (k, w) in scenario.wheels.iter().enumerate() {
            let h = 1e-6;
            let irr = &scenario.irregularity;
            let slope = (irr.height(w.position + h) - irr.height(w.position - h)) / (2.0 * h);
            v0[wheel_dof[k]] = -scenario.speed * slope;
            if let Some(ib) = body_dof[k] {
                v0[ib] = -scenario.speed * slope;
            }
        }
        // A massless wheel's row and column of M are zero: the stepper treats it as a massless
        // DOF (no inertia in its step row, start acceleration 0; the static start balances the
        // wheel row exactly, so (f_ext − C v − K q)_w = 0 there as well).
        let stepper = StructuralStepper::new(scenario.method, &mut structure, 0.0, &q0, &v0)?;
        let nw = scenario.wheels.len();
        let ncols: Vec<usize> = laws.iter().map(|l| l.columns().len()).collect();
        let work = Work {
            x: vec![0.0; n],
            r: vec![0.0; n],
            res: vec![0.0; n],
            f_ext: vec![0.0; n],
            shape_at_wheel: vec![vec![0.0; m]; nw],
            shape_at_columns: ncols.iter().map(|&c| vec![0.0; c * m]).collect(),
            r_at_wheel: vec![0.0; nw],
            r_at_columns: ncols.iter().map(|&c| vec![0.0; c]).collect(),
            column_gap: ncols.iter().map(|&c| vec![0.0; c]).collect(),
            column_force: ncols.iter().map(|&c| vec![0.0; c]).collect(),
            modal_load: vec![vec![0.0; m]; nw],
            g_hat: vec![vec![0.0; n]; nw],
            v: vec![vec![0.0; n]; nw],
            g_act: vec![vec![0.0; n]; nw],
            v_act: vec![vec![0.0; n]; nw],
            outputs: vec![ContactOutput::default(); nw],
            delta: vec![0.0; nw],
            prev_force: vec![0.0; nw],
            last_df: vec![0.0; nw],
            active: Vec::with_capacity(nw),
            compliance: vec![0.0; nw],
            delta_tilde: vec![0.0; nw],
            df: vec![0.0; nw],
            cap: CapacitanceWork::new(n, nw),
            dense: Vec::new(),
            floor_residual: vec![0.0; n],
            floor_ainv_g: vec![0.0; n],
            force_floor: 0.0,
        };
        let mut output_shapes = vec![0.0; m];
        scenario
            .bridge
            .eval_all(scenario.output_point, Derivative::Shape, &mut output_shapes)?;
        let mut sim = Self {
            laws,
            structure,
            stepper,
            eq: StepEquation::default(),
            wheel_dof,
            body_dof,
            static_loads,
            force_scale,
            contact_load,
            forces,
            samples: vec![WheelSample::default(); nw],
            work,
            a_matrix: BlockDiagonal::new(n),
            a_coefficients: (f64::NAN, f64::NAN, f64::NAN),
            stats: SolverStats::default(),
            output_shapes,
            loss_events: 0,
            wheel_loss_events: vec![0; nw],
            static_contact_stiffness: vec![0.0; nw],
            in_contact: vec![true; nw],
            scenario,
            traction: None,
            radau: None,
        };
        sim.initial_samples()?;
        Ok(sim)
    }

    /// Fills the samples at t = 0 (static state).
    fn initial_samples(&mut self) -> Result<(), VehicleBridgeError> {
        self.wheel_geometry(self.stepper.t())?;
        for k in 0..self.scenario.wheels.len() {
            let x = self.scenario.wheels[k].position;
            let q = self.stepper.q().to_vec();
            let zw = q[self.wheel_dof[k]];
            let delta = self.work.approach(k, self.wheel_dof[k], &q);
            let mut out = if self.laws[k].is_rigid() {
                ContactOutput {
                    force: self.static_loads[k],
                    ..ContactOutput::default()
                }
            } else {
                let ncol = self.laws[k].columns().len();
                let zero = vec![0.0; ncol];
                let mut cf = vec![0.0; ncol];
                self.laws[k].evaluate(delta, &zero, &mut cf, true)?
            };
            out.iterations = 0;
            self.static_contact_stiffness[k] = out.stiffness;
            self.samples[k] = WheelSample {
                position: x,
                wheel_displacement: zw,
                body_displacement: self.body_dof[k].map_or(zw, |ib| q[ib]),
                body_acceleration: 0.0,
                wheel_acceleration: 0.0,
                approach: delta,
                contact: out,
            };
        }
        Ok(())
    }

    /// The scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// Current time \[s\].
    pub fn t(&self) -> f64 {
        self.stepper.t()
    }

    /// Total simulated time of a [`run`](Self::run) \[s\].
    pub fn end_time(&self) -> f64 {
        self.scenario.duration.unwrap_or_else(|| {
            let first = self
                .scenario
                .wheels
                .iter()
                .map(|w| w.position)
                .fold(f64::INFINITY, f64::min);
            ((self.scenario.bridge.length() - first) / self.scenario.speed).max(0.0)
        })
    }

    /// The state vector (modes first, then per wheel: wheel DOF, body DOF if any).
    pub fn state(&self) -> &[f64] {
        self.stepper.q()
    }

    /// The velocity vector.
    pub fn velocity(&self) -> &[f64] {
        self.stepper.v()
    }

    /// The acceleration vector.
    pub fn acceleration(&self) -> &[f64] {
        self.stepper.a()
    }

    /// Per-wheel samples at the current time.
    pub fn wheels(&self) -> &[WheelSample] {
        &self.samples
    }

    /// Static wheel loads W_k = (m_w + m_b) g + P \[N\].
    pub fn static_loads(&self) -> &[f64] {
        &self.static_loads
    }

    /// Coupling statistics so far.
    pub fn stats(&self) -> SolverStats {
        self.stats
    }

    /// Number of transitions from contact to loss of contact (over all wheels).
    pub fn loss_of_contact_events(&self) -> usize {
        self.loss_events
    }

    /// Bridge deflection w(x) \[m\] at the current time (0 off the span).
    pub fn deflection_at(&self, x: f64) -> Result<f64, VehicleBridgeError> {
        let m = self.scenario.bridge.n_modes();
        if !(0.0..=self.scenario.bridge.length()).contains(&x) {
            return Ok(0.0);
        }
        let mut w = 0.0;
        for j in 0..m {
            w += self.stepper.q()[j] * self.scenario.bridge.shape(j, x)?;
        }
        Ok(w)
    }

    /// Deflection, velocity and acceleration of the bridge at the output point.
    pub fn output_point_response(&self) -> (f64, f64, f64) {
        let m = self.scenario.bridge.n_modes();
        let s = &self.output_shapes;
        let d = (0..m).map(|j| self.stepper.q()[j] * s[j]).sum();
        let v = (0..m).map(|j| self.stepper.v()[j] * s[j]).sum();
        let a = (0..m).map(|j| self.stepper.a()[j] * s[j]).sum();
        (d, v, a)
    }

    /// Quasi-static deflection at the output point under the static wheel loads at their
    /// current positions, `Σ_k W_k Σ_j w_j(x_out) w_j(x_k)/(m_j ω_j²)` \[m\] (same modal basis;
    /// `None` if the basis has a rigid-body mode, ω_j = 0).
    pub fn quasi_static_output_deflection(&self) -> Result<Option<f64>, VehicleBridgeError> {
        let basis = &*self.scenario.bridge;
        let omegas = basis.circular_frequencies();
        if omegas.iter().any(|&w| w <= 0.0) {
            return Ok(None);
        }
        let mut total = 0.0;
        for (k, sample) in self.samples.iter().enumerate() {
            let x = sample.position;
            if !(0.0..=basis.length()).contains(&x) {
                continue;
            }
            for j in 0..basis.n_modes() {
                total += self.static_loads[k] * self.output_shapes[j] * basis.shape(j, x)?
                    / (basis.modal_mass(j)? * omegas[j] * omegas[j]);
            }
        }
        Ok(Some(total))
    }

    /// The centreline pressure of wheel `k`'s last contact evaluation (ξ \[m\], p \[Pa\]).
    pub fn centreline_pressure(&self, k: usize, out: &mut Vec<(f64, f64)>) {
        self.laws[k].centreline_pressure(out);
    }

    /// Advances by one step of the scenario's Δt (with step reduction on failure).
    pub fn step(&mut self) -> Result<(), VehicleBridgeError> {
        let dt = self.scenario.dt;
        if self.radau.is_some() {
            self.radau_step(dt)?;
        } else {
            self.advance(dt, 0)?;
        }
        if let Some(tr) = self.traction.as_mut() {
            tr.update(dt, self.scenario.speed, &self.samples, &self.laws)?;
        }
        Ok(())
    }

    /// Switches on longitudinal friction (module [`traction`]; weak coupling after every
    /// step). Call before the first step; `exact` needs the `bem` contact law.
    pub fn set_traction(&mut self, spec: traction::TractionSpec) -> Result<(), VehicleBridgeError> {
        self.traction = Some(traction::Traction::new(
            spec,
            &self.scenario.geometry,
            &self.laws,
            self.scenario.speed,
        )?);
        Ok(())
    }

    /// The traction state (`None` without `set_traction`).
    pub fn traction(&self) -> Option<&traction::Traction> {
        self.traction.as_ref()
    }

    /// Steps to the end time, calling `progress` after every step (the run driver
    /// [`run::run`] with an observer that never stops the run).
    pub fn run(
        &mut self,
        mut progress: impl FnMut(&Self),
    ) -> Result<RunSummary, VehicleBridgeError> {
        let mut observer = |sim: &Self, _: StepInfo| {
            progress(sim);
            std::ops::ControlFlow::Continue(())
        };
        run::run(self, &mut observer).map_err(|f| f.error)
    }

    /// Steps of the scenario's Δt to [`end_time`](Self::end_time): `⌈T/Δt − 10⁻⁹⌉`.
    pub fn planned_steps(&self) -> usize {
        let steps = (self.end_time() / self.scenario.dt - 1e-9).ceil().max(0.0);
        steps as usize
    }

    /// Position of wheel `k` at the current time, `x_k(t) = x_k0 + c t` \[m\].
    pub fn wheel_position(&self, k: usize) -> f64 {
        self.scenario.wheels[k].position + self.scenario.speed * self.t()
    }

    /// The step-size indicators of the scenario (module [`run`]): Δt times the highest
    /// retained bridge frequency f_max = ω_max/2π, and Δt times the largest contact frequency
    /// `f_c = √(k_c/m_w)/2π` of a wheel on its contact spring at the static load (`None` for
    /// the rigid contact or massless wheels, which have no contact mode).
    pub fn step_indicators(&self) -> (f64, Option<f64>) {
        let dt = self.scenario.dt;
        let two_pi = 2.0 * std::f64::consts::PI;
        let omega_max = self
            .scenario
            .bridge
            .circular_frequencies()
            .iter()
            .fold(0.0f64, |m, &w| m.max(w));
        let contact = self
            .scenario
            .wheels
            .iter()
            .zip(&self.static_contact_stiffness)
            .filter(|(w, k)| w.wheel_mass > 0.0 && **k > 0.0)
            .map(|(w, &k)| dt * (k / w.wheel_mass).sqrt() / two_pi)
            .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))));
        (dt * omega_max / two_pi, contact)
    }

    /// Loss-of-contact events per wheel (their sum is
    /// [`loss_of_contact_events`](Self::loss_of_contact_events)).
    pub fn wheel_loss_of_contact_events(&self) -> &[usize] {
        &self.wheel_loss_events
    }

    fn advance(&mut self, dt: f64, depth: usize) -> Result<(), VehicleBridgeError> {
        match self.try_step(dt) {
            Ok(()) => Ok(()),
            Err(failure) => {
                if let Some(fatal) = failure.fatal {
                    return Err(fatal);
                }
                self.stats.failed_steps += 1;
                if depth >= self.scenario.coupling.max_halvings {
                    return Err(VehicleBridgeError::CouplingFailed {
                        solver: self.scenario.coupling.solver.name(),
                        t: self.t(),
                        dt,
                        halvings: depth,
                        iterations: failure.iterations,
                        change: failure.change,
                        reason: failure.reason,
                    });
                }
                self.advance(0.5 * dt, depth + 1)?;
                self.advance(0.5 * dt, depth + 1)
            }
        }
    }

    /// Rebuilds the block-diagonal step matrix A if the step coefficients changed. A singular
    /// block (e.g. a massless wheel without suspension in the step, or non-finite
    /// coefficients) is an error naming the DOF, never silently dropped.
    fn update_a(&mut self) -> Result<(), VehicleBridgeError> {
        let eq = &self.eq;
        let key = (
            eq.mass_coefficient,
            eq.damping_coefficient,
            eq.stiffness_coefficient,
        );
        if key == self.a_coefficients {
            return Ok(());
        }
        // Invalidate first: a failed rebuild must not be reused by the next step.
        self.a_coefficients = (f64::NAN, f64::NAN, f64::NAN);
        let (cm, cc, ck) = key;
        let s = &self.structure;
        let a = &mut self.a_matrix;
        a.clear();
        let entry = |i: usize, j: usize| {
            cm * s.mass[(i, j)] + cc * s.damping[(i, j)] + ck * s.stiffness[(i, j)]
        };
        let singular = |dof: usize, what: &str| VehicleBridgeError::SingularStepMatrix {
            dof,
            reason: format!(
                "the {what} block of A = {cm:e} M + {cc:e} C + {ck:e} K is singular or not finite"
            ),
        };
        let m = self.scenario.bridge.n_modes();
        for j in 0..m {
            if !a.push1(j, entry(j, j)) {
                return Err(singular(j, "bridge-mode"));
            }
        }
        for (k, &iw) in self.wheel_dof.iter().enumerate() {
            let ok = match self.body_dof[k] {
                None => a.push1(iw, entry(iw, iw)),
                Some(ib) => a.push2(
                    iw,
                    ib,
                    entry(iw, iw),
                    entry(iw, ib),
                    entry(ib, iw),
                    entry(ib, ib),
                ),
            };
            if !ok {
                return Err(singular(iw, "wheel"));
            }
        }
        self.a_coefficients = key;
        Ok(())
    }

    /// Mode shapes and irregularity at the wheels and their contact columns at time `t`.
    fn wheel_geometry(&mut self, t: f64) -> Result<(), VehicleBridgeError> {
        let basis = &*self.scenario.bridge;
        let length = basis.length();
        let m = basis.n_modes();
        let w = &mut self.work;
        for (k, spec) in self.scenario.wheels.iter().enumerate() {
            let x = spec.position + self.scenario.speed * t;
            self.samples[k].position = x;
            if (0.0..=length).contains(&x) {
                basis.eval_all(x, Derivative::Shape, &mut w.shape_at_wheel[k])?;
            } else {
                w.shape_at_wheel[k].fill(0.0);
            }
            w.r_at_wheel[k] = self.scenario.irregularity.height(x);
            for (i, &xi) in self.laws[k].columns().iter().enumerate() {
                let xc = x + xi;
                let out = &mut w.shape_at_columns[k][i * m..(i + 1) * m];
                if (0.0..=length).contains(&xc) {
                    basis.eval_all(xc, Derivative::Shape, out)?;
                } else {
                    out.fill(0.0);
                }
                w.r_at_columns[k][i] = self.scenario.irregularity.height(xc);
            }
        }
        Ok(())
    }

    /// Evaluates every contact at the iterate `work.x`: approach, force, modal loads, ĝ and v.
    fn evaluate_contacts(&mut self, tangent: bool) -> Result<(), VehicleBridgeError> {
        let m = self.scenario.bridge.n_modes();
        let w = &mut self.work;
        for k in 0..self.laws.len() {
            let iw = self.wheel_dof[k];
            let defl = w.deflection_under(k, &w.x);
            let delta = w.approach(k, iw, &w.x);
            w.delta[k] = delta;
            let shapes = &w.shape_at_wheel[k];
            let law = &mut self.laws[k];
            let out = if law.is_rigid() {
                let f = self.forces[k];
                w.column_force[k][0] = f;
                ContactOutput {
                    force: f,
                    ..ContactOutput::default()
                }
            } else {
                let ncol = law.columns().len();
                for i in 0..ncol {
                    let cs = &w.shape_at_columns[k][i * m..(i + 1) * m];
                    let wc: f64 = (0..m).map(|j| w.x[j] * cs[j]).sum();
                    w.column_gap[k][i] = (wc - defl) - (w.r_at_columns[k][i] - w.r_at_wheel[k]);
                }
                law.evaluate(delta, &w.column_gap[k], &mut w.column_force[k], tangent)?
            };
            w.outputs[k] = out;
            let load = &mut w.modal_load[k];
            load.fill(0.0);
            for (i, &fc) in w.column_force[k].iter().enumerate() {
                if fc != 0.0 {
                    let cs = &w.shape_at_columns[k][i * m..(i + 1) * m];
                    for j in 0..m {
                        load[j] += fc * cs[j];
                    }
                }
            }
            let (gh, v) = (&mut w.g_hat[k], &mut w.v[k]);
            gh.fill(0.0);
            v.fill(0.0);
            for j in 0..m {
                v[j] = -shapes[j];
                gh[j] = if out.force > 0.0 {
                    -load[j] / out.force
                } else {
                    -shapes[j]
                };
            }
            v[iw] = 1.0;
            gh[iw] = 1.0;
        }
        Ok(())
    }

    /// Quasi-Newton start without a contact evaluation: every contact law is replaced by its
    /// linearisation at the end of the previous step, `F ≈ F_n + k_n (δ − δ_n)`, with the
    /// previous column forces carried along with the wheel (modal loads
    /// `I_j ≈ (F/F_n) Σ_i F_n,i w_j(x_k + ξ_i)` at the new position), and one
    /// Sherman–Morrison/Woodbury update is applied to the predictor `work.x`. The following
    /// contact evaluations correct it; with a smooth force history the first correction is then
    /// often already below the tolerance, so the step needs one contact solve instead of two.
    /// Skipped unless every wheel is in compliant contact with a known tangent.
    fn extrapolated_start(&mut self, s: f64) {
        let m = self.scenario.bridge.n_modes();
        let nw = self.laws.len();
        let w = &mut self.work;
        let usable = (0..nw).all(|k| {
            !self.laws[k].is_rigid()
                && w.outputs[k].force > 0.0
                && w.outputs[k].stiffness > 0.0
                && w.column_force[k].iter().sum::<f64>() > 0.0
        });
        if !usable {
            return;
        }
        self.a_matrix.mul(&w.x, &mut w.res);
        for i in 0..w.x.len() {
            w.res[i] = w.r[i] - w.res[i];
        }
        for k in 0..nw {
            let iw = self.wheel_dof[k];
            let delta = w.approach(k, iw, &w.x);
            let shapes = &w.shape_at_wheel[k];
            let (f_n, k_n) = (w.outputs[k].force, w.outputs[k].stiffness);
            let force = f_n + k_n * (delta - w.delta[k]);
            if force <= 0.0 {
                return;
            }
            let cols: f64 = w.column_force[k].iter().sum();
            let scale = force / cols;
            let (gh, v) = (&mut w.g_act[k], &mut w.v_act[k]);
            gh.fill(0.0);
            v.fill(0.0);
            for (i, &fc) in w.column_force[k].iter().enumerate() {
                if fc != 0.0 {
                    let cs = &w.shape_at_columns[k][i * m..(i + 1) * m];
                    for j in 0..m {
                        gh[j] -= scale * fc * cs[j];
                    }
                }
            }
            // −R gets +s I_k on the modes and −s F_k on the wheel; ĝ = (−I/F, +1).
            for j in 0..m {
                w.res[j] -= s * gh[j];
                gh[j] /= force;
                v[j] = -shapes[j];
            }
            w.res[iw] -= s * force;
            gh[iw] = 1.0;
            v[iw] = 1.0;
            w.compliance[k] = 1.0 / k_n;
            w.delta_tilde[k] = 0.0;
        }
        let ok = contact_update(
            &self.a_matrix,
            s,
            &w.g_act[..nw],
            &w.v_act[..nw],
            &w.compliance[..nw],
            &w.delta_tilde[..nw],
            &mut w.res,
            &mut w.df,
            &mut w.cap,
        );
        if ok && w.res.iter().all(|d| d.is_finite()) {
            for (x, d) in w.x.iter_mut().zip(&w.res) {
                *x += d;
            }
        }
    }

    /// The floating-point floor of the contact forces in this step, into `work.force_floor`
    /// \[N\]: the largest over the wheels of
    ///
    /// ```text
    /// F_floor,k = κ ε (|v_k|ᵀ |A⁻¹| e + |δ|_k) / (1/k_c + s |v_kᵀ A⁻¹ ĝ_k|),
    /// e_i = |r_i| + |(A x)_i| + s |G_i|,   |δ|_k = |x_w| + Σ_j |q_j w_j(x_k)| + |r(x_k)|,
    /// ```
    ///
    /// with ε the machine epsilon and κ = 32: the step residual R = A x − r − s G cannot be
    /// computed more accurately than ε e (each entry is a sum of terms of size e_i), nor the
    /// approach than ε |δ|_k, and one (quasi-)Newton force update maps such an error through the
    /// same formula as a true residual (`linalg::contact_update`, one wheel). A force change
    /// below it is round-off: for a 2.8e5 N moving mass at Δt = 2e-5 s it is 2.9e-2 N,
    /// far above ε |F| because the step matrix A ~ m/(β Δt²) is large.
    fn force_floor(&mut self, s: f64) {
        let m = self.scenario.bridge.n_modes();
        let w = &mut self.work;
        let e = &mut w.floor_residual;
        self.a_matrix.mul(&w.x, e);
        for (i, ei) in e.iter_mut().enumerate() {
            *ei = ei.abs() + w.r[i].abs();
        }
        for k in 0..self.laws.len() {
            for j in 0..m {
                e[j] += s * w.modal_load[k][j].abs();
            }
            e[self.wheel_dof[k]] += s * w.outputs[k].force.abs();
        }
        self.a_matrix.solve_abs_in_place(e);
        let mut floor = 0.0f64;
        for k in 0..self.laws.len() {
            let iw = self.wheel_dof[k];
            let shapes = &w.shape_at_wheel[k];
            let approach_scale = w.x[iw].abs()
                + (0..m).map(|j| (w.x[j] * shapes[j]).abs()).sum::<f64>()
                + w.r_at_wheel[k].abs();
            let propagated: f64 = w.v[k].iter().zip(e.iter()).map(|(v, y)| v.abs() * y).sum();
            w.floor_ainv_g.copy_from_slice(&w.g_hat[k]);
            self.a_matrix.solve_in_place(&mut w.floor_ainv_g);
            let compliance = if self.laws[k].is_rigid() || w.outputs[k].stiffness <= 0.0 {
                0.0
            } else {
                1.0 / w.outputs[k].stiffness
            };
            let den = compliance + s * linalg::dot(&w.v[k], &w.floor_ainv_g).abs();
            if den > 0.0 && den.is_finite() {
                let f = 32.0 * f64::EPSILON * (propagated + approach_scale) / den;
                floor = floor.max(f);
            }
        }
        w.force_floor = floor;
    }

    /// One step attempt of size `dt`; on success the state is advanced.
    fn try_step(&mut self, dt: f64) -> Result<(), StepFailure> {
        let fatal = |e: VehicleBridgeError| StepFailure {
            iterations: 0,
            change: 0.0,
            reason: e.to_string(),
            fatal: Some(e),
        };
        self.stepper
            .step_equation_into(dt, &mut self.eq)
            .map_err(|e| fatal(e.into()))?;
        self.update_a().map_err(fatal)?;
        let s = 1.0 - self.eq.alpha_f;
        let n = self.work.x.len();
        for i in 0..n {
            self.work.f_ext[i] =
                self.structure.gravity_load[i] + self.eq.alpha_f * self.contact_load[i];
        }
        self.eq
            .effective_load(
                self.structure.mass.as_ref(),
                Some(self.structure.damping.as_ref()),
                &self.work.f_ext,
                &mut self.work.r,
            )
            .map_err(|e| fatal(e.into()))?;
        self.wheel_geometry(self.eq.t_new).map_err(fatal)?;
        let c_qa = self.eq.displacement_per_acceleration;
        for i in 0..n {
            self.work.x[i] = self.eq.q_pred[i] + c_qa * self.stepper.a()[i];
        }
        if self.scenario.coupling.solver == CouplingSolver::QuasiNewton {
            self.extrapolated_start(s);
        }
        let nw = self.laws.len();
        let tol = self.scenario.coupling.tol * self.force_scale;
        let solver = self.scenario.coupling.solver;
        let mut change = f64::INFINITY;
        let mut converged = false;
        let mut iterations = 0;
        let mut contact_iterations = 0;
        let mut growth = 0;
        // The force changes of the two previous iterations (stagnation test).
        let mut history = [f64::INFINITY; 2];
        // A rigid multiplier was clipped at zero in the last update (the state then does not
        // match the forces, so another iteration is needed).
        let mut clamped = false;
        for it in 1..=self.scenario.coupling.max_iter {
            iterations = it;
            let tangent = match solver {
                CouplingSolver::Newton => true,
                CouplingSolver::QuasiNewton => it == 1,
                CouplingSolver::Picard => false,
            };
            if let Err(e) = self.evaluate_contacts(tangent) {
                return Err(StepFailure {
                    iterations,
                    change,
                    reason: e.to_string(),
                    fatal: None,
                });
            }
            let w = &mut self.work;
            contact_iterations += w.outputs.iter().map(|o| o.iterations).sum::<usize>();
            if it > 1 {
                let mut c = 0.0f64;
                for k in 0..nw {
                    let d = if self.laws[k].is_rigid() {
                        w.last_df[k].abs()
                    } else {
                        (w.outputs[k].force - w.prev_force[k]).abs()
                    };
                    c = c.max(d);
                }
                if c > change {
                    growth += 1;
                } else {
                    growth = 0;
                }
                change = c;
                if !change.is_finite() || (growth >= 4 && change > 10.0 * self.force_scale) {
                    return Err(StepFailure {
                        iterations,
                        change,
                        reason: "the iteration diverges".to_string(),
                        fatal: None,
                    });
                }
                // Converged at the tolerance, or at the floating-point floor of the forces:
                // below the floor the change is round-off (it stagnates instead of falling), so
                // a change within the floor, or one that stopped decreasing over two iterations
                // within 16× the floor, is convergence.
                let floor = w.force_floor;
                let stagnant = change <= 16.0 * floor && history[0].min(history[1]) <= change;
                if (change <= tol.max(floor) || stagnant) && !clamped {
                    converged = true;
                    break;
                }
                history = [history[1], change];
            }
            for k in 0..nw {
                w.prev_force[k] = w.outputs[k].force;
            }
            // Residual R = A x − r − s Σ G_k, written as −R into `res`.
            self.a_matrix.mul(&w.x, &mut w.res);
            for i in 0..n {
                w.res[i] = w.r[i] - w.res[i];
            }
            let m = self.scenario.bridge.n_modes();
            for k in 0..nw {
                for j in 0..m {
                    w.res[j] += s * w.modal_load[k][j];
                }
                w.res[self.wheel_dof[k]] -= s * w.outputs[k].force;
            }
            if it == 1 {
                self.force_floor(s);
            }
            let w = &mut self.work;
            let ok = match solver {
                CouplingSolver::Picard => {
                    self.a_matrix.solve_in_place(&mut w.res);
                    true
                }
                CouplingSolver::QuasiNewton | CouplingSolver::Newton => {
                    w.active.clear();
                    for k in 0..nw {
                        let rigid = self.laws[k].is_rigid();
                        let active = if rigid {
                            self.forces[k] > 0.0 || w.delta[k] > 0.0
                        } else {
                            w.outputs[k].stiffness > 0.0
                        };
                        w.last_df[k] = 0.0;
                        if active {
                            let a = w.active.len();
                            w.compliance[a] = if rigid {
                                0.0
                            } else {
                                1.0 / w.outputs[k].stiffness
                            };
                            w.delta_tilde[a] = if rigid { w.delta[k] } else { 0.0 };
                            w.active.push(k);
                        }
                    }
                    let ka = w.active.len();
                    // The active wheels' vectors, copied into preallocated rows (no allocation).
                    for (a, &k) in w.active.iter().enumerate() {
                        w.g_act[a].copy_from_slice(&w.g_hat[k]);
                        w.v_act[a].copy_from_slice(&w.v[k]);
                    }
                    let (g_hat, v) = (&w.g_act[..ka], &w.v_act[..ka]);
                    let ok = if solver == CouplingSolver::QuasiNewton {
                        contact_update(
                            &self.a_matrix,
                            s,
                            g_hat,
                            v,
                            &w.compliance[..ka],
                            &w.delta_tilde[..ka],
                            &mut w.res,
                            &mut w.df,
                            &mut w.cap,
                        )
                    } else {
                        dense_contact_update(
                            &self.a_matrix,
                            s,
                            g_hat,
                            v,
                            &w.compliance[..ka],
                            &w.delta_tilde[..ka],
                            &mut w.res,
                            &mut w.df,
                            &mut w.dense,
                        )
                    };
                    clamped = false;
                    for (a, &k) in w.active.iter().enumerate() {
                        if self.laws[k].is_rigid() {
                            clamped |= self.forces[k] + w.df[a] < 0.0;
                            let f_new = (self.forces[k] + w.df[a]).max(0.0);
                            w.last_df[k] = f_new - self.forces[k];
                            self.forces[k] = f_new;
                        }
                    }
                    ok
                }
            };
            if !ok {
                return Err(StepFailure {
                    iterations,
                    change,
                    reason: "singular coupled step matrix".to_string(),
                    fatal: None,
                });
            }
            for i in 0..n {
                w.x[i] += w.res[i];
            }
            if w.x.iter().any(|v| !v.is_finite()) {
                return Err(StepFailure {
                    iterations,
                    change,
                    reason: "non-finite state".to_string(),
                    fatal: None,
                });
            }
            // (Quasi-)Newton: when every wheel is in contact and the predicted force
            // corrections are within the tolerance, accept the corrected state with the
            // linearised forces F + ΔF (error O(ΔF²)) without another contact evaluation.
            if solver != CouplingSolver::Picard && w.active.len() == nw && !clamped {
                let predicted = w.df[..nw].iter().fold(0.0f64, |m, d| m.max(d.abs()));
                let all_positive = w
                    .active
                    .iter()
                    .enumerate()
                    .all(|(a, &k)| w.outputs[k].force + w.df[a] > 0.0);
                if predicted <= tol.max(w.force_floor) && all_positive {
                    for (a, &k) in w.active.iter().enumerate() {
                        let f_old = w.outputs[k].force;
                        let f_new = if self.laws[k].is_rigid() {
                            self.forces[k]
                        } else {
                            f_old + w.df[a]
                        };
                        if f_old > 0.0 {
                            let scale = f_new / f_old;
                            w.modal_load[k].iter_mut().for_each(|l| *l *= scale);
                        } else {
                            for (l, sh) in w.modal_load[k].iter_mut().zip(&w.shape_at_wheel[k]) {
                                *l = f_new * sh;
                            }
                        }
                        w.outputs[k].force = f_new;
                        w.delta[k] = w.approach(k, self.wheel_dof[k], &w.x);
                    }
                    change = predicted;
                    converged = true;
                    break;
                }
            }
        }
        if !converged {
            return Err(StepFailure {
                iterations,
                change,
                reason: format!(
                    "no convergence in {} iterations to the target force change {:e} N (coupling.tol = {:e} × the largest static wheel load {:e} N; floating-point floor of the forces {:e} N)",
                    self.scenario.coupling.max_iter,
                    tol,
                    self.scenario.coupling.tol,
                    self.force_scale,
                    self.work.force_floor,
                ),
                fatal: None,
            });
        }
        // Accept: the generalized contact force at t_{n+1}.
        let m = self.scenario.bridge.n_modes();
        let w = &self.work;
        self.contact_load.fill(0.0);
        for k in 0..nw {
            for j in 0..m {
                self.contact_load[j] += w.modal_load[k][j];
            }
            self.contact_load[self.wheel_dof[k]] = -w.outputs[k].force;
        }
        self.structure
            .contact_load
            .copy_from_slice(&self.contact_load);
        let x = std::mem::take(&mut self.work.x);
        let finished = self.stepper.finish_step(&mut self.structure, dt, &x);
        self.work.x = x;
        finished.map_err(|e| fatal(e.into()))?;
        self.stats.steps += 1;
        self.stats.iterations += iterations;
        self.stats.max_iterations = self.stats.max_iterations.max(iterations);
        self.stats.contact_iterations += contact_iterations;
        self.stats.max_force_floor = self.stats.max_force_floor.max(self.work.force_floor);
        let q = self.stepper.q();
        let a = self.stepper.a();
        for k in 0..nw {
            let iw = self.wheel_dof[k];
            let contact = self.work.outputs[k];
            let touching = contact.force > 0.0;
            if self.in_contact[k] && !touching {
                self.loss_events += 1;
                self.wheel_loss_events[k] += 1;
            }
            self.in_contact[k] = touching;
            self.forces[k] = contact.force;
            let sample = &mut self.samples[k];
            sample.wheel_displacement = q[iw];
            sample.wheel_acceleration = a[iw];
            sample.body_displacement = self.body_dof[k].map_or(q[iw], |ib| q[ib]);
            sample.body_acceleration = self.body_dof[k].map_or(0.0, |ib| a[ib]);
            sample.approach = self.work.delta[k];
            sample.contact = ContactOutput {
                iterations: contact_iterations,
                ..contact
            };
        }
        Ok(())
    }
}
