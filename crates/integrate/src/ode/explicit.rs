//! Explicit one-step methods: explicit Euler, classic RK4 (fixed step) and Dormand–Prince
//! 5(4) (adaptive with PI control, or fixed step), all without allocation per step.

use super::fixed_step::FixedStepState;
use super::{
    OdeOptions, OdeStepper, OdeSystem, check_interpolation_range, check_state, limit_step,
};
use crate::error::IntegrateError;
use crate::ode::eval_rhs;
use crate::stats::Stats;

/// Explicit Euler, `y_{n+1} = y_n + h f(t_n, y_n)` (order 1). One evaluation of `f` per step
/// (the derivative at the new point, reused by the next step), plus one in `set_state`.
#[derive(Debug, Clone)]
pub struct ExplicitEuler {
    state: FixedStepState,
}

impl ExplicitEuler {
    /// Needs `options.fixed_step`.
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        Ok(Self {
            state: FixedStepState::new(dim, options, "euler")?,
        })
    }
}

impl OdeStepper for ExplicitEuler {
    fn name(&self) -> &'static str {
        "euler"
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        let h = self.state.next_step()?;
        let s = &mut self.state;
        s.begin_step();
        for i in 0..s.y.len() {
            s.y[i] = s.y_prev[i] + h * s.f_prev[i];
        }
        s.end_step(sys, h)
    }

    fixed_step_accessors!();
}

/// Classic fourth-order Runge–Kutta (Kutta 1901; Hairer–Nørsett–Wanner I, Table II.1.2):
/// `k1 = f(t, y)`, `k2 = f(t + h/2, y + h k1/2)`, `k3 = f(t + h/2, y + h k2/2)`,
/// `k4 = f(t + h, y + h k3)`, `y_{n+1} = y_n + h (k1 + 2k2 + 2k3 + k4)/6`.
/// Four evaluations per step (`k1` is the derivative at the end of the previous step).
#[derive(Debug, Clone)]
pub struct Rk4 {
    state: FixedStepState,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    stage: Vec<f64>,
}

impl Rk4 {
    /// Needs `options.fixed_step`.
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        Ok(Self {
            state: FixedStepState::new(dim, options, "rk4")?,
            k2: vec![0.0; dim],
            k3: vec![0.0; dim],
            k4: vec![0.0; dim],
            stage: vec![0.0; dim],
        })
    }
}

/// One classic RK4 step from `(t, y)` with `k1 = f(t, y)` given; writes `y_new`.
/// Three evaluations of `f`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn rk4_step(
    sys: &mut dyn OdeSystem,
    t: f64,
    h: f64,
    y: &[f64],
    k1: &[f64],
    [k2, k3, k4, stage]: [&mut [f64]; 4],
    y_new: &mut [f64],
) -> Result<(), IntegrateError> {
    let n = y.len();
    for i in 0..n {
        stage[i] = y[i] + 0.5 * h * k1[i];
    }
    eval_rhs(sys, t + 0.5 * h, stage, k2)?;
    for i in 0..n {
        stage[i] = y[i] + 0.5 * h * k2[i];
    }
    eval_rhs(sys, t + 0.5 * h, stage, k3)?;
    for i in 0..n {
        stage[i] = y[i] + h * k3[i];
    }
    eval_rhs(sys, t + h, stage, k4)?;
    for i in 0..n {
        y_new[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    Ok(())
}

impl OdeStepper for Rk4 {
    fn name(&self) -> &'static str {
        "rk4"
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        let h = self.state.next_step()?;
        let s = &mut self.state;
        s.begin_step();
        let t = s.t_prev;
        rk4_step(
            sys,
            t,
            h,
            &s.y_prev,
            &s.f_prev,
            [&mut self.k2, &mut self.k3, &mut self.k4, &mut self.stage],
            &mut s.y,
        )?;
        s.stats.f_evals += 3;
        s.end_step(sys, h)
    }

    fixed_step_accessors!();
}

// Dormand–Prince 5(4) coefficients (Dormand & Prince 1980; Hairer–Nørsett–Wanner I, Table II.5.2).
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
/// Differences between the 5th- and 4th-order weights (error estimate).
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
/// Coefficients of the 4th-order continuous extension (Shampine 1986, as in Hairer's DOPRI5).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// Safety factor, step-ratio bounds and PI exponent of Hairer's DOPRI5 (β = 0.04).
const SAFE: f64 = 0.9;
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 10.0;
const BETA_PI: f64 = 0.04;

/// Dormand–Prince 5(4) (order 5, FSAL, 6 new evaluations per step) with Hairer's PI step
/// control `h_new = h · min(10, max(0.2, 0.9 · err^{-(0.2 − 0.75β)} · err_old^{β}))`, β = 0.04
/// (Hairer–Nørsett–Wanner I, IV.2 / code DOPRI5) and the 4th-order dense output
/// `y(t_n + θh) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5)))`.
/// With `options.fixed_step` it takes steps of exactly that size without error control.
#[derive(Debug, Clone)]
pub struct Dopri5 {
    rtol: f64,
    atol: f64,
    fixed_step: Option<f64>,
    initial_step: Option<f64>,
    max_step: f64,
    max_steps: usize,
    h_cap: f64,
    t_stop: Option<f64>,
    t: f64,
    t_prev: f64,
    h_next: f64,
    err_old: f64,
    y: Vec<f64>,
    y_new: Vec<f64>,
    k: [Vec<f64>; 7],
    stage: Vec<f64>,
    /// Dense output coefficients r1..r5 of the last step.
    dense: [Vec<f64>; 5],
    stats: Stats,
}

impl Dopri5 {
    /// Adaptive unless `options.fixed_step` is set.
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        options.validate()?;
        let v = || vec![0.0; dim];
        Ok(Self {
            rtol: options.rtol,
            atol: options.atol,
            fixed_step: options.fixed_step,
            initial_step: options.initial_step,
            max_step: options.max_step,
            max_steps: options.max_steps,
            h_cap: f64::INFINITY,
            t_stop: None,
            t: 0.0,
            t_prev: 0.0,
            h_next: 0.0,
            err_old: 1e-4,
            y: v(),
            y_new: v(),
            k: [v(), v(), v(), v(), v(), v(), v()],
            stage: v(),
            dense: [v(), v(), v(), v(), v()],
            stats: Stats::default(),
        })
    }

    fn h_limit(&self) -> f64 {
        self.h_cap.min(self.max_step)
    }

    /// Hairer's starting step (Hairer–Nørsett–Wanner I, II.4, algorithm "HINIT"): from
    /// `‖y‖`, `‖f‖` and a difference estimate of `‖y''‖`, for a method of order 5.
    /// Uses one evaluation of `f`; `k[1]`, `k[2]` serve as scratch.
    fn initial_step_size(&mut self, sys: &mut dyn OdeSystem) -> Result<f64, IntegrateError> {
        let n = self.y.len();
        let (mut dnf, mut dny) = (0.0, 0.0);
        for i in 0..n {
            let sk = self.atol + self.rtol * self.y[i].abs();
            dnf += (self.k[0][i] / sk).powi(2);
            dny += (self.y[i] / sk).powi(2);
        }
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            (dny / dnf).sqrt() * 0.01
        };
        h = h.min(self.h_limit());
        for i in 0..n {
            self.k[1][i] = self.y[i] + h * self.k[0][i];
        }
        let (head, tail) = self.k.split_at_mut(2);
        eval_rhs(sys, self.t + h, &head[1], &mut tail[0])?;
        self.stats.f_evals += 1;
        let mut der2 = 0.0;
        for i in 0..n {
            let sk = self.atol + self.rtol * self.y[i].abs();
            der2 += ((self.k[2][i] - self.k[0][i]) / sk).powi(2);
        }
        let der2 = der2.sqrt() / h;
        let der12 = der2.abs().max(dnf.sqrt());
        let h1 = if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(1.0 / 5.0)
        };
        Ok((100.0 * h).min(h1).min(self.h_limit()))
    }

    /// The six new stages of a step of size `h` from `(t, y)`; `k[0] = f(t, y)` is given,
    /// `k[6] = f(t + h, y_new)` (first-same-as-last).
    fn stages(&mut self, sys: &mut dyn OdeSystem, h: f64) -> Result<(), IntegrateError> {
        let n = self.y.len();
        let t = self.t;
        let rows: [(f64, [f64; 6]); 6] = [
            (C2, [A21, 0.0, 0.0, 0.0, 0.0, 0.0]),
            (C3, [A31, A32, 0.0, 0.0, 0.0, 0.0]),
            (C4, [A41, A42, A43, 0.0, 0.0, 0.0]),
            (C5, [A51, A52, A53, A54, 0.0, 0.0]),
            (1.0, [A61, A62, A63, A64, A65, 0.0]),
            (1.0, [A71, 0.0, A73, A74, A75, A76]),
        ];
        for (s, (c, a)) in rows.iter().enumerate() {
            for i in 0..n {
                let mut acc = 0.0;
                for (j, aj) in a.iter().enumerate().take(s + 1) {
                    acc += aj * self.k[j][i];
                }
                self.stage[i] = self.y[i] + h * acc;
            }
            if s == 5 {
                self.y_new.copy_from_slice(&self.stage);
            }
            let (done, rest) = self.k.split_at_mut(s + 1);
            let _ = done;
            eval_rhs(sys, t + c * h, &self.stage, &mut rest[0])?;
        }
        self.stats.f_evals += 6;
        Ok(())
    }

    /// Weighted RMS norm of the embedded error estimate `h Σ e_j k_j`.
    fn error_norm(&mut self, h: f64) -> f64 {
        let n = self.y.len();
        let mut sum = 0.0;
        for i in 0..n {
            let k = &self.k;
            let e = h
                * (E1 * k[0][i]
                    + E3 * k[2][i]
                    + E4 * k[3][i]
                    + E5 * k[4][i]
                    + E6 * k[5][i]
                    + E7 * k[6][i]);
            let sk = self.atol + self.rtol * self.y[i].abs().max(self.y_new[i].abs());
            sum += (e / sk).powi(2);
        }
        let err = (sum / n.max(1) as f64).sqrt();
        if err.is_finite() { err } else { f64::INFINITY }
    }

    /// Accept the step: store the dense output, advance, reuse `k7` as the next `k1`.
    fn accept(&mut self, h: f64) {
        let n = self.y.len();
        for i in 0..n {
            let k = &self.k;
            let ydiff = self.y_new[i] - self.y[i];
            let bspl = h * k[0][i] - ydiff;
            self.dense[0][i] = self.y[i];
            self.dense[1][i] = ydiff;
            self.dense[2][i] = bspl;
            self.dense[3][i] = ydiff - h * k[6][i] - bspl;
            self.dense[4][i] = h
                * (D1 * k[0][i]
                    + D3 * k[2][i]
                    + D4 * k[3][i]
                    + D5 * k[4][i]
                    + D6 * k[5][i]
                    + D7 * k[6][i]);
        }
        self.t_prev = self.t;
        self.t += h;
        std::mem::swap(&mut self.y, &mut self.y_new);
        self.k.swap(0, 6);
        self.stats.steps += 1;
    }
}

impl OdeStepper for Dopri5 {
    fn name(&self) -> &'static str {
        "dopri5"
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
        eval_rhs(sys, t, y, &mut self.k[0])?;
        self.stats.f_evals += 1;
        self.err_old = 1e-4;
        for d in &mut self.dense {
            d.fill(0.0);
        }
        self.dense[0].copy_from_slice(y);
        self.h_next = match (self.fixed_step, self.initial_step) {
            (Some(h), _) | (None, Some(h)) => h,
            (None, None) => self.initial_step_size(sys)?,
        };
        Ok(())
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        let mut rejected_last = false;
        loop {
            let h = limit_step(self.t, self.h_next, self.h_limit(), self.t_stop);
            if h <= 10.0 * f64::EPSILON * self.t.abs().max(1.0) {
                return Err(IntegrateError::StepSizeTooSmall { t: self.t, h });
            }
            self.stages(sys, h)?;
            if let Some(hf) = self.fixed_step {
                if self.y_new.iter().any(|v| !v.is_finite()) {
                    return Err(IntegrateError::NonFinite { t: self.t + h });
                }
                self.accept(h);
                self.h_next = hf;
                return Ok(());
            }
            let err = self.error_norm(h);
            let fac11 = err.powf(0.2 - BETA_PI * 0.75);
            if err <= 1.0 {
                // PI controller (Gustafsson 1991 as implemented in DOPRI5).
                let fac =
                    (fac11 / self.err_old.powf(BETA_PI) / SAFE).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
                let mut h_new = h / fac;
                if rejected_last {
                    h_new = h_new.min(h);
                }
                self.err_old = err.max(1e-4);
                self.accept(h);
                self.h_next = h_new.min(self.h_limit());
                return Ok(());
            }
            self.stats.rejected_steps += 1;
            rejected_last = true;
            self.h_next = h / (fac11 / SAFE).min(1.0 / FAC_MIN);
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

    fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), IntegrateError> {
        check_interpolation_range(t, self.t_prev, self.t)?;
        let h = self.t - self.t_prev;
        if h == 0.0 {
            out.copy_from_slice(&self.y);
            return Ok(());
        }
        let th = (t - self.t_prev) / h;
        let th1 = 1.0 - th;
        let r = &self.dense;
        for i in 0..out.len() {
            out[i] = r[0][i] + th * (r[1][i] + th1 * (r[2][i] + th * (r[3][i] + th1 * r[4][i])));
        }
        Ok(())
    }

    stepper_bookkeeping!();
}
