//! Moving loads on finite-element modal bases (the same code path as the analytic modes), a
//! continuous two-span bridge against the FE static solution, and damped modal response against
//! an independent RK4 integration.

use std::f64::consts::PI;

use beam::closed_form::{speed_for_parameter, ss_midspan_static_deflection};
use beam::{
    AnalyticBeam, Derivative, FeBeam, ModalBasis, ModalDamping, MovingLoadSettings, MovingLoads,
    PointSupport, Section, Support, SupportKind, UniformBeam, simulate_moving_loads,
};

const L: f64 = 25.0;
const EI: f64 = 2.87e9 * 2.90;
const RHO_A: f64 = 2303.0;
const FORCE: f64 = 56.4e3;

fn section(length: f64) -> Vec<Section> {
    vec![Section {
        length,
        bending_stiffness: EI,
        mass_per_length: RHO_A,
    }]
}

/// FE modes (60 elements, 20 modes) in the moving-load simulation reproduce the undamped table
/// value 1.7054 at α = 0.5 (references.md §D1.1) to 2e-4: table rounding 5e-5, 20-mode truncation
/// ≈ 1.2e-5, FE frequency error of mode 1 ≈ 1e-9.
#[test]
fn fe_basis_reproduces_the_table() {
    let supports = [
        PointSupport {
            x: 0.0,
            kind: SupportKind::Pinned,
        },
        PointSupport {
            x: L,
            kind: SupportKind::Pinned,
        },
    ];
    let fe = FeBeam::new(&section(L), &supports, &[], 60)
        .unwrap()
        .modes(20)
        .unwrap();
    let beam = UniformBeam::new(L, EI, RHO_A).unwrap();
    let c = speed_for_parameter(&beam, 0.5).unwrap();
    let t1 = 2.0 * PI / fe.circular_frequencies()[0];
    let loads = MovingLoads::single(FORCE, c).unwrap();
    let settings = MovingLoadSettings::new(t1 / 4000.0, 0.0);
    // Through a trait object: analytic and FE bases are interchangeable behind `dyn ModalBasis`.
    let basis: &dyn ModalBasis = &fe;
    let r = simulate_moving_loads(
        basis,
        &ModalDamping::Undamped,
        &loads,
        &settings,
        &[0.5 * L],
    )
    .unwrap();
    let ratio = r.max_abs_deflection(0).unwrap() / ss_midspan_static_deflection(FORCE, L, EI);
    eprintln!("FE basis: passage max / d_st = {ratio:.6}");
    assert!((ratio - 1.7054).abs() < 2e-4, "{ratio}");
}

/// Continuous two-span bridge (2 × 25 m, pinned at 0, 25, 50 m), a force crawling at 0.2 m/s:
/// the quasi-static modal deflection under the force at x = 12.5 m (40 FE modes) equals the FE
/// static solution K⁻¹f (independent path, no modes) within the modal truncation (tolerance 1e-4
/// relative), and the dynamic response within the crawling-speed excess (tolerance 2e-3).
#[test]
fn two_span_quasi_static_matches_fe_static_solution() {
    let supports = [
        PointSupport {
            x: 0.0,
            kind: SupportKind::Pinned,
        },
        PointSupport {
            x: L,
            kind: SupportKind::Pinned,
        },
        PointSupport {
            x: 2.0 * L,
            kind: SupportKind::Pinned,
        },
    ];
    let fe_beam = FeBeam::new(&section(2.0 * L), &supports, &[], 100).unwrap();
    let modes = fe_beam.modes(40).unwrap();
    let exact = fe_beam
        .static_deflection(&[(0.5 * L, FORCE)])
        .unwrap()
        .eval(0.5 * L, Derivative::Shape)
        .unwrap();
    let speed = 0.2;
    let loads = MovingLoads::single(FORCE, speed).unwrap();
    let dt = 0.5 * L / speed / 2000.0;
    let settings = MovingLoadSettings::new(dt, 0.0);
    let r = simulate_moving_loads(
        &modes,
        &ModalDamping::Uniform(0.01),
        &loads,
        &settings,
        &[0.5 * L],
    )
    .unwrap();
    let i = r
        .times
        .iter()
        .position(|&t| (t * speed - 0.5 * L).abs() < 1e-9 * L)
        .unwrap();
    let quasi = r.quasi_static_deflection[i];
    let dynamic = r.deflection[i];
    eprintln!("two-span: static {exact:e}, quasi-static {quasi:e}, dynamic {dynamic:e}");
    assert!((quasi / exact - 1.0).abs() < 1e-4);
    assert!((dynamic / exact - 1.0).abs() < 2e-3);
}

/// Damped response (ζ = 5 %, one SS mode): the exact piecewise-linear modal step against a
/// classical RK4 integration of q'' + 2ζωq' + ω²q = F w₁(ct) with 20× smaller steps (RK4 error
/// ≈ (ωΔt)⁴/120 ≈ 1e-11 relative); tolerance 5e-7 of max|q|: the recurrence is exact for a
/// piecewise-linear force, and linear interpolation of sin(Ωt), Ω = πc/L, errs by up to
/// (ΩΔt)²/8 ≈ 2e-7 of the force amplitude.
#[test]
fn damped_modal_response_matches_rk4() {
    let beam = UniformBeam::new(L, EI, RHO_A).unwrap();
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, 1).unwrap();
    let omega = basis.circular_frequencies()[0];
    let zeta = 0.05;
    let c = speed_for_parameter(&beam, 0.4).unwrap();
    let t1 = 2.0 * PI / omega;
    let dt = t1 / 2000.0;
    let loads = MovingLoads::single(FORCE, c).unwrap();
    let settings = MovingLoadSettings::new(dt, 0.0);
    let r = simulate_moving_loads(
        &basis,
        &ModalDamping::Uniform(zeta),
        &loads,
        &settings,
        &[0.5 * L],
    )
    .unwrap();
    let amp = (2.0 / (RHO_A * L)).sqrt();
    let force = |t: f64| {
        if c * t <= L {
            FORCE * amp * (PI * c * t / L).sin()
        } else {
            0.0
        }
    };
    let rhs = |t: f64, q: f64, v: f64| (v, force(t) - 2.0 * zeta * omega * v - omega * omega * q);
    let (mut q, mut v) = (0.0, 0.0);
    let h = dt / 20.0;
    let mut worst: f64 = 0.0;
    let mut max_defl: f64 = 0.0;
    for (i, &t_sample) in r.times.iter().enumerate().skip(1) {
        let t0 = t_sample - dt;
        for k in 0..20 {
            let t = t0 + k as f64 * h;
            let (k1q, k1v) = rhs(t, q, v);
            let (k2q, k2v) = rhs(t + 0.5 * h, q + 0.5 * h * k1q, v + 0.5 * h * k1v);
            let (k3q, k3v) = rhs(t + 0.5 * h, q + 0.5 * h * k2q, v + 0.5 * h * k2v);
            let (k4q, k4v) = rhs(t + h, q + h * k3q, v + h * k3v);
            q += h / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
        let w = q * amp; // midspan shape value √(2/ρAL)·sin(π/2)
        worst = worst.max((r.deflection[i] - w).abs());
        max_defl = max_defl.max(w.abs());
    }
    eprintln!("damped vs RK4: max deviation {:e} of max", worst / max_defl);
    assert!(worst < 5e-7 * max_defl);
}
