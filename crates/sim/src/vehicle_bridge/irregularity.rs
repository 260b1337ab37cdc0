//! Rail irregularities r(x) \[m\], positive when the rail top is higher than nominal (it
//! increases the approach, δ = z_w − w(x) + r(x)).
//!
//! * [`Irregularity::None`]: a smooth rail;
//! * [`Irregularity::Dip`]: a local cosine dip (dipped joint), r = −(d/2)(1 − cos(2π(x − x₀)/ℓ))
//!   on x₀ ≤ x ≤ x₀ + ℓ;
//! * [`Irregularity::Ramp`]: a smooth step of height h over length ℓ (a ramp, e.g. at an
//!   abutment), r = h·s(ξ) with the C¹ step s(ξ) = 3ξ² − 2ξ³, ξ = (x − x₀)/ℓ ∈ [0, 1];
//! * [`Irregularity::WheelFlat`]: a haversine flat of depth d and length ℓ repeating every wheel
//!   revolution 2πR (references.md §D2.5: a fresh flat of chord ℓ has d ≈ ℓ²/(8R)), as an equivalent
//!   rail irregularity r = −(d/2)(1 − cos(2π s/ℓ)) for s = (x − x₀) mod 2πR < ℓ;
//! * [`Irregularity::Corrugation`]: r = a sin(2π(x − x₀)/λ) on [x₀, x₁];
//! * [`Irregularity::Random`]: a random profile with a one-sided spatial PSD S(Ω) [m²/(rad/m)]
//!   (references.md §D2.4), by the spectral representation
//!   r(x) = Σ_k √(2 S(Ω_k) ΔΩ) cos(Ω_k x + θ_k), θ_k uniform in [0, 2π) from a seeded ChaCha8
//!   generator, Ω_k at the centres of N equal bins of the band [2π/λ_max, 2π/λ_min]. Its
//!   variance is Σ_k S(Ω_k) ΔΩ ≈ ∫_band S dΩ.

use std::f64::consts::{PI, TAU};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::VehicleBridgeError;

/// Track-quality spectra of references.md §D2.4 (vertical profile), taken one-sided in Ω [rad/m].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrackSpectrum {
    /// US FRA class 1 … 6: S(Ω) = k A_v Ω_c² / (Ω² (Ω² + Ω_c²)), k = 0.25, Ω_c = 0.8245 rad/m,
    /// A_v in cm²·rad/m (converted to m² here).
    FraClass(u8),
    /// German high-speed spectrum, low disturbance: S(Ω) = A_v Ω_c² / ((Ω² + Ω_r²)(Ω² + Ω_c²)),
    /// A_v = 4.032e-7 m·rad, Ω_c = 0.8246, Ω_r = 0.0206 rad/m.
    GermanLow,
    /// German high-speed spectrum, high disturbance (A_v = 1.080e-6 m·rad).
    GermanHigh,
}

impl TrackSpectrum {
    /// The one-sided PSD S(Ω) [m²/(rad/m)] at the spatial circular frequency Ω [rad/m].
    pub fn psd(&self, omega: f64) -> f64 {
        let w2 = omega * omega;
        match *self {
            TrackSpectrum::FraClass(class) => {
                const A_V: [f64; 6] = [1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339];
                let a = A_V[(class.clamp(1, 6) - 1) as usize] * 1e-4; // cm² → m²
                let wc2 = 0.8245f64 * 0.8245;
                0.25 * a * wc2 / (w2 * (w2 + wc2))
            }
            TrackSpectrum::GermanLow | TrackSpectrum::GermanHigh => {
                let a = if matches!(self, TrackSpectrum::GermanLow) {
                    4.032e-7
                } else {
                    1.080e-6
                };
                let (wc2, wr2) = (0.8246f64 * 0.8246, 0.0206f64 * 0.0206);
                a * wc2 / ((w2 + wr2) * (w2 + wc2))
            }
        }
    }

    /// Parses `fra1` … `fra6`, `german_low`, `german_high`.
    pub fn by_name(name: &str) -> Option<Self> {
        let key = name.trim().to_ascii_lowercase().replace('-', "_");
        match key.as_str() {
            "german_low" => Some(Self::GermanLow),
            "german_high" => Some(Self::GermanHigh),
            _ => {
                let class = key
                    .strip_prefix("fra_class_")
                    .or_else(|| key.strip_prefix("fra"))?;
                let c: u8 = class.trim_start_matches('_').parse().ok()?;
                (1..=6).contains(&c).then_some(Self::FraClass(c))
            }
        }
    }
}

/// A rail irregularity (module documentation).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Irregularity {
    /// Smooth rail, r = 0.
    #[default]
    None,
    /// Cosine dip of depth `depth` \[m\] and length `length` \[m\] starting at `position` \[m\].
    Dip {
        position: f64,
        length: f64,
        depth: f64,
    },
    /// C¹ ramp of height `height` \[m\] over `length` \[m\] starting at `position` \[m\].
    Ramp {
        position: f64,
        length: f64,
        height: f64,
    },
    /// Haversine wheel flat of depth `depth` and length `length` \[m\] on a wheel of radius
    /// `wheel_radius`, first met at `position` \[m\], repeating every 2π·`wheel_radius`.
    WheelFlat {
        position: f64,
        length: f64,
        depth: f64,
        wheel_radius: f64,
    },
    /// Sinusoidal corrugation of amplitude `amplitude` \[m\] and wavelength `wavelength` \[m\]
    /// between `start` and `end` \[m\].
    Corrugation {
        amplitude: f64,
        wavelength: f64,
        start: f64,
        end: f64,
    },
    /// A random profile (sum of cosines), built by [`Irregularity::random`].
    Random(RandomProfile),
    /// A profile sampled with its slope on a uniform grid and interpolated by cubic Hermite
    /// polynomials ([`Irregularity::tabulated`]); zero outside the table.
    Tabulated(TabulatedProfile),
}

/// Values r_i and slopes r'_i at x_i = x0 + i h.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedProfile {
    /// First abscissa \[m\].
    pub x0: f64,
    /// Spacing h \[m\].
    pub h: f64,
    /// r(x_i) \[m\].
    pub values: Vec<f64>,
    /// r'(x_i).
    pub slopes: Vec<f64>,
}

/// A sampled random profile r(x) = Σ a_k cos(Ω_k x + θ_k).
#[derive(Debug, Clone, PartialEq)]
pub struct RandomProfile {
    /// Amplitudes a_k = √(2 S(Ω_k) ΔΩ) \[m\].
    pub amplitudes: Vec<f64>,
    /// Spatial circular frequencies Ω_k [rad/m].
    pub wavenumbers: Vec<f64>,
    /// Phases θ_k \[rad\].
    pub phases: Vec<f64>,
    /// Σ S(Ω_k) ΔΩ = Σ a_k²/2 \[m²\], the theoretical variance of the profile.
    pub variance: f64,
}

fn bad(name: &str, value: f64, reason: &str) -> VehicleBridgeError {
    VehicleBridgeError::InvalidParameter {
        name: name.to_string(),
        value,
        reason: reason.to_string(),
    }
}

fn check_positive(name: &str, v: f64) -> Result<(), VehicleBridgeError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(bad(name, v, "must be positive and finite"))
    }
}

fn check_finite(name: &str, v: f64) -> Result<(), VehicleBridgeError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(bad(name, v, "must be finite"))
    }
}

impl Irregularity {
    /// A random profile of `spectrum` over wavelengths [`lambda_min`, `lambda_max`] \[m\] with
    /// `components` cosines and phases from `seed` (module documentation).
    pub fn random(
        spectrum: TrackSpectrum,
        lambda_min: f64,
        lambda_max: f64,
        components: usize,
        seed: u64,
    ) -> Result<Self, VehicleBridgeError> {
        check_positive("irregularity.lambda_min", lambda_min)?;
        check_positive("irregularity.lambda_max", lambda_max)?;
        if lambda_max <= lambda_min {
            return Err(bad(
                "irregularity.lambda_max",
                lambda_max,
                "must exceed lambda_min",
            ));
        }
        if components == 0 || components > 100_000 {
            return Err(bad(
                "irregularity.components",
                components as f64,
                "must be in 1..=100000",
            ));
        }
        let (w_lo, w_hi) = (TAU / lambda_max, TAU / lambda_min);
        let dw = (w_hi - w_lo) / components as f64;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut profile = RandomProfile {
            amplitudes: Vec::with_capacity(components),
            wavenumbers: Vec::with_capacity(components),
            phases: Vec::with_capacity(components),
            variance: 0.0,
        };
        for k in 0..components {
            let w = w_lo + (k as f64 + 0.5) * dw;
            let s = spectrum.psd(w);
            profile.amplitudes.push((2.0 * s * dw).sqrt());
            profile.wavenumbers.push(w);
            profile.phases.push(rng.random::<f64>() * TAU);
            profile.variance += s * dw;
        }
        Ok(Irregularity::Random(profile))
    }

    /// The random profile tabulated on [x_start, x_end] with spacing λ_min/64 (values and
    /// analytic slopes), interpolated by cubic Hermite polynomials: the interpolation error is
    /// at most h⁴/384 · max|r''''| ≤ (2π/64)⁴/384 · Σ a_k ≈ 2.4e-7 Σ a_k, and an evaluation
    /// costs one cubic instead of one cosine per component. Other kinds are returned unchanged.
    pub fn tabulated(&self, x_start: f64, x_end: f64) -> Self {
        let Irregularity::Random(p) = self else {
            return self.clone();
        };
        let w_max = p.wavenumbers.iter().copied().fold(0.0, f64::max);
        if w_max <= 0.0 || x_end.is_nan() || x_start.is_nan() || x_end <= x_start {
            return self.clone();
        }
        let h = std::f64::consts::TAU / w_max / 64.0;
        let n = ((x_end - x_start) / h).ceil() as usize + 2;
        if n > 50_000_000 {
            return self.clone();
        }
        let mut table = TabulatedProfile {
            x0: x_start,
            h,
            values: Vec::with_capacity(n),
            slopes: Vec::with_capacity(n),
        };
        for i in 0..n {
            let x = x_start + i as f64 * h;
            let (mut r, mut dr) = (0.0, 0.0);
            for ((a, w), th) in p.amplitudes.iter().zip(&p.wavenumbers).zip(&p.phases) {
                let (sn, cs) = (w * x + th).sin_cos();
                r += a * cs;
                dr -= a * w * sn;
            }
            table.values.push(r);
            table.slopes.push(dr);
        }
        Irregularity::Tabulated(table)
    }

    /// Validates the parameters (keys named as in the scenario file's `[irregularity]`).
    pub fn validate(&self) -> Result<(), VehicleBridgeError> {
        match *self {
            Irregularity::None | Irregularity::Random(_) | Irregularity::Tabulated(_) => Ok(()),
            Irregularity::Dip {
                position,
                length,
                depth,
            } => {
                check_finite("irregularity.position", position)?;
                check_positive("irregularity.length", length)?;
                check_finite("irregularity.depth", depth)
            }
            Irregularity::Ramp {
                position,
                length,
                height,
            } => {
                check_finite("irregularity.position", position)?;
                check_positive("irregularity.length", length)?;
                check_finite("irregularity.height", height)
            }
            Irregularity::WheelFlat {
                position,
                length,
                depth,
                wheel_radius,
            } => {
                check_finite("irregularity.position", position)?;
                check_positive("irregularity.length", length)?;
                check_finite("irregularity.depth", depth)?;
                check_positive("contact.wheel_radius", wheel_radius)?;
                if length >= TAU * wheel_radius {
                    return Err(bad(
                        "irregularity.length",
                        length,
                        "a flat must be shorter than the wheel circumference",
                    ));
                }
                Ok(())
            }
            Irregularity::Corrugation {
                amplitude,
                wavelength,
                start,
                end,
            } => {
                check_finite("irregularity.amplitude", amplitude)?;
                check_positive("irregularity.wavelength", wavelength)?;
                check_finite("irregularity.start", start)?;
                check_finite("irregularity.end", end)?;
                if end < start {
                    return Err(bad("irregularity.end", end, "must not be below start"));
                }
                Ok(())
            }
        }
    }

    /// The rail height r(x) \[m\] at x \[m\].
    pub fn height(&self, x: f64) -> f64 {
        match self {
            Irregularity::None => 0.0,
            &Irregularity::Dip {
                position,
                length,
                depth,
            } => {
                let s = x - position;
                if (0.0..=length).contains(&s) {
                    -0.5 * depth * (1.0 - (TAU * s / length).cos())
                } else {
                    0.0
                }
            }
            &Irregularity::Ramp {
                position,
                length,
                height,
            } => {
                let xi = ((x - position) / length).clamp(0.0, 1.0);
                height * xi * xi * (3.0 - 2.0 * xi)
            }
            &Irregularity::WheelFlat {
                position,
                length,
                depth,
                wheel_radius,
            } => {
                let s = x - position;
                if s < 0.0 {
                    return 0.0;
                }
                let s = s.rem_euclid(2.0 * PI * wheel_radius);
                if s <= length {
                    -0.5 * depth * (1.0 - (TAU * s / length).cos())
                } else {
                    0.0
                }
            }
            &Irregularity::Corrugation {
                amplitude,
                wavelength,
                start,
                end,
            } => {
                if (start..=end).contains(&x) {
                    amplitude * (TAU * (x - start) / wavelength).sin()
                } else {
                    0.0
                }
            }
            Irregularity::Tabulated(t) => {
                let u = (x - t.x0) / t.h;
                if u.is_nan() || u < 0.0 || u >= (t.values.len() - 1) as f64 {
                    return 0.0;
                }
                let i = u as usize;
                let s = u - i as f64;
                let (s2, s3) = (s * s, s * s * s);
                (2.0 * s3 - 3.0 * s2 + 1.0) * t.values[i]
                    + (s3 - 2.0 * s2 + s) * t.h * t.slopes[i]
                    + (-2.0 * s3 + 3.0 * s2) * t.values[i + 1]
                    + (s3 - s2) * t.h * t.slopes[i + 1]
            }
            Irregularity::Random(p) => p
                .amplitudes
                .iter()
                .zip(&p.wavenumbers)
                .zip(&p.phases)
                .map(|((a, w), th)| a * (w * x + th).cos())
                .sum(),
        }
    }

    /// `true` for a smooth rail.
    pub fn is_none(&self) -> bool {
        matches!(self, Irregularity::None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dip reaches −depth at its centre and is zero at both ends (closed form).
    #[test]
    fn dip_shape() {
        let dip = Irregularity::Dip {
            position: 2.0,
            length: 1.0,
            depth: 1e-3,
        };
        assert!((dip.height(2.5) + 1e-3).abs() < 1e-15);
        assert!(dip.height(2.0).abs() < 1e-15 && dip.height(3.0).abs() < 1e-15);
        assert_eq!(dip.height(1.0), 0.0);
    }

    /// A flat repeats every wheel circumference.
    #[test]
    fn flat_repeats_every_revolution() {
        let flat = Irregularity::WheelFlat {
            position: 1.0,
            length: 0.05,
            depth: 0.68e-3,
            wheel_radius: 0.46,
        };
        let c = TAU * 0.46;
        for k in 0..3 {
            let centre = 1.0 + k as f64 * c + 0.025;
            assert!((flat.height(centre) + 0.68e-3).abs() < 1e-12);
            assert_eq!(flat.height(centre + 0.1), 0.0);
        }
    }

    /// The tabulated random profile equals the direct sum of cosines to 1e-6 of the largest
    /// amplitude sum (the bound of the interpolation error is 2.4e-7 Σ a_k).
    #[test]
    fn tabulated_profile_matches_direct_sum() {
        let direct = Irregularity::random(TrackSpectrum::GermanHigh, 1.0, 30.0, 100, 5).unwrap();
        let Irregularity::Random(p) = &direct else {
            unreachable!()
        };
        let sum_a: f64 = p.amplitudes.iter().sum();
        let table = direct.tabulated(-5.0, 40.0);
        let mut worst = 0.0f64;
        for i in 0..20_000 {
            let x = -5.0 + 45.0 * (i as f64 + 0.37) / 20_000.0;
            worst = worst.max((table.height(x) - direct.height(x)).abs());
        }
        assert!(worst < 1e-6 * sum_a, "{worst} vs {sum_a}");
        assert_eq!(table.height(-6.0), 0.0);
    }

    #[test]
    fn spectrum_names() {
        assert_eq!(
            TrackSpectrum::by_name("fra6"),
            Some(TrackSpectrum::FraClass(6))
        );
        assert_eq!(
            TrackSpectrum::by_name("German-Low"),
            Some(TrackSpectrum::GermanLow)
        );
        assert_eq!(TrackSpectrum::by_name("fra7"), None);
    }
}
