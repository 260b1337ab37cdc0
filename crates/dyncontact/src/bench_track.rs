//! `dyncontact bench track`: a quarter car over a 25 m bridge on the ballasted track
//! (docs/track.md), the cost per step against the length of the approach and exit track.

use std::time::Instant;

use anyhow::Result;

/// The quarter car over the 25 m bridge with `approach` m of ballasted track before and after
/// it (sleepers 0.6 m, 4 rail elements per bay), Hertz contact, Newmark, Δt = 1e-4 s, 0.5 s
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

/// Runs the table.
pub fn track() -> Result<()> {
    println!(
        "quarter car over a 25 m bridge (10 modes) on ballasted track (60E1, sleepers 0.6 m, 4 elements per bay), Hertz, newmark, dt = 1e-4 s, 0.5 s simulated, one thread"
    );
    println!(
        "{:>14} {:>11} {:>8} {:>10} {:>10} {:>14}",
        "approach [m]", "track DOFs", "steps", "wall [s]", "µs/step", "× real time"
    );
    for approach in [None, Some(20.0), Some(60.0), Some(120.0)] {
        let config = sim::config::vehicle_bridge::parse(&scenario(approach))?;
        let mut sim = match config.track {
            Some(t) => {
                sim::vehicle_bridge::Simulation::with_track(config.scenario, config.vehicles, t)?
            }
            None => {
                sim::vehicle_bridge::Simulation::with_vehicles(config.scenario, config.vehicles)?
            }
        };
        let dofs = sim.track_model().map_or(0, |t| t.n_track_dofs());
        let start = Instant::now();
        let summary = sim.run(|_| {})?;
        let wall = start.elapsed().as_secs_f64();
        let steps = summary.solver.steps;
        let label = approach.map_or("no track".to_string(), |a| format!("{a}"));
        println!(
            "{label:>14} {dofs:>11} {steps:>8} {wall:>10.4} {:>10.1} {:>14.2}",
            1e6 * wall / steps as f64,
            0.5 / wall
        );
    }
    Ok(())
}
