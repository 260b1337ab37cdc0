//! A vehicle–bridge run as a library: Biggs's sprung mass crossing a 25 m bridge at 100 km/h
//! (the scenario file `examples/vehicle_bridge_biggs.toml`, read by `sim::config`), stepped to
//! the end; the quasi-static deflection is checked against one mode's closed form. Run with
//! `cargo run --release -p sim --example library_vehicle_bridge`.

use std::path::Path;

use sim::config::{LoadOptions, ScenarioConfig, load};
use sim::vehicle_bridge::Simulation;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let text = include_str!("../../../examples/vehicle_bridge_biggs.toml");
    let ScenarioConfig::VehicleBridge(config) =
        load(text, Path::new("."), &LoadOptions::default())?
    else {
        return Err("not a vehicle_bridge scenario".into());
    };
    let mut sim = Simulation::new(config.scenario)?;
    let run = sim.run(|_| {})?; // the closure sees the simulation after every step
    println!(
        "max midspan deflection {:.4e} m, quasi-static {:.4e} m, dynamic amplification {:.4}, {} steps",
        run.deflection.max_abs(),
        run.max_quasi_static_deflection.unwrap_or(f64::NAN),
        run.dynamic_amplification.unwrap_or(f64::NAN),
        run.steps_taken
    );
    // One mode of a simply supported beam under the body's weight W at midspan:
    // w = 2 W L³ / (π⁴ E I) (references.md §D1.1).
    let (w, l, ei) = (5750.0 * 9.81, 25.0_f64, 2.87e9 * 2.90);
    let one_mode = 2.0 * w * l.powi(3) / (std::f64::consts::PI.powi(4) * ei);
    let quasi = run
        .max_quasi_static_deflection
        .ok_or("no quasi-static deflection")?;
    assert!(
        (quasi / one_mode - 1.0).abs() < 1e-3,
        "{quasi} vs {one_mode}"
    );
    Ok(())
}
