//! `dyncontact contact` with [friction]/[kinematics] and `dyncontact creep-curve` end to end:
//! JSON keys, CONTACT's published example outputs, output files, and key-naming errors.

mod support;

use support::{dyncontact, example, json_of, write};

fn f(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("missing numeric key {key}"))
}

#[test]
fn carter_example_reproduces_contact() {
    // CONTACT carter2d (55 elements): F_x/(μF_n) = 0.6480, 30 adhesion elements (0.2 %).
    let v = json_of(&[
        "contact",
        example("tangential_carter.toml").to_str().unwrap(),
        "--json",
    ]);
    for key in [
        "tangential_force_x",
        "tangential_force_y",
        "spin_moment",
        "adhesion_elements",
        "slip_elements",
        "creepage_x",
        "creepage_y",
        "frictional_power",
        "tangential_iterations",
        "normal_force",
    ] {
        assert!(v.get(key).is_some(), "missing key {key}");
    }
    let ratio = f(&v, "tangential_force_x") / (0.3 * f(&v, "normal_force"));
    assert!((ratio / 0.6480 - 1.0).abs() < 2e-3, "{ratio}");
    assert_eq!(v["adhesion_elements"], 30);
    assert_eq!(v["tangential_method"], "exact");
}

#[test]
fn cattaneo_example_reproduces_contact() {
    // CONTACT cattaneo (19 × 19): shift 8.155e-3 mm, 45 adhesion / 132 slip (0.05 %).
    let v = json_of(&[
        "contact",
        example("tangential_cattaneo.toml").to_str().unwrap(),
        "--json",
    ]);
    assert!((f(&v, "shift_x") / 8.155e-6 - 1.0).abs() < 5e-4);
    assert_eq!(v["adhesion_elements"], 45);
    assert_eq!(v["slip_elements"], 132);
    assert!((f(&v, "tangential_force_x") + 3.21839).abs() < 1e-4);
}

/// The tractcurv ellipse on a 20 × 20 grid (fast in debug builds).
const ELLIPSE: &str = r#"
[body1]
E = 209.92e9
nu = 0.28
[body2]
E = 209.92e9
nu = 0.28
[gap]
kind = "quadratic"
A = 0.8
B = 0.281417
[grid]
nx = 20
ny = 20
dx = 6.6188e-4
dy = 1.32375e-3
[load]
force = 106.7e3
[friction]
mu = 0.3
"#;

#[test]
fn methods_and_forces_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Linear theory at ξ = 1e-5: |F_x| = G c² C11 ξ = 243.3 N (references.md §C4.2, 4 digits).
    let lin = write(
        d,
        "lin.toml",
        &format!("{ELLIPSE}[kinematics]\ncreepage_x = 1e-5\nmethod = \"linear\"\n"),
    );
    let v = json_of(&["contact", &lin, "--json"]);
    assert!((f(&v, "tangential_force_x") + 243.3).abs() < 0.1, "{v}");
    assert!(v["spin_moment"].is_null());
    // FASTSIM and exact at ξ = 1e-3 agree within 0.03 μF_n (fastsim.rs measures 0.014 on
    // 44 × 44; this grid is coarser).
    let fs = write(
        d,
        "fs.toml",
        &format!("{ELLIPSE}[kinematics]\ncreepage_x = 1e-3\nmethod = \"fastsim\"\n"),
    );
    let ex = write(
        d,
        "ex.toml",
        &format!("{ELLIPSE}[kinematics]\ncreepage_x = 1e-3\n"),
    );
    let vf = json_of(&["contact", &fs, "--json"]);
    let ve = json_of(&["contact", &ex, "--json"]);
    let lim = 0.3 * 106.7e3;
    let (ff, fe) = (f(&vf, "tangential_force_x"), f(&ve, "tangential_force_x"));
    assert!(((ff - fe) / lim).abs() < 0.03, "{ff} {fe}");
    // Prescribing the exact solver's force gives back its creepage (Newton, 1 %).
    let fo = write(
        d,
        "fo.toml",
        &format!("{ELLIPSE}[kinematics]\nforce_x = {fe}\n"),
    );
    let vo = json_of(&["contact", &fo, "--json"]);
    assert!((f(&vo, "creepage_x") / 1e-3 - 1.0).abs() < 0.01, "{vo}");
    // --out writes the traction maps.
    let out = d.join("out");
    let o = dyncontact(&["contact", &ex, "--out", out.to_str().unwrap()]);
    assert!(o.status.success());
    for name in [
        "traction.csv",
        "traction_x.png",
        "traction_y.png",
        "adhesion_slip.png",
    ] {
        assert!(out.join(name).exists(), "missing {name}");
    }
    let csv = std::fs::read_to_string(out.join("traction.csv")).unwrap();
    assert!(csv.starts_with("x_m,y_m,px_pa,py_pa,state,slip_x,slip_y\n"));
    assert_eq!(csv.lines().count(), 1 + 400);
}

#[test]
fn invalid_kinematics_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases = [
        ("[kinematics]\ncreepage_x = 1e-3\nbogus = 1\n", "bogus"),
        (
            "[kinematics]\ncreepage_x = 1e-3\nforce_x = 10.0\n",
            "not both",
        ),
        (
            "[kinematics]\nshift_x = 1e-6\ncreepage_x = 1e-3\n",
            "creepage_x",
        ),
        ("[kinematics]\ncreepage_x = nan\n", "creepage_x"),
        (
            "[kinematics]\ncreepage_x = 1e-3\nmethod = \"magic\"\n",
            "method",
        ),
        (
            "[kinematics]\nforce_x = 100.0\nmethod = \"fastsim\"\n",
            "method",
        ),
        (
            "[kinematics]\nproblem = \"skid\"\ncreepage_x = 1e-3\n",
            "problem",
        ),
        ("[kinematics]\nproblem = \"shift\"\n", "shift_x"),
        ("[kinematics]\nforce_x = 1e6\n", "friction limit"),
    ];
    for (extra, needle) in cases {
        let path = write(d, "bad.toml", &format!("{ELLIPSE}{extra}"));
        let out = dyncontact(&["contact", &path]);
        assert!(!out.status.success(), "accepted: {extra}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{extra}: {err}");
    }
    // [friction] problems.
    let no_mu = ELLIPSE.replace("mu = 0.3", "") + "[kinematics]\ncreepage_x = 1e-3\n";
    let err =
        String::from_utf8_lossy(&dyncontact(&["contact", &write(d, "b.toml", &no_mu)]).stderr)
            .into_owned();
    assert!(err.contains("mu"), "{err}");
    let neg = ELLIPSE.replace("mu = 0.3", "mu = -0.3") + "[kinematics]\ncreepage_x = 1e-3\n";
    let err = String::from_utf8_lossy(&dyncontact(&["contact", &write(d, "b.toml", &neg)]).stderr)
        .into_owned();
    assert!(err.contains("`mu` = -0.3"), "{err}");
    let no_friction =
        ELLIPSE.replace("[friction]\nmu = 0.3\n", "") + "[kinematics]\ncreepage_x = 1e-3\n";
    let err = String::from_utf8_lossy(
        &dyncontact(&["contact", &write(d, "b.toml", &no_friction)]).stderr,
    )
    .into_owned();
    assert!(err.contains("[friction]"), "{err}");
}

#[test]
fn creep_curve_writes_three_methods() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let case = write(d, "case.toml", ELLIPSE);
    let out = d.join("curve");
    let v = json_of(&[
        "creep-curve",
        &case,
        "--creepage-x",
        "0:0.004:5",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 5);
    let lim = 0.3 * f(&v, "normal_force");
    // ξ = 0 gives no force; at ξ = 0.004 the exact force is near saturation (> 0.95 μF_n),
    // FASTSIM within 0.03 μF_n of it.
    assert!(f(&points[0], "exact_force_x").abs() < 1e-9 * lim);
    let last = &points[4];
    assert!(-f(last, "exact_force_x") > 0.95 * lim);
    assert!(((f(last, "fastsim_force_x") - f(last, "exact_force_x")) / lim).abs() < 0.03);
    // Linear theory is linear in ξ: the force at 0.004 is four times that at 0.001.
    let r = f(last, "linear_force_x") / f(&points[1], "linear_force_x");
    assert!((r - 4.0).abs() < 1e-9);
    for name in ["creep_curve.csv", "creep_curve.json", "creep_curve.png"] {
        assert!(out.join(name).exists(), "missing {name}");
    }
    let csv = std::fs::read_to_string(out.join("creep_curve.csv")).unwrap();
    assert_eq!(csv.lines().count(), 6);
    // Errors: no sweep, two sweeps, a malformed range.
    for args in [
        vec!["creep-curve", case.as_str()],
        vec![
            "creep-curve",
            case.as_str(),
            "--creepage-x",
            "0:1:3",
            "--spin",
            "0:1:3",
        ],
        vec!["creep-curve", case.as_str(), "--creepage-x", "0:0.004"],
    ] {
        let o = dyncontact(&args);
        assert!(!o.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("--creepage-x") || err.contains("--spin"),
            "{err}"
        );
    }
}

#[test]
fn dissimilar_materials_run_the_outer_loop() {
    // A rigid ball on a soft body (K = −0.3): the exact method alternates normal and
    // tangential solves; the prescribed force is met and the outer count is reported.
    let dir = tempfile::tempdir().unwrap();
    let case = write(
        dir.path(),
        "k.toml",
        r#"
[body1]
rigid = true
[body2]
E = 1e9
nu = 0.2
[gap]
kind = "sphere"
radius = 0.01
[grid]
n = 16
[load]
force = 50.0
[friction]
mu = 0.3
[kinematics]
problem = "shift"
force_x = 5.0
"#,
    );
    let v = json_of(&["contact", &case, "--json"]);
    assert!(v["outer_iterations"].as_u64().unwrap() > 1, "{v}");
    assert!((f(&v, "tangential_force_x") - 5.0).abs() < 1e-4);
    assert!((f(&v, "normal_force") - 50.0).abs() < 1e-6);
}
