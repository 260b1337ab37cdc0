//! `dyncontact run FILE` with `kind = "vehicle_bridge"`: wheels over a modal bridge with
//! local contact (docs/vehicle_bridge.md); its bench is `bench_coupling`.
//!
//! Every key is in SI units; unknown keys are errors.

use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

use anyhow::{Result, anyhow};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use sim::config::vehicle_bridge::VehicleBridgeConfig;
use sim::vehicle_bridge::track::TrackSpec;
use sim::vehicle_bridge::{ContactModel, Scenario, Simulation, SimulationParts, run};

use crate::errors::{BadInput, bad_input};
use crate::interrupt::{self, Interrupted};
use crate::output::{self, RunOutput};
use crate::vehicle_bridge_output::{self, OUTPUT_SET, Recorder, Row};

/// The vehicle-bridge default scenario (also the built-in default of `dyncontact run`).
pub const DEFAULT: &str = include_str!("../../../examples/vehicle_bridge_default.toml");

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

/// The `track` object of summary.json (docs/track.md): maxima over the run.
#[derive(Serialize)]
pub struct TrackSummaryJson {
    pub model: String,
    /// The rail's beam theory: `euler_bernoulli` or `timoshenko`.
    pub rail_beam: &'static str,
    /// Track DOFs (rail and support masses; the bridge modes and vehicles not counted).
    pub track_dofs: usize,
    /// Largest rail displacement under a wheel \[m\].
    pub max_rail_displacement: f64,
    /// Largest pad force over all sleepers \[N\].
    pub max_pad_force: f64,
    /// Largest force under a sleeper (ballast; slab: mortar) \[N\].
    pub max_ballast_force: f64,
    /// Largest |rail − bridge| displacement at the output point \[m\].
    pub max_rail_bridge_relative_displacement: f64,
}

#[derive(Serialize)]
pub struct ContactSummary {
    pub model: String,
    pub max_force: f64,
    pub min_force: f64,
    pub loss_of_contact_events: usize,
    /// Largest contact pressure \[Pa\]; `null` for rigid contact (a constraint has no pressure).
    pub max_pressure: Option<f64>,
    /// max over wheels and time of (W_k − F_k)/W_k (1 = a wheel fully unloaded).
    pub max_unloading_ratio: f64,
    /// BEM contact only: full NormCG solves over all wheels (the static start included).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub full_solves: Option<usize>,
    /// BEM contact only: exact solves by active-set updates of the dense factor of the last
    /// contact set instead of NormCG (`[contact] reuse_tol` > 0; references.md §C8.4).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factor_solves: Option<usize>,
    /// BEM contact only: evaluations answered without a solve (`[contact] reuse_tol`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reused_evaluations: Option<usize>,
    /// BEM contact only: the largest estimated force error of a reused evaluation, relative
    /// to the force of the full solve it was reused from (0 without reuse).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_reuse_error_estimate: Option<f64>,
    /// BEM contact with reuse only: evaluations answered by the shared response table F(δ)
    /// (wheels on a flat, rigid, smooth track; issue #14), not counted in
    /// `reused_evaluations`; their estimates are in `max_reuse_error_estimate`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub table_evaluations: Option<usize>,
    /// BEM contact with reuse only: exact solves the response tables were built from (once
    /// per table, shared by identical wheels), not counted in `full_solves`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub table_solves: Option<usize>,
}

pub use sim::train_response::{ComfortSummary, TrainSummary, VehicleMax as BogieVehicleMax};

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

/// The largest bridge response at a response point.
#[derive(Serialize)]
pub struct PointJson {
    /// Position on the bridge \[m\].
    pub x: f64,
    /// max |w| \[m\].
    pub max_deflection: f64,
    /// max |ẅ| \[m/s²\].
    pub max_acceleration: f64,
}

#[derive(Serialize)]
pub struct Summary {
    /// False when the run stopped early (interrupted, or a step failed): the outputs then hold
    /// the steps up to `time_reached` and timeseries.csv is named timeseries.partial.csv.
    pub completed: bool,
    /// Simulated time reached \[s\] (the end time when `completed`).
    pub time_reached: f64,
    /// Why the run stopped early (absent when `completed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_by: Option<String>,
    pub max_midspan_deflection: f64,
    pub max_midspan_acceleration: f64,
    /// Per response point of `[output] points` (absent without them).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<PointJson>,
    pub max_quasi_static_deflection: Option<f64>,
    pub dynamic_amplification: Option<f64>,
    pub contact: ContactSummary,
    pub vehicle: VehicleSummary,
    /// Per bogie vehicle (absent without bogie vehicles).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vehicles: Option<Vec<BogieVehicleMax>>,
    /// The train (absent without `[train]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub train: Option<TrainSummary>,
    /// Passenger comfort (trains only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub comfort: Option<ComfortSummary>,
    pub solver: SolverSummary,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub traction: Option<TractionSummaryJson>,
    /// The track's largest responses (absent without `[track]`; docs/track.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub track: Option<TrackSummaryJson>,
    pub wall_time_s: f64,
    pub simulated_time_s: f64,
}

/// The result of a run.
pub struct Outcome {
    pub summary: Summary,
    /// The recorded rows, thinned to at most [`vehicle_bridge_output::PLOT_ROWS`] (for plots).
    rows: Vec<Row>,
    snapshots: Vec<(f64, Vec<(f64, f64)>)>,
    /// The output point's position and the bridge's length \[m\] (for the plots).
    output_point: f64,
    bridge_length: f64,
    /// The response points \[m\] (for the plots).
    points: Vec<f64>,
    /// The train on the bridge at a few instants (trains only).
    train_pictures: Vec<vehicle_bridge_output::TrainPicture>,
    /// The error of the step that failed, when one did (the outputs up to it are written).
    failure: Option<anyhow::Error>,
}

/// Most steps a run may take (checked before the run starts).
const MAX_STEPS: f64 = 1e9;

/// Runs a scenario, recording every `every`-th step and `snapshots` pressure snapshots of the
/// first wheel along its passage over the span (no CSV: as `bench` uses it).
pub fn simulate(scenario: Scenario, every: usize, snapshots: usize) -> Result<Outcome> {
    simulate_full(
        scenario,
        SimulationParts::default(),
        None,
        every,
        snapshots,
        None,
    )
}

/// [`simulate`] with longitudinal friction (`traction`) and the recorded rows streamed to
/// `csv`. Stops
/// early, with `completed = false`, on an interrupt (Ctrl-C) or a failed step.
#[allow(clippy::too_many_arguments)]
pub fn simulate_full(
    scenario: Scenario,
    parts: SimulationParts,
    train: Option<sim::train::Train>,
    every: usize,
    snapshots: usize,
    csv: Option<&Path>,
) -> Result<Outcome> {
    let length = scenario.bridge.length();
    let model = match scenario.contact {
        ContactModel::Rigid => "rigid",
        ContactModel::Hertz => "hertz",
        ContactModel::Bem { .. } => "bem",
        ContactModel::BemProfiles(_) => "bem_profiles",
    };
    let integrator = scenario.integrator.name().to_string();
    let start = Instant::now();
    // Each vehicle's wheels (bogie vehicles: four; every other wheel its own vehicle), for the
    // train pictures.
    let groups: Vec<std::ops::Range<usize>> = if train.is_some() {
        let mut groups = Vec::new();
        let mut k = 0;
        while k < scenario.wheels.len() {
            let n = parts
                .vehicles
                .iter()
                .find(|v| v.first_wheel == k)
                .map_or(1, |v| v.vehicle.wheelsets());
            groups.push(k..k + n);
            k += n;
        }
        groups
    } else {
        Vec::new()
    };
    let track_model = parts.track.as_ref().map(track_model_name);
    let mut sim = Simulation::with_parts(scenario, parts).map_err(|e| bad_input(e.into()))?;
    let steps = sim.planned_steps();
    let (end, dt) = (sim.end_time(), sim.scenario().dt);
    if steps as f64 > MAX_STEPS {
        return Err(BadInput::error(format!(
            "[integrator] dt = {dt:e} s over the run of {end} s gives {steps:.3e} steps: at most {MAX_STEPS:e} are allowed (raise dt or shorten the run)"
        )));
    }
    let bar = ProgressBar::with_draw_target(Some(steps as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} steps, {elapsed} (eta {eta})")
            .map_err(|e| anyhow!("progress bar: {e}"))?,
    );
    let snap_positions: Vec<f64> = (0..snapshots)
        .map(|i| length * (i as f64 + 0.5) / snapshots as f64)
        .collect();
    let mut next_snap = 0;
    let mut snaps = Vec::new();
    let mut recorder = Recorder::new(&sim, csv)?;
    recorder.record(&sim, 0)?;
    let mut buf = Vec::new();
    let mut write_error = None;
    let mut monitor = sim::train_response::TrainMonitor::new(&sim);
    // Pictures when the leading wheel passes 1/4, 1/2, 3/4 of the span and the span's end.
    let picture_at: Vec<f64> = if groups.is_empty() {
        Vec::new()
    } else {
        vec![0.25 * length, 0.5 * length, 0.75 * length, length]
    };
    let mut pictures = Vec::new();
    interrupt::stop_at_next_step();
    // The run driver steps the simulation and computes the summary (maxima, amplification);
    // this observer streams the time series, takes the pressure snapshots and stops the run
    // on Ctrl-C.
    let mut observer = |sim: &Simulation, info: run::StepInfo| {
        if (info.step.is_multiple_of(every) || info.step == info.steps)
            && let Err(e) = recorder.record(sim, info.iterations)
        {
            write_error = Some(e);
            return ControlFlow::Break(());
        }
        monitor.observe(sim);
        if pictures.len() < picture_at.len() && sim.wheel_position(0) >= picture_at[pictures.len()]
        {
            pictures.push(vehicle_bridge_output::TrainPicture::of(sim, &groups));
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
        if interrupt::requested() {
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    };
    let (run, failure) = match run::run(&mut sim, &mut observer) {
        Ok(run) => (run, None),
        Err(f) => {
            let step = f.partial.steps_taken + 1;
            let e = anyhow::Error::new(f.error).context(format!("step {step} of {steps}"));
            (*f.partial, Some(e))
        }
    };
    if let Some(e) = write_error {
        return Err(e);
    }
    // A run stopped early ends its time series at the last completed step.
    if !run.completed && recorder.last_t != Some(sim.t()) {
        recorder.record(&sim, 0)?;
    }
    let stopped_by = match &failure {
        Some(e) => Some(crate::errors::error_text(e)),
        None if !run.completed => Some("interrupt (SIGINT or SIGTERM)".to_string()),
        None => None,
    };
    bar.finish_and_clear();
    for warning in &run.accuracy.warnings {
        eprintln!("warning: {warning}");
    }
    let wall = start.elapsed().as_secs_f64();
    let stats = run.solver;
    let solves = sim.contact_solves();
    let rows = recorder.finish()?;
    let summary = Summary {
        completed: run.completed,
        time_reached: run.time_reached,
        stopped_by,
        max_midspan_deflection: run.deflection.max_abs(),
        max_midspan_acceleration: run.acceleration.max_abs(),
        points: run
            .points
            .iter()
            .map(|p| PointJson {
                x: p.x,
                max_deflection: p.deflection.max_abs(),
                max_acceleration: p.acceleration.max_abs(),
            })
            .collect(),
        max_quasi_static_deflection: run.max_quasi_static_deflection,
        dynamic_amplification: run.dynamic_amplification,
        contact: ContactSummary {
            model: model.to_string(),
            max_force: run.max_force(),
            min_force: run.min_force(),
            loss_of_contact_events: run.loss_of_contact_events,
            max_pressure: (model != "rigid").then_some(run.max_pressure()),
            max_unloading_ratio: monitor.max_unloading_ratio(),
            full_solves: solves.map(|s| s.full_solves),
            factor_solves: solves.map(|s| s.factor_solves),
            reused_evaluations: solves.map(|s| s.reused),
            max_reuse_error_estimate: solves.map(|s| s.max_estimate),
            table_evaluations: solves.map(|s| s.table_answers),
            table_solves: solves.map(|s| s.table_solves),
        },
        vehicles: monitor.vehicles(),
        comfort: train
            .as_ref()
            .map(|_| ComfortSummary::of(run.max_body_acceleration())),
        train: train.as_ref().map(TrainSummary::of),
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
        track: track_model.and_then(|model| {
            let m = sim.track_maxima()?;
            Some(TrackSummaryJson {
                model,
                rail_beam: sim.track_model()?.rail().beam().name(),
                track_dofs: sim.track_model()?.n_track_dofs(),
                max_rail_displacement: m.rail_displacement,
                max_pad_force: m.pad_force,
                max_ballast_force: m.ballast_force,
                max_rail_bridge_relative_displacement: m.rail_bridge_relative,
            })
        }),
        wall_time_s: wall,
        simulated_time_s: run.time_reached,
    };
    Ok(Outcome {
        summary,
        rows,
        snapshots: snaps,
        output_point: sim.scenario().output_point,
        bridge_length: length,
        points: sim.output_points().to_vec(),
        train_pictures: pictures,
        failure,
    })
}

use crate::output::plural;

/// The track's model name for the summary.
fn track_model_name(spec: &TrackSpec) -> String {
    spec.model.clone()
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
    for p in &s.points {
        println!(
            "  at x = {} m: deflection max {:.4e} m, acceleration max {:.4} m/s²",
            p.x, p.max_deflection, p.max_acceleration
        );
    }
    if let Some(d) = s.dynamic_amplification {
        println!("  dynamic amplification {d:.4}");
    }
    println!(
        "  contact ({}): force {:.1} … {:.1} N, {}{}",
        s.contact.model,
        s.contact.min_force,
        s.contact.max_force,
        plural(s.contact.loss_of_contact_events, "loss-of-contact event"),
        s.contact
            .max_pressure
            .filter(|p| *p > 0.0)
            .map(|p| format!(", max pressure {:.1} MPa", 1e-6 * p))
            .unwrap_or_default()
    );
    println!(
        "  vehicle: max body acceleration {:.4} m/s²",
        s.vehicle.max_body_acceleration
    );
    // Radau5 counts the steps its error control rejected; the structural methods count step
    // attempts whose coupling failed (each retried with half the step).
    let failed = if s.solver.method == "radau5_newton" {
        plural(s.solver.failed_steps, "rejected step")
    } else {
        plural(s.solver.failed_steps, "failed step attempt")
    };
    println!(
        "  solver {} / {}: {}, {:.2} iterations/step (max {}){}, {failed}",
        s.solver.method,
        s.solver.integrator,
        plural(s.solver.steps, "step"),
        s.solver.mean_iterations_per_step,
        s.solver.max_iterations_per_step,
        if s.contact.model.starts_with("bem") {
            format!(
                ", {:.2} contact-solver iterations/step",
                s.solver.mean_contact_iterations_per_step
            )
        } else {
            String::new()
        }
    );
    if let Some(t) = &s.track {
        println!(
            "  track ({}, {} rail, {} DOFs): max rail displacement under a wheel {:.4e} m, max pad force {:.1} N, max ballast force {:.1} N, max |rail − bridge| at the output point {:.4e} m",
            t.model,
            t.rail_beam,
            t.track_dofs,
            t.max_rail_displacement,
            t.max_pad_force,
            t.max_ballast_force,
            t.max_rail_bridge_relative_displacement
        );
    }
    if let Some(t) = &s.traction {
        println!(
            "  traction ({}, mu = {}): max F_x {:.1} N, mean {:.1} N, {} saturated wheel-steps; NOT applied to the bridge (vertical modes only)",
            t.method, t.mu, t.max_longitudinal_force, t.mean_longitudinal_force, t.saturated_steps
        );
    }
}

/// `dyncontact run` for `kind = "vehicle_bridge"`.
pub fn run(mut config: VehicleBridgeConfig, out: &Path, json: bool) -> Result<()> {
    let parts = config.take_parts();
    let VehicleBridgeConfig {
        scenario,
        train,
        every,
        every_is_default,
        snapshots,
        warnings,
        ..
    } = config;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    if every_is_default && every > 1 && !json {
        println!(
            "timeseries.csv records one step in {every} (Δt = {:e} s): the default keeps the series within {:e} values; [output] every = 1 records every step (summary.json's extrema are over every step)",
            scenario.dt,
            sim::config::vehicle_bridge::DEFAULT_SERIES_VALUES
        );
    }
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    let outcome = simulate_full(
        scenario,
        parts,
        train,
        every,
        snapshots,
        Some(&run_out.path("timeseries.csv")),
    )?;
    output::write_summary(&run_out.path("summary.json"), &outcome.summary)?;
    vehicle_bridge_output::write_plots(
        &run_out,
        &outcome.rows,
        &outcome.snapshots,
        &vehicle_bridge_output::PlotContext {
            output_point: outcome.output_point,
            bridge_length: outcome.bridge_length,
            points: &outcome.points,
            static_loads: &outcome.summary.vehicle.static_wheel_loads,
            contact_model: &outcome.summary.contact.model,
        },
    )?;
    if !outcome.train_pictures.is_empty() {
        vehicle_bridge_output::write_train_pictures(&run_out, &outcome.train_pictures)?;
    }
    let completed = outcome.summary.completed;
    if !completed {
        run_out.mark_partial("timeseries.csv")?;
    }
    run_out.commit()?;
    if json {
        println!("{}", output::json_text(&outcome.summary)?);
    } else {
        print_summary(&outcome.summary);
        // The files this run wrote (pressure.png only with contact pressure, traction.png
        // only with traction, train.png only for trains).
        let written: Vec<String> = OUTPUT_SET
            .iter()
            .map(|name| {
                if !completed && *name == "timeseries.csv" {
                    output::partial_name(name)
                } else {
                    name.to_string()
                }
            })
            .filter(|name| out.join(name).exists())
            .collect();
        println!("wrote {}/{}", out.display(), written.join(", "));
    }
    if let Some(e) = outcome.failure {
        return Err(e.context("the outputs up to the failed step are written (completed = false)"));
    }
    if !completed {
        return Err(Interrupted {
            time_reached: outcome.summary.time_reached,
        }
        .into());
    }
    Ok(())
}
