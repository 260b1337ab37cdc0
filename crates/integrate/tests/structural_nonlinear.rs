//! Nonlinear internal forces: Newton's method on the step equation, finite-difference tangents,
//! and an outside solver (Sherman–Morrison on diagonal-plus-rank-one, references.md §D4.2) that
//! uses only `step_equation` and `finish_step`.

mod structural_support;

use faer::{Mat, MatMut, MatRef};
use integrate::IntegrateError;
use integrate::structural::{NewtonOptions, StructuralMethod, StructuralStepper, StructuralSystem};
use structural_support::{bisect, observed_order};

/// Pure cubic oscillator u'' + u³ = 0 (m = 1, f_int = u³), with or without analytic tangent.
struct CubicOscillator {
    mass: Mat<f64>,
    analytic_tangent: bool,
}

impl CubicOscillator {
    fn new(analytic_tangent: bool) -> Self {
        Self {
            mass: Mat::from_fn(1, 1, |_, _| 1.0),
            analytic_tangent,
        }
    }
}

impl StructuralSystem for CubicOscillator {
    fn dimension(&self) -> usize {
        1
    }
    fn mass_matrix(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }
    fn internal_force(&mut self, q: &[f64], f: &mut [f64]) {
        f[0] = q[0].powi(3);
    }
    fn tangent_stiffness(&mut self, q: &[f64], mut k: MatMut<'_, f64>) -> bool {
        k[(0, 0)] = 3.0 * q[0] * q[0];
        self.analytic_tangent
    }
    fn external_force(&mut self, _t: f64, f: &mut [f64]) {
        f[0] = 0.0;
    }
}

/// Period of u'' + u³ = 0 with amplitude A: T = 4√2/A ∫₀¹ ds/√(1 − s⁴) = Γ(1/4)²/(A√π)
/// (energy ½u'² + ¼u⁴ = ¼A⁴; Abramowitz & Stegun 6.1 for Γ(1/4) = 3.625609908221908…).
fn cubic_period(amplitude: f64) -> f64 {
    let gamma_quarter = 3.625_609_908_221_908_f64;
    gamma_quarter * gamma_quarter / (amplitude * std::f64::consts::PI.sqrt())
}

/// Period from the zero crossings of q located with the dense output (event location): the
/// mean spacing of the crossings in t ∈ [0, 40], times two.
fn measured_period(method: StructuralMethod, dt: f64) -> f64 {
    let mut problem = CubicOscillator::new(true);
    let mut s = StructuralStepper::new(method, &mut problem, 0.0, &[1.0], &[0.0]).unwrap();
    let mut crossings = Vec::new();
    let mut q = [0.0];
    while s.t() < 40.0 {
        let before = s.q()[0];
        s.step(&mut problem, dt).unwrap();
        if before * s.q()[0] < 0.0 {
            let (t0, t1) = s.last_step_interval().unwrap();
            crossings.push(bisect(t0, t1, |t| {
                s.dense_output(t, &mut q).unwrap();
                q[0]
            }));
        }
    }
    2.0 * (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64
}

#[test]
fn newton_solves_cubic_oscillator_with_second_order_period() {
    let exact = cubic_period(1.0);
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::generalized_alpha(0.8).unwrap(),
        StructuralMethod::hht(-0.1).unwrap(),
    ] {
        let e1 = (measured_period(method, 0.02) - exact).abs();
        let e2 = (measured_period(method, 0.01) - exact).abs();
        let p = observed_order(e1, e2);
        println!("{method:?}: period error {e1:e} → {e2:e}, order {p:.4}");
        // The trapezoidal rule is second order (references.md §D3.5); the crossings come from
        // the cubic Hermite dense output (O(Δt⁴) interpolation), so the order is that of the
        // scheme: ±0.2.
        assert!((p - 2.0).abs() < 0.2, "{method:?}: order {p}");
        assert!(e2 < 1e-3 * exact, "{method:?}: period error {e2}");
    }
}

#[test]
fn finite_difference_tangent_gives_the_same_trajectory() {
    // The tangent only steers Newton; the converged root is the same. Forward differences
    // have relative error ~√ε, so Newton still converges (linearly at rate ~1e-8) to the
    // tolerance 1e-10·|q|: trajectories agree to 1e-9.
    let method = StructuralMethod::generalized_alpha(0.5).unwrap();
    let mut exact_tangent = CubicOscillator::new(true);
    let mut fd_tangent = CubicOscillator::new(false);
    let mut a = StructuralStepper::new(method, &mut exact_tangent, 0.0, &[1.0], &[0.0]).unwrap();
    let mut b = StructuralStepper::new(method, &mut fd_tangent, 0.0, &[1.0], &[0.0]).unwrap();
    for _ in 0..500 {
        a.step(&mut exact_tangent, 0.05).unwrap();
        b.step(&mut fd_tangent, 0.05).unwrap();
        assert!(
            (a.q()[0] - b.q()[0]).abs() < 1e-9,
            "{} vs {}",
            a.q()[0],
            b.q()[0]
        );
    }
    // The finite-difference run evaluated f_int once more per tangent (n = 1).
    let (sa, sb) = (a.stats(), b.stats());
    assert_eq!(sb.f_evals - sa.f_evals, sb.jacobian_evals);
    println!("analytic: {sa:?}\nfinite differences: {sb:?}");
}

#[test]
fn newton_failure_is_a_typed_error_and_leaves_the_state() {
    let mut problem = CubicOscillator::new(true);
    let mut s = StructuralStepper::new(
        StructuralMethod::average_acceleration(),
        &mut problem,
        0.0,
        &[1.0],
        &[0.0],
    )
    .unwrap();
    s.set_newton_options(NewtonOptions {
        max_iterations: 1,
        ..NewtonOptions::default()
    })
    .unwrap();
    let err = s.step(&mut problem, 0.5).unwrap_err();
    match err {
        IntegrateError::NewtonFailed {
            t,
            iterations,
            residual,
        } => {
            assert_eq!(iterations, 1);
            assert!((t - 0.5).abs() < 1e-15 && residual > 0.0);
        }
        other => panic!("unexpected error {other:?}"),
    }
    assert_eq!((s.t(), s.q()[0], s.v()[0]), (0.0, 1.0, 0.0));
    assert!(
        s.set_newton_options(NewtonOptions {
            relative_tolerance: f64::NAN,
            ..NewtonOptions::default()
        })
        .is_err()
    );
}

/// Wheel (DOF 0) on one bridge mode (DOF 1) through a Hertz spring, the shape of the
/// vehicle–bridge problem: f_int(q) = K q + b F(bᵀq), b = (1, −1), F(δ) = k_H max(δ, 0)^{3/2},
/// M, C, K diagonal; gravity on the wheel and a harmonic load on the mode.
struct WheelOnMode {
    mass: Mat<f64>,
    damping: Mat<f64>,
    stiffness: [f64; 2],
    k_hertz: f64,
}

const B: [f64; 2] = [1.0, -1.0];

impl WheelOnMode {
    fn new() -> Self {
        Self {
            mass: Mat::from_fn(2, 2, |i, j| if i == j { [1.0, 2.0][i] } else { 0.0 }),
            damping: Mat::from_fn(2, 2, |i, j| if i == j { [0.0, 0.4][i] } else { 0.0 }),
            stiffness: [0.0, 200.0],
            k_hertz: 1e4,
        }
    }
    fn approach(q: &[f64]) -> f64 {
        B[0] * q[0] + B[1] * q[1]
    }
    fn contact_force(&self, delta: f64) -> f64 {
        self.k_hertz * delta.max(0.0).powf(1.5)
    }
    fn contact_stiffness(&self, delta: f64) -> f64 {
        1.5 * self.k_hertz * delta.max(0.0).sqrt()
    }
}

impl StructuralSystem for WheelOnMode {
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
        let force = self.contact_force(Self::approach(q));
        for i in 0..2 {
            f[i] = self.stiffness[i] * q[i] + B[i] * force;
        }
    }
    fn tangent_stiffness(&mut self, q: &[f64], mut k: MatMut<'_, f64>) -> bool {
        let kc = self.contact_stiffness(Self::approach(q));
        for i in 0..2 {
            for j in 0..2 {
                k[(i, j)] = kc * B[i] * B[j] + if i == j { self.stiffness[i] } else { 0.0 };
            }
        }
        true
    }
    fn external_force(&mut self, t: f64, f: &mut [f64]) {
        f[0] = 9.81;
        f[1] = 5.0 * (12.0 * t).sin();
    }
}

/// One step solved outside the stepper: Newton with the diagonal-plus-rank-one effective
/// matrix D + s·b bᵀ inverted by Sherman–Morrison, using only the numbers of the step
/// equation (references.md §D4.2): (D + s b bᵀ)⁻¹r = D⁻¹r − D⁻¹b · s(bᵀD⁻¹r)/(1 + s bᵀD⁻¹b).
fn outside_step(s: &mut StructuralStepper, p: &mut WheelOnMode, dt: f64) -> usize {
    let eq = s.step_equation(dt).unwrap();
    let mut f_ext = [0.0; 2];
    p.external_force(eq.t_force, &mut f_ext);
    let m = [p.mass[(0, 0)], p.mass[(1, 1)]];
    let c = [p.damping[(0, 0)], p.damping[(1, 1)]];
    // Same start as the built-in solver: a_{n+1} = a_n.
    let mut q: [f64; 2] =
        std::array::from_fn(|i| eq.q_pred[i] + eq.displacement_per_acceleration * s.a()[i]);
    let d: Vec<f64> = (0..2)
        .map(|i| {
            eq.mass_coefficient * m[i]
                + eq.damping_coefficient * c[i]
                + eq.stiffness_coefficient * p.stiffness[i]
        })
        .collect();
    for iteration in 1..=50 {
        // Residual R = (1−α_m) M a + (1−α_f)(C v + f_int) + h − f_ext.
        let delta = WheelOnMode::approach(&q);
        let force = p.contact_force(delta);
        let mut r = [0.0; 2];
        for i in 0..2 {
            let a = (q[i] - eq.q_pred[i]) / eq.displacement_per_acceleration;
            let v = eq.v_pred[i] + eq.velocity_per_acceleration * a;
            let f_int = p.stiffness[i] * q[i] + B[i] * force;
            r[i] = (1.0 - eq.alpha_m) * m[i] * a
                + (1.0 - eq.alpha_f) * (c[i] * v + f_int)
                + eq.history_force[i]
                - f_ext[i];
        }
        let rank_one = eq.stiffness_coefficient * p.contact_stiffness(delta);
        let dinv_r = [r[0] / d[0], r[1] / d[1]];
        let dinv_b = [B[0] / d[0], B[1] / d[1]];
        let bt_dinv_r = B[0] * dinv_r[0] + B[1] * dinv_r[1];
        let bt_dinv_b = B[0] * dinv_b[0] + B[1] * dinv_b[1];
        let factor = rank_one * bt_dinv_r / (1.0 + rank_one * bt_dinv_b);
        let mut step: f64 = 0.0;
        for i in 0..2 {
            let dq = dinv_r[i] - dinv_b[i] * factor;
            q[i] -= dq;
            step = step.max(dq.abs());
        }
        if step <= 1e-15 * (1.0 + q[0].abs().max(q[1].abs())) {
            s.finish_step(p, dt, &q).unwrap();
            return iteration;
        }
    }
    panic!("outside solver did not converge at t = {}", eq.t_new);
}

#[test]
fn outside_sherman_morrison_solver_reproduces_builtin_step() {
    // Both solve the same step equation to round-off, so they must agree to 1e-12 (the
    // states are O(0.1), the contact stiffness makes K_eff's condition number O(1e3)).
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::hht(-0.1).unwrap(),
        StructuralMethod::generalized_alpha(0.6).unwrap(),
        StructuralMethod::BackwardEuler,
    ] {
        let (mut p_in, mut p_out) = (WheelOnMode::new(), WheelOnMode::new());
        // The wheel touches the mode with a downward speed of 0.5: an impact, then rolling.
        let (q0, v0) = ([0.0, 0.0], [0.5, 0.0]);
        let mut builtin = StructuralStepper::new(method, &mut p_in, 0.0, &q0, &v0).unwrap();
        let mut outside = StructuralStepper::new(method, &mut p_out, 0.0, &q0, &v0).unwrap();
        let (mut max_diff, mut max_delta, mut iterations): (f64, f64, usize) = (0.0, 0.0, 0);
        for _ in 0..2000 {
            builtin.step(&mut p_in, 1e-3).unwrap();
            iterations += outside_step(&mut outside, &mut p_out, 1e-3);
            max_delta = max_delta.max(WheelOnMode::approach(builtin.q()));
            for i in 0..2 {
                max_diff = max_diff
                    .max((builtin.q()[i] - outside.q()[i]).abs())
                    .max((builtin.v()[i] - outside.v()[i]).abs());
            }
        }
        let stats = builtin.stats();
        println!(
            "{method:?}: max |Δ| = {max_diff:e}, max approach {max_delta:.4e}, Newton its {} (outside {iterations})",
            stats.newton_iterations
        );
        assert!(
            max_delta > 1e-3,
            "the contact must be active (approach {max_delta})"
        );
        assert!(
            max_diff < 1e-12,
            "{method:?}: trajectories differ by {max_diff:e}"
        );
        assert!((builtin.t() - outside.t()).abs() < 1e-15);
    }
}
