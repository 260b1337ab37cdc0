//! Analytic modes against references.md §D1.6 (roots to 20 digits, (βL)² coefficients, normalisation
//! facts), the textbook cosh/cos forms, the boundary conditions, the beam ODE and orthonormality.

// The reference roots are quoted with all 20 digits of the source table on purpose.
#![allow(clippy::excessive_precision)]
use beam::analytic::{asymptotic_root, characteristic_root};
use beam::{
    AnalyticBeam, BeamError, Derivative, ModalBasis, Quadrature, QuadratureRule, Support,
    UniformBeam,
};

/// references.md §D1.6 table (mpmath, 30 digits), n = 1..8.
const CC_FF: [f64; 8] = [
    4.7300407448627040260,
    7.8532046240958375565,
    10.995607838001670907,
    14.137165491257464177,
    17.278759657399481438,
    20.420352245626061091,
    23.561944902040455075,
    26.703537555508186248,
];
const CANTILEVER: [f64; 8] = [
    1.8751040687119611664,
    4.6940911329741745764,
    7.8547574382376125649,
    10.995540734875466991,
    14.137168391046470581,
    17.278759532088236334,
    20.420352251041250994,
    23.561944901806443502,
];
const CLAMPED_PINNED: [f64; 8] = [
    3.9266023120479187782,
    7.0685827456287320886,
    10.210176122813030545,
    13.351768777754093124,
    16.493361431346409781,
    19.634954084936207732,
    22.776546738526000979,
    25.918139392115794217,
];

const ALL: [Support; 5] = [
    Support::SimplySupported,
    Support::ClampedClamped,
    Support::ClampedFree,
    Support::ClampedPinned,
    Support::FreeFree,
];

/// Frýba's example bridge (references.md §D1.3): L = 25 m, EI = 2.87e9 · 2.90, ρA = 2303 kg/m.
fn fryba() -> UniformBeam {
    UniformBeam::new(25.0, 2.87e9 * 2.90, 2303.0).unwrap()
}

/// Roots to 1e-12 relative: the table has 20 digits, so the only error is ours; 1e-12 allows a
/// few ulp of the characteristic-function evaluation near the root (slope ≈ ±1 there).
#[test]
fn roots_match_the_twenty_digit_table() {
    for n in 1..=8 {
        let check = |support, exact: f64| {
            let got = characteristic_root(support, n).unwrap();
            let rel = ((got - exact) / exact).abs();
            assert!(
                rel <= 1e-12,
                "{support:?} n={n}: {got} vs {exact} (rel {rel:e})"
            );
            rel
        };
        let worst = [
            check(Support::ClampedClamped, CC_FF[n - 1]),
            check(Support::FreeFree, CC_FF[n - 1]),
            check(Support::ClampedFree, CANTILEVER[n - 1]),
            check(Support::ClampedPinned, CLAMPED_PINNED[n - 1]),
            check(Support::SimplySupported, n as f64 * std::f64::consts::PI),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        eprintln!("n={n}: worst relative root error {worst:e}");
        assert!(worst <= 1e-12);
    }
}

/// The asymptotic formula agrees with the bracketed root where both are used near the switch
/// (n = 10, 11 for CC/FF/CF; n = 4, 5 for CP): the correction there is ≤ 1e-13 relative.
#[test]
fn asymptotic_roots_agree_near_the_switch() {
    for (support, ns) in [
        (Support::ClampedClamped, [10, 11]),
        (Support::ClampedFree, [10, 11]),
        (Support::ClampedPinned, [4, 5]),
    ] {
        for n in ns {
            let root = characteristic_root(support, n).unwrap();
            let asym = asymptotic_root(support, n);
            assert!(
                ((root - asym) / root).abs() < 1e-13,
                "{support:?} n={n}: {root} vs {asym}"
            );
        }
    }
    // Beyond the switch the roots still satisfy the characteristic equations to rounding:
    // |cos β − sech β| ≤ 8 ε β (the argument of cos carries ε β of rounding).
    for n in 12..=200 {
        let b = characteristic_root(Support::ClampedClamped, n).unwrap();
        assert!(
            (b.cos() - 1.0 / b.cosh()).abs() <= 8.0 * f64::EPSILON * b,
            "CC n={n}"
        );
        let b = characteristic_root(Support::ClampedFree, n).unwrap();
        assert!(
            (b.cos() + 1.0 / b.cosh()).abs() <= 8.0 * f64::EPSILON * b,
            "CF n={n}"
        );
        let b = characteristic_root(Support::ClampedPinned, n).unwrap();
        assert!(
            (b.sin() - b.cos() * b.tanh()).abs() <= 8.0 * f64::EPSILON * b,
            "CP n={n}"
        );
    }
}

/// (βL)² coefficients of references.md §D1.6 (given to 12 significant digits → 1e-11 relative).
#[test]
fn frequency_coefficients() {
    let table: [(Support, [f64; 3]); 4] = [
        (
            Support::ClampedClamped,
            [22.3732854481, 61.6728228679, 120.903391727],
        ),
        (
            Support::ClampedFree,
            [3.5160152685, 22.0344915647, 61.6972144135],
        ),
        (
            Support::ClampedPinned,
            [15.418205717, 49.9648620318, 104.247696459],
        ),
        (
            Support::SimplySupported,
            [9.86960440109, 39.4784176044, 88.8264396098],
        ),
    ];
    // L = 1, EI = 1, ρA = 1 ⇒ ω = (βL)².
    let unit = UniformBeam::new(1.0, 1.0, 1.0).unwrap();
    for (support, coeffs) in table {
        let b = AnalyticBeam::new(support, unit, 3).unwrap();
        for (w, c) in b.circular_frequencies().iter().zip(coeffs) {
            assert!(((w - c) / c).abs() < 1e-11, "{support:?}: {w} vs {c}");
        }
    }
    // Frýba bridge, SS: ω₁ = 30.020 rad/s (references.md §D1.3, 5 digits).
    let ss = AnalyticBeam::new(Support::SimplySupported, fryba(), 1).unwrap();
    assert!((ss.circular_frequencies()[0] - 30.020).abs() < 5e-3);
}

/// Free–free: two rigid modes at ω = 0 (translation, rotation), then the CC roots.
#[test]
fn free_free_has_two_rigid_modes() {
    let b = AnalyticBeam::new(Support::FreeFree, fryba(), 4).unwrap();
    let w = b.circular_frequencies();
    assert_eq!(&w[..2], &[0.0, 0.0]);
    assert!((b.roots()[2] - CC_FF[0]).abs() < 1e-12 * CC_FF[0]);
    assert_eq!(b.mode_value(0, 3.0, Derivative::Curvature).unwrap(), 0.0);
    assert_eq!(b.mode_value(1, 3.0, Derivative::Curvature).unwrap(), 0.0);
}

/// ∫ ρA w_i w_j dx = δ_ij for i, j ≤ 100 and every support, to 1e-10. Quadrature: 300 panels of
/// 20-point Gauss–Legendre; mode 100 has ~50 waves, i.e. ~120 nodes per wave, far beyond what
/// a degree-39 rule needs for 1e-14.
#[test]
fn modes_are_orthonormal_up_to_100() {
    let beam = fryba();
    let q = Quadrature::new(
        QuadratureRule::GaussLegendre {
            points: 20,
            panels: 300,
        },
        0.0,
        beam.length,
    )
    .unwrap();
    let n = 100;
    for support in ALL {
        let b = AnalyticBeam::new(support, beam, n).unwrap();
        let mut values = vec![0.0; q.nodes().len() * n];
        for (k, &x) in q.nodes().iter().enumerate() {
            b.eval_all(x, Derivative::Shape, &mut values[k * n..(k + 1) * n])
                .unwrap();
        }
        let mut worst: f64 = 0.0;
        for i in 0..n {
            for j in i..n {
                let mut s = 0.0;
                for (k, w) in q.weights().iter().enumerate() {
                    s += w * values[k * n + i] * values[k * n + j];
                }
                let target = if i == j { 1.0 } else { 0.0 };
                worst = worst.max((beam.mass_per_length * s - target).abs());
            }
        }
        eprintln!("{support:?}: max |M_ij - delta_ij| = {worst:e}");
        assert!(worst < 1e-10, "{support:?}: max |M_ij − δ_ij| = {worst:e}");
    }
}

/// Textbook shapes (references.md §D1.6) with cosh/sinh, unnormalised.
fn textbook(support: Support, beta: f64, xi: f64) -> f64 {
    let (ch, sh, c, s) = (
        (beta * xi).cosh(),
        (beta * xi).sinh(),
        (beta * xi).cos(),
        (beta * xi).sin(),
    );
    let sigma_cc = (beta.cosh() - beta.cos()) / (beta.sinh() - beta.sin());
    match support {
        Support::ClampedClamped | Support::ClampedPinned => ch - c - sigma_cc * (sh - s),
        Support::ClampedFree => {
            let sigma = (beta.cosh() + beta.cos()) / (beta.sinh() + beta.sin());
            ch - c - sigma * (sh - s)
        }
        Support::FreeFree => ch + c - sigma_cc * (sh + s),
        Support::SimplySupported => s,
    }
}

/// For n ≤ 5 the textbook form is still accurate (max error 1.5e-9 at n = 5, references.md §D1.6), so
/// the stable form must agree with it to 1e-8 (absolute, unnormalised shapes of size O(1)).
#[test]
fn stable_shapes_agree_with_textbook_for_low_modes() {
    let beam = UniformBeam::new(1.0, 1.0, 1.0).unwrap();
    for support in [
        Support::ClampedClamped,
        Support::ClampedFree,
        Support::ClampedPinned,
        Support::FreeFree,
    ] {
        let b = AnalyticBeam::new(support, beam, 5 + support.rigid_modes()).unwrap();
        for j in support.rigid_modes()..b.n_modes() {
            let beta = b.roots()[j];
            for k in 0..=20 {
                let xi = k as f64 / 20.0;
                // ρA L = 1 here, so the mass-normalised shape equals the unnormalised φ.
                let stable = b.shape(j, xi).unwrap();
                let book = textbook(support, beta, xi);
                assert!(
                    (stable - book).abs() < 1e-8,
                    "{support:?} mode {j} ξ={xi}: {stable} vs {book}"
                );
            }
        }
    }
}

/// Boundary conditions for n ≤ 200: each required end value, scaled by (β/L)^k · max|w|, must
/// vanish to 1e-11 (the stable form has no cancellation; rounding is ~1e-14 of the scale, the
/// argument βξ ≈ 630 carries 1e-13 of phase error).
#[test]
fn boundary_conditions_hold_up_to_mode_200() {
    let beam = fryba();
    let l = beam.length;
    let amp = 1.0 / (beam.mass_per_length * l).sqrt();
    for support in ALL {
        let b = AnalyticBeam::new(support, beam, 200 + support.rigid_modes()).unwrap();
        let (left, right): (&[Derivative], &[Derivative]) = match support {
            Support::SimplySupported => (
                &[Derivative::Shape, Derivative::Curvature],
                &[Derivative::Shape, Derivative::Curvature],
            ),
            Support::ClampedClamped => (
                &[Derivative::Shape, Derivative::Slope],
                &[Derivative::Shape, Derivative::Slope],
            ),
            Support::ClampedFree => (
                &[Derivative::Shape, Derivative::Slope],
                &[Derivative::Curvature, Derivative::Third],
            ),
            Support::ClampedPinned => (
                &[Derivative::Shape, Derivative::Slope],
                &[Derivative::Shape, Derivative::Curvature],
            ),
            Support::FreeFree => (
                &[Derivative::Curvature, Derivative::Third],
                &[Derivative::Curvature, Derivative::Third],
            ),
        };
        for j in support.rigid_modes()..b.n_modes() {
            let k = b.roots()[j] / l;
            for (x, ds) in [(0.0, left), (l, right)] {
                for &d in ds {
                    let order = match d {
                        Derivative::Shape => 0,
                        Derivative::Slope => 1,
                        Derivative::Curvature => 2,
                        Derivative::Third => 3,
                    };
                    let scale = 2.0 * amp * k.powi(order);
                    let v = b.mode_value(j, x, d).unwrap();
                    assert!(
                        v.abs() < 1e-11 * scale,
                        "{support:?} mode {j} x={x} {d:?}: {v:e} (scale {scale:e})"
                    );
                }
            }
        }
    }
}

/// Normalisation facts of references.md §D1.6: cantilever tip φ(L) = 2(−1)^(n+1) and CC mode-1
/// midspan φ₁(L/2) = 1.5881462621 (10 digits → 1e-9), for the unnormalised φ = √(ρA L) w.
#[test]
fn normalisation_facts() {
    let beam = fryba();
    let scale = (beam.mass_per_length * beam.length).sqrt();
    let cf = AnalyticBeam::new(Support::ClampedFree, beam, 50).unwrap();
    for j in 0..50 {
        let tip = cf.shape(j, beam.length).unwrap() * scale;
        let expected = if j % 2 == 0 { 2.0 } else { -2.0 };
        assert!((tip - expected).abs() < 1e-12, "mode {j}: tip {tip}");
    }
    let cc = AnalyticBeam::new(Support::ClampedClamped, beam, 1).unwrap();
    let mid = cc.shape(0, 0.5 * beam.length).unwrap() * scale;
    assert!((mid - 1.5881462621).abs() < 1e-9, "{mid}");
}

/// The beam ODE w'''' = (β/L)⁴ w: central difference of the analytic w''' with step
/// h = 1e-3 L/β has truncation (h²/6)(β/L)⁶ relative ≈ 2e-7; tolerance 1e-6 of (β/L)⁴ max|w|.
#[test]
fn shapes_satisfy_the_beam_equation() {
    let beam = fryba();
    let l = beam.length;
    let amp = 1.0 / (beam.mass_per_length * l).sqrt();
    for support in ALL {
        let b = AnalyticBeam::new(support, beam, 22 + support.rigid_modes()).unwrap();
        for j in [0, 4, 21].map(|j| j + support.rigid_modes()) {
            let k = b.roots()[j] / l;
            let h = 1e-3 / k;
            for xi in [0.13, 0.5, 0.77] {
                let x = xi * l;
                let d4 = (b.mode_value(j, x + h, Derivative::Third).unwrap()
                    - b.mode_value(j, x - h, Derivative::Third).unwrap())
                    / (2.0 * h);
                let rhs = k.powi(4) * b.shape(j, x).unwrap();
                assert!(
                    (d4 - rhs).abs() < 1e-6 * k.powi(4) * 2.0 * amp,
                    "{support:?} mode {j} x={x}: {d4} vs {rhs}"
                );
            }
        }
    }
}

/// Derivative consistency: w' and w'' against central differences of w and w' (independent of
/// the analytic differentiation); tolerance 1e-6 relative for h = 1e-3 L/β.
#[test]
fn derivatives_match_finite_differences() {
    let beam = fryba();
    let l = beam.length;
    for support in ALL {
        let b = AnalyticBeam::new(support, beam, 30 + support.rigid_modes()).unwrap();
        for j in support.rigid_modes()..b.n_modes() {
            let k = b.roots()[j] / l;
            let h = 1e-3 / k;
            let x = 0.37 * l;
            let scale = 2.0 / (beam.mass_per_length * l).sqrt();
            let fd1 = (b.shape(j, x + h).unwrap() - b.shape(j, x - h).unwrap()) / (2.0 * h);
            let fd2 = (b.slope(j, x + h).unwrap() - b.slope(j, x - h).unwrap()) / (2.0 * h);
            assert!((fd1 - b.slope(j, x).unwrap()).abs() < 1e-6 * k * scale);
            assert!((fd2 - b.curvature(j, x).unwrap()).abs() < 1e-6 * k * k * scale);
        }
    }
}

#[test]
fn invalid_parameters_are_rejected_with_their_name() {
    match UniformBeam::new(-1.0, 1.0, 1.0) {
        Err(BeamError::InvalidParameter { name, .. }) => assert_eq!(name, "length"),
        other => panic!("unexpected {other:?}"),
    }
    assert!(UniformBeam::new(1.0, f64::NAN, 1.0).is_err());
    assert!(UniformBeam::new(1.0, 1.0, 0.0).is_err());
    assert!(AnalyticBeam::new(Support::SimplySupported, fryba(), 0).is_err());
    let b = AnalyticBeam::new(Support::SimplySupported, fryba(), 3).unwrap();
    assert!(b.shape(3, 1.0).is_err());
    assert!(b.shape(0, 26.0).is_err());
    assert!(b.eval_all(1.0, Derivative::Shape, &mut [0.0; 2]).is_err());
    assert!(characteristic_root(Support::ClampedClamped, 0).is_err());
}
