//! Adaptive methods: the global error follows the tolerance, and the error-vs-work slope
//! (log error against log number of steps) equals −p for a method of order p.

mod ode_support;

use integrate::ode::{Method, OdeOptions};
use ode_support::{Oscillator, run_to};

const T_END: f64 = 10.0;

/// (steps, max-norm error at T_END) for the oscillator at the given tolerance.
fn work_and_error(method: Method, order: Option<usize>, tol: f64) -> (usize, f64) {
    let opts = OdeOptions {
        order,
        ..OdeOptions::adaptive(tol, tol)
    };
    let mut s = method.build(2, &opts).unwrap();
    let y = run_to(s.as_mut(), &mut Oscillator, 0.0, &[1.0, 0.0], T_END);
    let err = (y[0] - T_END.cos()).abs().max((y[1] + T_END.sin()).abs());
    (s.stats().steps, err)
}

/// Least-squares slope of log(error) against log(steps).
fn slope(points: &[(usize, f64)]) -> f64 {
    let xs: Vec<f64> = points.iter().map(|p| (p.0 as f64).ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    let n = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

fn assert_slope(method: Method, order: Option<usize>, tols: &[f64], expected: f64) {
    let points: Vec<(usize, f64)> = tols
        .iter()
        .map(|&tol| work_and_error(method, order, tol))
        .collect();
    let p = -slope(&points);
    eprintln!(
        "{} {order:?}: (steps, error) {points:?}, order {p:.3}",
        method.name()
    );
    // Band ±0.35: the controller's step sequence changes non-smoothly with the tolerance, so
    // the error constant fluctuates between runs (measured deviations 0.01–0.33).
    assert!(
        (p - expected).abs() <= 0.35,
        "{} {order:?}: observed order {p:.3}, expected {expected}",
        method.name()
    );
}

const TIGHT: [f64; 6] = [1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];

/// Variable-step Adams PECE of order k: error ∝ steps^{−k} (measured 0.99, 2.02, 3.05, 4.13).
#[test]
fn variable_step_adams_has_order_k() {
    assert_slope(Method::Adams, Some(1), &[1e-4, 1e-5, 1e-6, 1e-7, 1e-8], 1.0);
    assert_slope(
        Method::Adams,
        Some(2),
        &[1e-6, 1e-7, 1e-8, 1e-9, 1e-10],
        2.0,
    );
    assert_slope(Method::Adams, Some(3), &TIGHT, 3.0);
    assert_slope(Method::Adams, Some(4), &TIGHT, 4.0);
}

/// Adaptive DOPRI5 and Radau5 (order 5) and BDF with maximum order 5 (measured 5.11, 5.20,
/// 5.33).
#[test]
fn adaptive_high_order_methods_have_order_five() {
    assert_slope(Method::Dopri5, None, &TIGHT, 5.0);
    assert_slope(Method::Radau5, None, &TIGHT, 5.0);
    assert_slope(Method::Bdf, None, &TIGHT, 5.0);
}

/// Error at `t_end` of a fixed-step order-4 multistep run with h = 0.01.
fn fixed_step_error(method: Method, t_end: f64) -> f64 {
    let opts = OdeOptions {
        order: Some(4),
        rtol: 1e-12,
        atol: 1e-14,
        ..OdeOptions::fixed(0.01)
    };
    let mut s = method.build(2, &opts).unwrap();
    let y = run_to(s.as_mut(), &mut Oscillator, 0.0, &[1.0, 0.0], t_end);
    (y[0] - t_end.cos()).abs().max((y[1] + t_end.sin()).abs())
}

/// A stop time off the grid shortens the last step of a fixed-step multistep method; the
/// history is re-sampled for it, so the error at T = 1.005 stays at the level of the
/// neighbouring grid points T = 1.00 and 1.01 (bound: twice the larger; a shortened step with
/// the unscaled constant-step formula errs by O(h²) ≈ 1e-5 instead).
#[test]
fn multistep_methods_land_on_an_off_grid_stop_time() {
    for method in [Method::Adams, Method::Bdf] {
        let off_grid = fixed_step_error(method, 1.005);
        let on_grid = fixed_step_error(method, 1.0).max(fixed_step_error(method, 1.01));
        eprintln!(
            "{}: error off grid {off_grid:.2e}, on grid {on_grid:.2e}",
            method.name()
        );
        assert!(
            off_grid <= 2.0 * on_grid,
            "{}: {off_grid:e} vs {on_grid:e}",
            method.name()
        );
    }
}
