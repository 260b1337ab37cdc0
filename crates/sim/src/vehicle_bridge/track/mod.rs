//! The track between the wheels and the bridge (references.md §D5; docs/track.md): the rail on
//! discrete pads, sleepers and ballast of [`beam::track`], continuous over an approach
//! embankment, the bridge and an exit embankment, coupled into the vehicle–bridge simulation.
//!
//! # Model
//! The wheels contact the rail, not the beam: `δ_k = z_w − u_rail(x_k) + r(x_k)` with
//! `u_rail(x) = N(x)ᵀu` (the Hermite shape functions of the rail element under the wheel, the
//! same vector b_k = N(x_k) that loads the rail with the contact force, references.md §D5.2).
//! The chains on the span stand on the bridge modes (their last spring's force enters mode j
//! as φ_j(x_s) F). The bridge of the scenario carries its own mass only: the rail and the
//! chain masses are in the track.
//!
//! # Time step (references.md §D5.4; §D3.5, §D4.2)
//! The whole structure, track + bridge modes + vehicles (quarter cars, bogie vehicles), is one
//! linear system `M ẍ + C ẋ + K x = f + Σ_k F_k (b_k − e_k)` (e_k: wheel k's DOF), advanced
//! by a member of the generalized-α family (Newmark, HHT-α, generalized-α; the step equation
//! of [`integrate::structural::StepEquation`]). Its step matrix `A = c_M M + c_C C + c_K K`
//! is constant for a fixed Δt and factorised once (sparse Cholesky, `A = PᵀLLᵀP`). With the
//! contact vectors `v_k = e_k − b_k` (so `δ_k = v_kᵀx + r_k`), `z = L⁻¹P r` and
//! `y_k = L⁻¹P v_k` (a sparse forward sweep), the step's state is
//! `x = PᵀL⁻ᵀ(z − s Σ_k F_k y_k)` (s = 1 − α_f) and the approaches are
//!
//! ```text
//! δ = δ₀ − S F,   δ₀_k = y_kᵀz + r_k,   S_jk = s y_jᵀy_k   (the capacitance matrix),
//! ```
//!
//! so the contact forces of the step solve the k equations `F_k = F_law(δ₀_k − (S F)_k)` by
//! Newton's method on the k × k capacitance system (Woodbury's formula, every iteration costs
//! O(k²) + k law evaluations and no solve with A). One step costs one forward and one
//! backward sweep of the factor, k sparse forward sweeps and the sparse products of the
//! step load.
//!
//! # Contact models and moving forces
//! Hertz and the real-profile law (one column at the wheel) take the point path above; the
//! boundary-element grid (module `patch`) adds the rail's deflection shape under the patch to
//! its gap and loads the rail where the columns carry the force, solved on the contact DOFs'
//! Woodbury system; the rigid contact (module `constraint`) is the complementarity problem of
//! δ = δ₀ − S F. Moving forces load the rail through b(x_p + c t) (module `moving`).
//!
//! # Start
//! The static solution of the track and bridge under the static wheel loads (and moving
//! forces) at the start positions (`K u = Σ_k W_k b_k`), every wheel at its static approach
//! above the deflected rail (a BEM wheel with its patch's load distribution and column gaps),
//! velocities from the irregularity slope as without the track; a rigid wheel also moves with
//! the static rail's slope under it, c u'(x_k).

mod constraint;
mod factor;
mod moving;
mod patch;
mod step;

use beam::track::{
    RailBeam, RailPoint, RailSection, SparseCholesky, SparseReach, Track, TrackLayout,
    TrackSupports,
};
use faer::sparse::Triplet;
use integrate::structural::sparse::SparseMatrix;
use integrate::structural::{AlphaParameters, StructuralMethod};

use halfspace::law::{ContactModel as LawModel, LawOutput};

use super::error::{invalid, invalid_text};
use super::{ContactModel, CouplingSolver, Integrator, Simulation, VehicleBridgeError};
#[cfg(test)]
use factor::step_coefficients;
use factor::{factorise, nested_dissection};

/// The track of a vehicle–bridge scenario (`[track]`, parsed by `config::track`).
#[derive(Debug, Clone, PartialEq)]
pub struct TrackSpec {
    /// The model's name for reports: `ballasted` or `slab`, followed by the zones whose
    /// model differs (e.g. `ballasted, slab on the bridge`).
    pub model: String,
    /// The rail section.
    pub rail: RailSection,
    /// Length of track before the bridge \[m\] (the approach embankment).
    pub approach: f64,
    /// Length of track after the bridge \[m\] (the exit embankment).
    pub exit: f64,
    /// Sleeper (fastener) spacing \[m\].
    pub sleeper_spacing: f64,
    /// Rail elements per sleeper bay (even, 2 … 32).
    pub elements_per_bay: usize,
    /// The support chains of approach, bridge and exit.
    pub supports: TrackSupports,
}

/// The track's response at the current time (module documentation; docs/track.md).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TrackSample {
    /// Rail displacement under each wheel u_rail(x_k) \[m\] (down).
    pub rail_displacement: Vec<f64>,
    /// Position of the most loaded sleeper (largest pad force) \[m\] (bridge coordinate: 0 =
    /// the bridge's left end, negative on the approach).
    pub loaded_sleeper: f64,
    /// Pad force at the most loaded sleeper \[N\] (compression positive).
    pub pad_force: f64,
    /// Force in the spring under the sleeper at the most loaded sleeper \[N\]: the ballast
    /// (slab track: the CA mortar; a pad alone: the pad).
    pub ballast_force: f64,
    /// Rail displacement minus bridge deflection at the output point \[m\].
    pub rail_bridge_relative: f64,
}

/// The largest values of a run so far (over time, wheels and sleepers).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TrackMaxima {
    /// Largest rail displacement under a wheel \[m\].
    pub rail_displacement: f64,
    /// Largest pad force \[N\].
    pub pad_force: f64,
    /// Largest force under a sleeper (ballast) \[N\].
    pub ballast_force: f64,
    /// Largest |rail − bridge| displacement at the output point \[m\].
    pub rail_bridge_relative: f64,
}

/// The track part of a simulation: the assembled system, its factorised step matrix and
/// state, and the work space of a step.
pub(super) struct TrackLayer {
    track: Track,
    params: AlphaParameters,
    /// Index of the simulation's DOF i (modes, wheels, bodies, bogies) in the coupled system:
    /// `offset + i` (the modal DOFs of `track` are `offset..offset + m`).
    offset: usize,
    mass: SparseMatrix,
    damping: SparseMatrix,
    stiffness: SparseMatrix,
    gravity: Vec<f64>,
    /// The step matrix's factor and the Δt it was built for.
    factor: SparseCholesky,
    dt: f64,
    /// The step matrix's terms (M, C, K entries) and elimination order, to factorise it for
    /// the halved Δt of a failed step, and the factors built so far for other Δt.
    terms: [Vec<(usize, usize, f64)>; 3],
    ordering: Vec<usize>,
    other_factors: Vec<(f64, SparseCholesky)>,
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// Contact forces of the last accepted step and the rail points they acted on.
    forces: Vec<f64>,
    points: Vec<RailPoint>,
    /// The rail points of the step being solved (adopted as `points` when it is accepted: a
    /// failed attempt, retried in halves, keeps the old load where it acted).
    next_points: Vec<RailPoint>,
    /// Work space.
    q_pred: Vec<f64>,
    v_pred: Vec<f64>,
    r: Vec<f64>,
    tmp: Vec<f64>,
    tmp_c: Vec<f64>,
    y: Vec<Vec<f64>>,
    /// The non-zero pattern of each y_k (the reach of its sparse forward sweep).
    reach: Vec<SparseReach>,
    /// The contact solve's work space.
    newton: step::NewtonWork,
    /// The boundary-element contacts (`None`: point contacts or the rigid constraint).
    patch: Option<patch::PatchContacts>,
    /// The rigid contacts' solve (`None`: force laws).
    rigid: Option<constraint::RigidContacts>,
    /// The wheels' track coordinates at the step's end \[m\].
    positions: Vec<f64>,
    sample: TrackSample,
    maxima: TrackMaxima,
    /// Output point in track coordinates \[m\].
    output_x: f64,
}

/// The integrator's generalized-α parameters, or the error naming `integrator.method`.
fn alpha_parameters(integrator: &Integrator) -> Result<AlphaParameters, VehicleBridgeError> {
    const ALLOWED: &str = "[track] needs a method of the Newmark / HHT / generalized-alpha family (newmark with beta > 0, hht, generalized_alpha)";
    match integrator {
        Integrator::Structural(method) if !method.is_explicit() => method
            .alpha_parameters()
            .ok_or_else(|| invalid_text("integrator.method", method.name(), ALLOWED)),
        other => Err(invalid_text("integrator.method", other.name(), ALLOWED)),
    }
}

/// Whether a member of the generalized-α family damps the highest frequencies: γ > ½
/// (Newmark with γ > ½; HHT-α and generalized-α, whose γ = ½ − α_m + α_f exceeds ½ exactly
/// when α_f > α_m, i.e. α < 0 or ρ∞ < 1; references.md §D3.5). The rigid contact's
/// displacement-level constraint needs it (module [`constraint`]).
fn dissipative(p: &AlphaParameters) -> bool {
    p.gamma > 0.5 + 1e-9
}

/// Merged (row, column, value) entries in compressed-row form.
fn rows_of(n: usize, entries: &[(usize, usize, f64)]) -> Result<SparseMatrix, VehicleBridgeError> {
    let t: Vec<Triplet<usize, usize, f64>> = entries
        .iter()
        .map(|&(i, j, v)| Triplet::new(i, j, v))
        .collect();
    faer::sparse::SparseRowMat::try_new_from_triplets(n, n, &t).map_err(|e| {
        VehicleBridgeError::SingularStepMatrix {
            dof: 0,
            reason: format!("the track's matrices could not be assembled ({e:?})"),
        }
    })
}

/// Merges entries with equal (row, column).
fn merged(mut entries: Vec<(usize, usize, f64)>) -> Vec<(usize, usize, f64)> {
    entries.sort_by_key(|&(i, j, _)| (i, j));
    let mut out: Vec<(usize, usize, f64)> = Vec::with_capacity(entries.len());
    for (i, j, v) in entries {
        match out.last_mut() {
            Some(last) if last.0 == i && last.1 == j => last.2 += v,
            _ => out.push((i, j, v)),
        }
    }
    out
}

impl Simulation {
    /// [`Simulation::with_vehicles`] with the track of `spec` between the wheels and the
    /// bridge (module [`track`](self)). Needs a method of the Newmark / HHT / generalized-α
    /// family (with numerical dissipation for the rigid contact), the capacitance Newton
    /// coupling, and a track long enough for every wheel over the whole run; an error names
    /// the key otherwise.
    pub fn with_track(
        scenario: super::Scenario,
        layouts: Vec<super::VehicleLayout>,
        spec: TrackSpec,
    ) -> Result<Self, VehicleBridgeError> {
        let params = alpha_parameters(&scenario.integrator)?;
        if let Integrator::Structural(StructuralMethod::Newmark { beta, gamma }) =
            scenario.integrator
        {
            // The rail's stiffest modes have ω Δt far beyond any stability limit: Newmark must
            // be unconditionally stable, 2β ≥ γ ≥ ½ (references.md §D3.5; measured: γ = 0.6
            // with the default β = 0.25 gave NaN within 0.1 s with the rigid contact and a
            // failed Hertz contact after 43 steps).
            if 2.0 * beta < gamma - 1e-12 {
                return Err(invalid(
                    "integrator.beta",
                    beta,
                    &format!(
                        "[track] needs an unconditionally stable Newmark method, beta >= gamma/2 = {:.4} (the rail's stiffest modes are far beyond a conditional stability limit); beta = (gamma + 0.5)^2/4 = {:.4} damps the highest frequencies most",
                        0.5 * gamma,
                        0.25 * (gamma + 0.5) * (gamma + 0.5)
                    ),
                ));
            }
        }
        if scenario.contact == ContactModel::Rigid && !dissipative(&params) {
            const WHY: &str = "the rigid contact on [track] needs a method with numerical dissipation (generalized_alpha with rho_inf < 1, hht with alpha < 0, or newmark with gamma > 0.5 and beta >= gamma/2): the constraint on the step's displacements makes the trapezoidal rule's contact force oscillate undamped at 2 dt and the wheel chatter";
            // Name the parameter that removes the dissipation where the method has one.
            return Err(match scenario.integrator {
                Integrator::Structural(StructuralMethod::GeneralizedAlpha { rho_inf }) => {
                    invalid("integrator.rho_inf", rho_inf, WHY)
                }
                Integrator::Structural(StructuralMethod::Hht { alpha }) => {
                    invalid("integrator.alpha", alpha, WHY)
                }
                _ => invalid_text("integrator.method", scenario.integrator.name(), WHY),
            });
        }
        if scenario.contact == ContactModel::Rigid && spec.rail.beam() == RailBeam::Timoshenko {
            // The element's displacement interpolation has a slope jump at every node (its
            // shear strain is constant per element) that a rigid wheel must follow: a velocity
            // jump, so an impulse, at each node it passes (measured: the Manchester car at
            // 70 m/s, 54E1, 8 elements per bay: 177 losses of contact, 248 kN against 101–117 kN
            // on the Euler–Bernoulli rail); the compliant contacts filter it.
            return Err(invalid_text(
                "contact.model",
                "rigid",
                "the rigid contact cannot ride on track.rail_beam = \"timoshenko\" (the element's slope jumps at the nodes give the wheel an impulse at every node it passes): use contact.model = \"hertz\" or \"bem\", or rail_beam = \"euler_bernoulli\"",
            ));
        }
        if scenario.coupling.solver == CouplingSolver::Picard {
            return Err(invalid_text(
                "coupling.solver",
                "picard",
                "[track] solves the contact forces by Newton's method on the capacitance system (quasi_newton or newton)",
            ));
        }
        let mut sim = Self::with_vehicles(scenario, layouts)?;
        let layer = TrackLayer::new(&mut sim, spec, params)?;
        sim.track = Some(Box::new(layer));
        sim.track_start_outputs()?;
        sim.track_samples()?;
        Ok(sim)
    }

    /// The contact outputs of the static start (the patch contacts' are left by their static
    /// start): a point law at the wheel's approach, the rigid constraint with the static load.
    fn track_start_outputs(&mut self) -> Result<(), VehicleBridgeError> {
        let layer = self.track.as_ref().expect("called with a track");
        if layer.patch.is_some() {
            return Ok(());
        }
        let q = self.stepper.q();
        for k in 0..self.scenario.wheels.len() {
            let x = self.scenario.wheels[k].position;
            let rail = layer.rail_point(x)?.value(&layer.q);
            let delta = q[self.wheel_dof[k]] - rail + self.scenario.irregularity.height(x);
            self.work.outputs[k] = match &mut self.contacts[k] {
                LawModel::Law(law) => law
                    .evaluate(delta, &[0.0], &mut [0.0], true)
                    .map_err(super::contact::wheel_error(k))?,
                LawModel::Rigid(_) => LawOutput {
                    force: self.static_loads[k],
                    ..LawOutput::default()
                },
            };
            self.work.delta[k] = delta;
        }
        Ok(())
    }

    /// The track's response at the current time (`None` without a track).
    pub fn track_sample(&self) -> Option<&TrackSample> {
        self.track.as_ref().map(|t| &t.sample)
    }

    /// The largest track responses so far (`None` without a track).
    pub fn track_maxima(&self) -> Option<TrackMaxima> {
        self.track.as_ref().map(|t| t.maxima)
    }

    /// Stored entries of the Cholesky factor of the track's step matrix (`None` without a
    /// track).
    pub fn track_factor_entries(&self) -> Option<usize> {
        self.track.as_ref().map(|t| t.factor.factor_entries())
    }

    /// The track model (`None` without a track).
    pub fn track_model(&self) -> Option<&Track> {
        self.track.as_ref().map(|t| &t.track)
    }

    /// The displacements of the coupled track system (track DOFs, bridge modes, then the
    /// simulation's vehicle DOFs; `None` without a track).
    pub fn track_state(&self) -> Option<&[f64]> {
        self.track.as_ref().map(|t| &t.q[..])
    }
}

impl TrackLayer {
    /// Builds the coupled system of `sim` (already set up without the track) and its static
    /// start; hands the start state to `sim`'s stepper.
    fn new(
        sim: &mut Simulation,
        spec: TrackSpec,
        params: AlphaParameters,
    ) -> Result<Self, VehicleBridgeError> {
        let sc = &sim.scenario;
        let length = sc.bridge.length();
        let layout = TrackLayout::new(spec.approach, length, spec.exit, spec.sleeper_spacing)
            .and_then(|l| l.with_elements_per_bay(spec.elements_per_bay))
            .map_err(track_key)?;
        // Every wheel and every moving force on the track for the whole run: a moving force
        // stepping onto (or off) the free end of the modelled rail would load (or unload) it
        // suddenly, a transient of the model's boundary that the real track, continuing beyond it,
        // does not have (measured: a 153.8 kN axle entering the rail's start at 60 m/s, the
        // largest pad force 178.8 kN against 52.7 kN with the rail 55 m longer).
        // A wheel's extent is its contact patch's (the grid columns of a BEM law, ±|ξ|max): the
        // patch's gap reads the rail under every column (module `patch`).
        let extent = |k: usize| match &sim.contacts[k] {
            LawModel::Law(law) => law.columns().iter().fold(0.0f64, |m, c| m.max(c.abs())),
            _ => 0.0,
        };
        let positions = || {
            sc.wheels
                .iter()
                .enumerate()
                .map(|(k, w)| (w.position - extent(k), w.position + extent(k)))
                .chain(sc.moving_forces.iter().map(|p| (p.position, p.position)))
        };
        let first = positions().map(|p| p.0).fold(f64::INFINITY, f64::min);
        let last = positions().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        if first + spec.approach < 0.0 {
            return Err(invalid(
                "track.approach_length",
                spec.approach,
                &format!(
                    "every wheel (with its contact patch) and moving force must start on the track: at least {} m (the rearmost axle starts at x = {first} m, 0 = the bridge's left end)",
                    -first
                ),
            ));
        }
        let reach = last + sc.speed * sim.planned_steps() as f64 * sc.dt;
        if reach > length + spec.exit {
            return Err(invalid(
                "track.exit_length",
                spec.exit,
                &format!(
                    "every wheel (with its contact patch) and moving force must stay on the track until the end of the run: at least {:.6} m (the leading axle reaches x = {reach:.6} m on a {length} m bridge)",
                    reach - length
                ),
            ));
        }
        let track = Track::on_bridge(spec.rail, layout, &spec.supports, &*sc.bridge, &sc.damping)
            .map_err(track_key)?;
        let m = sc.bridge.n_modes();
        let offset = track.n_track_dofs();
        let n_sim = sim.stepper.q().len();
        let n = offset + n_sim;
        // M, C, K: the track's (with the modes) and the vehicles' (simulation DOFs ≥ m).
        let s = &sim.structure;
        let vehicle = |mat: &faer::Mat<f64>| -> Vec<(usize, usize, f64)> {
            let mut e = Vec::new();
            for i in m..n_sim {
                for j in m..n_sim {
                    if mat[(i, j)] != 0.0 {
                        e.push((offset + i, offset + j, mat[(i, j)]));
                    }
                }
            }
            e
        };
        let assemble = |track_part: &[(usize, usize, f64)], mat: &faer::Mat<f64>| {
            let mut all = track_part.to_vec();
            all.extend(vehicle(mat));
            merged(all)
        };
        let mass = assemble(track.mass_entries(), &s.mass);
        let damping = assemble(track.damping_entries(), &s.damping);
        let stiffness = assemble(track.stiffness_entries(), &s.stiffness);
        let mut gravity = vec![0.0; n];
        gravity[offset + m..].copy_from_slice(&s.gravity_load[m..]);
        let dt = sc.dt;
        let ordering = nested_dissection(&track, n);
        let factor = factorise(n, &mass, &damping, &stiffness, &params, dt, &ordering)?;

        // Static start: the track and bridge under the static wheel loads.
        let nw = sc.wheels.len();
        let approach = spec.approach;
        let mut points = Vec::with_capacity(nw);
        let mut positions = Vec::with_capacity(nw);
        let mut load = vec![0.0; track.n_dofs()];
        moving::add_moving_loads(&track, sc, 0.0, 1.0, &mut load)?;
        let mut patch = patch::PatchContacts::of(&sim.contacts);
        let base = patch.as_ref().map(|_| load.clone());
        for (k, w) in sc.wheels.iter().enumerate() {
            let p = track.rail_point(w.position + approach).map_err(track_key)?;
            for a in 0..4 {
                load[p.dofs[a]] += sim.static_loads[k] * p.weights[a];
            }
            points.push(p);
            positions.push(w.position + approach);
        }
        // The wheels' static approaches: the patches' on the statically deflected rail (their
        // load distributed as they carry it), the laws' own otherwise (with_vehicles).
        let mut q_sim = sim.stepper.q().to_vec();
        let (u_track, shift) = match (patch.as_mut(), base) {
            (Some(patch), Some(base)) => {
                let wheel_dofs: Vec<usize> = sim.wheel_dof.iter().map(|&d| offset + d).collect();
                let (u, approaches) = patch.static_start(
                    &track,
                    &mut sim.contacts,
                    &positions,
                    &sim.static_loads,
                    &base,
                    &wheel_dofs,
                    &mut sim.work.outputs,
                )?;
                let shift: Vec<f64> = (0..nw)
                    .map(|k| {
                        let x = sc.wheels[k].position;
                        approaches[k] - (q_sim[sim.wheel_dof[k]] + sc.irregularity.height(x))
                    })
                    .collect();
                sim.work.delta[..nw].copy_from_slice(&approaches);
                (u, shift)
            }
            _ => (
                track.static_solution(&load).map_err(track_key)?,
                vec![0.0; nw],
            ),
        };
        // The vehicles ride on the deflected rail: each wheel (and its quarter-car body) moves
        // down with the rail under it, a bogie vehicle's bodies take their statics anew.
        q_sim[..m].copy_from_slice(&u_track[offset..]);
        for k in 0..nw {
            let u = points[k].value(&u_track) + shift[k];
            q_sim[sim.wheel_dof[k]] += u;
            if let Some(ib) = sim.body_dof[k] {
                q_sim[ib] += u;
            }
        }
        for v in &sim.vehicles {
            super::assembly::static_vehicle(v, &s.stiffness, &s.gravity_load, &mut q_sim)?;
        }
        let mut v_sim = sim.stepper.v().to_vec();
        v_sim[..m].fill(0.0);
        // A rigid wheel starts with the velocity c u_rail'(x_k) of the static rail point under
        // it (tied to the rail, it cannot take a jump of relative velocity without an impulse;
        // u' by a central difference over ±1 µm of the cubic Hermite interpolation).
        if sim.contacts.iter().all(super::contact::is_rigid) {
            let h = 1e-6;
            let rail_length = track.layout().rail_length();
            for (k, w) in sc.wheels.iter().enumerate() {
                let x = w.position + approach;
                // One-sided within h of the rail's ends (a wheel may stand on the end).
                let (xa, xb, width) = if x - h >= 0.0 && x + h <= rail_length {
                    (x - h, x + h, 2.0 * h)
                } else {
                    let (xa, xb) = ((x - h).max(0.0), (x + h).min(rail_length));
                    (xa, xb, xb - xa)
                };
                let slope = (track.rail_displacement(xb, &u_track).map_err(track_key)?
                    - track.rail_displacement(xa, &u_track).map_err(track_key)?)
                    / width;
                v_sim[sim.wheel_dof[k]] += sc.speed * slope;
                if let Some(ib) = sim.body_dof[k] {
                    v_sim[ib] += sc.speed * slope;
                }
            }
        }
        let mut q = vec![0.0; n];
        q[..offset].copy_from_slice(&u_track[..offset]);
        q[offset..].copy_from_slice(&q_sim);
        let mut v = vec![0.0; n];
        v[offset..].copy_from_slice(&v_sim);
        // Start accelerations: the track is in static equilibrium at rest; the vehicle DOFs
        // (diagonal mass) take a = M⁻¹(f − C v − K q) with the static contact forces.
        let mut a = vec![0.0; n];
        let mut a_sim = vec![0.0; n_sim];
        for i in m..n_sim {
            let mii = s.mass[(i, i)];
            if mii <= 0.0 {
                continue;
            }
            let mut f = s.gravity_load[i];
            for j in m..n_sim {
                f -= s.damping[(i, j)] * v_sim[j] + s.stiffness[(i, j)] * q_sim[j];
            }
            if let Some(k) = sim.wheel_dof.iter().position(|&iw| iw == i) {
                f -= sim.static_loads[k];
            }
            a_sim[i] = f / mii;
            a[offset + i] = a_sim[i];
        }
        sim.stepper
            .restart_with_acceleration(&mut sim.structure, 0.0, &q_sim, &v_sim, &a_sim)?;
        let output_x = sim.scenario.output_point + approach;
        let reach = (0..nw).map(|_| factor.new_reach()).collect();
        Ok(Self {
            params,
            offset,
            mass: rows_of(n, &mass)?,
            damping: rows_of(n, &damping)?,
            stiffness: rows_of(n, &stiffness)?,
            gravity,
            factor,
            dt,
            terms: [mass, damping, stiffness],
            ordering,
            other_factors: Vec::new(),
            forces: sim.static_loads.clone(),
            next_points: points.clone(),
            points,
            q_pred: vec![0.0; n],
            v_pred: vec![0.0; n],
            r: vec![0.0; n],
            tmp: vec![0.0; n],
            tmp_c: vec![0.0; n],
            y: vec![vec![0.0; n]; nw],
            reach,
            newton: step::NewtonWork::new(nw),
            rigid: sim
                .contacts
                .iter()
                .all(super::contact::is_rigid)
                .then(|| constraint::RigidContacts::new(nw)),
            patch,
            positions,
            q,
            v,
            a,
            sample: TrackSample {
                rail_displacement: vec![0.0; nw],
                ..TrackSample::default()
            },
            maxima: TrackMaxima::default(),
            output_x,
            track,
        })
    }

    /// Rail point of a wheel at bridge coordinate x.
    fn rail_point(&self, x: f64) -> Result<RailPoint, VehicleBridgeError> {
        self.track
            .rail_point(x + self.track.layout().approach())
            .map_err(track_key)
    }
}

/// The failure of a contact solve `solver` after `iterations` (the step fills in its time).
fn solve_failure(solver: &'static str, iterations: usize, reason: &str) -> VehicleBridgeError {
    VehicleBridgeError::CouplingFailed {
        solver,
        t: f64::NAN,
        dt: f64::NAN,
        halvings: 0,
        iterations,
        change: f64::NAN,
        reason: reason.to_string(),
    }
}

/// A track-model error as an input error of the `[track]` table (`track.<name>`).
fn track_key(e: beam::BeamError) -> VehicleBridgeError {
    match e {
        beam::BeamError::InvalidParameter {
            name,
            value,
            reason,
        } => invalid(format!("track.{name}"), value, reason),
        beam::BeamError::InvalidCount {
            name,
            value,
            reason,
        } => invalid(format!("track.{name}"), value as f64, reason),
        other => VehicleBridgeError::from(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use integrate::structural::StructuralMethod;

    /// The step coefficients of Newmark's average acceleration: c_M = 4/Δt², c_C = 2/Δt,
    /// c_K = 1 (exact).
    #[test]
    fn average_acceleration_coefficients() {
        let p = StructuralMethod::average_acceleration()
            .alpha_parameters()
            .unwrap();
        let (cm, cc, ck) = step_coefficients(&p, 0.5);
        assert_eq!((cm, cc, ck), (16.0, 4.0, 1.0));
        assert!(
            alpha_parameters(&Integrator::Structural(StructuralMethod::BackwardEuler)).is_err()
        );
    }
}
