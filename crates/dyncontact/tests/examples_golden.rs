//! Golden outputs of every example in `examples/`: each example is run through the binary and
//! the numbers README.md and docs/*.md quote for it (and for the CLI's outputs) are compared
//! with what it prints.
//!
//! Tolerance rule: a quoted number is rounded, so the program's value must round to it: it
//! lies within half a unit of the quoted number's last digit (`q(value, unit)`), plus 1e-9
//! relative for round-off differences between build profiles; counts (iterations, impacts,
//! elements, steps) exactly. Where the docs quote a full-precision value (docs/ball_drop.md's
//! summary.json) the tolerance is 1e-7 relative, far below the physics tolerances and above
//! the round-off differences between build profiles. Quoted program output (the text blocks
//! of the docs) is compared line by line and token by token with the program's output
//! (`excerpt`), wall times excepted. A test in this file that fails means the docs no longer
//! describe the program's output: fix whichever is wrong.

mod support;

use std::collections::BTreeSet;

use support::{PLOT_REPORT_ENV, check_plot_report, dyncontact, dyncontact_env, example, num};

/// One quoted number: JSON pointer, quoted value, allowed absolute deviation, where quoted.
struct Quote {
    pointer: &'static str,
    value: f64,
    tol: f64,
}

/// A number quoted to the digit of `unit`: the value rounds to it (half a unit, plus 1e-9
/// relative for round-off between build profiles).
fn q(pointer: &'static str, value: f64, unit: f64) -> Quote {
    Quote {
        pointer,
        value,
        tol: 0.5 * unit + 1e-9 * value.abs(),
    }
}

/// `got` rounds to `quoted` at the digit of `unit` (the rule of [`q`]), else a message.
fn near(what: &str, got: f64, quoted: f64, unit: f64) {
    assert!(
        (got - quoted).abs() <= 0.5 * unit + 1e-9 * quoted.abs(),
        "{what}: got {got:e}, the docs quote {quoted:e} (to {unit:e})"
    );
}

/// The text of README.md or a file of docs/.
fn doc(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Checks a block of program output quoted in `doc_name`: the block starts at the first line
/// that (trimmed) starts with `first` and ends before a blank line or a code fence. Every
/// line of it must appear, in order, among the lines of `output`, token by token (white space
/// folded), except the tokens listed in `wall_times` (timings, and round-off digits the docs
/// say change with the build), which may differ.
fn excerpt(doc_name: &str, first: &str, output: &str, wall_times: &[&str]) {
    excerpt_after(doc_name, "", first, output, wall_times);
}

/// [`excerpt`] for the first block starting with `first` after the first line of the doc
/// that contains `after`.
fn excerpt_after(doc_name: &str, after: &str, first: &str, output: &str, wall_times: &[&str]) {
    let text = doc(doc_name);
    let lines: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.contains(after))
        .skip_while(|l| !l.trim_start().starts_with(first))
        .take_while(|l| !l.trim().is_empty() && !l.trim_start().starts_with("```"))
        .collect();
    assert!(
        !lines.is_empty(),
        "{doc_name}: no block starting with {first:?}"
    );
    let out: Vec<Vec<&str>> = output
        .lines()
        .map(|l| l.split_whitespace().collect())
        .collect();
    let mut at = 0;
    for line in lines {
        let want: Vec<&str> = line.split_whitespace().collect();
        let same = |got: &Vec<&str>| {
            got.len() == want.len()
                && got
                    .iter()
                    .zip(&want)
                    .all(|(g, w)| g == w || wall_times.contains(w))
        };
        match out[at..].iter().position(same) {
            Some(k) => at += k + 1,
            None => panic!(
                "{doc_name}: the quoted line\n  {line}\nis not in the program's output (after line {at}):\n{output}"
            ),
        }
    }
}

/// What the binary run with `args` prints (must succeed): standard error (notes such as
/// "running the built-in default scenario", which come first), then standard output.
fn stdout_of(args: &[&str]) -> String {
    let o = dyncontact(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stderr).unwrap() + &String::from_utf8(o.stdout).unwrap()
}

/// The header and the rows of a CSV file the binary wrote.
fn csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// Runs `command` on `text` (an example modified by the test, written as `name` in `dir`)
/// with `--json` and an output directory; returns the JSON and standard error (must succeed).
fn run_text(
    dir: &std::path::Path,
    command: &str,
    name: &str,
    text: &str,
) -> (serde_json::Value, String) {
    let f = support::write(dir, name, text);
    let out = dir.join(format!("{name}.out"));
    let o = dyncontact(&[command, &f, "--json", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{name}: {stderr}");
    (serde_json::from_slice(&o.stdout).unwrap(), stderr)
}

/// The column `name` of a CSV table.
fn column(header: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let k = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows.iter().map(|r| r[k]).collect()
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
fn check(file: &str, args: &[&str], quotes: &[Quote], source: &str) -> serde_json::Value {
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
    v
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

/// The vehicle–bridge example with real profiles (docs/profiles.md, "In the vehicle–bridge
/// simulation"): the quarter car over the dip on S1002/60E1, and its first row (the static
/// start).
#[test]
fn vehicle_bridge_profiles_example_matches_docs_profiles() {
    let docs = "docs/profiles.md (vehicle–bridge example)";
    check(
        "vehicle_bridge_s1002_60e1.toml",
        &["run"],
        &[
            q("contact/min_force", 39409.9, 0.1),
            q("contact/max_force", 83285.5, 0.1),
            q("contact/max_pressure", 933.0e6, 0.1e6),
            q("max_midspan_deflection", 1.4370e-3, 0.0001e-3),
            n("solver/steps", 600.0),
            n("solver/failed_steps", 0.0),
        ],
        docs,
    );
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = dyncontact(&[
        "run",
        example("vehicle_bridge_s1002_60e1.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let (h, rows) = csv(&out.join("timeseries.csv"));
    let col = |name: &str| column(&h, &rows, name)[0];
    near("patch length [mm]", 1e3 * col("patch_length_m"), 9.99, 0.01);
    near("patch width [mm]", 1e3 * col("patch_width_m"), 19.95, 0.01);
    near(
        "peak pressure [MPa]",
        1e-6 * col("max_pressure_pa"),
        785.6,
        0.1,
    );
    near("approach [µm]", 1e6 * col("approach_m"), 53.42, 0.01);
    near("static force [N]", col("contact_force_n"), 62293.5, 1e-3);
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
    assert_eq!(files.len(), 25, "{files:?}");
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
    let v = check(
        "hertz_sphere.toml",
        &["contact"],
        &[
            n("grid/nx", 96.0),
            n("grid/ny", 96.0),
            n("iterations", 9.0),
            q("approach", 16.168e-6, 0.001e-6),
            q("hertz/approach", 16.166e-6, 0.001e-6),
            q("max_pressure", 2.9535e9, 0.0001e9),
            q("dfn_dapproach", 9.28e7, 0.01e7),
            // README, "Python": the full-precision value the package prints.
            full("max_pressure", 2953497820.696398),
        ],
        readme,
    );
    // "(Hertz 16.166, +0.009 %), p_max 2.9535 GPa (Hertz +0.001 %)".
    let rel = |a: &str, b: &str| 100.0 * (num(&v, a) / num(&v, b) - 1.0);
    near(
        "approach vs Hertz [%]",
        rel("approach", "hertz/approach"),
        0.009,
        0.001,
    );
    near(
        "p_max vs Hertz [%]",
        rel("max_pressure", "hertz/max_pressure"),
        0.001,
        0.001,
    );
    check(
        "hertz_ellipse.toml",
        &["contact"],
        &[
            n("grid/nx", 44.0),
            n("grid/ny", 44.0),
            n("iterations", 11.0),
            q("approach", 76.507e-6, 0.001e-6),
            q("hertz/approach", 76.517e-6, 0.001e-6),
            q("max_pressure", 640.7e6, 0.1e6),
            q("hertz/max_pressure", 641.06e6, 0.01e6),
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
            q("tangential_force_x", 6.960207e3, 0.000001e3),
            q("tangential_force_y", 0.0, 0.0),
            q("creepage_x", -2.4e-4, 1e-10),
            n("adhesion_elements", 30.0),
            n("slip_elements", 21.0),
            q("frictional_power", 1.588420, 0.000001),
            n("tangential_iterations", 9.0),
            n("newton_iterations", 0.0),
        ],
        docs,
    );
    check(
        "tangential_cattaneo.toml",
        &["contact"],
        &[
            q("tangential_force_x", -3.218390, 0.000001),
            q("shift_x", 8.154886e-6, 0.000001e-6),
            n("adhesion_elements", 45.0),
            n("slip_elements", 132.0),
            q("frictional_power", 2.749637e-6, 0.000001e-6),
            n("tangential_iterations", 188.0),
            n("newton_iterations", 3.0),
        ],
        docs,
    );
    // The quoted terminal output of the two CONTACT cases (wall times and the round-off
    // digits of F_y, the spin moment and the y shift, which the docs say change with the
    // build, excepted).
    excerpt(
        "docs/tangential.md",
        "tangential contact (rolling, exact), mu = 0.3",
        &stdout_of(&[
            "contact",
            example("tangential_carter.toml").to_str().unwrap(),
        ]),
        &["0.358"],
    );
    excerpt(
        "docs/tangential.md",
        "tangential contact (shift, exact), mu = 0.4",
        &stdout_of(&[
            "contact",
            example("tangential_cattaneo.toml").to_str().unwrap(),
        ]),
        &["57.811", "-4.089827e-7", "1.940884e-12", "1.001926e-12)"],
    );
    let v = check(
        "tangential_rolling.toml",
        &["contact"],
        &[
            q("tangential_force_x", -1.949442e4, 0.000001e4),
            n("adhesion_elements", 836.0),
            n("slip_elements", 560.0),
            n("tangential_iterations", 4.0),
            q("frictional_power", 18.06, 0.01),
        ],
        docs,
    );
    // "F_x/(μF_n) = −0.6090"; "With `method = "fastsim"` FASTSIM gives −0.624 μF_n".
    let mu_fn = 0.3 * num(&v, "normal_force");
    near(
        "F_x/(μF_n)",
        num(&v, "tangential_force_x") / mu_fn,
        -0.6090,
        0.0001,
    );
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("tangential_rolling.toml")).unwrap();
    let fastsim = text.replace("method = \"exact\"", "method = \"fastsim\"");
    assert_ne!(fastsim, text, "the example has a [kinematics] table");
    let (fv, _) = run_text(dir.path(), "contact", "fastsim.toml", &fastsim);
    near(
        "FASTSIM F_x/(μF_n)",
        num(&fv, "tangential_force_x") / mu_fn,
        -0.624,
        0.001,
    );
    // docs/tangential.md, the creep-curve table (9 points): F_x/(μF_n) of the exact solver,
    // FASTSIM and the linear theory, adhesion/slip elements and solver iterations per point.
    let mu_fn = 0.3 * 106.7e3;
    let table: [(f64, f64, f64, f64, f64); 9] = [
        (0.00000, 0.00000, -0.00000, 1396.0, 0.0),
        (-0.34540, -0.35986, -0.38003, 1114.0, 5.0),
        (-0.60901, -0.62361, -0.76007, 836.0, 7.0),
        (-0.79753, -0.78214, -1.14010, 574.0, 8.0),
        (-0.91806, -0.87028, -1.52013, 334.0, 8.0),
        (-0.98066, -0.91945, -1.90017, 148.0, 7.0),
        (-0.99870, -0.94775, -2.28020, 10.0, 7.0),
        (-0.99920, -0.96458, -2.66023, 0.0, 4.0),
        (-0.99938, -0.97535, -3.04027, 0.0, 3.0),
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
    for (k, &(exact, fastsim, linear, adhesion, iterations)) in table.iter().enumerate() {
        let p = &pointers[k];
        // Forces are quoted as F/(μF_n) to 5 decimals: one unit of the last digit times μF_n.
        let unit = 1e-5 * mu_fn;
        quotes.push(q(leak(&p[0]), exact * mu_fn, unit));
        quotes.push(q(leak(&p[1]), fastsim * mu_fn, unit));
        quotes.push(q(leak(&p[2]), linear * mu_fn, unit));
        quotes.push(n(leak(&p[3]), adhesion));
        quotes.push(n(leak(&p[4]), 1396.0 - adhesion));
        quotes.push(n(leak(&p[5]), iterations));
    }
    quotes.push(q("normal_force", 106.7e3, 0.1e3));
    check(
        "tangential_rolling.toml",
        &["creep-curve", "--creepage-x", "0:0.004:9"],
        &quotes,
        "docs/tangential.md (creep-curve table)",
    );
    // The table as printed (header with μF_n and the grid; the total time excepted).
    excerpt(
        "docs/tangential.md",
        "creep curve: F_x/(mu Fn) against creepage_x",
        &stdout_of(&[
            "creep-curve",
            example("tangential_rolling.toml").to_str().unwrap(),
            "--creepage-x",
            "0:0.004:9",
        ]),
        &["0.209"],
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
    // The quoted terminal output, line by line (the wall time excepted).
    excerpt(
        docs,
        "ball drop: m = 3.288200e-2 kg",
        &stdout_of(&["run", example("ball_drop_steel.toml").to_str().unwrap()]),
        &["1.564"],
    );
    let v = check(
        "ball_drop_steel.toml",
        &["run"],
        &[
            // "The first impact is at √(2h/g) = 0.142784312 s".
            q("impacts/0/time", 0.142784312, 1e-9),
            full("impacts/0/restitution", 1.0000002563041377),
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
    // "the peak force is within 3.4e-7 of the closed form, the rebound speed equals the
    // impact speed to 3e-7".
    near(
        "peak force vs closed form",
        num(&v, "impacts/0/peak_force") / num(&v, "closed_form/peak_force") - 1.0,
        3.4e-7,
        0.1e-7,
    );
    near(
        "rebound vs impact speed",
        num(&v, "impacts/0/rebound_velocity") / num(&v, "impacts/0/impact_velocity") - 1.0,
        3e-7,
        1e-7,
    );
    let radau_peak = num(&v, "impacts/0/peak_force");
    // docs/ball_drop.md: `--integrator verlet` on the steel example.
    let v = check(
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
    // "4 impacts with peak force 3462.4 N (3.0e-4 above the Radau5 value 3461.37 N: second
    // order at 50 steps per contact)": dt = 1 µs is refined to t_c/50 in contact.
    assert_eq!(v["impacts"].as_array().unwrap().len(), 4);
    near("radau5 peak force", radau_peak, 3461.37, 0.01);
    near(
        "verlet vs the adaptive peak",
        num(&v, "impacts/0/peak_force") / radau_peak - 1.0,
        3.0e-4,
        0.1e-4,
    );
    near(
        "steps per contact",
        num(&v, "accuracy/contact_time") / num(&v, "accuracy/contact_step"),
        50.0,
        1.0,
    );
    assert_eq!(v["accuracy"]["step_refined"], true);
    let v = check(
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
    // "one impact ... within 2e-4 of the Hertz closed form".
    assert_eq!(v["impacts"].as_array().unwrap().len(), 1);
    for (sim, closed) in [
        ("impacts/0/max_approach", "closed_form/max_approach"),
        ("impacts/0/peak_force", "closed_form/peak_force"),
        ("impacts/0/contact_duration", "closed_form/contact_duration"),
    ] {
        let e = num(&v, sim) / num(&v, closed) - 1.0;
        assert!(e.abs() <= 2e-4, "{sim}: {e:e} from the closed form");
    }
    let v = check(
        "ball_drop_damped_ellipsoid.toml",
        &["run"],
        &[
            q("impacts/0/restitution", 0.98049, 0.00001),
            q("impacts/1/restitution", 0.98042, 0.00001),
            q("energy_drift", 5.5e-8, 0.1e-8),
        ],
        docs,
    );
    assert_eq!(v["impacts"].as_array().unwrap().len(), 2, "two impacts");
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
            q("modes/1/frequency", 19.111414, 0.000001),
            q("modes/2/frequency", 43.000682, 0.000001),
            q("modes/2/beta_l", 9.42477796, 1e-8),
        ],
        docs,
    );
    excerpt(
        docs,
        "analytic simply_supported beam, L = 25 m",
        &stdout_of(&["modes", example("moving_load_fryba.toml").to_str().unwrap()]),
        &[],
    );
    check(
        "moving_load_fryba.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 2.3966e-3, 0.0001e-3),
            q("static_midspan_deflection", 2.2058e-3, 0.0001e-3),
            q("dynamic_amplification", 1.0865, 0.0001),
            q("max_midspan_acceleration", 0.439, 0.001),
            q(
                "static_midspan_deflection_closed_form",
                2.2059e-3,
                0.0001e-3,
            ),
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
            q("simulated_time_s", 1.91, 0.01),
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
            q("contact/min_force", 25.7e3, 0.1e3),
            q("contact/max_force", 224.1e3, 0.1e3),
            n("solver/steps", 14512.0),
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
    )["comfort"]["level"]
        .as_str()
        .map(|l| assert_eq!(l, "very good", "comfort level"))
        .expect("a comfort level");
}

/// docs/trains.md: a locomotive as moving forces ahead of two bogie vehicles; its
/// quasi-static peak against the closed-form influence line of the 12 static axle loads
/// (8 modes: within 2e-4).
#[test]
fn mixed_train_example_matches_the_docs() {
    let summary = check(
        "train_mixed.toml",
        &["run"],
        &[
            n("train/axles", 12.0),
            q("train/length", 68.71, 0.01),
            q("train/mass", 151_676.0, 1.0),
            q("max_midspan_deflection", 19.138e-3, 0.001e-3),
            q("max_quasi_static_deflection", 17.604e-3, 0.001e-3),
            q("dynamic_amplification", 1.0871, 0.0001),
            q("max_midspan_acceleration", 10.454, 0.001),
            q("contact/min_force", 3.2e3, 0.1e3),
            q("contact/max_force", 252.7e3, 0.1e3),
            n("contact/loss_of_contact_events", 0.0),
            q("vehicles/0/max_body_acceleration", 0.490, 0.001),
            q("vehicles/1/max_body_acceleration", 0.463, 0.001),
            n("solver/steps", 23678.0),
        ],
        "docs/trains.md",
    );
    let car = (32000.0 / 4.0 + 2615.0 / 2.0 + 1813.0) * 9.81;
    let mut axles: Vec<(f64, f64)> = [0.0, 3.0, 14.0, 17.0]
        .iter()
        .map(|&x| (x, 153.8e3))
        .collect();
    for lead in [22.15, 47.15] {
        axles.extend([0.0, 2.56, 19.0, 21.56].iter().map(|x| (lead + x, car)));
    }
    let (l, ei) = (25.0_f64, 8.323e9);
    let closed = (0..=100_000)
        .map(|i| {
            let lead = i as f64 * 1e-3;
            axles
                .iter()
                .map(|&(offset, load)| {
                    let b = lead - offset;
                    if (0.0..=l).contains(&b) {
                        let b = b.min(l - b);
                        load * b * (3.0 * l * l - 4.0 * b * b) / (48.0 * ei)
                    } else {
                        0.0
                    }
                })
                .sum::<f64>()
        })
        .fold(0.0f64, f64::max);
    near("closed-form quasi-static peak", closed, 17.604e-3, 0.001e-3);
    let modal = summary["max_quasi_static_deflection"].as_f64().unwrap();
    assert!((modal / closed - 1.0).abs() < 2e-4, "{modal} vs {closed}");
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
    // "first frequency 4.78 Hz".
    check(
        "ice3_bridge.toml",
        &["modes"],
        &[q("modes/0/frequency", 4.78, 0.01)],
        "docs/trains.md",
    );
    // "The closed-form influence-line sum of the 32 axle loads, Σ P b(3L² − 4b²)/(48 EI)
    // maximised over the train's position, gives 20.719 mm; the 8-mode quasi-static value is
    // 4e-5 above it, and with 60 modes the two agree to 5e-8."
    let axles = sim::train::presets::by_name("AVE-S103")
        .unwrap()
        .axles(9.81)
        .unwrap();
    let (l, ei) = (25.0_f64, 8.323e9);
    let at = |lead: f64| -> f64 {
        axles
            .iter()
            .map(|a| {
                let b = lead - a.offset;
                if (0.0..=l).contains(&b) {
                    let b = b.min(l - b);
                    a.load * b * (3.0 * l * l - 4.0 * b * b) / (48.0 * ei)
                } else {
                    0.0
                }
            })
            .sum()
    };
    // Every position of the leading axle in 0.1 mm steps: the maximum of a piecewise cubic
    // found to far better than the quoted digits.
    let closed = (0..2_300_000)
        .map(|i| at(i as f64 * 1e-4))
        .fold(0.0, f64::max);
    near(
        "closed-form static deflection [mm]",
        1e3 * closed,
        20.719,
        0.001,
    );
    let modal = |modes: &str| {
        let dir = tempfile::tempdir().unwrap();
        let text = std::fs::read_to_string(example("ice3_bridge.toml"))
            .unwrap()
            .replace("modes = 8", modes);
        let (v, _) = run_text(dir.path(), "run", "ice3.toml", &text);
        num(&v, "static_midspan_deflection")
    };
    near(
        "8 modes vs the closed form",
        modal("modes = 8") / closed - 1.0,
        4e-5,
        1e-5,
    );
    near(
        "60 modes vs the closed form",
        (modal("modes = 60") / closed - 1.0).abs(),
        5e-8,
        1e-8,
    );
}

/// docs/sweep.md: the HSLM-A sweep over a 20 m prestressed-concrete span.
#[test]
fn sweep_example_matches_the_docs() {
    let v = check(
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
    // "3 modes up to 44.998 Hz"; "the first resonance v₁ = n₀ D = 115.0 m/s" (HSLM-A6),
    // "v₁ = 90.0 m/s" (HSLM-A1); "HSLM-A10 ... its first resonance, 135 m/s, lies above the
    // range".
    let notes: Vec<&str> = v["notes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    assert!(notes.iter().any(|n| n.contains("= 44.998 Hz")), "{notes:?}");
    assert!(
        notes.iter().any(|n| n.contains("ζ = 1.2965 %")),
        "{notes:?}"
    );
    let resonance = |train: &str, order: u64| {
        v["checks"]["resonance_speeds"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["train"] == train && r["order"] == order)
            .map(|r| r["speed"].as_f64().unwrap())
    };
    near(
        "v1 of HSLM-A6",
        resonance("HSLM-A6", 1).unwrap(),
        115.0,
        0.1,
    );
    near("v1 of HSLM-A1", resonance("HSLM-A1", 1).unwrap(), 90.0, 0.1);
    assert_eq!(resonance("HSLM-A10", 1), None, "135 m/s is above the range");
    assert_eq!(v["trains"][5]["name"], "HSLM-A6");
    assert_eq!(v["checks"]["governing_train"], "HSLM-A6");
}

/// docs/sweep.md: the interaction sweep of two real trains' vehicle models.
#[test]
fn interaction_sweep_example_matches_the_docs() {
    check(
        "sweep_interaction.toml",
        &["sweep"],
        &[
            n("runs", 6.0),
            q("checks/first_frequency", 5.006, 0.001),
            q("damping_ratio", 0.01, 1e-12),
            q("trains/0/max_acceleration", 4.560, 0.001),
            q("trains/0/dynamic_factor", 2.245, 0.001),
            q("trains/1/max_acceleration", 10.996, 0.001),
            q("trains/1/max_deflection", 12.319e-3, 0.001e-3),
            q("trains/1/dynamic_factor", 5.196, 0.001),
            q("checks/governing_speed", 90.0, 1e-9),
            n("trains/1/loss_of_contact_events", 12.0),
            q("trains/1/max_unloading_ratio", 1.0, 0.0),
            q("trains/1/speeds_with_loss_of_contact/0", 90.0, 1e-9),
            n("trains/0/loss_of_contact_events", 0.0),
            q("trains/0/max_unloading_ratio", 0.365, 0.001),
            q("trains/0/max_body_acceleration", 0.140, 0.001),
        ],
        "docs/sweep.md",
    );
}

/// docs/vehicle_bridge.md: the default scenario, Biggs, Radau5, the two-span bogie and
/// docs/vehicle_bridge.md's braking example.
#[test]
fn vehicle_bridge_examples_match_the_docs() {
    let docs = "docs/vehicle_bridge.md";
    // The quoted output of `dyncontact run` (the built-in default), the wall time excepted.
    excerpt(
        docs,
        "running the built-in default scenario",
        &stdout_of(&["run"]),
        &["0.89"],
    );
    check(
        "vehicle_bridge_default.toml",
        &["run"],
        &[
            q("vehicle/static_wheel_loads/0", 62.29e3, 0.01e3),
            q("simulated_time_s", 0.833, 0.001),
            q("max_midspan_deflection", 2.5949e-3, 0.0001e-3),
            q("max_midspan_acceleration", 0.3680, 0.0001),
            q("dynamic_amplification", 1.0651, 0.0001),
            q("contact/min_force", 56777.2, 0.1),
            q("contact/max_force", 67893.6, 0.1),
            q("contact/max_pressure", 1086.5e6, 0.1e6),
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
    let (h, rows) = csv(&out.join("timeseries.csv"));
    let col = |name: &str| column(&h, &rows, name)[0];
    near("patch length [mm]", 1e3 * col("patch_length_m"), 13.0, 0.1);
    near("patch width [mm]", 1e3 * col("patch_width_m"), 9.8, 0.1);
    near(
        "peak pressure [MPa]",
        1e-6 * col("max_pressure_pa"),
        1055.0,
        1.0,
    );
    // docs/outputs.md's example of a CSV number ("all the digits of the f64"): the static
    // contact force of this first row, as written.
    let text = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    assert!(
        text.lines()
            .nth(1)
            .unwrap()
            .contains(",6.2293497801958634e4,")
    );
    // "the peak contact force is 67 892.5 / 67 893.6 / 67 894.7 N and the peak deflection
    // 2.59487 / 2.59486 / 2.59485 mm at Δt = 5e-4 / 2.5e-4 / 1.25e-4 s"; the 230 Hz
    // wheel-on-contact-spring mode from the under-resolution warning at 5e-4 s.
    let text = std::fs::read_to_string(example("vehicle_bridge_default.toml")).unwrap();
    for (dt, force, deflection) in [
        ("5e-4", 67_892.5, 2.59487),
        ("2.5e-4", 67_893.6, 2.59486),
        ("1.25e-4", 67_894.7, 2.59485),
    ] {
        let modified = text.replace("\ndt = 2.5e-4", &format!("\ndt = {dt}"));
        assert!(modified.contains(&format!("\ndt = {dt}")));
        let (v, e) = run_text(dir.path(), "run", &format!("dt{dt}.toml"), &modified);
        near(
            &format!("peak force at {dt}"),
            num(&v, "contact/max_force"),
            force,
            0.1,
        );
        near(
            &format!("peak deflection [mm] at {dt}"),
            1e3 * num(&v, "max_midspan_deflection"),
            deflection,
            0.00001,
        );
        if dt == "5e-4" {
            let fc = e
                .split("dt·f_c = ")
                .nth(1)
                .and_then(|r| r.split_whitespace().next())
                .and_then(|x| x.parse::<f64>().ok())
                .unwrap_or_else(|| panic!("no dt·f_c warning: {e}"))
                / 5e-4;
            near("contact mode [Hz]", fc, 230.0, 10.0);
        }
    }
    // "with tol 1e-6 the peak deflection changes by 2e-10, the contact-force extremes by
    // 2e-7 and the accelerations by 3e-5, relative" (bounds: the quoted digit rounded up).
    let tight = text.replace("\ntol = 1e-5\nmax_iter", "\ntol = 1e-6\nmax_iter");
    assert_ne!(tight, text, "the example's [coupling] tol");
    let run = |t: &str| run_text(dir.path(), "run", "tol.toml", t).0;
    let (a, b) = (run(&text), run(&tight));
    let change = |k: &str| (num(&b, k) / num(&a, k) - 1.0).abs();
    assert!(change("max_midspan_deflection") <= 2.5e-10);
    for k in ["contact/max_force", "contact/min_force"] {
        assert!(change(k) <= 2.5e-7, "{k}: {}", change(k));
    }
    for k in ["max_midspan_acceleration", "vehicle/max_body_acceleration"] {
        assert!(change(k) <= 3.5e-5, "{k}: {}", change(k));
    }
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
            q("max_midspan_deflection", 2.5977e-3, 0.0001e-3),
            q("dynamic_amplification", 1.0664, 0.0001),
            q("contact/min_force", 46307.8, 0.1),
            q("contact/max_force", 72182.0, 0.1),
            q("vehicle/max_body_acceleration", 0.2550, 0.0001),
            n("solver/steps", 12728.0),
            q("solver/mean_iterations_per_step", 1.65, 0.01),
            n("solver/failed_steps", 29.0),
            q("simulated_time_s", 0.900, 0.001),
        ],
        docs,
    );
    // "over every 10th step, as recorded in timeseries.csv, they were 46 460.9 … 71 999.4 N
    // and 0.2532 m/s²".
    let out = dir.path().join("radau5");
    let o = dyncontact(&[
        "run",
        example("vehicle_bridge_radau5.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let (h, rows) = csv(&out.join("timeseries.csv"));
    let f = column(&h, &rows, "contact_force_n");
    let max = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    near("recorded min force", min(&f), 46_460.9, 0.1);
    near("recorded max force", max(&f), 71_999.4, 0.1);
    let a = column(&h, &rows, "body_acceleration_m_s2");
    near(
        "recorded body acceleration",
        max(&a).max(-min(&a)),
        0.2532,
        0.0001,
    );
    check(
        "vehicle_bridge_two_span_flat.toml",
        &["run"],
        &[
            q("simulated_time_s", 1.417, 0.001),
            q("solver/mean_iterations_per_step", 1.55, 0.01),
            n("solver/max_iterations_per_step", 4.0),
            q("contact/min_force", 0.0, 0.5),
            q("contact/max_force", 419.5e3, 0.1e3),
            n("contact/loss_of_contact_events", 161.0),
            n("solver/failed_steps", 0.0),
            q("max_midspan_deflection", 1.8319e-3, 1e-7),
            n("points/0/x", 30.0),
            q("points/0/max_deflection", 1.8099e-3, 1e-7),
            q("points/0/max_acceleration", 37.86, 0.01),
        ],
        docs,
    );
    excerpt_after(
        docs,
        "**Worked example** (`dyncontact run examples/vehicle_bridge_braking.toml",
        "contact (bem): force 56777.2",
        &stdout_of(&[
            "run",
            example("vehicle_bridge_braking.toml").to_str().unwrap(),
        ]),
        &[],
    );
    check(
        "vehicle_bridge_braking.toml",
        &["run"],
        &[
            q("contact/min_force", 56777.2, 0.1),
            q("contact/max_force", 67893.6, 0.1),
            q("contact/max_pressure", 1086.5e6, 0.1e6),
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

/// docs/vehicle_bridge.md, "Traction (friction)": the braking example with the other two
/// methods (the table of max and mean F_x and saturated steps), and its first recorded step
/// ("F_n = 62 673 N and F_x = −14 604 N = 0.777 μF_n with 57.5 % of the patch in adhesion").
#[test]
fn braking_methods_match_the_docs() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("vehicle_bridge_braking.toml")).unwrap();
    for (method, max, mean, saturated) in [
        ("linear", -20_368.0, -18_714.0, 3334.0),
        ("exact", -18_982.0, -17_721.0, 0.0),
    ] {
        let modified = text.replace(
            "\nmethod = \"fastsim\"",
            &format!("\nmethod = \"{method}\""),
        );
        assert_ne!(modified, text);
        let (v, _) = run_text(dir.path(), "run", &format!("{method}.toml"), &modified);
        near(method, num(&v, "traction/max_longitudinal_force"), max, 1.0);
        near(
            method,
            num(&v, "traction/mean_longitudinal_force"),
            mean,
            1.0,
        );
        near(method, num(&v, "traction/saturated_steps"), saturated, 0.0);
        near(method, num(&v, "solver/steps"), 3334.0, 0.0);
    }
    let out = dir.path().join("fastsim");
    let o = dyncontact(&[
        "run",
        example("vehicle_bridge_braking.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let (h, rows) = csv(&out.join("timeseries.csv"));
    let first = |name: &str| column(&h, &rows, name)[1];
    let (fn_, fx) = (first("contact_force_n"), first("longitudinal_force_n"));
    near("F_n", fn_, 62_673.0, 1.0);
    near("F_x", fx, -14_604.0, 1.0);
    near("F_x/(μF_n)", -fx / (0.3 * fn_), 0.777, 0.001);
    near(
        "adhesion [%]",
        100.0 * first("adhesion_fraction"),
        57.5,
        0.1,
    );
}

/// The text of a doc with its line breaks and indentation folded into single spaces (quoted
/// messages wrap across lines).
fn folded(name: &str) -> String {
    doc(name).split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Runs the binary on `text` (written as `name`) with `args`, expects exit code 2 (bad
/// input), and checks that standard error holds every fragment and that `doc_name` quotes
/// each of them.
fn quoted_error(doc_name: &str, name: &str, text: &str, args: &[&str], fragments: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let file = support::write(dir.path(), name, text);
    let mut argv = vec![args[0], file.as_str()];
    argv.extend_from_slice(&args[1..]);
    let out = dir.path().join("out");
    argv.extend(["--out", out.to_str().unwrap()]);
    let o = dyncontact(&argv);
    let e = String::from_utf8_lossy(&o.stderr)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let quoted = folded(doc_name);
    for f in fragments {
        assert!(e.contains(f), "{name}: the program says\n{e}\nnot\n{f}");
        assert!(quoted.contains(f), "{doc_name} does not quote\n{f}");
    }
    assert_eq!(support::code(&o), Some(2), "{name}: bad input exits with 2");
}

/// The error messages docs/scenarios.md, docs/bridge.md and docs/vehicle_bridge.md quote are
/// the program's (each produced here from a file that triggers it).
#[test]
fn quoted_error_messages_match_the_program() {
    let fryba = std::fs::read_to_string(example("moving_load_fryba.toml")).unwrap();
    let ei = fryba.replace("\nEI = 8.323e9", "\nEI = 1e-300");
    assert_ne!(ei, fryba);
    quoted_error(
        "docs/scenarios.md",
        "ei.toml",
        &ei,
        &["run"],
        &["`bridge.EI` = 1e-300: must lie in [1e-6, 1e14] N m²"],
    );
    let sphere = std::fs::read_to_string(example("hertz_sphere.toml")).unwrap();
    let big = sphere.replace(
        "\nn = 96",
        "\nnx = 4096\nny = 2048\ndx = 1e-6\ndy = 1e-6\n#",
    );
    assert_ne!(big, sphere);
    quoted_error(
        "docs/scenarios.md",
        "grid.toml",
        &big,
        &["contact"],
        &[
            "`grid.nx × grid.ny`: a 4096 × 2048 grid has 8.388608e6 elements, at most 4194304 are allowed (about 1.7 GB of memory)",
        ],
    );
    let two = std::fs::read_to_string(example("vehicle_bridge_two_span_flat.toml")).unwrap();
    let second = two.rfind("suspension_stiffness").unwrap();
    let end = second + two[second..].find('\n').unwrap();
    let stiff = format!(
        "{}suspension_stiffness = 1e300{}",
        &two[..second],
        &two[end..]
    );
    quoted_error(
        "docs/scenarios.md",
        "stiff.toml",
        &stiff,
        &["run"],
        &["`vehicle.wheels[1].suspension_stiffness` = 1e300: must lie in [0, 1e15] N/m"],
    );
    let biggs = std::fs::read_to_string(example("vehicle_bridge_biggs.toml")).unwrap();
    let picard = biggs.replace("solver = \"quasi_newton\"", "solver = \"picard\"");
    assert_ne!(picard, biggs);
    quoted_error(
        "docs/scenarios.md",
        "picard.toml",
        &picard,
        &["run"],
        &[
            "`coupling.solver` = \"picard\": picard needs a compliant contact (contact.model = \"hertz\" or \"bem\");",
        ],
    );
    quoted_error(
        "docs/scenarios.md",
        "parse.toml",
        "kind = \"moving_load\"\n[bridge]\nlength = 25.0\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 3\nEI = \"abc\"\n[load]\nforce = 1e3\nspeed = 10.0\n",
        &["run"],
        &[
            "invalid scenario file: TOML parse error at line 7, column 6",
            "invalid type: string \"abc\", expected f64",
        ],
    );
    // README, case-file limits: per side and in total, element size, modulus.
    let side = sphere.replace("\nn = 96", "\nnx = 65537\nny = 1\ndx = 1e-6\ndy = 1e-6\n#");
    let dir = tempfile::tempdir().unwrap();
    for (text, says) in [
        (side, "`grid.nx` = 65537: at most 65536 is allowed"),
        (
            sphere.replace("\nn = 96", "\nnx = 8\nny = 8\ndx = 1e-10\ndy = 1e-10\n#"),
            "`grid.dx` = 1e-10: must lie in [1e-9, 10] m",
        ),
        (
            sphere.replacen("\nE = 210e9", "\nE = 1e14", 1),
            "`body1.E` = 1e14: must lie in [1, 1e13] Pa",
        ),
    ] {
        let f = support::write(dir.path(), "limit.toml", &text);
        let o = dyncontact(&[
            "contact",
            &f,
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ]);
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains(says), "{e}");
    }
    let readme = folded("README.md");
    for limit in [
        "nx, ny ≤ 65,536, nx·ny ≤ 4,194,304",
        "dx, dy in [1e-9, 10] m",
        "E in [1, 1e13] Pa",
    ] {
        assert!(readme.contains(limit), "README.md does not state {limit}");
    }
    // docs/bridge.md: "200 modes of Frýba's bridge (ω_200 = 1.2e6 rad/s) allow dt ≤ 1.67 µs
    // with central difference".
    let cd = fryba
        .replace("\nmodes = 20", "\nmodes = 200")
        .replace("method = \"newmark\"", "method = \"central_difference\"");
    let f = support::write(dir.path(), "cd.toml", &cd);
    let o = dyncontact(&["run", &f, "--out", dir.path().join("cd").to_str().unwrap()]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("stability limit 1.6655") && e.contains("ω_max = 1.2008"),
        "{e}"
    );
    assert!(
        folded("docs/bridge.md")
            .contains("(ω_200 = 1.2e6 rad/s) allow dt ≤ 1.67 µs with central difference")
    );
    // docs/vehicle_bridge.md: Picard beyond its limit (1 kg wheel pressed by 100 kN, Hertz,
    // Δt = 1e-4 s, no step halving; the scenario of the zoo test
    // `picard_beyond_its_limit_names_the_remedy`).
    let text = "kind = \"vehicle_bridge\"\n[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nmodes = 4\n\
                [vehicle]\nspeed = 30.0\n[[vehicle.wheels]]\nposition = 2.0\nwheel_mass = 1.0\nstatic_load = 99990.19\n\
                [contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"newmark\"\ndt = 1e-4\nduration = 2e-3\n\
                [coupling]\nsolver = \"picard\"\nmax_halvings = 0\n";
    let f = support::write(dir.path(), "picard_limit.toml", text);
    let o = dyncontact(&["run", &f, "--out", dir.path().join("p").to_str().unwrap()]);
    assert_eq!(support::code(&o), Some(1), "a failed run");
    let e = String::from_utf8_lossy(&o.stderr);
    let quoted = folded("docs/vehicle_bridge.md");
    for fragment in [
        "Picard coupling diverges (contraction factor 3.602 > 1 at wheel 0):",
        "use coupling.solver = \"quasi_newton\" (the default) or \"newton\", or integrator.dt <= 3.69e-5 s",
    ] {
        assert!(e.contains(fragment), "{e}");
        assert!(
            quoted.contains(fragment),
            "docs/vehicle_bridge.md: {fragment}"
        );
    }
}

/// docs/track.md's numbers for examples/track_quarter_car.toml (the quarter car on the
/// ballasted track over the 25 m bridge, Hertz contact on the rail).
#[test]
fn track_example_matches_the_docs() {
    let docs = "docs/track.md";
    check(
        "track_quarter_car.toml",
        &["run"],
        &[
            q("max_midspan_deflection", 2.6487e-3, 0.0001e-3),
            q("max_midspan_acceleration", 0.2517, 0.0001),
            q("contact/min_force", 61310.2, 0.1),
            q("contact/max_force", 63277.0, 0.1),
            q("track/max_rail_displacement", 3.4172e-3, 0.0001e-3),
            q("track/max_pad_force", 21886.6, 0.1),
            q("track/max_ballast_force", 22032.5, 0.1),
            q(
                "track/max_rail_bridge_relative_displacement",
                7.8922e-4,
                0.0001e-4,
            ),
            n("track/track_dofs", 1092.0),
            n("solver/steps", 11667.0),
            q("simulated_time_s", 1.167, 0.001),
        ],
        docs,
    );
    // "Today's model (no `[track]`, the bridge carrying the full 2303 kg/m) gives 2.6704e-3 m
    // … and the midspan acceleration from 0.3371".
    let text = std::fs::read_to_string(example("track_quarter_car.toml")).unwrap();
    let (start, end) = (
        text.find("[track]").unwrap(),
        text.find("[integrator]").unwrap(),
    );
    let today = format!("{}{}", &text[..start], &text[end..])
        .replace("mass_per_length = 1148.0", "mass_per_length = 2303.0");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("today.toml");
    std::fs::write(&path, today).unwrap();
    let out = dir.path().join("out");
    let o = dyncontact(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    near(
        "today's peak",
        num(&v, "max_midspan_deflection"),
        2.6704e-3,
        0.0001e-3,
    );
    near(
        "today's acceleration",
        num(&v, "max_midspan_acceleration"),
        0.3371,
        0.0001,
    );
}
