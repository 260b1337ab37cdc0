//! Moving forces on the track (the `moving_forces` vehicles of `[train]`; module
//! [`moving_forces`](super::super::moving_forces)): each axle load F_p at x_p + c t loads the
//! rail through the consistent (Hermite) load vector of the element under it, the same vector
//! b(x) through which a wheel's contact force loads the rail (references.md §D5.2). The track
//! layer refuses a force that is off the modelled track at any time of the run (its free ends
//! would take it as a sudden load); the range check below only guards the rail's ends.

use beam::track::Track;

use super::super::{Scenario, VehicleBridgeError};
use super::track_key;

/// Adds `scale` × Σ_p F_p b(x_p + c t) to the load vector `r` of the coupled system (the
/// track's DOFs come first in it).
pub(super) fn add_moving_loads(
    track: &Track,
    scenario: &Scenario,
    t: f64,
    scale: f64,
    r: &mut [f64],
) -> Result<(), VehicleBridgeError> {
    if scale == 0.0 {
        return Ok(());
    }
    let approach = track.layout().approach();
    let length = track.layout().rail_length();
    for p in &scenario.moving_forces {
        let x = p.position + scenario.speed * t + approach;
        if (0.0..=length).contains(&x) {
            track
                .add_point_force(x, scale * p.force, r)
                .map_err(track_key)?;
        }
    }
    Ok(())
}
