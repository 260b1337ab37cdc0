//! The `[train]` table: a train as an ordered list of vehicles, read in one place for every
//! scenario kind that takes trains (`moving_load`, `sweep` train files, `vehicle_bridge`).
//! Keys (SI units) are the field names of [`crate::train::vehicle`]; docs/trains.md.
//!
//! ```toml
//! [train]
//! name = "four cars"
//! speed = 80.0                # [m/s] (moving_load, vehicle_bridge)
//! position = 0.0              # x of the leading axle at t = 0 [m] (vehicle_bridge)
//! [[train.vehicles]]          # in running order; or preset = "AVE-S103", "HSLM-A1", … (a whole train)
//! type = "bogie_vehicle"      # moving_forces | quarter_car | sprung_mass | bogie_vehicle | articulated
//! count = 4                   # identical vehicles in a row
//! length = 25.0               # leading axle to the next vehicle's leading axle [m]
//! body_mass = 32000.0
//! # … the parameters of the type
//! ```

use serde::Deserialize;

use super::ConfigError;
use super::checks::{self, ranges};
use crate::train::{
    BogieVehicle, MovingForces, QuarterCar, SprungMass, Train, UniformArticulated, VehicleSpec,
    presets,
};

/// Largest number of vehicles of a train (after `count`).
pub const MAX_VEHICLES: usize = 256;
/// Largest number of axles of a train.
pub const MAX_AXLES: usize = 4096;

/// `[train]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrainTable {
    /// Name (default "train").
    pub name: Option<String>,
    /// Speed \[m/s\].
    pub speed: Option<f64>,
    /// x of the leading axle at t = 0 \[m\].
    pub position: Option<f64>,
    /// The vehicles in running order.
    #[serde(default)]
    pub vehicles: Vec<VehicleTable>,
}

/// `[[train.vehicles]]`: a preset or a type with its parameters.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleTable {
    pub preset: Option<String>,
    #[serde(rename = "type")]
    pub kind: Option<String>,
    pub count: Option<usize>,
    pub length: Option<f64>,
    pub body_mass: Option<f64>,
    pub body_pitch_inertia: Option<f64>,
    pub bogie_spacing: Option<f64>,
    pub bogie_mass: Option<f64>,
    pub bogie_pitch_inertia: Option<f64>,
    pub wheelbase: Option<f64>,
    pub wheelset_mass: Option<f64>,
    pub primary_stiffness: Option<f64>,
    pub primary_damping: Option<f64>,
    pub secondary_stiffness: Option<f64>,
    pub secondary_damping: Option<f64>,
    pub wheel_mass: Option<f64>,
    pub suspension_stiffness: Option<f64>,
    pub suspension_damping: Option<f64>,
    pub bodies: Option<usize>,
    pub axle_positions: Option<Vec<f64>>,
    pub axle_loads: Option<Vec<f64>>,
}

/// The vehicle types of `type`.
pub const VEHICLE_TYPES: &str =
    "moving_forces, quarter_car, sprung_mass, bogie_vehicle, articulated";

/// The train of a `[train]` table; `prefix` is the table's key as written (`train`, or
/// `trains.files[2]: train`).
pub fn build(table: &TrainTable, prefix: &str) -> Result<Train, ConfigError> {
    checks::count(
        &format!("{prefix}.vehicles"),
        table.vehicles.len(),
        1,
        MAX_VEHICLES,
    )?;
    let mut vehicles = Vec::new();
    for (i, v) in table.vehicles.iter().enumerate() {
        let key = format!("{prefix}.vehicles[{i}]");
        let count = checks::count(
            &format!("{key}.count"),
            v.count.unwrap_or(1),
            1,
            MAX_VEHICLES,
        )?;
        let specs = vehicle(v, &key)?;
        if vehicles.len() + count * specs.len() > MAX_VEHICLES {
            bail!("[{prefix}]: more than {MAX_VEHICLES} vehicles (count included)");
        }
        for _ in 0..count {
            vehicles.extend(specs.iter().cloned());
        }
    }
    let train = Train {
        name: table.name.clone().unwrap_or_else(|| "train".into()),
        vehicles,
    };
    let axles = train
        .axles(crate::vehicle_bridge::GRAVITY)
        .map_err(|e| invalid!("[{prefix}] {e}"))?;
    checks::count(
        &format!("the axles of [{prefix}]"),
        axles.len(),
        1,
        MAX_AXLES,
    )?;
    Ok(train)
}

/// One `[[train.vehicles]]` entry: its vehicles (a preset may be a whole train).
fn vehicle(v: &VehicleTable, key: &str) -> Result<Vec<VehicleSpec>, ConfigError> {
    if let Some(name) = &v.preset {
        if v.kind.is_some() || v.length.is_some() || v.body_mass.is_some() || v.axle_loads.is_some()
        {
            bail!("{key}: `preset` = \"{name}\" takes no vehicle parameters (only `count`)");
        }
        return presets::any_by_name(name)
            .map(|t| t.vehicles)
            .ok_or_else(|| {
                invalid!(
                    "{key}.preset = \"{name}\": known presets are {}",
                    presets::known()
                )
            });
    }
    let Some(kind) = v.kind.as_deref() else {
        bail!("{key}: give `type` ({VEHICLE_TYPES}) or `preset`");
    };
    let need = |value: Option<f64>, name: &str| -> Result<f64, ConfigError> {
        value.ok_or_else(|| invalid!("{key}: type = \"{kind}\" needs `{name}`"))
    };
    let length = ranges::POSITION.check(&format!("{key}.length"), need(v.length, "length")?)?;
    let mass = |value: Option<f64>, name: &str| -> Result<f64, ConfigError> {
        let m = ranges::MASS_OR_ZERO.check(&format!("{key}.{name}"), need(value, name)?)?;
        // The wheels' and bodies' range (`vehicle.wheels[k]` in check_ranges), named here
        // by the train's key.
        if m != 0.0 && !ranges::VEHICLE_MASS.contains(m) {
            bail!(
                "`{key}.{name}` = {}: must be 0 or lie in {}",
                checks::number(m),
                ranges::VEHICLE_MASS
            );
        }
        Ok(m)
    };
    let stiffness = |value: Option<f64>, name: &str| -> Result<f64, ConfigError> {
        ranges::STIFFNESS.check(&format!("{key}.{name}"), need(value, name)?)
    };
    let damper = |value: Option<f64>, name: &str| -> Result<f64, ConfigError> {
        ranges::DAMPER.check(&format!("{key}.{name}"), value.unwrap_or(0.0))
    };
    let inertia = |value: Option<f64>, name: &str| -> Result<f64, ConfigError> {
        ranges::INERTIA.check(&format!("{key}.{name}"), need(value, name)?)
    };
    let spec = match kind {
        "moving_forces" => {
            let positions = v.axle_positions.clone().ok_or_else(|| {
                invalid!("{key}: type = \"moving_forces\" needs `axle_positions` [m]")
            })?;
            let loads = v.axle_loads.clone().ok_or_else(|| {
                invalid!("{key}: type = \"moving_forces\" needs `axle_loads` [N]")
            })?;
            checks::count(
                &format!("{key}.axle_positions"),
                positions.len(),
                1,
                MAX_AXLES,
            )?;
            for (j, &p) in loads.iter().enumerate() {
                ranges::FORCE.check(&format!("{key}.axle_loads[{j}]"), p)?;
            }
            VehicleSpec::MovingForces(MovingForces {
                length,
                axle_positions: positions,
                axle_loads: loads,
            })
        }
        "quarter_car" => VehicleSpec::QuarterCar(QuarterCar {
            length,
            wheel_mass: mass(v.wheel_mass, "wheel_mass")?,
            body_mass: mass(v.body_mass, "body_mass")?,
            suspension_stiffness: stiffness(v.suspension_stiffness, "suspension_stiffness")?,
            suspension_damping: damper(v.suspension_damping, "suspension_damping")?,
        }),
        "sprung_mass" => VehicleSpec::SprungMass(SprungMass {
            length,
            body_mass: mass(v.body_mass, "body_mass")?,
            suspension_stiffness: stiffness(v.suspension_stiffness, "suspension_stiffness")?,
            suspension_damping: damper(v.suspension_damping, "suspension_damping")?,
        }),
        "bogie_vehicle" => VehicleSpec::BogieVehicle(BogieVehicle {
            length,
            body_mass: mass(v.body_mass, "body_mass")?,
            body_pitch_inertia: inertia(v.body_pitch_inertia, "body_pitch_inertia")?,
            bogie_spacing: need(v.bogie_spacing, "bogie_spacing")?,
            bogie_mass: mass(v.bogie_mass, "bogie_mass")?,
            bogie_pitch_inertia: inertia(v.bogie_pitch_inertia, "bogie_pitch_inertia")?,
            wheelbase: need(v.wheelbase, "wheelbase")?,
            wheelset_mass: mass(v.wheelset_mass, "wheelset_mass")?,
            primary_stiffness: stiffness(v.primary_stiffness, "primary_stiffness")?,
            primary_damping: damper(v.primary_damping, "primary_damping")?,
            secondary_stiffness: stiffness(v.secondary_stiffness, "secondary_stiffness")?,
            secondary_damping: damper(v.secondary_damping, "secondary_damping")?,
        }),
        "articulated" => VehicleSpec::Articulated(
            UniformArticulated {
                length,
                // Each body adds two axles: at most MAX_AXLES in the whole train.
                bodies: checks::count(
                    &format!("{key}.bodies"),
                    v.bodies
                        .ok_or_else(|| invalid!("{key}: type = \"articulated\" needs `bodies`"))?,
                    1,
                    MAX_AXLES / 2 - 1,
                )?,
                body_mass: mass(v.body_mass, "body_mass")?,
                body_pitch_inertia: inertia(v.body_pitch_inertia, "body_pitch_inertia")?,
                bogie_spacing: need(v.bogie_spacing, "bogie_spacing")?,
                bogie_mass: mass(v.bogie_mass, "bogie_mass")?,
                bogie_pitch_inertia: inertia(v.bogie_pitch_inertia, "bogie_pitch_inertia")?,
                wheelbase: need(v.wheelbase, "wheelbase")?,
                wheelset_mass: mass(v.wheelset_mass, "wheelset_mass")?,
                primary_stiffness: stiffness(v.primary_stiffness, "primary_stiffness")?,
                primary_damping: damper(v.primary_damping, "primary_damping")?,
                secondary_stiffness: stiffness(v.secondary_stiffness, "secondary_stiffness")?,
                secondary_damping: damper(v.secondary_damping, "secondary_damping")?,
            }
            .build(),
        ),
        other => bail!("{key}.type = \"{other}\": expected {VEHICLE_TYPES}"),
    };
    // Keys that do not belong to the type are errors (a misplaced key is a mistake).
    let used: &[&str] = match kind {
        "moving_forces" => &["axle_positions", "axle_loads"],
        "quarter_car" => &[
            "wheel_mass",
            "body_mass",
            "suspension_stiffness",
            "suspension_damping",
        ],
        "sprung_mass" => &["body_mass", "suspension_stiffness", "suspension_damping"],
        "bogie_vehicle" => &[
            "body_mass",
            "body_pitch_inertia",
            "bogie_spacing",
            "bogie_mass",
            "bogie_pitch_inertia",
            "wheelbase",
            "wheelset_mass",
            "primary_stiffness",
            "primary_damping",
            "secondary_stiffness",
            "secondary_damping",
        ],
        _ => &[
            "bodies",
            "body_mass",
            "body_pitch_inertia",
            "bogie_spacing",
            "bogie_mass",
            "bogie_pitch_inertia",
            "wheelbase",
            "wheelset_mass",
            "primary_stiffness",
            "primary_damping",
            "secondary_stiffness",
            "secondary_damping",
        ],
    };
    for (name, given) in given_keys(v) {
        if given && !used.contains(&name) {
            bail!("{key}.{name} does not apply to type = \"{kind}\"");
        }
    }
    Ok(vec![spec])
}

/// (key, given) of every parameter key of a vehicle table.
fn given_keys(v: &VehicleTable) -> [(&'static str, bool); 18] {
    [
        ("body_mass", v.body_mass.is_some()),
        ("body_pitch_inertia", v.body_pitch_inertia.is_some()),
        ("bogie_spacing", v.bogie_spacing.is_some()),
        ("bogie_mass", v.bogie_mass.is_some()),
        ("bogie_pitch_inertia", v.bogie_pitch_inertia.is_some()),
        ("wheelbase", v.wheelbase.is_some()),
        ("wheelset_mass", v.wheelset_mass.is_some()),
        ("primary_stiffness", v.primary_stiffness.is_some()),
        ("primary_damping", v.primary_damping.is_some()),
        ("secondary_stiffness", v.secondary_stiffness.is_some()),
        ("secondary_damping", v.secondary_damping.is_some()),
        ("wheel_mass", v.wheel_mass.is_some()),
        ("suspension_stiffness", v.suspension_stiffness.is_some()),
        ("suspension_damping", v.suspension_damping.is_some()),
        ("bodies", v.bodies.is_some()),
        ("axle_positions", v.axle_positions.is_some()),
        ("axle_loads", v.axle_loads.is_some()),
        ("count", false),
    ]
}
