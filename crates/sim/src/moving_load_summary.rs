//! The summary of a moving-load run (the CLI's summary.json, the Python package's `run`) and
//! the columns and rows of its time series (SI units: s, m, m/s, m/s², N m).

use beam::{BeamError, MovingLoadResponse, MovingLoads};
use serde::Serialize;

use crate::config::bridge::Bridge;

/// The summary of a moving-load run.
#[derive(Debug, Clone, Serialize)]
pub struct MovingLoadSummary {
    /// False when the run stopped early (interrupted): the outputs then end at `time_reached`
    /// and timeseries.csv is named timeseries.partial.csv.
    pub completed: bool,
    /// Simulated time reached \[s\].
    pub time_reached: f64,
    /// Why the run stopped early (absent when `completed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_by: Option<String>,
    pub bridge: String,
    pub speed: f64,
    pub axles: usize,
    pub integrator: String,
    pub dt: f64,
    pub modes_used: usize,
    pub max_midspan_deflection: f64,
    pub static_midspan_deflection: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub static_midspan_deflection_closed_form: Option<f64>,
    /// max |w| / max |w_static| at midspan; null when the midspan does not move (a support).
    pub dynamic_amplification: Option<f64>,
    pub max_midspan_acceleration: f64,
    pub max_midspan_moment: f64,
    pub max_free_vibration_deflection: f64,
    /// The other response points (`[output] points`; without them a continuous bridge's other
    /// spans' midspans), with their extrema (absent without such points).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<PointMax>,
    pub exit_time: f64,
    pub simulated_time_s: f64,
    pub wall_time_s: f64,
}

/// The largest response at a response point.
#[derive(Debug, Clone, Serialize)]
pub struct PointMax {
    /// Position on the bridge \[m\].
    pub x: f64,
    /// max |w| \[m\].
    pub max_deflection: f64,
    /// max |ẅ| \[m/s²\].
    pub max_acceleration: f64,
    /// max |M| \[N m\].
    pub max_moment: f64,
}

/// The summary of response `r` of `loads` over `bridge` (`integrator` and `dt` as run, `wall`
/// the wall time \[s\]).
pub fn summarise(
    bridge: &Bridge,
    loads: &MovingLoads,
    r: &MovingLoadResponse,
    integrator: &str,
    dt: f64,
    wall: f64,
) -> Result<MovingLoadSummary, BeamError> {
    let single = loads.axles().len() == 1;
    let closed_form = match (bridge.support, single) {
        (Some(beam::Support::SimplySupported), true) => {
            Some(beam::closed_form::ss_midspan_static_deflection(
                loads.axles()[0].force.abs(),
                bridge.reference.length,
                bridge.reference.bending_stiffness,
            ))
        }
        _ => None,
    };
    let end = r.times.last().copied().unwrap_or(0.0);
    Ok(MovingLoadSummary {
        completed: r.completed,
        time_reached: end,
        stopped_by: (!r.completed).then(|| "interrupt (SIGINT or SIGTERM)".to_string()),
        bridge: bridge.description.clone(),
        speed: loads.speed(),
        axles: loads.axles().len(),
        integrator: integrator.to_string(),
        dt,
        modes_used: bridge.basis.n_modes(),
        max_midspan_deflection: r.max_abs_deflection(0)?,
        static_midspan_deflection: r.max_abs_quasi_static(0)?,
        static_midspan_deflection_closed_form: closed_form,
        dynamic_amplification: Some(r.dynamic_amplification(0)?).filter(|d| d.is_finite()),
        max_midspan_acceleration: r.max_abs_acceleration(0)?,
        max_midspan_moment: r.max_abs_bending_moment(0)?,
        max_free_vibration_deflection: r.max_abs_deflection_between(0, r.exit_time, end)?,
        points: (1..r.n_points())
            .map(|p| {
                Ok(PointMax {
                    x: r.points[p],
                    max_deflection: r.max_abs_deflection(p)?,
                    max_acceleration: r.max_abs_acceleration(p)?,
                    max_moment: r.max_abs_bending_moment(p)?,
                })
            })
            .collect::<Result<_, BeamError>>()?,
        exit_time: r.exit_time,
        simulated_time_s: end,
        wall_time_s: wall,
    })
}

/// The column names of the time series at the response's points: `t_s`, `load_position_m`,
/// then per point (`midspan` for the first, `x<position>` for the others) deflection,
/// velocity, acceleration and moment with their units.
pub fn columns(r: &MovingLoadResponse) -> Vec<String> {
    let mut header = vec!["t_s".to_string(), "load_position_m".to_string()];
    for (p, x) in r.points.iter().enumerate() {
        let tag = if p == 0 {
            "midspan".to_string()
        } else {
            format!("x{x}")
        };
        for (q, unit) in [
            ("deflection", "m"),
            ("velocity", "m_s"),
            ("acceleration", "m_s2"),
            ("moment", "n_m"),
        ] {
            header.push(format!("{q}_{tag}_{unit}"));
        }
    }
    header
}

/// Row `i` of the time series into `out` (cleared first), in the order of [`columns`].
pub fn row(loads: &MovingLoads, r: &MovingLoadResponse, i: usize, out: &mut Vec<f64>) {
    let np = r.n_points();
    out.clear();
    let t = r.times[i];
    out.extend([t, loads.speed() * t]);
    for p in 0..np {
        let k = i * np + p;
        out.extend([
            r.deflection[k],
            r.velocity[k],
            r.acceleration[k],
            r.bending_moment[k],
        ]);
    }
}
