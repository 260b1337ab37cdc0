//! The track's step matrix `A = c_M M + c_C C + c_K K` (module documentation of [`super`]):
//! its elimination order, its sparse Cholesky factor for a Δt, and the factors of the halved
//! Δt of failed steps (module `step`), built on first use and kept.

use beam::track::{SparseCholesky, Track};
use integrate::structural::AlphaParameters;

use super::super::VehicleBridgeError;
use super::TrackLayer;

/// The coupled system's step-matrix coefficients (c_M, c_C, c_K) for Δt (the step equation
/// of [`integrate::structural::StepEquation`]).
pub(super) fn step_coefficients(p: &AlphaParameters, dt: f64) -> (f64, f64, f64) {
    let c_qa = p.beta * dt * dt;
    let c_va = p.gamma * dt;
    (
        (1.0 - p.alpha_m) / c_qa,
        (1.0 - p.alpha_f) * c_va / c_qa,
        1.0 - p.alpha_f,
    )
}

/// The step matrix c_M M + c_C C + c_K K of Δt, factorised.
pub(super) fn factorise(
    n: usize,
    mass: &[(usize, usize, f64)],
    damping: &[(usize, usize, f64)],
    stiffness: &[(usize, usize, f64)],
    params: &AlphaParameters,
    dt: f64,
    ordering: &[usize],
) -> Result<SparseCholesky, VehicleBridgeError> {
    let (cm, cc, ck) = step_coefficients(params, dt);
    let mut all: Vec<(usize, usize, f64)> =
        Vec::with_capacity(mass.len() + damping.len() + stiffness.len());
    all.extend(mass.iter().map(|&(i, j, v)| (i, j, cm * v)));
    all.extend(damping.iter().map(|&(i, j, v)| (i, j, cc * v)));
    all.extend(stiffness.iter().map(|&(i, j, v)| (i, j, ck * v)));
    SparseCholesky::factorise_entries(n, &all, Some(ordering), "track step matrix").map_err(|e| {
        VehicleBridgeError::SingularStepMatrix {
            dof: 0,
            reason: e.to_string(),
        }
    })
}

/// The elimination order of the coupled system: the vehicle DOFs first (they couple to the
/// track only through the contact), then the track by nested dissection along the rail (a
/// rail node's w, θ separate the track before it from the track after it; the chain masses
/// of a separating node's sleeper go just before it), the bridge modes last (they couple to
/// every sleeper on the span). The elimination tree is then shallow, so L⁻¹P v of a contact
/// vector is non-zero only on the path from the wheel's element to the root.
pub(super) fn nested_dissection(track: &Track, n: usize) -> Vec<usize> {
    let n_track = track.n_track_dofs();
    let nodes = track.node_positions().len();
    let group = |k: usize| -> std::ops::Range<usize> {
        let end = if k + 1 < nodes {
            track.rail_dof(k + 1)
        } else {
            n_track
        };
        track.rail_dof(k)..end
    };
    let mut order: Vec<usize> = (n_track + track.n_modes()..n).collect();
    // Recursive bisection of the node range [lo, hi) (depth log₂ of the node count).
    fn dissect(
        lo: usize,
        hi: usize,
        group: &dyn Fn(usize) -> std::ops::Range<usize>,
        order: &mut Vec<usize>,
    ) {
        if hi - lo <= 2 {
            for k in lo..hi {
                order.extend(group(k));
            }
            return;
        }
        let mid = (lo + hi) / 2;
        dissect(lo, mid, group, order);
        dissect(mid + 1, hi, group, order);
        // The separator: the sleeper's masses (after w, θ in the numbering), then w, θ.
        let g = group(mid);
        order.extend(g.start + 2..g.end);
        order.extend(g.start..g.start + 2);
    }
    dissect(0, nodes, &group, &mut order);
    order.extend(n_track..n_track + track.n_modes());
    order
}

impl TrackLayer {
    /// Puts the factor of the step matrix of `dt` in place: the one of the last step, one
    /// built before (the scenario's Δt and its halvings) or a new one. The elimination order
    /// and the matrices' pattern are the same for every Δt, so the elimination tree and the
    /// contacts' sweep work spaces ([`SparseReach`]) stay valid.
    pub(super) fn use_step_size(&mut self, dt: f64) -> Result<(), VehicleBridgeError> {
        if dt == self.dt {
            return Ok(());
        }
        let factor = match self.other_factors.iter().position(|(d, _)| *d == dt) {
            Some(i) => self.other_factors.swap_remove(i).1,
            None => {
                let [mass, damping, stiffness] = &self.terms;
                let n = self.q.len();
                factorise(
                    n,
                    mass,
                    damping,
                    stiffness,
                    &self.params,
                    dt,
                    &self.ordering,
                )?
            }
        };
        let previous = std::mem::replace(&mut self.factor, factor);
        self.other_factors.push((self.dt, previous));
        self.dt = dt;
        Ok(())
    }
}
