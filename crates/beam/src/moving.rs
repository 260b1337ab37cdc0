//! Moving loads over a modal beam: one force or a train of axle forces at constant speed.
//!
//! Each axle k is at x_k(t) = c t − d_k (d_k ≥ 0 its offset behind the first axle) and loads the
//! span only while 0 ≤ x_k ≤ L. The modal forces f_j(t) = Σ_(k on span) F_k w_j(x_k(t)) / m_j
//! are sampled at the step times and taken piecewise linear in between; each mode
//! q_j'' + c_j q_j' + ω_j² q_j = f_j is then advanced with the exact propagator
//! [`PiecewiseLinearSdof`] (Nigam–Jennings-type recurrence), so the only time-discretisation
//! error is the linear interpolation of f_j (O(Δt²)). Alternatively the modal system
//! M q'' + C q' + K q = f (diagonal M = diag(m_j), C = diag(m_j c_j), K = diag(m_j ω_j²)) is
//! integrated by a [`StructuralMethod`] of the `integrate` crate (Newmark-β, HHT-α,
//! generalized-α, ...), which adds that method's period and amplitude errors (references.md §D3.5).
//! The run lasts until the last axle leaves the span plus a free-vibration time. Loads and
//! deflections are positive in the same direction.

use std::ops::ControlFlow;

use faer::{Mat, MatMut, MatRef};
use integrate::structural::{StructuralMethod, StructuralStepper, StructuralSystem};

use crate::damping::ModalDamping;
use crate::error::{
    BeamError, MAX_MODES, MEMORY_LIMIT_BYTES, check_size, finite, inside_span, non_negative,
    positive,
};
use crate::modal::{Derivative, ModalBasis};
use crate::sdof::PiecewiseLinearSdof;

/// One axle of a moving load train.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axle {
    /// Distance behind the first axle \[m\] (≥ 0).
    pub offset: f64,
    /// Force \[N\], positive in the deflection direction.
    pub force: f64,
}

/// A set of axle forces travelling at constant speed, the first axle entering at x = 0, t = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingLoads {
    axles: Vec<Axle>,
    speed: f64,
}

impl MovingLoads {
    /// A single force.
    pub fn single(force: f64, speed: f64) -> Result<Self, BeamError> {
        Self::train(vec![Axle { offset: 0.0, force }], speed)
    }

    /// A train of axles (offsets ≥ 0, forces finite, speed > 0).
    pub fn train(axles: Vec<Axle>, speed: f64) -> Result<Self, BeamError> {
        positive("speed", speed)?;
        if axles.is_empty() {
            return Err(BeamError::InvalidCount {
                name: "axles",
                value: 0,
                reason: "at least one axle",
            });
        }
        for a in &axles {
            non_negative("offset", a.offset)?;
            finite("force", a.force)?;
        }
        Ok(Self { axles, speed })
    }

    /// The axles.
    pub fn axles(&self) -> &[Axle] {
        &self.axles
    }

    /// Speed c [m/s].
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// Time at which the last axle leaves a span of length L: (L + max d_k)/c.
    pub fn exit_time(&self, length: f64) -> f64 {
        let last = self.axles.iter().map(|a| a.offset).fold(0.0, f64::max);
        (length + last) / self.speed
    }
}

/// Time integration of the modal equations.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ModalIntegrator {
    /// Exact solution for forcing piecewise linear over each step (see module docs).
    #[default]
    ExactPiecewiseLinear,
    /// A structural integrator of the `integrate` crate applied to the whole modal system, e.g.
    /// Newmark average acceleration `StructuralMethod::average_acceleration()`.
    Structural(StructuralMethod),
}

/// Settings of a moving-load run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingLoadSettings {
    /// Time step Δt \[s\].
    pub dt: f64,
    /// Free-vibration time simulated after the last axle has left \[s\].
    pub free_vibration_time: f64,
    /// Record every `output_every`-th step (≥ 1); the final step is always recorded.
    pub output_every: usize,
    /// Modal time integrator.
    pub integrator: ModalIntegrator,
}

impl MovingLoadSettings {
    /// Settings with step `dt`, free-vibration time `free_vibration_time`, every step recorded.
    pub fn new(dt: f64, free_vibration_time: f64) -> Self {
        Self {
            dt,
            free_vibration_time,
            output_every: 1,
            integrator: ModalIntegrator::ExactPiecewiseLinear,
        }
    }
}

/// Time histories at the output points, stored sample-major: entry `[i * n_points + p]` is
/// sample i at point p.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingLoadResponse {
    /// Output positions x_p \[m\].
    pub points: Vec<f64>,
    /// Sample times \[s\].
    pub times: Vec<f64>,
    /// Deflection w(x_p, t) \[m\].
    pub deflection: Vec<f64>,
    /// Velocity ẇ(x_p, t) [m/s].
    pub velocity: Vec<f64>,
    /// Acceleration ẅ(x_p, t) [m/s²] (from the modal equations, q̈ = f − c q̇ − ω² q).
    pub acceleration: Vec<f64>,
    /// Bending moment M = −EI(x_p) Σ q_j w_j''(x_p) [N m].
    pub bending_moment: Vec<f64>,
    /// Quasi-static deflection Σ (f_j/ω_j²) w_j(x_p) from the same modal basis \[m\].
    pub quasi_static_deflection: Vec<f64>,
    /// Time at which the last axle left the span \[s\].
    pub exit_time: f64,
    /// `false` when the observer of [`simulate_moving_loads_observed`] stopped the run early
    /// (the histories then end at the last recorded step).
    pub completed: bool,
}

/// Where a moving-load run is: given to the observer of [`simulate_moving_loads_observed`]
/// after every step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepProgress {
    /// Steps taken.
    pub step: usize,
    /// Steps of the whole run.
    pub steps: usize,
    /// Time reached \[s\].
    pub t: f64,
}

impl MovingLoadResponse {
    /// Number of output points.
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    fn column_max_abs(&self, data: &[f64], p: usize, t0: f64, t1: f64) -> Result<f64, BeamError> {
        check_point(p, self.points.len())?;
        let n = self.points.len();
        Ok(self
            .times
            .iter()
            .enumerate()
            .filter(|(_, t)| **t >= t0 && **t <= t1)
            .map(|(i, _)| data[i * n + p].abs())
            .fold(0.0, f64::max))
    }

    /// max_t |w(x_p, t)| over the whole run.
    pub fn max_abs_deflection(&self, p: usize) -> Result<f64, BeamError> {
        self.column_max_abs(&self.deflection, p, f64::NEG_INFINITY, f64::INFINITY)
    }

    /// max |w(x_p, t)| for t in [t0, t1].
    pub fn max_abs_deflection_between(&self, p: usize, t0: f64, t1: f64) -> Result<f64, BeamError> {
        self.column_max_abs(&self.deflection, p, t0, t1)
    }

    /// max_t of the quasi-static deflection at x_p (the static maximum over all load positions).
    pub fn max_abs_quasi_static(&self, p: usize) -> Result<f64, BeamError> {
        self.column_max_abs(
            &self.quasi_static_deflection,
            p,
            f64::NEG_INFINITY,
            f64::INFINITY,
        )
    }

    /// max_t |ẅ(x_p, t)|.
    pub fn max_abs_acceleration(&self, p: usize) -> Result<f64, BeamError> {
        self.column_max_abs(&self.acceleration, p, f64::NEG_INFINITY, f64::INFINITY)
    }

    /// max_t |M(x_p, t)|.
    pub fn max_abs_bending_moment(&self, p: usize) -> Result<f64, BeamError> {
        self.column_max_abs(&self.bending_moment, p, f64::NEG_INFINITY, f64::INFINITY)
    }

    /// Dynamic amplification factor max|w_dyn(x_p)| / max|w_static(x_p)| with the static maximum
    /// from the same modal basis (quasi-static modal response over the passage).
    pub fn dynamic_amplification(&self, p: usize) -> Result<f64, BeamError> {
        Ok(self.max_abs_deflection(p)? / self.max_abs_quasi_static(p)?)
    }
}

fn check_point(p: usize, n: usize) -> Result<(), BeamError> {
    if p < n {
        Ok(())
    } else {
        Err(BeamError::InvalidCount {
            name: "point index",
            value: p,
            reason: "must be below the number of output points",
        })
    }
}

/// Preallocated state of one moving-load run.
struct Workspace {
    q: Vec<f64>,
    v: Vec<f64>,
    f_now: Vec<f64>,
    f_next: Vec<f64>,
    shapes: Vec<f64>,
    damping: Vec<f64>,
    inv_mass: Vec<f64>,
    /// Sine amplitudes of a simply supported uniform span (fast shapes), else `None`.
    sine: Option<Vec<f64>>,
    steppers: Vec<PiecewiseLinearSdof>,
}

/// Shape and curvature values at the output points, point-major, and EI there.
struct OutputOperator {
    shapes: Vec<f64>,
    curvatures: Vec<f64>,
    stiffness: Vec<f64>,
    n_modes: usize,
}

impl OutputOperator {
    fn new<B: ModalBasis + ?Sized>(basis: &B, points: &[f64]) -> Result<Self, BeamError> {
        let n = basis.n_modes();
        let mut shapes = vec![0.0; n * points.len()];
        let mut curvatures = vec![0.0; n * points.len()];
        let mut stiffness = Vec::with_capacity(points.len());
        for (p, &x) in points.iter().enumerate() {
            inside_span("output point", x, basis.length())?;
            basis.eval_all(x, Derivative::Shape, &mut shapes[p * n..(p + 1) * n])?;
            basis.eval_all(
                x,
                Derivative::Curvature,
                &mut curvatures[p * n..(p + 1) * n],
            )?;
            stiffness.push(basis.bending_stiffness(x)?);
        }
        Ok(Self {
            shapes,
            curvatures,
            stiffness,
            n_modes: n,
        })
    }
}

/// Modal forces Σ_(k on span) F_k w_j(x_k(t)) · `weights_j` at time t into `out`, using `shapes`
/// as scratch. Axles off the span contribute nothing.
///
/// On a simply supported uniform span (`sine`: the amplitudes A_j of w_j = A_j sin((j+1)πx/L),
/// `passage::sine_amplitudes`) the shapes come from the recurrence
/// sin((j+1)θ) = 2 cos θ sin(jθ) − sin((j−1)θ): one `sin_cos` per axle instead of one per mode.
fn modal_forces<B: ModalBasis + ?Sized>(
    basis: &B,
    loads: &MovingLoads,
    t: f64,
    weights: &[f64],
    sine: Option<&[f64]>,
    shapes: &mut [f64],
    out: &mut [f64],
) -> Result<(), BeamError> {
    out.fill(0.0);
    let l = basis.length();
    for axle in &loads.axles {
        let x = loads.speed * t - axle.offset;
        if !(0.0..=l).contains(&x) {
            continue;
        }
        match sine {
            Some(amplitudes) => {
                let (s1, c) = (std::f64::consts::PI * x / l).sin_cos();
                let (mut prev, mut cur) = (0.0, s1);
                for (f, a) in out.iter_mut().zip(amplitudes) {
                    *f += axle.force * a * cur;
                    (prev, cur) = (cur, 2.0 * c * cur - prev);
                }
            }
            None => {
                basis.eval_all(x, Derivative::Shape, shapes)?;
                for (f, w) in out.iter_mut().zip(shapes.iter()) {
                    *f += axle.force * w;
                }
            }
        }
    }
    for (f, m) in out.iter_mut().zip(weights) {
        *f *= m;
    }
    Ok(())
}

/// Modal forces / m_j at time t into `ws.f_next`.
fn modal_forces_at<B: ModalBasis + ?Sized>(
    basis: &B,
    loads: &MovingLoads,
    t: f64,
    ws: &mut Workspace,
) -> Result<(), BeamError> {
    modal_forces(
        basis,
        loads,
        t,
        &ws.inv_mass,
        ws.sine.as_deref(),
        &mut ws.shapes,
        &mut ws.f_next,
    )
}

/// The diagonal modal system m_j q_j'' + m_j c_j q_j' + m_j ω_j² q_j = f_j(t) as a
/// [`StructuralSystem`] for the `integrate` steppers (buffers owned, no allocation per call).
struct ModalSystem<'a, B: ?Sized> {
    basis: &'a B,
    loads: &'a MovingLoads,
    mass: Mat<f64>,
    damping: Mat<f64>,
    stiffness: Vec<f64>,
    unit_weights: Vec<f64>,
    shapes: Vec<f64>,
}

impl<'a, B: ModalBasis + ?Sized> ModalSystem<'a, B> {
    fn new(basis: &'a B, loads: &'a MovingLoads, masses: &[f64], damping: &[f64]) -> Self {
        let n = masses.len();
        let omegas = basis.circular_frequencies();
        Self {
            basis,
            loads,
            mass: Mat::from_fn(n, n, |i, j| if i == j { masses[i] } else { 0.0 }),
            damping: Mat::from_fn(
                n,
                n,
                |i, j| if i == j { masses[i] * damping[i] } else { 0.0 },
            ),
            stiffness: (0..n).map(|j| masses[j] * omegas[j] * omegas[j]).collect(),
            unit_weights: vec![1.0; n],
            shapes: vec![0.0; n],
        }
    }
}

impl<B: ModalBasis + ?Sized> StructuralSystem for ModalSystem<'_, B> {
    fn dimension(&self) -> usize {
        self.stiffness.len()
    }

    fn mass_matrix(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }

    fn damping_matrix(&self) -> Option<MatRef<'_, f64>> {
        Some(self.damping.as_ref())
    }

    fn internal_force(&mut self, q: &[f64], f_int: &mut [f64]) {
        for ((f, k), q) in f_int.iter_mut().zip(&self.stiffness).zip(q) {
            *f = k * q;
        }
    }

    fn tangent_stiffness(&mut self, _q: &[f64], mut k: MatMut<'_, f64>) -> bool {
        k.fill(0.0);
        for (j, kj) in self.stiffness.iter().enumerate() {
            k[(j, j)] = *kj;
        }
        true
    }

    fn is_linear(&self) -> bool {
        true
    }

    fn external_force(&mut self, t: f64, f_ext: &mut [f64]) {
        // Positions are filtered to the span and the slices have the basis size, so the
        // evaluation cannot fail; a failure would leave zero force (documented as impossible).
        if modal_forces(
            self.basis,
            self.loads,
            t,
            &self.unit_weights,
            None,
            &mut self.shapes,
            f_ext,
        )
        .is_err()
        {
            f_ext.fill(0.0);
        }
    }
}

/// Append the response at the current state to `out`.
fn record(
    basis_omegas: &[f64],
    ws: &Workspace,
    op: &OutputOperator,
    t: f64,
    out: &mut MovingLoadResponse,
) {
    out.times.push(t);
    let n = op.n_modes;
    for p in 0..op.stiffness.len() {
        let w = &op.shapes[p * n..(p + 1) * n];
        let k = &op.curvatures[p * n..(p + 1) * n];
        let (mut defl, mut vel, mut acc, mut curv, mut stat) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for j in 0..n {
            let omega2 = basis_omegas[j] * basis_omegas[j];
            let qddot = ws.f_now[j] - ws.damping[j] * ws.v[j] - omega2 * ws.q[j];
            defl += w[j] * ws.q[j];
            vel += w[j] * ws.v[j];
            acc += w[j] * qddot;
            curv += k[j] * ws.q[j];
            if omega2 > 0.0 {
                stat += w[j] * ws.f_now[j] / omega2;
            }
        }
        out.deflection.push(defl);
        out.velocity.push(vel);
        out.acceleration.push(acc);
        out.bending_moment.push(-op.stiffness[p] * curv);
        out.quasi_static_deflection.push(stat);
    }
}

/// Upper limit on the number of time steps of one run (guards the output preallocation).
pub const MAX_STEPS: usize = 1_000_000_000;

/// Simulate `loads` crossing the beam described by `basis` with modal `damping`, recording the
/// response at `points`. The beam starts at rest; the run ends `settings.free_vibration_time`
/// after the last axle has left. All buffers are allocated before the time loop.
pub fn simulate_moving_loads<B: ModalBasis + ?Sized>(
    basis: &B,
    damping: &ModalDamping,
    loads: &MovingLoads,
    settings: &MovingLoadSettings,
    points: &[f64],
) -> Result<MovingLoadResponse, BeamError> {
    let mut run_to_end = |_: StepProgress| ControlFlow::Continue(());
    simulate_moving_loads_observed(basis, damping, loads, settings, points, &mut run_to_end)
}

/// [`simulate_moving_loads`] with an `observer` called after every step short of the last;
/// `ControlFlow::Break` stops the run there: the step is recorded (whatever `output_every`)
/// and the response is returned with `completed = false` (an interrupt, a wall-clock budget).
pub fn simulate_moving_loads_observed<B: ModalBasis + ?Sized>(
    basis: &B,
    damping: &ModalDamping,
    loads: &MovingLoads,
    settings: &MovingLoadSettings,
    points: &[f64],
    observer: &mut dyn FnMut(StepProgress) -> ControlFlow<()>,
) -> Result<MovingLoadResponse, BeamError> {
    let dt = positive("dt", settings.dt)?;
    let free = non_negative("free_vibration_time", settings.free_vibration_time)?;
    if settings.output_every == 0 {
        return Err(BeamError::InvalidCount {
            name: "output_every",
            value: 0,
            reason: "must be >= 1",
        });
    }
    let n = basis.n_modes();
    // The structural stepper holds about eight n × n matrices.
    check_size("n_modes", n, MAX_MODES, "the modal time integration", |n| {
        64.0 * (n as f64).powi(2)
    })?;
    let omegas = basis.circular_frequencies();
    if let ModalIntegrator::Structural(method) = settings.integrator {
        check_stability(method, dt, omegas)?;
    }
    let mut ws = Workspace {
        q: vec![0.0; n],
        v: vec![0.0; n],
        f_now: vec![0.0; n],
        f_next: vec![0.0; n],
        shapes: vec![0.0; n],
        damping: damping.velocity_coefficients(omegas)?,
        inv_mass: (0..n)
            .map(|j| basis.modal_mass(j).map(|m| 1.0 / m))
            .collect::<Result<_, _>>()?,
        sine: crate::passage::sine_amplitudes(basis)?,
        steppers: Vec::with_capacity(n),
    };
    let op = OutputOperator::new(basis, points)?;
    let exit_time = loads.exit_time(basis.length());
    let steps = ((exit_time + free) / dt).ceil();
    if !steps.is_finite() || steps > MAX_STEPS as f64 {
        return Err(BeamError::InvalidParameter {
            name: "dt",
            value: dt,
            reason: "gives more than 1e9 time steps for the passage and free vibration",
        });
    }
    let n_steps = steps as usize;
    let n_samples = n_steps / settings.output_every + 2;
    let np = points.len();
    // Five histories of n_samples × n_points f64, checked before they are allocated.
    let output_bytes = 40.0 * n_samples as f64 * np.max(1) as f64;
    if output_bytes > MEMORY_LIMIT_BYTES {
        return Err(BeamError::TooLarge {
            name: "output_every",
            value: settings.output_every,
            max: usize::MAX,
            what: "the recorded time histories (5 × samples × points)",
            bytes_required: output_bytes,
            limit_bytes: MEMORY_LIMIT_BYTES,
        });
    }
    let mut out = MovingLoadResponse {
        points: points.to_vec(),
        times: Vec::with_capacity(n_samples),
        deflection: Vec::with_capacity(n_samples * np),
        velocity: Vec::with_capacity(n_samples * np),
        acceleration: Vec::with_capacity(n_samples * np),
        bending_moment: Vec::with_capacity(n_samples * np),
        quasi_static_deflection: Vec::with_capacity(n_samples * np),
        exit_time,
        completed: true,
    };
    modal_forces_at(basis, loads, 0.0, &mut ws)?;
    std::mem::swap(&mut ws.f_now, &mut ws.f_next);
    record(omegas, &ws, &op, 0.0, &mut out);
    let every = settings.output_every;
    match settings.integrator {
        ModalIntegrator::ExactPiecewiseLinear => {
            for (&omega, &c) in omegas.iter().zip(&ws.damping) {
                ws.steppers.push(PiecewiseLinearSdof::new(omega, c, dt)?);
            }
            for step in 1..=n_steps {
                let t = step as f64 * dt;
                modal_forces_at(basis, loads, t, &mut ws)?;
                for (((stepper, q), v), (f0, f1)) in ws
                    .steppers
                    .iter()
                    .zip(ws.q.iter_mut())
                    .zip(ws.v.iter_mut())
                    .zip(ws.f_now.iter().zip(&ws.f_next))
                {
                    (*q, *v) = stepper.step(*q, *v, *f0, *f1);
                }
                std::mem::swap(&mut ws.f_now, &mut ws.f_next);
                let stop = stop_requested(observer, step, n_steps, t);
                if step % every == 0 || step == n_steps || stop {
                    record(omegas, &ws, &op, t, &mut out);
                }
                if stop {
                    out.completed = false;
                    break;
                }
            }
        }
        ModalIntegrator::Structural(method) => {
            let masses: Vec<f64> = ws.inv_mass.iter().map(|m| 1.0 / m).collect();
            let mut system = ModalSystem::new(basis, loads, &masses, &ws.damping);
            let mut stepper = StructuralStepper::new(method, &mut system, 0.0, &ws.q, &ws.v)?;
            for step in 1..=n_steps {
                let t = step as f64 * dt;
                stepper.step(&mut system, dt)?;
                let stop = stop_requested(observer, step, n_steps, t);
                if step % every == 0 || step == n_steps || stop {
                    ws.q.copy_from_slice(stepper.q());
                    ws.v.copy_from_slice(stepper.v());
                    modal_forces_at(basis, loads, t, &mut ws)?;
                    std::mem::swap(&mut ws.f_now, &mut ws.f_next);
                    record(omegas, &ws, &op, t, &mut out);
                }
                if stop {
                    out.completed = false;
                    break;
                }
            }
        }
    }
    Ok(out)
}

/// Ask the observer after step `step` (never after the last one).
fn stop_requested(
    observer: &mut dyn FnMut(StepProgress) -> ControlFlow<()>,
    step: usize,
    steps: usize,
    t: f64,
) -> bool {
    step < steps && observer(StepProgress { step, steps, t }).is_break()
}

/// Refuse a step above the stability limit of a conditionally stable method
/// ([`StructuralMethod::critical_step`]: 2/ω_max for central difference and Verlet) for the
/// highest retained mode, before the run starts instead of failing mid-run with a non-finite
/// state.
fn check_stability(method: StructuralMethod, dt: f64, omegas: &[f64]) -> Result<(), BeamError> {
    let omega_max = omegas.iter().copied().fold(0.0, f64::max);
    if let Some(limit) = method.critical_step(omega_max)
        && dt > limit
    {
        return Err(BeamError::StepAboveStabilityLimit {
            method: method.name(),
            dt,
            limit,
            omega_max,
        });
    }
    Ok(())
}
