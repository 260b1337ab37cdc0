//! Vehicles shared by the unit tests of `train` (one definition of each test vehicle).

pub(crate) use super::presets::manchester;
use super::vehicle::{Articulated, ArticulatedBody, ArticulatedBogie, UniformArticulated};

/// An articulated chain of `bodies` Eurostar-like bodies (18.7 m between the shared bogies,
/// 3 m wheelbase; round values, not a published vehicle), 3 m longer than its bogie chain.
pub(crate) fn chain(bodies: usize) -> UniformArticulated {
    UniformArticulated {
        length: bodies as f64 * 18.7 + 3.0,
        bodies,
        body_mass: 28_000.0,
        body_pitch_inertia: 1.5e6,
        bogie_spacing: 18.7,
        bogie_mass: 3000.0,
        bogie_pitch_inertia: 2000.0,
        wheelbase: 3.0,
        wheelset_mass: 2000.0,
        primary_stiffness: 2.4e6,
        primary_damping: 2e4,
        secondary_stiffness: 8e5,
        secondary_damping: 3e4,
    }
}

/// An uneven articulated chain (round values, not a published vehicle): three bodies of
/// different masses with their centres of gravity off-centre (one nearer its front, one
/// nearer its rear, one midway), on four different bogies (masses, wheelbases, springs).
pub(crate) fn uneven_chain() -> Articulated {
    let body = |mass: f64, front: f64, rear: f64, k: f64| ArticulatedBody {
        mass,
        pitch_inertia: mass * (front + rear) * (front + rear) / 14.0,
        front,
        rear,
        secondary_stiffness: k,
        secondary_damping: 0.05 * k,
    };
    let bogie = |mass: f64, wheelbase: f64, k: f64| ArticulatedBogie {
        mass,
        pitch_inertia: 0.25 * mass * wheelbase * wheelbase,
        wheelbase,
        wheelset_mass: 0.6 * mass,
        primary_stiffness: k,
        primary_damping: 0.01 * k,
    };
    Articulated {
        length: 60.0,
        bodies: vec![
            body(36_000.0, 5.5, 13.2, 6e5),
            body(22_500.0, 8.9, 9.8, 8e5),
            body(27_000.0, 9.0, 9.0, 4e5),
        ],
        bogies: vec![
            bogie(2200.0, 3.0, 2.6e6),
            bogie(2900.0, 2.5, 2.0e6),
            bogie(3100.0, 3.0, 1.5e6),
            bogie(2700.0, 2.8, 1.3e6),
        ],
    }
}
