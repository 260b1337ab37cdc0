//! Stiff test set (references.md §D3.1): Radau5 and BDF against the published Bari test-set
//! reference values (computed by the test-set authors with RADAU at 1.1e-18 in extended
//! precision, i.e. independent of this code), Fortran RADAU5's run statistics, and the
//! explicit-vs-implicit step count on stiff Van der Pol.

// Reference values are quoted with all the digits the test set publishes.
#![allow(clippy::excessive_precision)]

mod ode_support;

use integrate::ode::{Method, OdeOptions, OdeStepper, Radau5};
use ode_support::{Hires, Oregonator, Robertson, VanDerPol, VanDerPolJac, run_to};

/// VDPOL reference y(2000) for μ = 1000 (test set); in the ε-scaled form (ε = 1/μ² = 1e-6,
/// x = t/μ ∈ [0, 2]) y₂ is multiplied by μ.
const VDPOL_REF: [f64; 2] = [1.706167732170469, -0.8928097010248125];
const ROBER_REF: [f64; 3] = [
    0.2083340149701255e-7,
    0.8333360770334713e-13,
    0.9999999791665050,
];
const HIRES_REF: [f64; 8] = [
    0.7371312573325668e-3,
    0.1442485726316185e-3,
    0.5888729740967575e-4,
    0.1175651343283149e-2,
    0.2386356198831331e-2,
    0.6238968252742796e-2,
    0.2849998395185769e-2,
    0.2850001604814231e-2,
];
const HIRES_Y0: [f64; 8] = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057];
const HIRES_END: f64 = 321.8122;

/// Largest relative deviation from the reference, per component.
fn max_relative_error(y: &[f64], reference: &[f64]) -> f64 {
    y.iter()
        .zip(reference)
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max)
}

fn solve_vdpol(method: Method, rtol: f64) -> f64 {
    let opts = OdeOptions {
        rtol,
        atol: rtol,
        ..OdeOptions::default()
    };
    let mut s = method.build(2, &opts).unwrap();
    let y = run_to(
        s.as_mut(),
        &mut VanDerPol { eps: 1e-6 },
        0.0,
        &[2.0, 0.0],
        2.0,
    );
    let err = max_relative_error(&y, &VDPOL_REF);
    eprintln!(
        "{} VDPOL rtol {rtol:e}: max rel error {err:.2e}, {:?}",
        method.name(),
        s.stats()
    );
    err
}

fn solve_rober(method: Method, rtol: f64) -> f64 {
    // atol far below y₂ ≈ 1e-13 so that every component is controlled relatively.
    let opts = OdeOptions {
        rtol,
        atol: 1e-20,
        ..OdeOptions::default()
    };
    let mut s = method.build(3, &opts).unwrap();
    let y = run_to(s.as_mut(), &mut Robertson, 0.0, &[1.0, 0.0, 0.0], 1e11);
    let err = max_relative_error(&y, &ROBER_REF);
    eprintln!(
        "{} ROBER rtol {rtol:e}: max rel error {err:.2e}, {:?}",
        method.name(),
        s.stats()
    );
    err
}

fn solve_hires(method: Method, rtol: f64) -> f64 {
    let opts = OdeOptions {
        rtol,
        atol: rtol * 1e-4,
        ..OdeOptions::default()
    };
    let mut s = method.build(8, &opts).unwrap();
    let y = run_to(s.as_mut(), &mut Hires, 0.0, &HIRES_Y0, HIRES_END);
    let err = max_relative_error(&y, &HIRES_REF);
    eprintln!(
        "{} HIRES rtol {rtol:e}: max rel error {err:.2e}, {:?}",
        method.name(),
        s.stats()
    );
    err
}

const OREGO_REF: [f64; 3] = [
    0.1000814870318523e1,
    0.1228178521549917e4,
    0.1320554942846706e3,
];

fn solve_orego(method: Method, rtol: f64) -> f64 {
    let opts = OdeOptions {
        rtol,
        atol: rtol,
        ..OdeOptions::default()
    };
    let mut s = method.build(3, &opts).unwrap();
    let y = run_to(s.as_mut(), &mut Oregonator, 0.0, &[1.0, 2.0, 3.0], 360.0);
    let err = max_relative_error(&y, &OREGO_REF);
    eprintln!(
        "{} OREGO rtol {rtol:e}: max rel error {err:.2e}, {:?}",
        method.name(),
        s.stats()
    );
    err
}

/// references.md §D3.1: assert about 1e-10 relative with rtol ≤ 1e-10. Measured 5–7e-11 (VDPOL),
/// 8.3e-12 (ROBER), and at rtol 1e-12 3.4e-11 (HIRES) and 1.1e-11 (OREGO); HIRES reaches
/// 1.8e-9 at rtol 1e-10: RADAU5's tolerance transformation rtol' = 0.1·rtol^{2/3} lets the
/// global error exceed rtol there.
#[test]
fn radau5_reproduces_stiff_test_set() {
    assert!(solve_vdpol(Method::Radau5, 1e-10) < 1e-10);
    assert!(solve_rober(Method::Radau5, 1e-10) < 1e-10);
    assert!(solve_hires(Method::Radau5, 1e-12) < 1e-10);
    assert!(solve_orego(Method::Radau5, 1e-12) < 1e-10);
}

/// BDF at rtol 1e-10 asserted at 1e-8 relative: a variable-order multistep method's global
/// error accumulates over the ~1000–6000 steps to 10–40 × rtol (measured 3.0e-9 VDPOL,
/// 3.5e-9 ROBER, 2.6e-9 HIRES). OREGO, whose relaxation oscillations amplify errors, needs
/// rtol 1e-11 for the same bound (measured 3.4e-8 at 1e-10, 5.1e-9 at 1e-11).
#[test]
fn bdf_reproduces_stiff_test_set() {
    assert!(solve_vdpol(Method::Bdf, 1e-10) < 1e-8);
    assert!(solve_rober(Method::Bdf, 1e-10) < 1e-8);
    assert!(solve_hires(Method::Bdf, 1e-10) < 1e-8);
    assert!(solve_orego(Method::Bdf, 1e-11) < 1e-8);
}

/// Fortran RADAU5 on VdP ε = 1e-6, y₀ = (2, −0.6), rtol = atol = 1e-4, h₀ = 1e-6 with the
/// analytic Jacobian (references.md §D3.1, russell logs): naccept 242, nstep 280, nreject 8,
/// njac 162, ndec 252 (pairs), nsol 668, nfcn 2248, y(2) = (1.706163410178079,
/// −0.8927971289301175). Every counter is reproduced exactly except nfcn, where we count
/// 2247: band ±1 (the one evaluation is not located; russell's port reports +1 itself).
/// The final state agrees to 1e-12 relative (rounding-level differences of a 280-step run).
#[test]
fn radau5_statistics_match_fortran_radau5_on_van_der_pol() {
    let opts = OdeOptions {
        rtol: 1e-4,
        atol: 1e-4,
        initial_step: Some(1e-6),
        ..OdeOptions::default()
    };
    let mut r = Radau5::new(2, &opts).unwrap();
    let y = run_to(
        &mut r,
        &mut VanDerPolJac { eps: 1e-6 },
        0.0,
        &[2.0, -0.6],
        2.0,
    );
    let s = r.stats();
    assert_eq!(s.steps, 242, "naccept");
    assert_eq!(s.steps + s.rejected_steps, 280, "nstep");
    assert_eq!(r.error_test_failures(), 8, "nreject");
    assert_eq!(s.jacobian_evals, 162, "njac");
    assert_eq!(s.lu_decompositions, 2 * 252, "ndec (real + complex)");
    assert_eq!(s.newton_iterations, 668, "nsol");
    assert!(s.f_evals.abs_diff(2248) <= 1, "nfcn {}", s.f_evals);
    assert!(
        max_relative_error(&y, &[1.706163410178079, -0.8927971289301175]) < 1e-12,
        "y = {y:?}"
    );
}

/// Fortran RADAU5 on Robertson, [0, 0.3], rtol 1e-2, atol 1e-8, h₀ = 1e-6 (references.md §D3.1):
/// 15 accepted of 17 steps, 1 rejected, 8 Jacobians, 15 decompositions, 88 f-evaluations and
/// y = (0.9886740138499884, 3.447720471782070e-5, 1.129150894529390e-2). Same band as above.
#[test]
fn radau5_statistics_match_fortran_radau5_on_robertson() {
    let opts = OdeOptions {
        rtol: 1e-2,
        atol: 1e-8,
        initial_step: Some(1e-6),
        ..OdeOptions::default()
    };
    let mut r = Radau5::new(3, &opts).unwrap();
    let y = run_to(&mut r, &mut Robertson, 0.0, &[1.0, 0.0, 0.0], 0.3);
    let s = r.stats();
    assert_eq!(s.steps, 15);
    assert_eq!(s.steps + s.rejected_steps, 17);
    assert_eq!(r.error_test_failures(), 1);
    assert_eq!(s.jacobian_evals, 8);
    assert_eq!(s.lu_decompositions, 2 * 15);
    assert!(s.f_evals.abs_diff(88) <= 1, "nfcn {}", s.f_evals);
    let reference = [
        0.9886740138499884,
        3.447720471782070e-5,
        1.129150894529390e-2,
    ];
    assert!(max_relative_error(&y, &reference) < 1e-12, "y = {y:?}");
}

/// Stiffness in numbers: on VdP ε = 1e-6 at rtol = atol = 1e-6 the explicit DOPRI5 is limited
/// by stability (h ≲ 3.3/|λ|, |λ| ~ 3/ε) and needs over a million steps, Radau5 about 500.
/// Asserted ratio ≥ 50 (references.md §R5.1); measured ≈ 2400.
#[test]
fn explicit_method_needs_far_more_steps_on_stiff_van_der_pol() {
    let opts = OdeOptions {
        rtol: 1e-6,
        atol: 1e-6,
        ..OdeOptions::default()
    };
    let mut explicit = Method::Dopri5.build(2, &opts).unwrap();
    let mut implicit = Method::Radau5.build(2, &opts).unwrap();
    let y_explicit = run_to(
        explicit.as_mut(),
        &mut VanDerPol { eps: 1e-6 },
        0.0,
        &[2.0, 0.0],
        2.0,
    );
    let y_implicit = run_to(
        implicit.as_mut(),
        &mut VanDerPol { eps: 1e-6 },
        0.0,
        &[2.0, 0.0],
        2.0,
    );
    let ratio = explicit.stats().steps as f64 / implicit.stats().steps as f64;
    eprintln!(
        "DOPRI5 {:?}\nRadau5 {:?}\nratio {ratio:.0}",
        explicit.stats(),
        implicit.stats()
    );
    assert!(ratio >= 50.0, "step ratio {ratio}");
    // Both still solve the problem (tolerance 1e-4: rtol 1e-6 with error growth at the jumps).
    assert!(max_relative_error(&y_explicit, &VDPOL_REF) < 1e-4);
    assert!(max_relative_error(&y_implicit, &VDPOL_REF) < 1e-4);
}
