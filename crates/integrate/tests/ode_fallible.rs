//! Fallible right-hand sides: a caller's error stops every ODE method and arrives unchanged
//! (same type, same content, same object) in `IntegrateError::Callback`; before the failure
//! the solution is the exact one of y' = 1 (y = t, integrated exactly by every method).

use faer::MatMut;
use integrate::ode::{FallibleRhs, Method, OdeOptions, OdeStepper, OdeSystem};
use integrate::{CallbackError, IntegrateError};

#[derive(Debug, PartialEq, thiserror::Error)]
#[error("contact solver failed at gap {gap}")]
struct ContactFailed {
    gap: f64,
}

const T_FAIL: f64 = 0.35;

#[allow(clippy::type_complexity)] // the closure type is the point of the test
fn failing_rhs() -> FallibleRhs<impl FnMut(f64, &[f64], &mut [f64]) -> Result<(), ContactFailed>> {
    FallibleRhs::new(1, |t: f64, _y: &[f64], dydt: &mut [f64]| {
        if t > T_FAIL {
            return Err(ContactFailed { gap: -1.25e-3 });
        }
        dydt[0] = 1.0;
        Ok(())
    })
}

fn run_until_error(stepper: &mut dyn OdeStepper, sys: &mut dyn OdeSystem) -> IntegrateError {
    stepper.set_state(sys, 0.0, &[0.0]).unwrap();
    stepper.set_stop_time(Some(1.0));
    for _ in 0..100_000 {
        let before = (stepper.t(), stepper.y()[0]);
        match stepper.step(sys) {
            Ok(()) => {
                assert!(stepper.t() <= T_FAIL + 0.2);
                assert!((stepper.y()[0] - stepper.t()).abs() < 1e-12, "{before:?}");
            }
            Err(e) => return e,
        }
    }
    panic!("{}: no error", stepper.name());
}

#[test]
fn every_method_returns_the_callers_error_unchanged() {
    for method in Method::ALL {
        for options in [OdeOptions::fixed(0.1), OdeOptions::adaptive(1e-6, 1e-9)] {
            let Ok(mut stepper) = method.build(1, &options) else {
                continue; // fixed-step-only methods with adaptive options
            };
            let mut sys = failing_rhs();
            let err = run_until_error(stepper.as_mut(), &mut sys);
            assert_eq!(
                err.callback_error::<ContactFailed>(),
                Some(&ContactFailed { gap: -1.25e-3 }),
                "{}: {err}",
                method.name()
            );
            let IntegrateError::Callback { t, .. } = err else {
                unreachable!()
            };
            assert!(t > T_FAIL, "{}: error reported at t = {t}", method.name());
            assert!(
                err.to_string()
                    .contains("contact solver failed at gap -0.00125"),
                "{err}"
            );
        }
    }
}

/// A system whose analytic Jacobian fails (the implicit methods call it; the error object
/// must be the very one returned).
struct FailingJacobian {
    error: CallbackError,
}

impl OdeSystem for FailingJacobian {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = -y[0];
    }
    fn try_jacobian(
        &mut self,
        _t: f64,
        _y: &[f64],
        _jac: MatMut<'_, f64>,
    ) -> Result<bool, CallbackError> {
        Err(self.error.clone())
    }
}

#[test]
fn implicit_methods_return_a_jacobian_error_unchanged() {
    for method in [Method::Radau5, Method::Bdf, Method::BackwardEuler] {
        let mut stepper = method.build(1, &OdeOptions::fixed(0.1)).unwrap();
        let error = CallbackError::new(ContactFailed { gap: 2.0 });
        let mut sys = FailingJacobian {
            error: error.clone(),
        };
        // BDF evaluates the Jacobian when it starts, the others in the first step.
        let err = stepper
            .set_state(&mut sys, 0.0, &[1.0])
            .and_then(|()| stepper.step(&mut sys))
            .unwrap_err();
        match err {
            IntegrateError::Callback { error: got, .. } => assert_eq!(got, error),
            other => panic!("{}: {other:?}", method.name()),
        }
    }
}

#[test]
fn infallible_systems_are_unchanged() {
    // The default `try_rhs` forwards to `rhs`: y' = −y with Radau5 still reaches e^{−1}.
    struct Decay;
    impl OdeSystem for Decay {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
            dydt[0] = -y[0];
        }
    }
    let mut stepper = Method::Radau5
        .build(1, &OdeOptions::adaptive(1e-10, 1e-12))
        .unwrap();
    stepper.set_state(&mut Decay, 0.0, &[1.0]).unwrap();
    stepper.set_stop_time(Some(1.0));
    while stepper.t() < 1.0 {
        stepper.step(&mut Decay).unwrap();
    }
    assert!((stepper.y()[0] - (-1.0f64).exp()).abs() < 1e-9);
}
