//! Bridges: `modes_text` (the modal table and mode shapes, `sim::modes`, as `dyncontact
//! modes`) and `run_text` (a vehicle–bridge run with its time series, as `dyncontact run`).

use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};

use crate::SolverError;
use crate::guard::{interruptible, released};

/// Samples of the mode shapes along the span (as `dyncontact modes --out`).
const SHAPE_SAMPLES: usize = 401;

/// `modes_text(text) -> dict`: the modal table of a file's `[bridge]` section (`summary_json`,
/// the CLI's `modes.json`), and the mass-normalised mode shapes \[1/√kg\] at 401 points: `x`
/// (shape (401,)) and `shapes` (shape (401, modes)).
#[pyfunction]
pub fn modes_text<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyDict>> {
    let text = text.to_string();
    let (summary, rows) = released(py, move || {
        let bridge = sim::config::bridge::parse_bridge_file(&text)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let summary = sim::modes::summary(&bridge);
        let rows = sim::modes::shapes(&bridge, SHAPE_SAMPLES)
            .map_err(|e| SolverError::new_err(e.to_string()))?;
        Ok::<_, PyErr>((summary, rows))
    })??;
    let json =
        serde_json::to_string(&summary).map_err(|e| SolverError::new_err(format!("modes: {e}")))?;
    let n = summary.modes.len();
    let d = PyDict::new(py);
    d.set_item("summary_json", PyString::new(py, &json))?;
    let x: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let shapes: Vec<f64> = rows.iter().flat_map(|r| r[1..].iter().copied()).collect();
    d.set_item("x", PyArray1::from_vec(py, x))?;
    d.set_item(
        "shapes",
        PyArray1::from_vec(py, shapes).reshape([rows.len(), n])?,
    )?;
    Ok(d)
}

/// Values of the time series a run may hold in memory (8 bytes each: 400 MB).
const MAX_SERIES_VALUES: usize = 50_000_000;

/// `run_text(text, base) -> dict`: a scenario file's text. `kind = "vehicle_bridge"` runs (as
/// `dyncontact run`, the library's run driver `sim::vehicle_bridge::run`) with the GIL
/// released and Ctrl-C polled every 50 ms, and returns `summary` (a dict of the run's key
/// numbers, named as in the CLI's `summary.json`), `columns` (the names of `timeseries.csv`)
/// and `series` (float64, one row per recorded step). Other kinds return only `kind` (the
/// wrapper dispatches `contact` and `sweep`; `ball_drop` and `moving_load` are refused).
/// What a run from Python produced (everything `Send`: the simulation itself is built and run
/// on the worker thread).
enum RunOutcome {
    /// Not a vehicle–bridge scenario: its kind.
    Kind(&'static str),
    /// Bad input (the message names the key).
    Invalid(String),
    /// A step failed.
    Failed(String),
    /// Stopped by Ctrl-C at this time \[s\].
    Interrupted(f64),
    /// A completed run.
    Done(Box<RunData>),
    /// A completed ball-drop or moving-load run: its kind, its summary (the CLI's summary.json
    /// as JSON text) and its time series (the columns of the CLI's timeseries.csv).
    Table {
        kind: &'static str,
        summary: String,
        columns: Vec<String>,
        series: Vec<f64>,
    },
}

/// A ball-drop run (on the worker thread), as `dyncontact run`: the summary of
/// `sim::ball_drop_summary` and the time series of every sample.
fn run_ball_drop(
    config: sim::config::ball_drop::BallDropConfig,
    stop: &std::sync::atomic::AtomicBool,
) -> RunOutcome {
    use std::ops::ControlFlow;
    use std::sync::atomic::Ordering;
    let mut observer = |_: sim::ball_drop::Progress| {
        if stop.load(Ordering::Relaxed) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let result = match config.scenario.simulate_observed(true, &mut observer) {
        Ok(r) => r,
        Err(
            e @ (sim::ball_drop::BallDropError::InvalidParameter { .. }
            | sim::ball_drop::BallDropError::Material { .. }),
        ) => return RunOutcome::Invalid(format!("ball drop: {e}")),
        Err(e) => return RunOutcome::Failed(format!("ball drop: {e}")),
    };
    if !result.completed {
        return RunOutcome::Interrupted(result.final_time);
    }
    let summary = sim::ball_drop_summary::summary(&config, &result);
    let series = result
        .samples
        .iter()
        .flat_map(sim::ball_drop_summary::row)
        .collect();
    RunOutcome::Table {
        kind: "ball_drop",
        summary: serde_json::to_string(&summary)
            .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}")),
        columns: sim::ball_drop_summary::COLUMNS
            .iter()
            .map(|c| c.to_string())
            .collect(),
        series,
    }
}

/// A moving-load run (on the worker thread), as `dyncontact run`: the summary of
/// `sim::moving_load_summary` and the time series at the output points.
fn run_moving_load(
    config: sim::config::moving_load::MovingLoadConfig,
    stop: &std::sync::atomic::AtomicBool,
) -> RunOutcome {
    use std::ops::ControlFlow;
    use std::sync::atomic::Ordering;
    let sim::config::moving_load::MovingLoadConfig {
        bridge,
        loads,
        integrator_name,
        settings,
        points,
    } = config;
    let start = std::time::Instant::now();
    let mut observer = |_: beam::StepProgress| {
        if stop.load(Ordering::Relaxed) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let response = match beam::simulate_moving_loads_observed(
        bridge.basis.as_ref(),
        &bridge.damping,
        &loads,
        &settings,
        &points,
        &mut observer,
    ) {
        Ok(r) => r,
        Err(
            e @ (beam::BeamError::InvalidParameter { .. }
            | beam::BeamError::InvalidCount { .. }
            | beam::BeamError::OutsideSpan { .. }),
        ) => return RunOutcome::Invalid(format!("moving-load run: {e}")),
        Err(e) => return RunOutcome::Failed(format!("moving-load run: {e}")),
    };
    if !response.completed {
        return RunOutcome::Interrupted(response.times.last().copied().unwrap_or(0.0));
    }
    let wall = start.elapsed().as_secs_f64();
    let summary = match sim::moving_load_summary::summarise(
        &bridge,
        &loads,
        &response,
        &integrator_name,
        settings.dt,
        wall,
    ) {
        Ok(s) => s,
        Err(e) => return RunOutcome::Failed(format!("moving-load run: {e}")),
    };
    let columns = sim::moving_load_summary::columns(&response);
    let mut series = Vec::with_capacity(columns.len() * response.times.len());
    let mut line = Vec::with_capacity(columns.len());
    for i in 0..response.times.len() {
        sim::moving_load_summary::row(&loads, &response, i, &mut line);
        series.extend_from_slice(&line);
    }
    RunOutcome::Table {
        kind: "moving_load",
        summary: serde_json::to_string(&summary)
            .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}")),
        columns,
        series,
    }
}

struct RunData {
    summary: sim::vehicle_bridge::RunSummary,
    /// The train's part of summary.json (`vehicles`, `train`, `comfort`,
    /// `max_unloading_ratio`; BEM contact: the solve counts of `contact`) as JSON text
    /// (`sim::train_response`).
    train_json: String,
    columns: Vec<String>,
    series: Vec<f64>,
    static_loads: Vec<f64>,
    warnings: Vec<String>,
}

/// Builds and runs a vehicle–bridge scenario (on the worker thread), recording the time series.
fn run_vehicle_bridge(text: &str, base: &str, stop: &std::sync::atomic::AtomicBool) -> RunOutcome {
    use std::ops::ControlFlow;
    use std::sync::atomic::Ordering;

    use sim::config::ScenarioConfig;
    use sim::vehicle_bridge::{Simulation, run};

    let config = match sim::config::load(text, std::path::Path::new(base), &Default::default()) {
        Ok(c) => c,
        Err(e) => return RunOutcome::Invalid(e.to_string()),
    };
    let config = match config {
        ScenarioConfig::VehicleBridge(config) => config,
        ScenarioConfig::BallDrop(config) => return run_ball_drop(*config, stop),
        ScenarioConfig::MovingLoad(config) => return run_moving_load(*config, stop),
        other => return RunOutcome::Kind(other.kind()),
    };
    let mut config = *config;
    let parts = config.take_parts();
    let sim::config::vehicle_bridge::VehicleBridgeConfig {
        scenario,
        every,
        warnings,
        train,
        ..
    } = config;
    let mut sim = match Simulation::with_parts(scenario, parts) {
        Ok(s) => s,
        Err(e) => return RunOutcome::Invalid(e.to_string()),
    };
    let every = every.max(1);
    let steps = sim.planned_steps();
    let columns = sim::vehicle_bridge_series::SeriesLayout::of(&sim).columns();
    let width = columns.len();
    let rows = steps / every + 2;
    if rows.saturating_mul(width) > MAX_SERIES_VALUES {
        return RunOutcome::Invalid(format!(
            "[output] `every` = {every}: {steps} steps would record {rows} rows of {width} values, more than the {MAX_SERIES_VALUES} a run from Python holds in memory; raise `every`"
        ));
    }
    let mut series = Vec::with_capacity(rows * width);
    let mut line = Vec::with_capacity(width);
    let mut record = |sim: &Simulation, iterations: usize, series: &mut Vec<f64>| {
        sim::vehicle_bridge_series::series_row(sim, iterations, &mut line);
        series.extend_from_slice(&line);
    };
    record(&sim, 0, &mut series);
    let mut monitor = sim::train_response::TrainMonitor::new(&sim);
    let mut observer = |s: &Simulation, info: run::StepInfo| {
        monitor.observe(s);
        if info.step.is_multiple_of(every) || info.step == info.steps {
            record(s, info.iterations, &mut series);
        }
        if stop.load(Ordering::Relaxed) {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    match run::run(&mut sim, &mut observer) {
        Ok(summary) if summary.completed => RunOutcome::Done(Box::new(RunData {
            train_json: serde_json::json!({
                "vehicles": monitor.vehicles(),
                "train": train.as_ref().map(sim::train_response::TrainSummary::of),
                "comfort": train.as_ref().map(|_| {
                    sim::train_response::ComfortSummary::of(summary.max_body_acceleration())
                }),
                "max_unloading_ratio": monitor.max_unloading_ratio(),
                "contact_solves": sim.contact_solves().map(|c| serde_json::json!({
                    "full_solves": c.full_solves,
                    "factor_solves": c.factor_solves,
                    "reused_evaluations": c.reused,
                    "max_reuse_error_estimate": c.max_estimate,
                    "table_evaluations": c.table_answers,
                    "table_solves": c.table_solves,
                })),
            })
            .to_string(),
            summary,
            columns,
            series,
            static_loads: sim.static_loads().to_vec(),
            warnings,
        })),
        Ok(summary) => RunOutcome::Interrupted(summary.time_reached),
        Err(f) => RunOutcome::Failed(format!(
            "step {} of {steps}: {}",
            f.partial.steps_taken + 1,
            f.error
        )),
    }
}

/// `run_text(text, base) -> dict`: a scenario file's text. `kind = "vehicle_bridge"` runs (as
/// `dyncontact run`, the library's run driver `sim::vehicle_bridge::run`) with the GIL
/// released and Ctrl-C polled every 50 ms, and returns `summary` (a dict of the run's key
/// numbers, named as in the CLI's `summary.json`), `columns` (the names of `timeseries.csv`)
/// and `series` (float64, one row per recorded step). `ball_drop` and `moving_load` run the
/// same way and return `summary_json` (the CLI's summary.json as JSON text), `columns` and
/// `series`. Other kinds return only `kind` (the wrapper dispatches `contact` and `sweep`).
#[pyfunction]
pub fn run_text<'py>(py: Python<'py>, text: &str, base: &str) -> PyResult<Bound<'py, PyDict>> {
    use pyo3::exceptions::PyKeyboardInterrupt;

    let d = PyDict::new(py);
    let data = match interruptible(py, |stop| run_vehicle_bridge(text, base, stop))? {
        RunOutcome::Kind(kind) => {
            d.set_item("kind", kind)?;
            return Ok(d);
        }
        RunOutcome::Invalid(m) => return Err(PyValueError::new_err(m)),
        RunOutcome::Failed(m) => return Err(SolverError::new_err(m)),
        RunOutcome::Interrupted(t) => {
            return Err(PyKeyboardInterrupt::new_err(format!(
                "the run was interrupted at t = {t} s"
            )));
        }
        RunOutcome::Done(data) => data,
        RunOutcome::Table {
            kind,
            summary,
            columns,
            series,
        } => {
            d.set_item("kind", kind)?;
            d.set_item("summary_json", summary)?;
            let width = columns.len().max(1);
            let n_rows = series.len() / width;
            d.set_item("columns", columns)?;
            d.set_item(
                "series",
                PyArray1::from_vec(py, series).reshape([n_rows, width])?,
            )?;
            return Ok(d);
        }
    };
    let RunData {
        summary,
        train_json,
        columns,
        series,
        static_loads,
        warnings,
    } = *data;
    d.set_item("kind", "vehicle_bridge")?;
    let width = columns.len();
    let s = PyDict::new(py);
    s.set_item("completed", summary.completed)?;
    s.set_item("time_reached", summary.time_reached)?;
    s.set_item("max_midspan_deflection", summary.deflection.max_abs())?;
    s.set_item("max_midspan_acceleration", summary.acceleration.max_abs())?;
    if !summary.points.is_empty() {
        let points = PyList::empty(py);
        for p in &summary.points {
            let d = PyDict::new(py);
            d.set_item("x", p.x)?;
            d.set_item("max_deflection", p.deflection.max_abs())?;
            d.set_item("max_acceleration", p.acceleration.max_abs())?;
            points.append(d)?;
        }
        s.set_item("points", points)?;
    }
    s.set_item(
        "max_quasi_static_deflection",
        summary.max_quasi_static_deflection,
    )?;
    s.set_item("dynamic_amplification", summary.dynamic_amplification)?;
    let contact = PyDict::new(py);
    contact.set_item("max_force", summary.max_force())?;
    contact.set_item("min_force", summary.min_force())?;
    contact.set_item("loss_of_contact_events", summary.loss_of_contact_events)?;
    contact.set_item("max_pressure", summary.max_pressure())?;
    s.set_item("contact", contact)?;
    let vehicle = PyDict::new(py);
    vehicle.set_item("max_body_acceleration", summary.max_body_acceleration())?;
    vehicle.set_item("max_wheel_acceleration", summary.max_wheel_acceleration())?;
    vehicle.set_item("static_wheel_loads", static_loads)?;
    s.set_item("vehicle", vehicle)?;
    let stats = summary.solver;
    let solver = PyDict::new(py);
    solver.set_item("steps", stats.steps)?;
    solver.set_item(
        "mean_iterations_per_step",
        stats.iterations as f64 / stats.steps.max(1) as f64,
    )?;
    solver.set_item("max_iterations_per_step", stats.max_iterations)?;
    solver.set_item(
        "mean_contact_iterations_per_step",
        stats.contact_iterations as f64 / stats.steps.max(1) as f64,
    )?;
    solver.set_item("failed_steps", stats.failed_steps)?;
    s.set_item("solver", solver)?;
    let mut all_warnings = warnings;
    all_warnings.extend(summary.accuracy.warnings.iter().cloned());
    s.set_item("warnings", all_warnings)?;
    d.set_item("summary", s)?;
    d.set_item("train_json", train_json)?;
    d.set_item("columns", columns)?;
    let n_rows = series.len() / width;
    d.set_item(
        "series",
        PyArray1::from_vec(py, series).reshape([n_rows, width])?,
    )?;
    Ok(d)
}
