//! The bogie vehicle's mass, stiffness and damping matrices (10 DOFs, 2-D vertical plane) and
//! its natural frequencies on a rigid track in closed form (references.md §D2.2).
//!
//! DOFs, z positive downwards, pitch θ positive nose-down (front end moving down):
//! `[z_c, θ_c, z_1, θ_1, z_2, θ_2, z_w1, z_w2, z_w3, z_w4]`: car body, front bogie (at +a from
//! the body centre, a = bogie_spacing/2), rear bogie (−a), the wheelsets of the front bogie at
//! ±b (b = wheelbase/2) and of the rear bogie. Springs (and dampers alike) with elongation
//! e = gᵀq add k g gᵀ to K:
//!
//! * secondary, bogie i (s_1 = +1, s_2 = −1): e = z_c + s_i a θ_c − z_i, stiffness k₂;
//! * primary, wheelset j of bogie i (s_j = ±1): e = z_i + s_j b θ_i − z_wij, stiffness k₁.
//!
//! On a rigid track (wheelsets fixed) the six body and bogie DOFs split into three problems
//! (symmetry): bounce (body z_c with both bogies in phase), pitch (body θ_c with the bogies in
//! anti-phase) and the two bogie pitches, with the roots
//!
//! ```text
//! bounce:  det([[2k₂ − ω²m_c, −2k₂], [−k₂, k₂ + 2k₁ − ω²m_b]]) = 0
//! pitch:   det([[2k₂a² − ω²J_c, −2k₂a], [−k₂a, k₂ + 2k₁ − ω²m_b]]) = 0
//! bogie pitch: ω² = 2k₁b²/J_b (twice)
//! ```

use super::BogieVehicle;

/// Number of DOFs of a bogie vehicle.
pub const DOFS: usize = 10;
/// Index of the first wheelset DOF.
pub const FIRST_WHEEL: usize = 6;

use super::multibody::SpringAssembler;
pub use super::multibody::VehicleMatrices;

/// The natural frequencies \[Hz\] of a bogie vehicle on a rigid track (wheelsets fixed).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidTrackFrequencies {
    /// Body bounce (lower root of the bounce problem).
    pub body_bounce: f64,
    /// Body pitch (lower root of the pitch problem).
    pub body_pitch: f64,
    /// Bogies bouncing in phase (upper root of the bounce problem).
    pub bogie_bounce: f64,
    /// Bogies bouncing in anti-phase (upper root of the pitch problem).
    pub bogie_anti_bounce: f64,
    /// Bogie pitch.
    pub bogie_pitch: f64,
}

impl BogieVehicle {
    /// The contact-free matrices (module documentation).
    pub fn matrices(&self) -> VehicleMatrices {
        let a = 0.5 * self.bogie_spacing;
        let b = 0.5 * self.wheelbase;
        let mut springs = SpringAssembler::new(DOFS);
        let mut add = |g: &[(usize, f64)], k: f64, c: f64| springs.add(g, k, c);
        for (i, s) in [(0usize, 1.0), (1, -1.0)] {
            let (z, theta) = (2 + 2 * i, 3 + 2 * i);
            add(
                &[(0, 1.0), (1, s * a), (z, -1.0)],
                self.secondary_stiffness,
                self.secondary_damping,
            );
            for (j, sj) in [(0usize, 1.0), (1, -1.0)] {
                let w = FIRST_WHEEL + 2 * i + j;
                add(
                    &[(z, 1.0), (theta, sj * b), (w, -1.0)],
                    self.primary_stiffness,
                    self.primary_damping,
                );
            }
        }
        let (stiffness, damping) = springs.finish();
        let (mb, jb, mw) = (
            self.bogie_mass,
            self.bogie_pitch_inertia,
            self.wheelset_mass,
        );
        VehicleMatrices {
            own_dofs: FIRST_WHEEL,
            mass: vec![
                self.body_mass,
                self.body_pitch_inertia,
                mb,
                jb,
                mb,
                jb,
                mw,
                mw,
                mw,
                mw,
            ],
            stiffness,
            damping,
        }
    }

    /// Natural frequencies on a rigid track in closed form (module documentation).
    pub fn rigid_track_frequencies(&self) -> RigidTrackFrequencies {
        let (k1, k2) = (self.primary_stiffness, self.secondary_stiffness);
        let a = 0.5 * self.bogie_spacing;
        let b = 0.5 * self.wheelbase;
        let mb = self.bogie_mass;
        // Roots ω² of det([[p − ω² m1, q], [q', r − ω² m2]]) = 0.
        let roots = |p: f64, q: f64, q2: f64, r: f64, m1: f64, m2: f64| {
            let (aa, bb, cc) = (m1 * m2, -(p * m2 + r * m1), p * r - q * q2);
            let disc = (bb * bb - 4.0 * aa * cc).max(0.0).sqrt();
            // Numerically stable pair.
            let big = (-bb + disc) / (2.0 * aa);
            (cc / (aa * big), big)
        };
        let hz = |w2: f64| w2.max(0.0).sqrt() / std::f64::consts::TAU;
        let (bounce_lo, bounce_hi) =
            roots(2.0 * k2, -2.0 * k2, -k2, k2 + 2.0 * k1, self.body_mass, mb);
        let (pitch_lo, pitch_hi) = roots(
            2.0 * k2 * a * a,
            -2.0 * k2 * a,
            -k2 * a,
            k2 + 2.0 * k1,
            self.body_pitch_inertia,
            mb,
        );
        RigidTrackFrequencies {
            body_bounce: hz(bounce_lo),
            body_pitch: hz(pitch_lo),
            bogie_bounce: hz(bounce_hi),
            bogie_anti_bounce: hz(pitch_hi),
            bogie_pitch: hz(2.0 * k1 * b * b / self.bogie_pitch_inertia),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::{Mat, Side};

    use crate::train::fixtures::manchester;

    /// Frequencies \[Hz\] of the assembled 6 body-and-bogie DOFs with the wheelsets fixed:
    /// eigenvalues of M^{-1/2} K M^{-1/2} (faer's symmetric eigen-solver).
    fn assembled_frequencies(v: &BogieVehicle) -> Vec<f64> {
        let m = v.matrices();
        let n = FIRST_WHEEL;
        let a = Mat::<f64>::from_fn(n, n, |i, j| {
            m.stiffness[(i, j)] / (m.mass[i] * m.mass[j]).sqrt()
        });
        let values = a.self_adjoint_eigenvalues(Side::Lower).unwrap();
        let mut f: Vec<f64> = values
            .iter()
            .map(|w2| w2.sqrt() / std::f64::consts::TAU)
            .collect();
        f.sort_by(f64::total_cmp);
        f
    }

    #[test]
    fn the_closed_form_frequencies_are_the_eigenvalues_of_the_assembled_model() {
        for v in [
            manchester(),
            BogieVehicle {
                bogie_spacing: 17.375,
                wheelbase: 3.0,
                secondary_stiffness: 5.0e5,
                primary_stiffness: 3.1e6,
                bogie_pitch_inertia: 2500.0,
                ..manchester()
            },
        ] {
            let c = v.rigid_track_frequencies();
            let mut closed = vec![
                c.body_bounce,
                c.body_pitch,
                c.bogie_bounce,
                c.bogie_anti_bounce,
                c.bogie_pitch,
                c.bogie_pitch,
            ];
            closed.sort_by(f64::total_cmp);
            let assembled = assembled_frequencies(&v);
            println!("closed form {closed:?}\nassembled   {assembled:?}");
            for (x, y) in closed.iter().zip(&assembled) {
                assert!((x / y - 1.0).abs() < 1e-10, "{x} vs {y}");
            }
        }
    }

    #[test]
    fn matrices_are_symmetric_and_balance_rigid_motion() {
        let m = manchester().matrices();
        for i in 0..DOFS {
            for j in 0..DOFS {
                assert_eq!(m.stiffness[(i, j)], m.stiffness[(j, i)]);
                assert_eq!(m.damping[(i, j)], m.damping[(j, i)]);
            }
        }
        // A rigid vertical translation (every z = 1, every θ = 0) stretches no spring, and a
        // rigid rotation of the whole vehicle by θ (z = x θ, every pitch = θ) neither.
        let a = 0.5 * manchester().bogie_spacing;
        let b = 0.5 * manchester().wheelbase;
        let translation = [1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        // Nose-down pitch moves the front (x = +a) down: z = x θ with θ = 1.
        let rotation = [0.0, 1.0, a, 1.0, -a, 1.0, a + b, a - b, -a + b, -a - b];
        for q in [translation, rotation] {
            for i in 0..DOFS {
                let f: f64 = (0..DOFS).map(|j| m.stiffness[(i, j)] * q[j]).sum();
                assert!(
                    f.abs() < 1e-9 * m.stiffness[(i, i)].abs().max(1.0),
                    "row {i}: {f}"
                );
            }
        }
    }
}
