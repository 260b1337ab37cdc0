//! `dyncontact run` with `kind = "vehicle_bridge"`, end to end.

mod support;

use std::path::Path;

use support::{dyncontact, write};

/// A 600 kg wheel with 100 kN total load crawling (2 m/s) over a heavily damped (ζ = 0.7)
/// simply supported bridge, Hertz contact.
const CRAWL: &str = r#"
kind = "vehicle_bridge"

[bridge]
length = 25.0
EI = 8.323e9
mass_per_length = 2303.0
supports = "simply_supported"
modes = 40
damping_ratio = 0.7

[vehicle]
speed = 2.0

[[vehicle.wheels]]
position = 0.0
wheel_mass = 600.0
static_load = 94114.0

[contact]
model = "hertz"

[integrator]
method = "generalized_alpha"
rho_inf = 0.5
dt = 2e-3

[output]
every = 10
"#;

fn run_json(dir: &Path, text: &str) -> serde_json::Value {
    let out = dyncontact(&[
        "run",
        &write(dir, "s.toml", text),
        "--out",
        &dir.join("out").to_string_lossy(),
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The summary of a crawl over the span: the largest midspan deflection is the static
/// F L³/(48 EI) with F = 600·9.81 + 94114 = 100 000 N (closed form). Tolerance 3e-4: the
/// quasi-static lag of a damped mode at the maximum is (4ζ² − 1)/ω₁² · ẅ_qs with
/// ẅ_qs = −12 c² w_st/L², i.e. 8e-5 relative at c = 2 m/s, plus 1e-6 of modal truncation.
/// The contact force stays at the weight (1e-4 relative: the wheel follows the deflection
/// curve, m_w c² w'' ≈ 1 N), and every output file and documented JSON key exists.
#[test]
fn crawl_to_midspan_gives_static_deflection_and_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let v = run_json(dir.path(), CRAWL);
    let w_static = 100e3 * 25f64.powi(3) / (48.0 * 8.323e9);
    let w = v["max_midspan_deflection"].as_f64().unwrap();
    println!("w = {w}, static {w_static}, rel {:.2e}", w / w_static - 1.0);
    assert!((w / w_static - 1.0).abs() < 3e-4, "{w} vs {w_static}");
    for key in ["max_force", "min_force"] {
        let f = v["contact"][key].as_f64().unwrap();
        assert!((f / 100e3 - 1.0).abs() < 1e-4, "{key} = {f}");
    }
    assert_eq!(v["contact"]["loss_of_contact_events"].as_u64(), Some(0));
    assert!(v["dynamic_amplification"].as_f64().unwrap() > 0.99);
    assert!(v["vehicle"]["max_body_acceleration"].is_number());
    for key in [
        "method",
        "mean_iterations_per_step",
        "max_iterations_per_step",
        "mean_contact_iterations_per_step",
        "failed_steps",
    ] {
        assert!(!v["solver"][key].is_null(), "solver.{key}");
    }
    assert!(v["wall_time_s"].as_f64().unwrap() > 0.0);
    assert!((v["simulated_time_s"].as_f64().unwrap() - 12.5).abs() < 1e-9);
    for file in [
        "timeseries.csv",
        "summary.json",
        "contact_force.png",
        "midspan.png",
        "vehicle.png",
        "pressure.png",
    ] {
        assert!(dir.path().join("out").join(file).exists(), "{file}");
    }
    let csv = std::fs::read_to_string(dir.path().join("out/timeseries.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    for col in [
        "t_s",
        "deflection_midspan_m",
        "acceleration_midspan_m_s2",
        "position_m",
        "wheel_z_m",
        "body_acceleration_m_s2",
        "contact_force_n",
        "approach_m",
        "patch_length_m",
        "patch_width_m",
        "max_pressure_pa",
    ] {
        assert!(header.split(',').any(|h| h == col), "column {col}");
    }
}

fn run_err(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dyncontact(&[
        "run",
        &write(dir.path(), "s.toml", text),
        "--out",
        &dir.path().join("out").to_string_lossy(),
    ]);
    assert!(!out.status.success(), "accepted:\n{text}");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Bad input is a clear error naming the key, never a panic.
#[test]
fn bad_input_names_the_key() {
    let e = run_err(&CRAWL.replace("wheel_mass = 600.0", "wheel_mass = -1.0"));
    assert!(e.contains("vehicle.wheels[0].wheel_mass"), "{e}");
    let e = run_err(&CRAWL.replace("model = \"hertz\"", "model = \"hertz\"\nnu = 0.5"));
    assert!(e.contains("contact.nu"), "{e}");
    let e = run_err(&CRAWL.replace("speed = 2.0", "speed = 2.0\nsped = 1.0"));
    assert!(e.contains("sped"), "{e}");
    let e = run_err(&CRAWL.replace("model = \"hertz\"", "model = \"elastic\""));
    assert!(e.contains("model"), "{e}");
    let e = run_err(&CRAWL.replace("dt = 2e-3", "dt = -1e-3"));
    assert!(e.contains("integrator.dt"), "{e}");
    let e = run_err(&CRAWL.replace(
        "[contact]\nmodel = \"hertz\"",
        "[contact]\nmodel = \"rigid\"\n[coupling]\nsolver = \"picard\"",
    ));
    assert!(e.contains("coupling.solver"), "{e}");
    let e = run_err(
        &CRAWL
            .replace(
                "[vehicle]\nspeed = 2.0\n",
                "[vehicle]\nspeed = 2.0\nwheels = []\n",
            )
            .replace(
                "[[vehicle.wheels]]\nposition = 0.0\nwheel_mass = 600.0\nstatic_load = 94114.0\n",
                "",
            ),
    );
    assert!(e.contains("wheels"), "{e}");
}

/// The sprung-mass benchmark (references.md §D1.3, examples/vehicle_bridge_biggs.toml) against an
/// independent RK4 (Δt = 1e-5 s) of Biggs's two-DOF model with one mode and a massless wheel:
/// `q̈ + ω₁² q = φ(ct) k_v (z − φ(ct) q)`, `M_v z̈ = M_v g − k_v (z − φ(ct) q)`, φ the
/// mass-normalised first mode √(2/(ρA L)) sin(πx/L), ω₁ = (π/L)²√(EI/ρA), starting from the
/// static spring compression. The example's wheel is massless (`wheel_mass = 0`), exactly as in
/// Biggs's model, so the only differences are the time discretisation (Δt = 1e-4 s,
/// generalized-α): the largest midspan deflection must agree to 1e-4 (measured 9.6e-6) and the
/// largest body acceleration to 5e-4 (measured 5e-5). The quasi-static deflection
/// of one mode is (96/π⁴) M_v g L³/(48 EI) = 0.985545 × 2.2062 mm (references.md §D1.3).
#[test]
fn biggs_sprung_mass_example_matches_independent_two_dof_integration() {
    let dir = tempfile::tempdir().unwrap();
    let example = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/vehicle_bridge_biggs.toml"
    );
    let out = dyncontact(&[
        "run",
        example,
        "--out",
        &dir.path().join("out").to_string_lossy(),
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let (l, ei, rho, mv, kv, c, g): (f64, f64, f64, f64, f64, f64, f64) =
        (25.0, 2.87e9 * 2.90, 2303.0, 5750.0, 1595e3, 27.78, 9.81);
    let pi = std::f64::consts::PI;
    let omega = (pi / l).powi(2) * (ei / rho).sqrt();
    let amp = (2.0 / (rho * l)).sqrt();
    let phi = |t: f64| {
        let x = c * t;
        if (0.0..=l).contains(&x) {
            amp * (pi * x / l).sin()
        } else {
            0.0
        }
    };
    let f = |t: f64, y: [f64; 4]| {
        let p = phi(t);
        let spring = kv * (y[2] - p * y[0]);
        [
            y[1],
            p * spring - omega * omega * y[0],
            y[3],
            g - spring / mv,
        ]
    };
    let h = 1e-5;
    let steps = (l / c / h).round() as usize;
    let mut y = [0.0, 0.0, mv * g / kv, 0.0];
    let (mut w_max, mut a_max) = (0.0f64, 0.0f64);
    for i in 0..steps {
        let t = i as f64 * h;
        let k1 = f(t, y);
        let k2 = f(t + 0.5 * h, std::array::from_fn(|j| y[j] + 0.5 * h * k1[j]));
        let k3 = f(t + 0.5 * h, std::array::from_fn(|j| y[j] + 0.5 * h * k2[j]));
        let k4 = f(t + h, std::array::from_fn(|j| y[j] + h * k3[j]));
        for j in 0..4 {
            y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
        w_max = w_max.max((y[0] * amp).abs());
        a_max = a_max.max((g - kv * (y[2] - phi(t + h) * y[0]) / mv).abs());
    }
    let w = v["max_midspan_deflection"].as_f64().unwrap();
    let a = v["vehicle"]["max_body_acceleration"].as_f64().unwrap();
    let qs = v["max_quasi_static_deflection"].as_f64().unwrap();
    println!(
        "Biggs: w_max {w:.6e} vs RK4 {w_max:.6e}; body a_max {a:.5} vs {a_max:.5}; quasi-static {qs:.6e}"
    );
    assert!((w / w_max - 1.0).abs() < 1e-4);
    assert!((a / a_max - 1.0).abs() < 5e-4);
    assert!((qs / (96.0 / pi.powi(4) * 2.2062e-3) - 1.0).abs() < 1e-3);
}
