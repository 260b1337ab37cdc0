//! The structural stepper: state, explicit steps, the implicit step equation, Newton's method,
//! the corrector and the dense output.

use faer::{Mat, MatRef};

use super::linalg::{check_matrix, check_vector, mat_vec_add, norm_inf};
use super::{StepEquation, StructuralMethod, StructuralSystem};
use crate::lu::DenseLu;
use crate::{IntegrateError, Stats};

/// Stopping rule of the Newton iteration on the step equation.
///
/// The iteration stops when the correction satisfies `‖Δq‖_∞ ≤ atol + rtol·‖q_{n+1}‖_∞`
/// (Newton converges quadratically, so the remaining error is far below that bound).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Maximum number of Newton iterations per step (≥ 1).
    pub max_iterations: usize,
    /// Relative tolerance `rtol` on the displacement correction (> 0).
    pub relative_tolerance: f64,
    /// Absolute tolerance `atol` on the displacement correction, in displacement units (≥ 0).
    pub absolute_tolerance: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            max_iterations: 25,
            relative_tolerance: 1e-10,
            absolute_tolerance: 1e-14,
        }
    }
}

impl NewtonOptions {
    fn validate(&self) -> Result<(), IntegrateError> {
        let bad = |name, reason| Err(IntegrateError::InvalidParameter { name, reason });
        if self.max_iterations == 0 {
            return bad("max_iterations", "0 (must be ≥ 1)".to_string());
        }
        if !(self.relative_tolerance.is_finite() && self.relative_tolerance > 0.0) {
            return bad(
                "relative_tolerance",
                format!("{} (must be finite and > 0)", self.relative_tolerance),
            );
        }
        if !(self.absolute_tolerance.is_finite() && self.absolute_tolerance >= 0.0) {
            return bad(
                "absolute_tolerance",
                format!("{} (must be finite and ≥ 0)", self.absolute_tolerance),
            );
        }
        Ok(())
    }
}

/// Kinematic coefficients of one implicit step (module documentation of
/// [`structural`](super)): `q̃ = q_n + Δt v_n + q_a a_n`, `ṽ = v_n + v_a a_n`,
/// `q_{n+1} = q̃ + c_qa a_{n+1}`, `v_{n+1} = ṽ + c_va a_{n+1}`.
#[derive(Debug, Clone, Copy)]
struct Kinematics {
    q_a: f64,
    v_a: f64,
    c_qa: f64,
    c_va: f64,
    alpha_m: f64,
    alpha_f: f64,
    /// Step-change correction of the start acceleration, `(α_m − α_f)(Δt − Δt_prev)/Δt_prev`
    /// (0 for a constant step, for Newmark and for backward Euler).
    a_shift: f64,
}

/// Preallocated buffers of the stepper (no allocation per step for linear problems).
struct Workspace {
    eq: StepEquation,
    f_ext: Vec<f64>,
    f_int: Vec<f64>,
    residual: Vec<f64>,
    q_iter: Vec<f64>,
    q_fd: Vec<f64>,
    f_fd: Vec<f64>,
    half: Vec<f64>,
    tangent: Mat<f64>,
    k_eff: Mat<f64>,
    /// The tangent of a linear problem, evaluated once.
    tangent_valid: bool,
    /// LU of `K_eff`, and the step size it was built for if it may be reused (linear
    /// problems only).
    implicit_lu: DenseLu<f64>,
    implicit_lu_dt: Option<f64>,
    /// LU of `M + c C`, and the coefficient `c` it was built for (explicit methods).
    explicit_lu: DenseLu<f64>,
    explicit_lu_c: Option<f64>,
}

impl Workspace {
    fn new(n: usize) -> Self {
        Self {
            eq: StepEquation::default(),
            f_ext: vec![0.0; n],
            f_int: vec![0.0; n],
            residual: vec![0.0; n],
            q_iter: vec![0.0; n],
            q_fd: vec![0.0; n],
            f_fd: vec![0.0; n],
            half: vec![0.0; n],
            tangent: Mat::zeros(n, n),
            k_eff: Mat::zeros(n, n),
            tangent_valid: false,
            implicit_lu: DenseLu::new(n),
            implicit_lu_dt: None,
            explicit_lu: DenseLu::new(n),
            explicit_lu_c: None,
        }
    }
}

/// Integrates a [`StructuralSystem`] one step at a time with a [`StructuralMethod`].
///
/// State: `t_n`, `q_n`, `v_n`, `a_n` (and `f_int(q_n)` for the α-weighted schemes).
/// `M` and `C` are copied from the problem when the stepper is created (they are constant).
/// For the implicit methods, [`step_equation`](Self::step_equation) and
/// [`finish_step`](Self::finish_step) let an outside solver take the step; [`step`](Self::step)
/// does it with Newton's method on the same equation.
///
/// Pass the same problem to every call: for a linear problem the tangent and the factorised
/// effective matrix are cached across steps.
pub struct StructuralStepper {
    method: StructuralMethod,
    newton: NewtonOptions,
    mass: Mat<f64>,
    /// LU of `M` with a unit diagonal in the massless rows (so it factorises; those rows of
    /// the solve are discarded).
    mass_lu: DenseLu<f64>,
    /// The massless DOFs: row and column of `M` entirely zero.
    massless: Vec<usize>,
    damping: Option<Mat<f64>>,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// The start acceleration of the previous step (`a_{n−1}`, shifted if the step changed)
    /// and the size of the step that produced `a_n` (implicit methods; `None` after a
    /// (re)start).
    a_prev: Vec<f64>,
    dt_prev: Option<f64>,
    f_int: Vec<f64>,
    last_step: Option<(f64, f64)>,
    q_old: Vec<f64>,
    v_old: Vec<f64>,
    stats: Stats,
    work: Workspace,
}

impl std::fmt::Debug for StructuralStepper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StructuralStepper")
            .field("method", &self.method)
            .field("t", &self.t)
            .field("q", &self.q)
            .field("v", &self.v)
            .field("a", &self.a)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl StructuralStepper {
    /// Creates a stepper at `(t0, q0, v0)` with the consistent initial acceleration
    /// `a₀ = M⁻¹(f_ext(t₀) − C v₀ − f_int(q₀))` (references.md §D3.5, start-up).
    ///
    /// # Massless DOFs
    /// A DOF whose row and column of `M` are entirely zero is *massless* (e.g. a massless
    /// wheel or the end node of a spring–damper): its balance row `C v + f_int = f_ext` has no
    /// inertia and is closed by the damping, stiffness or a constraint of the caller. Only the
    /// implicit methods accept massless DOFs (an explicit method needs `M⁻¹`); their step
    /// equation then has zero inertia in those rows (the history force holds only the
    /// α_f-weighted elastic and damping forces). `M⁻¹` above is taken over the massive DOFs;
    /// the start acceleration of a massless DOF is set to 0 — give the true one with
    /// [`restart_with_acceleration`](Self::restart_with_acceleration) where the method uses it
    /// (HHT, generalized-α; the trapezoidal rule's displacement update does not depend on it).
    pub fn new<P: StructuralSystem + ?Sized>(
        method: StructuralMethod,
        problem: &mut P,
        t0: f64,
        q0: &[f64],
        v0: &[f64],
    ) -> Result<Self, IntegrateError> {
        let mut stepper = Self::assemble(method, problem, t0, q0, v0)?;
        stepper.consistent_acceleration(problem)?;
        Ok(stepper)
    }

    /// Restarts at `(t, q, v)` with the consistent acceleration (e.g. after a discontinuity of
    /// the load or of the model). Statistics, options and factorisations are kept; the dense
    /// output is cleared. Invalid arguments leave the stepper unchanged; a non-finite force
    /// (`NonFinite`) leaves it half-restarted, to be restarted again.
    pub fn restart<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        t: f64,
        q: &[f64],
        v: &[f64],
    ) -> Result<(), IntegrateError> {
        self.check_problem(problem)?;
        check_time("t", t)?;
        check_vector("q", q, self.q.len())?;
        check_vector("v", v, self.q.len())?;
        let f_int = &mut self.work.f_int;
        problem.internal_force(q, f_int);
        self.stats.f_evals += 1;
        finite_or_error(f_int, t)?;
        self.f_int.copy_from_slice(f_int);
        self.t = t;
        self.q.copy_from_slice(q);
        self.v.copy_from_slice(v);
        self.last_step = None;
        self.dt_prev = None;
        self.consistent_acceleration(problem)
    }

    /// Restarts at `(t, q, v)` with the given acceleration `a` instead of the consistent one
    /// (for a system with massless DOFs whose acceleration the caller knows, e.g. from a
    /// constraint, or to continue from another integrator's state). Statistics, options and
    /// factorisations are kept; the dense output is cleared. Invalid arguments leave the
    /// stepper unchanged.
    pub fn restart_with_acceleration<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        t: f64,
        q: &[f64],
        v: &[f64],
        a: &[f64],
    ) -> Result<(), IntegrateError> {
        self.check_problem(problem)?;
        check_time("t", t)?;
        check_vector("q", q, self.q.len())?;
        check_vector("v", v, self.q.len())?;
        check_vector("a", a, self.q.len())?;
        let f_int = &mut self.work.f_int;
        problem.internal_force(q, f_int);
        self.stats.f_evals += 1;
        finite_or_error(f_int, t)?;
        self.f_int.copy_from_slice(f_int);
        self.t = t;
        self.q.copy_from_slice(q);
        self.v.copy_from_slice(v);
        self.a.copy_from_slice(a);
        self.last_step = None;
        self.dt_prev = None;
        Ok(())
    }

    /// The massless DOFs (row and column of `M` entirely zero), in increasing order.
    pub fn massless_dofs(&self) -> &[usize] {
        &self.massless
    }

    /// `a = M⁻¹(f_ext(t) − C v − f_int(q))` at the current state (references.md §D3.5, start-up),
    /// with `f_int(q)` already in `self.f_int`.
    fn consistent_acceleration<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
    ) -> Result<(), IntegrateError> {
        let w = &mut self.work;
        problem.external_force(self.t, &mut w.f_ext);
        for ((r, fe), fi) in w.residual.iter_mut().zip(&w.f_ext).zip(&self.f_int) {
            *r = fe - fi;
        }
        if let Some(c) = &self.damping {
            mat_vec_add(c.as_ref(), -1.0, &self.v, &mut w.residual);
        }
        self.mass_lu.solve_in_place(&mut w.residual);
        for &i in &self.massless {
            w.residual[i] = 0.0;
        }
        finite_or_error(&w.residual, self.t)?;
        self.a.copy_from_slice(&w.residual);
        Ok(())
    }

    /// Creates a stepper at `(t0, q0, v0)` with a given initial acceleration `a0` (which need
    /// not satisfy the balance equation; used to build amplification matrices).
    pub fn with_initial_acceleration<P: StructuralSystem + ?Sized>(
        method: StructuralMethod,
        problem: &mut P,
        t0: f64,
        q0: &[f64],
        v0: &[f64],
        a0: &[f64],
    ) -> Result<Self, IntegrateError> {
        let mut stepper = Self::assemble(method, problem, t0, q0, v0)?;
        check_vector("a0", a0, q0.len())?;
        stepper.a.copy_from_slice(a0);
        Ok(stepper)
    }

    /// Validates the method, the matrices and the initial state, factorises `M` and
    /// evaluates `f_int(q₀)`.
    fn assemble<P: StructuralSystem + ?Sized>(
        method: StructuralMethod,
        problem: &mut P,
        t0: f64,
        q0: &[f64],
        v0: &[f64],
    ) -> Result<Self, IntegrateError> {
        method.validate()?;
        let n = problem.dimension();
        if n == 0 {
            return Err(IntegrateError::InvalidParameter {
                name: "dimension",
                reason: "0 degrees of freedom".to_string(),
            });
        }
        check_time("t0", t0)?;
        check_vector("q0", q0, n)?;
        check_vector("v0", v0, n)?;
        let mass = problem.mass_matrix().to_owned();
        check_matrix("mass", mass.as_ref(), n)?;
        let massless: Vec<usize> = (0..n)
            .filter(|&i| (0..n).all(|j| mass[(i, j)] == 0.0 && mass[(j, i)] == 0.0))
            .collect();
        if let Some(i) = (0..n).find(|&i| mass[(i, i)] <= 0.0 && !massless.contains(&i)) {
            return Err(IntegrateError::InvalidParameter {
                name: "mass",
                reason: format!(
                    "diagonal entry {i} is {} (must be > 0, or row and column {i} entirely 0 for a massless DOF)",
                    mass[(i, i)]
                ),
            });
        }
        if let (Some(&i), true) = (massless.first(), method.is_explicit()) {
            return Err(IntegrateError::InvalidParameter {
                name: "mass",
                reason: format!(
                    "DOF {i} is massless (row and column of M are 0): the explicit method `{}` needs a nonsingular M; use an implicit method (newmark, hht, generalized_alpha, backward_euler)",
                    method.name()
                ),
            });
        }
        let damping = problem.damping_matrix().map(|c| c.to_owned());
        if let Some(c) = &damping {
            check_matrix("damping", c.as_ref(), n)?;
        }
        let mut mass_lu = DenseLu::new(n);
        if massless.is_empty() {
            mass_lu.factorize(mass.as_ref(), t0)?;
        } else {
            let mut regular = mass.clone();
            for &i in &massless {
                regular[(i, i)] = 1.0;
            }
            mass_lu.factorize(regular.as_ref(), t0)?;
        }
        let mut stats = Stats {
            lu_decompositions: 1,
            f_evals: 1,
            ..Stats::default()
        };
        let mut f_int = vec![0.0; n];
        problem.internal_force(q0, &mut f_int);
        if f_int.iter().any(|f| !f.is_finite()) {
            return Err(IntegrateError::NonFinite { t: t0 });
        }
        stats.steps = 0;
        Ok(Self {
            method,
            newton: NewtonOptions::default(),
            mass,
            mass_lu,
            massless,
            damping,
            t: t0,
            q: q0.to_vec(),
            v: v0.to_vec(),
            a: vec![0.0; n],
            a_prev: vec![0.0; n],
            dt_prev: None,
            f_int,
            last_step: None,
            q_old: q0.to_vec(),
            v_old: v0.to_vec(),
            stats,
            work: Workspace::new(n),
        })
    }

    /// Replaces the Newton stopping rule (validated).
    pub fn set_newton_options(&mut self, options: NewtonOptions) -> Result<(), IntegrateError> {
        options.validate()?;
        self.newton = options;
        Ok(())
    }

    /// The Newton stopping rule in use.
    pub fn newton_options(&self) -> NewtonOptions {
        self.newton
    }

    /// The method.
    pub fn method(&self) -> StructuralMethod {
        self.method
    }

    /// Number of degrees of freedom.
    pub fn dimension(&self) -> usize {
        self.q.len()
    }

    /// Current time `t_n`.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current displacement `q_n`.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// Current velocity `v_n`.
    pub fn v(&self) -> &[f64] {
        &self.v
    }

    /// Current acceleration `a_n` (the scheme's acceleration variable; for HHT and
    /// generalized-α it satisfies the balance only in the α-weighted sense).
    pub fn a(&self) -> &[f64] {
        &self.a
    }

    /// The mass matrix `M` copied from the problem.
    pub fn mass(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }

    /// The damping matrix `C` copied from the problem, if any.
    pub fn damping(&self) -> Option<MatRef<'_, f64>> {
        self.damping.as_ref().map(|c| c.as_ref())
    }

    /// Counters: steps, force evaluations (calls of `internal_force`, including those of
    /// finite-difference tangents), tangent evaluations, LU factorisations, Newton iterations.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Takes one step of size `dt` with the built-in solver (explicit update, or Newton's
    /// method on [`step_equation`](Self::step_equation) followed by
    /// [`finish_step`](Self::finish_step)). On error the state is unchanged.
    pub fn step<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
    ) -> Result<(), IntegrateError> {
        check_step_size(dt)?;
        self.check_problem(problem)?;
        match self.method {
            StructuralMethod::StormerVerlet => self.kick_drift_kick(problem, dt, true),
            StructuralMethod::Leapfrog => self.kick_drift_kick(problem, dt, false),
            StructuralMethod::Newmark { beta: 0.0, gamma } => {
                self.explicit_newmark(problem, dt, gamma)
            }
            _ => self.implicit_step(problem, dt),
        }
    }

    fn check_problem<P: StructuralSystem + ?Sized>(
        &self,
        problem: &P,
    ) -> Result<(), IntegrateError> {
        if problem.dimension() != self.q.len() {
            return Err(IntegrateError::InvalidParameter {
                name: "problem",
                reason: format!(
                    "dimension {} (the stepper has {})",
                    problem.dimension(),
                    self.q.len()
                ),
            });
        }
        Ok(())
    }

    /// Saves `(t_n, q_n, v_n)` for the dense output before the state is overwritten.
    fn save_old_state(&mut self, dt: f64) {
        self.q_old.copy_from_slice(&self.q);
        self.v_old.copy_from_slice(&self.v);
        self.last_step = Some((self.t, dt));
    }

    /// Störmer–Verlet (`implicit_damping = true`) or leapfrog (`false`), see
    /// [`StructuralMethod::StormerVerlet`] and [`StructuralMethod::Leapfrog`].
    fn kick_drift_kick<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
        implicit_damping: bool,
    ) -> Result<(), IntegrateError> {
        let t_new = self.t + dt;
        let w = &mut self.work;
        for (i, half) in w.half.iter_mut().enumerate() {
            *half = self.v[i] + 0.5 * dt * self.a[i];
            w.q_iter[i] = self.q[i] + dt * *half;
        }
        let c = if implicit_damping { 0.5 * dt } else { 0.0 };
        self.explicit_acceleration(problem, t_new, c)?;
        self.save_old_state(dt);
        for i in 0..self.q.len() {
            self.q[i] = self.work.q_iter[i];
            self.a[i] = self.work.residual[i];
            self.v[i] = self.work.half[i] + 0.5 * dt * self.a[i];
        }
        self.f_int.copy_from_slice(&self.work.f_int);
        self.t = t_new;
        self.stats.steps += 1;
        Ok(())
    }

    /// Explicit Newmark (β = 0): `q_{n+1} = q_n + Δt v_n + ½Δt² a_n`,
    /// `(M + γΔt C) a_{n+1} = f_ext(t_{n+1}) − f_int(q_{n+1}) − C ṽ`,
    /// `v_{n+1} = ṽ + γΔt a_{n+1}` with `ṽ = v_n + (1 − γ)Δt a_n` (Newmark 1959).
    fn explicit_newmark<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
        gamma: f64,
    ) -> Result<(), IntegrateError> {
        let t_new = self.t + dt;
        for i in 0..self.q.len() {
            self.work.q_iter[i] = self.q[i] + dt * self.v[i] + 0.5 * dt * dt * self.a[i];
            self.work.half[i] = self.v[i] + (1.0 - gamma) * dt * self.a[i];
        }
        self.explicit_acceleration(problem, t_new, gamma * dt)?;
        self.save_old_state(dt);
        for i in 0..self.q.len() {
            self.q[i] = self.work.q_iter[i];
            self.a[i] = self.work.residual[i];
            self.v[i] = self.work.half[i] + gamma * dt * self.a[i];
        }
        self.f_int.copy_from_slice(&self.work.f_int);
        self.t = t_new;
        self.stats.steps += 1;
        Ok(())
    }

    /// Solves `(M + c C) a = f_ext(t) − f_int(q) − C v` with `q = work.q_iter`,
    /// `v = work.half`; the result is left in `work.residual`, `f_int(q)` in `work.f_int`.
    fn explicit_acceleration<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        t: f64,
        c: f64,
    ) -> Result<(), IntegrateError> {
        let w = &mut self.work;
        problem.external_force(t, &mut w.f_ext);
        problem.internal_force(&w.q_iter, &mut w.f_int);
        self.stats.f_evals += 1;
        for i in 0..w.residual.len() {
            w.residual[i] = w.f_ext[i] - w.f_int[i];
        }
        let Some(damping) = &self.damping else {
            self.mass_lu.solve_in_place(&mut w.residual);
            return finite_or_error(&w.residual, t);
        };
        mat_vec_add(damping.as_ref(), -1.0, &w.half, &mut w.residual);
        if c == 0.0 {
            self.mass_lu.solve_in_place(&mut w.residual);
            return finite_or_error(&w.residual, t);
        }
        if w.explicit_lu_c != Some(c) {
            let n = self.q.len();
            for j in 0..n {
                for i in 0..n {
                    w.k_eff[(i, j)] = self.mass[(i, j)] + c * damping[(i, j)];
                }
            }
            w.explicit_lu_c = None;
            w.explicit_lu.factorize(w.k_eff.as_ref(), t)?;
            w.explicit_lu_c = Some(c);
            self.stats.lu_decompositions += 1;
        }
        w.explicit_lu.solve_in_place(&mut w.residual);
        finite_or_error(&w.residual, t)
    }

    /// The kinematic coefficients of the implicit scheme for step size `dt`.
    fn kinematics(&self, dt: f64) -> Result<Kinematics, IntegrateError> {
        if let Some(p) = self.method.alpha_parameters()
            && p.beta > 0.0
        {
            let a_shift = match self.dt_prev {
                Some(h) if h != dt && (0.5..=2.0).contains(&(dt / h)) => {
                    (p.alpha_m - p.alpha_f) * (dt - h) / h
                }
                _ => 0.0,
            };
            return Ok(Kinematics {
                q_a: dt * dt * (0.5 - p.beta),
                v_a: dt * (1.0 - p.gamma),
                c_qa: p.beta * dt * dt,
                c_va: p.gamma * dt,
                alpha_m: p.alpha_m,
                alpha_f: p.alpha_f,
                a_shift,
            });
        }
        if self.method == StructuralMethod::BackwardEuler {
            return Ok(Kinematics {
                q_a: 0.0,
                v_a: 0.0,
                c_qa: dt * dt,
                c_va: dt,
                alpha_m: 0.0,
                alpha_f: 0.0,
                a_shift: 0.0,
            });
        }
        Err(IntegrateError::InvalidParameter {
            name: "method",
            reason: format!(
                "`{}` is explicit and has no implicit step equation",
                self.method.name()
            ),
        })
    }

    /// The start acceleration of entry `i`. The algorithmic acceleration of HHT and
    /// generalized-α approximates `q''(t_n + (α_m − α_f)Δt)` (Erlicher, Bonaventura & Bursi
    /// 2002, *Comput. Mech.* 28:83–104), so after a step-size change it is moved to the new
    /// shift with the slope `(a_n − a*_{n−1})/Δt_prev`, where `a*_{n−1}` is the start
    /// acceleration of the previous step (so both ends carry the same shift):
    /// `a*_n = a_n + (α_m − α_f)(Δt − Δt_prev)(a_n − a*_{n−1})/Δt_prev`. Without this the
    /// methods drop to first order when Δt varies (measured in `tests/structural_order.rs`).
    /// The extrapolation is applied only for step ratios `Δt/Δt_prev ∈ [½, 2]`: for larger
    /// jumps it amplified stiff components (measured: gen-α ρ∞ = 0.5 became unstable under
    /// repeated 10× changes), so such a step starts from `a_n` unchanged, which costs O(Δt)
    /// in `a` at that step only.
    fn start_acceleration(&self, k: &Kinematics, i: usize) -> f64 {
        if k.a_shift == 0.0 {
            self.a[i]
        } else {
            self.a[i] + k.a_shift * (self.a[i] - self.a_prev[i])
        }
    }

    /// The predictors `(q̃_i, ṽ_i)` of entry `i`.
    fn predict(&self, k: &Kinematics, dt: f64, i: usize) -> (f64, f64) {
        let a = self.start_acceleration(k, i);
        (
            self.q[i] + dt * self.v[i] + k.q_a * a,
            self.v[i] + k.v_a * a,
        )
    }

    /// The step equation of the step `t_n → t_n + dt` (see [`StepEquation`]). Only for the
    /// implicit methods (Newmark with β > 0, HHT, generalized-α, backward Euler).
    pub fn step_equation(&self, dt: f64) -> Result<StepEquation, IntegrateError> {
        let mut eq = StepEquation::default();
        self.step_equation_into(dt, &mut eq)?;
        Ok(eq)
    }

    /// As [`step_equation`](Self::step_equation), writing into `eq` (its vectors are reused, so
    /// no allocation after the first call).
    pub fn step_equation_into(&self, dt: f64, eq: &mut StepEquation) -> Result<(), IntegrateError> {
        check_step_size(dt)?;
        let k = self.kinematics(dt)?;
        let n = self.q.len();
        eq.t_old = self.t;
        eq.dt = dt;
        eq.t_new = self.t + dt;
        eq.t_force = eq.t_new - k.alpha_f * dt;
        eq.q_pred.resize(n, 0.0);
        eq.v_pred.resize(n, 0.0);
        eq.history_force.resize(n, 0.0);
        for i in 0..n {
            (eq.q_pred[i], eq.v_pred[i]) = self.predict(&k, dt, i);
            let inertia: f64 = (0..n)
                .map(|j| self.mass[(i, j)] * self.start_acceleration(&k, j))
                .sum();
            eq.history_force[i] = k.alpha_m * inertia + k.alpha_f * self.f_int[i];
        }
        if let Some(c) = &self.damping {
            mat_vec_add(c.as_ref(), k.alpha_f, &self.v, &mut eq.history_force);
        }
        eq.displacement_per_acceleration = k.c_qa;
        eq.velocity_per_acceleration = k.c_va;
        eq.alpha_m = k.alpha_m;
        eq.alpha_f = k.alpha_f;
        eq.mass_coefficient = (1.0 - k.alpha_m) / k.c_qa;
        eq.damping_coefficient = (1.0 - k.alpha_f) * k.c_va / k.c_qa;
        eq.stiffness_coefficient = 1.0 - k.alpha_f;
        Ok(())
    }

    /// The corrector of an implicit step: given the solution `q_{n+1}` of the step equation
    /// for step size `dt`, sets `a_{n+1} = (q_{n+1} − q̃)/c_qa`, `v_{n+1} = ṽ + c_va a_{n+1}`,
    /// advances `t` and, for α_f ≠ 0, evaluates `f_int(q_{n+1})` (needed by the next step's
    /// history force; this is why the problem is passed).
    pub fn finish_step<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
        q_new: &[f64],
    ) -> Result<(), IntegrateError> {
        check_step_size(dt)?;
        let k = self.kinematics(dt)?;
        check_vector("q_new", q_new, self.q.len())?;
        self.check_problem(problem)?;
        self.save_old_state(dt);
        for (i, &qn) in q_new.iter().enumerate() {
            let (q_pred, v_pred) = self.predict(&k, dt, i);
            self.a_prev[i] = self.start_acceleration(&k, i);
            self.a[i] = (qn - q_pred) / k.c_qa;
            self.v[i] = v_pred + k.c_va * self.a[i];
            self.q[i] = qn;
        }
        self.t += dt;
        self.dt_prev = Some(dt);
        if k.alpha_f != 0.0 {
            problem.internal_force(&self.q, &mut self.f_int);
            self.stats.f_evals += 1;
        }
        self.stats.steps += 1;
        Ok(())
    }

    fn implicit_step<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        dt: f64,
    ) -> Result<(), IntegrateError> {
        let mut eq = std::mem::take(&mut self.work.eq);
        let solved = self
            .step_equation_into(dt, &mut eq)
            .and_then(|()| self.newton_solve(problem, &eq));
        self.work.eq = eq;
        solved?;
        let q_new = std::mem::take(&mut self.work.q_iter);
        let finished = self.finish_step(problem, dt, &q_new);
        self.work.q_iter = q_new;
        finished
    }

    /// Newton's method on `R(q_{n+1}) = 0` from the guess `a_{n+1} = a_n`; the solution is
    /// left in `work.q_iter`. For a linear problem one step is exact.
    fn newton_solve<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        eq: &StepEquation,
    ) -> Result<(), IntegrateError> {
        let linear = problem.is_linear();
        problem.external_force(eq.t_force, &mut self.work.f_ext);
        for i in 0..self.q.len() {
            self.work.q_iter[i] = eq.q_pred[i] + eq.displacement_per_acceleration * self.a[i];
        }
        let mut residual_norm = f64::INFINITY;
        for _ in 0..self.newton.max_iterations {
            let w = &mut self.work;
            problem.internal_force(&w.q_iter, &mut w.f_int);
            self.stats.f_evals += 1;
            eq.residual(
                self.mass.as_ref(),
                self.damping.as_ref().map(|c| c.as_ref()),
                &w.q_iter,
                &w.f_int,
                &w.f_ext,
                &mut w.residual,
            )?;
            finite_or_error(&w.residual, eq.t_new)?;
            residual_norm = norm_inf(&w.residual);
            self.prepare_effective_matrix(problem, eq, linear)?;
            let w = &mut self.work;
            w.implicit_lu.solve_in_place(&mut w.residual);
            for (q, dq) in w.q_iter.iter_mut().zip(&w.residual) {
                *q -= dq;
            }
            finite_or_error(&w.q_iter, eq.t_new)?;
            self.stats.newton_iterations += 1;
            let tolerance = self.newton.absolute_tolerance
                + self.newton.relative_tolerance * norm_inf(&w.q_iter);
            if linear || norm_inf(&w.residual) <= tolerance {
                return Ok(());
            }
        }
        Err(IntegrateError::NewtonFailed {
            t: eq.t_new,
            iterations: self.newton.max_iterations,
            residual: residual_norm,
        })
    }

    /// Builds and factorises `K_eff` at `work.q_iter` (with `f_int(q_iter)` in `work.f_int`).
    /// For a linear problem the tangent is evaluated once and the LU reused while Δt is unchanged.
    fn prepare_effective_matrix<P: StructuralSystem + ?Sized>(
        &mut self,
        problem: &mut P,
        eq: &StepEquation,
        linear: bool,
    ) -> Result<(), IntegrateError> {
        let cached = self.work.implicit_lu_dt == Some(eq.dt);
        if linear && self.work.tangent_valid && cached {
            return Ok(());
        }
        if !(linear && self.work.tangent_valid) {
            self.evaluate_tangent(problem);
            self.work.tangent_valid = linear;
        }
        let w = &mut self.work;
        eq.effective_stiffness(
            self.mass.as_ref(),
            self.damping.as_ref().map(|c| c.as_ref()),
            w.tangent.as_ref(),
            w.k_eff.as_mut(),
        )?;
        w.implicit_lu_dt = None;
        w.implicit_lu.factorize(w.k_eff.as_ref(), eq.t_new)?;
        if linear {
            w.implicit_lu_dt = Some(eq.dt);
        }
        self.stats.lu_decompositions += 1;
        Ok(())
    }

    /// `K_t` at `work.q_iter` from the problem, or by forward differences
    /// `K_t e_j ≈ (f_int(q + h_j e_j) − f_int(q))/h_j`, `h_j = √ε · max(|q_j|, ‖q‖_∞, ‖q − q_n‖_∞)`.
    fn evaluate_tangent<P: StructuralSystem + ?Sized>(&mut self, problem: &mut P) {
        self.stats.jacobian_evals += 1;
        let w = &mut self.work;
        if problem.tangent_stiffness(&w.q_iter, w.tangent.as_mut()) {
            return;
        }
        let motion = w
            .q_iter
            .iter()
            .zip(&self.q)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        let scale = norm_inf(&w.q_iter).max(motion).max(f64::MIN_POSITIVE);
        w.q_fd.copy_from_slice(&w.q_iter);
        for j in 0..w.q_iter.len() {
            let q_j = w.q_iter[j];
            w.q_fd[j] = q_j + f64::EPSILON.sqrt() * q_j.abs().max(scale);
            let h = w.q_fd[j] - q_j;
            problem.internal_force(&w.q_fd, &mut w.f_fd);
            self.stats.f_evals += 1;
            for i in 0..w.f_fd.len() {
                w.tangent[(i, j)] = (w.f_fd[i] - w.f_int[i]) / h;
            }
            w.q_fd[j] = q_j;
        }
    }

    /// Cubic Hermite interpolation of the displacement over the last step, from `q` and `v` at
    /// both ends: `q(θ) = h₀₀ q_n + h₁₀ Δt v_n + h₀₁ q_{n+1} + h₁₁ Δt v_{n+1}`, θ = (t − t_n)/Δt.
    pub fn dense_output(&self, t: f64, q_out: &mut [f64]) -> Result<(), IntegrateError> {
        let (theta, dt) = self.dense_theta(t, q_out.len())?;
        let (t2, t3) = (theta * theta, theta * theta * theta);
        let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
        let h10 = t3 - 2.0 * t2 + theta;
        let h01 = -2.0 * t3 + 3.0 * t2;
        let h11 = t3 - t2;
        for (i, out) in q_out.iter_mut().enumerate() {
            *out = h00 * self.q_old[i]
                + h10 * dt * self.v_old[i]
                + h01 * self.q[i]
                + h11 * dt * self.v[i];
        }
        Ok(())
    }

    /// Time derivative of the [`dense_output`](Self::dense_output) Hermite cubic.
    pub fn dense_velocity(&self, t: f64, v_out: &mut [f64]) -> Result<(), IntegrateError> {
        let (theta, dt) = self.dense_theta(t, v_out.len())?;
        let t2 = theta * theta;
        let d00 = 6.0 * t2 - 6.0 * theta;
        let d10 = 3.0 * t2 - 4.0 * theta + 1.0;
        let d11 = 3.0 * t2 - 2.0 * theta;
        for (i, out) in v_out.iter_mut().enumerate() {
            *out = (d00 * (self.q_old[i] - self.q[i])) / dt + d10 * self.v_old[i] + d11 * self.v[i];
        }
        Ok(())
    }

    /// The last step `[t_n, t_{n+1}]`, if a step was taken.
    pub fn last_step_interval(&self) -> Option<(f64, f64)> {
        self.last_step.map(|(t0, dt)| (t0, t0 + dt))
    }

    fn dense_theta(&self, t: f64, len: usize) -> Result<(f64, f64), IntegrateError> {
        if len != self.q.len() {
            return Err(IntegrateError::InvalidParameter {
                name: "out",
                reason: format!("length {len} (expected {})", self.q.len()),
            });
        }
        let Some((t0, dt)) = self.last_step else {
            return Err(IntegrateError::InvalidParameter {
                name: "t",
                reason: "no step has been taken yet".to_string(),
            });
        };
        let theta = (t - t0) / dt;
        let slack = 1e-12;
        if !(theta.is_finite() && (-slack..=1.0 + slack).contains(&theta)) {
            return Err(IntegrateError::InvalidParameter {
                name: "t",
                reason: format!("{t} outside the last step [{t0}, {}]", t0 + dt),
            });
        }
        Ok((theta, dt))
    }
}

fn check_time(name: &'static str, t: f64) -> Result<(), IntegrateError> {
    if t.is_finite() {
        Ok(())
    } else {
        Err(IntegrateError::InvalidParameter {
            name,
            reason: format!("{t} (must be finite)"),
        })
    }
}

fn check_step_size(dt: f64) -> Result<(), IntegrateError> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(IntegrateError::InvalidParameter {
            name: "dt",
            reason: format!("{dt} (must be finite and > 0)"),
        })
    }
}

fn finite_or_error(x: &[f64], t: f64) -> Result<(), IntegrateError> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(IntegrateError::NonFinite { t })
    }
}
