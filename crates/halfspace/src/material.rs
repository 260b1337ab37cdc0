//! Elastic materials of the two bodies and their combined constants.
//!
//! Combined constants after Kalker, as used by CONTACT (references.md §C3.1):
//!
//! * 1/G = ½ (1/G₁ + 1/G₂)
//! * ν/G = ½ (ν₁/G₁ + ν₂/G₂)
//! * K/G = ¼ [(1 − 2ν₁)/G₁ − (1 − 2ν₂)/G₂]   (Kalker's difference parameter)
//! * E* = G/(1 − ν), equal to the classical 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
//!
//! A rigid body has 1/G = 0. Body 1 is the upper body.

use crate::error::{ContactError, finite, in_range, positive};

/// Allowed Young's and shear moduli \[Pa\]: 1 Pa … 1e18 Pa (soft gels are ~1e3 Pa, diamond
/// ~1.2e12 Pa; 1 Pa admits unit-scaled problems, 1e18 Pa the near-rigid penalty studies that
/// scale steel by 1e4 and more).
pub const MODULUS_RANGE: (f64, f64) = (1.0, 1e18);

/// One of the two bodies in contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Body {
    /// A rigid body (infinite modulus).
    Rigid,
    /// A linear elastic body with Young's modulus `e` \[Pa\] and Poisson's ratio `nu`.
    Elastic { e: f64, nu: f64 },
}

impl Body {
    /// An elastic body, validated: E in [`MODULUS_RANGE`], −1 < ν < 0.5.
    pub fn elastic(e: f64, nu: f64) -> Result<Self, ContactError> {
        positive("E", e)?;
        let (lo, hi) = MODULUS_RANGE;
        in_range("E", e, lo, hi, "must lie in [1, 1e18] Pa")?;
        finite("nu", nu)?;
        if nu >= 0.5 {
            return Err(ContactError::InvalidParameter {
                name: "nu",
                value: nu,
                reason: "must be below 0.5 (0.5 is incompressible, not a valid half-space material here)",
            });
        }
        if nu <= -1.0 {
            return Err(ContactError::InvalidParameter {
                name: "nu",
                value: nu,
                reason: "must be above -1",
            });
        }
        Ok(Body::Elastic { e, nu })
    }

    /// Shear modulus G = E / (2(1 + ν)); `None` for a rigid body.
    pub fn shear_modulus(&self) -> Option<f64> {
        match *self {
            Body::Rigid => None,
            Body::Elastic { e, nu } => Some(e / (2.0 * (1.0 + nu))),
        }
    }
}

/// Combined elastic constants of a pair of bodies (references.md §C3.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Combined shear modulus G \[Pa\].
    pub g: f64,
    /// Combined Poisson's ratio ν.
    pub nu: f64,
    /// Kalker's difference parameter K (0 for quasi-identical bodies).
    pub k: f64,
    /// Effective modulus E* = G/(1 − ν) \[Pa\].
    pub e_star: f64,
}

impl Material {
    /// Combine the upper body 1 and the lower body 2.
    pub fn combine(body1: Body, body2: Body) -> Result<Self, ContactError> {
        let (c1, nu1) = compliance(&body1)?;
        let (c2, nu2) = compliance(&body2)?;
        if c1 == 0.0 && c2 == 0.0 {
            return Err(ContactError::BothRigid);
        }
        // c = 1/G of each body; 1/G = (c1 + c2)/2.
        let g = 2.0 / (c1 + c2);
        let nu = 0.5 * g * (nu1 * c1 + nu2 * c2);
        let k = 0.25 * g * ((1.0 - 2.0 * nu1) * c1 - (1.0 - 2.0 * nu2) * c2);
        Ok(Material {
            g,
            nu,
            k,
            e_star: g / (1.0 - nu),
        })
    }

    /// Two bodies of the same elastic material.
    pub fn identical(e: f64, nu: f64) -> Result<Self, ContactError> {
        let body = Body::elastic(e, nu)?;
        Self::combine(body, body)
    }

    /// Directly from combined G and ν (CONTACT's input form).
    pub fn from_combined(g: f64, nu: f64) -> Result<Self, ContactError> {
        positive("G", g)?;
        let (lo, hi) = MODULUS_RANGE;
        in_range("G", g, lo, hi, "must lie in [1, 1e18] Pa")?;
        finite("nu", nu)?;
        if !(-1.0..0.5).contains(&nu) {
            return Err(ContactError::InvalidParameter {
                name: "nu",
                value: nu,
                reason: "must lie in (-1, 0.5)",
            });
        }
        Ok(Material {
            g,
            nu,
            k: 0.0,
            e_star: g / (1.0 - nu),
        })
    }
}

/// (1/G, ν) of one body, 1/G = 0 when rigid.
fn compliance(body: &Body) -> Result<(f64, f64), ContactError> {
    match *body {
        Body::Rigid => Ok((0.0, 0.0)),
        Body::Elastic { e, nu } => {
            // Re-validate: the enum may have been built without `Body::elastic`.
            Body::elastic(e, nu)?;
            Ok((2.0 * (1.0 + nu) / e, nu))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn e_star_matches_classical_formula() {
        let (e1, nu1, e2, nu2) = (210e9, 0.3, 70e9, 0.33);
        let m = Material::combine(
            Body::elastic(e1, nu1).unwrap(),
            Body::elastic(e2, nu2).unwrap(),
        )
        .unwrap();
        let classical = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
        assert_relative_eq!(m.e_star, classical, max_relative = 1e-14);
    }

    #[test]
    fn rigid_on_elastic_doubles_g_and_gives_kalker_k() {
        // references.md §C3.1: rigid ball on elastic half-space: G = 2 G_el, ν = ν_el,
        // K = −(1 − 2ν)/2 when the elastic body is body 2.
        let el = Body::elastic(210e9, 0.3).unwrap();
        let m = Material::combine(Body::Rigid, el).unwrap();
        let g_el = 210e9 / 2.6;
        assert_relative_eq!(m.g, 2.0 * g_el, max_relative = 1e-14);
        assert_relative_eq!(m.nu, 0.3, max_relative = 1e-14);
        assert_relative_eq!(m.k, -(1.0 - 0.6) / 2.0, max_relative = 1e-14);
        let swapped = Material::combine(el, Body::Rigid).unwrap();
        assert_relative_eq!(swapped.k, -m.k, max_relative = 1e-14);
        assert_relative_eq!(m.e_star, 210e9 / (1.0 - 0.09), max_relative = 1e-14);
    }

    #[test]
    fn identical_bodies_have_zero_k() {
        let m = Material::identical(210e9, 0.28).unwrap();
        assert_eq!(m.k, 0.0);
    }

    #[test]
    fn invalid_materials_are_rejected() {
        assert!(matches!(
            Body::elastic(-1.0, 0.3),
            Err(ContactError::InvalidParameter { name: "E", .. })
        ));
        assert!(matches!(
            Body::elastic(1e9, 0.5),
            Err(ContactError::InvalidParameter { name: "nu", .. })
        ));
        assert!(matches!(
            Body::elastic(f64::NAN, 0.3),
            Err(ContactError::InvalidParameter { name: "E", .. })
        ));
        assert!(matches!(
            Material::combine(Body::Rigid, Body::Rigid),
            Err(ContactError::BothRigid)
        ));
    }

    #[test]
    fn moduli_outside_the_physical_range_are_named() {
        for e in [1e-300, 0.5, 1e300, 2e18] {
            let err = Body::elastic(e, 0.3).unwrap_err();
            assert!(matches!(
                err,
                ContactError::InvalidParameter { name: "E", .. }
            ));
            assert!(err.to_string().contains("[1, 1e18] Pa"), "{err}");
            let err = Material::from_combined(e, 0.3).unwrap_err();
            assert!(matches!(
                err,
                ContactError::InvalidParameter { name: "G", .. }
            ));
        }
        assert!(Body::elastic(1.0, 0.3).is_ok() && Body::elastic(1e18, 0.3).is_ok());
    }
}
