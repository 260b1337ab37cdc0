//! Tangential and coupling influence coefficients against an independent quadrature of
//! Cerruti's and Boussinesq's point-load solutions, and the FFT operator against the direct
//! operator's sums.

mod support;

use halfspace::influence::tangential_influence;
use halfspace::operator::Update;
use halfspace::{
    Body, DirectTangentialInfluence, FftTangentialInfluence, Grid, Material,
    TangentialInfluenceOperator, TangentialKernel,
};
use support::gauss_legendre;

/// 24-point Gauss–Legendre product rule over the element [−dx/2, dx/2] × [−dy/2, dy/2]
/// of the point-load density f(X, Y) at offset (ox, oy).
fn quadrature(f: impl Fn(f64, f64) -> f64, ox: f64, oy: f64, dx: f64, dy: f64) -> f64 {
    // Nodes and weights by Newton on the Legendre polynomial (independent of the primitives).
    let nodes = gauss_legendre(24);
    let mut s = 0.0;
    for &(u, wu) in &nodes {
        for &(v, wv) in &nodes {
            let (xi, eta) = (0.5 * dx * u, 0.5 * dy * v);
            s += wu * wv * f(ox - xi, oy - eta);
        }
    }
    s * 0.25 * dx * dy
}

#[test]
fn coefficients_integrate_the_point_load_solutions() {
    // Dissimilar bodies so that K ≠ 0 (references.md §C3.1): steel on a softer polymer-like body.
    let m = Material::combine(
        Body::elastic(210e9, 0.3).unwrap(),
        Body::elastic(3e9, 0.4).unwrap(),
    )
    .unwrap();
    assert!(m.k.abs() > 0.01);
    let pg = std::f64::consts::PI * m.g;
    let nu = m.nu;
    let (dx, dy) = (1.0e-3, 0.7e-3);
    // Observation points one to four elements away: the density is smooth over the element
    // and the 24-point rule is exact to ~1e-10 relative there.
    for (ox, oy) in [
        (2.0e-3, 0.0),
        (1.5e-3, 1.4e-3),
        (-3.0e-3, 2.1e-3),
        (0.0, -2.8e-3),
    ] {
        let a = tangential_influence(&m, ox, oy, dx, dy);
        let r = |x: f64, y: f64| x.hypot(y);
        let xx = quadrature(
            |x, y| ((1.0 - nu) / r(x, y) + nu * x * x / r(x, y).powi(3)) / pg,
            ox,
            oy,
            dx,
            dy,
        );
        let yy = quadrature(
            |x, y| ((1.0 - nu) / r(x, y) + nu * y * y / r(x, y).powi(3)) / pg,
            ox,
            oy,
            dx,
            dy,
        );
        let xy = quadrature(|x, y| nu * x * y / r(x, y).powi(3) / pg, ox, oy, dx, dy);
        let xn = quadrature(|x, y| -m.k * x / r(x, y).powi(2) / pg, ox, oy, dx, dy);
        let yn = quadrature(|x, y| -m.k * y / r(x, y).powi(2) / pg, ox, oy, dx, dy);
        let scale = xx.abs();
        for (name, got, want) in [
            ("xx", a.xx, xx),
            ("yy", a.yy, yy),
            ("xy", a.xy, xy),
            ("xn", a.xn, xn),
            ("yn", a.yn, yn),
        ] {
            assert!(
                (got - want).abs() <= 1e-8 * scale,
                "{name} at ({ox}, {oy}): {got:e} vs {want:e}"
            );
        }
    }
}

#[test]
fn own_element_values() {
    // At the element's own centre the Love brackets of A_xx for a square element are
    // (2 − ν)·2 s ln(1 + √2) (half of references.md's 4 s ln(1+√2) per term), A_xy = 0 by symmetry.
    let m = Material::from_combined(1.0, 0.28).unwrap();
    let s = 1.0;
    let a = tangential_influence(&m, 0.0, 0.0, s, s);
    let expected = (2.0 - 0.28) * 2.0 * s * (1.0 + 2f64.sqrt()).ln() / std::f64::consts::PI;
    assert!(
        (a.xx - expected).abs() < 1e-14 * expected,
        "{} {}",
        a.xx,
        expected
    );
    assert!((a.yy - a.xx).abs() < 1e-14 * expected);
    assert!(a.xy.abs() < 1e-15);
    assert_eq!(a.xn, 0.0);
}

#[test]
fn fft_operator_matches_direct_sums_with_shifted_kernels() {
    // The steady-rolling kernel C_v (observation points shifted by δq) is not symmetric;
    // the FFT product must still equal the direct double sum of the direct operator.
    let m = Material::from_combined(82e9, 0.28).unwrap();
    for (nx, ny, dx, dy) in [(7usize, 1usize, 4e-5, 0.2), (5, 4, 1e-3, 1.5e-3)] {
        let grid = Grid::centred(nx, ny, dx, dy, 0.0, 0.0).unwrap();
        let kernel = TangentialKernel::Shifted(0.7 * dx);
        let mut fast = FftTangentialInfluence::new(grid, &m).unwrap();
        let mut slow = DirectTangentialInfluence::new(grid, m).unwrap();
        fast.prepare(kernel);
        let p: Vec<f64> = (0..nx * ny)
            .map(|k| (k as f64 * 0.37).sin() + 0.3)
            .collect();
        let q: Vec<f64> = (0..nx * ny)
            .map(|k| (k as f64 * 0.91).cos() - 0.2)
            .collect();
        let n = nx * ny;
        let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
        let (mut vx, mut vy) = (vec![0.0; n], vec![0.0; n]);
        fast.traction_product(kernel, Update::Set, (&p, &q), (&mut ux, &mut uy));
        slow.traction_product(kernel, Update::Set, (&p, &q), (&mut vx, &mut vy));
        for i in 0..n {
            for (a, b) in [(ux[i], vx[i]), (uy[i], vy[i])] {
                assert!(
                    (a - b).abs() <= 1e-12 * b.abs().max(1e-14),
                    "{nx}x{ny} {i}: {a} {b}"
                );
            }
        }
    }
}
