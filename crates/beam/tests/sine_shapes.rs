//! The sine-recurrence shapes of a simply supported uniform span against the analytic basis's
//! direct evaluation (the oracle), and their detection.

use beam::{
    AnalyticBeam, Derivative, ModalBasis, Support, UniformBeam, sine_amplitudes, sine_shape_dot,
    sine_shapes,
};

/// A simply supported 25 m span with `modes` modes and its sine amplitudes A_j.
fn span_with_sine_shapes(modes: usize) -> (AnalyticBeam, Vec<f64>) {
    let b = AnalyticBeam::new(
        Support::SimplySupported,
        UniformBeam::new(25.0, 8.323e9, 2303.0).unwrap(),
        modes,
    )
    .unwrap();
    let a = sine_amplitudes(&b)
        .unwrap()
        .expect("a simply supported span has sine shapes");
    (b, a)
}

#[test]
fn recurrence_shapes_equal_the_direct_evaluation() {
    // 60 modes at 997 points: the recurrence's round-off grows about linearly with the mode
    // number; measured below 1e-13 of the amplitude, asserted 1e-11.
    let (b, a) = span_with_sine_shapes(60);
    let (mut direct, mut fast) = (vec![0.0; 60], vec![0.0; 60]);
    let mut worst = 0.0f64;
    for i in 0..=996 {
        let x = 25.0 * i as f64 / 996.0;
        b.eval_all(x, Derivative::Shape, &mut direct).unwrap();
        sine_shapes(&a, 25.0, x, &mut fast);
        for j in 0..60 {
            worst = worst.max((direct[j] - fast[j]).abs() / a[j].abs());
        }
    }
    println!("largest difference / amplitude: {worst:.2e}");
    assert!(worst < 1e-11, "{worst}");
}

#[test]
fn weighted_sum_of_the_recurrence_shapes_equals_the_direct_sum() {
    // Σ_j c_j w_j(x) with weights of both signs (as the quasi-static deflection's
    // w_j(x_out)/(m_j ω_j²)) against the direct shapes: measured 7e-16 of Σ|c_j A_j|,
    // asserted 1e-11 (the bound of the shapes themselves above).
    let (b, a) = span_with_sine_shapes(20);
    let weights: Vec<f64> = (0..20)
        .map(|j| (-0.7f64).powi(j) / (1.0 + j as f64))
        .collect();
    let scale: f64 = weights.iter().zip(&a).map(|(c, a)| (c * a).abs()).sum();
    let mut direct = vec![0.0; 20];
    let mut worst = 0.0f64;
    for i in 0..=400 {
        let x = 25.0 * i as f64 / 400.0;
        b.eval_all(x, Derivative::Shape, &mut direct).unwrap();
        let expected: f64 = weights.iter().zip(&direct).map(|(c, w)| c * w).sum();
        worst = worst.max((sine_shape_dot(&a, 25.0, x, &weights) - expected).abs() / scale);
    }
    println!("largest difference / Σ|c_j A_j|: {worst:.2e}");
    assert!(worst < 1e-11, "{worst}");
}

#[test]
fn other_supports_have_no_sine_shapes() {
    for support in [
        Support::ClampedClamped,
        Support::ClampedFree,
        Support::ClampedPinned,
    ] {
        let b = AnalyticBeam::new(support, UniformBeam::new(20.0, 1e10, 1e4).unwrap(), 5).unwrap();
        assert!(sine_amplitudes(&b).unwrap().is_none(), "{support:?}");
    }
}
