//! Shards of a sweep and their merge, one implementation for `dyncontact sweep --shard K/N` /
//! `sweep-merge` and the Python package's distributed sweep: a shard's passages are stored
//! exactly (floats as IEEE-754 bit patterns) with the scenario text they belong to, and the
//! merge checks that the shards form one complete set of that scenario before summarising
//! them, so a merged sweep equals the whole sweep run at once.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::summary::{SweepSummary, summarise};
use super::{Passage, Shard, SweepError, train_axles};
use crate::config::sweep::SweepConfig;
use crate::config::{ConfigError, ScenarioConfig};

/// A slice of the passages of a sweep (the CLI's `shard.json`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ShardFile {
    /// The scenario's text.
    pub scenario: String,
    /// The scenario file's name (for the `"input"` echo of the merged summary).
    #[serde(default)]
    pub scenario_file: Option<String>,
    /// The directory relative paths in the scenario (train files) are resolved against.
    pub base: PathBuf,
    /// `[K, N]`.
    pub shard: [usize; 2],
    /// The passages of the shard.
    pub passages: Vec<ShardPassage>,
    /// Wall time of the shard's run \[s\].
    pub wall_time_s: f64,
}

/// One passage of a shard, exact.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ShardPassage {
    /// Index of the train.
    pub train: usize,
    /// Index of the speed.
    pub speed: usize,
    /// Time steps of the passage.
    pub steps: usize,
    /// Peak deflections (bit patterns of f64) \[m\].
    pub deflection: Vec<u64>,
    /// Peak accelerations (bit patterns of f64) \[m/s²\].
    pub acceleration: Vec<u64>,
    /// Peak quasi-static deflections (bit patterns of f64) \[m\].
    pub static_deflection: Vec<u64>,
    /// The vehicles' peaks (interaction model; absent for moving forces).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vehicles: Option<ShardVehicles>,
}

/// [`super::interaction::VehiclePeaks`] of one passage, exact (floats as bit patterns).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct ShardVehicles {
    /// max (W_k − F_k)/W_k.
    pub max_unloading_ratio: u64,
    /// Smallest contact force \[N\].
    pub min_contact_force: u64,
    /// Loss-of-contact events.
    pub loss_of_contact_events: usize,
    /// Largest car-body acceleration \[m/s²\].
    pub max_body_acceleration: u64,
}

impl ShardFile {
    /// The shard `shard` of the scenario `scenario` (read relative to `base`) with its passages.
    pub fn new(
        scenario: &str,
        base: &Path,
        shard: Shard,
        passages: &[Passage],
        wall_time_s: f64,
    ) -> Self {
        ShardFile {
            scenario: scenario.to_string(),
            scenario_file: None,
            base: base.canonicalize().unwrap_or_else(|_| base.to_path_buf()),
            shard: [shard.index, shard.count],
            passages: passages.iter().map(encode).collect(),
            wall_time_s,
        }
    }
}

fn encode(p: &Passage) -> ShardPassage {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect();
    ShardPassage {
        train: p.train,
        speed: p.speed,
        steps: p.peaks.steps,
        deflection: bits(&p.peaks.deflection),
        acceleration: bits(&p.peaks.acceleration),
        static_deflection: bits(&p.peaks.static_deflection),
        vehicles: p.vehicles.map(|v| ShardVehicles {
            max_unloading_ratio: v.max_unloading_ratio.to_bits(),
            min_contact_force: v.min_contact_force.to_bits(),
            loss_of_contact_events: v.loss_of_contact_events,
            max_body_acceleration: v.max_body_acceleration.to_bits(),
        }),
    }
}

fn decode(p: &ShardPassage) -> Passage {
    let floats = |v: &[u64]| v.iter().map(|b| f64::from_bits(*b)).collect();
    Passage {
        train: p.train,
        speed: p.speed,
        peaks: beam::PassagePeaks {
            deflection: floats(&p.deflection),
            acceleration: floats(&p.acceleration),
            static_deflection: floats(&p.static_deflection),
            steps: p.steps,
        },
        vehicles: p.vehicles.map(|v| super::interaction::VehiclePeaks {
            max_unloading_ratio: f64::from_bits(v.max_unloading_ratio),
            min_contact_force: f64::from_bits(v.min_contact_force),
            loss_of_contact_events: v.loss_of_contact_events,
            max_body_acceleration: f64::from_bits(v.max_body_acceleration),
        }),
    }
}

/// Shards that do not form one complete sweep. Shards are named by the caller's labels (the
/// CLI: their directories).
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// No shard was given.
    #[error("no shards to merge")]
    Empty,
    /// A shard of another scenario than the first.
    #[error("{label}: shard of another scenario than {first}")]
    OtherScenario {
        /// The shard.
        label: String,
        /// The first shard.
        first: String,
    },
    /// A shard that is not one of the set `1/N … N/N`, or given twice.
    #[error("{label}: shard {k}/{n} does not fit the set of {count} shards (each once)")]
    DoesNotFit {
        /// The shard.
        label: String,
        /// Its K.
        k: usize,
        /// Its N.
        n: usize,
        /// N of the first shard.
        count: usize,
    },
    /// A shard of the set is missing.
    #[error("sweep-merge: shard {k}/{count} is missing")]
    Missing {
        /// The missing K.
        k: usize,
        /// N.
        count: usize,
    },
    /// The shards' scenario is invalid.
    #[error("{0}")]
    Config(#[from] ConfigError),
    /// The shards' scenario is not a sweep.
    #[error("the shards hold a {0} scenario, not a sweep")]
    NotSweep(&'static str),
    /// The shards do not hold every passage of the sweep once.
    #[error("sweep-merge: the shards hold {found} passages, the sweep has {expected}")]
    Count {
        /// Passages in the shards.
        found: usize,
        /// Passages of the sweep.
        expected: usize,
    },
}

/// A complete set of shards merged: the sweep's configuration and every passage in
/// (train, speed) order, as [`super::run`] returns them for the whole sweep.
pub struct Merged {
    /// The sweep (the scenario re-read from the shards).
    pub config: SweepConfig,
    /// Every passage, train-major.
    pub passages: Vec<Passage>,
    /// Sum of the shards' wall times \[s\].
    pub wall_time_s: f64,
}

/// Merges `shards` (each with a label for the error messages): they must hold the same
/// scenario and form the set `1/N … N/N`, each once.
pub fn merge(shards: &[(String, ShardFile)]) -> Result<Merged, MergeError> {
    let Some((first_label, first)) = shards.first() else {
        return Err(MergeError::Empty);
    };
    let count = first.shard[1];
    let mut seen = vec![false; count];
    for (label, s) in shards {
        if s.scenario != first.scenario {
            return Err(MergeError::OtherScenario {
                label: label.clone(),
                first: first_label.clone(),
            });
        }
        let [k, n] = s.shard;
        if n != count || k == 0 || k > n || std::mem::replace(&mut seen[k - 1], true) {
            return Err(MergeError::DoesNotFit {
                label: label.clone(),
                k,
                n,
                count,
            });
        }
    }
    if let Some(k) = seen.iter().position(|s| !s) {
        return Err(MergeError::Missing { k: k + 1, count });
    }
    let config = match crate::config::load(&first.scenario, &first.base, &Default::default())? {
        ScenarioConfig::Sweep(c) => *c,
        other => return Err(MergeError::NotSweep(other.kind())),
    };
    let mut passages = Vec::new();
    let mut wall_time_s = 0.0;
    for (_, s) in shards {
        wall_time_s += s.wall_time_s;
        passages.extend(s.passages.iter().map(decode));
    }
    passages.sort_by_key(|p| (p.train, p.speed));
    let expected = config.spec.trains.len() * config.spec.speeds.len();
    if passages.len() != expected {
        return Err(MergeError::Count {
            found: passages.len(),
            expected,
        });
    }
    Ok(Merged {
        config,
        passages,
        wall_time_s,
    })
}

/// The report of a whole sweep (the CLI's `summary.json`): the results and what the sweep was
/// run with.
#[derive(Debug, Serialize)]
pub struct SweepReport {
    /// Per-train maxima, envelope, check.
    #[serde(flatten)]
    pub results: SweepSummary,
    /// The bridge's description.
    pub bridge: String,
    /// Modes retained.
    pub modes: usize,
    /// The uniform damping ratio, if uniform.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_ratio: Option<f64>,
    /// Time step \[s\].
    pub dt: f64,
    /// Free vibration after the last axle \[s\].
    pub free_vibration: f64,
    /// Output points \[m\].
    pub points: Vec<f64>,
    /// How damping and modes were chosen.
    pub notes: Vec<String>,
    /// Wall time of the run (sum over the shards for a merged sweep) \[s\].
    pub wall_time_s: f64,
}

/// The report of a whole sweep's passages (every (train, speed) once, any order).
pub fn report(
    config: &SweepConfig,
    passages: &[Passage],
    wall_time_s: f64,
) -> Result<SweepReport, SweepError> {
    let spec = &config.spec;
    let axle_counts: Vec<usize> = train_axles(spec)?.iter().map(Vec::len).collect();
    let results = summarise(
        spec,
        passages,
        config.track,
        config.first_frequency,
        &axle_counts,
    );
    Ok(SweepReport {
        results,
        bridge: config.bridge.description.clone(),
        modes: config.bridge.basis.n_modes(),
        damping_ratio: config.damping_ratio,
        dt: spec.dt,
        free_vibration: spec.free_vibration,
        points: spec.points.clone(),
        notes: config.notes.clone(),
        wall_time_s,
    })
}
