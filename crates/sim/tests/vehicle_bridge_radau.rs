//! Radau5 for the coupled vehicle–bridge run: the Newmark (trapezoidal) trajectory converges to
//! the Radau5 trajectory at second order, and the input checks.

use beam::{AnalyticBeam, ModalDamping, Support, UniformBeam};
use integrate::structural::StructuralMethod;
use sim::config::vehicle_bridge::DEFAULT_GEOMETRY;
use sim::vehicle_bridge::{
    ContactModel, CouplingSpec, GRAVITY, Integrator, Irregularity, Radau5Spec, Scenario,
    Simulation, VehicleBridgeError, WheelSpec,
};

const L: f64 = 25.0;

fn scenario(dt: f64, contact: ContactModel, depth: f64) -> Scenario {
    Scenario {
        moving_forces: Vec::new(),
        bridge: Box::new(
            AnalyticBeam::new(
                Support::SimplySupported,
                UniformBeam::new(L, 2.87e9 * 2.90, 2303.0).unwrap(),
                10,
            )
            .unwrap(),
        ),
        damping: ModalDamping::Uniform(0.02),
        wheels: vec![WheelSpec {
            position: 0.0,
            wheel_mass: 600.0,
            body_mass: 5750.0,
            suspension_stiffness: 1595e3,
            suspension_damping: 1e4,
            static_load: 0.0,
        }],
        speed: 27.78,
        contact,
        geometry: DEFAULT_GEOMETRY,
        irregularity: Irregularity::Dip {
            position: 8.0,
            length: 1.0,
            depth,
        },
        integrator: Integrator::Structural(StructuralMethod::average_acceleration()),
        dt,
        duration: Some(0.4),
        coupling: CouplingSpec {
            tol: 1e-12,
            ..CouplingSpec::default()
        },
        gravity: GRAVITY,
        output_point: 0.5 * L,
    }
}

/// (t, contact force, midspan deflection, body displacement) after every step.
fn run(mut sim: Simulation) -> Vec<[f64; 4]> {
    let mut out = Vec::new();
    sim.run(|s| {
        out.push([
            s.t(),
            s.wheels()[0].contact.force,
            s.output_point_response().0,
            s.wheels()[0].body_displacement,
        ])
    })
    .unwrap();
    out
}

/// Largest differences (force, deflection, body) between `a` (every `stride`-th sample) and
/// the reference `r` on the same times.
fn diff(a: &[[f64; 4]], stride: usize, r: &[[f64; 4]]) -> [f64; 3] {
    let mut d = [0.0f64; 3];
    for (i, rr) in r.iter().enumerate() {
        let aa = &a[(i + 1) * stride - 1];
        assert!((aa[0] - rr[0]).abs() < 1e-9, "time {} vs {}", aa[0], rr[0]);
        for c in 0..3 {
            d[c] = d[c].max((aa[c + 1] - rr[c + 1]).abs());
        }
    }
    d
}

/// A Hertz quarter car (600 kg wheel, 5750 kg body, 10 modes, ζ = 2 %) over a 0.5 mm dip:
/// Radau5 (rtol 1e-10, atol 1e-13, output every 2e-4 s) is the reference; the trapezoidal
/// rule (quasi-Newton coupling) at Δt = 2e-4 and 1e-4 s must approach it at second order
/// (difference ratio in [3, 5.5] for the contact force, deflection and body displacement, the
/// O(Δt²) error of the trapezoidal rule; Radau5's own error, O(h⁵) under 1e-10 relative, is
/// negligible). At Δt = 1e-4 s the difference must be within 3 % of the dynamic force range
/// (the trapezoidal phase error of the ≈ 230 Hz wheel-on-contact-spring mode, (ωΔt)²/12 ≈ 2e-3
/// per cycle) and 1e-4 of the peak deflection and body displacement. Measured: ratios 3.98,
/// 3.98, 4.19; differences 1.5e-2 (force), 8.2e-6 (deflection), 2.8e-8 (body). This checks
/// that both paths integrate the same coupled equations with an independent integrator.
#[test]
fn newmark_converges_to_radau5_at_second_order() {
    let dt_ref = 2e-4;
    let mut sc = scenario(dt_ref, ContactModel::Hertz, 0.5e-3);
    sc.integrator = Integrator::Radau5(Radau5Spec {
        rtol: 1e-10,
        atol: 1e-13,
    });
    let sim = Simulation::new(sc).unwrap();
    assert!(sim.uses_radau5());
    let reference = run(sim);
    let stats_len = reference.len();
    assert_eq!(stats_len, 2000);
    let f_range = reference.iter().fold(0.0f64, |m, r| m.max(r[1]))
        - reference.iter().fold(f64::INFINITY, |m, r| m.min(r[1]));
    let scale = [
        f_range,
        reference.iter().fold(0.0f64, |m, r| m.max(r[2].abs())),
        reference.iter().fold(0.0f64, |m, r| m.max(r[3].abs())),
    ];
    let coarse = diff(
        &run(Simulation::new(scenario(2e-4, ContactModel::Hertz, 0.5e-3)).unwrap()),
        1,
        &reference,
    );
    let fine = diff(
        &run(Simulation::new(scenario(1e-4, ContactModel::Hertz, 0.5e-3)).unwrap()),
        2,
        &reference,
    );
    for c in 0..3 {
        let ratio = coarse[c] / fine[c];
        println!(
            "component {c}: Newmark − Radau5 at 2e-4 {:.3e}, at 1e-4 {:.3e} (relative {:.2e}), ratio {ratio:.2}",
            coarse[c],
            fine[c],
            fine[c] / scale[c]
        );
        assert!((3.0..=5.5).contains(&ratio), "component {c}: ratio {ratio}");
        let bound = if c == 0 { 3e-2 } else { 1e-4 };
        assert!(fine[c] < bound * scale[c], "component {c}");
    }
}

/// Radau5 with a rigid contact or bad tolerances is an error naming the key.
#[test]
fn radau5_input_errors_name_the_key() {
    let mut sc = scenario(1e-3, ContactModel::Rigid, 0.0);
    sc.integrator = Integrator::Radau5(Radau5Spec::default());
    let e = Simulation::new(sc).map(|_| ()).unwrap_err();
    assert!(matches!(e, VehicleBridgeError::InvalidChoice { .. }));
    assert!(e.to_string().contains("`contact.model` = \"rigid\""), "{e}");
    for (rtol, atol, key) in [
        (0.0, 1e-9, "integrator.rtol"),
        (f64::NAN, 1e-9, "integrator.rtol"),
        (1e-6, -1.0, "integrator.atol"),
    ] {
        let mut sc = scenario(1e-3, ContactModel::Hertz, 0.0);
        sc.integrator = Integrator::Radau5(Radau5Spec { rtol, atol });
        let e = Simulation::new(sc).map(|_| ()).unwrap_err();
        assert!(e.to_string().contains(key), "{e}");
    }
}

/// Loss of contact under Radau5 (no events: the Hertz force δ₊^{3/2} is C¹ and the step
/// control resolves it): a 300 kg wheel carrying 5 kN (no body) at 27.78 m/s over a 2 mm,
/// 0.4 m dip off the bridge jumps and lands. In flight the wheel follows the ballistic parabola
/// z(t) = z₀ + v₀(t − t₀) + ½ g_e (t − t₀)², g_e = (m_w g + P)/m_w, from its first flight
/// sample (closed form; Radau5 integrates a quadratic exactly, so the bound 1e-9 of the flight
/// drop only allows the tolerance-level error of the take-off state, rtol 1e-10; measured
/// 1e-14). The peak landing force (≈ 472 kN), sampled on the same 2e-6 s output grid, agrees
/// with the trapezoidal rule at Δt = 2e-6 s within 1e-4 (the trapezoidal O(Δt²) error on the
/// ≈ 0.3 ms impact, (ωΔt)²/12 ≈ 1e-5; measured 2.8e-6).
#[test]
fn radau5_wheel_jumps_and_lands() {
    let run_jump = |radau: bool, dt: f64| {
        let m_w = 300.0;
        let p = 5e3 - m_w * GRAVITY;
        let mut sc = scenario(dt, ContactModel::Hertz, 2e-3);
        sc.wheels = vec![WheelSpec {
            position: -3.0,
            wheel_mass: m_w,
            static_load: p,
            ..WheelSpec::default()
        }];
        sc.irregularity = Irregularity::Dip {
            position: -2.0,
            length: 0.4,
            depth: 2e-3,
        };
        sc.duration = Some(0.06);
        if radau {
            sc.integrator = Integrator::Radau5(Radau5Spec {
                rtol: 1e-10,
                atol: 1e-13,
            });
        }
        let mut sim = Simulation::new(sc).unwrap();
        let g_e = (m_w * GRAVITY + p) / m_w;
        let mut takeoff: Option<(f64, f64, f64)> = None;
        let (mut worst, mut drop, mut flight, mut landed, mut peak) =
            (0.0f64, 0.0f64, 0, false, 0.0f64);
        sim.run(|s| {
            let w = s.wheels()[0];
            if w.contact.force == 0.0 && !landed {
                let (t0, z0, v0) = *takeoff.get_or_insert((
                    s.t(),
                    w.wheel_displacement,
                    s.velocity()[s.velocity().len() - 1],
                ));
                let tau = s.t() - t0;
                let z = z0 + v0 * tau + 0.5 * g_e * tau * tau;
                worst = worst.max((w.wheel_displacement - z).abs());
                drop = drop.max((w.wheel_displacement - z0).abs());
                flight += 1;
            } else if takeoff.is_some() {
                landed = true;
                peak = peak.max(w.contact.force);
            }
        })
        .unwrap();
        (
            sim.loss_of_contact_events(),
            flight,
            worst,
            drop,
            landed,
            peak,
        )
    };
    let (events, flight, worst, drop, landed, peak) = run_jump(true, 2e-6);
    let (_, _, _, _, _, peak_trap) = run_jump(false, 2e-6);
    println!(
        "radau5 jump: {events} loss-of-contact events, {flight} flight samples, parabola error {:.2e} of the drop {drop:.3e} m; peak landing force {peak:.1} N vs trapezoidal {peak_trap:.1} N (rel {:.2e})",
        worst / drop,
        peak / peak_trap - 1.0
    );
    assert!(events >= 1 && flight > 10 && landed);
    assert!(worst < 1e-9 * drop.max(1e-12));
    assert!((peak / peak_trap - 1.0).abs() < 1e-4);
}
