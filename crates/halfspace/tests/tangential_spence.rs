//! Dissimilar materials under increasing normal load with friction: CONTACT's spence35
//! example (Kalker 1990, Fig. 5.25; CONTACT's examples/spence35.inp and .ref_out).

use halfspace::*;

#[test]
fn spence_compression_in_35_stages() {
    // Upper body G₁ = 0.5 N/mm², ν = 0; lower body G₂ = 1e5 N/mm² ("rigid"), ν = 0; so
    // G = 1 N/mm², K = 0.5. Gap 0.004116 (x² + y²) /mm, μ = 0.2986, 45 × 45 elements of
    // 0.2 mm from −4.4999 mm, F_n = (k/45)³ N in stage k = 1 … 35, each stage a coupled shift
    // step from the previous stage's tractions and pressure (Panagiotopoulos' process).
    // CONTACT's reference output (4 digits; element counts exact):
    //   stage 6:  approach 2.901e-3 mm, p_max 3.941e-3 N/mm², 29 in contact, 5 adhesion, 24 slip
    //   stage 35: approach 9.874e-2 mm, p_max 2.392e-2 N/mm², 921 in contact, 225 adhesion, 696 slip
    // Tolerance 0.05 % on approach and p_max (the printed digits), counts exact.
    let m = Material::combine(
        Body::elastic(1.0e6, 0.0).unwrap(),
        Body::elastic(2.0e11, 0.0).unwrap(),
    )
    .unwrap();
    assert!((m.k - 0.5).abs() < 1e-5);
    let d = 0.2e-3;
    let grid = Grid::new(45, 45, d, d, -4.4999e-3, -4.4999e-3).unwrap();
    let gap = GapShape::Quadratic { a: 4.116, b: 4.116 }
        .sample(&grid)
        .unwrap();
    let mut ns = NormalSolver::new(grid, m).unwrap();
    let mut ts = TangentialSolver::new(grid, m).unwrap();
    let mu = 0.2986;
    let n = grid.len();
    let (mut px, mut py, mut pn) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for k in 1..=35 {
        let fnk = (k as f64 / 45.0).powi(3);
        let c = solve_coupled_step(
            &mut ns,
            &mut ts,
            &gap,
            NormalLoad::Force(fnk),
            mu,
            (&px, &py),
            &pn,
            StepMotion::default(),
            &SolverOptions::default(),
            &TangentialOptions::default(),
            &CoupledOptions::default(),
        )
        .unwrap();
        let expected = match k {
            6 => Some((2.901e-6, 3941.0, 29, 5, 24)),
            35 => Some((9.874e-5, 23920.0, 921, 225, 696)),
            _ => None,
        };
        if let Some((approach, pmax, ncon, nadh, nslip)) = expected {
            println!(
                "stage {k}: approach {:e} m, p_max {} Pa, {} / {} / {}, {} outer iterations",
                c.normal.approach,
                c.normal.max_pressure,
                c.normal.elements_in_contact,
                c.tangential.adhesion_elements,
                c.tangential.slip_elements,
                c.outer_iterations
            );
            assert!((c.normal.approach / approach - 1.0).abs() < 5e-4);
            assert!((c.normal.max_pressure / pmax - 1.0).abs() < 5e-4);
            assert_eq!(c.normal.elements_in_contact, ncon);
            assert_eq!(c.tangential.adhesion_elements, nadh);
            assert_eq!(c.tangential.slip_elements, nslip);
        }
        // No net tangential force apart from the grid's 1e-4 mm offset (CONTACT prints
        // F_x/(μF_n) up to 1e-4 for the same reason).
        assert!(c.tangential.force_x.abs() < 1e-3 * mu * fnk, "stage {k}");
        px = c.tangential.traction_x;
        py = c.tangential.traction_y;
        pn = c.normal.pressure;
    }
}
