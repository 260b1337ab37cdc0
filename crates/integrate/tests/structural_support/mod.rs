//! Shared helpers of the structural integrator tests.
#![allow(dead_code)]

use faer::Mat;
use integrate::structural::{
    LinearStructure, StructuralMethod, StructuralStepper, StructuralSystem,
};

/// Undamped oscillator `u'' + ω² u = 0` (m = 1, k = ω²), no load.
pub fn oscillator(omega: f64) -> LinearStructure<fn(f64, &mut [f64])> {
    fn no_load(_t: f64, f: &mut [f64]) {
        f.fill(0.0);
    }
    LinearStructure::new(
        Mat::from_fn(1, 1, |_, _| 1.0),
        None,
        Mat::from_fn(1, 1, |_, _| omega * omega),
        no_load as fn(f64, &mut [f64]),
    )
    .expect("valid oscillator")
}

/// Steps `n` times with a fixed step `dt` and returns the stepper.
pub fn run<P: StructuralSystem>(
    method: StructuralMethod,
    problem: &mut P,
    q0: &[f64],
    v0: &[f64],
    dt: f64,
    n: usize,
) -> StructuralStepper {
    let mut stepper = StructuralStepper::new(method, problem, 0.0, q0, v0).expect("valid set-up");
    for _ in 0..n {
        stepper.step(problem, dt).expect("step");
    }
    stepper
}

/// Error at t = 10 of u'' + u = 0, u(0) = 1, u'(0) = 0 (exact u = cos t):
/// max(|q − cos t|, |v + sin t|).
pub fn oscillator_error(method: StructuralMethod, dt: f64) -> f64 {
    let n = (10.0 / dt).round() as usize;
    let s = run(method, &mut oscillator(1.0), &[1.0], &[0.0], dt, n);
    let t = s.t();
    (s.q()[0] - t.cos()).abs().max((s.v()[0] + t.sin()).abs())
}

/// Observed order `log2(e(Δt)/e(Δt/2))`.
pub fn observed_order(coarse: f64, fine: f64) -> f64 {
    (coarse / fine).log2()
}

/// Bisection for a sign change of `g` on `[a, b]` (g(a)·g(b) ≤ 0), to 1e-15 relative.
pub fn bisect(mut a: f64, mut b: f64, mut g: impl FnMut(f64) -> f64) -> f64 {
    let mut ga = g(a);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (b - a) <= 1e-15 * m.abs().max(1e-300) {
            break;
        }
        let gm = g(m);
        if (gm <= 0.0) == (ga <= 0.0) {
            a = m;
            ga = gm;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}
