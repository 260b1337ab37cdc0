//! The convenience driver [`solve`]: integrate to `t_end`, collect output, locate events and
//! guard short stiff contacts.
//!
//! # Events
//! An [`Event`] is a scalar function `g(t, y)`. After every accepted step, `g` is evaluated at
//! the end of the step and at [`INTERIOR_SAMPLES`] equally spaced interior points of the dense
//! output; every sign change that matches the event's [`Direction`] is located by the Illinois
//! variant of regula falsi on `g(t, y(t))` with `y(t)` from [`OdeStepper::interpolate`], to a
//! bracket width of `4ε·max(1, |t|)`. A terminal event ends the integration at the event time.
//!
//! # Contact guard (never step over a short stiff contact)
//! An event may carry a guard step `h_c` ([`Event::guard`]); `g ≤ 0` is then "inside" (the
//! bodies overlap). The rule, applied by the driver to any method:
//! 1. while `g ≤ 0` at the start of a step, the step is capped at `h_c`;
//! 2. a step that enters the region (`g > 0` at its start, `g ≤ 0` at its end or at one of the
//!    interior samples) and is longer than `h_c` is **undone**: the stepper is restarted at the
//!    start of the step and re-advanced with steps capped at `max(h_c, (t* − t)/2)`, where `t*`
//!    is the crossing time estimated on the rejected step's dense output, recomputed from the
//!    current `t` before every step. The approach to the contact therefore halves the distance
//!    to it per step until the step is at most `h_c`, and the contact itself is resolved with
//!    steps of at most `h_c` (choose e.g. `h_c = T_contact/50`).
//!
//! An implicit L-stable method (Radau5, BDF) taking a step much longer than the contact
//! otherwise finds a quasi-static "stuck" solution and loses the rebound; rule 2 detects this
//! because the end of such a step lies inside the region. A contact that begins and ends
//! between two samples of one step's dense output cannot be seen by rule 2; rule 1 and a
//! `max_step` in the options then bound the risk.

use super::{OdeStepper, OdeSystem};
use crate::error::IntegrateError;
use crate::root::illinois;
use crate::stats::Stats;

/// Interior points of each step at which event functions are sampled (besides the end point).
pub const INTERIOR_SAMPLES: usize = 4;
/// Maximum iterations of the event root finder.
const MAX_ROOT_ITERATIONS: usize = 200;

/// Which sign changes of `g` count as events.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// `g` goes from negative to non-negative.
    Rising,
    /// `g` goes from positive to non-positive.
    Falling,
    /// Either.
    Both,
}

impl Direction {
    fn matches(self, g_before: f64, g_after: f64) -> bool {
        let rising = g_before < 0.0 && g_after >= 0.0;
        let falling = g_before > 0.0 && g_after <= 0.0;
        match self {
            Direction::Rising => rising,
            Direction::Falling => falling,
            Direction::Both => rising || falling,
        }
    }
}

/// Boxed event function `g(t, y)`.
type EventFn<'a> = Box<dyn FnMut(f64, &[f64]) -> f64 + 'a>;

/// An event function `g(t, y)` with its options.
pub struct Event<'a> {
    g: EventFn<'a>,
    direction: Direction,
    terminal: bool,
    guard: Option<f64>,
}

impl<'a> Event<'a> {
    /// Both directions, not terminal, no guard.
    pub fn new(g: impl FnMut(f64, &[f64]) -> f64 + 'a) -> Self {
        Self {
            g: Box::new(g),
            direction: Direction::Both,
            terminal: false,
            guard: None,
        }
    }

    /// Only report crossings in `direction`.
    pub fn direction(mut self, direction: Direction) -> Self {
        self.direction = direction;
        self
    }

    /// Stop the integration at the first reported crossing.
    pub fn terminal(mut self) -> Self {
        self.terminal = true;
        self
    }

    /// Guard the region `g ≤ 0` with the step `h_c` (see the module documentation).
    pub fn guard(mut self, h_contact: f64) -> Result<Self, IntegrateError> {
        super::positive_finite("guard step", h_contact)?;
        self.guard = Some(h_contact);
        Ok(self)
    }

    fn eval(&mut self, t: f64, y: &[f64]) -> f64 {
        (self.g)(t, y)
    }
}

/// A located event.
#[derive(Debug, Clone, PartialEq)]
pub struct EventRecord {
    /// Index of the event in the slice given to [`solve`].
    pub index: usize,
    /// Event time.
    pub t: f64,
    /// State at the event time (dense output).
    pub y: Vec<f64>,
    /// `true` for a rising crossing (negative to non-negative).
    pub rising: bool,
}

/// What [`solve`] records.
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    /// The initial point and every accepted step.
    Steps,
    /// The given times (sorted, within `[t0, t_end]`), by dense output.
    Times(Vec<f64>),
    /// Only the final point.
    Final,
}

/// Result of [`solve`].
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Output times.
    pub t: Vec<f64>,
    /// Output states, one vector per time.
    pub y: Vec<Vec<f64>>,
    /// Events in time order.
    pub events: Vec<EventRecord>,
    /// Counters of the stepper for this run.
    pub stats: Stats,
    /// Steps undone by the contact guard.
    pub guard_retries: usize,
    /// `true` when a terminal event ended the run (then the last output is the event).
    pub terminated: bool,
}

/// Integrate from `(t0, y0)` to `t_end` with any stepper, recording `output` and locating
/// `events` (module documentation). The stepper is restarted at `t0` and its statistics reset.
pub fn solve(
    stepper: &mut dyn OdeStepper,
    sys: &mut dyn OdeSystem,
    (t0, y0): (f64, &[f64]),
    t_end: f64,
    events: &mut [Event<'_>],
    output: &Output,
) -> Result<Solution, IntegrateError> {
    if t_end.is_nan() || t_end <= t0 || t_end.is_infinite() {
        return Err(super::invalid(
            "t_end",
            format!("must be finite and > t0 = {t0}, got {t_end}"),
        ));
    }
    if let Output::Times(times) = output
        && (times.windows(2).any(|w| w[1] < w[0]) || times.iter().any(|&t| t < t0 || t > t_end))
    {
        return Err(super::invalid(
            "output times",
            format!("must be sorted and within [{t0}, {t_end}]"),
        ));
    }
    stepper.reset_stats();
    stepper.set_max_step(f64::INFINITY);
    stepper.set_state(sys, t0, y0)?;
    stepper.set_stop_time(Some(t_end));
    let mut run = Run::new(y0.len(), events.len());
    for (i, ev) in events.iter_mut().enumerate() {
        run.g_prev[i] = ev.eval(t0, y0);
    }
    let mut sol = Solution {
        t: Vec::new(),
        y: Vec::new(),
        events: Vec::new(),
        stats: Stats::default(),
        guard_retries: 0,
        terminated: false,
    };
    let mut next_output = 0;
    if matches!(output, Output::Steps) {
        sol.t.push(t0);
        sol.y.push(y0.to_vec());
    }
    while stepper.t() < t_end {
        let cap = run.step_cap(events, stepper.t());
        stepper.set_max_step(cap);
        run.t_save = stepper.t();
        run.y_save.copy_from_slice(stepper.y());
        stepper.step(sys)?;
        if let Some(t_cross) = run.guard_violation(stepper, events)? {
            sol.guard_retries += 1;
            run.approach = Some(t_cross);
            stepper.set_state(sys, run.t_save, &run.y_save)?;
            continue;
        }
        let found = run.locate_events(stepper, events)?;
        let terminal = found.iter().find(|r| events[r.index].terminal).map(|r| r.t);
        for rec in found {
            if terminal.is_some_and(|tt| rec.t > tt) {
                break;
            }
            sol.events.push(rec);
        }
        let t_last = terminal.unwrap_or(stepper.t());
        if let Output::Times(times) = output {
            while next_output < times.len() && times[next_output] <= t_last {
                stepper.interpolate(times[next_output], &mut run.y_tmp)?;
                sol.t.push(times[next_output]);
                sol.y.push(run.y_tmp.clone());
                next_output += 1;
            }
        }
        if let Some(tt) = terminal {
            stepper.interpolate(tt, &mut run.y_tmp)?;
            sol.t.push(tt);
            sol.y.push(run.y_tmp.clone());
            sol.terminated = true;
            break;
        }
        if matches!(output, Output::Steps) {
            sol.t.push(stepper.t());
            sol.y.push(stepper.y().to_vec());
        }
        for (i, ev) in events.iter_mut().enumerate() {
            run.g_prev[i] = ev.eval(stepper.t(), stepper.y());
        }
    }
    if matches!(output, Output::Final) && !sol.terminated {
        sol.t.push(stepper.t());
        sol.y.push(stepper.y().to_vec());
    }
    stepper.set_max_step(f64::INFINITY);
    stepper.set_stop_time(None);
    sol.stats = stepper.stats();
    Ok(sol)
}

/// Work buffers and guard memory of one `solve` run (allocated once per run).
struct Run {
    g_prev: Vec<f64>,
    y_save: Vec<f64>,
    y_tmp: Vec<f64>,
    t_save: f64,
    /// Estimated time of the next guarded crossing after an undone step.
    approach: Option<f64>,
}

impl Run {
    fn new(dim: usize, n_events: usize) -> Self {
        Self {
            g_prev: vec![0.0; n_events],
            y_save: vec![0.0; dim],
            y_tmp: vec![0.0; dim],
            t_save: 0.0,
            approach: None,
        }
    }

    /// Rules 1 and 2 of the contact guard: the cap for the next step from `t`.
    fn step_cap(&mut self, events: &[Event<'_>], t: f64) -> f64 {
        let mut cap = f64::INFINITY;
        let mut smallest_guard = f64::INFINITY;
        for (ev, &g) in events.iter().zip(&self.g_prev) {
            if let Some(hc) = ev.guard {
                smallest_guard = smallest_guard.min(hc);
                if g <= 0.0 {
                    cap = cap.min(hc);
                }
            }
        }
        if let Some(t_cross) = self.approach {
            if cap.is_finite() || t_cross <= t {
                // Inside, or past the estimate: the approach is over (a new violation
                // produces a new estimate).
                self.approach = None;
            } else {
                cap = smallest_guard.max(0.5 * (t_cross - t));
            }
        }
        cap
    }

    /// Rule 2: a guarded region entered by a step longer than its guard step. Returns the
    /// estimated crossing time, or `None` when the step is acceptable.
    fn guard_violation(
        &mut self,
        stepper: &dyn OdeStepper,
        events: &mut [Event<'_>],
    ) -> Result<Option<f64>, IntegrateError> {
        let (ta, tb) = (stepper.t_prev(), stepper.t());
        let h = tb - ta;
        let mut earliest: Option<f64> = None;
        for (i, ev) in events.iter_mut().enumerate() {
            let Some(hc) = ev.guard else { continue };
            if self.g_prev[i] <= 0.0 || h <= hc * (1.0 + 1e-9) {
                continue;
            }
            if let Some((lo, hi, g_lo, g_hi)) = first_sign_change(
                stepper,
                ev,
                Direction::Falling,
                (ta, self.g_prev[i]),
                tb,
                &mut self.y_tmp,
            )? {
                let t_cross = find_root(stepper, ev, i, (lo, g_lo), (hi, g_hi), &mut self.y_tmp)?;
                earliest = Some(earliest.map_or(t_cross, |e: f64| e.min(t_cross)));
            }
        }
        Ok(earliest)
    }

    /// All reported crossings of the last step, in time order.
    fn locate_events(
        &mut self,
        stepper: &dyn OdeStepper,
        events: &mut [Event<'_>],
    ) -> Result<Vec<EventRecord>, IntegrateError> {
        let (ta, tb) = (stepper.t_prev(), stepper.t());
        let mut found = Vec::new();
        for (i, ev) in events.iter_mut().enumerate() {
            let mut start = (ta, self.g_prev[i]);
            while let Some((lo, hi, g_lo, g_hi)) =
                first_sign_change(stepper, ev, ev.direction, start, tb, &mut self.y_tmp)?
            {
                let t_event = find_root(stepper, ev, i, (lo, g_lo), (hi, g_hi), &mut self.y_tmp)?;
                stepper.interpolate(t_event, &mut self.y_tmp)?;
                found.push(EventRecord {
                    index: i,
                    t: t_event,
                    y: self.y_tmp.clone(),
                    rising: g_lo < 0.0,
                });
                // Continue after this crossing (several crossings inside one step).
                if hi >= tb {
                    break;
                }
                start = (hi, g_hi);
            }
        }
        found.sort_by(|a, b| a.t.total_cmp(&b.t));
        Ok(found)
    }
}

/// `(t_lo, t_hi, g(t_lo), g(t_hi))` around a sign change.
type Bracket = (f64, f64, f64, f64);

/// Sample `g` on `(start.0, tb]` at the interior points and the end; return the first bracket
/// `[lo, hi]` with a sign change in `direction`.
fn first_sign_change(
    stepper: &dyn OdeStepper,
    ev: &mut Event<'_>,
    direction: Direction,
    (ta, ga): (f64, f64),
    tb: f64,
    y_tmp: &mut [f64],
) -> Result<Option<Bracket>, IntegrateError> {
    let (t0, t1) = (stepper.t_prev(), stepper.t());
    let h = t1 - t0;
    let (mut t_lo, mut g_lo) = (ta, ga);
    for s in 1..=INTERIOR_SAMPLES + 1 {
        let ts = if s == INTERIOR_SAMPLES + 1 {
            tb
        } else {
            t0 + h * s as f64 / (INTERIOR_SAMPLES + 1) as f64
        };
        if ts <= t_lo {
            continue;
        }
        let g = if ts == t1 {
            ev.eval(t1, stepper.y())
        } else {
            stepper.interpolate(ts, y_tmp)?;
            ev.eval(ts, y_tmp)
        };
        if direction.matches(g_lo, g) {
            return Ok(Some((t_lo, ts, g_lo, g)));
        }
        (t_lo, g_lo) = (ts, g);
    }
    Ok(None)
}

/// The root of `g(t, y(t))` over `[a, b]` with `g(a)·g(b) ≤ 0` by [`crate::root::illinois`]
/// on the stepper's dense output (bracket width `4ε·max(1, |t|)`).
fn find_root(
    stepper: &dyn OdeStepper,
    ev: &mut Event<'_>,
    index: usize,
    a: (f64, f64),
    b: (f64, f64),
    y_tmp: &mut [f64],
) -> Result<f64, IntegrateError> {
    let g = |t: f64| -> Result<f64, IntegrateError> {
        stepper.interpolate(t, y_tmp)?;
        Ok(ev.eval(t, y_tmp))
    };
    let root = illinois(g, a, b, MAX_ROOT_ITERATIONS)?;
    if root.converged {
        Ok(root.t)
    } else {
        Err(IntegrateError::EventLocation {
            index,
            t_start: a.0,
            t_end: b.0,
            iterations: MAX_ROOT_ITERATIONS,
        })
    }
}
