//! `dyncontact run FILE` with `kind = "moving_load"`: a force or a train of axle forces crossing
//! the bridge at constant speed (modal superposition; Frýba's problem, references.md §D1.1).

use std::path::Path;
use std::time::Instant;

use anyhow::{Result, anyhow, bail};
use beam::{Axle, ModalIntegrator, MovingLoadSettings, MovingLoads, simulate_moving_loads};
use integrate::structural::StructuralMethod;
use serde::{Deserialize, Serialize};

use crate::bridge::{Bridge, BridgeSpec};
use crate::errors::bad_input;
use crate::output::{self, RunOutput};
use crate::plot;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MovingLoadScenario {
    kind: String,
    bridge: BridgeSpec,
    load: LoadSpec,
    integrator: Option<IntegratorSpec>,
    output: Option<OutputSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoadSpec {
    /// One force \[N\] ...
    force: Option<f64>,
    /// ... or axles [[offset behind the first axle (m), force (N)], ...].
    axles: Option<Vec<[f64; 2]>>,
    /// Speed [m/s].
    speed: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct IntegratorSpec {
    /// "exact" (default: exact modal step for piecewise-linear forcing) or a structural method:
    /// newmark, hht, generalized_alpha, backward_euler, verlet, leapfrog, central_difference, ...
    method: Option<String>,
    /// Time step \[s\] (default 1e-4).
    dt: Option<f64>,
    beta: Option<f64>,
    gamma: Option<f64>,
    alpha: Option<f64>,
    rho_inf: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct OutputSpec {
    /// Extra response points \[m\] (midspan is always the first).
    points: Option<Vec<f64>>,
    /// Free vibration simulated after the last axle leaves \[s\] (default: 3 periods of mode 1, at most 5 s).
    free_vibration: Option<f64>,
    /// Record every n-th step (default: about 20 000 samples in all).
    every: Option<usize>,
}

#[derive(Debug, Serialize)]
pub struct MovingLoadSummary {
    pub bridge: String,
    pub speed: f64,
    pub axles: usize,
    pub integrator: String,
    pub dt: f64,
    pub modes_used: usize,
    pub max_midspan_deflection: f64,
    pub static_midspan_deflection: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub static_midspan_deflection_closed_form: Option<f64>,
    /// max |w| / max |w_static| at midspan; null when the midspan does not move (a support).
    pub dynamic_amplification: Option<f64>,
    pub max_midspan_acceleration: f64,
    pub max_midspan_moment: f64,
    pub max_free_vibration_deflection: f64,
    pub exit_time: f64,
    pub simulated_time_s: f64,
    pub wall_time_s: f64,
}

fn integrator(spec: Option<&IntegratorSpec>) -> Result<(ModalIntegrator, String, f64)> {
    let dt = spec.and_then(|s| s.dt).unwrap_or(1e-4);
    if !dt.is_finite() || dt <= 0.0 {
        bail!("[integrator] `dt` = {dt}: must be a positive number of seconds");
    }
    let name = spec
        .and_then(|s| s.method.clone())
        .unwrap_or_else(|| "exact".into());
    let mut params = Vec::new();
    if let Some(s) = spec {
        for (key, value) in [
            ("beta", s.beta),
            ("gamma", s.gamma),
            ("alpha", s.alpha),
            ("rho_inf", s.rho_inf),
        ] {
            if let Some(v) = value {
                params.push((key, v));
            }
        }
    }
    if name == "exact" {
        if let Some((key, _)) = params.first() {
            bail!("[integrator] `{key}` does not apply to method = \"exact\"");
        }
        return Ok((ModalIntegrator::ExactPiecewiseLinear, name, dt));
    }
    let method =
        StructuralMethod::by_name(&name, &params).map_err(|e| anyhow!("[integrator] {e}"))?;
    Ok((ModalIntegrator::Structural(method), name, dt))
}

fn loads(spec: &LoadSpec) -> Result<MovingLoads> {
    let axles = match (spec.force, &spec.axles) {
        (Some(f), None) => vec![Axle {
            offset: 0.0,
            force: f,
        }],
        (None, Some(list)) => list
            .iter()
            .map(|[offset, force]| Axle {
                offset: *offset,
                force: *force,
            })
            .collect(),
        (Some(_), Some(_)) => bail!("[load]: give either `force` or `axles`, not both"),
        (None, None) => bail!("[load]: missing `force` [N] (or `axles`)"),
    };
    MovingLoads::train(axles, spec.speed).map_err(|e| anyhow!("[load] {e}"))
}

/// A parsed and validated moving-load scenario.
struct Prepared {
    bridge: Bridge,
    loads: MovingLoads,
    name: String,
    dt: f64,
    settings: MovingLoadSettings,
    points: Vec<f64>,
}

fn prepare(text: &str) -> Result<Prepared> {
    let scenario: MovingLoadScenario =
        toml::from_str(text).map_err(|e| anyhow!("invalid scenario file: {e}"))?;
    if scenario.kind != "moving_load" {
        bail!(
            "`kind` = \"{}\" is not a moving-load scenario",
            scenario.kind
        );
    }
    let bridge = scenario.bridge.build()?;
    let loads = loads(&scenario.load)?;
    let (modal_integrator, name, dt) = integrator(scenario.integrator.as_ref())?;
    let length = bridge.basis.length();
    let omega1 = bridge
        .basis
        .circular_frequencies()
        .iter()
        .copied()
        .find(|w| *w > 0.0)
        .unwrap_or(1.0);
    let output_spec = scenario.output.as_ref();
    let free = output_spec
        .and_then(|o| o.free_vibration)
        .unwrap_or((3.0 * 2.0 * std::f64::consts::PI / omega1).min(5.0));
    let mut points = vec![0.5 * length];
    if let Some(extra) = output_spec.and_then(|o| o.points.clone()) {
        if let Some(x) = extra
            .iter()
            .find(|x| !(x.is_finite() && (0.0..=length).contains(*x)))
        {
            bail!("[output] `points` contains {x}: points must lie on the span [0, {length}]");
        }
        points.extend(extra);
    }
    let total_steps = ((loads.exit_time(length) + free) / dt).ceil().max(1.0);
    let every = match output_spec.and_then(|o| o.every) {
        Some(0) => bail!("[output] `every` = 0: must be at least 1"),
        Some(e) => e,
        None => ((total_steps / 20_000.0).ceil() as usize).max(1),
    };
    let settings = MovingLoadSettings {
        dt,
        free_vibration_time: free,
        output_every: every,
        integrator: modal_integrator,
    };
    Ok(Prepared {
        bridge,
        loads,
        name,
        dt,
        settings,
        points,
    })
}

/// The files a moving-load run writes (one run's output set).
const OUTPUT_SET: &[&str] = &["timeseries.csv", "summary.json", "midspan_deflection.png"];

/// Run a moving-load scenario from its text; writes outputs into `out`.
pub fn run(text: &str, out: &Path, json: bool) -> Result<()> {
    let Prepared {
        bridge,
        loads,
        name,
        dt,
        settings,
        points,
    } = prepare(text).map_err(bad_input)?;
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    let start = Instant::now();
    let response = simulate_moving_loads(
        bridge.basis.as_ref(),
        &bridge.damping,
        &loads,
        &settings,
        &points,
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
    let summary = summarise(&bridge, &loads, &response, &name, dt, wall)?;
    write_timeseries(&run_out, &loads, &response)?;
    plot_outputs(&run_out, &loads, &response, &summary)?;
    output::write_json(&run_out.path("summary.json"), &summary)?;
    run_out.commit()?;
    if json {
        println!("{}", output::json_text(&summary)?);
    } else {
        print_summary(&summary);
        println!(
            "wrote {}/timeseries.csv, summary.json, midspan_deflection.png",
            out.display()
        );
    }
    Ok(())
}

fn summarise(
    bridge: &Bridge,
    loads: &MovingLoads,
    r: &beam::MovingLoadResponse,
    integrator: &str,
    dt: f64,
    wall: f64,
) -> Result<MovingLoadSummary> {
    let e = |err: beam::BeamError| anyhow!("{err}");
    let single = loads.axles().len() == 1;
    let closed_form = match (bridge.support, single) {
        (Some(beam::Support::SimplySupported), true) => {
            Some(beam::closed_form::ss_midspan_static_deflection(
                loads.axles()[0].force.abs(),
                bridge.reference.length,
                bridge.reference.bending_stiffness,
            ))
        }
        _ => None,
    };
    let end = r.times.last().copied().unwrap_or(0.0);
    Ok(MovingLoadSummary {
        bridge: bridge.description.clone(),
        speed: loads.speed(),
        axles: loads.axles().len(),
        integrator: integrator.to_string(),
        dt,
        modes_used: bridge.basis.n_modes(),
        max_midspan_deflection: r.max_abs_deflection(0).map_err(e)?,
        static_midspan_deflection: r.max_abs_quasi_static(0).map_err(e)?,
        static_midspan_deflection_closed_form: closed_form,
        dynamic_amplification: Some(r.dynamic_amplification(0).map_err(e)?)
            .filter(|d| d.is_finite()),
        max_midspan_acceleration: r.max_abs_acceleration(0).map_err(e)?,
        max_midspan_moment: r.max_abs_bending_moment(0).map_err(e)?,
        max_free_vibration_deflection: r
            .max_abs_deflection_between(0, r.exit_time, end)
            .map_err(e)?,
        exit_time: r.exit_time,
        simulated_time_s: end,
        wall_time_s: wall,
    })
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
    let np = r.n_points();
    let mut header = vec!["t".to_string(), "load_position".to_string()];
    for (p, x) in r.points.iter().enumerate() {
        let tag = if p == 0 {
            "midspan".to_string()
        } else {
            format!("x{x}")
        };
        for q in ["deflection", "velocity", "acceleration", "moment"] {
            header.push(format!("{q}_{tag}"));
        }
    }
    let names: Vec<&str> = header.iter().map(String::as_str).collect();
    output::write_csv(
        &dir.path("timeseries.csv"),
        &names,
        r.times.iter().enumerate().map(|(i, &t)| {
            let mut row = vec![t, loads.speed() * t];
            for p in 0..np {
                let k = i * np + p;
                row.extend([
                    r.deflection[k],
                    r.velocity[k],
                    r.acceleration[k],
                    r.bending_moment[k],
                ]);
            }
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
                "midspan deflection, v = {} m/s, DAF = {}",
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
