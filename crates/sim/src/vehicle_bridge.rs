//! Wheels over a modal bridge with local contact, coupled at every time step (the
//! baseline model of references.md §D4.4; §D1.1–1.3, §D2.2–2.5, §D4.2–4.3).
//!
//! # Model (SI units; displacements positive downwards)
//! * Bridge: a mass-normalised modal basis ([`beam::ModalBasis`], analytic or FE),
//!   `q_j'' + c_j q_j' + ω_j² q_j = Σ_k I_jk`, with the modal damping `c_j` of
//!   [`beam::ModalDamping`] and the modal loads of wheel k `I_jk = Σ_i F_ki w_j(x_k + ξ_i)`
//!   (∫ p w_j dx of references.md §D4.4, with F_ki the force carried by grid column i of the contact);
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
//!   and `F_k = F(δ_k)` by a [`halfspace::law::ContactModel`]: `rigid` (δ_k = 0 while F_k > 0:
//!   the wheel follows the rail, which is the moving-mass model of references.md §D1.2 with all
//!   its inertia and convective terms, imposed as an acceleration-level constraint with
//!   projection onto the rail and plastic re-contact, module `rigid`), `hertz`, or `bem`. Loss
//!   of contact (F = 0) and re-contact are handled by every law.
//!
//! # Time step (references.md §D4.2)
//! The contact-free system `M x'' + C x' + K x = f` (bridge modes and vehicle DOFs; gravity in
//! f) is advanced by an implicit [`StructuralMethod`](integrate::structural::StructuralMethod) of the `integrate` crate through its
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
//! * `quasi_newton` (the baseline coupling, references.md §D4.4): the forces are linearised in the approach only (the pressure
//!   shape ĝ_k is lagged), `J = A + s Σ_k k_c ĝ_k v_kᵀ`, solved by Sherman–Morrison (one wheel,
//!   denominator 1 + λ) or Woodbury (k wheels, k × k capacitance matrix) in O(n) per
//!   iteration ([`linalg::contact_update`]);
//! * `newton`: the same linearisation solved densely ([`linalg::dense_contact_update`]), the
//!   reference.
//!
//! A rigid contact enters all of them as a zero compliance (an exact constraint) whose row v_k
//! is its acceleration-level gradient u_k (module `rigid`); Picard needs compliant contacts. The quasi-Newton iteration starts from the predictor corrected by a
//! contact linearisation: a point contact's law at the predicted approach (the predictor's,
//! corrected by its error in the last step: `F ≈ F(δ*) + k(δ*)(δ − δ*)`), any other law at the
//! previous step's (`F ≈ F_n + k_n(δ − δ_n)`, column forces carried with the wheel). It
//! computes the BEM tangent at the first contact evaluation of a step only, and accepts the
//! corrected state with the linearised forces once every predicted force correction is within
//! the tolerance, or — after a start of point contacts, whose state carries known forces φ —
//! the state once the first evaluation is within the tolerance of φ; in a smooth run most
//! steps need one contact evaluation (two before 2026-11-28, issue #10). A step whose iteration fails (no convergence in `max_iter`, divergence,
//! a contact-solver failure) is retried as two half steps, recursively up to `max_halvings`
//! times; every retry is counted in [`SolverStats::failed_steps`], and a step that still fails
//! is an error. Multibody vehicles at rest ahead of the span are held out of the coupled step,
//! and vehicles off the span are solved on their own (modules `resting` and `detached`).
//!
//! # Start
//! Every wheel starts in static equilibrium on an undeformed rail: F_k = W_k =
//! (m_w + m_b) g + P, z_w = δ_static − r(x_k0), z_b = z_w + m_b g/k_s, moving with the rail
//! under it (ż_w = ż_b = −c r'(x_k0)); the bridge starts at rest and undeflected (wheels
//! normally start off the span, x_k0 ≤ 0).

mod accept;
mod assembly;
mod contact;
mod contact_eval;
mod coupling;
mod detached;
mod error;
pub mod irregularity;
mod law_residual;
pub mod linalg;
pub mod moving_forces;
mod outputs;
mod parts;
mod picard;
pub mod points;
pub mod profiles;
pub mod radau;
mod resting;
mod rigid;
pub mod run;
mod scenario;
mod step;
pub mod track;
pub mod traction;
pub mod vehicles;

use halfspace::law::{self, LawOutput};
use integrate::structural::{StepEquation, StructuralStepper};

use assembly::Structure;
pub use contact::{ContactGeometry, ContactSolves};
pub use error::VehicleBridgeError;
pub use irregularity::{Irregularity, RandomProfile, TrackSpectrum};
use linalg::{BlockDiagonal, CapacitanceWork, DenseWork};
pub use moving_forces::MovingForce;
pub use outputs::{SolverStats, WheelSample};
pub use parts::SimulationParts;
pub use radau::Radau5Spec;
pub use run::{
    Accuracy, Extremum, NoObserver, PointSummary, Range, RunFailure, RunObserver, RunSummary,
    StepInfo, WheelSummary,
};
pub use scenario::{
    ContactModel, CouplingSolver, CouplingSpec, Integrator, MAX_STATIC_SAG, Scenario, WheelSpec,
};
pub use vehicles::{MultibodyVehicle, VehicleLayout, VehicleResponse};

/// Standard gravity \[m/s²\].
pub const GRAVITY: f64 = 9.81;

/// Most steps of Δt a run may plan (checked by [`Simulation::new`] before anything is
/// allocated; about a day of wall time for the cheapest scenarios).
pub const MAX_STEPS: f64 = 1e8;

/// The simulation: state, stepper and work space.
pub struct Simulation {
    scenario: Scenario,
    /// The contact of each wheel: a force law or the rigid constraint.
    contacts: Vec<law::ContactModel>,
    /// The response tables shared by the BEM wheels (module [`contact`]).
    contact_tables: contact::ContactTables,
    structure: Structure,
    stepper: StructuralStepper,
    eq: StepEquation,
    /// Index of each wheel's DOF and of its body's DOF (if any).
    wheel_dof: Vec<usize>,
    body_dof: Vec<Option<usize>>,
    /// Multibody vehicles on the wheels (module [`vehicles`]).
    vehicles: Vec<vehicles::VehicleDofs>,
    /// Per wheel: the multibody vehicle it belongs to.
    wheel_vehicle: Vec<Option<usize>>,
    /// Static wheel loads W_k \[N\] and the force scale of the tolerance.
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
    /// `w_j(x_out)/(m_j ω_j²)` of the quasi-static deflection (`None` with a rigid-body mode).
    quasi_static_weights: Option<Vec<f64>>,
    loss_events: usize,
    /// Loss-of-contact events per wheel.
    wheel_loss_events: Vec<usize>,
    /// Contact tangent dF/dδ at the static load per wheel \[N/m\] (0 for the rigid contact).
    static_contact_stiffness: Vec<f64>,
    in_contact: Vec<bool>,
    /// Longitudinal friction (`None` = frictionless; see [`traction`]).
    traction: Option<traction::Traction>,
    /// The Radau5 path (`None` = the structural method of the scenario; see [`radau`]).
    radau: Option<radau::RadauPath>,
    /// Rigid contacts: constraint gradients, projection state (module `rigid`).
    rigid: rigid::RigidWork,
    /// A_j of the shapes A_j sin((j+1)πx/L) when the bridge is a simply supported uniform span
    /// (`beam::sine_amplitudes`): the wheel geometry then costs one `sin_cos` per wheel.
    sine: Option<Vec<f64>>,
    /// The track between the wheels and the bridge (`None`: the rail is the beam; module
    /// [`track`]).
    track: Option<Box<track::TrackLayer>>,
    /// Vehicles at rest ahead of the span, held out of the step (module [`resting`]).
    resting: resting::Resting,
    /// Response points besides the output point (module [`points`]).
    points: points::ResponsePoints,
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
    /// Per wheel: where ĝ and v can be non-zero (the modes and the wheel's DOF); every
    /// other entry of ĝ, v and their extrapolated copies stays zero.
    pattern: Vec<Vec<usize>>,
    /// Per wheel: the number of modes its mode shapes can be non-zero on: all m while the
    /// wheel or one of its columns is on the span, 0 off it (the per-wheel modal sums then
    /// skip their zero terms; the mode entries of ĝ and v are zeroed when the wheel leaves).
    span_modes: Vec<usize>,
    /// The moving forces' modal loads at the time of the last `moving_force_load` (m) and
    /// the mode shapes there (scratch, m).
    moving_load: Vec<f64>,
    force_shapes: Vec<f64>,
    /// The extrapolated start's ĝ and v per wheel.
    g_act: Vec<Vec<f64>>,
    v_act: Vec<Vec<f64>>,
    outputs: Vec<LawOutput>,
    delta: Vec<f64>,
    prev_force: Vec<f64>,
    /// Per wheel: the predictor's approach at the last extrapolated start, and the number of
    /// accepted steps + 1 then (0: none); see [`Work::start_point`].
    predicted: Vec<(f64, usize)>,
    last_df: Vec<f64>,
    active: Vec<usize>,
    compliance: Vec<f64>,
    delta_tilde: Vec<f64>,
    df: Vec<f64>,
    cap: CapacitanceWork,
    dense: DenseWork,
    /// Round-off bound of the step residual and its image under |A⁻¹| (n), and the contact
    /// forces' floating-point floor per wheel (see `Simulation::force_floor`).
    floor_residual: Vec<f64>,
    /// A x of the first iterate of the step (for the floor's e; see `Simulation::force_floor`).
    floor_ax: Vec<f64>,
    floor_ainv_g: Vec<f64>,
    /// Per wheel: its floor in the last step it took part in; the largest is `force_floor`.
    wheel_floor: Vec<f64>,
    force_floor: f64,
    /// The floor bounded where that decides the same (`Simulation::bound_force_floor`), and
    /// the steps whose floor was so bounded.
    floor_bound: bool,
    floor_bounded: u64,
    /// Convergence by the contact laws' residual (opt-in; module `law_residual`).
    law: law_residual::LawResidual,
}

impl Work {
    /// The approach at which the extrapolated start linearises wheel `k`'s law (a point
    /// contact), given the predictor's approach `delta_p` in the step after `steps` accepted
    /// ones: `δ̃ + (δ_n − δ̃_n)`, the predictor's approach corrected by the predictor's error
    /// in the previous step (the approach δ_n it converged to, `delta`, minus its predicted
    /// δ̃_n), when the wheel's last start was in that step; else `δ̃`. The predictor's error
    /// varies slowly from step to step, so this is closer to the converged approach than δ̃
    /// (any point gives the same converged step: it only saves iterations).
    fn start_point(&mut self, k: usize, delta_p: f64, steps: usize) -> f64 {
        let (last, stamp) = self.predicted[k];
        self.predicted[k] = (delta_p, steps + 1);
        let correction = self.delta[k] - last;
        if stamp == steps && correction.is_finite() {
            delta_p + correction
        } else {
            delta_p
        }
    }

    /// Bridge deflection under wheel k, `w(x_k) = Σ_j q_j w_j(x_k)` \[m\], at the state `x`
    /// (mode shapes of the last [`Simulation::wheel_geometry`]).
    #[inline]
    fn deflection_under(&self, k: usize, x: &[f64]) -> f64 {
        let shapes = &self.shape_at_wheel[k][..self.span_modes[k]];
        shapes.iter().enumerate().map(|(j, s)| x[j] * s).sum()
    }

    /// The approach of wheel k, `δ_k = z_w − w(x_k) + r(x_k)` \[m\] (module documentation),
    /// at the state `x`; `iw` is the wheel's DOF. The one place δ is computed.
    #[inline]
    fn approach(&self, k: usize, iw: usize, x: &[f64]) -> f64 {
        x[iw] - self.deflection_under(k, x) + self.r_at_wheel[k]
    }
}
