//! The rigid wheel–rail contact as a moving mass (references.md §D1.2): while a wheel is on
//! the rail its vertical motion is that of the rail point under it,
//!
//! ```text
//! z_w = w(x_k, t) − r(x_k),   x_k = x_k0 + c t,   δ = z_w − w(x_k) + r(x_k) = 0,
//! δ̈ = z̈_w − Σ_j (w_j q̈_j + 2c w_j' q̇_j + c² w_j'' q_j) + c² r'' = 0,
//! ```
//!
//! so the wheel's mass rides on the bridge with its convective (Coriolis and centripetal)
//! terms: eliminating z̈_w and the multiplier F from the wheel row gives the glued-mass modal
//! equations `(M + m_w φφᵀ) q̈ + (C + 2c m_w φφ'ᵀ) q̇ + (K + c² m_w φφ''ᵀ) q = f` of
//! references.md §D1.2 (φ = w_j(x_k), φ' and φ'' its slope and curvature).
//!
//! # Index reduction and projection
//! The constraint is imposed at the *acceleration* level (index 1) in every step, with the
//! step's own kinematics `a = (x − q̃)/c_qa`, `v = ṽ + c_va a` (references.md §D4.2):
//!
//! ```text
//! C_k(x) = c_qa δ̈_{n+1}(x) = u_kᵀ x + b_k = 0,
//! u_k = +1 on the wheel, −(w_j + 2c c_va w_j' + c_qa c² w_j'') on mode j
//! ```
//!
//! (for the trapezoidal rule and backward Euler). The α-schemes (HHT, generalized-α) weight it
//! like their balance equation, inertia with α_m and the convective and rail terms with α_f,
//!
//! ```text
//! (1 − α_m) ā_{n+1} + α_m ā_n = (1 − α_f) κ_{n+1} + α_f κ_n,
//! ā = a_w − Σ_j w_j a_j,   κ = Σ_j (2c w_j' v_j + c² w_j'' q_j) − c² r'',
//! ```
//!
//! so that the wheel row returns the contact force at t_{n+1} (imposing ā_{n+1} = κ_{n+1} alone
//! made generalized-α's multiplier overshoot a jump of the rail curvature by
//! (α_f − α_m)/(1 − α_f) and decay like ρ∞ⁿ). It is
//! a linear constraint with the force direction ĝ_k of the compliant laws, so the
//! Sherman–Morrison / Woodbury update of the coupling ([`super::linalg::contact_update`],
//! compliance 0, δ̃ = C_k) solves it in O(n). After each step the wheel is projected back
//! onto the rail (displacement and velocity, `Simulation::rigid_finish`); the projection
//! removes the O(Δt³) drift of the acceleration-level constraint. A displacement-level
//! (index-3) multiplier, by contrast, leaves the wheel's velocity and acceleration as
//! differences of its prescribed positions, which the trapezoidal rule (ρ∞ = 1) turns into an
//! undamped 2Δt oscillation of the multiplier after any slope kink; here the wheel carries no
//! memory of that kind and every integrator gives a smooth contact force.
//!
//! # Loss of contact and re-contact
//! * A wheel on the rail whose multiplier would become negative is released for the step
//!   (F = 0; it flies freely under gravity and its suspension).
//! * The projection moves the wheel onto the rail surface (Δz_w = −δ; the bridge state is left
//!   as the step computed it) and removes the relative velocity δ̇ = ż_w − ẇ(x_k) + c r' in the
//!   mass metric of the wheel and the bridge point: with `S = Σ_j w_j²/M_j`,
//!   `Δż_w = −δ̇/(1 + m_w S)`, `Δq̇_j = m_w w_j δ̇/(M_j (1 + m_w S))`, a perfectly inelastic
//!   (plastic) impact with the impulse `Π = m_w δ̇/(1 + m_w S)` that conserves the momentum of
//!   wheel plus bridge (a massless wheel simply takes the rail's motion). For a wheel held on
//!   the rail both corrections are of the order of the step's truncation error.
//! * A flying wheel found penetrating the rail at the end of a step (δ > 0) has landed: it is
//!   put on the rail and, if it still approaches (δ̇ > 0), stopped by the plastic impact; it
//!   is then on the rail again.
//! * Landing time: before each step the gap of every flying wheel is predicted by its Taylor
//!   expansion `δ(τ) = δ + δ̇ τ + δ̈ τ²/2` at the step's start (free flight and bridge point
//!   are smooth between events, so the root τ* errs by O(Δt²)); the step is split at the
//!   first root τ* ∈ (0, Δt] (`Simulation::advance_locating_landings`), the wheel is landed at
//!   the end of that piece (put on the rail, plastic impact) whatever the sign of its
//!   O(τ³) residual gap, and the rest of the step follows. Landing at the end of the step
//!   instead made the impact time err by up to Δt: an erratic first-order error (the scenario
//!   zoo's case 19 peak deflection 6.1 % off at Δt = 1e-4 s, 0.21 % located).
//! * A wheel on the rail that meets a slope kink (the span ends, a kinked irregularity) needs
//!   a velocity jump; if the impulse to follow the rail, added to the step's contact impulse
//!   Δt F, would pull (Δt F + Π < 0), the wheel leaves the rail with its own velocity instead.

use beam::Derivative;

use super::{Simulation, VehicleBridgeError};

/// Step of the central differences of the rail irregularity's slope and curvature \[m\]
/// (truncation h² r⁗/12 and round-off ε r/h² both far below the curvature of any profile the
/// scenario validation admits).
const RAIL_DIFFERENCE_STEP: f64 = 1e-4;

/// Work space and state of the rigid contacts (preallocated; nothing is allocated per step).
#[derive(Debug, Default)]
pub(super) struct RigidWork {
    /// Per wheel: mode slopes w_j' and curvatures w_j'' at the wheel (m entries each).
    slope: Vec<Vec<f64>>,
    curvature: Vec<Vec<f64>>,
    /// Per wheel: rail slope r' and curvature r'' at the wheel.
    rail_slope: Vec<f64>,
    rail_curvature: Vec<f64>,
    /// Per wheel: the constraint gradient u_k (n entries) and offset b_k \[m\].
    gradient: Vec<Vec<f64>>,
    offset: Vec<f64>,
    /// Per wheel, at the start of the step (the α-schemes' old terms): the relative
    /// acceleration `a_w − Σ_j w_j a_j` and the convective and rail terms
    /// `Σ_j (2c w_j' v_j + c² w_j'' q_j) − c² r''` \[m/s²\].
    old_relative_acceleration: Vec<f64>,
    old_convective: Vec<f64>,
    /// Per wheel: the constraint value C_k(x) at the current iterate \[m\].
    pub(super) residual: Vec<f64>,
    /// Per wheel: released in this step (its multiplier would have become negative).
    pub(super) released: Vec<bool>,
    /// Per wheel: on the rail at the end of the step.
    pub(super) attached: Vec<bool>,
    /// Per wheel: a landing located inside the step ends the (sub-)step that reaches
    /// `landing_time` (module documentation, "Landing time").
    landing_due: Vec<bool>,
    /// The located landing time \[s\] (meaningful while a `landing_due` is set).
    landing_time: f64,
    /// State copies for the projection (n entries each).
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
}

impl RigidWork {
    /// Work space for `nw` wheels, `m` modes and `n` DOFs; empty unless `rigid`.
    pub(super) fn new(rigid: bool, nw: usize, m: usize, n: usize) -> Self {
        if !rigid {
            return Self::default();
        }
        Self {
            slope: vec![vec![0.0; m]; nw],
            curvature: vec![vec![0.0; m]; nw],
            rail_slope: vec![0.0; nw],
            rail_curvature: vec![0.0; nw],
            gradient: vec![vec![0.0; n]; nw],
            offset: vec![0.0; nw],
            old_relative_acceleration: vec![0.0; nw],
            old_convective: vec![0.0; nw],
            residual: vec![0.0; nw],
            released: vec![false; nw],
            attached: vec![true; nw],
            landing_due: vec![false; nw],
            landing_time: 0.0,
            q: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
        }
    }

    /// `true` if the work space was built for rigid contacts.
    fn is_used(&self) -> bool {
        !self.gradient.is_empty()
    }
}

impl Simulation {
    /// Slope and curvature of the modes and of the rail under every wheel at the wheels'
    /// current positions (`samples[k].position`, set by [`Simulation::wheel_geometry`]).
    fn rigid_geometry(&mut self) -> Result<(), VehicleBridgeError> {
        let basis = &*self.scenario.bridge;
        let length = basis.length();
        let rw = &mut self.rigid;
        for k in 0..self.scenario.wheels.len() {
            let x = self.samples[k].position;
            if (0.0..=length).contains(&x) {
                basis.eval_all(x, Derivative::Slope, &mut rw.slope[k])?;
                basis.eval_all(x, Derivative::Curvature, &mut rw.curvature[k])?;
            } else {
                rw.slope[k].fill(0.0);
                rw.curvature[k].fill(0.0);
            }
            let irr = &self.scenario.irregularity;
            let h = RAIL_DIFFERENCE_STEP;
            let (r_minus, r0, r_plus) = (irr.height(x - h), irr.height(x), irr.height(x + h));
            rw.rail_slope[k] = (r_plus - r_minus) / (2.0 * h);
            rw.rail_curvature[k] = (r_plus - 2.0 * r0 + r_minus) / (h * h);
        }
        Ok(())
    }

    /// The old terms of the α-weighted constraint at the current state (after
    /// [`Simulation::rigid_geometry`] at the current time): per wheel the relative acceleration
    /// `a_w − Σ_j w_j a_j` and the convective and rail terms (module documentation).
    fn rigid_old_terms(&mut self) {
        let m = self.scenario.bridge.n_modes();
        let c = self.scenario.speed;
        let (q, v, a) = (self.stepper.q(), self.stepper.v(), self.stepper.a());
        let rw = &mut self.rigid;
        for k in 0..self.scenario.wheels.len() {
            let shapes = &self.work.shape_at_wheel[k];
            let (slope, curv) = (&rw.slope[k], &rw.curvature[k]);
            let mut rel = a[self.wheel_dof[k]];
            let mut conv = -c * c * rw.rail_curvature[k];
            for j in 0..m {
                rel -= shapes[j] * a[j];
                conv += 2.0 * c * slope[j] * v[j] + c * c * curv[j] * q[j];
            }
            rw.old_relative_acceleration[k] = rel;
            rw.old_convective[k] = conv;
        }
    }

    /// The start of a run: the old terms of the first step (after
    /// [`Simulation::wheel_geometry`] at t = 0).
    pub(super) fn rigid_start(&mut self) -> Result<(), VehicleBridgeError> {
        if !self.rigid.is_used() {
            return Ok(());
        }
        self.rigid_geometry()?;
        self.rigid_old_terms();
        Ok(())
    }

    /// The geometry at the step's end (after [`Simulation::wheel_geometry`]) and the
    /// constraint gradients u_k and offsets b_k of the step (module documentation), with
    /// ρ = (1 − α_f)/(1 − α_m) and ā_n, κ_n the old relative acceleration and convective terms:
    ///
    /// ```text
    /// u_k = +1 on the wheel, −(w_j + ρ (2c c_va w_j' + c_qa c² w_j'')) on mode j,
    /// b_k = −q̃_w + Σ_j [w_j q̃_j − 2ρc w_j' (c_qa ṽ_j − c_va q̃_j)] + ρ c_qa c² r''
    ///       + c_qa (α_m ā_n − α_f κ_n)/(1 − α_m).
    /// ```
    pub(super) fn rigid_setup(&mut self) -> Result<(), VehicleBridgeError> {
        if !self.rigid.is_used() {
            return Ok(());
        }
        self.rigid_geometry()?;
        let m = self.scenario.bridge.n_modes();
        let c = self.scenario.speed;
        let eq = &self.eq;
        let (c_qa, c_va) = (
            eq.displacement_per_acceleration,
            eq.velocity_per_acceleration,
        );
        let rho = (1.0 - eq.alpha_f) / (1.0 - eq.alpha_m);
        let rw = &mut self.rigid;
        for k in 0..self.scenario.wheels.len() {
            let iw = self.wheel_dof[k];
            let shapes = &self.work.shape_at_wheel[k];
            let (slope, curv) = (&rw.slope[k], &rw.curvature[k]);
            let u = &mut rw.gradient[k];
            u.fill(0.0);
            u[iw] = 1.0;
            let old =
                eq.alpha_m * rw.old_relative_acceleration[k] - eq.alpha_f * rw.old_convective[k];
            let mut b = -eq.q_pred[iw]
                + rho * c_qa * c * c * rw.rail_curvature[k]
                + c_qa * old / (1.0 - eq.alpha_m);
            for j in 0..m {
                u[j] = -(shapes[j] + rho * (2.0 * c * c_va * slope[j] + c_qa * c * c * curv[j]));
                b += shapes[j] * eq.q_pred[j]
                    - 2.0 * rho * c * slope[j] * (c_qa * eq.v_pred[j] - c_va * eq.q_pred[j]);
            }
            rw.offset[k] = b;
            rw.released[k] = false;
        }
        Ok(())
    }

    /// For the rigid wheels at the iterate `work.x` (after
    /// [`Simulation::evaluate_contacts`]): the constraint gradient u_k replaces the approach
    /// gradient v_k of the coupling update, and `rigid.residual` gets C_k(x) = u_kᵀx + b_k.
    pub(super) fn rigid_constraints(&mut self) {
        if !self.rigid.is_used() {
            return;
        }
        let w = &mut self.work;
        let rw = &mut self.rigid;
        for k in 0..rw.gradient.len() {
            w.v[k].copy_from_slice(&rw.gradient[k]);
            rw.residual[k] = super::linalg::dot(&rw.gradient[k], &w.x) + rw.offset[k];
        }
    }

    /// After an accepted step: projects the wheels on the rail back onto it, lands the flying
    /// wheels that reached it, releases those that a slope kink throws off (module
    /// documentation), and restarts the stepper at the projected state if anything moved.
    /// `rigid.attached` gets the new contact state; `work.delta` the approach.
    pub(super) fn rigid_finish(&mut self, dt: f64) -> Result<(), VehicleBridgeError> {
        if !self.rigid.is_used() {
            return Ok(());
        }
        let m = self.scenario.bridge.n_modes();
        let c = self.scenario.speed;
        let rw = &mut self.rigid;
        rw.q.copy_from_slice(self.stepper.q());
        rw.v.copy_from_slice(self.stepper.v());
        rw.a.copy_from_slice(self.stepper.a());
        let mut moved = false;
        for k in 0..self.scenario.wheels.len() {
            let iw = self.wheel_dof[k];
            let shapes = &self.work.shape_at_wheel[k];
            let mass = self.scenario.wheels[k].wheel_mass;
            // S = Σ w_j²/M_j and the wheel's share 1/(1 + m_w S) of a correction.
            let s: f64 = (0..m)
                .map(|j| shapes[j] * shapes[j] / self.structure.mass[(j, j)])
                .sum();
            let wheel_share = 1.0 / (1.0 + mass * s);
            let gap = |q: &[f64]| -> f64 {
                q[iw] - (0..m).map(|j| shapes[j] * q[j]).sum::<f64>() + self.work.r_at_wheel[k]
            };
            let rate = |q: &[f64], v: &[f64]| -> f64 {
                v[iw]
                    - (0..m)
                        .map(|j| shapes[j] * v[j] + c * rw.slope[k][j] * q[j])
                        .sum::<f64>()
                    + c * rw.rail_slope[k]
            };
            let held = self.in_contact[k] && !rw.released[k];
            let delta = gap(&rw.q);
            let mut attached = held;
            // A landing located at this step's end (`rigid_landing_time`; the wheel is within
            // the O(τ³) error of the prediction of the rail).
            let due = rw.landing_due[k] && self.stepper.t() >= rw.landing_time - 1e-9 * dt;
            if held || delta > 0.0 || due {
                // The wheel back onto the rail (for a held wheel an O(Δt³) drift; for a
                // landing the penetration of its last step).
                rw.q[iw] -= delta;
                let rel = rate(&rw.q, &rw.v);
                let impulse = wheel_share * mass * rel;
                let force = self.forces[k];
                if held && dt * force + impulse < 0.0 {
                    // A kink throws the wheel off: it keeps its own velocity.
                    attached = false;
                } else if held || rel > 0.0 {
                    rw.v[iw] -= wheel_share * rel;
                    for j in 0..m {
                        rw.v[j] +=
                            wheel_share * mass * shapes[j] * rel / self.structure.mass[(j, j)];
                    }
                    attached = true;
                } else {
                    // Landed while already separating: on the rail, not held.
                    attached = false;
                }
                moved = true;
            }
            rw.attached[k] = attached;
        }
        if moved {
            let t = self.stepper.t();
            self.stepper
                .restart_with_acceleration(&mut self.structure, t, &rw.q, &rw.v, &rw.a)?;
        }
        let q = self.stepper.q();
        for k in 0..self.scenario.wheels.len() {
            self.work.delta[k] = self.work.approach(k, self.wheel_dof[k], q);
        }
        self.rigid_old_terms();
        Ok(())
    }
}

/// Shortest piece \[fraction of Δt\] into which a located landing splits a step: a landing
/// predicted closer than this to either end of the step is taken at that end (its time then
/// errs by at most this fraction of Δt).
const MIN_LANDING_SPLIT: f64 = 1e-3;

/// The smallest root τ ∈ (0, h] of `δ + δ̇ τ + δ̈ τ²/2` (a gap δ ≤ 0 closing), if any.
fn first_gap_root(delta: f64, rate: f64, accel: f64, h: f64) -> Option<f64> {
    let (a, b, c) = (0.5 * accel, rate, delta);
    let mut best = f64::INFINITY;
    let mut consider = |tau: f64| {
        if tau.is_finite() && tau > 0.0 && tau <= h {
            best = best.min(tau);
        }
    };
    if a.abs() * h <= 1e-12 * b.abs() {
        consider(-c / b);
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            consider(q / a);
            consider(c / q);
        }
    }
    best.is_finite().then_some(best)
}

impl Simulation {
    /// Locates the first landing of a flying rigid wheel within the next `h` seconds from the
    /// Taylor expansion of its gap at the current state, `δ(τ) = δ + δ̇ τ + δ̈ τ²/2` with
    /// δ̇ = ż_w − Σ_j (w_j q̇_j + c w_j' q_j) + c r' and δ̈ = ā − κ (module documentation);
    /// the wheel's free flight and the bridge point are smooth, so τ errs by O(h²).
    /// Flags the wheel that lands first and returns τ.
    fn rigid_landing_time(&mut self, h: f64) -> Option<f64> {
        if !self.rigid.is_used() {
            return None;
        }
        let m = self.scenario.bridge.n_modes();
        let c = self.scenario.speed;
        let (q, v) = (self.stepper.q(), self.stepper.v());
        let rw = &mut self.rigid;
        rw.landing_due.fill(false);
        let mut first: Option<(usize, f64)> = None;
        for k in 0..self.scenario.wheels.len() {
            if self.in_contact[k] || self.scenario.wheels[k].wheel_mass == 0.0 {
                continue;
            }
            let iw = self.wheel_dof[k];
            let shapes = &self.work.shape_at_wheel[k];
            let mut delta = q[iw] + self.work.r_at_wheel[k];
            let mut rate = v[iw] + c * rw.rail_slope[k];
            for j in 0..m {
                delta -= shapes[j] * q[j];
                rate -= shapes[j] * v[j] + c * rw.slope[k][j] * q[j];
            }
            if delta > 0.0 {
                continue;
            }
            let accel = rw.old_relative_acceleration[k] - rw.old_convective[k];
            if let Some(tau) = first_gap_root(delta, rate, accel, h)
                && first.is_none_or(|(_, t)| tau < t)
            {
                first = Some((k, tau));
            }
        }
        let (k, tau) = first?;
        rw.landing_due[k] = true;
        Some(tau)
    }

    /// Advances by `dt` with the structural stepper, split at the located landings of flying
    /// rigid wheels (`rigid_landing_time`): the step ends at the landing time, the landing
    /// wheel is put on the rail with its plastic impact there (`rigid_finish`), and the rest of
    /// the step follows. Without rigid contacts or flights this is one `advance(dt)`.
    pub(super) fn advance_locating_landings(&mut self, dt: f64) -> Result<(), VehicleBridgeError> {
        let mut remaining = dt;
        let min_split = MIN_LANDING_SPLIT * dt;
        for _ in 0..=self.scenario.wheels.len() {
            let Some(tau) = self.rigid_landing_time(remaining) else {
                break;
            };
            let piece = if tau >= remaining - min_split {
                remaining
            } else {
                tau.max(min_split)
            };
            self.rigid.landing_time = self.t() + piece;
            let stepped = self.advance(piece, 0);
            self.rigid.landing_due.fill(false);
            stepped?;
            remaining -= piece;
            if remaining <= 0.0 {
                return Ok(());
            }
        }
        self.advance(remaining, 0)
    }
}
