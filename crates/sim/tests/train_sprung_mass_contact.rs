//! A `sprung_mass` vehicle of a `[train]` (a body on a massless wheel) with a compliant contact
//! is refused naming the keys the file set, `contact.model` and `train.vehicles[i]`; before,
//! the refusal named `vehicle.wheels[0].wheel_mass`, a key of `[vehicle]` files that a train
//! file does not have (found by a campaign of sensible scenarios through the CLI, 2026-11-28).
//! With the rigid contact the same train runs and carries its weight.

use std::path::Path;

use sim::config::{LoadOptions, ScenarioConfig, load};
use sim::vehicle_bridge::Simulation;

/// A moving-force locomotive (a vehicle without a wheel DOF) and then two sprung masses over a
/// 20 m span (f₁ = 5 Hz, 15 t/m) at 30 m/s.
fn scenario(contact: &str) -> String {
    format!(
        r#"kind = "vehicle_bridge"
[bridge]
length = 20.0
EI = 2.43e10
mass_per_length = 15000.0
supports = "simply_supported"
modes = 6
damping_ratio = 0.02
[train]
speed = 30.0
position = -2.0
[[train.vehicles]]
type = "moving_forces"
length = 10.0
axle_positions = [0.0]
axle_loads = [1.0e5]
[[train.vehicles]]
type = "sprung_mass"
count = 2
length = 10.0
body_mass = 20000.0
suspension_stiffness = 2e6
suspension_damping = 3e4
[contact]
model = "{contact}"
[integrator]
duration = 0.05
"#
    )
}

fn error(text: &str) -> Option<String> {
    load(text, Path::new("."), &LoadOptions::default())
        .err()
        .map(|e| e.to_string())
}

#[test]
fn a_sprung_mass_with_a_compliant_contact_names_the_train_entry_and_the_contact() {
    for contact in ["hertz", "bem"] {
        let e = error(&scenario(contact)).expect("refused");
        assert!(
            e.contains(&format!("`contact.model` = \"{contact}\""))
                && e.contains("train.vehicles[1]")
                && e.contains("sprung_mass")
                && e.contains("quarter_car")
                && !e.contains("vehicle.wheels"),
            "{e}"
        );
    }
}

#[test]
fn the_same_train_runs_with_the_rigid_contact() {
    let ScenarioConfig::VehicleBridge(config) =
        load(&scenario("rigid"), Path::new("."), &LoadOptions::default()).expect("accepted")
    else {
        panic!("not a vehicle_bridge scenario");
    };
    let mut sim = Simulation::with_vehicles(config.scenario, config.vehicles).expect("built");
    sim.run(|_| {}).expect("runs");
    // Two bodies of 20 t on their wheels, at rest on the approach: each wheel carries its body's
    // weight m g = 196.2 kN (the moving force has no wheel). 1e-6 relative: the static start is
    // exact and the rail before the span is flat.
    for w in sim.wheels() {
        let f = w.contact.force;
        assert!((f / (20000.0 * 9.81) - 1.0).abs() < 1e-6, "{f}");
    }
}
