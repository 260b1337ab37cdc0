//! Step acceptance: the public step, recursive step halving of a failing attempt, and the
//! block-diagonal step matrix A = c_M M + c_C C + c_K K.

use super::{CouplingSolver, Simulation, VehicleBridgeError};

/// Why one step attempt failed.
#[derive(Debug)]
pub(super) struct StepFailure {
    pub(super) iterations: usize,
    pub(super) change: f64,
    pub(super) reason: String,
    pub(super) fatal: Option<VehicleBridgeError>,
}

impl Simulation {
    /// Advances by one step of the scenario's Δt (with step reduction on failure).
    pub fn step(&mut self) -> Result<(), VehicleBridgeError> {
        let dt = self.scenario.dt;
        if self.track.is_some() {
            self.track_step(dt)?;
        } else if self.radau.is_some() {
            self.radau_step(dt)?;
        } else {
            self.advance_locating_landings(dt)?;
        }
        if let Some(tr) = self.traction.as_mut() {
            tr.update(dt, self.scenario.speed, &self.samples, &self.contacts)?;
        }
        Ok(())
    }

    /// Advances by `dt`, retrying a failed attempt as two half steps up to
    /// `coupling.max_halvings` times (module documentation).
    pub(super) fn advance(&mut self, dt: f64, depth: usize) -> Result<(), VehicleBridgeError> {
        match self.try_step(dt) {
            Ok(()) => Ok(()),
            Err(failure) => {
                if let Some(fatal) = failure.fatal {
                    return Err(fatal);
                }
                self.stats.failed_steps += 1;
                if depth >= self.scenario.coupling.max_halvings {
                    let mut reason = failure.reason;
                    if self.scenario.coupling.solver == CouplingSolver::Picard {
                        reason.push_str(&self.picard_remedy(dt));
                    }
                    return Err(VehicleBridgeError::CouplingFailed {
                        solver: self.scenario.coupling.solver.name(),
                        t: self.t(),
                        dt,
                        halvings: depth,
                        iterations: failure.iterations,
                        change: failure.change,
                        reason,
                    });
                }
                self.advance(0.5 * dt, depth + 1)?;
                self.advance(0.5 * dt, depth + 1)
            }
        }
    }

    /// Rebuilds the block-diagonal step matrix A if the step coefficients changed. A singular
    /// block (e.g. a massless wheel without suspension in the step, or non-finite
    /// coefficients) is an error naming the DOF, never silently dropped.
    pub(super) fn update_a(&mut self) -> Result<(), VehicleBridgeError> {
        let eq = &self.eq;
        let key = (
            eq.mass_coefficient,
            eq.damping_coefficient,
            eq.stiffness_coefficient,
        );
        if key == self.a_coefficients {
            return Ok(());
        }
        // Invalidate first: a failed rebuild must not be reused by the next step.
        self.a_coefficients = (f64::NAN, f64::NAN, f64::NAN);
        let (cm, cc, ck) = key;
        let s = &self.structure;
        let a = &mut self.a_matrix;
        a.clear();
        let entry = |i: usize, j: usize| {
            cm * s.mass[(i, j)] + cc * s.damping[(i, j)] + ck * s.stiffness[(i, j)]
        };
        let singular = |dof: usize, what: &str| VehicleBridgeError::SingularStepMatrix {
            dof,
            reason: format!(
                "the {what} block of A = {cm:e} M + {cc:e} C + {ck:e} K is singular or not finite"
            ),
        };
        let m = self.scenario.bridge.n_modes();
        for j in 0..m {
            a.push1(j, entry(j, j))
                .map_err(|_| singular(j, "bridge-mode"))?;
        }
        for (k, &iw) in self.wheel_dof.iter().enumerate() {
            if self.wheel_vehicle[k].is_some() {
                continue; // in its vehicle's dense block
            }
            let pushed = match self.body_dof[k] {
                None => a.push1(iw, entry(iw, iw)),
                Some(ib) => a.push2(
                    iw,
                    ib,
                    entry(iw, iw),
                    entry(iw, ib),
                    entry(ib, iw),
                    entry(ib, ib),
                ),
            };
            pushed.map_err(|_| singular(iw, "wheel"))?;
        }
        let mut block = Vec::new();
        for v in &self.vehicles {
            let d = v.dofs.len();
            block.resize(d * d, 0.0);
            for (r, &i) in v.dofs.iter().enumerate() {
                for (c, &j) in v.dofs.iter().enumerate() {
                    block[r * d + c] = entry(i, j);
                }
            }
            a.push_dense(&v.dofs, &block[..d * d])
                .map_err(|_| singular(v.dofs[0], "multibody-vehicle"))?;
        }
        self.a_coefficients = key;
        Ok(())
    }
}
