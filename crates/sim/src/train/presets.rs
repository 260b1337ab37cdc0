//! Presets of real trains with published parameters (references.md §T4, §T5; docs/trains.md
//! lists every number with its source and marks the assumed ones).
//!
//! * `Manchester`: the Manchester benchmark car (Iwnicki 1998; §T4);
//! * `AVE-S103`: the eight-car AVE S-103 / ICE3 / Velaro E high-speed multiple unit
//!   (Goicolea 2014; §T5.1), `AVE-S103-car` one of its intermediate cars;
//! * `Eurostar`: a whole Eurostar as TTB-2D composes it, power car, end coach EC1, the
//!   articulated trailers EC2 … EC8, end coach EC9, power car (Doménech Monforte 2014;
//!   §T5.2, §T5.5);
//! * `Eurostar-EC2-EC8`: the seven articulated intermediate trailers of a Eurostar set
//!   (Doménech Monforte 2014; §T5.2), their centres of gravity taken at mid-coach;
//! * `double-deck-coach`: a double-deck passenger coach, the regional/commuter car
//!   (Zhai, Wang & Cai 2009; §T5.3);
//! * `Sgns`: a container flat wagon, the freight wagon (ROSE; §T5.4).
//!
//! [`by_name`] also knows the HSLM-A trains of [`super::hslm`]. Lookup is case-insensitive.
//! Every preset is a [`Train`]; `count` in a scenario repeats the whole preset.

use super::{
    Articulated, ArticulatedBody, ArticulatedBogie, BogieVehicle, Train, UniformArticulated,
    VehicleSpec, hslm,
};

/// The real-train preset names (HSLM-A1 … HSLM-A10 come on top, [`by_name`]).
pub const NAMES: [&str; 7] = [
    "Manchester",
    "AVE-S103",
    "AVE-S103-car",
    "Eurostar",
    "Eurostar-EC2-EC8",
    "double-deck-coach",
    "Sgns",
];

/// Every known preset name as one line for error messages.
pub fn known() -> String {
    format!("{}, HSLM-A1 … HSLM-A10", NAMES.join(", "))
}

/// The preset `name` (case-insensitive; a real train of [`NAMES`] or `HSLM-A1` … `HSLM-A10`).
pub fn by_name(name: &str) -> Option<Train> {
    let key = name.trim();
    let canonical = NAMES.iter().find(|n| n.eq_ignore_ascii_case(key))?;
    let vehicles = match *canonical {
        "Manchester" => vec![VehicleSpec::BogieVehicle(manchester())],
        "AVE-S103" => ave_s103(),
        "AVE-S103-car" => vec![VehicleSpec::BogieVehicle(ave_s103_car(
            AVE_S103_CAR_PITCH,
            AveCar::Intermediate,
        ))],
        "Eurostar" => eurostar(),
        "Eurostar-EC2-EC8" => vec![VehicleSpec::Articulated(eurostar_ec2_ec8())],
        "double-deck-coach" => vec![VehicleSpec::BogieVehicle(double_deck_coach())],
        "Sgns" => vec![VehicleSpec::BogieVehicle(sgns())],
        _ => return None,
    };
    Some(Train {
        name: (*canonical).to_string(),
        vehicles,
    })
}

/// [`by_name`] for the real trains, then the HSLM-A trains.
pub fn any_by_name(name: &str) -> Option<Train> {
    by_name(name).or_else(|| hslm::by_name(name))
}

/// The Manchester benchmark car (Iwnicki 1998, §T4): 3-D per-side suspension values doubled
/// for the 2-D model; 25 m from leading axle to the next car's leading axle (19 m bogie
/// centres plus 3.0 m from each outer bogie centre to the car end: TTB-2D's geometry, assumed).
pub(crate) fn manchester() -> BogieVehicle {
    BogieVehicle {
        length: 25.0,
        body_mass: 32_000.0,
        body_pitch_inertia: 1.97e6,
        bogie_spacing: 19.0,
        bogie_mass: 2615.0,
        bogie_pitch_inertia: 1476.0,
        wheelbase: 2.56,
        wheelset_mass: 1813.0,
        primary_stiffness: 2.0 * 1.2e6,
        primary_damping: 2.0 * 4.0e3,
        secondary_stiffness: 2.0 * 4.3e5,
        secondary_damping: 2.0 * 2.0e4,
    }
}

/// Bogie centres of an AVE S-103 car \[m\] (Goicolea 2014).
const AVE_S103_BOGIE_SPACING: f64 = 17.375;
/// Bogie centre to the car end, coupled ends \[m\]: half the 7.4 m between the bogie centres
/// of two coupled cars (Goicolea 2014).
const AVE_S103_COUPLED_END: f64 = 3.7;
/// Bogie centre to the nose of an end car \[m\] (Goicolea 2014).
const AVE_S103_NOSE_END: f64 = 4.76;
/// Leading axle to the next car's leading axle of coupled cars \[m\]:
/// 17.375 + 2 × 3.7 = 24.775 (the intermediate car length).
const AVE_S103_CAR_PITCH: f64 = AVE_S103_BOGIE_SPACING + 2.0 * AVE_S103_COUPLED_END;

/// The two body types of the AVE S-103.
#[derive(Clone, Copy)]
enum AveCar {
    /// Cars 1, 2, 3, 6, 7, 8.
    Intermediate,
    /// Cars 4 and 5 (lighter body, softer bogie pitch inertia).
    Light,
}

/// One AVE S-103 car (Goicolea 2014, §T5.1) with `length` to the next leading axle. Per-side
/// suspension values of the 3-D description doubled for the 2-D model.
fn ave_s103_car(length: f64, car: AveCar) -> BogieVehicle {
    let (body_mass, body_pitch_inertia, bogie_pitch_inertia) = match car {
        AveCar::Intermediate => (47_800.0, 1_957_888.0, 1715.0),
        AveCar::Light => (41_200.0, 1_687_552.0, 1372.0),
    };
    BogieVehicle {
        length,
        body_mass,
        body_pitch_inertia,
        bogie_spacing: AVE_S103_BOGIE_SPACING,
        bogie_mass: 3500.0,
        bogie_pitch_inertia,
        wheelbase: 2.5,
        wheelset_mass: 1800.0,
        primary_stiffness: 2.0 * 1.2e6,
        primary_damping: 2.0 * 10.0e3,
        secondary_stiffness: 2.0 * 3.5e5,
        secondary_damping: 2.0 * 2.0e4,
    }
}

/// The eight-car AVE S-103 (cars 1 … 8; cars 4 and 5 light). Every car but the last is
/// 24.775 m from its leading axle to the next car's (the end car's longer nose is ahead of
/// its leading axle); the last car's `length` reaches the leading axle of a second unit
/// coupled behind it: 24.775 + 2 × (4.76 − 3.7) = 26.895 m.
fn ave_s103() -> Vec<VehicleSpec> {
    let last = AVE_S103_CAR_PITCH + 2.0 * (AVE_S103_NOSE_END - AVE_S103_COUPLED_END);
    (1..=8)
        .map(|car| {
            let kind = if car == 4 || car == 5 {
                AveCar::Light
            } else {
                AveCar::Intermediate
            };
            let length = if car == 8 { last } else { AVE_S103_CAR_PITCH };
            VehicleSpec::BogieVehicle(ave_s103_car(length, kind))
        })
        .collect()
}

/// Coach length of the Eurostar articulated trailers (bogie centre to bogie centre) \[m\].
const EUROSTAR_COACH: f64 = 18.7;
/// Number of articulated intermediate trailers EC2 … EC8.
const EUROSTAR_BODIES: usize = 7;

/// Eurostar EC2 … EC8 (Doménech Monforte 2014, §T5.2): seven bodies on eight bogies, the body's
/// centre of gravity taken at mid-coach (published 8.926 m / 9.774 m from the bogies: the
/// whole [`eurostar`] has them). `length` (only matters when a vehicle follows): one coach
/// length past the last bogie, assumed.
fn eurostar_ec2_ec8() -> Articulated {
    UniformArticulated {
        length: (EUROSTAR_BODIES + 1) as f64 * EUROSTAR_COACH,
        bodies: EUROSTAR_BODIES,
        body_mass: 22_525.0,
        body_pitch_inertia: 810_000.0,
        bogie_spacing: EUROSTAR_COACH,
        bogie_mass: 2900.0,
        bogie_pitch_inertia: 2508.0,
        wheelbase: 3.0,
        wheelset_mass: 1900.0,
        primary_stiffness: 2.0e6,
        primary_damping: 12.0e3,
        secondary_stiffness: 5.8e5,
        secondary_damping: 0.0,
    }
    .build()
}

/// Bogie centres of the Eurostar power car \[m\] (§T5.5).
const EUROSTAR_POWER_CAR_BOGIES: f64 = 14.0;
/// Bogie centre of a power car to its coupling end (TTB-2D's "additional distance",
/// 20.275 − 14 m; §T5.5).
const EUROSTAR_POWER_CAR_END: f64 = 20.275 - EUROSTAR_POWER_CAR_BOGIES;
/// The same for EC1 at its power-car end (22.5 − 18.7 m) and EC9 (21.965 − 18.7 m).
const EUROSTAR_EC1_END: f64 = 22.5 - EUROSTAR_COACH;
/// See [`EUROSTAR_EC1_END`].
const EUROSTAR_EC9_END: f64 = 21.965 - EUROSTAR_COACH;
/// Distance between an end coach's centre of gravity and its own (outer) bogie \[m\];
/// 13.252 m to its shared bogie (§T5.5).
const EUROSTAR_END_COACH_CG: f64 = 5.448;

/// The Eurostar power car (§T5.5): a conventional bogie vehicle, the values already 2-D.
fn eurostar_power_car(length: f64) -> BogieVehicle {
    BogieVehicle {
        length,
        body_mass: 51_500.0,
        body_pitch_inertia: 1.05e6,
        bogie_spacing: EUROSTAR_POWER_CAR_BOGIES,
        bogie_mass: 2200.0,
        bogie_pitch_inertia: 1900.0,
        wheelbase: 3.0,
        wheelset_mass: 1700.0,
        primary_stiffness: 2.6e6,
        primary_damping: 12.0e3,
        secondary_stiffness: 3.26e6,
        secondary_damping: 90.0e3,
    }
}

/// The whole Eurostar as TTB-2D composes it (§T5.2, §T5.5; docs/trains.md lists what is
/// assumed): power car; the articulated rake EC1 … EC9 (nine bodies on ten bogies: EC1's own
/// motor bogie at the power-car end, eight shared bogies, EC9's own bogie at the other
/// power-car end); power car.
///
/// * Bodies: EC1 and EC9 with their centres of gravity 5.448 m from their own (outer) bogie
///   and 13.252 m from the shared one (for EC9 the mirror image of the data file's front and
///   rear, assumed: docs/trains.md), EC2 … EC8 8.926 m behind the front bogie and 9.774 m
///   ahead of the rear one; each body's secondary suspension at both its ends.
/// * Bogies: EC1's outer bogie that of the EC1 file (the power car's motor bogie values), the
///   shared bogies those of EC2 … EC8, EC9's outer bogie that of the EC9 file.
/// * Geometry: bogie centres 18.7 m apart along the rake; between a power car's bogie and
///   the end coach's outer bogie, the sum of the two vehicles' "additional distances" of
///   TTB-2D (6.275 m and 3.8 m at EC1, 3.265 m and 6.275 m at EC9). The last power car's
///   `length` puts a second train's leading axle where two sets coupled nose to nose would
///   have it (6.275 m on each side of the coupling), assumed.
fn eurostar() -> Vec<VehicleSpec> {
    let front_gap = EUROSTAR_POWER_CAR_END + EUROSTAR_EC1_END;
    let rear_gap = EUROSTAR_EC9_END + EUROSTAR_POWER_CAR_END;
    let motor_bogie = ArticulatedBogie {
        mass: 2200.0,
        pitch_inertia: 1900.0,
        wheelbase: 3.0,
        wheelset_mass: 1700.0,
        primary_stiffness: 2.6e6,
        primary_damping: 12.0e3,
    };
    let shared_bogie = ArticulatedBogie {
        mass: 2900.0,
        pitch_inertia: 2508.0,
        wheelbase: 3.0,
        wheelset_mass: 1900.0,
        primary_stiffness: 2.0e6,
        primary_damping: 12.0e3,
    };
    let ec9_bogie = ArticulatedBogie {
        primary_stiffness: 1.32e6,
        ..shared_bogie
    };
    let far = EUROSTAR_COACH - EUROSTAR_END_COACH_CG;
    let ec1 = ArticulatedBody {
        mass: 35_860.0,
        pitch_inertia: 1.658e6,
        front: EUROSTAR_END_COACH_CG,
        rear: far,
        secondary_stiffness: 90.0e3,
        secondary_damping: 20.0e3,
    };
    let ec2_ec8 = ArticulatedBody {
        mass: 22_525.0,
        pitch_inertia: 810_000.0,
        front: 8.926,
        rear: 9.774,
        secondary_stiffness: 5.8e5,
        secondary_damping: 0.0,
    };
    let ec9 = ArticulatedBody {
        mass: 27_122.0,
        pitch_inertia: 1.254e6,
        front: far,
        rear: EUROSTAR_END_COACH_CG,
        secondary_stiffness: 250.0e3,
        secondary_damping: 20.0e3,
    };
    let mut bodies = vec![ec1];
    bodies.extend([ec2_ec8; EUROSTAR_BODIES]);
    bodies.push(ec9);
    let mut bogies = vec![motor_bogie];
    bogies.extend([shared_bogie; EUROSTAR_BODIES + 1]);
    bogies.push(ec9_bogie);
    // Every wheelbase is 3 m, so leading axle to leading axle equals bogie centre to bogie
    // centre: EC1's outer bogie to EC9's, then the gap to the last power car's front bogie.
    let rake_length = (EUROSTAR_BODIES + 2) as f64 * EUROSTAR_COACH + rear_gap;
    let leading = EUROSTAR_POWER_CAR_BOGIES + front_gap;
    let trailing = EUROSTAR_POWER_CAR_BOGIES + 2.0 * EUROSTAR_POWER_CAR_END;
    vec![
        VehicleSpec::BogieVehicle(eurostar_power_car(leading)),
        VehicleSpec::Articulated(Articulated {
            length: rake_length,
            bodies,
            bogies,
        }),
        VehicleSpec::BogieVehicle(eurostar_power_car(trailing)),
    ]
}

/// The double-deck passenger coach (Zhai, Wang & Cai 2009, §T5.3): per-side suspension values
/// doubled for the 2-D model; 2.7 m from each outer bogie centre to the car end (TTB-2D's
/// geometry, assumed): 18 + 2 × 2.7 = 23.4 m.
fn double_deck_coach() -> BogieVehicle {
    BogieVehicle {
        length: 23.4,
        body_mass: 29_600.0,
        body_pitch_inertia: 2.139e6,
        bogie_spacing: 18.0,
        bogie_mass: 1700.0,
        bogie_pitch_inertia: 1700.0,
        wheelbase: 2.4,
        wheelset_mass: 1900.0,
        primary_stiffness: 2.0 * 0.873e6,
        primary_damping: 2.0 * 30.0e3,
        secondary_stiffness: 2.0 * 0.41e6,
        secondary_damping: 2.0 * 108.7e3,
    }
}

/// The Sgns container flat wagon of ROSE (§T5.4). ROSE models one rail: it halves the body and
/// bogie masses and inertias explicitly; the full 2-D vehicle here is twice ROSE's one-rail
/// model (every mass, inertia, stiffness and damper doubled), so its frequencies equal ROSE's.
/// 19.74 m over buffers.
fn sgns() -> BogieVehicle {
    BogieVehicle {
        length: 19.74,
        body_mass: 29_480.0,
        body_pitch_inertia: 784_200.0,
        bogie_spacing: 14.2,
        bogie_mass: 5000.0,
        bogie_pitch_inertia: 2100.0,
        wheelbase: 1.82,
        wheelset_mass: 2.0 * 1500.0,
        primary_stiffness: 2.0 * 3.27e6,
        primary_damping: 2.0 * 8.02e4,
        secondary_stiffness: 2.0 * 3.27e7,
        secondary_damping: 2.0 * 8.02e5,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_resolves_case_insensitively_and_unknown_names_do_not() {
        for name in NAMES {
            let t = by_name(name).unwrap();
            assert_eq!(t.name, name);
            assert_eq!(by_name(&name.to_ascii_uppercase()).unwrap(), t);
            assert!(t.axles(9.81).is_ok(), "{name}");
        }
        assert!(by_name("ICE4").is_none() && by_name("HSLM-A1").is_none());
        assert_eq!(any_by_name("hslm-a1").unwrap().name, "HSLM-A1");
        assert!(known().contains("Sgns") && known().contains("HSLM-A10"));
    }
}
