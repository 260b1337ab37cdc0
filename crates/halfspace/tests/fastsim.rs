//! FASTSIM against Kalker's linear theory (its small-creepage limit), the saturation limit
//! μF_n, and the exact half-space solution of the same Hertzian case.

use halfspace::*;

fn tractcurv(xi: f64, eta: f64, phi: f64) -> FastsimInput {
    // references.md §C4.1 tractcurv ellipse: a = 6.30360 mm, b = 12.60719 mm, F_n = 106.7 kN.
    FastsimInput {
        a: 6.30360e-3,
        b: 12.60719e-3,
        g: 82e9,
        nu: 0.28,
        mu: 0.3,
        normal_force: 106.7e3,
        xi,
        eta,
        phi,
    }
}

#[test]
fn small_creepage_converges_to_linear_theory() {
    // At ξ = 1e-7 nothing slips, and FASTSIM's flexibilities are chosen so that the continuum
    // limit is exactly the linear theory. The discrete error must fall with the strip count
    // (measured order printed; at least 1.4 between 20 and 80 strips) and be below 0.1 % on
    // 160 × 160.
    let input = tractcurv(1e-7, 0.0, 0.0);
    let (lin, _) = linear_forces(82e9, 0.28, input.a, input.b, input.xi, 0.0, 0.0).unwrap();
    let mut errors = Vec::new();
    for n in [20, 40, 80, 160] {
        let s = fastsim(&input, n, n).unwrap();
        assert_eq!(s.slip_elements, 0);
        errors.push((s.force_x / lin - 1.0).abs());
    }
    let order = (errors[0] / errors[2]).log2() / 2.0;
    println!("FASTSIM linear-limit errors {errors:?}, order {order:.2}");
    assert!(order > 1.4, "{order}");
    assert!(errors[3] < 1e-3);
    // Lateral creepage and spin, same limit (0.1 % on 160 × 160).
    let s = fastsim(&tractcurv(0.0, 1e-7, 0.0), 160, 160).unwrap();
    let (_, ly) = linear_forces(82e9, 0.28, input.a, input.b, 0.0, 1e-7, 0.0).unwrap();
    assert!((s.force_y / ly - 1.0).abs() < 1e-3, "{} {ly}", s.force_y);
    let s = fastsim(&tractcurv(0.0, 0.0, 1e-5), 160, 160).unwrap();
    let (_, ls) = linear_forces(82e9, 0.28, input.a, input.b, 0.0, 0.0, 1e-5).unwrap();
    assert!((s.force_y / ls - 1.0).abs() < 1e-3, "{} {ls}", s.force_y);
}

#[test]
fn large_creepage_saturates_at_mu_fn() {
    // Full slip: |p| = μ p₀ √(1 − x²/a² − y²/b²) everywhere, whose integral is μF_n; the
    // midpoint sum of the ellipse converges as n^(−3/2) — 0.5 % on 100 × 100.
    let s = fastsim(&tractcurv(0.5, 0.0, 0.0), 100, 100).unwrap();
    let ratio = -s.force_x / (0.3 * 106.7e3);
    println!("saturated FASTSIM {ratio}");
    assert_eq!(s.adhesion_elements, 0);
    assert!((ratio - 1.0).abs() < 5e-3, "{ratio}");
    assert!(s.frictional_power_per_speed > 0.0);
}

#[test]
fn fastsim_is_close_to_the_exact_solution() {
    // CONTACT's fastsim example shows FASTSIM (elliptic bound) within 0.01 μF_n of the exact
    // half-space solution (−0.60 vs −0.61, references.md §C3.6); FASTSIM's known error is largest
    // at intermediate creepage. We compare with our exact steady-rolling solution on the
    // tractcurv ellipse (44 × 44) at ξ = 1e-4, 3e-4, 1e-3 and require 0.02 μF_n: the published
    // 0.01 plus the ~1 % discretisation error of the 44 × 44 exact solution (measured: 0.0002,
    // 0.006, 0.014).
    let m = Material::from_combined(82e9, 0.28).unwrap();
    let shape = GapShape::Quadratic {
        a: 0.8,
        b: 0.281417,
    };
    let h = shape.hertz(&m, NormalLoad::Force(106.7e3)).unwrap();
    let grid = Grid::centred(44, 44, 2.1 * h.a / 44.0, 2.1 * h.b / 44.0, 0.0, 0.0).unwrap();
    let gap = shape.sample(&grid).unwrap();
    let n = NormalSolver::new(grid, m)
        .unwrap()
        .solve(&gap, NormalLoad::Force(106.7e3), &SolverOptions::default())
        .unwrap();
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let limit = 0.3 * 106.7e3;
    for xi in [1e-4, 3e-4, 1e-3] {
        let exact = ts
            .steady_rolling(
                &n.pressure,
                0.3,
                RollingLoad::Creepages(Creepages {
                    xi,
                    eta: 0.0,
                    phi: 0.0,
                }),
                &TangentialOptions::default(),
            )
            .unwrap();
        let mut input = tractcurv(xi, 0.0, 0.0);
        input.a = h.a;
        input.b = h.b;
        let fs = fastsim(&input, 100, 100).unwrap();
        let d = (fs.force_x - exact.force_x) / limit;
        println!(
            "xi {xi}: exact {} fastsim {} diff {d:.4}",
            exact.force_x / limit,
            fs.force_x / limit
        );
        assert!(d.abs() < 0.02, "{d}");
    }
}

#[test]
fn invalid_input_names_the_parameter() {
    let mut input = tractcurv(1e-3, 0.0, 0.0);
    input.mu = -1.0;
    assert!(
        fastsim(&input, 10, 10)
            .unwrap_err()
            .to_string()
            .contains("mu")
    );
    let mut input = tractcurv(1e-3, 0.0, 0.0);
    input.xi = f64::NAN;
    assert!(
        fastsim(&input, 10, 10)
            .unwrap_err()
            .to_string()
            .contains("creepage_x")
    );
}
