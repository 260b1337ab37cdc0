//! Tangential contact with Coulomb friction: shift (Cattaneo–Mindlin), steady rolling and
//! transient rolling, solved element by element the way CONTACT's ConvexGS / SteadyGS do.
//!
//! **Model** (references.md §C3.1, §3.5). Tractions p_t = (p_x, p_y) are constant per element and
//! act on body 1; u_t = A_tt p_t with the tangential influence coefficients of
//! [`crate::influence::tangential_influence`]. In one step in which the contact moves a
//! distance δq in +x over the material (the leading edge is at the largest x), the shift of
//! the particles now at element I is
//!
//! ```text
//! S_I = W_I + (A p)_I − (A_v p')_I,    W_I = δq (ξ − φ y_I, η + φ x_I) + (w_x, w_y)
//! ```
//!
//! with creepages ξ, η (dimensionless), spin φ [1/m] about the coordinate origin, an extra
//! rigid shift (w_x, w_y) \[m\], p' the tractions of the previous step and A_v CONTACT's
//! kernel "C_v": the influence coefficients with the observation point moved by δq
//! (the displacement the same particles had one step earlier). With μ the friction
//! coefficient and g = μ p_n the traction bound, each element in contact is either in
//! adhesion (S_I = 0, |p_I| ≤ g_I) or slips (p_I = −g_I S_I/|S_I|).
//!
//! * **Shift** (T = 1): δq = 0, p' = 0: S = W + A p.
//! * **Steady rolling** (T = 3, δq = δx as CONTACT recommends): p' = p, so S = δx w + (A − A_v) p;
//!   the relative slip velocity is s = S/δx.
//! * **Transient rolling** (T = 2): p' is the previous step's result, S = δq w + A p − A_v p';
//!   [`TangentialSolver::transient_step`] carries it, which is what a time-stepping caller needs.
//!
//! **Solver.** Block Gauss–Seidel over the elements in contact (ConvexGS, Vollebregt JOTA 87
//! (1995) 47): element I solves its own 2-unknown problem exactly with the other tractions
//! frozen. With r = S_I − D p_I (D = diag(C_xx, C_yy) the element's own coefficients; C_xy
//! vanishes at zero offset by symmetry) the adhesion trial is p = −D⁻¹ r; if it exceeds the
//! bound the element slips with p = −g (r_x/(λ + g D_x), r_y/(λ + g D_y)), where λ = |S_I| > 0
//! solves (r_x/(λ + g D_x))² + (r_y/(λ + g D_y))² = 1 (Newton from λ = 0, monotone since the
//! function is convex and decreasing). Adhesion updates are relaxed by ω. For the shift and
//! transient operators (C = A, symmetric positive definite) this is block coordinate descent
//! on a convex problem and converges; the steady operator A − A_v is far from symmetric
//! (nearly a discrete derivative), so there every update is under-relaxed (ω ≤ 0.5, halved
//! further by a factor 0.6 whenever a sweep changes p more than the previous one). S is kept exact
//! by adding the changed element's column of C (dense, O(n) per element) in the rows not
//! yet visited in the sweep, and is recomputed by FFT convolution before each sweep (which
//! brings the visited rows up to date: the iterates are those of full Gauss–Seidel). Sweeps
//! run row by row from the leading edge (largest x) to the trailing edge, the SteadyGS order
//! that resolves the dominant upstream coupling of steady rolling in one sweep. Stopping rule
//! (CONTACT's, references.md §C3.7): ‖Δp‖_rms ≤ tol·‖p‖_rms over one sweep.
//!
//! **Anderson acceleration.** The sweep map x ↦ G(x) (x = all tractions) is accelerated by
//! Anderson mixing of depth m (default 3; Walker & Ni, SIAM J. Numer. Anal. 49 (2011) 1715):
//! x_{k+1} = G(x_k) − Σ γ_j (Δx_j + Δf_j) with f = G(x) − x and γ the least-squares fit of
//! f_k by the last m differences Δf_j; the result is projected onto the traction bounds and S
//! is recomputed by FFT. The history restarts when ‖f‖ more than doubles. The fixed point (the
//! solution) is unchanged; measured: 2D rolling needs 10–20× fewer sweeps (Carter, 221
//! elements: 4448 → 192), shifts 2× fewer (44 × 44: 87 → 38), 3D rolling about the same.
//!
//! **Steady rolling: semismooth Newton–Krylov** (the default, [`SteadySolver::NewtonKrylov`];
//! references.md §C3.9; the sweeps above are the reference, [`SteadySolver::GaussSeidel`]).
//! Unknowns: p_I in adhesion, the angle θ_I in slip with p_I = g_I (cos θ_I, sin θ_I).
//! Equations F = 0: S_I = 0 in adhesion, S_I · t_I = 0 in slip (t_I = (−sin θ_I, cos θ_I):
//! S opposite to p). Each Newton step computes S (one FFT product), moves adhesion elements
//! beyond the bound to slip and slip elements with S·p > 0 to adhesion, and solves J d = −F
//! matrix-free by restarted GMRES (one FFT product per iteration) to a relative residual η
//! (0.1; tightened on the last steps so that the remaining error η‖Δp‖ ≤ tol‖p‖). The
//! preconditioner ([`NkPreconditioner`], references.md §C3.10) is by default the upstream line
//! solve: C(−1, 0) = −C(0, 0) (A_v(δx) is A moved by one element), so J is dominated by a
//! discrete derivative along x; its diagonal and upstream-neighbour blocks are solved exactly
//! by marching each grid row from the leading edge, O(N) per application. The diagonal of J
//! (Jacobi, the earlier default) is kept for comparison. J: adhesion rows C, slip columns
//! C g t, slip rows t·(…) plus the diagonal −p̂·S = |S|. It stops when the split is settled, every adhesion element is within its bound
//! and η‖Δp‖_rms ≤ tol‖p‖_rms; if it does not within min(`max_iter`, 100) steps the Gauss–Seidel
//! reference continues from its iterate ([`TangentialSolution::steady_fallback`]). Files
//! `steady_nk.rs` (the Newton iteration and J), `nk_precondition.rs` (the preconditioners) and
//! `gmres.rs`. The option [`NkPreconditioner::TwoLevel`] adds a coarse correction on 4 × 4
//! blocks whose Galerkin matrix of the line-preconditioned operator is built from the kernel
//! tables without products and solved by a few inner GMRES iterations inside flexible GMRES
//! (`two_level/`): its product count stays bounded as the grid grows (issue #18); it is not
//! the default (docs/tangential.md "Performance").
//!
//! **Nested start** ([`TangentialOptions::nested_start`], default on; references.md §C3.12).
//! A cold Newton–Krylov solve (no previous solution on this solver) on a grid of at least
//! 40 × 40 elements first solves the same case on the grid with elements twice as large
//! (pressure averaged over 2 × 2 elements, the same μ, creepages and spin; recursively down to
//! about 20 × 20, to tol 1e-4) and starts from its tractions and adhesion/slip split copied to
//! the four children (slip children on their own bound). The fixed point and the stopping rule
//! are unchanged; the Newton steps on the fine grid drop to 4–6 (from 8–12), the products on
//! it by about 40 % on the tractcurv case; the coarse levels add products costing about
//! 10 % of the fine ones. The products per Newton step still grow with the grid. Warm starts
//! (creep curves, Newton on the forces) do not use it. File `nested.rs`.
//!
//! **Prescribed forces.** Newton's method on (ξ, η) (rolling) or (w_x, w_y) (shift), with the
//! 2 × 2 Jacobian by forward differences and step halving, started from the full-adhesion
//! (linear) response; CONTACT does the same on the creepages (references.md §C3.5).
//!
//! **Dissimilar materials (K ≠ 0).** The pressure's own tangential displacement A_tn p_n
//! (references.md §C3.2) enters W: A_tn p_n in a shift from the unloaded state,
//! (A_tn − A_v,tn) p_n in steady rolling, A_tn p_n − A_v,tn p_n' in a transient step. The
//! reverse effect of the tangential tractions on the normal problem is
//! [`TangentialSolver::normal_displacement`]; [`crate::coupled`] alternates the two solves
//! (Panagiotopoulos' process). Friction is Coulomb with a constant μ.
//!
//! **Operator.** All products with the kernels A, A − A_v and A_v, the dense column updates
//! and the coupling terms go through [`TangentialInfluenceOperator`]:
//! [`TangentialSolver::new`] uses the FFT operator [`FftTangentialInfluence`],
//! [`TangentialSolver::with_operator`] any implementation (e.g. the direct O(n²) oracle
//! [`crate::DirectTangentialInfluence`]).
//!
//! Files: `sweep.rs` (the Gauss–Seidel sweep and the element solve), `newton.rs`
//! (prescribed forces), `nested.rs` (the nested start), `inputs.rs` (loads, motions and options), `anderson.rs` (acceleration of the sweeps), `coupling.rs` (the
//! pressure's tangential displacement for K ≠ 0); the kernels are in
//! [`crate::operator::tangential`].

mod anderson;
mod coupling;
mod gmres;
mod inputs;
mod nested;
mod newton;
mod nk_precondition;
mod steady_nk;
mod sweep;
mod two_level;

use crate::error::{ContactError, finite, positive};
use crate::grid::Grid;
use crate::material::Material;
use crate::operator::{
    FftTangentialInfluence, TangentialInfluenceOperator, TangentialKernel, Update,
};
use coupling::Coupling;
pub use inputs::{
    Creepages, ElementState, NkPreconditioner, RollingLoad, ShiftLoad, SteadySolver, StepMotion,
    TangentialOptions,
};
use nested::CoarseLevel;
pub use nested::CoarseProducts;

/// Result of a tangential solve (SI units; tractions and forces act on body 1).
#[derive(Debug, Clone)]
pub struct TangentialSolution {
    pub grid: Grid,
    /// Tangential tractions p_x, p_y per element \[Pa\].
    pub traction_x: Vec<f64>,
    pub traction_y: Vec<f64>,
    /// Element states.
    pub state: Vec<ElementState>,
    /// Slip per element: the relative slip velocity s = S/δq (dimensionless, per unit rolling
    /// speed) when the contact rolls (δq > 0), the shift S \[m\] itself in a shift problem.
    pub slip_x: Vec<f64>,
    pub slip_y: Vec<f64>,
    /// Total forces F_x, F_y \[N\] and the spin moment M_z = ΔA Σ (x p_y − y p_x) [N m] about
    /// the coordinate origin.
    pub force_x: f64,
    pub force_y: f64,
    pub moment_z: f64,
    pub adhesion_elements: usize,
    pub slip_elements: usize,
    /// Frictional dissipation −ΔA Σ p·s: per unit rolling speed \[N\] (multiply by V for watts)
    /// when rolling, the work \[J\] of the shift in a shift problem.
    pub frictional_power: f64,
    /// Creepages used (found ones when forces were prescribed in rolling).
    pub creepages: Creepages,
    /// Rigid shift (w_x, w_y) \[m\] used (found when forces were prescribed in a shift).
    pub shift: (f64, f64),
    /// Distance rolled per step δq \[m\] (δx in steady rolling, 0 in a shift).
    pub delta_q: f64,
    /// Solver iterations in total (all Newton iterations on forces included): Gauss–Seidel
    /// sweeps, or the Newton steps of the steady-rolling Newton–Krylov solver.
    pub iterations: usize,
    /// Newton iterations (0 when the creepages or the shift were prescribed).
    pub newton_iterations: usize,
    /// Last relative change ‖Δp‖_rms/‖p‖_rms.
    pub residual: f64,
    /// Products with the influence operator in this solve (each four FFT convolutions of the
    /// 2 × 2 traction block with the FFT operator; the Gauss–Seidel sweeps' dense column
    /// updates are not counted here): the cost measure of the benchmarks.
    pub products: usize,
    /// True when the steady-rolling Newton–Krylov solver did not converge within its limit
    /// and the Gauss–Seidel reference finished the solve (never set by other problems).
    pub steady_fallback: bool,
    /// Operator products on the coarse grids of nested starts in this solve (empty without
    /// one; [`TangentialOptions::nested_start`]); not included in `products`.
    pub coarse_products: CoarseProducts,
}

/// Solver of tangential contact problems on one grid and material pair, generic over the
/// tangential influence operator `T` (default: the FFT operator [`FftTangentialInfluence`],
/// which tabulates the kernels once, the steady and shifted ones on first use, and plans the
/// FFTs once). Owns the work vectors; repeated solves allocate only their result.
#[derive(Debug)]
pub struct TangentialSolver<T: TangentialInfluenceOperator = FftTangentialInfluence> {
    operator: T,
    px: Vec<f64>,
    py: Vec<f64>,
    sx: Vec<f64>,
    sy: Vec<f64>,
    bx: Vec<f64>,
    by: Vec<f64>,
    slipping: Vec<bool>,
    bound: Vec<f64>,
    has_previous: bool,
    /// The pressure of the current solve and of the previous transient step.
    pn: Vec<f64>,
    pn_previous: Option<Vec<f64>>,
    /// Tangential displacement difference from the pressure, added to W.
    cnx: Vec<f64>,
    cny: Vec<f64>,
    /// Operator products since the start of the solve.
    products: usize,
    /// Whether a steady solve of this public call fell back to Gauss–Seidel.
    fallback: bool,
    /// Friction coefficient of the current solve.
    mu: f64,
    /// The coarse level of nested starts (built on first use).
    coarse: Option<CoarseLevel>,
    /// Coarse-level products of the nested starts since the start of the solve.
    coarse_products: CoarseProducts,
}

impl TangentialSolver {
    /// Tabulate A_xx, A_xy, A_yy (and A_xn, A_yn for K ≠ 0) for `grid` and plan the FFTs.
    pub fn new(grid: Grid, material: Material) -> Result<Self, ContactError> {
        Self::with_operator(FftTangentialInfluence::new(grid, &material)?)
    }
}

impl<T: TangentialInfluenceOperator> TangentialSolver<T> {
    /// A solver over any tangential influence operator (its grid and material are the
    /// problem's).
    pub fn with_operator(operator: T) -> Result<Self, ContactError> {
        positive("G", operator.material().g)?;
        let n = operator.grid().len();
        Ok(TangentialSolver {
            operator,
            px: vec![0.0; n],
            py: vec![0.0; n],
            sx: vec![0.0; n],
            sy: vec![0.0; n],
            bx: vec![0.0; n],
            by: vec![0.0; n],
            slipping: vec![false; n],
            bound: vec![0.0; n],
            has_previous: false,
            pn: vec![0.0; n],
            pn_previous: None,
            cnx: vec![0.0; n],
            cny: vec![0.0; n],
            products: 0,
            fallback: false,
            mu: 0.0,
            coarse: None,
            coarse_products: CoarseProducts::default(),
        })
    }

    /// The influence operator.
    pub fn operator(&self) -> &T {
        &self.operator
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        self.operator.grid()
    }

    /// Forget the previous tractions (the next solve starts from zero).
    pub fn reset(&mut self) {
        self.has_previous = false;
        self.px.fill(0.0);
        self.py.fill(0.0);
    }

    pub(super) fn check_len(&self, name: &'static str, found: usize) -> Result<(), ContactError> {
        self.operator.grid().check_len(name, found)
    }

    /// Use `pressure` as the previous step's pressure p_n' in the coupling term of the next
    /// [`Self::transient_step`] (K ≠ 0 only; by default the current pressure is used, i.e.
    /// the normal load is taken as quasi-steady).
    pub fn set_previous_pressure(&mut self, pressure: &[f64]) -> Result<(), ContactError> {
        self.check_len("previous pressure", pressure.len())?;
        self.pn_previous = Some(pressure.to_vec());
        Ok(())
    }

    /// Normal displacement difference caused by tangential tractions, u_n = A_nx p_x + A_ny p_y
    /// with A_nx = −A_xn, A_ny = −A_yn (references.md §C3.2) \[m\]; zero for K = 0. The normal problem
    /// of dissimilar bodies sees the gap h + u_n (used by [`crate::coupled`]).
    pub fn normal_displacement(
        &mut self,
        traction_x: &[f64],
        traction_y: &[f64],
        out: &mut [f64],
    ) -> Result<(), ContactError> {
        self.check_len("traction_x", traction_x.len())?;
        self.check_len("traction_y", traction_y.len())?;
        self.check_len("displacement", out.len())?;
        self.operator
            .normal_from_traction((traction_x, traction_y), out);
        Ok(())
    }

    /// Set the traction bound g = μ p_n and validate the inputs.
    fn set_bound(&mut self, pressure: &[f64], mu: f64) -> Result<f64, ContactError> {
        self.check_len("pressure", pressure.len())?;
        positive("mu", mu)?;
        let mut force = 0.0;
        for (g, &p) in self.bound.iter_mut().zip(pressure) {
            if !p.is_finite() || p < 0.0 {
                return Err(ContactError::InvalidParameter {
                    name: "pressure",
                    value: p,
                    reason: "pressures must be finite and non-negative",
                });
            }
            *g = mu * p;
            force += p;
        }
        self.pn.copy_from_slice(pressure);
        self.products = 0;
        self.coarse_products.levels.clear();
        self.mu = mu;
        self.fallback = false;
        let area = self.grid().element_area();
        if force <= 0.0 {
            return Err(ContactError::NoContact {
                reason: "the pressure is zero everywhere",
            });
        }
        Ok(mu * force * area)
    }

    /// Rigid part W of the shift for a motion.
    fn set_rigid(&mut self, delta_q: f64, c: Creepages, shift: (f64, f64)) {
        let g = *self.grid();
        for iy in 0..g.ny {
            let y = g.y(iy);
            for ix in 0..g.nx {
                let x = g.x(ix);
                let k = iy * g.nx + ix;
                self.bx[k] = delta_q * (c.xi - c.phi * y) + shift.0 + self.cnx[k];
                self.by[k] = delta_q * (c.eta + c.phi * x) + shift.1 + self.cny[k];
            }
        }
    }

    /// Solve the shift problem (Cattaneo–Mindlin) for the pressure `pressure` \[Pa\] from the
    /// unloaded state: S = W + A p.
    pub fn shift(
        &mut self,
        pressure: &[f64],
        mu: f64,
        load: ShiftLoad,
        options: &TangentialOptions,
    ) -> Result<TangentialSolution, ContactError> {
        options.validate()?;
        let limit = self.set_bound(pressure, mu)?;
        self.prepare_coupling(Coupling::Direct);
        match load {
            ShiftLoad::Shift { wx, wy } => {
                finite("shift_x", wx)?;
                finite("shift_y", wy)?;
                self.set_rigid(0.0, Creepages::default(), (wx, wy));
                let (its, res) = self.solve_current(TangentialKernel::Direct, options)?;
                Ok(self.solution(0.0, Creepages::default(), (wx, wy), its, 0, res))
            }
            ShiftLoad::Forces { fx, fy } => {
                let target = self.check_force_target(fx, fy, limit)?;
                let (param, its, newton, res) =
                    self.newton(target, limit, options, |s, p, opts| {
                        s.set_rigid(0.0, Creepages::default(), (p[0], p[1]));
                        s.solve_current(TangentialKernel::Direct, opts)
                    })?;
                Ok(self.solution(
                    0.0,
                    Creepages::default(),
                    (param[0], param[1]),
                    its,
                    newton,
                    res,
                ))
            }
        }
    }

    /// Solve steady rolling (δq = δx) for the pressure `pressure` \[Pa\].
    pub fn steady_rolling(
        &mut self,
        pressure: &[f64],
        mu: f64,
        load: RollingLoad,
        options: &TangentialOptions,
    ) -> Result<TangentialSolution, ContactError> {
        options.validate()?;
        let limit = self.set_bound(pressure, mu)?;
        self.operator.prepare(TangentialKernel::Steady);
        self.prepare_coupling(Coupling::Steady);
        let dq = self.grid().dx;
        match load {
            RollingLoad::Creepages(c) => {
                c.validate()?;
                self.set_rigid(dq, c, (0.0, 0.0));
                let (its, res) = self.solve_steady(c, options)?;
                Ok(self.solution(dq, c, (0.0, 0.0), its, 0, res))
            }
            RollingLoad::Forces { fx, fy, phi } => {
                finite("spin", phi)?;
                let target = self.check_force_target(fx, fy, limit)?;
                let (param, its, newton, res) =
                    self.newton(target, limit, options, |s, p, opts| {
                        let c = Creepages {
                            xi: p[0],
                            eta: p[1],
                            phi,
                        };
                        s.set_rigid(dq, c, (0.0, 0.0));
                        s.solve_steady(c, opts)
                    })?;
                let c = Creepages {
                    xi: param[0],
                    eta: param[1],
                    phi,
                };
                Ok(self.solution(dq, c, (0.0, 0.0), its, newton, res))
            }
        }
    }

    /// One transient rolling step (references.md §C3.5, T = 2): the contact has moved `motion.delta_q`
    /// \[m\] in +x since the step whose tractions were `previous` = (p_x', p_y') on this same
    /// (moving) grid; S = W + A p − A_v(δq) p'. With `delta_q = 0` this is a shift step from a
    /// loaded state (T = 1 sequences). A time-stepping caller passes the tractions of the
    /// previous [`TangentialSolution`] each step (zeros for the first one).
    pub fn transient_step(
        &mut self,
        pressure: &[f64],
        mu: f64,
        previous: (&[f64], &[f64]),
        motion: StepMotion,
        options: &TangentialOptions,
    ) -> Result<TangentialSolution, ContactError> {
        options.validate()?;
        self.set_bound(pressure, mu)?;
        self.check_len("previous traction_x", previous.0.len())?;
        self.check_len("previous traction_y", previous.1.len())?;
        finite("delta_q", motion.delta_q)?;
        if motion.delta_q < 0.0 {
            return Err(ContactError::InvalidParameter {
                name: "delta_q",
                value: motion.delta_q,
                reason: "the distance rolled per step cannot be negative",
            });
        }
        motion.creepages.validate()?;
        finite("shift_x", motion.shift.0)?;
        finite("shift_y", motion.shift.1)?;
        if motion.delta_q > 0.0 {
            self.operator
                .prepare(TangentialKernel::Shifted(motion.delta_q));
            self.prepare_coupling(Coupling::Shifted(motion.delta_q));
        } else {
            // A shift step: the pressure's own tangential displacement changes by
            // A_tn (p_n − p_n').
            self.prepare_coupling(Coupling::Direct);
            if let Some(prev) = &self.pn_previous
                && self.operator.material().k != 0.0
            {
                self.operator.pressure_product(
                    TangentialKernel::Direct,
                    Update::Subtract,
                    prev,
                    (&mut self.cnx, &mut self.cny),
                );
            }
            self.pn_previous = None;
        }
        self.set_rigid(motion.delta_q, motion.creepages, motion.shift);
        // b −= A_v p'  (A_v = A when δq = 0).
        self.subtract_previous(motion.delta_q, previous.0, previous.1);
        if !self.has_previous || !options.warm_start {
            self.px.copy_from_slice(previous.0);
            self.py.copy_from_slice(previous.1);
            self.has_previous = true;
        }
        let (its, res) = self.solve_current(TangentialKernel::Direct, options)?;
        Ok(self.solution(motion.delta_q, motion.creepages, motion.shift, its, 0, res))
    }

    /// A transient rolling step (as [`Self::transient_step`]) with the total tangential forces
    /// F_x, F_y \[N\] prescribed and the spin φ [1/m] given: Newton's method finds the creepages
    /// ξ, η of the step (CONTACT's T = 2 with forces prescribed, e.g. the Cattaneo → Carter
    /// transient of references.md §C4.4). `delta_q` must be positive.
    #[allow(clippy::too_many_arguments)]
    pub fn transient_step_forces(
        &mut self,
        pressure: &[f64],
        mu: f64,
        previous: (&[f64], &[f64]),
        delta_q: f64,
        forces: (f64, f64),
        phi: f64,
        options: &TangentialOptions,
    ) -> Result<TangentialSolution, ContactError> {
        options.validate()?;
        let limit = self.set_bound(pressure, mu)?;
        self.check_len("previous traction_x", previous.0.len())?;
        self.check_len("previous traction_y", previous.1.len())?;
        positive("delta_q", delta_q)?;
        finite("spin", phi)?;
        let target = self.check_force_target(forces.0, forces.1, limit)?;
        self.operator.prepare(TangentialKernel::Shifted(delta_q));
        self.prepare_coupling(Coupling::Shifted(delta_q));
        let (prev_x, prev_y) = (previous.0.to_vec(), previous.1.to_vec());
        let (param, its, newton, res) = self.newton(target, limit, options, |s, p, opts| {
            let c = Creepages {
                xi: p[0],
                eta: p[1],
                phi,
            };
            s.set_rigid(delta_q, c, (0.0, 0.0));
            s.subtract_previous(delta_q, &prev_x, &prev_y);
            s.solve_current(TangentialKernel::Direct, opts)
        })?;
        let c = Creepages {
            xi: param[0],
            eta: param[1],
            phi,
        };
        Ok(self.solution(delta_q, c, (0.0, 0.0), its, newton, res))
    }

    /// Steady rolling with the current b and bound by the chosen solver; the Newton–Krylov
    /// solver falls back to Gauss–Seidel from where it stopped when it does not converge.
    /// A cold start (no previous solution) of the Newton–Krylov solver first solves the case
    /// (creepages `c`) on the coarse grid ([`TangentialOptions::nested_start`]).
    fn solve_steady(
        &mut self,
        c: Creepages,
        options: &TangentialOptions,
    ) -> Result<(usize, f64), ContactError> {
        if !options.warm_start || !self.has_previous {
            // A cold solve starts from zero, whatever an earlier solve left in px, py.
            self.px.fill(0.0);
            self.py.fill(0.0);
            self.has_previous = false;
        }
        if options.steady_solver == SteadySolver::NewtonKrylov {
            if options.nested_start
                && !self.has_previous
                && let Some(coarse) = self.nested_start(c, options)
            {
                self.coarse_products.add(&coarse);
                // The prolonged tractions are the start.
                self.has_previous = true;
            }
            match self.solve_steady_nk(options) {
                Ok(r) => return Ok((r.newton, r.change)),
                Err(r) => {
                    self.fallback = true;
                    let (its, res) = self.solve_current(TangentialKernel::Steady, options)?;
                    return Ok((r.newton + its, res));
                }
            }
        }
        self.solve_current(TangentialKernel::Steady, options)
    }

    /// b ← b − A_v(δq) p' (A_v(0) = A), the previous tractions' contribution to S.
    fn subtract_previous(&mut self, delta_q: f64, qx: &[f64], qy: &[f64]) {
        let kernel = if delta_q > 0.0 {
            TangentialKernel::Shifted(delta_q)
        } else {
            TangentialKernel::Direct
        };
        self.operator.traction_product(
            kernel,
            Update::Subtract,
            (qx, qy),
            (&mut self.bx, &mut self.by),
        );
    }
}
