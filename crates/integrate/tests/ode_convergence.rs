//! Observed orders of convergence of every method on problems with exact solutions, measured by
//! halving the (fixed) step: harmonic oscillator y'' = −y to T = 2 (exact (cos T, −sin T)) and
//! linear decay y' = −y to T = 2 (exact e^{−T}). Each observed order log2(e(h)/e(h/2)) must
//! equal the theoretical order within ±0.2 (references.md §R5.1; the step ranges are chosen in the
//! asymptotic regime and above round-off, which the printed errors document).

mod ode_support;

use integrate::ode::{Method, OdeOptions, OdeSystem};
use ode_support::{Decay, Oscillator, observed_orders, run_to};

const T_END: f64 = 2.0;

/// Max-norm global error at T_END for each step in `steps`.
fn errors(
    method: Method,
    base: OdeOptions,
    steps: &[f64],
    sys: &mut dyn OdeSystem,
    oscillator: bool,
) -> Vec<f64> {
    steps
        .iter()
        .map(|&h| {
            let opts = OdeOptions {
                fixed_step: Some(h),
                ..base
            };
            let mut stepper = method.build(sys.dim(), &opts).expect("valid options");
            if oscillator {
                let y = run_to(stepper.as_mut(), sys, 0.0, &[1.0, 0.0], T_END);
                (y[0] - T_END.cos()).abs().max((y[1] + T_END.sin()).abs())
            } else {
                let y = run_to(stepper.as_mut(), sys, 0.0, &[1.0], T_END);
                (y[0] - (-T_END).exp()).abs()
            }
        })
        .collect()
}

fn assert_order(method: Method, base: OdeOptions, steps: &[f64], expected: f64) {
    for oscillator in [true, false] {
        let errs: Vec<f64> = if oscillator {
            errors(method, base, steps, &mut Oscillator, true)
        } else {
            errors(method, base, steps, &mut Decay { lambda: 1.0 }, false)
        };
        let orders = observed_orders(&errs);
        let problem = if oscillator { "oscillator" } else { "decay" };
        eprintln!(
            "{} (order {expected}) on {problem}: errors {}, orders {orders:.3?}",
            method.name(),
            errs.iter()
                .map(|e| format!("{e:.3e}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
        for p in &orders {
            assert!(
                (p - expected).abs() <= 0.2,
                "{} on {problem}: observed order {p:.3}, expected {expected}",
                method.name()
            );
        }
    }
}

/// Steps h, h/2, h/4, h/8 with h = T_END/n0.
fn halvings(n0: usize) -> Vec<f64> {
    (0..4).map(|k| T_END / (n0 << k) as f64).collect()
}

#[test]
fn explicit_euler_is_first_order() {
    assert_order(Method::Euler, OdeOptions::default(), &halvings(80), 1.0);
}

#[test]
fn rk4_is_fourth_order() {
    assert_order(Method::Rk4, OdeOptions::default(), &halvings(10), 4.0);
}

#[test]
fn dopri5_fixed_step_is_fifth_order() {
    assert_order(Method::Dopri5, OdeOptions::default(), &halvings(16), 5.0);
}

#[test]
fn backward_euler_is_first_order() {
    // Newton converged far below the discretisation error (rtol 1e-12 sets its stopping test).
    let base = OdeOptions {
        rtol: 1e-12,
        atol: 1e-14,
        ..OdeOptions::default()
    };
    assert_order(Method::BackwardEuler, base, &halvings(80), 1.0);
}

#[test]
fn radau5_fixed_step_is_fifth_order() {
    let base = OdeOptions {
        rtol: 1e-13,
        atol: 1e-15,
        ..OdeOptions::default()
    };
    assert_order(Method::Radau5, base, &halvings(2), 5.0);
}

#[test]
fn bdf_fixed_order_k_has_order_k() {
    let base = OdeOptions {
        rtol: 1e-13,
        atol: 1e-15,
        ..OdeOptions::default()
    };
    let starts = [160, 80, 40, 40, 40];
    for k in 1..=5 {
        assert_order(
            Method::Bdf,
            OdeOptions {
                order: Some(k),
                ..base
            },
            &halvings(starts[k - 1]),
            k as f64,
        );
    }
}

#[test]
fn adams_pece_order_k_has_order_k() {
    let starts = [160, 40, 40, 40];
    for k in 1..=4 {
        assert_order(
            Method::Adams,
            OdeOptions {
                order: Some(k),
                ..OdeOptions::default()
            },
            &halvings(starts[k - 1]),
            k as f64,
        );
    }
}
