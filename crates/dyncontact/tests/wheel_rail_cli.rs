//! `dyncontact contact` / `run` / `profile-sweep` with `[gap] kind = "wheel_rail"`: dispatch
//! and input errors (exit code 2, the key, the value and the allowed range named).

mod support;

use support::{code, dyncontact, example, json_of, write};

const CASE: &str = r#"
kind = "contact"
[body1]
E = 210e9
nu = 0.3
[body2]
E = 210e9
nu = 0.3
[gap]
kind = "wheel_rail"
wheel = "S1002"
rail = "60E1"
inclination = "INCL"
lateral_shift = 0.002
[load]
force = 80e3
[grid]
n = 32
"#;

/// `run` and `contact` solve the same wheel–rail case; the vertical force is met on both
/// wheels and Δr is odd in the shift (the left wheel of +y is the right wheel of −y).
#[test]
fn run_and_contact_agree_and_the_left_wheel_mirrors_the_right() {
    let dir = tempfile::tempdir().unwrap();
    let plus = write(dir.path(), "plus.toml", &CASE.replace("INCL", "1:40"));
    let minus = write(
        dir.path(),
        "minus.toml",
        &CASE
            .replace("INCL", "1:40")
            .replace("lateral_shift = 0.002", "lateral_shift = -0.002"),
    );
    let out = dir.path().join("o").to_string_lossy().into_owned();
    let a = json_of(&["contact", &plus, "--json", "--out", &out]);
    let b = json_of(&["run", &plus, "--json", "--out", &out]);
    let m = json_of(&["contact", &minus, "--json", "--out", &out]);
    let f = |v: &serde_json::Value, p: &str| support::num(v, p);
    assert_eq!(f(&a, "delta_r"), f(&b, "delta_r"));
    assert!((f(&a, "right/vertical_force") / 80e3 - 1.0).abs() < 1e-6);
    assert!((f(&a, "left/vertical_force") / 80e3 - 1.0).abs() < 1e-6);
    assert!((f(&a, "delta_r") + f(&m, "delta_r")).abs() < 1e-12);
    assert!((f(&a, "right/lateral_force") - f(&m, "left/lateral_force")).abs() < 1e-6 * 80e3);
}

#[test]
fn bad_wheel_rail_inputs_name_key_value_and_range() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            CASE.replace("INCL", "1:10"),
            ["gap.inclination", "0.1", "[0, 0.05]"],
        ),
        (
            CASE.replace("INCL", "1:40").replace("\"S1002\"", "\"XYZ\""),
            ["`wheel`", "XYZ", "S1002"],
        ),
        (
            CASE.replace("INCL", "1:40")
                .replace("lateral_shift = 0.002", "lateral_shift = 0.05"),
            ["gap.lateral_shift", "0.05", "[-0.02, 0.02]"],
        ),
        (
            CASE.replace("INCL", "1:40").replace("n = 32", "n = 4"),
            ["grid.n", "4", "[8, 512]"],
        ),
    ];
    for (k, (text, needles)) in cases.iter().enumerate() {
        let file = write(dir.path(), &format!("bad{k}.toml"), text);
        for args in [
            vec!["contact", file.as_str()],
            vec!["profile-sweep", file.as_str()],
        ] {
            let o = dyncontact(&args);
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(code(&o), Some(2), "{args:?}: {err}");
            for n in needles {
                assert!(err.contains(n), "{args:?}: `{n}` not in: {err}");
            }
        }
    }
    // profile-sweep of a case that is not wheel_rail.
    let o = dyncontact(&[
        "profile-sweep",
        example("hertz_sphere.toml").to_str().unwrap(),
    ]);
    assert_eq!(code(&o), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("wheel_rail"));
}

/// A measured-profile file: 60E1 sampled every 0.1 mm, written z-down in mm like CONTACT's
/// rail files, read back through the interpolating spline, gives the built-in rail's
/// results: contact position to 1 µm, Δr to 0.1 µm, peak pressure to 0.5 % (the spline
/// rounds the curvature jumps at the arc joins over one 0.1 mm interval).
#[test]
fn a_measured_rail_file_reproduces_the_built_in_rail() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("# 60E1 head, y [mm], z down [mm]\n");
    // The head between ±36.5 mm (the 1:20 flanks start at ±36.0 mm).
    let rail = sim_rail_points();
    for (y, z) in rail {
        text.push_str(&format!("{y:.6} {z:.9}\n"));
    }
    write(dir.path(), "rail.txt", &text);
    let base = CASE
        .replace("INCL", "1:40")
        .replace("lateral_shift = 0.002", "lateral_shift = 0.003");
    let builtin = write(dir.path(), "builtin.toml", &base);
    let measured = write(
        dir.path(),
        "measured.toml",
        &base.replace("rail = \"60E1\"", "rail = \"rail.txt\""),
    );
    let out = dir.path().join("o").to_string_lossy().into_owned();
    let a = json_of(&["contact", &builtin, "--json", "--out", &out]);
    let b = json_of(&["contact", &measured, "--json", "--out", &out]);
    let f = |v: &serde_json::Value, p: &str| support::num(v, p);
    assert!((f(&a, "right/rail_y") - f(&b, "right/rail_y")).abs() < 1e-6);
    assert!((f(&a, "delta_r") - f(&b, "delta_r")).abs() < 1e-7);
    let (pa, pb) = (
        f(&a, "right/patches/0/max_pressure"),
        f(&b, "right/patches/0/max_pressure"),
    );
    assert!((pa / pb - 1.0).abs() < 5e-3, "{pa} vs {pb}");
}

/// 60E1's head as (y, z-down) in mm every 0.1 mm over ±36.5 mm, from the tangent
/// construction's published dimensions (references.md §W1.2) recomputed here.
fn sim_rail_points() -> Vec<(f64, f64)> {
    // Crown R300 to 10.228, R80 to 26.0265, R13, then the 1:20 flank.
    let (y1, y2) = (10.228f64, 26.0265f64);
    let c0 = (0.0, 300.0);
    let z1 = 300.0 - (300.0f64 * 300.0 - y1 * y1).sqrt();
    let n1 = ((c0.0 - y1) / 300.0, (c0.1 - z1) / 300.0);
    let c1 = (y1 + 80.0 * n1.0, z1 + 80.0 * n1.1);
    let z2 = c1.1 - (80.0f64 * 80.0 - (y2 - c1.0).powi(2)).sqrt();
    let n2 = ((c1.0 - y2) / 80.0, (c1.1 - z2) / 80.0);
    let c2 = (y2 + 13.0 * n2.0, z2 + 13.0 * n2.1);
    let a = (1.0f64 / 20.0).atan();
    let y3 = c2.0 + 13.0 * a.cos();
    let z3 = c2.1 - 13.0 * a.sin();
    let half = |y: f64| -> f64 {
        if y <= y1 {
            300.0 - (300.0 * 300.0 - y * y).sqrt()
        } else if y <= y2 {
            c1.1 - (80.0 * 80.0 - (y - c1.0).powi(2)).sqrt()
        } else if y <= y3 {
            c2.1 - (13.0 * 13.0 - (y - c2.0).powi(2)).sqrt()
        } else {
            z3 + (y - y3) * 20.0
        }
    };
    (-365..=365)
        .map(|k| {
            let y = 0.1 * k as f64;
            (y, half(y.abs()))
        })
        .collect()
}

/// The profiles `contact` writes (wheel_profile.txt, rail_profile.txt, 0.1 mm steps) read
/// back as profile files reproduce the run: contact positions to 5 µm, Δr to 0.5 µm, peak
/// pressure to 0.5 %. Measured: 1.5 µm on the wheel, 0.7 µm on the rail, 0.13 µm in Δr — the
/// tread contact is nearly conformal, so its position magnifies the spline's tiny curvature
/// error (δs ≈ δκ-error / (κ_w − κ_r)).
#[test]
fn written_profiles_read_back_reproduce_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let text = CASE
        .replace("INCL", "1:40")
        .replace("lateral_shift = 0.002", "lateral_shift = 0.003");
    let case = write(dir.path(), "case.toml", &text);
    let out = dir.path().join("o");
    let a = json_of(&["contact", &case, "--json", "--out", out.to_str().unwrap()]);
    for name in ["wheel_profile.txt", "rail_profile.txt"] {
        std::fs::copy(out.join(name), dir.path().join(name)).unwrap();
    }
    let again = write(
        dir.path(),
        "again.toml",
        &text
            .replace("wheel = \"S1002\"", "wheel = \"wheel_profile.txt\"")
            .replace("rail = \"60E1\"", "rail = \"rail_profile.txt\""),
    );
    let out2 = dir.path().join("o2").to_string_lossy().into_owned();
    let b = json_of(&["contact", &again, "--json", "--out", &out2]);
    let f = |v: &serde_json::Value, p: &str| support::num(v, p);
    assert!((f(&a, "right/rail_y") - f(&b, "right/rail_y")).abs() < 5e-6);
    assert!((f(&a, "right/wheel_s") - f(&b, "right/wheel_s")).abs() < 5e-6);
    assert!((f(&a, "delta_r") - f(&b, "delta_r")).abs() < 5e-7);
    let (pa, pb) = (
        f(&a, "right/patches/0/max_pressure"),
        f(&b, "right/patches/0/max_pressure"),
    );
    assert!((pa / pb - 1.0).abs() < 5e-3, "{pa} vs {pb}");
}
