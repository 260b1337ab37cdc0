//! Test problems with exact or published reference solutions, shared by the `ode_*` tests.
#![allow(dead_code)]

use faer::MatMut;
use integrate::ode::{OdeStepper, OdeSystem};

/// Harmonic oscillator `q' = p, p' = −q` (y'' = −y as a first-order system);
/// exact solution from (1, 0): `(cos t, −sin t)`.
pub struct Oscillator;

impl OdeSystem for Oscillator {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[1];
        dydt[1] = -y[0];
    }
    fn jacobian(&mut self, _t: f64, _y: &[f64], mut jac: MatMut<'_, f64>) -> bool {
        jac[(0, 0)] = 0.0;
        jac[(0, 1)] = 1.0;
        jac[(1, 0)] = -1.0;
        jac[(1, 1)] = 0.0;
        true
    }
}

/// Linear decay `y' = −λ y`, exact `y0 e^{−λt}`.
pub struct Decay {
    pub lambda: f64,
}

impl OdeSystem for Decay {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = -self.lambda * y[0];
    }
}

/// Van der Pol in Hairer's scaled form `y1' = y2, y2' = ((1 − y1²) y2 − y1)/ε`
/// (references.md §D3.1); with ε = 1e-6 on [0, 2] it is the test set's VDPOL (μ = 1000 on
/// [0, 2000]) with y2 scaled by μ. Finite-difference Jacobian (none given).
pub struct VanDerPol {
    pub eps: f64,
}

impl OdeSystem for VanDerPol {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[1];
        dydt[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.eps;
    }
}

/// Van der Pol with its analytic Jacobian (as in Hairer's driver `dr1_radau5.f`).
pub struct VanDerPolJac {
    pub eps: f64,
}

impl OdeSystem for VanDerPolJac {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[1];
        dydt[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.eps;
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) -> bool {
        jac[(0, 0)] = 0.0;
        jac[(0, 1)] = 1.0;
        jac[(1, 0)] = (-2.0 * y[0] * y[1] - 1.0) / self.eps;
        jac[(1, 1)] = (1.0 - y[0] * y[0]) / self.eps;
        true
    }
}

/// Robertson's chemical kinetics (ROBER of the Bari test set, references.md §D3.1).
pub struct Robertson;

impl OdeSystem for Robertson {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        let r1 = 0.04 * y[0];
        let r2 = 1e4 * y[1] * y[2];
        let r3 = 3e7 * y[1] * y[1];
        dydt[0] = -r1 + r2;
        dydt[1] = r1 - r2 - r3;
        dydt[2] = r3;
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) -> bool {
        jac[(0, 0)] = -0.04;
        jac[(0, 1)] = 1e4 * y[2];
        jac[(0, 2)] = 1e4 * y[1];
        jac[(1, 0)] = 0.04;
        jac[(1, 1)] = -1e4 * y[2] - 6e7 * y[1];
        jac[(1, 2)] = -1e4 * y[1];
        jac[(2, 0)] = 0.0;
        jac[(2, 1)] = 6e7 * y[1];
        jac[(2, 2)] = 0.0;
        true
    }
}

/// HIRES (8 equations, Schäfer 1975; Bari test set definition), finite-difference Jacobian.
pub struct Hires;

impl OdeSystem for Hires {
    fn dim(&self) -> usize {
        8
    }
    fn rhs(&mut self, _t: f64, y: &[f64], f: &mut [f64]) {
        f[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
        f[1] = 1.71 * y[0] - 8.75 * y[1];
        f[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
        f[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
        f[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
        f[5] = -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
        f[6] = 280.0 * y[5] * y[7] - 1.81 * y[6];
        f[7] = -f[6];
    }
}

/// OREGO, the Oregonator (Field–Noyes; Bari test set definition, references.md §D3.1).
pub struct Oregonator;

impl OdeSystem for Oregonator {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&mut self, _t: f64, y: &[f64], f: &mut [f64]) {
        f[0] = 77.27 * (y[1] + y[0] * (1.0 - 8.375e-6 * y[0] - y[1]));
        f[1] = (y[2] - (1.0 + y[0]) * y[1]) / 77.27;
        f[2] = 0.161 * (y[0] - y[2]);
    }
}

/// Run a stepper from (t0, y0) to exactly t_end; returns the final state.
pub fn run_to(
    stepper: &mut dyn OdeStepper,
    sys: &mut dyn OdeSystem,
    t0: f64,
    y0: &[f64],
    t_end: f64,
) -> Vec<f64> {
    stepper.set_state(sys, t0, y0).expect("valid initial state");
    stepper.set_stop_time(Some(t_end));
    while stepper.t() < t_end {
        stepper.step(sys).expect("step succeeds");
    }
    assert_eq!(stepper.t(), t_end, "the last step lands on the stop time");
    stepper.y().to_vec()
}

/// Observed order log2(e(h)/e(h/2)) for consecutive entries of `errors` (step halved each time).
pub fn observed_orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}
