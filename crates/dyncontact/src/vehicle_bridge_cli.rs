//! `dyncontact run FILE` with `kind = "vehicle_bridge"`: wheels over a modal bridge with
//! local contact (docs/vehicle_bridge.md), and `dyncontact bench coupling`.
//!
//! Every key is in SI units; unknown keys are errors.

use std::path::Path;
use std::time::Instant;

use anyhow::{Result, anyhow, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use integrate::structural::StructuralMethod;
use serde::{Deserialize, Serialize};
use sim::vehicle_bridge::traction::{TractionDrive, TractionMethod, TractionSample, TractionSpec};
use sim::vehicle_bridge::{
    ContactGeometry, ContactModel, CouplingSolver, CouplingSpec, GRAVITY, Irregularity, Radau5Spec,
    Scenario, Simulation, TrackSpectrum, WheelSpec, run,
};

use crate::bridge::BridgeSpec;
use crate::output;
use crate::plot::{self, Panel, Series};

/// The vehicle-bridge default scenario (also the built-in default of `dyncontact run`).
pub const DEFAULT: &str = include_str!("../../../examples/vehicle_bridge_default.toml");

/// The scenario file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleBridgeFile {
    pub kind: String,
    pub bridge: BridgeSpec,
    pub vehicle: VehicleSpec,
    pub contact: Option<ContactSpec>,
    pub irregularity: Option<IrregularitySpec>,
    pub integrator: Option<IntegratorSpec>,
    pub coupling: Option<CouplingToml>,
    pub output: Option<OutputSpec>,
    /// Longitudinal friction (optional; docs/vehicle_bridge.md, "Traction (friction)").
    pub traction: Option<TractionToml>,
}

/// `[traction]`: friction coefficient, tangential method and either a prescribed creepage or
/// a wheel torque [N m] with the wheel's polar inertia [kg m²].
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionToml {
    pub mu: f64,
    pub method: Option<String>,
    pub creepage: Option<f64>,
    pub torque: Option<f64>,
    pub wheel_inertia: Option<f64>,
    pub fastsim_elements: Option<usize>,
}

/// The `[traction]` section of a scenario file (`None` when absent: no friction). Values are
/// range-checked by [`TractionSpec::validate`] with errors naming the key.
pub fn parse_traction(text: &str) -> Result<Option<TractionSpec>> {
    let file: VehicleBridgeFile =
        toml::from_str(text).map_err(|e| anyhow!("invalid vehicle_bridge scenario: {e}"))?;
    let Some(t) = file.traction else {
        return Ok(None);
    };
    let name = t.method.as_deref().unwrap_or("fastsim");
    let method = TractionMethod::by_name(name).ok_or_else(|| {
        anyhow!("[traction] `method` = \"{name}\": expected exact, fastsim or linear")
    })?;
    let drive = match (t.creepage, t.torque, t.wheel_inertia) {
        (Some(xi), None, None) => TractionDrive::Creepage(xi),
        (None, Some(torque), Some(inertia)) => TractionDrive::Torque { torque, inertia },
        (None, Some(_), None) => bail!("[traction]: `torque` needs `wheel_inertia` [kg m²]"),
        (None, None, Some(_)) => bail!("[traction]: `wheel_inertia` applies with `torque` only"),
        (None, None, None) => bail!("[traction]: give exactly one of `creepage` or `torque`"),
        (Some(_), _, _) => {
            bail!("[traction]: `creepage` and `torque`/`wheel_inertia` exclude each other")
        }
    };
    let spec = TractionSpec {
        mu: t.mu,
        method,
        drive,
        fastsim_elements: t.fastsim_elements.unwrap_or(40),
    };
    spec.validate().map_err(|e| anyhow!("[traction]: {e}"))?;
    Ok(Some(spec))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleSpec {
    pub speed: f64,
    pub wheels: Vec<WheelToml>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WheelToml {
    pub position: Option<f64>,
    pub wheel_mass: f64,
    pub body_mass: Option<f64>,
    pub suspension_stiffness: Option<f64>,
    pub suspension_damping: Option<f64>,
    pub static_load: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    pub model: Option<String>,
    pub wheel_radius: Option<f64>,
    pub rail_profile_radius: Option<f64>,
    #[serde(rename = "E")]
    pub e: Option<f64>,
    pub nu: Option<f64>,
    pub grid: Option<usize>,
    pub bem_tol: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IrregularitySpec {
    pub kind: String,
    pub position: Option<f64>,
    pub length: Option<f64>,
    pub depth: Option<f64>,
    pub height: Option<f64>,
    pub amplitude: Option<f64>,
    pub wavelength: Option<f64>,
    pub start: Option<f64>,
    pub end: Option<f64>,
    pub spectrum: Option<String>,
    pub lambda_min: Option<f64>,
    pub lambda_max: Option<f64>,
    pub components: Option<usize>,
    pub seed: Option<u64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    pub method: Option<String>,
    pub dt: Option<f64>,
    pub beta: Option<f64>,
    pub gamma: Option<f64>,
    pub alpha: Option<f64>,
    pub rho_inf: Option<f64>,
    pub duration: Option<f64>,
    /// Radau5 tolerances (only with `method = "radau5"`).
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
}

/// `[integrator] method = "radau5"`: the Radau5 tolerances (`rtol`, `atol`; defaults of
/// [`Radau5Spec`]), or `None` for a structural method. `rtol`/`atol` with another method are
/// an error naming the key.
pub fn parse_radau5(text: &str) -> Result<Option<Radau5Spec>> {
    let file: VehicleBridgeFile =
        toml::from_str(text).map_err(|e| anyhow!("invalid vehicle_bridge scenario: {e}"))?;
    let Some(i) = file.integrator else {
        return Ok(None);
    };
    let radau = i
        .method
        .as_deref()
        .is_some_and(|m| m.trim().eq_ignore_ascii_case("radau5"));
    if !radau {
        for (key, v) in [("rtol", i.rtol), ("atol", i.atol)] {
            if v.is_some() {
                bail!("[integrator] `{key}` is only used by method = \"radau5\"");
            }
        }
        return Ok(None);
    }
    let d = Radau5Spec::default();
    Ok(Some(Radau5Spec {
        rtol: i.rtol.unwrap_or(d.rtol),
        atol: i.atol.unwrap_or(d.atol),
    }))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CouplingToml {
    pub solver: Option<String>,
    pub tol: Option<f64>,
    pub max_iter: Option<usize>,
    pub max_halvings: Option<usize>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Record every n-th step.
    pub every: Option<usize>,
    /// Output point of the bridge response \[m\] (default midspan).
    pub point: Option<f64>,
    /// Number of pressure snapshots along the passage.
    pub snapshots: Option<usize>,
}

/// Parses and validates a scenario file into a [`Scenario`].
pub fn parse(text: &str) -> Result<(Scenario, usize, usize)> {
    let file: VehicleBridgeFile =
        toml::from_str(text).map_err(|e| anyhow!("invalid vehicle_bridge scenario: {e}"))?;
    if file.kind != "vehicle_bridge" {
        bail!("`kind` = \"{}\": expected \"vehicle_bridge\"", file.kind);
    }
    let bridge = file.bridge.build()?;
    let length = bridge.basis.length();
    if file.vehicle.wheels.is_empty() {
        bail!("[vehicle]: at least one [[vehicle.wheels]] table is needed");
    }
    let wheels: Vec<WheelSpec> = file
        .vehicle
        .wheels
        .iter()
        .map(|w| WheelSpec {
            position: w.position.unwrap_or(0.0),
            wheel_mass: w.wheel_mass,
            body_mass: w.body_mass.unwrap_or(0.0),
            suspension_stiffness: w.suspension_stiffness.unwrap_or(0.0),
            suspension_damping: w.suspension_damping.unwrap_or(0.0),
            static_load: w.static_load.unwrap_or(0.0),
        })
        .collect();

    let c = file.contact.as_ref();
    let geometry = ContactGeometry {
        wheel_radius: c.and_then(|c| c.wheel_radius).unwrap_or(0.46),
        rail_profile_radius: c.and_then(|c| c.rail_profile_radius).unwrap_or(0.3),
        youngs_modulus: c.and_then(|c| c.e).unwrap_or(210e9),
        poisson_ratio: c.and_then(|c| c.nu).unwrap_or(0.3),
    };
    let contact = match c.and_then(|c| c.model.as_deref()).unwrap_or("rigid") {
        "rigid" => ContactModel::Rigid,
        "hertz" => ContactModel::Hertz,
        "bem" => ContactModel::Bem {
            elements: c.and_then(|c| c.grid).unwrap_or(32),
            tol: c.and_then(|c| c.bem_tol).unwrap_or(1e-8),
        },
        other => bail!("[contact] `model` = \"{other}\": expected rigid, hertz or bem"),
    };
    if let Some(c) = c
        && !matches!(contact, ContactModel::Bem { .. })
        && (c.grid.is_some() || c.bem_tol.is_some())
    {
        bail!("[contact]: `grid` and `bem_tol` apply to model = \"bem\" only");
    }

    let irregularity = match &file.irregularity {
        None => Irregularity::None,
        Some(spec) => irregularity(spec, geometry.wheel_radius)?,
    };

    let integ = file.integrator.as_ref();
    let method_name = integ.and_then(|i| i.method.as_deref()).unwrap_or("newmark");
    let mut params: Vec<(&str, f64)> = Vec::new();
    if let Some(i) = integ {
        for (k, v) in [
            ("beta", i.beta),
            ("gamma", i.gamma),
            ("alpha", i.alpha),
            ("rho_inf", i.rho_inf),
        ] {
            if let Some(v) = v {
                params.push((k, v));
            }
        }
    }
    // radau5 replaces the structural method (parse_radau5, Simulation::set_radau5); the
    // scenario keeps a placeholder that is not used.
    let method = if method_name.trim().eq_ignore_ascii_case("radau5") {
        StructuralMethod::average_acceleration()
    } else {
        StructuralMethod::by_name(method_name, &params)
            .map_err(|e| anyhow!("[integrator] `method` = \"{method_name}\": {e}"))?
    };
    if contact == ContactModel::Rigid
        && !method_name.trim().eq_ignore_ascii_case("radau5")
        && matches!(method, StructuralMethod::Newmark { gamma, .. } if gamma <= 0.5)
    {
        eprintln!(
            "warning: rigid contact with the undamped Newmark rule (gamma = 0.5): the contact multiplier can ring and grow at a slope kink (a wheel entering a deflected span); [integrator] method = \"generalized_alpha\" or \"hht\" damps it (docs/vehicle_bridge.md)"
        );
    }
    let dt = integ.and_then(|i| i.dt).unwrap_or(1e-4);
    let duration = integ.and_then(|i| i.duration);

    let cp = file.coupling.as_ref();
    let solver_name = cp
        .and_then(|c| c.solver.as_deref())
        .unwrap_or("quasi_newton");
    let solver = CouplingSolver::by_name(solver_name).ok_or_else(|| {
        anyhow!("[coupling] `solver` = \"{solver_name}\": expected picard, quasi_newton or newton")
    })?;
    let defaults = CouplingSpec::default();
    let coupling = CouplingSpec {
        solver,
        tol: cp.and_then(|c| c.tol).unwrap_or(defaults.tol),
        max_iter: cp.and_then(|c| c.max_iter).unwrap_or(defaults.max_iter),
        max_halvings: cp
            .and_then(|c| c.max_halvings)
            .unwrap_or(defaults.max_halvings),
    };
    let out = file.output.as_ref();
    let every = out.and_then(|o| o.every).unwrap_or(1);
    if every == 0 {
        bail!("[output] `every` must be at least 1");
    }
    let snapshots = out.and_then(|o| o.snapshots).unwrap_or(6);
    let scenario = Scenario {
        output_point: out.and_then(|o| o.point).unwrap_or(0.5 * length),
        bridge: bridge.basis,
        damping: bridge.damping,
        wheels,
        speed: file.vehicle.speed,
        contact,
        geometry,
        irregularity,
        method,
        dt,
        duration,
        coupling,
        gravity: GRAVITY,
    };
    Ok((scenario, every, snapshots))
}

fn need(v: Option<f64>, key: &str, kind: &str) -> Result<f64> {
    v.ok_or_else(|| anyhow!("[irregularity] kind = \"{kind}\" needs `{key}`"))
}

fn irregularity(spec: &IrregularitySpec, wheel_radius: f64) -> Result<Irregularity> {
    let k = spec.kind.as_str();
    let irr = match k {
        "none" => Irregularity::None,
        "dip" | "dipped_joint" => Irregularity::Dip {
            position: need(spec.position, "position", k)?,
            length: need(spec.length, "length", k)?,
            depth: need(spec.depth, "depth", k)?,
        },
        "ramp" => Irregularity::Ramp {
            position: need(spec.position, "position", k)?,
            length: need(spec.length, "length", k)?,
            height: need(spec.height, "height", k)?,
        },
        "wheel_flat" => {
            let length = need(spec.length, "length", k)?;
            // A fresh flat of chord ℓ has depth ℓ²/(8R) (references.md §D2.5) unless given.
            let depth = spec.depth.unwrap_or(length * length / (8.0 * wheel_radius));
            Irregularity::WheelFlat {
                position: spec.position.unwrap_or(0.0),
                length,
                depth,
                wheel_radius,
            }
        }
        "corrugation" => Irregularity::Corrugation {
            amplitude: need(spec.amplitude, "amplitude", k)?,
            wavelength: need(spec.wavelength, "wavelength", k)?,
            start: spec.start.unwrap_or(f64::NEG_INFINITY).max(-1e300),
            end: spec.end.unwrap_or(f64::INFINITY).min(1e300),
        },
        "random" => {
            let name = spec
                .spectrum
                .as_deref()
                .ok_or_else(|| anyhow!("[irregularity] kind = \"random\" needs `spectrum`"))?;
            let spectrum = TrackSpectrum::by_name(name).ok_or_else(|| {
                anyhow!(
                    "[irregularity] `spectrum` = \"{name}\": expected fra1 … fra6, german_low or german_high"
                )
            })?;
            Irregularity::random(
                spectrum,
                spec.lambda_min.unwrap_or(1.0),
                spec.lambda_max.unwrap_or(50.0),
                spec.components.unwrap_or(500),
                spec.seed.unwrap_or(1),
            )?
        }
        other => bail!(
            "[irregularity] `kind` = \"{other}\": expected none, dip, ramp, wheel_flat, corrugation or random"
        ),
    };
    irr.validate()?;
    Ok(irr)
}

/// One recorded row of the time series.
struct Row {
    t: f64,
    midspan: (f64, f64, f64),
    wheels: Vec<sim::vehicle_bridge::WheelSample>,
    iterations: usize,
    traction: Vec<TractionSample>,
}

/// The `traction` object of summary.json.
#[derive(Serialize)]
pub struct TractionSummaryJson {
    pub method: String,
    pub mu: f64,
    /// Largest |F_x| (signed) over all wheels and steps \[N\].
    pub max_longitudinal_force: f64,
    /// Mean F_x over wheel-steps in contact \[N\].
    pub mean_longitudinal_force: f64,
    /// Wheel-steps in full slip.
    pub saturated_steps: usize,
    /// Wheel angular velocities at the end [rad/s].
    pub final_angular_velocity: Vec<f64>,
    /// Always false: the longitudinal force is not applied to the (vertical) bridge model.
    pub bridge_horizontal_load_applied: bool,
}

#[derive(Serialize)]
pub struct ContactSummary {
    pub model: String,
    pub max_force: f64,
    pub min_force: f64,
    pub loss_of_contact_events: usize,
    pub max_pressure: f64,
}

#[derive(Serialize)]
pub struct VehicleSummary {
    pub max_body_acceleration: f64,
    pub max_wheel_acceleration: f64,
    pub static_wheel_loads: Vec<f64>,
}

#[derive(Serialize)]
pub struct SolverSummary {
    pub method: String,
    pub integrator: String,
    pub mean_iterations_per_step: f64,
    pub max_iterations_per_step: usize,
    pub mean_contact_iterations_per_step: f64,
    pub failed_steps: usize,
    pub steps: usize,
}

#[derive(Serialize)]
pub struct Summary {
    pub max_midspan_deflection: f64,
    pub max_midspan_acceleration: f64,
    pub max_quasi_static_deflection: Option<f64>,
    pub dynamic_amplification: Option<f64>,
    pub contact: ContactSummary,
    pub vehicle: VehicleSummary,
    pub solver: SolverSummary,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub traction: Option<TractionSummaryJson>,
    pub wall_time_s: f64,
    pub simulated_time_s: f64,
}

/// The result of a run.
pub struct Outcome {
    pub summary: Summary,
    rows: Vec<Row>,
    snapshots: Vec<(f64, Vec<(f64, f64)>)>,
}

/// Runs a scenario, recording every `every`-th step and `snapshots` pressure snapshots of the
/// first wheel along its passage over the span.
pub fn simulate(scenario: Scenario, every: usize, snapshots: usize) -> Result<Outcome> {
    simulate_with(scenario, None, every, snapshots)
}

/// [`simulate`] with longitudinal friction (`traction`, from [`parse_traction`]).
pub fn simulate_with(
    scenario: Scenario,
    traction: Option<TractionSpec>,
    every: usize,
    snapshots: usize,
) -> Result<Outcome> {
    simulate_full(scenario, traction, None, every, snapshots)
}

/// [`simulate_with`] with an optional Radau5 integration (from [`parse_radau5`]).
pub fn simulate_full(
    scenario: Scenario,
    traction: Option<TractionSpec>,
    radau: Option<Radau5Spec>,
    every: usize,
    snapshots: usize,
) -> Result<Outcome> {
    let length = scenario.bridge.length();
    let model = match scenario.contact {
        ContactModel::Rigid => "rigid",
        ContactModel::Hertz => "hertz",
        ContactModel::Bem { .. } => "bem",
    };
    let integrator = if radau.is_some() {
        "radau5".to_string()
    } else {
        scenario.method.name().to_string()
    };
    let start = Instant::now();
    let mut sim = Simulation::new(scenario)?;
    if let Some(spec) = radau {
        sim.set_radau5(spec)?;
    }
    if let Some(spec) = traction {
        sim.set_traction(spec)?;
    }
    let steps = sim.planned_steps();
    let bar = ProgressBar::with_draw_target(Some(steps as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} steps, {elapsed} (eta {eta})")
            .map_err(|e| anyhow!("progress bar: {e}"))?,
    );
    let snap_positions: Vec<f64> = (0..snapshots)
        .map(|i| length * (i as f64 + 0.5) / snapshots as f64)
        .collect();
    let mut next_snap = 0;
    let mut rows = Vec::with_capacity(steps / every + 2);
    let mut snaps = Vec::new();
    let record = |sim: &Simulation, rows: &mut Vec<Row>, iterations: usize| {
        rows.push(Row {
            t: sim.t(),
            midspan: sim.output_point_response(),
            wheels: sim.wheels().to_vec(),
            iterations,
            traction: sim
                .traction()
                .map(|t| t.samples().to_vec())
                .unwrap_or_default(),
        });
    };
    record(&sim, &mut rows, 0);
    let mut buf = Vec::new();
    // The run driver steps the simulation and computes the summary (maxima, amplification);
    // this observer records the time series and the pressure snapshots.
    let mut observer = |sim: &Simulation, info: run::StepInfo| {
        if info.step.is_multiple_of(every) || info.step == info.steps {
            record(sim, &mut rows, info.iterations);
        }
        let x = sim.wheel_position(0);
        if next_snap < snap_positions.len() && x >= snap_positions[next_snap] {
            sim.centreline_pressure(0, &mut buf);
            snaps.push((x, buf.clone()));
            next_snap += 1;
        }
        if info.step.is_multiple_of(64) {
            bar.set_position(info.step as u64);
        }
        std::ops::ControlFlow::Continue(())
    };
    let run = run::run_sampled(&mut sim, &mut observer, every).map_err(|f| {
        let step = f.partial.steps_taken + 1;
        anyhow::Error::new(f.error).context(format!("step {step} of {steps}"))
    })?;
    bar.finish_and_clear();
    for warning in &run.accuracy.warnings {
        eprintln!("warning: {warning}");
    }
    let wall = start.elapsed().as_secs_f64();
    let stats = run.solver;
    let summary = Summary {
        max_midspan_deflection: run.deflection.max_abs(),
        max_midspan_acceleration: run.acceleration.max_abs(),
        max_quasi_static_deflection: run.max_quasi_static_deflection,
        dynamic_amplification: run.dynamic_amplification,
        contact: ContactSummary {
            model: model.to_string(),
            max_force: run.max_force(),
            min_force: run.min_force(),
            loss_of_contact_events: run.loss_of_contact_events,
            max_pressure: run.max_pressure(),
        },
        vehicle: VehicleSummary {
            max_body_acceleration: run.max_body_acceleration(),
            max_wheel_acceleration: run.max_wheel_acceleration(),
            static_wheel_loads: sim.static_loads().to_vec(),
        },
        solver: SolverSummary {
            // With Radau5 the coupling is its own simplified Newton iteration.
            method: if sim.uses_radau5() {
                "radau5_newton".to_string()
            } else {
                sim.scenario().coupling.solver.name().to_string()
            },
            integrator,
            mean_iterations_per_step: stats.iterations as f64 / stats.steps.max(1) as f64,
            max_iterations_per_step: stats.max_iterations,
            mean_contact_iterations_per_step: stats.contact_iterations as f64
                / stats.steps.max(1) as f64,
            failed_steps: stats.failed_steps,
            steps: stats.steps,
        },
        traction: sim.traction().map(|t| {
            let s = t.summary();
            TractionSummaryJson {
                method: t.spec().method.name().to_string(),
                mu: t.spec().mu,
                max_longitudinal_force: s.max_longitudinal_force,
                mean_longitudinal_force: s.mean_longitudinal_force,
                saturated_steps: s.saturated_steps,
                final_angular_velocity: t.samples().iter().map(|w| w.angular_velocity).collect(),
                bridge_horizontal_load_applied: false,
            }
        }),
        wall_time_s: wall,
        simulated_time_s: run.time_reached,
    };
    Ok(Outcome {
        summary,
        rows,
        snapshots: snaps,
    })
}

/// Writes timeseries.csv, summary.json and the plots into `dir`.
pub fn write_outputs(dir: &Path, outcome: &Outcome) -> Result<()> {
    output::ensure_dir(dir)?;
    let nw = outcome.rows.first().map_or(0, |r| r.wheels.len());
    let with_traction = outcome.summary.traction.is_some();
    let mut header: Vec<String> = [
        "t",
        "midspan_deflection",
        "midspan_velocity",
        "midspan_acceleration",
        "iterations",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let per_wheel = [
        "position",
        "wheel_z",
        "body_z",
        "body_acceleration",
        "contact_force",
        "approach",
        "patch_length",
        "patch_width",
        "max_pressure",
        "longitudinal_force",
        "creepage",
        "adhesion_fraction",
    ];
    let per_wheel = &per_wheel[..if with_traction { 12 } else { 9 }];
    for k in 0..nw {
        for &name in per_wheel {
            header.push(if nw == 1 {
                name.to_string()
            } else {
                format!("{name}_{k}")
            });
        }
    }
    let header_refs: Vec<&str> = header.iter().map(|s| s.as_str()).collect();
    output::write_csv(
        &dir.join("timeseries.csv"),
        &header_refs,
        outcome.rows.iter().map(|r| {
            let mut row = vec![
                r.t,
                r.midspan.0,
                r.midspan.1,
                r.midspan.2,
                r.iterations as f64,
            ];
            for w in &r.wheels {
                row.extend([
                    w.position,
                    w.wheel_displacement,
                    w.body_displacement,
                    w.body_acceleration,
                    w.contact.force,
                    w.approach,
                    w.contact.patch_length,
                    w.contact.patch_width,
                    w.contact.max_pressure,
                ]);
            }
            for (k, t) in r.traction.iter().enumerate() {
                // Insert after wheel k's 9 columns (the first 5 columns are global).
                let at = 5 + (k + 1) * 12 - 3;
                row.splice(
                    at..at,
                    [t.longitudinal_force, t.creepage, t.adhesion_fraction],
                );
            }
            row
        }),
    )?;
    output::write_json(&dir.join("summary.json"), &outcome.summary)?;
    let wheel_series = |f: &dyn Fn(&Row, usize) -> (f64, f64), name: &str| -> Vec<Series> {
        (0..nw)
            .map(|k| {
                Series::new(
                    if nw == 1 {
                        name.to_string()
                    } else {
                        format!("{name} {k}")
                    },
                    outcome.rows.iter().map(|r| f(r, k)).collect(),
                )
            })
            .collect()
    };
    plot::panels(
        &dir.join("contact_force.png"),
        &[Panel {
            title: "Contact force against wheel position".into(),
            x_label: "position [m]".into(),
            y_label: "force [kN]".into(),
            series: wheel_series(
                &|r, k| (r.wheels[k].position, 1e-3 * r.wheels[k].contact.force),
                "wheel",
            ),
        }],
    )?;
    plot::panels(
        &dir.join("midspan.png"),
        &[
            Panel {
                title: "Bridge deflection at the output point".into(),
                x_label: "t [s]".into(),
                y_label: "deflection [mm]".into(),
                series: vec![Series::new(
                    "w",
                    outcome
                        .rows
                        .iter()
                        .map(|r| (r.t, 1e3 * r.midspan.0))
                        .collect(),
                )],
            },
            Panel {
                title: "Bridge acceleration at the output point".into(),
                x_label: "t [s]".into(),
                y_label: "acceleration [m/s²]".into(),
                series: vec![Series::new(
                    "a",
                    outcome.rows.iter().map(|r| (r.t, r.midspan.2)).collect(),
                )],
            },
        ],
    )?;
    let mut motion = wheel_series(&|r, k| (r.t, 1e3 * r.wheels[k].wheel_displacement), "wheel");
    motion.extend(wheel_series(
        &|r, k| (r.t, 1e3 * r.wheels[k].body_displacement),
        "body",
    ));
    plot::panels(
        &dir.join("vehicle.png"),
        &[
            Panel {
                title: "Wheel and body displacement (down)".into(),
                x_label: "t [s]".into(),
                y_label: "z [mm]".into(),
                series: motion,
            },
            Panel {
                title: "Body acceleration".into(),
                x_label: "t [s]".into(),
                y_label: "acceleration [m/s²]".into(),
                series: wheel_series(&|r, k| (r.t, r.wheels[k].body_acceleration), "body"),
            },
        ],
    )?;
    if !outcome.snapshots.is_empty() {
        plot::panels(
            &dir.join("pressure.png"),
            &[Panel {
                title: "Contact pressure along the track centreline (wheel 0)".into(),
                x_label: "ξ (along track, from the wheel) [mm]".into(),
                y_label: "pressure [MPa]".into(),
                series: outcome
                    .snapshots
                    .iter()
                    .map(|(x, p)| {
                        Series::new(
                            format!("x = {x:.2} m"),
                            p.iter().map(|(xi, p)| (1e3 * xi, 1e-6 * p)).collect(),
                        )
                    })
                    .collect(),
            }],
        )?;
    }
    Ok(())
}

/// Prints the readable summary.
pub fn print_summary(s: &Summary) {
    println!(
        "vehicle over bridge: {:.3} s simulated in {:.2} s wall",
        s.simulated_time_s, s.wall_time_s
    );
    println!(
        "  output-point deflection max {:.4e} m, acceleration max {:.4} m/s²",
        s.max_midspan_deflection, s.max_midspan_acceleration
    );
    if let Some(d) = s.dynamic_amplification {
        println!("  dynamic amplification {d:.4}");
    }
    println!(
        "  contact ({}): force {:.1} … {:.1} N, {} loss-of-contact events, max pressure {:.1} MPa",
        s.contact.model,
        s.contact.min_force,
        s.contact.max_force,
        s.contact.loss_of_contact_events,
        1e-6 * s.contact.max_pressure
    );
    println!(
        "  vehicle: max body acceleration {:.4} m/s²",
        s.vehicle.max_body_acceleration
    );
    println!(
        "  solver {} / {}: {} steps, {:.2} iterations/step (max {}), {:.2} contact-solver iterations/step, {} failed steps",
        s.solver.method,
        s.solver.integrator,
        s.solver.steps,
        s.solver.mean_iterations_per_step,
        s.solver.max_iterations_per_step,
        s.solver.mean_contact_iterations_per_step,
        s.solver.failed_steps
    );
    if let Some(t) = &s.traction {
        println!(
            "  traction ({}, mu = {}): max F_x {:.1} N, mean {:.1} N, {} saturated wheel-steps; NOT applied to the bridge (vertical modes only)",
            t.method, t.mu, t.max_longitudinal_force, t.mean_longitudinal_force, t.saturated_steps
        );
    }
}

/// `dyncontact run` for `kind = "vehicle_bridge"`.
pub fn run(text: &str, out: &Path, json: bool) -> Result<()> {
    let (scenario, every, snapshots) = parse(text)?;
    let traction = parse_traction(text)?;
    let radau = parse_radau5(text)?;
    let outcome = simulate_full(scenario, traction, radau, every, snapshots)?;
    write_outputs(out, &outcome)?;
    if json {
        println!("{}", serde_json::to_string_pretty(&outcome.summary)?);
    } else {
        print_summary(&outcome.summary);
        println!(
            "wrote {}/timeseries.csv, summary.json, contact_force.png, midspan.png, vehicle.png, pressure.png",
            out.display()
        );
    }
    Ok(())
}

/// `dyncontact bench coupling`: the default scenario (BEM contact, 32 × 32 grid) with Picard
/// and quasi-Newton coupling; wall time per step, simulated seconds per wall second, mean
/// coupling and contact-solver iterations per step.
pub fn bench(default_scenario: &str) -> Result<()> {
    println!(
        "default vehicle_bridge scenario, BEM contact 32 x 32 at every step; {} rayon threads",
        rayon::current_num_threads()
    );
    println!(
        "{:>13} {:>8} {:>11} {:>12} {:>13} {:>13} {:>16} {:>8}",
        "solver",
        "steps",
        "wall [s]",
        "µs/step",
        "sim s/wall s",
        "iter/step",
        "contact it/step",
        "failed"
    );
    for solver in ["picard", "quasi_newton"] {
        let (mut scenario, _, _) = parse(default_scenario)?;
        scenario.contact = match scenario.contact {
            ContactModel::Bem { tol, .. } => ContactModel::Bem { elements: 32, tol },
            _ => ContactModel::Bem {
                elements: 32,
                tol: 1e-8,
            },
        };
        scenario.coupling.solver = CouplingSolver::by_name(solver).expect("known name");
        match simulate(scenario, usize::MAX, 0) {
            Ok(o) => {
                let s = &o.summary;
                println!(
                    "{:>13} {:>8} {:>11.3} {:>12.1} {:>13.2} {:>13.2} {:>16.2} {:>8}",
                    solver,
                    s.solver.steps,
                    s.wall_time_s,
                    1e6 * s.wall_time_s / s.solver.steps.max(1) as f64,
                    s.simulated_time_s / s.wall_time_s,
                    s.solver.mean_iterations_per_step,
                    s.solver.mean_contact_iterations_per_step,
                    s.solver.failed_steps
                );
            }
            Err(e) => println!("{solver:>13} failed: {e:#}"),
        }
    }
    Ok(())
}
