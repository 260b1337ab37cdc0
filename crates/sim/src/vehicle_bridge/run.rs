//! The run driver: steps a [`Simulation`] to its end time, calls an observer after every
//! accepted step (which may stop the run, e.g. on Ctrl-C) and returns a [`RunSummary`]: the
//! extrema of the output-point response with their times, the dynamic amplification against
//! the quasi-static deflection, the contact-force extrema per wheel, the loss-of-contact
//! events and the solver statistics.
//!
//! [`run`] takes the extrema over every accepted step of the scenario's Δt and the start state
//! (t = 0); [`run_sampled`] over the steps a time series recorded every n-th step holds.
//!
//! Dynamic amplification (references.md §D1.5): `DAF = max_t |w(x_out, t)| / max_t |w_qs(x_out, t)|`
//! with the quasi-static deflection `w_qs` of [`Simulation::quasi_static_output_deflection`]
//! (the static wheel loads at their current positions, same modal basis).

use std::ops::ControlFlow;

use super::{Simulation, SolverStats, VehicleBridgeError};

/// What the observer learns about the step just taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepInfo {
    /// Number of the step just accepted (1-based).
    pub step: usize,
    /// Steps of the whole run (the end time divided by Δt, rounded up).
    pub steps: usize,
    /// Coupling iterations this step needed (over all its halvings).
    pub iterations: usize,
}

/// Called by [`run`] with the start state and after every accepted step; returning
/// [`ControlFlow::Break`] stops the run at that step (the summary then has
/// `completed = false`).
pub trait RunObserver {
    /// The start state (t = 0), before the first step.
    fn start(&mut self, _sim: &Simulation) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }

    /// After the step `info.step` of `info.steps` has been accepted.
    fn after_step(&mut self, sim: &Simulation, info: StepInfo) -> ControlFlow<()>;
}

/// Any `FnMut(&Simulation, StepInfo) -> ControlFlow<()>` is an observer.
impl<F> RunObserver for F
where
    F: FnMut(&Simulation, StepInfo) -> ControlFlow<()>,
{
    fn after_step(&mut self, sim: &Simulation, info: StepInfo) -> ControlFlow<()> {
        self(sim, info)
    }
}

/// An observer that watches nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoObserver;

impl RunObserver for NoObserver {
    fn after_step(&mut self, _sim: &Simulation, _info: StepInfo) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// A value and the time \[s\] at which it occurred (the first time, on ties).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremum {
    /// The value (in the unit of the quantity).
    pub value: f64,
    /// Time \[s\].
    pub time: f64,
}

/// Largest and smallest value of a signed quantity over the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Largest value and its time.
    pub max: Extremum,
    /// Smallest value and its time.
    pub min: Extremum,
}

impl Range {
    fn new(value: f64, time: f64) -> Self {
        let e = Extremum { value, time };
        Self { max: e, min: e }
    }

    fn update(&mut self, value: f64, time: f64) {
        if value > self.max.value {
            self.max = Extremum { value, time };
        }
        if value < self.min.value {
            self.min = Extremum { value, time };
        }
    }

    /// `max(|max|, |min|)`.
    pub fn max_abs(&self) -> f64 {
        self.max.value.abs().max(self.min.value.abs())
    }
}

/// Per-wheel extrema of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelSummary {
    /// Contact force F \[N\]: largest and smallest value with their times.
    pub force: Range,
    /// Largest peak contact pressure \[Pa\] (0 for the rigid contact, which has no pressure).
    pub max_pressure: f64,
    /// Largest |body acceleration| [m/s²] (0 without a body).
    pub max_body_acceleration: f64,
    /// Largest |wheel acceleration| [m/s²].
    pub max_wheel_acceleration: f64,
    /// Transitions of this wheel from contact to loss of contact.
    pub loss_of_contact_events: usize,
}

/// Extrema of the bridge response at a response point ([`Simulation::set_output_points`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PointSummary {
    /// Position on the bridge \[m\].
    pub x: f64,
    /// Deflection \[m\] (down positive).
    pub deflection: Range,
    /// Acceleration \[m/s²\].
    pub acceleration: Range,
}

/// Smallest largest quasi-static deflection at the output point, relative to that of the
/// heaviest static load standing there ([`Simulation::quasi_static_reference_deflection`]),
/// for which [`RunSummary::dynamic_amplification`] is given (0.1 %: below it the loads have
/// barely reached the span and the ratio of two near-zero deflections means nothing).
pub const DAF_MIN_LOADING: f64 = 1e-3;

/// The result of [`run`].
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// `true` when the run reached its end time; `false` when the observer stopped it.
    pub completed: bool,
    /// Time reached \[s\].
    pub time_reached: f64,
    /// The run's end time \[s\] ([`Simulation::end_time`]).
    pub end_time: f64,
    /// Steps of Δt taken and planned.
    pub steps_taken: usize,
    /// Steps of Δt of the whole run.
    pub steps_planned: usize,
    /// Bridge deflection at the output point \[m\] (down positive).
    pub deflection: Range,
    /// Bridge acceleration at the output point [m/s²].
    pub acceleration: Range,
    /// Largest |quasi-static deflection| at the output point \[m\] over the steps taken
    /// (`None` for a basis with a rigid-body mode).
    pub max_quasi_static_deflection: Option<f64>,
    /// `max |w| / max |w_qs|` at the output point (`None` without a positive quasi-static
    /// deflection, or when it stayed below [`DAF_MIN_LOADING`] of the heaviest load's
    /// quasi-static deflection at the output point).
    pub dynamic_amplification: Option<f64>,
    /// Per wheel.
    pub wheels: Vec<WheelSummary>,
    /// Per response point besides the output point ([`Simulation::output_points`]).
    pub points: Vec<PointSummary>,
    /// Transitions from contact to loss of contact, over all wheels.
    pub loss_of_contact_events: usize,
    /// Coupling statistics.
    pub solver: SolverStats,
    /// Step-size accuracy indicators and the warnings they raise.
    pub accuracy: Accuracy,
}

/// Largest Δt·f_c of a contact mode for an accurate run: at least 10 steps per period of
/// the wheel bouncing on its contact spring (the trapezoidal rule's period error is then
/// below 3.3 %, references.md §D3.5).
pub const MAX_DT_CONTACT: f64 = 0.1;

/// Largest Δt·f_max of the highest retained bridge mode: above 1 that mode has less than
/// one step per period, an implicit method filters it out (or, undamped, aliases it), and
/// retaining it only costs time.
pub const MAX_DT_MODE: f64 = 1.0;

/// Largest Δt·f_c of a contact mode with backward Euler: the first-order method damps an
/// oscillation of frequency f by the factor (1 + (2π f Δt)²)^{-1/2} per step, so by about
/// π² Δt f over half a period (the duration of an impact); 5 % there needs Δt·f_c ≤ 0.005.
pub const MAX_DT_CONTACT_FIRST_ORDER: f64 = 0.005;

/// Accuracy indicators of a run (see [`Simulation::step_indicators`]). No energy-balance
/// residual is reported: the coupled model has no closed energy balance in general (the
/// horizontal force that keeps the speed constant does work on the sloped rail).
#[derive(Debug, Clone, PartialEq)]
pub struct Accuracy {
    /// Δt · f_max of the highest retained bridge mode.
    pub dt_times_highest_mode_frequency: f64,
    /// Largest Δt · f_c of a wheel's contact mode (`None` for the rigid contact).
    pub dt_times_contact_frequency: Option<f64>,
    /// Indicators above [`MAX_DT_CONTACT`] / [`MAX_DT_MODE`] (at the start, and for the
    /// contact at the peak contact force of the run), backward Euler with a contact mode (at
    /// any Δt: its error in force peaks is first order), and rigid landings after a loss of contact, each with
    /// the key and remedy.
    pub warnings: Vec<String>,
}

impl Accuracy {
    fn of(sim: &Simulation) -> Self {
        let (mode, contact) = sim.step_indicators();
        let dt = sim.scenario().dt;
        let mut warnings = Vec::new();
        // Radau5 adapts its steps to its error tolerances (Δt only caps them): no contact-mode
        // resolution indicator applies to it.
        if let Some(c) = contact.filter(|&c| c > MAX_DT_CONTACT)
            && !sim.uses_radau5()
        {
            warnings.push(format!(
                "the contact mode is under-resolved: integrator.dt = {dt:e} s gives dt·f_c = {c:.3} > {MAX_DT_CONTACT} (fewer than 10 steps per contact period); use dt <= {:.3e} s",
                dt * MAX_DT_CONTACT / c
            ));
        }
        if let Some(c) = contact.filter(|&c| c <= MAX_DT_CONTACT)
            && sim.scenario().integrator.name() == "backward_euler"
            && !sim.uses_radau5()
        {
            // A first-order method's damping accumulates over the contact periods a force peak
            // takes to build up: the scenario zoo's long mode found a peak built over about
            // five half periods 12 % low at π²·dt·f_c = 2.5 % (case 496), converging only
            // linearly in dt. No dt keeps that bounded for every transient, so every
            // backward-Euler run with a contact mode is flagged.
            warnings.push(format!(
                "backward_euler (first order) damps the contact mode by about π²·dt·f_c = {:.2} % per half period (integrator.dt = {dt:e} s, dt·f_c = {c:.4}), so contact-force peaks that build up over several contact periods come out low by a multiple of that, converging only linearly in dt; use a second-order method (generalized_alpha) for contact forces{}",
                100.0 * std::f64::consts::PI.powi(2) * c,
                if c > MAX_DT_CONTACT_FIRST_ORDER {
                    format!(", or at least dt <= {:.3e} s", dt * MAX_DT_CONTACT_FIRST_ORDER / c)
                } else {
                    String::new()
                }
            ));
        }
        if mode > MAX_DT_MODE {
            warnings.push(format!(
                "the highest retained bridge mode has dt·f_max = {mode:.3} > {MAX_DT_MODE} (less than one step per period): it is filtered by the integrator; use fewer bridge.modes or dt <= {:.3e} s",
                dt * MAX_DT_MODE / mode
            ));
        }
        Self {
            dt_times_highest_mode_frequency: mode,
            dt_times_contact_frequency: contact,
            warnings,
        }
    }
}

impl Accuracy {
    /// The warnings that need the whole run: the contact mode at the peak force of each wheel
    /// (a Hertzian contact stiffens as k_c ∝ F^{1/3}, so f_c ∝ F^{1/6}: an impact of 30 W
    /// has a contact mode 1.8× faster than at the static load W), and a rigid contact that
    /// lost and regained contact (each landing is an impulse that one step spreads into a force
    /// of about impulse/Δt, so the peak forces depend on Δt, and so may the bounces that
    /// follow: the scenario zoo's long mode found midspan deflections 2–13 % apart at Δt/2).
    fn after_run(&mut self, sim: &Simulation, wheels: &[WheelSummary], loss_events: usize) {
        let dt = sim.scenario().dt;
        if self
            .dt_times_contact_frequency
            .is_some_and(|c| c <= MAX_DT_CONTACT)
            && !sim.uses_radau5()
        {
            let two_pi = 2.0 * std::f64::consts::PI;
            let worst = (0..wheels.len())
                .filter_map(|k| {
                    let (m_w, k_c, load) = (
                        sim.scenario.wheels[k].wheel_mass,
                        sim.static_contact_stiffness[k],
                        sim.static_loads[k],
                    );
                    let peak = wheels[k].force.max.value;
                    (m_w > 0.0 && k_c > 0.0 && load > 0.0 && peak > load).then(|| {
                        let c = dt * (k_c / m_w).sqrt() / two_pi * (peak / load).powf(1.0 / 6.0);
                        (c, k, peak)
                    })
                })
                .fold(None, |m: Option<(f64, usize, f64)>, v| match m {
                    Some(m) if m.0 >= v.0 => Some(m),
                    _ => Some(v),
                });
            if let Some((c, k, peak)) = worst.filter(|w| w.0 > MAX_DT_CONTACT) {
                self.warnings.push(format!(
                    "the contact mode at the peak contact force {peak:.4e} N of wheel {k} is under-resolved: the contact stiffens with the force, and integrator.dt = {dt:e} s gives dt·f_c = {c:.3} > {MAX_DT_CONTACT} there; use dt <= {:.3e} s",
                    dt * MAX_DT_CONTACT / c
                ));
            }
        }
        let compliant = !sim.contacts.iter().all(super::contact::is_rigid);
        if loss_events > 0 && compliant {
            // The scenario zoo (docs/vehicle_bridge.md, "Scenario campaign"): Eurostar trailers
            // at 120 m/s over a 10 m span with a random rail and no track lost contact hundreds
            // of times, and the deck's peak deflection did not converge in Δt (DAF 1.191,
            // 1.183, 1.240 at Δt = 1e-4, 5e-5, 2.5e-5 s): each landing sets the wheelset
            // bouncing on its contact spring, without a track undamped.
            let track = if sim.track.is_some() {
                ""
            } else {
                "; without a [track] nothing damps the wheelset on its contact spring (rail pads and ballast would)"
            };
            self.warnings.push(format!(
                "{loss_events} loss-of-contact events: wheels left the rail and landed again, and the landings set the wheelsets bouncing on their contact springs, so the peaks after them may depend on integrator.dt = {dt:e} s; check by halving integrator.dt{track}"
            ));
        }
        if loss_events > 0 && sim.contacts.iter().any(super::contact::is_rigid) {
            self.warnings.push(format!(
                "rigid contact with {loss_events} loss-of-contact events: each landing is an impulse that one step of integrator.dt = {dt:e} s spreads into a force of about impulse/dt, so the peak contact forces depend on dt, and the bounces after a landing (so the response) may too; use contact.model = \"hertz\" for impacts"
            ));
        }
    }
}

impl RunSummary {
    /// Largest contact force over all wheels \[N\] (at least 0).
    pub fn max_force(&self) -> f64 {
        self.wheels
            .iter()
            .fold(0.0f64, |m, w| m.max(w.force.max.value))
    }

    /// Smallest contact force over all wheels \[N\].
    pub fn min_force(&self) -> f64 {
        self.wheels
            .iter()
            .fold(f64::INFINITY, |m, w| m.min(w.force.min.value))
    }

    /// Largest peak pressure over all wheels \[Pa\].
    pub fn max_pressure(&self) -> f64 {
        self.wheels
            .iter()
            .fold(0.0f64, |m, w| m.max(w.max_pressure))
    }

    /// Largest |body acceleration| over all wheels [m/s²].
    pub fn max_body_acceleration(&self) -> f64 {
        self.wheels
            .iter()
            .fold(0.0f64, |m, w| m.max(w.max_body_acceleration))
    }

    /// Largest |wheel acceleration| over all wheels [m/s²].
    pub fn max_wheel_acceleration(&self) -> f64 {
        self.wheels
            .iter()
            .fold(0.0f64, |m, w| m.max(w.max_wheel_acceleration))
    }
}

/// A run that failed at a step: the error and the summary up to the last accepted step.
#[derive(Debug, thiserror::Error)]
#[error("{error}")]
pub struct RunFailure {
    /// Why the step failed.
    #[source]
    pub error: VehicleBridgeError,
    /// The summary of the steps accepted before the failure (`completed = false`).
    pub partial: Box<RunSummary>,
}

/// Accumulates the summary from the simulation state.
struct Recorder {
    summary: RunSummary,
}

impl Recorder {
    fn new(sim: &Simulation, steps: usize) -> Self {
        let t = sim.t();
        let (d, _, a) = sim.output_point_response();
        let wheels = sim
            .wheels()
            .iter()
            .map(|w| WheelSummary {
                force: Range::new(w.contact.force, t),
                max_pressure: w.contact.max_pressure.abs(),
                max_body_acceleration: w.body_acceleration.abs(),
                max_wheel_acceleration: w.wheel_acceleration.abs(),
                loss_of_contact_events: 0,
            })
            .collect();
        let points = (0..sim.output_points().len())
            .map(|i| {
                let (d, _, a) = sim.point_response(i);
                PointSummary {
                    x: sim.output_points()[i],
                    deflection: Range::new(d, t),
                    acceleration: Range::new(a, t),
                }
            })
            .collect();
        Self {
            summary: RunSummary {
                completed: false,
                time_reached: t,
                end_time: sim.end_time(),
                steps_taken: 0,
                steps_planned: steps,
                deflection: Range::new(d, t),
                acceleration: Range::new(a, t),
                max_quasi_static_deflection: None,
                dynamic_amplification: None,
                wheels,
                points,
                loss_of_contact_events: sim.loss_of_contact_events(),
                solver: sim.stats(),
                accuracy: Accuracy::of(sim),
            },
        }
    }

    /// Records the step just taken: the quasi-static deflection, the time, the events and
    /// the statistics at every step; the response and force extrema only when `sampled`.
    fn record(&mut self, sim: &Simulation, sampled: bool) -> Result<(), VehicleBridgeError> {
        let s = &mut self.summary;
        let t = sim.t();
        if let Some(qs) = sim.quasi_static_output_deflection()? {
            s.max_quasi_static_deflection =
                Some(s.max_quasi_static_deflection.unwrap_or(0.0).max(qs.abs()));
        }
        s.time_reached = t;
        s.steps_taken += 1;
        s.loss_of_contact_events = sim.loss_of_contact_events();
        s.solver = sim.stats();
        for (w, &events) in s.wheels.iter_mut().zip(sim.wheel_loss_of_contact_events()) {
            w.loss_of_contact_events = events;
        }
        if !sampled {
            return Ok(());
        }
        let (d, _, a) = sim.output_point_response();
        s.deflection.update(d, t);
        s.acceleration.update(a, t);
        for (i, p) in s.points.iter_mut().enumerate() {
            let (d, _, a) = sim.point_response(i);
            p.deflection.update(d, t);
            p.acceleration.update(a, t);
        }
        for (w, sample) in s.wheels.iter_mut().zip(sim.wheels()) {
            w.force.update(sample.contact.force, t);
            w.max_pressure = w.max_pressure.max(sample.contact.max_pressure.abs());
            w.max_body_acceleration = w.max_body_acceleration.max(sample.body_acceleration.abs());
            w.max_wheel_acceleration = w
                .max_wheel_acceleration
                .max(sample.wheel_acceleration.abs());
        }
        Ok(())
    }

    fn finish(mut self, sim: &Simulation, completed: bool) -> RunSummary {
        let s = &mut self.summary;
        s.accuracy
            .after_run(sim, &s.wheels, s.loss_of_contact_events);
        s.completed = completed;
        // Only when the loads have deflected the output point quasi-statically by more than
        // DAF_MIN_LOADING of what the heaviest load standing there would: a run that ends
        // as the first load enters the span has q ≈ 0 and no meaningful ratio.
        let reference = sim.quasi_static_reference_deflection().unwrap_or(0.0);
        s.dynamic_amplification = s
            .max_quasi_static_deflection
            .filter(|q| *q > 0.0 && *q > DAF_MIN_LOADING * reference)
            .map(|q| s.deflection.max_abs() / q);
        self.summary
    }
}

/// Steps `sim` to [`Simulation::end_time`] in steps of the scenario's Δt
/// ([`Simulation::planned_steps`] of them), calling `observer` with the start state and after
/// every accepted step. Stops early (with `completed = false`) when the observer returns
/// [`ControlFlow::Break`]. A step that fails returns the error with the summary up to the last
/// accepted step.
pub fn run(sim: &mut Simulation, observer: &mut dyn RunObserver) -> Result<RunSummary, RunFailure> {
    run_sampled(sim, observer, 1)
}

/// [`run`] with the response and force extrema taken at the start, every `every`-th step and
/// the last step only (the instants a time series recorded every `every` steps holds; the
/// CLI's `[output] every`), so that the summary describes the recorded series. The
/// quasi-static deflection (and so the DAF's denominator) is still taken at every step.
/// `every = 0` is treated as 1.
pub fn run_sampled(
    sim: &mut Simulation,
    observer: &mut dyn RunObserver,
    every: usize,
) -> Result<RunSummary, RunFailure> {
    let every = every.max(1);
    let steps = sim.planned_steps();
    let mut recorder = Recorder::new(sim, steps);
    if observer.start(sim).is_break() {
        return Ok(recorder.finish(sim, false));
    }
    for step in 1..=steps {
        let before = sim.stats().iterations;
        let sampled = step.is_multiple_of(every) || step == steps;
        let stepped = sim.step().and_then(|()| recorder.record(sim, sampled));
        if let Err(error) = stepped {
            return Err(RunFailure {
                error,
                partial: Box::new(recorder.finish(sim, false)),
            });
        }
        let info = StepInfo {
            step,
            steps,
            iterations: sim.stats().iterations - before,
        };
        if observer.after_step(sim, info).is_break() {
            return Ok(recorder.finish(sim, step == steps));
        }
    }
    Ok(recorder.finish(sim, true))
}
