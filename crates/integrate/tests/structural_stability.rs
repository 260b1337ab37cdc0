//! The stability limit `StructuralMethod::critical_step` checked by measurement: on an
//! undamped oscillator (ω = 10 rad/s), 5000 steps at 0.98 × the limit stay bounded and at
//! 1.02 × the limit grow without bound, for every conditionally stable method; the
//! unconditionally stable methods report no limit and stay bounded at Ω = ω Δt = 1e3.

use faer::Mat;
use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper};

const OMEGA: f64 = 10.0;

fn amplitude_after(method: StructuralMethod, dt: f64, steps: usize) -> f64 {
    let mut sys = LinearStructure::new(
        Mat::from_fn(1, 1, |_, _| 1.0),
        None,
        Mat::from_fn(1, 1, |_, _| OMEGA * OMEGA),
        |_t: f64, f: &mut [f64]| f[0] = 0.0,
    )
    .unwrap();
    let mut stepper = StructuralStepper::new(method, &mut sys, 0.0, &[1.0], &[0.0]).unwrap();
    let mut peak: f64 = 0.0;
    for _ in 0..steps {
        if stepper.step(&mut sys, dt).is_err() {
            return f64::INFINITY;
        }
        peak = peak.max(stepper.q()[0].abs());
        if !peak.is_finite() {
            return f64::INFINITY;
        }
    }
    peak
}

#[test]
fn conditionally_stable_methods_are_stable_exactly_up_to_the_limit() {
    for (method, omega_crit) in [
        (StructuralMethod::StormerVerlet, 2.0),
        (StructuralMethod::Leapfrog, 2.0),
        (StructuralMethod::central_difference(), 2.0),
        // Linear acceleration β = 1/6, γ = ½: Ω_crit = 1/√(1/4 − 1/6) = √12.
        (StructuralMethod::linear_acceleration(), 12f64.sqrt()),
    ] {
        let limit = method.critical_step(OMEGA).expect("conditionally stable");
        assert!(
            (limit * OMEGA / omega_crit - 1.0).abs() < 1e-14,
            "{method:?}: limit {limit}"
        );
        let below = amplitude_after(method, 0.98 * limit, 5000);
        let above = amplitude_after(method, 1.02 * limit, 5000);
        assert!(
            below < 100.0,
            "{method:?}: amplitude {below} below the limit"
        );
        assert!(above > 1e6, "{method:?}: amplitude {above} above the limit");
    }
}

#[test]
fn unconditionally_stable_methods_have_no_limit() {
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::hht(-0.1).unwrap(),
        StructuralMethod::generalized_alpha(0.5).unwrap(),
        StructuralMethod::BackwardEuler,
    ] {
        assert_eq!(method.critical_step(OMEGA), None, "{method:?}");
        let amplitude = amplitude_after(method, 1e3 / OMEGA, 2000);
        assert!(amplitude <= 1.0 + 1e-9, "{method:?}: {amplitude}");
    }
}
