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
    if [
        "run",
        "creep-curve",
        "sweep",
        "contact",
        "modes",
        "profile-sweep",
    ]
    .contains(&args[0])
    {
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

/// The wheel–rail example (docs/profiles.md, "Example"): the centred S1002/60E1 wheelset at
/// 100 kN per wheel, and its profile sweep's conicity at 3 mm.
#[test]
fn wheel_rail_example_matches_docs_profiles() {
    let docs = "docs/profiles.md (example)";
    check(
        "wheel_rail_s1002_60e1.toml",
        &["contact"],
        &[
            q("delta_r", 0.0, 1e-12),
            q("right/rolling_radius", 459.907e-3, 0.001e-3),
            q("right/contact_angle", 0.024356, 0.000001),
            q("right/wheel_s", 3.226e-3, 0.001e-3),
            q("right/rail_y", 0.192e-3, 0.001e-3),
            n("right/candidates", 2.0),
            q("right/vertical_approach", 74.98e-6, 0.01e-6),
            q("right/lateral_force", -2436.1, 0.1),
            q("right/patches/0/max_pressure", 980.7e6, 0.1e6),
            q("right/patches/0/half_length", 5.31e-3, 0.01e-3),
            q("right/patches/0/half_width", 10.39e-3, 0.01e-3),
            q("left/lateral_force", -2436.1, 0.1),
        ],
        docs,
    );
    check(
        "wheel_rail_s1002_60e1.toml",
        &[
            "profile-sweep",
            "--from",
            "-0.006",
            "--to",
            "0.006",
            "--step",
            "0.003",
            "--amplitudes",
            "0.003",
        ],
        &[
            q("conicity_3mm", 0.1785, 0.0001),
            q("points/3/delta_r", 0.9587e-3, 0.0001e-3),
            q("points/4/delta_r", 4.6609e-3, 0.0001e-3),
            q("points/4/right_contact_angle", 0.42120, 0.00001),
        ],
        docs,
    );
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
    assert_eq!(files.len(), 22, "{files:?}");
    let missing: Vec<&String> = files
        .iter()
        .filter(|f| !this.contains(&format!("\"{f}\"")))
        .collect();
    assert!(
        missing.is_empty(),
        "examples without a golden test: {missing:?}"
    );
}

/// Every example names its `kind`, so `dyncontact run FILE` accepts each of them (the contact
/// cases, tangential ones included, also run with `dyncontact contact`).
#[test]
fn every_example_names_its_kind() {
    let kinds = [
        "ball_drop",
        "contact",
        "moving_load",
        "sweep",
        "vehicle_bridge",
    ];
    for entry in std::fs::read_dir(example("")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let table: toml::Table = toml::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let kind = table.get("kind").and_then(|k| k.as_str());
        assert!(
            kind.is_some_and(|k| kinds.contains(&k)),
            "{}: kind = {kind:?}",
            path.display()
        );
    }
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
        &[
            n("iterations", 13.0),
            q("normal_force", 26.8, 0.1),
            n("elements_in_contact", 244.0),
        ],
        readme,
    );
    // "one patch, 0.125 mm × 0.4 mm": the loaded elements form one 4-connected region
    // spanning 10 × 32 elements of 12.5 µm.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = dyncontact(&[
        "contact",
        example("wavy_table.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let text = std::fs::read_to_string(out.join("pressure.csv")).unwrap();
    let h = 12.5e-6;
    let cell = |x: f64| ((x + 0.4e-3) / h - 0.5).round() as usize;
    let loaded: BTreeSet<(usize, usize)> = text
        .lines()
        .skip(1)
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').map(|s| s.parse().unwrap()).collect();
            (v[2] > 0.0).then(|| (cell(v[0]), cell(v[1])))
        })
        .collect();
    let mut seen = BTreeSet::new();
    let mut stack = vec![*loaded.iter().next().unwrap()];
    while let Some((i, j)) = stack.pop() {
        if !loaded.contains(&(i, j)) || !seen.insert((i, j)) {
            continue;
        }
        stack.extend([
            (i + 1, j),
            (i.wrapping_sub(1), j),
            (i, j + 1),
            (i, j.wrapping_sub(1)),
        ]);
    }
    assert_eq!(seen.len(), loaded.len(), "the patch is not one region");
    let span = |f: fn(&(usize, usize)) -> usize| {
        loaded.iter().map(f).max().unwrap() - loaded.iter().map(f).min().unwrap() + 1
    };
    assert_eq!(
        (span(|c| c.0), span(|c| c.1)),
        (10, 32),
        "extent in elements"
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
            q("tangential_force_y", 0.0, 0.0),
            q("creepage_x", -2.4e-4, 1e-10),
            n("adhesion_elements", 30.0),
            n("slip_elements", 21.0),
            q("frictional_power", 1.588420, 0.000001),
            n("tangential_iterations", 323.0),
            n("newton_iterations", 0.0),
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
            q("frictional_power", 2.749637e-6, 0.000001e-6),
            n("tangential_iterations", 188.0),
            n("newton_iterations", 3.0),
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
            q("frictional_power", 18.06, 0.01),
        ],
        docs,
    );
    // docs/tangential.md, the creep-curve table (9 points): F_x/(μF_n) of the exact solver,
    // FASTSIM and the linear theory, adhesion/slip elements and sweeps per point.
    let mu_fn = 0.3 * 106.7e3;
    let table: [(f64, f64, f64, f64, f64); 9] = [
        (0.00000, 0.00000, -0.00000, 1396.0, 0.0),
        (-0.34540, -0.35986, -0.38003, 1114.0, 45.0),
        (-0.60901, -0.62361, -0.76007, 836.0, 40.0),
        (-0.79753, -0.78214, -1.14010, 574.0, 35.0),
        (-0.91806, -0.87028, -1.52013, 334.0, 29.0),
        (-0.98066, -0.91945, -1.90017, 148.0, 25.0),
        (-0.99870, -0.94775, -2.28020, 10.0, 19.0),
        (-0.99920, -0.96458, -2.66023, 0.0, 15.0),
        (-0.99938, -0.97535, -3.04027, 0.0, 13.0),
    ];
    let pointers: Vec<[String; 6]> = (0..9)
        .map(|k| {
            [
                "exact_force_x",
                "fastsim_force_x",
                "linear_force_x",
                "exact_adhesion_elements",
                "exact_slip_elements",
                "exact_sweeps",
            ]
            .map(|key| format!("points/{k}/{key}"))
        })
        .collect();
    let mut quotes = Vec::new();
    for (k, &(exact, fastsim, linear, adhesion, sweeps)) in table.iter().enumerate() {
        let p = &pointers[k];
        // Forces are quoted as F/(μF_n) to 5 decimals: one unit of the last digit times μF_n.
        let unit = 1e-5 * mu_fn;
        quotes.push(q(leak(&p[0]), exact * mu_fn, unit));
        quotes.push(q(leak(&p[1]), fastsim * mu_fn, unit));
        quotes.push(q(leak(&p[2]), linear * mu_fn, unit));
        quotes.push(n(leak(&p[3]), adhesion));
        quotes.push(n(leak(&p[4]), 1396.0 - adhesion));
        quotes.push(n(leak(&p[5]), sweeps));
    }
    check(
        "tangential_rolling.toml",
        &["creep-curve", "--creepage-x", "0:0.004:9"],
        &quotes,
        "docs/tangential.md (creep-curve table)",
    );
}

/// A pointer built at run time, as the `&'static str` of a [`Quote`].
fn leak(s: &str) -> &'static str {
    Box::leak(s.to_string().into_boxed_str())
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
    // docs/ball_drop.md: `--integrator verlet` on the steel example.
    check(
        "ball_drop_steel.toml",
        &["run", "--integrator", "verlet"],
        &[
            q("impacts/3/time", 0.99964, 0.00001),
            q("impacts/0/peak_force", 3462.4, 0.1),
            q("restitution", 1.00001, 0.00001),
            q("energy_drift", 2.2e-5, 0.1e-5),
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

/// docs/trains.md: the AVE S-103 preset as moving forces over a 25 m span.
#[test]
fn preset_train_example_matches_the_docs() {
    check(
        "ice3_bridge.toml",
        &["run"],
        &[
            n("axles", 32.0),
            q("exit_time", 2.6196, 0.0001),
            q("static_midspan_deflection", 20.720e-3, 0.001e-3),
            q("max_midspan_deflection", 26.801e-3, 0.001e-3),
            q("dynamic_amplification", 1.2935, 0.0001),
            q("max_midspan_acceleration", 9.044, 0.001),
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

/// docs/sweep.md: the interaction sweep of two real trains' vehicle models.
#[test]
fn interaction_sweep_example_matches_the_docs() {
    check(
        "sweep_interaction.toml",
        &["sweep"],
        &[
            n("runs", 6.0),
            q("trains/0/max_acceleration", 4.560, 0.001),
            q("trains/0/dynamic_factor", 2.245, 0.001),
            q("trains/1/max_acceleration", 10.996, 0.001),
            q("trains/1/max_deflection", 12.319e-3, 0.001e-3),
            q("trains/1/dynamic_factor", 5.196, 0.001),
            q("checks/governing_speed", 90.0, 1e-9),
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
            n("solver/max_iterations_per_step", 2.0),
            q("solver/mean_contact_iterations_per_step", 4.41, 0.01),
            n("contact/loss_of_contact_events", 0.0),
        ],
        docs,
    );
    // "The patch is 13.0 mm long and 9.8 mm wide at the start (static load), peak pressure
    // 1055 MPa": the first row of timeseries.csv.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = dyncontact(&[
        "run",
        example("vehicle_bridge_default.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let csv = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let first: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let col = |name: &str| first[header.iter().position(|h| *h == name).unwrap()];
    assert!(
        (1e3 * col("patch_length_m") - 13.0).abs() <= 0.05,
        "{}",
        col("patch_length_m")
    );
    assert!(
        (1e3 * col("patch_width_m") - 9.8).abs() <= 0.05,
        "{}",
        col("patch_width_m")
    );
    assert!(
        (1e-6 * col("max_pressure_pa") - 1055.0).abs() <= 0.5,
        "{}",
        col("max_pressure_pa")
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
            // The prescribed creepage fixes the rotation: ω = V(1 − ξ)/R = 30 × 0.998/0.46.
            q(
                "traction/final_angular_velocity/0",
                30.0 * 0.998 / 0.46,
                1e-9,
            ),
        ],
        docs,
    );
}
