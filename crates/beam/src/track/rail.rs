//! Rail cross-sections: bending stiffness and mass per length of one rail (references.md §D5.1).

use crate::error::{BENDING_STIFFNESS_RANGE, BeamError, MASS_PER_LENGTH_RANGE, in_range, positive};

/// Young's modulus of rail steel used by the EN presets \[Pa\] (references.md §D5.1).
pub const RAIL_STEEL_YOUNGS_MODULUS: f64 = 210e9;

/// One rail as an Euler–Bernoulli beam: bending stiffness EI \[N m²\] about the horizontal axis
/// and mass per length \[kg/m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailSection {
    bending_stiffness: f64,
    mass_per_length: f64,
}

impl RailSection {
    /// A rail of bending stiffness EI \[N m²\] and mass per length m \[kg/m\] (both checked
    /// against the physical ranges of the beam crate).
    pub fn new(bending_stiffness: f64, mass_per_length: f64) -> Result<Self, BeamError> {
        positive("bending_stiffness", bending_stiffness)?;
        positive("mass_per_length", mass_per_length)?;
        in_range(
            "bending_stiffness",
            bending_stiffness,
            BENDING_STIFFNESS_RANGE,
            "N m^2",
        )?;
        in_range(
            "mass_per_length",
            mass_per_length,
            MASS_PER_LENGTH_RANGE,
            "kg/m",
        )?;
        Ok(Self {
            bending_stiffness,
            mass_per_length,
        })
    }

    /// 60E1 (UIC60), EN 13674-1: 60.21 kg/m, I = 3038.3 cm⁴, E = 210 GPa (references.md §D5.1).
    pub fn e60() -> Self {
        Self {
            bending_stiffness: RAIL_STEEL_YOUNGS_MODULUS * 3038.3e-8,
            mass_per_length: 60.21,
        }
    }

    /// 54E1 (UIC54), EN 13674-1: 54.77 kg/m, I = 2337.9 cm⁴, E = 210 GPa (references.md §D5.1).
    pub fn e54() -> Self {
        Self {
            bending_stiffness: RAIL_STEEL_YOUNGS_MODULUS * 2337.9e-8,
            mass_per_length: 54.77,
        }
    }

    /// The 60 kg/m rail of Zhai, Wang & Lin (2004): E = 2.059e11 Pa, I = 3.217e-5 m⁴,
    /// 60.64 kg/m (references.md §D2.5, §D5.2), the rail of [`super::SupportStack::ballasted_high_speed`].
    pub fn chn60() -> Self {
        Self {
            bending_stiffness: 2.059e11 * 3.217e-5,
            mass_per_length: 60.64,
        }
    }

    /// A preset by name: `"60E1"`/`"UIC60"`, `"54E1"`/`"UIC54"`, `"CHN60"` (case-insensitive).
    pub fn by_name(name: &str) -> Option<Self> {
        match name.to_ascii_uppercase().as_str() {
            "60E1" | "UIC60" => Some(Self::e60()),
            "54E1" | "UIC54" => Some(Self::e54()),
            "CHN60" => Some(Self::chn60()),
            _ => None,
        }
    }

    /// Bending stiffness EI \[N m²\].
    pub fn bending_stiffness(&self) -> f64 {
        self.bending_stiffness
    }

    /// Mass per length \[kg/m\].
    pub fn mass_per_length(&self) -> f64 {
        self.mass_per_length
    }

    /// Pinned–pinned frequency of an Euler–Bernoulli rail on supports `spacing` apart \[Hz\]:
    /// f_pp = (π/d)² √(EI/m) / (2π) (references.md §D5.3).
    pub fn pinned_pinned_frequency(&self, spacing: f64) -> f64 {
        let k = std::f64::consts::PI / spacing;
        k * k * (self.bending_stiffness / self.mass_per_length).sqrt()
            / (2.0 * std::f64::consts::PI)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The presets carry the published section values; names resolve case-insensitively;
    /// bad input is refused with the parameter named.
    #[test]
    fn presets_and_validation() {
        let r = RailSection::by_name("uic60").unwrap();
        assert_eq!(r, RailSection::e60());
        assert!((r.bending_stiffness() - 6.38043e6).abs() < 1.0);
        assert!((RailSection::e54().mass_per_length() - 54.77).abs() < 1e-12);
        assert!(RailSection::by_name("49E1").is_none());
        let err = RailSection::new(-1.0, 60.0).unwrap_err().to_string();
        assert!(err.contains("bending_stiffness"), "{err}");
        // f_pp of 60E1 at 0.6 m: (π/0.6)² √(6.38043e6/60.21)/(2π) = 1420.39 Hz (computed by hand, 6 digits).
        let f = RailSection::e60().pinned_pinned_frequency(0.6);
        assert!((f - 1420.39).abs() < 0.01, "{f}");
    }
}
