//! Adams–Bashforth–Moulton predictor–corrector in PECE mode, fixed step, orders 1–4
//! (Hairer–Nørsett–Wanner I, §III.1; Butcher 2016, §24).
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
//! rule. Two evaluations of `f` per step. The first k − 1 steps are classic RK4 steps (local
//! error O(h⁵), so the starting values do not lower the order). Dense output: cubic Hermite.

use super::explicit::rk4_step;
use super::{
    OdeOptions, OdeStepper, OdeSystem, check_interpolation_range, check_state, hermite_interpolate,
    limit_step,
};
use crate::error::IntegrateError;
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

/// Adams–Bashforth–Moulton PECE stepper (see the module documentation).
#[derive(Debug, Clone)]
pub struct AdamsPece {
    order: usize,
    h: f64,
    h_cap: f64,
    max_step: f64,
    max_steps: usize,
    t_stop: Option<f64>,
    t: f64,
    t_prev: f64,
    y: Vec<f64>,
    y_prev: Vec<f64>,
    /// `f_n, f_{n−1}, …` (newest first), `history_len` of them valid.
    f_hist: Vec<Vec<f64>>,
    history_len: usize,
    f_prev: Vec<f64>,
    predicted: Vec<f64>,
    f_star: Vec<f64>,
    rk_work: [Vec<f64>; 4],
    stats: Stats,
}

impl AdamsPece {
    /// Needs `options.fixed_step`; `options.order` in 1..=4 (default 4).
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
            h: options.required_fixed_step("adams")?,
            h_cap: f64::INFINITY,
            max_step: options.max_step,
            max_steps: options.max_steps,
            t_stop: None,
            t: 0.0,
            t_prev: 0.0,
            y: v(),
            y_prev: v(),
            f_hist: (0..MAX_ORDER).map(|_| v()).collect(),
            history_len: 0,
            f_prev: v(),
            predicted: v(),
            f_star: v(),
            rk_work: [v(), v(), v(), v()],
            stats: Stats::default(),
        })
    }

    /// PECE step of size h with the full history.
    #[allow(clippy::needless_range_loop)]
    fn pece(&mut self, sys: &mut dyn OdeSystem, h: f64) {
        let k = self.order;
        let n = self.y.len();
        for i in 0..n {
            let mut acc = 0.0;
            for j in 0..k {
                acc += AB[k - 1][j] * self.f_hist[j][i];
            }
            self.predicted[i] = self.y_prev[i] + h * acc;
        }
        sys.rhs(self.t_prev + h, &self.predicted, &mut self.f_star);
        for i in 0..n {
            let mut acc = AM[k - 1][0] * self.f_star[i];
            for j in 1..k {
                acc += AM[k - 1][j] * self.f_hist[j - 1][i];
            }
            self.y[i] = self.y_prev[i] + h * acc;
        }
        self.stats.f_evals += 1;
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
        sys.rhs(t, y, &mut self.f_hist[0]);
        self.stats.f_evals += 1;
        self.f_prev.copy_from_slice(&self.f_hist[0]);
        self.history_len = 1;
        Ok(())
    }

    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        let h = limit_step(self.t, self.h, self.h_cap.min(self.max_step), self.t_stop);
        std::mem::swap(&mut self.y, &mut self.y_prev);
        self.f_prev.copy_from_slice(&self.f_hist[0]);
        self.t_prev = self.t;
        if self.history_len < self.order {
            let [w0, w1, w2, w3] = &mut self.rk_work;
            rk4_step(
                sys,
                self.t_prev,
                h,
                &self.y_prev,
                &self.f_hist[0],
                [w0, w1, w2, w3],
                &mut self.y,
            );
            self.stats.f_evals += 3;
        } else {
            self.pece(sys, h);
        }
        self.t = self.t_prev + h;
        if self.y.iter().any(|v| !v.is_finite()) {
            return Err(IntegrateError::NonFinite { t: self.t });
        }
        // Newest derivative goes to the front; the oldest vector is recycled.
        self.f_hist.rotate_right(1);
        sys.rhs(self.t, &self.y, &mut self.f_hist[0]);
        self.stats.f_evals += 1;
        self.history_len = (self.history_len + 1).min(MAX_ORDER);
        self.stats.steps += 1;
        Ok(())
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

    fn stats(&self) -> Stats {
        self.stats
    }

    fn reset_stats(&mut self) {
        self.stats = Stats::default();
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
