//! Real wheel and rail profiles as the wheels' contact (`[contact] model = "bem"` with a
//! `[contact.profiles]` table; docs/profiles.md, "In the vehicle–bridge simulation").
//!
//! Each wheel's contact is a [`wheelrail::ProfileLaw`]: the right wheel of a wheelset held at
//! a fixed lateral shift (and the roll that keeps both wheels on their rails, or a prescribed
//! one) on its rail; every evaluation solves each patch of the wheel in its own contact plane
//! at the vertical approach δ and returns the vertical force F_v = Σ F_n cos γ and its tangent
//! Σ cos²γ dF_n/dδ_n (references.md §W3.2). The vehicle–bridge model is vertical and planar:
//! the modelled rail is the right one, and a positive shift moves the wheelset towards it
//! (its flange towards the rail's gauge corner); by symmetry the left wheel at a shift y is
//! the right wheel at −y. The rigid geometry is computed once per law (the lateral shift does
//! not change during the run).

use std::sync::Arc;

use halfspace::Material;
use wheelrail::{PatchOptions, ProfileLaw, Roll, Side, Wheelset};

use super::VehicleBridgeError;

/// The profiles, the wheelset's position and the patch grids of the profile contact.
#[derive(Debug, Clone)]
pub struct ProfileContact {
    /// Wheel and rail profiles, gauge, inclination, back-to-back distance and nominal rolling
    /// radius (shared by the wheels).
    pub wheelset: Arc<Wheelset>,
    /// Lateral shift of the wheelset towards the modelled (right) rail \[m\].
    pub lateral_shift: f64,
    /// The wheelset's roll.
    pub roll: Roll,
    /// Elements per direction of each patch's grid.
    pub elements: usize,
}

/// Equal when they share the same wheelset (the same `Arc`) and the same settings.
impl PartialEq for ProfileContact {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.wheelset, &other.wheelset)
            && self.lateral_shift == other.lateral_shift
            && self.roll == other.roll
            && self.elements == other.elements
    }
}

impl ProfileContact {
    /// Nominal rolling radius r₀ of the wheels \[m\].
    pub fn wheel_radius(&self) -> f64 {
        self.wheelset.params().wheel_radius
    }

    /// The patch grids' settings.
    pub fn options(&self) -> PatchOptions {
        PatchOptions {
            nx: self.elements,
            ny: self.elements,
            ..PatchOptions::default()
        }
    }

    /// The contact law of one wheel (rigid geometry computed here) for the combined material
    /// `material`.
    pub fn law(&self, material: Material) -> Result<ProfileLaw, VehicleBridgeError> {
        ProfileLaw::with_roll(
            (*self.wheelset).clone(),
            self.lateral_shift,
            self.roll,
            Side::Right,
            material,
            self.options(),
        )
        .map_err(VehicleBridgeError::from)
    }
}
