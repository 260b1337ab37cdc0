//! The boundary-element contact on the rail (`contact.model = "bem"` with `[track]`;
//! docs/track.md, references.md §D5.4).
//!
//! # Model
//! Each wheel's law ([`halfspace::law::BemLaw`]) solves the pressure on its grid at the
//! approach `δ_k = z_w − u_rail(x_k) + r(x_k)` with the column corrections of the gap
//!
//! ```text
//! c(ξ_i) = [u_rail(x_k + ξ_i) − u_rail(x_k)] − [r(x_k + ξ_i) − r(x_k)],
//! ```
//!
//! the rail's deflection shape under the patch (the Hermite interpolation `N(x)ᵀu` of the rail
//! element(s) under each grid column, as the beam's mode shapes give it without the track)
//! and the irregularity relative to the wheel point. The column forces F_i load the rail where
//! they act, `Σ_i F_i N(x_k + ξ_i)`, so the load direction of wheel k is
//! `v̂_k = e_k − Σ_i ω_i N(x_k + ξ_i)` with the shares `ω_i = F_i / F` of its last evaluation.
//!
//! # The contact equations of a step
//! Every vector above touches a few DOFs only: the wheel's and the rail DOFs of the elements
//! under the patch (the contact DOFs D). With `u_d = L⁻¹P e_d` (one sparse forward sweep per
//! contact DOF), `h_d = u_dᵀz` and `G_de = s u_dᵀu_e`, the state on D of the step is affine in
//! the nodal contact forces `f = Σ_k F_k v̂_k` (Woodbury's formula on D, references.md §D4.2),
//!
//! ```text
//! x_D = h − G f,
//! ```
//!
//! from which the approaches and the column gaps follow exactly. The forces solve
//! `F_k = F_law,k(δ_k(F), c_k(F))` by Newton's method with the capacitance Jacobian
//! `I + diag(k_c) S`, `S_jk = v̂_jᵀ G v̂_k` and the laws' tangents k_c = dF/dδ (the gap's
//! dependence on F, a small correction, is left to the iteration); the shares are updated
//! after every accepted iterate, and the iteration ends when the force residual is below
//! `coupling.tol` and the shares have settled (1e-6).
//!
//! # Start
//! The static solution under the wheel loads distributed as the patches' column forces, and
//! each wheel at the approach that carries its static load with the column gaps of that
//! static rail (a fixed point of both, iterated to 1e-9 of the shares).

use beam::track::{RailPoint, SparseCholesky, Track};
use halfspace::law::{ContactModel as LawModel, LawOutput};
use integrate::DenseLu;

use super::super::contact::wheel_error;
use super::super::{Simulation, VehicleBridgeError};
use super::TrackLayer;
use super::step::dot;

/// Largest change of a column's share of the force at which the iteration stops.
const SHARE_TOL: f64 = 1e-6;
/// Largest change of a share that ends the static start's fixed point.
const STATIC_SHARE_TOL: f64 = 1e-9;

/// A rail point in the contact DOFs: Σ_a weights\[a\] x_D\[slots\[a\]\].
#[derive(Debug, Clone, Copy, Default)]
struct SlotPoint {
    slots: [usize; 4],
    weights: [f64; 4],
}

impl SlotPoint {
    fn value(&self, x: &[f64]) -> f64 {
        (0..4).map(|a| self.weights[a] * x[self.slots[a]]).sum()
    }
}

/// The boundary-element contacts of the wheels on the rail and their work space (module
/// documentation), sized once (the sweeps grow only when a step needs more contact DOFs).
#[derive(Debug)]
pub(super) struct PatchContacts {
    /// Column positions ξ_i of each wheel's grid relative to the wheel \[m\].
    xi: Vec<Vec<f64>>,
    /// Coupled-system DOF of each contact DOF (slot).
    slots: Vec<usize>,
    /// u_d = L⁻¹P e_d of each slot.
    sweeps: Vec<Vec<f64>>,
    /// h_d = u_dᵀz and G = s UᵀU (row-major, slots × slots).
    h: Vec<f64>,
    gram: Vec<f64>,
    /// Slot of each wheel's DOF, its rail point and its grid columns' rail points.
    wheel_slot: Vec<usize>,
    centre: Vec<SlotPoint>,
    columns: Vec<Vec<SlotPoint>>,
    /// r(x_k) and r(x_k + ξ_i) − r(x_k).
    r_wheel: Vec<f64>,
    r_columns: Vec<Vec<f64>>,
    /// The shares ω_i = F_i/F of the load (empty: a point load at x_k) and the column gaps
    /// and forces of the last evaluation.
    share: Vec<Vec<f64>>,
    gap: Vec<Vec<f64>>,
    column_force: Vec<Vec<f64>>,
    /// Load directions v̂_k on the slots (k × slots), G v̂_k, f = Σ F_k v̂_k and x_D.
    direction: Vec<f64>,
    g_direction: Vec<f64>,
    f: Vec<f64>,
    x: Vec<f64>,
    /// Approaches of the last evaluation.
    delta: Vec<f64>,
    /// The capacitance matrix S = V̂ᵀ G V̂ (k × k, row-major).
    cap: Vec<f64>,
    /// Newton's work space (taken out while the iteration runs).
    newton: Option<PatchNewton>,
    /// The half-space solver's iterations over the evaluations of the last solve.
    law_iterations: usize,
    /// The accepted step's nodal contact forces −f on the slots' DOFs (the old load of the
    /// next step).
    old_load: Vec<(usize, f64)>,
}

/// The vectors and the LU storage of the contact Newton iteration (k wheels).
#[derive(Debug)]
struct PatchNewton {
    residual: Vec<f64>,
    trial_residual: Vec<f64>,
    step: Vec<f64>,
    trial: Vec<f64>,
    trial_outputs: Vec<LawOutput>,
    lu: DenseLu<f64>,
}

impl PatchContacts {
    /// The patch contacts of `contacts`, `None` unless every wheel's law has a grid of
    /// columns (the point laws and the rigid constraint take the point path of the step).
    pub(super) fn of(contacts: &[LawModel]) -> Option<Self> {
        let xi: Vec<Vec<f64>> = contacts
            .iter()
            .map(|c| match c {
                LawModel::Law(law) if law.columns() != [0.0] => Some(law.columns().to_vec()),
                _ => None,
            })
            .collect::<Option<_>>()?;
        let k = xi.len();
        let cols = |v: f64| -> Vec<Vec<f64>> { xi.iter().map(|x| vec![v; x.len()]).collect() };
        Some(Self {
            slots: Vec::new(),
            sweeps: Vec::new(),
            h: Vec::new(),
            gram: Vec::new(),
            wheel_slot: vec![0; k],
            centre: vec![SlotPoint::default(); k],
            columns: xi
                .iter()
                .map(|x| vec![SlotPoint::default(); x.len()])
                .collect(),
            r_wheel: vec![0.0; k],
            r_columns: cols(0.0),
            share: vec![Vec::new(); k],
            gap: cols(0.0),
            column_force: cols(0.0),
            direction: Vec::new(),
            g_direction: Vec::new(),
            f: Vec::new(),
            x: Vec::new(),
            delta: vec![0.0; k],
            cap: vec![0.0; k * k],
            law_iterations: 0,
            newton: Some(PatchNewton {
                residual: vec![0.0; k],
                trial_residual: vec![0.0; k],
                step: vec![0.0; k],
                trial: vec![0.0; k],
                trial_outputs: vec![LawOutput::default(); k],
                lu: DenseLu::new(k),
            }),
            old_load: Vec::new(),
            xi,
        })
    }

    /// The column positions and the column gaps c(ξ_i) of wheel k's last evaluation \[m\].
    pub(super) fn gaps(&self, k: usize) -> (&[f64], &[f64]) {
        (&self.xi[k], &self.gap[k])
    }

    /// r += scale × the last accepted step's contact load.
    pub(super) fn add_old_load(&self, scale: f64, r: &mut [f64]) {
        if scale != 0.0 {
            for &(dof, value) in &self.old_load {
                r[dof] += scale * value;
            }
        }
    }

    /// The slot of coupled-system DOF `dof` (added if new).
    fn slot(&mut self, dof: usize) -> usize {
        match self.slots.iter().position(|&d| d == dof) {
            Some(i) => i,
            None => {
                self.slots.push(dof);
                self.slots.len() - 1
            }
        }
    }

    fn slot_point(&mut self, p: &RailPoint) -> SlotPoint {
        let mut sp = SlotPoint {
            weights: p.weights,
            ..SlotPoint::default()
        };
        for a in 0..4 {
            sp.slots[a] = self.slot(p.dofs[a]);
        }
        sp
    }

    /// The contact DOFs and rail points of the wheels at track coordinates `x` (a column
    /// beyond the track's ends takes the end point: only the last centimetres of a track are
    /// affected, where no wheel runs by the scenario's checks).
    fn geometry(
        &mut self,
        track: &Track,
        x: &[f64],
        wheel_dofs: impl Iterator<Item = usize>,
        height: impl Fn(f64) -> f64,
    ) -> Result<(), VehicleBridgeError> {
        self.slots.clear();
        let length = track.layout().rail_length();
        let approach = track.layout().approach();
        for (k, dof) in wheel_dofs.enumerate() {
            self.wheel_slot[k] = self.slot(dof);
            let p = track.rail_point(x[k]).map_err(super::track_key)?;
            self.centre[k] = self.slot_point(&p);
            self.r_wheel[k] = height(x[k] - approach);
            for i in 0..self.xi[k].len() {
                let xc = (x[k] + self.xi[k][i]).clamp(0.0, length);
                let p = track.rail_point(xc).map_err(super::track_key)?;
                self.columns[k][i] = self.slot_point(&p);
                self.r_columns[k][i] = height(x[k] + self.xi[k][i] - approach) - self.r_wheel[k];
            }
        }
        let nd = self.slots.len();
        let k = self.xi.len();
        self.h.resize(nd, 0.0);
        self.gram.resize(nd * nd, 0.0);
        self.direction.resize(k * nd, 0.0);
        self.g_direction.resize(k * nd, 0.0);
        self.f.resize(nd, 0.0);
        self.x.resize(nd, 0.0);
        Ok(())
    }

    /// u_d = L⁻¹P e_d, h = Uᵀz and G = s UᵀU.
    fn sweeps(&mut self, factor: &SparseCholesky, z: &[f64], s: f64) {
        let nd = self.slots.len();
        while self.sweeps.len() < nd {
            self.sweeps.push(vec![0.0; z.len()]);
        }
        for d in 0..nd {
            factor.forward_sparse(&[(self.slots[d], 1.0)], &mut self.sweeps[d]);
            self.h[d] = dot(&self.sweeps[d], z);
        }
        for d in 0..nd {
            for e in 0..=d {
                let g = s * dot(&self.sweeps[d], &self.sweeps[e]);
                self.gram[d * nd + e] = g;
                self.gram[e * nd + d] = g;
            }
        }
    }

    /// The load directions v̂_k from the shares, G v̂_k and S = V̂ᵀ G V̂.
    fn directions(&mut self) {
        let nd = self.slots.len();
        let k = self.xi.len();
        self.direction.fill(0.0);
        for w in 0..k {
            let dir = &mut self.direction[w * nd..(w + 1) * nd];
            dir[self.wheel_slot[w]] = 1.0;
            let mut add = |p: &SlotPoint, share: f64| {
                for a in 0..4 {
                    dir[p.slots[a]] -= share * p.weights[a];
                }
            };
            if self.share[w].is_empty() {
                add(&self.centre[w], 1.0);
            } else {
                for (p, &om) in self.columns[w].iter().zip(&self.share[w]) {
                    if om != 0.0 {
                        add(p, om);
                    }
                }
            }
        }
        for w in 0..k {
            for d in 0..nd {
                self.g_direction[w * nd + d] = (0..nd)
                    .map(|e| self.gram[d * nd + e] * self.direction[w * nd + e])
                    .sum();
            }
        }
        for i in 0..k {
            for j in 0..k {
                self.cap[i * k + j] = (0..nd)
                    .map(|d| self.direction[i * nd + d] * self.g_direction[j * nd + d])
                    .sum();
            }
        }
    }

    /// f = Σ_k F_k v̂_k and x_D = h − G f.
    fn state(&mut self, forces: &[f64]) {
        let nd = self.slots.len();
        self.f.fill(0.0);
        self.x.copy_from_slice(&self.h);
        for (w, &fw) in forces.iter().enumerate() {
            for d in 0..nd {
                self.f[d] += fw * self.direction[w * nd + d];
                self.x[d] -= fw * self.g_direction[w * nd + d];
            }
        }
    }

    /// Evaluates every law at the state of the forces `forces`: approaches, column gaps,
    /// `residual = F − F_law` and the laws' outputs; returns max |residual|.
    fn evaluate(
        &mut self,
        contacts: &mut [LawModel],
        forces: &[f64],
        residual: &mut [f64],
        outputs: &mut [LawOutput],
    ) -> Result<f64, VehicleBridgeError> {
        self.state(forces);
        let mut worst = 0.0f64;
        for (k, contact) in contacts.iter_mut().enumerate() {
            let u0 = self.centre[k].value(&self.x);
            self.delta[k] = self.x[self.wheel_slot[k]] - u0 + self.r_wheel[k];
            for i in 0..self.xi[k].len() {
                self.gap[k][i] = self.columns[k][i].value(&self.x) - u0 - self.r_columns[k][i];
            }
            let LawModel::Law(law) = contact else {
                unreachable!("patch contacts are laws (checked at set-up)")
            };
            outputs[k] = law
                .evaluate(self.delta[k], &self.gap[k], &mut self.column_force[k], true)
                .map_err(wheel_error(k))?;
            self.law_iterations += outputs[k].iterations;
            residual[k] = forces[k] - outputs[k].force;
            worst = worst.max(residual[k].abs());
        }
        Ok(worst)
    }

    /// The shares of the last evaluation's column forces (a wheel without force keeps its
    /// shares); returns their largest change.
    fn adopt_shares(&mut self) -> f64 {
        let mut moved = 0.0f64;
        for k in 0..self.xi.len() {
            let total: f64 = self.column_force[k].iter().sum();
            if total <= 0.0 {
                continue;
            }
            let share = &mut self.share[k];
            if share.is_empty() {
                share.resize(self.column_force[k].len(), 0.0);
                moved = f64::INFINITY;
            }
            for (om, &fc) in share.iter_mut().zip(&self.column_force[k]) {
                let new = fc / total;
                moved = moved.max((new - *om).abs());
                *om = new;
            }
        }
        moved
    }

    /// Newton's method on the contact forces (module documentation); `forces` holds the start
    /// on entry and the solution on exit, `outputs` the laws' outputs at it. Returns the
    /// iterations.
    fn solve(
        &mut self,
        contacts: &mut [LawModel],
        forces: &mut [f64],
        outputs: &mut [LawOutput],
        tol: f64,
        max_iter: usize,
    ) -> Result<usize, VehicleBridgeError> {
        let mut newton = self
            .newton
            .take()
            .expect("the Newton work space is in place");
        let result = self.solve_with(&mut newton, contacts, forces, outputs, tol, max_iter);
        self.newton = Some(newton);
        result
    }

    fn solve_with(
        &mut self,
        nw: &mut PatchNewton,
        contacts: &mut [LawModel],
        forces: &mut [f64],
        outputs: &mut [LawOutput],
        tol: f64,
        max_iter: usize,
    ) -> Result<usize, VehicleBridgeError> {
        let k = forces.len();
        self.law_iterations = 0;
        self.directions();
        let mut residual = self.evaluate(contacts, forces, &mut nw.residual, outputs)?;
        for it in 1..=max_iter {
            let moved = self.adopt_shares();
            if residual <= tol && moved <= SHARE_TOL {
                return Ok(it - 1);
            }
            self.directions();
            // The residual was evaluated with the shares before this adoption.
            let stale = moved > 0.0;
            // (I + diag(k_c) S) ΔF = −G.
            {
                let mut m = nw.lu.matrix_mut();
                for r in 0..k {
                    for c in 0..k {
                        let id = if r == c { 1.0 } else { 0.0 };
                        m[(r, c)] = id + outputs[r].stiffness * self.cap[r * k + c];
                    }
                }
            }
            if !nw.lu.factor() {
                return Err(failure(it, "singular capacitance Jacobian"));
            }
            for c in 0..k {
                nw.step[c] = -nw.residual[c];
            }
            nw.lu.solve_in_place(&mut nw.step);
            let mut scale = 1.0;
            let mut accepted = false;
            let mut trial_residual = f64::INFINITY;
            for _ in 0..30 {
                for c in 0..k {
                    nw.trial[c] = (forces[c] + scale * nw.step[c]).max(0.0);
                }
                trial_residual = self.evaluate(
                    contacts,
                    &nw.trial,
                    &mut nw.trial_residual,
                    &mut nw.trial_outputs,
                )?;
                if trial_residual < residual || trial_residual <= tol {
                    forces.copy_from_slice(&nw.trial);
                    outputs.copy_from_slice(&nw.trial_outputs);
                    nw.residual.copy_from_slice(&nw.trial_residual);
                    residual = trial_residual;
                    accepted = true;
                    break;
                }
                scale *= 0.5;
            }
            if !accepted && stale {
                // The adopted shares moved the column gaps and the load directions, so the
                // residual the line search compared with belongs to the old shares: evaluate
                // it again at the same forces with the new ones and take the next iteration
                // from there (its adoption finds the shares of this evaluation).
                residual = self.evaluate(contacts, forces, &mut nw.residual, outputs)?;
                continue;
            }
            if !accepted {
                // No decrease in 30 halvings: at the floating-point floor of the residual.
                return if residual <= 1e3 * tol {
                    self.adopt_shares();
                    Ok(it)
                } else {
                    Err(failure(
                        it,
                        &format!("no decrease of the residual ({trial_residual:e} N)"),
                    ))
                };
            }
        }
        Err(failure(
            max_iter,
            &format!("no convergence in {max_iter} iterations (residual {residual:e} N)"),
        ))
    }

    /// After the solve: f of the forces with the settled shares, z ← z − s Σ_d f_d u_d, and
    /// the step's load for the next step's old part.
    fn apply(&mut self, forces: &[f64], s: f64, z: &mut [f64]) {
        self.directions();
        self.state(forces);
        self.old_load.clear();
        for d in 0..self.slots.len() {
            let f = self.f[d];
            if f != 0.0 {
                for (zi, ui) in z.iter_mut().zip(&self.sweeps[d]) {
                    *zi -= s * f * ui;
                }
            }
            self.old_load.push((self.slots[d], -f));
        }
    }

    /// The static start (module documentation): the static solution `u` of the track under
    /// `base` (the moving forces) and the wheel loads `loads` at track coordinates `x`
    /// distributed as the patches carry them, and each wheel's static approach on it.
    /// Returns u and the approaches; leaves the laws' outputs in `outputs` and the static
    /// contact load (wheels' DOFs `wheel_dofs` in the coupled system) as the first step's old
    /// load.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn static_start(
        &mut self,
        track: &Track,
        contacts: &mut [LawModel],
        x: &[f64],
        loads: &[f64],
        base: &[f64],
        wheel_dofs: &[usize],
        outputs: &mut [LawOutput],
    ) -> Result<(Vec<f64>, Vec<f64>), VehicleBridgeError> {
        let k = loads.len();
        let length = track.layout().rail_length();
        let point = |x: f64| {
            track
                .rail_point(x.clamp(0.0, length))
                .map_err(super::track_key)
        };
        let mut approaches = vec![0.0; k];
        for (c, contact) in contacts.iter_mut().enumerate() {
            let LawModel::Law(law) = contact else {
                unreachable!("patch contacts are laws")
            };
            approaches[c] = law.static_approach(loads[c]).map_err(wheel_error(c))?;
        }
        for _ in 0..20 {
            let mut load = base.to_vec();
            for c in 0..k {
                if self.share[c].is_empty() {
                    track
                        .add_point_force(x[c], loads[c], &mut load)
                        .map_err(super::track_key)?;
                } else {
                    for (i, &om) in self.share[c].iter().enumerate() {
                        let p = point(x[c] + self.xi[c][i])?;
                        for a in 0..4 {
                            load[p.dofs[a]] += loads[c] * om * p.weights[a];
                        }
                    }
                }
            }
            let u = track.static_solution(&load).map_err(super::track_key)?;
            for c in 0..k {
                let u0 = point(x[c])?.value(&u);
                for i in 0..self.xi[c].len() {
                    self.gap[c][i] = point(x[c] + self.xi[c][i])?.value(&u) - u0;
                }
                let LawModel::Law(law) = &mut contacts[c] else {
                    unreachable!("patch contacts are laws")
                };
                // Newton's method on F_law(δ, c) = W.
                let mut converged = false;
                for _ in 0..50 {
                    outputs[c] = law
                        .evaluate(approaches[c], &self.gap[c], &mut self.column_force[c], true)
                        .map_err(wheel_error(c))?;
                    let r = loads[c] - outputs[c].force;
                    if r.abs() <= 1e-12 * loads[c] {
                        converged = true;
                        break;
                    }
                    if outputs[c].stiffness <= 0.0 {
                        break;
                    }
                    approaches[c] += r / outputs[c].stiffness;
                }
                if !converged {
                    return Err(failure(
                        50,
                        "the static approach of a patch did not converge",
                    ));
                }
            }
            if self.adopt_shares() <= STATIC_SHARE_TOL {
                // The static contact load, the old load of the first step.
                self.old_load.clear();
                for c in 0..k {
                    self.old_load.push((wheel_dofs[c], -loads[c]));
                    for (i, &om) in self.share[c].iter().enumerate() {
                        let p = point(x[c] + self.xi[c][i])?;
                        for a in 0..4 {
                            self.old_load
                                .push((p.dofs[a], loads[c] * om * p.weights[a]));
                        }
                    }
                }
                return Ok((u, approaches));
            }
        }
        Err(failure(
            20,
            "the static start's load distribution did not settle",
        ))
    }
}

fn failure(iterations: usize, reason: &str) -> VehicleBridgeError {
    super::solve_failure("track_patch_newton", iterations, reason)
}

impl Simulation {
    /// The boundary-element contacts' forces of a step (module documentation): the contact
    /// DOFs' sweeps, the Newton iteration, and z ← z − s L⁻¹P f in `l.r`. Returns the
    /// iterations.
    pub(super) fn patch_contact(
        &mut self,
        l: &mut TrackLayer,
        t_new: f64,
    ) -> Result<usize, VehicleBridgeError> {
        let mut patch = l.patch.take().expect("called with patch contacts");
        let result = self.patch_contact_with(l, &mut patch, t_new);
        l.patch = Some(patch);
        result
    }

    fn patch_contact_with(
        &mut self,
        l: &mut TrackLayer,
        patch: &mut PatchContacts,
        t_new: f64,
    ) -> Result<usize, VehicleBridgeError> {
        let s = 1.0 - l.params.alpha_f;
        let nw = self.scenario.wheels.len();
        let approach = l.track.layout().approach();
        for k in 0..nw {
            l.positions[k] =
                self.scenario.wheels[k].position + self.scenario.speed * t_new + approach;
        }
        let irregularity = &self.scenario.irregularity;
        patch.geometry(
            &l.track,
            &l.positions,
            self.wheel_dof.iter().map(|&d| l.offset + d),
            |x| irregularity.height(x),
        )?;
        patch.sweeps(&l.factor, &l.r, s);
        let tol = self.scenario.coupling.tol * self.force_scale;
        let mut forces = std::mem::take(&mut l.forces);
        let solved = patch.solve(
            &mut self.contacts,
            &mut forces,
            &mut self.work.outputs,
            tol,
            self.scenario.coupling.max_iter,
        );
        self.stats.contact_iterations += patch.law_iterations;
        if solved.is_ok() {
            patch.apply(&forces, s, &mut l.r);
            for k in 0..nw {
                self.work.delta[k] = patch.delta[k];
                self.work.r_at_wheel[k] = patch.r_wheel[k];
                l.points[k] = l
                    .track
                    .rail_point(l.positions[k])
                    .map_err(super::track_key)?;
            }
        }
        l.forces = forces;
        solved
    }

    /// The grid columns' positions ξ_i relative to wheel k and the column gaps c(ξ_i) of its
    /// last evaluation \[m\] (module `track::patch`); `None` without a track or with a point
    /// contact.
    pub fn track_patch_gaps(&self, wheel: usize) -> Option<(&[f64], &[f64])> {
        self.track
            .as_ref()
            .and_then(|t| t.patch.as_ref())
            .map(|p| p.gaps(wheel))
    }
}
