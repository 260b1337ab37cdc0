//! Why a Picard coupling failed, and what to do about it (references.md §D4.2).
//!
//! The Picard iteration lags the contact force: its error map at wheel k is `e ← −λ_k e` with
//! the contraction factor
//!
//! ```text
//! λ_k = s k_c,k v_kᵀ A⁻¹ v_k   (≈ k_c β Δt² / m_w for a wheel much lighter than the bridge)
//! ```
//!
//! (s = 1 − α_f, k_c,k = dF/dδ of wheel k's contact at its static load, v_k the approach
//! vector of the module documentation, which is also the force direction ĝ_k of a point
//! contact), so it converges only when λ_k < 1, and slowly when λ_k approaches 1. λ grows
//! like Δt². A failed Picard step names the largest λ_k and the remedy.

use super::Simulation;

/// Contraction factors from which a failed Picard step is blamed on the iteration itself: at
/// λ = 0.5 the error falls by 2⁵⁰ ≈ 1e15 in 50 iterations, just enough for the default
/// tolerance, so a slower contraction can exhaust the iteration limit.
const SLOW_CONTRACTION: f64 = 0.5;

impl Simulation {
    /// The largest Picard contraction factor λ_k of the step matrix A of the last attempt,
    /// and its wheel (module documentation); `None` for rigid contacts only.
    pub(super) fn picard_contraction(&mut self) -> Option<(f64, usize)> {
        let s = 1.0 - self.eq.alpha_f;
        let w = &mut self.work;
        let mut largest: Option<(f64, usize)> = None;
        for k in 0..self.contacts.len() {
            let k_c = self.static_contact_stiffness[k];
            if super::contact::is_rigid(&self.contacts[k]) || k_c.is_nan() || k_c <= 0.0 {
                continue;
            }
            // v_k: −w_j(x_k) on the modes, +1 on the wheel (evaluate_contacts).
            w.floor_ainv_g.copy_from_slice(&w.v[k]);
            self.a_matrix.solve_in_place(&mut w.floor_ainv_g);
            let lambda = s * k_c * super::linalg::dot(&w.v[k], &w.floor_ainv_g).abs();
            if lambda.is_finite() && largest.is_none_or(|(l, _)| lambda > l) {
                largest = Some((lambda, k));
            }
        }
        largest
    }

    /// The diagnosis appended to the reason of a Picard step of size `dt` that failed: empty
    /// unless the contraction factor explains the failure.
    pub(super) fn picard_remedy(&mut self, dt: f64) -> String {
        let Some((lambda, k)) = self.picard_contraction() else {
            return String::new();
        };
        if lambda < SLOW_CONTRACTION {
            return String::new();
        }
        // λ ∝ Δt²: Δt/√λ · 0.7 gives λ ≈ 0.5.
        let dt_ok = 0.7 * dt / lambda.sqrt();
        let what = if lambda >= 1.0 {
            format!("Picard coupling diverges (contraction factor {lambda:.3} > 1 at wheel {k})")
        } else {
            format!(
                "Picard coupling converges too slowly (contraction factor {lambda:.3}, close to 1, at wheel {k})"
            )
        };
        format!(
            "; {what}: the contact stiffness {:.3e} N/m is too stiff for a lagged contact force at this step; use coupling.solver = \"quasi_newton\" (the default) or \"newton\", or integrator.dt <= {dt_ok:.2e} s",
            self.static_contact_stiffness[k]
        )
    }
}
