//! DOFs frozen at rest (`StructuralStepper::freeze`): left out of the implicit step's work,
//! they stay exactly at rest, and the other DOFs step exactly as without the freeze.

use faer::Mat;
use faer::linalg::solvers::Solve;
use integrate::IntegrateError;
use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper, sparse};

/// Two uncoupled parts in interleaved DOFs: a damped, forced 3-chain on {0, 2, 4} and a
/// 2-DOF oscillator on {1, 3} under a constant load, started at its static equilibrium.
const CHAIN: [usize; 3] = [0, 2, 4];
const REST: [usize; 2] = [1, 3];

fn matrices() -> (Mat<f64>, Mat<f64>, Mat<f64>) {
    let mut m = Mat::zeros(5, 5);
    let mut k = Mat::zeros(5, 5);
    for (a, &i) in CHAIN.iter().enumerate() {
        m[(i, i)] = [1.0, 2.0, 0.5][a];
        for (b, &j) in CHAIN.iter().enumerate() {
            k[(i, j)] = match a.abs_diff(b) {
                0 => 6.0,
                1 => -2.0,
                _ => 0.0,
            };
        }
    }
    m[(1, 1)] = 3.0;
    m[(3, 3)] = 1.5;
    k[(1, 1)] = 9.0;
    k[(1, 3)] = -4.0;
    k[(3, 1)] = -4.0;
    k[(3, 3)] = 5.0;
    let c = Mat::from_fn(5, 5, |i, j| 0.1 * m[(i, j)] + 0.05 * k[(i, j)]);
    (m, c, k)
}

fn load(t: f64, f: &mut [f64]) {
    f.fill(0.0);
    f[0] = (2.0 * t).sin();
    f[2] = 0.3;
    f[1] = 2.0;
    f[3] = -1.0;
}

/// One step of `dt` taken outside (the step equation, its load with compressed-row M and C,
/// and a dense solve of each part's rows of K_eff); the part on `REST` is solved only if
/// `solve_rest` (otherwise it gets q̃). Returns the effective load.
fn outside_step(
    s: &mut StructuralStepper,
    p: &mut LinearStructure<fn(f64, &mut [f64])>,
    k: &Mat<f64>,
    dt: f64,
    solve_rest: bool,
) -> [f64; 5] {
    let eq = s.step_equation(dt).unwrap();
    let mut f_ext = [0.0; 5];
    load(eq.t_force, &mut f_ext);
    let (m_sparse, c_sparse) = (
        sparse::sparse_from_dense(s.mass()),
        sparse::sparse_from_dense(s.damping().unwrap()),
    );
    let mut r = [0.0; 5];
    eq.effective_load_sparse(m_sparse.as_ref(), Some(c_sparse.as_ref()), &f_ext, &mut r)
        .unwrap();
    let mut k_eff = Mat::zeros(5, 5);
    eq.effective_stiffness(s.mass(), s.damping(), k.as_ref(), k_eff.as_mut())
        .unwrap();
    let mut q_new = eq.q_pred.clone();
    let parts: &[&[usize]] = if solve_rest {
        &[&CHAIN, &REST]
    } else {
        &[&CHAIN]
    };
    for part in parts {
        let n = part.len();
        let a = Mat::from_fn(n, n, |x, y| k_eff[(part[x], part[y])]);
        let mut b = Mat::from_fn(n, 1, |x, _| r[part[x]]);
        a.partial_piv_lu().solve_in_place(b.as_mut());
        for (x, &i) in part.iter().enumerate() {
            q_new[i] = b[(x, 0)];
        }
    }
    s.finish_step(p, dt, &q_new).unwrap();
    r
}

#[test]
fn frozen_dofs_stay_at_rest_and_the_others_step_bit_for_bit() {
    let (m, c, k) = matrices();
    // The oscillator's static equilibrium K_rr q_r = f_r: 9 q1 − 4 q3 = 2, −4 q1 + 5 q3 = −1.
    let det = 9.0 * 5.0 - 16.0;
    let q1 = (2.0 * 5.0 - 4.0) / det;
    let q3 = (-9.0 + 4.0 * 2.0) / det;
    let q0 = [0.1, q1, 0.0, q3, -0.1];
    let v0 = [0.0, 0.0, 0.2, 0.0, 0.0];
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::hht(-0.3).unwrap(),
        StructuralMethod::generalized_alpha(0.7).unwrap(),
        StructuralMethod::BackwardEuler,
    ] {
        let mut p = LinearStructure::new(
            m.clone(),
            Some(c.clone()),
            k.clone(),
            load as fn(f64, &mut [f64]),
        )
        .unwrap();
        let mut full = StructuralStepper::new(method, &mut p, 0.0, &q0, &v0).unwrap();
        let mut frozen = StructuralStepper::new(method, &mut p, 0.0, &q0, &v0).unwrap();
        frozen.freeze(&[3, 1]).unwrap();
        assert_eq!(frozen.frozen(), &[1..2, 3..4]);
        for _ in 0..200 {
            let eq = frozen.step_equation(0.05).unwrap();
            let r_frozen = outside_step(&mut frozen, &mut p, &k, 0.05, false);
            outside_step(&mut full, &mut p, &k, 0.05, true);
            for &i in &REST {
                // Exactly at rest: q̃ = q, ṽ = 0, the rows not evaluated (zero).
                assert_eq!((eq.q_pred[i], eq.v_pred[i], r_frozen[i]), (q0[i], 0.0, 0.0));
                assert_eq!(
                    (frozen.q()[i], frozen.v()[i], frozen.a()[i]),
                    (q0[i], 0.0, 0.0)
                );
                // The full step keeps the part at rest to round-off only (its start balances
                // it to round-off).
                let drift = (full.q()[i] - q0[i]).abs();
                assert!(drift <= 1e-13, "{method:?}: {drift:e}");
            }
            for &i in &CHAIN {
                for (x, y) in [
                    (full.q()[i], frozen.q()[i]),
                    (full.v()[i], frozen.v()[i]),
                    (full.a()[i], frozen.a()[i]),
                ] {
                    assert_eq!(x.to_bits(), y.to_bits(), "{method:?} DOF {i}");
                }
            }
        }
        // Unfrozen, the part steps again from rest (a load step on it moves it).
        frozen.freeze(&[]).unwrap();
        assert!(frozen.frozen().is_empty());
        let eq = frozen.step_equation(0.05).unwrap();
        assert!(eq.frozen_rows.is_empty());
    }
}

#[test]
fn bad_frozen_sets_are_rejected() {
    let (m, c, k) = matrices();
    let mut p = LinearStructure::new(m, Some(c), k, load as fn(f64, &mut [f64])).unwrap();
    let q0 = [0.0; 5];
    let mut s = StructuralStepper::new(
        StructuralMethod::average_acceleration(),
        &mut p,
        0.0,
        &q0,
        &q0,
    )
    .unwrap();
    let name = |e: IntegrateError| match e {
        IntegrateError::InvalidParameter { name, .. } => name,
        other => panic!("{other:?}"),
    };
    assert_eq!(name(s.freeze(&[5]).unwrap_err()), "frozen DOFs");
    let mut explicit = StructuralStepper::new(
        StructuralMethod::central_difference(),
        &mut p,
        0.0,
        &q0,
        &q0,
    )
    .unwrap();
    assert_eq!(name(explicit.freeze(&[1]).unwrap_err()), "frozen DOFs");
    assert!(explicit.freeze(&[]).is_ok());
}
