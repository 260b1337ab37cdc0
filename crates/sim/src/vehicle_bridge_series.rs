//! The time series of a vehicle–bridge run, one row per recorded step: its columns and the
//! values of a row, shared by the CLI's `timeseries.csv` and the Python package's `run`
//! (SI units: s, m, m/s, m/s², N, Pa).
//!
//! Columns: `t`, `midspan_deflection`, `midspan_velocity`, `midspan_acceleration` (at the
//! output point), `iterations` (coupling iterations of the step), then per wheel `position`,
//! `wheel_z`, `body_z`, `body_acceleration`, `contact_force`, `approach`, `patch_length`,
//! `patch_width`, `max_pressure` and, with traction, `longitudinal_force`, `creepage`,
//! `adhesion_fraction` (suffixed `_k` for wheel k when there are several wheels).

use crate::vehicle_bridge::WheelSample;
use crate::vehicle_bridge::traction::TractionSample;

const PER_WHEEL: [&str; 12] = [
    "position",
    "wheel_z",
    "body_z",
    "body_acceleration",
    "contact_force",
    "approach",
    "patch_length",
    "patch_width",
    "max_pressure",
    "longitudinal_force",
    "creepage",
    "adhesion_fraction",
];

/// The column names for `wheels` wheels (with the three traction columns per wheel when
/// `with_traction`).
pub fn columns(wheels: usize, with_traction: bool) -> Vec<String> {
    let mut header: Vec<String> = [
        "t",
        "midspan_deflection",
        "midspan_velocity",
        "midspan_acceleration",
        "iterations",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let per_wheel = &PER_WHEEL[..if with_traction { 12 } else { 9 }];
    for k in 0..wheels {
        for &name in per_wheel {
            header.push(if wheels == 1 {
                name.to_string()
            } else {
                format!("{name}_{k}")
            });
        }
    }
    header
}

/// The values of one row into `out` (cleared first), in the order of [`columns`]: time `t`,
/// the output point's (deflection, velocity, acceleration), the step's coupling iterations,
/// the wheels and their traction samples (empty without traction).
pub fn row(
    t: f64,
    midspan: (f64, f64, f64),
    iterations: usize,
    wheels: &[WheelSample],
    traction: &[TractionSample],
    out: &mut Vec<f64>,
) {
    out.clear();
    out.extend([t, midspan.0, midspan.1, midspan.2, iterations as f64]);
    for (k, w) in wheels.iter().enumerate() {
        out.extend([
            w.position,
            w.wheel_displacement,
            w.body_displacement,
            w.body_acceleration,
            w.contact.force,
            w.approach,
            w.contact.patch_length,
            w.contact.patch_width,
            w.contact.max_pressure,
        ]);
        if let Some(s) = traction.get(k) {
            out.extend([s.longitudinal_force, s.creepage, s.adhesion_fraction]);
        }
    }
}
