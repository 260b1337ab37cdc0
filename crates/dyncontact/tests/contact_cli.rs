//! The `contact` subcommand end to end: valid cases, JSON keys, output files, and errors that
//! name the offending key.

mod support;

use std::path::Path;

use support::{dyncontact, write};

const VALID: &str = r#"
[body1]
E = 210e9
nu = 0.3
[body2]
E = 210e9
nu = 0.3
[gap]
kind = "quadratic"
A = 50.0
B = 50.0
[grid]
nx = 48
ny = 48
dx = 1.8e-5
dy = 1.8e-5
[load]
force = 1000.0
[solver]
tol = 1e-8
max_iter = 200
"#;

#[test]
fn json_summary_has_the_documented_keys_and_matches_hertz() {
    let dir = tempfile::tempdir().unwrap();
    let case = write(dir.path(), "case.toml", VALID);
    let out = dyncontact(&["contact", &case, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "normal_force",
        "approach",
        "max_pressure",
        "contact_area",
        "elements_in_contact",
        "iterations",
        "residual",
        "converged",
        "dfn_dapproach",
        "solve_time_s",
    ] {
        assert!(v.get(key).is_some(), "missing key {key}");
    }
    assert_eq!(v["converged"], true);
    let hertz = &v["hertz"];
    for key in ["approach", "max_pressure", "a", "b", "normal_force"] {
        assert!(hertz.get(key).is_some(), "missing hertz.{key}");
    }
    // 48 × 48 elements over ±0.43 mm, patch radius 0.40 mm: ~22 elements per radius gives
    // approach and peak pressure within 0.5 % of Hertz (the solver tests measure O(h²)).
    let rel = |a: &serde_json::Value, b: &serde_json::Value| {
        (a.as_f64().unwrap() / b.as_f64().unwrap() - 1.0).abs()
    };
    assert!(rel(&v["approach"], &hertz["approach"]) < 5e-3);
    assert!(rel(&v["max_pressure"], &hertz["max_pressure"]) < 5e-3);
    assert!((v["normal_force"].as_f64().unwrap() - 1000.0).abs() < 1e-9);
}

#[test]
fn out_dir_gets_csv_png_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let case = write(dir.path(), "case.toml", VALID);
    let out_dir = dir.path().join("result");
    let out = dyncontact(&["contact", &case, "--out", out_dir.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(out_dir.join("pressure.csv")).unwrap();
    assert!(csv.starts_with("x_m,y_m,p_pa\n"));
    assert_eq!(csv.lines().count(), 1 + 48 * 48);
    let png = std::fs::read(out_dir.join("pressure.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(out_dir.join("summary.json").exists());
    // No temporary files are left behind.
    for entry in std::fs::read_dir(&out_dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.contains("partial"), "left over {name}");
    }
}

#[test]
fn prescribed_approach_and_force_are_consistent_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let by_force = dyncontact(&["contact", &write(dir.path(), "f.toml", VALID), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&by_force.stdout).unwrap();
    let approach = v["approach"].as_f64().unwrap();
    let text = VALID.replace("force = 1000.0", &format!("approach = {approach:e}"));
    let by_approach = dyncontact(&["contact", &write(dir.path(), "a.toml", &text), "--json"]);
    let w: serde_json::Value = serde_json::from_slice(&by_approach.stdout).unwrap();
    assert!((w["normal_force"].as_f64().unwrap() / 1000.0 - 1.0).abs() < 1e-6);
}

/// Run an invalid variant of the valid case and return its error message.
fn error_of(dir: &Path, text: &str) -> String {
    let case = write(dir, "bad.toml", text);
    let out = dyncontact(&["contact", &case, "--json"]);
    assert!(!out.status.success(), "accepted invalid case:\n{text}");
    assert!(out.stdout.is_empty(), "printed output for an invalid case");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn invalid_cases_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "E = 210e9\nnu = 0.3\n[body2]",
            "E = -210e9\nnu = 0.3\n[body2]",
            &["body1", "`E`", "positive"],
        ),
        (
            "nu = 0.3\n[gap]",
            "nu = 0.5\n[gap]",
            &["body2", "`nu`", "0.5"],
        ),
        (
            "nu = 0.3\n[gap]",
            "nu = nan\n[gap]",
            &["body2", "`nu`", "finite"],
        ),
        ("A = 50.0", "A = 50.0\nfoo = 1.0", &["unknown field", "foo"]),
        (
            "[solver]",
            "[extra]\nx = 1\n[solver]",
            &["unknown field", "extra"],
        ),
        ("force = 1000.0", "", &["[load]", "missing load"]),
        (
            "force = 1000.0",
            "force = 1000.0\napproach = 1e-6",
            &["[load]", "exactly one"],
        ),
        ("force = 1000.0", "force = -5.0", &["[load]", "force"]),
        ("nx = 48", "nx = 0", &["`grid.nx` = 0"]),
        ("nx = 48", "nx = 70000", &["`grid.nx` = 70000", "65536"]),
        (
            "dx = 1.8e-5",
            "dx = 0.0",
            &["`grid.dx` = 0", "[1e-9, 10] m"],
        ),
        ("ny = 48\n", "", &["[grid]", "ny"]),
        (
            "kind = \"quadratic\"",
            "kind = \"cone\"",
            &["[gap]", "kind", "cone"],
        ),
        ("A = 50.0\n", "", &["[gap]", "`A`"]),
        (
            "A = 50.0",
            "A = 50.0\nradius = 0.01",
            &["[gap]", "radius", "quadratic"],
        ),
        ("tol = 1e-8", "tol = 0.0", &["[solver]", "tol"]),
        ("max_iter = 200", "max_iter = 0", &["[solver]", "max_iter"]),
    ];
    for (from, to, needles) in cases {
        assert!(VALID.contains(from), "test setup: {from}");
        let message = error_of(d, &VALID.replacen(from, to, 1));
        for needle in *needles {
            assert!(
                message.contains(needle),
                "error for `{to}` lacks `{needle}`: {message}"
            );
        }
    }
    // Both bodies rigid.
    let text = VALID
        .replacen("E = 210e9\nnu = 0.3\n[body2]", "rigid = true\n[body2]", 1)
        .replacen("[body2]\nE = 210e9\nnu = 0.3", "[body2]\nrigid = true", 1);
    assert!(error_of(d, &text).contains("rigid"));
}

#[test]
fn missing_files_are_reported() {
    let out = dyncontact(&["contact", "/nonexistent/case.toml"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read"));
    let dir = tempfile::tempdir().unwrap();
    let text = VALID.replace(
        "kind = \"quadratic\"\nA = 50.0\nB = 50.0",
        "kind = \"table\"\nfile = \"missing.csv\"",
    );
    let message = error_of(dir.path(), &text);
    assert!(
        message.contains("[gap]") && message.contains("missing.csv"),
        "{message}"
    );
}

#[test]
fn tabulated_gap_reproduces_the_analytic_one() {
    let dir = tempfile::tempdir().unwrap();
    let (n, d) = (48usize, 1.8e-5);
    let mut csv = String::from("# quadratic gap, 50 (x² + y²)\n");
    for iy in 0..n {
        let y = (iy as f64 + 0.5 - n as f64 / 2.0) * d;
        let row: Vec<String> = (0..n)
            .map(|ix| {
                let x = (ix as f64 + 0.5 - n as f64 / 2.0) * d;
                format!("{:e}", 50.0 * (x * x + y * y))
            })
            .collect();
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    std::fs::write(dir.path().join("gap.csv"), csv).unwrap();
    let text = VALID.replace(
        "kind = \"quadratic\"\nA = 50.0\nB = 50.0",
        "kind = \"table\"\nfile = \"gap.csv\"",
    );
    let table = dyncontact(&["contact", &write(dir.path(), "t.toml", &text), "--json"]);
    assert!(
        table.status.success(),
        "{}",
        String::from_utf8_lossy(&table.stderr)
    );
    let analytic = dyncontact(&["contact", &write(dir.path(), "q.toml", VALID), "--json"]);
    let a: serde_json::Value = serde_json::from_slice(&analytic.stdout).unwrap();
    let t: serde_json::Value = serde_json::from_slice(&table.stdout).unwrap();
    let (ta, aa) = (
        t["approach"].as_f64().unwrap(),
        a["approach"].as_f64().unwrap(),
    );
    assert!((ta / aa - 1.0).abs() < 1e-8, "{ta} vs {aa}");
    // A short row is an error naming the line.
    std::fs::write(dir.path().join("gap.csv"), "0.0,1.0\n").unwrap();
    assert!(error_of(dir.path(), &text).contains("line 1"));
}

#[test]
fn examples_run_and_converge() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for name in [
        "hertz_sphere.toml",
        "hertz_ellipse.toml",
        "rounded_punch.toml",
        "wavy_table.toml",
    ] {
        let path = root.join(name);
        let out = dyncontact(&["contact", path.to_str().unwrap(), "--json"]);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["converged"], true, "{name}");
    }
}
