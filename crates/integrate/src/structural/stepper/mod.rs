//! The structural stepper: state, explicit steps, the implicit step equation, Newton's method,
//! the corrector and the dense output.
//!
//! * `mod.rs`: the stepper state, construction, restart and the step dispatch;
//! * `explicit`: the explicit steps (Störmer–Verlet, leapfrog, explicit Newmark);
//! * `implicit`: the implicit step equation, Newton's method and the corrector;
//! * `frozen`: DOFs frozen at rest, left out of the implicit step's work;
//! * `accessors`: the state accessors and the dense output.

mod accessors;
mod explicit;
mod frozen;
mod implicit;

pub use implicit::NewtonOptions;

use faer::Mat;

use super::linalg::{check_matrix, check_vector};
use super::sparse::{SparseMatrix, sparse_from_dense, sparse_mul_add};
use super::{StepEquation, StructuralMethod, StructuralSystem};
use crate::lu::DenseLu;
use crate::{IntegrateError, Stats};

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
    /// Compressed-row copies of `M` and `C` for the products of a step (O(nnz)).
    mass_sparse: SparseMatrix,
    damping_sparse: Option<SparseMatrix>,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// The start acceleration of the previous step (`a_{n−1}`, shifted if the step changed)
    /// and the size of the step that produced `a_n` (implicit methods; `None` after a
    /// (re)start).
    a_prev: Vec<f64>,
    dt_prev: Option<f64>,
    /// The DOFs frozen at rest ([`freeze`](Self::freeze)), as sorted, disjoint ranges.
    frozen: Vec<std::ops::Range<usize>>,
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
        self.restart_state(problem, t, q, v)?;
        self.consistent_acceleration(problem)
    }

    /// The common part of the restarts: checks the arguments, evaluates the internal force at
    /// `q` and sets `(t, q, v)`, clearing the step history (not the acceleration).
    fn restart_state<P: StructuralSystem + ?Sized>(
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
        self.frozen.clear();
        Ok(())
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
        check_vector("a", a, self.q.len())?;
        self.restart_state(problem, t, q, v)?;
        self.a.copy_from_slice(a);
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
        if let Some(c) = &self.damping_sparse {
            sparse_mul_add(c.as_ref(), -1.0, &self.v, &mut w.residual);
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
            mass_sparse: sparse_from_dense(mass.as_ref()),
            damping_sparse: damping.as_ref().map(|c| sparse_from_dense(c.as_ref())),
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
            frozen: Vec::new(),
            f_int,
            last_step: None,
            q_old: q0.to_vec(),
            v_old: v0.to_vec(),
            stats,
            work: Workspace::new(n),
        })
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
