//! Observed global order of convergence on u'' + u = 0, t ∈ [0, 10], Δt = 0.01 → 0.005
//! (references.md §D3.5 "Observed global order"). The error is max(|q − cos t|, |v + sin t|) at
//! t = 10, against the exact solution. Every order must lie within ±0.2 of theory (the
//! assignment's bar); where references.md prints an observed order, we also check it to ±0.01.

mod structural_support;

use integrate::structural::StructuralMethod;
use structural_support::{observed_order, oscillator_error};

fn order(method: StructuralMethod) -> f64 {
    let p = observed_order(
        oscillator_error(method, 0.01),
        oscillator_error(method, 0.005),
    );
    println!("{:>20} {method:?}: observed order {p:.4}", method.name());
    p
}

#[test]
fn newmark_average_acceleration_is_second_order() {
    let p = order(StructuralMethod::average_acceleration());
    assert!((p - 2.0).abs() < 0.2, "order {p}");
}

#[test]
fn newmark_linear_acceleration_is_second_order() {
    let p = order(StructuralMethod::linear_acceleration());
    assert!((p - 2.0).abs() < 0.2, "order {p}");
}

#[test]
fn hht_minus_0_1_is_second_order() {
    let p = order(StructuralMethod::hht(-0.1).unwrap());
    assert!((p - 2.0).abs() < 0.2, "order {p}");
    // references.md §D3.5 prints 1.999.
    assert!((p - 1.999).abs() < 0.01, "order {p} vs published 1.999");
}

#[test]
fn generalized_alpha_0_5_is_second_order() {
    let p = order(StructuralMethod::generalized_alpha(0.5).unwrap());
    assert!((p - 2.0).abs() < 0.2, "order {p}");
    // references.md §D3.5 prints 1.998.
    assert!((p - 1.998).abs() < 0.01, "order {p} vs published 1.998");
}

#[test]
fn newmark_gamma_0_6_is_first_order() {
    let p = order(StructuralMethod::newmark(0.3025, 0.6).unwrap());
    assert!((p - 1.0).abs() < 0.2, "order {p}");
    // references.md §D3.5 prints 0.990.
    assert!((p - 0.990).abs() < 0.01, "order {p} vs published 0.990");
}

#[test]
fn verlet_is_second_order() {
    let p = order(StructuralMethod::StormerVerlet);
    assert!((p - 2.0).abs() < 0.2, "order {p}");
}

#[test]
fn leapfrog_is_second_order() {
    let p = order(StructuralMethod::Leapfrog);
    assert!((p - 2.0).abs() < 0.2, "order {p}");
}

#[test]
fn central_difference_is_second_order() {
    let p = order(StructuralMethod::central_difference());
    assert!((p - 2.0).abs() < 0.2, "order {p}");
}

#[test]
fn backward_euler_is_first_order() {
    let p = order(StructuralMethod::BackwardEuler);
    assert!((p - 1.0).abs() < 0.2, "order {p}");
}

/// Error at t = 10 of u'' + u = 0 with alternating steps h, 1.7h (the last one clipped).
fn alternating_step_error(method: StructuralMethod, h: f64) -> f64 {
    let mut p = structural_support::oscillator(1.0);
    let mut s =
        integrate::structural::StructuralStepper::new(method, &mut p, 0.0, &[1.0], &[0.0]).unwrap();
    let mut k = 0;
    while s.t() < 10.0 - 1e-12 {
        let dt = if k % 2 == 0 { h } else { 1.7 * h };
        s.step(&mut p, dt.min(10.0 - s.t())).unwrap();
        k += 1;
    }
    let t = s.t();
    (s.q()[0] - t.cos()).abs().max((s.v()[0] + t.sin()).abs())
}

#[test]
fn second_order_survives_step_size_changes() {
    // HHT and generalized-α need the step-change correction of the algorithmic acceleration
    // (without it this test measured orders 1.57 → 1.40, tending to 1); one-step Newmark and
    // Verlet are second order for any step sequence. ±0.2 as above.
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::hht(-0.1).unwrap(),
        StructuralMethod::generalized_alpha(0.5).unwrap(),
        StructuralMethod::generalized_alpha(0.0).unwrap(),
        StructuralMethod::StormerVerlet,
    ] {
        let (e1, e2) = (
            alternating_step_error(method, 0.01),
            alternating_step_error(method, 0.005),
        );
        let p = observed_order(e1, e2);
        println!("{method:?} with alternating steps: {e1:e} → {e2:e}, order {p:.4}");
        assert!((p - 2.0).abs() < 0.2, "{method:?}: order {p}");
    }
}

#[test]
fn step_size_changes_keep_stiff_components_damped() {
    // A stiff mode (ω = 1e4, Ω up to 100) under repeated step changes by a factor 2 (where
    // the step-change correction acts) and 10 (where it is skipped): the dissipative schemes
    // must still damp it. Criterion: max(|q|, |v|/ω) falls from 1e-4 below 1e-6 in 400 steps.
    // (Measured: ρ∞ = 0.9 damps slowest, to ~5e-9; extrapolating at every 10× jump made
    // gen-α(0.5) grow to 1e31 here, which is why the correction is limited to ratios ≤ 2.)
    use faer::Mat;
    use integrate::structural::{LinearStructure, StructuralStepper};
    for method in [
        StructuralMethod::hht(-0.1).unwrap(),
        StructuralMethod::generalized_alpha(0.5).unwrap(),
        StructuralMethod::generalized_alpha(0.0).unwrap(),
        StructuralMethod::generalized_alpha(0.9).unwrap(),
    ] {
        for ratio in [2.0, 10.0] {
            let stiffness = Mat::from_fn(2, 2, |i, j| if i == j { [1.0, 1e8][i] } else { 0.0 });
            let mut p =
                LinearStructure::new(Mat::identity(2, 2), None, stiffness, |_, f: &mut [f64]| {
                    f.fill(0.0)
                })
                .unwrap();
            let mut s =
                StructuralStepper::new(method, &mut p, 0.0, &[1.0, 1e-4], &[0.0, 0.0]).unwrap();
            for k in 0..400 {
                let dt = if (k / 3) % 2 == 0 { 1e-3 } else { 1e-3 * ratio };
                s.step(&mut p, dt).unwrap();
            }
            let amplitude = s.q()[1].abs().max(s.v()[1].abs() / 1e4);
            println!("{method:?}, step ratio {ratio}: stiff amplitude {amplitude:e}");
            assert!(
                amplitude < 1e-6,
                "{method:?}, ratio {ratio}: amplitude {amplitude:e}"
            );
        }
    }
}
