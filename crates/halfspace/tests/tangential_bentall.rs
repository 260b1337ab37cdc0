//! Dissimilar materials in steady rolling: CONTACT's Bentall–Johnson example.

use halfspace::*;

#[test]
fn bentall_johnson_free_rolling() {
    // CONTACT's bentall example, case 4 (user guide §5.3): an aluminium roller (G = 23 GPa,
    // ν = 0.31) on a steel roller (82 GPa, 0.28), K = 0.1002, effective R = 25 mm
    // (gap 0.020 x² /mm), F_n = 16 201.9 N on a 1 m strip, 216 elements of 1 µm from
    // −0.108 mm, μ = 0.05, free rolling (F_x = 0 prescribed), Panagiotopoulos' process.
    // CONTACT rolls in −x (χ = 180°); mirrored to our +x the creepage changes sign.
    // CONTACT: ξ = 4.294e-4, 125 adhesion / 75 slip, approach 2.080e-3 mm, p_max 103.6 N/mm².
    // Tolerance: the printed 4 digits (0.05 %), counts exact. Outer-loop and Newton tolerances
    // of 1e-5 (instead of 1e-6) keep the debug-build test short; they perturb ξ by < 1e-5
    // relative, far below the printed digits.
    let m = Material::combine(
        Body::elastic(2.0 * 23e9 * 1.31, 0.31).unwrap(),
        Body::elastic(2.0 * 82e9 * 1.28, 0.28).unwrap(),
    )
    .unwrap();
    assert!((m.k - 0.1002).abs() < 1e-4);
    let grid = Grid::new(216, 1, 1e-6, 1.0, -0.108e-3, -0.5).unwrap();
    let gap = grid.sample(|x, _| 20.0 * x * x);
    let mut ns = NormalSolver::new(grid, m).unwrap();
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let c = solve_coupled(
        &mut ns,
        &mut ts,
        &gap,
        NormalLoad::Force(16201.9),
        0.05,
        CoupledProblem::SteadyRolling(RollingLoad::Forces {
            fx: 0.0,
            fy: 0.0,
            phi: 0.0,
        }),
        &SolverOptions::default(),
        &TangentialOptions {
            force_tol: 1e-5,
            ..Default::default()
        },
        &CoupledOptions {
            tol: 1e-5,
            ..Default::default()
        },
    )
    .unwrap();
    println!(
        "xi {:e}, {} / {}, approach {:e}, p_max {:e}, {} outer",
        c.tangential.creepages.xi,
        c.tangential.adhesion_elements,
        c.tangential.slip_elements,
        c.normal.approach,
        c.normal.max_pressure,
        c.outer_iterations
    );
    assert!((c.tangential.creepages.xi / -4.294e-4 - 1.0).abs() < 5e-4);
    assert_eq!(c.tangential.adhesion_elements, 125);
    assert_eq!(c.tangential.slip_elements, 75);
    assert!((c.normal.approach / 2.080e-6 - 1.0).abs() < 5e-4);
    assert!((c.normal.max_pressure / 103.6e6 - 1.0).abs() < 5e-4);
}
