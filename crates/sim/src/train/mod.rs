//! Trains: an ordered list of rail vehicles (module [`vehicle`]) crossing the bridge.
//!
//! A train is described by its vehicles in running order; vehicle i's leading axle is the sum
//! of the `length`s of the vehicles before it behind the train's leading axle. This module
//! holds the description only (parameters, geometry, statics); the scenario keys are parsed
//! in `config` and the dynamics are in `vehicle_bridge` (and the moving-force models of
//! `beam`). SI units.

pub mod vehicle;

pub use vehicle::{Articulated, BogieVehicle, MovingForces, QuarterCar, SprungMass, VehicleSpec};

/// A train: a name and its vehicles in running order (`count` already expanded).
#[derive(Debug, Clone, PartialEq)]
pub struct Train {
    /// Name (a preset name, or the scenario's).
    pub name: String,
    /// The vehicles, leading vehicle first.
    pub vehicles: Vec<VehicleSpec>,
}
