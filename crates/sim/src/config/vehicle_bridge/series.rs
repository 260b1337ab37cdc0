//! The recorded time series of a `vehicle_bridge` run: its default stride, the checks of the
//! run's length and of the series' memory, and the response points of `[output] points`.

use super::super::ConfigError;
use super::super::checks;
use super::MAX_IRREGULARITY_WORK;
use crate::vehicle_bridge::{Irregularity, Scenario};
use crate::vehicle_bridge_series::SeriesLayout;

/// The simulated time of a scenario: `integrator.duration`, or until the rearmost wheel or
/// moving force has left the span (as [`crate::vehicle_bridge::Simulation::end_time`]).
fn end_time(s: &Scenario) -> f64 {
    s.duration
        .unwrap_or_else(|| ((s.bridge.length() - s.rearmost_position()) / s.speed).max(0.0))
}

/// The most values (rows × columns) the time series of a run holds when `[output] every` is
/// not given: about 80 MB of `timeseries.csv` (about 20 bytes a value; 32 MB in memory from
/// Python). A single wheel's run of up to 2.8e5 steps (14 columns), or a 32-wheel train's of
/// up to 1.3e4 (309 columns, with its 8 car bodies), is still recorded at every step; longer runs record one step in
/// [`default_every`] (the summary's extrema are taken at every step regardless).
pub const DEFAULT_SERIES_VALUES: f64 = 4e6;

/// The default `[output] every`: the smallest stride that keeps the time series (its columns:
/// `layout`) within [`DEFAULT_SERIES_VALUES`].
pub fn default_every(s: &Scenario, layout: &SeriesLayout) -> usize {
    let width = layout.width();
    let rows = (end_time(s) / s.dt).ceil() + 2.0;
    let every = (rows * width as f64 / DEFAULT_SERIES_VALUES).ceil();
    if every.is_finite() && every >= 1.0 {
        every.min(u32::MAX as f64) as usize
    } else {
        1
    }
}

/// Steps, output rows and the irregularity's setup work of the run, refused when absurd (the
/// work of the steps: [`super::cost`]); `width` values per recorded row.
pub(super) fn check_run_length(
    s: &Scenario,
    every: usize,
    width: usize,
) -> Result<(), ConfigError> {
    let end = end_time(s);
    let steps = checks::steps(
        "the run (integrator.duration or the passage) at integrator.dt",
        end / s.dt,
    )?;
    let rows = steps / every as f64 + 2.0;
    checks::output_rows("the run with output.every", rows)?;
    checks::memory(
        "the recorded time series (output.every)",
        rows,
        8.0 * width as f64,
    )?;
    if let Irregularity::Random(p) = &s.irregularity {
        let w_max = p.wavenumbers.iter().copied().fold(0.0, f64::max);
        let (lo, hi) = s
            .wheels
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), w| {
                (lo.min(w.position), hi.max(w.position))
            });
        let travel = hi - lo + s.speed * end + 2.0;
        let points = travel * w_max * 64.0 / std::f64::consts::TAU;
        let work = points * p.wavenumbers.len() as f64;
        if work.is_nan() || work > MAX_IRREGULARITY_WORK {
            return Err(ConfigError::TooLarge(format!(
                "the random irregularity over {} m of track (vehicle.speed × duration) with irregularity.components = {} and irregularity.lambda_min needs about {} cosine evaluations to tabulate (limit {})",
                checks::number(travel),
                p.wavenumbers.len(),
                checks::number(work),
                checks::number(MAX_IRREGULARITY_WORK)
            )));
        }
    }
    Ok(())
}
