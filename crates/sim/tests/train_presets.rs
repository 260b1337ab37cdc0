//! The real-train presets (`sim::train::presets`, references.md §T4–§T9, docs/trains.md):
//! axle counts, lengths, static axle loads and masses against hand computations from the
//! published numbers; the bogie vehicles' body bounce and pitch frequencies on a rigid track
//! two independent ways (the closed form of `train::bogie_vehicle` and a QZ generalized
//! eigenvalue solve of the assembled K, M with the wheelsets fixed, modes identified by their
//! eigenvectors); and a golden test that docs/trains.md quotes exactly the computed numbers.

use faer::Mat;
use faer::linalg::solvers::GeneralizedEigen;
use sim::train::bogie_vehicle::FIRST_WHEEL;
use sim::train::{BogieVehicle, Train, VehicleSpec, presets};

const G: f64 = 9.81;

fn preset(name: &str) -> Train {
    presets::by_name(name).unwrap_or_else(|| panic!("preset {name}"))
}

/// (axles, first-to-last axle \[m\], mass \[kg\], distinct axle loads \[kg\] × g in running order).
struct Expected {
    name: &'static str,
    axles: usize,
    length: f64,
    mass: f64,
    axle_masses: &'static [f64],
}

/// Hand computations from the published parameters (docs/trains.md):
/// bogie vehicle axle = m_body/4 + m_bogie/2 + m_wheelset; articulated end bogie axle
/// = (m_body/2 + m_bogie)/2 + m_ws, inner = (m_body + m_bogie)/2 + m_ws; a body whose centre
/// of gravity lies f ahead of one support and r behind the other puts m r/(f + r) on the
/// first and m f/(f + r) on the second (lever rule).
const EXPECTED: [Expected; 7] = [
    Expected {
        name: "Manchester",
        axles: 4,
        length: 19.0 + 2.56,
        // 32 000 + 2 × 2615 + 4 × 1813
        mass: 44_482.0,
        axle_masses: &[8000.0 + 1307.5 + 1813.0],
    },
    Expected {
        name: "AVE-S103",
        axles: 32,
        // 7 × 24.775 + 17.375 + 2.5
        length: 193.3,
        // 6 × 47 800 + 2 × 41 200 + 16 × 3500 + 32 × 1800
        mass: 482_800.0,
        axle_masses: &[11_950.0 + 1750.0 + 1800.0, 10_300.0 + 1750.0 + 1800.0],
    },
    Expected {
        name: "AVE-S103-car",
        axles: 4,
        length: 19.875,
        mass: 47_800.0 + 7000.0 + 7200.0,
        axle_masses: &[15_500.0],
    },
    Expected {
        name: "Eurostar",
        // Power cars 2 × 4, the rake's 10 bogies 20.
        axles: 28,
        // Power car: 14 + (6.275 + 3.8) to EC1's leading axle; rake: 9 × 18.7 + (3.265 +
        // 6.275) to the last power car's leading axle; then its 14 + 3.
        length: (14.0 + 6.275 + 3.8) + (9.0 * 18.7 + 3.265 + 6.275) + 17.0,
        // Power cars 2 × (51 500 + 2 × 2200 + 4 × 1700); bodies 35 860 + 7 × 22 525 + 27 122;
        // bogies (2200 + 2 × 1700) + 8 × (2900 + 2 × 1900) + (2900 + 2 × 1900).
        mass: 2.0 * 62_700.0 + 220_657.0 + 5600.0 + 8.0 * 6700.0 + 6700.0,
        axle_masses: &[
            // Power car.
            51_500.0 / 4.0 + 1100.0 + 1700.0,
            // EC1's own bogie: EC1's front end (CG 5.448 m behind it, 13.252 m ahead of J1).
            0.5 * (35_860.0 * 13.252 / 18.7 + 2200.0) + 1700.0,
            // J1: EC1's rear end and EC2's front end (CG 8.926 m behind it, 9.774 m ahead of
            // its rear bogie).
            0.5 * (35_860.0 * 5.448 / 18.7 + 22_525.0 * 9.774 / 18.7 + 2900.0) + 1900.0,
            // J2 … J7: two EC2–EC8 ends, a whole body.
            0.5 * (22_525.0 * 8.926 / 18.7 + 22_525.0 * 9.774 / 18.7 + 2900.0) + 1900.0,
            // J8: EC8's rear end and EC9's front end (EC9's CG 13.252 m behind it).
            0.5 * (22_525.0 * 8.926 / 18.7 + 27_122.0 * 5.448 / 18.7 + 2900.0) + 1900.0,
            // EC9's own bogie (CG 5.448 m ahead of it).
            0.5 * (27_122.0 * 13.252 / 18.7 + 2900.0) + 1900.0,
        ],
    },
    Expected {
        name: "Eurostar-EC2-EC8",
        axles: 16,
        // 7 × 18.7 + 3.0
        length: 133.9,
        // 7 × 22 525 + 8 × (2900 + 2 × 1900)
        mass: 211_275.0,
        axle_masses: &[
            0.5 * (0.5 * 22_525.0 + 2900.0) + 1900.0,
            0.5 * (22_525.0 + 2900.0) + 1900.0,
        ],
    },
    Expected {
        name: "double-deck-coach",
        axles: 4,
        length: 18.0 + 2.4,
        mass: 29_600.0 + 3400.0 + 7600.0,
        axle_masses: &[7400.0 + 850.0 + 1900.0],
    },
    Expected {
        name: "Sgns",
        axles: 4,
        length: 14.2 + 1.82,
        mass: 29_480.0 + 10_000.0 + 12_000.0,
        axle_masses: &[7370.0 + 2500.0 + 3000.0],
    },
];

#[test]
fn presets_have_the_published_axles_lengths_loads_and_masses() {
    assert_eq!(EXPECTED.len(), presets::NAMES.len());
    for e in &EXPECTED {
        let t = preset(e.name);
        let axles = t.axles(G).unwrap();
        assert_eq!(axles.len(), e.axles, "{}", e.name);
        assert!(
            (t.length() - e.length).abs() < 1e-9,
            "{}: {}",
            e.name,
            t.length()
        );
        assert!((t.mass() - e.mass).abs() < 1e-6, "{}: {}", e.name, t.mass());
        // Every axle load is one of the expected ones, each expected one occurs, and the
        // loads sum to the weight (statics).
        for a in &axles {
            assert!(
                e.axle_masses.iter().any(|m| (a.load - m * G).abs() < 1e-6),
                "{}: axle load {} N",
                e.name,
                a.load
            );
        }
        for m in e.axle_masses {
            assert!(axles.iter().any(|a| (a.load - m * G).abs() < 1e-6));
        }
        let total: f64 = axles.iter().map(|a| a.load).sum();
        assert!((total - e.mass * G).abs() < 1e-9 * total, "{}", e.name);
    }
    // AVE S-103: the light cars are the fourth and fifth (axles 12 … 19).
    let ave = preset("AVE-S103").axles(G).unwrap();
    for (i, a) in ave.iter().enumerate() {
        let light = (12..20).contains(&i);
        let m = if light { 13_850.0 } else { 15_500.0 };
        assert!((a.load - m * G).abs() < 1e-6, "axle {i}");
    }
    // Car pitch 24.775 m: every car's leading axle.
    for car in 0..8 {
        assert!((ave[4 * car].offset - 24.775 * car as f64).abs() < 1e-9);
    }
    // Eurostar rake: bogies 18.7 m apart, 3 m wheelbase; end bogies lighter.
    let es = preset("Eurostar-EC2-EC8").axles(G).unwrap();
    for (i, a) in es.iter().enumerate() {
        let x = 18.7 * (i / 2) as f64 + 3.0 * (i % 2) as f64;
        assert!((a.offset - x).abs() < 1e-9, "axle {i}");
    }
    // The whole Eurostar: the axle positions and the load of every axle in running order.
    let loads = EXPECTED[3].axle_masses;
    let whole = preset("Eurostar").axles(G).unwrap();
    let rake = 14.0 + 6.275 + 3.8;
    let last_car = rake + 9.0 * 18.7 + 3.265 + 6.275;
    let mut expected: Vec<(f64, f64)> = Vec::new();
    for x in [0.0, 3.0, 14.0, 17.0] {
        expected.push((x, loads[0]));
    }
    for bogie in 0..10 {
        let m = match bogie {
            0 => loads[1],
            1 => loads[2],
            8 => loads[4],
            9 => loads[5],
            _ => loads[3],
        };
        let x = rake + 18.7 * bogie as f64;
        expected.extend([(x, m), (x + 3.0, m)]);
    }
    for x in [0.0, 3.0, 14.0, 17.0] {
        expected.push((last_car + x, loads[0]));
    }
    assert_eq!(whole.len(), expected.len());
    for (i, (a, (x, m))) in whole.iter().zip(&expected).enumerate() {
        assert!((a.offset - x).abs() < 1e-9, "axle {i}: {} vs {x}", a.offset);
        assert!(
            (a.load - m * G).abs() < 1e-6,
            "axle {i}: {} vs {}",
            a.load,
            m * G
        );
    }
}

/// Body bounce and body pitch \[Hz\] of the 6 body-and-bogie DOFs with the wheelsets fixed,
/// from the QZ generalized eigenvalue solve of (K, M) (faer), modes identified by the share of
/// their kinetic energy in the body bounce (DOF 0) and body pitch (DOF 1) coordinates.
fn generalized_eigen_body_frequencies(v: &BogieVehicle) -> (f64, f64) {
    let m = v.matrices();
    let n = FIRST_WHEEL;
    let k = Mat::<f64>::from_fn(n, n, |i, j| m.stiffness[(i, j)]);
    let mass = Mat::<f64>::from_fn(n, n, |i, j| if i == j { m.mass[i] } else { 0.0 });
    let evd = GeneralizedEigen::new_from_real(k.as_ref(), mass.as_ref()).unwrap();
    let (s_a, s_b, u) = (evd.S_a(), evd.S_b(), evd.U());
    let mut bounce = (0.0, 0.0);
    let mut pitch = (0.0, 0.0);
    for j in 0..n {
        let (a, b) = (s_a[j], s_b[j]);
        let omega2 = (a / b).re;
        assert!((a / b).im.abs() < 1e-9 * omega2.abs(), "complex eigenvalue");
        let energy: Vec<f64> = (0..n).map(|i| u[(i, j)].norm_sqr() * m.mass[i]).collect();
        let total: f64 = energy.iter().sum();
        let f = omega2.sqrt() / std::f64::consts::TAU;
        if energy[0] / total > bounce.0 {
            bounce = (energy[0] / total, f);
        }
        if energy[1] / total > pitch.0 {
            pitch = (energy[1] / total, f);
        }
    }
    // Body modes: the body carries most of their kinetic energy.
    assert!(bounce.0 > 0.5 && pitch.0 > 0.5, "{bounce:?} {pitch:?}");
    (bounce.1, pitch.1)
}

/// The distinct bogie vehicles of the presets: (preset, which cars, vehicle).
fn bogie_vehicles() -> Vec<(&'static str, &'static str, BogieVehicle)> {
    let mut out = Vec::new();
    for name in presets::NAMES {
        let t = preset(name);
        let mut seen: Vec<(BogieVehicle, Vec<usize>)> = Vec::new();
        for (i, v) in t.vehicles.iter().enumerate() {
            if let VehicleSpec::BogieVehicle(b) = v {
                // Cars that differ only in `length` have the same dynamics.
                let key = BogieVehicle { length: 0.0, ..*b };
                match seen.iter_mut().find(|(s, _)| *s == key) {
                    Some((_, cars)) => cars.push(i + 1),
                    None => seen.push((key, vec![i + 1])),
                }
            }
        }
        for (v, cars) in seen {
            let which = match (name, cars.as_slice()) {
                ("AVE-S103", [4, 5]) => "cars 4, 5",
                ("AVE-S103", _) => "cars 1–3, 6–8",
                ("AVE-S103-car", _) => "car 2",
                ("Eurostar", _) => "power cars",
                _ => "car",
            };
            out.push((name, which, v));
        }
    }
    out
}

#[test]
fn body_frequencies_agree_between_closed_form_and_generalized_eigen_solve() {
    let vehicles = bogie_vehicles();
    assert_eq!(vehicles.len(), 7);
    let mut worst: f64 = 0.0;
    for (name, which, v) in &vehicles {
        let closed = v.rigid_track_frequencies();
        let (bounce, pitch) = generalized_eigen_body_frequencies(v);
        println!(
            "{name} {which}: bounce {:.6} / {bounce:.6} Hz, pitch {:.6} / {pitch:.6} Hz",
            closed.body_bounce, closed.body_pitch
        );
        for (x, y) in [(closed.body_bounce, bounce), (closed.body_pitch, pitch)] {
            worst = worst.max((x / y - 1.0).abs());
        }
    }
    println!("largest relative difference {worst:.1e}");
    // QZ is backward stable; the 6 × 6 pencils are well conditioned: 1e-10 is far above
    // round-off (measured ~1e-15) and far below any modelling difference.
    assert!(worst < 1e-10, "{worst}");
}

/// A row of docs/trains.md's preset table.
fn summary_row(t: &Train) -> String {
    let axles = t.axles(G).unwrap();
    let mut loads: Vec<f64> = Vec::new();
    for a in &axles {
        let kn = (a.load / 1e3 * 100.0).round() / 100.0;
        if !loads.contains(&kn) {
            loads.push(kn);
        }
    }
    let loads: Vec<String> = loads.iter().map(|l| format!("{l:.2}")).collect();
    format!(
        "| `{}` | {} | {:.3} | {:.3} | {} |",
        t.name,
        axles.len(),
        t.length(),
        t.mass() / 1e3,
        loads.join(" / ")
    )
}

/// A row of docs/trains.md's frequency table.
fn frequency_row(name: &str, which: &str, v: &BogieVehicle) -> String {
    let f = v.rigid_track_frequencies();
    format!(
        "| `{name}` | {which} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} |",
        f.body_bounce, f.body_pitch, f.bogie_bounce, f.bogie_anti_bounce, f.bogie_pitch
    )
}

#[test]
fn docs_quote_the_computed_numbers() {
    let docs =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/trains.md"))
            .unwrap();
    let mut missing = Vec::new();
    for name in presets::NAMES {
        let row = summary_row(&preset(name));
        println!("{row}");
        if !docs.contains(&row) {
            missing.push(row);
        }
    }
    for (name, which, v) in bogie_vehicles() {
        let row = frequency_row(name, which, &v);
        println!("{row}");
        if !docs.contains(&row) {
            missing.push(row);
        }
    }
    assert!(
        missing.is_empty(),
        "docs/trains.md lacks these rows (or quotes other numbers):\n{}",
        missing.join("\n")
    );
}

#[test]
fn scenario_keys_take_the_presets_and_name_the_known_ones() {
    // `preset` with `count` in a [train] table.
    let text = r#"
kind = "moving_load"
[bridge]
length = 25.0
EI = 1.0e10
mass_per_length = 10000.0
[train]
speed = 50.0
[[train.vehicles]]
preset = "ave-s103-car"
count = 3
"#;
    let table: toml::Table = text.parse().unwrap();
    let train_table: sim::config::train::TrainTable = table["train"].clone().try_into().unwrap();
    let t = sim::config::train::build(&train_table, "train").unwrap();
    assert_eq!(t.vehicles.len(), 3);
    assert_eq!(t.axles(G).unwrap().len(), 12);
    let mut bad = train_table.clone();
    bad.vehicles[0].preset = Some("ICE4".into());
    let e = sim::config::train::build(&bad, "train")
        .unwrap_err()
        .to_string();
    for name in presets::NAMES {
        assert!(e.contains(name), "{e}");
    }
    assert!(e.contains("ICE4") && e.contains("HSLM-A1"), "{e}");
}

#[test]
fn sweep_names_take_the_presets_as_their_static_axle_loads() {
    let text = |names: &str| {
        format!(
            "kind = \"sweep\"\n[bridge]\nlength = 20.0\nEI = 1.9452e10\nmass_per_length = 12000.0\nsupports = \"simply_supported\"\nmodes = 3\ndamping_ratio = 0.01\n[trains]\nnames = [{names}]\n[speeds]\nlist = [50.0]\n"
        )
    };
    let load = |names: &str| {
        sim::config::load(
            &text(names),
            std::path::Path::new("."),
            &sim::config::LoadOptions::default(),
        )
    };
    let config = match load("\"Sgns\", \"ave-s103\", \"HSLM-A1\"").unwrap() {
        sim::config::ScenarioConfig::Sweep(c) => c,
        _ => panic!("not a sweep"),
    };
    let axles = sim::sweep::train_axles(&config.spec).unwrap();
    assert_eq!(axles.iter().map(Vec::len).collect::<Vec<_>>(), [4, 32, 50]);
    let Err(e) = load("\"TGV\"") else {
        panic!("an unknown train name was accepted")
    };
    let e = e.to_string();
    assert!(
        e.contains("TGV") && e.contains("Eurostar-EC2-EC8") && e.contains("HSLM-A"),
        "{e}"
    );
}

#[test]
fn the_train_example_file_is_the_manchester_preset() {
    // examples/train_bridge.toml spells the Manchester car out key by key; the preset is the
    // same vehicle (an independent transcription of §T4).
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/train_bridge.toml"
    ))
    .unwrap();
    let table: toml::Table = text.parse().unwrap();
    let train_table: sim::config::train::TrainTable = table["train"].clone().try_into().unwrap();
    let explicit = sim::config::train::build(&train_table, "train").unwrap();
    let preset = preset("Manchester");
    assert_eq!(explicit.vehicles.len(), 2);
    for v in &explicit.vehicles {
        assert_eq!(v, &preset.vehicles[0]);
    }
}

#[test]
fn the_ave_s103_preset_stands_on_its_statics_in_the_coupled_model() {
    // The eight-car preset on the approach track of a vehicle_bridge run (Hertz contact): every
    // wheelset carries its car's statics, 15 500 kg × g (cars 1–3, 6–8) or 13 850 kg × g
    // (cars 4, 5), and stays there (the static start balances every DOF).
    let mut sim = standing_on_the_approach("AVE-S103");
    assert_eq!(sim.wheels().len(), 32);
    assert_eq!(sim.multibody_vehicle_count(), 8);
    let expected = |i: usize| {
        if (12..20).contains(&i) {
            13_850.0 * G
        } else {
            15_500.0 * G
        }
    };
    for _ in 0..50 {
        sim.step().unwrap();
    }
    for (i, s) in sim.wheels().iter().enumerate() {
        assert!(
            (s.contact.force / expected(i) - 1.0).abs() < 1e-6,
            "wheel {i}: {}",
            s.contact.force
        );
    }
    for v in 0..8 {
        let r = sim.vehicle_response(v).unwrap();
        assert!(r.body_acceleration.abs() < 1e-6, "{r:?}");
    }
}

#[test]
fn the_whole_eurostar_stands_on_its_statics_in_the_coupled_model() {
    // Power car, the nine-body rake with off-centre centres of gravity, power car on the
    // approach track of a vehicle_bridge run (Hertz contact): every wheelset carries the load
    // of the lever-rule hand computation (EXPECTED), at the start and after 50 steps, and the
    // bodies stay at rest.
    let mut sim = standing_on_the_approach("Eurostar");
    assert_eq!(sim.wheels().len(), 28);
    assert_eq!(sim.multibody_vehicle_count(), 3);
    let loads = EXPECTED[3].axle_masses;
    let expected = |i: usize| {
        G * match i {
            0..4 | 24..28 => loads[0],
            4 | 5 => loads[1],
            6 | 7 => loads[2],
            20 | 21 => loads[4],
            22 | 23 => loads[5],
            _ => loads[3],
        }
    };
    for step in 0..=50 {
        for (i, s) in sim.wheels().iter().enumerate() {
            assert!(
                (s.contact.force / expected(i) - 1.0).abs() < 1e-6,
                "step {step}, wheel {i}: {} vs {}",
                s.contact.force,
                expected(i)
            );
        }
        if step < 50 {
            sim.step().unwrap();
        }
    }
    for v in 0..3 {
        let r = sim.vehicle_response(v).unwrap();
        assert!(
            r.body_acceleration.abs() < 1e-6 && r.body_pitch_acceleration.abs() < 1e-6,
            "{r:?}"
        );
    }
}

/// The lowest body-bounce and body-pitch frequencies \[Hz\] of an articulated chain on a
/// rigid track: QZ generalized eigenvalues of (K, M) over the body and bogie DOFs (faer), the
/// modes identified by the share of their kinetic energy in the bodies' z (even DOFs below
/// 2n) or θ (odd DOFs below 2n) coordinates (> 1/2). Each with the body that carries most of
/// that mode's bounce (pitch) energy.
fn chain_body_frequencies(a: &sim::train::Articulated) -> ((f64, usize), (f64, usize)) {
    let m = a.matrices();
    let n = m.own_dofs;
    let k = Mat::<f64>::from_fn(n, n, |i, j| m.stiffness[(i, j)]);
    let mass = Mat::<f64>::from_fn(n, n, |i, j| if i == j { m.mass[i] } else { 0.0 });
    let evd = GeneralizedEigen::new_from_real(k.as_ref(), mass.as_ref()).unwrap();
    let (s_a, s_b, u) = (evd.S_a(), evd.S_b(), evd.U());
    let (mut bounce, mut pitch) = ((f64::INFINITY, 0), (f64::INFINITY, 0));
    let bodies = a.body_count();
    // The body whose coordinate `offset` (0: z, 1: θ) carries the most energy.
    let dominant = |energy: &[f64], offset: usize| {
        (0..bodies)
            .max_by(|&x, &y| energy[2 * x + offset].total_cmp(&energy[2 * y + offset]))
            .unwrap_or(0)
    };
    for j in 0..n {
        let omega2 = (s_a[j] / s_b[j]).re;
        let energy: Vec<f64> = (0..n).map(|i| u[(i, j)].norm_sqr() * m.mass[i]).collect();
        let total: f64 = energy.iter().sum();
        let body_z: f64 = (0..bodies).map(|b| energy[2 * b]).sum();
        let body_theta: f64 = (0..bodies).map(|b| energy[2 * b + 1]).sum();
        let f = omega2.sqrt() / std::f64::consts::TAU;
        if body_z / total > 0.5 && f < bounce.0 {
            bounce = (f, dominant(&energy, 0));
        }
        if body_theta / total > 0.5 && f < pitch.0 {
            pitch = (f, dominant(&energy, 1));
        }
    }
    (bounce, pitch)
}

#[test]
fn the_articulated_presets_have_their_body_frequencies_in_the_docs() {
    let docs =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/trains.md"))
            .unwrap();
    for (name, which) in [
        ("Eurostar-EC2-EC8", "7 bodies"),
        ("Eurostar", "EC1–EC9, 9 bodies"),
    ] {
        let t = preset(name);
        let Some(a) = t.vehicles.iter().find_map(|v| match v {
            VehicleSpec::Articulated(a) => Some(a),
            _ => None,
        }) else {
            panic!("{name} has an articulated rake");
        };
        let ((bounce, bounce_body), (pitch, pitch_body)) = chain_body_frequencies(a);
        println!("{name}: lowest body bounce in body {bounce_body}, pitch in body {pitch_body}");
        if name == "Eurostar" {
            // Both are EC1's (its soft secondary suspension, docs/trains.md).
            assert_eq!((bounce_body, pitch_body), (0, 0));
        }
        // The symmetric eigen-solver of Articulated::rigid_track_frequencies (another
        // algorithm: M^{-1/2} K M^{-1/2}, tridiagonal QR) has both among its frequencies, to
        // 1e-10.
        let all = a.rigid_track_frequencies();
        for f in [bounce, pitch] {
            let nearest = all
                .iter()
                .map(|x| (x / f - 1.0).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(nearest < 1e-10, "{f} vs {all:?}");
        }
        assert!(
            which.ends_with(&format!("{} bodies", a.body_count())),
            "{which}"
        );
        let row = format!("| `{name}` | {which} | {bounce:.3} | {pitch:.3} |");
        println!("{row}");
        assert!(docs.contains(&row), "docs/trains.md lacks {row}");
    }
}

/// The preset train `name` standing on the approach track of a vehicle_bridge run (its leading
/// axle 250 m before the 25 m span, 10 m/s, Hertz contact, generalized-α at Δt = 1e-3 s).
fn standing_on_the_approach(name: &str) -> sim::vehicle_bridge::Simulation {
    let text = format!(
        "kind = \"vehicle_bridge\"\n[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 8\ndamping_ratio = 0.02\n[train]\nspeed = 10.0\nposition = -250.0\n[[train.vehicles]]\npreset = \"{name}\"\n[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"generalized_alpha\"\ndt = 1e-3\nduration = 0.1\n"
    );
    match sim::config::load(
        &text,
        std::path::Path::new("."),
        &sim::config::LoadOptions::default(),
    ) {
        Ok(sim::config::ScenarioConfig::VehicleBridge(v)) => {
            sim::vehicle_bridge::Simulation::with_vehicles(v.scenario, v.vehicles).unwrap()
        }
        Ok(_) => panic!("not vehicle_bridge"),
        Err(e) => panic!("{e}"),
    }
}
