//! The results of a sweep: per-train maxima, the envelope over trains at each speed, and the
//! deck-acceleration check (EN 1990 A2; references.md §T2). Serialised as the `summary.json`
//! of `dyncontact sweep` (keys documented in docs/sweep.md).

use serde::Serialize;

use super::eurocode::{Track, comfort_level, resonance_speeds};
use super::interaction::VehiclePeaks;
use super::{Passage, SweepSpec};
use crate::train::hslm;

/// One train over all speeds.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TrainSummary {
    /// Train name.
    pub name: String,
    /// Axles.
    pub axles: usize,
    /// Peak deck acceleration over speeds and output points \[m/s²\].
    pub max_acceleration: f64,
    /// Speed of that peak \[m/s\].
    pub speed_at_max_acceleration: f64,
    /// Peak deflection over speeds and output points \[m\].
    pub max_deflection: f64,
    /// Speed of that peak \[m/s\].
    pub speed_at_max_deflection: f64,
    /// φ'_dyn = max over speeds of (peak dynamic deflection / peak quasi-static deflection).
    pub dynamic_factor: f64,
    /// Speed of φ'_dyn \[m/s\].
    pub speed_at_dynamic_factor: f64,
    /// The vehicles' side (interaction model only; its keys appear in the train's object).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub vehicles: Option<TrainVehicles>,
}

/// What a train's wheels and car bodies went through over all speeds (interaction model).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TrainVehicles {
    /// max over speeds, wheels and steps of (W_k − F_k)/W_k (1: a wheel out of contact).
    pub max_unloading_ratio: f64,
    /// Speed of that peak \[m/s\].
    pub speed_at_max_unloading_ratio: f64,
    /// The smallest contact force of any wheel at any speed \[N\].
    pub min_contact_force: f64,
    /// Loss-of-contact events summed over the speeds.
    pub loss_of_contact_events: usize,
    /// The speeds at which a wheel lost contact \[m/s\].
    pub speeds_with_loss_of_contact: Vec<f64>,
    /// The largest vertical car-body acceleration over the speeds \[m/s²\].
    pub max_body_acceleration: f64,
    /// Speed of that peak \[m/s\].
    pub speed_at_max_body_acceleration: f64,
    /// The EN 1990 A2.4.4.3.2 comfort level it reaches (`very good`, `good`, `acceptable`;
    /// `null` when worse).
    pub comfort_level: Option<&'static str>,
}

impl TrainVehicles {
    fn new() -> Self {
        TrainVehicles {
            max_unloading_ratio: f64::NEG_INFINITY,
            speed_at_max_unloading_ratio: 0.0,
            min_contact_force: f64::INFINITY,
            loss_of_contact_events: 0,
            speeds_with_loss_of_contact: Vec::new(),
            max_body_acceleration: f64::NEG_INFINITY,
            speed_at_max_body_acceleration: 0.0,
            comfort_level: None,
        }
    }

    /// Takes the passage at `speed` into the maxima.
    fn add(&mut self, v: &VehiclePeaks, speed: f64) {
        if v.max_unloading_ratio > self.max_unloading_ratio {
            (self.max_unloading_ratio, self.speed_at_max_unloading_ratio) =
                (v.max_unloading_ratio, speed);
        }
        self.min_contact_force = self.min_contact_force.min(v.min_contact_force);
        self.loss_of_contact_events += v.loss_of_contact_events;
        if v.loss_of_contact_events > 0 {
            self.speeds_with_loss_of_contact.push(speed);
        }
        if v.max_body_acceleration > self.max_body_acceleration {
            (
                self.max_body_acceleration,
                self.speed_at_max_body_acceleration,
            ) = (v.max_body_acceleration, speed);
        }
        self.comfort_level = comfort_level(self.max_body_acceleration);
    }
}

/// The maxima over all trains at each speed.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Envelope {
    /// Speeds \[m/s\].
    pub speeds: Vec<f64>,
    /// Peak deck acceleration \[m/s²\].
    pub max_acceleration: Vec<f64>,
    /// Peak deflection \[m\].
    pub max_deflection: Vec<f64>,
    /// φ' (the largest over trains).
    pub dynamic_factor: Vec<f64>,
    /// The largest wheel unloading ratio (W − F)/W over trains (interaction model only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_unloading_ratio: Option<Vec<f64>>,
    /// The largest car-body acceleration over trains \[m/s²\] (interaction model only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_body_acceleration: Option<Vec<f64>>,
}

/// A resonance speed of a train with regular coach length.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Resonance {
    /// Train.
    pub train: String,
    /// Order i of v_i = n₀ D / i.
    pub order: usize,
    /// Speed \[m/s\].
    pub speed: f64,
}

/// The deck-acceleration check.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Checks {
    /// `ballasted` or `ballastless`.
    pub track: String,
    /// The limit \[m/s²\] (EN 1990 A2.4.4.2.1).
    pub acceleration_limit: f64,
    /// The peak deck acceleration over every train and speed \[m/s²\].
    pub max_acceleration: f64,
    /// Its train and speed \[m/s\].
    pub governing_train: String,
    /// Its speed \[m/s\].
    pub governing_speed: f64,
    /// max_acceleration ≤ acceleration_limit.
    pub passed: bool,
    /// The first bending frequency n₀ \[Hz\].
    pub first_frequency: f64,
    /// Resonance speeds v_i = n₀ D / i in the speed range, for the trains with a regular coach
    /// length D (the HSLM-A trains).
    pub resonance_speeds: Vec<Resonance>,
}

/// Everything a sweep reports except its wall time.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SweepSummary {
    /// Per train.
    pub trains: Vec<TrainSummary>,
    /// Per speed.
    pub envelope: Envelope,
    /// The check.
    pub checks: Checks,
    /// Passages run.
    pub runs: usize,
}

/// Summarises the passages of a whole sweep (every (train, speed) once, any order).
pub fn summarise(
    spec: &SweepSpec,
    passages: &[Passage],
    track: Track,
    first_frequency: f64,
    axle_counts: &[usize],
) -> SweepSummary {
    let ns = spec.speeds.len();
    let mut sorted: Vec<&Passage> = passages.iter().collect();
    sorted.sort_by_key(|p| (p.train, p.speed));
    let peak = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let phi = |p: &Passage| {
        let s = peak(&p.peaks.static_deflection);
        if s > 0.0 {
            peak(&p.peaks.deflection) / s
        } else {
            0.0
        }
    };
    let mut envelope = Envelope {
        speeds: spec.speeds.clone(),
        max_acceleration: vec![0.0; ns],
        max_deflection: vec![0.0; ns],
        dynamic_factor: vec![0.0; ns],
        max_unloading_ratio: None,
        max_body_acceleration: None,
    };
    let with_vehicles = sorted.iter().any(|p| p.vehicles.is_some());
    if with_vehicles {
        envelope.max_unloading_ratio = Some(vec![0.0; ns]);
        envelope.max_body_acceleration = Some(vec![0.0; ns]);
    }
    let mut trains = Vec::with_capacity(spec.trains.len());
    for (t, train) in spec.trains.iter().enumerate() {
        let mut s = TrainSummary {
            name: train.name.clone(),
            axles: axle_counts.get(t).copied().unwrap_or(0),
            max_acceleration: 0.0,
            speed_at_max_acceleration: f64::NAN,
            max_deflection: 0.0,
            speed_at_max_deflection: f64::NAN,
            dynamic_factor: 0.0,
            speed_at_dynamic_factor: f64::NAN,
            vehicles: None,
        };
        for p in sorted.iter().filter(|p| p.train == t) {
            let v = spec.speeds[p.speed];
            let (a, w, f) = (
                peak(&p.peaks.acceleration),
                peak(&p.peaks.deflection),
                phi(p),
            );
            if a > s.max_acceleration || s.speed_at_max_acceleration.is_nan() {
                (s.max_acceleration, s.speed_at_max_acceleration) = (a, v);
            }
            if w > s.max_deflection || s.speed_at_max_deflection.is_nan() {
                (s.max_deflection, s.speed_at_max_deflection) = (w, v);
            }
            if f > s.dynamic_factor || s.speed_at_dynamic_factor.is_nan() {
                (s.dynamic_factor, s.speed_at_dynamic_factor) = (f, v);
            }
            let e = p.speed;
            envelope.max_acceleration[e] = envelope.max_acceleration[e].max(a);
            envelope.max_deflection[e] = envelope.max_deflection[e].max(w);
            envelope.dynamic_factor[e] = envelope.dynamic_factor[e].max(f);
            if let Some(vp) = &p.vehicles {
                s.vehicles.get_or_insert_with(TrainVehicles::new).add(vp, v);
                if let Some(u) = envelope.max_unloading_ratio.as_mut() {
                    u[e] = u[e].max(vp.max_unloading_ratio);
                }
                if let Some(b) = envelope.max_body_acceleration.as_mut() {
                    b[e] = b[e].max(vp.max_body_acceleration);
                }
            }
        }
        trains.push(s);
    }
    let governing = trains.iter().fold(None::<&TrainSummary>, |g, t| match g {
        Some(g) if g.max_acceleration >= t.max_acceleration => Some(g),
        _ => Some(t),
    });
    let (v_min, v_max) = (
        spec.speeds.first().copied().unwrap_or(0.0),
        spec.speeds.last().copied().unwrap_or(0.0),
    );
    let resonance = spec
        .trains
        .iter()
        .filter_map(|t| {
            let number = t.name.strip_prefix("HSLM-A")?.parse::<usize>().ok()?;
            let d = hslm::parameters(number)?.coach_length;
            Some(
                resonance_speeds(first_frequency, d, v_min, v_max)
                    .into_iter()
                    .map(|(order, speed)| Resonance {
                        train: t.name.clone(),
                        order,
                        speed,
                    })
                    .collect::<Vec<_>>(),
            )
        })
        .flatten()
        .collect();
    let max_acceleration = governing.map_or(0.0, |g| g.max_acceleration);
    SweepSummary {
        checks: Checks {
            track: track.name().to_string(),
            acceleration_limit: track.acceleration_limit(),
            max_acceleration,
            governing_train: governing.map_or(String::new(), |g| g.name.clone()),
            governing_speed: governing.map_or(0.0, |g| g.speed_at_max_acceleration),
            passed: max_acceleration <= track.acceleration_limit(),
            first_frequency,
            resonance_speeds: resonance,
        },
        trains,
        envelope,
        runs: passages.len(),
    }
}

/// The columns of [`passage_table`] (the CLI's `sweep.csv`; SI units as the names say).
pub const PASSAGE_COLUMNS: [&str; 7] = [
    "train",
    "speed_m_s",
    "point_m",
    "max_deflection_m",
    "max_acceleration_m_s2",
    "max_static_deflection_m",
    "dynamic_factor",
];

/// The columns [`passage_table`] adds when the passages carry their vehicles' peaks (the
/// interaction model; the same values on every output point's row of a passage).
pub const VEHICLE_COLUMNS: [&str; 4] = [
    "max_unloading_ratio",
    "min_contact_force_n",
    "loss_of_contact_events",
    "max_body_acceleration_m_s2",
];

/// One row per (passage, output point), in the order of `passages`, as named columns
/// ([`PASSAGE_COLUMNS`]): the train as its index, the speed, the point, the peaks and the
/// dynamic factor (peak deflection over peak quasi-static deflection; 0 where the latter is
/// not positive); then, when every passage carries its vehicles' peaks (the interaction
/// model), [`VEHICLE_COLUMNS`].
pub fn passage_table(spec: &SweepSpec, passages: &[Passage]) -> Vec<(&'static str, Vec<f64>)> {
    let mut columns: [Vec<f64>; 7] = Default::default();
    let with_vehicles = !passages.is_empty() && passages.iter().all(|p| p.vehicles.is_some());
    let mut vehicle_columns: [Vec<f64>; 4] = Default::default();
    for p in passages {
        if let (true, Some(v)) = (with_vehicles, &p.vehicles) {
            let row = [
                v.max_unloading_ratio,
                v.min_contact_force,
                v.loss_of_contact_events as f64,
                v.max_body_acceleration,
            ];
            for c in vehicle_columns.iter_mut().zip(row) {
                c.0.extend(std::iter::repeat_n(c.1, spec.points.len()));
            }
        }
        for k in 0..spec.points.len() {
            let (w, a, s) = (
                p.peaks.deflection[k],
                p.peaks.acceleration[k],
                p.peaks.static_deflection[k],
            );
            let row = [
                p.train as f64,
                spec.speeds[p.speed],
                spec.points[k],
                w,
                a,
                s,
                if s > 0.0 { w / s } else { 0.0 },
            ];
            for (c, v) in columns.iter_mut().zip(row) {
                c.push(v);
            }
        }
    }
    let mut table: Vec<(&'static str, Vec<f64>)> =
        PASSAGE_COLUMNS.into_iter().zip(columns).collect();
    if with_vehicles {
        table.extend(VEHICLE_COLUMNS.into_iter().zip(vehicle_columns));
    }
    table
}
