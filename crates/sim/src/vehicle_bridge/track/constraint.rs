//! The rigid wheel–rail contact on the track (`contact.model = "rigid"` with `[track]`;
//! docs/track.md): each wheel is tied to the rail point under it while it presses on it,
//!
//! ```text
//! δ_k = z_w − u_rail(x_k) + r(x_k) = 0   while F_k > 0,     F_k = 0 while δ_k < 0,
//! ```
//!
//! imposed on the step's displacements (the limit of the Hertz spring as its coefficient grows
//! without bound, solved on the same discrete equations). With the capacitance system of the
//! step (module [`super`], "Time step"), `δ = δ₀ − S F`, the forces solve the linear
//! complementarity problem `F ≥ 0, δ₀ − S F ≤ 0, F·(δ₀ − S F) = 0` (S = s Vᵀ A⁻¹ V is
//! symmetric positive definite for wheels on distinct rail points, so the problem has one
//! solution, references.md §D4.2). An active-set iteration finds it: the wheels on the rail
//! solve `S_AA F_A = δ₀_A`; a wheel whose force would pull leaves the set, a lifted wheel that
//! would penetrate the rail joins it. A wheel that lifts off flies freely (its suspension and
//! gravity) and lands when its gap closes at the end of a step (a plastic impact: it is put on
//! the rail with the rail's motion by the constraint of that step).

use halfspace::law::LawOutput;
use integrate::DenseLu;

use super::super::VehicleBridgeError;

/// The active-set solve of the rigid contacts (module documentation), sized for k wheels.
#[derive(Debug)]
pub(super) struct RigidContacts {
    active: Vec<bool>,
    lu: DenseLu<f64>,
    rhs: Vec<f64>,
}

impl RigidContacts {
    /// Work space for `k` wheels.
    pub(super) fn new(k: usize) -> Self {
        Self {
            active: vec![true; k],
            lu: DenseLu::new(k),
            rhs: vec![0.0; k],
        }
    }

    /// The forces F of the complementarity problem of δ₀ and S (k × k, row-major) into
    /// `forces` (holding the last step's forces on entry: the wheels that carried a force
    /// start in the active set), the law outputs (the force only) into `outputs`. A wheel
    /// joins the set when the force it would need to close its gap exceeds `tol` \[N\].
    /// Returns the active-set iterations.
    pub(super) fn forces(
        &mut self,
        delta0: &[f64],
        cap: &[f64],
        forces: &mut [f64],
        outputs: &mut [LawOutput],
        tol: f64,
    ) -> Result<usize, VehicleBridgeError> {
        let k = delta0.len();
        for c in 0..k {
            self.active[c] = forces[c] > 0.0 || delta0[c] > 0.0;
        }
        let max_iter = 4 * k + 4;
        for it in 1..=max_iter {
            // Rows of the active wheels: S_AA F_A = δ₀_A; of the others: F = 0.
            {
                let mut m = self.lu.matrix_mut();
                for r in 0..k {
                    for c in 0..k {
                        m[(r, c)] = if self.active[r] {
                            if self.active[c] { cap[r * k + c] } else { 0.0 }
                        } else if r == c {
                            1.0
                        } else {
                            0.0
                        };
                    }
                }
            }
            if !self.lu.factor() {
                return Err(failure(
                    it,
                    "singular capacitance matrix (two rigid wheels on the same rail point?)",
                ));
            }
            for c in 0..k {
                self.rhs[c] = if self.active[c] { delta0[c] } else { 0.0 };
            }
            self.lu.solve_in_place(&mut self.rhs);
            forces.copy_from_slice(&self.rhs);
            // A pulling wheel leaves the set (the most pulling first).
            let pulling = (0..k)
                .filter(|&c| self.active[c] && forces[c] < 0.0)
                .min_by(|&a, &b| forces[a].total_cmp(&forces[b]));
            if let Some(c) = pulling {
                self.active[c] = false;
                continue;
            }
            // A lifted wheel that would penetrate joins it (the deepest first).
            let penetrating = (0..k)
                .filter(|&c| !self.active[c])
                .map(|c| {
                    let delta = delta0[c] - (0..k).map(|j| cap[c * k + j] * forces[j]).sum::<f64>();
                    (c, delta / cap[c * k + c])
                })
                .filter(|&(_, f)| f > tol)
                .max_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((c, _)) = penetrating {
                self.active[c] = true;
                continue;
            }
            for c in 0..k {
                outputs[c] = LawOutput {
                    force: forces[c],
                    ..LawOutput::default()
                };
            }
            return Ok(it);
        }
        Err(failure(max_iter, "the active set did not settle"))
    }
}

fn failure(iterations: usize, reason: &str) -> VehicleBridgeError {
    super::solve_failure("track_rigid_active_set", iterations, reason)
}
