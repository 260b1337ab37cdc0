//! The contact solver as a library: a steel ball pressed on a steel half-space with 1 kN,
//! solved on a 48 × 48 grid and compared with Hertz's closed form. Run with
//! `cargo run --release -p sim --example library_contact`.

use halfspace::{GapShape, Material, NormalLoad, NormalSolver, SolverOptions, auto_grid};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let material = Material::identical(210e9, 0.3)?; // E [Pa], ν of both bodies
    let shape = GapShape::Sphere { radius: 0.01 }; // gap of a 10 mm ball [m]
    let load = NormalLoad::Force(1000.0); // total force [N]
    let grid = auto_grid(&shape, &material, load, 48)?; // 48 × 48 elements around the patch
    let mut solver = NormalSolver::new(grid, material)?;
    let solution = solver.solve(&shape.sample(&grid)?, load, &SolverOptions::default())?;
    let hertz = shape
        .hertz(&material, load)
        .expect("a sphere has Hertz's solution");
    println!(
        "approach {:.4e} m (Hertz {:.4e} m), max pressure {:.4e} Pa (Hertz {:.4e} Pa), {} iterations",
        solution.approach,
        hertz.approach,
        solution.max_pressure,
        hertz.max_pressure,
        solution.iterations
    );
    // 48 elements across the patch resolve the approach to well within 1 %
    // (docs/verification.md: measured orders of convergence on Hertz cases).
    assert!((solution.approach / hertz.approach - 1.0).abs() < 0.01);
    Ok(())
}
