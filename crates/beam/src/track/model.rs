//! The track model: an Euler–Bernoulli rail in Hermite finite elements over approach, bridge and
//! exit, on discrete support chains every sleeper spacing, on rigid ground or on the modes of a
//! bridge beam (references.md §D5.2). Assembly of the sparse symmetric M, C, K.
//!
//! Sign convention: displacements positive in the direction of the wheel load (downward); spring
//! forces positive in compression.

use crate::damping::ModalDamping;
use crate::error::{BeamError, finite, non_negative, positive};
use crate::modal::{Derivative, ModalBasis};

use super::element::RailElement;
use super::rail::RailSection;
use super::sparse::{SparseCholesky, SymmetricEntries};
use super::support::SupportStack;

/// Largest number of rail nodes of a track model.
pub const MAX_TRACK_NODES: usize = 500_000;

/// Where along the track a sleeper stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Zone {
    /// Approach embankment (before the bridge).
    Approach,
    /// On the bridge.
    Bridge,
    /// Exit embankment (after the bridge).
    Exit,
}

/// Lengths along the track and the mesh: the rail runs from x = 0 (start of the approach) over
/// the bridge, which starts at x = `approach`, to the end of the exit, rounded up to whole
/// sleeper bays; sleeper j stands at x = (j + ½) d.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackLayout {
    approach: f64,
    bridge: f64,
    exit: f64,
    sleeper_spacing: f64,
    elements_per_bay: usize,
}

impl TrackLayout {
    /// Approach, bridge and exit lengths \[m\] (≥ 0, total > 0) and sleeper spacing d \[m\]
    /// (0 < d ≤ 5 m); 4 rail elements per bay.
    pub fn new(
        approach: f64,
        bridge: f64,
        exit: f64,
        sleeper_spacing: f64,
    ) -> Result<Self, BeamError> {
        non_negative("approach_length", approach)?;
        non_negative("bridge_length", bridge)?;
        non_negative("exit_length", exit)?;
        positive("sleeper_spacing", sleeper_spacing)?;
        if sleeper_spacing > 5.0 {
            return Err(BeamError::InvalidParameter {
                name: "sleeper_spacing",
                value: sleeper_spacing,
                reason: "must be at most 5 m",
            });
        }
        let layout = Self {
            approach,
            bridge,
            exit,
            sleeper_spacing,
            elements_per_bay: 4,
        };
        if layout.n_bays() < 2 {
            return Err(BeamError::InvalidParameter {
                name: "track_length",
                value: approach + bridge + exit,
                reason: "the track must span at least two sleeper spacings",
            });
        }
        layout.check_size()?;
        Ok(layout)
    }

    /// The same layout with `n` rail elements per sleeper bay (even, 2 ≤ n ≤ 32).
    pub fn with_elements_per_bay(mut self, n: usize) -> Result<Self, BeamError> {
        if !(2..=32).contains(&n) || !n.is_multiple_of(2) {
            return Err(BeamError::InvalidCount {
                name: "elements_per_bay",
                value: n,
                reason: "must be even, between 2 and 32",
            });
        }
        self.elements_per_bay = n;
        self.check_size()?;
        Ok(self)
    }

    fn check_size(&self) -> Result<(), BeamError> {
        let nodes = self.n_bays().saturating_mul(self.elements_per_bay) + 1;
        if nodes > MAX_TRACK_NODES {
            return Err(BeamError::InvalidCount {
                name: "track rail nodes",
                value: nodes,
                reason: "at most 500000 rail nodes (track length / sleeper spacing × elements per bay)",
            });
        }
        Ok(())
    }

    /// Number of sleeper bays (and sleepers).
    pub fn n_bays(&self) -> usize {
        let bays = (self.approach + self.bridge + self.exit) / self.sleeper_spacing;
        (bays - 1e-9).ceil().max(0.0) as usize
    }

    /// Rail length (whole bays) \[m\].
    pub fn rail_length(&self) -> f64 {
        self.n_bays() as f64 * self.sleeper_spacing
    }

    /// Approach length \[m\] (the bridge starts here).
    pub fn approach(&self) -> f64 {
        self.approach
    }

    /// Bridge length \[m\].
    pub fn bridge(&self) -> f64 {
        self.bridge
    }

    /// Exit length \[m\].
    pub fn exit(&self) -> f64 {
        self.exit
    }

    /// Sleeper spacing \[m\].
    pub fn sleeper_spacing(&self) -> f64 {
        self.sleeper_spacing
    }

    /// Rail elements per bay.
    pub fn elements_per_bay(&self) -> usize {
        self.elements_per_bay
    }

    /// Zone of a position x along the track.
    pub fn zone(&self, x: f64) -> Zone {
        if x < self.approach {
            Zone::Approach
        } else if self.bridge > 0.0 && x <= self.approach + self.bridge {
            Zone::Bridge
        } else {
            Zone::Exit
        }
    }
}

/// The support chains of the three zones.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackSupports {
    /// On the approach embankment (to rigid ground).
    pub approach: SupportStack,
    /// On the bridge (to the bridge beam, or to rigid ground if no bridge is attached).
    pub bridge: SupportStack,
    /// On the exit embankment (to rigid ground).
    pub exit: SupportStack,
}

impl TrackSupports {
    /// The same chain in every zone.
    pub fn uniform(stack: SupportStack) -> Self {
        Self {
            approach: stack.clone(),
            bridge: stack.clone(),
            exit: stack,
        }
    }

    fn of(&self, zone: Zone) -> &SupportStack {
        match zone {
            Zone::Approach => &self.approach,
            Zone::Bridge => &self.bridge,
            Zone::Exit => &self.exit,
        }
    }
}

/// What the last spring of a chain stands on.
#[derive(Debug, Clone, PartialEq)]
pub enum Foundation {
    /// Rigid ground.
    Ground,
    /// The bridge: the mode shapes φ_j at the sleeper (the foundation displacement is Σ φ_j q_j).
    Bridge(Vec<f64>),
}

/// One sleeper (support point) of the model.
#[derive(Debug, Clone, PartialEq)]
pub struct Sleeper {
    /// Position along the track \[m\].
    pub x: f64,
    /// Its zone.
    pub zone: Zone,
    /// Index of the rail node above it.
    pub node: usize,
    /// DOF indices of the chain's masses, from the rail down.
    pub body_dofs: Vec<usize>,
    /// The chain.
    pub stack: SupportStack,
    /// What the chain stands on.
    pub foundation: Foundation,
}

/// The rail DOFs of the element containing a point and their weights (the displacement shape
/// functions of the rail element: Hermite, or the Timoshenko IIE's N_w): the rail
/// displacement there is Σ wᵢ u\[dofᵢ\], and a point force F there has the consistent load
/// vector F wᵢ on the same DOFs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailPoint {
    /// DOF indices (w₁, θ₁, w₂, θ₂).
    pub dofs: [usize; 4],
    /// Displacement shape-function values at the point.
    pub weights: [f64; 4],
}

impl RailPoint {
    /// Σ wᵢ u\[dofᵢ\].
    pub fn value(&self, u: &[f64]) -> f64 {
        (0..4).map(|a| self.weights[a] * u[self.dofs[a]]).sum()
    }
}

/// The assembled track (and bridge modes, if attached): DOF layout and sparse M, C, K.
#[derive(Debug, Clone)]
pub struct Track {
    rail: RailSection,
    layout: TrackLayout,
    element_length: f64,
    element: RailElement,
    node_dof: Vec<usize>,
    sleepers: Vec<Sleeper>,
    n_track: usize,
    n_modes: usize,
    mass: SymmetricEntries,
    damping: SymmetricEntries,
    stiffness: SymmetricEntries,
}

impl Track {
    /// A track on rigid ground everywhere (the bridge zone too).
    pub fn on_ground(
        rail: RailSection,
        layout: TrackLayout,
        supports: &TrackSupports,
    ) -> Result<Self, BeamError> {
        Self::build(rail, layout, supports, None)
    }

    /// A track whose bridge-zone chains stand on a modal bridge beam of length
    /// `layout.bridge()`, with modal damping `damping`. The bridge modes should carry the
    /// bridge's own mass only (the rail and the chain masses are in the track).
    pub fn on_bridge(
        rail: RailSection,
        layout: TrackLayout,
        supports: &TrackSupports,
        modes: &dyn ModalBasis,
        damping: &ModalDamping,
    ) -> Result<Self, BeamError> {
        let lb = modes.length();
        if layout.bridge() <= 0.0 || (lb - layout.bridge()).abs() > 1e-9 * lb.max(1.0) {
            return Err(BeamError::InvalidParameter {
                name: "bridge_length",
                value: layout.bridge(),
                reason: "must equal the length of the bridge modes",
            });
        }
        Self::build(rail, layout, supports, Some((modes, damping)))
    }

    fn build(
        rail: RailSection,
        layout: TrackLayout,
        supports: &TrackSupports,
        bridge: Option<(&dyn ModalBasis, &ModalDamping)>,
    ) -> Result<Self, BeamError> {
        let d = layout.sleeper_spacing;
        let ne = layout.elements_per_bay;
        let n_bays = layout.n_bays();
        let n_el = n_bays * ne;
        let h = d / ne as f64;
        // DOF numbering node by node: w, θ, then the chain masses of a sleeper at that node.
        let mut node_dof = Vec::with_capacity(n_el + 1);
        let mut sleepers = Vec::with_capacity(n_bays);
        let mut next = 0usize;
        for k in 0..=n_el {
            node_dof.push(next);
            next += 2;
            if k % ne == ne / 2 {
                let j = k / ne;
                let x = (j as f64 + 0.5) * d;
                let zone = layout.zone(x);
                let stack = supports.of(zone).clone();
                let body_dofs: Vec<usize> = (0..stack.masses().len()).map(|i| next + i).collect();
                next += body_dofs.len();
                sleepers.push(Sleeper {
                    x,
                    zone,
                    node: k,
                    body_dofs,
                    stack,
                    foundation: Foundation::Ground,
                });
            }
        }
        let n_track = next;
        let n_modes = bridge.map_or(0, |(m, _)| m.n_modes());
        let n = n_track + n_modes;
        let mut mass = SymmetricEntries::new(n);
        let mut damping = SymmetricEntries::new(n);
        let mut stiffness = SymmetricEntries::new(n);

        // Rail elements: Hermite (EI/h³, m h/420) or Timoshenko IIE matrices.
        let element = RailElement::new(&rail, h)?;
        let (ke, me) = (element.stiffness(), element.mass());
        for e in 0..n_el {
            let dofs = [
                node_dof[e],
                node_dof[e] + 1,
                node_dof[e + 1],
                node_dof[e + 1] + 1,
            ];
            for a in 0..4 {
                for b in 0..=a {
                    stiffness.add(dofs[a], dofs[b], ke[a][b]);
                    mass.add(dofs[a], dofs[b], me[a][b]);
                }
            }
        }

        // Bridge modes: mass-normalised (modal mass m_j), K = m_j ω_j², C = m_j c_j.
        if let Some((modes, modal_damping)) = bridge {
            let omegas = modes.circular_frequencies();
            let c = modal_damping.velocity_coefficients(omegas)?;
            for j in 0..n_modes {
                let mj = modes.modal_mass(j)?;
                let q = n_track + j;
                mass.add(q, q, mj);
                stiffness.add(q, q, mj * omegas[j] * omegas[j]);
                damping.add(q, q, mj * c[j]);
            }
            let mut phi = vec![0.0; n_modes];
            for s in sleepers.iter_mut().filter(|s| s.zone == Zone::Bridge) {
                let xl = (s.x - layout.approach).clamp(0.0, modes.length());
                modes.eval_all(xl, Derivative::Shape, &mut phi)?;
                s.foundation = Foundation::Bridge(phi.clone());
            }
        }

        // Support chains: each spring couples the generalized coordinates above and below it.
        for s in &sleepers {
            let rail_dof = node_dof[s.node];
            let masses = s.stack.masses();
            for (i, &mi) in masses.iter().enumerate() {
                mass.add(s.body_dofs[i], s.body_dofs[i], mi);
            }
            for (i, spring) in s.stack.springs().iter().enumerate() {
                let mut coords: Vec<(usize, f64)> = Vec::new();
                coords.push((if i == 0 { rail_dof } else { s.body_dofs[i - 1] }, 1.0));
                if i < masses.len() {
                    coords.push((s.body_dofs[i], -1.0));
                } else if let Foundation::Bridge(phi) = &s.foundation {
                    coords.extend(phi.iter().enumerate().map(|(j, &p)| (n_track + j, -p)));
                }
                for (a, &(da, ca)) in coords.iter().enumerate() {
                    for &(db, cb) in &coords[..=a] {
                        stiffness.add(da, db, spring.stiffness * ca * cb);
                        damping.add(da, db, spring.damping * ca * cb);
                    }
                }
            }
        }
        mass.compress();
        damping.compress();
        stiffness.compress();
        Ok(Self {
            rail,
            layout,
            element_length: h,
            element,
            node_dof,
            sleepers,
            n_track,
            n_modes,
            mass,
            damping,
            stiffness,
        })
    }

    /// Total number of DOFs (track, then bridge modes).
    pub fn n_dofs(&self) -> usize {
        self.n_track + self.n_modes
    }

    /// Number of track DOFs (rail and chain masses); the bridge modal DOFs follow them.
    pub fn n_track_dofs(&self) -> usize {
        self.n_track
    }

    /// Number of bridge modes (0 on ground).
    pub fn n_modes(&self) -> usize {
        self.n_modes
    }

    /// DOF index of bridge mode `j`.
    pub fn modal_dof(&self, j: usize) -> usize {
        self.n_track + j
    }

    /// The rail section.
    pub fn rail(&self) -> RailSection {
        self.rail
    }

    /// The rail element (every element of the rail has this length and these matrices).
    pub fn rail_element(&self) -> &RailElement {
        &self.element
    }

    /// The layout.
    pub fn layout(&self) -> &TrackLayout {
        &self.layout
    }

    /// The sleepers, in order along the track.
    pub fn sleepers(&self) -> &[Sleeper] {
        &self.sleepers
    }

    /// Rail nodes' positions \[m\].
    pub fn node_positions(&self) -> Vec<f64> {
        (0..self.node_dof.len())
            .map(|k| k as f64 * self.element_length)
            .collect()
    }

    /// DOF index of the rail displacement at node `k`.
    pub fn rail_dof(&self, node: usize) -> usize {
        self.node_dof[node]
    }

    /// Merged entries (both triangles) of the mass matrix.
    pub fn mass_entries(&self) -> &[(usize, usize, f64)] {
        self.mass.entries()
    }

    /// Merged entries (both triangles) of the damping matrix.
    pub fn damping_entries(&self) -> &[(usize, usize, f64)] {
        self.damping.entries()
    }

    /// Merged entries (both triangles) of the stiffness matrix.
    pub fn stiffness_entries(&self) -> &[(usize, usize, f64)] {
        self.stiffness.entries()
    }

    pub(crate) fn matrices(&self) -> [&SymmetricEntries; 3] {
        [&self.mass, &self.damping, &self.stiffness]
    }

    /// The rail element containing x (0 ≤ x ≤ rail length) and its displacement shape
    /// functions there ([`super::RailElement::displacement_shape`]).
    pub fn rail_point(&self, x: f64) -> Result<RailPoint, BeamError> {
        let length = self.layout.rail_length();
        finite("x", x)?;
        if !(0.0..=length).contains(&x) {
            return Err(BeamError::OutsideSpan {
                name: "x",
                x,
                length,
            });
        }
        let h = self.element_length;
        let n_el = self.node_dof.len() - 1;
        let e = ((x / h).floor() as usize).min(n_el - 1);
        let xi = ((x - e as f64 * h) / h).clamp(0.0, 1.0);
        let weights = self.element.displacement_shape(xi);
        let (a, b) = (self.node_dof[e], self.node_dof[e + 1]);
        Ok(RailPoint {
            dofs: [a, a + 1, b, b + 1],
            weights,
        })
    }

    /// Rail displacement at x for the DOF vector `u` (the element's displacement
    /// interpolation).
    pub fn rail_displacement(&self, x: f64, u: &[f64]) -> Result<f64, BeamError> {
        Ok(self.rail_point(x)?.value(u))
    }

    /// Add the consistent load vector of a point force `force` \[N\] on the rail at x to `load`.
    pub fn add_point_force(&self, x: f64, force: f64, load: &mut [f64]) -> Result<(), BeamError> {
        let p = self.rail_point(x)?;
        for a in 0..4 {
            load[p.dofs[a]] += force * p.weights[a];
        }
        Ok(())
    }

    /// Displacement of the foundation under sleeper `s` (0 on ground, Σ φ_j q_j on the bridge).
    pub fn foundation_displacement(&self, s: usize, u: &[f64]) -> f64 {
        match &self.sleepers[s].foundation {
            Foundation::Ground => 0.0,
            Foundation::Bridge(phi) => phi
                .iter()
                .enumerate()
                .map(|(j, p)| p * u[self.n_track + j])
                .sum(),
        }
    }

    /// Rail displacement above sleeper `s` minus its foundation displacement (on the bridge:
    /// the rail–bridge relative displacement there) \[m\].
    pub fn rail_to_foundation(&self, s: usize, u: &[f64]) -> f64 {
        u[self.node_dof[self.sleepers[s].node]] - self.foundation_displacement(s, u)
    }

    /// Forces in the springs of sleeper `s`'s chain, from the pad down \[N\], compression positive:
    /// k (u_above − u_below) + c (v_above − v_below).
    pub fn chain_forces(&self, s: usize, u: &[f64], v: &[f64]) -> Vec<f64> {
        let sl = &self.sleepers[s];
        let rail_dof = self.node_dof[sl.node];
        let n_body = sl.body_dofs.len();
        let level = |i: usize, x: &[f64]| -> f64 {
            // Displacement of level i: 0 rail, 1..=n bodies, n+1 foundation.
            if i == 0 {
                x[rail_dof]
            } else if i <= n_body {
                x[sl.body_dofs[i - 1]]
            } else {
                match &sl.foundation {
                    Foundation::Ground => 0.0,
                    Foundation::Bridge(phi) => phi
                        .iter()
                        .enumerate()
                        .map(|(j, p)| p * x[self.n_track + j])
                        .sum(),
                }
            }
        };
        sl.stack
            .springs()
            .iter()
            .enumerate()
            .map(|(i, k)| {
                k.stiffness * (level(i, u) - level(i + 1, u))
                    + k.damping * (level(i, v) - level(i + 1, v))
            })
            .collect()
    }

    /// Index of the sleeper nearest to x.
    pub fn sleeper_near(&self, x: f64) -> usize {
        let d = self.layout.sleeper_spacing;
        ((x / d - 0.5).round().max(0.0) as usize).min(self.sleepers.len() - 1)
    }

    /// Static displacement K u = f for the load vector `load` (length [`Self::n_dofs`]).
    pub fn static_solution(&self, load: &[f64]) -> Result<Vec<f64>, BeamError> {
        crate::modal::check_len("load", load.len(), self.n_dofs())?;
        let mut chol = SparseCholesky::factorise(
            self.n_dofs(),
            &[(1.0, &self.stiffness)],
            "track stiffness matrix",
        )?;
        let mut u = load.to_vec();
        chol.solve_in_place(&mut u);
        Ok(u)
    }

    /// The step matrix c_M M + c_C C + c_K K factorised once (sparse Cholesky): every implicit
    /// scheme of the `integrate` crate has this form (references.md §D3.5).
    pub fn factorise_step_matrix(
        &self,
        c_m: f64,
        c_c: f64,
        c_k: f64,
    ) -> Result<SparseCholesky, BeamError> {
        SparseCholesky::factorise(
            self.n_dofs(),
            &[
                (c_m, &self.mass),
                (c_c, &self.damping),
                (c_k, &self.stiffness),
            ],
            "track step matrix",
        )
    }

    /// y += s (M x), (C x) or (K x) for `which` = 0, 1, 2.
    #[cfg(test)]
    pub(crate) fn mul_add(&self, which: usize, s: f64, x: &[f64], y: &mut [f64]) {
        self.matrices()[which].mul_add(s, x, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::SpringDamper;

    fn simple() -> Track {
        let stack = SupportStack::ballasted(
            SpringDamper::new(1e8, 1e4).unwrap(),
            100.0,
            SpringDamper::new(5e7, 1e4).unwrap(),
        )
        .unwrap();
        let layout = TrackLayout::new(3.0, 0.0, 3.0, 0.6).unwrap();
        Track::on_ground(RailSection::e60(), layout, &TrackSupports::uniform(stack)).unwrap()
    }

    /// Mass conservation: uᵀ M u for a rigid unit translation of everything is the rail mass plus
    /// the chain masses (exact up to rounding); K annihilates a rigid rail translation except
    /// through the pads.
    #[test]
    fn total_mass_and_layout() {
        let t = simple();
        assert_eq!(t.sleepers().len(), 10);
        assert!((t.sleepers()[0].x - 0.3).abs() < 1e-12);
        let n = t.n_dofs();
        // A unit translation of the rail only (w = 1, θ = 0; chain masses at rest).
        let mut u = vec![0.0; n];
        for k in 0..t.node_positions().len() {
            u[t.rail_dof(k)] = 1.0;
        }
        let mut mu = vec![0.0; n];
        t.mul_add(0, 1.0, &u, &mut mu);
        let rail_mass: f64 = u.iter().zip(&mu).map(|(a, b)| a * b).sum();
        assert!((rail_mass - 60.21 * 6.0).abs() < 1e-9, "{rail_mass}");
        // K u = pad forces only: Σ = 10 pads × 1e8.
        let mut ku = vec![0.0; n];
        t.mul_add(2, 1.0, &u, &mut ku);
        let s: f64 = u.iter().zip(&ku).map(|(a, b)| a * b).sum();
        assert!((s - 10.0 * 1e8).abs() < 1e-3, "{s}");
        assert!(t.rail_point(6.1).is_err());
        assert!(TrackLayout::new(0.3, 0.0, 0.0, 0.6).is_err());
        assert!(
            TrackLayout::new(3.0, 0.0, 3.0, 0.6)
                .unwrap()
                .with_elements_per_bay(3)
                .is_err()
        );
    }
}
