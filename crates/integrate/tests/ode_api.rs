//! The step-wise API: statistics counted per method, selection by name, parameter validation,
//! restart between steps, dense output (order measured by halving) and output collection.

mod ode_support;

use integrate::IntegrateError;
use integrate::ode::{Method, OdeOptions, OdeStepper, Output, solve};
use ode_support::{Decay, Oscillator, observed_orders};

fn fixed(h: f64) -> OdeOptions {
    OdeOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..OdeOptions::fixed(h)
    }
}

/// Options that make every method usable: fixed step for the fixed-step ones.
fn options_for(method: Method) -> OdeOptions {
    match method {
        Method::Euler | Method::Rk4 | Method::BackwardEuler | Method::Adams => fixed(1e-3),
        _ => OdeOptions::adaptive(1e-9, 1e-12),
    }
}

/// A method, its options and the expected evaluation count after `n` steps.
type CountCase = (Method, OdeOptions, fn(usize) -> usize);

fn steps(stepper: &mut dyn OdeStepper, sys: &mut dyn integrate::ode::OdeSystem, n: usize) {
    for _ in 0..n {
        stepper.step(sys).unwrap();
    }
}

/// Exact evaluation counts of the explicit methods: each derivative at a new point is computed
/// once and reused (FSAL), plus one in `set_state`.
#[test]
fn explicit_methods_count_their_evaluations() {
    let n = 25;
    let cases: [CountCase; 4] = [
        (Method::Euler, fixed(0.01), |s| s + 1),
        (Method::Rk4, fixed(0.01), |s| 4 * s + 1),
        (Method::Dopri5, fixed(0.01), |s| 6 * s + 1),
        // Adams order 4: 3 RK4 starting steps (4 evaluations each), then 2 per PECE step.
        (Method::Adams, fixed(0.01), |s| 1 + 4 * 3 + 2 * (s - 3)),
    ];
    for (method, opts, expected) in cases {
        let mut s = method.build(2, &opts).unwrap();
        s.set_state(&mut Oscillator, 0.0, &[1.0, 0.0]).unwrap();
        steps(s.as_mut(), &mut Oscillator, n);
        let st = s.stats();
        assert_eq!(st.steps, n);
        assert_eq!(st.f_evals, expected(n), "{}", method.name());
        assert_eq!(
            (
                st.jacobian_evals,
                st.lu_decompositions,
                st.newton_iterations
            ),
            (0, 0, 0)
        );
    }
    // Adaptive DOPRI5: 6 per attempted step, plus set_state and the starting-step estimate.
    let mut s = Method::Dopri5
        .build(1, &OdeOptions::adaptive(1e-8, 1e-10))
        .unwrap();
    s.set_state(&mut Decay { lambda: 50.0 }, 0.0, &[1.0])
        .unwrap();
    steps(s.as_mut(), &mut Decay { lambda: 50.0 }, n);
    let st = s.stats();
    assert_eq!(st.f_evals, 6 * (st.steps + st.rejected_steps) + 2);
}

/// Implicit methods: backward Euler factorises once per step (Jacobian at the step start) and
/// spends one evaluation per Newton iteration plus one at the new point; BDF in fixed-step mode
/// spends one per Newton iteration after its RK4 start; Radau5 three per Newton iteration.
#[test]
fn implicit_methods_count_their_work() {
    let n = 30;
    let mut be = Method::BackwardEuler.build(2, &fixed(0.01)).unwrap();
    be.set_state(&mut Oscillator, 0.0, &[1.0, 0.0]).unwrap();
    steps(be.as_mut(), &mut Oscillator, n);
    let st = be.stats();
    assert_eq!(
        (st.steps, st.jacobian_evals, st.lu_decompositions),
        (n, n, n)
    );
    assert_eq!(st.f_evals, 1 + st.newton_iterations + n);
    assert!(st.newton_iterations >= n);

    let k = 3;
    let mut bdf = Method::Bdf
        .build(
            2,
            &OdeOptions {
                order: Some(k),
                ..fixed(0.01)
            },
        )
        .unwrap();
    bdf.set_state(&mut Oscillator, 0.0, &[1.0, 0.0]).unwrap();
    steps(bdf.as_mut(), &mut Oscillator, n);
    let st = bdf.stats();
    // set_state: f(t0) and the evaluation at the Jacobian point; k starting steps of 4 RK4 sub-steps.
    assert_eq!(st.f_evals, 2 + 16 * k + st.newton_iterations);
    assert_eq!(
        st.jacobian_evals, 1,
        "linear problem: the first Jacobian is never refreshed"
    );
    assert_eq!(st.steps, n);

    let mut radau = Method::Radau5
        .build(2, &OdeOptions::adaptive(1e-8, 1e-10))
        .unwrap();
    radau.set_state(&mut Oscillator, 0.0, &[1.0, 0.0]).unwrap();
    steps(radau.as_mut(), &mut Oscillator, n);
    let st = radau.stats();
    // 3 per Newton iteration, 1 per accepted step (f at the new point), 1 in set_state, and
    // RADAU5's extra filtered error estimate (at most one per rejected or first step).
    let base = 3 * st.newton_iterations + st.steps + 1;
    assert!(
        st.f_evals >= base && st.f_evals <= base + st.rejected_steps + 1,
        "{st:?}"
    );
    assert_eq!(
        st.lu_decompositions % 2,
        0,
        "real and complex factorisations come in pairs"
    );
}

#[test]
fn methods_are_selected_by_name() {
    for method in Method::ALL {
        assert_eq!(Method::from_name(method.name()).unwrap(), method);
        let stepper = method.build(1, &options_for(method)).unwrap();
        assert_eq!(stepper.name(), method.name());
    }
    assert_eq!(
        Method::from_name("Backward-Euler").unwrap(),
        Method::BackwardEuler
    );
    assert!(matches!(
        Method::from_name("rk45"),
        Err(IntegrateError::InvalidParameter { name: "method", .. })
    ));
}

#[test]
fn invalid_parameters_are_rejected_with_their_name() {
    let name_of = |r: Result<Box<dyn OdeStepper>, IntegrateError>| match r {
        Err(IntegrateError::InvalidParameter { name, .. }) => name,
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("accepted invalid options"),
    };
    let nan_rtol = OdeOptions {
        rtol: f64::NAN,
        ..OdeOptions::default()
    };
    assert_eq!(name_of(Method::Radau5.build(2, &nan_rtol)), "rtol");
    assert_eq!(
        name_of(Method::Dopri5.build(
            2,
            &OdeOptions {
                atol: -1.0,
                ..OdeOptions::default()
            }
        )),
        "atol"
    );
    assert_eq!(
        name_of(Method::Rk4.build(2, &OdeOptions::fixed(-0.1))),
        "fixed_step"
    );
    assert_eq!(
        name_of(Method::Euler.build(2, &OdeOptions::default())),
        "fixed_step"
    );
    assert_eq!(
        name_of(Method::Bdf.build(
            2,
            &OdeOptions {
                order: Some(6),
                ..OdeOptions::default()
            }
        )),
        "order"
    );
    assert_eq!(
        name_of(Method::Adams.build(
            2,
            &OdeOptions {
                order: Some(0),
                ..fixed(0.1)
            }
        )),
        "order"
    );
    assert_eq!(
        name_of(Method::Dopri5.build(
            2,
            &OdeOptions {
                max_step: 0.0,
                ..OdeOptions::default()
            }
        )),
        "max_step"
    );

    let mut s = Method::Rk4.build(2, &fixed(0.1)).unwrap();
    assert!(matches!(
        s.set_state(&mut Oscillator, 0.0, &[1.0]),
        Err(IntegrateError::DimensionMismatch {
            expected: 2,
            found: 1
        })
    ));
    assert!(matches!(
        s.set_state(&mut Oscillator, 0.0, &[f64::NAN, 0.0]),
        Err(IntegrateError::NonFinite { .. })
    ));
    s.set_state(&mut Oscillator, 0.0, &[1.0, 0.0]).unwrap();
    s.step(&mut Oscillator).unwrap();
    let mut out = [0.0; 2];
    assert!(matches!(
        s.interpolate(0.5, &mut out),
        Err(IntegrateError::OutsideLastStep { .. })
    ));
}

/// An outer loop changes the state between steps: integrate y' = −y to t = 1, restart at
/// (1, 2) and continue to t = 2; the result must be 2e^{−1} (the first leg forgotten).
/// Tolerance 2e-3 relative for the first-order methods (h = 1e-3), 1e-7 for the others.
#[test]
fn set_state_restarts_every_method() {
    for method in Method::ALL {
        let mut s = method.build(1, &options_for(method)).unwrap();
        let sys = &mut Decay { lambda: 1.0 };
        s.set_state(sys, 0.0, &[1.0]).unwrap();
        s.set_stop_time(Some(1.0));
        while s.t() < 1.0 {
            s.step(sys).unwrap();
        }
        s.set_state(sys, 1.0, &[2.0]).unwrap();
        s.set_stop_time(Some(2.0));
        while s.t() < 2.0 {
            s.step(sys).unwrap();
        }
        let exact = 2.0 * (-1.0f64).exp();
        let tol = if matches!(method, Method::Euler | Method::BackwardEuler) {
            2e-3
        } else {
            1e-7
        };
        let rel = (s.y()[0] / exact - 1.0).abs();
        assert!(rel < tol, "{}: relative error {rel:e}", method.name());
        assert_eq!(s.t(), 2.0);
    }
}

/// Error of the dense output at the middle of one step of size h taken from the exact state
/// of the oscillator at t = 0.3.
fn midpoint_error(method: Method, h: f64) -> f64 {
    let mut s = method.build(2, &fixed(h)).unwrap();
    let t0 = 0.3f64;
    s.set_state(&mut Oscillator, t0, &[t0.cos(), -t0.sin()])
        .unwrap();
    s.step(&mut Oscillator).unwrap();
    let tm = t0 + 0.5 * h;
    let mut out = [0.0; 2];
    s.interpolate(tm, &mut out).unwrap();
    (out[0] - tm.cos()).abs().max((out[1] + tm.sin()).abs())
}

/// Local order of the dense output, by halving h: the error of an order-q interpolant after
/// one step is O(h^{q+1}). DOPRI5's continuous extension is of order 4 (error h⁵), the Radau5
/// collocation polynomial of order 3 = stage order (h⁴), the cubic Hermite of RK4 of order 3
/// (h⁴). Band ±0.3 (pre-asymptotic terms at the largest h).
#[test]
fn dense_output_has_its_local_order() {
    for (method, expected) in [
        (Method::Dopri5, 5.0),
        (Method::Radau5, 4.0),
        (Method::Rk4, 4.0),
    ] {
        let errs: Vec<f64> = [0.2, 0.1, 0.05, 0.025]
            .iter()
            .map(|&h| midpoint_error(method, h))
            .collect();
        let orders = observed_orders(&errs);
        eprintln!(
            "{} dense output: errors {errs:?}, orders {orders:?}",
            method.name()
        );
        for p in orders {
            assert!(
                (p - expected).abs() < 0.3,
                "{}: dense-output order {p}",
                method.name()
            );
        }
    }
}

/// `solve` with requested output times returns the dense-output states there (oscillator,
/// DOPRI5 at rtol 1e-10: error bound 1e-8 for the global error of a 10-unit run).
#[test]
fn solve_collects_requested_times() {
    let times: Vec<f64> = (0..=20).map(|i| 0.5 * i as f64).collect();
    let mut s = Method::Dopri5
        .build(2, &OdeOptions::adaptive(1e-10, 1e-12))
        .unwrap();
    let sol = solve(
        s.as_mut(),
        &mut Oscillator,
        (0.0, &[1.0, 0.0]),
        10.0,
        &mut [],
        &Output::Times(times.clone()),
    )
    .unwrap();
    assert_eq!(sol.t, times);
    for (t, y) in sol.t.iter().zip(&sol.y) {
        assert!(
            (y[0] - t.cos()).abs() < 1e-8 && (y[1] + t.sin()).abs() < 1e-8,
            "t = {t}: {y:?}"
        );
    }
    assert_eq!(sol.stats, s.stats());
    let mut s = Method::Rk4.build(2, &fixed(0.1)).unwrap();
    let sol = solve(
        s.as_mut(),
        &mut Oscillator,
        (0.0, &[1.0, 0.0]),
        1.0,
        &mut [],
        &Output::Steps,
    )
    .unwrap();
    assert_eq!(sol.t.len(), 11, "initial point and 10 steps");
    assert!((sol.t[10] - 1.0).abs() < 1e-15);
}

/// `set_max_step` caps every following step of every method, and removing the cap lets the
/// adaptive ones grow again (oscillator, rtol 1e-6: natural steps ≈ 0.1–0.5 ≫ cap 1e-3).
#[test]
fn step_cap_applies_to_every_method() {
    for method in Method::ALL {
        let opts = match method {
            Method::Euler | Method::Rk4 | Method::BackwardEuler => fixed(0.05),
            _ => OdeOptions::adaptive(1e-6, 1e-9),
        };
        let mut s = method.build(2, &opts).unwrap();
        s.set_state(&mut Oscillator, 0.0, &[1.0, 0.0]).unwrap();
        steps(s.as_mut(), &mut Oscillator, 20);
        s.set_max_step(1e-3);
        for _ in 0..20 {
            s.step(&mut Oscillator).unwrap();
            assert!(
                s.last_step_size() <= 1e-3 * (1.0 + 1e-12),
                "{}: {}",
                method.name(),
                s.last_step_size()
            );
        }
        s.set_max_step(f64::INFINITY);
        steps(s.as_mut(), &mut Oscillator, 40);
        assert!(
            s.last_step_size() > 1e-2,
            "{}: step stays at {}",
            method.name(),
            s.last_step_size()
        );
    }
}
