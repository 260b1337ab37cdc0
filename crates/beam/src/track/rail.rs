//! Rail cross-sections: bending stiffness, mass per length, shear stiffness κGA and rotary
//! inertia ρI of one rail, and the beam theory its elements use (references.md §D5.1, §D5.5).

use crate::error::{BENDING_STIFFNESS_RANGE, BeamError, MASS_PER_LENGTH_RANGE, in_range, positive};

/// Young's modulus of rail steel used by the EN presets \[Pa\] (references.md §D5.1).
pub const RAIL_STEEL_YOUNGS_MODULUS: f64 = 210e9;

/// Poisson's ratio of rail steel: G = E / (2 (1 + ν)) (references.md §D5.5).
pub const RAIL_STEEL_POISSON_RATIO: f64 = 0.3;

/// Shear coefficient κ of a rail in vertical bending (references.md §D5.5).
pub const RAIL_SHEAR_COEFFICIENT: f64 = 0.4;

/// Range of the shear stiffness κGA \[N\] (from 1e6, about 1/250 of the presets' 2.3e8–2.5e8 N:
/// with 1e3 N a rail under a wheel moved 9.4e3 m before the run failed; up to 1e16: the
/// Euler–Bernoulli limit in tests).
pub const SHEAR_STIFFNESS_RANGE: (f64, f64) = (1e6, 1e16);

/// Range of the rotary inertia ρI per length \[kg m\].
pub const ROTARY_INERTIA_RANGE: (f64, f64) = (0.0, 1e4);

/// The beam theory of the rail elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RailBeam {
    /// Euler–Bernoulli: Hermite cubic elements (no shear deformation, no rotary inertia).
    #[default]
    EulerBernoulli,
    /// Timoshenko: shear deformation (κGA) and rotary inertia (ρI), in the two-node
    /// interdependent-interpolation element ([`super::RailElement`], references.md §D5.5).
    Timoshenko,
}

impl RailBeam {
    /// By name: `"euler_bernoulli"` or `"timoshenko"`.
    pub fn by_name(name: &str) -> Option<Self> {
        match name {
            "euler_bernoulli" => Some(Self::EulerBernoulli),
            "timoshenko" => Some(Self::Timoshenko),
            _ => None,
        }
    }

    /// The name `by_name` accepts.
    pub fn name(self) -> &'static str {
        match self {
            Self::EulerBernoulli => "euler_bernoulli",
            Self::Timoshenko => "timoshenko",
        }
    }
}

/// One rail: bending stiffness EI \[N m²\] about the horizontal axis, mass per length \[kg/m\],
/// shear stiffness κGA \[N\] and rotary inertia ρI \[kg m\] (used by the Timoshenko beam
/// only), and the beam theory of its elements (Euler–Bernoulli unless [`Self::timoshenko`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailSection {
    bending_stiffness: f64,
    mass_per_length: f64,
    shear_stiffness: f64,
    rotary_inertia: f64,
    beam: RailBeam,
}

/// κGA and ρI of a homogeneous steel rail of area `area` \[m²\], second moment `inertia`
/// \[m⁴\], mass per length `mass` \[kg/m\] and Young's modulus `youngs` \[Pa\]:
/// κ G A with G = E/(2(1 + ν)), and ρI = (m/A) I.
fn shear_data(youngs: f64, area: f64, inertia: f64, mass: f64) -> (f64, f64) {
    let g = youngs / (2.0 * (1.0 + RAIL_STEEL_POISSON_RATIO));
    (RAIL_SHEAR_COEFFICIENT * g * area, mass / area * inertia)
}

impl RailSection {
    /// An Euler–Bernoulli rail of bending stiffness EI \[N m²\] and mass per length m \[kg/m\]
    /// (both checked against the physical ranges of the beam crate), without shear data
    /// (κGA = ∞, ρI = 0 until [`Self::with_shear`]).
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
            shear_stiffness: f64::INFINITY,
            rotary_inertia: 0.0,
            beam: RailBeam::EulerBernoulli,
        })
    }

    fn preset(youngs: f64, inertia: f64, mass: f64, area: f64) -> Self {
        let (shear_stiffness, rotary_inertia) = shear_data(youngs, area, inertia, mass);
        Self {
            bending_stiffness: youngs * inertia,
            mass_per_length: mass,
            shear_stiffness,
            rotary_inertia,
            beam: RailBeam::EulerBernoulli,
        }
    }

    /// 60E1 (UIC60), EN 13674-1: 60.21 kg/m, I = 3038.3 cm⁴, A = 76.70 cm², E = 210 GPa
    /// (references.md §D5.1); κGA = 0.4 × 80.77 GPa × A = 2.478e8 N, ρI = 0.2385 kg m
    /// (references.md §D5.5).
    pub fn e60() -> Self {
        Self::preset(RAIL_STEEL_YOUNGS_MODULUS, 3038.3e-8, 60.21, 76.70e-4)
    }

    /// 54E1 (UIC54), EN 13674-1: 54.77 kg/m, I = 2337.9 cm⁴, A = 69.77 cm², E = 210 GPa
    /// (references.md §D5.1); κGA = 2.254e8 N, ρI = 0.1835 kg m (references.md §D5.5).
    pub fn e54() -> Self {
        Self::preset(RAIL_STEEL_YOUNGS_MODULUS, 2337.9e-8, 54.77, 69.77e-4)
    }

    /// The 60 kg/m rail of Zhai, Wang & Lin (2004): E = 2.059e11 Pa, I = 3.217e-5 m⁴,
    /// 60.64 kg/m (references.md §D2.5, §D5.2), the rail of [`super::SupportStack::ballasted_high_speed`];
    /// A = 77.45 cm² for κGA and ρI (references.md §D5.5).
    pub fn chn60() -> Self {
        Self::preset(2.059e11, 3.217e-5, 60.64, 77.45e-4)
    }

    /// The same rail in Timoshenko beam elements (its κGA and ρI; see [`RailBeam`]).
    pub fn timoshenko(mut self) -> Self {
        self.beam = RailBeam::Timoshenko;
        self
    }

    /// The same rail with the beam theory `beam`.
    pub fn with_beam(mut self, beam: RailBeam) -> Self {
        self.beam = beam;
        self
    }

    /// The same rail with shear stiffness κGA \[N\] (1e3 … 1e16) and rotary inertia ρI
    /// \[kg m\] (0 … 1e4) (used by the Timoshenko beam).
    pub fn with_shear(
        mut self,
        shear_stiffness: f64,
        rotary_inertia: f64,
    ) -> Result<Self, BeamError> {
        in_range(
            "rail_shear_stiffness",
            shear_stiffness,
            SHEAR_STIFFNESS_RANGE,
            "N",
        )?;
        in_range(
            "rail_rotary_inertia",
            rotary_inertia,
            ROTARY_INERTIA_RANGE,
            "kg m",
        )?;
        self.shear_stiffness = shear_stiffness;
        self.rotary_inertia = rotary_inertia;
        Ok(self)
    }

    /// The beam theory of the rail elements.
    pub fn beam(&self) -> RailBeam {
        self.beam
    }

    /// Shear stiffness κGA \[N\] (∞ for a section built without shear data).
    pub fn shear_stiffness(&self) -> f64 {
        self.shear_stiffness
    }

    /// Rotary inertia ρI per length \[kg m\].
    pub fn rotary_inertia(&self) -> f64 {
        self.rotary_inertia
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

    /// Pinned–pinned frequency of the rail on supports `spacing` apart \[Hz\]: the first
    /// frequency of a simply supported span d = `spacing` (references.md §D5.3, §D5.5).
    /// Euler–Bernoulli: f_pp = (π/d)² √(EI/m) / (2π); Timoshenko:
    /// [`Self::simply_supported_frequency`] with n = 1.
    pub fn pinned_pinned_frequency(&self, spacing: f64) -> f64 {
        match self.beam {
            RailBeam::EulerBernoulli => {
                let k = std::f64::consts::PI / spacing;
                k * k * (self.bending_stiffness / self.mass_per_length).sqrt()
                    / (2.0 * std::f64::consts::PI)
            }
            RailBeam::Timoshenko => self.simply_supported_frequency(spacing, 1),
        }
    }

    /// Frequency \[Hz\] of the n-th flexural mode of a simply supported Timoshenko beam of length
    /// `length` with this rail's EI, m, κGA and ρI: with w = W sin kx, ψ = Ψ cos kx, k = nπ/L,
    /// the frequency equation (κGA k² − mω²)(EI k² + κGA − ρI ω²) = (κGA k)², whose lower
    /// root in ω² is the flexural one (references.md §D5.5). κGA = ∞ gives the Rayleigh beam
    /// ω² = EI k⁴ / (m + ρI k²).
    pub fn simply_supported_frequency(&self, length: f64, n: usize) -> f64 {
        let k = n as f64 * std::f64::consts::PI / length;
        let (ei, m, s, j) = (
            self.bending_stiffness,
            self.mass_per_length,
            self.shear_stiffness,
            self.rotary_inertia,
        );
        let k2 = k * k;
        let omega2 = if s.is_infinite() {
            ei * k2 * k2 / (m + j * k2)
        } else {
            // m J ω⁴ − (m (EI k² + S) + J S k²) ω² + EI S k⁴ = 0: the smaller root, written
            // as 2c / (b + √(b² − 4ac)) (no cancellation).
            let a = m * j;
            let b = m * (ei * k2 + s) + j * s * k2;
            let c = ei * s * k2 * k2;
            2.0 * c / (b + (b * b - 4.0 * a * c).max(0.0).sqrt())
        };
        omega2.sqrt() / (2.0 * std::f64::consts::PI)
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
        // Shear data (by hand): 60E1 κGA = 0.4 × 210e9/2.6 × 76.70e-4 = 2.478e8 N,
        // ρI = 60.21 × 3038.3e-8 / 76.70e-4 = 0.238509 kg m; 54E1 2.25411e8 N, 0.183527 kg m.
        assert_eq!(r.beam(), RailBeam::EulerBernoulli);
        assert!((r.shear_stiffness() / 2.478e8 - 1.0).abs() < 1e-12);
        assert!((r.rotary_inertia() - 0.238509).abs() < 1e-6);
        let r54 = RailSection::e54();
        assert!((r54.shear_stiffness() / 2.25411e8 - 1.0).abs() < 1e-5);
        assert!((r54.rotary_inertia() - 0.183527).abs() < 1e-6);
        assert_eq!(r.timoshenko().beam(), RailBeam::Timoshenko);
        let err = r.with_shear(-1.0, 0.2).unwrap_err().to_string();
        assert!(err.contains("rail_shear_stiffness"), "{err}");
        let err = r.with_shear(1e8, -0.2).unwrap_err().to_string();
        assert!(err.contains("rail_rotary_inertia"), "{err}");
        assert_eq!(RailBeam::by_name("timoshenko"), Some(RailBeam::Timoshenko));
        assert_eq!(
            RailBeam::by_name(RailBeam::EulerBernoulli.name()),
            Some(RailBeam::EulerBernoulli)
        );
        // Without shear data the section is Euler–Bernoulli with κGA = ∞: its Timoshenko
        // frequency is the Rayleigh beam's with ρI = 0, i.e. the Euler–Bernoulli one.
        let plain = RailSection::new(6.38043e6, 60.21).unwrap();
        let ft = plain.timoshenko().pinned_pinned_frequency(0.6);
        assert!((ft / plain.pinned_pinned_frequency(0.6) - 1.0).abs() < 1e-14);
    }
}
