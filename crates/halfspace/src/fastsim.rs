//! FASTSIM: Kalker's simplified theory of steady rolling (Kalker, Vehicle System Dynamics 11
//! (1982) 1–13; references.md §C3.6).
//!
//! The half-space is replaced by a Winkler bed, u = L p, with three flexibilities taken from
//! the linear theory so that FASTSIM reproduces it at vanishing creepage:
//!
//! ```text
//! L₁ = 8a/(3 C₁₁ G),   L₂ = 8a/(3 C₂₂ G),   L₃ = π a √(a/b)/(4 C₂₃ G)
//! ```
//!
//! In adhesion the slip s = w − ∂u/∂x vanishes (the contact moves in +x over the material,
//! the leading edge is at x = +a(y)), so each strip y = const is marched from the leading
//! edge with
//!
//! ```text
//! p_x(x − δx) = p_x(x) − δx (ξ/L₁ − φ y/L₃),   p_y(x − δx) = p_y(x) − δx (η/L₂ + φ x/L₃)
//! ```
//!
//! Where the trial traction
//! exceeds the elliptic traction bound g = μ p₀ √(1 − x²/a² − y²/b²), p₀ = 3F_n/(2πab), it is
//! scaled back onto the bound and the element slips. The rigid slip of each step is taken
//! at the step's midpoint (second order in δx; with the point value at x the spin force
//! converges only to first order). Strips are centred at ny equally spaced
//! y in (−b, b), each split into nx elements of length δx = 2a(y)/nx; the traction of an
//! element is taken at its centre (a half step from the leading edge for the first one).

use crate::error::{ContactError, positive};
use crate::linear_theory::creep_coefficients;

/// Input of a FASTSIM computation (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastsimInput {
    /// Semi-axis along the rolling direction x \[m\].
    pub a: f64,
    /// Lateral semi-axis \[m\].
    pub b: f64,
    /// Combined shear modulus G \[Pa\].
    pub g: f64,
    /// Combined Poisson's ratio ν.
    pub nu: f64,
    /// Coulomb friction coefficient μ.
    pub mu: f64,
    /// Normal force F_n \[N\].
    pub normal_force: f64,
    /// Longitudinal creepage ξ.
    pub xi: f64,
    /// Lateral creepage η.
    pub eta: f64,
    /// Spin φ [1/m].
    pub phi: f64,
}

/// FASTSIM result.
#[derive(Debug, Clone, PartialEq)]
pub struct FastsimSolution {
    /// Longitudinal force F_x on body 1 \[N\].
    pub force_x: f64,
    /// Lateral force F_y \[N\].
    pub force_y: f64,
    /// Spin moment M_z = ∫ (x p_y − y p_x) dA [N m].
    pub moment_z: f64,
    /// Elements in adhesion and in slip.
    pub adhesion_elements: usize,
    pub slip_elements: usize,
    /// Frictional power per unit rolling speed, ∫ |p_t| |s| dA over the slip area \[N\].
    pub frictional_power_per_speed: f64,
    /// Flexibilities L₁, L₂, L₃ [m/Pa].
    pub flexibilities: [f64; 3],
}

/// Run FASTSIM on `nx × ny` elements of the ellipse (see the module documentation).
pub fn fastsim(
    input: &FastsimInput,
    nx: usize,
    ny: usize,
) -> Result<FastsimSolution, ContactError> {
    let FastsimInput {
        a,
        b,
        g,
        nu,
        mu,
        normal_force,
        xi,
        eta,
        phi,
    } = *input;
    positive("a", a)?;
    positive("b", b)?;
    positive("G", g)?;
    positive("mu", mu)?;
    positive("normal_force", normal_force)?;
    for (name, v) in [("creepage_x", xi), ("creepage_y", eta), ("spin", phi)] {
        crate::error::finite(name, v)?;
    }
    if nx == 0 || ny == 0 {
        return Err(ContactError::InvalidParameter {
            name: "fastsim elements",
            value: 0.0,
            reason: "FASTSIM needs at least one element per direction",
        });
    }
    let c = creep_coefficients(a, b, nu)?;
    let l1 = 8.0 * a / (3.0 * c.c11 * g);
    let l2 = 8.0 * a / (3.0 * c.c22 * g);
    let l3 = std::f64::consts::PI * a * (a / b).sqrt() / (4.0 * c.c23 * g);
    let p0 = 3.0 * normal_force / (2.0 * std::f64::consts::PI * a * b);
    let dy = 2.0 * b / ny as f64;
    let (mut fx, mut fy, mut mz, mut power) = (0.0, 0.0, 0.0, 0.0);
    let (mut adhesion, mut slip) = (0usize, 0usize);
    for j in 0..ny {
        let y = -b + (j as f64 + 0.5) * dy;
        let ay = a * (1.0 - (y / b).powi(2)).max(0.0).sqrt();
        let dx = 2.0 * ay / nx as f64;
        let area = dx * dy;
        let (mut px, mut py) = (0.0, 0.0);
        for i in 0..nx {
            let x = ay - (i as f64 + 0.5) * dx;
            let step = if i == 0 { 0.5 * dx } else { dx };
            // The implicit-Euler step from the upstream traction (rigid slip w at x).
            let tx = px - step * (xi / l1 - phi * y / l3);
            // Rigid slip at the midpoint of the step (second-order accurate in δx).
            let xm = x + 0.5 * step;
            let ty = py - step * (eta / l2 + phi * xm / l3);
            let bound = mu * p0 * (1.0 - (x / a).powi(2) - (y / b).powi(2)).max(0.0).sqrt();
            let t = tx.hypot(ty);
            if t > bound {
                let f = if t > 0.0 { bound / t } else { 0.0 };
                px = tx * f;
                py = ty * f;
                slip += 1;
                // Slip s = w − ∂u/∂x with u = L p: s = L (p − p_trial)/δx per component,
                // opposite to the traction; the power −p·s ≥ 0.
                let sx = l1 * (px - tx) / step;
                let sy = l2 * (py - ty) / step;
                power -= (px * sx + py * sy) * area;
            } else {
                px = tx;
                py = ty;
                adhesion += 1;
            }
            fx += px * area;
            fy += py * area;
            mz += (x * py - y * px) * area;
        }
    }
    Ok(FastsimSolution {
        force_x: fx,
        force_y: fy,
        moment_z: mz,
        adhesion_elements: adhesion,
        slip_elements: slip,
        frictional_power_per_speed: power,
        flexibilities: [l1, l2, l3],
    })
}
