//! The ball drop with the structural methods of `integrate::structural`:
//! `m z'' + f_int(z) = −m g`, `f_int(z) = −F_el(max(0, −z))`, tangent `F_el'(δ)`.
//!
//! Step schedule: `dt` while in contact (or below the surface), `dt_flight` in free flight.
//! A flight step longer than `dt` that ends below the surface is undone; the stepper is
//! restarted at the step's start and takes one step that lands on the crossing time of the
//! free-flight parabola (integrated exactly by these schemes), then continues with `dt`. Contact start/end (`z = 0`) and the maximum approach (`z' = 0`) are located inside
//! each step by the Illinois method on the dense output.

use faer::{Mat, MatMut, MatRef};
use integrate::structural::{StructuralStepper, StructuralSystem};
use integrate::{IntegrateError, illinois};

use super::{
    BallDrop, BallDropError, ContactForce, ElasticForce, Impact, Integrator, RunOutput, RunStats,
    Sample,
};

/// Iteration limit of the Illinois root finder (superlinear: a few tens suffice; on the limit
/// the better bracket end is taken).
const ROOT_ITERATIONS: usize = 200;

struct DropStructure {
    mass: Mat<f64>,
    m: f64,
    g: f64,
    model: ContactForce,
    error: Option<BallDropError>,
}

impl StructuralSystem for DropStructure {
    fn dimension(&self) -> usize {
        1
    }
    fn mass_matrix(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }
    fn internal_force(&mut self, q: &[f64], f_int: &mut [f64]) {
        match self.model.elastic(-q[0], false) {
            Ok(el) => f_int[0] = -el.force,
            Err(e) => {
                self.error.get_or_insert(e);
                f_int[0] = f64::NAN;
            }
        }
    }
    fn tangent_stiffness(&mut self, q: &[f64], mut k: MatMut<'_, f64>) -> bool {
        match self.model.elastic(-q[0], true) {
            Ok(ElasticForce {
                stiffness: Some(s), ..
            }) => {
                k[(0, 0)] = s;
                true
            }
            _ => false,
        }
    }
    fn external_force(&mut self, _t: f64, f_ext: &mut [f64]) {
        f_ext[0] = -self.m * self.g;
    }
}

pub(super) fn run(
    scenario: &BallDrop,
    model: ContactForce,
    interval: f64,
    record: bool,
) -> Result<RunOutput, BallDropError> {
    let Integrator::Structural {
        method,
        dt,
        dt_flight,
    } = scenario.integrator
    else {
        unreachable!("second_order::run is called for structural methods only")
    };
    let (m, g) = (scenario.mass, scenario.gravity);
    let mut sys = DropStructure {
        mass: Mat::from_fn(1, 1, |_, _| m),
        m,
        g,
        model,
        error: None,
    };
    let check = |sys: &mut DropStructure, r: Result<(), integrate::IntegrateError>| {
        if let Some(e) = sys.error.take() {
            return Err(e);
        }
        r.map_err(BallDropError::from)
    };
    let created = StructuralStepper::new(
        method,
        &mut sys,
        0.0,
        &[scenario.height],
        &[scenario.velocity],
    );
    let mut stepper = match created {
        Ok(s) => s,
        Err(e) => return Err(sys.error.take().unwrap_or(e.into())),
    };
    let t_end = scenario.duration;
    let mut impacts: Vec<Impact> = Vec::new();
    let mut in_contact = scenario.starts_in_contact();
    if in_contact {
        impacts.push(Impact::start(0.0, -scenario.velocity));
    }
    let mut samples = Vec::new();
    let mut last_kept = f64::NEG_INFINITY;
    let mut guard_retries = 0;
    let mut out = [0.0];
    if record {
        samples.push(sample(&mut sys, 0.0, scenario.height, scenario.velocity)?);
        last_kept = 0.0;
    }
    while stepper.t() < t_end * (1.0 - 1e-14) {
        let (t0, z0, v0) = (stepper.t(), stepper.q()[0], stepper.v()[0]);
        let wide = !(in_contact || z0 <= 0.0);
        let h = if wide { dt_flight } else { dt }.min(t_end - t0);
        let r = stepper.step(&mut sys, h);
        check(&mut sys, r)?;
        let (t1, z1, v1) = (stepper.t(), stepper.q()[0], stepper.v()[0]);
        if wide && h > dt * (1.0 + 1e-9) && z1 < 0.0 {
            // Undo, land on the crossing, continue with dt. The crossing is that of the
            // free-flight parabola z0 + v0 τ − g τ²/2 (every structural scheme integrates a
            // constant acceleration exactly, while the end velocity of this step already
            // holds a contact kick, so the Hermite dense output is not used here):
            // τ = 2 z0 / (√(v0² + 2 g z0) − v0), stable for g = 0 too.
            let t_hit = t0 + 2.0 * z0 / ((v0 * v0 + 2.0 * g * z0).sqrt() - v0);
            guard_retries += 1;
            let r = stepper.restart(&mut sys, t0, &[z0], &[v0]);
            check(&mut sys, r)?;
            if t_hit - t0 > 1e-12 * dt {
                let r = stepper.step(&mut sys, t_hit - t0);
                check(&mut sys, r)?;
            }
            in_contact = true;
            impacts.push(Impact::start(stepper.t(), -stepper.v()[0]));
            continue;
        }
        // Contact start inside the step: on the free-flight parabola from the step's start
        // (the force is zero until z = 0 and the schemes integrate the flight exactly; the
        // Hermite dense output would carry the contact kick of the step's end velocity).
        if !in_contact && z0 > 0.0 && z1 <= 0.0 {
            let tau = 2.0 * z0 / ((v0 * v0 + 2.0 * g * z0).sqrt() - v0);
            impacts.push(Impact::start(t0 + tau, -(v0 - g * tau)));
            in_contact = true;
        }
        // Maximum approach: z' rises through 0 while in contact.
        if in_contact && v0 < 0.0 && v1 >= 0.0 {
            let tm = illinois(
                |t| {
                    stepper.dense_velocity(t, &mut out)?;
                    Ok::<_, IntegrateError>(out[0])
                },
                (t0, v0),
                (t1, v1),
                ROOT_ITERATIONS,
            )?
            .t;
            stepper.dense_output(tm, &mut out)?;
            let delta = -out[0];
            let f = sys.model.elastic(delta, false)?.force;
            if let Some(imp) = impacts.last_mut() {
                imp.max_approach = imp.max_approach.max(delta);
                imp.peak_force = imp.peak_force.max(f);
            }
        }
        // Contact end.
        if in_contact && z0 <= 0.0 && z1 > 0.0 {
            let te = illinois(
                |t| {
                    stepper.dense_output(t, &mut out)?;
                    Ok::<_, IntegrateError>(out[0])
                },
                (t0, z0),
                (t1, z1),
                ROOT_ITERATIONS,
            )?
            .t;
            stepper.dense_velocity(te, &mut out)?;
            if let Some(imp) = impacts.last_mut() {
                imp.contact_duration = Some(te - imp.time);
                imp.rebound_velocity = Some(out[0]);
            }
            in_contact = false;
        }
        if record && (z1 < 0.0 || z0 < 0.0 || t1 - last_kept >= interval || t1 >= t_end) {
            samples.push(sample(&mut sys, t1, z1, v1)?);
            last_kept = t1;
        }
    }
    let (t_fin, z_fin, v_fin) = (stepper.t(), stepper.q()[0], stepper.v()[0]);
    let final_energy = sample(&mut sys, t_fin, z_fin, v_fin)?.energy;
    let st = stepper.stats();
    Ok(RunOutput {
        samples,
        impacts,
        final_energy,
        final_time: t_fin,
        stats: RunStats {
            method: scenario.integrator.name(),
            steps: st.steps,
            rejected_steps: st.rejected_steps,
            f_evals: st.f_evals,
            jacobian_evals: st.jacobian_evals,
            lu_decompositions: st.lu_decompositions,
            newton_iterations: st.newton_iterations,
            guard_retries,
            contact_solves: sys.model.solves(),
        },
    })
}

fn sample(sys: &mut DropStructure, t: f64, z: f64, v: f64) -> Result<Sample, BallDropError> {
    let el = sys.model.elastic(-z, false)?;
    let (m, g) = (sys.m, sys.g);
    Ok(Sample {
        t,
        z,
        v,
        a: el.force / m - g,
        approach: (-z).max(0.0),
        force: el.force,
        energy: 0.5 * m * v * v + m * g * z + el.energy,
    })
}
