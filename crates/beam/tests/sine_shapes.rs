//! The sine-recurrence shapes of a simply supported uniform span against the analytic basis's
//! direct evaluation (the oracle), and their detection.

use beam::{
    AnalyticBeam, Derivative, ModalBasis, Support, UniformBeam, sine_amplitudes, sine_shapes,
};

#[test]
fn recurrence_shapes_equal_the_direct_evaluation() {
    // 60 modes at 997 points: the recurrence's round-off grows about linearly with the mode
    // number; measured below 1e-13 of the amplitude, asserted 1e-11.
    let b = AnalyticBeam::new(
        Support::SimplySupported,
        UniformBeam::new(25.0, 8.323e9, 2303.0).unwrap(),
        60,
    )
    .unwrap();
    let a = sine_amplitudes(&b)
        .unwrap()
        .expect("a simply supported span has sine shapes");
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
