//! Peak response of a modal beam to one passage of a train of moving forces, for speed sweeps
//! (EN 1991-2 §6.4.6: every train at every speed; references.md §T2).
//!
//! The physics is that of [`crate::moving`]: axle k at x_k(t) = c t − d_k loads the span while
//! 0 ≤ x_k ≤ L, the modal forces f_j(t) = Σ_(k on span) F_k w_j(x_k(t)) / m_j are sampled at
//! the step times and taken piecewise linear in between, and each mode is advanced with the
//! exact propagator [`PiecewiseLinearSdof`] (Nigam–Jennings-type recurrence). A passage only
//! keeps the peaks at the output points (no time history), so thousands of passages cost no
//! memory; a [`PassagePlan`] is built once per bridge, step and output points (the propagators
//! and the output shapes) and shared by every passage, each with its own [`PassageWork`].
//!
//! Simply supported uniform spans, whose mass-normalised shapes are w_j(x) = A_j sin(jπx/L),
//! are detected from the basis itself (the shapes are checked at several points) and evaluated
//! with one `sin_cos` per axle and step and the Chebyshev recurrence
//! sin((j+1)θ) = 2 cos θ sin(jθ) − sin((j−1)θ); any other basis is evaluated through
//! [`ModalBasis::eval_all`].
//!
//! Outputs at x_p: the deflection w = Σ_j w_j(x_p) q_j, the acceleration
//! ẅ = Σ_j w_j(x_p) q̈_j with q̈_j = f_j − c_j q̇_j − ω_j² q_j (exact at the step times), and the
//! quasi-static deflection Σ_j w_j(x_p) f_j/ω_j² of the same modes (so that the ratio of the
//! two peaks, φ', tends to 1 as the speed tends to 0).

use crate::damping::ModalDamping;
use crate::error::{BeamError, MAX_MODES, check_size, inside_span, non_negative, positive};
use crate::modal::{Derivative, ModalBasis};
use crate::moving::{Axle, MAX_STEPS};
use crate::sdof::PiecewiseLinearSdof;

/// Largest relative difference between a basis shape and A_j sin(jπx/L) for the sine path.
const SINE_SHAPE_TOLERANCE: f64 = 1e-9;

/// What one passage is planned with: propagators, damping, output shapes (built once).
#[derive(Debug, Clone)]
pub struct PassagePlan {
    dt: f64,
    length: f64,
    omegas: Vec<f64>,
    velocity_coefficients: Vec<f64>,
    inv_mass: Vec<f64>,
    steppers: Vec<PiecewiseLinearSdof>,
    /// w_j(x_p), point-major (`[p * n + j]`).
    point_shapes: Vec<f64>,
    points: Vec<f64>,
    /// A_j of w_j = A_j sin((j+1)πx/L) when the basis is a simply supported uniform span.
    sine_amplitudes: Option<Vec<f64>>,
}

/// Peaks of one passage at each output point (absolute values).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PassagePeaks {
    /// max_t |w(x_p, t)| \[m\].
    pub deflection: Vec<f64>,
    /// max_t |ẅ(x_p, t)| \[m/s²\].
    pub acceleration: Vec<f64>,
    /// max_t |w_static(x_p, t)| \[m\] (quasi-static, same modes).
    pub static_deflection: Vec<f64>,
    /// Time steps taken.
    pub steps: usize,
}

/// Buffers of one passage (one per thread; no allocation inside the time loop).
#[derive(Debug, Clone, Default)]
pub struct PassageWork {
    q: Vec<f64>,
    v: Vec<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
    shapes: Vec<f64>,
}

impl PassagePlan {
    /// Plans passages over `basis` with modal `damping`, time step `dt` \[s\] and output points
    /// `points` \[m\]. Every mode must be elastic (ω_j > 0): a rigid-body mode has no
    /// quasi-static response.
    pub fn new(
        basis: &dyn ModalBasis,
        damping: &ModalDamping,
        dt: f64,
        points: &[f64],
    ) -> Result<Self, BeamError> {
        let dt = positive("dt", dt)?;
        let n = basis.n_modes();
        check_size("n_modes", n, MAX_MODES, "a passage plan", |n| {
            16.0 * n as f64
        })?;
        let omegas = basis.circular_frequencies().to_vec();
        if let Some(j) = omegas.iter().position(|&w| w.is_nan() || w <= 0.0) {
            return Err(BeamError::InvalidParameter {
                name: "omega",
                value: omegas[j],
                reason: "a passage needs elastic modes only (no rigid-body mode)",
            });
        }
        let velocity_coefficients = damping.velocity_coefficients(&omegas)?;
        let inv_mass = (0..n)
            .map(|j| basis.modal_mass(j).map(|m| 1.0 / m))
            .collect::<Result<Vec<_>, _>>()?;
        let steppers = omegas
            .iter()
            .zip(&velocity_coefficients)
            .map(|(&w, &c)| PiecewiseLinearSdof::new(w, c, dt))
            .collect::<Result<Vec<_>, _>>()?;
        let length = basis.length();
        let mut point_shapes = vec![0.0; points.len() * n];
        for (p, &x) in points.iter().enumerate() {
            inside_span("x", x, length)?;
            basis.eval_all(x, Derivative::Shape, &mut point_shapes[p * n..(p + 1) * n])?;
        }
        Ok(Self {
            dt,
            length,
            omegas,
            velocity_coefficients,
            inv_mass,
            steppers,
            point_shapes,
            points: points.to_vec(),
            sine_amplitudes: sine_amplitudes(basis)?,
        })
    }

    /// The time step \[s\].
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The output points \[m\].
    pub fn points(&self) -> &[f64] {
        &self.points
    }

    /// True when the shapes are evaluated by the sine recurrence (simply supported span).
    pub fn uses_sine_shapes(&self) -> bool {
        self.sine_amplitudes.is_some()
    }

    /// Fresh buffers for [`Self::peaks`].
    pub fn work(&self) -> PassageWork {
        let n = self.omegas.len();
        PassageWork {
            q: vec![0.0; n],
            v: vec![0.0; n],
            f0: vec![0.0; n],
            f1: vec![0.0; n],
            shapes: vec![0.0; n],
        }
    }

    /// The peaks of one passage of `axles` (offsets behind the first axle, any order) at
    /// `speed` \[m/s\], from rest until `free_vibration` \[s\] after the last axle has left.
    pub fn peaks(
        &self,
        basis: &dyn ModalBasis,
        axles: &[Axle],
        speed: f64,
        free_vibration: f64,
        work: &mut PassageWork,
    ) -> Result<PassagePeaks, BeamError> {
        let speed = positive("speed", speed)?;
        let free = non_negative("free_vibration_time", free_vibration)?;
        if axles.is_empty() {
            return Err(BeamError::InvalidCount {
                name: "axles",
                value: 0,
                reason: "at least one axle",
            });
        }
        if let Some(w) = axles.windows(2).find(|w| w[1].offset < w[0].offset) {
            return Err(BeamError::InvalidParameter {
                name: "offset",
                value: w[1].offset,
                reason: "axle offsets must be non-decreasing (first axle first)",
            });
        }
        for a in axles {
            non_negative("offset", a.offset)?;
        }
        let last = axles[axles.len() - 1].offset;
        let exit = (self.length + last) / speed;
        let steps = ((exit + free) / self.dt).ceil();
        if !steps.is_finite() || steps > MAX_STEPS as f64 {
            return Err(BeamError::InvalidParameter {
                name: "dt",
                value: self.dt,
                reason: "gives more than 1e9 time steps for the passage and free vibration",
            });
        }
        let steps = steps as usize;
        let n = self.omegas.len();
        let np = self.points.len();
        if work.q.len() != n {
            *work = self.work();
        }
        work.q.fill(0.0);
        work.v.fill(0.0);
        let mut peaks = PassagePeaks {
            deflection: vec![0.0; np],
            acceleration: vec![0.0; np],
            static_deflection: vec![0.0; np],
            steps,
        };
        let mut window = AxleWindow::default();
        self.modal_forces(basis, axles, speed, 0.0, &mut window, work, true)?;
        self.record(work, &mut peaks);
        for step in 1..=steps {
            let t = step as f64 * self.dt;
            self.modal_forces(basis, axles, speed, t, &mut window, work, false)?;
            for (j, stepper) in self.steppers.iter().enumerate() {
                (work.q[j], work.v[j]) = stepper.step(work.q[j], work.v[j], work.f0[j], work.f1[j]);
            }
            std::mem::swap(&mut work.f0, &mut work.f1);
            self.record(work, &mut peaks);
        }
        Ok(peaks)
    }

    /// f_j(t) / m_j into `work.f0` (`initial`) or `work.f1`.
    #[allow(clippy::too_many_arguments)]
    fn modal_forces(
        &self,
        basis: &dyn ModalBasis,
        axles: &[Axle],
        speed: f64,
        t: f64,
        window: &mut AxleWindow,
        work: &mut PassageWork,
        initial: bool,
    ) -> Result<(), BeamError> {
        let PassageWork { f0, f1, shapes, .. } = work;
        let f = if initial { f0 } else { f1 };
        f.fill(0.0);
        window.advance(axles, speed, t, self.length);
        for axle in &axles[window.left..window.entered] {
            let x = (speed * t - axle.offset).clamp(0.0, self.length);
            match &self.sine_amplitudes {
                Some(amplitudes) => {
                    let (s1, c) = (std::f64::consts::PI * x / self.length).sin_cos();
                    let (mut prev, mut cur) = (0.0, s1);
                    for (fj, a) in f.iter_mut().zip(amplitudes) {
                        *fj += axle.force * a * cur;
                        (prev, cur) = (cur, 2.0 * c * cur - prev);
                    }
                }
                None => {
                    basis.eval_all(x, Derivative::Shape, shapes)?;
                    for (fj, w) in f.iter_mut().zip(shapes.iter()) {
                        *fj += axle.force * w;
                    }
                }
            }
        }
        for (fj, im) in f.iter_mut().zip(&self.inv_mass) {
            *fj *= im;
        }
        Ok(())
    }

    /// Updates the peaks with the state in `work` (forces at the same time in `work.f0`).
    fn record(&self, work: &PassageWork, peaks: &mut PassagePeaks) {
        let n = self.omegas.len();
        for p in 0..self.points.len() {
            let shapes = &self.point_shapes[p * n..(p + 1) * n];
            let (mut w, mut a, mut s) = (0.0, 0.0, 0.0);
            for (j, shape) in shapes.iter().enumerate() {
                let omega2 = self.omegas[j] * self.omegas[j];
                let (q, f) = (work.q[j], work.f0[j]);
                w += shape * q;
                a += shape * (f - self.velocity_coefficients[j] * work.v[j] - omega2 * q);
                s += shape * f / omega2;
            }
            peaks.deflection[p] = peaks.deflection[p].max(w.abs());
            peaks.acceleration[p] = peaks.acceleration[p].max(a.abs());
            peaks.static_deflection[p] = peaks.static_deflection[p].max(s.abs());
        }
    }
}

/// The axles on the span, `left..entered` of the offset-sorted list: x_k = c t − d_k decreases
/// with k, so both ends only move forward in time.
#[derive(Debug, Default)]
struct AxleWindow {
    left: usize,
    entered: usize,
}

impl AxleWindow {
    fn advance(&mut self, axles: &[Axle], speed: f64, t: f64, length: f64) {
        while self.entered < axles.len() && speed * t - axles[self.entered].offset >= 0.0 {
            self.entered += 1;
        }
        while self.left < self.entered && speed * t - axles[self.left].offset > length {
            self.left += 1;
        }
    }
}

/// A_j when every shape of `basis` is A_j sin((j+1)πx/L) (a simply supported uniform span, as
/// [`crate::AnalyticBeam`] with `Support::SimplySupported`), checked at four points; `None`
/// for any other basis. With them, [`sine_shapes`] evaluates every shape at one `sin_cos`.
pub fn sine_amplitudes<B: ModalBasis + ?Sized>(basis: &B) -> Result<Option<Vec<f64>>, BeamError> {
    let n = basis.n_modes();
    let length = basis.length();
    let mut amplitudes = vec![0.0; n];
    let mut shapes = vec![0.0; n];
    // Irrational fractions of the span: no mode has a node there for j ≤ MAX_MODES.
    let probes = [
        std::f64::consts::FRAC_1_PI,
        0.4 * std::f64::consts::FRAC_1_PI,
        std::f64::consts::FRAC_1_SQRT_2,
        0.577_215_664_901_533,
    ];
    basis.eval_all(probes[0] * length, Derivative::Shape, &mut shapes)?;
    for (j, (a, w)) in amplitudes.iter_mut().zip(&shapes).enumerate() {
        let s = ((j + 1) as f64 * std::f64::consts::PI * probes[0]).sin();
        if s.abs() < 1e-3 {
            return Ok(None);
        }
        *a = w / s;
    }
    for &xi in &probes[1..] {
        basis.eval_all(xi * length, Derivative::Shape, &mut shapes)?;
        for (j, (a, w)) in amplitudes.iter().zip(&shapes).enumerate() {
            let expected = a * ((j + 1) as f64 * std::f64::consts::PI * xi).sin();
            if (w - expected).abs() > SINE_SHAPE_TOLERANCE * a.abs().max(f64::MIN_POSITIVE) {
                return Ok(None);
            }
        }
    }
    Ok(Some(amplitudes))
}

/// The shapes w_j(x) = A_j sin((j+1)πx/L) of a simply supported uniform span of length `length`
/// (`amplitudes` from [`sine_amplitudes`]) into `out`, by the recurrence
/// sin((j+1)θ) = 2 cos θ sin(jθ) − sin((j−1)θ) (one `sin_cos`; agrees with the direct
/// evaluation to a few ulp per mode for the mode counts of a bridge model, tested).
pub fn sine_shapes(amplitudes: &[f64], length: f64, x: f64, out: &mut [f64]) {
    for (o, w) in out.iter_mut().zip(sine_shape_values(amplitudes, length, x)) {
        *o = w;
    }
}

/// `Σ_j weights_j w_j(x)` with the shapes of [`sine_shapes`] (the same recurrence, summed as it
/// goes: no buffer). The sum runs over the shorter of `amplitudes` and `weights`.
pub fn sine_shape_dot(amplitudes: &[f64], length: f64, x: f64, weights: &[f64]) -> f64 {
    sine_shape_values(amplitudes, length, x)
        .zip(weights)
        .map(|(w, c)| c * w)
        .sum()
}

/// The shapes A_j sin((j+1)θ), θ = πx/L, in mode order, by the recurrence of [`sine_shapes`].
fn sine_shape_values(amplitudes: &[f64], length: f64, x: f64) -> impl Iterator<Item = f64> + '_ {
    let (s1, c) = (std::f64::consts::PI * x / length).sin_cos();
    amplitudes.iter().scan((0.0, s1), move |(prev, cur), a| {
        let w = a * *cur;
        (*prev, *cur) = (*cur, 2.0 * c * *cur - *prev);
        Some(w)
    })
}
