//! The reference-case harness of the normal contact solver: one table of published cases
//! (problem, quantity, reference value, tolerance, source), every case run with every method
//! — NormCG over the FFT influence operator (the load prescribed as a force and as an
//! approach) and over the direct O(n²) operator (force).
//!
//! Sources (docs/references.md §C4.1): Hertz's closed forms (Johnson 1985, §4.2) and the
//! discrete outputs CONTACT prints for the same grids (Vollebregt's CONTACT examples
//! `tractcurv` and `cattaneo`, as listed in §C4.1).
//!
//! Tolerances: a CONTACT value is printed to 4 significant digits, so it is compared to one
//! unit of its last printed digit (the same discretisation gives the same number); a Hertz
//! value is exact and the grid's discretisation error is allowed (half-element smearing of
//! the patch edge: ~2e-3 relative on the approach and 1e-2 on the peak pressure on these
//! grids, 15–44 elements across the patch).

use halfspace::{
    DirectInfluence, FftInfluence, GapShape, Grid, InfluenceOperator, Material, NormalLoad,
    NormalSolution, NormalSolver, SolverOptions,
};

/// A normal contact problem: combined material, quadratic gap h = A x² + B y² \[1/m\], normal
/// force \[N\] and the centred grid (nx × ny elements of dx × dy \[m\]).
struct Problem {
    name: &'static str,
    shear_modulus: f64,
    poisson: f64,
    a: f64,
    b: f64,
    force: f64,
    grid: (usize, usize, f64, f64),
}

/// A quantity of the solution.
#[derive(Clone, Copy, Debug)]
enum Quantity {
    /// Approach δ \[m\].
    Approach,
    /// Peak pressure \[Pa\].
    MaxPressure,
}

/// One row of the table: problem, quantity, value, absolute tolerance, source.
struct Row {
    problem: usize,
    quantity: Quantity,
    value: f64,
    tol: f64,
    source: &'static str,
}

const PROBLEMS: [Problem; 2] = [
    Problem {
        // tractcurv: A = 0.0008/mm, a/b = 0.5, Fn = 106.7 kN, G = 82 GPa, ν = 0.28.
        name: "tractcurv ellipse 44×44",
        shear_modulus: 82e9,
        poisson: 0.28,
        a: 0.8,
        b: 0.281417,
        force: 106.7e3,
        grid: (44, 44, 0.3e-3, 0.6e-3),
    },
    Problem {
        // cattaneo: G = 200 MPa, ν = 0.42, R = 50 mm, 15 × 15 elements across a = b = 1 mm.
        name: "Cattaneo sphere 19×19",
        shear_modulus: 200e6,
        poisson: 0.42,
        a: 10.0,
        b: 10.0,
        force: 9.1954,
        grid: (19, 19, 2e-3 / 15.0, 2e-3 / 15.0),
    },
];

const ROWS: [Row; 8] = [
    Row {
        problem: 0,
        quantity: Quantity::Approach,
        value: 76.51e-6,
        tol: 0.005e-6,
        source: "CONTACT tractcurv, 44×44: δ = 0.07651 mm",
    },
    Row {
        problem: 0,
        quantity: Quantity::MaxPressure,
        value: 640.7e6,
        tol: 0.05e6,
        source: "CONTACT tractcurv, 44×44: p_max = 640.7 N/mm²",
    },
    Row {
        problem: 0,
        quantity: Quantity::Approach,
        value: 76.5171e-6,
        tol: 2e-3 * 76.5171e-6,
        source: "Hertz (elliptic), δ = 0.0765171 mm",
    },
    Row {
        problem: 0,
        quantity: Quantity::MaxPressure,
        value: 641.06e6,
        tol: 1e-2 * 641.06e6,
        source: "Hertz (elliptic), p₀ = 641.06 N/mm²",
    },
    Row {
        problem: 1,
        quantity: Quantity::Approach,
        value: 0.01998e-3,
        tol: 0.000005e-3,
        source: "CONTACT cattaneo, 19×19: δ = 0.01998 mm",
    },
    Row {
        problem: 1,
        quantity: Quantity::MaxPressure,
        value: 4.393e6,
        tol: 0.0005e6,
        source: "CONTACT cattaneo, 19×19: p_max = 4.393 N/mm²",
    },
    Row {
        problem: 1,
        quantity: Quantity::Approach,
        value: 0.020000e-3,
        tol: 2e-3 * 0.02e-3,
        source: "Hertz (sphere), δ = a²/R = 0.020000 mm",
    },
    Row {
        problem: 1,
        quantity: Quantity::MaxPressure,
        value: 4.3905e6,
        tol: 1e-2 * 4.3905e6,
        source: "Hertz (sphere), p₀ = 4.3905 N/mm²",
    },
];

/// Solves with the operator `op`, the load as a force; then (with `both`) again with the
/// approach of that solution prescribed (which must give the same force).
fn solve_loads<A: InfluenceOperator>(
    op: A,
    gap: &[f64],
    force: f64,
    both: bool,
) -> Vec<NormalSolution> {
    let options = SolverOptions {
        tol: 1e-10,
        ..SolverOptions::default()
    };
    let mut solver = NormalSolver::with_operator(op).unwrap();
    let by_force = solver
        .solve(gap, NormalLoad::Force(force), &options)
        .unwrap();
    if !both {
        return vec![by_force];
    }
    solver.reset();
    let by_approach = solver
        .solve(gap, NormalLoad::Approach(by_force.approach), &options)
        .unwrap();
    assert!(
        (by_approach.normal_force - force).abs() <= 1e-8 * force,
        "approach-prescribed force {} vs {force}",
        by_approach.normal_force
    );
    vec![by_force, by_approach]
}

#[test]
fn every_method_reproduces_the_published_normal_cases() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for (index, p) in PROBLEMS.iter().enumerate() {
        let material = Material::from_combined(p.shear_modulus, p.poisson).unwrap();
        let (nx, ny, dx, dy) = p.grid;
        let grid = Grid::centred(nx, ny, dx, dy, 0.0, 0.0).unwrap();
        let gap = GapShape::Quadratic { a: p.a, b: p.b }
            .sample(&grid)
            .unwrap();
        let fft = solve_loads(
            FftInfluence::new(grid, &material).unwrap(),
            &gap,
            p.force,
            true,
        );
        // The direct operator evaluates Love's formula in every product (the slow oracle): the
        // force-prescribed solve only, to keep the test at seconds.
        let direct = solve_loads(
            DirectInfluence::new(grid, material).unwrap(),
            &gap,
            p.force,
            false,
        );
        let methods = [
            ("fft, force", &fft[0]),
            ("fft, approach", &fft[1]),
            ("direct, force", &direct[0]),
        ];
        for row in ROWS.iter().filter(|r| r.problem == index) {
            for (method, s) in methods {
                let got = match row.quantity {
                    Quantity::Approach => s.approach,
                    Quantity::MaxPressure => s.max_pressure,
                };
                checked += 1;
                if (got - row.value).abs() > row.tol {
                    failures.push(format!(
                        "{} [{method}] {:?}: {got:e}, {} gives {:e} ± {:e}",
                        p.name, row.quantity, row.source, row.value, row.tol
                    ));
                }
            }
        }
    }
    assert_eq!(checked, ROWS.len() * 3);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
