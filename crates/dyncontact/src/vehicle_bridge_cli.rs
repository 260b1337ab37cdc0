//! `dyncontact run FILE` with `kind = "vehicle_bridge"`: wheels over a modal bridge with
//! local contact (docs/vehicle_bridge.md), and `dyncontact bench coupling`.
//!
//! Every key is in SI units; unknown keys are errors.

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use sim::config::vehicle_bridge::VehicleBridgeConfig;
use sim::vehicle_bridge::traction::{TractionSample, TractionSpec};
use sim::vehicle_bridge::{ContactModel, CouplingSolver, Radau5Spec, Scenario, Simulation};

use crate::output;
use crate::plot::{self, Panel, Series};

/// The vehicle-bridge default scenario (also the built-in default of `dyncontact run`).
pub const DEFAULT: &str = include_str!("../../../examples/vehicle_bridge_default.toml");

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

/// [`simulate`] with longitudinal friction (`traction`).
pub fn simulate_with(
    scenario: Scenario,
    traction: Option<TractionSpec>,
    every: usize,
    snapshots: usize,
) -> Result<Outcome> {
    simulate_full(scenario, traction, None, every, snapshots)
}

/// [`simulate_with`] with an optional Radau5 integration.
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
    let end = sim.end_time();
    let dt = sim.scenario().dt;
    let steps = (end / dt - 1e-9).ceil().max(0.0) as usize;
    let bar = ProgressBar::with_draw_target(Some(steps as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} steps, {elapsed} (eta {eta})")
            .map_err(|e| anyhow!("progress bar: {e}"))?,
    );
    let x0 = sim.scenario().wheels[0].position;
    let speed = sim.scenario().speed;
    let snap_positions: Vec<f64> = (0..snapshots)
        .map(|i| length * (i as f64 + 0.5) / snapshots as f64)
        .collect();
    let mut next_snap = 0;
    let mut rows = Vec::with_capacity(steps / every + 2);
    let mut snaps = Vec::new();
    let mut max_qs = None::<f64>;
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
    for step in 1..=steps {
        let before = sim.stats().iterations;
        sim.step()
            .with_context(|| format!("step {step} of {steps}"))?;
        let its = sim.stats().iterations - before;
        if let Some(qs) = sim.quasi_static_output_deflection()? {
            max_qs = Some(max_qs.unwrap_or(0.0).max(qs.abs()));
        }
        if step % every == 0 || step == steps {
            record(&sim, &mut rows, its);
        }
        let x = x0 + speed * sim.t();
        if next_snap < snap_positions.len() && x >= snap_positions[next_snap] {
            sim.centreline_pressure(0, &mut buf);
            snaps.push((x, buf.clone()));
            next_snap += 1;
        }
        if step % 64 == 0 {
            bar.set_position(step as u64);
        }
    }
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();
    let stats = sim.stats();
    let fold = |f: &dyn Fn(&Row) -> f64| rows.iter().map(f).fold(0.0f64, |m, v| m.max(v.abs()));
    let max_defl = fold(&|r| r.midspan.0);
    let max_acc = fold(&|r| r.midspan.2);
    let forces = rows
        .iter()
        .flat_map(|r| r.wheels.iter().map(|w| w.contact.force));
    let (min_f, max_f) = forces.fold((f64::INFINITY, 0.0f64), |(lo, hi), f| {
        (lo.min(f), hi.max(f))
    });
    let all = |f: &dyn Fn(&sim::vehicle_bridge::WheelSample) -> f64| {
        rows.iter()
            .flat_map(|r| r.wheels.iter().map(f))
            .fold(0.0f64, |m, v| m.max(v.abs()))
    };
    let summary = Summary {
        max_midspan_deflection: max_defl,
        max_midspan_acceleration: max_acc,
        max_quasi_static_deflection: max_qs,
        dynamic_amplification: max_qs.filter(|q| *q > 0.0).map(|q| max_defl / q),
        contact: ContactSummary {
            model: model.to_string(),
            max_force: max_f,
            min_force: min_f,
            loss_of_contact_events: sim.loss_of_contact_events(),
            max_pressure: all(&|w| w.contact.max_pressure),
        },
        vehicle: VehicleSummary {
            max_body_acceleration: all(&|w| w.body_acceleration),
            max_wheel_acceleration: all(&|w| w.wheel_acceleration),
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
        simulated_time_s: sim.t(),
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
pub fn run(config: VehicleBridgeConfig, out: &Path, json: bool) -> Result<()> {
    let VehicleBridgeConfig {
        scenario,
        traction,
        radau5,
        every,
        snapshots,
        warnings,
    } = config;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    let outcome = simulate_full(scenario, traction, radau5, every, snapshots)?;
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
        let mut scenario = sim::config::vehicle_bridge::parse(default_scenario)?.scenario;
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
