//! Time stepping of the track with Newmark's average-acceleration rule (β = ¼, γ = ½;
//! references.md §D3.5): the step matrix K + γ/(βΔt) C + 1/(βΔt²) M is constant for a fixed
//! Δt, so it is factorised once and every step is one pair of triangular sweeps.

use integrate::structural::sparse::{SparseMatrix, sparse_mul_add};

use crate::error::{BeamError, positive};

use super::model::{RailPoint, Track};
use super::sparse::SparseCholesky;

const BETA: f64 = 0.25;
const GAMMA: f64 = 0.5;

/// Newmark (average acceleration) integrator of a [`Track`] under prescribed loads.
#[derive(Debug)]
pub struct TrackNewmark<'a> {
    track: &'a Track,
    mass: SparseMatrix,
    damping: SparseMatrix,
    dt: f64,
    solver: SparseCholesky,
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
    time: f64,
}

impl<'a> TrackNewmark<'a> {
    /// Start at rest in static equilibrium under `initial_load` (K u₀ = f₀, v₀ = a₀ = 0) with
    /// step Δt; factorises the step matrix.
    pub fn new(track: &'a Track, dt: f64, initial_load: &[f64]) -> Result<Self, BeamError> {
        positive("dt", dt)?;
        let u = track.static_solution(initial_load)?;
        let n = track.n_dofs();
        let solver =
            track.factorise_step_matrix(1.0 / (BETA * dt * dt), GAMMA / (BETA * dt), 1.0)?;
        let [m, c, _] = track.matrices();
        Ok(Self {
            track,
            mass: m.to_rows(),
            damping: c.to_rows(),
            dt,
            solver,
            u,
            v: vec![0.0; n],
            a: vec![0.0; n],
            tmp: vec![0.0; n],
            tmp2: vec![0.0; n],
            time: 0.0,
        })
    }

    /// One step to t + Δt under the load vector `load` at t + Δt (length n):
    /// [`Self::predict`] then [`Self::advance_to`].
    pub fn step(&mut self, load: &[f64]) -> Result<(), BeamError> {
        let mut u = std::mem::take(&mut self.tmp2);
        u.resize(self.u.len(), 0.0);
        let result = self
            .predict(load, &mut u)
            .and_then(|()| self.advance_to(&u));
        self.tmp2 = u;
        result
    }

    /// The displacement at t + Δt under `load` (length n) into `out`, without advancing:
    /// u = A⁻¹(f + M(a₀u + a₂v + a₃a) + C(a₁u + a₄v + a₅a)). The response is linear in the
    /// load, so a coupling adds F · A⁻¹b for a contact force F on the load vector b
    /// ([`Self::solve_step_matrix`]).
    pub fn predict(&mut self, load: &[f64], out: &mut [f64]) -> Result<(), BeamError> {
        crate::modal::check_len("load", load.len(), self.u.len())?;
        crate::modal::check_len("out", out.len(), self.u.len())?;
        self.history(load, out);
        self.solver.solve_in_place(out);
        Ok(())
    }

    /// out = f + M(a₀u + a₂v + a₃a) + C(a₁u + a₄v + a₅a).
    fn history(&mut self, load: &[f64], out: &mut [f64]) {
        let dt = self.dt;
        let (a0, a2, a3) = (1.0 / (BETA * dt * dt), 1.0 / (BETA * dt), 0.5 / BETA - 1.0);
        let (a1, a4, a5) = (
            GAMMA / (BETA * dt),
            GAMMA / BETA - 1.0,
            dt * (GAMMA / (2.0 * BETA) - 1.0),
        );
        out.copy_from_slice(load);
        for i in 0..self.u.len() {
            self.tmp[i] = a0 * self.u[i] + a2 * self.v[i] + a3 * self.a[i];
        }
        sparse_mul_add(self.mass.as_ref(), 1.0, &self.tmp, out);
        for i in 0..self.u.len() {
            self.tmp[i] = a1 * self.u[i] + a4 * self.v[i] + a5 * self.a[i];
        }
        sparse_mul_add(self.damping.as_ref(), 1.0, &self.tmp, out);
    }

    /// [`Self::predict`]'s right-hand side after the forward half of the solve only:
    /// z = L⁻¹P(f + history) (A = PᵀLLᵀP). With y = [`Self::forward_point`] of a contact at
    /// the rail point p, the rail displacement there under a contact force F is
    /// yᵀz + F yᵀy, and [`Self::backward`] of z + F y is the displacement at t + Δt: one solve
    /// per coupled step (references.md §D4.2, §D5.2).
    pub fn predict_forward(&mut self, load: &[f64], out: &mut [f64]) -> Result<(), BeamError> {
        crate::modal::check_len("load", load.len(), self.u.len())?;
        crate::modal::check_len("out", out.len(), self.u.len())?;
        self.history(load, out);
        self.solver.forward(out);
        Ok(())
    }

    /// y = L⁻¹P b for the consistent load vector b of a unit force at the rail point `p`.
    pub fn forward_point(&self, p: &RailPoint, out: &mut [f64]) -> Result<(), BeamError> {
        crate::modal::check_len("out", out.len(), self.u.len())?;
        let b: [(usize, f64); 4] = std::array::from_fn(|a| (p.dofs[a], p.weights[a]));
        self.solver.forward_sparse(&b, out);
        Ok(())
    }

    /// z ← PᵀL⁻ᵀz: the backward half of the step-matrix solve.
    pub fn backward(&mut self, z: &mut [f64]) -> Result<(), BeamError> {
        crate::modal::check_len("z", z.len(), self.u.len())?;
        self.solver.backward(z);
        Ok(())
    }

    /// r ← A⁻¹ r with the step matrix A = K + γ/(βΔt) C + 1/(βΔt²) M.
    pub fn solve_step_matrix(&mut self, r: &mut [f64]) -> Result<(), BeamError> {
        crate::modal::check_len("r", r.len(), self.u.len())?;
        self.solver.solve_in_place(r);
        Ok(())
    }

    /// Accept `u_next` as the displacement at t + Δt (Newmark's corrector for a and v).
    pub fn advance_to(&mut self, u_next: &[f64]) -> Result<(), BeamError> {
        crate::modal::check_len("u_next", u_next.len(), self.u.len())?;
        let dt = self.dt;
        let (a0, a2, a3) = (1.0 / (BETA * dt * dt), 1.0 / (BETA * dt), 0.5 / BETA - 1.0);
        for (i, &un) in u_next.iter().enumerate() {
            let an = a0 * (un - self.u[i]) - a2 * self.v[i] - a3 * self.a[i];
            self.v[i] += dt * ((1.0 - GAMMA) * self.a[i] + GAMMA * an);
            self.a[i] = an;
            self.u[i] = un;
        }
        self.time += dt;
        Ok(())
    }

    /// Current time \[s\] (0 at the start).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Displacements.
    pub fn displacement(&self) -> &[f64] {
        &self.u
    }

    /// Velocities.
    pub fn velocity(&self) -> &[f64] {
        &self.v
    }

    /// The track being integrated.
    pub fn track(&self) -> &Track {
        self.track
    }

    /// Number of stored entries of the step matrix's Cholesky factor.
    pub fn factor_entries(&self) -> usize {
        self.solver.factor_entries()
    }

    /// The step size.
    pub fn dt(&self) -> f64 {
        self.dt
    }
}
