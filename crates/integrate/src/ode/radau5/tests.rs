//! Unit tests of the Radau IIA(5) stepper's internals.

#![allow(clippy::needless_range_loop)]

use super::*;

/// Radau IIA(5) coefficient matrix A (Hairer–Wanner II, Table IV.5.6).
fn radau_a() -> [[f64; 3]; 3] {
    [
        [
            (88.0 - 7.0 * SQ6) / 360.0,
            (296.0 - 169.0 * SQ6) / 1800.0,
            (-2.0 + 3.0 * SQ6) / 225.0,
        ],
        [
            (296.0 + 169.0 * SQ6) / 1800.0,
            (88.0 + 7.0 * SQ6) / 360.0,
            (-2.0 - 3.0 * SQ6) / 225.0,
        ],
        [(16.0 - SQ6) / 36.0, (16.0 + SQ6) / 36.0, 1.0 / 9.0],
    ]
}

fn t_matrix() -> [[f64; 3]; 3] {
    [[T11, T12, T13], [T21, T22, T23], [T31, 1.0, 0.0]]
}

fn ti_matrix() -> [[f64; 3]; 3] {
    [[TI11, TI12, TI13], [TI21, TI22, TI23], [TI31, TI32, TI33]]
}

fn mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                c[i][j] += a[i][k] * b[k][j];
            }
        }
    }
    c
}

/// The hard-coded T, T⁻¹ satisfy `T⁻¹ T = I` and `T⁻¹ A T = diag(1/γ̂, block)`, i.e. they
/// diagonalise A as `T⁻¹ A⁻¹ T = [γ̂ 0 0; 0 α̂ −β̂; 0 β̂ α̂]`; checked against the published A.
/// Tolerance 1e-13: the constants carry 20 digits, products lose a few ulps.
#[test]
fn transformation_diagonalises_a_inverse() {
    let (gamma, alpha, beta) = eigenvalues_of_a_inverse();
    let ident = mul(ti_matrix(), t_matrix());
    for i in 0..3 {
        for j in 0..3 {
            let expect = if i == j { 1.0 } else { 0.0 };
            assert!(
                (ident[i][j] - expect).abs() < 1e-13,
                "TI·T[{i}][{j}] = {}",
                ident[i][j]
            );
        }
    }
    // A T = T Λ⁻¹ with Λ = [γ 0 0; 0 α −β; 0 β α]; check T⁻¹ A T = Λ⁻¹.
    let d = mul(ti_matrix(), mul(radau_a(), t_matrix()));
    let cno = alpha * alpha + beta * beta;
    let expect = [
        [1.0 / gamma, 0.0, 0.0],
        [0.0, alpha / cno, beta / cno],
        [0.0, -beta / cno, alpha / cno],
    ];
    for i in 0..3 {
        for j in 0..3 {
            assert!(
                (d[i][j] - expect[i][j]).abs() < 1e-13,
                "T⁻¹AT[{i}][{j}] = {} vs {}",
                d[i][j],
                expect[i][j]
            );
        }
    }
}
