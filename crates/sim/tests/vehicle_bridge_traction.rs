//! Longitudinal friction in the wheel-over-bridge run (sim::vehicle_bridge::traction) against
//! Kalker's linear theory (references.md §C4.2), Coulomb saturation, the torque balance of the wheel
//! and loss of contact.
//!
//! The steady runs keep the wheel on the rigid approach track (x < 0) so the normal force is
//! exactly the static load W = m_w g + P (an independent value), and the Hertz ellipse under W
//! is the patch of the linear-theory reference.

use beam::{AnalyticBeam, ModalBasis, ModalDamping, Support, UniformBeam};
use halfspace::{Hertz, Material, creep_coefficients};
use integrate::structural::StructuralMethod;
use sim::config::vehicle_bridge::{DEFAULT_BEM_GRID, DEFAULT_FASTSIM_ELEMENTS, DEFAULT_GEOMETRY};
use sim::vehicle_bridge::traction::{TractionDrive, TractionMethod, TractionSpec};
use sim::vehicle_bridge::{
    ContactGeometry, ContactModel, CouplingSpec, GRAVITY, Integrator, Irregularity, Scenario,
    Simulation, VehicleBridgeError, WheelSpec,
};

const GEOMETRY: ContactGeometry = DEFAULT_GEOMETRY;
const M_W: f64 = 600.0;
const P: f64 = 50e3;
const BEM_N: usize = DEFAULT_BEM_GRID;
const MU: f64 = 0.3;

fn weight() -> f64 {
    M_W * GRAVITY + P
}

/// The Hertz ellipse under the static load (semi-axes along, across the track).
fn hertz(force: f64) -> Hertz {
    let mat = GEOMETRY.material().unwrap();
    let (ca, cb) = GEOMETRY.curvatures();
    Hertz::elliptic(ca, cb, mat.e_star, force).unwrap()
}

/// Kalker's G c² C₁₁ [N] on the Hertz ellipse under W.
fn kalker_slope() -> f64 {
    let h = hertz(weight());
    let mat: Material = GEOMETRY.material().unwrap();
    mat.g * h.a * h.b * creep_coefficients(h.a, h.b, mat.nu).unwrap().c11
}

/// Crawling (2 m/s) on the approach track; Δt so that δq = V Δt is one BEM element (the grid
/// spans ±1.25 a of the Hertz ellipse at 2.5 W, `BemLaw::new`).
fn scenario(contact: ContactModel, steps: usize) -> Scenario {
    let speed = 2.0;
    let dx = 2.0 * 1.25 * hertz(2.5 * weight()).a / BEM_N as f64;
    let dt = dx / speed;
    Scenario {
        moving_forces: Vec::new(),
        bridge: Box::new(
            AnalyticBeam::new(
                Support::SimplySupported,
                UniformBeam::new(10.0, 1e10, 2000.0).unwrap(),
                3,
            )
            .unwrap(),
        ) as Box<dyn ModalBasis>,
        damping: ModalDamping::Uniform(0.02),
        wheels: vec![WheelSpec {
            position: -1.0,
            wheel_mass: M_W,
            static_load: P,
            ..WheelSpec::default()
        }],
        speed,
        contact,
        geometry: GEOMETRY,
        irregularity: Irregularity::None,
        integrator: Integrator::Structural(StructuralMethod::generalized_alpha(0.9).unwrap()),
        dt,
        duration: Some(steps as f64 * dt),
        coupling: CouplingSpec {
            tol: 1e-8,
            ..CouplingSpec::default()
        },
        gravity: GRAVITY,
        output_point: 5.0,
    }
}

fn contact_for(method: TractionMethod) -> ContactModel {
    match method {
        TractionMethod::Exact => ContactModel::Bem {
            elements: BEM_N,
            tol: 1e-9,
            reuse_tol: 0.0,
        },
        _ => ContactModel::Hertz,
    }
}

/// Runs `steps` steps; returns the (F_n, F_x, ξ, adhesion fraction, ω) history of wheel 0.
fn run(method: TractionMethod, drive: TractionDrive, steps: usize) -> (Vec<[f64; 5]>, Simulation) {
    let mut sim = Simulation::new(scenario(contact_for(method), steps)).unwrap();
    sim.set_traction(TractionSpec {
        mu: MU,
        method,
        drive,
        fastsim_elements: DEFAULT_FASTSIM_ELEMENTS,
    })
    .unwrap();
    let mut out = Vec::new();
    sim.run(|s| {
        let t = s.traction().unwrap().samples()[0];
        out.push([
            s.wheels()[0].contact.force,
            t.longitudinal_force,
            t.creepage,
            t.adhesion_fraction,
            t.angular_velocity,
        ]);
    })
    .unwrap();
    (out, sim)
}

/// (1) Small creepage ξ = 1e-4 (F_x ≈ 0.9 % of μF_n, so the nonlinear correction of the
/// traction curve, ≈ u/3 with u = Gc²C₁₁ξ/(3μF_n) ≈ 0.3 %, is negligible): after rolling 60
/// elements (≈ 5 patch lengths, transient settled) F_x of every method agrees with Kalker's
/// F_x = −G c² C₁₁ ξ on the Hertz ellipse under W within 3 % (`exact`: BEM discretisation of
/// ≈ 19 elements along the patch and CONTACT's δq = δx time discretisation, measured ≈ 1–2 %
/// on such grids, docs/tangential.md; `fastsim`: its flexibilities reproduce the linear theory
/// at vanishing creepage up to the 40 × 40 element rule). The sign is the solver's (ξ > 0
/// brakes: F_x < 0).
#[test]
fn small_creepage_matches_kalker_linear_theory() {
    let xi = 1e-4;
    let reference = -kalker_slope() * xi;
    for method in [
        TractionMethod::Linear,
        TractionMethod::Fastsim,
        TractionMethod::Exact,
    ] {
        let (h, _) = run(method, TractionDrive::Creepage(xi), 60);
        let last = h.last().unwrap();
        assert!(
            (last[0] - weight()).abs() < 1e-6 * weight(),
            "{method:?}: F_n {} vs W {}",
            last[0],
            weight()
        );
        let err = (last[1] - reference).abs() / reference.abs();
        println!(
            "{:8} F_x = {:.2} N, Kalker {:.2} N, rel. error {:.2e}, adhesion {:.3}",
            method.name(),
            last[1],
            reference,
            err,
            last[3]
        );
        assert!(err < 0.03, "{method:?}: {} vs {reference}", last[1]);
        assert!(
            last[3] > 0.8,
            "{method:?}: mostly adhesion, got {}",
            last[3]
        );
    }
}

/// (2) Large creepage ξ = 0.05 (about 5 × the saturation creepage 3μF_n/(Gc²C₁₁)): every
/// element slips and |F_x| = μF_n within 1 % (Coulomb's law; `exact` integrates μ p_n over
/// the BEM patch, whose total force is F_n; `fastsim` integrates the elliptic bound on 40 × 40
/// elements). Braking: F_x < 0.
#[test]
fn large_creepage_saturates_at_coulomb_limit() {
    for method in [
        TractionMethod::Linear,
        TractionMethod::Fastsim,
        TractionMethod::Exact,
    ] {
        let (h, sim) = run(method, TractionDrive::Creepage(0.05), 20);
        let last = h.last().unwrap();
        let limit = MU * last[0];
        let err = (last[1] + limit).abs() / limit;
        println!(
            "{:8} F_x = {:.2} N, -mu F_n = {:.2} N, rel. error {:.2e}",
            method.name(),
            last[1],
            -limit,
            err
        );
        assert!(err < 0.01, "{method:?}: {} vs {}", last[1], -limit);
        assert_eq!(last[3], 0.0, "{method:?}: full slip");
        let summary = sim.traction().unwrap().summary();
        assert!(summary.saturated_steps >= 10, "{summary:?}");
    }
}

/// (3) A driving torque T = 0.3 μ F_n R on a wheel of I = 50 kg m² starting in free rolling:
/// ω grows above V/R until the creep force balances the torque; at the end T = F_x R within
/// 1e-6 relative (the wheel's angular momentum balance I ω' = T − F_x R with ω' → 0). With the
/// capped linear theory the balance creepage is also checked against the closed form
/// ξ* = −T/(R G c² C₁₁) (1e-6). A torque above μF_nR cannot be balanced: the wheel spins up.
#[test]
fn driving_torque_reaches_torque_balance() {
    let r = GEOMETRY.wheel_radius;
    let torque = 0.3 * MU * weight() * r;
    for method in [TractionMethod::Linear, TractionMethod::Fastsim] {
        let (h, _) = run(
            method,
            TractionDrive::Torque {
                torque,
                inertia: 50.0,
            },
            200,
        );
        let last = h.last().unwrap();
        let speed = 2.0;
        assert!(last[4] > speed / r, "driving: ω above free rolling");
        let balance = (last[1] * r - torque).abs() / torque;
        println!(
            "{:8} F_x R = {:.3} N m, T = {:.3} N m, rel. {:.2e}, xi = {:.4e}, omega = {:.6} rad/s",
            method.name(),
            last[1] * r,
            torque,
            balance,
            last[2],
            last[4]
        );
        assert!(
            balance < 1e-6,
            "{method:?}: F_x R = {} vs T = {torque}",
            last[1] * r
        );
        assert!(
            last[2] < 0.0,
            "driving creepage is negative in the solver convention"
        );
        if method == TractionMethod::Linear {
            let xi_star = -torque / (r * kalker_slope());
            assert!((last[2] - xi_star).abs() < 1e-6 * xi_star.abs());
        }
    }
    // Above the Coulomb limit: no balance, ω keeps growing, every step saturated.
    let (h, sim) = run(
        TractionMethod::Fastsim,
        TractionDrive::Torque {
            torque: 2.0 * MU * weight() * r,
            inertia: 50.0,
        },
        100,
    );
    assert!(h[99][4] > h[50][4] && h[50][4] > h[10][4]);
    assert!(sim.traction().unwrap().summary().saturated_steps > 80);
}

/// (4) A fast wheel (30 m/s, no body) over a 3 mm dip 0.3 m long leaves the rail (the dip
/// accelerates the rail down at ≈ 600 m/s², the wheel only at W/m_w ≈ 93 m/s²): every step
/// with F_n = 0 has F_x = 0 and no adhesion, and steps in contact carry the creep force.
#[test]
fn loss_of_contact_gives_zero_traction() {
    let mut sc = scenario(ContactModel::Hertz, 1);
    sc.speed = 30.0;
    sc.dt = 1e-4;
    sc.duration = Some(0.05);
    sc.wheels[0].position = -1.0;
    sc.irregularity = Irregularity::Dip {
        position: -0.5,
        length: 0.3,
        depth: 3e-3,
    };
    let mut sim = Simulation::new(sc).unwrap();
    sim.set_traction(TractionSpec {
        mu: MU,
        method: TractionMethod::Fastsim,
        drive: TractionDrive::Creepage(1e-3),
        fastsim_elements: 20,
    })
    .unwrap();
    let (mut free, mut touching) = (0, 0);
    sim.run(|s| {
        let t = s.traction().unwrap().samples()[0];
        if s.wheels()[0].contact.force <= 0.0 {
            free += 1;
            assert_eq!(t.longitudinal_force, 0.0);
            assert_eq!(t.adhesion_fraction, 0.0);
        } else {
            touching += 1;
            assert!(t.longitudinal_force < 0.0);
        }
    })
    .unwrap();
    println!("steps without contact {free}, in contact {touching}");
    assert!(sim.loss_of_contact_events() > 0 && free > 5 && touching > 5);
}

/// Bad `[traction]` values and `exact` with a closed-form contact are errors naming the key.
#[test]
fn invalid_traction_input_names_the_key() {
    let cases = [
        (
            TractionSpec {
                mu: -0.1,
                method: TractionMethod::Fastsim,
                drive: TractionDrive::Creepage(0.0),
                fastsim_elements: 10,
            },
            ContactModel::Hertz,
            "traction.mu",
        ),
        (
            TractionSpec {
                mu: 0.3,
                method: TractionMethod::Fastsim,
                drive: TractionDrive::Creepage(f64::NAN),
                fastsim_elements: 10,
            },
            ContactModel::Hertz,
            "traction.creepage",
        ),
        (
            TractionSpec {
                mu: 0.3,
                method: TractionMethod::Linear,
                drive: TractionDrive::Torque {
                    torque: 1.0,
                    inertia: 0.0,
                },
                fastsim_elements: 10,
            },
            ContactModel::Hertz,
            "traction.wheel_inertia",
        ),
        (
            TractionSpec {
                mu: 0.3,
                method: TractionMethod::Exact,
                drive: TractionDrive::Creepage(0.0),
                fastsim_elements: 10,
            },
            ContactModel::Hertz,
            "traction.method",
        ),
    ];
    for (spec, contact, key) in cases {
        let mut sim = Simulation::new(scenario(contact, 1)).unwrap();
        match sim.set_traction(spec) {
            Err(
                VehicleBridgeError::InvalidParameter { name, .. }
                | VehicleBridgeError::InvalidChoice { name, .. },
            ) => assert_eq!(name, key),
            other => panic!("{key}: expected an error, got {other:?}"),
        }
    }
}

/// (3b) The same torque with `exact` transient rolling: the creep force now builds up over
/// about a patch length of rolling (≈ 15 steps here), a lag that makes the wheel's rotation a
/// damped oscillator (the creepage overshoots and even changes sign at first). After 600 steps
/// (≈ 40 patch lengths) it has settled: T = F_x R within 1e-4 (measured 2.1e-5; the oscillation
/// decays by about 2 per 80 steps), ω above free rolling, and the balance creepage lies within
/// 10 % of the linear-theory ξ* = −T/(R G c² C₁₁) (the exact half-space and the linear theory
/// differ by ≈ 1 % in slope, and F_x = 0.3 μF_n is already past the linear range: ≈ 7 %).
#[test]
fn driving_torque_with_exact_transient_rolling_settles_to_torque_balance() {
    let r = GEOMETRY.wheel_radius;
    let torque = 0.3 * MU * weight() * r;
    let (h, _) = run(
        TractionMethod::Exact,
        TractionDrive::Torque {
            torque,
            inertia: 50.0,
        },
        600,
    );
    let last = h.last().unwrap();
    let balance = (last[1] * r - torque).abs() / torque;
    let xi_star = -torque / (r * kalker_slope());
    println!(
        "exact F_x R = {:.3} N m, T = {:.3} N m, rel. {:.2e}, xi = {:.4e} (linear theory {:.4e})",
        last[1] * r,
        torque,
        balance,
        last[2],
        xi_star
    );
    assert!(balance < 1e-4);
    assert!(last[4] > 2.0 / r);
    assert!((last[2] / xi_star - 1.0).abs() < 0.1);
}
