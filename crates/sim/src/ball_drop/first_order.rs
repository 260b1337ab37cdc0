//! The ball drop with the first-order methods of `integrate::ode`: `y = (z, v, D)`, events
//! for contact start (guarded), maximum approach, peak force and contact end.

use std::cell::RefCell;
use std::ops::ControlFlow;
use std::rc::Rc;

use faer::MatMut;
use integrate::IntegrateError;
use integrate::ode::{Direction, Event, OdeOptions, OdeSystem, Output, solve_observed};

use super::{
    BallDrop, BallDropError, ContactForce, HertzImpact, Impact, Integrator, Progress, RunOutput,
    RunStats, Sample, invalid,
};

/// Shared force model (the system and the peak-force event both evaluate it, never at once).
type Shared<T> = Rc<RefCell<T>>;

/// `z' = v`, `v' = F/m − g`, `D' = (F − F_el)·δ'` with `δ' = −v` in contact.
struct DropSystem {
    m: f64,
    g: f64,
    model: Shared<ContactForce>,
    error: Shared<Option<BallDropError>>,
}

impl DropSystem {
    fn fail(&self, e: BallDropError, out: &mut [f64]) {
        self.error.borrow_mut().get_or_insert(e);
        out.fill(f64::NAN);
    }
}

impl OdeSystem for DropSystem {
    fn dim(&self) -> usize {
        3
    }

    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        let (z, v) = (y[0], y[1]);
        let res = self.model.borrow_mut().total(-z, -v);
        match res {
            Ok((f, f_el)) => {
                dydt[0] = v;
                dydt[1] = f / self.m - self.g;
                dydt[2] = if z < 0.0 { (f - f_el) * -v } else { 0.0 };
            }
            Err(e) => self.fail(e, dydt),
        }
    }

    /// Analytic Jacobian. In contact with `F = F_el + cδ' > 0`:
    /// `∂v'/∂z = −F_el'/m`, `∂v'/∂v = −c/m`, `∂D'/∂v = 2cv`; with the clamp active (`F = 0`):
    /// `D' = F_el v`, so `∂D'/∂z = −F_el' v`, `∂D'/∂v = F_el`.
    fn jacobian(&mut self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) -> bool {
        let (z, v) = (y[0], y[1]);
        for i in 0..3 {
            for j in 0..3 {
                jac[(i, j)] = 0.0;
            }
        }
        jac[(0, 1)] = 1.0;
        if z >= 0.0 {
            return true;
        }
        let mut model = self.model.borrow_mut();
        let c = model.damping();
        let el = match model.elastic(-z, true) {
            Ok(el) => el,
            Err(_) => return false,
        };
        let Some(k) = el.stiffness else { return false };
        if el.force - c * v > 0.0 {
            jac[(1, 0)] = -k / self.m;
            jac[(1, 1)] = -c / self.m;
            jac[(2, 1)] = 2.0 * c * v;
        } else {
            jac[(2, 0)] = -k * v;
            jac[(2, 1)] = el.force;
        }
        true
    }
}

/// The run; `(interval, record)` as in the driver, an adaptive method stopped with an error
/// after `step_budget` steps, `observer` after every accepted step.
pub(super) fn run(
    scenario: &BallDrop,
    model: ContactForce,
    reference: &HertzImpact,
    (interval, record, step_budget): (f64, bool, usize),
    observer: &mut dyn FnMut(Progress) -> ControlFlow<()>,
) -> Result<RunOutput, BallDropError> {
    let Integrator::Ode {
        method,
        rtol,
        atol,
        dt,
        guard_step,
        max_step,
    } = scenario.integrator
    else {
        unreachable!("first_order::run is called for first-order methods only")
    };
    let (m, g) = (scenario.mass, scenario.gravity);
    let adaptive = scenario.integrator.is_adaptive();
    let options = if adaptive {
        OdeOptions {
            rtol,
            atol,
            max_step: max_step.unwrap_or(f64::INFINITY),
            max_steps: step_budget,
            ..OdeOptions::default()
        }
    } else {
        OdeOptions {
            max_steps: 2_000_000_000,
            ..OdeOptions::fixed(dt)
        }
    };
    let guard = if adaptive {
        guard_step.or_else(|| {
            let tc = reference.contact_duration;
            (tc.is_finite() && tc > 0.0).then_some(tc / 50.0)
        })
    } else {
        Some(dt)
    };
    let model = Rc::new(RefCell::new(model));
    let error = Rc::new(RefCell::new(None));
    let mut sys = DropSystem {
        m,
        g,
        model: Rc::clone(&model),
        error: Rc::clone(&error),
    };
    let mut stepper = method.build(3, &options)?;
    let contact_start = Event::new(|_t, y: &[f64]| y[0]).direction(Direction::Falling);
    let contact_start = match guard {
        Some(h) => contact_start.guard(h)?,
        None => contact_start,
    };
    let mut events = vec![
        contact_start,
        Event::new(|_t, y: &[f64]| y[0]).direction(Direction::Rising),
        Event::new(|_t, y: &[f64]| y[1]).direction(Direction::Rising),
    ];
    if scenario.damping > 0.0 {
        // dF/dt = F_el'(δ) δ' + c δ'' with δ'' = −(F/m − g), while the unclamped force is
        // positive; +1 out of contact and −1 when clamped, so only a maximum falls through 0.
        let shared = Rc::clone(&model);
        let err = Rc::clone(&error);
        events.push(
            Event::new(move |_t, y: &[f64]| {
                let (z, v) = (y[0], y[1]);
                if z >= 0.0 {
                    return 1.0;
                }
                let mut model = shared.borrow_mut();
                let c = model.damping();
                match model.elastic(-z, true) {
                    Ok(el) => {
                        let f = el.force - c * v;
                        if f <= 0.0 {
                            return -1.0;
                        }
                        el.stiffness.unwrap_or(f64::NAN) * -v - c * (f / m - g)
                    }
                    Err(e) => {
                        err.borrow_mut().get_or_insert(e);
                        f64::NAN
                    }
                }
            })
            .direction(Direction::Falling),
        );
    }
    let output = if record { Output::Steps } else { Output::Final };
    let y0 = [scenario.height, scenario.velocity, 0.0];
    let end = scenario.duration;
    let mut steps = 0;
    let solved = solve_observed(
        stepper.as_mut(),
        &mut sys,
        (0.0, &y0),
        end,
        &mut events,
        &output,
        &mut |t, _y| {
            steps += 1;
            observer(Progress { t, end, steps })
        },
    );
    if let Some(e) = error.borrow_mut().take() {
        return Err(e);
    }
    let sol = match solved {
        Err(IntegrateError::TooManySteps { t, max_steps }) if adaptive => {
            return Err(invalid(
                "duration",
                scenario.duration,
                &format!(
                    "the adaptive method reached its step budget of {max_steps} steps (20 × the plan's estimate, at least 1e6) at t = {t:e} s: the ball has come to rest on the surface or bounces ever faster (every contact step is limited to t_c/50, [integrator] guard_step), or an explicit method meets a stiff contact ([contact] damping / [ball] mass); shorten `duration` or use radau5"
                ),
            ));
        }
        other => other?,
    };
    drop(events);
    let mut model = model.borrow_mut();

    // Impacts from the events.
    let mut impacts: Vec<Impact> = Vec::new();
    if scenario.starts_in_contact() {
        impacts.push(Impact::start(0.0, -scenario.velocity));
    }
    for ev in &sol.events {
        let (z, v) = (ev.y[0], ev.y[1]);
        let open = impacts
            .last_mut()
            .filter(|imp| imp.contact_duration.is_none());
        match ev.index {
            0 => {
                let mut imp = Impact::start(ev.t, -v);
                // With damping the force jumps to c·|v| at contact: a peak candidate.
                imp.peak_force = model.damping() * -v;
                impacts.push(imp);
            }
            1 => {
                if let Some(imp) = open {
                    imp.contact_duration = Some(ev.t - imp.time);
                    imp.rebound_velocity = Some(v);
                }
            }
            _ => {
                if let Some(imp) = open {
                    let (f, _) = model.total(-z, -v)?;
                    imp.max_approach = imp.max_approach.max(-z);
                    imp.peak_force = imp.peak_force.max(f);
                }
            }
        }
    }

    // Time series: every step in (or next to) contact, free flight every `interval`. The
    // driver keeps no dense output after the run, so free-flight points between two accepted
    // steps that are both above the surface come from the exact flight solution from the
    // earlier step, z = zᵢ + vᵢτ − gτ²/2, v = vᵢ − gτ (F = 0 there; the guard never lets a
    // whole contact fall inside one step).
    let mut samples = Vec::new();
    let n = sol.t.len();
    let mut last_kept = f64::NEG_INFINITY;
    let mut y_fill = [0.0; 3];
    for i in 0..n {
        let near_contact = sol.y[i][0] < 0.0
            || (i > 0 && sol.y[i - 1][0] < 0.0)
            || (i + 1 < n && sol.y[i + 1][0] < 0.0);
        if i > 0 && !near_contact {
            let (ti, yi) = (sol.t[i - 1], &sol.y[i - 1]);
            while last_kept + interval < sol.t[i] {
                let tau = last_kept + interval - ti;
                if tau <= 0.0 {
                    last_kept = ti;
                    continue;
                }
                y_fill[0] = yi[0] + yi[1] * tau - 0.5 * g * tau * tau;
                y_fill[1] = yi[1] - g * tau;
                y_fill[2] = yi[2];
                last_kept = ti + tau;
                samples.push(sample(&mut model, m, g, last_kept, &y_fill)?);
            }
        }
        if !(near_contact || i == 0 || i + 1 == n || sol.t[i] - last_kept >= interval) {
            continue;
        }
        last_kept = sol.t[i];
        samples.push(sample(&mut model, m, g, sol.t[i], &sol.y[i])?);
    }
    let y_end = sol.y.last().map_or(&y0[..], |y| y.as_slice());
    let t_end = sol.t.last().copied().unwrap_or(0.0);
    let final_energy = sample(&mut model, m, g, t_end, y_end)?.energy;
    let st = sol.stats;
    Ok(RunOutput {
        samples,
        impacts,
        final_energy,
        final_time: t_end,
        completed: !sol.stopped,
        stats: RunStats {
            method: method.name(),
            steps: st.steps,
            rejected_steps: st.rejected_steps,
            f_evals: st.f_evals,
            jacobian_evals: st.jacobian_evals,
            lu_decompositions: st.lu_decompositions,
            newton_iterations: st.newton_iterations,
            guard_retries: sol.guard_retries,
            contact_solves: model.solves(),
        },
    })
}

/// The sample at state `y = (z, v, D)`.
fn sample(
    model: &mut ContactForce,
    m: f64,
    g: f64,
    t: f64,
    y: &[f64],
) -> Result<Sample, BallDropError> {
    let (z, v, d) = (y[0], y[1], y[2]);
    let (f, _) = model.total(-z, -v)?;
    let w = model.elastic(-z, false)?.energy;
    Ok(Sample {
        t,
        z,
        v,
        a: f / m - g,
        approach: (-z).max(0.0),
        force: f,
        energy: 0.5 * m * v * v + m * g * z + w + d,
    })
}
