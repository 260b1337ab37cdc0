//! The rail's two-node beam element (DOFs w₁, θ₁, w₂, θ₂): Hermite cubic for the
//! Euler–Bernoulli rail (references.md §D5.2), the interdependent-interpolation element (IIE)
//! for the Timoshenko rail (references.md §D5.5).
//!
//! The IIE (Friedman & Kosmatka 1993; Reddy 1997) interpolates the displacement w by a cubic
//! and the cross-section rotation ψ by a quadratic that solve the homogeneous Timoshenko
//! equations (EI ψ')' + κGA (w' − ψ) = 0, (κGA (w' − ψ))' = 0 exactly, so the element is exact
//! for nodal loads and does not lock. With φ = 12 EI / (κGA h²) and ξ = x/h ∈ \[0, 1\]:
//!
//! ```text
//! N_w = [1 − 3ξ² + 2ξ³ + φ(1 − ξ),  h(ξ − 2ξ² + ξ³ + φ(ξ − ξ²)/2),
//!        3ξ² − 2ξ³ + φξ,            h(ξ³ − ξ² − φ(ξ − ξ²)/2)] / (1 + φ)
//! N_ψ = [6(ξ² − ξ)/h,  1 − 4ξ + 3ξ² + φ(1 − ξ),  6(ξ − ξ²)/h,  3ξ² − 2ξ + φξ] / (1 + φ)
//! K   = EI / ((1 + φ) h³) [[12, 6h, −12, 6h], [6h, (4 + φ)h², −6h, (2 − φ)h²],
//!                          [−12, −6h, 12, −6h], [6h, (2 − φ)h², −6h, (4 + φ)h²]]
//! M   = ∫₀ʰ (m N_w N_wᵀ + ρI N_ψ N_ψᵀ) dx   (consistent, 4-point Gauss: exact for degree 7)
//! ```
//!
//! φ = 0 gives the Hermite shape functions and stiffness. A point force F at ξ has the
//! consistent load vector F N_w(ξ), and the rail displacement there is N_w(ξ)ᵀu: the same
//! vector, so a wheel's contact vector stays symmetric with either theory.

use crate::error::{BeamError, positive};
use crate::fe::shape::hermite;
use crate::modal::Derivative;

use super::rail::{RailBeam, RailSection};

/// One rail element of length h: stiffness, consistent mass and shape functions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailElement {
    length: f64,
    /// φ = 12 EI / (κGA h²); `None` for the Euler–Bernoulli (Hermite) element.
    shear_parameter: Option<f64>,
    stiffness: [[f64; 4]; 4],
    mass: [[f64; 4]; 4],
}

impl RailElement {
    /// The element of `rail` (its beam theory) of length `length` \[m\] (> 0).
    pub fn new(rail: &RailSection, length: f64) -> Result<Self, BeamError> {
        positive("element_length", length)?;
        let (ei, m, h) = (rail.bending_stiffness(), rail.mass_per_length(), length);
        Ok(match rail.beam() {
            RailBeam::EulerBernoulli => Self {
                length,
                shear_parameter: None,
                stiffness: hermite_stiffness(ei, h),
                mass: hermite_mass(m, h),
            },
            RailBeam::Timoshenko => {
                let phi = 12.0 * ei / (rail.shear_stiffness() * h * h);
                let mut element = Self {
                    length,
                    shear_parameter: Some(phi),
                    stiffness: timoshenko_stiffness(ei, h, phi),
                    mass: [[0.0; 4]; 4],
                };
                element.mass = element.consistent_mass(m, rail.rotary_inertia());
                element
            }
        })
    }

    /// Element length h \[m\].
    pub fn length(&self) -> f64 {
        self.length
    }

    /// φ = 12 EI / (κGA h²) of the Timoshenko element (`None`: Euler–Bernoulli).
    pub fn shear_parameter(&self) -> Option<f64> {
        self.shear_parameter
    }

    /// Element stiffness matrix (DOFs w₁, θ₁, w₂, θ₂).
    pub fn stiffness(&self) -> &[[f64; 4]; 4] {
        &self.stiffness
    }

    /// Consistent element mass matrix.
    pub fn mass(&self) -> &[[f64; 4]; 4] {
        &self.mass
    }

    /// Displacement shape functions N_w at ξ ∈ \[0, 1\] (Hermite for Euler–Bernoulli).
    pub fn displacement_shape(&self, xi: f64) -> [f64; 4] {
        let h = self.length;
        match self.shear_parameter {
            None => hermite(xi, h, Derivative::Shape),
            Some(phi) => {
                let (x2, x3) = (xi * xi, xi * xi * xi);
                let c = 1.0 / (1.0 + phi);
                let b = 0.5 * phi * (xi - x2);
                [
                    c * (1.0 - 3.0 * x2 + 2.0 * x3 + phi * (1.0 - xi)),
                    c * h * (xi - 2.0 * x2 + x3 + b),
                    c * (3.0 * x2 - 2.0 * x3 + phi * xi),
                    c * h * (x3 - x2 - b),
                ]
            }
        }
    }

    /// Rotation shape functions N_ψ at ξ (the slope w' of the Hermite functions for
    /// Euler–Bernoulli).
    pub fn rotation_shape(&self, xi: f64) -> [f64; 4] {
        let h = self.length;
        match self.shear_parameter {
            None => hermite(xi, h, Derivative::Slope),
            Some(phi) => {
                let x2 = xi * xi;
                let c = 1.0 / (1.0 + phi);
                [
                    c * 6.0 * (x2 - xi) / h,
                    c * (1.0 - 4.0 * xi + 3.0 * x2 + phi * (1.0 - xi)),
                    c * 6.0 * (xi - x2) / h,
                    c * (3.0 * x2 - 2.0 * xi + phi * xi),
                ]
            }
        }
    }

    /// ∫₀ʰ (m N_w N_wᵀ + ρI N_ψ N_ψᵀ) dx by 4-point Gauss–Legendre (exact: degree ≤ 6).
    fn consistent_mass(&self, m: f64, rho_i: f64) -> [[f64; 4]; 4] {
        const GAUSS: [(f64, f64); 4] = [
            (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
            (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
        ];
        let mut out = [[0.0; 4]; 4];
        for (t, w) in GAUSS {
            let xi = 0.5 * (t + 1.0);
            let (nw, npsi) = (self.displacement_shape(xi), self.rotation_shape(xi));
            let dx = 0.5 * w * self.length;
            for a in 0..4 {
                for b in 0..4 {
                    out[a][b] += dx * (m * nw[a] * nw[b] + rho_i * npsi[a] * npsi[b]);
                }
            }
        }
        out
    }
}

/// Hermite element stiffness EI/h³ \[\[12, 6h, −12, 6h\], …\] (DOFs w₁, θ₁, w₂, θ₂).
pub(crate) fn hermite_stiffness(ei: f64, h: f64) -> [[f64; 4]; 4] {
    let c = ei / (h * h * h);
    let (h2, hh) = (h * h, h);
    [
        [12.0 * c, 6.0 * hh * c, -12.0 * c, 6.0 * hh * c],
        [6.0 * hh * c, 4.0 * h2 * c, -6.0 * hh * c, 2.0 * h2 * c],
        [-12.0 * c, -6.0 * hh * c, 12.0 * c, -6.0 * hh * c],
        [6.0 * hh * c, 2.0 * h2 * c, -6.0 * hh * c, 4.0 * h2 * c],
    ]
}

/// Consistent Hermite element mass m h/420 \[\[156, 22h, 54, −13h\], …\].
pub(crate) fn hermite_mass(m: f64, h: f64) -> [[f64; 4]; 4] {
    let c = m * h / 420.0;
    let h2 = h * h;
    [
        [156.0 * c, 22.0 * h * c, 54.0 * c, -13.0 * h * c],
        [22.0 * h * c, 4.0 * h2 * c, 13.0 * h * c, -3.0 * h2 * c],
        [54.0 * c, 13.0 * h * c, 156.0 * c, -22.0 * h * c],
        [-13.0 * h * c, -3.0 * h2 * c, -22.0 * h * c, 4.0 * h2 * c],
    ]
}

/// The IIE stiffness EI/((1 + φ)h³) \[\[12, 6h, −12, 6h\], \[6h, (4 + φ)h², −6h, (2 − φ)h²\], …\].
fn timoshenko_stiffness(ei: f64, h: f64, phi: f64) -> [[f64; 4]; 4] {
    let c = ei / ((1.0 + phi) * h * h * h);
    let h2 = h * h;
    let (d, o) = ((4.0 + phi) * h2 * c, (2.0 - phi) * h2 * c);
    [
        [12.0 * c, 6.0 * h * c, -12.0 * c, 6.0 * h * c],
        [6.0 * h * c, d, -6.0 * h * c, o],
        [-12.0 * c, -6.0 * h * c, 12.0 * c, -6.0 * h * c],
        [6.0 * h * c, o, -6.0 * h * c, d],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The IIE stiffness equals the strain energy of its own shape functions,
    /// ∫ (EI N_ψ'N_ψ'ᵀ + κGA γγᵀ) dx with γ = N_w' − N_ψ (derivatives by central differences,
    /// quadrature by 8-point composite Simpson on 400 panels: 1e-7 relative), so the stiffness
    /// and the interpolation that carries the wheel are one element; the shear strain of the
    /// shape functions is constant (equilibrium without distributed load); φ → 0 gives Hermite
    /// (differences O(φ), asserted 2φ); the mass of a rigid translation is m h (1e-13).
    #[test]
    fn iie_is_consistent_with_its_shape_functions() {
        let rail = RailSection::e60().timoshenko();
        let h = 0.15;
        let el = RailElement::new(&rail, h).unwrap();
        let (ei, s) = (rail.bending_stiffness(), rail.shear_stiffness());
        let phi = el.shear_parameter().unwrap();
        assert!((phi - 12.0 * ei / (s * h * h)).abs() < 1e-15);
        let e = 1e-6;
        let deriv = |f: &dyn Fn(f64) -> [f64; 4], xi: f64| -> [f64; 4] {
            let (a, b) = (f(xi + e), f(xi - e));
            std::array::from_fn(|i| (a[i] - b[i]) / (2.0 * e * h))
        };
        let nw = |xi: f64| el.displacement_shape(xi);
        let npsi = |xi: f64| el.rotation_shape(xi);
        let panels = 400;
        let mut k = [[0.0; 4]; 4];
        for p in 0..panels {
            for (q, wq) in [(0.0, 1.0), (0.5, 4.0), (1.0, 1.0)] {
                let xi = (p as f64 + q) / panels as f64;
                let (dw, dpsi, psi) = (deriv(&nw, xi), deriv(&npsi, xi), npsi(xi));
                let gamma: [f64; 4] = std::array::from_fn(|i| dw[i] - psi[i]);
                let wx = wq / 6.0 * h / panels as f64;
                for a in 0..4 {
                    for b in 0..4 {
                        k[a][b] += wx * (ei * dpsi[a] * dpsi[b] + s * gamma[a] * gamma[b]);
                    }
                }
            }
        }
        let scale = el.stiffness()[0][0];
        // Rotation DOFs scaled by 1/h: every entry in N/m.
        let unit = |a: usize| if a % 2 == 1 { h } else { 1.0 };
        for (a, row) in k.iter().enumerate() {
            for (b, got) in row.iter().enumerate() {
                let want = el.stiffness()[a][b] / (unit(a) * unit(b));
                let got = got / (unit(a) * unit(b));
                assert!(
                    (got - want).abs() < 1e-7 * scale,
                    "K[{a}][{b}] {got} vs {want}"
                );
            }
        }
        // Constant shear strain along the element.
        for i in 0..4 {
            let g = |xi: f64| deriv(&nw, xi)[i] - npsi(xi)[i];
            assert!((g(0.1) - g(0.9)).abs() < 1e-6 * g(0.5).abs().max(1.0 / h));
        }
        // φ → 0: Hermite.
        let eb = RailElement::new(&rail.with_beam(RailBeam::EulerBernoulli), h).unwrap();
        let stiff = RailElement::new(&rail.with_shear(1e16, 0.0).unwrap(), h).unwrap();
        // φ = 3.4e-7 here: the matrices differ from Hermite by O(φ).
        let phi_stiff = stiff.shear_parameter().unwrap();
        for a in 0..4 {
            for b in 0..4 {
                let d = (stiff.stiffness()[a][b] - eb.stiffness()[a][b]).abs();
                assert!(d < 2.0 * phi_stiff * eb.stiffness()[0][0], "{d}");
                let dm = (stiff.mass()[a][b] - eb.mass()[a][b]).abs();
                assert!(dm < 2.0 * phi_stiff * eb.mass()[0][0], "{dm}");
            }
            let xi = 0.3;
            let d = stiff.displacement_shape(xi)[a] - eb.displacement_shape(xi)[a];
            assert!(d.abs() < 2.0 * phi_stiff * h.max(1.0), "{d}");
        }
        // Rigid translation: mass m h; partition of unity of N_w.
        let mt: f64 = [0, 2]
            .iter()
            .flat_map(|&a| [0, 2].map(|b| el.mass()[a][b]))
            .sum();
        assert!((mt - rail.mass_per_length() * h).abs() < 1e-13 * mt, "{mt}");
        let n = el.displacement_shape(0.37);
        assert!((n[0] + n[2] - 1.0).abs() < 1e-15);
    }
}
