//! Kalker's linear theory of steady rolling with the creepage coefficients C₁₁, C₂₂, C₂₃.
//!
//! For an elliptic (Hertzian) contact with semi-axes a (along the rolling direction x) and
//! b, c = √(ab), combined shear modulus G and Poisson's ratio ν, at vanishing creepage
//! (Kalker 1967; book 1990 App. E; references.md §C4.2; forces on body 1, CONTACT's signs):
//!
//! ```text
//! F_x = −G c² C₁₁ ξ
//! F_y = −G c² C₂₂ η − G c³ C₂₃ φ
//! ```
//!
//! The coefficients come from Kalker's table E.3 as carried in CONTACT (`m_hertz.f90`,
//! routine `linrol`, with C₂₃(a/b = 0.8, ν = 0.25) = 1.25), interpolated by CONTACT's rule:
//! linear in the semi-axis ratio g between table rows, then a quadratic Lagrange fit of
//! 1/C through ν = 0, 0.25, 0.5; below g = 0.1 the asymptotes of references.md §C4.2 are used.
//! C₃₃ is not in the table, so the spin moment is not given here.

use crate::error::{ContactError, positive};

/// Rows g = 0.1, 0.2, …, 1.0; for each row [C₁₁, C₂₂, C₂₃] × [ν = 0, 0.25, 0.5]
/// (Kalker's tabulated values; 3.14 there is a table entry, not π).
type Table = [[[f64; 3]; 3]; 10];

/// Case a ≤ b, row label g = a/b.
#[allow(clippy::approx_constant)]
const TABLE_A_LE_B: Table = [
    [
        [2.51, 3.31, 4.85],
        [2.51, 2.52, 2.53],
        [0.334, 0.473, 0.731],
    ],
    [
        [2.59, 3.37, 4.81],
        [2.59, 2.63, 2.66],
        [0.483, 0.603, 0.809],
    ],
    [
        [2.68, 3.44, 4.80],
        [2.68, 2.75, 2.81],
        [0.607, 0.715, 0.889],
    ],
    [
        [2.78, 3.53, 4.82],
        [2.78, 2.88, 2.98],
        [0.720, 0.823, 0.977],
    ],
    [[2.88, 3.62, 4.83], [2.88, 3.01, 3.14], [0.827, 0.929, 1.07]],
    [[2.98, 3.72, 4.91], [2.98, 3.14, 3.31], [0.930, 1.03, 1.18]],
    [[3.09, 3.81, 4.97], [3.09, 3.28, 3.48], [1.03, 1.14, 1.29]],
    [[3.19, 3.91, 5.05], [3.19, 3.41, 3.65], [1.13, 1.25, 1.40]],
    [[3.29, 4.01, 5.12], [3.29, 3.54, 3.82], [1.23, 1.36, 1.51]],
    [[3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63]],
];

/// Case a ≥ b, row label g = b/a.
const TABLE_A_GE_B: Table = [
    [[10.7, 11.7, 12.9], [10.7, 12.8, 16.0], [12.2, 14.6, 18.0]],
    [[6.96, 7.78, 8.82], [6.96, 8.14, 9.79], [5.72, 6.63, 7.89]],
    [[5.57, 6.34, 7.34], [5.57, 6.40, 7.51], [3.79, 4.32, 5.01]],
    [[4.84, 5.57, 6.57], [4.84, 5.48, 6.31], [2.88, 3.24, 3.70]],
    [[4.37, 5.10, 6.11], [4.37, 4.90, 5.56], [2.35, 2.62, 2.96]],
    [[4.06, 4.78, 5.80], [4.06, 4.50, 5.04], [2.01, 2.23, 2.50]],
    [[3.82, 4.54, 5.58], [3.82, 4.21, 4.67], [1.76, 1.95, 2.18]],
    [[3.65, 4.36, 5.42], [3.65, 3.99, 4.39], [1.58, 1.75, 1.94]],
    [[3.51, 4.22, 5.30], [3.51, 3.81, 4.16], [1.44, 1.59, 1.77]],
    [[3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63]],
];

/// Kalker's creepage coefficients (dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepCoefficients {
    pub c11: f64,
    pub c22: f64,
    pub c23: f64,
}

/// Asymptotes for g = a/b → 0 (references.md §C4.2).
fn asymptote_a_small(g: f64, nu: f64) -> CreepCoefficients {
    let pi = std::f64::consts::PI;
    CreepCoefficients {
        c11: pi * pi / (4.0 * (1.0 - nu)),
        c22: pi * pi / 4.0,
        c23: pi * g.sqrt() / (3.0 * (1.0 - nu)) * (1.0 + nu * ((16.0 / g).ln() - 5.0)),
    }
}

/// Asymptotes for g = b/a → 0, Λ = ln(16/g²) (references.md §C4.2).
fn asymptote_b_small(g: f64, nu: f64) -> CreepCoefficients {
    let pi = std::f64::consts::PI;
    let l = (16.0 / (g * g)).ln();
    let c = 3.0 - 4f64.ln();
    let d22 = (1.0 - nu) * l + 2.0 * nu;
    CreepCoefficients {
        c11: 2.0 * pi / ((l - 2.0 * nu) * g) * (1.0 + c / (l - 2.0 * nu)),
        c22: 2.0 * pi / g * (1.0 + (1.0 - nu) * c / d22) / d22,
        c23: 2.0 * pi / (3.0 * g.powf(1.5) * ((1.0 - nu) * l - 2.0 + 4.0 * nu)),
    }
}

/// Quadratic Lagrange interpolation of 1/C through ν = 0, 0.25, 0.5 (CONTACT's harmonic fit).
fn harmonic_in_nu(values: [f64; 3], nu: f64) -> f64 {
    let (n0, n1, n2) = (0.0, 0.25, 0.5);
    let l0 = (nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2));
    let l1 = (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2));
    let l2 = (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1));
    1.0 / (l0 / values[0] + l1 / values[1] + l2 / values[2])
}

/// Kalker's creepage coefficients for semi-axes `a` (rolling direction) and `b` \[m\] and the
/// combined Poisson's ratio `nu` ∈ [0, 0.5], by CONTACT's interpolation rule (module doc).
pub fn creep_coefficients(a: f64, b: f64, nu: f64) -> Result<CreepCoefficients, ContactError> {
    positive("a", a)?;
    positive("b", b)?;
    if !(0.0..=0.5).contains(&nu) {
        return Err(ContactError::InvalidParameter {
            name: "nu",
            value: nu,
            reason: "Kalker's table covers 0 <= nu <= 0.5",
        });
    }
    let (table, g) = if a <= b {
        (&TABLE_A_LE_B, a / b)
    } else {
        (&TABLE_A_GE_B, b / a)
    };
    if g < 0.1 {
        return Ok(if a <= b {
            asymptote_a_small(g, nu)
        } else {
            asymptote_b_small(g, nu)
        });
    }
    // Rows at g = 0.1 (k = 0) … 1.0 (k = 9).
    let pos = ((g - 0.1) / 0.1).clamp(0.0, 9.0);
    let k = (pos.floor() as usize).min(8);
    let t = pos - k as f64;
    let mut c = [0.0; 3];
    for (m, cm) in c.iter_mut().enumerate() {
        let mut by_nu = [0.0; 3];
        for (q, v) in by_nu.iter_mut().enumerate() {
            *v = (1.0 - t) * table[k][m][q] + t * table[k + 1][m][q];
        }
        *cm = harmonic_in_nu(by_nu, nu);
    }
    Ok(CreepCoefficients {
        c11: c[0],
        c22: c[1],
        c23: c[2],
    })
}

/// Creep forces of the linear theory \[N\] for creepages ξ, η (dimensionless) and spin φ
/// [1/m] on an ellipse with semi-axes `a`, `b` \[m\]: (F_x, F_y) = (−G c² C₁₁ ξ,
/// −G c² C₂₂ η − G c³ C₂₃ φ) with c = √(ab) and combined shear modulus `g` \[Pa\].
pub fn linear_forces(
    g: f64,
    nu: f64,
    a: f64,
    b: f64,
    xi: f64,
    eta: f64,
    phi: f64,
) -> Result<(f64, f64), ContactError> {
    positive("G", g)?;
    let k = creep_coefficients(a, b, nu)?;
    let c2 = a * b;
    let c = c2.sqrt();
    Ok((
        -g * c2 * k.c11 * xi,
        -g * c2 * k.c22 * eta - g * c2 * c * k.c23 * phi,
    ))
}
