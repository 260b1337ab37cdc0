//! `kind = "vehicle_bridge"`: wheels over a modal bridge with local contact
//! (docs/vehicle_bridge.md). Every key is in SI units; unknown keys are errors.

use std::path::Path;

use halfspace::law::ContactLaw;
use serde::Deserialize;

use super::ConfigError;
use super::bridge::BridgeSpec;
use super::checks::{self, MAX_ITERATIONS, ranges};
use super::integrator::StructuralParameters;
use super::irregularity::irregularity;
pub use super::irregularity::{
    DEFAULT_IRREGULARITY_COMPONENTS, DEFAULT_LAMBDA_MAX, DEFAULT_LAMBDA_MIN, IrregularitySpec,
    MAX_IRREGULARITY_WORK,
};
pub use super::train_wheels::MAX_ARTICULATED_BODIES;
use super::train_wheels::train_wheels;
pub(crate) use super::wheel_contact::contact_of;
pub use super::wheel_contact::{
    ContactSpec, DEFAULT_BEM_GRID, DEFAULT_BEM_TOL, DEFAULT_CONTACT_MODEL, DEFAULT_GEOMETRY,
    ProfilesToml,
};
use crate::vehicle_bridge::traction::{TractionDrive, TractionMethod, TractionSpec};
use crate::vehicle_bridge::{
    ContactModel, CouplingSolver, CouplingSpec, GRAVITY, Integrator, Irregularity, Radau5Spec,
    Scenario, WheelSpec,
};
use crate::vehicle_bridge_series::SeriesLayout;

mod series;
use series::check_run_length;
pub use series::{DEFAULT_SERIES_VALUES, default_every};

/// Default structural method.
pub const DEFAULT_METHOD: &str = "newmark";
/// Default structural method of a rigid contact on a `[track]`: there the constraint acts on
/// the step's displacements, which needs numerical dissipation (`Simulation::with_track`
/// refuses the trapezoidal rule, whose contact force oscillates undamped at 2 Δt there), so
/// the default is the generalized-α method with its default ρ∞ (unless Newmark's `beta`/`gamma`
/// or HHT's `alpha` are given: they name their method).
pub const DEFAULT_METHOD_RIGID_TRACK: &str = "generalized_alpha";
/// Default time step \[s\], the longest default: a compliant contact shortens it to
/// [`DEFAULT_DT_CONTACT`] / f_c (see [`default_dt`]).
pub const DEFAULT_DT: f64 = 1e-4;
/// Default Δt·f_c of the fastest contact mode (40 steps per period of a wheel bouncing on
/// its contact spring at the static load): a quarter of the accuracy limit
/// [`MAX_DT_CONTACT`](crate::vehicle_bridge::run::MAX_DT_CONTACT), which leaves room for the
/// stiffening of a Hertzian contact under force peaks (f_c ∝ F^{1/6}: an impact at 32 W
/// still has 22 steps per contact period, ~11 over the impact). With half the limit the
/// scenario zoo found an impact peak at 32 W 5.7 % low (case 16 of the default set).
pub const DEFAULT_DT_CONTACT: f64 = 0.25 * crate::vehicle_bridge::run::MAX_DT_CONTACT;
/// The same for backward Euler, whose first-order damping of the contact mode needs
/// Δt·f_c ≤ [`MAX_DT_CONTACT_FIRST_ORDER`](crate::vehicle_bridge::run::MAX_DT_CONTACT_FIRST_ORDER).
pub const DEFAULT_DT_CONTACT_FIRST_ORDER: f64 =
    0.5 * crate::vehicle_bridge::run::MAX_DT_CONTACT_FIRST_ORDER;
/// Default coupling solver (tolerance and limits: [`CouplingSpec::default`]).
pub const DEFAULT_COUPLING_SOLVER: &str = "quasi_newton";
/// Default number of pressure snapshots.
pub const DEFAULT_SNAPSHOTS: usize = 6;
/// Largest number of pressure snapshots.
pub const MAX_SNAPSHOTS: usize = 1000;
/// Default FASTSIM elements per direction of `[traction]`.
pub const DEFAULT_FASTSIM_ELEMENTS: usize = 40;
/// A validated vehicle–bridge scenario.
pub struct VehicleBridgeConfig {
    /// The scenario of [`crate::vehicle_bridge::Simulation::new`].
    pub scenario: Scenario,
    /// Bogie vehicles on the scenario's wheels ([`crate::vehicle_bridge::Simulation::with_vehicles`]).
    pub vehicles: Vec<crate::vehicle_bridge::VehicleLayout>,
    /// The train of a `[train]` scenario (for the report).
    pub train: Option<crate::train::Train>,
    /// Longitudinal friction (`[traction]`), if given.
    pub traction: Option<TractionSpec>,
    /// Record every n-th step (`output.every`; when not given, [`default_every`]).
    pub every: usize,
    /// Whether `every` is the default ([`default_every`]) rather than the file's.
    pub every_is_default: bool,
    /// Number of pressure snapshots (`output.snapshots`).
    pub snapshots: usize,
    /// Warnings for the user (the scenario is valid but has a known weakness).
    pub warnings: Vec<String>,
    /// The track between the wheels and the bridge (`[track]`; `None`: the rail is the beam;
    /// [`crate::vehicle_bridge::Simulation::with_track`]).
    pub track: Option<crate::vehicle_bridge::track::TrackSpec>,
    /// Response points of the bridge besides the output point (`output.points` \[m\];
    /// [`crate::vehicle_bridge::Simulation::set_output_points`]).
    pub points: Vec<f64>,
}

impl VehicleBridgeConfig {
    /// Takes the parts of the simulation out of the configuration (vehicles, track,
    /// traction, response points), leaving the report's (train, output settings).
    pub fn take_parts(&mut self) -> crate::vehicle_bridge::SimulationParts {
        crate::vehicle_bridge::SimulationParts {
            vehicles: std::mem::take(&mut self.vehicles),
            track: self.track.take(),
            traction: self.traction.take(),
            points: std::mem::take(&mut self.points),
        }
    }
}

/// The scenario file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleBridgeFile {
    pub kind: String,
    pub bridge: BridgeSpec,
    pub vehicle: Option<VehicleSpec>,
    /// A train instead of `[vehicle]` (quarter cars and sprung masses; docs/trains.md).
    pub train: Option<super::train::TrainTable>,
    pub contact: Option<ContactSpec>,
    pub irregularity: Option<IrregularitySpec>,
    pub integrator: Option<IntegratorSpec>,
    pub coupling: Option<CouplingToml>,
    pub output: Option<OutputSpec>,
    /// Longitudinal friction (optional; docs/vehicle_bridge.md, "Traction (friction)").
    pub traction: Option<TractionToml>,
    /// The track between the wheels and the bridge (optional; docs/track.md).
    pub track: Option<super::track::TrackToml>,
}

/// `[traction]`: friction coefficient, tangential method and either a prescribed creepage or
/// a wheel torque [N m] with the wheel's polar inertia [kg m²].
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionToml {
    pub mu: f64,
    pub method: Option<String>,
    pub creepage: Option<f64>,
    pub torque: Option<f64>,
    pub wheel_inertia: Option<f64>,
    pub fastsim_elements: Option<usize>,
}

/// The `[traction]` section (`None` when absent: no friction). Values are range-checked by
/// [`TractionSpec::validate`] with errors naming the key.
fn traction(traction: Option<&TractionToml>) -> Result<Option<TractionSpec>, ConfigError> {
    let Some(t) = traction else {
        return Ok(None);
    };
    let name = t.method.as_deref().unwrap_or("fastsim");
    let method = TractionMethod::by_name(name).ok_or_else(|| {
        invalid!("[traction] `method` = \"{name}\": expected exact, fastsim or linear")
    })?;
    let drive = match (t.creepage, t.torque, t.wheel_inertia) {
        (Some(xi), None, None) => TractionDrive::Creepage(xi),
        (None, Some(torque), Some(inertia)) => TractionDrive::Torque { torque, inertia },
        (None, Some(_), None) => bail!("[traction]: `torque` needs `wheel_inertia` [kg m²]"),
        (None, None, Some(_)) => bail!("[traction]: `wheel_inertia` applies with `torque` only"),
        (None, None, None) => bail!("[traction]: give exactly one of `creepage` or `torque`"),
        (Some(_), _, _) => {
            bail!("[traction]: `creepage` and `torque`/`wheel_inertia` exclude each other")
        }
    };
    let spec = TractionSpec {
        mu: t.mu,
        method,
        drive,
        fastsim_elements: t.fastsim_elements.unwrap_or(DEFAULT_FASTSIM_ELEMENTS),
    };
    spec.validate().map_err(|e| invalid!("[traction]: {e}"))?;
    ranges::FRICTION.check("traction.mu", spec.mu)?;
    match spec.drive {
        TractionDrive::Creepage(xi) => {
            ranges::CREEPAGE.check("traction.creepage", xi)?;
        }
        TractionDrive::Torque { torque, inertia } => {
            ranges::TORQUE.check("traction.torque", torque)?;
            ranges::INERTIA.check("traction.wheel_inertia", inertia)?;
        }
    }
    checks::count("traction.fastsim_elements", spec.fastsim_elements, 1, 1000)?;
    Ok(Some(spec))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleSpec {
    pub speed: f64,
    pub wheels: Vec<WheelToml>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WheelToml {
    pub position: Option<f64>,
    pub wheel_mass: f64,
    pub body_mass: Option<f64>,
    pub suspension_stiffness: Option<f64>,
    pub suspension_damping: Option<f64>,
    pub static_load: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    pub method: Option<String>,
    pub dt: Option<f64>,
    pub beta: Option<f64>,
    pub gamma: Option<f64>,
    pub alpha: Option<f64>,
    pub rho_inf: Option<f64>,
    pub duration: Option<f64>,
    /// Radau5 tolerances (only with `method = "radau5"`).
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
}

/// `[integrator] method = "radau5"`: the Radau5 tolerances (`rtol`, `atol`; defaults of
/// [`Radau5Spec`]), or `None` for a structural method. `rtol`/`atol` with another method are
/// an error naming the key.
fn radau5(integrator: Option<&IntegratorSpec>) -> Result<Option<Radau5Spec>, ConfigError> {
    let Some(i) = integrator else {
        return Ok(None);
    };
    let radau = i
        .method
        .as_deref()
        .is_some_and(|m| m.trim().eq_ignore_ascii_case("radau5"));
    if !radau {
        for (key, v) in [("rtol", i.rtol), ("atol", i.atol)] {
            if v.is_some() {
                bail!("[integrator] `{key}` is only used by method = \"radau5\"");
            }
        }
        return Ok(None);
    }
    let d = Radau5Spec::default();
    Ok(Some(Radau5Spec {
        rtol: ranges::TOLERANCE.check("integrator.rtol", i.rtol.unwrap_or(d.rtol))?,
        atol: ranges::ABS_TOLERANCE.check("integrator.atol", i.atol.unwrap_or(d.atol))?,
    }))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CouplingToml {
    pub solver: Option<String>,
    pub tol: Option<f64>,
    pub max_iter: Option<usize>,
    pub max_halvings: Option<usize>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Record every n-th step.
    pub every: Option<usize>,
    /// Output point of the bridge response \[m\] (default midspan).
    pub point: Option<f64>,
    /// More response points of the bridge \[m\] (deflection, velocity and acceleration in
    /// the time series, their extrema in the summary; default none).
    pub points: Option<Vec<f64>>,
    /// Number of pressure snapshots along the passage.
    pub snapshots: Option<usize>,
}

/// Parses and validates a scenario file's text (profile files of `[contact.profiles]`
/// relative to the working directory).
pub fn parse(text: &str) -> Result<VehicleBridgeConfig, ConfigError> {
    build(super::from_str(text)?)
}

/// Parses and validates a scenario file's text, profile files of `[contact.profiles]`
/// relative to `base`.
pub fn parse_in(text: &str, base: &Path) -> Result<VehicleBridgeConfig, ConfigError> {
    build_in(super::from_str(text)?, base)
}

/// The wheels of `[vehicle]`.
fn vehicle_wheels(vehicle: &VehicleSpec) -> Result<Vec<WheelSpec>, ConfigError> {
    checks::count(
        "vehicle.wheels",
        vehicle.wheels.len(),
        0,
        checks::MAX_WHEELS,
    )?;
    if vehicle.wheels.is_empty() {
        bail!("[vehicle]: at least one [[vehicle.wheels]] table is needed");
    }
    Ok(vehicle
        .wheels
        .iter()
        .map(|w| WheelSpec {
            position: w.position.unwrap_or(0.0),
            wheel_mass: w.wheel_mass,
            body_mass: w.body_mass.unwrap_or(0.0),
            suspension_stiffness: w.suspension_stiffness.unwrap_or(0.0),
            suspension_damping: w.suspension_damping.unwrap_or(0.0),
            static_load: w.static_load.unwrap_or(0.0),
        })
        .collect())
}

/// Validates a parsed scenario file (profile files of `[contact.profiles]` relative to the
/// working directory).
pub fn build(file: VehicleBridgeFile) -> Result<VehicleBridgeConfig, ConfigError> {
    build_in(file, Path::new("."))
}

/// Validates a parsed scenario file, profile files of `[contact.profiles]` relative to `base`.
pub fn build_in(file: VehicleBridgeFile, base: &Path) -> Result<VehicleBridgeConfig, ConfigError> {
    // Sizes first, before the bridge's modes are computed.
    let (wheels, speed, vehicles, moving_forces, train) = match (&file.vehicle, &file.train) {
        (Some(vehicle), None) => (
            vehicle_wheels(vehicle)?,
            vehicle.speed,
            Vec::new(),
            Vec::new(),
            None,
        ),
        (None, Some(table)) => {
            let (on_track, speed) = train_wheels(table)?;
            (
                on_track.wheels,
                speed,
                on_track.layouts,
                on_track.forces,
                Some(super::train::build(table, "train")?),
            )
        }
        (Some(_), Some(_)) => {
            bail!("[train] replaces [vehicle] and [[vehicle.wheels]]: give one of them")
        }
        (None, None) => bail!("missing [vehicle] with [[vehicle.wheels]] (or [train])"),
    };
    if file.kind != "vehicle_bridge" {
        bail!("`kind` = \"{}\": expected \"vehicle_bridge\"", file.kind);
    }
    let bridge = file.bridge.build()?;
    let length = bridge.basis.length();
    let bridge_output_point = bridge.default_output_point();

    let c = file.contact.as_ref();
    let (contact, geometry) = contact_of(c, wheels.len(), Some(base))?;
    if let Some(table) = &file.train {
        super::train_wheels::check_sprung_masses(table, &contact)?;
    }

    let irregularity = match &file.irregularity {
        None => Irregularity::None,
        Some(spec) => irregularity(spec, geometry.wheel_radius)?,
    };

    let integ = file.integrator.as_ref();
    let rigid_on_track = matches!(contact, ContactModel::Rigid)
        && file
            .track
            .as_ref()
            .is_some_and(|t| !t.model.trim().eq_ignore_ascii_case("none"));
    // Without a method, parameters of the Newmark family (beta, gamma) or HHT's alpha name
    // their method on the track too (gamma = 0.6 alone is a dissipative Newmark).
    let given = |f: fn(&IntegratorSpec) -> Option<f64>| integ.and_then(f).is_some();
    let method_name = integ.and_then(|i| i.method.as_deref()).unwrap_or(
        if !rigid_on_track || given(|i| i.beta) || given(|i| i.gamma) {
            DEFAULT_METHOD
        } else if given(|i| i.alpha) {
            "hht"
        } else {
            DEFAULT_METHOD_RIGID_TRACK
        },
    );
    let params = StructuralParameters {
        beta: integ.and_then(|i| i.beta),
        gamma: integ.and_then(|i| i.gamma),
        alpha: integ.and_then(|i| i.alpha),
        rho_inf: integ.and_then(|i| i.rho_inf),
    };
    let integrator = match radau5(integ)? {
        Some(spec) => Integrator::Radau5(spec),
        None => Integrator::Structural(params.method(method_name, &["radau5"])?),
    };
    let mut warnings = Vec::new();
    let dt = integ.and_then(|i| i.dt).unwrap_or(f64::NAN);
    let duration = integ.and_then(|i| i.duration);

    let cp = file.coupling.as_ref();
    let solver_name = cp
        .and_then(|c| c.solver.as_deref())
        .unwrap_or(DEFAULT_COUPLING_SOLVER);
    let solver = CouplingSolver::by_name(solver_name).ok_or_else(|| {
        invalid!("[coupling] `solver` = \"{solver_name}\": expected picard, quasi_newton or newton")
    })?;
    let defaults = CouplingSpec::default();
    let coupling = CouplingSpec {
        solver,
        tol: cp.and_then(|c| c.tol).unwrap_or(defaults.tol),
        max_iter: cp.and_then(|c| c.max_iter).unwrap_or(defaults.max_iter),
        max_halvings: cp
            .and_then(|c| c.max_halvings)
            .unwrap_or(defaults.max_halvings),
    };
    let out = file.output.as_ref();
    let every_given = out.and_then(|o| o.every);
    if every_given == Some(0) {
        bail!("[output] `every` must be at least 1");
    }
    let snapshots = checks::count(
        "output.snapshots",
        out.and_then(|o| o.snapshots).unwrap_or(DEFAULT_SNAPSHOTS),
        0,
        MAX_SNAPSHOTS,
    )?;
    let output_point = match out.and_then(|o| o.point) {
        Some(x) => x,
        None => {
            let (x, note) = bridge_output_point;
            warnings.extend(note);
            x
        }
    };
    let default_points = bridge.other_span_midpoints(output_point);
    let scenario = Scenario {
        output_point,
        bridge: bridge.basis,
        damping: bridge.damping,
        wheels,
        moving_forces,
        speed,
        contact,
        geometry,
        irregularity,
        integrator,
        dt,
        duration,
        coupling,
        gravity: GRAVITY,
    };
    let mut scenario = scenario;
    let dt_given = !scenario.dt.is_nan();
    if !dt_given {
        scenario.dt = DEFAULT_DT;
    }
    check_ranges(&scenario)?;
    if !dt_given {
        scenario.dt = default_dt(&scenario)?;
    }
    // Without `points`, a continuous bridge reports the midspan of every other span too.
    let points = match out.and_then(|o| o.points.as_deref()) {
        Some(p) => checks::points_on_span(p, 0, length)?,
        None => default_points,
    };
    let layout = SeriesLayout {
        wheels: scenario.wheels.len(),
        traction: file.traction.is_some(),
        track: file.track.is_some(),
        points: points.clone(),
        car_bodies: vehicles.iter().map(|v| v.vehicle.bodies()).sum(),
    };
    let every = every_given.unwrap_or_else(|| default_every(&scenario, &layout));
    check_run_length(&scenario, every, layout.width())?;
    check_implicit(&scenario)?;
    check_coupling(&scenario)?;
    let traction = traction(file.traction.as_ref())?;
    if traction.is_some() && matches!(scenario.contact, ContactModel::BemProfiles(_)) {
        bail!(
            "[traction]: not available with [contact.profiles] (the creep forces use the Hertz geometry of contact.wheel_radius and contact.rail_profile_radius; the profile contact is normal only)"
        );
    }
    let track = super::track::track(file.track.as_ref())?;
    if let Some(t) = &track {
        super::track::check_size(t, length)?;
        super::track::check_method(method_name, &scenario.integrator)?;
    }
    Ok(VehicleBridgeConfig {
        scenario,
        vehicles,
        train,
        traction,
        every,
        every_is_default: every_given.is_none(),
        snapshots,
        warnings,
        track,
        points,
    })
}

pub(crate) fn check_ranges(s: &Scenario) -> Result<(), ConfigError> {
    for (k, w) in s.wheels.iter().enumerate() {
        let key = |f: &str| format!("vehicle.wheels[{k}].{f}");
        ranges::POSITION.check(&key("position"), w.position)?;
        for (name, mass) in [("wheel_mass", w.wheel_mass), ("body_mass", w.body_mass)] {
            if mass != 0.0 && !ranges::VEHICLE_MASS.contains(mass) {
                bail!(
                    "`{}` = {}: must be 0 or lie in {}",
                    key(name),
                    checks::number(mass),
                    ranges::VEHICLE_MASS
                );
            }
        }
        ranges::STIFFNESS.check(&key("suspension_stiffness"), w.suspension_stiffness)?;
        ranges::DAMPER.check(&key("suspension_damping"), w.suspension_damping)?;
        ranges::FORCE.check(&key("static_load"), w.static_load)?;
    }
    ranges::SPEED.check("vehicle.speed", s.speed)?;
    s.geometry.material().map_err(|e| invalid!("{e}"))?;
    ranges::RADIUS.check("contact.wheel_radius", s.geometry.wheel_radius)?;
    ranges::RADIUS.check(
        "contact.rail_profile_radius",
        s.geometry.rail_profile_radius,
    )?;
    ranges::MODULUS.check("contact.E", s.geometry.youngs_modulus)?;
    check_patch_small(s)?;
    ranges::TIME_STEP.check("integrator.dt", s.dt)?;
    ranges::DURATION.check_opt("integrator.duration", s.duration)?;
    ranges::TOLERANCE.check("coupling.tol", s.coupling.tol)?;
    checks::count("coupling.max_iter", s.coupling.max_iter, 1, MAX_ITERATIONS)?;
    checks::count("coupling.max_halvings", s.coupling.max_halvings, 0, 40)?;
    let length = s.bridge.length();
    if !(s.output_point.is_finite() && (0.0..=length).contains(&s.output_point)) {
        bail!(
            "`output.point` = {}: must lie on the span [0, {length}] m",
            checks::number(s.output_point)
        );
    }
    Ok(())
}

/// Largest Hertz approach under a static wheel load, as a fraction of the smaller radius of
/// curvature: δ ≤ 0.01 min(R_w, R_r) keeps the patch semi-axes below about 0.1 of the radii
/// (δ ≈ a²/R), where the half-space idealisation of both compliant laws holds
/// (references.md §C4.1).
const MAX_APPROACH_PER_RADIUS: f64 = 0.01;

/// The compliant contact laws need a patch small against the wheel and rail-head radii
/// (half-space contact); a tiny radius under a wheel load would put the BEM grid outside the
/// wheel circle. Checked under each wheel's static load (rigid contact has no patch).
fn check_patch_small(s: &Scenario) -> Result<(), ConfigError> {
    if matches!(
        s.contact,
        ContactModel::Rigid | ContactModel::BemProfiles(_)
    ) {
        // The profile contact sizes each patch from its own curvatures (ProfileLaw).
        return Ok(());
    }
    let mut law = s.geometry.hertz().map_err(|e| invalid!("{e}"))?;
    let radius = s.geometry.wheel_radius.min(s.geometry.rail_profile_radius);
    for (k, w) in s.wheels.iter().enumerate() {
        let load = (w.wheel_mass + w.body_mass) * s.gravity + w.static_load;
        if load.is_nan() || load <= 0.0 {
            continue;
        }
        let approach = law.static_approach(load).map_err(|e| invalid!("{e}"))?;
        if approach > MAX_APPROACH_PER_RADIUS * radius {
            bail!(
                "`contact.wheel_radius` = {} m, `contact.rail_profile_radius` = {} m: the static load {} N of vehicle.wheels[{k}] gives a Hertz approach of {:.3e} m, more than {MAX_APPROACH_PER_RADIUS} × the smaller radius, so the contact patch is not small against the radii and half-space contact does not apply (use larger radii, a stiffer material or contact.model = \"rigid\")",
                checks::number(s.geometry.wheel_radius),
                checks::number(s.geometry.rail_profile_radius),
                checks::number(load),
                approach,
            );
        }
    }
    Ok(())
}

/// The time step when `integrator.dt` is not given: [`DEFAULT_DT`], shortened so that the
/// fastest contact mode, a wheel of mass m_w bouncing on its contact spring
/// k_c = dF/dδ = 3W/(2δ) at its static load W (Hertz, references.md §C4.1; the BEM law
/// has the same stiffness to its discretisation error), has Δt·f_c ≤ [`DEFAULT_DT_CONTACT`]
/// (≤ [`DEFAULT_DT_CONTACT_FIRST_ORDER`] with backward Euler), f_c = √(k_c/m_w)/2π. Rigid
/// contact and massless wheels have no contact mode; Radau5 adapts its own steps.
pub fn default_dt(s: &Scenario) -> Result<f64, ConfigError> {
    let first_order = match s.integrator {
        Integrator::Radau5(_) => return Ok(DEFAULT_DT),
        Integrator::Structural(method) => method.name() == "backward_euler",
    };
    if s.contact == ContactModel::Rigid {
        return Ok(DEFAULT_DT);
    }
    let target = if first_order {
        DEFAULT_DT_CONTACT_FIRST_ORDER
    } else {
        DEFAULT_DT_CONTACT
    };
    let mut law: Box<dyn ContactLaw> = match &s.contact {
        ContactModel::BemProfiles(p) => Box::new(
            p.law(s.geometry.material().map_err(|e| invalid!("{e}"))?)
                .map_err(|e| invalid!("[contact.profiles]: {e}"))?,
        ),
        _ => Box::new(s.geometry.hertz().map_err(|e| invalid!("{e}"))?),
    };
    let mut dt = DEFAULT_DT;
    // Contact stiffness per static load (the profile law solves for it; trains repeat loads).
    let mut known: Vec<(f64, f64)> = Vec::new();
    for w in &s.wheels {
        let load = (w.wheel_mass + w.body_mass) * s.gravity + w.static_load;
        if !(w.wheel_mass > 0.0 && load > 0.0) {
            continue;
        }
        let stiffness = match known.iter().find(|(l, _)| *l == load) {
            Some(&(_, k)) => k,
            None => {
                let k = static_stiffness(law.as_mut(), load)?;
                known.push((load, k));
                k
            }
        };
        let f_c = (stiffness / w.wheel_mass).sqrt() / std::f64::consts::TAU;
        if f_c.is_finite() && f_c > 0.0 {
            dt = dt.min(target / f_c);
        }
    }
    Ok(dt)
}

/// The contact stiffness dF/dδ of `law` at its static approach under `load` \[N\]: 3W/(2δ)
/// for the Hertz law (references.md §C4.1), the profile law's own tangent.
fn static_stiffness(law: &mut dyn ContactLaw, load: f64) -> Result<f64, ConfigError> {
    let approach = law.static_approach(load).map_err(|e| invalid!("{e}"))?;
    if law.name() != "bem_profiles" {
        return Ok(1.5 * load / approach);
    }
    let mut force = [0.0];
    let out = law
        .evaluate(approach, &[0.0], &mut force, true)
        .map_err(|e| invalid!("{e}"))?;
    Ok(if out.stiffness > 0.0 {
        out.stiffness
    } else {
        1.5 * load / approach
    })
}

/// The coupled step needs an implicit structural method (not for Radau5).
pub(crate) fn check_implicit(s: &Scenario) -> Result<(), ConfigError> {
    if let Integrator::Structural(method) = s.integrator
        && method.is_explicit()
    {
        bail!(
            "`integrator.method` = \"{}\": the coupled step needs an implicit method (newmark with beta > 0, hht, generalized_alpha, backward_euler, radau5)",
            method.name()
        );
    }
    Ok(())
}

/// Combinations of `coupling.solver` and `contact.model` that cannot work.
fn check_coupling(s: &Scenario) -> Result<(), ConfigError> {
    if s.coupling.solver == CouplingSolver::Picard && s.contact == ContactModel::Rigid {
        bail!(
            "`coupling.solver` = \"picard\": picard needs a compliant contact (contact.model = \"hertz\" or \"bem\"); a rigid contact has no force law to iterate on: use quasi_newton or newton"
        );
    }
    Ok(())
}
