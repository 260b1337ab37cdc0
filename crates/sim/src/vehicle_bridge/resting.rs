//! Multibody vehicles at rest ahead of the span, held out of the coupled step (issue #10,
//! performance).
//!
//! A bogie or articulated vehicle starts in static equilibrium on the rigid, smooth approach
//! (module documentation, "Start"). While none of its wheels is on the span (all mode shapes
//! under it zero) and the rail under every wheel and contact column is smooth (r = 0 there,
//! and r was zero along its whole path so far, with a zero start velocity), nothing acts on it
//! but gravity and the rail, so its exact solution stays the static state: its step changes
//! nothing. The coupled step then leaves it out — its wheels are not evaluated and take no part
//! in the coupling iteration (residual, capacitance groups, convergence; the force floor keeps
//! their last value), its rows of A are held (`linalg::BlockDiagonal::hold_dense`) and its DOFs
//! are frozen in the structural stepper (`StructuralStepper::freeze`: v = a = 0, q kept, so
//! `x = q̃ = q`, and the predictor, history force, effective load and corrector skip its rows;
//! the structure keeps their rows of K q, `Structure::keep_rows`)
//! — until the first step whose geometry puts one of its wheels on the span or on a non-zero
//! irregularity; from then on it is stepped like every other vehicle, for good. The geometry
//! of a step is therefore evaluated before its step equation.
//!
//! The full step instead moves a vehicle at rest by its start's imbalance: the static start
//! (wheel loads from the vehicle's statics, body and bogies from K_ff q_f = g_f − K_fw z_w)
//! balances it to round-off of its matrices, and the full step lets that residual accelerate
//! it (measured for the Manchester car: about 1e-9 m/s² of body acceleration, 1e-10 of g; 4e-11
//! m of body displacement in 0.3 s). The held vehicle stays exactly static. The test
//! `train_resting_vehicles::held_vehicles_equal_the_full_step` compares the whole crossing's
//! histories with and without the hold: they agree to 1e-10 of the state and 1e-9 of the
//! contact forces (the imbalance carried through the stiff Hertz contact once the car runs).
//!
//! The hold applies to the structural methods with the quasi-Newton coupling and compliant
//! contacts (Hertz, BEM), without friction (the track and Radau5 paths do not use it); a
//! vehicle is evaluated in the first step (its contact outputs are those of the static state
//! from then on).

use std::ops::Range;

use super::contact::is_rigid;
use super::scenario::CouplingSolver;
use super::{Simulation, VehicleBridgeError};

/// How a multibody vehicle takes part in the current step attempt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Part {
    /// In the coupled step with every other wheel.
    Coupled,
    /// At rest ahead of the span: held out of the step, its DOFs keep the predictor.
    Resting,
    /// Off the span and not at rest: held out of the coupled step and solved on its own
    /// (module `detached`).
    Detached,
}

/// Which vehicles are held out of the current step attempt.
#[derive(Debug, Default)]
pub(super) struct Resting {
    /// The hold of vehicles at rest is on for this run ([`Simulation::hold_resting_vehicles`])
    /// and applicable to its scenario (module documentation).
    enabled: bool,
    /// The solve of detached vehicles on their own is on ([`Simulation::solve_detached_vehicles`]).
    pub(super) detach: bool,
    /// Per multibody vehicle: still at rest (nothing has reached it since the start).
    at_rest: Vec<bool>,
    /// Per multibody vehicle: its part in the current step attempt.
    pub(super) part: Vec<Part>,
    /// The vehicles solved on their own in the current step attempt.
    pub(super) detached: Vec<usize>,
    /// The DOFs of the vehicles at rest (they keep the predictor).
    pub(super) resting_dofs: Vec<usize>,
    /// Per wheel: its vehicle is held.
    pub(super) held_wheel: Vec<bool>,
    /// Per wheel: its last sample was written while its vehicle was held at rest (the
    /// samples of the following steps at rest are the same but for the step's count:
    /// `Simulation::accept`).
    pub(super) sampled_at_rest: Vec<bool>,
    /// The wheels taking part in the current step attempt, ascending.
    pub(super) live: Vec<usize>,
    /// The DOFs of the held vehicles (at rest or detached).
    pub(super) held_dofs: Vec<usize>,
    /// The DOFs outside the held vehicles (the rows of the coupled iteration's residual and
    /// update; a held vehicle's rows of the residual are zero), and outside the vehicles at
    /// rest (the rows of the step's load and predictor: a detached vehicle needs them), as
    /// sorted ranges.
    pub(super) live_rows: Vec<Range<usize>>,
    pub(super) moving_rows: Vec<Range<usize>>,
    /// Vehicle-steps at rest and detached so far (step attempts × vehicles in them).
    held_steps: u64,
    detached_steps: u64,
}

impl Simulation {
    /// Holds vehicles at rest ahead of the span out of the coupled step (`true`, the default
    /// where it applies: module `resting`), or steps every vehicle in every step (`false`,
    /// the reference the hold is tested against). Call before the first step.
    pub fn hold_resting_vehicles(&mut self, hold: bool) {
        let v0 = self.stepper.v();
        let nw = self.contacts.len();
        let r = &mut self.resting;
        r.enabled = hold && !self.contacts.iter().any(is_rigid);
        // A vehicle starting with a velocity (the rail's slope under it) is not at rest.
        r.at_rest = self
            .vehicles
            .iter()
            .map(|v| v.dofs.iter().all(|&i| v0[i] == 0.0))
            .collect();
        r.part = vec![Part::Coupled; self.vehicles.len()];
        r.detached.clear();
        r.resting_dofs.clear();
        r.held_wheel = vec![false; nw];
        r.sampled_at_rest = vec![false; nw];
        r.live = (0..nw).collect();
        r.held_dofs.clear();
        let n = self.work.x.len();
        ranges_outside(n, &[], &mut r.live_rows);
        ranges_outside(n, &[], &mut r.moving_rows);
        for d in 0..self.vehicles.len() {
            self.a_matrix.hold_dense(d, false);
        }
        // Nothing frozen (an empty set cannot fail).
        let _ = self.stepper.freeze(&[]);
        self.structure.keep_rows(&[]);
    }

    /// Decides which vehicles are held out of the step attempt whose geometry
    /// (`wheel_geometry`) is in the work space, and lists the wheels that take part.
    pub(super) fn select_live_wheels(&mut self) -> Result<(), VehicleBridgeError> {
        let r = &mut self.resting;
        if r.at_rest.is_empty() || !(r.enabled || r.detach) {
            return Ok(());
        }
        // The structural path with the quasi-Newton coupling and without friction (the track
        // and Radau5 paths do not come here).
        let allowed = r.enabled
            && self.scenario.coupling.solver == CouplingSolver::QuasiNewton
            && self.traction.is_none();
        let w = &self.work;
        let evaluated = self.stats.steps > 0;
        let mut changed = false;
        for (v, veh) in self.vehicles.iter().enumerate() {
            let wheels = veh.first_wheel..veh.first_wheel + (veh.dofs.len() - veh.own().len());
            let off_span = wheels.clone().all(|k| w.span_modes[k] == 0);
            // Once released, a vehicle is never at rest again: the rail under it matters only
            // while it is.
            if r.at_rest[v] {
                let smooth = wheels.clone().all(|k| {
                    w.r_at_wheel[k] == 0.0 && w.r_at_columns[k].iter().all(|&rc| rc == 0.0)
                });
                if !(off_span && smooth) {
                    r.at_rest[v] = false;
                }
            }
            let part = if !evaluated {
                Part::Coupled
            } else if allowed && r.at_rest[v] {
                Part::Resting
            } else if allowed
                && r.detach
                && off_span
                && super::detached::applies(veh, &self.contacts)
            {
                Part::Detached
            } else {
                Part::Coupled
            };
            if part != r.part[v] {
                changed = true;
                r.part[v] = part;
                let held = part != Part::Coupled;
                self.a_matrix.hold_dense(v, held);
                for k in wheels {
                    r.held_wheel[k] = held;
                }
            }
        }
        if changed {
            r.live.clear();
            r.live
                .extend((0..r.held_wheel.len()).filter(|&k| !r.held_wheel[k]));
            r.held_dofs.clear();
            r.resting_dofs.clear();
            r.detached.clear();
            for (v, veh) in self.vehicles.iter().enumerate() {
                match r.part[v] {
                    Part::Coupled => {}
                    Part::Resting => r.resting_dofs.extend_from_slice(&veh.dofs),
                    Part::Detached => r.detached.push(v),
                }
                if r.part[v] != Part::Coupled {
                    r.held_dofs.extend_from_slice(&veh.dofs);
                }
            }
            let n = self.work.x.len();
            ranges_outside(n, &r.held_dofs, &mut r.live_rows);
            ranges_outside(n, &r.resting_dofs, &mut r.moving_rows);
        }
        r.held_steps += r.part.iter().filter(|&&p| p == Part::Resting).count() as u64;
        r.detached_steps += r.detached.len() as u64;
        if changed {
            // The vehicles at rest are frozen in the stepper: v = a = 0, q kept, their rows
            // left out of the step's work.
            self.stepper.freeze(&self.resting.resting_dofs)?;
            // Their rows of K q are unchanged as well (their q is).
            self.structure.keep_rows(self.stepper.frozen());
        }
        Ok(())
    }

    /// Solves vehicles off the span on their own (`true`, the default where it applies:
    /// module `detached`), or in the coupled step with every other wheel (`false`, the
    /// reference the detached solve is tested against). Call before the first step.
    pub fn solve_detached_vehicles(&mut self, detach: bool) {
        self.resting.detach = detach;
    }

    /// Vehicle-steps solved on their own so far (step attempts × vehicles detached in them;
    /// module `detached`).
    pub fn detached_vehicle_steps(&self) -> u64 {
        self.resting.detached_steps
    }

    /// Vehicle-steps held out of the coupled step so far (step attempts × vehicles held in
    /// them; module `resting`).
    pub fn held_vehicle_steps(&self) -> u64 {
        self.resting.held_steps
    }

    /// Whether wheel `k`'s vehicle is held at rest in the current step attempt.
    pub(super) fn wheel_at_rest(&self, k: usize) -> bool {
        self.wheel_vehicle[k].is_some_and(|v| self.resting.part.get(v) == Some(&Part::Resting))
    }

    /// Zeroes the entries of the held vehicles' DOFs in `y` (a residual or a correction: a
    /// held vehicle keeps its state).
    pub(super) fn zero_held(held_dofs: &[usize], y: &mut [f64]) {
        for &i in held_dofs {
            y[i] = 0.0;
        }
    }
}

/// The indices `0..n` not in `dofs`, as sorted ranges into `out` (allocates: called when the
/// held vehicles change).
fn ranges_outside(n: usize, dofs: &[usize], out: &mut Vec<Range<usize>>) {
    let mut held = vec![false; n];
    for &i in dofs {
        held[i] = true;
    }
    out.clear();
    let mut start = None;
    for i in 0..=n {
        match (i < n && !held[i], start) {
            (true, None) => start = Some(i),
            (false, Some(first)) => {
                out.push(first..i);
                start = None;
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::ranges_outside;

    /// The complement of a DOF set as ranges: at the ends, in the middle, empty and full.
    #[test]
    fn ranges_outside_complement_the_dofs() {
        let mut out = Vec::new();
        ranges_outside(10, &[3, 4, 9, 0], &mut out);
        assert_eq!(out, vec![1..3, 5..9]);
        ranges_outside(4, &[], &mut out);
        assert_eq!(out, vec![0..4]);
        ranges_outside(3, &[2, 1, 0], &mut out);
        assert!(out.is_empty());
    }
}
