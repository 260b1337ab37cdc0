//! Multibody vehicles on the wheels of the coupled model: a bogie vehicle
//! ([`crate::train::BogieVehicle`], 10 DOFs, `crate::train::bogie_vehicle`) owns four of the
//! scenario's wheels (its wheelsets, in running order) and adds its car body and bogies (6
//! DOFs). The wheels stay the model's contact DOFs; the vehicle's mass, stiffness and damping
//! couple them through the suspensions, so the step matrix A gets one dense 10 × 10 block per
//! vehicle (`linalg::BlockDiagonal::push_dense`) and the coupling iteration, the contact laws
//! (rigid, Hertz, BEM) and loss of contact are those of every wheel.
//!
//! Static start: each wheel's approach is that of its static load W_k (the vehicle's statics,
//! `crate::train::Train::axles`), and the body and bogie DOFs solve K_ff q_f = g_f − K_fw z_w
//! with the wheels at their start positions; on a level track this is exactly the equilibrium
//! with the contact forces W_k.

use crate::train::BogieVehicle;
use crate::train::bogie_vehicle::{DOFS, FIRST_WHEEL};

/// A bogie vehicle placed on four consecutive wheels of the scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct BogieLayout {
    /// The vehicle.
    pub vehicle: BogieVehicle,
    /// Index of its first (leading) wheelset among the scenario's wheels; the next three are
    /// its other wheelsets in running order.
    pub first_wheel: usize,
}

/// A placed vehicle's global DOF indices (body and bogies, then its four wheels) and matrices.
#[derive(Debug, Clone)]
pub(super) struct VehicleDofs {
    pub(super) first_wheel: usize,
    /// Global index of each of the 10 local DOFs.
    pub(super) dofs: [usize; DOFS],
    pub(super) matrices: crate::train::bogie_vehicle::VehicleMatrices,
}

impl VehicleDofs {
    /// Global index of the car body's vertical DOF.
    pub(super) fn body(&self) -> usize {
        self.dofs[0]
    }

    /// The 6 own DOFs (body, bogies).
    pub(super) fn own(&self) -> &[usize] {
        &self.dofs[..FIRST_WHEEL]
    }
}

/// The accelerations of a bogie vehicle's body and bogies at the current state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BogieVehicleResponse {
    /// Car body vertical acceleration \[m/s²\] (positive downwards).
    pub body_acceleration: f64,
    /// Car body pitch acceleration \[rad/s²\].
    pub body_pitch_acceleration: f64,
    /// Front and rear bogie vertical accelerations \[m/s²\].
    pub bogie_accelerations: [f64; 2],
}

impl super::Simulation {
    /// Number of bogie vehicles on the wheels.
    pub fn bogie_vehicle_count(&self) -> usize {
        self.vehicles.len()
    }

    /// The body and bogie accelerations of bogie vehicle `v` (running order) at the current
    /// state; `None` if there is no such vehicle.
    pub fn bogie_vehicle_response(&self, v: usize) -> Option<BogieVehicleResponse> {
        let d = &self.vehicles.get(v)?.dofs;
        let a = self.acceleration();
        Some(BogieVehicleResponse {
            body_acceleration: a[d[0]],
            body_pitch_acceleration: a[d[1]],
            bogie_accelerations: [a[d[2]], a[d[4]]],
        })
    }
}
