//! Test problems shared by the halfspace integration tests (`mod support;`).

use halfspace::{Body, GapShape, Grid, Material, NormalLoad};

/// A rigid sphere (R = 10 mm) pressed into an elastic body (E = 1 GPa, ν = 0.2: K = −0.3) on
/// an n × n grid 2.6 Hertz radii wide (Hertz force 50 N): grid, material and gap.
pub fn ball_on_soft(n: usize) -> (Grid, Material, Vec<f64>) {
    let m = Material::combine(Body::Rigid, Body::elastic(1e9, 0.2).unwrap()).unwrap();
    let shape = GapShape::Quadratic { a: 50.0, b: 50.0 };
    let h = shape.hertz(&m, NormalLoad::Force(50.0)).unwrap();
    let d = 2.6 * h.a / n as f64;
    let grid = Grid::centred(n, n, d, d, 0.0, 0.0).unwrap();
    let gap = shape.sample(&grid).unwrap();
    (grid, m, gap)
}
