//! The `[contact]` table of `kind = "vehicle_bridge"` scenarios and of the sweep's interaction
//! model (docs/vehicle_bridge.md, docs/profiles.md): the wheel–rail contact law of every wheel
//! (rigid, Hertz, boundary elements, or boundary elements on real profiles with
//! `[contact.profiles]`), its geometry and material. SI units; unknown keys are errors.

use std::path::Path;
use std::sync::Arc;

use serde::Deserialize;

use super::ConfigError;
use super::checks::{self, ranges};
use super::wheel_rail::{ProfileKeys, profile_setup};
use crate::vehicle_bridge::profiles::ProfileContact;
use crate::vehicle_bridge::{ContactGeometry, ContactModel};

/// Default contact geometry and material: a 0.92 m wheel (R = 0.46 m) on a rail head of
/// transverse radius 0.3 m, steel on steel (E = 210 GPa, ν = 0.3).
pub const DEFAULT_GEOMETRY: ContactGeometry = ContactGeometry {
    wheel_radius: 0.46,
    rail_profile_radius: 0.3,
    youngs_modulus: 210e9,
    poisson_ratio: 0.3,
};
/// Default contact model.
pub const DEFAULT_CONTACT_MODEL: &str = "rigid";
/// Default boundary-element grid of `model = "bem"` (elements per side).
pub const DEFAULT_BEM_GRID: usize = 32;
/// Default NormCG tolerance of `model = "bem"`.
pub const DEFAULT_BEM_TOL: f64 = 1e-8;
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    pub model: Option<String>,
    pub wheel_radius: Option<f64>,
    pub rail_profile_radius: Option<f64>,
    #[serde(rename = "E")]
    pub e: Option<f64>,
    pub nu: Option<f64>,
    pub grid: Option<usize>,
    pub bem_tol: Option<f64>,
    pub reuse_tol: Option<f64>,
    /// Real wheel and rail profiles (`model = "bem"` only; docs/profiles.md).
    pub profiles: Option<ProfilesToml>,
}

/// `[contact.profiles]`: the keys of `[gap] kind = "wheel_rail"` that place the wheelset
/// (same names, defaults and ranges; [`super::wheel_rail::ProfileKeys`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfilesToml {
    pub wheel: Option<String>,
    pub rail: Option<String>,
    pub inclination: Option<toml::Value>,
    pub gauge: Option<f64>,
    pub back_to_back: Option<f64>,
    pub wheel_radius: Option<f64>,
    pub lateral_shift: Option<f64>,
    pub roll: Option<f64>,
    pub smoothing: Option<f64>,
}

/// The contact model and geometry of a `[contact]` table (vehicle_bridge; the sweep's
/// interaction model), for `wheels` wheels (each BEM wheel holds its own grid). `profiles`:
/// the directory profile files are resolved against, `None` where `[contact.profiles]` is
/// not available (sweeps).
pub(crate) fn contact_of(
    c: Option<&ContactSpec>,
    wheels: usize,
    profiles: Option<&Path>,
) -> Result<(ContactModel, ContactGeometry), ConfigError> {
    if let Some(spec) = c
        && let Some(table) = &spec.profiles
    {
        let Some(base) = profiles else {
            bail!(
                "[contact.profiles]: real profiles are available in kind = \"vehicle_bridge\" scenarios only"
            );
        };
        return profile_contact(spec, table, wheels, base);
    }
    let geometry = ContactGeometry {
        wheel_radius: c
            .and_then(|c| c.wheel_radius)
            .unwrap_or(DEFAULT_GEOMETRY.wheel_radius),
        rail_profile_radius: c
            .and_then(|c| c.rail_profile_radius)
            .unwrap_or(DEFAULT_GEOMETRY.rail_profile_radius),
        youngs_modulus: c
            .and_then(|c| c.e)
            .unwrap_or(DEFAULT_GEOMETRY.youngs_modulus),
        poisson_ratio: c
            .and_then(|c| c.nu)
            .unwrap_or(DEFAULT_GEOMETRY.poisson_ratio),
    };
    let contact = match c
        .and_then(|c| c.model.as_deref())
        .unwrap_or(DEFAULT_CONTACT_MODEL)
    {
        "rigid" => ContactModel::Rigid,
        "hertz" => ContactModel::Hertz,
        "bem" => {
            let elements = c.and_then(|c| c.grid).unwrap_or(DEFAULT_BEM_GRID);
            checks::grid("contact.grid", elements, elements)?;
            // Every wheel holds its own solver and grid.
            checks::memory(
                "`contact.grid` for every wheel",
                (elements * elements) as f64 * wheels as f64,
                checks::GRID_BYTES_PER_ELEMENT,
            )?;
            ContactModel::Bem {
                elements,
                tol: ranges::TOLERANCE.check(
                    "contact.bem_tol",
                    c.and_then(|c| c.bem_tol).unwrap_or(DEFAULT_BEM_TOL),
                )?,
                reuse_tol: reuse_tol(c.and_then(|c| c.reuse_tol))?,
            }
        }
        other => bail!("[contact] `model` = \"{other}\": expected rigid, hertz or bem"),
    };
    if let Some(c) = c
        && !matches!(contact, ContactModel::Bem { .. })
        && (c.grid.is_some() || c.bem_tol.is_some() || c.reuse_tol.is_some())
    {
        bail!("[contact]: `grid`, `bem_tol` and `reuse_tol` apply to model = \"bem\" only");
    }
    Ok((contact, geometry))
}

/// Elements per direction of each patch grid with `[contact.profiles]` (as `[grid] n` of a
/// wheel–rail contact case).
const PROFILE_PATCH_ELEMENTS: checks::Range = checks::Range::closed(8.0, 512.0, "elements");

/// `[contact]` with `[contact.profiles]`: the profile contact of `model = "bem"`
/// ([`ProfileContact`]); `wheel_radius` comes from the profiles' table, the material from
/// `E`, `nu`.
fn profile_contact(
    c: &ContactSpec,
    table: &ProfilesToml,
    wheels: usize,
    base: &Path,
) -> Result<(ContactModel, ContactGeometry), ConfigError> {
    let model = c.model.as_deref().unwrap_or(DEFAULT_CONTACT_MODEL);
    if model != "bem" {
        bail!(
            "[contact] `model` = \"{model}\": [contact.profiles] needs model = \"bem\" (the profiles' patches are solved by the half-space solver)"
        );
    }
    for (key, set) in [
        ("wheel_radius", c.wheel_radius.is_some()),
        ("rail_profile_radius", c.rail_profile_radius.is_some()),
        ("bem_tol", c.bem_tol.is_some()),
        ("reuse_tol", c.reuse_tol.is_some()),
    ] {
        if set {
            bail!(
                "[contact] `{key}` is not used with [contact.profiles] (the radii come from the profiles and their `wheel_radius`; each patch is solved to the solver's default tolerance)"
            );
        }
    }
    let setup = profile_setup(
        &ProfileKeys {
            wheel: table.wheel.as_deref(),
            rail: table.rail.as_deref(),
            inclination: table.inclination.as_ref(),
            gauge: table.gauge,
            back_to_back: table.back_to_back,
            wheel_radius: table.wheel_radius,
            lateral_shift: table.lateral_shift,
            roll: table.roll,
            smoothing: table.smoothing,
        },
        "contact.profiles",
        base,
    )?;
    let elements = c.grid.unwrap_or(DEFAULT_BEM_GRID);
    PROFILE_PATCH_ELEMENTS.check("contact.grid", elements as f64)?;
    checks::memory(
        "`contact.grid` for every wheel",
        (elements * elements) as f64 * wheels as f64,
        checks::GRID_BYTES_PER_ELEMENT,
    )?;
    let geometry = ContactGeometry {
        wheel_radius: setup.wheelset.params().wheel_radius,
        rail_profile_radius: DEFAULT_GEOMETRY.rail_profile_radius,
        youngs_modulus: c.e.unwrap_or(DEFAULT_GEOMETRY.youngs_modulus),
        poisson_ratio: c.nu.unwrap_or(DEFAULT_GEOMETRY.poisson_ratio),
    };
    let contact = ProfileContact {
        wheelset: Arc::new(setup.wheelset),
        lateral_shift: setup.lateral_shift,
        roll: setup.roll,
        elements,
    };
    // The rigid geometry once here: an error names the table, not a wheel of the run.
    contact
        .law(geometry.material().map_err(|e| invalid!("{e}"))?)
        .map_err(|e| {
            invalid!(
                "[contact.profiles] at `lateral_shift` = {} m: {e}",
                setup.lateral_shift
            )
        })?;
    Ok((ContactModel::BemProfiles(contact), geometry))
}

/// `[contact] reuse_tol`: 0 (the default, a solve at every evaluation) … 1e-2.
fn reuse_tol(v: Option<f64>) -> Result<f64, ConfigError> {
    let v = v.unwrap_or(0.0);
    if !(v.is_finite() && (0.0..=1e-2).contains(&v)) {
        return Err(invalid!(
            "[contact] `reuse_tol` = {v}: must be in [0, 0.01] (0: solve at every evaluation)"
        ));
    }
    Ok(v)
}
