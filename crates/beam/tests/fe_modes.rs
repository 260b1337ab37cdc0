//! Finite-element beam against analytic modes (convergence rate), the two-span frequency
//! equation, closed-form statics of a stepped cantilever, spring/mass limits and scaling identities.

use beam::{
    AnalyticBeam, Derivative, FeBeam, FeModes, ModalBasis, PointMass, PointSupport, Quadrature,
    QuadratureRule, Section, Support, SupportKind, UniformBeam,
};

const L: f64 = 25.0;
const EI: f64 = 2.87e9 * 2.90;
const RHO_A: f64 = 2303.0;

fn uniform(length: f64) -> Vec<Section> {
    vec![Section {
        length,
        bending_stiffness: EI,
        mass_per_length: RHO_A,
    }]
}

fn supports_for(support: Support) -> Vec<PointSupport> {
    let s = |x, kind| PointSupport { x, kind };
    match support {
        Support::SimplySupported => vec![s(0.0, SupportKind::Pinned), s(L, SupportKind::Pinned)],
        Support::ClampedClamped => vec![s(0.0, SupportKind::Clamped), s(L, SupportKind::Clamped)],
        Support::ClampedFree => vec![s(0.0, SupportKind::Clamped)],
        Support::ClampedPinned => vec![s(0.0, SupportKind::Clamped), s(L, SupportKind::Pinned)],
        Support::FreeFree => vec![],
    }
}

fn fe_modes(support: Support, n_el: usize, n_modes: usize) -> FeModes {
    FeBeam::new(&uniform(L), &supports_for(support), &[], n_el)
        .unwrap()
        .modes(n_modes)
        .unwrap()
}

/// Eigenvalue error of Hermite cubics is O(h⁴) (Strang & Fix 1973, §6.3: error h^(2(k−m)) with
/// k = 4, m = 2). Measure log2(e_h / e_(h/2)) for modes 1–3 and meshes 4 → 32 elements; assert the
/// mean order of the last two refinements within 4 ± 0.3.
#[test]
fn eigenvalues_converge_at_fourth_order() {
    let beam = UniformBeam::new(L, EI, RHO_A).unwrap();
    for support in [
        Support::SimplySupported,
        Support::ClampedClamped,
        Support::ClampedFree,
        Support::ClampedPinned,
    ] {
        let exact = AnalyticBeam::new(support, beam, 3).unwrap();
        for j in 0..3 {
            let w = exact.circular_frequencies()[j];
            let errors: Vec<f64> = [4, 8, 16, 32]
                .iter()
                .map(|&n| {
                    let fe = fe_modes(support, n, 3).circular_frequencies()[j];
                    (fe * fe - w * w) / (w * w)
                })
                .collect();
            assert!(
                errors.iter().all(|e| *e > 0.0),
                "{support:?} mode {j}: FE must be stiffer (Rayleigh-Ritz)"
            );
            let orders: Vec<f64> = errors.windows(2).map(|p| (p[0] / p[1]).log2()).collect();
            let order = 0.5 * (orders[1] + orders[2]);
            eprintln!(
                "{support:?} mode {}: rel. eigenvalue errors {errors:?}, orders {orders:.3?}",
                j + 1
            );
            assert!(
                (order - 4.0).abs() < 0.3,
                "{support:?} mode {j}: order {order}"
            );
        }
    }
}

/// With 100 elements (h = L/100) the FE shapes, slopes and curvatures match the analytic
/// mass-normalised shapes. Interpolation errors with k = β_j/L: shape O((kh)⁴) (tolerance 1e-5 of
/// max|w|), slope O((kh)³) (tolerance (kh)³/10), curvature piecewise linear, O((kh)²) with
/// constant 1/8 at element midpoints (tolerance (kh)²/4); modes 1–5 for each support; free–free
/// skips its rigid modes (degenerate eigenvalue 0, any rotation of them is valid).
#[test]
fn fe_shapes_match_analytic_shapes() {
    let beam = UniformBeam::new(L, EI, RHO_A).unwrap();
    for support in [
        Support::SimplySupported,
        Support::ClampedClamped,
        Support::ClampedFree,
        Support::ClampedPinned,
        Support::FreeFree,
    ] {
        let r = support.rigid_modes();
        let exact = AnalyticBeam::new(support, beam, 5 + r).unwrap();
        let fe = fe_modes(support, 100, 5 + r);
        for j in r..5 + r {
            let xs: Vec<f64> = (0..=250).map(|i| L * i as f64 / 250.0).collect();
            let sign = if exact.shape(j, 0.3 * L).unwrap() * fe.shape(j, 0.3 * L).unwrap() < 0.0 {
                -1.0
            } else {
                1.0
            };
            let kh = exact.roots()[j] / 100.0;
            for (d, tol) in [
                (Derivative::Shape, 1e-5),
                (Derivative::Slope, kh.powi(3) / 10.0),
                (Derivative::Curvature, kh * kh / 4.0),
            ] {
                let max = xs
                    .iter()
                    .map(|&x| exact.mode_value(j, x, d).unwrap().abs())
                    .fold(0.0, f64::max);
                let err = xs
                    .iter()
                    .map(|&x| {
                        (sign * fe.mode_value(j, x, d).unwrap()
                            - exact.mode_value(j, x, d).unwrap())
                        .abs()
                    })
                    .fold(0.0, f64::max);
                assert!(
                    err < tol * max,
                    "{support:?} mode {j} {d:?}: {:e}",
                    err / max
                );
            }
        }
    }
}

/// Two equal spans, pinned at 0, L, 2L (continuous beam): mode 1 is antisymmetric with the
/// simply supported span frequency (βL = π); mode 2 is symmetric, each span clamped–pinned
/// (βL = 3.9266023120479, references.md §D1.6). 40 elements per span: O(h⁴) error ≈ 1e-8; tolerance 1e-6.
#[test]
fn two_span_continuous_beam() {
    let supports = [
        PointSupport {
            x: 0.0,
            kind: SupportKind::Pinned,
        },
        PointSupport {
            x: L,
            kind: SupportKind::Pinned,
        },
        PointSupport {
            x: 2.0 * L,
            kind: SupportKind::Pinned,
        },
    ];
    let fe = FeBeam::new(&uniform(2.0 * L), &supports, &[], 80)
        .unwrap()
        .modes(2)
        .unwrap();
    let scale = (EI / (RHO_A * L.powi(4))).sqrt();
    let w1 = std::f64::consts::PI.powi(2) * scale;
    let w2 = 3.9266023120479187_f64.powi(2) * scale;
    let (e1, e2) = (
        (fe.circular_frequencies()[0] / w1 - 1.0).abs(),
        (fe.circular_frequencies()[1] / w2 - 1.0).abs(),
    );
    eprintln!("two-span: rel. errors {e1:e}, {e2:e}");
    assert!(e1 < 1e-6 && e2 < 1e-6);
    // Mode 1 antisymmetric about the middle support, mode 2 symmetric (1e-8 of max).
    let w = |j, x| fe.shape(j, x).unwrap();
    assert!((w(0, 0.4 * L) + w(0, 1.6 * L)).abs() < 1e-8 * w(0, 0.4 * L).abs());
    assert!((w(1, 0.4 * L) - w(1, 1.6 * L)).abs() < 1e-8 * w(1, 0.4 * L).abs());
}

/// A stepped cantilever (EI₁ on [0, a], EI₂ on [a, L]) under a tip force P has the closed-form tip
/// deflection δ = P[L³ − (L−a)³]/(3EI₁) + P(L−a)³/(3EI₂) (unit-load method). Hermite elements are
/// nodally exact for piecewise-constant EI, so the tolerance is rounding: 1e-9 relative.
#[test]
fn stepped_cantilever_static_tip_deflection() {
    let (a, ei1, ei2, p) = (10.0, 3.0 * EI, EI, 1e5);
    let sections = [
        Section {
            length: a,
            bending_stiffness: ei1,
            mass_per_length: RHO_A,
        },
        Section {
            length: L - a,
            bending_stiffness: ei2,
            mass_per_length: RHO_A,
        },
    ];
    let fe = FeBeam::new(
        &sections,
        &[PointSupport {
            x: 0.0,
            kind: SupportKind::Clamped,
        }],
        &[],
        7,
    )
    .unwrap();
    let tip = fe
        .static_deflection(&[(L, p)])
        .unwrap()
        .eval(L, Derivative::Shape)
        .unwrap();
    let exact = p * (L.powi(3) - (L - a).powi(3)) / (3.0 * ei1) + p * (L - a).powi(3) / (3.0 * ei2);
    eprintln!("stepped cantilever: tip {tip:e} vs {exact:e}");
    assert!((tip / exact - 1.0).abs() < 1e-9);
    // Bending moment M = −EI w'' at the root equals −P L (statics), exact for the cubic interpolation
    // in the first element (the moment is linear in x): 1e-8.
    let curv = fe
        .static_deflection(&[(L, p)])
        .unwrap()
        .eval(0.0, Derivative::Curvature)
        .unwrap();
    assert!(
        (ei1 * curv / (p * L) - 1.0).abs() < 1e-8,
        "{}",
        ei1 * curv / (p * L)
    );
}

/// Piecewise-constant sections that are all equal reproduce the uniform beam (same mesh: the
/// breakpoints lie on the uniform grid), and scaling EI by 4 doubles every ω while scaling ρA by 4
/// halves it (ω² = eig(K, M) is homogeneous of degree 1 in K and −1 in M): tolerance 1e-10.
#[test]
fn sections_and_scaling_identities() {
    let split: Vec<Section> = [5.0, 7.5, 12.5]
        .iter()
        .map(|&length| Section {
            length,
            bending_stiffness: EI,
            mass_per_length: RHO_A,
        })
        .collect();
    let sup = supports_for(Support::ClampedPinned);
    let one = FeBeam::new(&uniform(L), &sup, &[], 50)
        .unwrap()
        .modes(6)
        .unwrap();
    let three = FeBeam::new(&split, &sup, &[], 50)
        .unwrap()
        .modes(6)
        .unwrap();
    let scaled = |k: f64, m: f64| {
        let s: Vec<Section> = split
            .iter()
            .map(|s| Section {
                bending_stiffness: k * s.bending_stiffness,
                mass_per_length: m * s.mass_per_length,
                ..*s
            })
            .collect();
        FeBeam::new(&s, &sup, &[], 50).unwrap().modes(6).unwrap()
    };
    let stiff = scaled(4.0, 1.0);
    let heavy = scaled(1.0, 4.0);
    for j in 0..6 {
        let w = one.circular_frequencies()[j];
        assert!((three.circular_frequencies()[j] / w - 1.0).abs() < 1e-10);
        assert!((stiff.circular_frequencies()[j] / (2.0 * w) - 1.0).abs() < 1e-10);
        assert!((heavy.circular_frequencies()[j] / (0.5 * w) - 1.0).abs() < 1e-10);
        // Mass normalisation: shapes of the heavy beam are those of the light one divided by 2.
        let (a, b) = (one.shape(j, 7.0).unwrap(), heavy.shape(j, 7.0).unwrap());
        assert!((b - 0.5 * a).abs() < 1e-8 * a.abs().max(1e-3 * one.shape(j, 11.0).unwrap().abs()));
    }
}

/// Free beam on two soft end springs k: bounce ω² = 2k/(ρA L) and pitch ω² = 6k/(ρA L) (rigid beam
/// on springs) when these are far below the first bending frequency; the relative correction is
/// O(ω²_rigid/ω²_bend) ≈ 1e-6 here, tolerance 1e-4. Very stiff clamping springs at x = 0 approach
/// the cantilever: error O(EI/(k L³)) = 1e-7, tolerance 1e-5.
#[test]
fn elastic_supports_limits() {
    let k = 1e-3 * EI / L.powi(3);
    let springs = [
        PointSupport {
            x: 0.0,
            kind: SupportKind::Spring {
                translational: k,
                rotational: 0.0,
            },
        },
        PointSupport {
            x: L,
            kind: SupportKind::Spring {
                translational: k,
                rotational: 0.0,
            },
        },
    ];
    let fe = FeBeam::new(&uniform(L), &springs, &[], 40)
        .unwrap()
        .modes(3)
        .unwrap();
    let bounce = (2.0 * k / (RHO_A * L)).sqrt();
    let pitch = (6.0 * k / (RHO_A * L)).sqrt();
    let w = fe.circular_frequencies();
    eprintln!(
        "springs: bounce {} vs {bounce}, pitch {} vs {pitch}",
        w[0], w[1]
    );
    assert!((w[0] / bounce - 1.0).abs() < 1e-4 && (w[1] / pitch - 1.0).abs() < 1e-4);

    let stiff = [PointSupport {
        x: 0.0,
        kind: SupportKind::Spring {
            translational: 1e7 * EI / L.powi(3),
            rotational: 1e7 * EI / L,
        },
    }];
    let fe = FeBeam::new(&uniform(L), &stiff, &[], 40)
        .unwrap()
        .modes(2)
        .unwrap();
    let cf = fe_modes(Support::ClampedFree, 40, 2);
    for j in 0..2 {
        let rel = (fe.circular_frequencies()[j] / cf.circular_frequencies()[j] - 1.0).abs();
        assert!(rel < 1e-5, "mode {j}: {rel:e}");
    }
}

/// A heavy point mass M at midspan of a light simply supported beam: ω² → 48EI/(M L³)
/// (massless-beam spring 48EI/L³); with ρA L = 1e-4 M the beam mass adds ≈ 0.5·1e-4 relative to ω²,
/// tolerance 1e-3. Also checks ∫ρA w_i w_j + M w_i w_j(x_M) = δ_ij (Gauss on each element, exact
/// for the cubic interpolants) to 1e-10.
#[test]
fn point_mass_limit_and_mass_orthonormality() {
    let m = 1e4 * RHO_A * L;
    let fe_beam = FeBeam::new(
        &uniform(L),
        &supports_for(Support::SimplySupported),
        &[PointMass {
            x: 0.5 * L,
            mass: m,
            rotary_inertia: 0.0,
        }],
        20,
    )
    .unwrap();
    let fe = fe_beam.modes(4).unwrap();
    let exact = (48.0 * EI / (m * L.powi(3))).sqrt();
    let rel = fe.circular_frequencies()[0] / exact - 1.0;
    eprintln!("point mass: rel. deviation {rel:e}");
    assert!(rel.abs() < 1e-3);
    let q = Quadrature::new(
        QuadratureRule::GaussLegendre {
            points: 4,
            panels: 20,
        },
        0.0,
        L,
    )
    .unwrap();
    for i in 0..4 {
        for j in 0..4 {
            let integral =
                q.integrate(|x| RHO_A * fe.shape(i, x).unwrap() * fe.shape(j, x).unwrap());
            let lumped = m * fe.shape(i, 0.5 * L).unwrap() * fe.shape(j, 0.5 * L).unwrap();
            let target = if i == j { 1.0 } else { 0.0 };
            assert!(
                (integral + lumped - target).abs() < 1e-10,
                "({i},{j}): {}",
                integral + lumped
            );
        }
    }
}

/// Free–free FE: two zero-frequency rigid modes (|ω| < 1e-4 ω₃, rounding of K's null space
/// through the reduction), the first elastic ω within the O(h⁴) error (1e-6 at 60 elements) of
/// the analytic CC/FF root.
#[test]
fn free_free_rigid_modes() {
    let fe = fe_modes(Support::FreeFree, 60, 3);
    let exact = AnalyticBeam::new(
        Support::FreeFree,
        UniformBeam::new(L, EI, RHO_A).unwrap(),
        3,
    )
    .unwrap();
    let w = fe.circular_frequencies();
    assert!(w[0] < 1e-4 * w[2] && w[1] < 1e-4 * w[2], "{w:?}");
    assert!((w[2] / exact.circular_frequencies()[2] - 1.0).abs() < 1e-6);
}

#[test]
fn invalid_fe_input() {
    assert!(FeBeam::new(&[], &[], &[], 10).is_err());
    assert!(FeBeam::new(&uniform(L), &[], &[], 0).is_err());
    let bad = [Section {
        length: L,
        bending_stiffness: -1.0,
        mass_per_length: RHO_A,
    }];
    assert!(FeBeam::new(&bad, &[], &[], 10).is_err());
    let outside = [PointSupport {
        x: 30.0,
        kind: SupportKind::Pinned,
    }];
    assert!(FeBeam::new(&uniform(L), &outside, &[], 10).is_err());
    let neg_mass = [PointMass {
        x: 1.0,
        mass: -1.0,
        rotary_inertia: 0.0,
    }];
    assert!(FeBeam::new(&uniform(L), &[], &neg_mass, 10).is_err());
    let fe = FeBeam::new(&uniform(L), &supports_for(Support::SimplySupported), &[], 4).unwrap();
    assert!(fe.modes(0).is_err());
    assert!(fe.modes(100).is_err());
    // No supports: K is singular, the static solve must fail with an error, not panic.
    let free = FeBeam::new(&uniform(L), &[], &[], 4).unwrap();
    assert!(free.static_deflection(&[(1.0, 1.0)]).is_err());
}

/// All three Cholesky reductions give the same modes on a coarse mesh (1e-10 in ω, 1e-8 in the
/// shapes), including a free–free beam with springs (rigid-like modes). On a fine mesh (400
/// elements) the conditioning κ ∝ n_el⁴ limits what double precision can deliver: the square-root
/// (SVD) reduction and the banded subspace iteration (square-root Rayleigh–Ritz, error ε²κ) keep
/// ω₁ within 1e-9 of the analytic value (discretisation ≈ 3e-12, rounding
/// ε√κ ≈ 1e-10), the others are printed for the record (measured ≈ 3e-6 and 4e-8).
#[test]
fn eigen_reductions_agree_and_fine_meshes_stay_accurate() {
    use beam::EigenReduction;
    let cases = [
        FeBeam::new(&uniform(L), &supports_for(Support::ClampedPinned), &[], 20).unwrap(),
        FeBeam::new(
            &uniform(L),
            &[PointSupport {
                x: 3.0,
                kind: SupportKind::Spring {
                    translational: 1e7,
                    rotational: 1e8,
                },
            }],
            &[PointMass {
                x: 20.0,
                mass: 5e3,
                rotary_inertia: 10.0,
            }],
            20,
        )
        .unwrap(),
        // Four equal spans: the first four frequencies form a tight cluster (between the SS and
        // the clamped–pinned span frequencies), the hard case for subspace iteration.
        FeBeam::new(
            &uniform(4.0 * L),
            &(0..=4)
                .map(|k| PointSupport {
                    x: k as f64 * L,
                    kind: SupportKind::Pinned,
                })
                .collect::<Vec<_>>(),
            &[],
            40,
        )
        .unwrap(),
    ];
    for fe in &cases {
        let a = fe.modes_with(5, EigenReduction::Mass).unwrap();
        for other in [
            EigenReduction::ShiftedStiffness,
            EigenReduction::StiffnessSquareRoot,
            EigenReduction::BandedSubspace,
        ] {
            let b = fe.modes_with(5, other).unwrap();
            for j in 0..5 {
                let (wa, wb) = (a.circular_frequencies()[j], b.circular_frequencies()[j]);
                assert!(
                    (wa / wb - 1.0).abs() < 1e-10,
                    "{other:?} mode {j}: {wa} vs {wb}"
                );
                let (sa, sb) = (a.shape(j, 9.0).unwrap(), b.shape(j, 9.0).unwrap());
                let size = a
                    .shape(j, 9.0)
                    .unwrap()
                    .abs()
                    .max(a.shape(j, 14.0).unwrap().abs());
                assert!(
                    (sa - sb).abs() < 1e-8 * size,
                    "{other:?} mode {j}: {sa} vs {sb}"
                );
            }
        }
    }
    let exact = AnalyticBeam::new(
        Support::SimplySupported,
        UniformBeam::new(L, EI, RHO_A).unwrap(),
        1,
    )
    .unwrap()
    .circular_frequencies()[0];
    let fine = FeBeam::new(
        &uniform(L),
        &supports_for(Support::SimplySupported),
        &[],
        400,
    )
    .unwrap();
    let err = |r| fine.modes_with(1, r).unwrap().circular_frequencies()[0] / exact - 1.0;
    let (mass, shifted, root, banded) = (
        err(EigenReduction::Mass),
        err(EigenReduction::ShiftedStiffness),
        err(EigenReduction::StiffnessSquareRoot),
        err(EigenReduction::BandedSubspace),
    );
    eprintln!(
        "400 elements: omega_1 rel. error mass {mass:e}, shifted {shifted:e}, square-root {root:e}, banded subspace {banded:e}"
    );
    assert!(banded.abs() < 1e-9);
    assert!(root.abs() < 1e-9);
}
