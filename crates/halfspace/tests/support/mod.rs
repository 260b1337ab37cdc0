//! Test problems and quadrature shared by the halfspace integration tests (`mod support;`).
// Each test crate uses a subset of these helpers.
#![allow(dead_code)]

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

/// Gauss–Legendre nodes and weights on [−1, 1] by Newton's method on P_n (independent of the
/// code under test).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (1..=n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}
