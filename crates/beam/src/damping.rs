//! Modal damping models.
//!
//! Each mode obeys q_j'' + c_j q_j' + ω_j² q_j = f_j with the velocity coefficient c_j = 2 ζ_j ω_j.
//! Rayleigh damping C = α M + β K is diagonal in a mass-normalised basis with c_j = α + β ω_j²,
//! i.e. ζ_j = α/(2ω_j) + β ω_j/2 (Clough & Penzien, *Dynamics of Structures*, §12-4); for rigid
//! modes (ω_j = 0) it leaves the finite coefficient c_j = α.

use crate::error::{BeamError, non_negative};

/// How the modes are damped.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum ModalDamping {
    /// No damping.
    #[default]
    Undamped,
    /// One damping ratio ζ for every mode.
    Uniform(f64),
    /// One damping ratio per mode (length = number of modes).
    PerMode(Vec<f64>),
    /// Rayleigh damping C = α M + β K.
    Rayleigh {
        /// Mass-proportional coefficient α [1/s].
        mass_coefficient: f64,
        /// Stiffness-proportional coefficient β \[s\].
        stiffness_coefficient: f64,
    },
}

impl ModalDamping {
    /// Rayleigh coefficients giving ratio ζ_a at ω_a and ζ_b at ω_b:
    /// solve ζ = α/(2ω) + βω/2 at both frequencies (ω_a ≠ ω_b, both > 0).
    pub fn rayleigh_from_two_modes(
        omega_a: f64,
        zeta_a: f64,
        omega_b: f64,
        zeta_b: f64,
    ) -> Result<Self, BeamError> {
        let omega_a = crate::error::positive("omega_a", omega_a)?;
        let omega_b = crate::error::positive("omega_b", omega_b)?;
        non_negative("zeta_a", zeta_a)?;
        non_negative("zeta_b", zeta_b)?;
        if (omega_a - omega_b).abs() <= 1e-12 * omega_a.max(omega_b) {
            return Err(BeamError::InvalidParameter {
                name: "omega_b",
                value: omega_b,
                reason: "must differ from omega_a",
            });
        }
        let (alpha, beta) = solve_rayleigh(omega_a, zeta_a, omega_b, zeta_b);
        Ok(ModalDamping::Rayleigh {
            mass_coefficient: alpha,
            stiffness_coefficient: beta,
        })
    }

    /// Velocity coefficients c_j = 2 ζ_j ω_j (or α + β ω_j² for Rayleigh) for the given ω_j.
    pub fn velocity_coefficients(&self, omegas: &[f64]) -> Result<Vec<f64>, BeamError> {
        let mut out = vec![0.0; omegas.len()];
        self.fill_velocity_coefficients(omegas, &mut out)?;
        Ok(out)
    }

    /// As [`Self::velocity_coefficients`] into a preallocated slice.
    pub fn fill_velocity_coefficients(
        &self,
        omegas: &[f64],
        out: &mut [f64],
    ) -> Result<(), BeamError> {
        crate::modal::check_len("out", out.len(), omegas.len())?;
        match self {
            ModalDamping::Undamped => out.fill(0.0),
            ModalDamping::Uniform(zeta) => {
                let zeta = non_negative("zeta", *zeta)?;
                for (c, w) in out.iter_mut().zip(omegas) {
                    *c = 2.0 * zeta * w;
                }
            }
            ModalDamping::PerMode(zetas) => {
                crate::modal::check_len("zetas", zetas.len(), omegas.len())?;
                for ((c, w), z) in out.iter_mut().zip(omegas).zip(zetas) {
                    *c = 2.0 * non_negative("zeta", *z)? * w;
                }
            }
            ModalDamping::Rayleigh {
                mass_coefficient,
                stiffness_coefficient,
            } => {
                let a = non_negative("mass_coefficient", *mass_coefficient)?;
                let b = non_negative("stiffness_coefficient", *stiffness_coefficient)?;
                for (c, w) in out.iter_mut().zip(omegas) {
                    *c = a + b * w * w;
                }
            }
        }
        Ok(())
    }

    /// Damping ratio ζ_j = c_j / (2ω_j) of a mode with circular frequency ω > 0.
    pub fn damping_ratio(&self, j: usize, omega: f64) -> Result<f64, BeamError> {
        let omega = crate::error::positive("omega", omega)?;
        let c = match self {
            ModalDamping::PerMode(z) => {
                let zeta = z.get(j).ok_or(BeamError::ModeIndex {
                    index: j,
                    n_modes: z.len(),
                })?;
                2.0 * non_negative("zeta", *zeta)? * omega
            }
            _ => self.velocity_coefficients(&[omega])?[0],
        };
        Ok(c / (2.0 * omega))
    }
}

/// Solve [1/(2ω_a), ω_a/2; 1/(2ω_b), ω_b/2] (α, β) = (ζ_a, ζ_b) by Cramer's rule.
/// (the caller guarantees ω_a ≠ ω_b, so the determinant ¼(ω_b/ω_a − ω_a/ω_b) is non-zero).
fn solve_rayleigh(wa: f64, za: f64, wb: f64, zb: f64) -> (f64, f64) {
    let det = 0.25 * (wb / wa - wa / wb);
    let alpha = (za * 0.5 * wb - zb * 0.5 * wa) / det;
    let beta = (zb / (2.0 * wa) - za / (2.0 * wb)) / det;
    (alpha, beta)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two-mode Rayleigh fit must reproduce both target ratios (closed-form identity
    /// ζ = α/(2ω) + βω/2); tolerance 1e-14 relative (a 2x2 solve).
    #[test]
    fn rayleigh_hits_both_targets() {
        let d = ModalDamping::rayleigh_from_two_modes(30.0, 0.02, 270.0, 0.03).unwrap();
        let z1 = d.damping_ratio(0, 30.0).unwrap();
        let z2 = d.damping_ratio(1, 270.0).unwrap();
        assert!(
            (z1 - 0.02).abs() < 1e-14 && (z2 - 0.03).abs() < 1e-14,
            "{z1} {z2}"
        );
        // Between the anchors Rayleigh damping is below the larger target (it is convex in ω with
        // its minimum √(αβ) inside) — a property, not a re-computation.
        let zmid = d.damping_ratio(0, 90.0).unwrap();
        assert!(zmid < 0.03);
    }

    #[test]
    fn uniform_gives_two_zeta_omega_and_rejects_negative() {
        let c = ModalDamping::Uniform(0.05)
            .velocity_coefficients(&[0.0, 10.0])
            .unwrap();
        assert_eq!(c, vec![0.0, 1.0]);
        assert!(
            ModalDamping::Uniform(-0.1)
                .velocity_coefficients(&[1.0])
                .is_err()
        );
        assert!(
            ModalDamping::Uniform(f64::NAN)
                .velocity_coefficients(&[1.0])
                .is_err()
        );
        assert!(
            ModalDamping::PerMode(vec![0.1])
                .velocity_coefficients(&[1.0, 2.0])
                .is_err()
        );
    }
}
