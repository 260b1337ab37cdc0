//! Transient rolling with forces prescribed: CONTACT's "Cattaneo → Carter" example
//! (examples/catt_to_cart.inp, Kalker 1990 §5.2.2.5; references.md §C4.4).

use halfspace::*;

#[test]
fn cattaneo_to_carter_creepage_history() {
    // A circle of radius 3.5 mm (28 elements across), G = 1 N/mm² (1e6 Pa), ν = 0.28,
    // μ = 0.4013, F_n = 0.4705 N, F_x = −0.657 μF_n, δx = δy = δq = 0.25 mm, A = B = 2.963 /m,
    // on a 34 × 33 grid moving with the contact (T = 2), an element centred on the first point
    // of contact. After a Cattaneo start, each rolling step finds the creepage that keeps F_x.
    // CONTACT prints 1.824e-3, 1.882e-3, 1.955e-3, 2.050e-3 for the first steps: 4 digits,
    // so the tolerance is 0.05 % (half a unit in the last digit plus Newton's 1e-6 μF_n).
    let m = Material::from_combined(1e6, 0.28).unwrap();
    let d = 0.25e-3;
    let grid = Grid::new(34, 33, d, d, -16.5 * d, -16.5 * d).unwrap();
    let gap = GapShape::Quadratic { a: 2.963, b: 2.963 }
        .sample(&grid)
        .unwrap();
    let n = NormalSolver::new(grid, m)
        .unwrap()
        .solve(&gap, NormalLoad::Force(0.4705), &SolverOptions::default())
        .unwrap();
    let mu = 0.4013;
    let fx = -0.657 * mu * 0.4705;
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let opts = TangentialOptions::default();
    let start = ts
        .shift(&n.pressure, mu, ShiftLoad::Forces { fx, fy: 0.0 }, &opts)
        .unwrap();
    let (mut px, mut py) = (start.traction_x, start.traction_y);
    let expected = [1.824e-3, 1.882e-3, 1.955e-3, 2.050e-3];
    for (k, want) in expected.iter().enumerate() {
        let s = ts
            .transient_step_forces(&n.pressure, mu, (&px, &py), d, (fx, 0.0), 0.0, &opts)
            .unwrap();
        println!(
            "step {}: xi = {:.5e} (CONTACT {want:e})",
            k + 1,
            s.creepages.xi
        );
        assert!((s.force_x - fx).abs() < 1e-5 * mu * 0.4705);
        assert!(
            (s.creepages.xi / want - 1.0).abs() < 5e-4,
            "step {}: {}",
            k + 1,
            s.creepages.xi
        );
        px = s.traction_x;
        py = s.traction_y;
    }
}

#[test]
fn transient_input_errors() {
    let m = Material::from_combined(1e6, 0.28).unwrap();
    let grid = Grid::centred(8, 8, 1e-3, 1e-3, 0.0, 0.0).unwrap();
    let p = vec![1.0; grid.len()];
    let z = vec![0.0; grid.len()];
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let o = TangentialOptions::default();
    let e = ts
        .transient_step_forces(&p, 0.3, (&z, &z), 0.0, (0.1, 0.0), 0.0, &o)
        .unwrap_err();
    assert!(e.to_string().contains("delta_q"), "{e}");
    let motion = StepMotion {
        delta_q: -1.0,
        ..Default::default()
    };
    let e = ts
        .transient_step(&p, 0.3, (&z, &z), motion, &o)
        .unwrap_err();
    assert!(e.to_string().contains("delta_q"), "{e}");
    let e = ts
        .transient_step(&p, 0.3, (&z[1..], &z), StepMotion::default(), &o)
        .unwrap_err();
    assert!(matches!(e, ContactError::SizeMismatch { .. }));
}
