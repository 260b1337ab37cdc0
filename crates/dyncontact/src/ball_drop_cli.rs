//! `dyncontact run FILE` with `kind = "ball_drop"`: a ball dropped on an elastic half-space
//! (Hertz or boundary-element contact, any integrator), and `dyncontact bench integrators`.
//! The schema is documented in docs/ball_drop.md. SI units; unknown keys are errors.

use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

use anyhow::{Result, anyhow};
use sim::ball_drop::{
    BallDrop, BallDropError, BallDropResult, HertzImpact, Integrator, IntegratorSettings,
    METHOD_NAMES, Progress,
};
use sim::config::ball_drop::BallDropConfig;

use crate::errors::bad_input;
use crate::interrupt::{self, Interrupted};
use crate::output::{self, RunOutput};
use crate::plot;
use crate::plot::{Panel, Series};
use sim::ball_drop_summary::{self, summary};

/// The files a ball-drop run writes (one run's output set).
const OUTPUT_SET: &[&str] = &["timeseries.csv", "summary.json", "ball_drop.png"];

/// `dyncontact run FILE` for `kind = "ball_drop"`. Ctrl-C stops the run at its next step;
/// what is complete is written with `"completed": false` (module [`crate::interrupt`]).
pub fn run(prepared: BallDropConfig, out: &Path, json: bool) -> Result<()> {
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    interrupt::stop_at_next_step();
    let mut stop_on_interrupt = |_: Progress| {
        if interrupt::requested() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let result = prepared
        .scenario
        .simulate_observed(true, &mut stop_on_interrupt)
        .map_err(|e| {
            // A parameter or material the model rejects is the input's fault (exit 2).
            let input = matches!(
                e,
                BallDropError::InvalidParameter { .. } | BallDropError::Material { .. }
            );
            let e = anyhow!("ball drop: {e}");
            if input { bad_input(e) } else { e }
        })?;
    let summary = summary(&prepared, &result);
    output::write_csv(
        &run_out.path("timeseries.csv"),
        &ball_drop_summary::COLUMNS,
        result
            .samples
            .iter()
            .map(|s| ball_drop_summary::row(s).to_vec()),
    )?;
    output::write_summary(&run_out.path("summary.json"), &summary)?;
    if prepared.plot {
        write_plot(&run_out.path("ball_drop.png"), &result)?;
    }
    if !result.completed {
        run_out.mark_partial("timeseries.csv")?;
    }
    run_out.commit()?;
    if json {
        println!("{}", output::json_text(&summary)?);
    } else {
        print_summary(&prepared, &result);
        println!(
            "wrote {}/{}, summary.json{}",
            out.display(),
            if result.completed {
                "timeseries.csv"
            } else {
                "timeseries.partial.csv"
            },
            if prepared.plot { ", ball_drop.png" } else { "" }
        );
    }
    if !result.completed {
        return Err(Interrupted {
            time_reached: result.final_time,
        }
        .into());
    }
    Ok(())
}

fn print_summary(p: &BallDropConfig, r: &BallDropResult) {
    let st = &r.stats;
    println!(
        "ball drop: m = {:.6e} kg, K = {:.6e} N/m^1.5, {} in {} s; {}: {} ({} rejected), {} f-evals, {:.3} ms",
        p.scenario.mass,
        r.hertz_constant,
        crate::output::plural(r.impacts.len(), "impact"),
        r.final_time,
        st.method,
        crate::output::plural(st.steps, "step"),
        st.rejected_steps,
        st.f_evals,
        1e3 * r.wall_time_s
    );
    let c = r.reference;
    println!(
        "closed form (first impact, v = {:.6} m/s): δ* = {:.6e} m, F* = {:.6e} N, t_c = {:.6e} s",
        c.impact_speed, c.max_approach, c.peak_force, c.contact_duration
    );
    println!(
        "{:>4} {:>12} {:>12} {:>13} {:>13} {:>13} {:>12} {:>10}",
        "#", "time s", "v_in m/s", "max δ m", "peak F N", "duration s", "v_out m/s", "e"
    );
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.6e}"));
    for (k, i) in r.impacts.iter().enumerate() {
        println!(
            "{:>4} {:>12.8} {:>12.8} {:>13.6e} {:>13.6e} {:>13} {:>12} {:>10}",
            k + 1,
            i.time,
            i.impact_velocity,
            i.max_approach,
            i.peak_force,
            opt(i.contact_duration),
            i.rebound_velocity
                .map_or("-".to_string(), |v| format!("{v:.8}")),
            i.restitution.map_or("-".to_string(), |e| format!("{e:.7}")),
        );
    }
    println!(
        "restitution {}, energy drift {:.3e} (max {})",
        r.restitution.map_or("-".to_string(), |e| format!("{e:.8}")),
        r.energy_drift,
        r.energy_drift_max
            .map_or("-".to_string(), |e| format!("{e:.3e}"))
    );
}

/// z(t) and F(t) over the run, and F(t) over the first impact (time from its start, µs).
fn write_plot(path: &Path, r: &BallDropResult) -> Result<()> {
    let z: Vec<(f64, f64)> = r.samples.iter().map(|s| (s.t, s.z)).collect();
    let f: Vec<(f64, f64)> = r.samples.iter().map(|s| (s.t, s.force)).collect();
    let mut panels = vec![
        Panel {
            title: "height of the lowest point".into(),
            x_label: "t [s]".into(),
            y_label: "z [m]".into(),
            series: vec![Series::new("height of the lowest point", z)],
        },
        Panel {
            title: "contact force".into(),
            x_label: "t [s]".into(),
            y_label: "F [N]".into(),
            series: vec![
                Series::new("contact force", f),
                Series::new(
                    "peak of each impact (widened to be visible)",
                    peak_markers(r),
                ),
            ],
        },
    ];
    if let Some(first) = r.impacts.first() {
        let tc = first
            .contact_duration
            .unwrap_or(r.reference.contact_duration);
        let (a, b) = (first.time - 0.1 * tc, first.time + 1.1 * tc);
        let zoom: Vec<(f64, f64)> = r
            .samples
            .iter()
            .filter(|s| s.t >= a && s.t <= b)
            .map(|s| (1e6 * (s.t - first.time), s.force))
            .collect();
        let hertz = closed_form_marker(r);
        panels.push(Panel {
            title: format!("first impact (t₀ = {:.6} s)", first.time),
            x_label: "t − t₀ [µs]".into(),
            y_label: "F [N]".into(),
            series: vec![
                Series::new("simulated contact force", zoom),
                Series::new("closed-form F* over the closed-form t_c", hertz),
            ],
        });
    }
    plot::panels(path, &panels)
}

/// A contact lasts ~1e-4 of the run, narrower than a pixel: a triangle per impact, 0.8 % of
/// the run wide, with the impact's peak force as its height.
fn peak_markers(r: &BallDropResult) -> Vec<(f64, f64)> {
    let w = 0.004 * r.final_time;
    let mut points = Vec::new();
    for i in &r.impacts {
        let mid = i.time + 0.5 * i.contact_duration.unwrap_or(0.0);
        points.extend([(mid - w, 0.0), (mid, i.peak_force), (mid + w, 0.0)]);
    }
    points
}

/// Marker of the closed form on the zoom: the Hertz peak force F* drawn over [0, t_c].
fn closed_form_marker(r: &BallDropResult) -> Vec<(f64, f64)> {
    let c = r.reference;
    vec![
        (0.0, c.peak_force),
        (1e6 * c.contact_duration, c.peak_force),
    ]
}

/// One benchmark row.
struct Row {
    method: &'static str,
    setting: String,
    impacts: usize,
    error: f64,
    steps: usize,
    f_evals: usize,
    wall: f64,
}

fn bench_case(method: &str, settings: &IntegratorSettings) -> Result<BallDrop> {
    Ok(BallDrop {
        integrator: Integrator::from_name(method, settings).map_err(|e| anyhow!("{e}"))?,
        ..BallDrop::steel_ball()
    })
}

/// Error of the first peak force against the energy-balance closed form, and the result.
fn bench_run(scenario: &BallDrop, reference: &HertzImpact) -> Result<(f64, BallDropResult)> {
    let r = scenario.simulate(false).map_err(|e| anyhow!("{e}"))?;
    let err = r.impacts.first().map_or(f64::INFINITY, |i| {
        (i.peak_force / reference.peak_force - 1.0).abs()
    });
    Ok((err, r))
}

/// `dyncontact bench integrators`: the reference drop (references.md §C4.10) (steel ball, 0.1 m, 1 s, 4 bounces) with
/// every method, at the loosest tolerance (adaptive) or largest step (fixed) that gives a
/// relative error ≤ `target` in the first impact's peak force against the closed form
/// `(2/5)Kδ*^{5/2} = ½mv² + mgδ*`, `F* = Kδ*^{3/2}`.
pub fn bench_integrators(target: f64) -> Result<()> {
    let base = BallDrop::steel_ball();
    let material = base.validate().map_err(|e| anyhow!("{e}"))?;
    let k = sim::ball_drop::hertz_constant(&base.shape, &material).map_err(|e| anyhow!("{e}"))?;
    let reference = HertzImpact::new(base.mass, k, base.impact_speed(), base.gravity);
    println!(
        "ball drop: steel ball R = 10 mm on steel, h = 0.1 m, 1 s (4 impacts), Hertz; target: first peak force within {target:.0e} of F* = {:.6} N",
        reference.peak_force
    );
    let mut rows = Vec::new();
    for method in METHOD_NAMES {
        let mut found: Option<(String, IntegratorSettings)> = None;
        let mut best = (f64::INFINITY, String::new());
        let adaptive = matches!(method, "dopri5" | "radau5" | "bdf" | "adams");
        let structural = matches!(
            method,
            "verlet" | "leapfrog" | "newmark" | "hht" | "generalized_alpha"
        );
        if adaptive {
            for e in 4..=13 {
                let rtol = 10f64.powi(-e);
                let s = IntegratorSettings {
                    rtol,
                    atol: rtol * 1e-4,
                    ..IntegratorSettings::default()
                };
                let (err, r) = bench_run(&bench_case(method, &s)?, &reference)?;
                let label = format!("rtol {rtol:.0e}");
                if err < best.0 {
                    best = (err, label.clone());
                }
                if err <= target && r.impacts.len() == 4 {
                    found = Some((label, s));
                    break;
                }
            }
        } else {
            // Fixed steps: halve from 1 µs; first-order methods stop at a 2e7-step budget.
            let mut dt = 1e-6;
            loop {
                let steps = if structural {
                    4.0 * 50e-6 / dt
                } else {
                    1.0 / dt
                };
                if steps > 2e7 {
                    break;
                }
                let s = IntegratorSettings {
                    dt,
                    dt_flight: structural.then_some(1e-3),
                    ..IntegratorSettings::default()
                };
                let (err, r) = bench_run(&bench_case(method, &s)?, &reference)?;
                let label = if structural {
                    format!("dt {dt:.2e}, flight 1e-3")
                } else {
                    format!("dt {dt:.2e}")
                };
                if err < best.0 {
                    best = (err, label.clone());
                }
                if err <= target && r.impacts.len() == 4 {
                    found = Some((label, s));
                    break;
                }
                dt *= 0.5;
            }
        }
        match found {
            Some((label, s)) => {
                let scenario = bench_case(method, &s)?;
                let mut wall = f64::INFINITY;
                let mut last = None;
                for _ in 0..5 {
                    let t = Instant::now();
                    let out = bench_run(&scenario, &reference)?;
                    wall = wall.min(t.elapsed().as_secs_f64());
                    last = Some(out);
                }
                let (err, r) = last.expect("five runs");
                rows.push(Row {
                    method: r.stats.method,
                    setting: label,
                    impacts: r.impacts.len(),
                    error: err,
                    steps: r.stats.steps,
                    f_evals: r.stats.f_evals,
                    wall,
                });
            }
            None => println!(
                "{method:>18}: target not reached within the budget; best error {:.2e} at {}",
                best.0, best.1
            ),
        }
    }
    println!(
        "{:>18} {:>24} {:>7} {:>10} {:>9} {:>9} {:>10} {:>8}",
        "method", "setting", "impacts", "F* error", "steps", "f-evals", "wall ms", "µs/step"
    );
    for r in &rows {
        println!(
            "{:>18} {:>24} {:>7} {:>10.2e} {:>9} {:>9} {:>10.3} {:>8.3}",
            r.method,
            r.setting,
            r.impacts,
            r.error,
            r.steps,
            r.f_evals,
            1e3 * r.wall,
            1e6 * r.wall / r.steps.max(1) as f64
        );
    }
    let fastest = rows.iter().min_by(|a, b| a.wall.total_cmp(&b.wall));
    let multistep = rows
        .iter()
        .filter(|r| matches!(r.method, "bdf" | "adams"))
        .map(|r| r.steps)
        .min();
    if let (Some(f), Some(n)) = (fastest, multistep) {
        let (lo, hi) = (8e-6 * n as f64, 23e-6 * n as f64);
        println!(
            "fastest: {} in {:.3} ms. ESTIMATE (not a measurement of scipy): LSODA at 8–23 µs/step (an assumed cost, docs/references.md §R5.2) over {n} steps (our variable-order bdf/adams step count at this accuracy) ≈ {:.1}–{:.1} ms, i.e. {:.0}–{:.0}× the fastest method here.",
            f.method,
            1e3 * f.wall,
            1e3 * lo,
            1e3 * hi,
            lo / f.wall,
            hi / f.wall
        );
    }
    println!(
        "wall = best of 5 runs of the full 1 s drop without time-series recording; one thread."
    );
    Ok(())
}
