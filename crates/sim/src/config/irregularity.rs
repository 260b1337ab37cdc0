//! The `[irregularity]` table of `kind = "vehicle_bridge"` scenarios (docs/vehicle_bridge.md):
//! the rail profile under the wheels (none, dip, ramp, wheel flat, corrugation, random
//! spectrum), its keys, their ranges and defaults. SI units.

use serde::Deserialize;

use super::ConfigError;
use super::checks::{self, ranges};
use crate::vehicle_bridge::{Irregularity, TrackSpectrum};

/// Default shortest wavelength of a random irregularity \[m\].
pub const DEFAULT_LAMBDA_MIN: f64 = 1.0;
/// Default longest wavelength of a random irregularity \[m\].
pub const DEFAULT_LAMBDA_MAX: f64 = 50.0;
/// Default number of cosines of a random irregularity.
pub const DEFAULT_IRREGULARITY_COMPONENTS: usize = 500;
/// Largest setup work of a random irregularity (table points × cosines).
pub const MAX_IRREGULARITY_WORK: f64 = 2e9;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IrregularitySpec {
    pub kind: String,
    pub position: Option<f64>,
    pub length: Option<f64>,
    pub depth: Option<f64>,
    pub height: Option<f64>,
    pub amplitude: Option<f64>,
    pub wavelength: Option<f64>,
    pub start: Option<f64>,
    pub end: Option<f64>,
    pub spectrum: Option<String>,
    pub lambda_min: Option<f64>,
    pub lambda_max: Option<f64>,
    pub components: Option<usize>,
    pub seed: Option<u64>,
}

fn need(v: Option<f64>, key: &str, kind: &str) -> Result<f64, ConfigError> {
    v.ok_or_else(|| invalid!("[irregularity] kind = \"{kind}\" needs `{key}`"))
}

pub(crate) fn irregularity(
    spec: &IrregularitySpec,
    wheel_radius: f64,
) -> Result<Irregularity, ConfigError> {
    let k = spec.kind.as_str();
    let irr = match k {
        "none" => Irregularity::None,
        "dip" | "dipped_joint" => Irregularity::Dip {
            position: need(spec.position, "position", k)?,
            length: need(spec.length, "length", k)?,
            depth: need(spec.depth, "depth", k)?,
        },
        "ramp" => Irregularity::Ramp {
            position: need(spec.position, "position", k)?,
            length: need(spec.length, "length", k)?,
            height: need(spec.height, "height", k)?,
        },
        "wheel_flat" => {
            let length = need(spec.length, "length", k)?;
            // A fresh flat of chord ℓ has depth ℓ²/(8R) (references.md §D2.5) unless given.
            let depth = spec.depth.unwrap_or(length * length / (8.0 * wheel_radius));
            Irregularity::WheelFlat {
                position: spec.position.unwrap_or(0.0),
                length,
                depth,
                wheel_radius,
            }
        }
        "corrugation" => {
            let wavelength = need(spec.wavelength, "wavelength", k)?;
            Irregularity::Corrugation {
                amplitude: need(spec.amplitude, "amplitude", k)?,
                wavelength,
                start: spec
                    .start
                    .unwrap_or_else(|| corrugation_default_start(wavelength)),
                end: spec.end.unwrap_or(f64::INFINITY).min(1e300),
            }
        }
        "random" => {
            let name = spec
                .spectrum
                .as_deref()
                .ok_or_else(|| invalid!("[irregularity] kind = \"random\" needs `spectrum`"))?;
            let spectrum = TrackSpectrum::by_name(name).ok_or_else(|| {
                invalid!(
                    "[irregularity] `spectrum` = \"{name}\": expected fra1 … fra6, german_low or german_high"
                )
            })?;
            let components = checks::count(
                "irregularity.components",
                spec.components.unwrap_or(DEFAULT_IRREGULARITY_COMPONENTS),
                1,
                checks::MAX_IRREGULARITY_COMPONENTS,
            )?;
            Irregularity::random(
                spectrum,
                spec.lambda_min.unwrap_or(DEFAULT_LAMBDA_MIN),
                spec.lambda_max.unwrap_or(DEFAULT_LAMBDA_MAX),
                components,
                spec.seed.unwrap_or(1),
            )
            .map_err(|e| invalid!("{e}"))?
        }
        other => bail!(
            "[irregularity] `kind` = \"{other}\": expected none, dip, ramp, wheel_flat, corrugation or random"
        ),
    };
    irr.validate().map_err(|e| invalid!("{e}"))?;
    check_irregularity_ranges(spec)?;
    Ok(irr)
}

/// Physical ranges of the keys (after the sign checks above, whose messages are kept).
/// Ranges of the `[irregularity]` keys.
fn check_irregularity_ranges(spec: &IrregularitySpec) -> Result<(), ConfigError> {
    ranges::POSITION.check_opt("irregularity.position", spec.position)?;
    ranges::SPAN.check_opt("irregularity.length", spec.length)?;
    ranges::SMALL_DISPLACEMENT.check_opt("irregularity.depth", spec.depth)?;
    ranges::SMALL_DISPLACEMENT.check_opt("irregularity.height", spec.height)?;
    ranges::SMALL_DISPLACEMENT.check_opt("irregularity.amplitude", spec.amplitude)?;
    ranges::SPAN.check_opt("irregularity.wavelength", spec.wavelength)?;
    ranges::POSITION.check_opt("irregularity.start", spec.start)?;
    ranges::POSITION.check_opt("irregularity.end", spec.end)?;
    ranges::SPAN.check_opt("irregularity.lambda_min", spec.lambda_min)?;
    ranges::SPAN.check_opt("irregularity.lambda_max", spec.lambda_max)?;
    Ok(())
}

/// The start of a corrugation without `start`: a whole number of wavelengths before x = 0,
/// about 1e7 m away, so the phase is that of a corrugation starting at x = 0 (r = a sin(2πx/λ))
/// and x − x₀ keeps x to 2e-9 m (a start at −1e300 would round x away entirely). A wavelength
/// that is not positive and finite is left to the irregularity's own check.
fn corrugation_default_start(wavelength: f64) -> f64 {
    if wavelength.is_finite() && wavelength > 0.0 {
        -(1e7 / wavelength).ceil() * wavelength
    } else {
        -1e7
    }
}
