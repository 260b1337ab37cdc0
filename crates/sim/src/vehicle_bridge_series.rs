//! The time series of a vehicle–bridge run, one row per recorded step: its columns and the
//! values of a row, shared by the CLI's `timeseries.csv` and the Python package's `run`
//! (SI units: s, m, m/s, m/s², N, Pa).
//!
//! Columns (quantity, where, unit; docs/outputs.md): `t_s`, `deflection_midspan_m`,
//! `velocity_midspan_m_s`, `acceleration_midspan_m_s2` (at the output point), `iterations`
//! (coupling iterations of the step), then per wheel `position_m`, `wheel_z_m`, `body_z_m`,
//! `body_acceleration_m_s2`, `contact_force_n`, `approach_m`, `patch_length_m`,
//! `patch_width_m`, `max_pressure_pa` and, with traction, `longitudinal_force_n`, `creepage`,
//! `adhesion_fraction` (with several wheels the wheel index k goes before the unit:
//! `contact_force_1_n`).

use crate::vehicle_bridge::WheelSample;
use crate::vehicle_bridge::traction::TractionSample;

/// (quantity, unit suffix) of each per-wheel column.
const PER_WHEEL: [(&str, &str); 12] = [
    ("position", "_m"),
    ("wheel_z", "_m"),
    ("body_z", "_m"),
    ("body_acceleration", "_m_s2"),
    ("contact_force", "_n"),
    ("approach", "_m"),
    ("patch_length", "_m"),
    ("patch_width", "_m"),
    ("max_pressure", "_pa"),
    ("longitudinal_force", "_n"),
    ("creepage", ""),
    ("adhesion_fraction", ""),
];

/// The column names for `wheels` wheels (with the three traction columns per wheel when
/// `with_traction`).
pub fn columns(wheels: usize, with_traction: bool) -> Vec<String> {
    let mut header: Vec<String> = [
        "t_s",
        "deflection_midspan_m",
        "velocity_midspan_m_s",
        "acceleration_midspan_m_s2",
        "iterations",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let per_wheel = &PER_WHEEL[..if with_traction { 12 } else { 9 }];
    for k in 0..wheels {
        for &(name, unit) in per_wheel {
            header.push(if wheels == 1 {
                format!("{name}{unit}")
            } else {
                format!("{name}_{k}{unit}")
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

/// The track's columns (after those of [`columns`], with `[track]` only; docs/track.md): per
/// wheel `rail_z_m` (the rail displacement under the wheel; `rail_z_k_m` with several wheels),
/// then `loaded_sleeper_x_m`, `pad_force_n`, `ballast_force_n` (at the sleeper with the
/// largest pad force) and `rail_bridge_relative_m` (rail minus bridge at the output point).
pub fn track_columns(wheels: usize) -> Vec<String> {
    let mut header: Vec<String> = (0..wheels)
        .map(|k| {
            if wheels == 1 {
                "rail_z_m".to_string()
            } else {
                format!("rail_z_{k}_m")
            }
        })
        .collect();
    header.extend(
        [
            "loaded_sleeper_x_m",
            "pad_force_n",
            "ballast_force_n",
            "rail_bridge_relative_m",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    header
}

/// Appends the values of [`track_columns`] of `sample` to `out`.
pub fn track_row(sample: &crate::vehicle_bridge::track::TrackSample, out: &mut Vec<f64>) {
    out.extend(&sample.rail_displacement);
    out.extend([
        sample.loaded_sleeper,
        sample.pad_force,
        sample.ballast_force,
        sample.rail_bridge_relative,
    ]);
}
