//! Speed sweeps: every train at every speed over one bridge, the moving-force model
//! (references.md §T2). Each passage is a [`beam::PassagePlan`] run (exact modal recurrence
//! for piecewise-linear modal forces, peaks only); the passages are independent and run on all
//! cores with `rayon`, each result stored at its (train, speed) index, so the results do not
//! depend on the number of threads or on the order in which passages finish.
//!
//! * [`eurocode`]: EN 1991-2 / EN 1990 A2 damping, modes and limits;
//! * [`summary`]: per-train maxima, the envelope over trains, the check;
//! * [`shard`]: shards stored exactly, their merge, the report of a whole sweep.
//!
//! A sweep can be cut into disjoint shards ([`Shard`]) whose passages, concatenated in any
//! order, summarise exactly as the whole sweep (`dyncontact sweep --shard`, `sweep-merge`).

pub mod eurocode;
pub mod interaction;
pub mod schedule;
pub mod shard;
pub mod summary;

use beam::{Axle as BeamAxle, ModalBasis, ModalDamping, PassagePeaks, PassagePlan};

use crate::train::{Train, TrainError};

/// A sweep, validated (by `config::sweep`).
#[derive(Debug, Clone)]
pub struct SweepSpec {
    /// The trains.
    pub trains: Vec<Train>,
    /// The speeds \[m/s\], increasing.
    pub speeds: Vec<f64>,
    /// Output points x \[m\].
    pub points: Vec<f64>,
    /// Time step \[s\].
    pub dt: f64,
    /// Free vibration after the last axle has left \[s\].
    pub free_vibration: f64,
    /// Gravity \[m/s²\] for the static axle loads of vehicle models.
    pub gravity: f64,
    /// The train model: moving forces (default), or the vehicles with their contact law.
    pub model: SweepModel,
}

/// How the trains load the bridge.
#[derive(Debug, Clone, Default)]
pub enum SweepModel {
    /// Their static axle loads as moving forces (exact modal recurrence).
    #[default]
    MovingForces,
    /// Their vehicle models coupled to the bridge through the contact law ([`interaction`]).
    Interaction(Box<interaction::InteractionModel>),
}

/// The K-th (1-based) of N disjoint slices of the (train, speed) list: passage i belongs to
/// shard (i mod N) + 1 (interleaved, so every shard gets a share of slow and fast passages).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, 1 … N.
    pub index: usize,
    /// N ≥ 1.
    pub count: usize,
}

impl Shard {
    /// The whole sweep.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Whether passage `i` (train-major order) belongs to this shard.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }
}

/// The peaks of one passage.
#[derive(Debug, Clone, PartialEq)]
pub struct Passage {
    /// Index of the train in [`SweepSpec::trains`].
    pub train: usize,
    /// Index of the speed in [`SweepSpec::speeds`].
    pub speed: usize,
    /// Peaks at the output points.
    pub peaks: PassagePeaks,
    /// The wheels' unloading and contact losses and the car bodies' peak acceleration
    /// (interaction model only; `None` for moving forces).
    pub vehicles: Option<interaction::VehiclePeaks>,
}

/// A sweep that cannot run.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// The bridge model or a passage failed.
    #[error("{0}")]
    Beam(#[from] beam::BeamError),
    /// A train description is invalid.
    #[error("{0}")]
    Train(#[from] TrainError),
    /// A coupled vehicle–bridge passage (interaction model) failed.
    #[error("{train} at {speed} m/s: {source}")]
    Interaction {
        /// The train's name.
        train: String,
        /// The speed \[m/s\].
        speed: f64,
        /// What failed.
        source: Box<crate::vehicle_bridge::VehicleBridgeError>,
    },
    /// Stopped by the caller (an interrupt).
    #[error("the sweep was interrupted after {done} of {total} passages")]
    Interrupted {
        /// Passages completed.
        done: usize,
        /// Passages of the shard.
        total: usize,
    },
}

/// The axles of every train as `beam` axles (offset-sorted), computed once.
pub fn train_axles(spec: &SweepSpec) -> Result<Vec<Vec<BeamAxle>>, SweepError> {
    spec.trains
        .iter()
        .map(|t| {
            let mut axles: Vec<BeamAxle> = t
                .axles(spec.gravity)?
                .into_iter()
                .map(|a| BeamAxle {
                    offset: a.offset,
                    force: a.load,
                })
                .collect();
            axles.sort_by(|a, b| a.offset.total_cmp(&b.offset));
            Ok(axles)
        })
        .collect()
}

/// Runs the passages of `shard`, in parallel; `tick` is called as each passage starts and
/// returns false to stop the sweep (an interrupt: the passages not started are skipped). Results in train-major order.
pub fn run(
    basis: &(dyn ModalBasis + Sync),
    damping: &ModalDamping,
    spec: &SweepSpec,
    shard: Shard,
    tick: &(dyn Fn() -> bool + Sync),
) -> Result<Vec<Passage>, SweepError> {
    let plan = PassagePlan::new(basis, damping, spec.dt, &spec.points)?;
    let axles = train_axles(spec)?;
    let ns = spec.speeds.len();
    let jobs: Vec<(usize, usize)> = (0..spec.trains.len() * ns)
        .filter(|&i| shard.contains(i))
        .map(|i| (i / ns, i % ns))
        .collect();
    let total = jobs.len();
    // Mode shapes at the output points (interaction model), point-major.
    let m = basis.n_modes();
    let mut point_shapes = vec![0.0; m * spec.points.len()];
    for (p, &x) in spec.points.iter().enumerate() {
        basis.eval_all(
            x,
            beam::Derivative::Shape,
            &mut point_shapes[p * m..(p + 1) * m],
        )?;
    }
    // The costliest passages first (module `schedule`): coupled steps times axles.
    let cost: Vec<f64> = jobs
        .iter()
        .map(|&(train, speed)| passage_cost(basis.length(), &axles[train], spec, train, speed))
        .collect();
    let order = schedule::longest_first(&cost);
    let results: Vec<Option<Result<Passage, SweepError>>> = schedule::run_in_order(
        &order,
        || plan.work(),
        |work, job| {
            let (train, speed) = jobs[job];
            if !tick() {
                return None;
            }
            let v = spec.speeds[speed];
            let moving = plan
                .peaks(basis, &axles[train], v, spec.free_vibration, work)
                .map_err(SweepError::from);
            let peaks = match (&spec.model, moving) {
                (SweepModel::MovingForces, moving) => moving.map(|peaks| (peaks, None)),
                (SweepModel::Interaction(model), Ok(moving)) => {
                    interaction::passage(model, train, v, &point_shapes, spec.free_vibration)
                        .map(|(peaks, vehicles)| {
                            let peaks = beam::PassagePeaks {
                                static_deflection: moving.static_deflection,
                                ..peaks
                            };
                            (peaks, Some(vehicles))
                        })
                        .map_err(|e| SweepError::Interaction {
                            train: spec.trains[train].name.clone(),
                            speed: v,
                            source: Box::new(e),
                        })
                }
                (_, Err(e)) => Err(e),
            };
            Some(peaks.map(|(peaks, vehicles)| Passage {
                train,
                speed,
                peaks,
                vehicles,
            }))
        },
    );
    let done = results.iter().filter(|r| r.is_some()).count();
    if done < total {
        return Err(SweepError::Interrupted { done, total });
    }
    results.into_iter().flatten().collect()
}

/// The estimated cost of a passage (module `schedule`): its steps up to the last axle's exit,
/// (L + train length)/v/Δt, times its axles (the coupled model's wheels or the moving forces).
fn passage_cost(
    length: f64,
    axles: &[BeamAxle],
    spec: &SweepSpec,
    train: usize,
    speed: usize,
) -> f64 {
    let (first, last) = axles.iter().fold((0.0f64, 0.0f64), |(lo, hi), a| {
        (lo.min(a.offset), hi.max(a.offset))
    });
    let dt = match &spec.model {
        SweepModel::Interaction(model) => model.trains[train].dt,
        SweepModel::MovingForces => spec.dt,
    };
    (length + (last - first)) / spec.speeds[speed] / dt * axles.len() as f64
}
