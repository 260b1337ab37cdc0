//! Verification of the normal contact solver against independent references:
//! direct summation of Love's coefficients, Hertz's closed forms, Boussinesq's flat punch,
//! finite differences, and the complementarity conditions themselves.

use approx::assert_relative_eq;
use halfspace::*;

fn steel() -> Material {
    Material::identical(210e9, 0.3).unwrap()
}

/// A reproducible pseudo-random sequence in [0, 1) (64-bit LCG; good enough for test data).
fn lcg(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Least-squares slope of log(err) against log(h).
fn observed_order(h: &[f64], err: &[f64]) -> f64 {
    let n = h.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = h
        .iter()
        .zip(err)
        .map(|(h, e)| (h.ln(), e.abs().ln()))
        .unzip();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn fft_convolution_equals_direct_summation() {
    // The oracle sums A_nn over all element pairs straight from Love's formula (no FFT, no
    // circulant table). Relative agreement 1e-12: the FFT's round-off is ~1e-15·log N.
    let material = Material::from_combined(80e9, 0.28).unwrap();
    let mut rand = lcg(7);
    for (nx, ny) in [(8, 8), (12, 5), (7, 7), (5, 9), (11, 1), (1, 6)] {
        let grid = Grid::new(nx, ny, 1.3e-4, 0.8e-4, 0.0, 0.0).unwrap();
        let p: Vec<f64> = (0..grid.len()).map(|_| 1e8 * rand()).collect();
        let mut u = vec![0.0; grid.len()];
        FftInfluence::new(grid, &material)
            .unwrap()
            .apply(&p, &mut u);
        let mut direct = vec![0.0; grid.len()];
        DirectInfluence::new(grid, material)
            .unwrap()
            .apply(&p, &mut direct);
        let max_u = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let max_err = u
            .iter()
            .zip(&direct)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            max_err <= 1e-12 * max_u,
            "{nx}x{ny}: error {max_err:e} of {max_u:e}"
        );
    }
}

#[test]
fn fft_convolution_matches_direct_on_a_parallel_sized_grid() {
    // 160 × 130 is above the threshold where rows and columns are split over threads.
    let material = Material::from_combined(1.0, 0.25).unwrap();
    let (nx, ny) = (160, 130);
    let grid = Grid::new(nx, ny, 1.0, 1.0, 0.0, 0.0).unwrap();
    let mut rand = lcg(3);
    let p: Vec<f64> = (0..grid.len()).map(|_| rand()).collect();
    let mut u = vec![0.0; grid.len()];
    FftInfluence::new(grid, &material)
        .unwrap()
        .apply(&p, &mut u);
    // Check a sample of outputs (the full direct product is O(N²) = 4e8 operations).
    let oracle = DirectInfluence::new(grid, material).unwrap();
    for &i in &[0, 77, nx * ny / 2 + 13, nx * ny - 1] {
        assert_relative_eq!(u[i], oracle.displacement_at(i, &p), max_relative = 1e-12);
    }
}

/// Solve the Hertz case `(a_curv, b_curv)` at F = 1 kN on an automatic n × n grid.
fn solve_hertz(a_curv: f64, b_curv: f64, n: usize, load: NormalLoad) -> (NormalSolution, Hertz) {
    let m = steel();
    let shape = GapShape::Quadratic {
        a: a_curv,
        b: b_curv,
    };
    let grid = auto_grid(&shape, &m, NormalLoad::Force(1000.0), n).unwrap();
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let sol = solver
        .solve(
            &shape.sample(&grid).unwrap(),
            load,
            &SolverOptions::default(),
        )
        .unwrap();
    (sol, shape.hertz(&m, load).unwrap())
}

/// Semi-axes from the second moments of the pressure: for Hertz's p₀√(1 − x²/a² − y²/b²),
/// ⟨x²⟩_p = a²/5 and ⟨y²⟩_p = b²/5. A smooth functional of p, unlike the set's extent.
fn moment_semi_axes(sol: &NormalSolution) -> (f64, f64) {
    let (mut sx, mut sy, mut s) = (0.0, 0.0, 0.0);
    for (k, &p) in sol.pressure.iter().enumerate() {
        let (x, y) = sol.grid.centre(k);
        sx += p * x * x;
        sy += p * y * y;
        s += p;
    }
    ((5.0 * sx / s).sqrt(), (5.0 * sy / s).sqrt())
}

#[test]
fn hertz_ellipses_converge_at_second_order() {
    // a/b = 1, 0.5, 0.2 (A/B = 1, ~0.35, ~0.085 by the curvature-ratio relation).
    for (ratio_label, b_curv) in [(1.0, 50.0), (0.5, 50.0 / 0.351772), (0.2, 50.0 / 0.084555)] {
        let sizes = [24usize, 48, 96, 192];
        let mut h = Vec::new();
        let (mut e_app, mut e_p0, mut e_a, mut e_b) = (vec![], vec![], vec![], vec![]);
        for &n in &sizes {
            let (sol, hz) = solve_hertz(50.0, b_curv, n, NormalLoad::Force(1000.0));
            assert!(
                sol.converged && sol.iterations <= 35,
                "{n}: {} iterations",
                sol.iterations
            );
            let (a, b) = moment_semi_axes(&sol);
            h.push(1.0 / n as f64);
            e_app.push(sol.approach / hz.approach - 1.0);
            e_p0.push(sol.max_pressure / hz.max_pressure - 1.0);
            e_a.push(a / hz.a - 1.0);
            e_b.push(b / hz.b - 1.0);
            // Semi-axis ratio of the closed form is the label.
            assert_relative_eq!(
                hz.b.min(hz.a) / hz.a.max(hz.b),
                ratio_label,
                max_relative = 1e-4
            );
            // The contact set's extent matches the Hertz semi-axes to one element.
            let (wa, wb) = sol.patch_half_widths();
            assert!(
                (wa - hz.a).abs() <= 1.01 * sol.grid.dx,
                "a {wa} vs {}",
                hz.a
            );
            assert!(
                (wb - hz.b).abs() <= 1.01 * sol.grid.dy,
                "b {wb} vs {}",
                hz.b
            );
        }
        // Finest grid: every quantity within 0.02 % of Hertz.
        for e in [&e_app, &e_p0, &e_a, &e_b] {
            assert!(e.last().unwrap().abs() < 2e-4, "{ratio_label}: {e:?}");
        }
        // Observed orders (theory 2; the discrete contact boundary adds noise, hence 1.6).
        let (oa, op) = (observed_order(&h, &e_app), observed_order(&h, &e_p0));
        let (oxa, oxb) = (observed_order(&h, &e_a), observed_order(&h, &e_b));
        eprintln!(
            "a/b = {ratio_label}: orders approach {oa:.2}, p0 {op:.2}, a {oxa:.2}, b {oxb:.2}; finest errors {:.1e} {:.1e} {:.1e} {:.1e}",
            e_app[3], e_p0[3], e_a[3], e_b[3]
        );
        assert!(
            oa > 1.6 && oa < 2.6,
            "{ratio_label}: approach order {oa} {e_app:?}"
        );
        assert!(
            op > 1.6 && op < 2.6,
            "{ratio_label}: p0 order {op} {e_p0:?}"
        );
        assert!(
            oxa > 1.6 && oxb > 1.6,
            "{ratio_label}: semi-axis orders {oxa} {oxb}"
        );
    }
}

#[test]
fn exact_sphere_matches_hertz_at_small_load() {
    // The exact sphere differs from Hertz's paraboloid by O(a²/R²) = 1e-4 here.
    let m = steel();
    let shape = GapShape::Sphere { radius: 0.01 };
    let load = NormalLoad::Force(1000.0);
    let grid = auto_grid(&shape, &m, load, 96).unwrap();
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let sol = solver
        .solve(
            &shape.sample(&grid).unwrap(),
            load,
            &SolverOptions::default(),
        )
        .unwrap();
    let hz = shape.hertz(&m, load).unwrap();
    assert_relative_eq!(sol.approach, hz.approach, max_relative = 1e-3);
    assert_relative_eq!(sol.max_pressure, hz.max_pressure, max_relative = 1e-3);
    assert_relative_eq!(sol.normal_force, 1000.0, max_relative = 1e-12);
}

#[test]
fn line_contact_matches_hertz_2d() {
    // Carter's cylinder (references.md §C4.1): R = 0.5 m, G = 82 GPa, ν = 0.28, F' = 178.9 kN/m
    // gives a = 1 mm and p₀ = 113.88 MPa. One row of elements of length L = 0.2 m ≫ a
    // approximates plane strain (CONTACT's 2D mode); discretisation error O(dx²).
    let m = Material::from_combined(82e9, 0.28).unwrap();
    let length = 0.2;
    let shape = GapShape::Cylinder {
        radius: 0.5,
        length,
    };
    let load = NormalLoad::Force(178.90e3 * length);
    let grid = auto_grid(&shape, &m, load, 100).unwrap();
    assert_eq!(grid.ny, 1);
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let sol = solver
        .solve(
            &shape.sample(&grid).unwrap(),
            load,
            &SolverOptions::default(),
        )
        .unwrap();
    let line = LineHertz::new(0.5, m.e_star, 178.90e3).unwrap();
    assert_relative_eq!(line.a, 1e-3, max_relative = 1e-4);
    assert_relative_eq!(sol.max_pressure, line.max_pressure, max_relative = 2e-3);
    let mut second_moment = 0.0;
    for (k, &p) in sol.pressure.iter().enumerate() {
        let (x, _) = grid.centre(k);
        second_moment += p * x * x;
    }
    // For p₀√(1 − x²/a²): ⟨x²⟩_p = a²/4.
    let a = (4.0 * second_moment / sol.pressure.iter().sum::<f64>()).sqrt();
    assert_relative_eq!(a, line.a, max_relative = 2e-3);
}

#[test]
fn flat_punch_stiffness_matches_boussinesq() {
    // Rigid flat circular punch of radius a on a half-space (Boussinesq): F = 2 a E* δ.
    // The punch face is a staircase of square elements (error O(dx/a)), hence 1.5 %.
    let m = Material::combine(Body::Rigid, Body::elastic(70e9, 0.33).unwrap()).unwrap();
    let radius = 2e-3;
    let n = 80;
    let grid = Grid::centred(
        n,
        n,
        2.4 * radius / n as f64,
        2.4 * radius / n as f64,
        0.0,
        0.0,
    )
    .unwrap();
    let gap = grid.sample(|x, y| {
        if x * x + y * y <= radius * radius {
            0.0
        } else {
            f64::INFINITY
        }
    });
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let approach = 1e-6;
    // Tight tolerances on both solves: the identity below is checked to 1e-8.
    let opts = SolverOptions {
        tol: 1e-12,
        sensitivity_tol: 1e-12,
        ..Default::default()
    };
    let sol = solver
        .solve(&gap, NormalLoad::Approach(approach), &opts)
        .unwrap();
    assert_relative_eq!(
        sol.normal_force,
        2.0 * radius * m.e_star * approach,
        max_relative = 0.015
    );
    // The stiffness of a flat punch does not depend on δ: dF/dδ = F/δ exactly (same set).
    assert_relative_eq!(
        sol.dfn_dapproach.unwrap(),
        sol.normal_force / approach,
        max_relative = 1e-8
    );
    // Edge singularity: the pressure is highest on the rim, not at the centre.
    let centre = sol.pressure[(n / 2) * n + n / 2];
    assert!(sol.max_pressure > 2.0 * centre);
}

#[test]
fn sensitivity_matches_finite_difference_and_hertz() {
    let m = steel();
    let shape = GapShape::Quadratic { a: 50.0, b: 80.0 };
    let grid = auto_grid(&shape, &m, NormalLoad::Force(1000.0), 64).unwrap();
    let gap = shape.sample(&grid).unwrap();
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let hz = shape.hertz(&m, NormalLoad::Force(1000.0)).unwrap();
    let d = hz.approach;
    let opts = SolverOptions {
        tol: 1e-12,
        ..Default::default()
    };
    let sol = solver.solve(&gap, NormalLoad::Approach(d), &opts).unwrap();
    let step = 1e-3 * d;
    let up = solver
        .solve(&gap, NormalLoad::Approach(d + step), &opts)
        .unwrap();
    let down = solver
        .solve(&gap, NormalLoad::Approach(d - step), &opts)
        .unwrap();
    let fd = (up.normal_force - down.normal_force) / (2.0 * step);
    let dfn = sol.dfn_dapproach.unwrap();
    eprintln!(
        "dF/dδ = {dfn:e}, finite difference {fd:e}, Hertz {:e}",
        1.5 * sol.normal_force / d
    );
    // The central difference over ±0.1 % of δ crosses a few boundary elements, each a jump
    // of the discrete derivative: agreement to 1 % (CONTACT quotes ~1 % for its sensitivities).
    assert_relative_eq!(dfn, fd, max_relative = 0.01);
    // And the continuous value 3F/(2δ) of Hertz, to the discretisation error.
    assert_relative_eq!(dfn, 1.5 * sol.normal_force / d, max_relative = 0.01);
}

#[test]
fn warm_start_needs_fewer_iterations() {
    let m = steel();
    let shape = GapShape::Quadratic { a: 50.0, b: 50.0 };
    let grid = auto_grid(&shape, &m, NormalLoad::Force(1000.0), 96).unwrap();
    let gap = shape.sample(&grid).unwrap();
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let cold_opts = SolverOptions {
        warm_start: false,
        ..Default::default()
    };
    let d = shape.hertz(&m, NormalLoad::Force(1000.0)).unwrap().approach;
    solver
        .solve(&gap, NormalLoad::Approach(d), &cold_opts)
        .unwrap();
    let cold = solver
        .solve(&gap, NormalLoad::Approach(1.002 * d), &cold_opts)
        .unwrap();
    solver
        .solve(&gap, NormalLoad::Approach(d), &SolverOptions::default())
        .unwrap();
    let warm = solver
        .solve(
            &gap,
            NormalLoad::Approach(1.002 * d),
            &SolverOptions::default(),
        )
        .unwrap();
    assert_relative_eq!(warm.normal_force, cold.normal_force, max_relative = 1e-7);
    assert!(
        warm.iterations < cold.iterations,
        "warm {} vs cold {}",
        warm.iterations,
        cold.iterations
    );
}

#[test]
fn iteration_limit_is_a_typed_error() {
    let m = steel();
    let shape = GapShape::Quadratic { a: 50.0, b: 50.0 };
    let grid = auto_grid(&shape, &m, NormalLoad::Force(1000.0), 64).unwrap();
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let opts = SolverOptions {
        max_iter: 2,
        warm_start: false,
        ..Default::default()
    };
    match solver.solve(
        &shape.sample(&grid).unwrap(),
        NormalLoad::Force(1000.0),
        &opts,
    ) {
        Err(ContactError::NotConverged {
            iterations,
            residual,
            last,
        }) => {
            assert_eq!(iterations, 2);
            assert!(residual > opts.tol);
            assert!(!last.converged);
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

#[test]
fn no_contact_below_the_gap() {
    let m = steel();
    let grid = Grid::centred(8, 8, 1e-5, 1e-5, 0.0, 0.0).unwrap();
    let gap = grid.sample(|x, y| 1e-6 + 50.0 * (x * x + y * y));
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let sol = solver
        .solve(&gap, NormalLoad::Approach(5e-7), &SolverOptions::default())
        .unwrap();
    assert_eq!(sol.normal_force, 0.0);
    assert_eq!(sol.elements_in_contact, 0);
    assert_eq!(sol.dfn_dapproach, Some(0.0));
}

#[test]
fn bad_inputs_are_rejected() {
    let m = steel();
    let grid = Grid::centred(4, 4, 1e-5, 1e-5, 0.0, 0.0).unwrap();
    let mut solver = NormalSolver::new(grid, m).unwrap();
    let gap = vec![0.0; 16];
    assert!(matches!(
        solver.solve(&gap[..3], NormalLoad::Force(1.0), &SolverOptions::default()),
        Err(ContactError::SizeMismatch { name: "gap", .. })
    ));
    assert!(matches!(
        solver.solve(&gap, NormalLoad::Force(-1.0), &SolverOptions::default()),
        Err(ContactError::InvalidParameter { name: "force", .. })
    ));
    assert!(matches!(
        solver.solve(
            &gap,
            NormalLoad::Approach(f64::NAN),
            &SolverOptions::default()
        ),
        Err(ContactError::InvalidParameter {
            name: "approach",
            ..
        })
    ));
    let bad = SolverOptions {
        tol: 0.0,
        ..Default::default()
    };
    assert!(matches!(
        solver.solve(&gap, NormalLoad::Force(1.0), &bad),
        Err(ContactError::InvalidParameter { name: "tol", .. })
    ));
}
