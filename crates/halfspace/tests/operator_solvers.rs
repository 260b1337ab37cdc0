//! The solvers run over the direct O(n²) influence operators give the solutions they give
//! over the FFT operators (the RustFFT-style check: the slow oracle against the fast path,
//! here through whole solves).
//!
//! Both operators share the preconditioner, so a solve takes the same path with either and
//! only the round-off of the products differs (FFT ~1e-15·log n, direct sum ~1e-16·n
//! relative). Tolerance: 1e-12 relative to the largest value of each field, and equal
//! iteration counts; far below the solvers' own tolerances (1e-8, 1e-7), so an operator
//! that differed in any coefficient would fail.

mod support;

use halfspace::*;
use support::ball_on_soft;

/// max |a − b| ≤ tol · max |b| over two fields.
fn assert_fields_close(name: &str, a: &[f64], b: &[f64], tol: f64) {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(err <= tol * scale, "{name}: error {err:e} of {scale:e}");
}

fn assert_close(name: &str, a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol * b.abs(), "{name}: {a:e} vs {b:e}");
}

fn compare_normal(fast: &NormalSolution, slow: &NormalSolution) {
    assert_eq!(fast.iterations, slow.iterations);
    assert_eq!(fast.in_contact, slow.in_contact);
    assert_fields_close("pressure", &slow.pressure, &fast.pressure, 1e-12);
    assert_fields_close(
        "displacement",
        &slow.displacement,
        &fast.displacement,
        1e-12,
    );
    assert_close("force", slow.normal_force, fast.normal_force, 1e-12);
    assert_close("approach", slow.approach, fast.approach, 1e-12);
    match (fast.dfn_dapproach, slow.dfn_dapproach) {
        (Some(f), Some(s)) => assert_close("dF/dδ", s, f, 1e-12),
        (None, None) => {}
        other => panic!("sensitivities differ: {other:?}"),
    }
}

#[test]
fn normcg_over_direct_operator_equals_fft_solve() {
    // An elliptic gap on a rectangular grid (approach and force prescribed, with the
    // sensitivity solve), and a 2D line contact (ny = 1) at prescribed force.
    let m = Material::identical(210e9, 0.3).unwrap();
    let shape = GapShape::Quadratic { a: 40.0, b: 90.0 };
    let grid = auto_grid(&shape, &m, NormalLoad::Force(500.0), 14).unwrap();
    let grid = Grid::new(14, 11, grid.dx, grid.dy * 14.0 / 11.0, grid.x0, grid.y0).unwrap();
    let gap = shape.sample(&grid).unwrap();
    let line = Grid::centred(40, 1, 2e-5, 1e-2, 0.0, 0.0).unwrap();
    let line_gap: Vec<f64> = (0..line.len())
        .map(|k| line.centre(k).0.powi(2) / (2.0 * 0.5))
        .collect();
    let options = SolverOptions::default();
    for (grid, gap, loads) in [
        (
            grid,
            &gap,
            vec![NormalLoad::Approach(8e-6), NormalLoad::Force(500.0)],
        ),
        (line, &line_gap, vec![NormalLoad::Force(1e3)]),
    ] {
        let mut fast = NormalSolver::with_operator(FftInfluence::new(grid, &m).unwrap()).unwrap();
        let mut slow = NormalSolver::with_operator(DirectInfluence::new(grid, m).unwrap()).unwrap();
        for load in loads {
            // Twice: a cold start and a warm start from the previous solution.
            for _ in 0..2 {
                let f = fast.solve(gap, load, &options).unwrap();
                let s = slow.solve(gap, load, &options).unwrap();
                assert!(f.elements_in_contact > 3 && f.converged);
                compare_normal(&f, &s);
            }
        }
        assert_eq!(fast.convolutions(), slow.convolutions());
    }
}

/// The two paths of the default operator ([`NormalInfluence`]: FFT, or on small grids the
/// dense sums for sparse inputs) and the dense operator alone give the FFT operator's
/// solutions: a small Hertz patch on 12 × 12 (contact set of ~20 elements: every product
/// dense), a patch over most of a 20 × 16 grid (FFT once the set has grown) and a 40 × 40
/// grid. The dense preconditioner is the FFT one tabulated (its impulse response), equal to
/// round-off, so the iterates agree to round-off: tolerance 1e-12 as above.
#[test]
fn normcg_over_dense_sums_equals_fft_solve() {
    let m = Material::identical(210e9, 0.3).unwrap();
    let shape = GapShape::Quadratic { a: 50.0, b: 50.0 };
    let options = SolverOptions::default();
    let mut used_dense = 0;
    for (n, ny, half_width) in [(12, 12, 4e-4), (20, 16, 1.2e-4), (40, 40, 3e-4)] {
        let grid = Grid::centred(
            n,
            ny,
            2.0 * half_width / n as f64,
            2.0 * half_width / ny as f64,
            0.0,
            0.0,
        )
        .unwrap();
        let gap = shape.sample(&grid).unwrap();
        let mut fft = NormalSolver::with_operator(FftInfluence::new(grid, &m).unwrap()).unwrap();
        let mut dense =
            NormalSolver::with_operator(DenseInfluence::new(grid, &m).unwrap()).unwrap();
        let mut auto = NormalSolver::new(grid, m).unwrap();
        for load in [NormalLoad::Force(20.0), NormalLoad::Approach(1e-6)] {
            let f = fft.solve(&gap, load, &options).unwrap();
            assert!(
                f.elements_in_contact > 3 && f.converged,
                "{n}x{ny} {load:?}"
            );
            compare_normal(&dense.solve(&gap, load, &options).unwrap(), &f);
            compare_normal(&auto.solve(&gap, load, &options).unwrap(), &f);
        }
        used_dense += auto.operator().dense_products();
        if n == 12 {
            // Every product of the small patch is dense.
            assert_eq!(auto.operator().dense_products(), auto.convolutions());
        }
    }
    assert!(used_dense > 0);
}

fn compare_tangential(fast: &TangentialSolution, slow: &TangentialSolution) {
    assert_eq!(fast.iterations, slow.iterations);
    assert_eq!(fast.newton_iterations, slow.newton_iterations);
    assert_eq!(fast.state, slow.state);
    assert_fields_close("traction_x", &slow.traction_x, &fast.traction_x, 1e-12);
    assert_fields_close("traction_y", &slow.traction_y, &fast.traction_y, 1e-12);
    let slip = |s: &TangentialSolution| [s.slip_x.clone(), s.slip_y.clone()].concat();
    assert_fields_close("slip", &slip(slow), &slip(fast), 1e-12);
    // Forces relative to ΔA Σ |p_t| (the net force of a symmetric problem is round-off).
    let area = fast.grid.element_area();
    let scale: f64 = area
        * fast
            .traction_x
            .iter()
            .zip(&fast.traction_y)
            .map(|(x, y)| x.hypot(*y))
            .sum::<f64>();
    assert!((fast.force_x - slow.force_x).abs() <= 1e-12 * scale);
    assert!((fast.force_y - slow.force_y).abs() <= 1e-12 * scale);
}

#[test]
fn tangential_solver_over_direct_operator_equals_fft_solve() {
    // Dissimilar materials (K ≠ 0): every kernel and coupling term is used. A shift with
    // forces prescribed (Newton), steady rolling, and a transient step from the shift's
    // tractions (shifted kernels).
    let (grid, m, gap) = ball_on_soft(8);
    let mut normal = NormalSolver::new(grid, m).unwrap();
    let pressure = normal
        .solve(&gap, NormalLoad::Force(50.0), &SolverOptions::default())
        .unwrap()
        .pressure;
    let mu = 0.3;
    let options = TangentialOptions::default();
    let mut fast = TangentialSolver::new(grid, m).unwrap();
    let mut slow =
        TangentialSolver::with_operator(DirectTangentialInfluence::new(grid, m).unwrap()).unwrap();
    let shift = ShiftLoad::Forces { fx: 6.0, fy: -2.0 };
    let f = fast.shift(&pressure, mu, shift, &options).unwrap();
    let s = slow.shift(&pressure, mu, shift, &options).unwrap();
    assert!(f.slip_elements > 0 && f.adhesion_elements > 0);
    compare_tangential(&f, &s);

    let rolling = RollingLoad::Creepages(Creepages {
        xi: 5e-4,
        eta: -2e-4,
        phi: 0.5,
    });
    let fr = fast
        .steady_rolling(&pressure, mu, rolling, &options)
        .unwrap();
    let sr = slow
        .steady_rolling(&pressure, mu, rolling, &options)
        .unwrap();
    assert!(fr.slip_elements > 0 && fr.adhesion_elements > 0);
    compare_tangential(&fr, &sr);

    let motion = StepMotion {
        delta_q: 0.5 * grid.dx,
        creepages: Creepages {
            xi: 1e-3,
            eta: 0.0,
            phi: 0.0,
        },
        shift: (0.0, 0.0),
    };
    // The previous pressure differs from the current one: the shifted coupling term is
    // A_tn p_n − A_v,tn p_n'.
    let previous_pressure: Vec<f64> = pressure.iter().map(|p| 0.9 * p).collect();
    fast.set_previous_pressure(&previous_pressure).unwrap();
    slow.set_previous_pressure(&previous_pressure).unwrap();
    let previous = (&f.traction_x[..], &f.traction_y[..]);
    let ft = fast
        .transient_step(&pressure, mu, previous, motion, &options)
        .unwrap();
    let st = slow
        .transient_step(&pressure, mu, previous, motion, &options)
        .unwrap();
    compare_tangential(&ft, &st);
}

#[test]
fn coupled_solve_over_direct_operators_equals_fft_solve() {
    // Panagiotopoulos' outer loop (several passes for K ≠ 0), every product direct.
    let (grid, m, gap) = ball_on_soft(7);
    // The frictional indentation of the rigid ball (zero shift, μ = 0.3).
    fn indent<N: InfluenceOperator, T: TangentialInfluenceOperator>(
        mut normal: NormalSolver<N>,
        mut tangential: TangentialSolver<T>,
        gap: &[f64],
    ) -> CoupledSolution {
        solve_coupled(
            &mut normal,
            &mut tangential,
            gap,
            NormalLoad::Force(50.0),
            0.3,
            CoupledProblem::Shift(ShiftLoad::Shift { wx: 0.0, wy: 0.0 }),
            &SolverOptions::default(),
            &TangentialOptions::default(),
            &CoupledOptions::default(),
        )
        .unwrap()
    }
    let fast = indent(
        NormalSolver::new(grid, m).unwrap(),
        TangentialSolver::new(grid, m).unwrap(),
        &gap,
    );
    let slow = indent(
        NormalSolver::with_operator(DirectInfluence::new(grid, m).unwrap()).unwrap(),
        TangentialSolver::with_operator(DirectTangentialInfluence::new(grid, m).unwrap()).unwrap(),
        &gap,
    );
    assert!(fast.outer_iterations > 1);
    assert_eq!(fast.outer_iterations, slow.outer_iterations);
    compare_normal(&fast.normal, &slow.normal);
    compare_tangential(&fast.tangential, &slow.tangential);
}
