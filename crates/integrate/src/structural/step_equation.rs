//! The nonlinear equation of one implicit step, in a form an outside solver can use.

use faer::sparse::SparseRowMatRef;
use faer::{MatMut, MatRef};

use std::ops::Range;

use super::sparse::{rows_outside, sparse_mul_add_rows, sparse_mul_add2_rows};

use crate::IntegrateError;

/// The equation of one implicit step `n → n+1`, with the displacement `q_{n+1}` as unknown
/// (module documentation of [`structural`](super); Chung & Hulbert 1993 for the α form):
///
/// ```text
/// a_{n+1} = (q_{n+1} − q̃)/c_qa,   v_{n+1} = ṽ + c_va · a_{n+1}
/// R(q_{n+1}) = (1−α_m) M a_{n+1} + (1−α_f) [C v_{n+1} + f_int(q_{n+1})] + h − f_ext(t_force) = 0
/// h = α_m M a_n + α_f [C v_n + f_int(q_n)]
/// ∂R/∂q_{n+1} = K_eff = c_M M + c_C C + c_K K_t
/// ```
///
/// An outside solver (the vehicle–bridge coupling of references.md §D4.2) adds its own forces to
/// `f_ext` (weighted consistently, e.g. `(1−α_f) F_{n+1} + α_f F_n`), solves `R = 0` for
/// `q_{n+1}` and hands it to [`StructuralStepper::finish_step`](super::StructuralStepper::finish_step).
/// For a linear structure, [`effective_load`](Self::effective_load) and
/// [`effective_stiffness`](Self::effective_stiffness) give the linear system `K_eff q_{n+1} = r`
/// directly.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StepEquation {
    /// `t_n`.
    pub t_old: f64,
    /// Step size Δt.
    pub dt: f64,
    /// `t_{n+1} = t_n + Δt`.
    pub t_new: f64,
    /// Time of the load, `t_{n+1−α_f} = t_{n+1} − α_f Δt`.
    pub t_force: f64,
    /// Displacement predictor `q̃` (`q_{n+1}` when `a_{n+1} = 0`).
    pub q_pred: Vec<f64>,
    /// Velocity predictor `ṽ`.
    pub v_pred: Vec<f64>,
    /// `c_qa` in `q_{n+1} = q̃ + c_qa a_{n+1}`: `βΔt²` (α family) or `Δt²` (backward Euler).
    pub displacement_per_acceleration: f64,
    /// `c_va` in `v_{n+1} = ṽ + c_va a_{n+1}`: `γΔt` (α family) or `Δt` (backward Euler).
    pub velocity_per_acceleration: f64,
    /// Inertia weight α_m of the old acceleration.
    pub alpha_m: f64,
    /// Force weight α_f of the old state (damping, internal and external forces).
    pub alpha_f: f64,
    /// History force `h = α_m M a_n + α_f [C v_n + f_int(q_n)]`.
    pub history_force: Vec<f64>,
    /// `c_M = (1 − α_m)/c_qa`.
    pub mass_coefficient: f64,
    /// `c_C = (1 − α_f) c_va/c_qa`.
    pub damping_coefficient: f64,
    /// `c_K = 1 − α_f`.
    pub stiffness_coefficient: f64,
    /// The DOFs frozen at rest ([`StructuralStepper::freeze`](super::StructuralStepper::freeze)),
    /// as sorted, disjoint ranges (empty: none): `q̃ = q_n`, `ṽ = 0`, and their rows of `h` and
    /// of [`effective_load_sparse`](Self::effective_load_sparse) are not evaluated (zero).
    pub frozen_rows: Vec<Range<usize>>,
}

impl StepEquation {
    /// Number of degrees of freedom `n`.
    pub fn dimension(&self) -> usize {
        self.q_pred.len()
    }

    /// Checks that a vector argument has length `n`.
    fn check_len(&self, name: &'static str, len: usize) -> Result<(), IntegrateError> {
        if len == self.dimension() {
            Ok(())
        } else {
            Err(IntegrateError::InvalidParameter {
                name,
                reason: format!("length {len} (expected {})", self.dimension()),
            })
        }
    }

    /// Checks that a matrix argument is `n × n`.
    fn check_shape(&self, name: &'static str, a: MatRef<'_, f64>) -> Result<(), IntegrateError> {
        let n = self.dimension();
        if a.nrows() == n && a.ncols() == n {
            Ok(())
        } else {
            Err(IntegrateError::InvalidParameter {
                name,
                reason: format!("shape {}x{} (expected {n}x{n})", a.nrows(), a.ncols()),
            })
        }
    }

    /// `a_{n+1} = (q_{n+1} − q̃)/c_qa` for entry `i`.
    ///
    /// # Panics
    /// If `i ≥ n` (like slice indexing).
    pub fn acceleration(&self, i: usize, q_new_i: f64) -> f64 {
        (q_new_i - self.q_pred[i]) / self.displacement_per_acceleration
    }

    /// `v_{n+1} = ṽ + c_va a_{n+1}` for entry `i`.
    ///
    /// # Panics
    /// If `i ≥ n` (like slice indexing).
    pub fn velocity(&self, i: usize, q_new_i: f64) -> f64 {
        self.v_pred[i] + self.velocity_per_acceleration * self.acceleration(i, q_new_i)
    }

    /// Writes `v_{n+1}` and `a_{n+1}` implied by `q_{n+1}`.
    pub fn kinematics(
        &self,
        q_new: &[f64],
        v_new: &mut [f64],
        a_new: &mut [f64],
    ) -> Result<(), IntegrateError> {
        self.check_len("q_new", q_new.len())?;
        self.check_len("v_new", v_new.len())?;
        self.check_len("a_new", a_new.len())?;
        for (i, &q) in q_new.iter().enumerate() {
            a_new[i] = self.acceleration(i, q);
            v_new[i] = self.v_pred[i] + self.velocity_per_acceleration * a_new[i];
        }
        Ok(())
    }

    /// The residual `R(q_{n+1})` of the balance equation, given `f_int(q_{n+1})` and the load
    /// `f_ext(t_force)`. No allocation: the accelerations and velocities are formed on the fly.
    pub fn residual(
        &self,
        mass: MatRef<'_, f64>,
        damping: Option<MatRef<'_, f64>>,
        q_new: &[f64],
        f_int_new: &[f64],
        f_ext: &[f64],
        out: &mut [f64],
    ) -> Result<(), IntegrateError> {
        self.check_shape("mass", mass)?;
        if let Some(c) = damping {
            self.check_shape("damping", c)?;
        }
        self.check_len("q_new", q_new.len())?;
        self.check_len("f_int_new", f_int_new.len())?;
        self.check_len("f_ext", f_ext.len())?;
        self.check_len("out", out.len())?;
        let w_inertia = 1.0 - self.alpha_m;
        let w_force = 1.0 - self.alpha_f;
        for (i, r) in out.iter_mut().enumerate() {
            let inertia: f64 = (0..q_new.len())
                .map(|j| mass[(i, j)] * self.acceleration(j, q_new[j]))
                .sum();
            let damping_force: f64 = damping.map_or(0.0, |c| {
                (0..q_new.len())
                    .map(|j| c[(i, j)] * self.velocity(j, q_new[j]))
                    .sum()
            });
            *r = w_inertia * inertia
                + w_force * (damping_force + f_int_new[i])
                + self.history_force[i]
                - f_ext[i];
        }
        Ok(())
    }

    /// The load vector `r` of the step equation of a linear structure, `K_eff q_{n+1} = r`
    /// (references.md §D4.2 writes a coupled step as `A·x = r + b·F`):
    ///
    /// ```text
    /// r = c_M M q̃ + c_C C q̃ − (1 − α_f) C ṽ − h + f_ext(t_force)
    /// ```
    ///
    /// obtained by expanding `R(q)` with `f_int(q) = K q`. A nonlinear part of `f_int` (or a
    /// contact force) is added by the caller with weight `(1 − α_f)`.
    pub fn effective_load(
        &self,
        mass: MatRef<'_, f64>,
        damping: Option<MatRef<'_, f64>>,
        f_ext: &[f64],
        out: &mut [f64],
    ) -> Result<(), IntegrateError> {
        self.check_shape("mass", mass)?;
        if let Some(c) = damping {
            self.check_shape("damping", c)?;
        }
        self.check_len("f_ext", f_ext.len())?;
        self.check_len("out", out.len())?;
        let n = self.dimension();
        for (i, r) in out.iter_mut().enumerate() {
            let inertia: f64 = (0..n).map(|j| mass[(i, j)] * self.q_pred[j]).sum();
            let damping_force: f64 = damping.map_or(0.0, |c| {
                (0..n)
                    .map(|j| {
                        c[(i, j)]
                            * (self.damping_coefficient * self.q_pred[j]
                                - (1.0 - self.alpha_f) * self.v_pred[j])
                    })
                    .sum()
            });
            *r = self.mass_coefficient * inertia + damping_force - self.history_force[i] + f_ext[i];
        }
        Ok(())
    }

    /// [`effective_load`](Self::effective_load) with compressed-row `M` and `C`
    /// ([`super::sparse`]): the same formula in O(nnz), over the rows not in
    /// [`frozen_rows`](Self::frozen_rows) (those are zero).
    pub fn effective_load_sparse(
        &self,
        mass: SparseRowMatRef<'_, usize, f64>,
        damping: Option<SparseRowMatRef<'_, usize, f64>>,
        f_ext: &[f64],
        out: &mut [f64],
    ) -> Result<(), IntegrateError> {
        let n = self.dimension();
        for (name, a) in std::iter::once(("mass", mass)).chain(damping.map(|c| ("damping", c))) {
            if a.nrows() != n || a.ncols() != n {
                return Err(IntegrateError::InvalidParameter {
                    name,
                    reason: format!("shape {}x{} (expected {n}x{n})", a.nrows(), a.ncols()),
                });
            }
        }
        self.check_len("f_ext", f_ext.len())?;
        self.check_len("out", out.len())?;
        let rows = || rows_outside(n, &self.frozen_rows);
        for range in &self.frozen_rows {
            out[range.clone()].fill(0.0);
        }
        for range in rows() {
            for ((r, f), h) in out[range.clone()]
                .iter_mut()
                .zip(&f_ext[range.clone()])
                .zip(&self.history_force[range])
            {
                *r = f - h;
            }
        }
        sparse_mul_add_rows(mass, self.mass_coefficient, &self.q_pred, out, rows());
        if let Some(c) = damping {
            // C q̃ and C ṽ in one pass (the same operations as two products in turn).
            sparse_mul_add2_rows(
                c,
                (self.damping_coefficient, &self.q_pred),
                (-(1.0 - self.alpha_f), &self.v_pred),
                out,
                rows(),
            );
        }
        Ok(())
    }

    /// Writes the effective stiffness `K_eff = c_M M + c_C C + c_K K_t` into `out`.
    pub fn effective_stiffness(
        &self,
        mass: MatRef<'_, f64>,
        damping: Option<MatRef<'_, f64>>,
        tangent: MatRef<'_, f64>,
        mut out: MatMut<'_, f64>,
    ) -> Result<(), IntegrateError> {
        self.check_shape("mass", mass)?;
        if let Some(c) = damping {
            self.check_shape("damping", c)?;
        }
        self.check_shape("tangent", tangent)?;
        self.check_shape("out", out.as_ref())?;
        for j in 0..out.ncols() {
            for i in 0..out.nrows() {
                let c = damping.map_or(0.0, |c| c[(i, j)]);
                out[(i, j)] = self.mass_coefficient * mass[(i, j)]
                    + self.damping_coefficient * c
                    + self.stiffness_coefficient * tangent[(i, j)];
            }
        }
        Ok(())
    }
}
