//! A wheel–rail contact case: a contact case file whose `[gap]` has `kind = "wheel_rail"`
//! (`dyncontact contact`, `dyncontact profile-sweep`; docs/profiles.md).
//!
//! ```toml
//! [body1]            # wheel
//! E = 210e9
//! nu = 0.3
//! [body2]            # rail
//! E = 210e9
//! nu = 0.3
//! [gap]
//! kind = "wheel_rail"
//! wheel = "S1002"          # built-in name, or a profile file (mm; see docs/profiles.md)
//! rail = "60E1"
//! inclination = "1:40"     # "1:20", "1:40", "0" or the tangent as a number
//! gauge = 1.435            # m
//! back_to_back = 1.360     # m
//! wheel_radius = 0.46      # m
//! lateral_shift = 0.0      # m
//! [load]
//! force = 100e3            # vertical force per wheel [N] (or `approach` [m])
//! [grid]
//! n = 48                   # elements per direction of each patch's grid
//! ```

use std::path::Path;

use halfspace::Material;
use wheelrail::{PatchOptions, Profile, Roll, WheelLoad, Wheelset, WheelsetParams};

use super::ConfigError;
use super::checks::Range;
use super::contact::{ContactCase, GapSpec, checked_material};

/// Built-in wheel profiles.
pub const WHEELS: &[&str] = &["S1002"];
/// Built-in rail profiles.
pub const RAILS: &[&str] = &["60E1"];

/// Default elements per direction of a patch grid.
pub const DEFAULT_PATCH_ELEMENTS: usize = 48;

const GAUGE: Range = Range::closed(0.6, 2.0, "m");
const BACK_TO_BACK: Range = Range::closed(0.5, 1.9, "m");
const WHEEL_RADIUS: Range = Range::closed(0.1, 1.0, "m");
const SHIFT: Range = Range::symmetric(0.02, "m");
const ROLL: Range = Range::symmetric(0.05, "rad");
const INCLINATION: Range = Range::closed(0.0, 0.05, "(tangent of the cant angle)");
const FORCE: Range = Range::closed(1.0, 1e7, "N");
const APPROACH: Range = Range::closed(1e-9, 5e-3, "m");
const SMOOTHING: Range = Range::closed(0.0, 1.0, "m³");
const PATCH_ELEMENTS: Range = Range::closed(8.0, 512.0, "elements");

/// A validated wheel–rail case.
#[derive(Debug, Clone)]
pub struct WheelRailConfig {
    /// Wheelset, profiles and track.
    pub wheelset: Wheelset,
    /// Combined material of wheel and rail.
    pub material: Material,
    /// Load on each wheel.
    pub load: WheelLoad,
    /// Lateral shift of the wheelset \[m\].
    pub lateral_shift: f64,
    /// Roll: the equilibrium one or prescribed.
    pub roll: Roll,
    /// Patch grids.
    pub options: PatchOptions,
    /// The inclination as written ("1:40", …).
    pub inclination_label: String,
}

/// Parse a case file's text: `Ok(None)` when its `[gap]` is not `kind = "wheel_rail"`.
pub fn parse(text: &str, base: &Path) -> Result<Option<WheelRailConfig>, ConfigError> {
    let case: ContactCase = toml::from_str(text).map_err(|e| {
        ConfigError::Schema(super::with_key_suggestion(format!(
            "invalid case file: {e}"
        )))
    })?;
    if case.gap.kind != "wheel_rail" {
        return Ok(None);
    }
    build(&case, base).map(Some)
}

fn profile(
    table: &str,
    key: &str,
    value: Option<&str>,
    default: &str,
    builtin: &[&str],
    base: &Path,
    smoothing: f64,
) -> Result<Profile, ConfigError> {
    let name = value.unwrap_or(default);
    match name.to_ascii_uppercase().as_str() {
        "S1002" if builtin.contains(&"S1002") => return Ok(wheelrail::s1002()),
        "60E1" | "UIC60" if builtin.contains(&"60E1") => return Ok(wheelrail::rail_60e1()),
        _ => {}
    }
    let path = base.join(name);
    if !path.is_file() {
        bail!(
            "[{table}] `{key}` = \"{name}\": neither a built-in profile (allowed: {}) nor a profile file ({} does not exist)",
            builtin.join(", "),
            path.display()
        );
    }
    let text = std::fs::read_to_string(&path).map_err(|source| ConfigError::Io {
        context: format!("[{table}] cannot read `{key}` {}", path.display()),
        source,
    })?;
    let kind = if key == "wheel" {
        wheelrail::ProfileKind::Wheel
    } else {
        wheelrail::ProfileKind::Rail
    };
    wheelrail::parse_profile(name, &text, kind, 1e-3, smoothing)
        .map_err(|e| invalid!("[{table}] `{key}` = \"{name}\" ({}): {e}", path.display()))
}

/// The inclination key: "1:N" (N ≥ 20), "0", or the tangent.
fn inclination(table: &str, value: Option<&toml::Value>) -> Result<(f64, String), ConfigError> {
    let Some(v) = value else {
        return Ok((1.0 / 40.0, "1:40".into()));
    };
    let t = match v {
        toml::Value::String(s) => {
            let s = s.trim();
            if s == "0" {
                0.0
            } else if let Some((a, b)) = s.split_once(':') {
                let (a, b): (f64, f64) = match (a.trim().parse(), b.trim().parse()) {
                    (Ok(a), Ok(b)) if b != 0.0 => (a, b),
                    _ => bail!(
                        "[{table}] `inclination` = \"{s}\": expected a ratio like \"1:40\", \"0\" or a number"
                    ),
                };
                a / b
            } else {
                bail!(
                    "[{table}] `inclination` = \"{s}\": expected a ratio like \"1:40\", \"0\" or a number"
                )
            }
        }
        toml::Value::Float(f) => *f,
        toml::Value::Integer(i) => *i as f64,
        other => bail!(
            "[{table}] `inclination` = {other}: expected a ratio like \"1:40\", \"0\" or a number"
        ),
    };
    INCLINATION.check(&format!("{table}.inclination"), t)?;
    let label = match v {
        toml::Value::String(s) => s.trim().to_string(),
        _ => format!("{t}"),
    };
    Ok((t, label))
}

/// Validate a parsed case with `[gap] kind = "wheel_rail"`.
pub fn build(case: &ContactCase, base: &Path) -> Result<WheelRailConfig, ConfigError> {
    if let Some(kind) = &case.kind
        && kind != "contact"
    {
        bail!("`kind` = \"{kind}\" is not a contact case");
    }
    let g: &GapSpec = &case.gap;
    for (key, set) in [
        ("A", g.a.is_some()),
        ("B", g.b.is_some()),
        ("R1x", g.r1x.is_some()),
        ("R1y", g.r1y.is_some()),
        ("R2x", g.r2x.is_some()),
        ("R2y", g.r2y.is_some()),
        ("radius", g.radius.is_some()),
        ("length", g.length.is_some()),
        ("edge_radius", g.edge_radius.is_some()),
        ("file", g.file.is_some()),
    ] {
        if set {
            bail!("[gap] key `{key}` is not used by kind = \"wheel_rail\"");
        }
    }
    if case.friction.is_some() || case.kinematics.is_some() {
        bail!(
            "[friction]/[kinematics]: the tangential problem is not available with [gap] kind = \"wheel_rail\" (normal contact only)"
        );
    }
    if case.solver.is_some() {
        bail!(
            "[solver]: not used with [gap] kind = \"wheel_rail\" (the patch solves use the defaults)"
        );
    }
    let material = checked_material(&case.body1, &case.body2)?;
    let setup = profile_setup(
        &ProfileKeys {
            wheel: g.wheel.as_deref(),
            rail: g.rail.as_deref(),
            inclination: g.inclination.as_ref(),
            gauge: g.gauge,
            back_to_back: g.back_to_back,
            wheel_radius: g.wheel_radius,
            lateral_shift: g.lateral_shift,
            roll: g.roll,
            smoothing: g.smoothing,
        },
        "gap",
        base,
    )?;
    let load = match (case.load.force, case.load.approach) {
        (Some(f), None) => WheelLoad::VerticalForce(FORCE.check("load.force", f)?),
        (None, Some(d)) => WheelLoad::VerticalApproach(APPROACH.check("load.approach", d)?),
        (Some(_), Some(_)) => bail!("[load]: give exactly one of `force` or `approach`, not both"),
        (None, None) => {
            bail!(
                "[load]: missing load: give the vertical wheel force `force` [N] or `approach` [m]"
            )
        }
    };
    let mut options = PatchOptions::default();
    if let Some(grid) = &case.grid {
        for (key, set) in [
            ("dx", grid.dx.is_some()),
            ("dy", grid.dy.is_some()),
            ("x0", grid.x0.is_some()),
            ("y0", grid.y0.is_some()),
        ] {
            if set {
                bail!(
                    "[grid] key `{key}` is not used by [gap] kind = \"wheel_rail\" (each patch's grid is sized from its contact; give `n` or `nx`, `ny`)"
                );
            }
        }
        let n = grid.n.unwrap_or(DEFAULT_PATCH_ELEMENTS);
        let nx = grid.nx.unwrap_or(n);
        let ny = grid.ny.unwrap_or(n);
        for (key, v) in [("grid.n", n), ("grid.nx", nx), ("grid.ny", ny)] {
            PATCH_ELEMENTS.check(key, v as f64)?;
        }
        options.nx = nx;
        options.ny = ny;
    } else {
        options.nx = DEFAULT_PATCH_ELEMENTS;
        options.ny = DEFAULT_PATCH_ELEMENTS;
    }
    Ok(WheelRailConfig {
        wheelset: setup.wheelset,
        material,
        load,
        lateral_shift: setup.lateral_shift,
        roll: setup.roll,
        options,
        inclination_label: setup.inclination_label,
    })
}

/// The keys that place a wheelset on its track with its profiles, shared by `[gap]` with
/// `kind = "wheel_rail"` and the vehicle–bridge `[contact.profiles]` (same names, defaults
/// and ranges; docs/profiles.md).
#[derive(Debug, Clone, Copy, Default)]
pub struct ProfileKeys<'a> {
    /// Wheel profile: built-in name or a profile file.
    pub wheel: Option<&'a str>,
    /// Rail profile: built-in name or a profile file.
    pub rail: Option<&'a str>,
    /// Rail inclination, "1:20", "1:40", "0" or its tangent.
    pub inclination: Option<&'a toml::Value>,
    /// Track gauge \[m\].
    pub gauge: Option<f64>,
    /// Back-to-back distance of the wheels \[m\].
    pub back_to_back: Option<f64>,
    /// Nominal rolling radius \[m\].
    pub wheel_radius: Option<f64>,
    /// Lateral shift of the wheelset \[m\].
    pub lateral_shift: Option<f64>,
    /// Prescribed roll \[rad\] (default: both wheels on their rails).
    pub roll: Option<f64>,
    /// Smoothing parameter λ \[m³\] of measured profiles.
    pub smoothing: Option<f64>,
}

/// A wheelset with its profiles on its track, at its lateral shift and roll.
#[derive(Debug, Clone)]
pub struct ProfileSetup {
    /// Wheelset, profiles and track.
    pub wheelset: Wheelset,
    /// Lateral shift of the wheelset \[m\].
    pub lateral_shift: f64,
    /// Roll: the equilibrium one or prescribed.
    pub roll: Roll,
    /// The inclination as written ("1:40", …).
    pub inclination_label: String,
}

/// Validates the [`ProfileKeys`] of the table `table` (named in the errors: "gap",
/// "contact.profiles"); profile files are resolved against `base`.
pub fn profile_setup(
    keys: &ProfileKeys<'_>,
    table: &str,
    base: &Path,
) -> Result<ProfileSetup, ConfigError> {
    let key = |k: &str| format!("{table}.{k}");
    let smoothing = SMOOTHING.check(&key("smoothing"), keys.smoothing.unwrap_or(0.0))?;
    let wheel = profile(table, "wheel", keys.wheel, "S1002", WHEELS, base, smoothing)?;
    let rail = profile(table, "rail", keys.rail, "60E1", RAILS, base, smoothing)?;
    let (incl, inclination_label) = inclination(table, keys.inclination)?;
    let defaults = WheelsetParams::default();
    let params = WheelsetParams {
        gauge: GAUGE.check(&key("gauge"), keys.gauge.unwrap_or(defaults.gauge))?,
        inclination: incl,
        back_to_back: BACK_TO_BACK.check(
            &key("back_to_back"),
            keys.back_to_back.unwrap_or(defaults.back_to_back),
        )?,
        wheel_radius: WHEEL_RADIUS.check(
            &key("wheel_radius"),
            keys.wheel_radius.unwrap_or(defaults.wheel_radius),
        )?,
        ..defaults
    };
    if params.gauge <= params.back_to_back {
        bail!(
            "[{table}] `gauge` = {} must exceed `back_to_back` = {}",
            params.gauge,
            params.back_to_back
        );
    }
    let lateral_shift = SHIFT.check(&key("lateral_shift"), keys.lateral_shift.unwrap_or(0.0))?;
    let roll = match keys.roll {
        None => Roll::Equilibrium,
        Some(r) => Roll::Fixed(ROLL.check(&key("roll"), r)?),
    };
    let wheelset =
        Wheelset::new(wheel, rail, params).map_err(|e| invalid!("[{table}] wheelset: {e}"))?;
    Ok(ProfileSetup {
        wheelset,
        lateral_shift,
        roll,
        inclination_label,
    })
}
