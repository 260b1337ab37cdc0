//! Energy behaviour and equivalences between schemes.

mod structural_support;

use faer::Mat;
use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper};
use structural_support::oscillator;

/// Three masses in a chain between two walls: M = diag(1, 2, 0.5), springs 4, 3, 5, 2.
fn chain_matrices() -> (Mat<f64>, Mat<f64>) {
    let m = Mat::from_fn(3, 3, |i, j| if i == j { [1.0, 2.0, 0.5][i] } else { 0.0 });
    let k_springs = [4.0, 3.0, 5.0, 2.0];
    let k = Mat::from_fn(3, 3, |i, j| {
        if i == j {
            k_springs[i] + k_springs[i + 1]
        } else if i + 1 == j || j + 1 == i {
            -k_springs[i.max(j)]
        } else {
            0.0
        }
    });
    (m, k)
}

/// E = ½ vᵀMv + ½ qᵀKq.
fn energy(m: &Mat<f64>, k: &Mat<f64>, q: &[f64], v: &[f64]) -> f64 {
    let mut e = 0.0;
    for i in 0..q.len() {
        for j in 0..q.len() {
            e += 0.5 * (v[i] * m[(i, j)] * v[j] + q[i] * k[(i, j)] * q[j]);
        }
    }
    e
}

#[test]
fn average_acceleration_conserves_linear_energy() {
    // The trapezoidal rule conserves ½vᵀMv + ½qᵀKq of an undamped, unforced linear system
    // exactly (Newmark 1959; references.md §D3.5: zero algorithmic damping). Over 1e4 steps only
    // round-off accumulates: a few ε per step, at worst linearly, ≈ 1e4·1e-15 → bound 1e-11.
    let (m, k) = chain_matrices();
    let mut problem =
        LinearStructure::new(m.clone(), None, k.clone(), |_, f: &mut [f64]| f.fill(0.0)).unwrap();
    let (q0, v0) = ([0.3, -0.2, 0.1], [0.0, 1.0, -0.5]);
    let e0 = energy(&m, &k, &q0, &v0);
    let mut s = StructuralStepper::new(
        StructuralMethod::average_acceleration(),
        &mut problem,
        0.0,
        &q0,
        &v0,
    )
    .unwrap();
    let mut max_drift: f64 = 0.0;
    for _ in 0..10_000 {
        s.step(&mut problem, 0.37).unwrap();
        max_drift = max_drift.max((energy(&m, &k, s.q(), s.v()) / e0 - 1.0).abs());
    }
    println!("average acceleration: max relative energy drift over 1e4 steps {max_drift:e}");
    assert!(max_drift < 1e-11, "drift {max_drift:e}");
}

/// Max relative energy error of Verlet on u'' + u = 0 over `n` steps of `dt`.
fn verlet_energy_error(dt: f64, n: usize) -> f64 {
    let mut problem = oscillator(1.0);
    let mut s = StructuralStepper::new(
        StructuralMethod::StormerVerlet,
        &mut problem,
        0.0,
        &[1.0],
        &[0.0],
    )
    .unwrap();
    let mut err: f64 = 0.0;
    for _ in 0..n {
        s.step(&mut problem, dt).unwrap();
        let e = 0.5 * (s.q()[0].powi(2) + s.v()[0].powi(2));
        err = err.max((e / 0.5 - 1.0).abs());
    }
    err
}

#[test]
fn verlet_energy_error_is_bounded_and_second_order() {
    // Symplectic: the energy error oscillates without drift, with amplitude O(Δt²)
    // (Hairer, Lubich & Wanner 2006, §IX.8; for the oscillator it is exactly Ω²/4 at most).
    let coarse = verlet_energy_error(0.1, 1_000);
    let fine = verlet_energy_error(0.05, 2_000);
    let order = (coarse / fine).log2();
    println!("Verlet energy error: {coarse:e} (Δt = 0.1), {fine:e} (Δt = 0.05), order {order:.4}");
    assert!((order - 2.0).abs() < 0.2, "order {order}");
    // Closed form: for u'' + u = 0 velocity Verlet's one-step matrix [[1 − Ω²/2, Ω],
    // [−Ω(1 − Ω²/4), 1 − Ω²/2]] conserves I = (1 − Ω²/4)q² + v² exactly, so from q = 1, v = 0
    // the energy ratio E_n/E_0 ranges over [1 − Ω²/4, 1]: the maximum error is Ω²/4 = 2.5e-3.
    // 1000 samples of a period-6.28 oscillation come within 1e-3 (relative) of the extremum.
    let bound = 0.1_f64.powi(2) / 4.0;
    assert!(
        coarse <= bound * (1.0 + 1e-12) && coarse >= bound * (1.0 - 1e-3),
        "error {coarse:e}, closed form {bound:e}"
    );
    // Bounded: ten times longer does not increase the maximum (no secular drift), to 1 %.
    let long = verlet_energy_error(0.1, 10_000);
    assert!(
        long < 1.01 * coarse,
        "long-time error {long:e} vs {coarse:e}"
    );
}

/// Damped 3-DOF chain for scheme comparisons, forced if `forced`.
fn damped_chain(forced: bool) -> LinearStructure<impl FnMut(f64, &mut [f64])> {
    let amplitude = if forced { 1.0 } else { 0.0 };
    let (m, k) = chain_matrices();
    let c = Mat::from_fn(3, 3, |i, j| 0.05 * m[(i, j)] + 0.02 * k[(i, j)]);
    LinearStructure::new(m, Some(c), k, move |t: f64, f: &mut [f64]| {
        f[0] = amplitude * (1.3 * t).sin();
        f[1] = 0.0;
        f[2] = amplitude * 0.5 * (0.7 * t).cos();
    })
    .unwrap()
}

fn trajectories_agree(
    a: StructuralMethod,
    b: StructuralMethod,
    forced: bool,
    dt: f64,
    n: usize,
    tol: f64,
) {
    let (mut pa, mut pb) = (damped_chain(forced), damped_chain(forced));
    let (q0, v0) = ([0.1, 0.0, -0.2], [0.0, 0.4, 0.0]);
    let mut sa = StructuralStepper::new(a, &mut pa, 0.0, &q0, &v0).unwrap();
    let mut sb = StructuralStepper::new(b, &mut pb, 0.0, &q0, &v0).unwrap();
    let mut max_diff: f64 = 0.0;
    for _ in 0..n {
        sa.step(&mut pa, dt).unwrap();
        sb.step(&mut pb, dt).unwrap();
        for i in 0..3 {
            max_diff = max_diff
                .max((sa.q()[i] - sb.q()[i]).abs())
                .max((sa.v()[i] - sb.v()[i]).abs());
        }
    }
    println!("{a:?} vs {b:?}: max difference {max_diff:e}");
    assert!(max_diff < tol, "{a:?} vs {b:?}: {max_diff:e}");
}

#[test]
fn hht_minus_one_third_equals_generalized_alpha_one_half() {
    // references.md §D3.5: α_m = 0 at ρ∞ = 0.5, so HHT(−1/3) and gen-α(0.5) are one method; the
    // two parameter mappings agree to round-off, so the trajectories agree to 1e-12.
    trajectories_agree(
        StructuralMethod::hht(-1.0 / 3.0).unwrap(),
        StructuralMethod::generalized_alpha(0.5).unwrap(),
        true,
        0.05,
        2_000,
        1e-12,
    );
}

#[test]
fn generalized_alpha_one_equals_trapezoidal_rule() {
    // references.md §D3.5: ρ∞ = 1 gives α_m = α_f = ½, γ = ½, β = ¼. For a linear system the
    // α-weighted balance is the average of the balances at n and n+1, which the trapezoidal
    // rule also satisfies, so without load the trajectories agree up to round-off (1e-10 over
    // 2000 steps). With a load they differ at O(Δt²): gen-α takes f(t_{n+½}), not the average.
    trajectories_agree(
        StructuralMethod::generalized_alpha(1.0).unwrap(),
        StructuralMethod::average_acceleration(),
        false,
        0.05,
        2_000,
        1e-10,
    );
}

#[test]
fn verlet_equals_central_difference() {
    // Velocity Verlet is Newmark β = 0, γ = ½ written in kick–drift–kick form (two separate
    // code paths here); with damping both solve (M + ½ΔtC) a = …: round-off agreement.
    trajectories_agree(
        StructuralMethod::StormerVerlet,
        StructuralMethod::central_difference(),
        true,
        0.05,
        2_000,
        1e-12,
    );
}

#[test]
fn leapfrog_equals_verlet_without_damping_and_is_first_order_in_damping() {
    // Without damping leapfrog and Verlet coincide (the damping treatment is their only
    // difference): round-off agreement on the undamped oscillator.
    let mut p1 = oscillator(2.0);
    let mut p2 = oscillator(2.0);
    let mut a =
        StructuralStepper::new(StructuralMethod::Leapfrog, &mut p1, 0.0, &[1.0], &[0.5]).unwrap();
    let mut b = StructuralStepper::new(
        StructuralMethod::StormerVerlet,
        &mut p2,
        0.0,
        &[1.0],
        &[0.5],
    )
    .unwrap();
    for _ in 0..1000 {
        a.step(&mut p1, 0.05).unwrap();
        b.step(&mut p2, 0.05).unwrap();
        assert!((a.q()[0] - b.q()[0]).abs() < 1e-13 && (a.v()[0] - b.v()[0]).abs() < 1e-13);
    }
    // With damping the half-step damping velocity costs one order: u'' + 2ζu' + u = 0,
    // ζ = 0.1, u(0) = 1, u'(0) = 0, exact u = e^{−ζt}(cos ω_d t + ζ/ω_d sin ω_d t).
    let zeta: f64 = 0.1;
    let wd = (1.0 - zeta * zeta).sqrt();
    let exact = |t: f64| (-zeta * t).exp() * ((wd * t).cos() + zeta / wd * (wd * t).sin());
    let error = |method: StructuralMethod, dt: f64| {
        let mut p = LinearStructure::new(
            Mat::from_fn(1, 1, |_, _| 1.0),
            Some(Mat::from_fn(1, 1, |_, _| 2.0 * zeta)),
            Mat::from_fn(1, 1, |_, _| 1.0),
            |_, f: &mut [f64]| f.fill(0.0),
        )
        .unwrap();
        let n = (10.0 / dt).round() as usize;
        let mut s = StructuralStepper::new(method, &mut p, 0.0, &[1.0], &[0.0]).unwrap();
        for _ in 0..n {
            s.step(&mut p, dt).unwrap();
        }
        (s.q()[0] - exact(s.t())).abs()
    };
    let leap =
        (error(StructuralMethod::Leapfrog, 0.01) / error(StructuralMethod::Leapfrog, 0.005)).log2();
    let verlet = (error(StructuralMethod::StormerVerlet, 0.01)
        / error(StructuralMethod::StormerVerlet, 0.005))
    .log2();
    println!("damped oscillator: leapfrog order {leap:.4}, Verlet order {verlet:.4}");
    assert!((leap - 1.0).abs() < 0.2, "leapfrog order {leap}");
    assert!((verlet - 2.0).abs() < 0.2, "Verlet order {verlet}");
}
