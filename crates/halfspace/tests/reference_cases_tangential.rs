//! The reference-case harness of the tangential solver: one table of published values for the
//! Cattaneo shift problem (problem, quantity, value, tolerance, source) run with every method —
//! the tangential solver over the FFT influence operator and over the direct O(n²) operator.
//!
//! The problem is CONTACT's `cattaneo` example (references.md §C4.4): G = 200 N/mm², ν = 0.42,
//! R = 50 mm (A = B = 10 /m), F_n = 9.1954 N (a = 1 mm), μ = 0.4, a 19 × 19 grid with 15
//! elements across the diameter, F_x = −0.875 μF_n prescribed (θ = ½). Tolerances: CONTACT's
//! printed shift has 4 digits (5e-4 relative) and its element counts are exact on the same
//! discretisation; Cattaneo–Mindlin's continuum shift W_x = 3μF_n(2 − ν)(1 − θ²)/(8aG) differs
//! by the 19 × 19 discretisation error (CONTACT shows the same), allowed 5e-3 relative.

use halfspace::{
    DirectTangentialInfluence, FftTangentialInfluence, GapShape, Grid, Material, NormalLoad,
    NormalSolver, ShiftLoad, SolverOptions, TangentialInfluenceOperator, TangentialOptions,
    TangentialSolution, TangentialSolver,
};

const MU: f64 = 0.4;
const FN: f64 = 9.1954;
const G: f64 = 2e8;
const NU: f64 = 0.42;

/// A quantity of the tangential solution.
#[derive(Clone, Copy, Debug)]
enum Quantity {
    /// Rigid shift W_x \[m\].
    ShiftX,
    /// Elements in adhesion.
    Adhesion,
    /// Elements in slip.
    Slip,
}

/// One row: quantity, value, absolute tolerance, source.
struct Row(Quantity, f64, f64, &'static str);

fn rows() -> Vec<Row> {
    let theta: f64 = 0.5;
    let continuum = 3.0 * MU * FN * (2.0 - NU) * (1.0 - theta * theta) / (8.0 * 1e-3 * G);
    vec![
        Row(
            Quantity::ShiftX,
            8.155e-6,
            5e-4 * 8.155e-6,
            "CONTACT cattaneo: shift 8.155e-3 mm",
        ),
        Row(
            Quantity::ShiftX,
            continuum,
            5e-3 * continuum,
            "Cattaneo–Mindlin continuum shift",
        ),
        Row(
            Quantity::Adhesion,
            45.0,
            0.0,
            "CONTACT cattaneo: 45 elements in adhesion",
        ),
        Row(
            Quantity::Slip,
            132.0,
            0.0,
            "CONTACT cattaneo: 132 elements in slip",
        ),
    ]
}

fn shift_with<T: TangentialInfluenceOperator>(op: T, pressure: &[f64]) -> TangentialSolution {
    let mut solver = TangentialSolver::with_operator(op).unwrap();
    solver
        .shift(
            pressure,
            MU,
            ShiftLoad::Forces {
                fx: -0.875 * MU * FN,
                fy: 0.0,
            },
            &TangentialOptions::default(),
        )
        .unwrap()
}

#[test]
fn every_method_reproduces_the_cattaneo_case() {
    let material = Material::from_combined(G, NU).unwrap();
    let d = 2e-3 / 15.0;
    let grid = Grid::centred(19, 19, d, d, 0.0, 0.0).unwrap();
    let gap = GapShape::Quadratic { a: 10.0, b: 10.0 }
        .sample(&grid)
        .unwrap();
    let pressure = NormalSolver::new(grid, material)
        .unwrap()
        .solve(&gap, NormalLoad::Force(FN), &SolverOptions::default())
        .unwrap()
        .pressure;
    let methods = [
        (
            "fft",
            shift_with(
                FftTangentialInfluence::new(grid, &material).unwrap(),
                &pressure,
            ),
        ),
        (
            "direct",
            shift_with(
                DirectTangentialInfluence::new(grid, material).unwrap(),
                &pressure,
            ),
        ),
    ];
    let mut failures = Vec::new();
    let table = rows();
    for (method, s) in &methods {
        for Row(quantity, value, tol, source) in &table {
            let got = match quantity {
                Quantity::ShiftX => s.shift.0,
                Quantity::Adhesion => s.adhesion_elements as f64,
                Quantity::Slip => s.slip_elements as f64,
            };
            if (got - value).abs() > *tol {
                failures.push(format!(
                    "[{method}] {quantity:?}: {got:e}, {source} gives {value:e} ± {tol:e}"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
