//! Building a [`Simulation`] from a scenario and the optional parts of a `vehicle_bridge`
//! file: multibody vehicles, the track, traction and the response points (the one place the
//! CLI, the Python package and the tests assemble a run).

use super::track::TrackSpec;
use super::traction::TractionSpec;
use super::{Scenario, Simulation, VehicleBridgeError, VehicleLayout};

/// The parts of a run besides its [`Scenario`].
#[derive(Debug, Default)]
pub struct SimulationParts {
    /// Multibody vehicles on the scenario's wheels ([`Simulation::with_vehicles`]).
    pub vehicles: Vec<VehicleLayout>,
    /// The track between the wheels and the bridge ([`Simulation::with_track`]).
    pub track: Option<TrackSpec>,
    /// Longitudinal friction ([`Simulation::set_traction`]).
    pub traction: Option<TractionSpec>,
    /// Response points besides the output point \[m\] ([`Simulation::set_output_points`]).
    pub points: Vec<f64>,
}

impl Simulation {
    /// The simulation of `scenario` with `parts`.
    pub fn with_parts(
        scenario: Scenario,
        parts: SimulationParts,
    ) -> Result<Self, VehicleBridgeError> {
        let SimulationParts {
            vehicles,
            track,
            traction,
            points,
        } = parts;
        let mut sim = match track {
            Some(track) => Simulation::with_track(scenario, vehicles, track)?,
            None => Simulation::with_vehicles(scenario, vehicles)?,
        };
        if let Some(spec) = traction {
            sim.set_traction(spec)?;
        }
        sim.set_output_points(&points)?;
        Ok(sim)
    }
}
