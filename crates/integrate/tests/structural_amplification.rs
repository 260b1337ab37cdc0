//! Amplification matrices built from one step of the real stepping code, compared with the
//! table of references.md §D3.5 and with the closed forms of §3.4.
//!
//! For u'' + ω²u = 0 with ω = 1 and Δt = Ω, the step maps (q_n, v_n, a_n) linearly to
//! (q_{n+1}, v_{n+1}, a_{n+1}). Column j of the amplification matrix is one step from the j-th
//! unit initial condition (with the acceleration given, not made consistent). The state is
//! scaled as (q, Δt·v, Δt²·a), a similarity transform that leaves the eigenvalues unchanged
//! but keeps the matrix well scaled at Ω = 1e4.
//!
//! From the principal (complex) eigenvalue pair λ = ρ_p e^{±iΩ̄}: algorithmic damping
//! ξ̄ = −ln(ρ_p)/Ω̄ and period error ΔT/T = Ω/Ω̄ − 1.

mod structural_support;

use faer::Mat;
use integrate::structural::{StructuralMethod, StructuralStepper};
use structural_support::oscillator;

/// The 3×3 amplification matrix of `method` at Ω = ωΔt (ω = 1), in scaled variables.
fn amplification(method: StructuralMethod, omega_dt: f64) -> Mat<f64> {
    let dt = omega_dt;
    let scale = [1.0, dt, dt * dt];
    let mut a = Mat::zeros(3, 3);
    for j in 0..3 {
        let mut x0 = [0.0; 3];
        x0[j] = 1.0 / scale[j];
        let mut problem = oscillator(1.0);
        let mut s = StructuralStepper::with_initial_acceleration(
            method,
            &mut problem,
            0.0,
            &[x0[0]],
            &[x0[1]],
            &[x0[2]],
        )
        .unwrap();
        s.step(&mut problem, dt).unwrap();
        let x1 = [s.q()[0], s.v()[0], s.a()[0]];
        for i in 0..3 {
            a[(i, j)] = scale[i] * x1[i];
        }
    }
    a
}

/// Spectral radius ρ, and (ξ̄, ΔT/T) of the principal complex pair if there is one.
struct Spectrum {
    rho: f64,
    damping: Option<f64>,
    period_error: Option<f64>,
}

fn spectrum(method: StructuralMethod, omega_dt: f64) -> Spectrum {
    let eig = amplification(method, omega_dt).eigenvalues().unwrap();
    let rho = eig.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let principal = eig
        .iter()
        .filter(|z| z.im.abs() > 1e-12)
        .max_by(|x, y| x.norm().total_cmp(&y.norm()));
    Spectrum {
        rho,
        damping: principal.map(|z| -z.norm().ln() / z.arg().abs()),
        period_error: principal.map(|z| omega_dt / z.arg().abs() - 1.0),
    }
}

/// One row of the references.md §D3.5 table:
/// ρ(0.1), ρ(1), ρ(1e4), ξ̄(0.1), ΔT/T(0.1), ξ̄(0.5), ΔT/T(0.5).
struct Row {
    method: StructuralMethod,
    rho: [f64; 3],
    xi_01: f64,
    dt_01: f64,
    xi_05: f64,
    dt_05: f64,
}

/// Tolerance of one unit in the last printed digit of a value printed with 4 significant
/// digits (e.g. 5.615e-6 → 1e-9); zero entries are checked to 1e-12 (round-off).
fn last_digit_tol(printed: f64) -> f64 {
    if printed == 0.0 {
        1e-12
    } else {
        10f64.powf(printed.abs().log10().floor() - 3.0)
    }
}

fn table() -> Vec<Row> {
    let row = |method, rho, xi_01, dt_01, xi_05, dt_05| Row {
        method,
        rho,
        xi_01,
        dt_01,
        xi_05,
        dt_05,
    };
    vec![
        row(
            StructuralMethod::average_acceleration(),
            [1.0, 1.0, 1.0],
            0.0,
            8.328e-4,
            0.0,
            2.050e-2,
        ),
        row(
            StructuralMethod::linear_acceleration(),
            [1.0, 1.0, 3.73205],
            0.0,
            4.164e-4,
            0.0,
            1.024e-2,
        ),
        row(
            StructuralMethod::newmark(0.3025, 0.6).unwrap(),
            [0.99950, 0.96085, 0.81818],
            4.992e-3,
            8.577e-4,
            2.401e-2,
            2.107e-2,
        ),
        row(
            StructuralMethod::hht(-0.05).unwrap(),
            [1.0, 0.99649, 0.90476],
            5.615e-6,
            9.480e-4,
            6.327e-4,
            2.317e-2,
        ),
        row(
            StructuralMethod::hht(-0.1).unwrap(),
            [1.0, 0.99385, 0.81818],
            1.008e-5,
            1.045e-3,
            1.129e-3,
            2.541e-2,
        ),
        row(
            StructuralMethod::hht(-1.0 / 3.0).unwrap(),
            [1.0, 0.98931, 0.50168],
            1.842e-5,
            1.248e-3,
            2.038e-3,
            3.015e-2,
        ),
        row(
            StructuralMethod::generalized_alpha(1.0).unwrap(),
            [1.0, 1.0, 1.0],
            0.0,
            8.328e-4,
            0.0,
            2.050e-2,
        ),
        row(
            StructuralMethod::generalized_alpha(0.8).unwrap(),
            [1.0, 0.99947, 0.80167],
            6.844e-7,
            8.790e-4,
            8.151e-5,
            2.162e-2,
        ),
        row(
            StructuralMethod::generalized_alpha(0.5).unwrap(),
            [1.0, 0.98931, 0.50168],
            1.842e-5,
            1.248e-3,
            2.038e-3,
            3.015e-2,
        ),
        row(
            StructuralMethod::generalized_alpha(0.0).unwrap(),
            [0.99995, 0.90656, 0.00216],
            4.830e-4,
            4.501e-3,
            3.449e-2,
            8.579e-2,
        ),
    ]
}

#[test]
fn spectral_radii_match_dynamics_table() {
    for row in table() {
        for (omega, expected) in [0.1, 1.0, 1e4].into_iter().zip(row.rho) {
            let rho = spectrum(row.method, omega).rho;
            println!("{:?} ρ({omega}) = {rho:.6} (table {expected})", row.method);
            // Printed to 5 decimals: ±1 in the last digit.
            assert!(
                (rho - expected).abs() <= 1e-5,
                "{:?} ρ({omega}) = {rho}, table {expected}",
                row.method
            );
        }
    }
}

#[test]
fn damping_and_period_error_match_dynamics_table() {
    for row in table() {
        for (omega, xi_ref, dt_ref) in [(0.1, row.xi_01, row.dt_01), (0.5, row.xi_05, row.dt_05)] {
            let s = spectrum(row.method, omega);
            let (xi, dt) = (s.damping.unwrap(), s.period_error.unwrap());
            println!(
                "{:?} Ω = {omega}: ξ̄ = {xi:.4e} (table {xi_ref:e}), ΔT/T = {dt:.4e} (table {dt_ref:e})",
                row.method
            );
            assert!(
                (xi - xi_ref).abs() <= last_digit_tol(xi_ref),
                "{:?} ξ̄({omega}) = {xi:e}, table {xi_ref:e}",
                row.method
            );
            assert!(
                (dt - dt_ref).abs() <= last_digit_tol(dt_ref),
                "{:?} ΔT/T({omega}) = {dt:e}, table {dt_ref:e}",
                row.method
            );
        }
    }
}

#[test]
fn newmark_linear_acceleration_is_unstable_at_high_frequency() {
    // references.md §D3.5: ρ(1e4) = 3.73205 → 2 + √3 as Ω → ∞; the stability limit is Ω = 2√3.
    let rho = spectrum(StructuralMethod::linear_acceleration(), 1e4).rho;
    assert!((rho - 3.73205).abs() <= 1e-5, "ρ = {rho}");
    let below = spectrum(
        StructuralMethod::linear_acceleration(),
        0.99 * 2.0 * 3f64.sqrt(),
    )
    .rho;
    let above = spectrum(
        StructuralMethod::linear_acceleration(),
        1.01 * 2.0 * 3f64.sqrt(),
    )
    .rho;
    assert!((below - 1.0).abs() < 1e-12, "ρ below the limit = {below}");
    assert!(above > 1.0 + 1e-3, "ρ above the limit = {above}");
}

/// Closed-form spectral radius of central difference / Verlet for u'' + u = 0 (references.md
/// §D3.4): λ² − (2 − Ω²)λ + 1 = 0, so ρ = 1 for Ω ≤ 2 and
/// ρ = (Ω² − 2 + √((Ω² − 2)² − 4))/2 above.
fn central_difference_radius(omega: f64) -> f64 {
    let b = omega * omega - 2.0;
    if b <= 2.0 {
        1.0
    } else {
        0.5 * (b + (b * b - 4.0).sqrt())
    }
}

#[test]
fn central_difference_is_stable_below_two_and_unstable_above() {
    for method in [
        StructuralMethod::central_difference(),
        StructuralMethod::StormerVerlet,
        StructuralMethod::Leapfrog,
    ] {
        for omega in [0.1, 1.0, 1.9, 1.99, 2.01, 2.1, 3.0] {
            let rho = spectrum(method, omega).rho;
            let exact = central_difference_radius(omega);
            println!("{method:?} ρ({omega}) = {rho:.8} (closed form {exact:.8})");
            // Near Ω = 2 the eigenvalue pair approaches a double root (λ = −1), where a
            // perturbation ε of the matrix moves the eigenvalues by ~√ε ≈ 1e-8; 1e-7 covers it.
            assert!(
                (rho - exact).abs() < 1e-7 * exact,
                "{method:?} Ω = {omega}: ρ = {rho}, exact {exact}"
            );
            assert_eq!(
                rho > 1.0 + 1e-6,
                omega > 2.0,
                "{method:?} Ω = {omega}: ρ = {rho}"
            );
        }
    }
}

#[test]
fn verlet_period_shortens_as_published() {
    // references.md §D3.4: T̄/T = Ω/(2 arcsin(Ω/2)), 0.999583 at Ω = 0.1.
    for omega in [0.1, 0.5, 1.0, 1.5] {
        let s = spectrum(StructuralMethod::StormerVerlet, omega);
        let exact = omega / (2.0 * (omega / 2.0).asin());
        let ratio = 1.0 + s.period_error.unwrap();
        assert!(
            (ratio - exact).abs() < 1e-12,
            "Ω = {omega}: T̄/T = {ratio}, exact {exact}"
        );
        assert!(s.damping.unwrap().abs() < 1e-12, "Verlet is undamped");
    }
    let ratio = 1.0
        + spectrum(StructuralMethod::StormerVerlet, 0.1)
            .period_error
            .unwrap();
    assert!(
        (ratio - 0.999583).abs() < 1e-6,
        "printed value 0.999583, got {ratio}"
    );
}

#[test]
fn backward_euler_spectral_radius_is_closed_form() {
    // Backward Euler on the first-order form of u'' + u = 0: λ = 1/(1 ± iΩ), ρ = 1/√(1 + Ω²)
    // (L-stable, references.md §D3.4).
    for omega in [0.1, 1.0, 10.0, 1e4] {
        let rho = spectrum(StructuralMethod::BackwardEuler, omega).rho;
        let exact = 1.0 / (1.0 + omega * omega).sqrt();
        // Eigenvalues of a matrix with O(1) entries carry an absolute error of a few ε‖A‖,
        // which matters at Ω = 1e4 where ρ = 1e-4: tolerance 1e-12 absolute + 1e-10 relative.
        assert!(
            (rho - exact).abs() <= 1e-12 + 1e-10 * exact,
            "Ω = {omega}: ρ = {rho}, exact {exact}"
        );
    }
}
