//! Golden outputs of every example in `examples/`: each example is run through the binary and
//! its key numbers are compared with the values README.md and docs/*.md quote for it.
//!
//! Tolerance rule: a quoted number is rounded, so it is compared to within one unit in its last
//! quoted digit (`q(value, unit)`); counts (iterations, impacts, elements, steps) exactly.
//! Where the docs quote a full-precision value (docs/ball_drop.md's summary.json) the tolerance
//! is 1e-7 relative, far below the physics tolerances and above the round-off differences
//! between build profiles. A test in this file that fails means the docs no longer describe
//! the program's output: fix whichever is wrong.

mod support;

use std::collections::BTreeSet;

use support::{PLOT_REPORT_ENV, check_plot_report, dyncontact, dyncontact_env, example, num};

/// One quoted number: JSON pointer, quoted value, allowed absolute deviation, where quoted.
struct Quote {
    pointer: &'static str,
    value: f64,
    tol: f64,
}

/// A number quoted to the digit of `unit`: tolerance one unit.
const fn q(pointer: &'static str, value: f64, unit: f64) -> Quote {
    Quote {
        pointer,
        value,
        tol: unit,
    }
}

/// A count quoted exactly.
const fn n(pointer: &'static str, value: f64) -> Quote {
    Quote {
        pointer,
        value,
        tol: 0.0,
    }
}

/// A full-precision value: 1e-7 relative.
fn full(pointer: &'static str, value: f64) -> Quote {
    Quote {
        pointer,
        value,
        tol: 1e-7 * value.abs(),
    }
}

/// Run `examples/FILE` with `args` (the file is inserted after the first argument), `--json`
/// and an output directory, check every quote, and check every plot it drew
/// (`support::check_plot_report`: data inside the axes, legends with drawn lines, equal
/// scales of maps, ...).
fn check(file: &str, args: &[&str], quotes: &[Quote], source: &str) {
    let dir = tempfile::tempdir().unwrap();
    let path = example(file);
    let out_dir = dir.path().join("out");
    let mut argv: Vec<&str> = vec![args[0], path.to_str().unwrap()];
    argv.extend_from_slice(&args[1..]);
    if ["run", "creep-curve", "sweep", "contact", "modes"].contains(&args[0]) {
        argv.extend(["--out", out_dir.to_str().unwrap()]);
    }
    argv.push("--json");
    let report = dir.path().join("plots.jsonl");
    let o = dyncontact_env(&argv, &[(PLOT_REPORT_ENV, report.as_os_str())]);
    assert!(
        o.status.success(),
        "{file}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let mut failures = Vec::new();
    for quote in quotes {
        let got = num(&v, quote.pointer);
        if (got - quote.value).abs() > quote.tol {
            failures.push(format!(
                "{}: got {got:e}, {source} quotes {:e} (± {:e})",
                quote.pointer, quote.value, quote.tol
            ));
        }
    }
    assert!(failures.is_empty(), "{file}:\n{}", failures.join("\n"));
    let figures = check_plot_report(&report, &out_dir, file);
    assert!(figures > 0, "{file}: no plot drawn");
}

/// Every example file is checked by a test in this file (a new example needs its golden).
#[test]
fn every_example_has_a_golden_test() {
    let this = include_str!("examples_golden.rs");
    let dir = example("");
    let files: BTreeSet<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    assert_eq!(files.len(), 19, "{files:?}");
    let missing: Vec<&String> = files
        .iter()
        .filter(|f| !this.contains(&format!("\"{f}\"")))
        .collect();
    assert!(
        missing.is_empty(),
        "examples without a golden test: {missing:?}"
    );
}

/// The built-in default of `dyncontact run` is the example file itself (one copy).
#[test]
fn the_default_scenario_is_the_example() {
    let o = dyncontact(&["run", "--out", "/nonexistent-parent/out"]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("examples/vehicle_bridge_default.toml"),
        "the default names its source: {e}"
    );
    assert!(
        !std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenarios/default.toml")
            .exists(),
        "a second copy of the default scenario"
    );
}

/// README.md, "Examples" table of `dyncontact contact`.
#[test]
fn contact_examples_match_the_readme_table() {
    let readme = "README.md (contact examples table)";
    check(
        "hertz_sphere.toml",
        &["contact"],
        &[
            n("iterations", 9.0),
            q("approach", 16.168e-6, 0.001e-6),
            q("max_pressure", 2.9535e9, 0.0001e9),
            q("dfn_dapproach", 9.28e7, 0.01e7),
        ],
        readme,
    );
    check(
        "hertz_ellipse.toml",
        &["contact"],
        &[
            n("iterations", 11.0),
            q("approach", 76.507e-6, 0.001e-6),
            q("max_pressure", 640.7e6, 0.1e6),
        ],
        readme,
    );
    check(
        "rounded_punch.toml",
        &["contact"],
        &[
            n("iterations", 12.0),
            q("approach", 6.21e-6, 0.01e-6),
            q("max_pressure", 503e6, 1e6),
        ],
        readme,
    );
    check(
        "wavy_table.toml",
        &["contact"],
        &[n("iterations", 13.0), q("normal_force", 26.8, 0.1)],
        readme,
    );
}

/// docs/tangential.md, "Worked examples (real output)".
#[test]
fn tangential_examples_match_the_docs() {
    let docs = "docs/tangential.md";
    check(
        "tangential_carter.toml",
        &["contact"],
        &[
            q("tangential_force_x", 6.960208e3, 0.000001e3),
            n("adhesion_elements", 30.0),
            n("slip_elements", 21.0),
        ],
        docs,
    );
    check(
        "tangential_cattaneo.toml",
        &["contact"],
        &[
            q("tangential_force_x", -3.218390, 0.000001),
            q("shift_x", 8.154887e-6, 0.000001e-6),
            n("adhesion_elements", 45.0),
            n("slip_elements", 132.0),
        ],
        docs,
    );
    check(
        "tangential_rolling.toml",
        &["contact"],
        &[
            q("tangential_force_x", -1.949442e4, 0.000001e4),
            n("adhesion_elements", 836.0),
            n("slip_elements", 560.0),
            n("tangential_iterations", 41.0),
        ],
        docs,
    );
}

/// docs/ball_drop.md, "Worked example".
#[test]
fn ball_drop_examples_match_the_docs() {
    let docs = "docs/ball_drop.md";
    check(
        "ball_drop_steel.toml",
        &["run"],
        &[
            full("impacts/0/time", 0.14278431229269725),
            full("impacts/0/impact_velocity", 1.400714468798393),
            full("impacts/0/max_approach", 2.330348287234115e-5),
            full("impacts/0/peak_force", 3461.3689254418855),
            full("impacts/0/contact_duration", 4.8964415471947076e-5),
            full("impacts/0/rebound_velocity", 1.400714827807307),
            q("impacts/3/time", 0.99963733, 0.00000001),
            q("restitution", 1.00000014, 0.00000001),
            n("integrator/steps", 306.0),
            n("integrator/rejected_steps", 102.0),
            n("integrator/f_evals", 2545.0),
        ],
        docs,
    );
    check(
        "ball_drop_bem.toml",
        &["run"],
        &[
            q("impacts/0/max_approach", 2.330015e-5, 0.000001e-5),
            q("impacts/0/peak_force", 3.461131e3, 0.000001e3),
            q("impacts/0/contact_duration", 4.896134e-5, 0.000001e-5),
            q("restitution", 1.0000024, 0.0000001),
            n("integrator/f_evals", 533.0),
            n("integrator/contact_solves", 396.0),
        ],
        docs,
    );
    check(
        "ball_drop_damped_ellipsoid.toml",
        &["run"],
        &[
            q("impacts/0/restitution", 0.98049, 0.00001),
            q("impacts/1/restitution", 0.98042, 0.00001),
            q("energy_drift", 5.5e-8, 0.1e-8),
        ],
        docs,
    );
}

/// docs/bridge.md: the modal table of Frýba's bridge and its moving-force run; the two-span
/// train's numbers as docs/bridge.md quotes them.
#[test]
fn bridge_examples_match_the_docs() {
    let docs = "docs/bridge.md";
    check(
        "moving_load_fryba.toml",
        &["modes"],
        &[
            q("modes/0/omega", 30.020140, 0.000001),
            q("modes/1/omega", 120.080558, 0.000001),
            q("modes/2/omega", 270.181256, 0.000001),
            q("modes/0/frequency", 4.777854, 0.000001),
        ],
        docs,
    );
    check(
        "moving_load_fryba.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 2.3966e-3, 0.0001e-3),
            q("static_midspan_deflection", 2.2058e-3, 0.0001e-3),
            q("dynamic_amplification", 1.0865, 0.0001),
            q("max_midspan_acceleration", 0.439, 0.001),
            q("simulated_time_s", 1.53, 0.01),
        ],
        docs,
    );
    check(
        "moving_load_two_span_train.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 4.1093e-3, 0.0001e-3),
            q("static_midspan_deflection", 4.0103e-3, 0.0001e-3),
            q("dynamic_amplification", 1.0247, 0.0001),
            q("max_midspan_acceleration", 6.819, 0.001),
        ],
        docs,
    );
}

/// docs/trains.md: two bogie vehicles over a 25 m span.
#[test]
fn train_example_matches_the_docs() {
    check(
        "train_bridge.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 17.378e-3, 0.001e-3),
            q("dynamic_amplification", 1.1207, 0.0001),
            q("contact/max_force", 224.1e3, 0.1e3),
            q("vehicle/max_body_acceleration", 0.441, 0.001),
            q("vehicle/static_wheel_loads/0", 109.09e3, 0.01e3),
            n("contact/loss_of_contact_events", 0.0),
            q("contact/max_unloading_ratio", 0.764, 0.001),
            n("train/axles", 8.0),
            q("train/length", 46.56, 0.01),
            q("train/mass", 88964.0, 1.0),
            q("vehicles/1/max_body_acceleration", 0.441, 0.001),
            q("vehicles/0/max_bogie_acceleration", 2.112, 0.001),
            q("comfort/max_body_acceleration", 0.441, 0.001),
        ],
        "docs/trains.md",
    );
}

/// docs/sweep.md: the HSLM-A sweep over a 20 m prestressed-concrete span.
#[test]
fn sweep_example_matches_the_docs() {
    check(
        "sweep_hslm.toml",
        &["sweep"],
        &[
            n("runs", 570.0),
            n("modes", 3.0),
            q("damping_ratio", 0.012965, 0.000001),
            q("checks/max_acceleration", 41.80, 0.01),
            q("checks/governing_speed", 115.28, 0.01),
            q("checks/first_frequency", 5.000, 0.001),
            q("trains/0/max_acceleration", 28.99, 0.01),
            q("trains/0/speed_at_max_acceleration", 90.28, 0.01),
            q("trains/0/dynamic_factor", 6.569, 0.001),
            q("trains/9/max_acceleration", 13.71, 0.01),
        ],
        "docs/sweep.md",
    );
}

/// docs/vehicle_bridge.md: the default scenario, Biggs, Radau5, the two-span bogie and
/// docs/vehicle_bridge.md's braking example.
#[test]
fn vehicle_bridge_examples_match_the_docs() {
    let docs = "docs/vehicle_bridge.md";
    check(
        "vehicle_bridge_default.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 2.5949e-3, 0.0001e-3),
            q("max_midspan_acceleration", 0.3680, 0.0001),
            q("dynamic_amplification", 1.0651, 0.0001),
            q("contact/min_force", 56777.2, 0.1),
            q("contact/max_force", 67893.6, 0.1),
            q("contact/max_pressure", 1086.4e6, 0.1e6),
            q("vehicle/max_body_acceleration", 0.9095, 0.0001),
            n("solver/steps", 3334.0),
            n("solver/failed_steps", 0.0),
            q("solver/mean_iterations_per_step", 1.01, 0.01),
            q("solver/mean_contact_iterations_per_step", 4.41, 0.01),
        ],
        docs,
    );
    check(
        "vehicle_bridge_biggs.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 2.3840e-3, 0.0001e-3),
            q("max_quasi_static_deflection", 2.1742e-3, 0.0001e-3),
            q("dynamic_amplification", 1.0965, 0.0001),
            q("vehicle/max_body_acceleration", 0.1836, 0.0001),
            q("simulated_time_s", 0.900, 0.001),
        ],
        docs,
    );
    check(
        "vehicle_bridge_radau5.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 2.5976e-3, 0.0001e-3),
            q("dynamic_amplification", 1.0664, 0.0001),
            q("contact/min_force", 46307.8, 0.1),
            q("contact/max_force", 72182.0, 0.1),
            q("vehicle/max_body_acceleration", 0.2550, 0.0001),
            n("solver/steps", 12728.0),
            q("solver/mean_iterations_per_step", 1.65, 0.01),
        ],
        docs,
    );
    check(
        "vehicle_bridge_two_span_flat.toml",
        &["run"],
        &[
            q("simulated_time_s", 1.417, 0.001),
            q("solver/mean_iterations_per_step", 2.23, 0.01),
            n("solver/max_iterations_per_step", 4.0),
            q("contact/min_force", 0.0, 0.5),
            q("contact/max_force", 419.5e3, 0.1e3),
            n("contact/loss_of_contact_events", 161.0),
            n("solver/failed_steps", 0.0),
        ],
        docs,
    );
    check(
        "vehicle_bridge_braking.toml",
        &["run"],
        &[
            q("contact/min_force", 56777.2, 0.1),
            q("contact/max_force", 67893.6, 0.1),
            q("contact/max_pressure", 1086.4e6, 0.1e6),
            q("traction/max_longitudinal_force", -15621.9, 0.1),
            q("traction/mean_longitudinal_force", -14542.3, 0.1),
            n("traction/saturated_steps", 0.0),
        ],
        docs,
    );
}
