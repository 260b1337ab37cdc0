//! HSLM-A1 … A10 with vehicle models, for the interaction model of a sweep: EN 1991-2 Annex E
//! defines the universal trains by their axle geometry and one point force P per axle only
//! ([`super::hslm`]), so every mass, inertia and suspension value below is an assumption,
//! chosen so that the train's statics reproduce the standard exactly and its dynamics are those
//! of the articulated train HSLM-A is modelled on (docs/sweep.md, "HSLM-A with vehicle models").
//!
//! * Geometry: that of [`super::hslm::axle_offsets`], axle for axle: a power car (a
//!   [`BogieVehicle`], axles 3 m, 11 m, 3 m apart), then one [`Articulated`] rake (end coach,
//!   N intermediate coaches, end coach: N + 2 bodies on N + 3 bogies of axle spacing d, the
//!   inner N + 1 shared by neighbouring coaches, their centres D apart; each end coach from
//!   its own outer bogie to the first shared one, D − d/2 − 3.525/2 m), then the rear power
//!   car.
//! * Statics: every axle carries P. With bogie mass m_b and wheelset mass m_w, each bogie
//!   must receive Q = 2P − g (m_b + 2 m_w) from the bodies above it. An intermediate body
//!   weighs Q (half on each of its shared bogies); an end coach weighs 1.5 Q with its centre
//!   of gravity one third of its support distance from its outer bogie (Q on the outer bogie,
//!   Q/2 on the shared one, which gets the other Q/2 from the first intermediate coach); a
//!   power car's body weighs 4P − g (2 m_b + 4 m_w), midway between its bogies.
//! * Bogies, wheelsets and suspensions: the Eurostar's published values (references.md §T5.2,
//!   §T5.5): the power car's (bogie 2200 kg, 1900 kg m², wheelset 1700 kg, primary 2.6e6 N/m,
//!   12e3 N s/m, secondary 3.26e6 N/m, 90e3 N s/m) for the power cars, the articulated
//!   trailers' (bogie 2900 kg, 2508 kg m², wheelset 1900 kg, primary 2.0e6 N/m, 12e3 N s/m,
//!   secondary 5.8e5 N/m per body end) for the coaches; the trailers' secondary damping,
//!   published as zero, is taken as the end coaches' 20e3 N s/m (assumed), so that no body
//!   bounce is undamped.
//! * Body pitch inertias: scaled from the Eurostar with the body's mass and support distance
//!   squared, J = J_E (m/m_E) (s/s_E)² (the power car with its mass only: same bogie spacing).

use super::hslm::{HslmParameters, parameters};
use super::{Articulated, ArticulatedBody, ArticulatedBogie, BogieVehicle, Train, VehicleSpec};

/// The Eurostar power car's body (mass \[kg\], pitch inertia \[kg m²\]), §T5.5.
const POWER_CAR_BODY: (f64, f64) = (51_500.0, 1.05e6);
/// The Eurostar articulated trailer's body (mass \[kg\], pitch inertia \[kg m²\], support
/// distance \[m\]), §T5.2.
const TRAILER_BODY: (f64, f64, f64) = (22_525.0, 810_000.0, 18.7);
/// Power-car bogie centres \[m\] (EN 1991-2 Figure E.8: inner axles 11 m apart, wheelbase 3 m).
const POWER_CAR_BOGIES: f64 = 14.0;
/// Power-car wheelbase \[m\].
const POWER_CAR_WHEELBASE: f64 = 3.0;
/// From a power car's last axle to the end coach's first axle \[m\] (Figure E.8).
const COUPLING_GAP: f64 = 3.525;
/// Secondary damping per body end of the coaches \[N s/m\] (assumed, above).
const COACH_SECONDARY_DAMPING: f64 = 20.0e3;

/// HSLM-A`number` (1 … 10) with the vehicle models of this module, under gravity `g`
/// \[m/s²\]; `None` for another number, or if P is too small for the assumed bogies (never for
/// the ten trains of the standard).
pub fn interaction_train(number: usize, g: f64) -> Option<Train> {
    let p = parameters(number)?;
    Some(Train {
        name: format!("HSLM-A{number}"),
        vehicles: vehicles(p, g)?,
    })
}

/// The interaction train of an HSLM-A name (`HSLM-A3`, case-insensitive), or `None`.
pub fn interaction_train_by_name(name: &str, g: f64) -> Option<Train> {
    let upper = name.trim().to_ascii_uppercase();
    let number = upper.strip_prefix("HSLM-A")?.parse::<usize>().ok()?;
    interaction_train(number, g)
}

fn power_car_bogie() -> ArticulatedBogie {
    ArticulatedBogie {
        mass: 2200.0,
        pitch_inertia: 1900.0,
        wheelbase: POWER_CAR_WHEELBASE,
        wheelset_mass: 1700.0,
        primary_stiffness: 2.6e6,
        primary_damping: 12.0e3,
    }
}

fn coach_bogie(axle_spacing: f64) -> ArticulatedBogie {
    ArticulatedBogie {
        mass: 2900.0,
        pitch_inertia: 2508.0,
        wheelbase: axle_spacing,
        wheelset_mass: 1900.0,
        primary_stiffness: 2.0e6,
        primary_damping: 12.0e3,
    }
}

/// A power car whose four axles each carry `p`'s force, `length` from its leading axle to
/// the next vehicle's.
fn power_car(p: HslmParameters, g: f64, length: f64) -> Option<BogieVehicle> {
    let bogie = power_car_bogie();
    let body_weight = 4.0 * p.point_force - g * (2.0 * bogie.mass + 4.0 * bogie.wheelset_mass);
    let body_mass = body_weight / g;
    (body_mass > 0.0).then(|| BogieVehicle {
        length,
        body_mass,
        body_pitch_inertia: POWER_CAR_BODY.1 * body_mass / POWER_CAR_BODY.0,
        bogie_spacing: POWER_CAR_BOGIES,
        bogie_mass: bogie.mass,
        bogie_pitch_inertia: bogie.pitch_inertia,
        wheelbase: bogie.wheelbase,
        wheelset_mass: bogie.wheelset_mass,
        primary_stiffness: bogie.primary_stiffness,
        primary_damping: bogie.primary_damping,
        secondary_stiffness: 3.26e6,
        secondary_damping: 90.0e3,
    })
}

/// A coach body of mass `mass` on supports `front` + `rear` apart.
fn coach_body(mass: f64, front: f64, rear: f64) -> ArticulatedBody {
    let (m_e, j_e, s_e) = TRAILER_BODY;
    let s = front + rear;
    ArticulatedBody {
        mass,
        pitch_inertia: j_e * (mass / m_e) * (s / s_e).powi(2),
        front,
        rear,
        secondary_stiffness: 5.8e5,
        secondary_damping: COACH_SECONDARY_DAMPING,
    }
}

/// The vehicles of an HSLM-A train with parameters `p`: power car, articulated rake, power car.
fn vehicles(p: HslmParameters, g: f64) -> Option<Vec<VehicleSpec>> {
    let (d, big_d, n) = (p.axle_spacing, p.coach_length, p.coaches);
    let bogie = coach_bogie(d);
    // What each coach bogie receives from the bodies above it [N].
    let q = 2.0 * p.point_force - g * (bogie.mass + 2.0 * bogie.wheelset_mass);
    if q <= 0.0 {
        return None;
    }
    // End coach: outer bogie centre to the first shared bogie centre.
    let end_span = big_d - 0.5 * d - 0.5 * COUPLING_GAP;
    let end_mass = 1.5 * q / g;
    let front_end = coach_body(end_mass, end_span / 3.0, 2.0 * end_span / 3.0);
    let rear_end = coach_body(end_mass, 2.0 * end_span / 3.0, end_span / 3.0);
    let intermediate = coach_body(q / g, 0.5 * big_d, 0.5 * big_d);
    let mut bodies = Vec::with_capacity(n + 2);
    bodies.push(front_end);
    bodies.extend(std::iter::repeat_n(intermediate, n));
    bodies.push(rear_end);
    let bogies = vec![bogie; n + 3];
    // The rake's leading axle to its last axle: the bogie centres plus one wheelbase; then the
    // gap to the rear power car's leading axle.
    let centres = 2.0 * end_span + n as f64 * big_d;
    let rake_length = centres + d + COUPLING_GAP;
    let power_car_length = POWER_CAR_BOGIES + POWER_CAR_WHEELBASE + COUPLING_GAP;
    Some(vec![
        VehicleSpec::BogieVehicle(power_car(p, g, power_car_length)?),
        VehicleSpec::Articulated(Articulated {
            length: rake_length,
            bodies,
            bogies,
        }),
        VehicleSpec::BogieVehicle(power_car(p, g, power_car_length)?),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::train::hslm;

    /// Axle for axle the geometry of the moving-force train, and every static axle load P
    /// (the vehicles' lever-rule statics, an independent computation from the masses).
    #[test]
    fn every_axle_is_where_the_standard_puts_it_and_carries_p() {
        for number in 1..=10 {
            let p = parameters(number).unwrap();
            let train = interaction_train(number, 9.81).unwrap();
            let axles = train.axles(9.81).unwrap();
            let offsets = hslm::axle_offsets(p);
            assert_eq!(axles.len(), offsets.len(), "A{number}");
            for (a, x) in axles.iter().zip(&offsets) {
                assert!(
                    (a.offset - x).abs() < 1e-9,
                    "A{number}: {} vs {x}",
                    a.offset
                );
                assert!(
                    (a.load - p.point_force).abs() < 1e-9 * p.point_force,
                    "A{number}: axle at {x} carries {} N, P = {} N",
                    a.load,
                    p.point_force
                );
            }
            let moving = hslm::by_name(&format!("HSLM-A{number}")).unwrap();
            assert!((train.length() - moving.length()).abs() < 1e-9);
            let weight = p.point_force * offsets.len() as f64;
            assert!((train.mass() * 9.81 - weight).abs() < 1e-9 * weight);
        }
    }

    #[test]
    fn names_resolve_case_insensitively() {
        assert_eq!(
            interaction_train_by_name("hslm-a7", 9.81).unwrap().name,
            "HSLM-A7"
        );
        assert!(interaction_train_by_name("HSLM-A11", 9.81).is_none());
        assert!(interaction_train_by_name("AVE-S103", 9.81).is_none());
    }
}
