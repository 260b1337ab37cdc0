//! Multibody vehicles on the wheels of the coupled model: a bogie vehicle
//! ([`crate::train::BogieVehicle`], 10 DOFs, `crate::train::bogie_vehicle`) owns four of the
//! scenario's wheels (its wheelsets, in running order) and adds its car body and bogies (6
//! DOFs); an articulated train ([`crate::train::Articulated`], `crate::train::articulated`)
//! with n bodies owns 2(n+1) wheels and adds its bodies and bogies (4n + 2 DOFs). The wheels
//! stay the model's contact DOFs; the vehicle's mass, stiffness and damping couple them
//! through the suspensions, so the step matrix A gets one dense block per vehicle
//! (`linalg::BlockDiagonal::push_dense`) and the coupling iteration, the contact laws (rigid,
//! Hertz, BEM) and loss of contact are those of every wheel.
//!
//! Static start: each wheel's approach is that of its static load W_k (the vehicle's statics,
//! `crate::train::Train::axles`), and the body and bogie DOFs solve K_ff q_f = g_f − K_fw z_w
//! with the wheels at their start positions; on a level track this is exactly the equilibrium
//! with the contact forces W_k.

use crate::train::multibody::VehicleMatrices;
use crate::train::{Articulated, BogieVehicle};

/// A multibody vehicle of the coupled model.
#[derive(Debug, Clone, PartialEq)]
pub enum MultibodyVehicle {
    /// A car body on two bogies (10 DOFs).
    Bogie(BogieVehicle),
    /// Car bodies sharing their bogies with their neighbours.
    Articulated(Articulated),
}

impl MultibodyVehicle {
    /// Its matrices (body and bogie DOFs first, then the wheelsets).
    pub fn matrices(&self) -> VehicleMatrices {
        match self {
            Self::Bogie(b) => b.matrices(),
            Self::Articulated(a) => a.matrices(),
        }
    }

    /// Number of wheelsets (wheels of the scenario it owns).
    pub fn wheelsets(&self) -> usize {
        match self {
            Self::Bogie(_) => 4,
            Self::Articulated(a) => a.wheelsets(),
        }
    }

    /// Number of car bodies.
    pub fn bodies(&self) -> usize {
        match self {
            Self::Bogie(_) => 1,
            Self::Articulated(a) => a.body_count(),
        }
    }
}

/// A multibody vehicle placed on consecutive wheels of the scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleLayout {
    /// The vehicle.
    pub vehicle: MultibodyVehicle,
    /// Index of its first (leading) wheelset among the scenario's wheels; the next
    /// `vehicle.wheelsets() − 1` are its other wheelsets in running order.
    pub first_wheel: usize,
}

/// A placed vehicle's global DOF indices (bodies and bogies, then its wheels) and matrices.
#[derive(Debug, Clone)]
pub(super) struct VehicleDofs {
    pub(super) first_wheel: usize,
    /// Number of car bodies (their (z, θ) are the first own DOFs; the bogies follow).
    pub(super) bodies: usize,
    /// Global index of each local DOF.
    pub(super) dofs: Vec<usize>,
    pub(super) matrices: VehicleMatrices,
}

impl VehicleDofs {
    /// Global index of the vertical DOF of the car body over local wheelset `w`: the body
    /// resting on the wheelset's bogie (for a shared bogie, the body ahead of it).
    pub(super) fn body_over(&self, w: usize) -> usize {
        let bogie = w / 2;
        self.dofs[2 * bogie.min(self.bodies - 1)]
    }

    /// The own DOFs (bodies, bogies).
    pub(super) fn own(&self) -> &[usize] {
        &self.dofs[..self.matrices.own_dofs]
    }
}

/// The largest accelerations (signed, largest magnitude) of a multibody vehicle's bodies and
/// bogies at the current state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VehicleResponse {
    /// Car body vertical acceleration \[m/s²\] (positive downwards).
    pub body_acceleration: f64,
    /// Car body pitch acceleration \[rad/s²\].
    pub body_pitch_acceleration: f64,
    /// Bogie vertical acceleration \[m/s²\].
    pub bogie_acceleration: f64,
}

/// The entry of largest magnitude.
fn extreme(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |m: f64, v| if v.abs() > m.abs() { v } else { m })
}

impl super::Simulation {
    /// Number of multibody (bogie and articulated) vehicles on the wheels.
    pub fn multibody_vehicle_count(&self) -> usize {
        self.vehicles.len()
    }

    /// The body and bogie accelerations of multibody vehicle `v` (running order) at the
    /// current state; `None` if there is no such vehicle.
    pub fn vehicle_response(&self, v: usize) -> Option<VehicleResponse> {
        let veh = self.vehicles.get(v)?;
        let d = &veh.dofs;
        let a = self.acceleration();
        let nb = veh.bodies;
        let bogies = (veh.matrices.own_dofs - 2 * nb) / 2;
        Some(VehicleResponse {
            body_acceleration: extreme((0..nb).map(|j| a[d[2 * j]])),
            body_pitch_acceleration: extreme((0..nb).map(|j| a[d[2 * j + 1]])),
            bogie_acceleration: extreme((0..bogies).map(|i| a[d[2 * nb + 2 * i]])),
        })
    }

    /// Number of car bodies of the multibody vehicles (a bogie vehicle has one, an
    /// articulated vehicle several).
    pub fn car_body_count(&self) -> usize {
        self.vehicles.iter().map(|v| v.bodies).sum()
    }

    /// Vertical acceleration of its centre of gravity \[m/s²\] (positive downwards) and pitch
    /// acceleration \[rad/s²\] of every car body at the current state, in running order
    /// (vehicle by vehicle, each vehicle's bodies front to rear).
    pub fn car_body_accelerations(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let a = self.acceleration();
        self.vehicles.iter().flat_map(move |veh| {
            (0..veh.bodies).map(move |j| (a[veh.dofs[2 * j]], a[veh.dofs[2 * j + 1]]))
        })
    }
}
