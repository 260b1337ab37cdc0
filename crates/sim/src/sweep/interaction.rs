//! The interaction model of a sweep (`[trains] model = "interaction"`): every passage is a
//! coupled vehicle–bridge run ([`crate::vehicle_bridge::Simulation`]) of the train's vehicle
//! models (quarter cars, sprung masses, bogie vehicles, articulated trains) with the wheel–rail
//! contact law of the sweep's `[contact]` table, instead of the train's static axle loads.
//! The train starts with its leading axle at the span's entry (x = 0), the rest of it on the
//! rigid approach track in static equilibrium, and runs coupled until its last axle has left
//! the span; the free vibration that follows is the exact modal recurrence of the unloaded
//! bridge (the vehicles, on the rigid track, no longer act on it). The peaks at the output points are taken from the modal state
//! of every step, w(x_p) = Σ_j w_j(x_p) q_j and ẅ(x_p) = Σ_j w_j(x_p) q̈_j, over the same modes as
//! the moving-force model; the quasi-static deflection (for φ') is that of the train's static
//! axle loads (the moving-force passage's). References: docs/sweep.md, references.md §T2.

use std::sync::Arc;

use beam::sdof::PiecewiseLinearSdof;
use beam::{ModalBasis, ModalDamping, PassagePeaks};

use crate::train_response::TrainMonitor;
use crate::vehicle_bridge::{
    ContactGeometry, ContactModel, CouplingSpec, Integrator, Irregularity, Scenario, Simulation,
    VehicleBridgeError, VehicleLayout, WheelSpec,
};

/// One train of an interaction sweep: its wheels with the leading axle at x = 0 and its
/// multibody vehicles.
#[derive(Debug, Clone)]
pub struct TrainVehicles {
    /// The wheels (positions ≤ 0, the leading axle at 0).
    pub wheels: Vec<WheelSpec>,
    /// The multibody vehicles on those wheels.
    pub layouts: Vec<VehicleLayout>,
    /// The axles of the train's `moving_forces` vehicles (positions ≤ 0).
    pub forces: Vec<crate::vehicle_bridge::MovingForce>,
    /// The time step of its passages \[s\] (resolves the contact modes: the coupled model's
    /// default, `config::vehicle_bridge::default_dt`, unless given).
    pub dt: f64,
}

/// The settings of the interaction model (validated by `config::sweep`).
#[derive(Clone)]
pub struct InteractionModel {
    /// The bridge modes (shared by every passage).
    pub basis: Arc<dyn ModalBasis + Send + Sync>,
    /// Modal damping.
    pub damping: ModalDamping,
    /// One entry per train of the sweep (same order).
    pub trains: Vec<TrainVehicles>,
    /// Contact law of every wheel.
    pub contact: ContactModel,
    /// Contact geometry and material.
    pub geometry: ContactGeometry,
    /// The time integrator.
    pub integrator: Integrator,
    /// The coupling iteration.
    pub coupling: CouplingSpec,
    /// Gravity \[m/s²\].
    pub gravity: f64,
}

impl std::fmt::Debug for InteractionModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InteractionModel")
            .field("modes", &self.basis.n_modes())
            .field("trains", &self.trains.len())
            .field("contact", &self.contact)
            .field("integrator", &self.integrator)
            .finish_non_exhaustive()
    }
}

/// What the train's wheels and car bodies went through in one passage (the coupled part of
/// the run, from the leading axle's entry until the last axle has left the span).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VehiclePeaks {
    /// max over wheels and steps of (W_k − F_k)/W_k, W_k the wheel's static load and F_k its
    /// contact force (1: a wheel fully unloaded, i.e. out of contact).
    pub max_unloading_ratio: f64,
    /// The smallest contact force of any wheel \[N\] (0 when a wheel lost contact).
    pub min_contact_force: f64,
    /// Transitions of a wheel from contact to loss of contact, over all wheels.
    pub loss_of_contact_events: usize,
    /// The largest vertical car-body acceleration \[m/s²\] (EN 1990 A2.4.4.3.2's comfort
    /// criterion; 0 without a multibody vehicle).
    pub max_body_acceleration: f64,
}

/// The deflection and acceleration peaks of train `train` crossing at `speed` \[m/s\], at
/// `points` (their mode shapes in `point_shapes`, point-major), the run ending
/// `free_vibration` \[s\] after the last axle has left the span, and what its vehicles went
/// through. `static_deflection` is left empty (the caller takes it from the moving-force
/// passage).
pub fn passage(
    model: &InteractionModel,
    train: usize,
    speed: f64,
    point_shapes: &[f64],
    free_vibration: f64,
) -> Result<(PassagePeaks, VehiclePeaks), VehicleBridgeError> {
    passage_with(model, train, speed, point_shapes, free_vibration, |_, _| {})
}

/// The time history (t \[s\], w \[m\], ẅ \[m/s²\]) of the passage at the first point of
/// `point_shapes` (as [`passage`]), at most `samples` + 1 values, evenly spaced in steps.
pub fn history(
    model: &InteractionModel,
    train: usize,
    speed: f64,
    point_shapes: &[f64],
    free_vibration: f64,
    samples: usize,
) -> Result<Vec<(f64, f64, f64)>, VehicleBridgeError> {
    let m = model.basis.n_modes();
    let vehicles = &model.trains[train];
    let last = rearmost(vehicles);
    let steps = ((model.basis.length() - last) / speed + free_vibration) / vehicles.dt;
    let every = ((steps / samples.max(1) as f64).ceil() as usize).max(1);
    let mut out = Vec::new();
    let mut step = 0usize;
    passage_with(
        model,
        train,
        speed,
        &point_shapes[..m],
        free_vibration,
        |t, wa| {
            if step.is_multiple_of(every) {
                out.push((t, wa[0].0, wa[0].1));
            }
            step += 1;
        },
    )?;
    Ok(out)
}

/// [`passage`], calling `observe(t, [(w, ẅ) per point])` after every step.
fn passage_with(
    model: &InteractionModel,
    train: usize,
    speed: f64,
    point_shapes: &[f64],
    free_vibration: f64,
    mut observe: impl FnMut(f64, &[(f64, f64)]),
) -> Result<(PassagePeaks, VehiclePeaks), VehicleBridgeError> {
    let vehicles = &model.trains[train];
    let length = model.basis.length();
    let m = model.basis.n_modes();
    let points = point_shapes.len() / m.max(1);
    let exit = (length - rearmost(vehicles)) / speed;
    let dt = vehicles.dt;
    // The steps of the passage and its free vibration (as `Simulation::planned_steps`).
    let total_steps = ((exit + free_vibration) / dt - 1e-9).ceil().max(0.0) as usize;
    let mut sim = passage_simulation(model, train, speed)?;
    let mut peaks = PassagePeaks {
        deflection: vec![0.0; points],
        acceleration: vec![0.0; points],
        static_deflection: Vec::new(),
        steps: 0,
    };
    let mut values = vec![(0.0, 0.0); points];
    let mut record = |t: f64, q: &[f64], a: &[f64]| {
        for p in 0..points {
            let shapes = &point_shapes[p * m..(p + 1) * m];
            let (mut w, mut acc) = (0.0, 0.0);
            for j in 0..m {
                w += shapes[j] * q[j];
                acc += shapes[j] * a[j];
            }
            peaks.deflection[p] = peaks.deflection[p].max(w.abs());
            peaks.acceleration[p] = peaks.acceleration[p].max(acc.abs());
            values[p] = (w, acc);
        }
        observe(t, &values);
    };
    let mut monitor = TrainMonitor::new(&sim);
    let summary = sim.run(|s| {
        record(s.t(), &s.state()[..m], &s.acceleration()[..m]);
        monitor.observe(s);
    })?;
    let coupled = summary.solver.steps;
    let vehicle_peaks = VehiclePeaks {
        max_unloading_ratio: monitor.max_unloading_ratio(),
        min_contact_force: summary
            .wheels
            .iter()
            .map(|w| w.force.min.value)
            .reduce(f64::min)
            .unwrap_or(0.0)
            .max(0.0),
        loss_of_contact_events: summary.loss_of_contact_events,
        max_body_acceleration: monitor
            .vehicles()
            .into_iter()
            .flatten()
            .map(|v| v.max_body_acceleration)
            .fold(0.0, f64::max),
    };
    // Free vibration: every axle has left the span, so the modes no longer feel the vehicles
    // (they load the rigid approach): the exact modal recurrence from the coupled run's final
    // modal state, on the same time grid.
    let tail = FreeVibration::new(model, dt)?;
    let (mut q, mut v) = (sim.state()[..m].to_vec(), sim.velocity()[..m].to_vec());
    let mut a = vec![0.0; m];
    for step in coupled + 1..=total_steps {
        tail.step(&mut q, &mut v, &mut a);
        record(step as f64 * dt, &q, &a);
    }
    peaks.steps = coupled.max(total_steps);
    Ok((peaks, vehicle_peaks))
}

/// The coupled run of train `train` crossing at `speed` \[m/s\]: its leading axle at the span's
/// entry, until its last axle has left the span, the force floor bounded
/// (`Simulation::bound_force_floor`: a sweep reports no floor) and the coupling iteration
/// converged by the contact laws' residual (`Simulation::accept_by_law_residual`).
pub fn passage_simulation(
    model: &InteractionModel,
    train: usize,
    speed: f64,
) -> Result<Simulation, VehicleBridgeError> {
    let vehicles = &model.trains[train];
    let length = model.basis.length();
    let scenario = Scenario {
        bridge: Box::new(Arc::clone(&model.basis)),
        damping: model.damping.clone(),
        wheels: vehicles.wheels.clone(),
        moving_forces: vehicles.forces.clone(),
        speed,
        contact: model.contact.clone(),
        geometry: model.geometry,
        irregularity: Irregularity::None,
        integrator: model.integrator,
        dt: vehicles.dt,
        duration: Some((length - rearmost(vehicles)) / speed),
        coupling: model.coupling,
        gravity: model.gravity,
        output_point: 0.5 * length,
    };
    let mut sim = Simulation::with_vehicles(scenario, vehicles.layouts.clone())?;
    sim.bound_force_floor(true);
    sim.accept_by_law_residual(true);
    Ok(sim)
}

/// The rearmost axle's position (wheels and moving forces) \[m\] (≤ 0).
fn rearmost(vehicles: &TrainVehicles) -> f64 {
    vehicles
        .wheels
        .iter()
        .map(|w| w.position)
        .chain(vehicles.forces.iter().map(|f| f.position))
        .fold(0.0f64, f64::min)
}

/// The free vibration of the bridge modes: q̈_j + c_j q̇_j + ω_j² q_j = 0 (the mass-normalised
/// modal equations of the coupled model without loads), advanced by the exact propagator of
/// each mode (`beam::sdof::PiecewiseLinearSdof` with zero load, the moving-force sweep's
/// recurrence; references.md §T2), with q̈_j taken from the equation at each step.
struct FreeVibration {
    steppers: Vec<PiecewiseLinearSdof>,
    omegas: Vec<f64>,
    damping: Vec<f64>,
}

impl FreeVibration {
    fn new(model: &InteractionModel, dt: f64) -> Result<Self, VehicleBridgeError> {
        let omegas = model.basis.circular_frequencies().to_vec();
        let damping = model.damping.velocity_coefficients(&omegas)?;
        let steppers = omegas
            .iter()
            .zip(&damping)
            .map(|(&w, &c)| PiecewiseLinearSdof::new(w, c, dt))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            steppers,
            omegas,
            damping,
        })
    }

    /// One step of (q, q̇), and q̈ at its end.
    fn step(&self, q: &mut [f64], v: &mut [f64], a: &mut [f64]) {
        for (j, stepper) in self.steppers.iter().enumerate() {
            (q[j], v[j]) = stepper.step(q[j], v[j], 0.0, 0.0);
            a[j] = -self.damping[j] * v[j] - self.omegas[j] * self.omegas[j] * q[j];
        }
    }
}
