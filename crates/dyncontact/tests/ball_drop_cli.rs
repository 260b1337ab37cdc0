//! `dyncontact run` with `kind = "ball_drop"`: JSON keys, output files, the `--integrator`
//! override, and errors that name the offending key.

mod support;

use support::{dyncontact, write};

/// The reference drop (references.md §C4.10), shortened to 0.3 s (one impact at t = √(2h/g) = 0.1428 s).
const VALID: &str = r#"
kind = "ball_drop"
duration = 0.3
[ball]
radius = 0.01
density = 7850.0
rigid = true
[surface]
E = 210e9
nu = 0.3
[initial]
height = 0.1
velocity = 0.0
[contact]
model = "hertz"
[integrator]
method = "radau5"
rtol = 1e-8
atol = 1e-12
"#;

/// The summary has the documented keys, the impact matches the energy-balance closed form
/// printed next to it (peak force within 2e-6 at rtol 1e-8, rebound = impact speed within
/// 1e-5), and the three output files exist.
#[test]
fn json_summary_and_files() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "drop.toml", VALID);
    let out = dir.path().join("out");
    let o = dyncontact(&["run", &file, "--out", out.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for key in [
        "impacts",
        "restitution",
        "energy_drift",
        "integrator",
        "wall_time_s",
        "closed_form",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    for key in [
        "method",
        "steps",
        "f_evals",
        "rejected_steps",
        "jacobian_evals",
    ] {
        assert!(
            v["integrator"].get(key).is_some(),
            "missing integrator.{key}"
        );
    }
    assert_eq!(v["integrator"]["method"], "radau5");
    let impacts = v["impacts"].as_array().unwrap();
    assert_eq!(impacts.len(), 1);
    let imp = &impacts[0];
    for key in [
        "time",
        "max_approach",
        "peak_force",
        "contact_duration",
        "rebound_velocity",
    ] {
        assert!(imp[key].is_f64(), "impact key {key}");
    }
    let f = imp["peak_force"].as_f64().unwrap();
    let f_exact = v["closed_form"]["peak_force"].as_f64().unwrap();
    assert!((f / f_exact - 1.0).abs() < 2e-6, "{f} vs {f_exact}");
    assert!((imp["rebound_velocity"].as_f64().unwrap() - 1.4007141).abs() < 1e-5);
    assert!(((v["restitution"].as_f64().unwrap()) - 1.0).abs() < 1e-5);
    let csv = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    assert!(csv.starts_with("t_s,z_m,v_m_s,a_m_s2,approach_m,force_n,energy_j\n"));
    assert!(csv.lines().count() > 100);
    assert!(out.join("summary.json").exists() && out.join("ball_drop.png").exists());
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(written["impacts"], v["impacts"]);
}

/// `--integrator` overrides the file's method; the structural scheme needs no change of keys
/// (its `dt` defaults to 1 µs) and still sees the impact.
#[test]
fn integrator_override() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "drop.toml", VALID);
    let out = dir.path().join("out");
    let o = dyncontact(&[
        "run",
        &file,
        "--out",
        out.to_str().unwrap(),
        "--json",
        "--integrator",
        "newmark",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["integrator"]["method"], "newmark");
    assert_eq!(v["impacts"].as_array().unwrap().len(), 1);
    let o = dyncontact(&[
        "run",
        &file,
        "--out",
        out.to_str().unwrap(),
        "--integrator",
        "rk45",
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("[integrator] method") && err.contains("radau5"),
        "{err}"
    );
}

fn error_of(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "bad.toml", text);
    let out = dir.path().join("out");
    let o = dyncontact(&["run", &file, "--out", out.to_str().unwrap()]);
    assert!(!o.status.success(), "should fail:\n{text}");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Bad input: the message names the key (and nothing panics).
#[test]
fn errors_name_the_key() {
    let cases = [
        (
            VALID.replace("rigid = true", "rigid = true\ncolour = 1"),
            "colour",
        ),
        (
            VALID.replace("[initial]\nheight = 0.1\nvelocity = 0.0\n", ""),
            "initial",
        ),
        (VALID.replace("nu = 0.3", "nu = 0.5"), "nu"),
        (VALID.replace("density = 7850.0", "mass = -1.0"), "mass"),
        (
            VALID.replace("density = 7850.0", "density = nan"),
            "density",
        ),
        (VALID.replace("height = 0.1", "height = -0.1"), "height"),
        (
            VALID.replace("model = \"hertz\"", "model = \"fem\""),
            "model",
        ),
        (VALID.replace("rtol = 1e-8", "rtol = -1.0"), "rtol"),
        (
            VALID.replace("duration = 0.3", "duration = 0.0"),
            "duration",
        ),
        (
            VALID.replace("rigid = true", "rigid = true\nE = 1e9"),
            "rigid body takes no `E`",
        ),
        (
            VALID
                .replace("model = \"hertz\"", "model = \"hertz\"\ndamping = 1.0")
                .replace("method = \"radau5\"", "method = \"verlet\""),
            "damping",
        ),
    ];
    for (text, key) in cases {
        let err = error_of(&text);
        assert!(err.contains(key), "expected `{key}` in: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// `--integrator` on a scenario kind that does not take it is an error.
#[test]
fn integrator_flag_is_rejected_for_other_kinds() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(
        dir.path(),
        "contact.toml",
        "kind = \"contact\"\n[body1]\nE = 210e9\nnu = 0.3\n[body2]\nE = 210e9\nnu = 0.3\n[gap]\nkind = \"sphere\"\nradius = 0.01\n[load]\nforce = 1000.0\n",
    );
    let out = dir.path().join("out");
    let o = dyncontact(&[
        "run",
        &file,
        "--out",
        out.to_str().unwrap(),
        "--integrator",
        "rk4",
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--integrator"));
}

/// `model = "bem"` through the CLI (16 × 16 elements): the half-space solver is called and the
/// impact agrees with the Hertz closed form within the 16-element discretisation error
/// (2.5e-3, see crates/sim/tests/ball_drop_bem.rs; measured 1.7e-3 in the peak force).
#[test]
fn bem_model_runs_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let text = VALID
        .replace(
            "model = \"hertz\"",
            "model = \"bem\"\nelements = 16\ntol = 1e-10",
        )
        .replace("rtol = 1e-8", "rtol = 1e-6");
    let file = write(dir.path(), "bem.toml", &text);
    let out = dir.path().join("out");
    let o = dyncontact(&["run", &file, "--out", out.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["contact"]["model"], "bem");
    assert_eq!(v["contact"]["elements"], 16);
    assert!(v["integrator"]["contact_solves"].as_u64().unwrap() > 0);
    let f = v["impacts"][0]["peak_force"].as_f64().unwrap();
    let f_exact = v["closed_form"]["peak_force"].as_f64().unwrap();
    assert!((f / f_exact - 1.0).abs() < 2.5e-3, "{f} vs {f_exact}");
}
