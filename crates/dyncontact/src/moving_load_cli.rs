//! `dyncontact run FILE` with `kind = "moving_load"`: a force or a train of axle forces crossing
//! the bridge at constant speed (modal superposition; Frýba's problem, references.md §D1.1).

use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

use anyhow::{Result, anyhow};
use beam::{MovingLoads, StepProgress, simulate_moving_loads_observed};
use sim::config::moving_load::MovingLoadConfig;
use sim::moving_load_summary::{self, MovingLoadSummary};

use crate::errors::bad_input;
use crate::interrupt::{self, Interrupted};
use crate::output::{self, RunOutput};
use crate::plot;

/// The files a moving-load run writes (one run's output set).
const OUTPUT_SET: &[&str] = &["timeseries.csv", "summary.json", "midspan_deflection.png"];

/// Run a validated moving-load scenario; writes outputs into `out`. Ctrl-C stops the run at
/// its next step; what is complete is written with `"completed": false`.
pub fn run(config: MovingLoadConfig, out: &Path, json: bool) -> Result<()> {
    let MovingLoadConfig {
        bridge,
        loads,
        integrator_name: name,
        settings,
        points,
    } = config;
    let dt = settings.dt;
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    let start = Instant::now();
    interrupt::stop_at_next_step();
    let mut stop_on_interrupt = |_: StepProgress| {
        if interrupt::requested() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let response = simulate_moving_loads_observed(
        bridge.basis.as_ref(),
        &bridge.damping,
        &loads,
        &settings,
        &points,
        &mut stop_on_interrupt,
    )
    .map_err(|e| {
        // Parameters, counts and positions the solver rejects are the input's fault (exit 2).
        let input = matches!(
            e,
            beam::BeamError::InvalidParameter { .. }
                | beam::BeamError::InvalidCount { .. }
                | beam::BeamError::OutsideSpan { .. }
        );
        let e = anyhow!("moving-load run: {e}");
        if input { bad_input(e) } else { e }
    })?;
    let wall = start.elapsed().as_secs_f64();
    let summary = moving_load_summary::summarise(&bridge, &loads, &response, &name, dt, wall)
        .map_err(|e| anyhow!("{e}"))?;
    write_timeseries(&run_out, &loads, &response)?;
    plot_outputs(&run_out, &loads, &response, &summary)?;
    output::write_summary(&run_out.path("summary.json"), &summary)?;
    if !summary.completed {
        run_out.mark_partial("timeseries.csv")?;
    }
    run_out.commit()?;
    if json {
        println!("{}", output::json_text(&summary)?);
    } else {
        print_summary(&summary);
        println!(
            "wrote {}/{}, summary.json, midspan_deflection.png",
            out.display(),
            if summary.completed {
                "timeseries.csv"
            } else {
                "timeseries.partial.csv"
            }
        );
    }
    if !summary.completed {
        return Err(Interrupted {
            time_reached: summary.time_reached,
        }
        .into());
    }
    Ok(())
}

fn print_summary(s: &MovingLoadSummary) {
    println!("moving load over {}", s.bridge);
    println!(
        "  {} axle(s) at {} m/s, integrator {} (dt = {:e} s), {} modes",
        s.axles, s.speed, s.integrator, s.dt, s.modes_used
    );
    println!(
        "  max midspan deflection     {:>12.6e} m",
        s.max_midspan_deflection
    );
    println!(
        "  static midspan deflection  {:>12.6e} m (quasi-static modal maximum)",
        s.static_midspan_deflection
    );
    if let Some(c) = s.static_midspan_deflection_closed_form {
        println!("  F L^3/(48 EI)              {c:>12.6e} m");
    }
    match s.dynamic_amplification {
        Some(d) => println!("  dynamic amplification      {d:>12.6}"),
        None => {
            println!("  dynamic amplification      n/a (the midspan does not deflect: a support?)")
        }
    }
    println!(
        "  max midspan acceleration   {:>12.6e} m/s^2",
        s.max_midspan_acceleration
    );
    println!(
        "  max midspan moment         {:>12.6e} N m",
        s.max_midspan_moment
    );
    println!(
        "  free vibration (after {:.3} s): max midspan deflection {:.6e} m",
        s.exit_time, s.max_free_vibration_deflection
    );
    println!(
        "  simulated {:.3} s in {:.3} s wall time",
        s.simulated_time_s, s.wall_time_s
    );
}

fn write_timeseries(
    dir: &RunOutput,
    loads: &MovingLoads,
    r: &beam::MovingLoadResponse,
) -> Result<()> {
    let header = moving_load_summary::columns(r);
    let names: Vec<&str> = header.iter().map(String::as_str).collect();
    output::write_csv(
        &dir.path("timeseries.csv"),
        &names,
        (0..r.times.len()).map(|i| {
            let mut row = Vec::new();
            moving_load_summary::row(loads, r, i, &mut row);
            row
        }),
    )
}

fn plot_outputs(
    dir: &RunOutput,
    loads: &MovingLoads,
    r: &beam::MovingLoadResponse,
    s: &MovingLoadSummary,
) -> Result<()> {
    let np = r.n_points();
    let mm = |v: f64| 1e3 * v;
    let dynamic: Vec<(f64, f64)> = r
        .times
        .iter()
        .enumerate()
        .map(|(i, &t)| (loads.speed() * t, mm(r.deflection[i * np])))
        .collect();
    let quasi: Vec<(f64, f64)> = r
        .times
        .iter()
        .enumerate()
        .map(|(i, &t)| (loads.speed() * t, mm(r.quasi_static_deflection[i * np])))
        .collect();
    plot::panels(
        &dir.path("midspan_deflection.png"),
        &[plot::Panel {
            title: format!(
                "deflection at mid-length, x = {} m, v = {} m/s, DAF = {}",
                r.points[0],
                s.speed,
                s.dynamic_amplification
                    .map_or("n/a".into(), |d| format!("{d:.4}"))
            ),
            x_label: "position of the first axle [m]".into(),
            y_label: "deflection [mm]".into(),
            series: vec![
                plot::Series::new("dynamic", dynamic),
                plot::Series::new("quasi-static", quasi),
            ],
        }],
    )
}
