//! The bogie vehicle's natural frequencies on a rigid track against a published table
//! (references.md §T7): two high-speed cars (trailer and motor car) with their parameters and
//! their body bounce, body pitch, bogie bounce and bogie pitch frequencies as printed, to two
//! decimals, by Zeng, Yu, Zhao, Xu, Chen & Lou, Shock and Vibration 2014, article 304219,
//! Table 1.
//!
//! An independent check of `BogieVehicle::rigid_track_frequencies` and of the parameter
//! conventions (k₁ per wheelset, k₂ per bogie, both rails together; half distances doubled):
//! had the table's stiffnesses been per rail side, or per bogie for the primary suspension,
//! every frequency would be off by a factor of √2 or more.

// 6.28 Hz is a printed frequency of the table, not an approximation of τ.
#![allow(clippy::approx_constant)]

use sim::train::BogieVehicle;

/// A car of the table (lengths: bogie centres 2 × 8.6875 m, wheelbase 2 × 1.25 m, bogie
/// centre to car end 3.45 m); dampers do not enter the undamped frequencies.
struct PublishedCar {
    name: &'static str,
    vehicle: BogieVehicle,
    /// Body bounce, body pitch, bogie bounce, bogie pitch \[Hz\] as published.
    published: [f64; 4],
}

fn car(
    body: (f64, f64),
    bogie: (f64, f64),
    primary: (f64, f64),
    secondary: (f64, f64),
) -> BogieVehicle {
    BogieVehicle {
        length: 2.0 * (8.6875 + 3.45),
        body_mass: body.0,
        body_pitch_inertia: body.1,
        bogie_spacing: 2.0 * 8.6875,
        bogie_mass: bogie.0,
        bogie_pitch_inertia: bogie.1,
        wheelbase: 2.0 * 1.25,
        wheelset_mass: 2.4e3,
        primary_stiffness: primary.0,
        primary_damping: primary.1,
        secondary_stiffness: secondary.0,
        secondary_damping: secondary.1,
    }
}

fn published_cars() -> Vec<PublishedCar> {
    vec![
        PublishedCar {
            name: "trailer car",
            vehicle: car(
                (4.4e4, 2.7e6),
                (2.4e3, 2.2e3),
                (1.4e6, 8.0e4),
                (6.0e5, 8.0e4),
            ),
            published: [0.75, 0.84, 6.00, 7.10],
        },
        PublishedCar {
            // The table prints 4.78 Hz as the motor car's bogie bounce and 6.28 Hz as its
            // bogie pitch. With the printed parameters the two are the other way round
            // (ω² = 2k₁b²/J_b = 902.8 s⁻², 4.782 Hz, for the pitch; (k₂ + 2k₁)/m_b =
            // 1550 s⁻², 6.266 Hz uncoupled, for the bounce); the trailer car's pair is in
            // the printed order. The labels are swapped here and the swap is asserted below.
            name: "motor car",
            vehicle: car(
                (4.8e4, 2.7e6),
                (3.2e3, 7.2e3),
                (2.08e6, 6.0e4),
                (8.0e5, 9.0e4),
            ),
            published: [0.84, 0.97, 6.28, 4.78],
        },
    ]
}

/// Half a unit of the published last digit (0.005 Hz) plus the spread between the coupled
/// 2 × 2 roots computed here and the simpler uncoupled estimate of the body frequencies (body on
/// the series springs k₂ and 2k₁: at most 0.0026 Hz for these cars). The table does not say
/// which it printed: its trailer-car body pitch, 0.84 Hz, is the uncoupled 0.8373 Hz rounded
/// (the coupled root 0.8347 Hz rounds to 0.83), while its bogie bounce frequencies are the
/// coupled roots rounded (6.0007 and 6.2770 Hz; uncoupled 5.990 and 6.266 Hz).
const TOLERANCE_HZ: f64 = 0.008;

#[test]
fn bogie_vehicle_frequencies_match_the_published_table() {
    let mut worst: f64 = 0.0;
    for c in published_cars() {
        let f = c.vehicle.rigid_track_frequencies();
        let computed = [f.body_bounce, f.body_pitch, f.bogie_bounce, f.bogie_pitch];
        println!(
            "{}: computed {:.4} / {:.4} / {:.4} / {:.4} Hz, published {:?} Hz",
            c.name, computed[0], computed[1], computed[2], computed[3], c.published
        );
        for (x, p) in computed.iter().zip(c.published) {
            worst = worst.max((x - p).abs());
            assert!(
                (x - p).abs() < TOLERANCE_HZ,
                "{}: computed {x:.4} Hz, published {p} Hz",
                c.name
            );
        }
    }
    println!("largest difference {worst:.4} Hz (tolerance {TOLERANCE_HZ} Hz)");
}

#[test]
fn the_motor_car_s_printed_bogie_frequencies_are_swapped() {
    // In the printed order (4.78 Hz bounce, 6.28 Hz pitch) the motor car is 1.5 Hz off in
    // both: the swap noted above is a labelling matter, not an agreement bought by choice.
    let motor = &published_cars()[1];
    let f = motor.vehicle.rigid_track_frequencies();
    assert!((f.bogie_bounce - 4.78).abs() > 1.0, "{}", f.bogie_bounce);
    assert!((f.bogie_pitch - 6.28).abs() > 1.0, "{}", f.bogie_pitch);
}

#[test]
fn per_side_stiffnesses_would_not_match() {
    // The same cars with the table's stiffnesses read as per rail side (both rails: twice
    // the printed values) miss the published body bounce by far more than the tolerance:
    // the test above can fail on the convention.
    for c in published_cars() {
        let mut v = c.vehicle;
        v.primary_stiffness *= 2.0;
        v.secondary_stiffness *= 2.0;
        let f = v.rigid_track_frequencies();
        assert!(
            (f.body_bounce - c.published[0]).abs() > 10.0 * TOLERANCE_HZ,
            "{}: {}",
            c.name,
            f.body_bounce
        );
    }
}
