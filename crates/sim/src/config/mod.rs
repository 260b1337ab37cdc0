//! Scenario files: TOML text parsed once into typed structs (`serde`, unknown keys are
//! errors), every key range-checked with an error that names it as written in the file, and
//! converted into the input types of the physics crates.
//!
//! * [`load`]: a `dyncontact run` scenario, dispatched on its `kind`;
//! * [`contact::parse`]: a contact case (`dyncontact contact`, `creep-curve`);
//! * [`bridge::parse_bridge_file`]: a `[bridge]` section (`dyncontact modes`).
//!
//! Relative paths in a scenario (a gap table) are resolved against `base`, the directory of
//! the scenario file. Sizes (grids, modes, elements, wheels, steps, output rows) are checked
//! against the limits of [`checks`] *before* anything is allocated. SI units throughout; the
//! numerical defaults are public constants of the submodules (docs/*.md list them).

use std::path::Path;

use serde::de::DeserializeOwned;

/// An error of a scenario file. The message names the key as written in the file.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// TOML syntax, an unknown key or a value of the wrong type.
    #[error("{0}")]
    Schema(String),
    /// A value out of range, a missing key or keys that exclude each other.
    #[error("{0}")]
    Invalid(String),
    /// A size or run length refused before allocating (the message states the estimate).
    #[error("{0}")]
    TooLarge(String),
    /// A file named by the scenario cannot be read.
    #[error("{context}: {source}")]
    Io {
        /// What was read (key and path).
        context: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
}

/// `ConfigError::Invalid` with a formatted message.
macro_rules! invalid {
    ($($t:tt)*) => { $crate::config::ConfigError::Invalid(format!($($t)*)) };
}

/// Return `ConfigError::Invalid` with a formatted message.
macro_rules! bail {
    ($($t:tt)*) => { return Err(invalid!($($t)*)) };
}

pub mod ball_drop;
pub mod bridge;
pub mod checks;
pub mod contact;
mod contact_tangential;
pub mod cost;
pub mod integrator;
pub mod irregularity;
pub mod moving_load;
pub mod sweep;
pub mod track;
pub mod train;
mod train_wheels;
pub mod vehicle_bridge;
pub mod wheel_contact;
pub mod wheel_rail;

/// Scenario kinds of [`load`].
pub const SCENARIO_KINDS: &[&str] = &[
    "ball_drop",
    "contact",
    "moving_load",
    "sweep",
    "vehicle_bridge",
];

/// A scenario of `dyncontact run`, validated and ready for its simulation.
pub enum ScenarioConfig {
    /// `kind = "ball_drop"`.
    BallDrop(Box<ball_drop::BallDropConfig>),
    /// `kind = "contact"`.
    Contact(Box<contact::ContactConfig>),
    /// `kind = "moving_load"`.
    MovingLoad(Box<moving_load::MovingLoadConfig>),
    /// `kind = "vehicle_bridge"`.
    VehicleBridge(Box<vehicle_bridge::VehicleBridgeConfig>),
    /// `kind = "sweep"`.
    Sweep(Box<sweep::SweepConfig>),
}

impl ScenarioConfig {
    /// The scenario's `kind`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::BallDrop(_) => "ball_drop",
            Self::Contact(_) => "contact",
            Self::MovingLoad(_) => "moving_load",
            Self::VehicleBridge(_) => "vehicle_bridge",
            Self::Sweep(_) => "sweep",
        }
    }
}

/// Options of [`load`] that come from outside the file.
#[derive(Debug, Clone, Default)]
pub struct LoadOptions {
    /// Replaces the ball drop's `[integrator] method` (`dyncontact run --integrator`); an
    /// error for the other kinds.
    pub integrator: Option<String>,
    /// Largest estimated work of a run (default [`cost::MAX_WORK`]; `dyncontact run
    /// --max-work`).
    pub max_work: Option<f64>,
}

/// Parse a scenario's text once, dispatch on `kind`, validate. `base` is the directory that
/// relative paths in the file are resolved against.
pub fn load(text: &str, base: &Path, options: &LoadOptions) -> Result<ScenarioConfig, ConfigError> {
    let table = parse_table(text)?;
    let kind = match table.get_ref().get("kind").map(|v| v.get_ref()) {
        Some(toml::de::DeValue::String(k)) => k.to_string(),
        Some(other) => {
            bail!(
                "`kind` must be a string, found a {} (known kinds: {})",
                other.type_str(),
                SCENARIO_KINDS.join(", ")
            )
        }
        None => bail!(
            "missing `kind` (known kinds: {})",
            SCENARIO_KINDS.join(", ")
        ),
    };
    if let Some(name) = &options.integrator
        && kind != "ball_drop"
    {
        bail!(
            "--integrator {name}: kind = \"{kind}\" does not take --integrator (only ball_drop does); set `[integrator] method` in the scenario file (docs/integrators.md lists the methods)"
        );
    }
    let config = build(&kind, table, text, base, options)?;
    cost::check(&config, options.max_work.unwrap_or(cost::MAX_WORK))?;
    Ok(config)
}

/// The validated scenario of a parsed file of kind `kind`.
fn build(
    kind: &str,
    table: Document<'_>,
    text: &str,
    base: &Path,
    options: &LoadOptions,
) -> Result<ScenarioConfig, ConfigError> {
    match kind {
        "ball_drop" => {
            let file = deserialize(table, text)?;
            ball_drop::build(file, options.integrator.as_deref())
                .map(|c| ScenarioConfig::BallDrop(Box::new(c)))
        }
        "contact" => {
            let file = deserialize(table, text)?;
            contact::build(file, base).map(|c| ScenarioConfig::Contact(Box::new(c)))
        }
        "moving_load" => {
            let file = deserialize(table, text)?;
            moving_load::build(file).map(|c| ScenarioConfig::MovingLoad(Box::new(c)))
        }
        "vehicle_bridge" => {
            let file = deserialize(table, text)?;
            vehicle_bridge::build_in(file, base).map(|c| ScenarioConfig::VehicleBridge(Box::new(c)))
        }
        "sweep" => {
            let file = deserialize(table, text)?;
            sweep::build(file, base).map(|c| ScenarioConfig::Sweep(Box::new(c)))
        }
        other => bail!(
            "unknown `kind` = \"{other}\" (known kinds: {})",
            SCENARIO_KINDS.join(", ")
        ),
    }
}

type Document<'i> = toml::Spanned<toml::de::DeTable<'i>>;

/// The one TOML parse of a file.
fn parse_table(text: &str) -> Result<Document<'_>, ConfigError> {
    toml::de::DeTable::parse(text)
        .map_err(|e| ConfigError::Schema(format!("invalid scenario file: {e}")))
}

/// The typed file struct of a parsed document (errors point at the line of the key; an
/// unknown key gets the nearest known one as a suggestion).
fn deserialize<T: DeserializeOwned>(table: Document<'_>, text: &str) -> Result<T, ConfigError> {
    T::deserialize(toml::de::Deserializer::from(table)).map_err(|mut e| {
        e.set_input(Some(text));
        ConfigError::Schema(with_key_suggestion(format!("invalid scenario file: {e}")))
    })
}

/// Edit distance (insertions, deletions, substitutions and swaps of neighbours) between two
/// names, case-insensitive.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_lowercase().chars().collect();
    let b: Vec<char> = b.to_lowercase().chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for j in 0..=b.len() {
        d[0][j] = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

/// ` (did you mean `NAME`?)` for the known name nearest to `given`, when it is a near miss (at
/// most one edit per three characters, at least one allowed); empty otherwise.
pub(crate) fn suggestion(given: &str, known: &[&str]) -> String {
    let allowed = (given.chars().count() / 3).max(1);
    known
        .iter()
        .map(|k| (edit_distance(given, k), *k))
        .filter(|(d, _)| *d <= allowed)
        .min()
        .map_or_else(String::new, |(_, k)| format!(" (did you mean `{k}`?)"))
}

/// Appends a suggestion to serde's "unknown field `x`, expected one of `a`, `b`" message.
pub(crate) fn with_key_suggestion(message: String) -> String {
    let Some(start) = message.find("unknown field `") else {
        return message;
    };
    let rest = &message[start + "unknown field `".len()..];
    let Some(end) = rest.find('`') else {
        return message;
    };
    let given = &rest[..end];
    let known: Vec<&str> = rest[end + 1..].split('`').skip(1).step_by(2).collect();
    let hint = suggestion(given, &known);
    if hint.is_empty() {
        message
    } else {
        format!("{}{hint}", message.trim_end())
    }
}

/// Parse text straight into a typed file struct (one parse).
fn from_str<T: DeserializeOwned>(text: &str) -> Result<T, ConfigError> {
    deserialize(parse_table(text)?, text)
}

#[cfg(test)]
mod suggestion_tests {
    use super::{edit_distance, suggestion, with_key_suggestion};

    #[test]
    fn near_misses_are_suggested_and_far_names_are_not() {
        assert_eq!(edit_distance("lenght", "length"), 1); // a swap of neighbours
        assert_eq!(edit_distance("speed", "sped"), 1);
        assert_eq!(edit_distance("Modes", "modes"), 0);
        assert_eq!(edit_distance("abc", "xyz"), 3);
        let known = ["length", "modes", "supports"];
        assert_eq!(suggestion("lenght", &known), " (did you mean `length`?)");
        assert_eq!(suggestion("mode", &known), " (did you mean `modes`?)");
        assert_eq!(suggestion("damping", &known), "");
        let m = with_key_suggestion(
            "invalid: unknown field `lenght`, expected one of `length`, `EI`, `E`\n".into(),
        );
        assert!(m.ends_with("`E` (did you mean `length`?)"), "{m}");
        let m = with_key_suggestion("unknown field `x`, expected `kind`".into());
        assert_eq!(m, "unknown field `x`, expected `kind`");
    }
}
