//! `dyncontact sweep FILE` (and `run` with `kind = "sweep"`): every train at every speed,
//! the Eurocode deck-acceleration check, plots; `--shard K/N` runs a slice and writes
//! `shard.json`; `dyncontact sweep-merge DIR…` combines shards into the outputs of the whole
//! sweep (docs/sweep.md).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use sim::config::sweep::SweepConfig;
use sim::sweep::shard::{self, MergeError, ShardFile};
use sim::sweep::summary::SweepSummary;
use sim::sweep::{Passage, Shard, SweepError};

use crate::errors::bad_input;
use crate::interrupt::{self, Interrupted};
use crate::output::{self, RunOutput};
use crate::plot;

/// The files of a whole sweep.
const OUTPUT_SET: &[&str] = &[
    "summary.json",
    "sweep.csv",
    "acceleration.png",
    "deflection.png",
    "governing.png",
];
/// The file of a shard.
const SHARD_SET: &[&str] = &["shard.json"];

/// Parses `K/N` (1 ≤ K ≤ N).
pub fn parse_shard(text: &str) -> Result<Shard> {
    let parsed = text.split_once('/').and_then(|(k, n)| {
        Some(Shard {
            index: k.trim().parse().ok()?,
            count: n.trim().parse().ok()?,
        })
    });
    match parsed {
        Some(s) if s.count >= 1 && (1..=s.count).contains(&s.index) => Ok(s),
        _ => Err(bad_input(anyhow!(
            "--shard {text}: expected K/N with 1 <= K <= N (e.g. --shard 2/8)"
        ))),
    }
}

/// Runs a sweep (or its shard) and writes the outputs into `out`.
pub fn run(
    config: SweepConfig,
    scenario: &str,
    base: &Path,
    out: &Path,
    json: bool,
    shard: Shard,
) -> Result<()> {
    let set = if shard == Shard::ALL {
        OUTPUT_SET
    } else {
        SHARD_SET
    };
    let run_out = RunOutput::create(out, set)?;
    let start = Instant::now();
    let passages = run_passages(&config, shard)?;
    let wall = start.elapsed().as_secs_f64();
    if shard != Shard::ALL {
        let mut file = ShardFile::new(scenario, base, shard, &passages, wall);
        file.scenario_file = output::input_name();
        output::write_json(&run_out.path("shard.json"), &file)?;
        run_out.commit()?;
        if !json {
            println!(
                "shard {}/{}: {} passages in {wall:.3} s; wrote {}/shard.json (combine with dyncontact sweep-merge)",
                shard.index,
                shard.count,
                passages.len(),
                out.display()
            );
        }
        return Ok(());
    }
    finish(&config, &passages, wall, run_out, out, json)
}

/// `dyncontact sweep-merge DIR…`: the shards' passages summarised as one sweep.
pub fn merge(dirs: &[PathBuf], out: &Path, json: bool) -> Result<()> {
    if dirs.is_empty() {
        return Err(bad_input(anyhow!(
            "sweep-merge: give the shard directories"
        )));
    }
    let mut shards = Vec::new();
    for d in dirs {
        let path = d.join("shard.json");
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))
            .map_err(bad_input)?;
        let file: ShardFile = serde_json::from_str(&text)
            .with_context(|| format!("{} is not a dyncontact shard file", path.display()))
            .map_err(bad_input)?;
        shards.push((d.clone(), file));
    }
    output::set_input(
        shards[0]
            .1
            .scenario_file
            .clone()
            .unwrap_or_else(|| "the shards' scenario".to_string()),
        shards[0].1.scenario.clone(),
    );
    let shards: Vec<(String, ShardFile)> = shards
        .into_iter()
        .map(|(d, f)| (d.display().to_string(), f))
        .collect();
    let merged = shard::merge(&shards).map_err(|e| match e {
        MergeError::NotSweep(_) => anyhow!(e),
        other => bad_input(other.into()),
    })?;
    let (config, passages, wall) = (merged.config, merged.passages, merged.wall_time_s);
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    finish(&config, &passages, wall, run_out, out, json)
}

/// The passages of `shard` with a progress bar; Ctrl-C stops them (nothing is written).
fn run_passages(config: &SweepConfig, shard: Shard) -> Result<Vec<Passage>> {
    let total = (0..config.spec.trains.len() * config.spec.speeds.len())
        .filter(|&i| shard.contains(i))
        .count();
    let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} passages, {elapsed} (eta {eta})")
            .map_err(|e| anyhow!("progress bar: {e}"))?,
    );
    interrupt::stop_at_next_step();
    let tick = || {
        bar.inc(1);
        !interrupt::requested()
    };
    let result = sim::sweep::run(
        config.bridge.basis.as_ref(),
        &config.bridge.damping,
        &config.spec,
        shard,
        &tick,
    );
    bar.finish_and_clear();
    match result {
        Ok(p) => Ok(p),
        Err(SweepError::Interrupted { done, total }) => {
            eprintln!("interrupted after {done} of {total} passages: nothing written");
            Err(Interrupted { time_reached: 0.0 }.into())
        }
        Err(e) => Err(anyhow!("sweep: {e}")),
    }
}

/// Summary, CSV and plots of a whole sweep.
fn finish(
    config: &SweepConfig,
    passages: &[Passage],
    wall: f64,
    run_out: RunOutput,
    out: &Path,
    json: bool,
) -> Result<()> {
    let spec = &config.spec;
    let file = shard::report(config, passages, wall).map_err(|e| anyhow!("{e}"))?;
    let summary = &file.results;
    output::write_summary(&run_out.path("summary.json"), &file)?;
    write_csv(&run_out, spec, passages)?;
    plot_sweep(&run_out, config, summary, passages)?;
    run_out.commit()?;
    if json {
        println!("{}", output::json_text(&file)?);
    } else {
        print_summary(config, summary, wall);
        println!(
            "wrote {}/summary.json, sweep.csv, acceleration.png, deflection.png, governing.png",
            out.display()
        );
    }
    Ok(())
}

fn write_csv(
    run_out: &RunOutput,
    spec: &sim::sweep::SweepSpec,
    passages: &[Passage],
) -> Result<()> {
    // One row per (train, speed, output point); the train as its index (names in summary.json).
    let table = sim::sweep::summary::passage_table(spec, passages);
    let rows = (0..table[0].1.len()).map(|r| table.iter().map(|c| c.1[r]).collect::<Vec<f64>>());
    let header: Vec<&str> = table.iter().map(|c| c.0).collect();
    output::write_csv(&run_out.path("sweep.csv"), &header, rows)
}

fn print_summary(config: &SweepConfig, s: &SweepSummary, wall: f64) {
    println!(
        "speed sweep over {} ({} modes, n0 = {:.3} Hz), {} trains × {} speeds = {} passages in {wall:.3} s",
        config.bridge.description,
        config.bridge.basis.n_modes(),
        config.first_frequency,
        config.spec.trains.len(),
        config.spec.speeds.len(),
        s.runs
    );
    for n in &config.notes {
        println!("  {n}");
    }
    println!(
        "  {:<12} {:>14} {:>10} {:>14} {:>10} {:>8}",
        "train", "max acc m/s^2", "at m/s", "max defl mm", "at m/s", "phi'"
    );
    for t in &s.trains {
        println!(
            "  {:<12} {:>14.4} {:>10.2} {:>14.4} {:>10.2} {:>8.4}",
            t.name,
            t.max_acceleration,
            t.speed_at_max_acceleration,
            1e3 * t.max_deflection,
            t.speed_at_max_deflection,
            t.dynamic_factor
        );
    }
    let with_vehicles: Vec<_> = s
        .trains
        .iter()
        .filter_map(|t| t.vehicles.as_ref().map(|v| (&t.name, v)))
        .collect();
    if !with_vehicles.is_empty() {
        println!(
            "  {:<12} {:>14} {:>10} {:>14} {:>14} {:>10}",
            "train", "unloading", "at m/s", "lost contact", "body m/s^2", "at m/s"
        );
        for (name, v) in with_vehicles {
            println!(
                "  {:<12} {:>14.4} {:>10.2} {:>14} {:>14.4} {:>10.2}",
                name,
                v.max_unloading_ratio,
                v.speed_at_max_unloading_ratio,
                format!(
                    "{} at {} v",
                    v.loss_of_contact_events,
                    v.speeds_with_loss_of_contact.len()
                ),
                v.max_body_acceleration,
                v.speed_at_max_body_acceleration
            );
        }
    }
    let c = &s.checks;
    println!(
        "  deck acceleration {:.4} m/s^2 ({} at {:.2} m/s) against {} m/s^2 ({} track, EN 1990 A2): {}",
        c.max_acceleration,
        c.governing_train,
        c.governing_speed,
        c.acceleration_limit,
        c.track,
        if c.passed { "PASS" } else { "FAIL" }
    );
}

fn plot_sweep(
    run_out: &RunOutput,
    config: &SweepConfig,
    s: &SweepSummary,
    passages: &[Passage],
) -> Result<()> {
    let spec = &config.spec;
    let speeds_kmh: Vec<f64> = spec.speeds.iter().map(|v| 3.6 * v).collect();
    let along = |values: &[f64], scale: f64| -> Vec<(f64, f64)> {
        speeds_kmh
            .iter()
            .zip(values)
            .map(|(&v, &y)| (v, scale * y))
            .collect()
    };
    let (v_lo, v_hi) = (
        speeds_kmh.first().copied().unwrap_or(0.0),
        speeds_kmh.last().copied().unwrap_or(0.0),
    );
    // Per-train curves: the largest value over the output points at each speed.
    let mut per_train_acc = vec![vec![0.0f64; spec.speeds.len()]; spec.trains.len()];
    let mut per_train_defl = per_train_acc.clone();
    for p in passages {
        let peak = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        per_train_acc[p.train][p.speed] = peak(&p.peaks.acceleration);
        per_train_defl[p.train][p.speed] = peak(&p.peaks.deflection);
    }
    let mut acc_series: Vec<plot::Series> = spec
        .trains
        .iter()
        .enumerate()
        .map(|(t, train)| plot::Series::new(train.name.clone(), along(&per_train_acc[t], 1.0)))
        .collect();
    acc_series.push(
        plot::Series::new("envelope", along(&s.envelope.max_acceleration, 1.0)).in_every_part(),
    );
    acc_series.push(plot::Series::reference(
        format!(
            "limit {} m/s² ({})",
            s.checks.acceleration_limit, s.checks.track
        ),
        vec![
            (v_lo, s.checks.acceleration_limit),
            (v_hi, s.checks.acceleration_limit),
        ],
    ));
    plot::panels(
        &run_out.path("acceleration.png"),
        &[plot::Panel {
            title: format!(
                "peak deck acceleration at x = {} m: {:.3} m/s² ({} at {:.0} km/h)",
                spec.points[0],
                s.checks.max_acceleration,
                s.checks.governing_train,
                3.6 * s.checks.governing_speed
            ),
            x_label: "speed [km/h]".into(),
            y_label: "acceleration [m/s²]".into(),
            series: acc_series,
        }],
    )?;
    let mut defl_series: Vec<plot::Series> = spec
        .trains
        .iter()
        .enumerate()
        .map(|(t, train)| plot::Series::new(train.name.clone(), along(&per_train_defl[t], 1e3)))
        .collect();
    defl_series.push(
        plot::Series::new("envelope", along(&s.envelope.max_deflection, 1e3)).in_every_part(),
    );
    plot::panels(
        &run_out.path("deflection.png"),
        &[
            plot::Panel {
                title: "peak deflection over the output points".into(),
                x_label: "speed [km/h]".into(),
                y_label: "deflection [mm]".into(),
                series: defl_series,
            },
            plot::Panel {
                title: "dynamic factor φ' = max dynamic / max static deflection (envelope)".into(),
                x_label: "speed [km/h]".into(),
                y_label: "φ' [-]".into(),
                series: vec![plot::Series::new(
                    "φ' (largest over trains)",
                    along(&s.envelope.dynamic_factor, 1.0),
                )],
            },
        ],
    )?;
    plot_governing(run_out, config, s)
}

/// The time history of the governing passage (largest deck acceleration).
fn plot_governing(run_out: &RunOutput, config: &SweepConfig, s: &SweepSummary) -> Result<()> {
    let spec = &config.spec;
    let Some(t) = spec
        .trains
        .iter()
        .position(|t| t.name == s.checks.governing_train)
    else {
        return Ok(());
    };
    // (t, w, ẅ) at the first output point, recomputed with the sweep's model.
    let history: Vec<(f64, f64, f64)> = match &spec.model {
        sim::sweep::SweepModel::Interaction(model) => {
            let basis = config.bridge.basis.as_ref();
            let mut shapes = vec![0.0; basis.n_modes()];
            basis
                .eval_all(spec.points[0], beam::Derivative::Shape, &mut shapes)
                .map_err(|e| anyhow!("governing time history: {e}"))?;
            sim::sweep::interaction::history(
                model,
                t,
                s.checks.governing_speed,
                &shapes,
                spec.free_vibration,
                20_000,
            )
            .map_err(|e| anyhow!("governing time history: {e}"))?
        }
        sim::sweep::SweepModel::MovingForces => {
            let axles: Vec<beam::Axle> =
                sim::sweep::train_axles(spec).map_err(|e| anyhow!("{e}"))?[t].clone();
            let loads = beam::MovingLoads::train(axles, s.checks.governing_speed)
                .map_err(|e| anyhow!("{e}"))?;
            let mut settings = beam::MovingLoadSettings::new(spec.dt, spec.free_vibration);
            let steps =
                (loads.exit_time(config.bridge.basis.length()) + spec.free_vibration) / spec.dt;
            settings.output_every = ((steps / 20_000.0).ceil() as usize).max(1);
            let r = beam::simulate_moving_loads(
                config.bridge.basis.as_ref(),
                &config.bridge.damping,
                &loads,
                &settings,
                &spec.points[..1],
            )
            .map_err(|e| anyhow!("governing time history: {e}"))?;
            r.times
                .iter()
                .zip(&r.deflection)
                .zip(&r.acceleration)
                .map(|((&t, &w), &a)| (t, w, a))
                .collect()
        }
    };
    let series = |pick: fn(&(f64, f64, f64)) -> f64, scale: f64| -> Vec<(f64, f64)> {
        history.iter().map(|h| (h.0, scale * pick(h))).collect()
    };
    plot::panels(
        &run_out.path("governing.png"),
        &[
            plot::Panel {
                title: format!(
                    "{} at {:.1} km/h: deck acceleration at x = {} m",
                    s.checks.governing_train,
                    3.6 * s.checks.governing_speed,
                    spec.points[0]
                ),
                x_label: "time [s]".into(),
                y_label: "acceleration [m/s²]".into(),
                series: vec![plot::Series::new("acceleration", series(|h| h.2, 1.0))],
            },
            plot::Panel {
                title: format!("deck deflection at x = {} m", spec.points[0]),
                x_label: "time [s]".into(),
                y_label: "deflection [mm]".into(),
                series: vec![plot::Series::new("deflection", series(|h| h.1, 1e3))],
            },
        ],
    )
}
