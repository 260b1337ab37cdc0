//! `kind = "sweep"`: every train at every speed over one bridge (docs/sweep.md). Parsed and
//! range-checked here, in one place; the sweep itself is [`crate::sweep`].
//!
//! ```toml
//! kind = "sweep"
//! [bridge]                 # as moving_load, plus:
//! modes = "eurocode"       # or a number: every mode up to max(30 Hz, 1.5 f1, f3)
//! damping = "eurocode"     # with `type`: EN 1991-2 Table 6.6 + Δζ (eq. 6.13); or damping_ratio
//! type = "prestressed_concrete"
//! [trains]
//! names = ["HSLM-A"]       # HSLM-A (all ten), HSLM-A1 … HSLM-A10, real trains (AVE-S103, …)
//! model = "moving_forces"  # or "interaction": the vehicle models with [contact] (as vehicle_bridge)
//! [speeds]                 # m/s: from/to/step, or list
//! from = 38.8889
//! to = 116.6667
//! step = 1.388889
//! [output]
//! points = [10.0]          # default: the midspan of each span
//! [check]
//! track = "ballasted"      # 3.5 m/s²; "ballastless": 5 m/s²
//! ```

use serde::Deserialize;

use super::ConfigError;
use super::bridge::{Bridge, BridgeSpec};
use super::checks::{self, ranges};
use crate::sweep::eurocode::{self, BridgeType, Track};
use crate::sweep::interaction::{InteractionModel, TrainVehicles};
use crate::sweep::{SweepModel, SweepSpec};
use crate::train::{MovingForces, Train, VehicleSpec, hslm, presets};

/// Steps per period of the highest retained mode (default time step 1/(40 f_max)): the sampled
/// peak of an oscillation is then low by at most (π/40)²/2 = 0.31 %.
pub const STEPS_PER_PERIOD: f64 = 40.0;
/// Default free vibration after the last axle has left, in periods of mode 1.
pub const FREE_VIBRATION_PERIODS: f64 = 2.0;
/// Largest number of passages of one sweep.
pub const MAX_PASSAGES: usize = 1_000_000;
/// Largest total number of time steps of a sweep (all passages).
pub const MAX_TOTAL_STEPS: f64 = 1e11;
/// Candidate modes searched for `modes = "eurocode"`.
const MAX_EUROCODE_MODES: usize = 200;

/// The file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepFile {
    /// `"sweep"`.
    pub kind: String,
    /// The bridge table (as moving_load, plus `modes = "eurocode"`, `damping = "eurocode"`,
    /// `type`).
    pub bridge: toml::Table,
    /// The trains.
    pub trains: TrainsSpec,
    /// The speeds.
    pub speeds: SpeedsSpec,
    /// Output points.
    pub output: Option<OutputSpec>,
    /// The check.
    pub check: Option<CheckSpec>,
    /// Time step and free vibration.
    pub integrator: Option<IntegratorSpec>,
    /// The wheel–rail contact of the interaction model (the keys of vehicle_bridge's
    /// `[contact]`).
    pub contact: Option<super::vehicle_bridge::ContactSpec>,
}

/// `[trains]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrainsSpec {
    /// Preset names: `HSLM-A` (all ten), `HSLM-A1` … `HSLM-A10` and the real trains of
    /// [`crate::train::presets`] (their static axle loads).
    #[serde(default)]
    pub names: Vec<String>,
    /// Train files (any TOML file with a `[train]` table, paths relative to the sweep file):
    /// each vehicle's static axle loads.
    #[serde(default)]
    pub files: Vec<String>,
    /// `moving_forces` (default) or `interaction`.
    pub model: Option<String>,
    /// Trains given by their axles.
    #[serde(default)]
    pub train: Vec<AxleTrainSpec>,
}

/// `[[trains.train]]`: a moving-force train.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxleTrainSpec {
    /// Name.
    pub name: String,
    /// Axle positions behind the first axle \[m\].
    pub axle_positions: Vec<f64>,
    /// Axle loads \[N\].
    pub axle_loads: Vec<f64>,
}

/// `[speeds]` \[m/s\].
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedsSpec {
    /// First speed.
    pub from: Option<f64>,
    /// Last speed (included when (to − from)/step is whole, to 1e-9).
    pub to: Option<f64>,
    /// Increment.
    pub step: Option<f64>,
    /// Or an explicit list.
    pub list: Option<Vec<f64>>,
}

/// `[output]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Points x \[m\] (default midspan).
    pub points: Option<Vec<f64>>,
}

/// `[check]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckSpec {
    /// `ballasted` (default) or `ballastless`.
    pub track: Option<String>,
}

/// `[integrator]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    /// Time step \[s\] (default 1/(40 f_max); interaction: the coupled model's default).
    pub dt: Option<f64>,
    /// Interaction model: the structural method (default as vehicle_bridge).
    pub method: Option<String>,
    /// Newmark β (interaction model).
    pub beta: Option<f64>,
    /// Newmark γ (interaction model).
    pub gamma: Option<f64>,
    /// HHT α (interaction model).
    pub alpha: Option<f64>,
    /// Generalized-α ρ∞ (interaction model).
    pub rho_inf: Option<f64>,
    /// Free vibration after the last axle \[s\] (default 2 periods of mode 1).
    pub free_vibration: Option<f64>,
}

/// A validated sweep.
pub struct SweepConfig {
    /// The bridge.
    pub bridge: Bridge,
    /// The sweep.
    pub spec: SweepSpec,
    /// The track of the acceleration check.
    pub track: Track,
    /// n₀ \[Hz\].
    pub first_frequency: f64,
    /// The damping ratio used (uniform damping), if uniform.
    pub damping_ratio: Option<f64>,
    /// How the damping and modes were chosen, for the report.
    pub notes: Vec<String>,
}

/// Validates a parsed file.
pub fn build(file: SweepFile, base: &std::path::Path) -> Result<SweepConfig, ConfigError> {
    if file.kind != "sweep" {
        bail!("`kind` = \"{}\": expected \"sweep\"", file.kind);
    }
    let model = file.trains.model.as_deref().unwrap_or("moving_forces");
    let interaction = match model {
        "moving_forces" => false,
        "interaction" => true,
        other => bail!("[trains] `model` = \"{other}\": expected moving_forces or interaction"),
    };
    if !interaction && file.contact.is_some() {
        bail!("[contact] applies to [trains] model = \"interaction\" only");
    }
    if !interaction
        && file.integrator.as_ref().is_some_and(|i| {
            i.method.is_some()
                || i.beta.is_some()
                || i.gamma.is_some()
                || i.alpha.is_some()
                || i.rho_inf.is_some()
        })
    {
        bail!(
            "[integrator] `method` and its parameters apply to [trains] model = \"interaction\" only (moving forces use the exact modal recurrence)"
        );
    }
    let bridge_table = interaction.then(|| file.bridge.clone());
    let speeds = speeds(&file.speeds)?;
    let trains = trains(&file.trains, base)?;
    checks::count(
        "the passages (trains × speeds)",
        trains.len() * speeds.len(),
        1,
        MAX_PASSAGES,
    )?;
    let mut notes = Vec::new();
    let (bridge, damping_ratio) = bridge(file.bridge, &mut notes)?;
    let omegas = bridge.basis.circular_frequencies();
    if let Some(w) = omegas.iter().find(|w| w.is_nan() || **w <= 0.0) {
        bail!(
            "[bridge]: a sweep needs elastic modes only (found ω = {w} rad/s, a rigid-body mode); use supports that hold the span"
        );
    }
    let two_pi = std::f64::consts::TAU;
    let first_frequency = omegas[0] / two_pi;
    let f_max = omegas[omegas.len() - 1] / two_pi;
    let length = bridge.basis.length();
    let integ = file.integrator.as_ref();
    let dt_given = match integ.and_then(|i| i.dt) {
        Some(dt) => Some(ranges::TIME_STEP.check("integrator.dt", dt)?),
        None => None,
    };
    let dt = match (dt_given, interaction) {
        (Some(dt), false) => dt,
        _ => 1.0 / (STEPS_PER_PERIOD * f_max),
    };
    let free_vibration = match integ.and_then(|i| i.free_vibration) {
        Some(f) => checks::Range::closed(0.0, 1e4, "s").check("integrator.free_vibration", f)?,
        None => FREE_VIBRATION_PERIODS / first_frequency,
    };
    let points = match file.output.as_ref().and_then(|o| o.points.clone()) {
        // Issue #12: the midspan of each span (an FE bridge's spans between its supports).
        None => bridge.span_midpoints(),
        Some(p) => checks::points_on_span(&p, 1, length)?,
    };
    let track = match file.check.as_ref().and_then(|c| c.track.as_deref()) {
        None => Track::Ballasted,
        Some(name) => Track::by_name(name).ok_or_else(|| {
            invalid!("[check] `track` = \"{name}\": expected ballasted or ballastless")
        })?,
    };
    let model = match bridge_table {
        None => SweepModel::MovingForces,
        Some(table) => SweepModel::Interaction(Box::new(interaction_model(
            &trains,
            table,
            file.contact.as_ref(),
            integ,
            dt_given,
            speeds.iter().copied().fold(0.0, f64::max),
        )?)),
    };
    if let SweepModel::Interaction(m) = &model {
        let dts: Vec<String> = m.trains.iter().map(|t| format!("{:.3e}", t.dt)).collect();
        notes.push(format!(
            "interaction model: each train's vehicles coupled to the bridge ({:?} contact, {}), Δt = {} s per train",
            m.contact,
            m.integrator.name(),
            dts.join(", ")
        ));
    }
    let spec = SweepSpec {
        trains,
        speeds,
        points,
        dt,
        free_vibration,
        gravity: crate::vehicle_bridge::GRAVITY,
        model,
    };
    check_work(&spec, length)?;
    Ok(SweepConfig {
        bridge,
        spec,
        track,
        first_frequency,
        damping_ratio,
        notes,
    })
}

/// The speeds of `[speeds]`.
fn speeds(s: &SpeedsSpec) -> Result<Vec<f64>, ConfigError> {
    let list = match (&s.list, s.from, s.to, s.step) {
        (Some(list), None, None, None) => {
            checks::count("speeds.list", list.len(), 1, MAX_PASSAGES)?;
            list.clone()
        }
        (None, Some(from), Some(to), Some(step)) => {
            ranges::SPEED.check("speeds.from", from)?;
            ranges::SPEED.check("speeds.to", to)?;
            if to < from {
                bail!("[speeds] `to` = {to} is below `from` = {from}");
            }
            if !(step.is_finite() && step > 0.0) {
                bail!("[speeds] `step` = {step}: must be a positive speed increment [m/s]");
            }
            let n = ((to - from) / step * (1.0 + 1e-9)).floor() + 1.0;
            checks::count(
                "the speeds (speeds.from … speeds.to by speeds.step)",
                n as usize,
                1,
                MAX_PASSAGES,
            )?;
            (0..n as usize).map(|i| from + i as f64 * step).collect()
        }
        (Some(_), ..) => bail!("[speeds]: give either `list` or `from`, `to` and `step`"),
        _ => bail!("[speeds]: give `from`, `to` and `step` [m/s] (or `list`)"),
    };
    for (i, &v) in list.iter().enumerate() {
        ranges::SPEED.check(&format!("speeds.list[{i}]"), v)?;
        if v <= 0.0 {
            bail!("[speeds] speed {v} m/s: speeds must be positive");
        }
    }
    if !list.is_sorted_by(|a, b| a < b) {
        bail!("[speeds]: the speeds must increase");
    }
    Ok(list)
}

/// The trains of `[trains]`.
fn trains(spec: &TrainsSpec, base: &std::path::Path) -> Result<Vec<Train>, ConfigError> {
    let mut trains = Vec::new();
    checks::count("trains.files", spec.files.len(), 0, 1000)?;
    for (k, name) in spec.files.iter().enumerate() {
        let path = base.join(name);
        let text = std::fs::read_to_string(&path).map_err(|source| ConfigError::Io {
            context: format!("trains.files[{k}] = \"{name}\" ({})", path.display()),
            source,
        })?;
        let mut table: toml::Table = text
            .parse()
            .map_err(|e| ConfigError::Schema(format!("trains.files[{k}] = \"{name}\": {e}")))?;
        let train = table
            .remove("train")
            .ok_or_else(|| invalid!("trains.files[{k}] = \"{name}\": no [train] table"))?;
        let table = super::train::TrainTable::deserialize(train).map_err(|e| {
            ConfigError::Schema(format!("trains.files[{k}] = \"{name}\" [train]: {e}"))
        })?;
        let mut train = super::train::build(&table, &format!("trains.files[{k}]: train"))?;
        if table.name.is_none() {
            train.name = name.clone();
        }
        trains.push(train);
    }
    for name in &spec.names {
        if name.trim().eq_ignore_ascii_case("HSLM-A") {
            trains.extend(hslm::all());
        } else if let Some(t) = presets::any_by_name(name) {
            trains.push(t);
        } else {
            bail!(
                "[trains] `names` contains \"{name}\": known trains are HSLM-A (all ten), {} (or give the axles in [[trains.train]], or a train file in `files`)",
                presets::known()
            );
        }
    }
    for (k, t) in spec.train.iter().enumerate() {
        checks::count(
            &format!("trains.train[{k}].axle_positions"),
            t.axle_positions.len(),
            1,
            10_000,
        )?;
        if t.axle_loads.len() != t.axle_positions.len() {
            bail!(
                "[[trains.train]] {k} (\"{}\"): `axle_loads` has {} entries, `axle_positions` {}: one load per axle",
                t.name,
                t.axle_loads.len(),
                t.axle_positions.len()
            );
        }
        for (i, (&x, &p)) in t.axle_positions.iter().zip(&t.axle_loads).enumerate() {
            ranges::POSITION.check(&format!("trains.train[{k}].axle_positions[{i}]"), x)?;
            ranges::FORCE.check(&format!("trains.train[{k}].axle_loads[{i}]"), p)?;
        }
        let span = t.axle_positions.iter().copied().fold(0.0, f64::max);
        let train = Train {
            name: t.name.clone(),
            vehicles: vec![VehicleSpec::MovingForces(MovingForces {
                length: span,
                axle_positions: t.axle_positions.clone(),
                axle_loads: t.axle_loads.clone(),
            })],
        };
        train
            .axles(crate::vehicle_bridge::GRAVITY)
            .map_err(|e| invalid!("[[trains.train]] {k} (\"{}\"): {e}", t.name))?;
        trains.push(train);
    }
    if trains.is_empty() {
        bail!(
            "[trains]: no train given: set `names` (e.g. [\"HSLM-A\"]), `files` or [[trains.train]]"
        );
    }
    Ok(trains)
}

/// The bridge of a sweep: the `[bridge]` table without the sweep's own keys, then the
/// Eurocode modes and damping when asked for.
fn bridge(
    mut table: toml::Table,
    notes: &mut Vec<String>,
) -> Result<(Bridge, Option<f64>), ConfigError> {
    let damping = table.remove("damping");
    let bridge_type = table.remove("type");
    let modes = table.get("modes").cloned();
    let eurocode_modes = match &modes {
        Some(toml::Value::String(s)) if s == "eurocode" => true,
        Some(toml::Value::String(s)) => {
            bail!("[bridge] `modes` = \"{s}\": expected a number of modes or \"eurocode\"")
        }
        _ => false,
    };
    let length = table
        .get("length")
        .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)));
    let mut damping_ratio = table.get("damping_ratio").and_then(toml::Value::as_float);
    match damping {
        None => {
            if bridge_type.is_some() {
                bail!("[bridge] `type` applies with damping = \"eurocode\" only");
            }
        }
        Some(toml::Value::String(s)) if s == "eurocode" => {
            if table.contains_key("damping_ratio")
                || table.contains_key("damping_ratios")
                || table.contains_key("rayleigh")
            {
                bail!(
                    "[bridge]: damping = \"eurocode\" excludes damping_ratio, damping_ratios and rayleigh"
                );
            }
            let name = match bridge_type {
                Some(toml::Value::String(n)) => n,
                _ => bail!(
                    "[bridge] damping = \"eurocode\" needs `type` ({})",
                    BridgeType::NAMES
                ),
            };
            let ty = BridgeType::by_name(&name).ok_or_else(|| {
                invalid!(
                    "[bridge] `type` = \"{name}\": expected {}",
                    BridgeType::NAMES
                )
            })?;
            let span = length.ok_or_else(|| {
                invalid!("[bridge] damping = \"eurocode\" needs the span `length` [m]")
            })?;
            ranges::SPAN.check("bridge.length", span)?;
            let zeta = eurocode::damping_ratio(ty, span);
            notes.push(format!(
                "damping ζ = {:.4} % (EN 1991-2 Table 6.6 lower limit {:.4} % for {name}, L = {span} m, + Δζ {:.4} % of eq. 6.13)",
                100.0 * zeta,
                100.0 * ty.damping_lower_limit(span),
                100.0 * eurocode::additional_damping(span)
            ));
            table.insert("damping_ratio".into(), toml::Value::Float(zeta));
            damping_ratio = Some(zeta);
        }
        Some(other) => {
            bail!("[bridge] `damping` = {other}: expected \"eurocode\" (or use damping_ratio)")
        }
    }
    let build = |table: &toml::Table, n: Option<usize>| -> Result<Bridge, ConfigError> {
        let mut t = table.clone();
        if let Some(n) = n {
            t.insert("modes".into(), toml::Value::Integer(n as i64));
        }
        let spec = BridgeSpec::deserialize(toml::Value::Table(t))
            .map_err(|e| ConfigError::Schema(format!("[bridge]: {e}")))?;
        spec.build()
    };
    if !eurocode_modes {
        return Ok((build(&table, None)?, damping_ratio));
    }
    // Every mode up to max(30 Hz, 1.5 n0, n3): find n0 and n3, then count.
    let probe = build(&table, Some(3))?;
    let f = |b: &Bridge, j: usize| b.basis.circular_frequencies()[j] / std::f64::consts::TAU;
    let limit = eurocode::mode_frequency_limit(f(&probe, 0), f(&probe, 2));
    let mut n = 3;
    let mut candidate = probe;
    while f(&candidate, n - 1) <= limit && n < MAX_EUROCODE_MODES {
        n = (2 * n).min(MAX_EUROCODE_MODES);
        candidate = build(&table, Some(n))?;
    }
    let count = candidate
        .basis
        .circular_frequencies()
        .iter()
        .filter(|w| **w / std::f64::consts::TAU <= limit * (1.0 + 1e-12))
        .count()
        .max(3);
    notes.push(format!(
        "modes: {count} (every mode up to max(30 Hz, 1.5 n0, n3) = {limit:.3} Hz, EN 1991-2 §6.4.6.5)"
    ));
    Ok((build(&table, Some(count))?, damping_ratio))
}

/// Refuses a sweep whose total time steps are absurd (before any passage runs).
fn check_work(spec: &SweepSpec, length: f64) -> Result<(), ConfigError> {
    let mut total = 0.0;
    for (i, t) in spec.trains.iter().enumerate() {
        let span = t.length();
        let dt = match &spec.model {
            SweepModel::MovingForces => spec.dt,
            SweepModel::Interaction(m) => m.trains[i].dt,
        };
        for &v in &spec.speeds {
            total += ((length + span) / v + spec.free_vibration) / dt;
        }
    }
    if total.is_nan() || total > MAX_TOTAL_STEPS {
        return Err(ConfigError::TooLarge(format!(
            "the sweep needs about {} time steps in all (trains × speeds × (passage + free vibration) / integrator.dt), more than {}: use fewer speeds, a larger speeds.step or integrator.dt",
            checks::number(total),
            checks::number(MAX_TOTAL_STEPS)
        )));
    }
    Ok(())
}

/// The interaction model: each train's wheels and multibody vehicles (its leading axle at the
/// span's entry), the contact law of `[contact]`, the structural method of `[integrator]`, and
/// per train the time step (given, or the coupled model's default that resolves its contact
/// modes, `vehicle_bridge::default_dt`); every train checked as a vehicle_bridge scenario at
/// the highest speed. HSLM-A trains get the assumed vehicle models of
/// [`crate::train::hslm_vehicles`]; other trains given by their axle loads only (moving
/// forces) have no vehicle model and are refused.
fn interaction_model(
    trains: &[Train],
    bridge_table: toml::Table,
    contact: Option<&super::vehicle_bridge::ContactSpec>,
    integ: Option<&IntegratorSpec>,
    dt_given: Option<f64>,
    top_speed: f64,
) -> Result<InteractionModel, ConfigError> {
    use super::vehicle_bridge as vb;
    use crate::vehicle_bridge::{CouplingSpec, Integrator, Irregularity, Scenario};
    let (bridge, _) = bridge(bridge_table, &mut Vec::new())?;
    let basis: std::sync::Arc<dyn beam::ModalBasis + Send + Sync> =
        std::sync::Arc::from(bridge.basis);
    let method_name = integ
        .and_then(|i| i.method.as_deref())
        .unwrap_or(vb::DEFAULT_METHOD);
    if method_name == "radau5" {
        bail!(
            "[integrator] `method` = \"radau5\": the interaction sweep uses the structural methods (newmark, hht, generalized_alpha, backward_euler)"
        );
    }
    let parameters = super::integrator::StructuralParameters {
        beta: integ.and_then(|i| i.beta),
        gamma: integ.and_then(|i| i.gamma),
        alpha: integ.and_then(|i| i.alpha),
        rho_inf: integ.and_then(|i| i.rho_inf),
    };
    let integrator = Integrator::Structural(parameters.method(method_name, &[])?);
    let mut wheels_max = 1;
    let mut vehicles = Vec::with_capacity(trains.len());
    // HSLM-A: the standard's point forces become the assumed vehicle models of
    // `train::hslm_vehicles` (same axles, every static axle load P).
    let with_models: Vec<Train> = trains
        .iter()
        .map(|t| {
            crate::train::hslm_vehicles::interaction_train_by_name(
                &t.name,
                crate::vehicle_bridge::GRAVITY,
            )
            .filter(|_| *t == hslm_by_name(&t.name))
            .unwrap_or_else(|| t.clone())
        })
        .collect();
    let trains = &with_models[..];
    for t in trains {
        if t.vehicles
            .iter()
            .all(|v| matches!(v, VehicleSpec::MovingForces(_)))
        {
            bail!(
                "[trains] model = \"interaction\": train \"{}\" is given by its axle loads only (moving forces), and the interaction model needs vehicle models: use presets or train files of quarter_car, sprung_mass, bogie_vehicle or articulated vehicles, or model = \"moving_forces\"",
                t.name
            );
        }
        let on_track = super::train_wheels::wheels_of(t, 0.0)
            .map_err(|e| invalid!("[trains] train \"{}\": {e}", t.name))?;
        wheels_max = wheels_max.max(on_track.wheels.len());
        vehicles.push(TrainVehicles {
            wheels: on_track.wheels,
            layouts: on_track.layouts,
            forces: on_track.forces,
            dt: f64::NAN,
        });
    }
    let (contact, geometry) = vb::contact_of(contact, wheels_max, None)?;
    let mut model = InteractionModel {
        basis,
        damping: bridge.damping,
        trains: Vec::new(),
        contact,
        geometry,
        integrator,
        coupling: CouplingSpec::default(),
        gravity: crate::vehicle_bridge::GRAVITY,
    };
    for (t, mut v) in trains.iter().zip(vehicles) {
        let mut scenario = Scenario {
            bridge: Box::new(std::sync::Arc::clone(&model.basis)),
            damping: model.damping.clone(),
            wheels: v.wheels.clone(),
            moving_forces: v.forces.clone(),
            speed: top_speed,
            contact: model.contact.clone(),
            geometry,
            irregularity: Irregularity::None,
            integrator,
            dt: dt_given.unwrap_or(vb::DEFAULT_DT),
            duration: None,
            coupling: model.coupling,
            gravity: model.gravity,
            output_point: 0.5 * model.basis.length(),
        };
        let name = &t.name;
        let in_train = |e: ConfigError| invalid!("[trains] train \"{name}\": {e}");
        vb::check_ranges(&scenario).map_err(in_train)?;
        vb::check_implicit(&scenario).map_err(in_train)?;
        if dt_given.is_none() {
            scenario.dt = vb::default_dt(&scenario).map_err(in_train)?;
        }
        v.dt = scenario.dt;
        model.trains.push(v);
    }
    Ok(model)
}

/// The moving-force HSLM-A train of `name` (or an empty train when the name is not one): a
/// train keeps its vehicle models in the interaction model unless it is exactly the
/// standard's moving-force train.
fn hslm_by_name(name: &str) -> Train {
    hslm::by_name(name).unwrap_or(Train {
        name: String::new(),
        vehicles: Vec::new(),
    })
}
