//! Time stepping of the track with Newmark's average-acceleration rule (β = ¼, γ = ½;
//! references.md §D3.5): the step matrix K + γ/(βΔt) C + 1/(βΔt²) M is constant for a fixed
//! Δt, so it is factorised once and every step is one pair of triangular sweeps.

use integrate::structural::sparse::{SparseMatrix, sparse_mul_add};

use crate::error::{BeamError, positive};

use super::model::Track;
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
    rhs: Vec<f64>,
    tmp: Vec<f64>,
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
            rhs: vec![0.0; n],
            tmp: vec![0.0; n],
            time: 0.0,
        })
    }

    /// One step to t + Δt under the load vector `load` at t + Δt (length n).
    pub fn step(&mut self, load: &[f64]) -> Result<(), BeamError> {
        crate::modal::check_len("load", load.len(), self.u.len())?;
        let dt = self.dt;
        let (a0, a2, a3) = (1.0 / (BETA * dt * dt), 1.0 / (BETA * dt), 0.5 / BETA - 1.0);
        let (a1, a4, a5) = (
            GAMMA / (BETA * dt),
            GAMMA / BETA - 1.0,
            dt * (GAMMA / (2.0 * BETA) - 1.0),
        );
        self.rhs.copy_from_slice(load);
        // M (a0 u + a2 v + a3 a)
        for i in 0..self.u.len() {
            self.tmp[i] = a0 * self.u[i] + a2 * self.v[i] + a3 * self.a[i];
        }
        sparse_mul_add(self.mass.as_ref(), 1.0, &self.tmp, &mut self.rhs);
        // C (a1 u + a4 v + a5 a)
        for i in 0..self.u.len() {
            self.tmp[i] = a1 * self.u[i] + a4 * self.v[i] + a5 * self.a[i];
        }
        sparse_mul_add(self.damping.as_ref(), 1.0, &self.tmp, &mut self.rhs);
        self.solver.solve_in_place(&mut self.rhs);
        for i in 0..self.u.len() {
            let un = self.rhs[i];
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
