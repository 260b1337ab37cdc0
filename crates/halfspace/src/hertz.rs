//! Hertz's closed-form solutions: elliptic (3D), spherical and 2D line contact.
//!
//! For the quadratic gap h = A x² + B y² (references.md §C4.1), with ρ = 2/(A + B):
//!
//! * the ratio g = (smaller semi-axis)/(larger) solves
//!   (smaller curvature)/(larger curvature) = (K(k) − E(k)) / (E(k)/g² − K(k)), k² = 1 − g²,
//!   and the smaller curvature belongs to the larger semi-axis;
//! * c = √(ab) with c³ = 3 F ρ E(k) / (4π E* √g);
//! * approach δ = 2 a_min² K(k) / (ρ E(k)); peak pressure p₀ = 3F/(2π a b);
//! * pressure p(x, y) = p₀ √(1 − x²/a² − y²/b²).
//!
//! Sphere (A = B = 1/(2R)): a = (3FR/(4E*))^{1/3}, δ = a²/R.
//! Line contact per unit length F': a² = 4RF'/(πE*), p₀ = 2F'/(πa) (1/R = 2A).
//!
//! K and E are the complete elliptic integrals of the first and second kind (the `ellip`
//! crate, parameter m = k²).

use crate::error::{ContactError, positive};

/// The Hertzian solution of an elliptic contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Semi-axis along x \[m\].
    pub a: f64,
    /// Semi-axis along y \[m\].
    pub b: f64,
    /// Approach δ \[m\].
    pub approach: f64,
    /// Peak pressure p₀ \[Pa\].
    pub max_pressure: f64,
    /// Total normal force F_n \[N\].
    pub normal_force: f64,
    /// Contact stiffness dF_n/dδ = 3F/(2δ) [N/m] (F ∝ δ^{3/2}).
    pub stiffness: f64,
}

/// Complete elliptic integrals (K(m), E(m)), m = k².
fn complete_elliptic(m: f64) -> (f64, f64) {
    let k = ellip::ellipk(m).expect("0 <= m < 1 by construction");
    let e = ellip::ellipe(m).expect("0 <= m < 1 by construction");
    (k, e)
}

/// Curvature ratio (smaller/larger) of the gap that gives the semi-axis ratio `g` ≤ 1.
pub fn curvature_ratio(g: f64) -> f64 {
    if g >= 1.0 {
        return 1.0;
    }
    let (k, e) = complete_elliptic(1.0 - g * g);
    (k - e) / (e / (g * g) - k)
}

/// Semi-axis ratio g = a_min/a_max ∈ (0, 1] for a curvature ratio in (0, 1], by bisection
/// (the ratio is increasing in g).
pub fn semi_axis_ratio(curvature_ratio_target: f64) -> f64 {
    if curvature_ratio_target >= 1.0 {
        return 1.0;
    }
    let (mut lo, mut hi) = (1e-12_f64, 1.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if curvature_ratio(mid) < curvature_ratio_target {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-16 {
            break;
        }
    }
    0.5 * (lo + hi)
}

impl Hertz {
    /// Elliptic contact of the gap h = A x² + B y² [1/m] under the force `force` \[N\], with
    /// effective modulus `e_star` \[Pa\].
    pub fn elliptic(
        a_curv: f64,
        b_curv: f64,
        e_star: f64,
        force: f64,
    ) -> Result<Self, ContactError> {
        positive("A", a_curv)?;
        positive("B", b_curv)?;
        positive("E*", e_star)?;
        positive("force", force)?;
        let (small, large) = if a_curv <= b_curv {
            (a_curv, b_curv)
        } else {
            (b_curv, a_curv)
        };
        let g = semi_axis_ratio(small / large);
        let (kk, ee) = complete_elliptic(1.0 - g * g);
        let rho = 2.0 / (a_curv + b_curv);
        let c = (3.0 * force * rho * ee / (4.0 * std::f64::consts::PI * e_star * g.sqrt())).cbrt();
        let (a_min, a_max) = (c * g.sqrt(), c / g.sqrt());
        // The smaller curvature belongs to the larger semi-axis.
        let (a, b) = if a_curv <= b_curv {
            (a_max, a_min)
        } else {
            (a_min, a_max)
        };
        let approach = 2.0 * a_min * a_min * kk / (rho * ee);
        Ok(Hertz {
            a,
            b,
            approach,
            max_pressure: 3.0 * force / (2.0 * std::f64::consts::PI * a * b),
            normal_force: force,
            stiffness: 1.5 * force / approach,
        })
    }

    /// Elliptic contact at a prescribed approach δ \[m\] (F ∝ δ^{3/2}).
    pub fn elliptic_at_approach(
        a_curv: f64,
        b_curv: f64,
        e_star: f64,
        approach: f64,
    ) -> Result<Self, ContactError> {
        positive("approach", approach)?;
        let unit = Self::elliptic(a_curv, b_curv, e_star, 1.0)?;
        let force = (approach / unit.approach).powf(1.5);
        Self::elliptic(a_curv, b_curv, e_star, force)
    }

    /// A sphere of combined radius `radius` \[m\] on a plane (A = B = 1/(2R)).
    pub fn sphere(radius: f64, e_star: f64, force: f64) -> Result<Self, ContactError> {
        positive("radius", radius)?;
        let c = 0.5 / radius;
        Self::elliptic(c, c, e_star, force)
    }

    /// Force of a sphere at approach δ: F = (4/3) E* √R δ^{3/2} (0 for δ ≤ 0).
    pub fn sphere_force(radius: f64, e_star: f64, approach: f64) -> f64 {
        if approach <= 0.0 {
            0.0
        } else {
            4.0 / 3.0 * e_star * radius.sqrt() * approach.powf(1.5)
        }
    }

    /// Hertz pressure at (x, y) relative to the centre of the contact.
    pub fn pressure_at(&self, x: f64, y: f64) -> f64 {
        let s = 1.0 - (x / self.a).powi(2) - (y / self.b).powi(2);
        if s > 0.0 {
            self.max_pressure * s.sqrt()
        } else {
            0.0
        }
    }
}

/// Quadratic gap coefficients A, B [1/m] from the principal radii of curvature of both
/// bodies along x and y (positive when convex; `f64::INFINITY` for a flat direction):
/// A = ½(1/R₁ₓ + 1/R₂ₓ), B = ½(1/R₁ᵧ + 1/R₂ᵧ).
pub fn curvatures_from_radii(
    r1x: f64,
    r1y: f64,
    r2x: f64,
    r2y: f64,
) -> Result<(f64, f64), ContactError> {
    let inv = |name: &'static str, r: f64| -> Result<f64, ContactError> {
        if r.is_nan() || r == 0.0 {
            return Err(ContactError::InvalidParameter {
                name,
                value: r,
                reason: "a radius of curvature must be non-zero (use infinity for flat)",
            });
        }
        Ok(1.0 / r)
    };
    let a = 0.5 * (inv("r1x", r1x)? + inv("r2x", r2x)?);
    let b = 0.5 * (inv("r1y", r1y)? + inv("r2y", r2y)?);
    if a <= 0.0 || b <= 0.0 {
        return Err(ContactError::InvalidParameter {
            name: "radii",
            value: a.min(b),
            reason: "the combined curvature must be positive in both directions (the bodies must touch at a point)",
        });
    }
    Ok((a, b))
}

/// Hertz's 2D line contact (per unit length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineHertz {
    /// Half-width of the contact strip \[m\].
    pub a: f64,
    /// Peak pressure p₀ \[Pa\].
    pub max_pressure: f64,
    /// Force per unit length F' [N/m].
    pub force_per_length: f64,
}

impl LineHertz {
    /// Line contact of combined radius `radius` \[m\] (1/R = 2A) with force per length F' [N/m].
    pub fn new(radius: f64, e_star: f64, force_per_length: f64) -> Result<Self, ContactError> {
        positive("radius", radius)?;
        positive("E*", e_star)?;
        positive("force per length", force_per_length)?;
        let a = (4.0 * radius * force_per_length / (std::f64::consts::PI * e_star)).sqrt();
        Ok(LineHertz {
            a,
            max_pressure: 2.0 * force_per_length / (std::f64::consts::PI * a),
            force_per_length,
        })
    }

    /// Pressure at x from the strip centre: p₀ √(1 − x²/a²).
    pub fn pressure_at(&self, x: f64) -> f64 {
        let s = 1.0 - (x / self.a).powi(2);
        if s > 0.0 {
            self.max_pressure * s.sqrt()
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn elliptic_integral_table() {
        // references.md §C4.1 test vectors (AGM): g, K, E, D_min/D_max.
        let table = [
            (0.1, 3.695637, 1.015994, 0.027370),
            (0.2, 3.016112, 1.050502, 0.084555),
            (0.3, 2.627773, 1.096478, 0.160256),
            (0.5, 2.156516, 1.211056, 0.351772),
            (0.7, 1.862641, 1.345592, 0.585250),
            (0.9, 1.654617, 1.493290, 0.853799),
        ];
        for (g, k, e, ratio) in table {
            let (kk, ee) = complete_elliptic(1.0 - g * g);
            assert_relative_eq!(kk, k, max_relative = 1e-6);
            assert_relative_eq!(ee, e, max_relative = 1e-6);
            assert_relative_eq!(curvature_ratio(g), ratio, max_relative = 2e-5);
            assert_relative_eq!(semi_axis_ratio(ratio), g, max_relative = 1e-4);
        }
    }

    #[test]
    fn sphere_closed_form() {
        let (r, e_star, f) = (0.01, 230e9, 1000.0);
        let h = Hertz::sphere(r, e_star, f).unwrap();
        let a = (3.0 * f * r / (4.0 * e_star)).cbrt();
        assert_relative_eq!(h.a, a, max_relative = 1e-12);
        assert_relative_eq!(h.b, a, max_relative = 1e-12);
        assert_relative_eq!(h.approach, a * a / r, max_relative = 1e-12);
        assert_relative_eq!(
            h.max_pressure,
            3.0 * f / (2.0 * std::f64::consts::PI * a * a),
            max_relative = 1e-12
        );
        assert_relative_eq!(
            Hertz::sphere_force(r, e_star, h.approach),
            f,
            max_relative = 1e-12
        );
    }

    #[test]
    fn contact_worked_cases() {
        // references.md §C4.1, CONTACT's units mm, N, N/mm² converted to SI.
        // Cattaneo sphere: G = 200, ν = 0.42, R = 50 → A = B = 0.01/mm; Fn = 9.1954 N gives
        // a = 1 mm, p₀ = 4.3905 N/mm², δ = 0.020000 mm.
        let e_star = 200e6 / (1.0 - 0.42);
        let h = Hertz::elliptic(10.0, 10.0, e_star, 9.1954).unwrap();
        assert_relative_eq!(h.a, 1e-3, max_relative = 2e-5);
        assert_relative_eq!(h.max_pressure, 4.3905e6, max_relative = 2e-5);
        assert_relative_eq!(h.approach, 0.020000e-3, max_relative = 5e-5);
        // tractcurv ellipse: A = 0.0008/mm, B = 2.81417e-4/mm, Fn = 106.7 kN, G = 82000, ν = 0.28
        // → a = 6.30360, b = 12.60719 mm, δ = 0.0765171 mm, p₀ = 641.06 N/mm².
        let e_star = 82000e6 / (1.0 - 0.28);
        let h = Hertz::elliptic(0.8, 0.281417, e_star, 106.7e3).unwrap();
        assert_relative_eq!(h.a, 6.30360e-3, max_relative = 2e-5);
        assert_relative_eq!(h.b, 12.60719e-3, max_relative = 2e-5);
        assert_relative_eq!(h.approach, 0.0765171e-3, max_relative = 2e-5);
        assert_relative_eq!(h.max_pressure, 641.06e6, max_relative = 2e-5);
        // FASTSIM ellipse: A = 8.46419e-4, B = 2.40616e-3 /mm, Fn = 82 kN → a = 8, b = 4 mm,
        // δ = 0.0926694 mm, p₀ = 1223.50.
        let h = Hertz::elliptic(0.846419, 2.40616, e_star, 82e3).unwrap();
        assert_relative_eq!(h.a, 8e-3, max_relative = 2e-5);
        assert_relative_eq!(h.b, 4e-3, max_relative = 2e-5);
        assert_relative_eq!(h.approach, 0.0926694e-3, max_relative = 2e-5);
        assert_relative_eq!(h.max_pressure, 1223.50e6, max_relative = 2e-5);
    }

    #[test]
    fn carter_line_contact() {
        // references.md §C4.1: R = 500 mm, G = 82000, ν = 0.28, a = 1 mm ⇒ F' = 178.90 N/mm,
        // p₀ = 113.88 N/mm².
        let e_star = 82000e6 / (1.0 - 0.28);
        let l = LineHertz::new(0.5, e_star, 178.90e3).unwrap();
        assert_relative_eq!(l.a, 1e-3, max_relative = 1e-4);
        assert_relative_eq!(l.max_pressure, 113.88e6, max_relative = 1e-4);
    }

    #[test]
    fn approach_inversion_and_radii() {
        let h = Hertz::elliptic_at_approach(30.0, 70.0, 1e11, 2e-5).unwrap();
        assert_relative_eq!(h.approach, 2e-5, max_relative = 1e-12);
        let (a, b) = curvatures_from_radii(0.46, f64::INFINITY, f64::INFINITY, 0.3).unwrap();
        assert_relative_eq!(a, 0.5 / 0.46, max_relative = 1e-15);
        assert_relative_eq!(b, 0.5 / 0.3, max_relative = 1e-15);
        assert!(curvatures_from_radii(0.0, 1.0, 1.0, 1.0).is_err());
    }
}
