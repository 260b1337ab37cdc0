//! The articulated train's mass, stiffness and damping matrices (2-D vertical plane): n car
//! bodies on n + 1 bogies, each inner bogie shared by two neighbouring bodies (Jacobs bogies,
//! as in the TGV/Eurostar family and the HSLM-A trains of EN 1991-2 Annex E; references.md
//! §D2.2), its axle positions and its statics.
//!
//! DOFs, z positive downwards, pitch θ positive nose-down (as in [`super::bogie_vehicle`]):
//! bodies `[z_c,j, θ_c,j]` (j = 0 … n−1, leading body first), bogies `[z_i, θ_i]`
//! (i = 0 … n), then the wheelsets, two per bogie in running order. Body j rests with its
//! front end on bogie j, f_j ahead of its centre of gravity, and with its rear end on bogie
//! j+1, r_j behind it (f_j = r_j = s/2 for the uniform rake of a train table; the Eurostar's
//! coaches have f_j ≠ r_j). Bogie i's wheelsets are at ±b_i (b_i = its wheelbase/2) from its
//! centre. Springs (and dampers alike) with elongation e = gᵀq add k g gᵀ to K:
//!
//! * secondary, body j front: e = z_c,j + f_j θ_c,j − z_j; rear: e = z_c,j − r_j θ_c,j −
//!   z_{j+1} (body j's stiffness k₂,j at each end);
//! * primary, wheelset of bogie i at ±b_i: e = z_i ± b_i θ_i − z_w (bogie i's k₁,i).
//!
//! Statics (rigid track): each body is statically determinate on its two supports, so bogie i
//! carries m_{i−1} g f_{i−1}/(f_{i−1} + r_{i−1}) from the body ahead (lever rule) and
//! m_i g r_i/(f_i + r_i) from the body behind, plus its own weight, shared equally by its two
//! wheelsets. A unit test solves K_ff q_f = g_f and finds these loads in the primary springs.
//!
//! With one symmetric body this is exactly the bogie vehicle (same DOF order, same matrices;
//! tested), whose frequencies have a closed form; the uniform rake of a train table
//! ([`super::UniformArticulated`]) is assembled exactly as before the bodies could differ
//! (a test keeps that assembly and compares bit for bit).

use faer::Mat;

use super::Articulated;
use super::multibody::{SpringAssembler, VehicleMatrices};

impl Articulated {
    /// Number of car bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Number of own (body and bogie) DOFs: 2n + 2(n+1).
    pub fn own_dofs(&self) -> usize {
        2 * self.bodies.len() + 2 * self.bogies.len()
    }

    /// Number of wheelsets: 2(n+1).
    pub fn wheelsets(&self) -> usize {
        2 * self.bogies.len()
    }

    /// Total mass \[kg\]: bodies, bogies and wheelsets.
    pub fn mass(&self) -> f64 {
        let bodies: f64 = self.bodies.iter().map(|b| b.mass).sum();
        let bogies: f64 = self
            .bogies
            .iter()
            .map(|b| b.mass + 2.0 * b.wheelset_mass)
            .sum();
        bodies + bogies
    }

    /// Offset of each bogie's leading axle behind the vehicle's leading axle \[m\]: bogie
    /// i+1's centre lies f_i + r_i behind bogie i's.
    pub fn bogie_leading_axles(&self) -> Vec<f64> {
        let mut x = Vec::with_capacity(self.bogies.len());
        let mut first = 0.0;
        for (i, bogie) in self.bogies.iter().enumerate() {
            x.push(first);
            if let (Some(body), Some(next)) = (self.bodies.get(i), self.bogies.get(i + 1)) {
                first += (body.front + body.rear) + 0.5 * (bogie.wheelbase - next.wheelbase);
            }
        }
        x
    }

    /// Offset behind the vehicle's leading axle of its last axle \[m\].
    pub fn last_axle(&self) -> f64 {
        match (self.bogie_leading_axles().last(), self.bogies.last()) {
            (Some(x), Some(b)) => x + b.wheelbase,
            _ => 0.0,
        }
    }

    /// The suspended mass on each wheelset of bogie i \[kg\]: half of the body ends it
    /// carries (lever rule, module documentation) and of the bogie itself; the wheelset's own
    /// mass comes on top at the rail.
    pub fn suspended_wheelset_masses(&self) -> Vec<f64> {
        (0..self.bogies.len())
            .map(|i| {
                let mut ends = 0.0;
                if let Some(ahead) = i.checked_sub(1).and_then(|j| self.bodies.get(j)) {
                    ends += ahead.mass * (ahead.front / (ahead.front + ahead.rear));
                }
                if let Some(behind) = self.bodies.get(i) {
                    ends += behind.mass * (behind.rear / (behind.front + behind.rear));
                }
                0.5 * (ends + self.bogies[i].mass)
            })
            .collect()
    }

    /// (offset behind the leading axle \[m\], static axle load \[N\]) of each axle in
    /// running order at gravity `g`: each wheelset's suspended mass plus its own.
    pub fn axles(&self, g: f64) -> Vec<(f64, f64)> {
        self.bogie_leading_axles()
            .into_iter()
            .zip(&self.bogies)
            .zip(self.suspended_wheelset_masses())
            .flat_map(|((x, bogie), suspended)| {
                let load = (suspended + bogie.wheelset_mass) * g;
                [(x, load), (x + bogie.wheelbase, load)]
            })
            .collect()
    }

    /// The contact-free matrices (module documentation).
    pub fn matrices(&self) -> VehicleMatrices {
        let n = self.bodies.len();
        let own = self.own_dofs();
        let dofs = own + self.wheelsets();
        let bogie = |i: usize| (2 * n + 2 * i, 2 * n + 2 * i + 1);
        let mut springs = SpringAssembler::new(dofs);
        for (j, body) in self.bodies.iter().enumerate() {
            let (z, theta) = (2 * j, 2 * j + 1);
            for (end, arm) in [(j, body.front), (j + 1, -body.rear)] {
                springs.add(
                    &[(z, 1.0), (theta, arm), (bogie(end).0, -1.0)],
                    body.secondary_stiffness,
                    body.secondary_damping,
                );
            }
        }
        for (i, b) in self.bogies.iter().enumerate() {
            let (z, theta) = bogie(i);
            let half = 0.5 * b.wheelbase;
            for (w, sign) in [(0usize, 1.0), (1, -1.0)] {
                springs.add(
                    &[(z, 1.0), (theta, sign * half), (own + 2 * i + w, -1.0)],
                    b.primary_stiffness,
                    b.primary_damping,
                );
            }
        }
        let mut mass = Vec::with_capacity(dofs);
        for body in &self.bodies {
            mass.extend([body.mass, body.pitch_inertia]);
        }
        for b in &self.bogies {
            mass.extend([b.mass, b.pitch_inertia]);
        }
        for b in &self.bogies {
            mass.extend([b.wheelset_mass; 2]);
        }
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
    use crate::train::fixtures::{chain, uneven_chain};
    use crate::train::{BogieVehicle, Train, VehicleSpec};

    /// One body on two bogies is the bogie vehicle: the same matrices entry by entry, hence
    /// the closed-form frequencies of `bogie_vehicle` (body bounce, pitch, bogie modes).
    #[test]
    fn one_body_is_the_bogie_vehicle() {
        let u = chain(1);
        let a = u.build();
        let b = BogieVehicle {
            length: u.length,
            body_mass: u.body_mass,
            body_pitch_inertia: u.body_pitch_inertia,
            bogie_spacing: u.bogie_spacing,
            bogie_mass: u.bogie_mass,
            bogie_pitch_inertia: u.bogie_pitch_inertia,
            wheelbase: u.wheelbase,
            wheelset_mass: u.wheelset_mass,
            primary_stiffness: u.primary_stiffness,
            primary_damping: u.primary_damping,
            secondary_stiffness: u.secondary_stiffness,
            secondary_damping: u.secondary_damping,
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

    /// The uniform rake of a train table, assembled by the general code, against the uniform
    /// assembly the articulated type had before its bodies could differ (kept here: symmetric
    /// bodies, a = s/2, every bogie alike): K, C and M equal bit for bit, the axle loads bit
    /// for bit ((½ (k m_body + m_bogie) + m_ws) g with k = ½ at the end bogies and 1 inside),
    /// and the axle offsets (i s and i s + wheelbase) to round-off of the running sum.
    #[test]
    fn the_uniform_rake_is_assembled_as_before() {
        for n in [1, 3, 7] {
            let u = chain(n);
            let m = u.build().matrices();
            let own = 2 * n + 2 * (n + 1);
            let dofs = own + 2 * (n + 1);
            let (a, b) = (0.5 * u.bogie_spacing, 0.5 * u.wheelbase);
            let bogie = |i: usize| 2 * n + 2 * i;
            let mut reference = SpringAssembler::new(dofs);
            for j in 0..n {
                for (end, sign) in [(j, 1.0), (j + 1, -1.0)] {
                    reference.add(
                        &[(2 * j, 1.0), (2 * j + 1, sign * a), (bogie(end), -1.0)],
                        u.secondary_stiffness,
                        u.secondary_damping,
                    );
                }
            }
            for i in 0..=n {
                for (w, sign) in [(0usize, 1.0), (1, -1.0)] {
                    reference.add(
                        &[
                            (bogie(i), 1.0),
                            (bogie(i) + 1, sign * b),
                            (own + 2 * i + w, -1.0),
                        ],
                        u.primary_stiffness,
                        u.primary_damping,
                    );
                }
            }
            let (k, c) = reference.finish();
            for i in 0..dofs {
                for j in 0..dofs {
                    assert_eq!(m.stiffness[(i, j)].to_bits(), k[(i, j)].to_bits());
                    assert_eq!(m.damping[(i, j)].to_bits(), c[(i, j)].to_bits());
                }
            }
            let mut mass = Vec::new();
            for _ in 0..n {
                mass.extend([u.body_mass, u.body_pitch_inertia]);
            }
            for _ in 0..=n {
                mass.extend([u.bogie_mass, u.bogie_pitch_inertia]);
            }
            mass.extend(std::iter::repeat_n(u.wheelset_mass, 2 * (n + 1)));
            assert_eq!(m.mass, mass);
            let g = 9.81;
            for (axle, (x, load)) in u.build().axles(g).into_iter().enumerate() {
                let i = axle / 2;
                let bodies = if i == 0 || i == n { 0.5 } else { 1.0 };
                let old = (0.5 * (bodies * u.body_mass + u.bogie_mass) + u.wheelset_mass) * g;
                assert_eq!(load.to_bits(), old.to_bits(), "axle {axle}");
                let old_x = i as f64 * u.bogie_spacing + (axle % 2) as f64 * u.wheelbase;
                assert!(
                    (x - old_x).abs() <= 1e-13 * old_x.max(1.0),
                    "axle {axle}: {x}"
                );
            }
        }
    }

    /// Rigid-track statics: K_ff q_f = g_f with the wheels fixed gives primary forces equal to
    /// the static axle loads of `Train::axles` minus the wheelsets' own weight, to 1e-9
    /// relative. The uniform 3-body chain (end bogies half a body, inner bogies a whole one)
    /// and an uneven chain whose bodies have their centre of gravity off-centre and differ
    /// from each other, as do its bogies (lever rule).
    #[test]
    fn chain_statics_match_the_axle_loads() {
        for a in [chain(3).build(), uneven_chain()] {
            let m = a.matrices();
            let f = m.own_dofs;
            let g = 9.81;
            // Gravity on the z DOFs (even own indices).
            let rhs =
                Mat::<f64>::from_fn(f, 1, |i, _| if i % 2 == 0 { m.mass[i] * g } else { 0.0 });
            let kff = Mat::<f64>::from_fn(f, f, |i, j| m.stiffness[(i, j)]);
            let q = {
                use faer::linalg::solvers::Solve;
                kff.partial_piv_lu().solve(&rhs)
            };
            let train = Train {
                name: "chain".into(),
                vehicles: vec![VehicleSpec::Articulated(a.clone())],
            };
            let axles = train.axles(g).unwrap();
            for (w, axle) in axles.iter().enumerate() {
                // Primary force on wheel w = −(K_wf q_f) (the wheel at rest at 0).
                let force: f64 = -(0..f)
                    .map(|i| m.stiffness[(f + w, i)] * q[(i, 0)])
                    .sum::<f64>();
                let expected = axle.load - a.bogies[w / 2].wheelset_mass * g;
                assert!(
                    (force / expected - 1.0).abs() < 1e-9,
                    "wheel {w}: {force} vs {expected}"
                );
            }
            let total: f64 = axles.iter().map(|x| x.load).sum();
            assert!((total / (a.mass() * g) - 1.0).abs() < 1e-12);
        }
    }

    /// K of the uneven chain has no force under a rigid vertical translation or a rigid
    /// rotation of the whole vehicle (z = X θ, X forward from any origin, every pitch θ):
    /// the support distances, bogie positions and wheelbases fit together.
    #[test]
    fn the_uneven_chain_balances_rigid_motion() {
        let a = uneven_chain();
        let m = a.matrices();
        let (n, own, dofs) = (a.bodies.len(), m.own_dofs, m.dofs());
        let leading = a.bogie_leading_axles();
        // Bogie centres, forward positive (X = −offset behind the leading axle).
        let centre: Vec<f64> = leading
            .iter()
            .zip(&a.bogies)
            .map(|(x, b)| -(x + 0.5 * b.wheelbase))
            .collect();
        let mut rotation = vec![0.0; dofs];
        for (j, body) in a.bodies.iter().enumerate() {
            rotation[2 * j] = centre[j] - body.front;
            rotation[2 * j + 1] = 1.0;
        }
        for (i, b) in a.bogies.iter().enumerate() {
            rotation[2 * n + 2 * i] = centre[i];
            rotation[2 * n + 2 * i + 1] = 1.0;
            rotation[own + 2 * i] = centre[i] + 0.5 * b.wheelbase;
            rotation[own + 2 * i + 1] = centre[i] - 0.5 * b.wheelbase;
        }
        let translation: Vec<f64> = (0..dofs)
            .map(|i| if i < own && i % 2 == 1 { 0.0 } else { 1.0 })
            .collect();
        for q in [translation, rotation] {
            // Round-off of sums of terms up to K_ii max|q|.
            let scale = q.iter().fold(0.0f64, |s, x| s.max(x.abs()));
            for i in 0..dofs {
                let f: f64 = (0..dofs).map(|j| m.stiffness[(i, j)] * q[j]).sum();
                assert!(
                    f.abs() < 1e-12 * m.stiffness[(i, i)] * scale,
                    "row {i}: {f}"
                );
            }
        }
    }
}
