//! The `[track]` table of `kind = "vehicle_bridge"` scenarios (docs/track.md): the rail on
//! discrete pads, sleepers and ballast (or a slab) between the wheels and the bridge,
//! continued on approach and exit embankments (references.md §D5). Absent or
//! `model = "none"`: the rail is the beam, as without the table. SI units.

use beam::track::{
    ROTARY_INERTIA_RANGE, RailBeam, RailSection, SHEAR_STIFFNESS_RANGE, SpringDamper, SupportStack,
    TrackSupports,
};
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
/// The rail's shear stiffness κGA (Timoshenko).
const RAIL_SHEAR_STIFFNESS: Range =
    Range::closed(SHEAR_STIFFNESS_RANGE.0, SHEAR_STIFFNESS_RANGE.1, "N");
/// The rail's rotary inertia ρI per length (Timoshenko).
const RAIL_ROTARY_INERTIA: Range =
    Range::closed(ROTARY_INERTIA_RANGE.0, ROTARY_INERTIA_RANGE.1, "kg m");

/// `[track]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackToml {
    /// `ballasted`, `slab` or `none`.
    pub model: String,
    /// Rail section preset: `60E1` (default), `54E1`, `CHN60`.
    pub rail: Option<String>,
    /// The rail's beam theory: `euler_bernoulli` (default) or `timoshenko`.
    pub rail_beam: Option<String>,
    /// Timoshenko: the rail's shear stiffness κGA \[N\] (default: the preset's).
    pub rail_shear_stiffness: Option<f64>,
    /// Timoshenko: the rail's rotary inertia ρI per length \[kg m\] (default: the preset's).
    pub rail_rotary_inertia: Option<f64>,
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
    /// `[track.approach]`: the chain on the approach embankment, if it differs.
    pub approach: Option<ZoneToml>,
    /// `[track.bridge]`: the chain on the bridge (e.g. `model = "slab"`: ballastless track on
    /// the deck), if it differs.
    pub bridge: Option<ZoneToml>,
    /// `[track.exit]`: the chain on the exit embankment, if it differs.
    pub exit: Option<ZoneToml>,
}

/// `[track.approach]`, `[track.bridge]`, `[track.exit]`: one zone's support chain. With the
/// model of `[track]` (or no `model`), its keys replace those of `[track]` for this zone;
/// with another model, the zone's chain is that model with its own keys and defaults.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZoneToml {
    /// `ballasted` or `slab` (default: the model of `[track]`).
    pub model: Option<String>,
    pub pad_stiffness: Option<f64>,
    pub pad_damping: Option<f64>,
    pub sleeper_mass: Option<f64>,
    pub ballast_stiffness: Option<f64>,
    pub ballast_damping: Option<f64>,
    pub ballast_mass: Option<f64>,
    pub subgrade_stiffness: Option<f64>,
    pub subgrade_damping: Option<f64>,
    pub slab_mass: Option<f64>,
    pub mortar_stiffness: Option<f64>,
    pub mortar_damping: Option<f64>,
}

/// The support keys of one chain, whichever table they come from.
#[derive(Debug, Clone, Copy, Default)]
struct ChainKeys {
    pad_stiffness: Option<f64>,
    pad_damping: Option<f64>,
    sleeper_mass: Option<f64>,
    ballast_stiffness: Option<f64>,
    ballast_damping: Option<f64>,
    ballast_mass: Option<f64>,
    subgrade_stiffness: Option<f64>,
    subgrade_damping: Option<f64>,
    slab_mass: Option<f64>,
    mortar_stiffness: Option<f64>,
    mortar_damping: Option<f64>,
}

impl ChainKeys {
    fn of_track(t: &TrackToml) -> Self {
        Self {
            pad_stiffness: t.pad_stiffness,
            pad_damping: t.pad_damping,
            sleeper_mass: t.sleeper_mass,
            ballast_stiffness: t.ballast_stiffness,
            ballast_damping: t.ballast_damping,
            ballast_mass: t.ballast_mass,
            subgrade_stiffness: t.subgrade_stiffness,
            subgrade_damping: t.subgrade_damping,
            slab_mass: t.slab_mass,
            mortar_stiffness: t.mortar_stiffness,
            mortar_damping: t.mortar_damping,
        }
    }

    fn of_zone(z: &ZoneToml) -> Self {
        Self {
            pad_stiffness: z.pad_stiffness,
            pad_damping: z.pad_damping,
            sleeper_mass: z.sleeper_mass,
            ballast_stiffness: z.ballast_stiffness,
            ballast_damping: z.ballast_damping,
            ballast_mass: z.ballast_mass,
            subgrade_stiffness: z.subgrade_stiffness,
            subgrade_damping: z.subgrade_damping,
            slab_mass: z.slab_mass,
            mortar_stiffness: z.mortar_stiffness,
            mortar_damping: z.mortar_damping,
        }
    }

    /// These keys, each replaced by `over`'s where that one is given.
    fn overridden_by(self, over: Self) -> Self {
        Self {
            pad_stiffness: over.pad_stiffness.or(self.pad_stiffness),
            pad_damping: over.pad_damping.or(self.pad_damping),
            sleeper_mass: over.sleeper_mass.or(self.sleeper_mass),
            ballast_stiffness: over.ballast_stiffness.or(self.ballast_stiffness),
            ballast_damping: over.ballast_damping.or(self.ballast_damping),
            ballast_mass: over.ballast_mass.or(self.ballast_mass),
            subgrade_stiffness: over.subgrade_stiffness.or(self.subgrade_stiffness),
            subgrade_damping: over.subgrade_damping.or(self.subgrade_damping),
            slab_mass: over.slab_mass.or(self.slab_mass),
            mortar_stiffness: over.mortar_stiffness.or(self.mortar_stiffness),
            mortar_damping: over.mortar_damping.or(self.mortar_damping),
        }
    }

    fn ballast_keys(&self) -> [(&'static str, bool); 6] {
        [
            ("sleeper_mass", self.sleeper_mass.is_some()),
            ("ballast_stiffness", self.ballast_stiffness.is_some()),
            ("ballast_damping", self.ballast_damping.is_some()),
            ("ballast_mass", self.ballast_mass.is_some()),
            ("subgrade_stiffness", self.subgrade_stiffness.is_some()),
            ("subgrade_damping", self.subgrade_damping.is_some()),
        ]
    }

    fn slab_keys(&self) -> [(&'static str, bool); 3] {
        [
            ("slab_mass", self.slab_mass.is_some()),
            ("mortar_stiffness", self.mortar_stiffness.is_some()),
            ("mortar_damping", self.mortar_damping.is_some()),
        ]
    }
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

/// An error if any of `keys` is given: it does not apply to `model` (in table `table`).
fn refuse(table: &str, model: &str, keys: &[(&str, bool)]) -> Result<(), ConfigError> {
    if let Some((key, _)) = keys.iter().find(|(_, present)| *present) {
        bail!("[{table}] `{key}` does not apply to model = \"{model}\"");
    }
    Ok(())
}

/// The support chain of `model` ("ballasted" or "slab") with the keys `k` of table `table`
/// (`track` or `track.bridge`, …) at sleeper spacing `d`.
fn chain(table: &str, model: &str, k: &ChainKeys, d: f64) -> Result<SupportStack, ConfigError> {
    let key = |name: &str| format!("{table}.{name}");
    let stack = match model {
        "ballasted" => {
            refuse(table, model, &k.slab_keys())?;
            let preset = SupportStack::ballasted_high_speed();
            let (s, m) = (preset.springs(), preset.masses());
            let pad = spring(
                &key("pad_stiffness"),
                k.pad_stiffness,
                &key("pad_damping"),
                k.pad_damping,
                s[0],
            )?;
            let sleeper =
                SUPPORT_MASS.check(&key("sleeper_mass"), k.sleeper_mass.unwrap_or(m[0]))?;
            let ballast = spring(
                &key("ballast_stiffness"),
                k.ballast_stiffness,
                &key("ballast_damping"),
                k.ballast_damping,
                s[1],
            )?;
            let ballast_mass = k.ballast_mass.unwrap_or(m[1]);
            if ballast_mass == 0.0 {
                if k.subgrade_stiffness.is_some() || k.subgrade_damping.is_some() {
                    bail!(
                        "[{table}] `subgrade_stiffness`/`subgrade_damping` need a ballast mass (ballast_mass > 0)"
                    );
                }
                SupportStack::ballasted(pad, sleeper, ballast)
            } else {
                let ballast_mass = SUPPORT_MASS.check(&key("ballast_mass"), ballast_mass)?;
                let subgrade = spring(
                    &key("subgrade_stiffness"),
                    k.subgrade_stiffness,
                    &key("subgrade_damping"),
                    k.subgrade_damping,
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
            refuse(table, model, &k.ballast_keys())?;
            let preset = SupportStack::slab_track(d).map_err(|e| invalid!("[{table}]: {e}"))?;
            let (s, m) = (preset.springs(), preset.masses());
            let pad = spring(
                &key("pad_stiffness"),
                k.pad_stiffness,
                &key("pad_damping"),
                k.pad_damping,
                s[0],
            )?;
            let slab = SUPPORT_MASS.check(&key("slab_mass"), k.slab_mass.unwrap_or(m[0]))?;
            let mortar = spring(
                &key("mortar_stiffness"),
                k.mortar_stiffness,
                &key("mortar_damping"),
                k.mortar_damping,
                s[1],
            )?;
            SupportStack::new(vec![pad, mortar], vec![slab])
        }
        other => bail!("[{table}] `model` = \"{other}\": expected \"ballasted\" or \"slab\""),
    };
    stack.map_err(|e| invalid!("[{table}]: {e}"))
}

/// The rail of `[track]`: the section preset `rail`, its beam theory `rail_beam` and, for the
/// Timoshenko beam, `rail_shear_stiffness` and `rail_rotary_inertia` (the preset's values by
/// default; both refused with the Euler–Bernoulli beam, which has neither).
fn rail(t: &TrackToml) -> Result<RailSection, ConfigError> {
    let rail_name = t.rail.as_deref().unwrap_or("60E1");
    let rail = RailSection::by_name(rail_name).ok_or_else(|| {
        invalid!("[track] `rail` = \"{rail_name}\": expected \"60E1\", \"54E1\" or \"CHN60\"")
    })?;
    let beam_name = t.rail_beam.as_deref().unwrap_or("euler_bernoulli");
    // Case-insensitive like `model` and `rail`.
    let beam = RailBeam::by_name(&beam_name.trim().to_ascii_lowercase()).ok_or_else(|| {
        invalid!(
            "[track] `rail_beam` = \"{beam_name}\": expected \"euler_bernoulli\" or \"timoshenko\""
        )
    })?;
    if beam == RailBeam::EulerBernoulli {
        for (key, given) in [
            ("rail_shear_stiffness", t.rail_shear_stiffness.is_some()),
            ("rail_rotary_inertia", t.rail_rotary_inertia.is_some()),
        ] {
            if given {
                bail!(
                    "[track] `{key}` does not apply to rail_beam = \"euler_bernoulli\" (the default): set rail_beam = \"timoshenko\""
                );
            }
        }
        return Ok(rail);
    }
    let shear = RAIL_SHEAR_STIFFNESS.check(
        "track.rail_shear_stiffness",
        t.rail_shear_stiffness.unwrap_or(rail.shear_stiffness()),
    )?;
    let rotary = RAIL_ROTARY_INERTIA.check(
        "track.rail_rotary_inertia",
        t.rail_rotary_inertia.unwrap_or(rail.rotary_inertia()),
    )?;
    Ok(rail
        .with_shear(shear, rotary)
        .map_err(|e| invalid!("[track]: {e}"))?
        .timoshenko())
}

/// The `[track]` table: `None` when absent or `model = "none"` (the rail is the beam).
pub fn track(t: Option<&TrackToml>) -> Result<Option<TrackSpec>, ConfigError> {
    let Some(t) = t else {
        return Ok(None);
    };
    let model = t.model.trim().to_ascii_lowercase();
    let top = ChainKeys::of_track(t);
    if model == "none" {
        refuse("track", "none", &top.ballast_keys())?;
        refuse("track", "none", &top.slab_keys())?;
        refuse(
            "track",
            "none",
            &[
                ("rail", t.rail.is_some()),
                ("rail_beam", t.rail_beam.is_some()),
                ("rail_shear_stiffness", t.rail_shear_stiffness.is_some()),
                ("rail_rotary_inertia", t.rail_rotary_inertia.is_some()),
                ("approach_length", t.approach_length.is_some()),
                ("exit_length", t.exit_length.is_some()),
                ("sleeper_spacing", t.sleeper_spacing.is_some()),
                ("elements_per_bay", t.elements_per_bay.is_some()),
                ("pad_stiffness", t.pad_stiffness.is_some()),
                ("pad_damping", t.pad_damping.is_some()),
                ("approach", t.approach.is_some()),
                ("bridge", t.bridge.is_some()),
                ("exit", t.exit.is_some()),
            ],
        )?;
        return Ok(None);
    }
    if model != "ballasted" && model != "slab" {
        bail!(
            "[track] `model` = \"{}\": expected \"ballasted\", \"slab\" or \"none\"",
            t.model.trim()
        );
    }
    let d = SPACING.check(
        "track.sleeper_spacing",
        t.sleeper_spacing.unwrap_or(DEFAULT_SLEEPER_SPACING),
    )?;
    let main = chain("track", &model, &top, d)?;
    // A zone table: the same model with some keys replaced, or another model of its own.
    let zone = |name: &str, z: Option<&ZoneToml>| -> Result<(SupportStack, String), ConfigError> {
        let Some(z) = z else {
            return Ok((main.clone(), model.clone()));
        };
        let table = format!("track.{name}");
        let zone_model = z
            .model
            .as_deref()
            .map(|m| m.trim().to_ascii_lowercase())
            .unwrap_or_else(|| model.clone());
        let keys = if zone_model == model {
            top.overridden_by(ChainKeys::of_zone(z))
        } else {
            ChainKeys::of_zone(z)
        };
        Ok((chain(&table, &zone_model, &keys, d)?, zone_model))
    };
    let (approach_stack, approach_model) = zone("approach", t.approach.as_ref())?;
    let (bridge_stack, bridge_model) = zone("bridge", t.bridge.as_ref())?;
    let (exit_stack, exit_model) = zone("exit", t.exit.as_ref())?;
    let rail = rail(t)?;
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
    // The report's name: the model, and every zone whose model differs.
    let mut name = model.clone();
    for (zone_name, zone_model) in [
        ("approach", &approach_model),
        ("bridge", &bridge_model),
        ("exit", &exit_model),
    ] {
        if *zone_model != model {
            name.push_str(&format!(", {zone_model} on the {zone_name}"));
        }
    }
    Ok(Some(TrackSpec {
        model: name,
        rail,
        approach,
        exit,
        sleeper_spacing: d,
        elements_per_bay,
        supports: TrackSupports {
            approach: approach_stack,
            bridge: bridge_stack,
            exit: exit_stack,
        },
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

/// A named method that is a conditionally stable Newmark scheme (2β < γ, e.g.
/// `linear_acceleration`, β = 1/6) is refused on a `[track]` naming `integrator.method`, the
/// key the file set (the check of `Simulation::with_track` names `integrator.beta`, right for
/// `method = "newmark"` with its own `beta`/`gamma`). The rail's stiffest modes lie far beyond
/// any conditional stability limit (references.md §D3.5; docs/track.md, "Restrictions").
pub(crate) fn check_method(
    method_name: &str,
    integrator: &crate::vehicle_bridge::Integrator,
) -> Result<(), ConfigError> {
    use crate::vehicle_bridge::Integrator;
    use integrate::StructuralMethod;
    let key = method_name.trim().to_ascii_lowercase().replace('-', "_");
    if key == "newmark" {
        return Ok(());
    }
    if let Integrator::Structural(StructuralMethod::Newmark { beta, gamma }) = integrator
        && 2.0 * beta < gamma - 1e-12
    {
        return Err(invalid!(
            "invalid `integrator.method` = \"{}\": [track] needs an unconditionally stable method, and {} is Newmark with beta = {beta:.4} < gamma/2 = {:.4} (conditionally stable; the rail's stiffest modes are far beyond its stability limit): use newmark (the default, beta = 0.25), hht or generalized_alpha",
            method_name.trim(),
            method_name.trim(),
            0.5 * gamma
        ));
    }
    Ok(())
}
