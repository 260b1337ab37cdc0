//! Method selection by name, parameter validation, the step-equation numbers, the dense
//! output and the statistics of the structural steppers.

mod structural_support;

use faer::Mat;
use integrate::IntegrateError;
use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper, sparse};
use structural_support::oscillator;

fn invalid_name(err: IntegrateError) -> &'static str {
    match err {
        IntegrateError::InvalidParameter { name, .. } => name,
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

/// Named parameters as a command line would pass them.
type NamedParameters = Vec<(&'static str, f64)>;

#[test]
fn methods_are_selected_by_name() {
    use StructuralMethod as M;
    let cases: Vec<(&str, NamedParameters, M)> = vec![
        (
            "newmark",
            vec![],
            M::Newmark {
                beta: 0.25,
                gamma: 0.5,
            },
        ),
        (
            "Newmark",
            vec![("beta", 0.3025), ("gamma", 0.6)],
            M::Newmark {
                beta: 0.3025,
                gamma: 0.6,
            },
        ),
        ("average-acceleration", vec![], M::average_acceleration()),
        (
            "linear_acceleration",
            vec![],
            M::Newmark {
                beta: 1.0 / 6.0,
                gamma: 0.5,
            },
        ),
        (
            "central_difference",
            vec![],
            M::Newmark {
                beta: 0.0,
                gamma: 0.5,
            },
        ),
        ("hht", vec![("alpha", -0.3)], M::Hht { alpha: -0.3 }),
        (
            "generalized_alpha",
            vec![("rho_inf", 0.5)],
            M::GeneralizedAlpha { rho_inf: 0.5 },
        ),
        ("verlet", vec![], M::StormerVerlet),
        ("leapfrog", vec![], M::Leapfrog),
        ("backward_euler", vec![], M::BackwardEuler),
    ];
    for (name, params, expected) in cases {
        let method = M::by_name(name, &params).unwrap();
        assert_eq!(method, expected, "{name}");
        // The short name selects the same method again.
        assert_eq!(
            M::by_name(method.name(), &params).unwrap().name(),
            method.name()
        );
    }
    assert_eq!(invalid_name(M::by_name("rk4", &[]).unwrap_err()), "method");
    assert_eq!(
        invalid_name(M::by_name("hht", &[("rho_inf", 0.5)]).unwrap_err()),
        "parameter"
    );
    assert!(M::StormerVerlet.is_explicit() && M::central_difference().is_explicit());
    assert!(!M::average_acceleration().is_explicit() && !M::BackwardEuler.is_explicit());
}

#[test]
fn parameters_out_of_range_are_rejected_with_their_name() {
    use StructuralMethod as M;
    assert_eq!(invalid_name(M::hht(0.1).unwrap_err()), "alpha");
    assert_eq!(invalid_name(M::hht(-0.34).unwrap_err()), "alpha");
    assert_eq!(invalid_name(M::hht(f64::NAN).unwrap_err()), "alpha");
    assert!(M::hht(-1.0 / 3.0).is_ok() && M::hht(0.0).is_ok());
    assert_eq!(
        invalid_name(M::generalized_alpha(1.01).unwrap_err()),
        "rho_inf"
    );
    assert_eq!(
        invalid_name(M::generalized_alpha(-0.01).unwrap_err()),
        "rho_inf"
    );
    assert_eq!(invalid_name(M::newmark(-0.1, 0.5).unwrap_err()), "beta");
    assert_eq!(invalid_name(M::newmark(0.25, 0.4).unwrap_err()), "gamma");
    assert_eq!(
        invalid_name(M::newmark(0.25, f64::INFINITY).unwrap_err()),
        "gamma"
    );
    // A method built directly as an enum is validated by the stepper.
    let err = StructuralStepper::new(
        M::Hht { alpha: 0.5 },
        &mut oscillator(1.0),
        0.0,
        &[1.0],
        &[0.0],
    );
    assert_eq!(invalid_name(err.err().unwrap()), "alpha");
}

#[test]
fn bad_problems_and_states_are_rejected() {
    let load = |_: f64, f: &mut [f64]| f.fill(0.0);
    let one = || Mat::from_fn(1, 1, |_, _| 1.0);
    let negative_mass = LinearStructure::new(Mat::from_fn(1, 1, |_, _| -2.0), None, one(), load);
    assert_eq!(invalid_name(negative_mass.err().unwrap()), "mass");
    let nan_stiffness =
        LinearStructure::new(one(), None, Mat::from_fn(1, 1, |_, _| f64::NAN), load);
    assert_eq!(invalid_name(nan_stiffness.err().unwrap()), "stiffness");
    let wrong_damping = LinearStructure::new(one(), Some(Mat::zeros(2, 2)), one(), load);
    assert_eq!(invalid_name(wrong_damping.err().unwrap()), "damping");

    let method = StructuralMethod::average_acceleration();
    let mut p = oscillator(1.0);
    let nan_q = StructuralStepper::new(method, &mut p, 0.0, &[f64::NAN], &[0.0]);
    assert_eq!(invalid_name(nan_q.err().unwrap()), "q0");
    let short_v = StructuralStepper::new(method, &mut p, 0.0, &[1.0], &[]);
    assert_eq!(invalid_name(short_v.err().unwrap()), "v0");
    let mut s = StructuralStepper::new(method, &mut p, 0.0, &[1.0], &[0.0]).unwrap();
    for dt in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        assert_eq!(invalid_name(s.step(&mut p, dt).unwrap_err()), "dt");
    }
    let mut singular_mass = LinearStructure::new(
        Mat::from_fn(2, 2, |_, _| 1.0),
        None,
        Mat::identity(2, 2),
        load,
    )
    .unwrap();
    let err = StructuralStepper::new(method, &mut singular_mass, 0.5, &[0.0; 2], &[0.0; 2]);
    assert_eq!(
        err.err().unwrap(),
        IntegrateError::SingularMatrix { t: 0.5 }
    );
    let mut two_dof =
        LinearStructure::new(Mat::identity(2, 2), None, Mat::identity(2, 2), load).unwrap();
    assert_eq!(
        invalid_name(s.step(&mut two_dof, 0.1).unwrap_err()),
        "problem"
    );
    let mut out = [0.0];
    assert_eq!(
        invalid_name(s.dense_output(0.0, &mut out).unwrap_err()),
        "t"
    );
    s.step(&mut p, 0.1).unwrap();
    assert_eq!(
        invalid_name(s.dense_output(0.2, &mut out).unwrap_err()),
        "t"
    );
    assert_eq!(
        invalid_name(s.finish_step(&mut p, 0.1, &[f64::NAN]).unwrap_err()),
        "q_new"
    );
    assert_eq!(s.t(), 0.1, "failed calls leave the state");

    let eq = s.step_equation(0.1).unwrap();
    let mut out = [0.0; 2];
    let err = eq.residual(s.mass(), None, &[0.0], &[0.0], &[0.0], &mut out);
    assert_eq!(invalid_name(err.unwrap_err()), "out");
    let (mut v, mut a) = ([0.0], [0.0; 3]);
    assert_eq!(
        invalid_name(eq.kinematics(&[0.0], &mut v, &mut a).unwrap_err()),
        "a_new"
    );

    let verlet =
        StructuralStepper::new(StructuralMethod::StormerVerlet, &mut p, 0.0, &[1.0], &[0.0])
            .unwrap();
    assert_eq!(
        invalid_name(verlet.step_equation(0.1).unwrap_err()),
        "method"
    );
}

#[test]
fn backward_euler_step_is_the_baseline_linear_system() {
    // references.md §D4.4 writes one backward-Euler step of a mode c'' = −ω²c as
    // [[1, −Δt], [Δt ω², 1]] (c, ċ)^{k+1} = (c, ċ)^k, solved here by Cramer's rule.
    let (omega, dt, q0, v0) = (3.0_f64, 0.07, 0.4, -1.1);
    let mut p = oscillator(omega);
    let mut s =
        StructuralStepper::new(StructuralMethod::BackwardEuler, &mut p, 0.0, &[q0], &[v0]).unwrap();
    let eq = s.step_equation(dt).unwrap();
    // Documented form: q̃ = q_n + Δt v_n, c_qa = Δt², ṽ = v_n, c_va = Δt, α_m = α_f = 0.
    assert_eq!(eq.q_pred, vec![q0 + dt * v0]);
    assert_eq!(eq.v_pred, vec![v0]);
    assert_eq!(
        (
            eq.displacement_per_acceleration,
            eq.velocity_per_acceleration
        ),
        (dt * dt, dt)
    );
    assert_eq!((eq.alpha_m, eq.alpha_f, eq.t_force), (0.0, 0.0, dt));
    s.step(&mut p, dt).unwrap();
    let det = 1.0 + dt * dt * omega * omega;
    let (q1, v1) = ((q0 + dt * v0) / det, (v0 - dt * omega * omega * q0) / det);
    // One LU solve of a 1×1 system: round-off.
    assert!(
        (s.q()[0] - q1).abs() < 1e-15 && (s.v()[0] - v1).abs() < 1e-14,
        "{:?} vs {q1}, {v1}",
        (s.q(), s.v())
    );
}

#[test]
fn generalized_alpha_step_equation_numbers() {
    // Chung & Hulbert (references.md §D3.5) at ρ∞ = 0.8: α_m = 0.6/1.8, α_f = 0.8/1.8,
    // γ = ½ − α_m + α_f, β = ¼(1 − α_m + α_f)².
    let rho: f64 = 0.8;
    let (am, af) = ((2.0 * rho - 1.0) / (rho + 1.0), rho / (rho + 1.0));
    let (gamma, beta) = (0.5 - am + af, 0.25 * (1.0 - am + af).powi(2));
    let mut p = oscillator(2.0);
    let (q0, v0, dt) = (0.5, 0.25, 0.1);
    let s = StructuralStepper::new(
        StructuralMethod::generalized_alpha(rho).unwrap(),
        &mut p,
        1.0,
        &[q0],
        &[v0],
    )
    .unwrap();
    let a0 = -4.0 * q0;
    let eq = s.step_equation(dt).unwrap();
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-14 * y.abs().max(1.0);
    assert!(close(eq.alpha_m, am) && close(eq.alpha_f, af));
    assert!(close(eq.t_force, 1.0 + dt - af * dt));
    assert!(close(
        eq.q_pred[0],
        q0 + dt * v0 + dt * dt * (0.5 - beta) * a0
    ));
    assert!(close(eq.v_pred[0], v0 + dt * (1.0 - gamma) * a0));
    assert!(close(eq.displacement_per_acceleration, beta * dt * dt));
    assert!(close(eq.velocity_per_acceleration, gamma * dt));
    // h = α_m M a_n + α_f (C v_n + f_int(q_n)) with M = 1, C = 0, f_int = 4q.
    assert!(close(eq.history_force[0], am * a0 + af * 4.0 * q0));
    assert!(close(eq.mass_coefficient, (1.0 - am) / (beta * dt * dt)));
    assert!(close(
        eq.damping_coefficient,
        (1.0 - af) * gamma / (beta * dt)
    ));
    assert!(close(eq.stiffness_coefficient, 1.0 - af));
}

#[test]
fn dense_output_is_exact_for_constant_acceleration() {
    // Under a constant load every Newmark-family scheme and Verlet reproduce the quadratic
    // q = q0 + v0 t + ½(F/m)t² exactly, and the cubic Hermite interpolant reproduces quadratics:
    // round-off agreement (1e-12 relative) inside the last step.
    let (m, force, q0, v0) = (2.0, 3.0, 0.1, -0.4);
    let exact = |t: f64| q0 + v0 * t + 0.5 * force / m * t * t;
    let exact_v = |t: f64| v0 + force / m * t;
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::linear_acceleration(),
        StructuralMethod::hht(-0.2).unwrap(),
        StructuralMethod::generalized_alpha(0.3).unwrap(),
        StructuralMethod::StormerVerlet,
        StructuralMethod::Leapfrog,
        StructuralMethod::central_difference(),
    ] {
        let mut p = LinearStructure::new(
            Mat::from_fn(1, 1, |_, _| m),
            None,
            Mat::zeros(1, 1),
            move |_, f: &mut [f64]| f.fill(force),
        )
        .unwrap();
        let mut s = StructuralStepper::new(method, &mut p, 0.0, &[q0], &[v0]).unwrap();
        for _ in 0..7 {
            s.step(&mut p, 0.3).unwrap();
        }
        let (t0, t1) = s.last_step_interval().unwrap();
        let t = t0 + 0.37 * (t1 - t0);
        let (mut q, mut v) = ([0.0], [0.0]);
        s.dense_output(t, &mut q).unwrap();
        s.dense_velocity(t, &mut v).unwrap();
        assert!(
            (q[0] - exact(t)).abs() < 1e-12 * exact(t).abs(),
            "{method:?}: q {} vs {}",
            q[0],
            exact(t)
        );
        assert!(
            (v[0] - exact_v(t)).abs() < 1e-12 * exact_v(t).abs(),
            "{method:?}: v {} vs {}",
            v[0],
            exact_v(t)
        );
    }
}

#[test]
fn linear_problems_factorise_once_per_step_size() {
    let mut p = oscillator(1.0);
    let mut s = StructuralStepper::new(
        StructuralMethod::average_acceleration(),
        &mut p,
        0.0,
        &[1.0],
        &[0.0],
    )
    .unwrap();
    for _ in 0..10 {
        s.step(&mut p, 0.1).unwrap();
    }
    let st = s.stats();
    // M at start-up plus K_eff once; one tangent; one Newton iteration (exact) and one f_int
    // evaluation per step, plus f_int(q0) at start-up.
    assert_eq!(
        (st.steps, st.lu_decompositions, st.jacobian_evals),
        (10, 2, 1)
    );
    assert_eq!((st.newton_iterations, st.f_evals), (10, 11));
    s.step(&mut p, 0.05).unwrap();
    assert_eq!(
        s.stats().lu_decompositions,
        3,
        "a new step size needs a new factorisation"
    );
}

#[test]
fn linear_step_is_k_eff_times_q_equals_effective_load() {
    // For f_int = K q the step equation is K_eff q_{n+1} = r (references.md §D4.2, A·x = r):
    // solving it with a separate dense solver (faer's LU) must reproduce the built-in step of
    // every implicit scheme to round-off (1e-12 on O(1) states) on a damped, forced 3-DOF chain.
    use faer::linalg::solvers::Solve;
    let m = Mat::from_fn(3, 3, |i, j| if i == j { [1.0, 2.0, 0.5][i] } else { 0.0 });
    let k = Mat::from_fn(3, 3, |i, j| match i.abs_diff(j) {
        0 => 6.0,
        1 => -2.0,
        _ => 0.0,
    });
    let c = Mat::from_fn(3, 3, |i, j| 0.1 * m[(i, j)] + 0.05 * k[(i, j)]);
    let load = |t: f64, f: &mut [f64]| {
        f[0] = (2.0 * t).sin();
        f[1] = 0.3;
        f[2] = 0.0;
    };
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::newmark(0.3025, 0.6).unwrap(),
        StructuralMethod::hht(-0.3).unwrap(),
        StructuralMethod::generalized_alpha(0.7).unwrap(),
        StructuralMethod::BackwardEuler,
    ] {
        let mut p = LinearStructure::new(m.clone(), Some(c.clone()), k.clone(), load).unwrap();
        let mut builtin =
            StructuralStepper::new(method, &mut p, 0.0, &[0.1, 0.0, -0.1], &[0.0, 0.2, 0.0])
                .unwrap();
        let mut outside =
            StructuralStepper::new(method, &mut p, 0.0, &[0.1, 0.0, -0.1], &[0.0, 0.2, 0.0])
                .unwrap();
        for _ in 0..200 {
            builtin.step(&mut p, 0.05).unwrap();
            let eq = outside.step_equation(0.05).unwrap();
            let mut f_ext = [0.0; 3];
            load(eq.t_force, &mut f_ext);
            let mut r = Mat::zeros(3, 1);
            let mut r_vec = [0.0; 3];
            eq.effective_load(outside.mass(), outside.damping(), &f_ext, &mut r_vec)
                .unwrap();
            // The compressed-row form gives the same load (only the summation order differs).
            let (m_sparse, c_sparse) = (
                sparse::sparse_from_dense(outside.mass()),
                sparse::sparse_from_dense(outside.damping().unwrap()),
            );
            let mut r_sparse = [0.0; 3];
            eq.effective_load_sparse(
                m_sparse.as_ref(),
                Some(c_sparse.as_ref()),
                &f_ext,
                &mut r_sparse,
            )
            .unwrap();
            for i in 0..3 {
                assert!((r_sparse[i] - r_vec[i]).abs() <= 1e-12 * (1.0 + r_vec[i].abs()));
            }
            for i in 0..3 {
                r[(i, 0)] = r_vec[i];
            }
            let mut k_eff = Mat::zeros(3, 3);
            eq.effective_stiffness(
                outside.mass(),
                outside.damping(),
                k.as_ref(),
                k_eff.as_mut(),
            )
            .unwrap();
            k_eff.partial_piv_lu().solve_in_place(r.as_mut());
            let q_new = [r[(0, 0)], r[(1, 0)], r[(2, 0)]];
            outside.finish_step(&mut p, 0.05, &q_new).unwrap();
            for i in 0..3 {
                assert!(
                    (builtin.q()[i] - outside.q()[i]).abs() < 1e-12,
                    "{method:?}"
                );
                assert!(
                    (builtin.v()[i] - outside.v()[i]).abs() < 1e-12,
                    "{method:?}"
                );
            }
        }
    }
}
