//! The articulated train's mass, stiffness and damping matrices (2-D vertical plane): n car
//! bodies on n + 1 bogies, each inner bogie shared by two neighbouring bodies (Jacobs bogies,
//! as in the TGV/Eurostar family and the HSLM-A trains of EN 1991-2 Annex E; references.md
//! §D2.2).
//!
//! DOFs, z positive downwards, pitch θ positive nose-down (as in [`super::bogie_vehicle`]):
//! bodies `[z_c,j, θ_c,j]` (j = 0 … n−1, leading body first), bogies `[z_i, θ_i]`
//! (i = 0 … n), then the wheelsets, two per bogie in running order. Bogie i's centre is
//! i·s + b behind the leading axle (s = `bogie_spacing`, b = `wheelbase`/2); body j rests
//! with its front end (+a, a = s/2 from its centre) on bogie j and its rear end (−a) on
//! bogie j+1. Springs (and dampers alike) with elongation e = gᵀq add k g gᵀ to K:
//!
//! * secondary, body j front: e = z_c,j + a θ_c,j − z_j; rear: e = z_c,j − a θ_c,j − z_{j+1}
//!   (stiffness k₂ per body end);
//! * primary, wheelset of bogie i at ±b: e = z_i ± b θ_i − z_w (stiffness k₁ per wheelset).
//!
//! With one body this is exactly the bogie vehicle (same DOF order, same matrices; tested),
//! whose frequencies have a closed form; the chain's statics (inner bogies carry two body
//! halves) are those of [`super::Train::axles`].

use faer::Mat;

use super::Articulated;
use super::multibody::{SpringAssembler, VehicleMatrices};

impl Articulated {
    /// Number of own (body and bogie) DOFs: 2n + 2(n+1).
    pub fn own_dofs(&self) -> usize {
        2 * self.bodies + 2 * (self.bodies + 1)
    }

    /// Number of wheelsets: 2(n+1).
    pub fn wheelsets(&self) -> usize {
        2 * (self.bodies + 1)
    }

    /// The contact-free matrices (module documentation).
    pub fn matrices(&self) -> VehicleMatrices {
        let n = self.bodies;
        let own = self.own_dofs();
        let dofs = own + self.wheelsets();
        let a = 0.5 * self.bogie_spacing;
        let b = 0.5 * self.wheelbase;
        let bogie = |i: usize| (2 * n + 2 * i, 2 * n + 2 * i + 1);
        let mut springs = SpringAssembler::new(dofs);
        for j in 0..n {
            let (z, theta) = (2 * j, 2 * j + 1);
            for (end, sign) in [(j, 1.0), (j + 1, -1.0)] {
                springs.add(
                    &[(z, 1.0), (theta, sign * a), (bogie(end).0, -1.0)],
                    self.secondary_stiffness,
                    self.secondary_damping,
                );
            }
        }
        for i in 0..=n {
            let (z, theta) = bogie(i);
            for (w, sign) in [(0usize, 1.0), (1, -1.0)] {
                springs.add(
                    &[(z, 1.0), (theta, sign * b), (own + 2 * i + w, -1.0)],
                    self.primary_stiffness,
                    self.primary_damping,
                );
            }
        }
        let mut mass = Vec::with_capacity(dofs);
        for _ in 0..n {
            mass.extend([self.body_mass, self.body_pitch_inertia]);
        }
        for _ in 0..=n {
            mass.extend([self.bogie_mass, self.bogie_pitch_inertia]);
        }
        mass.extend(std::iter::repeat_n(self.wheelset_mass, self.wheelsets()));
        let (stiffness, damping) = springs.finish();
        VehicleMatrices {
            mass,
            stiffness,
            damping,
            own_dofs: own,
        }
    }

    /// The natural frequencies \[Hz\] of the body-and-bogie DOFs on a rigid track (wheelsets
    /// fixed), ascending: the eigenvalues of M^{-1/2} K M^{-1/2} over the own DOFs (faer's
    /// symmetric eigen-solver).
    pub fn rigid_track_frequencies(&self) -> Vec<f64> {
        let m = self.matrices();
        let n = m.own_dofs;
        let scaled = Mat::<f64>::from_fn(n, n, |i, j| {
            m.stiffness[(i, j)] / (m.mass[i] * m.mass[j]).sqrt()
        });
        let mut f: Vec<f64> = scaled
            .self_adjoint_eigenvalues(faer::Side::Lower)
            .map(|values| {
                values
                    .iter()
                    .map(|w2| w2.max(0.0).sqrt() / std::f64::consts::TAU)
                    .collect()
            })
            .unwrap_or_default();
        f.sort_by(f64::total_cmp);
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::train::BogieVehicle;
    use crate::train::fixtures::chain;

    /// One body on two bogies is the bogie vehicle: the same matrices entry by entry, hence
    /// the closed-form frequencies of `bogie_vehicle` (body bounce, pitch, bogie modes).
    #[test]
    fn one_body_is_the_bogie_vehicle() {
        let a = chain(1);
        let b = BogieVehicle {
            length: a.length,
            body_mass: a.body_mass,
            body_pitch_inertia: a.body_pitch_inertia,
            bogie_spacing: a.bogie_spacing,
            bogie_mass: a.bogie_mass,
            bogie_pitch_inertia: a.bogie_pitch_inertia,
            wheelbase: a.wheelbase,
            wheelset_mass: a.wheelset_mass,
            primary_stiffness: a.primary_stiffness,
            primary_damping: a.primary_damping,
            secondary_stiffness: a.secondary_stiffness,
            secondary_damping: a.secondary_damping,
        };
        let (ma, mb) = (a.matrices(), b.matrices());
        assert_eq!(ma.mass, mb.mass);
        assert_eq!(ma.own_dofs, mb.own_dofs);
        for i in 0..10 {
            for j in 0..10 {
                assert_eq!(ma.stiffness[(i, j)], mb.stiffness[(i, j)], "K ({i}, {j})");
                assert_eq!(ma.damping[(i, j)], mb.damping[(i, j)], "C ({i}, {j})");
            }
        }
        let closed = b.rigid_track_frequencies();
        let f = a.rigid_track_frequencies();
        // The closed form (two 2×2 problems and the bogie pitch) against the eigen-solver:
        // round-off of a 6×6 symmetric eigenproblem, 1e-9 relative.
        for expected in [
            closed.body_bounce,
            closed.body_pitch,
            closed.bogie_bounce,
            closed.bogie_anti_bounce,
            closed.bogie_pitch,
        ] {
            assert!(
                f.iter().any(|x| (x / expected - 1.0).abs() < 1e-9),
                "{expected} not in {f:?}"
            );
        }
    }

    /// Rigid-track statics of a 3-body chain: K_ff q_f = g_f with the wheels fixed gives
    /// primary forces equal to the static axle loads of `Train::axles` minus the wheelsets'
    /// own weight (end bogies half a body, inner bogies a whole one), to 1e-9 relative.
    #[test]
    fn chain_statics_match_the_axle_loads() {
        let a = chain(3);
        let m = a.matrices();
        let f = m.own_dofs;
        let g = 9.81;
        // Gravity on the z DOFs (even own indices).
        let rhs = Mat::<f64>::from_fn(f, 1, |i, _| if i % 2 == 0 { m.mass[i] * g } else { 0.0 });
        let kff = Mat::<f64>::from_fn(f, f, |i, j| m.stiffness[(i, j)]);
        let q = {
            use faer::linalg::solvers::Solve;
            kff.partial_piv_lu().solve(&rhs)
        };
        let train = crate::train::Train {
            name: "chain".into(),
            vehicles: vec![crate::train::VehicleSpec::Articulated(a)],
        };
        let axles = train.axles(g).unwrap();
        for (w, axle) in axles.iter().enumerate() {
            // Primary force on wheel w = −(K_wf q_f) (the wheel at rest at 0).
            let force: f64 = -(0..f)
                .map(|i| m.stiffness[(f + w, i)] * q[(i, 0)])
                .sum::<f64>();
            let expected = axle.load - a.wheelset_mass * g;
            assert!(
                (force / expected - 1.0).abs() < 1e-9,
                "wheel {w}: {force} vs {expected}"
            );
        }
    }
}
