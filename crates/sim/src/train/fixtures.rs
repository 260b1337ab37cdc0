//! Vehicles shared by the unit tests of `train` (one definition of each test vehicle).

pub(crate) use super::presets::manchester;
use super::vehicle::Articulated;

/// An articulated chain of `bodies` Eurostar-like bodies (18.7 m between the shared bogies,
/// 3 m wheelbase; round values, not a published vehicle), 3 m longer than its bogie chain.
pub(crate) fn chain(bodies: usize) -> Articulated {
    Articulated {
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
