//! The interaction model of a sweep (`[trains] model = "interaction"`): every passage is a
//! coupled vehicle–bridge run ([`crate::vehicle_bridge::Simulation`]) of the train's vehicle
//! models (quarter cars, sprung masses, bogie vehicles, articulated trains) with the wheel–rail
//! contact law of the sweep's `[contact]` table, instead of the train's static axle loads.
//! The train starts with its leading axle at the span's entry (x = 0), the rest of it on the
//! rigid approach track in static equilibrium, and runs until its last axle has left the span
//! plus the free-vibration time. The peaks at the output points are taken from the modal state
//! of every step, w(x_p) = Σ_j w_j(x_p) q_j and ẅ(x_p) = Σ_j w_j(x_p) q̈_j, over the same modes as
//! the moving-force model; the quasi-static deflection (for φ') is that of the train's static
//! axle loads (the moving-force passage's). References: docs/sweep.md, references.md §T2.

use std::sync::Arc;

use beam::{ModalBasis, ModalDamping, PassagePeaks};

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

/// The deflection and acceleration peaks of train `train` crossing at `speed` \[m/s\], at
/// `points` (their mode shapes in `point_shapes`, point-major), the run ending
/// `free_vibration` \[s\] after the last axle has left the span. `static_deflection` is left
/// empty (the caller takes it from the moving-force passage).
pub fn passage(
    model: &InteractionModel,
    train: usize,
    speed: f64,
    point_shapes: &[f64],
    free_vibration: f64,
) -> Result<PassagePeaks, VehicleBridgeError> {
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
    let last = vehicles
        .wheels
        .iter()
        .map(|w| w.position)
        .chain(vehicles.forces.iter().map(|f| f.position))
        .fold(0.0f64, f64::min);
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
) -> Result<PassagePeaks, VehicleBridgeError> {
    let vehicles = &model.trains[train];
    let length = model.basis.length();
    let m = model.basis.n_modes();
    let points = point_shapes.len() / m.max(1);
    let last = vehicles
        .wheels
        .iter()
        .map(|w| w.position)
        .fold(0.0f64, f64::min);
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
        duration: Some((length - last) / speed + free_vibration),
        coupling: model.coupling,
        gravity: model.gravity,
        output_point: 0.5 * length,
    };
    let mut sim = Simulation::with_vehicles(scenario, vehicles.layouts.clone())?;
    let mut peaks = PassagePeaks {
        deflection: vec![0.0; points],
        acceleration: vec![0.0; points],
        static_deflection: Vec::new(),
        steps: 0,
    };
    let mut values = vec![(0.0, 0.0); points];
    let summary = sim.run(|s| {
        let (q, a) = (&s.state()[..m], &s.acceleration()[..m]);
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
        observe(s.t(), &values);
    })?;
    peaks.steps = summary.solver.steps;
    Ok(peaks)
}
