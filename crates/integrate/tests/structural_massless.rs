//! Massless DOFs in the structural stepper (zero rows and columns of M), checked against
//! closed-form solutions.
//!
//! System: DOF 0 an undamped oscillator (m = 2 kg, k = 8 N/m, q(0) = 1 m: q = cos 2t);
//! DOF 1 the massless end node of a spring–damper (k₁ = 2 N/m, c₁ = 0.5 N s/m) under a
//! constant force F = 1 N: `c₁ q' + k₁ q = F`, a first-order relaxation with the exact
//! solution q₁(t) = F/k₁ (1 − e^{−t/τ}), τ = c₁/k₁ = 0.25 s (consistent start v₁(0) = F/c₁).

use faer::Mat;
use integrate::IntegrateError;
use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper};

const M0: f64 = 2.0;
const K0: f64 = 8.0;
const K1: f64 = 2.0;
const C1: f64 = 0.5;
const F: f64 = 1.0;

fn system() -> LinearStructure<impl FnMut(f64, &mut [f64])> {
    let mass = Mat::from_fn(2, 2, |i, j| if i == 0 && j == 0 { M0 } else { 0.0 });
    let damping = Mat::from_fn(2, 2, |i, j| if i == 1 && j == 1 { C1 } else { 0.0 });
    let stiffness = Mat::from_fn(2, 2, |i, j| match (i, j) {
        (0, 0) => K0,
        (1, 1) => K1,
        _ => 0.0,
    });
    LinearStructure::new(mass, Some(damping), stiffness, |_t: f64, f: &mut [f64]| {
        f[0] = 0.0;
        f[1] = F;
    })
    .unwrap()
}

fn exact_relaxation(t: f64) -> f64 {
    F / K1 * (1.0 - (-t * K1 / C1).exp())
}

/// Error of both DOFs at t = 1 s with step `dt`; `exact_start` gives the exact initial
/// acceleration of the massless DOF (−k₁/c₁ · v₁(0)) through `restart_with_acceleration`.
fn errors_at_one_second(method: StructuralMethod, dt: f64, exact_start: bool) -> (f64, f64) {
    let mut sys = system();
    let q0 = [1.0, 0.0];
    let v0 = [0.0, F / C1];
    let mut stepper = StructuralStepper::new(method, &mut sys, 0.0, &q0, &v0).unwrap();
    assert_eq!(stepper.massless_dofs(), &[1]);
    // The massive DOF's start acceleration comes from M⁻¹ over the massive rows.
    assert!((stepper.a()[0] - (-K0 / M0)).abs() < 1e-12);
    assert_eq!(stepper.a()[1], 0.0);
    if exact_start {
        let a0 = [-K0 / M0, -K1 / C1 * F / C1];
        stepper
            .restart_with_acceleration(&mut sys, 0.0, &q0, &v0, &a0)
            .unwrap();
    }
    let n = (1.0 / dt).round() as usize;
    for _ in 0..n {
        stepper.step(&mut sys, dt).unwrap();
    }
    let t = stepper.t();
    (
        (stepper.q()[0] - (2.0 * t).cos()).abs(),
        (stepper.q()[1] - exact_relaxation(t)).abs(),
    )
}

/// Observed orders log2(e(dt)/e(dt/2)) over three halvings.
fn observed_orders(method: StructuralMethod, exact_start: bool) -> Vec<(f64, f64)> {
    let dts = [0.02, 0.01, 0.005, 0.0025];
    let errs: Vec<(f64, f64)> = dts
        .iter()
        .map(|&dt| errors_at_one_second(method, dt, exact_start))
        .collect();
    eprintln!(
        "{} errors (oscillator, relaxation) at dt = {dts:?}: {errs:?}",
        method.name()
    );
    errs.windows(2)
        .map(|w| ((w[0].0 / w[1].0).log2(), (w[0].1 / w[1].1).log2()))
        .collect()
}

#[test]
fn trapezoidal_rule_is_second_order_on_a_massless_relaxation() {
    // Newmark β = ¼, γ = ½ on the massless row is the trapezoidal rule for c q' + k q = F,
    // whatever the start acceleration (q_{n+1} = q_n + Δt/2 (v_n + v_{n+1})): order 2.
    let method = StructuralMethod::average_acceleration();
    let orders = observed_orders(method, false);
    for &(p0, p1) in &orders {
        assert!(
            (p0 - 2.0).abs() < 0.05,
            "oscillator order {p0} ({orders:?})"
        );
        assert!(
            (p1 - 2.0).abs() < 0.05,
            "relaxation order {p1} ({orders:?})"
        );
    }
    // Absolute accuracy: the trapezoidal rule's leading global error for y' = −y/τ is
    // (Δt²/12τ²)·(t/τ)·e^{−t/τ}·F/k₁ = 3.05e-7 at Δt = 2.5 ms, t = 1 s (measured 3.05e-7);
    // allow 5 % for the higher-order terms.
    let (_, e1) = errors_at_one_second(method, 0.0025, false);
    let leading = (0.0025f64 / 0.25).powi(2) / 12.0 * 4.0 * (-4.0f64).exp() * F / K1;
    assert!(
        (e1 / leading - 1.0).abs() < 0.05,
        "relaxation error {e1:e} vs {leading:e}"
    );
}

#[test]
fn generalized_alpha_with_given_start_acceleration_is_second_order() {
    // Generalized-α uses a_n in the massless row's history; with the exact start acceleration
    // it keeps order 2 there.
    let method = StructuralMethod::generalized_alpha(0.8).unwrap();
    let orders = observed_orders(method, true);
    for &(p0, p1) in &orders {
        assert!(
            (p0 - 2.0).abs() < 0.15,
            "oscillator order {p0} ({orders:?})"
        );
        assert!(
            (p1 - 2.0).abs() < 0.15,
            "relaxation order {p1} ({orders:?})"
        );
    }
}

#[test]
fn hht_and_backward_euler_converge_on_the_massless_row() {
    // Backward Euler: first order (measured ratio of errors ≈ 2 per halving).
    let orders = observed_orders(StructuralMethod::BackwardEuler, false);
    for &(_, p1) in &orders {
        assert!(
            (p1 - 1.0).abs() < 0.1,
            "backward Euler order {p1} ({orders:?})"
        );
    }
    let orders = observed_orders(StructuralMethod::hht(-0.1).unwrap(), true);
    for &(_, p1) in &orders {
        assert!((p1 - 2.0).abs() < 0.15, "HHT order {p1} ({orders:?})");
    }
}

#[test]
fn explicit_methods_refuse_massless_dofs() {
    for method in [
        StructuralMethod::StormerVerlet,
        StructuralMethod::Leapfrog,
        StructuralMethod::central_difference(),
    ] {
        let mut sys = system();
        let err =
            StructuralStepper::new(method, &mut sys, 0.0, &[1.0, 0.0], &[0.0, 2.0]).unwrap_err();
        match err {
            IntegrateError::InvalidParameter { name, reason } => {
                assert_eq!(name, "mass");
                assert!(reason.contains("DOF 1 is massless"), "{reason}");
            }
            other => panic!("unexpected error {other:?}"),
        }
    }
}

#[test]
fn a_zero_diagonal_with_off_diagonal_mass_is_still_an_error() {
    let mass = Mat::from_fn(2, 2, |i, j| match (i, j) {
        (0, 0) => 1.0,
        (1, 1) => 0.0,
        _ => 0.5,
    });
    let err = LinearStructure::new(
        mass,
        None,
        Mat::<f64>::identity(2, 2),
        |_t: f64, f: &mut [f64]| f.fill(0.0),
    )
    .err()
    .expect("a zero diagonal with off-diagonal mass must be rejected");
    assert!(matches!(
        err,
        IntegrateError::InvalidParameter { name: "mass", .. }
    ));
}
