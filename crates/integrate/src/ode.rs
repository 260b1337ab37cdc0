//! First-order systems `y' = f(t, y)` and the methods that integrate them.
//!
//! # Problem / method separation
//! A problem implements [`OdeSystem`] (right-hand side with `&mut self`, so a contact model can
//! cache warm-start state; optional analytic Jacobian, finite differences otherwise). A method
//! implements [`OdeStepper`]: it is initialised with [`OdeStepper::set_state`], advanced one
//! accepted step at a time with [`OdeStepper::step`], read with [`OdeStepper::t`] /
//! [`OdeStepper::y`], and interpolated inside the last step with [`OdeStepper::interpolate`].
//! An outer loop may change the state between steps (`set_state` restarts the method, e.g.
//! after a discontinuity) and cap the step ([`OdeStepper::set_max_step`]).
//!
//! | name (`Method::from_name`) | method | order | step | dense output |
//! |---|---|---|---|---|
//! | `euler` | explicit Euler | 1 | fixed | cubic Hermite |
//! | `rk4` | classic Runge–Kutta | 4 | fixed | cubic Hermite |
//! | `dopri5` | Dormand–Prince 5(4), PI control | 5 | adaptive or fixed | 4th-order Hairer |
//! | `backward_euler` | implicit Euler, Newton | 1 | fixed | cubic Hermite |
//! | `radau5` | Radau IIA, 3 stages (RADAU5 design) | 5 | adaptive or fixed | collocation |
//! | `bdf` | variable-order BDF 1–5 (backward differences) | 1–5 | adaptive or fixed | interpolating polynomial |
//! | `adams` | Adams–Bashforth–Moulton PECE | 1–4 | adaptive or fixed | cubic Hermite |
//!
//! The convenience driver [`solve`] integrates to `t_end`, collects output, locates events
//! (zero crossings of user functions) and guards short contacts (see [`events`]).
//! Only forward integration (`t` increasing) is supported.
//!
//! # Example: an outer loop driving a method step by step
//! ```
//! use integrate::ode::{Method, OdeOptions, OdeStepper, OdeSystem};
//!
//! /// y' = −2y.
//! struct Decay;
//! impl OdeSystem for Decay {
//!     fn dim(&self) -> usize { 1 }
//!     fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) { dydt[0] = -2.0 * y[0]; }
//! }
//!
//! let method = Method::from_name("radau5")?;
//! let mut stepper = method.build(1, &OdeOptions::adaptive(1e-8, 1e-10))?;
//! let mut sys = Decay;
//! stepper.set_state(&mut sys, 0.0, &[1.0])?;
//! stepper.set_stop_time(Some(1.0));
//! while stepper.t() < 1.0 {
//!     stepper.step(&mut sys)?;
//!     // ... the outer simulation may inspect or change the state here, e.g. restart after a
//!     // discontinuity with `stepper.set_state(&mut sys, t, &y_new)`.
//! }
//! assert!((stepper.y()[0] - (-2.0f64).exp()).abs() < 1e-7);
//! # Ok::<(), integrate::IntegrateError>(())
//! ```

/// The bookkeeping methods of [`OdeStepper`] that the steppers implement identically
/// (statistics, step cap, stop time, last step size), for a stepper that keeps `t`, `t_prev`,
/// `stats`, `h_cap` and `t_stop` in itself (`stepper_bookkeeping!()`) or in a field
/// (`stepper_bookkeeping!(state)`).
macro_rules! stepper_bookkeeping {
    ($($path:ident).*) => {
        fn stats(&self) -> Stats {
            self$(.$path)*.stats
        }
        fn reset_stats(&mut self) {
            self$(.$path)*.stats = Stats::default();
        }
        fn set_max_step(&mut self, h_max: f64) {
            self$(.$path)*.h_cap = if h_max > 0.0 { h_max } else { f64::INFINITY };
        }
        fn set_stop_time(&mut self, t_stop: Option<f64>) {
            self$(.$path)*.t_stop = t_stop;
        }
        fn last_step_size(&self) -> f64 {
            self$(.$path)*.t - self$(.$path)*.t_prev
        }
    };
}

#[macro_use]
mod fixed_step;
mod adams;
mod backward_euler;
mod bdf;
pub mod events;
mod explicit;
mod linalg;
mod radau5;

pub use adams::AdamsPece;
pub use backward_euler::BackwardEuler;
pub use bdf::Bdf;
pub use events::{Direction, Event, EventRecord, Output, Solution, solve, solve_observed};
pub use explicit::{Dopri5, ExplicitEuler, Rk4};
pub use linalg::finite_difference_jacobian;
pub use radau5::Radau5;

use crate::error::{CallbackError, IntegrateError};
use crate::stats::Stats;
use faer::MatMut;

/// A system given by a fallible closure `f(t, y, dydt) -> Result<(), E>`: an error of the
/// closure stops the method, which returns [`IntegrateError::Callback`] holding it unchanged.
///
/// ```
/// use integrate::ode::{FallibleRhs, Method, OdeOptions};
///
/// #[derive(Debug, thiserror::Error, PartialEq)]
/// #[error("contact solver failed")]
/// struct ContactFailed;
///
/// let mut sys = FallibleRhs::new(1, |t: f64, _y: &[f64], dydt: &mut [f64]| {
///     if t > 0.5 { return Err(ContactFailed); }
///     dydt[0] = 1.0;
///     Ok(())
/// });
/// let mut stepper = Method::Rk4.build(1, &OdeOptions::fixed(0.1))?;
/// stepper.set_state(&mut sys, 0.0, &[0.0])?;
/// let err = loop {
///     if let Err(e) = stepper.step(&mut sys) { break e; }
/// };
/// assert_eq!(err.callback_error::<ContactFailed>(), Some(&ContactFailed));
/// # Ok::<(), integrate::IntegrateError>(())
/// ```
pub struct FallibleRhs<F> {
    dim: usize,
    f: F,
}

impl<F> FallibleRhs<F> {
    /// A system of `dim` unknowns with the right-hand side `f`.
    pub fn new(dim: usize, f: F) -> Self {
        Self { dim, f }
    }
}

impl<F, E> OdeSystem for FallibleRhs<F>
where
    F: FnMut(f64, &[f64], &mut [f64]) -> Result<(), E>,
    E: std::error::Error + Send + Sync + 'static,
{
    fn dim(&self) -> usize {
        self.dim
    }
    /// The infallible form: an error of the closure becomes NaN (rejected as non-finite).
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        if (self.f)(t, y, dydt).is_err() {
            dydt.fill(f64::NAN);
        }
    }
    fn try_rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) -> Result<(), CallbackError> {
        (self.f)(t, y, dydt).map_err(CallbackError::new)
    }
}

/// `f(t, y)` through [`OdeSystem::try_rhs`], a callback error carried as
/// [`IntegrateError::Callback`].
pub(crate) fn eval_rhs(
    sys: &mut dyn OdeSystem,
    t: f64,
    y: &[f64],
    dydt: &mut [f64],
) -> Result<(), IntegrateError> {
    sys.try_rhs(t, y, dydt)
        .map_err(|error| IntegrateError::Callback { t, error })
}

/// A first-order system `y' = f(t, y)` of fixed dimension.
///
/// `rhs` takes `&mut self` so that models with internal caches (the contact solver's warm
/// start) can update them. A model that cannot evaluate `f` has two ways to say so:
///
/// * return its own error from [`try_rhs`](Self::try_rhs) (or [`try_jacobian`](Self::try_jacobian)):
///   every method stops and returns [`IntegrateError::Callback`] carrying that error unchanged
///   (recover it with [`IntegrateError::callback_error`]). [`FallibleRhs`] wraps a closure
///   `FnMut(t, y, dydt) -> Result<(), E>` for this;
/// * write a non-finite value from `rhs`: adaptive methods then reject the step and retry with
///   a smaller one, fixed-step methods return [`IntegrateError::NonFinite`].
///
/// The methods call `try_rhs` and `try_jacobian` only; their defaults forward to the
/// infallible `rhs` and `jacobian`.
pub trait OdeSystem {
    /// Number of unknowns.
    fn dim(&self) -> usize;
    /// Evaluate `dydt = f(t, y)`.
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]);
    /// Evaluate `dydt = f(t, y)` or fail with the caller's error (default: [`Self::rhs`],
    /// never fails).
    fn try_rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) -> Result<(), CallbackError> {
        self.rhs(t, y, dydt);
        Ok(())
    }
    /// As [`Self::jacobian`], or fail with the caller's error (default: [`Self::jacobian`],
    /// never fails).
    fn try_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        jac: MatMut<'_, f64>,
    ) -> Result<bool, CallbackError> {
        Ok(self.jacobian(t, y, jac))
    }
    /// Write the analytic Jacobian `∂f/∂y (t, y)` into `jac` (dim × dim) and return `true`, or
    /// return `false` (the default) to request finite differences
    /// ([`finite_difference_jacobian`]).
    fn jacobian(&mut self, t: f64, y: &[f64], jac: MatMut<'_, f64>) -> bool {
        let _ = (t, y, jac);
        false
    }
}

/// Settings shared by all methods. Fields a method does not use are ignored
/// (`rtol`/`atol` by the fixed-step methods, `order` by the one-step methods).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OdeOptions {
    /// Relative tolerance of the local error test (adaptive mode); also scales the Newton
    /// convergence test of the implicit methods.
    pub rtol: f64,
    /// Absolute tolerance of the local error test.
    pub atol: f64,
    /// `Some(h)`: take steps of exactly `h` (required by euler, rk4 and backward_euler;
    /// optional for dopri5, radau5, bdf and adams, which are adaptive when it is `None`).
    pub fixed_step: Option<f64>,
    /// First trial step of an adaptive method; `None` chooses one automatically.
    pub initial_step: Option<f64>,
    /// Upper bound of the step size (default: unbounded).
    pub max_step: f64,
    /// Upper bound on the number of accepted steps of one stepper (counted from the last
    /// `reset_stats`).
    pub max_steps: usize,
    /// BDF: maximum order (adaptive) or the order (fixed step), 1..=5, default 5.
    /// Adams: the order, 1..=4, default 4.
    pub order: Option<usize>,
}

impl Default for OdeOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol: 1e-9,
            fixed_step: None,
            initial_step: None,
            max_step: f64::INFINITY,
            max_steps: 10_000_000,
            order: None,
        }
    }
}

impl OdeOptions {
    /// Adaptive stepping with the given tolerances.
    pub fn adaptive(rtol: f64, atol: f64) -> Self {
        Self {
            rtol,
            atol,
            ..Self::default()
        }
    }

    /// Fixed steps of size `h`.
    pub fn fixed(h: f64) -> Self {
        Self {
            fixed_step: Some(h),
            ..Self::default()
        }
    }

    /// Check every field; the error names the offending field.
    pub fn validate(&self) -> Result<(), IntegrateError> {
        positive_finite("rtol", self.rtol)?;
        if !(self.atol >= 0.0 && self.atol.is_finite()) {
            return Err(invalid(
                "atol",
                format!("must be finite and >= 0, got {}", self.atol),
            ));
        }
        if let Some(h) = self.fixed_step {
            positive_finite("fixed_step", h)?;
        }
        if let Some(h) = self.initial_step {
            positive_finite("initial_step", h)?;
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return Err(invalid(
                "max_step",
                format!("must be > 0, got {}", self.max_step),
            ));
        }
        if self.max_steps == 0 {
            return Err(invalid("max_steps", "must be >= 1, got 0".to_string()));
        }
        Ok(())
    }

    /// The fixed step, or an error naming `fixed_step` for a method that needs one.
    pub(crate) fn required_fixed_step(&self, method: &str) -> Result<f64, IntegrateError> {
        self.fixed_step.ok_or_else(|| {
            invalid(
                "fixed_step",
                format!("method `{method}` is a fixed-step method and needs `fixed_step`"),
            )
        })
    }
}

/// One method, driven step by step. All methods are object safe (`Box<dyn OdeStepper>`).
pub trait OdeStepper {
    /// The method's name as accepted by [`Method::from_name`].
    fn name(&self) -> &'static str;
    /// (Re)start the method at `(t, y)`: the history of multistep methods is discarded and
    /// the next step is a starting step. Statistics are kept (see [`Self::reset_stats`]).
    fn set_state(
        &mut self,
        sys: &mut dyn OdeSystem,
        t: f64,
        y: &[f64],
    ) -> Result<(), IntegrateError>;
    /// Advance by one accepted step (adaptive methods retry internally until the local
    /// error test passes). Never steps past the stop time set by [`Self::set_stop_time`].
    fn step(&mut self, sys: &mut dyn OdeSystem) -> Result<(), IntegrateError>;
    /// Current time.
    fn t(&self) -> f64;
    /// Current state.
    fn y(&self) -> &[f64];
    /// Start of the last accepted step (equal to `t()` right after `set_state`).
    fn t_prev(&self) -> f64;
    /// State at `t ∈ [t_prev(), t()]` from the method's dense output.
    fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), IntegrateError>;
    /// Counters since construction or the last [`Self::reset_stats`].
    fn stats(&self) -> Stats;
    /// Zero the counters.
    fn reset_stats(&mut self);
    /// Cap every following step at `h_max` (`f64::INFINITY` removes the cap set here; the
    /// cap of the options always applies).
    fn set_max_step(&mut self, h_max: f64);
    /// Do not step past `t_stop` (`None` removes the limit); the step that reaches it ends
    /// exactly on it.
    fn set_stop_time(&mut self, t_stop: Option<f64>);
    /// Size of the last accepted step.
    fn last_step_size(&self) -> f64;
}

/// The methods selectable by name (for the CLI).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Explicit Euler.
    Euler,
    /// Classic fourth-order Runge–Kutta.
    Rk4,
    /// Dormand–Prince 5(4).
    Dopri5,
    /// Backward (implicit) Euler.
    BackwardEuler,
    /// Radau IIA of order 5.
    Radau5,
    /// Variable-order BDF.
    Bdf,
    /// Adams–Bashforth–Moulton PECE.
    Adams,
}

impl Method {
    /// All methods, in the order of the module table.
    pub const ALL: [Method; 7] = [
        Method::Euler,
        Method::Rk4,
        Method::Dopri5,
        Method::BackwardEuler,
        Method::Radau5,
        Method::Bdf,
        Method::Adams,
    ];

    /// Parse `euler`, `rk4`, `dopri5`, `backward_euler`, `radau5`, `bdf`, `adams`
    /// (case-insensitive, `-` accepted for `_`).
    pub fn from_name(name: &str) -> Result<Self, IntegrateError> {
        let key = name.trim().to_ascii_lowercase().replace('-', "_");
        Self::ALL
            .into_iter()
            .find(|m| m.name() == key)
            .ok_or_else(|| invalid("method", format!("unknown method `{name}`")))
    }

    /// The canonical name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Euler => "euler",
            Method::Rk4 => "rk4",
            Method::Dopri5 => "dopri5",
            Method::BackwardEuler => "backward_euler",
            Method::Radau5 => "radau5",
            Method::Bdf => "bdf",
            Method::Adams => "adams",
        }
    }

    /// Build a stepper for a system of dimension `dim`.
    pub fn build(
        self,
        dim: usize,
        options: &OdeOptions,
    ) -> Result<Box<dyn OdeStepper>, IntegrateError> {
        Ok(match self {
            Method::Euler => Box::new(ExplicitEuler::new(dim, options)?),
            Method::Rk4 => Box::new(Rk4::new(dim, options)?),
            Method::Dopri5 => Box::new(Dopri5::new(dim, options)?),
            Method::BackwardEuler => Box::new(BackwardEuler::new(dim, options)?),
            Method::Radau5 => Box::new(Radau5::new(dim, options)?),
            Method::Bdf => Box::new(Bdf::new(dim, options)?),
            Method::Adams => Box::new(AdamsPece::new(dim, options)?),
        })
    }
}

pub(crate) fn invalid(name: &'static str, reason: String) -> IntegrateError {
    IntegrateError::InvalidParameter { name, reason }
}

pub(crate) fn positive_finite(name: &'static str, value: f64) -> Result<(), IntegrateError> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(invalid(
            name,
            format!("must be finite and > 0, got {value}"),
        ))
    }
}

/// Validate the arguments of `set_state`: dimension, finite time and state.
pub(crate) fn check_state(
    sys: &dyn OdeSystem,
    dim: usize,
    t: f64,
    y: &[f64],
) -> Result<(), IntegrateError> {
    if sys.dim() != dim || y.len() != dim {
        return Err(IntegrateError::DimensionMismatch {
            expected: dim,
            found: if sys.dim() != dim { sys.dim() } else { y.len() },
        });
    }
    if !t.is_finite() || y.iter().any(|v| !v.is_finite()) {
        return Err(IntegrateError::NonFinite { t });
    }
    Ok(())
}

/// Error unless `t ∈ [t0 − tol, t1 + tol]` with a rounding tolerance relative to the step.
pub(crate) fn check_interpolation_range(t: f64, t0: f64, t1: f64) -> Result<(), IntegrateError> {
    let tol = 1e-12 * (t1 - t0).abs().max(t1.abs() * f64::EPSILON);
    if t.is_finite() && t >= t0 - tol && t <= t1 + tol {
        Ok(())
    } else {
        Err(IntegrateError::OutsideLastStep {
            t,
            t_start: t0,
            t_end: t1,
        })
    }
}

/// The step actually taken from `t` with the wished size `h`: capped by `h_max` and, when a
/// stop time is set, shortened to land exactly on it (a step within 1e-10·h of the stop time
/// is stretched onto it rather than leaving a sliver).
pub(crate) fn limit_step(t: f64, h: f64, h_max: f64, t_stop: Option<f64>) -> f64 {
    let mut h = h.min(h_max);
    if let Some(ts) = t_stop {
        let remaining = ts - t;
        if remaining > 0.0 && (t + h * (1.0 + 1e-10) >= ts) {
            h = remaining;
        }
    }
    h
}

/// Weighted root-mean-square norm `sqrt(Σ (v_i / (atol + rtol·|s_i|))² / n)`, the error norm
/// of Hairer–Wanner (II.4.11).
pub(crate) fn rms_norm(v: &[f64], scale: &[f64]) -> f64 {
    let n = v.len().max(1) as f64;
    (v.iter()
        .zip(scale)
        .map(|(a, s)| (a / s) * (a / s))
        .sum::<f64>()
        / n)
        .sqrt()
}

/// Cubic Hermite interpolation on `[t0, t0 + h]` from the end values and derivatives
/// (Hairer–Nørsett–Wanner I, II.6): third-order accurate dense output of the fixed-step methods.
pub(crate) fn hermite_interpolate(
    t: f64,
    t0: f64,
    h: f64,
    (y0, f0): (&[f64], &[f64]),
    (y1, f1): (&[f64], &[f64]),
    out: &mut [f64],
) {
    if h == 0.0 {
        out.copy_from_slice(y1);
        return;
    }
    let s = (t - t0) / h;
    let h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s);
    let h10 = s * (1.0 - s) * (1.0 - s);
    let h01 = s * s * (3.0 - 2.0 * s);
    let h11 = s * s * (s - 1.0);
    for i in 0..out.len() {
        out[i] = h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i];
    }
}
