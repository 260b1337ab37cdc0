//! The inputs of a tangential solve: the rigid motion (creepages, shift, a transient step),
//! the load (creepages or forces) and the solver options, and the element states of its
//! result (module [`super`], which re-exports them).

use crate::error::{ContactError, finite, positive};

/// State of one element after a tangential solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementState {
    /// Outside the contact area (p_n = 0).
    Exterior,
    /// Adhesion: no slip, |p_t| ≤ μ p_n.
    Adhesion,
    /// Slip: |p_t| = μ p_n, opposite to the slip.
    Slip,
}

/// Creepages of rolling: ξ, η dimensionless (slip velocity over rolling speed), φ in 1/m.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Creepages {
    pub xi: f64,
    pub eta: f64,
    pub phi: f64,
}

impl Creepages {
    pub(super) fn validate(&self) -> Result<(), ContactError> {
        finite("creepage_x", self.xi)?;
        finite("creepage_y", self.eta)?;
        finite("spin", self.phi)?;
        Ok(())
    }
}

/// What is prescribed in steady rolling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RollingLoad {
    /// Creepages and spin prescribed.
    Creepages(Creepages),
    /// Total tangential forces F_x, F_y \[N\] on body 1 and spin φ [1/m] prescribed; the
    /// creepages ξ, η are found by Newton's method.
    Forces { fx: f64, fy: f64, phi: f64 },
}

/// What is prescribed in a shift problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ShiftLoad {
    /// Rigid shift (w_x, w_y) \[m\] of body 1 relative to body 2.
    Shift { wx: f64, wy: f64 },
    /// Total tangential forces F_x, F_y \[N\]; the shift is found by Newton's method.
    Forces { fx: f64, fy: f64 },
}

/// The motion of one transient rolling step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepMotion {
    /// Distance rolled in this step δq = V δt \[m\] (≥ 0; 0 for a pure shift step).
    pub delta_q: f64,
    /// Creepages applied over δq.
    pub creepages: Creepages,
    /// Additional rigid shift (w_x, w_y) \[m\] in this step.
    pub shift: (f64, f64),
}

/// The solver of steady rolling (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SteadySolver {
    /// Semismooth Newton–Krylov on the adhesion/slip split with FFT products and the
    /// preconditioner of [`TangentialOptions::nk_preconditioner`] (the default); falls back to
    /// [`Self::GaussSeidel`] if it does not converge.
    #[default]
    NewtonKrylov,
    /// SteadyGS-type Gauss–Seidel sweeps with Anderson acceleration (the reference).
    GaussSeidel,
}

/// The preconditioner of the linear systems of the steady-rolling Newton–Krylov solver
/// (module documentation; references.md §C3.10).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NkPreconditioner {
    /// The diagonal blocks of the Jacobian and the coupling of each element to its upstream
    /// neighbour (one element towards the leading edge), solved exactly by marching each grid
    /// row from the leading edge (the default until 2026-11-27; on grids below 6000 elements
    /// the default [`Self::TwoLevel`] is this).
    UpstreamLine,
    /// The diagonal of the Jacobian (the solver's preconditioner before the line solve; kept
    /// for comparison).
    Jacobi,
    /// The upstream line solve with a two-level correction on 4 × 4 blocks whose coarse
    /// matrix is the Galerkin matrix of the line-preconditioned operator, built without
    /// products (near entries from the kernel table, far field by a point-force convolution on
    /// the grid of blocks) and solved by a few inner GMRES iterations; the outer iteration is
    /// flexible GMRES. Its product count stays bounded as the grid grows (docs/tangential.md
    /// "Performance", issue #18). The default; below 6000 elements, where the correction costs
    /// more than it saves, it is the line solve alone.
    #[default]
    TwoLevel,
}

/// Controls of the tangential iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialOptions {
    /// Relative tolerance on ‖Δp‖_rms/‖p‖_rms per Gauss–Seidel sweep, and on the remaining
    /// error η‖Δp‖_rms/‖p‖_rms of the steady-rolling Newton–Krylov solver (default 1e-7).
    pub tol: f64,
    /// Sweep limit per solve (default 10000; 2D rolling with large adhesion areas needs
    /// thousands); the Newton–Krylov solver stops after min(max_iter, 100) Newton steps.
    pub max_iter: usize,
    /// Relaxation ω ∈ (0, 2) of adhesion updates (default 1). Steady rolling relaxes every
    /// element with min(ω, 0.5), reduced automatically when sweeps oscillate.
    pub omega: f64,
    /// Newton tolerance on the force error, relative to μ F_n (default 1e-6).
    pub force_tol: f64,
    /// Newton iteration limit (default 40).
    pub max_newton: usize,
    /// Start from the previous solution of this solver (default true).
    pub warm_start: bool,
    /// Depth m of the Anderson acceleration of the sweeps (0 switches it off; default 3).
    pub anderson_depth: usize,
    /// The steady-rolling solver (default [`SteadySolver::NewtonKrylov`]).
    pub steady_solver: SteadySolver,
    /// The preconditioner of its linear systems (default [`NkPreconditioner::UpstreamLine`]).
    pub nk_preconditioner: NkPreconditioner,
    /// Start a cold Newton–Krylov solve of steady rolling from the solution on the grid with
    /// elements twice as large (nested iteration, recursively down to about 20 × 20
    /// elements; module documentation, "Nested start"). Default true; false starts from
    /// zero tractions (the solver before, the reference in tests).
    pub nested_start: bool,
}

impl Default for TangentialOptions {
    fn default() -> Self {
        TangentialOptions {
            tol: 1e-7,
            max_iter: 10000,
            omega: 1.0,
            force_tol: 1e-6,
            max_newton: 40,
            warm_start: true,
            anderson_depth: 3,
            steady_solver: SteadySolver::NewtonKrylov,
            nk_preconditioner: NkPreconditioner::UpstreamLine,
            nested_start: true,
        }
    }
}

impl TangentialOptions {
    pub(super) fn validate(&self) -> Result<(), ContactError> {
        positive("tol", self.tol)?;
        positive("force_tol", self.force_tol)?;
        positive("omega", self.omega)?;
        if self.omega >= 2.0 {
            return Err(ContactError::InvalidParameter {
                name: "omega",
                value: self.omega,
                reason: "relaxation must lie in (0, 2)",
            });
        }
        if self.max_iter == 0 || self.max_newton == 0 {
            return Err(ContactError::InvalidParameter {
                name: "max_iter",
                value: 0.0,
                reason: "iteration limits must be at least 1",
            });
        }
        Ok(())
    }
}
