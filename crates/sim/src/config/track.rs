//! The `[track]` table of `kind = "vehicle_bridge"` scenarios (docs/track.md): the rail on
//! discrete pads, sleepers and ballast (or a slab) between the wheels and the bridge,
//! continued on approach and exit embankments (references.md §D5). Absent or
//! `model = "none"`: the rail is the beam, as without the table. SI units.

use beam::track::{RailSection, SpringDamper, SupportStack, TrackSupports};
use serde::Deserialize;

use super::ConfigError;
use super::checks::{self, Range};
use crate::vehicle_bridge::track::TrackSpec;

/// Default approach and exit length \[m\].
pub const DEFAULT_EMBANKMENT: f64 = 30.0;
/// Default sleeper spacing \[m\] (the ballasted preset's, references.md §D5.2).
pub const DEFAULT_SLEEPER_SPACING: f64 = SupportStack::BALLASTED_HIGH_SPEED_SPACING;
/// Default rail elements per sleeper bay.
pub const DEFAULT_ELEMENTS_PER_BAY: usize = 4;
/// Most rail nodes of a `[track]` (track length / sleeper spacing × elements per bay + 1).
pub const MAX_RAIL_NODES: usize = 200_000;

/// Approach and exit lengths.
const EMBANKMENT: Range = Range::closed(0.0, 1e4, "m");
/// Sleeper spacing.
const SPACING: Range = Range::closed(0.1, 2.0, "m");
/// Support stiffnesses.
const SUPPORT_STIFFNESS: Range = Range::closed(1e4, 1e13, "N/m");
/// Support dampings.
const SUPPORT_DAMPING: Range = Range::closed(0.0, 1e9, "N s/m");
/// Sleeper, ballast and slab masses.
const SUPPORT_MASS: Range = Range::closed(1e-3, 1e6, "kg");

/// `[track]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackToml {
    /// `ballasted`, `slab` or `none`.
    pub model: String,
    /// Rail section preset: `60E1` (default), `54E1`, `CHN60`.
    pub rail: Option<String>,
    pub approach_length: Option<f64>,
    pub exit_length: Option<f64>,
    pub sleeper_spacing: Option<f64>,
    pub elements_per_bay: Option<usize>,
    pub pad_stiffness: Option<f64>,
    pub pad_damping: Option<f64>,
    /// Ballasted: the sleeper (half sleeper per rail) \[kg\].
    pub sleeper_mass: Option<f64>,
    pub ballast_stiffness: Option<f64>,
    pub ballast_damping: Option<f64>,
    /// Ballasted: the ballast mass under a sleeper \[kg\]; 0 = none (then no subgrade).
    pub ballast_mass: Option<f64>,
    pub subgrade_stiffness: Option<f64>,
    pub subgrade_damping: Option<f64>,
    /// Slab: the slab mass per fastener \[kg\].
    pub slab_mass: Option<f64>,
    pub mortar_stiffness: Option<f64>,
    pub mortar_damping: Option<f64>,
}

fn spring(
    k_key: &str,
    k: Option<f64>,
    c_key: &str,
    c: Option<f64>,
    preset: SpringDamper,
) -> Result<SpringDamper, ConfigError> {
    let k = SUPPORT_STIFFNESS.check(k_key, k.unwrap_or(preset.stiffness))?;
    let c = SUPPORT_DAMPING.check(c_key, c.unwrap_or(preset.damping))?;
    SpringDamper::new(k, c).map_err(|e| invalid!("[track]: {e}"))
}

/// The `[track]` table: `None` when absent or `model = "none"` (the rail is the beam).
pub fn track(t: Option<&TrackToml>) -> Result<Option<TrackSpec>, ConfigError> {
    let Some(t) = t else {
        return Ok(None);
    };
    let model = t.model.trim().to_ascii_lowercase();
    let given = |keys: &[(&str, bool)]| -> Result<(), ConfigError> {
        for &(key, present) in keys {
            if present {
                bail!(
                    "[track] `{key}` does not apply to model = \"{}\"",
                    t.model.trim()
                );
            }
        }
        Ok(())
    };
    let ballast_keys = [
        ("sleeper_mass", t.sleeper_mass.is_some()),
        ("ballast_stiffness", t.ballast_stiffness.is_some()),
        ("ballast_damping", t.ballast_damping.is_some()),
        ("ballast_mass", t.ballast_mass.is_some()),
        ("subgrade_stiffness", t.subgrade_stiffness.is_some()),
        ("subgrade_damping", t.subgrade_damping.is_some()),
    ];
    let slab_keys = [
        ("slab_mass", t.slab_mass.is_some()),
        ("mortar_stiffness", t.mortar_stiffness.is_some()),
        ("mortar_damping", t.mortar_damping.is_some()),
    ];
    let d = SPACING.check(
        "track.sleeper_spacing",
        t.sleeper_spacing.unwrap_or(DEFAULT_SLEEPER_SPACING),
    )?;
    let stack = match model.as_str() {
        "none" => {
            given(&ballast_keys)?;
            given(&slab_keys)?;
            given(&[
                ("rail", t.rail.is_some()),
                ("approach_length", t.approach_length.is_some()),
                ("exit_length", t.exit_length.is_some()),
                ("sleeper_spacing", t.sleeper_spacing.is_some()),
                ("elements_per_bay", t.elements_per_bay.is_some()),
                ("pad_stiffness", t.pad_stiffness.is_some()),
                ("pad_damping", t.pad_damping.is_some()),
            ])?;
            return Ok(None);
        }
        "ballasted" => {
            given(&slab_keys)?;
            let preset = SupportStack::ballasted_high_speed();
            let (s, m) = (preset.springs(), preset.masses());
            let pad = spring(
                "track.pad_stiffness",
                t.pad_stiffness,
                "track.pad_damping",
                t.pad_damping,
                s[0],
            )?;
            let sleeper = SUPPORT_MASS.check("track.sleeper_mass", t.sleeper_mass.unwrap_or(m[0]))?;
            let ballast = spring(
                "track.ballast_stiffness",
                t.ballast_stiffness,
                "track.ballast_damping",
                t.ballast_damping,
                s[1],
            )?;
            let ballast_mass = t.ballast_mass.unwrap_or(m[1]);
            if ballast_mass == 0.0 {
                given(&[
                    ("subgrade_stiffness", t.subgrade_stiffness.is_some()),
                    ("subgrade_damping", t.subgrade_damping.is_some()),
                ])
                .map_err(|_| {
                    invalid!("[track] `subgrade_stiffness`/`subgrade_damping` need a ballast mass (ballast_mass > 0)")
                })?;
                SupportStack::ballasted(pad, sleeper, ballast)
            } else {
                let ballast_mass = SUPPORT_MASS.check("track.ballast_mass", ballast_mass)?;
                let subgrade = spring(
                    "track.subgrade_stiffness",
                    t.subgrade_stiffness,
                    "track.subgrade_damping",
                    t.subgrade_damping,
                    s[2],
                )?;
                SupportStack::ballasted_with_ballast_mass(
                    pad,
                    sleeper,
                    ballast,
                    ballast_mass,
                    subgrade,
                )
            }
        }
        "slab" => {
            given(&ballast_keys)?;
            let preset = SupportStack::slab_track(d).map_err(|e| invalid!("[track]: {e}"))?;
            let (s, m) = (preset.springs(), preset.masses());
            let pad = spring(
                "track.pad_stiffness",
                t.pad_stiffness,
                "track.pad_damping",
                t.pad_damping,
                s[0],
            )?;
            let slab = SUPPORT_MASS.check("track.slab_mass", t.slab_mass.unwrap_or(m[0]))?;
            let mortar = spring(
                "track.mortar_stiffness",
                t.mortar_stiffness,
                "track.mortar_damping",
                t.mortar_damping,
                s[1],
            )?;
            SupportStack::new(vec![pad, mortar], vec![slab])
        }
        other => bail!(
            "[track] `model` = \"{other}\": expected \"ballasted\", \"slab\" or \"none\""
        ),
    }
    .map_err(|e| invalid!("[track]: {e}"))?;
    let rail_name = t.rail.as_deref().unwrap_or("60E1");
    let rail = RailSection::by_name(rail_name).ok_or_else(|| {
        invalid!("[track] `rail` = \"{rail_name}\": expected \"60E1\", \"54E1\" or \"CHN60\"")
    })?;
    let approach = EMBANKMENT.check(
        "track.approach_length",
        t.approach_length.unwrap_or(DEFAULT_EMBANKMENT),
    )?;
    let exit = EMBANKMENT.check(
        "track.exit_length",
        t.exit_length.unwrap_or(DEFAULT_EMBANKMENT),
    )?;
    let elements_per_bay = t.elements_per_bay.unwrap_or(DEFAULT_ELEMENTS_PER_BAY);
    checks::count("track.elements_per_bay", elements_per_bay, 2, 32)?;
    if elements_per_bay % 2 != 0 {
        bail!(
            "[track] `elements_per_bay` = {elements_per_bay}: must be even (a sleeper at mid-bay)"
        );
    }
    Ok(Some(TrackSpec {
        model: if model == "slab" { "slab" } else { "ballasted" },
        rail,
        approach,
        exit,
        sleeper_spacing: d,
        elements_per_bay,
        supports: TrackSupports::uniform(stack),
    }))
}

/// The rail nodes of a track over a `bridge` m span: an error naming the keys when there are
/// more than [`MAX_RAIL_NODES`].
pub fn check_size(spec: &TrackSpec, bridge: f64) -> Result<(), ConfigError> {
    let length = spec.approach + bridge + spec.exit;
    let nodes = (length / spec.sleeper_spacing).ceil() * spec.elements_per_bay as f64 + 1.0;
    if nodes > MAX_RAIL_NODES as f64 {
        bail!(
            "[track]: approach_length + bridge + exit_length = {length} m at sleeper_spacing = {} m with elements_per_bay = {} gives {nodes:.0} rail nodes: at most {MAX_RAIL_NODES}",
            spec.sleeper_spacing,
            spec.elements_per_bay
        );
    }
    Ok(())
}
