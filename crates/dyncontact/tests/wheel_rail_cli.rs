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
