//! Vehicle–bridge coupling: limits against closed forms and an independent moving-force
//! solution, and agreement of the coupling solvers.

use beam::{
    AnalyticBeam, ModalBasis, ModalDamping, MovingLoadSettings, MovingLoads, Support, UniformBeam,
};
use integrate::structural::StructuralMethod;
use sim::config::vehicle_bridge::DEFAULT_GEOMETRY;
use sim::vehicle_bridge::{
    ContactGeometry, ContactModel, CouplingSolver, CouplingSpec, GRAVITY, Integrator, Irregularity,
    Scenario, Simulation, WheelSpec,
};

/// Frýba / Biggs bridge of references.md §D1.3: L = 25 m, EI = 2.87e9 × 2.90, ρA = 2303 kg/m.
const L: f64 = 25.0;
const EI: f64 = 2.87e9 * 2.90;
const RHO_A: f64 = 2303.0;

fn bridge(support: Support, modes: usize) -> Box<dyn ModalBasis> {
    Box::new(AnalyticBeam::new(support, UniformBeam::new(L, EI, RHO_A).unwrap(), modes).unwrap())
}

fn geometry() -> ContactGeometry {
    DEFAULT_GEOMETRY
}

fn scenario(
    bridge: Box<dyn ModalBasis>,
    wheels: Vec<WheelSpec>,
    speed: f64,
    contact: ContactModel,
    dt: f64,
) -> Scenario {
    Scenario {
        moving_forces: Vec::new(),
        bridge,
        damping: ModalDamping::Undamped,
        wheels,
        speed,
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

/// A wheel of 600 kg carrying 100 kN in total.
fn heavy_wheel(position: f64) -> WheelSpec {
    WheelSpec {
        position,
        wheel_mass: 600.0,
        static_load: 100e3 - 600.0 * GRAVITY,
        ..WheelSpec::default()
    }
}

/// Crawling limit: a wheel creeping onto midspan of a heavily damped bridge (ζ = 0.7 in
/// every mode, so the start transient decays like e^{−ζω₁t} < 1e-15 within the run) gives the
/// static midspan deflection F L³/(48 EI) (simply supported) or F L³/(192 EI) (clamped), and a
/// contact force equal to the wheel's weight. Tolerances: 1e-4 relative on the deflection
/// (40 modes: the modal truncation of a point-load deflection is O(Σ j⁻⁴) ≈ 1e-6; the creep
/// speed leaves a lag of order (2ζ/ω₁)·c·w' = 0 at the maximum) and 1e-6 on the force
/// (F − W = m_w z̈_w with z̈_w of order c² w'' ≈ 1e-5 m/s²). Generalized-α (ρ∞ = 0.5) damps
/// the start transient of the contact mode.
#[test]
fn crawling_wheel_gives_static_deflection_and_weight() {
    for (support, factor) in [
        (Support::SimplySupported, 48.0),
        (Support::ClampedClamped, 192.0),
    ] {
        for contact in [ContactModel::Rigid, ContactModel::Hertz] {
            let speed = 0.5;
            let duration = 2.0;
            let mut sc = scenario(
                bridge(support, 40),
                vec![heavy_wheel(0.5 * L - speed * duration)],
                speed,
                contact.clone(),
                1e-3,
            );
            sc.damping = ModalDamping::Uniform(0.7);
            sc.duration = Some(duration);
            // Generalized-α (ρ∞ = 0.5) damps the start transient of the Hertz contact mode.
            sc.integrator =
                Integrator::Structural(StructuralMethod::generalized_alpha(0.5).unwrap());
            let mut sim = Simulation::new(sc).unwrap();
            sim.run(|_| {}).unwrap();
            let x = sim.wheels()[0].position;
            assert!((x - 0.5 * L).abs() < 1e-9, "wheel at {x}");
            let (w_mid, _, _) = sim.output_point_response();
            let f = 100e3;
            let w_static = f * L.powi(3) / (factor * EI);
            let rel = (w_mid / w_static - 1.0).abs();
            let force = sim.wheels()[0].contact.force;
            println!(
                "{support:?} {contact:?}: w = {w_mid:.6e} static {w_static:.6e} rel {rel:.2e}; F = {force}"
            );
            assert!(rel < 1e-4, "{support:?} {contact:?}: rel {rel}");
            assert!((force / f - 1.0).abs() < 1e-6, "force {force}");
        }
    }
}

/// Moving-force limit: a light wheel (1 kg, 100 kN static load) on a smooth track gives the
/// moving-force solution, computed independently by the beam crate's exact piecewise-linear
/// modal propagator (no coupling, no Newmark). Tolerance 2e-3 of the maximum deflection:
/// Newmark's O(Δt²) phase error at Δt = 1e-4 s on mode 1 (ω₁Δt = 3e-3, relative period error
/// (ωΔt)²/12 ≈ 1e-6) and the 1 kg wheel's inertia force (≈ 1e-4 of the load) are far below it.
#[test]
fn light_wheel_reproduces_moving_force() {
    let speed = 27.78;
    let p = 100e3;
    let dt = 1e-4;
    let modes = 20;
    let reference = beam::simulate_moving_loads(
        &AnalyticBeam::new(
            Support::SimplySupported,
            UniformBeam::new(L, EI, RHO_A).unwrap(),
            modes,
        )
        .unwrap(),
        &ModalDamping::Uniform(0.02),
        &MovingLoads::single(p, speed).unwrap(),
        &MovingLoadSettings::new(dt, 0.0),
        &[0.5 * L],
    )
    .unwrap();
    for contact in [ContactModel::Rigid, ContactModel::Hertz] {
        let wheel = WheelSpec {
            position: 0.0,
            wheel_mass: 1.0,
            static_load: p - GRAVITY,
            ..WheelSpec::default()
        };
        let mut sc = scenario(
            bridge(Support::SimplySupported, modes),
            vec![wheel],
            speed,
            contact.clone(),
            dt,
        );
        sc.damping = ModalDamping::Uniform(0.02);
        let mut sim = Simulation::new(sc).unwrap();
        let mut max_err = 0.0f64;
        let mut max_w = 0.0f64;
        let mut step = 0;
        sim.run(|s| {
            step += 1;
            let (w, _, _) = s.output_point_response();
            let w_ref = reference.deflection[step];
            assert!((reference.times[step] - s.t()).abs() < 1e-9);
            max_err = max_err.max((w - w_ref).abs());
            max_w = max_w.max(w_ref.abs());
        })
        .unwrap();
        println!(
            "{contact:?}: max |w − w_ref| = {max_err:.3e} of max {max_w:.4e} ({:.2e})",
            max_err / max_w
        );
        assert!(step > 8000);
        assert!(max_err < 2e-3 * max_w, "{contact:?}: {max_err} vs {max_w}");
    }
}

/// A quarter car (600 kg wheel, 5750 kg body, Hertz contact) at Δt = 2e-4 s, where
/// λ = k_c c_Δt ≈ 0.02 and Picard converges: Picard, quasi-Newton (Sherman–Morrison) and dense
/// Newton give the same trajectory to 1e-8 relative (tolerance 1e-12 of the wheel load per step;
/// the remaining differences are the iteration errors, far below 1e-8).
#[test]
fn coupling_solvers_agree() {
    let mut runs = Vec::new();
    for solver in [
        CouplingSolver::Picard,
        CouplingSolver::QuasiNewton,
        CouplingSolver::Newton,
    ] {
        let wheel = WheelSpec {
            position: 0.0,
            wheel_mass: 600.0,
            body_mass: 5750.0,
            suspension_stiffness: 1595e3,
            suspension_damping: 1e4,
            static_load: 0.0,
        };
        let mut sc = scenario(
            bridge(Support::SimplySupported, 10),
            vec![wheel],
            27.78,
            ContactModel::Hertz,
            2e-4,
        );
        sc.irregularity = Irregularity::Dip {
            position: 8.0,
            length: 1.0,
            depth: 0.5e-3,
        };
        sc.coupling = CouplingSpec {
            solver,
            tol: 1e-12,
            max_iter: 100,
            max_halvings: 0,
        };
        sc.duration = Some(0.6);
        let mut sim = Simulation::new(sc).unwrap();
        let mut forces = Vec::new();
        let mut defl = Vec::new();
        sim.run(|s| {
            forces.push(s.wheels()[0].contact.force);
            defl.push(s.output_point_response().0);
        })
        .unwrap();
        let stats = sim.stats();
        println!(
            "{solver:?}: mean iterations {:.2}, max {}",
            stats.iterations as f64 / stats.steps as f64,
            stats.max_iterations
        );
        runs.push((forces, defl));
    }
    let (f_ref, d_ref) = &runs[2];
    let f_scale = f_ref.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let d_scale = d_ref.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    for (forces, defl) in &runs[..2] {
        let ef = forces
            .iter()
            .zip(f_ref)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        let ed = defl
            .iter()
            .zip(d_ref)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        println!(
            "force diff {:.2e}, deflection diff {:.2e}",
            ef / f_scale,
            ed / d_scale
        );
        assert!(ef < 1e-8 * f_scale && ed < 1e-8 * d_scale);
    }
}
