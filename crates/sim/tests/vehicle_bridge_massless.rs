//! Massless wheels (`wheel_mass = 0`, rigid contact): the classic Biggs / Yang–Yau sprung
//! mass (references.md §D1.3) against an independent RK4 of its equations, the crawling limit,
//! and the input checks.

use beam::{AnalyticBeam, Derivative, ModalBasis, ModalDamping, Support, UniformBeam};
use integrate::structural::StructuralMethod;
use sim::config::vehicle_bridge::{DEFAULT_BEM_TOL, DEFAULT_GEOMETRY};
use sim::vehicle_bridge::{
    ContactModel, CouplingSpec, GRAVITY, Integrator, Irregularity, Scenario, Simulation,
    VehicleBridgeError, WheelSpec,
};

/// Biggs's bridge (references.md §D1.3): L = 25 m, EI = 2.87e9 × 2.90, ρA = 2303 kg/m.
const L: f64 = 25.0;
const EI: f64 = 2.87e9 * 2.90;
const RHO_A: f64 = 2303.0;
/// Biggs's sprung mass: 5750 kg on 1595 kN/m, at 100 km/h.
const M_B: f64 = 5750.0;
const K_S: f64 = 1595e3;
const SPEED: f64 = 27.78;

fn basis(modes: usize) -> AnalyticBeam {
    AnalyticBeam::new(
        Support::SimplySupported,
        UniformBeam::new(L, EI, RHO_A).unwrap(),
        modes,
    )
    .unwrap()
}

fn scenario(modes: usize, wheel: WheelSpec, speed: f64, contact: ContactModel) -> Scenario {
    Scenario {
        moving_forces: Vec::new(),
        bridge: Box::new(basis(modes)),
        damping: ModalDamping::Undamped,
        wheels: vec![wheel],
        speed,
        contact,
        geometry: DEFAULT_GEOMETRY,
        irregularity: Irregularity::None,
        integrator: Integrator::Structural(StructuralMethod::generalized_alpha(0.9).unwrap()),
        dt: 1e-4,
        duration: None,
        coupling: CouplingSpec::default(),
        gravity: GRAVITY,
        output_point: 0.5 * L,
    }
}

fn massless(c_s: f64) -> WheelSpec {
    WheelSpec {
        position: 0.0,
        wheel_mass: 0.0,
        body_mass: M_B,
        suspension_stiffness: K_S,
        suspension_damping: c_s,
        static_load: 0.0,
    }
}

/// Independent RK4 (Δt = 1e-5 s) of the sprung mass on a massless wheel that follows the
/// deflected rail, z_w = u = Σ q_j φ_j(ct) (Biggs 1964 §8.5; Yang & Yau 1997):
/// `q_j'' + ω_j² q_j = F φ_j(ct)`, `m_b z_b'' = m_b g − k_s(z_b − u) − c_s(ż_b − u̇)`,
/// `F = m_b g − m_b z_b''` (the massless wheel passes the suspension force on), with
/// `u̇ = Σ (q̇_j φ_j + c q_j φ_j')`. Returns (t, midspan deflection, body displacement) every
/// 1e-4 s.
fn biggs_rk4(modes: usize, c_s: f64) -> Vec<(f64, f64, f64)> {
    let b = basis(modes);
    let om: Vec<f64> = b.circular_frequencies().to_vec();
    let rhs = |t: f64, y: &[f64]| -> Vec<f64> {
        let x = (SPEED * t).clamp(0.0, L);
        let mut phi = vec![0.0; modes];
        let mut d1 = vec![0.0; modes];
        b.eval_all(x, Derivative::Shape, &mut phi).unwrap();
        b.eval_all(x, Derivative::Slope, &mut d1).unwrap();
        let (q, v) = (&y[..modes], &y[modes..2 * modes]);
        let (zb, vb) = (y[2 * modes], y[2 * modes + 1]);
        let u: f64 = (0..modes).map(|j| q[j] * phi[j]).sum();
        let du: f64 = (0..modes)
            .map(|j| v[j] * phi[j] + SPEED * q[j] * d1[j])
            .sum();
        let spring = K_S * (zb - u) + c_s * (vb - du);
        // F = k_s(z_b − u) + c_s(ż_b − u̇) = m_b g − m_b z_b''.
        let force = spring;
        let mut out = v.to_vec();
        out.extend((0..modes).map(|j| force * phi[j] - om[j] * om[j] * q[j]));
        out.push(vb);
        out.push(GRAVITY - spring / M_B);
        out
    };
    let mut mid = vec![0.0; modes];
    b.eval_all(0.5 * L, Derivative::Shape, &mut mid).unwrap();
    let h = 1e-5;
    let n = ((L / SPEED) / h).round() as usize;
    let mut y = vec![0.0; 2 * modes + 2];
    y[2 * modes] = M_B * GRAVITY / K_S;
    let mut out = vec![(0.0, 0.0, y[2 * modes])];
    for i in 0..n {
        let t = i as f64 * h;
        let k1 = rhs(t, &y);
        let y2: Vec<f64> = y.iter().zip(&k1).map(|(a, k)| a + 0.5 * h * k).collect();
        let k2 = rhs(t + 0.5 * h, &y2);
        let y3: Vec<f64> = y.iter().zip(&k2).map(|(a, k)| a + 0.5 * h * k).collect();
        let k3 = rhs(t + 0.5 * h, &y3);
        let y4: Vec<f64> = y.iter().zip(&k3).map(|(a, k)| a + h * k).collect();
        let k4 = rhs(t + h, &y4);
        for j in 0..y.len() {
            y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
        if (i + 1) % 10 == 0 {
            let w: f64 = (0..modes).map(|j| y[j] * mid[j]).sum();
            out.push(((i + 1) as f64 * h, w, y[2 * modes]));
        }
    }
    out
}

/// The Biggs sprung mass with a truly massless wheel (rigid contact) follows the independent
/// RK4 of its two-DOF (one mode) equations, and of the same equations with 4 modes and a
/// suspension damper (c_s = 50 kN s/m, which makes the wheel's velocity enter the force):
/// midspan deflection and body displacement within 1e-4 of their peak values (generalized-α
/// ρ∞ = 0.9 at Δt = 1e-4 s: O(Δt²) phase error (ωΔt)²/12 ≈ 2e-6 on the body mode plus ρ∞'s
/// slight numerical damping; measured 2.2e-6 / 6.1e-7 (1 mode) and 5.2e-6 / 6.2e-7 (4 modes,
/// damper); RK4 at 1e-5 s is exact to ≈ 1e-12, so the margin is ≈ 20×).
#[test]
fn biggs_massless_wheel_matches_an_independent_integration() {
    for (modes, c_s) in [(1, 0.0), (4, 50e3)] {
        let reference = biggs_rk4(modes, c_s);
        let mut sim =
            Simulation::new(scenario(modes, massless(c_s), SPEED, ContactModel::Rigid)).unwrap();
        let mut hist = vec![(0.0, 0.0, sim.wheels()[0].body_displacement)];
        sim.run(|s| {
            hist.push((
                s.t(),
                s.output_point_response().0,
                s.wheels()[0].body_displacement,
            ))
        })
        .unwrap();
        assert!(hist.len() >= reference.len() - 1);
        let z0 = M_B * GRAVITY / K_S;
        let peak_w = reference.iter().fold(0.0f64, |m, r| m.max(r.1.abs()));
        let peak_z = reference
            .iter()
            .fold(0.0f64, |m, r| m.max((r.2 - z0).abs()));
        let (mut ew, mut ez) = (0.0f64, 0.0f64);
        for (r, h) in reference.iter().zip(&hist) {
            assert!((r.0 - h.0).abs() < 1e-9, "time grid {} vs {}", r.0, h.0);
            ew = ew.max((r.1 - h.1).abs());
            ez = ez.max((r.2 - h.2).abs());
        }
        println!(
            "Biggs massless, {modes} modes, c_s {c_s}: peak w {peak_w:.5e} m (rel err {:.2e}), peak body {peak_z:.5e} m (rel err {:.2e})",
            ew / peak_w,
            ez / peak_z
        );
        assert!(ew < 1e-4 * peak_w, "deflection error {ew} vs {peak_w}");
        assert!(ez < 1e-4 * peak_z, "body error {ez} vs {peak_z}");
    }
}

/// Crawling limit: the massless wheel with its body (critically damped suspension,
/// c_s = 2√(k_s m_b), bridge ζ = 0.7) creeping onto midspan gives the static deflection
/// m_b g L³/(48 EI) within 1e-4 (40 modes: modal truncation ≈ 1e-6) and a contact force equal
/// to the body weight within 1e-5 (F − m_b g = −m_b z̈_b, z̈_b of order c² w'' ≈ 1e-5 m/s²,
/// and the start transients decay below e^{-30}). Measured: −5.3e-6 and 1.4e-6.
#[test]
fn crawling_massless_wheel_gives_static_deflection_and_weight() {
    let speed = 0.5;
    let duration = 2.0;
    let mut wheel = massless(2.0 * (K_S * M_B).sqrt());
    wheel.position = 0.5 * L - speed * duration;
    let mut sc = scenario(40, wheel, speed, ContactModel::Rigid);
    sc.damping = ModalDamping::Uniform(0.7);
    sc.duration = Some(duration);
    sc.dt = 1e-3;
    sc.integrator = Integrator::Structural(StructuralMethod::generalized_alpha(0.5).unwrap());
    let mut sim = Simulation::new(sc).unwrap();
    sim.run(|_| {}).unwrap();
    assert!((sim.wheels()[0].position - 0.5 * L).abs() < 1e-9);
    let w = sim.output_point_response().0;
    let weight = M_B * GRAVITY;
    let w_static = weight * L.powi(3) / (48.0 * EI);
    let force = sim.wheels()[0].contact.force;
    println!(
        "crawling massless: w {w:.6e} static {w_static:.6e} rel {:.2e}; F {force} vs {weight} rel {:.2e}",
        w / w_static - 1.0,
        force / weight - 1.0
    );
    assert!((w / w_static - 1.0).abs() < 1e-4);
    assert!((force / weight - 1.0).abs() < 1e-5);
}

/// `wheel_mass = 0` with a compliant contact or without a body, and a negative or NaN wheel
/// mass, are errors naming the key.
#[test]
fn massless_wheel_input_errors_name_the_key() {
    let check = |wheel: WheelSpec, contact: ContactModel, text: &str| match Simulation::new(
        scenario(1, wheel, SPEED, contact),
    ) {
        Err(e @ VehicleBridgeError::InvalidParameter { .. }) => {
            let msg = e.to_string();
            assert!(msg.contains("vehicle.wheels[0].wheel_mass"), "{msg}");
            assert!(msg.contains(text), "{msg}");
        }
        Err(e) => panic!("expected InvalidParameter, got {e}"),
        Ok(_) => panic!("expected an error for {text}"),
    };
    check(massless(0.0), ContactModel::Hertz, "rigid");
    check(
        massless(0.0),
        ContactModel::Bem {
            elements: 8,
            tol: DEFAULT_BEM_TOL,
            reuse_tol: 0.0,
        },
        "rigid",
    );
    let no_body = WheelSpec {
        body_mass: 0.0,
        suspension_stiffness: 0.0,
        static_load: 1e4,
        ..massless(0.0)
    };
    check(no_body, ContactModel::Rigid, "body");
    for bad in [-1.0, f64::NAN] {
        let w = WheelSpec {
            wheel_mass: bad,
            ..massless(0.0)
        };
        check(w, ContactModel::Rigid, ">= 0");
    }
}
