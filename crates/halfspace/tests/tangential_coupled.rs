//! Dissimilar materials (K ≠ 0): the coupling coefficients against Boussinesq's radial
//! displacement, and the Panagiotopoulos outer loop against its own equations evaluated by
//! the direct operators (sums of the closed-form influence coefficients, independent of the
//! FFT path).

mod support;

use halfspace::influence::tangential_influence;
use halfspace::operator::Update;
use halfspace::*;
use support::ball_on_soft;

#[test]
fn coupling_coefficient_is_boussinesq_radial_displacement() {
    // Rigid body 1 on elastic body 2 (G₂, ν₂): K = −(1 − 2ν₂)/2, G = 2G₂. Under a compressive
    // point load P the elastic surface moves toward the load by (1 − 2ν₂)P/(4πG₂ r)
    // (Boussinesq), so u = u⁽¹⁾ − u⁽²⁾ has u_x = +(1 − 2ν₂) P x/(4πG₂ r²). Far from a loaded
    // element the coefficient must approach that with P = ΔA (O((s/r)²) = 6e-4 at 40 elements).
    let (e2, nu2) = (210e9, 0.3);
    let m = Material::combine(Body::Rigid, Body::elastic(e2, nu2).unwrap()).unwrap();
    let g2 = e2 / (2.0 * (1.0 + nu2));
    let s = 1e-3;
    for (ox, oy) in [(40.0 * s, 0.0), (30.0 * s, 25.0 * s), (-20.0 * s, 35.0 * s)] {
        let a = tangential_influence(&m, ox, oy, s, s);
        let r2 = ox * ox + oy * oy;
        let bx = (1.0 - 2.0 * nu2) * s * s * ox / (4.0 * std::f64::consts::PI * g2 * r2);
        let by = (1.0 - 2.0 * nu2) * s * s * oy / (4.0 * std::f64::consts::PI * g2 * r2);
        assert!(
            (a.xn - bx).abs() <= 2e-3 * bx.abs().max(by.abs()),
            "{} {bx}",
            a.xn
        );
        assert!(
            (a.yn - by).abs() <= 2e-3 * bx.abs().max(by.abs()),
            "{} {by}",
            a.yn
        );
    }
}

#[test]
fn coupled_indentation_satisfies_its_equations() {
    let (grid, m, gap) = ball_on_soft(20);
    assert!((m.k + 0.3).abs() < 1e-12);
    let mut ns = NormalSolver::new(grid, m).unwrap();
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let mu = 0.3;
    let sol = solve_coupled(
        &mut ns,
        &mut ts,
        &gap,
        NormalLoad::Force(50.0),
        mu,
        CoupledProblem::Shift(ShiftLoad::Shift { wx: 0.0, wy: 0.0 }),
        &SolverOptions::default(),
        &TangentialOptions::default(),
        &CoupledOptions::default(),
    )
    .unwrap();
    println!(
        "outer {} adhesion {} slip {} F_x {} F_y {}",
        sol.outer_iterations,
        sol.tangential.adhesion_elements,
        sol.tangential.slip_elements,
        sol.tangential.force_x,
        sol.tangential.force_y
    );
    assert!(sol.outer_iterations > 1 && sol.outer_iterations < 30);
    let (pn, px, py) = (
        &sol.normal.pressure,
        &sol.tangential.traction_x,
        &sol.tangential.traction_y,
    );
    // Symmetry: no net tangential force, and p_x at x > 0 points inward on body 1 (the soft
    // surface is drawn toward the centre, friction on body 2 resists that).
    let fscale = mu * sol.normal.normal_force;
    assert!(sol.tangential.force_x.abs() < 1e-6 * fscale);
    assert!(sol.tangential.force_y.abs() < 1e-6 * fscale);
    let pmax = px.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(pmax > 0.0);
    for k in 0..grid.len() {
        let (x, _) = grid.centre(k);
        if x > 0.0 && pn[k] > 0.0 {
            assert!(px[k] <= 1e-9 * pmax, "p_x = {} at x = {x}", px[k]);
        }
    }
    // The equations by the direct operators: normal e = h − δ + A_nn p_n + A_nx p_x + A_ny p_y = 0 in
    // contact, ≥ 0 outside; tangential S = A_xx p_x + A_xy p_y + A_xn p_n (and y) vanishing in
    // adhesion, opposite to p_t with |p_t| = μ p_n in slip. Tolerances: 1e-5 of the approach
    // and of the largest |S| (NormCG and Gauss–Seidel stop at 1e-8 / 1e-7 relative changes).
    let n = grid.len();
    let mut normal_op = DirectInfluence::new(grid, m).unwrap();
    let mut tangential_op = DirectTangentialInfluence::new(grid, m).unwrap();
    let (mut e, mut un) = (vec![0.0; n], vec![0.0; n]);
    normal_op.apply(pn, &mut e);
    tangential_op.normal_from_traction((px, py), &mut un);
    for ((e, h), u) in e.iter_mut().zip(&gap).zip(&un) {
        *e += h - sol.normal.approach + u;
    }
    let (mut sx, mut sy) = (vec![0.0; n], vec![0.0; n]);
    let (mut cx, mut cy) = (vec![0.0; n], vec![0.0; n]);
    let direct = TangentialKernel::Direct;
    tangential_op.traction_product(direct, Update::Set, (px, py), (&mut sx, &mut sy));
    tangential_op.pressure_product(direct, Update::Set, pn, (&mut cx, &mut cy));
    for k in 0..n {
        sx[k] += cx[k];
        sy[k] += cy[k];
    }
    let delta = sol.normal.approach;
    let smax = sx.iter().chain(&sy).fold(0.0f64, |m, v| m.max(v.abs()));
    for k in 0..n {
        if pn[k] > 0.0 {
            assert!(e[k].abs() < 1e-5 * delta, "e = {} at {k}", e[k]);
        } else {
            assert!(e[k] > -1e-5 * delta);
        }
        match sol.tangential.state[k] {
            ElementState::Adhesion => {
                assert!(
                    sx[k].hypot(sy[k]) < 1e-5 * smax,
                    "adhesion slip {} at {k}",
                    sx[k].hypot(sy[k])
                );
                assert!(px[k].hypot(py[k]) <= mu * pn[k] * (1.0 + 1e-9));
            }
            ElementState::Slip => {
                assert!((px[k].hypot(py[k]) - mu * pn[k]).abs() < 1e-9 * mu * pn[k]);
                assert!(px[k] * sx[k] + py[k] * sy[k] < 0.0);
            }
            ElementState::Exterior => assert_eq!(pn[k], 0.0),
        }
    }
}

#[test]
fn identical_materials_need_one_pass() {
    let m = Material::identical(210e9, 0.3).unwrap();
    let shape = GapShape::Quadratic { a: 50.0, b: 50.0 };
    let grid = auto_grid(&shape, &m, NormalLoad::Force(1000.0), 16).unwrap();
    let gap = shape.sample(&grid).unwrap();
    let mut ns = NormalSolver::new(grid, m).unwrap();
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let sol = solve_coupled(
        &mut ns,
        &mut ts,
        &gap,
        NormalLoad::Force(1000.0),
        0.3,
        CoupledProblem::SteadyRolling(RollingLoad::Creepages(Creepages {
            xi: 1e-3,
            eta: 0.0,
            phi: 0.0,
        })),
        &SolverOptions::default(),
        &TangentialOptions::default(),
        &CoupledOptions::default(),
    )
    .unwrap();
    assert_eq!(sol.outer_iterations, 1);
    let mut u = vec![1.0; grid.len()];
    ts.normal_displacement(
        &sol.tangential.traction_x,
        &sol.tangential.traction_y,
        &mut u,
    )
    .unwrap();
    assert!(u.iter().all(|&v| v == 0.0));
}

#[test]
fn transient_steps_with_coupling_reach_steady_rolling() {
    // K ≠ 0 with a fixed pressure: transient steps (coupling A_xn p_n − A_v,xn p_n') started
    // from rest must settle on the steady-rolling solution ((A_xn − A_v,xn) p_n); the traction
    // memory leaves the patch after about one patch length (16 steps here), 80 steps leave a
    // residual transient far below the 1e-4 μF_n tolerance.
    let (grid, m, gap) = ball_on_soft(16);
    let n = NormalSolver::new(grid, m)
        .unwrap()
        .solve(&gap, NormalLoad::Force(50.0), &SolverOptions::default())
        .unwrap();
    let mu = 0.3;
    let c = Creepages {
        xi: 2e-3,
        eta: 0.0,
        phi: 0.0,
    };
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let steady = ts
        .steady_rolling(
            &n.pressure,
            mu,
            RollingLoad::Creepages(c),
            &TangentialOptions::default(),
        )
        .unwrap();
    ts.reset();
    let (mut px, mut py) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
    let motion = StepMotion {
        delta_q: grid.dx,
        creepages: c,
        shift: (0.0, 0.0),
    };
    let mut last = None;
    for _ in 0..80 {
        let s = ts
            .transient_step(
                &n.pressure,
                mu,
                (&px, &py),
                motion,
                &TangentialOptions::default(),
            )
            .unwrap();
        px = s.traction_x.clone();
        py = s.traction_y.clone();
        last = Some(s);
    }
    let last = last.unwrap();
    let lim = mu * n.normal_force;
    println!(
        "steady {} transient {}",
        steady.force_x / lim,
        last.force_x / lim
    );
    assert!((last.force_x - steady.force_x).abs() < 1e-4 * lim);
    assert!((last.force_y - steady.force_y).abs() < 1e-4 * lim);
}
