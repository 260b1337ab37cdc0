//! Convergence of the (quasi-)Newton coupling iteration by the contact laws' residual
//! (opt-in: [`Simulation::accept_by_law_residual`], used by the sweep's passages).
//!
//! Each (quasi-)Newton update solves the step equation with every contact law replaced by
//! its linearisation, so the new iterate x satisfies `A x = r + s Σ_k G_k(F_lin,k)` to
//! round-off, with the linearised forces `F_lin,k = F_k + ΔF_k` (for the extrapolated start,
//! `F_n + k_n (δ − δ_n) + ΔF`; for an off-span wheel folded into an articulated rake's band
//! factorised from a stiffness within the fold tolerance of its own, a chord step, ΔF is the
//! increment of that stiffness, `linalg::CapacitanceWork::fold_ratio`). The contact
//! evaluation at x that follows gives the laws' forces `F_k(δ_k(x))`. Their difference
//!
//! ```text
//! ρ = max_k |F_k(δ_k(x)) − F_lin,k|
//! ```
//!
//! is the whole residual of the coupled step at x with the evaluated forces: the laws hold
//! exactly there, and the step equation is off by `s Σ_k ĝ_k (F_k − F_lin,k)` (for a point
//! contact, whose ĝ = (−w(x_k), 1) does not depend on F). It is also what drives the next
//! update: with a fresh tangent the next force correction is ρ contracted by
//! `(1/k_c) / (1/k_c + s vᵀA⁻¹ĝ) ≤ 1` per wheel (Sherman–Morrison; references.md §D4.2).
//! When `ρ ≤ tol` the iterate is accepted with the evaluated forces: the same criterion as
//! the Picard iteration's `|F_it − F_it−1| ≤ tol` (whose iterate x_it also holds the
//! equation with the forces F_it−1), measured against the forces x was actually solved
//! with, instead of the default's, which compares two evaluations and so asks for one more
//! update after the Newton iteration has converged (the quadratic convergence makes the
//! correction of that update ≈ ρ). The accepted state differs from the default's by about
//! the last correction, i.e. within the coupling tolerance (`coupling.tol` × the largest
//! static wheel load).
//!
//! Since the extrapolated start records its forces φ in `prev_force` as well (the default
//! iteration's first change test |F(δ) − φ|, 2026-11-28), this test adds nothing at the first
//! evaluation after such a start (`law.force` equals `prev_force` there and the default test,
//! with max(tol, floor), runs first); it pays at the later iterations, i.e. in steps where
//! wheels lose or regain contact (about 3 % of the iterations of resonant HSLM passages,
//! `sweep_interaction_law.rs`).
//!
//! The test applies only when every wheel taking part is a compliant point contact (no rigid
//! constraint) and each is in contact both evaluated and linearised, or out of contact in
//! both (a wheel in the air has no tangent and stays out of the update, its force zero): no
//! wheel leaving or landing, so it never hides a change of the contact state.

use super::Simulation;
use super::contact::{is_point, is_rigid};

/// The linearised forces of the last update and the switch of the law-residual test.
#[derive(Debug, Default)]
pub(super) struct LawResidual {
    /// The test is on ([`Simulation::accept_by_law_residual`]).
    pub(super) on: bool,
    /// `force` holds every live wheel's linearised force of the last update.
    pub(super) valid: bool,
    /// Per wheel: F_lin of the last update \[N\].
    pub(super) force: Vec<f64>,
    /// Per wheel: a compliant point contact (the test can apply while it takes part).
    pub(super) eligible: Vec<bool>,
    /// Steps accepted by the test (statistics).
    pub(super) accepted: u64,
}

impl Simulation {
    /// Accepts a (quasi-)Newton iterate as converged when its contact laws' residual is
    /// within the coupling tolerance (module `law_residual`), instead of asking for one more
    /// update; off by default (the default iteration's states, forces and counts are then
    /// unchanged). Call before the first step.
    pub fn accept_by_law_residual(&mut self, on: bool) {
        self.work.law.on = on;
        self.work.law.valid = false;
        self.work.law.eligible = self
            .contacts
            .iter()
            .map(|c| !is_rigid(c) && is_point(c))
            .collect();
    }

    /// The steps accepted by the law-residual test ([`Self::accept_by_law_residual`]).
    pub fn law_residual_accepts(&self) -> u64 {
        self.work.law.accepted
    }

    /// Records the linearised forces of an update, valid when every live wheel is a
    /// compliant point contact: after the extrapolated start (`start`: it takes every live
    /// wheel, by position, their linearised start forces already in `law.force`)
    /// `force + df[a]`; after an update of the iteration the evaluated force + df[a] of the
    /// wheels `active`, and the evaluated force of the others (out of contact: zero, which
    /// the update keeps). For a wheel folded into a factorisation kept from other
    /// stiffnesses (a chord step, `linalg::CapacitanceWork::fold_ratio`) the increment is the
    /// one the solve used, so that the iterate holds the step equation with these forces.
    pub(super) fn record_linearised(&mut self, start: bool) {
        let w = &mut self.work;
        if !w.law.on {
            return;
        }
        let live = &self.resting.live;
        w.law.valid = live.iter().all(|&k| w.law.eligible[k]);
        if !w.law.valid {
            return;
        }
        let active = if start {
            live
        } else {
            for &k in live {
                w.law.force[k] = w.outputs[k].force;
            }
            &w.active
        };
        // A wheel folded into a kept (chord) factorisation: the increment the solve used.
        for (a, &k) in active.iter().enumerate() {
            w.law.force[k] += w.cap.fold_ratio(a) * w.df[a];
        }
    }

    /// The law residual ρ at the current evaluation (module `law_residual`), if the test
    /// applies: every live wheel is a compliant point contact and each is in contact both
    /// evaluated and linearised, or out of contact in both (no wheel leaving or landing).
    pub(super) fn law_residual(&self) -> Option<f64> {
        let w = &self.work;
        if !(w.law.on && w.law.valid) {
            return None;
        }
        let mut rho = 0.0f64;
        for &k in &self.resting.live {
            let (f, lin) = (w.outputs[k].force, w.law.force[k]);
            if (f > 0.0) != (lin > 0.0) {
                return None;
            }
            rho = rho.max((f - lin).abs());
        }
        Some(rho)
    }
}
