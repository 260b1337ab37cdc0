//! `[train]` tables (`sim::config::train`): one train description serving the moving-force
//! model (`moving_load`, `sweep` train files) and, for quarter cars and sprung masses, the
//! coupled `vehicle_bridge` model; each checked against the same case written the old way.

use std::path::Path;

use sim::config::{self, ConfigError, LoadOptions, ScenarioConfig};

fn load(text: &str, base: &Path) -> Result<ScenarioConfig, ConfigError> {
    config::load(text, base, &LoadOptions::default())
}

const BRIDGE: &str = "[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 6\ndamping_ratio = 0.02\n";

/// The Manchester benchmark car (references.md §T4) with a 25 m length, twice.
const MANCHESTER: &str = "[train]\nname = \"two cars\"\nspeed = 50.0\n[[train.vehicles]]\ntype = \"bogie_vehicle\"\ncount = 2\nlength = 25.0\nbody_mass = 32000.0\nbody_pitch_inertia = 1.97e6\nbogie_spacing = 19.0\nbogie_mass = 2615.0\nbogie_pitch_inertia = 1476.0\nwheelbase = 2.56\nwheelset_mass = 1813.0\nprimary_stiffness = 2.4e6\nprimary_damping = 8.0e3\nsecondary_stiffness = 8.6e5\nsecondary_damping = 4.0e4\n";

fn moving_load(text: &str) -> sim::config::moving_load::MovingLoadConfig {
    match load(text, Path::new(".")).unwrap_or_else(|e| panic!("{e}")) {
        ScenarioConfig::MovingLoad(m) => *m,
        _ => panic!("not moving_load"),
    }
}

#[test]
fn a_train_of_bogie_vehicles_is_its_static_axle_loads() {
    let from_train = moving_load(&format!("kind = \"moving_load\"\n{BRIDGE}{MANCHESTER}"));
    // The same axles by hand: (32,000/4 + 2,615/2 + 1,813) × 9.81 N at 0, 2.56, 19, 21.56 m
    // and 25 m further on.
    let p = (32000.0 / 4.0 + 2615.0 / 2.0 + 1813.0) * 9.81;
    let axles: Vec<String> = [0.0, 2.56, 19.0, 21.56, 25.0, 27.56, 44.0, 46.56]
        .iter()
        .map(|x| format!("[{x:?}, {p:?}]"))
        .collect();
    let by_hand = moving_load(&format!(
        "kind = \"moving_load\"\n{BRIDGE}[load]\nspeed = 50.0\naxles = [{}]\n",
        axles.join(", ")
    ));
    assert_eq!(from_train.loads.axles().len(), 8);
    for (a, b) in from_train.loads.axles().iter().zip(by_hand.loads.axles()) {
        assert!((a.offset - b.offset).abs() < 1e-12 && (a.force - b.force).abs() < 1e-9);
    }
    let run = |m: &sim::config::moving_load::MovingLoadConfig| {
        beam::simulate_moving_loads(
            m.bridge.basis.as_ref(),
            &m.bridge.damping,
            &m.loads,
            &m.settings,
            &m.points,
        )
        .unwrap()
    };
    let (a, b) = (run(&from_train), run(&by_hand));
    let (da, db) = (
        a.max_abs_deflection(0).unwrap(),
        b.max_abs_deflection(0).unwrap(),
    );
    assert!((da / db - 1.0).abs() < 1e-12, "{da} vs {db}");
}

#[test]
fn a_quarter_car_train_drives_the_coupled_model() {
    let train = "[train]\nspeed = 30.0\nposition = 0.0\n[[train.vehicles]]\ntype = \"quarter_car\"\ncount = 2\nlength = 12.0\nwheel_mass = 600.0\nbody_mass = 5750.0\nsuspension_stiffness = 1.595e6\nsuspension_damping = 2.0e4\n";
    let wheels = "[vehicle]\nspeed = 30.0\n[[vehicle.wheels]]\nposition = 0.0\nwheel_mass = 600.0\nbody_mass = 5750.0\nsuspension_stiffness = 1.595e6\nsuspension_damping = 2.0e4\n[[vehicle.wheels]]\nposition = -12.0\nwheel_mass = 600.0\nbody_mass = 5750.0\nsuspension_stiffness = 1.595e6\nsuspension_damping = 2.0e4\n";
    let tail = "[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"generalized_alpha\"\nduration = 0.2\n";
    let summary = |text: String| match load(&text, Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
    {
        ScenarioConfig::VehicleBridge(v) => {
            let mut sim =
                sim::vehicle_bridge::Simulation::with_vehicles(v.scenario, v.vehicles).unwrap();
            sim.run(|_| {}).unwrap()
        }
        _ => panic!("not vehicle_bridge"),
    };
    let a = summary(format!("kind = \"vehicle_bridge\"\n{BRIDGE}{train}{tail}"));
    let b = summary(format!("kind = \"vehicle_bridge\"\n{BRIDGE}{wheels}{tail}"));
    assert_eq!(a.max_force(), b.max_force());
    assert_eq!(a.deflection.max_abs(), b.deflection.max_abs());
}

#[test]
fn a_train_of_moving_forces_only_is_refused_by_the_coupled_model_with_the_remedy() {
    let forces = "[train]\nspeed = 50.0\n[[train.vehicles]]\ntype = \"moving_forces\"\nlength = 20.0\naxle_positions = [0.0, 3.0]\naxle_loads = [1.0e5, 1.0e5]\n";
    let e = load(
        &format!("kind = \"vehicle_bridge\"\n{BRIDGE}{forces}"),
        Path::new("."),
    )
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.contains("moving_forces") && e.contains("moving_load"),
        "{e}"
    );
}

#[test]
fn bad_train_tables_name_the_key() {
    let cases = [
        (
            MANCHESTER.replace("wheelbase = 2.56\n", ""),
            "needs `wheelbase`",
        ),
        (
            MANCHESTER.replace("type = \"bogie_vehicle\"", "type = \"tram\""),
            "train.vehicles[0].type = \"tram\"",
        ),
        (
            MANCHESTER.replace("count = 2\n", "count = 2\nwheel_mass = 100.0\n"),
            "train.vehicles[0].wheel_mass does not apply",
        ),
        (
            MANCHESTER.replace("length = 25.0", "length = 10.0"),
            "`length` = 10",
        ),
        (
            MANCHESTER.replace("count = 2", "count = 0"),
            "train.vehicles[0].count",
        ),
        (
            "[train]\nspeed = 50.0\n[[train.vehicles]]\npreset = \"ICE9\"\n".to_string(),
            "preset = \"ICE9\"",
        ),
        (MANCHESTER.replace("speed = 50.0\n", ""), "missing `speed`"),
    ];
    for (train, key) in cases {
        let e = load(
            &format!("kind = \"moving_load\"\n{BRIDGE}{train}"),
            Path::new("."),
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
        assert!(e.contains(key), "{key}: {e}");
    }
}

#[test]
fn a_sweep_reads_train_files() {
    let dir = tempfile_dir();
    std::fs::write(dir.join("cars.toml"), MANCHESTER).unwrap();
    let sweep = |trains: &str| {
        format!("kind = \"sweep\"\n{BRIDGE}[trains]\n{trains}\n[speeds]\nlist = [40.0, 60.0]\n")
    };
    let p = (32000.0 / 4.0 + 2615.0 / 2.0 + 1813.0) * 9.81;
    let run = |text: String| match load(&text, &dir).unwrap_or_else(|e| panic!("{e}")) {
        ScenarioConfig::Sweep(c) => sim::sweep::run(
            c.bridge.basis.as_ref(),
            &c.bridge.damping,
            &c.spec,
            sim::sweep::Shard::ALL,
            &|| true,
        )
        .unwrap(),
        _ => panic!("not a sweep"),
    };
    let from_file = run(sweep("files = [\"cars.toml\"]"));
    let by_hand = run(sweep(&format!(
        "[[trains.train]]\nname = \"x\"\naxle_positions = [0.0, 2.56, 19.0, 21.56, 25.0, 27.56, 44.0, 46.56]\naxle_loads = [{p:?}, {p:?}, {p:?}, {p:?}, {p:?}, {p:?}, {p:?}, {p:?}]"
    )));
    for (a, b) in from_file.iter().zip(&by_hand) {
        for (x, y) in a.peaks.acceleration.iter().zip(&b.peaks.acceleration) {
            assert!((x / y - 1.0).abs() < 1e-12, "{x} vs {y}");
        }
    }
    let e = load(&sweep("files = [\"missing.toml\"]"), &dir)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("trains.files[0]"), "{e}");
}

fn tempfile_dir() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("dyncontact-train-files-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
