//! Structural problems integrated by the first-order methods through `FirstOrderForm`.

use faer::{Mat, MatMut, MatRef};
use integrate::ode::{Method, OdeOptions, OdeSystem, finite_difference_jacobian};
use integrate::structural::{FirstOrderForm, LinearStructure, StructuralSystem};

const ZETA: f64 = 0.1;

/// u'' + 2ζu' + u = 0, u(0) = 1, u'(0) = 0:
/// u = e^{−ζt}(cos ω_d t + ζ/ω_d sin ω_d t), u' = −e^{−ζt}(1/ω_d) sin ω_d t, ω_d = √(1 − ζ²).
fn exact(t: f64) -> [f64; 2] {
    let wd = (1.0 - ZETA * ZETA).sqrt();
    let decay = (-ZETA * t).exp();
    [
        decay * ((wd * t).cos() + ZETA / wd * (wd * t).sin()),
        -decay * (wd * t).sin() / wd,
    ]
}

fn damped_oscillator() -> LinearStructure<fn(f64, &mut [f64])> {
    fn no_load(_: f64, f: &mut [f64]) {
        f.fill(0.0);
    }
    LinearStructure::new(
        Mat::from_fn(1, 1, |_, _| 2.0),
        Some(Mat::from_fn(1, 1, |_, _| 4.0 * ZETA)),
        Mat::from_fn(1, 1, |_, _| 2.0),
        no_load as fn(f64, &mut [f64]),
    )
    .unwrap()
}

/// Integrates to t = 10 and returns the error max(|q − u|, |v − u'|).
fn error_at_ten(method: Method, options: OdeOptions) -> f64 {
    let mut sys = FirstOrderForm::new(damped_oscillator()).unwrap();
    let mut stepper = method.build(sys.dim(), &options).unwrap();
    stepper.set_state(&mut sys, 0.0, &[1.0, 0.0]).unwrap();
    stepper.set_stop_time(Some(10.0));
    while stepper.t() < 10.0 {
        stepper.step(&mut sys).unwrap();
    }
    let e = exact(stepper.t());
    (stepper.y()[0] - e[0])
        .abs()
        .max((stepper.y()[1] - e[1]).abs())
}

#[test]
fn rk4_through_the_adapter_is_fourth_order() {
    let (e1, e2) = (
        error_at_ten(Method::Rk4, OdeOptions::fixed(0.1)),
        error_at_ten(Method::Rk4, OdeOptions::fixed(0.05)),
    );
    let p = (e1 / e2).log2();
    println!("RK4 on the damped oscillator: {e1:e} → {e2:e}, order {p:.3}");
    // Classic RK4 is fourth order: ±0.2.
    assert!((p - 4.0).abs() < 0.2, "order {p}");
}

#[test]
fn radau5_through_the_adapter_meets_its_tolerance() {
    let e = error_at_ten(Method::Radau5, OdeOptions::adaptive(1e-10, 1e-12));
    println!("Radau5 (rtol 1e-10) on the damped oscillator: error {e:e}");
    // Global error of a tolerance-controlled run: within two orders of rtol.
    assert!(e < 1e-8, "error {e:e}");
}

/// Two masses joined by a cubic spring, one tied to the ground: f_int = (k q0 + s(q0 − q1)³,
/// −s(q0 − q1)³), with a full damping matrix.
struct CubicPair {
    mass: Mat<f64>,
    damping: Mat<f64>,
}

impl StructuralSystem for CubicPair {
    fn dimension(&self) -> usize {
        2
    }
    fn mass_matrix(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }
    fn damping_matrix(&self) -> Option<MatRef<'_, f64>> {
        Some(self.damping.as_ref())
    }
    fn internal_force(&mut self, q: &[f64], f: &mut [f64]) {
        let spring = 5.0 * (q[0] - q[1]).powi(3);
        f[0] = 3.0 * q[0] + spring;
        f[1] = -spring;
    }
    fn tangent_stiffness(&mut self, q: &[f64], mut k: MatMut<'_, f64>) -> bool {
        let ks = 15.0 * (q[0] - q[1]).powi(2);
        k[(0, 0)] = 3.0 + ks;
        k[(0, 1)] = -ks;
        k[(1, 0)] = -ks;
        k[(1, 1)] = ks;
        true
    }
    fn external_force(&mut self, t: f64, f: &mut [f64]) {
        f[0] = t.cos();
        f[1] = 0.0;
    }
}

#[test]
fn analytic_jacobian_matches_finite_differences() {
    let mut sys = FirstOrderForm::new(CubicPair {
        mass: Mat::from_fn(2, 2, |i, j| [[2.0, 0.5], [0.5, 1.0]][i][j]),
        damping: Mat::from_fn(2, 2, |i, j| [[0.3, -0.1], [-0.1, 0.2]][i][j]),
    })
    .unwrap();
    let y = [0.4, -0.3, 0.7, 0.2];
    let mut analytic = Mat::zeros(4, 4);
    assert!(sys.jacobian(0.3, &y, analytic.as_mut()));
    let mut f0 = [0.0; 4];
    sys.rhs(0.3, &y, &mut f0);
    let (mut y_work, mut f_work) = ([0.0; 4], [0.0; 4]);
    let mut numeric = Mat::zeros(4, 4);
    finite_difference_jacobian(
        &mut sys,
        0.3,
        &y,
        &f0,
        &mut y_work,
        &mut f_work,
        numeric.as_mut(),
    );
    // Forward differences with step ~√ε·|y|: error ~1e-7 relative to the O(10) entries.
    for i in 0..4 {
        for j in 0..4 {
            assert!(
                (analytic[(i, j)] - numeric[(i, j)]).abs() < 1e-6 * (1.0 + analytic[(i, j)].abs()),
                "J[{i},{j}] analytic {} vs FD {}",
                analytic[(i, j)],
                numeric[(i, j)]
            );
        }
    }
    // Structure: ∂q'/∂v = I.
    assert_eq!(
        (analytic[(0, 2)], analytic[(1, 3)], analytic[(0, 3)]),
        (1.0, 1.0, 0.0)
    );
}
