//! `dyncontact bench track`: a quarter car over a 25 m bridge on the ballasted track
//! (docs/track.md), the cost per step against the length of the approach and exit track.

use std::time::Instant;

use anyhow::Result;

/// The quarter car over the 25 m bridge with `approach` m of ballasted track before and after
/// it (sleepers 0.6 m), Hertz contact, Newmark, Δt = 1e-4 s, 0.5 s
/// simulated from 10 m before the bridge; `None`: no track (the rail is the beam).
fn scenario(approach: Option<f64>) -> String {
    let track = approach.map_or(String::new(), |a| {
        format!(
            "[track]\nmodel = \"ballasted\"\napproach_length = {a}\nexit_length = {a}\nsleeper_spacing = 0.6\n"
        )
    });
    format!(
        "kind = \"vehicle_bridge\"\n[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 1148.0\nsupports = \"simply_supported\"\nmodes = 10\ndamping_ratio = 0.02\n[vehicle]\nspeed = 30.0\n[[vehicle.wheels]]\nposition = -10.0\nwheel_mass = 600.0\nbody_mass = 5750.0\nsuspension_stiffness = 1595e3\nsuspension_damping = 2e4\n[contact]\nmodel = \"hertz\"\n{track}[integrator]\nmethod = \"newmark\"\ndt = 1e-4\nduration = 0.5\n"
    )
}

/// CPU time of the calling thread \[s\] (Linux: /proc/thread-self/schedstat, nanoseconds on
/// the CPU), or NaN where unavailable. On a shared machine the wall time includes waiting for
/// a core; the CPU time does not.
pub(crate) fn thread_cpu_time() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| 1e-9 * ns)
}

/// Runs the table.
pub fn track() -> Result<()> {
    println!(
        "quarter car over a 25 m bridge (10 modes) on ballasted track (60E1, sleepers 0.6 m), Hertz, newmark, dt = 1e-4 s, 0.5 s simulated, one thread; no m_b: without the ballast mass and subgrade"
    );
    println!(
        "{:>14} {:>9} {:>11} {:>13} {:>8} {:>10} {:>12} {:>16} {:>14}",
        "approach [m]",
        "el./bay",
        "track DOFs",
        "factor nnz",
        "steps",
        "wall [s]",
        "CPU µs/step",
        "× real time CPU",
        "× real time wall"
    );
    // (approach and exit, rail elements per bay, with the ballast mass and subgrade): the last
    // row is the pad–sleeper–ballast chain without a ballast mass, the size (about 1000 track
    // DOFs for 60 m approaches) of issue #11's speed target.
    let rows = [
        (None, 4, true),
        (Some(20.0), 4, true),
        (Some(60.0), 4, true),
        (Some(120.0), 4, true),
        (Some(60.0), 2, true),
        (Some(60.0), 2, false),
    ];
    for (approach, per_bay, ballast_mass) in rows {
        let mut text = scenario(approach);
        if approach.is_some() {
            let chain = if ballast_mass {
                ""
            } else {
                "ballast_mass = 0.0\n"
            };
            text = text.replace(
                "sleeper_spacing = 0.6\n",
                &format!("sleeper_spacing = 0.6\nelements_per_bay = {per_bay}\n{chain}"),
            );
        }
        let config = sim::config::vehicle_bridge::parse(&text)?;
        let mut sim = match config.track {
            Some(t) => {
                sim::vehicle_bridge::Simulation::with_track(config.scenario, config.vehicles, t)?
            }
            None => {
                sim::vehicle_bridge::Simulation::with_vehicles(config.scenario, config.vehicles)?
            }
        };
        let dofs = sim.track_model().map_or(0, |t| t.n_track_dofs());
        let nnz = sim.track_factor_entries().unwrap_or(0);
        let (start, cpu0) = (Instant::now(), thread_cpu_time());
        let summary = sim.run(|_| {})?;
        let (wall, cpu) = (start.elapsed().as_secs_f64(), thread_cpu_time() - cpu0);
        let steps = summary.solver.steps;
        let label = approach.map_or("no track".to_string(), |a| format!("{a}"));
        let bay = match (approach, ballast_mass) {
            (None, _) => "-".to_string(),
            (Some(_), true) => per_bay.to_string(),
            (Some(_), false) => format!("{per_bay}, no m_b"),
        };
        // The scheduler's CPU clock advances in ticks of a few ms: shorter runs show "-".
        let (per_step, speed) = if cpu >= 0.02 {
            (
                format!("{:.1}", 1e6 * cpu / steps as f64),
                format!("{:.2}", 0.5 / cpu),
            )
        } else {
            ("-".to_string(), "-".to_string())
        };
        println!(
            "{label:>14} {bay:>9} {dofs:>11} {nnz:>13} {steps:>8} {wall:>10.4} {per_step:>12} {speed:>16} {:>14.2}",
            0.5 / wall
        );
    }
    Ok(())
}
