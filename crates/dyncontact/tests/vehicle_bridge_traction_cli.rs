//! `dyncontact run` with a `[traction]` section, end to end: the time-series columns, the
//! summary's `traction` object against Kalker's linear theory, and input errors naming the key.

mod support;

use std::path::Path;
use std::process::Output;

use halfspace::{Hertz, Material, creep_coefficients};
use sim::config::vehicle_bridge::DEFAULT_GEOMETRY as G;

use support::dyncontact;

/// A 600 kg wheel with 50 kN extra load rolling at 2 m/s on the rigid approach track (it starts
/// at x = −3 m and runs 0.5 s, so the normal force is the static W = 600·9.81 + 50e3 N).
fn scenario(traction: &str) -> String {
    format!(
        r#"
kind = "vehicle_bridge"

[bridge]
length = 25.0
EI = 8.323e9
mass_per_length = 2303.0
supports = "simply_supported"
modes = 4
damping_ratio = 0.02

[vehicle]
speed = 2.0

[[vehicle.wheels]]
position = -3.0
wheel_mass = 600.0
static_load = 50e3

[contact]
model = "hertz"

[integrator]
method = "generalized_alpha"
dt = 1e-3
duration = 0.5

[traction]
{traction}
"#
    )
}

fn run(dir: &Path, text: &str) -> Output {
    let path = dir.join("s.toml");
    std::fs::write(&path, text).unwrap();
    dyncontact(&[
        "run",
        &path.to_string_lossy(),
        "--out",
        &dir.join("out").to_string_lossy(),
        "--json",
    ])
}

/// Linear theory with braking creepage ξ = 1e-4: every recorded step carries
/// F_x = −G c² C₁₁ ξ on the Hertz ellipse under W (Kalker's coefficient from the halfspace
/// table; the semi-axes from the closed-form Hertz solution) to 1e-9 relative (round-off: the
/// normal force is W to machine precision on the rigid approach track); the CSV has the three
/// documented columns, and summary.json the `traction` object with
/// `bridge_horizontal_load_applied = false`.
#[test]
fn linear_braking_reports_kalker_force() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &scenario("mu = 0.3\nmethod = \"linear\"\ncreepage = 1e-4"),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let w = 600.0 * 9.81 + 50e3;
    let mat = Material::identical(G.youngs_modulus, G.poisson_ratio).unwrap();
    let h = Hertz::elliptic(
        0.5 / G.wheel_radius,
        0.5 / G.rail_profile_radius,
        mat.e_star,
        w,
    )
    .unwrap();
    let c11 = creep_coefficients(h.a, h.b, G.poisson_ratio).unwrap().c11;
    let reference = -mat.g * h.a * h.b * c11 * 1e-4;
    let t = &v["traction"];
    let mean = t["mean_longitudinal_force"].as_f64().unwrap();
    println!("mean F_x {mean} N, Kalker {reference} N");
    assert!((mean / reference - 1.0).abs() < 1e-9);
    assert!((t["max_longitudinal_force"].as_f64().unwrap() / reference - 1.0).abs() < 1e-9);
    assert_eq!(t["method"], "linear");
    assert_eq!(t["saturated_steps"], 0);
    assert_eq!(t["bridge_horizontal_load_applied"], false);
    let csv = std::fs::read_to_string(dir.path().join("out/timeseries.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (fx, xi, adh) = (
        col("longitudinal_force_n"),
        col("creepage"),
        col("adhesion_fraction"),
    );
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    assert!((last[fx] / reference - 1.0).abs() < 1e-9);
    assert_eq!(last[xi], 1e-4);
    assert_eq!(last[adh], 1.0);
}

/// Bad `[traction]` input fails with a message naming the key (no panic).
#[test]
fn traction_input_errors_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    for (section, key) in [
        ("mu = -0.3\ncreepage = 1e-3", "traction.mu"),
        ("mu = 0.3\ncreepage = 1e-3\nfoo = 1", "foo"),
        ("mu = 0.3\ntorque = 100.0", "wheel_inertia"),
        ("mu = 0.3\ncreepage = 1e-3\ntorque = 1.0", "creepage"),
        ("mu = 0.3", "creepage"),
        ("mu = 0.3\nmethod = \"magic\"\ncreepage = 1e-3", "method"),
        (
            "mu = 0.3\nmethod = \"exact\"\ncreepage = 1e-3",
            "traction.method",
        ),
        (
            "mu = 0.3\ntorque = 10.0\nwheel_inertia = -1.0",
            "traction.wheel_inertia",
        ),
    ] {
        let out = run(dir.path(), &scenario(section));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{section}: should fail");
        assert!(err.contains(key), "{section}: `{err}` should name {key}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// Two wheels (the second with a 10 kN smaller extra load): every wheel's block of columns
/// keeps its order with the three traction columns at its end, each wheel's F_x is Kalker's
/// −G c² C₁₁ ξ for its own static load (1e-9), and the shipped braking example runs.
#[test]
fn two_wheels_get_their_own_traction_columns() {
    let dir = tempfile::tempdir().unwrap();
    let text = scenario("mu = 0.3\nmethod = \"linear\"\ncreepage = 1e-4").replace(
        "[contact]",
        "[[vehicle.wheels]]\nposition = -5.0\nwheel_mass = 600.0\nstatic_load = 40e3\n\n[contact]",
    );
    let out = run(dir.path(), &text);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.path().join("out/timeseries.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    let mat = Material::identical(G.youngs_modulus, G.poisson_ratio).unwrap();
    for (k, p) in [(0, 50e3), (1, 40e3)] {
        // Wheel k's column: the index before the unit (`contact_force_1_n`, `creepage_1`).
        let col = |name: &str, unit: &str| {
            header
                .iter()
                .position(|h| *h == format!("{name}_{k}{unit}"))
                .unwrap()
        };
        assert_eq!(
            col("longitudinal_force", "_n"),
            col("max_pressure", "_pa") + 1
        );
        assert_eq!(col("adhesion_fraction", ""), col("max_pressure", "_pa") + 3);
        let w = 600.0 * 9.81 + p;
        assert!((last[col("contact_force", "_n")] / w - 1.0).abs() < 1e-9);
        let h = Hertz::elliptic(
            0.5 / G.wheel_radius,
            0.5 / G.rail_profile_radius,
            mat.e_star,
            w,
        )
        .unwrap();
        let c11 = creep_coefficients(h.a, h.b, G.poisson_ratio).unwrap().c11;
        let reference = -mat.g * h.a * h.b * c11 * 1e-4;
        assert!((last[col("longitudinal_force", "_n")] / reference - 1.0).abs() < 1e-9);
        assert_eq!(last[col("creepage", "")], 1e-4);
    }
    // The shipped braking example, shortened to 40 steps: it runs, and its FASTSIM braking force
    // at ξ = 2e-3 lies between 0.5 and 1 × μF_n (the linear theory would exceed μF_n; the
    // worked example in docs/vehicle_bridge.md measures 0.777 μF_n in its first step).
    let example = include_str!("../../../examples/vehicle_bridge_braking.toml")
        .replace("dt = 2.5e-4", "dt = 2.5e-4\nduration = 0.01");
    let out = run(dir.path(), &example);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let fx = v["traction"]["mean_longitudinal_force"].as_f64().unwrap();
    let fn_max = v["contact"]["max_force"].as_f64().unwrap();
    assert_eq!(v["traction"]["method"], "fastsim");
    assert!(fx < -0.5 * 0.3 * fn_max && fx > -0.3 * fn_max, "{fx}");
}
