//! Property tests on random gaps: the discrete complementarity conditions, consistency of
//! the two load modes, and the sensitivity against a finite difference.

use halfspace::*;
use proptest::prelude::*;

/// A random smooth gap: an elliptic paraboloid, tilted, plus a waviness.
fn random_gap(grid: &Grid, a: f64, b: f64, tilt: f64, amp: f64, k: f64, phase: f64) -> Vec<f64> {
    let raw = grid.sample(|x, y| {
        a * x * x + b * y * y + tilt * x + amp * (k * x + phase).sin() * (0.7 * k * y).cos()
    });
    let min = raw.iter().copied().fold(f64::INFINITY, f64::min);
    raw.iter().map(|h| h - min).collect()
}

fn setup(n: usize) -> (Grid, Material) {
    let material = Material::identical(210e9, 0.3).unwrap();
    // 0.6 mm square: a sphere of R ≈ 10 mm at ~0.5–3 kN has a ≈ 0.15–0.25 mm.
    let grid = Grid::centred(n, n, 0.6e-3 / n as f64, 0.6e-3 / n as f64, 0.0, 0.0).unwrap();
    (grid, material)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]

    #[test]
    fn complementarity_holds(
        a in 20.0f64..120.0, b in 20.0f64..120.0, tilt in -2e-3f64..2e-3,
        amp in 0.0f64..3e-7, k in 5e3f64..4e4, phase in 0.0f64..6.3,
        approach in 2e-6f64..8e-6,
    ) {
        let (grid, m) = setup(24);
        let gap = random_gap(&grid, a, b, tilt, amp, k, phase);
        let mut solver = NormalSolver::new(grid, m).unwrap();
        let opts = SolverOptions { tol: 1e-10, ..Default::default() };
        let sol = solver.solve(&gap, NormalLoad::Approach(approach), &opts).unwrap();
        // Deformed distance tolerance: the relative pressure tolerance 1e-10 bounds e on the
        // contact set far below 1e-6·δ; 1e-6·δ leaves room for the FFT's round-off.
        let tol_e = 1e-6 * approach;
        for i in 0..grid.len() {
            let p = sol.pressure[i];
            let e = sol.deformed_distance[i];
            prop_assert!(p >= 0.0, "negative pressure {p}");
            prop_assert!(e >= -tol_e, "penetration {e:e} at {i}");
            if e > tol_e {
                prop_assert!(p == 0.0, "pressure {p} where gap {e:e} is open");
            }
            if p > 0.0 {
                prop_assert!(e.abs() <= tol_e, "gap {e:e} where pressure {p}");
            }
        }
        prop_assert!(sol.normal_force > 0.0);
    }

    #[test]
    fn force_and_approach_are_inverse(
        a in 20.0f64..120.0, b in 20.0f64..120.0, tilt in -2e-3f64..2e-3,
        amp in 0.0f64..3e-7, k in 5e3f64..4e4, phase in 0.0f64..6.3,
        approach in 2e-6f64..8e-6,
    ) {
        let (grid, m) = setup(20);
        let gap = random_gap(&grid, a, b, tilt, amp, k, phase);
        let mut solver = NormalSolver::new(grid, m).unwrap();
        let opts = SolverOptions { tol: 1e-11, warm_start: false, ..Default::default() };
        let by_approach = solver.solve(&gap, NormalLoad::Approach(approach), &opts).unwrap();
        let by_force = solver.solve(&gap, NormalLoad::Force(by_approach.normal_force), &opts).unwrap();
        // Both solve the same discrete problem: agreement to the solver tolerance (1e-7 ≫ 1e-11
        // allows for the conditioning of δ(F), about |δ/F · dF/dδ| ≈ 1.5).
        prop_assert!((by_force.approach / approach - 1.0).abs() < 1e-7,
            "approach {} vs {}", by_force.approach, approach);
        for (p, q) in by_force.pressure.iter().zip(&by_approach.pressure) {
            prop_assert!((p - q).abs() <= 1e-6 * by_approach.max_pressure);
        }
    }

    #[test]
    fn sensitivity_agrees_with_finite_difference(
        a in 20.0f64..120.0, b in 20.0f64..120.0, amp in 0.0f64..2e-7,
        k in 5e3f64..2e4, phase in 0.0f64..6.3, approach in 3e-6f64..8e-6,
    ) {
        let (grid, m) = setup(32);
        let gap = random_gap(&grid, a, b, 0.0, amp, k, phase);
        let mut solver = NormalSolver::new(grid, m).unwrap();
        let opts = SolverOptions { tol: 1e-12, ..Default::default() };
        let sol = solver.solve(&gap, NormalLoad::Approach(approach), &opts).unwrap();
        let step = 2e-3 * approach;
        let up = solver.solve(&gap, NormalLoad::Approach(approach + step), &opts).unwrap();
        let down = solver.solve(&gap, NormalLoad::Approach(approach - step), &opts).unwrap();
        let fd = (up.normal_force - down.normal_force) / (2.0 * step);
        let dfn = sol.dfn_dapproach.unwrap();
        // Elements joining the contact set within ±0.2 % of δ make the discrete F(δ) only
        // piecewise smooth; on a 32 × 32 grid this stays within 3 %.
        prop_assert!((dfn / fd - 1.0).abs() < 0.03, "dF/dδ {dfn:e} vs FD {fd:e}");
    }
}
