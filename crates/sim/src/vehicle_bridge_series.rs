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
//! `contact_force_1_n`); with `[track]` the track's columns ([`track_columns`]); per response
//! point x of `[output] points` `deflection_x<x>_m`, `velocity_x<x>_m_s`,
//! `acceleration_x<x>_m_s2` (as `moving_load` names its points, e.g. `deflection_x30_m`); per car body b of the multibody vehicles (running order)
//! `car_body_acceleration_b_m_s2` (vertical, at its centre of gravity) and
//! `car_body_pitch_acceleration_b_rad_s2`. [`SeriesLayout`] and [`series_row`] give a run's
//! columns and rows.

use crate::vehicle_bridge::traction::TractionSample;
use crate::vehicle_bridge::{Simulation, WheelSample};

/// Which column groups a run's time series has (see the module documentation).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SeriesLayout {
    /// Wheels.
    pub wheels: usize,
    /// With the three traction columns per wheel.
    pub traction: bool,
    /// With the track's columns.
    pub track: bool,
    /// Response points besides the output point \[m\].
    pub points: Vec<f64>,
    /// Car bodies of the multibody vehicles.
    pub car_bodies: usize,
}

impl SeriesLayout {
    /// The layout of `sim`'s series.
    pub fn of(sim: &Simulation) -> Self {
        SeriesLayout {
            wheels: sim.wheels().len(),
            traction: sim.traction().is_some(),
            track: sim.track_sample().is_some(),
            points: sim.output_points().to_vec(),
            car_bodies: sim.car_body_count(),
        }
    }

    /// The column names, in the order of [`series_row`].
    pub fn columns(&self) -> Vec<String> {
        let mut names = columns(self.wheels, self.traction);
        if self.track {
            names.extend(track_columns(self.wheels));
        }
        for x in &self.points {
            names.push(format!("deflection_x{x}_m"));
            names.push(format!("velocity_x{x}_m_s"));
            names.push(format!("acceleration_x{x}_m_s2"));
        }
        for b in 0..self.car_bodies {
            names.push(format!("car_body_acceleration_{b}_m_s2"));
            names.push(format!("car_body_pitch_acceleration_{b}_rad_s2"));
        }
        names
    }

    /// Values per row.
    pub fn width(&self) -> usize {
        self.columns().len()
    }
}

/// The row of `sim`'s current state into `out` (cleared first), in the order of
/// [`SeriesLayout::columns`]; `iterations`: the coupling iterations of the last step.
pub fn series_row(sim: &Simulation, iterations: usize, out: &mut Vec<f64>) {
    let traction = sim.traction().map(|t| t.samples()).unwrap_or(&[]);
    row(
        sim.t(),
        sim.output_point_response(),
        iterations,
        sim.wheels(),
        traction,
        out,
    );
    if let Some(track) = sim.track_sample() {
        track_row(track, out);
    }
    for i in 0..sim.output_points().len() {
        let (d, v, a) = sim.point_response(i);
        out.extend([d, v, a]);
    }
    for (a, pitch) in sim.car_body_accelerations() {
        out.extend([a, pitch]);
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_traction_columns_follow_each_wheel() {
        let h = columns(2, true);
        assert_eq!(h.len(), 5 + 2 * 12);
        assert_eq!(h[0], "t_s");
        assert_eq!(h[5 + 8], "max_pressure_0_pa");
        assert_eq!(h[5 + 9], "longitudinal_force_0_n");
        assert_eq!(h[5 + 10], "creepage_0");
        assert_eq!(h[5 + 12], "position_1_m");
        assert_eq!(columns(1, false)[5..7], ["position_m", "wheel_z_m"]);
    }

    #[test]
    fn points_and_car_bodies_come_after_the_track() {
        let layout = SeriesLayout {
            wheels: 2,
            traction: false,
            track: true,
            points: vec![10.0, 27.5],
            car_bodies: 1,
        };
        let h = layout.columns();
        let base = 5 + 2 * 9 + 2 + 4;
        assert_eq!(h.len(), base + 2 * 3 + 2);
        assert_eq!(layout.width(), h.len());
        assert_eq!(h[base - 1], "rail_bridge_relative_m");
        assert_eq!(
            h[base..],
            [
                "deflection_x10_m",
                "velocity_x10_m_s",
                "acceleration_x10_m_s2",
                "deflection_x27.5_m",
                "velocity_x27.5_m_s",
                "acceleration_x27.5_m_s2",
                "car_body_acceleration_0_m_s2",
                "car_body_pitch_acceleration_0_rad_s2",
            ]
        );
    }
}
