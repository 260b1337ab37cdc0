//! Real wheel and rail profiles as the wheels' contact in the coupled run
//! (`ContactModel::BemProfiles`, `[contact.profiles]`; docs/profiles.md).

use std::sync::Arc;

use beam::{AnalyticBeam, ModalBasis, ModalDamping, Support, UniformBeam};
use halfspace::Material;
use halfspace::law::ContactLaw;
use integrate::structural::StructuralMethod;
use sim::config::vehicle_bridge::DEFAULT_GEOMETRY;
use sim::vehicle_bridge::profiles::ProfileContact;
use sim::vehicle_bridge::{
    ContactGeometry, ContactModel, CouplingSpec, GRAVITY, Integrator, Irregularity, Scenario,
    Simulation, WheelSpec,
};
use wheelrail::{Profile, Roll, Segment, Wheelset, WheelsetParams};

const MM: f64 = 1e-3;

/// A cone of slope tan γ (no inclination) on a circular rail head of radius `r`.
fn cone_on_circle(tan_gamma: f64, r: f64) -> Wheelset {
    let cone = Profile::new(
        "cone",
        vec![Segment::Line {
            y0: -60.0 * MM,
            y1: 60.0 * MM,
            z0: 60.0 * MM * tan_gamma,
            slope: -tan_gamma,
        }],
    )
    .unwrap();
    let circle = Profile::new(
        "circle",
        vec![Segment::Arc {
            y0: -35.0 * MM,
            y1: 35.0 * MM,
            yc: 0.0,
            zc: -r,
            r,
            upper: true,
        }],
    )
    .unwrap();
    let params = WheelsetParams {
        inclination: 0.0,
        gauge_depth: 1.0 * MM,
        ..WheelsetParams::default()
    };
    Wheelset::new(cone, circle, params).unwrap()
}

/// The quarter car of `vehicle_bridge_bem.rs` (600 kg wheel, 5750 kg body, W = 62.3 kN) over
/// a 0.5 mm dip on a 25 m span: the wheel's contact force and the midspan deflection.
fn run(contact: ContactModel, geometry: ContactGeometry) -> (Vec<f64>, Vec<f64>, Simulation) {
    let basis: Box<dyn ModalBasis> = Box::new(
        AnalyticBeam::new(
            Support::SimplySupported,
            UniformBeam::new(25.0, 2.87e9 * 2.90, 2303.0).unwrap(),
            10,
        )
        .unwrap(),
    );
    let scenario = Scenario {
        moving_forces: Vec::new(),
        bridge: basis,
        damping: ModalDamping::Uniform(0.02),
        wheels: vec![WheelSpec {
            position: 0.0,
            wheel_mass: 600.0,
            body_mass: 5750.0,
            suspension_stiffness: 1595e3,
            suspension_damping: 2e4,
            static_load: 0.0,
        }],
        speed: 27.78,
        contact,
        geometry,
        irregularity: Irregularity::Dip {
            position: 3.0,
            length: 0.6,
            depth: 0.5e-3,
        },
        integrator: Integrator::Structural(StructuralMethod::generalized_alpha(0.8).unwrap()),
        dt: 2.5e-4,
        duration: Some(0.2),
        coupling: CouplingSpec {
            tol: 1e-7,
            ..CouplingSpec::default()
        },
        gravity: GRAVITY,
        output_point: 12.5,
    };
    let mut sim = Simulation::new(scenario).unwrap();
    let mut forces = Vec::new();
    let mut defl = Vec::new();
    sim.run(|s| {
        forces.push(s.wheels()[0].contact.force);
        defl.push(s.output_point_response().0);
    })
    .unwrap();
    (forces, defl, sim)
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

fn peak(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// A cone (tan γ = 1/20) on a circular head (R = 300 mm) in the coupled run equals the Hertz
/// law with the equivalent radii: the vertical force at a vertical approach δ is
/// F_v = cos γ F_n(δ cos γ) with Hertz's F_n = C(A, B, E*) δ_n^{3/2}, A = cos γ/(2 r_c),
/// B = 1/(2R) (references.md §W3.1, §W3.2), which is the vehicle–bridge Hertz law of a wheel of
/// radius r_c/cos γ on a head of radius R with Young's modulus E cos^{5/2} γ. The difference of
/// the force histories over the dip shrinks with the patch grid (the BEM discretisation of
/// the patch: F at Hertz's static approach is 2.1e-3 off on 16 × 16 elements, 3.2e-4 on
/// 32 × 32) and stays below 1.5 × that static error of the grid.
#[test]
fn cone_on_circle_equals_hertz_with_the_equivalent_radii() {
    let tan_g: f64 = 1.0 / 20.0;
    let r = 0.3;
    let ws = Arc::new(cone_on_circle(tan_g, r));
    let rc = ws
        .contact(0.0, Roll::Fixed(0.0))
        .unwrap()
        .right
        .rolling_radius();
    let gamma = tan_g.atan();
    let hertz_geometry = ContactGeometry {
        wheel_radius: rc / gamma.cos(),
        rail_profile_radius: r,
        youngs_modulus: DEFAULT_GEOMETRY.youngs_modulus * gamma.cos().powf(2.5),
        poisson_ratio: DEFAULT_GEOMETRY.poisson_ratio,
    };
    let (f_h, d_h, sim_h) = run(ContactModel::Hertz, hertz_geometry);
    let w = sim_h.static_loads()[0];
    let f_peak = peak(&f_h);
    assert!(f_peak > 1.15 * w, "the dip must excite the wheel: {f_peak}");
    let mut errors = Vec::new();
    for n in [16, 32] {
        let contact = ContactModel::BemProfiles(ProfileContact {
            wheelset: Arc::clone(&ws),
            lateral_shift: 0.0,
            roll: Roll::Fixed(0.0),
            elements: n,
        });
        let geometry = ContactGeometry {
            wheel_radius: ws.params().wheel_radius,
            ..DEFAULT_GEOMETRY
        };
        let (f_b, d_b, sim_b) = run(contact, geometry);
        // The static error of the grid: the profile law's force at Hertz's static approach.
        let mut law = match &sim_b.scenario().contact {
            ContactModel::BemProfiles(p) => p
                .law(Material::identical(DEFAULT_GEOMETRY.youngs_modulus, 0.3).unwrap())
                .unwrap(),
            _ => unreachable!(),
        };
        let mut hertz = hertz_geometry.hertz().unwrap();
        let d0 = hertz.static_approach(w).unwrap();
        let mut col = [0.0];
        let f0 = law.evaluate(d0, &[0.0], &mut col, false).unwrap().force;
        let static_error = (f0 / w - 1.0).abs();
        let df = max_diff(&f_h, &f_b) / f_peak;
        let dd = max_diff(&d_h, &d_b) / peak(&d_h);
        let stats = sim_b.stats();
        println!(
            "n = {n}: static force error {static_error:.2e}, max |F_bem − F_hertz| / peak {df:.2e}, deflection {dd:.2e}; {} steps, {} contact evaluations",
            stats.steps, stats.iterations
        );
        errors.push((static_error, df, dd));
    }
    // Measured: the force histories differ by 0.86 (16²) and 0.83 (32²) of the static
    // error, the midspan deflections by 2e-3 of the force difference (the bridge responds
    // to the force, the wheel's compliance barely changes it).
    for &(static_error, df, dd) in &errors {
        assert!(df < 1.5 * static_error, "{df} vs {static_error}");
        assert!(dd < 0.1 * df, "{dd} vs {df}");
    }
    assert!(errors[1].1 < errors[0].1, "{errors:?}");
}

mod support;

const EXAMPLE: &str = include_str!("../../../examples/vehicle_bridge_s1002_60e1.toml");

/// The vehicle–bridge example with real profiles (S1002 on 60E1, 1:40, centred; 16 × 16
/// elements per patch) starts in static equilibrium: the wheel's first sample carries the
/// static load W = (m_w + m_b) g with the vertical approach of `ProfileLaw::static_approach(W)`
/// of a law built independently from the same profiles, and the law evaluated at that
/// approach returns W (`wheelrail::law::STATIC_TOL` = 1e-10 relative; before the static
/// approach iterated on the evaluations themselves the start was 8.5e-4 off W, the force
/// solve's grid differing from the evaluation's).
#[test]
fn s1002_on_60e1_static_start_carries_the_wheel_load() {
    let sim = support::simulation(EXAMPLE);
    let w = sim.static_loads()[0];
    assert!((w - (600.0 + 5750.0) * GRAVITY).abs() < 1e-6);
    let params = WheelsetParams {
        inclination: 1.0 / 40.0,
        gauge: 1.435,
        back_to_back: 1.360,
        wheel_radius: 0.46,
        ..WheelsetParams::default()
    };
    let ws = Wheelset::new(wheelrail::s1002(), wheelrail::rail_60e1(), params).unwrap();
    let material = Material::identical(210e9, 0.3).unwrap();
    let options = wheelrail::PatchOptions {
        nx: 16,
        ny: 16,
        ..wheelrail::PatchOptions::default()
    };
    let mut law =
        wheelrail::ProfileLaw::new(ws, 0.0, wheelrail::Side::Right, material, options).unwrap();
    let d = law.static_approach(w).unwrap();
    let mut col = [0.0];
    let f = law.evaluate(d, &[0.0], &mut col, true).unwrap();
    let sample = &sim.wheels()[0];
    println!(
        "W = {w:.1} N: approach {:.6e} m (law {d:.6e}), force {:.3} N, law at it {:.3} N, k = {:.4e} N/m",
        sample.approach, sample.contact.force, f.force, f.stiffness
    );
    assert!(
        (sample.approach / d - 1.0).abs() < 1e-9,
        "{}",
        sample.approach
    );
    assert!((sample.contact.force / w - 1.0).abs() < 1e-9);
    assert!((f.force / w - 1.0).abs() < 1e-9, "{}", f.force);
    // Hertz's 3W/(2δ) as a plausibility bound on the solver's tangent (a non-Hertzian patch).
    let k_hertz = 1.5 * w / d;
    assert!(
        (f.stiffness / k_hertz - 1.0).abs() < 0.2,
        "{} vs {k_hertz}",
        f.stiffness
    );
}

/// `[contact.profiles]` errors name the key, the value and the allowed range, or the
/// conflicting key.
#[test]
fn profile_contact_keys_are_checked() {
    let with = |from: &str, to: &str| {
        assert!(EXAMPLE.contains(from), "{from}");
        support::load(&EXAMPLE.replace(from, to))
            .err()
            .unwrap_or_default()
    };
    let e = with("gauge = 1.435", "gauge = 3.0");
    assert!(
        e.contains("contact.profiles.gauge") && e.contains('3'),
        "{e}"
    );
    let e = with("lateral_shift = 0.0", "lateral_shift = 0.05");
    assert!(e.contains("contact.profiles.lateral_shift"), "{e}");
    let e = with("inclination = \"1:40\"", "inclination = \"1:x\"");
    assert!(e.contains("[contact.profiles] `inclination`"), "{e}");
    let e = with("rail = \"60E1\"", "rail = \"no_such_rail.txt\"");
    assert!(
        e.contains("[contact.profiles] `rail`") && e.contains("60E1"),
        "{e}"
    );
    let e = with("model = \"bem\"", "model = \"hertz\"");
    assert!(e.contains("needs model = \"bem\""), "{e}");
    let e = with("grid = 16", "grid = 16\nwheel_radius = 0.5");
    assert!(e.contains("`wheel_radius` is not used"), "{e}");
    let e = with("grid = 16", "grid = 4");
    assert!(e.contains("contact.grid"), "{e}");
    let e = with("gauge = 1.435", "gauge = 1.435\nflange = 1");
    assert!(e.contains("flange"), "{e}");
    let e = with(
        "[irregularity]",
        "[traction]\nmu = 0.3\ncreepage = 0.001\n\n[irregularity]",
    );
    assert!(e.contains("[traction]"), "{e}");
}
