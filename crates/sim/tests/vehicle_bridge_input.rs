//! Scenario inputs the long fuzz run (docs/scenarios.md) found failing only during the run
//! with a message naming no key, or printing a name as `NaN`: each is now refused by the
//! reader (or by `Simulation::new`) with the key, the value and the allowed range.

use std::path::{Path, PathBuf};

use sim::config::{self, LoadOptions, ScenarioConfig};
use sim::vehicle_bridge::Simulation;

fn example(name: &str) -> String {
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "..", "..", "examples", name]
        .iter()
        .collect();
    std::fs::read_to_string(path).unwrap()
}

/// The example with the first line `key = …` replaced by `key = value`.
fn with(text: &str, key: &str, value: &str) -> String {
    let mut done = false;
    let lines: Vec<String> = text
        .lines()
        .map(|l| {
            if !done && l.trim_start().starts_with(&format!("{key} =")) {
                done = true;
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect();
    assert!(done, "no `{key}` in the example");
    lines.join("\n")
}

/// The reader's error, or the error of `Simulation::new` if the reader accepts.
fn error(text: &str) -> String {
    match config::load(text, Path::new("."), &LoadOptions::default()) {
        Err(e) => e.to_string(),
        Ok(ScenarioConfig::VehicleBridge(v)) => match Simulation::new(v.scenario) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("accepted"),
        },
        Ok(_) => panic!("not a vehicle_bridge scenario"),
    }
}

#[test]
fn a_wheel_radius_too_small_for_its_load_is_refused() {
    // Fuzz case 1324: wheel_radius = 1e-7 m under a 62 kN wheel put the BEM grid outside the
    // wheel circle (NaN gap). The Hertz approach is 2.3e-4 m there, 2.3e5 × the limit 1e-9 m.
    let e = error(&with(
        &example("vehicle_bridge_default.toml"),
        "wheel_radius",
        "1e-7",
    ));
    assert!(e.contains("`contact.wheel_radius` = 1e-7"), "{e}");
    assert!(e.contains("half-space contact does not apply"), "{e}");
    // A small real wheel under the same load is accepted.
    let ok = with(
        &example("vehicle_bridge_default.toml"),
        "wheel_radius",
        "0.2",
    );
    assert!(config::load(&ok, Path::new("."), &LoadOptions::default()).is_ok());
}

#[test]
fn a_tiny_positive_vehicle_mass_is_refused() {
    // Fuzz case 243: body_mass = 1e-300 kg gave "singular iteration matrix at t = 0".
    let e = error(&with(
        &example("vehicle_bridge_radau5.toml"),
        "body_mass",
        "1e-300",
    ));
    assert!(
        e.contains("`vehicle.wheels[0].body_mass` = 1e-300: must be 0 or lie in [0.001, "),
        "{e}"
    );
}

#[test]
fn a_name_is_printed_as_text_not_nan() {
    // Radau5 with rigid contact printed `contact.model = NaN`.
    let text = with(&example("vehicle_bridge_radau5.toml"), "model", "\"rigid\"");
    let e = error(&text);
    assert!(e.contains("`contact.model` = \"rigid\""), "{e}");
    assert!(!e.contains("NaN"), "{e}");
}

/// A corrugation without `start` runs everywhere with the phase of one starting at x = 0,
/// r = a sin(2πx/λ) (it was a constant: a start at −1e300 rounded x away): on the approach, on
/// the span and far along it, its height equals the closed form to 1e-6 of the amplitude (the
/// default start lies about 1e7 m before x = 0, so x − x₀ keeps x to ~2e-9 m).
#[test]
fn a_corrugation_without_start_has_its_phase_at_x_zero() {
    let default = example("vehicle_bridge_default.toml");
    let (head, rest) = default.split_once("[irregularity]").unwrap();
    let (_, tail) = rest.split_once("[integrator]").unwrap();
    let text = format!(
        "{head}[irregularity]\nkind = \"corrugation\"\namplitude = 5e-6\nwavelength = 0.04\n[integrator]{tail}"
    );
    let irregularity = match config::load(&text, Path::new("."), &LoadOptions::default()) {
        Ok(ScenarioConfig::VehicleBridge(v)) => v.scenario.irregularity,
        Ok(_) => panic!("not a vehicle_bridge scenario"),
        Err(e) => panic!("{e}"),
    };
    for x in [-12.345, -0.01, 0.0, 0.013, 3.21, 12.5, 24.999, 1234.5678] {
        let expected = 5e-6 * (std::f64::consts::TAU * x / 0.04).sin();
        let got = irregularity.height(x);
        assert!(
            (got - expected).abs() <= 1e-6 * 5e-6,
            "x = {x}: {got} vs {expected}"
        );
    }
}

#[test]
fn the_default_output_point_is_never_a_support() {
    // A continuous FE bridge whose middle is a support (spans of 10, 5 and 15 m on 30 m): the
    // deck does not move there, so the default output point is the midspan of the longest
    // span (22.5 m), with a note; the bridge's middle when it is not a support (spans 12 and
    // 18 m); a given point is kept as given.
    let scenario = |supports: &str, output: &str| {
        let text = format!(
            "kind = \"vehicle_bridge\"\n[bridge]\nlength = 30.0\nEI = 8.323e9\nmass_per_length = 2303.0\nelements = 60\nsupports_at = {supports}\nmodes = 6\n[vehicle]\nspeed = 20.0\n[[vehicle.wheels]]\nposition = 0.0\nwheel_mass = 600.0\n{output}"
        );
        match config::load(&text, Path::new("."), &LoadOptions::default()) {
            Ok(ScenarioConfig::VehicleBridge(c)) => *c,
            Ok(_) => panic!("not a vehicle_bridge scenario"),
            Err(e) => panic!("{e}"),
        }
    };
    let c = scenario("[0.0, 10.0, 15.0, 30.0]", "");
    assert_eq!(c.scenario.output_point, 22.5);
    assert!(
        c.warnings.iter().any(|w| w.contains("longest span")),
        "{:?}",
        c.warnings
    );
    let c = scenario("[0.0, 12.0, 30.0]", "");
    assert_eq!(c.scenario.output_point, 15.0);
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    let c = scenario("[0.0, 10.0, 15.0, 30.0]", "[output]\npoint = 15.0\n");
    assert_eq!(c.scenario.output_point, 15.0);
}

#[test]
fn the_series_memory_check_counts_the_recorded_columns() {
    // The recorded time series is refused when it would exceed the memory limit, estimated
    // from the columns really written (t, the bridge, per wheel; before 2026-11-27 a rough
    // 5 + 12 values per wheel, which refused runs that fit). Two Manchester cars: 8 wheels,
    // 2 car bodies.
    let layout = sim::vehicle_bridge_series::SeriesLayout {
        wheels: 8,
        car_bodies: 2,
        ..Default::default()
    };
    assert_eq!(layout.width(), 5 + 9 * 8 + 2 * 2);
    let width = layout.width() as f64;
    let limit_rows = sim::config::checks::MAX_MEMORY_BYTES / (8.0 * width);
    for (factor, accepted) in [(0.97, true), (1.03, false)] {
        let duration = factor * limit_rows * 1e-4;
        let text = format!(
            "{}\nduration = {duration}\n[output]\nevery = 1\n",
            example("train_bridge.toml")
        );
        let result = config::load(&text, Path::new("."), &LoadOptions::default());
        match (accepted, result) {
            (true, Ok(_)) => {}
            (false, Err(e)) => {
                let e = e.to_string();
                assert!(e.contains("recorded time series (output.every)"), "{e}");
            }
            (true, Err(e)) => panic!("refused at {factor} of the limit: {e}"),
            (false, Ok(_)) => panic!("accepted at {factor} of the limit"),
        }
    }
}
