//! `dyncontact modes` and `run` with `kind = "moving_load"`, end to end, against closed forms.

// Reference roots are copied verbatim (20 digits) from references.md §D1.6.
#![allow(clippy::excessive_precision)]

mod support;

use std::process::Output;

use support::{dyncontact, write};

const BRIDGE: &str = r#"
[bridge]
length = 25.0
EI = 8.323e9
mass_per_length = 2303.0
supports = "simply_supported"
modes = 8
"#;

fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn simply_supported_modes_match_the_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    let v = json(&dyncontact(&[
        "modes",
        &write(dir.path(), "b.toml", BRIDGE),
        "--json",
    ]));
    let modes = v["modes"].as_array().unwrap();
    assert_eq!(modes.len(), 8);
    for (k, m) in modes.iter().enumerate() {
        let n = (k + 1) as f64;
        let omega = (n * std::f64::consts::PI / 25.0).powi(2) * (8.323e9_f64 / 2303.0).sqrt();
        assert_eq!(m["n"].as_u64().unwrap(), k as u64 + 1);
        assert!((m["beta_l"].as_f64().unwrap() / (n * std::f64::consts::PI) - 1.0).abs() < 1e-14);
        assert!((m["omega"].as_f64().unwrap() / omega - 1.0).abs() < 1e-12);
        assert!(
            (m["frequency"].as_f64().unwrap() * 2.0 * std::f64::consts::PI / omega - 1.0).abs()
                < 1e-12
        );
    }
    // Clamped–clamped first root (references.md §D1.6).
    let cc = BRIDGE.replace("simply_supported", "clamped_clamped");
    let v = json(&dyncontact(&[
        "modes",
        &write(dir.path(), "c.toml", &cc),
        "--json",
    ]));
    assert!(
        (v["modes"][0]["beta_l"].as_f64().unwrap() / 4.7300407448627040260 - 1.0).abs() < 1e-13
    );
}

#[test]
fn two_span_fe_bridge_has_the_single_span_frequency() {
    // A continuous beam over two equal spans: mode 1 is the simply supported mode of one span
    // (the middle support is a node of the antisymmetric mode); mode 2 the clamped–pinned span
    // mode, βL = 3.9266 per span (references.md §D1.6).
    let dir = tempfile::tempdir().unwrap();
    let text = r#"
[bridge]
length = 40.0
EI = 8.323e9
mass_per_length = 2303.0
modes = 3
elements = 80
supports_at = [0.0, 20.0, 40.0]
"#;
    let out_dir = dir.path().join("modes");
    let v = json(&dyncontact(&[
        "modes",
        &write(dir.path(), "f.toml", text),
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let span = 20.0_f64;
    let c = (8.323e9_f64 / 2303.0).sqrt();
    let w1 = (std::f64::consts::PI / span).powi(2) * c;
    let w2 = (3.9266023120479187782 / span).powi(2) * c;
    // Hermite cubics, 40 elements per span: eigenvalue error O(h⁴) ≈ 1e-9 relative.
    assert!((v["modes"][0]["omega"].as_f64().unwrap() / w1 - 1.0).abs() < 1e-7);
    assert!((v["modes"][1]["omega"].as_f64().unwrap() / w2 - 1.0).abs() < 1e-7);
    let csv = std::fs::read_to_string(out_dir.join("mode_shapes.csv")).unwrap();
    assert!(csv.starts_with("x_m,w1_1_sqrt_kg,w2_1_sqrt_kg,w3_1_sqrt_kg\n"));
    assert_eq!(
        &std::fs::read(out_dir.join("modes.png")).unwrap()[1..4],
        b"PNG"
    );
}

#[test]
fn moving_force_reproduces_frybas_table() {
    // Undamped, α = c/(2 f₁ L) = 0.5: max midspan deflection 1.7054 δ_st (references.md §D1.1).
    let dir = tempfile::tempdir().unwrap();
    let f1 = (std::f64::consts::PI / 25.0).powi(2) * (8.323e9_f64 / 2303.0).sqrt()
        / (2.0 * std::f64::consts::PI);
    let speed = 0.5 * 2.0 * f1 * 25.0;
    let text = format!(
        "kind = \"moving_load\"\n{}\n[load]\nforce = 56.4e3\nspeed = {speed}\n[integrator]\nmethod = \"exact\"\ndt = 2e-5\n",
        BRIDGE.replace("modes = 8", "modes = 20")
    );
    let out_dir = dir.path().join("run");
    let v = json(&dyncontact(&[
        "run",
        &write(dir.path(), "m.toml", &text),
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let st = 56.4e3 * 25.0_f64.powi(3) / (48.0 * 8.323e9);
    assert!(
        (v["static_midspan_deflection_closed_form"].as_f64().unwrap() / st - 1.0).abs() < 1e-12
    );
    // Table value to 4 decimals; 20 modes and Δt = 2e-5 s resolve it to well below 1e-4.
    let ratio = v["max_midspan_deflection"].as_f64().unwrap() / st;
    assert!((ratio - 1.7054).abs() < 1e-4, "{ratio}");
    for key in [
        "dynamic_amplification",
        "max_midspan_acceleration",
        "max_midspan_moment",
        "modes_used",
        "wall_time_s",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["modes_used"].as_u64().unwrap(), 20);
    let csv = std::fs::read_to_string(out_dir.join("timeseries.csv")).unwrap();
    assert!(csv.starts_with("t_s,load_position_m,deflection_midspan_m,"));
    assert!(out_dir.join("midspan_deflection.png").exists());
}

#[test]
fn bridge_errors_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "EI = 8.323e9",
            "EI = -1.0",
            &["`bridge.EI` = -1", "must lie in"],
        ),
        ("modes = 8", "modes = 0", &["[bridge]", "modes"]),
        ("modes = 8", "modes = 8\nfoo = 1", &["unknown field", "foo"]),
        (
            "\"simply_supported\"",
            "\"hinged\"",
            &["supports", "hinged"],
        ),
        ("EI = 8.323e9", "EI = 8.323e9\nE = 2e11", &["EI", "E"]),
        ("mass_per_length = 2303.0\n", "", &["mass_per_length"]),
    ];
    for (from, to, needles) in cases {
        let out = dyncontact(&[
            "modes",
            &write(dir.path(), "bad.toml", &BRIDGE.replacen(from, to, 1)),
        ]);
        assert!(!out.status.success(), "accepted `{to}`");
        let message = String::from_utf8_lossy(&out.stderr);
        for needle in *needles {
            assert!(
                message.contains(needle),
                "error for `{to}` lacks `{needle}`: {message}"
            );
        }
    }
    let text = format!(
        "kind = \"moving_load\"\n{BRIDGE}\n[load]\nforce = 1.0\naxles = [[0.0, 1.0]]\nspeed = 10.0\n"
    );
    let out = dyncontact(&[
        "run",
        &write(dir.path(), "m.toml", &text),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("[load]"));
    let text = format!("kind = \"moving_load\"\n{BRIDGE}\n[load]\nforce = 1.0\nspeed = -10.0\n");
    let out = dyncontact(&[
        "run",
        &write(dir.path(), "m.toml", &text),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("speed"));
}
