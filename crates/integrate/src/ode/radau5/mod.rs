//! Radau IIA of order 5 (3 stages, stage order 3, L-stable) after Hairer & Wanner's RADAU5
//! (Solving ODEs II, §IV.8, and the Fortran code `radau5.f`).
//!
//! * Stage system `Z = h (A ⊗ I) F(Z)` solved by simplified Newton, transformed with the
//!   eigen-decomposition `T⁻¹ A⁻¹ T = diag(γ̂, [α̂ −β̂; β̂ α̂])`: per iteration one real system
//!   `(γ̂/h − J) ΔW₁ = r₁` and one complex system `((α̂ + iβ̂)/h − J) ΔW₂ = r₂ + i r₃`.
//! * Starting values extrapolated from the collocation polynomial of the previous step.
//! * Newton stopped when `η‖ΔW‖ ≤ κ·tol` with `η = θ/(1 − θ)`; slow convergence shrinks the step.
//! * Jacobian kept across steps while the contraction factor θ ≤ 0.001; the LU factors are
//!   kept too when moreover the step ratio is in [1, 1.2].
//! * Error estimate `err = (γ̂/h − J)⁻¹ [f(t, y) + (e₁Z₁ + e₂Z₂ + e₃Z₃)/h]` (the `(γ₀h)⁻¹`
//!   filter), with one extra filtered evaluation after a rejection or on the first step.
//! * Step control `h_new = h / clamp(err^{1/4}/fac, 1/8, 5)` and Gustafsson's predictive
//!   controller `h_new = h / max(…, (h_acc/h)(err²/err_acc)^{1/4}/0.9)`.
//! * Tolerances transformed as in RADAU5: `rtol' = 0.1 rtol^{2/3}`, `atol' = rtol'·atol/rtol`.
//! * Dense output: the collocation polynomial through `(t_n + c_i h, y_n + Z_i)`.
//!
//! Statistics: `lu_decompositions` counts the real and the complex factorisation separately
//! (twice RADAU5's `NDEC`); `f_evals` excludes the evaluations spent on finite-difference
//! Jacobians (RADAU5's `NFCN` convention); `steps + rejected_steps` is RADAU5's `NSTEP`.

// The transformation constants are quoted with RADAU5's 20 digits.
#![allow(clippy::excessive_precision)]

use super::linalg::evaluate_jacobian;
use super::{
    OdeOptions, OdeStepper, OdeSystem, check_interpolation_range, check_state, limit_step,
};
use crate::error::IntegrateError;
use crate::lu::DenseLu;
use crate::ode::eval_rhs;
use crate::stats::Stats;
use faer::{Mat, c64};

mod coefficients;
use coefficients::*;

/// RADAU5's default controls: Newton iterations, safety, θ for Jacobian reuse, step-ratio band
/// that keeps the LU factors, and step-ratio bounds.
const NIT: usize = 7;
const SAFE: f64 = 0.9;
const THET: f64 = 0.001;
const QUOT1: f64 = 1.0;
const QUOT2: f64 = 1.2;
const FACL: f64 = 5.0;
const FACR: f64 = 0.125;
const UROUND: f64 = f64::EPSILON / 2.0;

/// What must happen before the next attempt (RADAU5's labels 10, 20, 30).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Pending {
    Jacobian,
    Decomposition,
    Ready,
}

enum NewtonOutcome {
    Converged {
        iterations: usize,
    },
    /// Predicted to converge too slowly: retry with `h · factor`.
    TooSlow {
        factor: f64,
    },
    /// Diverged or did not converge in NIT iterations.
    Failed,
}

/// Radau IIA order 5 stepper (see the module documentation).
#[derive(Debug)]
pub struct Radau5 {
    rtol: f64,
    atol: f64,
    fnewt: f64,
    fixed_step: Option<f64>,
    initial_step: Option<f64>,
    max_step: f64,
    max_steps: usize,
    h_cap: f64,
    t_stop: Option<f64>,
    gamma: f64,
    alpha: f64,
    beta: f64,
    // state
    t: f64,
    t_prev: f64,
    h: f64,
    h_old: f64,
    y: Vec<f64>,
    f0: Vec<f64>,
    f0_valid: bool,
    scal: Vec<f64>,
    // stage vectors (Z) and transformed stage vectors (W = T⁻¹ Z)
    z: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    cont: [Vec<f64>; 4],
    work: Vec<f64>,
    fz: Vec<f64>,
    err_base: Vec<f64>,
    cplx: Vec<c64>,
    jac: Mat<f64>,
    lu_real: DenseLu<f64>,
    lu_cplx: DenseLu<c64>,
    // controller memory
    pending: Pending,
    first: bool,
    reject: bool,
    jacobian_current: bool,
    faccon: f64,
    theta: f64,
    h_acc: f64,
    err_acc: f64,
    accepted_since_start: usize,
    singular_count: usize,
    error_test_failures: usize,
    stats: Stats,
}

impl Radau5 {
    /// Adaptive unless `options.fixed_step` is set (then every step has that size and the
    /// Newton iteration must converge, else [`IntegrateError::NewtonFailed`]).
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        options.validate()?;
        if options.rtol <= 10.0 * UROUND {
            return Err(super::invalid(
                "rtol",
                format!("must exceed 10 ε, got {}", options.rtol),
            ));
        }
        let rtol = 0.1 * options.rtol.powf(2.0 / 3.0);
        let atol = rtol * options.atol / options.rtol;
        let fnewt = (10.0 * UROUND / rtol).max(0.03f64.min(rtol.sqrt()));
        let (gamma, alpha, beta) = eigenvalues_of_a_inverse();
        let v = || vec![0.0; dim];
        Ok(Self {
            rtol,
            atol,
            fnewt,
            fixed_step: options.fixed_step,
            initial_step: options.initial_step,
            max_step: options.max_step,
            max_steps: options.max_steps,
            h_cap: f64::INFINITY,
            t_stop: None,
            gamma,
            alpha,
            beta,
            t: 0.0,
            t_prev: 0.0,
            h: 0.0,
            h_old: 0.0,
            y: v(),
            f0: v(),
            f0_valid: false,
            scal: v(),
            z: [v(), v(), v()],
            w: [v(), v(), v()],
            cont: [v(), v(), v(), v()],
            work: v(),
            fz: v(),
            err_base: v(),
            cplx: vec![c64::new(0.0, 0.0); dim],
            jac: Mat::zeros(dim, dim),
            lu_real: DenseLu::new(dim),
            lu_cplx: DenseLu::new(dim),
            pending: Pending::Jacobian,
            first: true,
            reject: false,
            jacobian_current: false,
            faccon: 1.0,
            theta: THET,
            h_acc: 0.0,
            err_acc: 1e-2,
            accepted_since_start: 0,
            singular_count: 0,
            error_test_failures: 0,
            stats: Stats::default(),
        })
    }

    /// Error-test failures after the first accepted step (RADAU5's `NREJCT`).
    pub fn error_test_failures(&self) -> usize {
        self.error_test_failures
    }

    fn h_limit(&self) -> f64 {
        self.h_cap.min(self.max_step)
    }

    fn update_scale(&mut self) {
        for (s, y) in self.scal.iter_mut().zip(&self.y) {
            *s = self.atol + self.rtol * y.abs();
        }
    }

    fn compute_jacobian(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        let n = self.y.len();
        let (yw, fw) = (&mut self.work, &mut self.fz);
        let _fd_evals = evaluate_jacobian(sys, self.t, &self.y, &self.f0, yw, fw, &mut self.jac)?;
        debug_assert!(_fd_evals == 0 || _fd_evals == n);
        self.stats.jacobian_evals += 1;
        self.jacobian_current = true;
        Ok(())
    }

    /// Factorise `E₁ = γ̂/h − J` and `E₂ = (α̂ + iβ̂)/h − J`. `false` if either is singular.
    fn decompose(&mut self) -> bool {
        let n = self.y.len();
        let fac1 = self.gamma / self.h;
        let shift = c64::new(self.alpha / self.h, self.beta / self.h);
        {
            let mut e1 = self.lu_real.matrix_mut();
            for j in 0..n {
                for i in 0..n {
                    e1[(i, j)] = -self.jac[(i, j)];
                }
                e1[(j, j)] += fac1;
            }
        }
        {
            let mut e2 = self.lu_cplx.matrix_mut();
            for j in 0..n {
                for i in 0..n {
                    e2[(i, j)] = c64::new(-self.jac[(i, j)], 0.0);
                }
                e2[(j, j)] += shift;
            }
        }
        self.stats.lu_decompositions += 2;
        let ok_real = self.lu_real.factor();
        let ok_cplx = self.lu_cplx.factor();
        ok_real && ok_cplx
    }

    /// Starting values of `Z` and `W = T⁻¹Z`: zero on the first step, otherwise the previous
    /// collocation polynomial extrapolated to the new stage times.
    fn starting_values(&mut self) {
        if self.first {
            for k in 0..3 {
                self.z[k].fill(0.0);
                self.w[k].fill(0.0);
            }
            return;
        }
        let c3q = self.h / self.h_old;
        let c1q = C1 * c3q;
        let c2q = C2 * c3q;
        for i in 0..self.y.len() {
            let (ak1, ak2, ak3) = (self.cont[1][i], self.cont[2][i], self.cont[3][i]);
            let z1 = c1q * (ak1 + (c1q - C2M1) * (ak2 + (c1q - C1M1) * ak3));
            let z2 = c2q * (ak1 + (c2q - C2M1) * (ak2 + (c2q - C1M1) * ak3));
            let z3 = c3q * (ak1 + (c3q - C2M1) * (ak2 + (c3q - C1M1) * ak3));
            self.z[0][i] = z1;
            self.z[1][i] = z2;
            self.z[2][i] = z3;
            self.w[0][i] = TI11 * z1 + TI12 * z2 + TI13 * z3;
            self.w[1][i] = TI21 * z1 + TI22 * z2 + TI23 * z3;
            self.w[2][i] = TI31 * z1 + TI32 * z2 + TI33 * z3;
        }
    }

    /// Evaluate `F(Z)` at the three stages, overwriting `z[k]` with `f(t + c_k h, y + Z_k)`.
    fn evaluate_stages(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        for (k, c) in [C1, C2, 1.0].into_iter().enumerate() {
            for i in 0..self.y.len() {
                self.work[i] = self.y[i] + self.z[k][i];
            }
            eval_rhs(sys, self.t + c * self.h, &self.work, &mut self.fz)?;
            self.z[k].copy_from_slice(&self.fz);
        }
        self.stats.f_evals += 3;
        Ok(())
    }

    /// One simplified-Newton increment: transform `F(Z)` with `T⁻¹`, form the right-hand sides
    /// and solve the real and complex systems. Leaves `ΔW` in `z`; returns its scaled norm.
    fn newton_increment(&mut self) -> f64 {
        let n = self.y.len();
        let fac1 = self.gamma / self.h;
        let (alphn, betan) = (self.alpha / self.h, self.beta / self.h);
        for i in 0..n {
            let (a1, a2, a3) = (self.z[0][i], self.z[1][i], self.z[2][i]);
            let r1 = TI11 * a1 + TI12 * a2 + TI13 * a3 - self.w[0][i] * fac1;
            let s2 = -self.w[1][i];
            let s3 = -self.w[2][i];
            let r2 = TI21 * a1 + TI22 * a2 + TI23 * a3 + s2 * alphn - s3 * betan;
            let r3 = TI31 * a1 + TI32 * a2 + TI33 * a3 + s3 * alphn + s2 * betan;
            self.z[0][i] = r1;
            self.cplx[i] = c64::new(r2, r3);
        }
        self.lu_real.solve_in_place(&mut self.z[0]);
        self.lu_cplx.solve_in_place(&mut self.cplx);
        let mut sum = 0.0;
        for i in 0..n {
            self.z[1][i] = self.cplx[i].re;
            self.z[2][i] = self.cplx[i].im;
            for k in 0..3 {
                sum += (self.z[k][i] / self.scal[i]).powi(2);
            }
        }
        (sum / (3 * n.max(1)) as f64).sqrt()
    }

    /// The simplified Newton iteration of RADAU5 (contraction estimate θ, predicted
    /// convergence test `η‖ΔW‖ θ^{NIT−1−k} / κ < 1`).
    fn newton(&mut self, sys: &mut dyn OdeSystem) -> Result<NewtonOutcome, IntegrateError> {
        let n = self.y.len();
        self.faccon = self.faccon.max(UROUND).powf(0.8);
        self.theta = THET;
        let mut newt = 0;
        let (mut dynold, mut thqold) = (0.0f64, 0.0f64);
        loop {
            if newt >= NIT {
                return Ok(NewtonOutcome::Failed);
            }
            self.evaluate_stages(sys)?;
            let dyno = self.newton_increment();
            self.stats.newton_iterations += 1;
            newt += 1;
            if !dyno.is_finite() {
                return Ok(NewtonOutcome::Failed);
            }
            if newt > 1 && newt < NIT {
                let thq = dyno / dynold;
                self.theta = if newt == 2 {
                    thq
                } else {
                    (thq * thqold).sqrt()
                };
                thqold = thq;
                if self.theta < 0.99 {
                    self.faccon = self.theta / (1.0 - self.theta);
                    let remaining = (NIT - 1 - newt) as i32;
                    let dyth = self.faccon * dyno * self.theta.powi(remaining) / self.fnewt;
                    if dyth >= 1.0 {
                        let qnewt = dyth.clamp(1e-4, 20.0);
                        let factor = 0.8 * qnewt.powf(-1.0 / (4.0 + remaining as f64));
                        return Ok(NewtonOutcome::TooSlow { factor });
                    }
                } else {
                    return Ok(NewtonOutcome::Failed);
                }
            }
            dynold = dyno.max(UROUND);
            for i in 0..n {
                self.w[0][i] += self.z[0][i];
                self.w[1][i] += self.z[1][i];
                self.w[2][i] += self.z[2][i];
                let (w1, w2, w3) = (self.w[0][i], self.w[1][i], self.w[2][i]);
                self.z[0][i] = T11 * w1 + T12 * w2 + T13 * w3;
                self.z[1][i] = T21 * w1 + T22 * w2 + T23 * w3;
                self.z[2][i] = T31 * w1 + w2;
            }
            if self.faccon * dyno <= self.fnewt {
                return Ok(NewtonOutcome::Converged { iterations: newt });
            }
        }
    }

    /// Filtered error estimate `‖E₁⁻¹ (f₀ + (dd₁Z₁ + dd₂Z₂ + dd₃Z₃)/h)‖`, with RADAU5's second
    /// filter `E₁⁻¹(f(t, y + err) + …)` when the first estimate fails on a first or rejected step.
    fn error_estimate(&mut self, sys: &mut dyn OdeSystem) -> Result<f64, IntegrateError> {
        let n = self.y.len();
        let (hee1, hee2, hee3) = (DD1 / self.h, DD2 / self.h, DD3 / self.h);
        for i in 0..n {
            self.err_base[i] = hee1 * self.z[0][i] + hee2 * self.z[1][i] + hee3 * self.z[2][i];
            self.work[i] = self.err_base[i] + self.f0[i];
        }
        self.lu_real.solve_in_place(&mut self.work);
        let mut err = super::rms_norm(&self.work, &self.scal).max(1e-10);
        if err >= 1.0 && (self.first || self.reject) {
            for i in 0..n {
                self.work[i] += self.y[i];
            }
            eval_rhs(sys, self.t, &self.work, &mut self.fz)?;
            self.stats.f_evals += 1;
            for i in 0..n {
                self.work[i] = self.fz[i] + self.err_base[i];
            }
            self.lu_real.solve_in_place(&mut self.work);
            err = super::rms_norm(&self.work, &self.scal).max(1e-10);
        }
        Ok(if err.is_finite() { err } else { f64::INFINITY })
    }

    /// Advance the state with the converged stages and store the collocation polynomial.
    fn accept_state(&mut self) {
        for i in 0..self.y.len() {
            let (z1, z2, z3) = (self.z[0][i], self.z[1][i], self.z[2][i]);
            self.y[i] += z3;
            self.cont[1][i] = (z2 - z3) / C2M1;
            let ak = (z1 - z2) / C1MC2;
            let acont3 = (ak - z1 / C1) / C2;
            self.cont[2][i] = (ak - self.cont[1][i]) / C1M1;
            self.cont[3][i] = self.cont[2][i] - acont3;
            self.cont[0][i] = self.y[i];
        }
        self.t_prev = self.t;
        self.h_old = self.h;
        self.t += self.h;
        self.update_scale();
        self.jacobian_current = false;
        self.first = false;
        self.stats.steps += 1;
        self.accepted_since_start += 1;
    }

    /// Unexpected rejection (Newton failure or singular matrix): halve the step (RADAU5 label 78).
    fn unexpected_rejection(&mut self, singular: bool) -> Result<(), IntegrateError> {
        if singular {
            self.singular_count += 1;
            if self.singular_count >= 5 {
                return Err(IntegrateError::SingularMatrix { t: self.t });
            }
        }
        if self.fixed_step.is_some() {
            return Err(IntegrateError::NewtonFailed {
                t: self.t,
                iterations: NIT,
                residual: self.theta,
            });
        }
        self.stats.rejected_steps += 1;
        self.h *= 0.5;
        self.reject = true;
        self.pending = if self.jacobian_current {
            Pending::Decomposition
        } else {
            Pending::Jacobian
        };
        Ok(())
    }

    /// Step-size proposal after a converged Newton iteration with `newt` iterations.
    fn proposed_step(&self, err: f64, newt: usize) -> (f64, f64) {
        let cfac = SAFE * (1 + 2 * NIT) as f64;
        let fac = SAFE.min(cfac / (newt + 2 * NIT) as f64);
        let quot = (err.powf(0.25) / fac).clamp(FACR, FACL);
        (self.h / quot, quot)
    }

    /// Bookkeeping after an accepted step (RADAU5's code after label "STEP IS ACCEPTED").
    fn after_acceptance(
        &mut self,
        sys: &mut dyn OdeSystem,
        err: f64,
        newt: usize,
    ) -> Result<(), IntegrateError> {
        let (mut h_new, mut quot) = self.proposed_step(err, newt);
        if self.accepted_since_start > 0 {
            let facgus = ((self.h_acc / self.h) * (err * err / self.err_acc).powf(0.25) / SAFE)
                .clamp(FACR, FACL);
            quot = quot.max(facgus);
            h_new = self.h / quot;
        }
        self.h_acc = self.h;
        self.err_acc = err.max(1e-2);
        let rejected_before = self.reject;
        self.accept_state();
        let reached_stop = self.t_stop.is_some_and(|ts| self.t >= ts);
        if reached_stop {
            self.f0_valid = false;
        } else {
            eval_rhs(sys, self.t, &self.y, &mut self.f0)?;
            self.stats.f_evals += 1;
            self.f0_valid = true;
        }
        if let Some(hf) = self.fixed_step {
            self.h = hf;
            self.pending = if self.theta <= THET {
                Pending::Ready
            } else {
                Pending::Jacobian
            };
            self.reject = false;
            return Ok(());
        }
        h_new = h_new.min(self.h_limit());
        if rejected_before {
            h_new = h_new.min(self.h);
        }
        self.reject = false;
        let reaches_stop = self
            .t_stop
            .is_some_and(|ts| self.t + h_new / QUOT1 >= ts && ts > self.t);
        if reaches_stop {
            self.h = self.t_stop.unwrap_or(self.t) - self.t;
        } else {
            let qt = h_new / self.h;
            if self.theta <= THET && (QUOT1..=QUOT2).contains(&qt) {
                self.pending = Pending::Ready;
                return Ok(());
            }
            self.h = h_new;
        }
        self.pending = if self.theta <= THET {
            Pending::Decomposition
        } else {
            Pending::Jacobian
        };
        Ok(())
    }
}

impl OdeStepper for Radau5 {
    fn name(&self) -> &'static str {
        "radau5"
    }

    fn set_state(
        &mut self,
        sys: &mut dyn OdeSystem,
        t: f64,
        y: &[f64],
    ) -> Result<(), IntegrateError> {
        check_state(sys, self.y.len(), t, y)?;
        self.t = t;
        self.t_prev = t;
        self.y.copy_from_slice(y);
        for c in &mut self.cont {
            c.fill(0.0);
        }
        self.cont[0].copy_from_slice(y);
        self.update_scale();
        eval_rhs(sys, t, y, &mut self.f0)?;
        self.stats.f_evals += 1;
        self.f0_valid = true;
        self.h = self.fixed_step.or(self.initial_step).unwrap_or(1e-6);
        self.h_old = self.h;
        self.pending = Pending::Jacobian;
        self.first = true;
        self.reject = false;
        self.jacobian_current = false;
        self.faccon = 1.0;
        self.theta = THET;
        self.accepted_since_start = 0;
        self.singular_count = 0;
        Ok(())
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        if !self.f0_valid {
            eval_rhs(sys, self.t, &self.y, &mut self.f0)?;
            self.stats.f_evals += 1;
            self.f0_valid = true;
        }
        loop {
            let h_lim = limit_step(self.t, self.h, self.h_limit(), self.t_stop);
            if h_lim != self.h {
                self.h = h_lim;
                if self.pending == Pending::Ready {
                    self.pending = Pending::Decomposition;
                }
            }
            if self.pending == Pending::Jacobian {
                self.compute_jacobian(sys)?;
                self.pending = Pending::Decomposition;
            }
            if self.pending == Pending::Decomposition {
                if !self.decompose() {
                    self.unexpected_rejection(true)?;
                    continue;
                }
                self.pending = Pending::Ready;
            }
            if 0.1 * self.h.abs() <= self.t.abs() * UROUND || !self.h.is_finite() {
                return Err(IntegrateError::StepSizeTooSmall {
                    t: self.t,
                    h: self.h,
                });
            }
            self.starting_values();
            let newt = match self.newton(sys)? {
                NewtonOutcome::Converged { iterations } => iterations,
                NewtonOutcome::TooSlow { factor } => {
                    if self.fixed_step.is_some() {
                        // Fixed step: h cannot be reduced, so slow convergence is a failure.
                        self.unexpected_rejection(false)?;
                        continue;
                    }
                    self.stats.rejected_steps += 1;
                    self.h *= factor;
                    self.reject = true;
                    self.pending = if self.jacobian_current {
                        Pending::Decomposition
                    } else {
                        Pending::Jacobian
                    };
                    continue;
                }
                NewtonOutcome::Failed => {
                    self.unexpected_rejection(false)?;
                    continue;
                }
            };
            if self.fixed_step.is_some() {
                self.after_acceptance(sys, 1.0, newt)?;
                return Ok(());
            }
            let err = self.error_estimate(sys)?;
            if err < 1.0 {
                self.after_acceptance(sys, err, newt)?;
                return Ok(());
            }
            // Error-test failure.
            self.stats.rejected_steps += 1;
            if self.accepted_since_start >= 1 {
                self.error_test_failures += 1;
            }
            if self.first {
                self.h *= 0.1;
            } else {
                self.h = self.proposed_step(err, newt).0;
            }
            self.reject = true;
            self.pending = if self.jacobian_current {
                Pending::Decomposition
            } else {
                Pending::Jacobian
            };
        }
    }

    fn t(&self) -> f64 {
        self.t
    }

    fn y(&self) -> &[f64] {
        &self.y
    }

    fn t_prev(&self) -> f64 {
        self.t_prev
    }

    /// RADAU5's `CONTR5`: `y(t) = c₀ + s(c₁ + (s − c₂ + 1)(c₂' + (s − c₁ + 1) c₃'))`,
    /// `s = (t − t_n)/h ∈ [−1, 0]` measured from the end of the step.
    fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), IntegrateError> {
        check_interpolation_range(t, self.t_prev, self.t)?;
        let h = self.t - self.t_prev;
        if h == 0.0 {
            out.copy_from_slice(&self.y);
            return Ok(());
        }
        let s = (t - self.t) / h;
        let c = &self.cont;
        for i in 0..out.len() {
            out[i] = c[0][i] + s * (c[1][i] + (s - C2M1) * (c[2][i] + (s - C1M1) * c[3][i]));
        }
        Ok(())
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn reset_stats(&mut self) {
        self.stats = Stats::default();
        self.error_test_failures = 0;
    }

    fn set_max_step(&mut self, h_max: f64) {
        self.h_cap = if h_max > 0.0 { h_max } else { f64::INFINITY };
    }

    fn set_stop_time(&mut self, t_stop: Option<f64>) {
        self.t_stop = t_stop;
    }

    fn last_step_size(&self) -> f64 {
        self.t - self.t_prev
    }
}

#[cfg(test)]
mod tests;
