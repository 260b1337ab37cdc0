//! The wheels and multibody vehicles of a train in the coupled vehicle–bridge model: a
//! `[train]` table of `kind = "vehicle_bridge"`, or a train of the sweep's interaction model
//! (`config::sweep`), laid out on the track, with the coupled model's checks of each vehicle.

use super::ConfigError;
use super::checks::{self, ranges};
use crate::vehicle_bridge::{GRAVITY, WheelSpec};

/// The wheels, speed and bogie vehicles of a `[train]`: vehicle i's leading axle at
/// `position` − (its offset behind the train's leading axle); a quarter car or sprung mass is
/// one wheel with its body, a bogie vehicle four bare wheelsets carrying its body and bogies
/// (their `static_load` the suspended share, for the contact's static state and the checks).
/// An articulated train owns one bare wheelset per axle, like a bogie vehicle. A
/// `moving_forces` vehicle's axles are moving forces (no DOFs, no contact).
pub(crate) fn train_wheels(
    table: &super::train::TrainTable,
) -> Result<(TrainOnTrack, f64), ConfigError> {
    let train = super::train::build(table, "train")?;
    let speed = table
        .speed
        .ok_or_else(|| invalid!("[train]: missing `speed` [m/s]"))?;
    ranges::SPEED.check("train.speed", speed)?;
    let position = table.position.unwrap_or(0.0);
    ranges::POSITION.check("train.position", position)?;
    Ok((wheels_of(&train, position)?, speed))
}

/// A train laid out for the coupled model.
#[derive(Debug, Clone, Default)]
pub(crate) struct TrainOnTrack {
    /// The wheels (with their bodies for quarter cars and sprung masses).
    pub(crate) wheels: Vec<WheelSpec>,
    /// The multibody vehicles on those wheels.
    pub(crate) layouts: Vec<crate::vehicle_bridge::VehicleLayout>,
    /// The axles of `moving_forces` vehicles.
    pub(crate) forces: Vec<crate::vehicle_bridge::MovingForce>,
}

/// The wheels, multibody vehicles and moving forces of `train` with its leading axle at
/// `position` \[m\] (see [`train_wheels`]); an error for a train without wheels (moving forces
/// only: nothing to couple).
pub(crate) fn wheels_of(
    train: &crate::train::Train,
    position: f64,
) -> Result<TrainOnTrack, ConfigError> {
    use crate::train::VehicleSpec as V;
    let g = GRAVITY;
    let mut offset = 0.0;
    let mut wheels = Vec::new();
    let mut layouts = Vec::new();
    let mut forces = Vec::new();
    for (i, v) in train.vehicles.iter().enumerate() {
        let single = |wheel_mass: f64, body_mass: f64, k: f64, c: f64| WheelSpec {
            position: position - offset,
            wheel_mass,
            body_mass,
            suspension_stiffness: k,
            suspension_damping: c,
            static_load: 0.0,
        };
        let length = match v {
            V::QuarterCar(q) => {
                wheels.push(single(
                    q.wheel_mass,
                    q.body_mass,
                    q.suspension_stiffness,
                    q.suspension_damping,
                ));
                q.length
            }
            V::SprungMass(m) => {
                wheels.push(single(
                    0.0,
                    m.body_mass,
                    m.suspension_stiffness,
                    m.suspension_damping,
                ));
                m.length
            }
            V::BogieVehicle(b) => {
                layouts.push(crate::vehicle_bridge::VehicleLayout {
                    vehicle: crate::vehicle_bridge::MultibodyVehicle::Bogie(*b),
                    first_wheel: wheels.len(),
                });
                let suspended = (0.25 * b.body_mass + 0.5 * b.bogie_mass) * g;
                for x in [
                    0.0,
                    b.wheelbase,
                    b.bogie_spacing,
                    b.bogie_spacing + b.wheelbase,
                ] {
                    wheels.push(WheelSpec {
                        position: position - offset - x,
                        wheel_mass: b.wheelset_mass,
                        static_load: suspended,
                        ..WheelSpec::default()
                    });
                }
                for (key, value) in [
                    ("primary_stiffness", b.primary_stiffness),
                    ("secondary_stiffness", b.secondary_stiffness),
                    ("wheelset_mass", b.wheelset_mass),
                    ("bogie_mass", b.bogie_mass),
                    ("body_pitch_inertia", b.body_pitch_inertia),
                    ("bogie_pitch_inertia", b.bogie_pitch_inertia),
                ] {
                    if value <= 0.0 {
                        bail!(
                            "train vehicle {i}: `{key}` = {value}: a bogie vehicle in vehicle_bridge needs it positive"
                        );
                    }
                }
                // The body's static sag on both suspension stages.
                let sag = 0.5 * b.body_mass * g / b.secondary_stiffness
                    + (0.25 * b.body_mass + 0.5 * b.bogie_mass) * g / b.primary_stiffness;
                if sag > crate::vehicle_bridge::MAX_STATIC_SAG {
                    bail!(
                        "train vehicle {i}: `primary_stiffness` = {}, `secondary_stiffness` = {}: too soft, the body would sag {sag:.3e} m under its weight (at most 10 m)",
                        b.primary_stiffness,
                        b.secondary_stiffness
                    );
                }
                b.length
            }
            V::Articulated(a) => {
                articulated_checks(i, a)?;
                layouts.push(crate::vehicle_bridge::VehicleLayout {
                    vehicle: crate::vehicle_bridge::MultibodyVehicle::Articulated(a.clone()),
                    first_wheel: wheels.len(),
                });
                // Each wheelset carries its bogie's suspended share (Train::axles).
                let alone = crate::train::Train {
                    name: String::new(),
                    vehicles: vec![V::Articulated(a.clone())],
                };
                let axles = alone.axles(g).map_err(|e| invalid!("{e}"))?;
                for (k, (x, load)) in axles
                    .iter()
                    .map(|axle| (axle.offset, axle.load))
                    .enumerate()
                {
                    let wheelset_mass = a.bogies[k / 2].wheelset_mass;
                    wheels.push(WheelSpec {
                        position: position - offset - x,
                        wheel_mass: wheelset_mass,
                        static_load: load - wheelset_mass * g,
                        ..WheelSpec::default()
                    });
                }
                a.length
            }
            V::MovingForces(f) => {
                for (&x, &load) in f.axle_positions.iter().zip(&f.axle_loads) {
                    forces.push(crate::vehicle_bridge::MovingForce {
                        position: position - offset - x,
                        force: load,
                    });
                }
                f.length
            }
        };
        offset += length;
    }
    if wheels.is_empty() {
        bail!(
            "the train \"{}\" is moving forces only (type = \"moving_forces\" or a standard load model such as HSLM-A): the coupled model needs at least one vehicle with wheels (quarter_car, sprung_mass, bogie_vehicle or articulated); run the axle loads as kind = \"moving_load\" (exact modal steps) or in a sweep with model = \"moving_forces\"",
            train.name
        );
    }
    checks::count("the wheels of [train]", wheels.len(), 1, checks::MAX_WHEELS)?;
    checks::count(
        "the moving-force axles of [train]",
        forces.len(),
        0,
        checks::MAX_WHEELS,
    )?;
    Ok(TrainOnTrack {
        wheels,
        layouts,
        forces,
    })
}

/// The coupled model's requirements on an articulated train: positive masses, inertias and
/// stiffnesses, at most [`MAX_ARTICULATED_BODIES`] bodies (one dense block of the step
/// matrix), and a suspension that holds the bodies (static sag ≤ 10 m on every bogie). A key
/// of the uniform rake of a train table names itself; a body or bogie of a preset's rake is
/// named by its index.
fn articulated_checks(i: usize, a: &crate::train::Articulated) -> Result<(), ConfigError> {
    if a.bodies.len() > MAX_ARTICULATED_BODIES {
        bail!(
            "train vehicle {i}: `bodies` = {}: an articulated train in vehicle_bridge has 1 … {MAX_ARTICULATED_BODIES} bodies (split a longer rake into several articulated vehicles)",
            a.bodies.len()
        );
    }
    let positive = |part: String, key: &str, value: f64| {
        if value.is_nan() || value <= 0.0 {
            bail!(
                "train vehicle {i}{part}: `{key}` = {value}: an articulated train in vehicle_bridge needs it positive"
            );
        }
        Ok(())
    };
    for (j, body) in a.bodies.iter().enumerate() {
        let part = format!(", body {j}");
        positive(part.clone(), "body_pitch_inertia", body.pitch_inertia)?;
        positive(part, "secondary_stiffness", body.secondary_stiffness)?;
    }
    for (j, bogie) in a.bogies.iter().enumerate() {
        let part = format!(", bogie {j}");
        positive(part.clone(), "primary_stiffness", bogie.primary_stiffness)?;
        positive(part.clone(), "wheelset_mass", bogie.wheelset_mass)?;
        positive(part.clone(), "bogie_mass", bogie.mass)?;
        positive(part, "bogie_pitch_inertia", bogie.pitch_inertia)?;
    }
    // Each bogie's static sag on both stages: the body ends it carries on their secondary
    // springs (lever rule), then those and the bogie on its two primary springs.
    let g = GRAVITY;
    let suspended = a.suspended_wheelset_masses();
    for (j, bogie) in a.bogies.iter().enumerate() {
        let mut sag_secondary: f64 = 0.0;
        if let Some(ahead) = j.checked_sub(1).and_then(|k| a.bodies.get(k)) {
            let share = ahead.mass * ahead.front / (ahead.front + ahead.rear);
            sag_secondary = sag_secondary.max(share * g / ahead.secondary_stiffness);
        }
        if let Some(behind) = a.bodies.get(j) {
            let share = behind.mass * behind.rear / (behind.front + behind.rear);
            sag_secondary = sag_secondary.max(share * g / behind.secondary_stiffness);
        }
        let sag = sag_secondary + suspended[j] * g / bogie.primary_stiffness;
        if sag > crate::vehicle_bridge::MAX_STATIC_SAG {
            bail!(
                "train vehicle {i}, bogie {j}: `primary_stiffness` = {}, `secondary_stiffness` = {}: too soft, the bodies would sag {sag:.3e} m under their weight (at most 10 m)",
                bogie.primary_stiffness,
                a.bodies[j.min(a.bodies.len() - 1)].secondary_stiffness
            );
        }
    }
    Ok(())
}

/// Most bodies of one articulated vehicle in the coupled model (its 6n + 4 DOFs form one
/// dense block of the step matrix, at most `linalg::MAX_DENSE_BLOCK` = 256).
pub const MAX_ARTICULATED_BODIES: usize = 42;

/// A `sprung_mass` vehicle of a train table rides on a massless wheel, which needs the rigid
/// contact (docs/trains.md, docs/vehicle_bridge.md "Massless wheels"). With a compliant
/// contact the refusal names the vehicle's entry and `contact.model`, the keys the file set
/// (the wheel check of the simulation names `vehicle.wheels[k].wheel_mass`, a key only a
/// `[vehicle]` file has).
pub(crate) fn check_sprung_masses(
    table: &super::train::TrainTable,
    contact: &crate::vehicle_bridge::ContactModel,
) -> Result<(), ConfigError> {
    if matches!(contact, crate::vehicle_bridge::ContactModel::Rigid) {
        return Ok(());
    }
    let sprung = table.vehicles.iter().position(|v| {
        v.kind
            .as_deref()
            .is_some_and(|k| k.trim().eq_ignore_ascii_case("sprung_mass"))
    });
    match sprung {
        Some(i) => Err(invalid!(
            "invalid `contact.model` = \"{}\": train.vehicles[{i}] has type = \"sprung_mass\", a body on a massless wheel, which needs contact.model = \"rigid\" (a compliant contact would leave the wheel without inertia against the contact spring); use contact.model = \"rigid\", or type = \"quarter_car\" with a wheel_mass for a compliant contact",
            contact_name(contact)
        )),
        None => Ok(()),
    }
}

/// The scenario name of a contact model (`hertz`, `bem`).
fn contact_name(contact: &crate::vehicle_bridge::ContactModel) -> &'static str {
    use crate::vehicle_bridge::ContactModel;
    match contact {
        ContactModel::Rigid => "rigid",
        ContactModel::Hertz => "hertz",
        _ => "bem",
    }
}
