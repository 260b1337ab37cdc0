//! Adams–Bashforth–Moulton predictor–corrector in PECE mode, orders 1–4, fixed or variable
//! step (Hairer–Nørsett–Wanner I, §III.1 and §III.5; Butcher 2016, §24).
//!
//! Order k pairs the k-step Adams–Bashforth predictor (order k) with the (k − 1)-step
//! Adams–Moulton corrector (order k), so the PECE method has order k:
//!
//! * P: `y* = y_n + h Σ_{j=0}^{k−1} β^{AB}_{k,j} f_{n−j}`
//! * E: `f* = f(t_{n+1}, y*)`
//! * C: `y_{n+1} = y_n + h (β^{AM}_{k,0} f* + Σ_{j=1}^{k−1} β^{AM}_{k,j} f_{n+1−j})`
//! * E: `f_{n+1} = f(t_{n+1}, y_{n+1})`
//!
//! k = 1 is Euler predictor / backward-Euler corrector, k = 2 uses AB2 with the trapezoidal
//! rule. Two evaluations of `f` per step. With a fixed step the first k − 1 steps are classic
//! RK4 steps (local error O(h⁵), so the starting values do not lower the order); with a
//! variable step the method starts at order 1 and raises the order by one per step, every
//! step under error control. Dense output: cubic Hermite.
//!
//! **Variable step** (no `fixed_step`): the local error of the corrector is estimated by
//! Milne's device, `err ≈ C^{AM}/(C^{AB} − C^{AM}) · (y_{n+1} − y*)` with the error constants
//! `C^{AB}_{k+1} = 1/2, 5/12, 3/8, 251/720` and `C^{AM}_{k+1} = −1/2, −1/12, −1/24, −19/720`;
//! the step ratio is `clamp(0.9 · err^{−1/(k+1)}, 0.2, 2)`. A change of step (also one forced by
//! the stop time or a step cap, in both modes) re-samples the derivative history on the new
//! equidistant grid from its interpolating polynomial of degree k − 1 (the "interpolation"
//! strategy of variable-step multistep methods, HNW I §III.5), so the constant-step
//! coefficients stay valid.

use super::explicit::rk4_step;
use super::{
    OdeOptions, OdeStepper, OdeSystem, check_interpolation_range, check_state, hermite_interpolate,
    limit_step, rms_norm,
};
use crate::error::IntegrateError;
use crate::ode::eval_rhs;
use crate::stats::Stats;

const MAX_ORDER: usize = 4;

/// Adams–Bashforth weights of `f_n, f_{n−1}, …` for orders 1..=4.
const AB: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [3.0 / 2.0, -1.0 / 2.0, 0.0, 0.0],
    [23.0 / 12.0, -16.0 / 12.0, 5.0 / 12.0, 0.0],
    [55.0 / 24.0, -59.0 / 24.0, 37.0 / 24.0, -9.0 / 24.0],
];

/// Adams–Moulton weights of `f_{n+1}, f_n, f_{n−1}, …` for orders 1..=4.
const AM: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [1.0 / 2.0, 1.0 / 2.0, 0.0, 0.0],
    [5.0 / 12.0, 8.0 / 12.0, -1.0 / 12.0, 0.0],
    [9.0 / 24.0, 19.0 / 24.0, -5.0 / 24.0, 1.0 / 24.0],
];

/// Milne factors `C^{AM}_{k+1} / (C^{AB}_{k+1} − C^{AM}_{k+1})` for orders 1..=4.
const MILNE: [f64; 4] = [-0.5, -1.0 / 6.0, -0.1, -19.0 / 270.0];

const SAFETY: f64 = 0.9;
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 2.0;

/// Adams–Bashforth–Moulton PECE stepper (see the module documentation).
#[derive(Debug, Clone)]
pub struct AdamsPece {
    order: usize,
    rtol: f64,
    atol: f64,
    fixed_step: Option<f64>,
    initial_step: Option<f64>,
    h_next: f64,
    /// Spacing of the stored derivative history.
    spacing: f64,
    h_cap: f64,
    max_step: f64,
    max_steps: usize,
    t_stop: Option<f64>,
    t: f64,
    t_prev: f64,
    y: Vec<f64>,
    y_prev: Vec<f64>,
    y_new: Vec<f64>,
    /// `f_n, f_{n−1}, …` (newest first) on the grid of spacing `spacing`; `history_len` valid.
    f_hist: Vec<Vec<f64>>,
    f_tmp: Vec<Vec<f64>>,
    history_len: usize,
    f_prev: Vec<f64>,
    predicted: Vec<f64>,
    f_star: Vec<f64>,
    scale: Vec<f64>,
    rk_work: [Vec<f64>; 4],
    stats: Stats,
}

impl AdamsPece {
    /// `options.order` in 1..=4 (default 4); fixed step if `options.fixed_step` is set,
    /// variable step with `rtol`/`atol` otherwise.
    pub fn new(dim: usize, options: &OdeOptions) -> Result<Self, IntegrateError> {
        options.validate()?;
        let order = options.order.unwrap_or(MAX_ORDER);
        if !(1..=MAX_ORDER).contains(&order) {
            return Err(super::invalid(
                "order",
                format!("Adams order must be in 1..=4, got {order}"),
            ));
        }
        let v = || vec![0.0; dim];
        Ok(Self {
            order,
            rtol: options.rtol,
            atol: options.atol,
            fixed_step: options.fixed_step,
            initial_step: options.initial_step,
            h_next: 0.0,
            spacing: 0.0,
            h_cap: f64::INFINITY,
            max_step: options.max_step,
            max_steps: options.max_steps,
            t_stop: None,
            t: 0.0,
            t_prev: 0.0,
            y: v(),
            y_prev: v(),
            y_new: v(),
            f_hist: (0..MAX_ORDER).map(|_| v()).collect(),
            f_tmp: (0..MAX_ORDER).map(|_| v()).collect(),
            history_len: 0,
            f_prev: v(),
            predicted: v(),
            f_star: v(),
            scale: v(),
            rk_work: [v(), v(), v(), v()],
            stats: Stats::default(),
        })
    }

    fn h_limit(&self) -> f64 {
        self.h_cap.min(self.max_step)
    }

    /// Starting step for the order-1 start from `‖y‖`, `‖f‖` and a difference estimate of `‖y''‖`
    /// (Hairer–Nørsett–Wanner I, II.4). One evaluation of `f`.
    fn initial_step_size(&mut self, sys: &mut dyn OdeSystem) -> Result<f64, IntegrateError> {
        let n = self.y.len();
        for i in 0..n {
            self.scale[i] = self.atol + self.rtol * self.y[i].abs();
        }
        let d0 = rms_norm(&self.y, &self.scale);
        let d1 = rms_norm(&self.f_hist[0], &self.scale);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        for i in 0..n {
            self.predicted[i] = self.y[i] + h0 * self.f_hist[0][i];
        }
        eval_rhs(sys, self.t + h0, &self.predicted, &mut self.f_star)?;
        self.stats.f_evals += 1;
        for i in 0..n {
            self.y_new[i] = self.f_star[i] - self.f_hist[0][i];
        }
        let d2 = rms_norm(&self.y_new, &self.scale) / h0;
        let h1 = if d1.max(d2) <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            // The variable-step start is of order 1.
            (0.01 / d1.max(d2)).sqrt()
        };
        Ok((100.0 * h0).min(h1).min(self.h_limit()))
    }

    /// Re-sample the derivative history on the grid of spacing `ratio · spacing`: with nodes
    /// `s_m = −m` (in units of the old spacing), `f̃_j = Σ_m ℓ_m(−j·ratio) f_m`, Lagrange basis
    /// `ℓ_m(s) = Π_{q≠m} (s + q)/(q − m)`.
    fn resample_history(&mut self, ratio: f64) {
        let len = self.history_len;
        for j in 1..len {
            let s = -(j as f64) * ratio;
            self.f_tmp[j].fill(0.0);
            for m in 0..len {
                let mut weight = 1.0;
                for q in (0..len).filter(|&q| q != m) {
                    weight *= (s + q as f64) / (q as f64 - m as f64);
                }
                for (out, fm) in self.f_tmp[j].iter_mut().zip(&self.f_hist[m]) {
                    *out += weight * fm;
                }
            }
        }
        for j in 1..len {
            std::mem::swap(&mut self.f_hist[j], &mut self.f_tmp[j]);
        }
        self.spacing *= ratio;
    }

    /// PECE step of order `k` (≤ the history length) and size h into `y_new`; returns the
    /// Milne error norm.
    #[allow(clippy::needless_range_loop)]
    fn pece(&mut self, sys: &mut dyn OdeSystem, h: f64, k: usize) -> Result<f64, IntegrateError> {
        let n = self.y.len();
        for i in 0..n {
            let mut acc = 0.0;
            for j in 0..k {
                acc += AB[k - 1][j] * self.f_hist[j][i];
            }
            self.predicted[i] = self.y[i] + h * acc;
        }
        eval_rhs(sys, self.t + h, &self.predicted, &mut self.f_star)?;
        self.stats.f_evals += 1;
        for i in 0..n {
            let mut acc = AM[k - 1][0] * self.f_star[i];
            for j in 1..k {
                acc += AM[k - 1][j] * self.f_hist[j - 1][i];
            }
            self.y_new[i] = self.y[i] + h * acc;
            // Milne's estimate, kept in `predicted`.
            self.scale[i] = self.atol + self.rtol * self.y[i].abs().max(self.y_new[i].abs());
            self.predicted[i] = MILNE[k - 1] * (self.y_new[i] - self.predicted[i]);
        }
        let err = rms_norm(&self.predicted, &self.scale);
        Ok(if err.is_finite() { err } else { f64::INFINITY })
    }

    /// Accept `y_new` at `t + h`: rotate states and history, evaluate `f` at the new point.
    fn accept(&mut self, sys: &mut dyn OdeSystem, h: f64) -> Result<(), IntegrateError> {
        self.f_prev.copy_from_slice(&self.f_hist[0]);
        std::mem::swap(&mut self.y_prev, &mut self.y);
        std::mem::swap(&mut self.y, &mut self.y_new);
        self.t_prev = self.t;
        self.t += h;
        self.f_hist.rotate_right(1);
        eval_rhs(sys, self.t, &self.y, &mut self.f_hist[0])?;
        self.stats.f_evals += 1;
        self.history_len = (self.history_len + 1).min(self.order);
        self.stats.steps += 1;
        Ok(())
    }
}

impl OdeStepper for AdamsPece {
    fn name(&self) -> &'static str {
        "adams"
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
        self.y_prev.copy_from_slice(y);
        eval_rhs(sys, t, y, &mut self.f_hist[0])?;
        self.stats.f_evals += 1;
        self.f_prev.copy_from_slice(&self.f_hist[0]);
        self.history_len = 1;
        self.h_next = match (self.fixed_step, self.initial_step) {
            (Some(h), _) | (None, Some(h)) => h,
            (None, None) => self.initial_step_size(sys)?,
        };
        self.spacing = self.h_next;
        Ok(())
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        loop {
            let h = limit_step(self.t, self.h_next, self.h_limit(), self.t_stop);
            if h <= 10.0 * f64::EPSILON * self.t.abs().max(1.0) || !h.is_finite() {
                return Err(IntegrateError::StepSizeTooSmall { t: self.t, h });
            }
            if h != self.spacing {
                self.resample_history(h / self.spacing);
            }
            if self.history_len < self.order && self.fixed_step.is_some() {
                let [w0, w1, w2, w3] = &mut self.rk_work;
                rk4_step(
                    sys,
                    self.t,
                    h,
                    &self.y,
                    &self.f_hist[0],
                    [w0, w1, w2, w3],
                    &mut self.y_new,
                )?;
                self.stats.f_evals += 3;
                if self.y_new.iter().any(|v| !v.is_finite()) {
                    return Err(IntegrateError::NonFinite { t: self.t + h });
                }
                self.accept(sys, h)?;
                return Ok(());
            }
            // Variable step starts with order 1 and raises the order by one per step as the
            // history fills (every step error-controlled).
            let k = self.history_len.min(self.order);
            let err = self.pece(sys, h, k)?;
            if let Some(hf) = self.fixed_step {
                if self.y_new.iter().any(|v| !v.is_finite()) {
                    return Err(IntegrateError::NonFinite { t: self.t + h });
                }
                self.accept(sys, h)?;
                self.h_next = hf;
                return Ok(());
            }
            let factor = (SAFETY * err.powf(-1.0 / (k + 1) as f64)).clamp(FAC_MIN, FAC_MAX);
            if err > 1.0 {
                self.stats.rejected_steps += 1;
                self.h_next = h * factor;
                continue;
            }
            self.accept(sys, h)?;
            self.h_next = (h * factor).min(self.h_limit());
            return Ok(());
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
        hermite_interpolate(
            t,
            self.t_prev,
            self.t - self.t_prev,
            (&self.y_prev, &self.f_prev),
            (&self.y, &self.f_hist[0]),
            out,
        );
        Ok(())
    }

    stepper_bookkeeping!();
}
