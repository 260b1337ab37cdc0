//! What a vehicle–bridge run reports about its train (the CLI's summary.json, the Python
//! package's `run`): per multibody vehicle the peak body, pitch and bogie accelerations, the
//! largest wheel unloading ratio, the train's name, axles, length and mass, and the passenger
//! comfort level of EN 1990 A2.4.4.3.2 (references.md §T3). SI units.

use serde::Serialize;

use crate::train::Train;
use crate::vehicle_bridge::Simulation;

/// Per multibody (bogie or articulated) vehicle: peak accelerations over the run.
#[derive(Debug, Serialize, Clone, Copy, Default, PartialEq)]
pub struct VehicleMax {
    /// Car body vertical \[m/s²\].
    pub max_body_acceleration: f64,
    /// Car body pitch \[rad/s²\].
    pub max_body_pitch_acceleration: f64,
    /// Bogies vertical \[m/s²\].
    pub max_bogie_acceleration: f64,
}

/// The train of a `[train]` scenario.
#[derive(Debug, Serialize, Clone, PartialEq)]
pub struct TrainSummary {
    /// Its name.
    pub name: String,
    /// Number of axles.
    pub axles: usize,
    /// First axle to last \[m\].
    pub length: f64,
    /// Total mass \[kg\].
    pub mass: f64,
}

impl TrainSummary {
    /// The summary of `train` (static axle loads at the model's gravity).
    pub fn of(train: &Train) -> Self {
        TrainSummary {
            name: train.name.clone(),
            axles: train
                .axles(crate::vehicle_bridge::GRAVITY)
                .map_or(0, |a| a.len()),
            length: train.length(),
            mass: train.mass(),
        }
    }
}

/// Passenger comfort (EN 1990 A2.4.4.3.2): the largest vertical car-body acceleration and the
/// level it reaches.
#[derive(Debug, Serialize, Clone, PartialEq)]
pub struct ComfortSummary {
    /// \[m/s²\].
    pub max_body_acceleration: f64,
    /// `very good` (≤ 1.0 m/s²), `good` (≤ 1.3), `acceptable` (≤ 2.0) or `null` (worse).
    pub level: Option<&'static str>,
    /// The levels and their limits \[m/s²\].
    pub levels: Vec<(&'static str, f64)>,
}

impl ComfortSummary {
    /// The comfort of a run whose largest car-body acceleration is `max_body_acceleration`.
    pub fn of(max_body_acceleration: f64) -> Self {
        ComfortSummary {
            max_body_acceleration,
            level: crate::sweep::eurocode::comfort_level(max_body_acceleration),
            levels: crate::sweep::eurocode::COMFORT_LEVELS.to_vec(),
        }
    }
}

/// Accumulates the per-vehicle peaks and the unloading ratio over the steps of a run: call
/// [`Self::observe`] after every step.
#[derive(Debug, Clone, Default)]
pub struct TrainMonitor {
    vehicles: Vec<VehicleMax>,
    max_unloading_ratio: f64,
}

impl TrainMonitor {
    /// A monitor for the vehicles of `sim`.
    pub fn new(sim: &Simulation) -> Self {
        TrainMonitor {
            vehicles: vec![VehicleMax::default(); sim.multibody_vehicle_count()],
            max_unloading_ratio: 0.0,
        }
    }

    /// Takes the state of `sim` after a step into the peaks.
    pub fn observe(&mut self, sim: &Simulation) {
        for (v, m) in self.vehicles.iter_mut().enumerate() {
            if let Some(r) = sim.vehicle_response(v) {
                m.max_body_acceleration = m.max_body_acceleration.max(r.body_acceleration.abs());
                m.max_body_pitch_acceleration = m
                    .max_body_pitch_acceleration
                    .max(r.body_pitch_acceleration.abs());
                m.max_bogie_acceleration = m.max_bogie_acceleration.max(r.bogie_acceleration.abs());
            }
        }
        for (w, &load) in sim.wheels().iter().zip(sim.static_loads()) {
            if load > 0.0 {
                self.max_unloading_ratio = self
                    .max_unloading_ratio
                    .max((load - w.contact.force) / load);
            }
        }
    }

    /// Per multibody vehicle (running order), or `None` without any.
    pub fn vehicles(&self) -> Option<Vec<VehicleMax>> {
        (!self.vehicles.is_empty()).then(|| self.vehicles.clone())
    }

    /// max over wheels and steps of (W_k − F_k)/W_k (1 = a wheel fully unloaded).
    pub fn max_unloading_ratio(&self) -> f64 {
        self.max_unloading_ratio
    }
}
