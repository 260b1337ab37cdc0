//! Several wheels (Woodbury), loss of contact and re-contact, and the Picard limit.

use beam::{
    AnalyticBeam, Axle, ModalDamping, MovingLoadSettings, MovingLoads, Support, UniformBeam,
};
use integrate::structural::StructuralMethod;
use sim::config::vehicle_bridge::DEFAULT_GEOMETRY;
use sim::vehicle_bridge::{
    ContactGeometry, ContactModel, CouplingSolver, CouplingSpec, GRAVITY, Integrator, Irregularity,
    Scenario, Simulation, WheelSpec,
};

const L: f64 = 25.0;
const EI: f64 = 2.87e9 * 2.90;
const RHO_A: f64 = 2303.0;

fn basis(modes: usize) -> AnalyticBeam {
    AnalyticBeam::new(
        Support::SimplySupported,
        UniformBeam::new(L, EI, RHO_A).unwrap(),
        modes,
    )
    .unwrap()
}

fn geometry() -> ContactGeometry {
    DEFAULT_GEOMETRY
}

fn scenario(wheels: Vec<WheelSpec>, contact: ContactModel, dt: f64) -> Scenario {
    Scenario {
        moving_forces: Vec::new(),
        bridge: Box::new(basis(10)),
        damping: ModalDamping::Uniform(0.02),
        wheels,
        speed: 27.78,
        contact,
        geometry: geometry(),
        irregularity: Irregularity::None,
        integrator: Integrator::Structural(StructuralMethod::average_acceleration()),
        dt,
        duration: None,
        coupling: CouplingSpec::default(),
        gravity: GRAVITY,
        output_point: 0.5 * L,
    }
}

/// Four light wheels (1 kg each, 80 kN static loads) at the axle spacings of two bogies,
/// rigid contact: the bridge response equals the moving-force train of the beam crate's exact
/// modal propagator (independent of the coupling), to 2e-3 of the peak (the wheels' inertia
/// forces are ≈ 1e-4 of the loads, the integrator's phase error at Δt = 1e-4 s ≈ 1e-6).
#[test]
fn light_wheel_train_reproduces_moving_force_train() {
    let offsets = [0.0, 2.5, 17.5, 20.0];
    let p = 80e3;
    let dt = 1e-4;
    let loads = MovingLoads::train(
        offsets
            .iter()
            .map(|&d| Axle {
                offset: d,
                force: p,
            })
            .collect(),
        27.78,
    )
    .unwrap();
    let reference = beam::simulate_moving_loads(
        &basis(10),
        &ModalDamping::Uniform(0.02),
        &loads,
        &MovingLoadSettings::new(dt, 0.0),
        &[0.5 * L],
    )
    .unwrap();
    let wheels = offsets
        .iter()
        .map(|&d| WheelSpec {
            position: -d,
            wheel_mass: 1.0,
            static_load: p - GRAVITY,
            ..WheelSpec::default()
        })
        .collect();
    let mut sc = scenario(wheels, ContactModel::Rigid, dt);
    // Rigid contacts are index-3 constraints: when a wheel enters an already deflected span
    // (slope kink) the trapezoidal rule's undamped multiplier oscillation grows (measured:
    // ±2.5 kN after 20 steps); generalized-α with ρ∞ = 0.9 damps it.
    sc.integrator = Integrator::Structural(StructuralMethod::generalized_alpha(0.9).unwrap());
    let mut sim = Simulation::new(sc).unwrap();
    let (mut err, mut peak, mut step) = (0.0f64, 0.0f64, 0);
    sim.run(|s| {
        step += 1;
        let w_ref = reference.deflection[step];
        err = err.max((s.output_point_response().0 - w_ref).abs());
        peak = peak.max(w_ref.abs());
    })
    .unwrap();
    println!("train: max error {err:.3e} of peak {peak:.4e}");
    assert!(err < 2e-3 * peak);
}

/// Two quarter cars (four wheels with bodies) with Hertz contact over a dip: quasi-Newton
/// with the Woodbury capacitance solve, dense Newton and Picard (Δt = 2e-4 s: λ ≈ 0.02) give
/// the same force histories to 1e-8 relative (coupling tolerance 1e-12 of the wheel load).
#[test]
fn woodbury_newton_and_picard_agree_for_four_wheels() {
    let mut histories = Vec::new();
    for solver in [
        CouplingSolver::QuasiNewton,
        CouplingSolver::Newton,
        CouplingSolver::Picard,
    ] {
        let wheels = [0.0, 2.5, 17.5, 20.0]
            .iter()
            .map(|&d| WheelSpec {
                position: -d,
                wheel_mass: 900.0,
                body_mass: 8000.0,
                suspension_stiffness: 1.2e6,
                suspension_damping: 2e4,
                static_load: 0.0,
            })
            .collect();
        let mut sc = scenario(wheels, ContactModel::Hertz, 2e-4);
        sc.irregularity = Irregularity::Dip {
            position: 5.0,
            length: 0.8,
            depth: 0.5e-3,
        };
        sc.duration = Some(0.5);
        sc.coupling = CouplingSpec {
            solver,
            tol: 1e-12,
            max_iter: 100,
            max_halvings: 0,
        };
        let mut sim = Simulation::new(sc).unwrap();
        let mut h = Vec::new();
        sim.run(|s| h.extend(s.wheels().iter().map(|w| w.contact.force)))
            .unwrap();
        let st = sim.stats();
        println!(
            "{solver:?}: {:.2} iterations/step",
            st.iterations as f64 / st.steps as f64
        );
        histories.push(h);
    }
    let scale = histories[1].iter().fold(0.0f64, |m, f| m.max(*f));
    for h in [&histories[0], &histories[2]] {
        let d = h
            .iter()
            .zip(&histories[1])
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        println!("difference {:.2e}", d / scale);
        assert!(d < 1e-8 * scale);
    }
}

/// A 300 kg wheel carrying only 5 kN (no body) at 27.78 m/s over a 2 mm, 0.4 m dip off the
/// bridge loses contact and lands again, with every contact model. During the flight
/// (F = 0) its acceleration is the free fall (m_w g + P)/m_w (closed form, 1e-9 relative:
/// backward Euler — the baseline scheme of references.md §D4.4 — satisfies the balance at t_{n+1} exactly when no
/// contact force acts), and it lands again (an elastic contact may bounce several times). Backward Euler is also
/// what makes the rigid landing an inelastic impact: the α-schemes impose δ = 0 at the
/// position level and return a spurious rebound velocity at a rigid impact.
#[test]
fn wheel_jumps_over_a_dip_with_every_model() {
    for contact in [
        ContactModel::Rigid,
        ContactModel::Hertz,
        ContactModel::Bem {
            elements: 16,
            tol: 1e-9,
            reuse_tol: 0.0,
        },
    ] {
        let m_w = 300.0;
        let p = 5e3 - m_w * GRAVITY;
        let wheel = WheelSpec {
            position: -3.0,
            wheel_mass: m_w,
            static_load: p,
            ..WheelSpec::default()
        };
        let mut sc = scenario(vec![wheel], contact.clone(), 5e-5);
        sc.irregularity = Irregularity::Dip {
            position: -2.0,
            length: 0.4,
            depth: 2e-3,
        };
        sc.integrator = Integrator::Structural(StructuralMethod::BackwardEuler);
        sc.duration = Some(0.1);
        sc.coupling.tol = 1e-9;
        let mut sim = Simulation::new(sc).unwrap();
        let free_fall = (m_w * GRAVITY + p) / m_w;
        let mut flight_steps = 0;
        let mut landings = 0;
        let mut worst = 0.0f64;
        let mut flying = false;
        sim.run(|s| {
            let w = s.wheels()[0];
            if w.contact.force == 0.0 {
                flight_steps += 1;
                flying = true;
                worst = worst.max((w.wheel_acceleration / free_fall - 1.0).abs());
            } else if flying {
                flying = false;
                landings += 1;
            }
        })
        .unwrap();
        let last = sim.wheels()[0];
        println!(
            "{contact:?}: {} loss-of-contact events, {landings} landings, {flight_steps} flight steps, free-fall error {worst:.2e}, final force {:.1} N, failed steps {}",
            sim.loss_of_contact_events(),
            last.contact.force,
            sim.stats().failed_steps
        );
        assert!(sim.loss_of_contact_events() >= 1);
        assert!(flight_steps > 10);
        assert!(worst < 1e-9, "{worst}");
        assert!(landings >= 1);
    }
}

/// Picard's divergence threshold (references.md §D4.2): for a wheel on a rigid track, Newmark
/// β = ¼ without damping, λ = k_c c_Δt = k_c β Δt²/m_w, so Picard converges iff
/// Δt < Δt* = √(m_w/(β k_c)). The step where Picard first fails (located by bisection on Δt,
/// Hertz contact at the static load with a 1 µm corrugation) agrees with Δt* within 10 %; the
/// quasi-Newton (Sherman–Morrison) iteration converges at 3 Δt*, and Picard with one step
/// halving allowed runs at 1.3 Δt* by halving (each failure counted in `failed_steps`).
#[test]
fn picard_threshold_matches_lambda_one() {
    let m_w = 900.0;
    let load = 100e3;
    let hertz = geometry().hertz().unwrap();
    let delta = (load / hertz.coefficient()).powf(2.0 / 3.0);
    let k_c = 1.5 * load / delta;
    let dt_star = (m_w / (0.25 * k_c)).sqrt();
    let simulation = |dt: f64, solver: CouplingSolver, max_halvings: usize| {
        let wheel = WheelSpec {
            position: -200.0,
            wheel_mass: m_w,
            static_load: load - m_w * GRAVITY,
            ..WheelSpec::default()
        };
        let mut sc = scenario(vec![wheel], ContactModel::Hertz, dt);
        sc.damping = ModalDamping::Undamped;
        sc.irregularity = Irregularity::Corrugation {
            amplitude: 1e-6,
            wavelength: 0.5,
            start: -1000.0,
            end: 1000.0,
        };
        sc.duration = Some(30.0 * dt);
        sc.coupling = CouplingSpec {
            solver,
            tol: 1e-9,
            max_iter: 2000,
            max_halvings,
        };
        let mut sim = Simulation::new(sc).unwrap();
        let ok = sim.run(|_| {}).is_ok();
        (ok, sim.stats())
    };
    let converges = |dt: f64, solver: CouplingSolver| simulation(dt, solver, 0).0;
    assert!(converges(3.0 * dt_star, CouplingSolver::QuasiNewton));
    assert!(converges(0.8 * dt_star, CouplingSolver::Picard));
    assert!(!converges(1.3 * dt_star, CouplingSolver::Picard));
    let (mut lo, mut hi) = (0.8 * dt_star, 1.3 * dt_star);
    for _ in 0..12 {
        let mid = 0.5 * (lo + hi);
        if converges(mid, CouplingSolver::Picard) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let ratio = 0.5 * (lo + hi) / dt_star;
    println!("Δt* = {dt_star:.4e} s (k_c = {k_c:.3e} N/m); Picard fails from {ratio:.4} Δt*");
    assert!((ratio - 1.0).abs() < 0.1, "{ratio}");
    // Step reduction: at 1.3 Δt* every step fails once and succeeds as two halves
    // (0.65 Δt* < Δt*); the failures are reported, not hidden.
    let (ok, stats) = simulation(1.3 * dt_star, CouplingSolver::Picard, 1);
    println!(
        "Picard at 1.3 Δt* with one halving: {} failed steps, {} accepted steps",
        stats.failed_steps, stats.steps
    );
    assert!(ok);
    assert!(stats.failed_steps >= 25 && stats.steps >= 2 * stats.failed_steps);
}
